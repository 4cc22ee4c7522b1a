/* Seed 000 experiment E5 (notes §2) on a Gmsh cavity (a box meshed with tetrahedra refined near
 * the walls, examples/e5_cavity.msh).
 *  1. The circumcentric stars are checked. Gmsh's Delaunay mesh, left unoptimised
 *     (examples/e5_cavity.geo), has positive *_eps on every interior edge and *_nu on every
 *     interior face: for a Delaunay tetrahedralisation the circumcentric dual of an interior
 *     edge is its Voronoi face and the dual of an interior face the Voronoi edge between two
 *     circumcentres, both of positive measure. Near-cospherical vertex sets (the box's corners
 *     and edges) give a few tiny dual cells, hence tiny local CFL limits there: the case the
 *     AVI is for.
 *  2. The AVI, every face at `fraction` of its local limit (power-of-two levels), random
 *     initial E, E at one point sampled every sample_dt, harminv resonances against the
 *     analytic ones of the box (every peak within 5 % of one: else spurious), energy and the
 *     invariants.
 *  3. The consistent (Whitney) star's leapfrog on the same mesh, its resonances the same way.
 *  4. Cost to t_compare: the AVI against uniform leapfrog stepping (diagonal star) at the AVI's
 *     smallest face step, and the Whitney leapfrog at its own step.
 * If the stars are not positive (a mesh made with Gmsh's optimisers), 2 and 4 are skipped and
 * 3 runs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/dec.h"
#include "geomint/fields.h"
#include "geomint/mesh.h"

#define E5_BLOWUP_RATIO 10.0 /* legitimate AVI runs stay below 2.7 (docs/maxwell-mesh.md) */

gm_e5_config gm_e5_defaults(void) {
  gm_e5_config c = {8.0, 1, 2.0, 0.25, 0.005, 1.0, NULL, NULL};
  return c;
}

static void run_clear(gm_e5_run *r) {
  free(r->signals);
  r->signals = NULL;
}

void gm_e5_result_clear(gm_e5_result *r) {
  if (r == NULL) return;
  run_clear(&r->avi);
  run_clear(&r->whitney);
}

static double cpu_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* splitmix64 (Steele, Lea & Flood, OOPSLA 2014), uniform in [-1/2, 1/2) */
static double e5_rand(uint64_t *z) {
  uint64_t x = (*z += 0x9e3779b97f4a7c15ull);
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  x ^= x >> 31;
  return (double)(x >> 11) / 9007199254740992.0 - 0.5;
}

static int dbl_cmp(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Distinct resonances f = 1/2 sqrt((m/a)^2 + (n/b)^2 + (p/c)^2) of the PEC box (at most one
 * index zero), ascending, up to f_max; returns the count (<= cap). */
static size_t box_resonances(const double L[3], double f_max, double *out, size_t cap) {
  size_t n = 0;
  double *all = malloc(4096 * sizeof *all);
  if (all == NULL) return 0;
  for (int m = 0; m < 16; ++m)
    for (int p = 0; p < 16; ++p)
      for (int q = 0; q < 16; ++q) {
        if ((m == 0) + (p == 0) + (q == 0) > 1) continue;
        const double f = 0.5 * sqrt(m * m / (L[0] * L[0]) + p * p / (L[1] * L[1]) +
                                    q * q / (L[2] * L[2]));
        if (f <= f_max && n < 4096) all[n++] = f;
      }
  qsort(all, n, sizeof(double), dbl_cmp);
  size_t k = 0;
  for (size_t i = 0; i < n && k < cap; ++i)
    if (k == 0 || all[i] > out[k - 1] * (1.0 + 1e-9)) out[k++] = all[i];
  free(all);
  return k;
}

/* The resonances harminv finds (error < 1e-3) in the three probe signals, merged within 0.3 %.
 * Every step's sample is used: decimating the signal aliases the grid-scale modes of the random
 * initial field into the band (7 spurious peaks of 17 with every 6th sample). */
static size_t probe_resonances(const gm_mesh_maxwell *s, double f_lo, double f_hi, double *out,
                               size_t cap) {
  size_t k = 0;
  double all[3 * GM_E5_MAX_MODES];
  for (size_t id = 0; id < 3; ++id) {
    size_t n;
    const double *t, *v;
    if (gm_mesh_maxwell_probe_samples(s, id, &n, &t, &v) != GM_OK || n < 16) continue;
    gm_harminv_mode modes[GM_E5_MAX_MODES];
    size_t nm = 0;
    gm_error err = {{0}};
    if (gm_harminv(n, v, NULL, t[1] - t[0], f_lo, f_hi, 0, GM_E5_MAX_MODES, modes, &nm, &err) !=
        GM_OK)
      continue;
    for (size_t i = 0; i < nm; ++i)
      if (modes[i].error < 1e-3 && modes[i].frequency > f_lo) all[k++] = modes[i].frequency;
  }
  qsort(all, k, sizeof(double), dbl_cmp);
  size_t w = 0;
  for (size_t i = 0; i < k && w < cap; ++i)
    if (w == 0 || all[i] > out[w - 1] * 1.003) out[w++] = all[i];
  return w;
}

static double nearest_rel(double f, const double *ref, size_t n) {
  double best = INFINITY;
  for (size_t i = 0; i < n; ++i) best = fmin(best, fabs(f - ref[i]) / ref[i]);
  return best;
}

/* the blow-up guard: the plain energy against its value at the start */
typedef struct e5_guard {
  double limit; /* E5_BLOWUP_RATIO (AVI) or INFINITY (leapfrog: non-finite only) */
  int started, fired;
  double e0, max_ratio, max_dev;
  char message[GM_ERRMSG_SIZE];
  const char *advice;
} e5_guard;

static int guard_check(e5_guard *g, double t, double plain) {
  if (!g->started) {
    g->started = 1;
    g->e0 = plain;
    g->max_ratio = isfinite(plain) ? 1.0 : NAN;
  }
  const double ratio = g->e0 != 0.0 ? fabs(plain) / fabs(g->e0) : 0.0;
  if (isnan(ratio) || ratio > g->max_ratio) g->max_ratio = ratio;
  if (isfinite(plain) && ratio <= g->limit) return 0;
  g->fired = 1;
  if (isfinite(plain))
    snprintf(g->message, sizeof g->message, "the run blew up at t = %.6g: the field energy is "
             "%.3g x its initial value (the limit is %g; nothing here injects energy)%s", t,
             ratio, g->limit, g->advice);
  else
    snprintf(g->message, sizeof g->message, "the run blew up at t = %.6g: the field energy is "
             "non-finite (%g x its initial value)%s", t, ratio, g->advice);
  return 1;
}

static int observe(void *ctx, const gm_mesh_maxwell *s) {
  e5_guard *g = ctx;
  gm_mesh_maxwell_energy en;
  gm_mesh_maxwell_energy_get(s, &en);
  const int blew_up = guard_check(g, gm_mesh_maxwell_time(s), en.plain);
  const double dev = fabs(en.plain - g->e0) / g->e0;
  if (!isnan(g->max_dev) && (isnan(dev) || dev > g->max_dev)) g->max_dev = dev; /* NaN sticks */
  return blew_up;
}

/* advance to t in 200 pieces (the same run as one advance_to), reporting progress */
static gm_status advance(gm_mesh_maxwell *s, double t, const gm_e5_config *c) {
  enum { PIECES = 200 };
  const int avi = gm_mesh_maxwell_avi_groups(s) > 0;
  const double t0 = gm_mesh_maxwell_time(s);
  const size_t step0 = gm_mesh_maxwell_step(s);
  double total = avi ? 0.0 : floor(t / gm_mesh_maxwell_dt(s) * (1.0 + 1e-14)) - (double)step0;
  gm_status st = GM_OK;
  for (size_t k = 1; k <= PIECES && st == GM_OK; ++k) {
    st = gm_mesh_maxwell_advance_to(s, k == PIECES ? t : t0 + (t - t0) * (double)k / PIECES);
    const double done = (double)(gm_mesh_maxwell_step(s) - step0);
    if (avi) total = done * PIECES / (double)k; /* updates per unit time are ~constant */
    if (done > total) total = done;
    if (st == GM_OK && c->progress != NULL && c->progress(c->progress_ctx, done, total) != 0)
      st = GM_ECALLBACK;
  }
  return st;
}

/* Create, random E (seed), E_x, E_y, E_z probes at x (every step of the leapfrog, every
 * sample_dt of the AVI; none if x is NULL), the plain energy's largest deviation, advance to
 * t_end. */
static gm_status e5_go(const gm_geometry *g, const gm_mesh_maxwell_options *o,
                       const gm_e5_config *c, const double *x, double sample_dt, double t_end,
                       gm_mesh_maxwell **out, e5_guard *guard, gm_e5_run *r, gm_error *err) {
  *out = NULL;
  gm_mesh_maxwell *s = NULL;
  gm_status st = gm_mesh_maxwell_create(g, NULL, NULL, o, &s, err);
  if (st != GM_OK) return st;
  *out = s;
  const int avi = o->scheme == GM_MESH_AVI;
  const size_t ne = gm_complex_count(gm_geometry_complex(g), 1);
  const size_t nv = gm_complex_count(gm_geometry_complex(g), 0);
  double *E = malloc(ne * sizeof(double)), *gauss0 = malloc((nv ? nv : 1) * sizeof(double));
  if (E == NULL || gauss0 == NULL) {
    free(E);
    free(gauss0);
    return gm_error_set(err, GM_ENOMEM, "e5: out of memory");
  }
  uint64_t seed = c->seed;
  for (size_t e = 0; e < ne; ++e) E[e] = e5_rand(&seed);
  gm_mesh_maxwell_set_fields(s, E, NULL);
  free(E);
  memset(guard, 0, sizeof *guard);
  guard->limit = avi ? E5_BLOWUP_RATIO : INFINITY;
  char advice[200] = "";
  if (avi)
    snprintf(advice, sizeof advice, "; the AVI has no stability bound for neighbouring faces "
             "with different steps: use a smaller --fraction (now %g)", o->avi_fraction);
  guard->advice = advice;
  gm_mesh_maxwell_gauss(s, gauss0);
  if (avi && (st = gm_mesh_maxwell_set_sample_dt(s, sample_dt)) != GM_OK) {
    free(gauss0);
    return gm_error_set(err, st, "%s", gm_mesh_maxwell_errmsg(s));
  }
  const size_t cap = (size_t)(t_end / (avi ? sample_dt : gm_mesh_maxwell_dt(s))) + 4;
  const gm_yee_component comp[3] = {GM_EX, GM_EY, GM_EZ};
  for (int k = 0; x && k < 3 && st == GM_OK; ++k)
    if ((st = gm_mesh_maxwell_add_probe(s, comp[k], x, cap, NULL)) != GM_OK)
      gm_error_set(err, st, "probe: %s", gm_mesh_maxwell_errmsg(s));
  /* the energy 1000 times over the run (AVI: at probe samples) */
  const double every_t = t_end / 1000.0;
  const size_t every = (size_t)(every_t / (avi ? sample_dt : gm_mesh_maxwell_dt(s)));
  if (st == GM_OK && x && (st = gm_mesh_maxwell_add_observer(s, every ? every : 1, observe,
                                                             guard)) != GM_OK)
    gm_error_set(err, st, "observer: %s", gm_mesh_maxwell_errmsg(s));
  gm_mesh_maxwell_energy en;
  if (st == GM_OK && !x) { /* the timed runs have no observer: the start and the end */
    gm_mesh_maxwell_energy_get(s, &en);
    guard_check(guard, 0.0, en.plain);
  }
  if (st != GM_OK) {
    free(gauss0);
    return st;
  }
  const double t0 = cpu_now();
  st = advance(s, t_end, c);
  r->cpu_s = cpu_now() - t0;
  if (st != GM_OK) {
    free(gauss0);
    if (guard->fired) return gm_error_set(err, GM_EDOMAIN, "%s", guard->message);
    return gm_error_set(err, st, "%s%s", st == GM_ECALLBACK && c->progress
                                              ? "stopped by the progress callback"
                                              : gm_mesh_maxwell_errmsg(s), advice);
  }
  gm_mesh_maxwell_energy_get(s, &en);
  if (!x && guard_check(guard, gm_mesh_maxwell_time(s), en.plain)) {
    free(gauss0);
    return gm_error_set(err, GM_EDOMAIN, "%s", guard->message);
  }
  r->ran = 1;
  r->dt = gm_mesh_maxwell_dt(s);
  r->steps = gm_mesh_maxwell_step(s);
  r->avi_groups = gm_mesh_maxwell_avi_groups(s);
  gm_mesh_maxwell_update_counts(s, &r->face_updates, &r->edge_updates);
  /* energy, div B and the drift of Gauss's law (the random E has a divergence; it must stay) */
  r->energy0 = guard->e0;
  r->energy = en.plain;
  r->max_rel_energy_error = guard->max_dev;
  r->max_energy_ratio = guard->max_ratio;
  r->max_div_b = gm_mesh_maxwell_div_b(s);
  double *gv = malloc((nv ? nv : 1) * sizeof(double)), drift = 0.0;
  if (gv == NULL) {
    free(gauss0);
    return gm_error_set(err, GM_ENOMEM, "e5: out of memory");
  }
  gm_mesh_maxwell_gauss(s, gv);
  for (size_t v = 0; v < nv && !isnan(drift); ++v) { /* NaN sticks (fmax would drop it) */
    const double d = fabs(gv[v] - gauss0[v]);
    if (isnan(d) || d > drift) drift = d;
  }
  r->gauss_drift = drift;
  free(gv);
  free(gauss0);
  return GM_OK;
}

/* harminv of the run's probes against the analytic resonances; a copy of its signals */
static gm_status spectrum(const gm_mesh_maxwell *s, const gm_e5_result *res, gm_e5_run *r,
                          gm_error *err) {
  gm_e5_spectrum *x = &r->spectrum;
  x->n_peaks = probe_resonances(s, res->f_lo, res->f_top, x->peaks, GM_E5_MAX_MODES);
  for (size_t i = 0; i < x->n_peaks; ++i) {
    const double rel = nearest_rel(x->peaks[i], res->analytic, res->n_analytic);
    double near = res->analytic[0];
    for (size_t j = 0; j < res->n_analytic; ++j)
      if (fabs(x->peaks[i] - res->analytic[j]) < fabs(x->peaks[i] - near)) near = res->analytic[j];
    x->nearest[i] = near;
    x->rel_error[i] = rel;
    if (rel > 0.05) ++x->spurious;
    else x->worst = fmax(x->worst, rel);
  }
  for (size_t j = 0; j < res->n_check; ++j)
    if (nearest_rel(res->analytic[j], x->peaks, x->n_peaks) <= 0.05) ++x->matched;
  size_t n;
  const double *t, *v[3];
  for (size_t k = 0; k < 3; ++k) gm_mesh_maxwell_probe_samples(s, k, &n, &t, &v[k]);
  if (n < 2) return GM_OK;
  r->signals = malloc(3 * n * sizeof(double));
  if (r->signals == NULL) return gm_error_set(err, GM_ENOMEM, "e5: out of memory");
  for (size_t k = 0; k < 3; ++k) memcpy(r->signals + k * n, v[k], n * sizeof(double));
  r->n_samples = n;
  r->sample_dt = t[1] - t[0];
  return GM_OK;
}

static void star_limits(const gm_complex *cx, const gm_mesh_maxwell *s, gm_e5_result *r) {
  const size_t nf = gm_complex_count(cx, 2);
  const double *lim = gm_mesh_maxwell_face_limits(s);
  double *sorted = malloc((nf ? nf : 1) * sizeof(double));
  size_t n = 0;
  for (size_t f = 0; sorted && f < nf; ++f)
    if (isfinite(lim[f])) sorted[n++] = lim[f];
  if (sorted && n) {
    qsort(sorted, n, sizeof(double), dbl_cmp);
    const double med = sorted[n / 2];
    size_t small = 0;
    while (small < n && sorted[small] < 0.25 * med) ++small;
    r->have_limits = 1;
    r->cfl_limit = gm_mesh_maxwell_cfl_limit(s);
    r->face_limit_min = sorted[0];
    r->face_limit_max = sorted[n - 1];
    r->face_limit_median = med;
    r->small_faces = small;
  }
  free(sorted);
}

gm_status gm_experiment_e5(const gm_mesh *mesh, const gm_e5_config *c, gm_e5_result *r,
                           gm_error *err) {
  memset(r, 0, sizeof *r);
  if (mesh->dim != 3 || mesh->N != 3)
    return gm_error_set(err, GM_EINVAL, "the E5 cavity is a tetrahedral mesh of a box");
  if (!(c->t_end > 0.0) || !isfinite(c->t_end) || !(c->t_compare > 0.0) ||
      !isfinite(c->t_compare) || !(c->sample_dt > 0.0) || !(c->fraction > 0.0 && c->fraction <= 1.0) ||
      !(c->f_max > 0.0) || !isfinite(c->f_max))
    return gm_error_set(err, GM_EINVAL, "e5: t_end %g, t_compare %g, sample_dt %g and f_max %g "
                        "must be finite and > 0, fraction %g in (0, 1]", c->t_end, c->t_compare,
                        c->sample_dt, c->f_max, c->fraction);
  const double wall0 = gm_experiment_clock();
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t v = 0; v < mesh->n_vertices; ++v)
    for (int d = 0; d < 3; ++d) {
      lo[d] = fmin(lo[d], mesh->x[3 * v + (size_t)d]);
      hi[d] = fmax(hi[d], mesh->x[3 * v + (size_t)d]);
    }
  for (int d = 0; d < 3; ++d) r->L[d] = hi[d] - lo[d];
  r->n_analytic = box_resonances(r->L, c->f_max, r->analytic, GM_E5_MAX_MODES);
  if (r->n_analytic == 0)
    return gm_error_set(err, GM_EINVAL, "e5: no resonance of the box below f_max = %g",
                        c->f_max);
  r->n_check = r->n_analytic < 10 ? r->n_analytic : 10; /* the first 10 distinct resonances */
  r->f_lo = 0.5 * r->analytic[0];
  r->f_top = r->analytic[r->n_check - 1] * 1.02;
  const double *L = r->L;
  r->probe[0] = lo[0] + 0.31 * L[0];
  r->probe[1] = lo[1] + 0.27 * L[1];
  r->probe[2] = lo[2] + 0.19 * L[2];

  gm_complex *cx = NULL;
  gm_geometry *g = NULL;
  gm_mesh_maxwell *s = NULL;
  e5_guard guard;
  gm_status st = gm_mesh_complex(mesh, &cx, err);
  if (st == GM_OK) st = gm_geometry_create(cx, NULL, &g, err);
  if (st != GM_OK) {
    st = st == GM_ENOMEM ? st : GM_EINVAL;
    goto done;
  }
  /* 1. the mesh and its circumcentric stars */
  const double *vol = gm_geometry_primal_volumes(g, 3);
  r->volume_min = INFINITY;
  for (size_t T = 0; T < gm_complex_count(cx, 3); ++T)
    r->volume_min = fmin(r->volume_min, vol[T]), r->volume_max = fmax(r->volume_max, vol[T]);
  r->n_tetrahedra = gm_complex_count(cx, 3);
  r->n_edges = gm_complex_count(cx, 1);
  r->n_faces = gm_complex_count(cx, 2);
  gm_mesh_maxwell_options oa = gm_mesh_maxwell_defaults();
  oa.scheme = GM_MESH_AVI;
  oa.avi_fraction = c->fraction;
  oa.avi_levels = 1;
  gm_error star_err = {{0}};
  r->positive = gm_mesh_maxwell_create(g, NULL, NULL, &oa, &s, &star_err) == GM_OK;
  if (r->positive) star_limits(cx, s, r);
  else snprintf(r->star_message, sizeof r->star_message, "%s", star_err.message);
  gm_mesh_maxwell_free(s);
  s = NULL;

  /* 2. the AVI */
  if (r->positive) {
    if ((st = e5_go(g, &oa, c, r->probe, c->sample_dt, c->t_end, &s, &guard, &r->avi, err)) !=
        GM_OK)
      goto done;
    if ((st = spectrum(s, r, &r->avi, err)) != GM_OK) goto done;
    gm_mesh_maxwell_free(s);
    s = NULL;
  }
  /* 3. the Whitney leapfrog */
  gm_mesh_maxwell_options ow = gm_mesh_maxwell_defaults();
  ow.star = GM_MESH_STAR_WHITNEY;
  if ((st = e5_go(g, &ow, c, r->probe, 0.0, c->t_end, &s, &guard, &r->whitney, err)) != GM_OK)
    goto done;
  if ((st = spectrum(s, r, &r->whitney, err)) != GM_OK) goto done;
  gm_mesh_maxwell_free(s);
  s = NULL;

  /* 4. cost to t_compare */
  if (r->positive) {
    gm_e5_run ac = {0}, uc = {0}, wc = {0};
    if ((st = e5_go(g, &oa, c, NULL, c->sample_dt, c->t_compare, &s, &guard, &ac, err)) != GM_OK)
      goto done;
    gm_mesh_maxwell_free(s);
    s = NULL;
    gm_mesh_maxwell_options ou = gm_mesh_maxwell_defaults();
    ou.dt = ac.dt; /* the AVI's smallest face step */
    if ((st = e5_go(g, &ou, c, NULL, 0.0, c->t_compare, &s, &guard, &uc, err)) != GM_OK)
      goto done;
    gm_mesh_maxwell_free(s);
    s = NULL;
    if ((st = e5_go(g, &ow, c, NULL, 0.0, c->t_compare, &s, &guard, &wc, err)) != GM_OK)
      goto done;
    r->uniform_dt = ou.dt;
    r->uniform_steps = uc.steps;
    r->uniform_face_updates = (double)uc.face_updates;
    r->uniform_cpu_s = uc.cpu_s;
    r->avi_face_updates = ac.face_updates;
    r->avi_cpu_s = ac.cpu_s;
    r->whitney_steps = wc.steps;
    r->whitney_cpu_s = wc.cpu_s;
  }
  r->wall_s = gm_experiment_clock() - wall0;
done:
  gm_mesh_maxwell_free(s);
  gm_geometry_free(g);
  gm_complex_free(cx);
  if (st != GM_OK) gm_e5_result_clear(r);
  return st;
}

gm_status gm_experiment_run_e5(const char *dir, gm_experiment_result *result, gm_error *err) {
  (void)dir; /* numbers only; the spectrum figure is the command's */
  static const char path[] = "examples/e5_cavity.msh"; /* as the row's command: from the repo */
  gm_mesh *mesh = NULL;
  gm_status st = gm_mesh_read(path, &mesh, err);
  if (st != GM_OK) {
    char why[GM_ERRMSG_SIZE];
    snprintf(why, sizeof why, "%s", err->message);
    return gm_error_set(err, st, "e5 reads %s from the working directory (run it in the "
                        "geomint source tree): %s", path, why);
  }
  gm_e5_config c = gm_e5_defaults();
  gm_e5_result r;
  st = gm_experiment_e5(mesh, &c, &r, err);
  gm_mesh_free(mesh);
  if (st != GM_OK) return st;
  const gm_e5_run *x = r.positive ? &r.avi : &r.whitney;
  gm_experiment_add(result, "peaks", (double)x->spectrum.n_peaks);
  gm_experiment_add(result, "matched", (double)x->spectrum.matched);
  gm_experiment_add(result, "spurious", (double)x->spectrum.spurious);
  gm_experiment_add(result, "max_rel_frequency_error", x->spectrum.worst);
  gm_experiment_add(result, "max_rel_energy_error", x->max_rel_energy_error);
  if (r.positive) {
    gm_experiment_add(result, "face_update_ratio",
                      (double)r.avi_face_updates / r.uniform_face_updates);
    gm_experiment_add(result, "cpu_ratio_avi_uniform", r.avi_cpu_s / r.uniform_cpu_s);
  }
  gm_experiment_add(result, "wall_s", r.wall_s);
  gm_e5_result_clear(&r);
  return GM_OK;
}
