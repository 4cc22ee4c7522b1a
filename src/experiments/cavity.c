/* The rectangular PEC cavity on Yee's grid (seed 000 §3.4.1): a band-limited pulse (a Gaussian
 * on a carrier, from dipoles) rings the cavity; each E probe's signal goes through harminv
 * (separately: a sum of probes can cancel a mode), and the first 10 distinct resonant
 * frequencies are compared with
 *   analytic:  f = 1/2 sqrt(sum_a (m_a / L_a)^2)                              (c = 1)
 *   Yee:       sin(pi f dt) / dt = sqrt(sum_a sin^2(pi m_a h_a / 2L_a) / h_a^2)  (the discrete
 *              dispersion relation, Taflove & Hagness 3rd ed. eq. 4.21 with k_a = pi m_a / L_a)
 * 2-D: TM (Ez, Hx, Hy) in [0,1]x[0,0.8], modes m_x, m_y >= 1. 3-D: [0,1]x[0,0.8]x[0,0.6],
 * modes with at least two non-zero indices (TE and TM together; the two polarizations of a
 * mode with three non-zero indices share one frequency). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/fields.h"

#define CAV_MAX_FOUND 128

static const double cav_pi = 3.14159265358979323846;
static const double box[3] = {1.0, 0.8, 0.6};

/* Source and probe points (fractions of the box) chosen so that each of the first 10 modes,
 * in 2-D and 3-D, couples source to probe with at least a third of the largest possible
 * |mode(source) . mode(probe)| (searched over random points; with points near 1/4 of a side a
 * (4, m) mode is nearly invisible). */
static const double source_at[3][3] = {{0.393, 0.782, 0.258}, {0.180, 0.237, 0.305},
                                       {0.296, 0.896, 0.913}};
static const double probe_at[3][3] = {{0.514, 0.259, 0.644}, {0.616, 0.180, 0.230},
                                      {0.171, 0.566, 0.802}};

gm_cavity_config gm_cavity_defaults(void) {
  gm_cavity_config c = {3, 16, 200.0, 0, NULL, NULL};
  return c;
}

void gm_cavity_result_clear(gm_cavity_result *r) {
  if (r == NULL) return;
  free(r->signals);
  r->signals = NULL;
  r->n_signal = 0;
}

gm_resonance_params gm_resonance_params_defaults(void) {
  return (gm_resonance_params){0, 1e-4, 1.0, 1e-6};
}

gm_status gm_experiment_resonances_with(const double *signal, size_t n, double dt, double f_min,
                                        double f_max, const gm_resonance_params *params,
                                        gm_harminv_mode *modes, size_t cap, size_t *n_modes,
                                        gm_error *err) {
  const gm_resonance_params hp = params ? *params : gm_resonance_params_defaults();
  gm_harminv_mode all[256];
  size_t n_all = 0;
  *n_modes = 0;
  gm_status st = gm_harminv(n, signal, NULL, dt, f_min, f_max, hp.basis, 256, all, &n_all, err);
  if (st != GM_OK) return st;
  /* harminv also returns weak, badly resolved components of noise: keep a mode when its
   * error estimate is small, it is not overdamped (|Q| > 1; a lossless mode's decay is +-1e-13,
   * so Q's sign means nothing there), and its amplitude is not negligible against the
   * strongest one. */
  double a_max = 0;
  for (size_t k = 0; k < n_all; ++k)
    if (isfinite(all[k].amplitude)) a_max = fmax(a_max, all[k].amplitude);
  size_t kept = 0;
  for (size_t k = 0; k < n_all && kept < cap; ++k)
    if (all[k].error < hp.max_error && fabs(all[k].q) > hp.min_q && isfinite(all[k].frequency) &&
        all[k].amplitude > hp.min_amplitude * a_max)
      modes[kept++] = all[k];
  *n_modes = kept;
  return GM_OK;
}

gm_status gm_experiment_resonances(const double *signal, size_t n, double dt, double f_min,
                                   double f_max, gm_harminv_mode *modes, size_t cap,
                                   size_t *n_modes, gm_error *err) {
  return gm_experiment_resonances_with(signal, n, dt, f_min, f_max, NULL, modes, cap, n_modes,
                                       err);
}

typedef struct band_mode {
  int m[3];
  double analytic, yee;
} band_mode;

static int by_analytic(const void *a, const void *b) {
  double x = ((const band_mode *)a)->analytic, y = ((const band_mode *)b)->analytic;
  return (x > y) - (x < y);
}

/* The first n_want distinct analytic frequencies with their Yee counterparts. */
static size_t cavity_modes(int dim, const double h[3], double dt, band_mode *out, size_t n_want) {
  band_mode *list = malloc(4096 * sizeof *list);
  if (list == NULL) return 0;
  size_t n = 0;
  int top = 12, zmax = dim == 3 ? top : 0;
  for (int a = 0; a <= top; ++a)
    for (int b = 0; b <= top; ++b)
      for (int c = 0; c <= zmax; ++c) {
        int nonzero = (a > 0) + (b > 0) + (c > 0);
        if (dim == 2 ? (a == 0 || b == 0) : nonzero < 2) continue;
        int m[3] = {a, b, c};
        double s2 = 0, ks = 0;
        for (int k = 0; k < dim; ++k) {
          s2 += (m[k] / box[k]) * (m[k] / box[k]);
          double sk = sin(cav_pi * m[k] * h[k] / (2 * box[k])) / h[k];
          ks += sk * sk;
        }
        if (n < 4096) {
          list[n].m[0] = a, list[n].m[1] = b, list[n].m[2] = c;
          list[n].analytic = 0.5 * sqrt(s2);
          list[n].yee = asin(fmin(1.0, dt * sqrt(ks))) / (cav_pi * dt);
          ++n;
        }
      }
  qsort(list, n, sizeof list[0], by_analytic);
  size_t kept = 0;
  for (size_t i = 0; i < n && kept < n_want; ++i)
    if (kept == 0 || list[i].analytic > out[kept - 1].analytic * (1 + 1e-12)) out[kept++] = list[i];
  free(list);
  return kept;
}

/* Run the cavity; the probes' signals from the end of the pulse on into r. */
static gm_status run_cavity(const gm_cavity_config *c, band_mode *modes, size_t n_modes,
                            gm_cavity_result *r, gm_error *err) {
  const int dim = c->dim;
  const size_t n = c->n;
  gm_yee_grid grid = {dim == 3 ? GM_YEE_3D : GM_YEE_2D_TM, {n, n, dim == 3 ? n : 1},
                      {box[0] / (double)n, box[1] / (double)n, dim == 3 ? box[2] / (double)n : 1},
                      {0, 0, 0}};
  gm_yee_options opt = gm_yee_defaults();
  opt.n_threads = c->n_threads;
  gm_yee *s = NULL;
  gm_status st = gm_yee_create(&grid, NULL, &opt, &s, err);
  if (st != GM_OK) return st;
  /* A Gaussian pulse on a carrier at the middle of the band [f_1, f_10], spectral width half
   * the band: every mode of the band is excited to within ~e^-1/2 of the peak, and the grid's
   * many modes above the band hardly at all (they would blur harminv's estimates). */
  double f_lo = modes[0].analytic, f_hi = modes[n_modes - 1].analytic;
  double sigma_f = 0.5 * (f_hi - f_lo), width = 1.0 / (2 * cav_pi * sigma_f);
  gm_waveform wave = {GM_WAVE_GAUSSIAN, 1.0, 0.5 * (f_lo + f_hi), width, 6 * width, 0.0, NULL,
                      NULL};
  int n_src = dim == 3 ? 3 : 1;
  const size_t steps = r->steps;
  for (int k = 0; k < n_src && st == GM_OK; ++k) {
    gm_point_source src = {dim == 3 ? (gm_yee_component)(GM_EX + k) : GM_EZ,
                           {source_at[k][0] * box[0], source_at[k][1] * box[1],
                            dim == 3 ? source_at[k][2] * box[2] : 0},
                           GM_SOURCE_SOFT, wave};
    if ((st = gm_yee_add_point_source(s, &src, NULL)) != GM_OK)
      gm_error_set(err, st, "%s", gm_yee_errmsg(s));
  }
  size_t n_probes = 0;
  for (int p = 0; p < 3 && st == GM_OK; ++p)
    for (int k = 0; k < (dim == 3 ? 3 : 1) && st == GM_OK; ++k) {
      double x[3] = {probe_at[p][0] * box[0], probe_at[p][1] * box[1],
                     dim == 3 ? probe_at[p][2] * box[2] : 0};
      if ((st = gm_yee_add_probe(s, dim == 3 ? (gm_yee_component)(GM_EX + k) : GM_EZ, x, steps,
                                 NULL)) != GM_OK)
        gm_error_set(err, st, "%s", gm_yee_errmsg(s));
      else
        ++n_probes;
    }
  const double t0 = gm_experiment_clock();
  const size_t chunk = steps / 100 > 0 ? steps / 100 : 1;
  for (size_t done = 0; done < steps && st == GM_OK;) {
    size_t k = steps - done < chunk ? steps - done : chunk;
    if ((st = gm_yee_advance(s, k)) != GM_OK) {
      gm_error_set(err, st, "%s", gm_yee_errmsg(s));
      break;
    }
    done += k;
    if (c->progress != NULL && c->progress(c->progress_ctx, (double)done, (double)steps) != 0)
      st = gm_error_set(err, GM_ECALLBACK, "cavity: stopped by the progress callback at step "
                        "%zu of %zu", done, steps);
  }
  r->wall_s = gm_experiment_clock() - t0;
  if (st != GM_OK) {
    gm_yee_free(s);
    return st;
  }
  const size_t first = (size_t)ceil(2 * wave.delay / r->dt), len = steps - first;
  double *all = malloc(n_probes * len * sizeof *all);
  if (all == NULL) {
    gm_yee_free(s);
    return gm_error_set(err, GM_ENOMEM, "cavity: out of memory for %zu probe samples",
                        n_probes * len);
  }
  for (size_t p = 0; p < n_probes; ++p) {
    size_t ns;
    const double *t, *re, *im;
    gm_yee_probe_samples(s, p, &ns, &t, &re, &im);
    memcpy(all + p * len, re + first, len * sizeof *all);
  }
  gm_yee_free(s);
  r->signals = all;
  r->n_probes = n_probes;
  r->n_signal = len;
  return GM_OK;
}

/* Each expected mode takes, over all probes' harminv modes, the one nearest its Yee frequency
 * within a tenth of the gap to its neighbours. A computed mode near no Yee mode of the band
 * (within 1e-3 relative) is spurious. */
static void match_modes(gm_cavity_result *r, const band_mode *band, size_t n_band,
                        const gm_harminv_mode *modes, size_t n) {
  r->n_found = 0;
  for (size_t k = 0; k < r->n_modes; ++k) {
    gm_cavity_mode *x = &r->modes[k];
    double f = x->yee, gap = INFINITY;
    if (k > 0) gap = fmin(gap, f - r->modes[k - 1].yee);
    if (k + 1 < n_band) gap = fmin(gap, band[k + 1].yee - f);
    double best = 0.1 * gap;
    x->found = 0;
    for (size_t i = 0; i < n; ++i)
      if (fabs(modes[i].frequency - f) < best) {
        best = fabs(modes[i].frequency - f);
        x->computed = modes[i];
        x->found = 1;
      }
    if (x->found) {
      r->n_found++;
      r->max_rel_error_yee = fmax(r->max_rel_error_yee, fabs(x->computed.frequency / x->yee - 1));
      r->max_rel_error_analytic =
          fmax(r->max_rel_error_analytic, fabs(x->computed.frequency / x->analytic - 1));
    }
  }
  r->spurious = 0;
  for (size_t i = 0; i < n; ++i) {
    int near = 0;
    for (size_t k = 0; k < n_band && !near; ++k)
      near = fabs(modes[i].frequency / band[k].yee - 1) < 1e-3;
    r->spurious += !near;
  }
}

gm_status gm_experiment_cavity(const gm_cavity_config *c, gm_cavity_result *r, gm_error *err) {
  memset(r, 0, sizeof *r);
  if (c->dim != 2 && c->dim != 3)
    return gm_error_set(err, GM_EINVAL, "cavity: dim must be 2 or 3, got %d", c->dim);
  if (c->n < 4 || c->n > (c->dim == 3 ? 256u : 4096u))
    return gm_error_set(err, GM_EINVAL, "cavity: n must be in [4, %d], got %zu",
                        c->dim == 3 ? 256 : 4096, c->n);
  if (!(c->periods >= 10 && c->periods <= 1e5))
    return gm_error_set(err, GM_EINVAL, "cavity: periods must be in [10, 1e5], got %g",
                        c->periods);
  const double t0 = gm_experiment_clock();
  const size_t n = c->n;
  const double h[3] = {box[0] / (double)n, box[1] / (double)n,
                       c->dim == 3 ? box[2] / (double)n : 1};
  /* the Yee step at the default Courant number, as gm_yee_create sets it */
  gm_yee_grid grid = {c->dim == 3 ? GM_YEE_3D : GM_YEE_2D_TM, {n, n, c->dim == 3 ? n : 1},
                      {h[0], h[1], h[2]}, {0, 0, 0}};
  gm_yee_options opt = gm_yee_defaults();
  gm_yee *probe = NULL;
  gm_status st = gm_yee_create(&grid, NULL, &opt, &probe, err);
  if (st != GM_OK) return st;
  r->dt = gm_yee_dt(probe);
  gm_yee_free(probe);
  r->dim = c->dim;
  r->n = n;
  r->cells = n * n * (c->dim == 3 ? n : 1);
  band_mode modes[GM_CAVITY_CHECK], *band = malloc(GM_CAVITY_BAND * sizeof *band);
  if (band == NULL) return gm_error_set(err, GM_ENOMEM, "cavity: out of memory");
  r->n_modes = cavity_modes(c->dim, h, r->dt, modes, GM_CAVITY_CHECK);
  const size_t n_band = cavity_modes(c->dim, h, r->dt, band, GM_CAVITY_BAND);
  for (size_t k = 0; k < r->n_modes; ++k) {
    memcpy(r->modes[k].m, modes[k].m, sizeof modes[k].m);
    r->modes[k].analytic = modes[k].analytic;
    r->modes[k].yee = modes[k].yee;
  }
  r->steps = (size_t)ceil(c->periods / (modes[0].analytic * r->dt));
  if ((st = run_cavity(c, modes, r->n_modes, r, err)) != GM_OK) {
    free(band);
    return st;
  }
  r->f_max = modes[r->n_modes - 1].analytic * 1.15;
  gm_harminv_mode *found = malloc(r->n_probes * CAV_MAX_FOUND * sizeof *found);
  size_t n_found = 0;
  if (found == NULL) st = gm_error_set(err, GM_ENOMEM, "cavity: out of memory");
  for (size_t p = 0; st == GM_OK && p < r->n_probes; ++p) {
    size_t k = 0;
    st = gm_experiment_resonances(r->signals + p * r->n_signal, r->n_signal, r->dt,
                                  0.5 * modes[0].yee, r->f_max, found + n_found, CAV_MAX_FOUND,
                                  &k, err);
    n_found += k;
  }
  if (st == GM_OK) {
    r->n_harminv = n_found;
    match_modes(r, band, n_band, found, n_found);
  } else {
    char why[GM_ERRMSG_SIZE];
    snprintf(why, sizeof why, "%s", err->message);
    gm_error_set(err, st, "harminv: %s", why);
    gm_cavity_result_clear(r);
  }
  free(found);
  free(band);
  r->wall_s = st == GM_OK ? r->wall_s : gm_experiment_clock() - t0;
  return st;
}

gm_status gm_experiment_run_cavity(const char *dir, gm_experiment_result *result, gm_error *err) {
  (void)dir; /* numbers only; the spectrum figure is the command's */
  gm_cavity_config c = gm_cavity_defaults();
  gm_cavity_result r;
  gm_status st = gm_experiment_cavity(&c, &r, err);
  if (st != GM_OK) return st;
  gm_experiment_add(result, "steps", (double)r.steps);
  gm_experiment_add(result, "found", (double)r.n_found);
  gm_experiment_add(result, "spurious", (double)r.spurious);
  gm_experiment_add(result, "max_rel_error_yee", r.max_rel_error_yee);
  gm_experiment_add(result, "max_rel_error_analytic", r.max_rel_error_analytic);
  gm_experiment_add(result, "wall_s", r.wall_s);
  gm_cavity_result_clear(&r);
  return GM_OK;
}
