/* geomint maxwell cavity [--dim 2|3] [--n N]: the rectangular PEC cavity check as one command.
 * A band-limited pulse (Gaussian on a carrier, from dipoles) rings the cavity; each E probe's signal
 * goes through harminv (separately: a sum of probes can cancel a mode), and the first 10
 * distinct resonant frequencies are compared with
 *   analytic:  f = ½ sqrt(Σ_a (m_a / L_a)²)                                (c = 1)
 *   Yee:       sin(π f Δt) / Δt = sqrt(Σ_a sin²(π m_a h_a / 2L_a) / h_a²)  (the discrete
 *              dispersion relation, Taflove & Hagness 3rd ed. eq. 4.21 with k_a = π m_a / L_a)
 * 2-D: TM (Ez, Hx, Hy) in [0,1]×[0,0.8], modes m_x, m_y ≥ 1. 3-D: [0,1]×[0,0.8]×[0,0.6],
 * modes with at least two non-zero indices (TE and TM together; the two polarizations of a
 * mode with three non-zero indices share one frequency). */
#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/maxwell.h"

#define COMMAND "maxwell cavity"
#define N_CHECK 10
#define MAX_FOUND 128

static const double pi = 3.14159265358979323846;
static const double box[3] = {1.0, 0.8, 0.6};

typedef struct cavity_mode {
  int m[3];
  double analytic, discrete;
} cavity_mode;

static int by_analytic(const void *a, const void *b) {
  double x = ((const cavity_mode *)a)->analytic, y = ((const cavity_mode *)b)->analytic;
  return (x > y) - (x < y);
}

/* The first n_want distinct analytic frequencies with their Yee counterparts. */
static size_t cavity_modes(int dim, const double h[3], double dt, cavity_mode *out,
                           size_t n_want) {
  cavity_mode all[4096];
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
          double sk = sin(pi * m[k] * h[k] / (2 * box[k])) / h[k];
          ks += sk * sk;
        }
        if (n < sizeof all / sizeof all[0]) {
          all[n].m[0] = a, all[n].m[1] = b, all[n].m[2] = c;
          all[n].analytic = 0.5 * sqrt(s2);
          all[n].discrete = asin(fmin(1.0, dt * sqrt(ks))) / (pi * dt);
          ++n;
        }
      }
  qsort(all, n, sizeof all[0], by_analytic);
  size_t kept = 0;
  for (size_t i = 0; i < n && kept < n_want; ++i)
    if (kept == 0 || all[i].analytic > out[kept - 1].analytic * (1 + 1e-12)) out[kept++] = all[i];
  return kept;
}

#define N_BAND 400

typedef struct cavity_result {
  cavity_mode modes[N_CHECK];
  size_t n_modes;
  cavity_mode band[N_BAND]; /* every distinct mode up to the band's top, for spurious ones */
  size_t n_band;
  int found[N_CHECK];
  gm_harminv_mode computed[N_CHECK];
  size_t n_harminv, spurious;
  size_t steps, cells;
  double dt, wall;
} cavity_result;

/* Source and probe points (fractions of the box) chosen so that each of the first 10 modes,
 * in 2-D and 3-D, couples source to probe with at least a third of the largest possible
 * |mode(source) · mode(probe)| (searched over random points; with points near 1/4 of a side a
 * (4, m) mode is nearly invisible). */
static const double source_at[3][3] = {{0.393, 0.782, 0.258}, {0.180, 0.237, 0.305},
                                       {0.296, 0.896, 0.913}};
static const double probe_at[3][3] = {{0.514, 0.259, 0.644}, {0.616, 0.180, 0.230},
                                      {0.171, 0.566, 0.802}};

/* Run the cavity; signals: n_probes rows of n_signal samples (owned by the caller). */
static int run_cavity(int dim, size_t n, double periods, int threads, cavity_result *r,
                      double **signals, size_t *n_probes_out, size_t *n_signal) {
  gm_yee_grid grid = {dim == 3 ? GM_YEE_3D : GM_YEE_2D_TM, {n, n, dim == 3 ? n : 1},
                      {box[0] / (double)n, box[1] / (double)n, dim == 3 ? box[2] / (double)n : 1},
                      {0, 0, 0}};
  gm_yee_options opt = gm_yee_defaults();
  opt.n_threads = threads;
  gm_yee *s = NULL;
  gm_error err = {{0}};
  if (gm_yee_create(&grid, NULL, &opt, &s, &err) != GM_OK) {
    cli_error(COMMAND, "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  r->dt = gm_yee_dt(s);
  r->cells = n * n * (dim == 3 ? n : 1);
  r->n_modes = cavity_modes(dim, grid.h, r->dt, r->modes, N_CHECK);
  r->n_band = cavity_modes(dim, grid.h, r->dt, r->band, N_BAND);
  /* A Gaussian pulse on a carrier at the middle of the band [f_1, f_10], spectral width half
   * the band: every mode of the band is excited to within ~e^-1/2 of the peak, and the grid's
   * many modes above the band hardly at all (they would blur harminv's estimates). */
  double f_lo = r->modes[0].analytic, f_hi = r->modes[r->n_modes - 1].analytic;
  double sigma_f = 0.5 * (f_hi - f_lo), width = 1.0 / (2 * pi * sigma_f);
  gm_waveform wave = {GM_WAVE_GAUSSIAN, 1.0, 0.5 * (f_lo + f_hi), width, 6 * width, 0.0, NULL,
                      NULL};
  int n_src = dim == 3 ? 3 : 1;
  size_t steps = (size_t)ceil(periods / (r->modes[0].analytic * r->dt));
  r->steps = steps;
  for (int k = 0; k < n_src; ++k) {
    gm_point_source src = {dim == 3 ? (gm_yee_component)(GM_EX + k) : GM_EZ,
                           {source_at[k][0] * box[0], source_at[k][1] * box[1],
                            dim == 3 ? source_at[k][2] * box[2] : 0},
                           GM_SOURCE_SOFT, wave};
    if (gm_yee_add_point_source(s, &src, NULL) != GM_OK) {
      cli_error(COMMAND, "%s", gm_yee_errmsg(s));
      gm_yee_free(s);
      return CLI_EXIT_FAILURE;
    }
  }
  /* E probes (each E component in 3-D) */
  size_t n_probes = 0;
  for (int p = 0; p < 3; ++p)
    for (int c = 0; c < (dim == 3 ? 3 : 1); ++c) {
      double x[3] = {probe_at[p][0] * box[0], probe_at[p][1] * box[1],
                     dim == 3 ? probe_at[p][2] * box[2] : 0};
      if (gm_yee_add_probe(s, dim == 3 ? (gm_yee_component)(GM_EX + c) : GM_EZ, x, steps, NULL) !=
          GM_OK) {
        cli_error(COMMAND, "%s", gm_yee_errmsg(s));
        gm_yee_free(s);
        return CLI_EXIT_FAILURE;
      }
      ++n_probes;
    }
  mx_progress progress;
  mx_progress_start(&progress, steps);
  double t0 = mx_now();
  size_t chunk = steps / 100 > 0 ? steps / 100 : 1;
  for (size_t done = 0; done < steps;) {
    size_t k = steps - done < chunk ? steps - done : chunk;
    if (gm_yee_advance(s, k) != GM_OK) {
      mx_progress_end(&progress);
      cli_error(COMMAND, "%s", gm_yee_errmsg(s));
      gm_yee_free(s);
      return CLI_EXIT_FAILURE;
    }
    done += k;
    mx_progress_show(&progress, done);
  }
  r->wall = mx_now() - t0;
  mx_progress_end(&progress);
  /* the signals from the end of the pulse on */
  size_t first = (size_t)ceil(2 * wave.delay / r->dt);
  size_t len = steps - first;
  double *all = malloc(n_probes * len * sizeof *all);
  if (all == NULL) {
    gm_yee_free(s);
    cli_error(COMMAND, "out of memory");
    return CLI_EXIT_FAILURE;
  }
  for (size_t p = 0; p < n_probes; ++p) {
    size_t ns;
    const double *t, *re, *im;
    gm_yee_probe_samples(s, p, &ns, &t, &re, &im);
    memcpy(all + p * len, re + first, len * sizeof *all);
  }
  gm_yee_free(s);
  *signals = all;
  *n_probes_out = n_probes;
  *n_signal = len;
  return CLI_EXIT_OK;
}

/* Each expected mode takes, over all probes' harminv modes, the one nearest its Yee frequency
 * within a tenth of the gap to its neighbours. A computed mode near no Yee mode of the band
 * (within 1e-3 relative) is spurious. */
static void match_modes(cavity_result *r, const gm_harminv_mode *modes, size_t n) {
  for (size_t k = 0; k < r->n_modes; ++k) {
    double f = r->modes[k].discrete, gap = INFINITY;
    if (k > 0) gap = fmin(gap, f - r->modes[k - 1].discrete);
    if (k + 1 < r->n_band) gap = fmin(gap, r->band[k + 1].discrete - f);
    double best = 0.1 * gap;
    r->found[k] = 0;
    for (size_t i = 0; i < n; ++i)
      if (fabs(modes[i].frequency - f) < best) {
        best = fabs(modes[i].frequency - f);
        r->computed[k] = modes[i];
        r->found[k] = 1;
      }
  }
  r->spurious = 0;
  for (size_t i = 0; i < n; ++i) {
    int near = 0;
    for (size_t k = 0; k < r->n_band && !near; ++k)
      near = fabs(modes[i].frequency / r->band[k].discrete - 1) < 1e-3;
    r->spurious += !near;
  }
}

int mx_cavity_main(int argc, char **argv) {
  size_t dim = 3, n = 16, threads = 0;
  double periods = 200;
  const char *out_dir = "maxwell-output";
  int json = 0;
  cli_option options[] = {{"--dim", CLI_ARG_COUNT, &dim, 0},
                          {"--n", CLI_ARG_COUNT, &n, 0},
                          {"--periods", CLI_ARG_DOUBLE, &periods, 0},
                          {"--out", CLI_ARG_STRING, &out_dir, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0},
                          {"--threads", CLI_ARG_COUNT, &threads, 0}};
  const char *positional[1];
  size_t n_pos = 0;
  int status = cli_parse(COMMAND, argc, argv, options, 6, positional, 0, &n_pos);
  if (status == CLI_HELP) {
    fputs(mx_usage(), stdout);
    return CLI_EXIT_OK;
  }
  if (status != CLI_EXIT_OK) return status;
  if (dim != 2 && dim != 3) {
    cli_error(COMMAND, "--dim must be 2 or 3, got %zu", dim);
    return CLI_EXIT_USAGE;
  }
  if (n < 4 || n > (dim == 3 ? 256 : 4096)) {
    cli_error(COMMAND, "--n must be in [4, %d], got %zu", dim == 3 ? 256 : 4096, n);
    return CLI_EXIT_USAGE;
  }
  if (cli_check_positive(COMMAND, "--periods", periods) != CLI_EXIT_OK) return CLI_EXIT_USAGE;
  if (periods < 10 || periods > 1e5) {
    cli_error(COMMAND, "--periods must be in [10, 1e5], got %g", periods);
    return CLI_EXIT_USAGE;
  }
  if ((status = mx_make_dir(COMMAND, out_dir)) != CLI_EXIT_OK) return status;

  cavity_result r;
  memset(&r, 0, sizeof r);
  double *signals = NULL;
  size_t n_probes = 0, n_signal = 0;
  status = run_cavity((int)dim, n, periods, (int)threads, &r, &signals, &n_probes, &n_signal);
  if (status != CLI_EXIT_OK) return status;
  double f_max = r.modes[r.n_modes - 1].analytic * 1.15;
  gm_harminv_mode *modes = malloc(n_probes * MAX_FOUND * sizeof *modes);
  size_t n_found = 0;
  char msg[256] = "out of memory";
  for (size_t p = 0; modes != NULL && p < n_probes; ++p) {
    n_found += mx_resonances(signals + p * n_signal, n_signal, r.dt, 0.5 * r.modes[0].discrete,
                             f_max, modes + n_found, MAX_FOUND, msg, sizeof msg);
    if (msg[0] != '\0') break;
  }
  if (modes == NULL || msg[0] != '\0') {
    free(signals);
    free(modes);
    cli_error(COMMAND, "harminv: %s", msg);
    return CLI_EXIT_FAILURE;
  }
  r.n_harminv = n_found;
  match_modes(&r, modes, n_found);
  free(modes);
  double marks[N_CHECK];
  for (size_t k = 0; k < r.n_modes; ++k) marks[k] = r.modes[k].analytic;
  char png[4096], title[128];
  snprintf(title, sizeof title, "PEC cavity, %zu-D, %zu cells per axis: spectrum of the E probes",
           dim, n);
  mx_path(png, sizeof png, out_dir, "cavity-spectrum.png");
  int plot_status = cli_gnuplot_available()
                        ? mx_plot_spectrum(COMMAND, png, title, n_probes, n_signal, signals, r.dt,
                                           f_max, marks, r.n_modes)
                        : CLI_EXIT_FAILURE;
  free(signals);
  size_t n_ok = 0;
  for (size_t k = 0; k < r.n_modes; ++k) n_ok += (size_t)r.found[k];

  if (json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "dim", (double)dim);
    cJSON_AddNumberToObject(o, "n", (double)n);
    cJSON_AddNumberToObject(o, "dt", r.dt);
    cJSON_AddNumberToObject(o, "steps", (double)r.steps);
    cJSON_AddNumberToObject(o, "wall_s", r.wall);
    cJSON_AddNumberToObject(o, "found", (double)n_ok);
    cJSON_AddNumberToObject(o, "spurious", (double)r.spurious);
    cJSON_AddNumberToObject(o, "harminv_modes", (double)r.n_harminv);
    cJSON *arr = cJSON_AddArrayToObject(o, "modes");
    for (size_t k = 0; k < r.n_modes; ++k) {
      cJSON *m = cJSON_CreateObject();
      double idx[3] = {r.modes[k].m[0], r.modes[k].m[1], r.modes[k].m[2]};
      cJSON_AddItemToObject(m, "indices", cli_json_numbers(idx, dim));
      cJSON_AddNumberToObject(m, "analytic", r.modes[k].analytic);
      cJSON_AddNumberToObject(m, "yee", r.modes[k].discrete);
      if (r.found[k]) {
        cJSON_AddNumberToObject(m, "computed", r.computed[k].frequency);
        cJSON_AddItemToObject(m, "q", cli_json_number(r.computed[k].q));
        cJSON_AddNumberToObject(m, "rel_error_analytic",
                                r.computed[k].frequency / r.modes[k].analytic - 1);
        cJSON_AddNumberToObject(m, "rel_error_yee", r.computed[k].frequency / r.modes[k].discrete - 1);
      } else {
        cJSON_AddNullToObject(m, "computed");
      }
      cJSON_AddItemToArray(arr, m);
    }
    if (plot_status == CLI_EXIT_OK) cJSON_AddStringToObject(o, "plot", png);
    status = cli_json_print(o);
  } else {
    printf("PEC cavity %s, %zu-D %s, %zu cells per axis: dt %.6g, %zu steps (%.2f s)\n",
           dim == 3 ? "[0,1]x[0,0.8]x[0,0.6]" : "[0,1]x[0,0.8]", dim, dim == 3 ? "" : "TM", n,
           r.dt, r.steps, r.wall);
    printf("%3s %-9s %13s %13s %13s %12s %12s\n", "", "mode", "analytic", "Yee", "computed",
           "vs analytic", "vs Yee");
    for (size_t k = 0; k < r.n_modes; ++k) {
      char idx[32];
      if (dim == 3)
        snprintf(idx, sizeof idx, "(%d,%d,%d)", r.modes[k].m[0], r.modes[k].m[1], r.modes[k].m[2]);
      else
        snprintf(idx, sizeof idx, "(%d,%d)", r.modes[k].m[0], r.modes[k].m[1]);
      printf("%3zu %-9s %13.9f %13.9f ", k + 1, idx, r.modes[k].analytic, r.modes[k].discrete);
      if (r.found[k])
        printf("%13.9f %12.3e %12.3e\n", r.computed[k].frequency,
               r.computed[k].frequency / r.modes[k].analytic - 1,
               r.computed[k].frequency / r.modes[k].discrete - 1);
      else
        printf("%13s\n", "not found");
    }
    printf("%zu of %zu resonances found; %zu harminv modes from %zu probes, %zu of them near no "
           "Yee mode; ", n_ok, r.n_modes, r.n_harminv, n_probes, r.spurious);
    if (plot_status == CLI_EXIT_OK)
      printf("spectrum: %s\n", png);
    else
      printf("no plot (gnuplot missing or failed)\n");
  }
  if (status == CLI_EXIT_OK && n_ok < r.n_modes) status = CLI_EXIT_FAILURE;
  return status;
}
