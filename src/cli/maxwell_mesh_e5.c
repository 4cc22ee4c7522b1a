/* geomint maxwell mesh CAVITY.msh --e5: seed 000 experiment E5 (notes §2) as one command, on
 * the Gmsh cavity (a box meshed with tetrahedra refined near the walls, examples/e5_cavity.msh).
 *  1. The circumcentric stars are checked. Gmsh's Delaunay mesh, left unoptimised
 *     (examples/e5_cavity.geo), has positive ⋆_ε on every interior edge and ⋆_ν on every
 *     interior face: for a Delaunay tetrahedralisation the circumcentric dual of an interior
 *     edge is its Voronoi face and the dual of an interior face the Voronoi edge between two
 *     circumcentres, both of positive measure — well-centredness is sufficient, not necessary.
 *     Near-cospherical vertex sets (the box's corners and edges) give a few tiny dual cells,
 *     hence tiny local CFL limits there: the case the AVI is for.
 *  2. The AVI, every face at --fraction of its local limit (power-of-two levels), random initial
 *     E, E at one point sampled every --sample time, harminv resonances against the analytic
 *     ones of the box (every peak within 5 % of one: else "spurious"), energy and the
 *     invariants, the spectrum with the analytic resonances marked (e5-spectrum.png).
 *  3. The consistent (Whitney) star's leapfrog on the same mesh, its resonances the same way
 *     (the reference discretisation; CHOLMOD at each step, CFL limit unaffected by the
 *     near-cospherical cells).
 *  4. Cost to --t-compare: the AVI against uniform leapfrog stepping (diagonal star) at the
 *     AVI's smallest face step, the smallest stable step of the finest cells: face updates,
 *     CPU time and their ratios; and the Whitney leapfrog's CPU time to the same time.
 * If the stars are not positive (a mesh made with Gmsh's optimisers), 2 and 4 are skipped with
 * the count, and 3 runs. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli/cli.h"
#include "cli/maxwell.h"
#include "cli/maxwell_mesh.h"

#define E5 "maxwell mesh --e5"
#define E5_MAX_MODES 64

static double cpu_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

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

/* Distinct resonances f = ½ √((m/a)² + (n/b)² + (p/c)²) of the PEC box (at most one index
 * zero), ascending, up to f_max; returns the count (<= cap). */
static size_t box_resonances(const double L[3], double f_max, double *out, size_t cap) {
  size_t n = 0;
  double all[4096];
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
  return k;
}

/* The resonances harminv finds (error < 1e-3) in the three probe signals, merged within 0.3 %.
 * Every step's sample is used: decimating the signal aliases the grid-scale modes of the random
 * initial field into the band (7 spurious peaks of 17 with every 6th sample). */
static size_t probe_resonances(const gm_mesh_maxwell *s, double f_lo, double f_hi, double *out,
                               size_t cap) {
  size_t k = 0;
  double all[3 * E5_MAX_MODES];
  for (size_t id = 0; id < 3; ++id) {
    size_t n;
    const double *t, *v;
    if (gm_mesh_maxwell_probe_samples(s, id, &n, &t, &v) != GM_OK || n < 16) continue;
    const double dt = t[1] - t[0];
    const size_t stride = 1;
    const size_t m = n / stride;
    double *w = malloc((m ? m : 1) * sizeof(double));
    if (!w) continue;
    for (size_t i = 0; i < m; ++i) w[i] = v[i * stride];
    gm_harminv_mode modes[E5_MAX_MODES];
    size_t nm = 0;
    gm_error err = {{0}};
    const gm_status st =
        gm_harminv(m, w, NULL, dt * (double)stride, f_lo, f_hi, 0, E5_MAX_MODES, modes, &nm, &err);
    free(w);
    if (st != GM_OK) continue;
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

typedef struct e5_run {
  gm_mesh_maxwell *s;
  double *gauss0; /* owned: the Gauss residual per vertex at the start */
  double cpu, max_dev;
  size_t faces, edges;
  mm_guard guard; /* guard.e0: the plain energy at t_0 */
} e5_run;

static void e5_run_free(e5_run *r) {
  gm_mesh_maxwell_free(r->s);
  free(r->gauss0);
}

static int e5_observe(void *ctx, const gm_mesh_maxwell *s) {
  e5_run *r = ctx;
  gm_mesh_maxwell_energy en;
  gm_mesh_maxwell_energy_get(s, &en);
  const int blew_up = mm_guard_check(&r->guard, gm_mesh_maxwell_time(s), en.plain);
  const double dev = fabs(en.plain - r->guard.e0) / r->guard.e0;
  if (!isnan(r->max_dev) && (isnan(dev) || dev > r->max_dev)) r->max_dev = dev; /* NaN sticks */
  return blew_up;
}

/* Create, random E (seed), E_x, E_y, E_z probes at x (sampled every step of the leapfrog, every
 * sample_dt of the AVI; none if x is NULL), the plain energy's largest deviation, advance to
 * t_end; s is owned by the caller. */
static int e5_go(const gm_geometry *g, const gm_mesh_maxwell_options *o, uint64_t seed,
                 const double *x, double sample_dt, double t_end, e5_run *r) {
  gm_error err = {{0}};
  memset(r, 0, sizeof *r);
  if (gm_mesh_maxwell_create(g, NULL, NULL, o, &r->s, &err) != GM_OK) {
    cli_error(E5, "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  const int avi = o->scheme == GM_MESH_AVI;
  const size_t ne = gm_complex_count(gm_geometry_complex(g), 1);
  double *E = malloc(ne * sizeof(double));
  if (!E) return CLI_EXIT_FAILURE;
  for (size_t e = 0; e < ne; ++e) E[e] = e5_rand(&seed);
  gm_mesh_maxwell_set_fields(r->s, E, NULL);
  free(E);
  r->guard.command = E5;
  r->guard.limit = avi ? MM_BLOWUP_RATIO : INFINITY;
  if (avi)
    snprintf(r->guard.advice, sizeof r->guard.advice, "; the AVI has no stability bound for "
             "neighbouring faces with different steps: use a smaller --fraction (now %g)",
             o->avi_fraction);
  r->gauss0 = malloc(gm_complex_count(gm_geometry_complex(g), 0) * sizeof(double));
  if (!r->gauss0) return CLI_EXIT_FAILURE;
  gm_mesh_maxwell_gauss(r->s, r->gauss0);
  if (avi && gm_mesh_maxwell_set_sample_dt(r->s, sample_dt) != GM_OK) {
    cli_error(E5, "%s", gm_mesh_maxwell_errmsg(r->s));
    return CLI_EXIT_FAILURE;
  }
  const size_t cap = (size_t)(t_end / (avi ? sample_dt : gm_mesh_maxwell_dt(r->s))) + 4;
  const gm_yee_component comp[3] = {GM_EX, GM_EY, GM_EZ};
  for (int c = 0; x && c < 3; ++c)
    if (gm_mesh_maxwell_add_probe(r->s, comp[c], x, cap, NULL) != GM_OK) {
      cli_error(E5, "probe: %s", gm_mesh_maxwell_errmsg(r->s));
      return CLI_EXIT_FAILURE;
    }
  /* the energy 1000 times over the run (AVI: at probe samples) */
  const double every_t = t_end / 1000.0;
  size_t every = (size_t)(every_t / (avi ? sample_dt : gm_mesh_maxwell_dt(r->s)));
  if (x && gm_mesh_maxwell_add_observer(r->s, every ? every : 1, e5_observe, r) != GM_OK) {
    cli_error(E5, "observer: %s", gm_mesh_maxwell_errmsg(r->s));
    return CLI_EXIT_FAILURE;
  }
  gm_mesh_maxwell_energy en;
  if (!x) { /* the timed runs have no observer: the guard looks at the start and the end */
    gm_mesh_maxwell_energy_get(r->s, &en);
    mm_guard_check(&r->guard, 0.0, en.plain);
  }
  const double t0 = cpu_now();
  const gm_status st = mm_advance_progress(r->s, t_end);
  r->cpu = cpu_now() - t0;
  if (st != GM_OK) {
    if (!r->guard.fired) cli_error(E5, "%s%s", gm_mesh_maxwell_errmsg(r->s), r->guard.advice);
    return CLI_EXIT_FAILURE;
  }
  if (!x) {
    gm_mesh_maxwell_energy_get(r->s, &en);
    if (mm_guard_check(&r->guard, gm_mesh_maxwell_time(r->s), en.plain)) return CLI_EXIT_FAILURE;
  }
  gm_mesh_maxwell_update_counts(r->s, &r->faces, &r->edges);
  return CLI_EXIT_OK;
}

/* harminv of run r's probes in (f_lo, f_top) against the analytic resonances: a table, the
 * count of spurious peaks (none within 5 % of an analytic resonance) and of the first n_check
 * analytic resonances seen; writes *n_found peaks to found. */
static void e5_spectrum(const e5_run *r, const double *ana, size_t n_ana, size_t n_check,
                        double f_lo, double f_top, double *found, size_t *n_found) {
  *n_found = probe_resonances(r->s, f_lo, f_top, found, E5_MAX_MODES);
  size_t spurious = 0, matched = 0;
  double worst = 0.0;
  printf("   %-12s %-12s %s\n", "harminv", "analytic", "rel. error");
  for (size_t i = 0; i < *n_found; ++i) {
    const double rel = nearest_rel(found[i], ana, n_ana);
    double near = ana[0];
    for (size_t j = 0; j < n_ana; ++j)
      if (fabs(found[i] - ana[j]) < fabs(found[i] - near)) near = ana[j];
    printf("   %-12.5f %-12.5f %.2e%s\n", found[i], near, rel, rel > 0.05 ? "  SPURIOUS" : "");
    if (rel > 0.05) ++spurious;
    else worst = fmax(worst, rel);
  }
  for (size_t j = 0; j < n_check; ++j)
    if (nearest_rel(ana[j], found, *n_found) <= 0.05) ++matched;
  printf("   first %zu analytic resonances: %zu seen at the probe; %zu peaks, %zu spurious, worst "
         "error of the others %.2e\n", n_check, matched, *n_found, spurious, worst);
}

/* Energy, div B and the drift of Gauss's law (the random E has a divergence; it must not move). */
static int e5_invariants(const e5_run *r, size_t nv) {
  gm_mesh_maxwell_energy en;
  gm_mesh_maxwell_energy_get(r->s, &en);
  double *g = malloc((nv ? nv : 1) * sizeof(double)), drift = 0.0;
  if (!g) return CLI_EXIT_FAILURE;
  gm_mesh_maxwell_gauss(r->s, g);
  for (size_t v = 0; v < nv && !isnan(drift); ++v) { /* NaN sticks (fmax would drop it) */
    const double d = fabs(g[v] - r->gauss0[v]);
    if (isnan(d) || d > drift) drift = d;
  }
  free(g);
  printf("   energy: start %.10g, end %.10g, max |E(t) - E0|/E0 %.3e over 1000 samples (max "
         "E/E0 %.4g); max |div B| %.2e, Gauss drift %.2e\n", r->guard.e0, en.plain, r->max_dev,
         r->guard.max_ratio, gm_mesh_maxwell_div_b(r->s), drift);
  return CLI_EXIT_OK;
}

/* The spectrum figure: the three probe signals of r (sampled at interval dt). */
static void e5_plot(const e5_run *r, const char *out_dir, const char *title, double f_top,
                    const double *ana, size_t n_check) {
  char png[4096];
  snprintf(png, sizeof png, "%s/e5-spectrum.png", out_dir);
  size_t n;
  const double *t, *v[3];
  for (size_t c = 0; c < 3; ++c) gm_mesh_maxwell_probe_samples(r->s, c, &n, &t, &v[c]);
  double *sig = n > 1 ? malloc(3 * n * sizeof(double)) : NULL;
  if (!sig) return;
  for (size_t c = 0; c < 3; ++c) memcpy(sig + c * n, v[c], n * sizeof(double));
  if (cli_gnuplot_available() &&
      mx_plot_spectrum(E5, png, title, 3, n, sig, t[1] - t[0], f_top * 1.1, ana, n_check) ==
          CLI_EXIT_OK)
    printf("   wrote %s\n", png);
  free(sig);
}

int cli_maxwell_mesh_e5(const gm_mesh *mesh, const char *out_dir, double t_end, uint64_t seed,
                        double f_max, double fraction, double sample_dt, double t_compare) {
  gm_error err = {{0}};
  if (mesh->dim != 3 || mesh->N != 3) {
    cli_error(E5, "the E5 cavity is a tetrahedral mesh of a box");
    return CLI_EXIT_USAGE;
  }
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, L[3];
  for (size_t v = 0; v < mesh->n_vertices; ++v)
    for (int d = 0; d < 3; ++d) {
      lo[d] = fmin(lo[d], mesh->x[3 * v + (size_t)d]);
      hi[d] = fmax(hi[d], mesh->x[3 * v + (size_t)d]);
    }
  for (int d = 0; d < 3; ++d) L[d] = hi[d] - lo[d];
  if (out_dir && mx_make_dir(E5, out_dir) != CLI_EXIT_OK) return CLI_EXIT_FAILURE;
  double ana[E5_MAX_MODES];
  const size_t n_ana = box_resonances(L, f_max, ana, E5_MAX_MODES);
  const size_t n_check = n_ana < 10 ? n_ana : 10; /* the first 10 distinct resonances */
  const double f_lo = 0.5 * ana[0], f_top = n_check ? ana[n_check - 1] * 1.02 : f_max;
  const double x[3] = {lo[0] + 0.31 * L[0], lo[1] + 0.27 * L[1], lo[2] + 0.19 * L[2]};
  printf("E5: PEC box %.4g x %.4g x %.4g, random initial E (seed %llu), t = %g, E at (%.3g, "
         "%.3g, %.3g)\n", L[0], L[1], L[2], (unsigned long long)seed, t_end, x[0], x[1], x[2]);

  gm_complex *cx = NULL;
  gm_geometry *g = NULL;
  e5_run avi = {0}, wh = {0}, ac = {0}, uc = {0}, wc = {0};
  int status = CLI_EXIT_FAILURE;
  if (gm_mesh_complex(mesh, &cx, &err) != GM_OK || gm_geometry_create(cx, NULL, &g, &err) != GM_OK) {
    cli_error(E5, "%s", err.message);
    status = CLI_EXIT_USAGE;
    goto done;
  }
  /* 1. the mesh and its circumcentric stars */
  const double *vol = gm_geometry_primal_volumes(g, 3);
  double vmin = INFINITY, vmax = 0.0;
  for (size_t T = 0; T < gm_complex_count(cx, 3); ++T) vmin = fmin(vmin, vol[T]), vmax = fmax(vmax, vol[T]);
  printf("1. Gmsh mesh: %zu tetrahedra, %zu edges, %zu faces; cell volumes %.3g .. %.3g (ratio "
         "%.0f)\n", gm_complex_count(cx, 3), gm_complex_count(cx, 1),
         gm_complex_count(cx, 2), vmin, vmax, vmax / vmin);
  gm_mesh_maxwell_options oa = gm_mesh_maxwell_defaults();
  oa.scheme = GM_MESH_AVI;
  oa.avi_fraction = fraction;
  oa.avi_levels = 1;
  gm_mesh_maxwell *probe_star = NULL;
  const int positive = gm_mesh_maxwell_create(g, NULL, NULL, &oa, &probe_star, &err) == GM_OK;
  if (positive) {
    const size_t nf = gm_complex_count(cx, 2);
    const double *lim = gm_mesh_maxwell_face_limits(probe_star);
    double *sorted = malloc((nf ? nf : 1) * sizeof(double));
    size_t n = 0;
    for (size_t f = 0; sorted && f < nf; ++f)
      if (isfinite(lim[f])) sorted[n++] = lim[f];
    if (sorted && n) {
      qsort(sorted, n, sizeof(double), dbl_cmp);
      const double med = sorted[n / 2];
      size_t small = 0;
      while (small < n && sorted[small] < 0.25 * med) ++small;
      printf("   circumcentric stars: positive on every interior edge and face (the mesh is "
             "Delaunay)\n   CFL limit of the whole mesh %.3g; local face limits %.3g .. %.3g, "
             "median %.3g; %zu faces below 1/4 of the median (near-cospherical vertices)\n",
             gm_mesh_maxwell_cfl_limit(probe_star), sorted[0], sorted[n - 1], med, small);
    }
    free(sorted);
    gm_mesh_maxwell_free(probe_star);
  } else {
    printf("   circumcentric stars: %s\n   -> the AVI cannot run here (it needs a positive "
           "diagonal star): make the mesh with examples/e5_cavity.geo (Delaunay, no "
           "optimisation); the Whitney leapfrog runs alone\n", err.message);
  }

  /* 2. the AVI */
  double found[E5_MAX_MODES];
  size_t n_found;
  if (positive) {
    if ((status = e5_go(g, &oa, seed, x, sample_dt, t_end, &avi)) != CLI_EXIT_OK) goto done;
    printf("2. AVI: every face at %.2g of its local limit in %zu power-of-two groups, smallest "
           "step %.3g; E sampled every %.3g; %zu face updates, %.2f s CPU\n", fraction,
           gm_mesh_maxwell_avi_groups(avi.s), gm_mesh_maxwell_dt(avi.s), sample_dt, avi.faces,
           avi.cpu);
    e5_spectrum(&avi, ana, n_ana, n_check, f_lo, f_top, found, &n_found);
    if ((status = e5_invariants(&avi, gm_complex_count(cx, 0))) != CLI_EXIT_OK) goto done;
    if (out_dir)
      e5_plot(&avi, out_dir, "E5: Gmsh cavity refined near the walls, AVI (diagonal star); "
              "dashed: analytic resonances", f_top, ana, n_check);
  }

  /* 3. the Whitney leapfrog */
  gm_mesh_maxwell_options ow = gm_mesh_maxwell_defaults();
  ow.star = GM_MESH_STAR_WHITNEY;
  if ((status = e5_go(g, &ow, seed, x, 0.0, t_end, &wh)) != CLI_EXIT_OK) goto done;
  printf("3. leapfrog, Whitney star (CHOLMOD): dt %.4g (0.9 of its CFL limit), %zu steps, %.2f s "
         "CPU\n", gm_mesh_maxwell_dt(wh.s), gm_mesh_maxwell_step(wh.s), wh.cpu);
  e5_spectrum(&wh, ana, n_ana, n_check, f_lo, f_top, found, &n_found);
  if ((status = e5_invariants(&wh, gm_complex_count(cx, 0))) != CLI_EXIT_OK) goto done;
  if (out_dir && !positive)
    e5_plot(&wh, out_dir, "E5: Gmsh cavity refined near the walls, leapfrog (Whitney star); "
            "dashed: analytic resonances", f_top, ana, n_check);

  /* 4. cost to t_compare */
  if (positive) {
    if ((status = e5_go(g, &oa, seed, NULL, sample_dt, t_compare, &ac)) != CLI_EXIT_OK) goto done;
    gm_mesh_maxwell_options ou = gm_mesh_maxwell_defaults();
    ou.dt = gm_mesh_maxwell_dt(ac.s); /* the AVI's smallest face step */
    if ((status = e5_go(g, &ou, seed, NULL, 0.0, t_compare, &uc)) != CLI_EXIT_OK) goto done;
    if ((status = e5_go(g, &ow, seed, NULL, 0.0, t_compare, &wc)) != CLI_EXIT_OK) goto done;
    const double uni_faces = (double)uc.faces;
    printf("4. cost to t = %g:\n   uniform leapfrog (diagonal star) at the AVI's smallest step "
           "%.4g: %zu steps, %.0f face updates, %.3f s CPU\n", t_compare, ou.dt,
           gm_mesh_maxwell_step(uc.s), uni_faces, uc.cpu);
    printf("   AVI: %zu face updates, ratio to uniform %.4f; %.3f s CPU: time ratio AVI/uniform "
           "%.4f (%s)\n", ac.faces, (double)ac.faces / uni_faces, ac.cpu, ac.cpu / uc.cpu,
           ac.cpu < uc.cpu ? "faster" : "NOT faster");
    printf("   leapfrog, Whitney star at its own step: %zu steps, %.3f s CPU: time ratio "
           "AVI/Whitney %.3f (%s)\n", gm_mesh_maxwell_step(wc.s), wc.cpu, ac.cpu / wc.cpu,
           ac.cpu < wc.cpu ? "the AVI is faster" : "the Whitney leapfrog is faster");
  }
  status = CLI_EXIT_OK;
done:
  e5_run_free(&avi);
  e5_run_free(&wh);
  e5_run_free(&ac);
  e5_run_free(&uc);
  e5_run_free(&wc);
  gm_geometry_free(g);
  gm_complex_free(cx);
  return status;
}
