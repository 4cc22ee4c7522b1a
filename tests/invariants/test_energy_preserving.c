/* The mimetic integrators (seed 003) and the discrete gradient methods:
 *  - MCI = Gauss–Legendre collocation with p stages, the same trajectory over 100 steps;
 *  - MGI with p = 1 = avf on canonical problems;
 *  - MGI, avf and both discrete gradients keep the energy of the pendulum (H = p²/2 − 10 cos q,
 *    dt = 0.1) and of Kepler (e = 0.6, dt = 0.1) over 10⁵ steps; MCI's error is bounded;
 *  - both mimetic integrators are reversible; avf on Lotka–Volterra as a Poisson system keeps
 *    H while MCI and MGI (on y' = S∇H) do not;
 *  - measured order 2p of MCI and MGI, p = 1..4, on the pendulum;
 *  - dense output interpolates the element's nodal values. */
#include <stdio.h>

#include "test_util.h"

static gm_integrator *make(const char *name, const test_model *tm, int compensated) {
  gm_integrator *it = test_integrator(gm_method_find(name), tm->problem, tm->t0, tm->y0);
  cr_assert_eq(gm_integrator_set_compensated(it, compensated), GM_OK);
  return it;
}

static double max_diff(size_t n, const double *a, const double *b) {
  double d = 0.0;
  for (size_t i = 0; i < n; ++i) d = fmax(d, fabs(a[i] - b[i]));
  return d;
}

Test(energy_preserving, canonical_equals_gauss) {
  static const char *const problems[] = {"pendulum", "kepler"};
  for (size_t k = 0; k < 2; ++k) {
    test_model tm = k == 0 ? test_model_with("pendulum", "k", 10.0) : test_model_make("kepler");
    for (int p = 1; p <= 6; ++p) {
      char a[32], b[32];
      snprintf(a, sizeof a, "mimetic-canonical-%d", p);
      snprintf(b, sizeof b, "gauss-%d", p);
      gm_integrator *i1 = make(a, &tm, 0), *i2 = make(b, &tm, 0);
      double worst = 0.0;
      for (int s = 0; s < 100; ++s) {
        cr_assert_eq(gm_integrator_step(i1, 0.1), GM_OK, "%s", gm_integrator_errmsg(i1));
        cr_assert_eq(gm_integrator_step(i2, 0.1), GM_OK, "%s", gm_integrator_errmsg(i2));
        worst = fmax(worst, max_diff(tm.n, gm_integrator_state(i1), gm_integrator_state(i2)));
      }
      /* round-off: ~ε per step of the two nodal solves, 100 steps, amplified at Kepler's
       * pericentre (measured up to 1.2e-13) */
      cr_expect_leq(worst, 1e-12, "%s vs %s on %s: %.2e", a, b, problems[k], worst);
      gm_integrator_free(i1);
      gm_integrator_free(i2);
    }
    gm_model_free(tm.model);
  }
}

Test(energy_preserving, galerkin_1_equals_avf) {
  for (size_t k = 0; k < 2; ++k) {
    test_model tm = k == 0 ? test_model_with("pendulum", "k", 10.0) : test_model_make("kepler");
    gm_integrator *i1 = make("mimetic-galerkin-1", &tm, 0), *i2 = make("avf", &tm, 0);
    cr_expect_eq(gm_integrator_quadrature(i1), gm_integrator_quadrature(i2));
    double worst = 0.0;
    for (int s = 0; s < 100; ++s) {
      cr_assert_eq(gm_integrator_step(i1, 0.1), GM_OK);
      cr_assert_eq(gm_integrator_step(i2, 0.1), GM_OK);
      worst = fmax(worst, max_diff(tm.n, gm_integrator_state(i1), gm_integrator_state(i2)));
    }
    cr_expect_leq(worst, 1e-13, "mimetic-galerkin-1 vs avf: %.2e", worst);
    gm_integrator_free(i1);
    gm_integrator_free(i2);
    gm_model_free(tm.model);
  }
}

typedef struct {
  const gm_problem *pb;
  double h0, scale, max;
} energy_watch;

static int watch(void *ctx, size_t step, double t, const double *y) {
  (void)step;
  (void)t;
  energy_watch *w = ctx;
  w->max = fmax(w->max, fabs(gm_problem_energy(w->pb, y) - w->h0) / w->scale);
  return 0;
}

/* Largest |H − H0| / scale over n steps of 0.1 (observed every 10 steps). The pendulum starts
 * at H0 = 0, so its scale is k = 10 (the size of the potential); Kepler's is |H0| = 0.5. */
static double energy_error(const char *method, const test_model *tm, double scale, size_t n,
                           int compensated) {
  gm_integrator *it = make(method, tm, compensated);
  energy_watch w = {tm->problem, gm_problem_energy(tm->problem, tm->y0), scale, 0.0};
  cr_assert_eq(gm_integrator_add_observer(it, watch, &w, 10), GM_OK);
  cr_assert_eq(gm_integrator_run(it, n, 0.1), GM_OK, "%s: %s", method, gm_integrator_errmsg(it));
  gm_integrator_free(it);
  return w.max;
}

/* The energy-preserving rows keep H to round-off: the tolerance is the random walk of the
 * rounding of the increment, ε|∇H||Δy| per step over 10⁵ steps (compensated summation removes
 * the rounding of the state itself). Measured values are in docs/mimetic.md. */
static const char *const preserving[] = {"mimetic-galerkin-1", "mimetic-galerkin-2", "avf",
                                         "discrete-gradient-gonzalez",
                                         "discrete-gradient-itoh-abe"};

Test(energy_preserving, pendulum_energy_1e5_steps, .timeout = 600) {
  test_model tm = test_model_with("pendulum", "k", 10.0);
  for (size_t k = 0; k < sizeof preserving / sizeof preserving[0]; ++k) {
    double e = energy_error(preserving[k], &tm, 10.0, 100000, 1);
    cr_expect_leq(e, 1e-12, "%s: pendulum energy error %.2e", preserving[k], e);
  }
  gm_model_free(tm.model);
}

Test(energy_preserving, kepler_energy_1e5_steps, .timeout = 600) {
  test_model tm = test_model_make("kepler");
  for (size_t k = 0; k < sizeof preserving / sizeof preserving[0]; ++k) {
    double e = energy_error(preserving[k], &tm, 0.5, 100000, 1);
    cr_expect_leq(e, 1e-12, "%s: kepler energy error %.2e", preserving[k], e);
  }
  gm_model_free(tm.model);
}

/* Higher degrees: the same, at the round-off of the larger nodal systems. */
Test(energy_preserving, galerkin_3_to_6_kepler_1e4_steps, .timeout = 600) {
  test_model tm = test_model_make("kepler");
  for (int p = 3; p <= 6; ++p) {
    char name[32];
    snprintf(name, sizeof name, "mimetic-galerkin-%d", p);
    double e = energy_error(name, &tm, 0.5, 10000, 1);
    cr_expect_leq(e, 1e-12, "%s: kepler energy error %.2e", name, e);
  }
  gm_model_free(tm.model);
}

/* MCI: bounded, no drift — the error in the last tenth of 10⁵ steps is no larger than in the
 * first tenth; and far above round-off (it is not energy-preserving). */
typedef struct {
  const gm_problem *pb;
  double h0, first, last;
  size_t n;
} windows;

static int watch_windows(void *ctx, size_t step, double t, const double *y) {
  (void)t;
  windows *w = ctx;
  double e = fabs(gm_problem_energy(w->pb, y) - w->h0);
  if (step <= w->n / 10) w->first = fmax(w->first, e);
  if (step >= w->n - w->n / 10) w->last = fmax(w->last, e);
  return 0;
}

Test(energy_preserving, canonical_energy_bounded, .timeout = 600) {
  for (size_t k = 0; k < 2; ++k) {
    test_model tm = k == 0 ? test_model_with("pendulum", "k", 10.0) : test_model_make("kepler");
    gm_integrator *it = make("mimetic-canonical-2", &tm, 0);
    windows w = {tm.problem, gm_problem_energy(tm.problem, tm.y0), 0, 0, 100000};
    cr_assert_eq(gm_integrator_add_observer(it, watch_windows, &w, 1), GM_OK);
    cr_assert_eq(gm_integrator_run(it, w.n, 0.1), GM_OK);
    cr_expect_leq(w.last, 1.05 * w.first, "MCI drifts: %.3e then %.3e", w.last, w.first);
    cr_expect_gt(w.first, 1e-6, "MCI's energy error %.3e (dt = 0.1)", w.first);
    gm_integrator_free(it);
    gm_model_free(tm.model);
  }
}

Test(energy_preserving, mimetic_reversible) {
  static const char *const names[] = {"mimetic-canonical-2", "mimetic-galerkin-2",
                                      "mimetic-canonical-4", "mimetic-galerkin-4"};
  test_model tm = test_model_with("pendulum", "k", 10.0);
  for (size_t k = 0; k < 4; ++k) {
    gm_integrator *it = make(names[k], &tm, 0);
    for (int s = 0; s < 10; ++s) cr_assert_eq(gm_integrator_step(it, 0.2), GM_OK);
    for (int s = 0; s < 10; ++s) cr_assert_eq(gm_integrator_step(it, -0.2), GM_OK);
    double e = max_diff(tm.n, gm_integrator_state(it), tm.y0);
    cr_expect_leq(e, 1e-13, "%s returns with error %.2e", names[k], e);
    gm_integrator_free(it);
  }
  gm_model_free(tm.model);
}

/* Lotka–Volterra, dt = 0.3, 200 steps (seed 003 §6.2): MCI and MGI integrate y' = S(y)∇H(y) as
 * a first-order system and lose V by ~7e-3 (the notes' check); the discrete gradient methods
 * use S at the midpoint and keep it. */
Test(energy_preserving, lotka_volterra) {
  test_model tm = test_model_make("lotka-volterra");
  static const char *const names[] = {"mimetic-canonical-2", "mimetic-galerkin-2", "avf",
                                      "discrete-gradient-gonzalez", "discrete-gradient-itoh-abe"};
  for (size_t k = 0; k < 5; ++k) {
    gm_integrator *it = make(names[k], &tm, 0);
    if (k == 2) /* ln u, ln v are not polynomials: enough points for dt = 0.3 */
      cr_assert_eq(gm_integrator_set_quadrature(it, 24), GM_OK);
    energy_watch w = {tm.problem, gm_problem_energy(tm.problem, tm.y0), 1.0, 0.0};
    cr_assert_eq(gm_integrator_add_observer(it, watch, &w, 1), GM_OK);
    cr_assert_eq(gm_integrator_run(it, 200, 0.3), GM_OK, "%s", gm_integrator_errmsg(it));
    if (k < 2)
      cr_expect(w.max > 1e-3 && w.max < 2e-2, "%s: |dV| = %.3e", names[k], w.max);
    else
      cr_expect_leq(w.max, 1e-13, "%s: |dV| = %.3e", names[k], w.max);
    gm_integrator_free(it);
  }
  gm_model_free(tm.model);
}

/* Order 2p on the pendulum (k = 10, released at π/2, exact solution), p = 1..4: steps from
 * 0.05 (p ≤ 2) or 0.4 down by factors 2 to t = 2, fitted over the errors above 1e-12. */
Test(energy_preserving, order_2p_on_pendulum, .timeout = 300) {
  test_model tm = test_model_with("pendulum", "k", 10.0);
  for (int family = 0; family < 2; ++family)
    for (int p = 1; p <= 4; ++p) {
      char name[32];
      snprintf(name, sizeof name, family ? "mimetic-galerkin-%d" : "mimetic-canonical-%d", p);
      const gm_scheme sc = {gm_method_find(name), NULL, GM_SOLVER_DEFAULT, 0};
      gm_order_result r;
      gm_error err = {{0}};
      const double dt0 = p <= 2 ? 0.05 : 0.4;
      cr_assert_eq(gm_order_measure(&sc, tm.problem, tm.t0, tm.y0, tm.t0 + 2.0, dt0, 5, 2.0,
                                    NULL, &r, &err), GM_OK, "%s", err.message);
      double sx = 0, sy = 0, sxx = 0, sxy = 0;
      size_t m = 0;
      for (size_t l = 0; l < r.n_levels; ++l) {
        if (!(r.errors[l] > 1e-12 && r.errors[l] < 1e-2)) continue;
        double x = log(r.dts[l]), y = log(r.errors[l]);
        sx += x, sy += y, sxx += x * x, sxy += x * y, ++m;
      }
      cr_assert_geq(m, 3, "%s: only %zu levels in the window", name, m);
      double order = ((double)m * sxy - sx * sy) / ((double)m * sxx - sx * sx);
      cr_expect(fabs(order - 2 * p) <= 0.3, "%s: measured order %.3f", name, order);
    }
  gm_model_free(tm.model);
}

Test(energy_preserving, dense_output_and_quadrature_option) {
  test_model tm = test_model_with("pendulum", "k", 10.0);
  gm_integrator *it = make("mimetic-galerkin-3", &tm, 0);
  double y[2];
  cr_expect_eq(gm_mimetic_dense_output(it, 0.0, y), GM_EINVAL); /* no step yet */
  cr_expect_eq(gm_integrator_quadrature(it), 12u);
  cr_assert_eq(gm_integrator_set_quadrature(it, 20), GM_OK);
  cr_expect_eq(gm_integrator_quadrature(it), 20u);
  cr_assert_eq(gm_integrator_step(it, 0.1), GM_OK);
  cr_assert_eq(gm_mimetic_dense_output(it, 0.0, y), GM_OK);
  cr_expect_leq(max_diff(2, y, tm.y0), 1e-15);
  cr_assert_eq(gm_mimetic_dense_output(it, 0.1, y), GM_OK);
  cr_expect_leq(max_diff(2, y, gm_integrator_state(it)), 1e-15);
  /* inside the element: close to the exact solution (the degree-3 polynomial, error O(h⁴)) */
  double ex[2];
  cr_assert_eq(gm_mimetic_dense_output(it, 0.037, y), GM_OK);
  tm.problem->exact(tm.problem->ctx, 0.037, ex);
  cr_expect_leq(max_diff(2, y, ex), 1e-5, "dense output error %.2e", max_diff(2, y, ex));
  gm_integrator_free(it);
  it = make("gauss-2", &tm, 0);
  cr_expect_eq(gm_integrator_set_quadrature(it, 4), GM_EUNSUPPORTED);
  cr_expect_eq(gm_mimetic_dense_output(it, 0.0, y), GM_EUNSUPPORTED);
  gm_integrator_free(it);
  it = make("mimetic-canonical-2", &tm, 0);
  cr_expect_eq(gm_integrator_set_quadrature(it, 4), GM_EUNSUPPORTED);
  cr_expect(strstr(gm_integrator_errmsg(it), "Galerkin") != NULL, "%s", gm_integrator_errmsg(it));
  gm_integrator_free(it);
  gm_model_free(tm.model);
}
