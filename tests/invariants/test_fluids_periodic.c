/* DEC fluids on domains without boundary (src/fluids/closed.c, src/fluids/flows.c):
 * - the periodic square [0, 2π]² as the quotient complex of its two pairs of sides: the
 *   Taylor–Green decay rate against exp(−2νt) and its convergence; the inviscid double shear
 *   layer's energy, enstrophy and total vorticity over 10⁴ midpoint steps;
 * - the unit sphere rotating at Ω = 1: the Rossby–Haurwitz wave's pattern speed against
 *   Haurwitz's closed form at three resolutions, with energy conserved;
 * - the errors of periodic pairs and surfaces. Numbers: docs/fluids.md. */
#include "../fluids_util.h"

/* least-squares slope of log e against log h */
static double slope(size_t n, const double *h, const double *e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < n; ++i) {
    double x = log(h[i]), y = log(e[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

Test(fluids_periodic, taylor_green_decay_rate_converges) {
  gm_error err = {{0}};
  gm_fluid_flow_result r;
  double h[3], e[3];
  /* measured relative errors of the decay rate (nu = 0.05, dt = 0.05, t = 1):
   * 6.298e-2 (n = 8), 1.839e-2 (16), 4.763e-3 (32) */
  const double want[3] = {6.298e-2, 1.839e-2, 4.763e-3};
  for (size_t i = 0; i < 3; ++i) {
    size_t n = (size_t)8 << i;
    cr_assert_eq(gm_fluid_taylor_green(n, 0.05, 0.05, 20, &r, &err), GM_OK, "%s", err.message);
    h[i] = r.mean_edge;
    e[i] = fabs(r.measured / r.exact - 1.0);
    cr_log_info("Taylor-Green n = %zu: %zu triangles, mean edge %.4e, decay rate %.6e vs 2 nu = "
                "%.6e, relative error %.3e; div %.1e, total vorticity drift %.1e",
                n, r.n_triangles, r.mean_edge, r.measured, r.exact, e[i], r.div_max,
                r.vorticity_drift);
    cr_assert_leq(e[i], 1.5 * want[i], "n = %zu: decay rate error %.3e", n, e[i]);
    cr_assert_leq(r.div_max, 1e-14, "div %.3e", r.div_max);
    cr_assert_leq(r.vorticity_drift, 1e-14, "total vorticity drift %.3e", r.vorticity_drift);
  }
  double p = slope(3, h, e);
  cr_log_info("Taylor-Green decay rate: convergence rate %.3f", p);
  /* measured 1.967 */
  cr_assert(fabs(p - 1.97) <= 0.15, "rate %.3f", p);
}

Test(fluids_periodic, double_shear_layer_invariants_over_1e4_steps, .timeout = 120) {
  gm_error err = {{0}};
  gm_fluid_flow_result r;
  cr_assert_eq(gm_fluid_double_shear(16, 0.05, 10000, &r, &err), GM_OK, "%s", err.message);
  cr_log_info("double shear layer, n = 16 (%zu triangles), 1e4 steps of 0.05: energy drift %.2e, "
              "enstrophy %.2e, total vorticity %.2e, div %.1e, <= %zu iterations",
              r.n_triangles, r.energy_drift, r.enstrophy_drift, r.vorticity_drift, r.div_max,
              r.max_iterations);
  cr_assert_leq(r.energy_drift, 1e-12, "energy drift %.3e", r.energy_drift);
  cr_assert_leq(r.enstrophy_drift, 1e-12, "enstrophy drift %.3e", r.enstrophy_drift);
  cr_assert_leq(r.vorticity_drift, 1e-13, "total vorticity drift %.3e", r.vorticity_drift);
  cr_assert_leq(r.div_max, 1e-14, "div %.3e", r.div_max);
}

Test(fluids_periodic, rossby_haurwitz_speed_converges) {
  gm_error err = {{0}};
  gm_fluid_flow_result r;
  double h[3], e[3];
  /* measured relative errors of the pattern speed (t = 10, dt = 0.4, 0.2, 0.1):
   * 5.480e-1 (subdivisions 2), 1.739e-1 (3), 4.636e-2 (4) */
  const double want[3] = {5.480e-1, 1.739e-1, 4.636e-2};
  for (size_t i = 0; i < 3; ++i) {
    size_t s = 2 + i;
    cr_assert_eq(gm_fluid_rossby_haurwitz(s, 0.4 / (double)(1u << i), 10.0, &r, &err), GM_OK,
                 "%s", err.message);
    h[i] = r.mean_edge;
    e[i] = fabs(r.measured / r.exact - 1.0);
    cr_log_info("Rossby-Haurwitz, %zu subdivisions: %zu triangles, mean edge %.4e, speed %.6e vs "
                "%.6e, relative error %.3e; energy drift %.1e, total vorticity drift %.1e",
                s, r.n_triangles, r.mean_edge, r.measured, r.exact, e[i], r.energy_drift,
                r.vorticity_drift);
    cr_assert_leq(e[i], 1.5 * want[i], "subdivisions %zu: speed error %.3e", s, e[i]);
    cr_assert_leq(r.energy_drift, 1e-13, "energy drift %.3e", r.energy_drift);
    cr_assert_leq(r.vorticity_drift, 1e-13, "vorticity drift %.3e", r.vorticity_drift);
  }
  double p = slope(3, h, e);
  cr_log_info("Rossby-Haurwitz speed: convergence rate %.3f", p);
  /* measured 1.79 */
  cr_assert(fabs(p - 1.79) <= 0.15, "rate %.3f", p);
}

static gm_status square_with(const gm_fluid_bc *bc, size_t nbc, gm_fluid_scheme scheme,
                             gm_error *err) {
  fl_fixture fx = fl_rect(1.0, 1.0, 8);
  gm_fluid_options o = gm_fluid_defaults();
  o.scheme = scheme;
  o.nu = 0.0;
  gm_fluid *f = NULL;
  gm_status st = gm_fluid_create(fx.mesh, fx.groups, nbc, bc, &o, &f, err);
  gm_fluid_free(f);
  fl_free(&fx);
  return st;
}

Test(fluids_periodic, bad_periodic_pairs) {
  gm_error err = {{0}};
  gm_fluid_bc bc[3];
  memset(bc, 0, sizeof bc);
  bc[0].group = "left";
  bc[0].kind = GM_FLUID_PERIODIC;
  bc[0].partner = "nowhere";
  bc[1].group = "bottom";
  bc[1].kind = GM_FLUID_PERIODIC;
  bc[1].partner = "top";
  cr_assert_eq(square_with(bc, 2, GM_FLUID_MIDPOINT, &err), GM_ENOTFOUND);
  cr_assert(strstr(err.message, "\"nowhere\""), "%s", err.message);
  bc[0].partner = "right";
  cr_assert_eq(square_with(bc, 2, GM_FLUID_SEED, &err), GM_EUNSUPPORTED);
  cr_assert(strstr(err.message, "midpoint"), "%s", err.message);
  /* a periodic channel: walls above and below */
  bc[1].kind = GM_FLUID_WALL;
  bc[2] = bc[1];
  bc[2].group = "top";
  cr_assert_eq(square_with(bc, 3, GM_FLUID_MIDPOINT, &err), GM_EUNSUPPORTED);
  cr_assert(strstr(err.message, "\"bottom\" is not periodic"), "%s", err.message);
  /* only one pair: the other sides have no condition */
  cr_assert_eq(square_with(bc, 1, GM_FLUID_MIDPOINT, &err), GM_EUNSUPPORTED);
  cr_assert(strstr(err.message, "boundary edges are in periodic groups"), "%s", err.message);
  /* sides that do not match: left against bottom */
  bc[0].partner = "bottom";
  bc[1].kind = GM_FLUID_PERIODIC;
  bc[1].group = "right";
  bc[1].partner = "top";
  cr_assert_eq(square_with(bc, 2, GM_FLUID_MIDPOINT, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "\"left\""), "%s", err.message);
}

/* Two octahedra sharing one vertex: every edge has two triangles, but the shared vertex's
 * triangles form two fans (not a manifold). */
Test(fluids_periodic, non_manifold_surface_is_refused) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_create(3, 11, 2, 16, &m), GM_OK);
  const double x[33] = {1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, /* octahedron 1 */
                        3, 0, 0, 2, 1, 0, 2, -1, 0, 2, 0, 1, 2, 0, -1}; /* octahedron 2 at x=2 */
  memcpy(m->x, x, sizeof x);
  /* octahedron 1: vertices 0..5 (±x, ±y, ±z); octahedron 2: 0 (its −x tip), 6..10 */
  const size_t c[48] = {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4, 1, 0, 5, 2, 1, 5, 3, 2, 5, 0, 3, 5,
                        6, 7, 9, 7, 0, 9, 0, 8, 9, 8, 6, 9, 7, 6, 10, 0, 7, 10, 8, 0, 10, 6, 8, 10};
  memcpy(m->cells, c, sizeof c);
  gm_fluid_groups g = {0, NULL, 0, NULL, NULL};
  gm_fluid_options o = gm_fluid_defaults();
  o.scheme = GM_FLUID_MIDPOINT;
  o.nu = 0.0;
  gm_fluid *f = NULL;
  gm_error err = {{0}};
  gm_status st = gm_fluid_create(m, &g, 0, NULL, &o, &f, &err);
  cr_assert_eq(st, GM_EINVAL, "status %d: %s", (int)st, err.message);
  cr_assert(strstr(err.message, "not a closed manifold") &&
                strstr(err.message, "1 vertices whose triangles do not form one fan"),
            "%s", err.message);
  /* the seed scheme is refused on surfaces */
  o.scheme = GM_FLUID_SEED;
  cr_assert_eq(gm_fluid_create(m, &g, 0, NULL, &o, &f, &err), GM_EUNSUPPORTED);
  gm_mesh_free(m);
}

/* The torus: a closed surface of genus 1 (the DEC is intrinsic). A smooth stream function
 * conserves energy and total vorticity with the midpoint scheme. */
Test(fluids_periodic, torus_invariants) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_torus(2.0, 0.8, 40, 16, &m, &err), GM_OK, "%s", err.message);
  gm_fluid_groups g = {0, NULL, 0, NULL, NULL};
  gm_fluid_options o = gm_fluid_defaults();
  o.scheme = GM_FLUID_MIDPOINT;
  o.nu = 0.0;
  o.kappa = 0.0;
  o.dt = 0.05;
  gm_fluid *f = NULL;
  gm_status st = gm_fluid_create(m, &g, 0, NULL, &o, &f, &err);
  gm_mesh_free(m);
  cr_assert_eq(st, GM_OK, "%s", err.message);
  const size_t nv = gm_fluid_n_vertices(f);
  const double *x = gm_fluid_coordinates(f);
  double *psi = malloc(nv * sizeof *psi);
  for (size_t v = 0; v < nv; ++v)
    psi[v] = 0.3 * x[3 * v + 2] * x[3 * v] + 0.2 * sin(atan2(x[3 * v + 1], x[3 * v]) * 2.0);
  cr_assert_eq(gm_fluid_set_state(f, psi, psi), GM_OK, "%s", gm_fluid_errmsg(f));
  free(psi);
  gm_fluid_diagnostics d0, d;
  gm_fluid_diagnose(f, &d0);
  double de = 0, dz = 0, dv = 0, dm = 0;
  for (int s = 0; s < 400; ++s) {
    cr_assert_eq(gm_fluid_advance(f, 1), GM_OK, "%s", gm_fluid_errmsg(f));
    gm_fluid_diagnose(f, &d);
    de = fmax(de, fabs(d.kinetic_energy / d0.kinetic_energy - 1));
    dz = fmax(dz, fabs(d.enstrophy / d0.enstrophy - 1));
    dv = fmax(dv, fabs(d.total_vorticity - d0.total_vorticity));
    dm = fmax(dm, fabs(d.scalar_mass - d0.scalar_mass));
  }
  cr_log_info("torus (%zu triangles), 400 steps: energy drift %.2e, enstrophy %.2e, total "
              "vorticity %.2e, scalar mass %.2e",
              gm_fluid_n_triangles(f), de, dz, dv, dm);
  cr_assert_leq(de, 1e-13, "energy drift %.3e", de);
  cr_assert_leq(dz, 1e-13, "enstrophy drift %.3e", dz);
  cr_assert_leq(dv, 1e-13, "total vorticity drift %.3e", dv);
  cr_assert_leq(dm, 1e-13, "scalar mass drift %.3e", dm);
  gm_fluid_free(f);
}
