/* DEC fluids on the periodic square [0, 2π]² (src/fluids/closed.c, src/fluids/flows.c), the
 * quotient complex of its two pairs of sides (gm_fluid_periodic_square_mesh), midpoint scheme:
 * the Taylor–Green decay rate against exp(−2νt) and its convergence; the inviscid double shear
 * layer's energy, enstrophy and total vorticity over 10⁴ steps; the errors of periodic pairs.
 * Numbers: docs/fluids.md. */
#include "../fluids_util.h"

Test(fluids_periodic, taylor_green_decay_rate_converges) {
  gm_error err = {{0}};
  gm_fluid_flow_result r;
  double h[3], e[3];
  /* measured relative errors of the decay rate (nu = 0.05, dt = 0.05, t = 1):
   * 7.090e-2 (n = 8), 1.944e-2 (16), 4.891e-3 (32) */
  const double want[3] = {7.090e-2, 1.944e-2, 4.891e-3};
  for (size_t i = 0; i < 3; ++i) {
    size_t n = (size_t)8 << i;
    cr_assert_eq(gm_fluid_taylor_green(GM_FLUID_MIDPOINT, n, 0.05, 0.05, 20, &r, &err), GM_OK, "%s", err.message);
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
  double p = fl_slope(3, h, e);
  cr_log_info("Taylor-Green decay rate: convergence rate %.3f", p);
  /* measured 2.002 */
  cr_assert(fabs(p - 2.00) <= 0.15, "rate %.3f", p);
}

Test(fluids_periodic, double_shear_layer_invariants_over_1e4_steps, .timeout = 120) {
  gm_error err = {{0}};
  gm_fluid_flow_result r;
  cr_assert_eq(gm_fluid_double_shear(GM_FLUID_MIDPOINT, 12, 0.05, 10000, &r, &err), GM_OK, "%s", err.message);
  cr_log_info("double shear layer, n = 12 (%zu triangles), 1e4 steps of 0.05: energy drift %.2e, "
              "enstrophy %.2e, total vorticity %.2e, div %.1e, <= %zu iterations",
              r.n_triangles, r.energy_drift, r.enstrophy_drift, r.vorticity_drift, r.div_max,
              r.max_iterations);
  cr_assert_leq(r.energy_drift, 1e-12, "energy drift %.3e", r.energy_drift);
  cr_assert_leq(r.enstrophy_drift, 1e-12, "enstrophy drift %.3e", r.enstrophy_drift);
  cr_assert_leq(r.vorticity_drift, 1e-13, "total vorticity drift %.3e", r.vorticity_drift);
  cr_assert_leq(r.div_max, 1e-14, "div %.3e", r.div_max);
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

