/* Discrete conservation laws of the pde schemes (seed 004 §2.2): the multisymplectic law per
 * cell for the Preissmann and Euler boxes (two tangent variations carried along), EC's discrete
 * energy law, and the bounded energy error of the symplectic box schemes. */
#include "pde_util.h"

static void ms_law(const char *scheme, size_t n, double dt, size_t steps, double tol) {
  gm_pde *p = pde_breather_solver(scheme, n, dt, 1);
  gm_error err = {{0}};
  double worst = 0.0;
  double *rel = calloc(n, sizeof *rel);
  for (size_t k = 0; k < steps; k++) {
    cr_assert_eq(gm_pde_advance(p, 1, &err), GM_OK, "%s", err.message);
    double r = gm_pde_ms_residual(p, rel);
    if (k >= 1) cr_assert(r >= 0.0, "%s: residual not available at step %zu", scheme, k + 1);
    if (r > worst) worst = r;
  }
  cr_log_info("%s: max per-cell relative multisymplectic residual %.3e over %zu steps", scheme,
              worst, steps);
  cr_assert(worst <= tol, "%s: multisymplectic residual %.3e > %.1e", scheme, worst, tol);
  free(rel);
  gm_pde_free(p);
}

Test(pde_laws, preissmann_multisymplectic_per_cell) { ms_law("preissmann", 201, 0.1, 200, 1e-12); }

Test(pde_laws, euler_box_multisymplectic_per_cell) { ms_law("euler-box", 200, 0.1, 200, 1e-12); }

Test(pde_laws, ec_discrete_energy_law) {
  /* E^{n+½} = E^{n−½} for EC up to the scalar solves' floor; LF at the same step drifts */
  gm_pde *ec = pde_breather_solver("ec", 200, 0.1, 0), *lf = pde_breather_solver("lf", 200, 0.1, 0);
  gm_error err = {{0}};
  double e0 = gm_pde_energy(ec), l0 = gm_pde_energy(lf), dec = 0.0, dlf = 0.0;
  for (int k = 0; k < 500; k++) {
    cr_assert_eq(gm_pde_advance(ec, 1, &err), GM_OK, "%s", err.message);
    cr_assert_eq(gm_pde_advance(lf, 1, &err), GM_OK, "%s", err.message);
    dec = fmax(dec, fabs(gm_pde_energy(ec) - e0) / fabs(e0));
    dlf = fmax(dlf, fabs(gm_pde_energy(lf) - l0) / fabs(l0));
  }
  cr_log_info("relative energy error over 500 steps: EC %.3e, LF %.3e", dec, dlf);
  cr_assert(dec <= 1e-13, "EC energy error %.3e", dec);
  cr_assert(dlf > 1e-6, "LF energy error %.3e should be visible (the law is EC's own)", dlf);
  gm_pde_free(ec);
  gm_pde_free(lf);
}

Test(pde_laws, box_energy_bounded) {
  /* Preissmann: the energy error stays O(Δt²) and does not grow over 100 breather periods */
  gm_pde *p = pde_breather_solver("preissmann", 201, 0.2, 0);
  gm_error err = {{0}};
  double e0 = gm_pde_energy(p), first = 0.0, last = 0.0;
  size_t steps = (size_t)(100 * 2 * 3.141592653589793 / PDE_OMEGA / 0.2);
  for (size_t k = 0; k < steps; k++) {
    cr_assert_eq(gm_pde_advance(p, 1, &err), GM_OK, "%s", err.message);
    double d = fabs(gm_pde_energy(p) - e0) / fabs(e0);
    if (k < steps / 10) first = fmax(first, d);
    if (k >= steps - steps / 10) last = fmax(last, d);
  }
  cr_log_info("Preissmann energy error: first tenth %.3e, last tenth %.3e", first, last);
  cr_assert(last <= 1.5 * first, "energy error grows: %.3e -> %.3e", first, last);
  cr_assert(first < 0.05);
  gm_pde_free(p);
}

/* The local energy and momentum laws are not exact for the Preissmann box; their per-cell
 * defects are O(Δt² + Δx²): measured 4.20e-2 / 1.14e-2 (energy), 1.27e-2 / 3.61e-3 (momentum)
 * for n = 101 / 201, Δt = Δx/2, t ∈ [0, 2]. */
static void local_max(size_t n, double *em, double *mm) {
  double h = 2.0 * PDE_L / (double)n;
  gm_pde *p = pde_breather_solver("preissmann", n, h / 2, 0);
  double *E = calloc(n, sizeof *E), *M = calloc(n, sizeof *M);
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_local_residuals(p, E, M), GM_EUNSUPPORTED); /* before the first step */
  *em = *mm = 0.0;
  for (size_t k = 0; k < (size_t)llround(2.0 / (h / 2)); k++) {
    cr_assert_eq(gm_pde_advance(p, 1, &err), GM_OK, "%s", err.message);
    cr_assert_eq(gm_pde_local_residuals(p, E, M), GM_OK);
    for (size_t i = 0; i < n; i++) {
      *em = fmax(*em, fabs(E[i]));
      *mm = fmax(*mm, fabs(M[i]));
    }
  }
  free(E);
  free(M);
  gm_pde_free(p);
}

Test(pde_laws, preissmann_local_energy_momentum_defects_second_order) {
  double e1, m1, e2, m2;
  local_max(101, &e1, &m1);
  local_max(201, &e2, &m2);
  cr_log_info("local defects: energy %.3e -> %.3e, momentum %.3e -> %.3e", e1, e2, m1, m2);
  cr_assert(e1 / e2 > 3.3 && e1 / e2 < 4.8, "energy defect ratio %.2f", e1 / e2);
  cr_assert(m1 / m2 > 3.3 && m1 / m2 < 4.8, "momentum defect ratio %.2f", m1 / m2);
  gm_pde *s = pde_breather_solver("ms", 100, 0.1, 0);
  cr_assert_eq(gm_pde_local_residuals(s, NULL, NULL), GM_EUNSUPPORTED);
  gm_pde_free(s);
}
