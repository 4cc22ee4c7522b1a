/* DEC fluids on closed surfaces in R³ (the DEC is intrinsic; src/fluids/closed.c): the
 * Rossby–Haurwitz wave on the rotating unit sphere (pattern speed against Haurwitz's closed form
 * at three resolutions, energy conserved), the torus's invariants, a non-manifold surface
 * refused. Numbers: docs/fluids.md. */
#include "../fluids_util.h"

Test(fluids_sphere, rossby_haurwitz_speed_converges) {
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
  double p = fl_slope(3, h, e);
  cr_log_info("Rossby-Haurwitz speed: convergence rate %.3f", p);
  /* measured 1.79 */
  cr_assert(fabs(p - 1.79) <= 0.15, "rate %.3f", p);
}

/* Two octahedra sharing one vertex: every edge has two triangles, but the shared vertex's
 * triangles form two fans (not a manifold). */
Test(fluids_sphere, non_manifold_surface_is_refused) {
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
  gm_mesh_free(m);
}

/* The torus: a closed surface of genus 1 (the DEC is intrinsic). A smooth stream function
 * conserves energy and total vorticity with the midpoint scheme. */
Test(fluids_sphere, torus_invariants) {
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

