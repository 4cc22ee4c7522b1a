/* geomint maxwell mesh CAVITY.msh --e5: seed 000 experiment E5 (notes §2) as one command.
 *  1. The Gmsh cavity (a box meshed with tetrahedra refined near the walls, e.g.
 *     examples/e5_cavity.msh): its circumcentric star is checked (Gmsh meshes are not
 *     well-centred, so the count of non-positive entries is printed and the Whitney star is
 *     used), random initial E, the leapfrog, E at one point every step, harminv resonances
 *     against the analytic ones of the box (every peak within 5 % of one: else "spurious"),
 *     and the spectrum with the analytic resonances marked (e5-spectrum.png).
 *  2. The AVI needs a diagonal star, hence a well-centred mesh, which Gmsh does not give: it
 *     runs on body-centred cubic tetrahedra of the same box (gm_mesh_bcc, without the boundary
 *     pyramids) mapped by an inversion in a sphere (conformal: the cells keep their shape and
 *     stay well-centred, create checks it; their size falls by 11× across the cavity — a
 *     per-axis grading x ↦ x − α sin(2πx)/(2π) stays well-centred only up to α ≈ 0.1, local
 *     limits within 1.9×, too little for the AVI to gain), every face at --fraction of its
 *     local limit (power-of-two levels), against uniform leapfrog stepping at the AVI's smallest
 *     step (the smallest stable step of the refined region): element updates, CPU time and the
 *     ratio, and the two runs' resonances against each other (the inverted cavity has no
 *     analytic spectrum). */
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
  double cpu;
  size_t faces, edges;
} e5_run;

/* Create, random E (seed), three E probes at x, advance to t_end; s is owned by the caller. */
static int e5_go(const gm_geometry *g, const gm_mesh_maxwell_options *o, uint64_t seed,
                 const double x[3], double t_end, e5_run *r) {
  gm_error err = {{0}};
  memset(r, 0, sizeof *r);
  if (gm_mesh_maxwell_create(g, NULL, NULL, o, &r->s, &err) != GM_OK) {
    cli_error(E5, "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  const size_t ne = gm_complex_count(gm_geometry_complex(g), 1);
  double *E = malloc(ne * sizeof(double));
  if (!E) return CLI_EXIT_FAILURE;
  for (size_t e = 0; e < ne; ++e) E[e] = e5_rand(&seed);
  gm_mesh_maxwell_set_fields(r->s, E, NULL);
  free(E);
  const size_t cap = (size_t)(t_end / gm_mesh_maxwell_dt(r->s)) + 4;
  const gm_yee_component comp[3] = {GM_EX, GM_EY, GM_EZ};
  for (int c = 0; c < 3; ++c)
    if (gm_mesh_maxwell_add_probe(r->s, comp[c], x, cap, NULL) != GM_OK) {
      cli_error(E5, "probe: %s", gm_mesh_maxwell_errmsg(r->s));
      return CLI_EXIT_FAILURE;
    }
  const double t0 = cpu_now();
  if (gm_mesh_maxwell_advance_to(r->s, t_end) != GM_OK) {
    cli_error(E5, "%s", gm_mesh_maxwell_errmsg(r->s));
    return CLI_EXIT_FAILURE;
  }
  r->cpu = cpu_now() - t0;
  gm_mesh_maxwell_update_counts(r->s, &r->faces, &r->edges);
  return CLI_EXIT_OK;
}

int cli_maxwell_mesh_e5(const gm_mesh *mesh, const char *out_dir, double t_end, uint64_t seed,
                        double f_max, double fraction) {
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

  /* 1. the Gmsh mesh */
  gm_complex *cx = NULL;
  gm_geometry *g = NULL;
  gm_mesh *bcc = NULL;
  gm_complex *cx2 = NULL;
  gm_geometry *g2 = NULL;
  e5_run wh = {0}, avi = {0}, uni = {0};
  int status = CLI_EXIT_FAILURE;
  if (gm_mesh_complex(mesh, &cx, &err) != GM_OK || gm_geometry_create(cx, NULL, &g, &err) != GM_OK) {
    cli_error(E5, "%s", err.message);
    status = CLI_EXIT_USAGE;
    goto done;
  }
  const double *vol = gm_geometry_primal_volumes(g, 3);
  double vmin = INFINITY, vmax = 0.0;
  for (size_t T = 0; T < gm_complex_count(cx, 3); ++T) vmin = fmin(vmin, vol[T]), vmax = fmax(vmax, vol[T]);
  printf("1. Gmsh mesh: %zu tetrahedra, %zu edges, %zu faces; cell volumes %.3g .. %.3g (ratio "
         "%.0f: refined near the walls)\n", gm_complex_count(cx, 3), gm_complex_count(cx, 1),
         gm_complex_count(cx, 2), vmin, vmax, vmax / vmin);
  gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
  gm_mesh_maxwell *probe_star = NULL;
  if (gm_mesh_maxwell_create(g, NULL, NULL, &o, &probe_star, &err) == GM_OK) {
    printf("   circumcentric star: positive (well-centred)\n");
    gm_mesh_maxwell_free(probe_star);
  } else {
    printf("   circumcentric star: %s -> the Whitney star (CHOLMOD); the AVI cannot run here\n",
           err.message);
    o.star = GM_MESH_STAR_WHITNEY;
  }
  if ((status = e5_go(g, &o, seed, x, t_end, &wh)) != CLI_EXIT_OK) goto done;
  double found[E5_MAX_MODES];
  const size_t n_found = probe_resonances(wh.s, f_lo, f_top, found, E5_MAX_MODES);
  size_t spurious = 0, matched = 0;
  double worst = 0.0;
  printf("   leapfrog dt %.4g (0.9 of the CFL limit), %zu steps, %.2f s CPU\n",
         gm_mesh_maxwell_dt(wh.s), gm_mesh_maxwell_step(wh.s), wh.cpu);
  printf("   %-12s %-12s %s\n", "harminv", "analytic", "rel. error");
  for (size_t i = 0; i < n_found; ++i) {
    const double r = nearest_rel(found[i], ana, n_ana);
    double near = ana[0];
    for (size_t j = 0; j < n_ana; ++j) if (fabs(found[i] - ana[j]) < fabs(found[i] - near)) near = ana[j];
    printf("   %-12.5f %-12.5f %.2e%s\n", found[i], near, r, r > 0.05 ? "  SPURIOUS" : "");
    if (r > 0.05) ++spurious;
    else worst = fmax(worst, r);
  }
  for (size_t j = 0; j < n_check; ++j)
    if (nearest_rel(ana[j], found, n_found) <= 0.05) ++matched;
  printf("   first %zu analytic resonances: %zu seen at the probe; %zu peaks, %zu spurious, worst "
         "error of the others %.2e\n", n_check, matched, n_found, spurious, worst);
  if (out_dir) {
    char png[4096];
    snprintf(png, sizeof png, "%s/e5-spectrum.png", out_dir);
    size_t n;
    const double *t, *v0, *v1, *v2;
    gm_mesh_maxwell_probe_samples(wh.s, 0, &n, &t, &v0);
    gm_mesh_maxwell_probe_samples(wh.s, 1, &n, &t, &v1);
    gm_mesh_maxwell_probe_samples(wh.s, 2, &n, &t, &v2);
    double *sig = malloc(3 * n * sizeof(double));
    if (sig && n > 1) {
      memcpy(sig, v0, n * sizeof(double));
      memcpy(sig + n, v1, n * sizeof(double));
      memcpy(sig + 2 * n, v2, n * sizeof(double));
      if (cli_gnuplot_available() &&
          mx_plot_spectrum(E5, png, "E5: Gmsh cavity refined near the walls, leapfrog (Whitney "
                           "star); dashed: analytic resonances", 3, n, sig, t[1] - t[0],
                           f_top * 1.1, ana, n_check) == CLI_EXIT_OK)
        printf("   wrote %s\n", png);
    }
    free(sig);
  }

  /* 2. the AVI against uniform stepping on a well-centred mesh refined towards the walls */
  const double h = 0.1 * L[0];
  size_t nc[3];
  for (int d = 0; d < 3; ++d) nc[d] = (size_t)lround(L[d] / h) < 2 ? 2 : (size_t)lround(L[d] / h);
  if (gm_mesh_bcc(lo, hi, nc[0], nc[1], nc[2], 0, &bcc, &err) != GM_OK) {
    cli_error(E5, "%s", err.message);
    goto done;
  }
  /* inversion in the sphere of radius d about p = lo − d e_x + centre of the x = lo face: a
     Möbius map, conformal, so the tetrahedra keep their shape to first order and stay
     well-centred (create checks it), while their size falls as d²/|x − p|² */
  const double d_inv = 0.3 * L[0];
  const double p_inv[3] = {lo[0] - d_inv, lo[1] + 0.5 * L[1], lo[2] + 0.5 * L[2]};
  for (size_t v = 0; v < bcc->n_vertices; ++v) {
    double *y = bcc->x + 3 * v, r2 = 0.0;
    for (int d = 0; d < 3; ++d) r2 += (y[d] - p_inv[d]) * (y[d] - p_inv[d]);
    for (int d = 0; d < 3; ++d) y[d] = p_inv[d] + (y[d] - p_inv[d]) * d_inv * d_inv / r2;
  }
  if (gm_mesh_complex(bcc, &cx2, &err) != GM_OK || gm_geometry_create(cx2, NULL, &g2, &err) != GM_OK) {
    cli_error(E5, "%s", err.message);
    goto done;
  }
  gm_mesh_maxwell_options oa = gm_mesh_maxwell_defaults();
  oa.scheme = GM_MESH_AVI;
  oa.avi_fraction = fraction;
  oa.avi_levels = 1;
  double xi[3], r2x = 0.0; /* the probe point's image */
  for (int d = 0; d < 3; ++d) r2x += (x[d] - p_inv[d]) * (x[d] - p_inv[d]);
  for (int d = 0; d < 3; ++d) xi[d] = p_inv[d] + (x[d] - p_inv[d]) * d_inv * d_inv / r2x;
  if ((status = e5_go(g2, &oa, seed, xi, t_end, &avi)) != CLI_EXIT_OK) goto done;
  gm_mesh_maxwell_options ou = gm_mesh_maxwell_defaults();
  ou.dt = gm_mesh_maxwell_dt(avi.s); /* the AVI's smallest face step */
  if ((status = e5_go(g2, &ou, seed, xi, t_end, &uni)) != CLI_EXIT_OK) goto done;
  const double *lim = gm_mesh_maxwell_face_limits(avi.s);
  double lmin = INFINITY, lmax = 0.0;
  for (size_t f = 0; f < gm_complex_count(cx2, 2); ++f)
    if (isfinite(lim[f])) lmin = fmin(lmin, lim[f]), lmax = fmax(lmax, lim[f]);
  printf("2. AVI vs uniform stepping: bcc tetrahedra of the box inverted in a sphere (radius "
         "%.3g, centre %.3g outside the x = %.3g wall; cells shrink as d^2/r^2 away from it), %zu "
         "tetrahedra, local limits %.3g .. %.3g (ratio %.1f); steps %.2g x the local limit in %zu "
         "power-of-two groups\n", d_inv, d_inv, lo[0], gm_complex_count(cx2, 3), lmin, lmax,
         lmax / lmin, fraction, gm_mesh_maxwell_avi_groups(avi.s));
  size_t active = 0; /* faces with an interior edge: the ones either scheme changes */
  for (size_t f = 0; f < gm_complex_count(cx2, 2); ++f) active += isfinite(lim[f]) != 0;
  const double uni_faces = (double)active * (double)gm_mesh_maxwell_step(uni.s);
  printf("   uniform leapfrog at the smallest step %.4g: %zu steps, %.0f face updates (faces with "
         "an interior edge), %.3f s CPU\n", ou.dt, gm_mesh_maxwell_step(uni.s), uni_faces,
         uni.cpu);
  printf("   AVI: %zu face updates, ratio to uniform %.3f; %.3f s CPU: time ratio AVI/uniform %.3f "
         "(%s)\n", avi.faces, (double)avi.faces / uni_faces, avi.cpu, avi.cpu / uni.cpu,
         avi.cpu < uni.cpu ? "faster" : "NOT faster");
  double fa[E5_MAX_MODES], fu[E5_MAX_MODES];
  /* the inverted cavity is about d across: its band is higher than the box's */
  const double g_lo = f_lo * L[0] / d_inv, g_hi = f_top * L[0] / d_inv;
  const size_t na = probe_resonances(avi.s, g_lo, g_hi, fa, E5_MAX_MODES);
  const size_t nu = probe_resonances(uni.s, g_lo, g_hi, fu, E5_MAX_MODES);
  double dmax = 0.0;
  for (size_t i = 0; i < na; ++i) dmax = fmax(dmax, nearest_rel(fa[i], fu, nu));
  printf("   resonances: AVI %zu, uniform %zu in (%.3g, %.3g); max relative distance of an AVI "
         "peak to a uniform one %.2e\n", na, nu, g_lo, g_hi, dmax);
  status = CLI_EXIT_OK;
done:
  gm_mesh_maxwell_free(wh.s);
  gm_mesh_maxwell_free(avi.s);
  gm_mesh_maxwell_free(uni.s);
  gm_geometry_free(g2);
  gm_complex_free(cx2);
  gm_mesh_free(bcc);
  gm_geometry_free(g);
  gm_complex_free(cx);
  return status;
}
