/* Point vortices: the canonical form reproduces Kirchhoff's equations (checked against the
 * Biot–Savart velocities), the configurations are where they should be, symmetries and
 * invariants are kept along accurate integrations, and parameters are checked. */
#include <stdio.h>
#include <stdlib.h>

#include "test_util.h"

#define MAXV 16

typedef struct vortex_model {
  gm_model *model;
  const gm_problem *pb;
  size_t n; /* number of vortices */
  double y0[2 * MAXV];
} vortex_model;

/* point-vortices with settings "name=value,..." */
static vortex_model vortices(const char *settings) {
  vortex_model vm = {0};
  cr_assert_eq(gm_model_create("point-vortices", &vm.model), GM_OK);
  char buf[128];
  snprintf(buf, sizeof buf, "%s", settings);
  for (char *item = strtok(buf, ","); item != NULL; item = strtok(NULL, ",")) {
    char *eq = strchr(item, '=');
    cr_assert_not_null(eq);
    *eq = '\0';
    cr_assert_eq(gm_model_set(vm.model, item, strtod(eq + 1, NULL)), GM_OK);
  }
  cr_assert_eq(gm_model_build(vm.model), GM_OK, "%s", gm_model_errmsg(vm.model));
  vm.pb = gm_model_problem(vm.model);
  vm.n = vm.pb->dim;
  cr_assert_leq(vm.n, MAXV);
  gm_model_initial_state(vm.model, NULL, vm.y0);
  return vm;
}

/* The circulations of the configurations, as documented. */
static void circulations(const char *settings, size_t n, double *gamma) {
  double g = 1.0;
  const char *at = strstr(settings, "gamma=");
  if (at != NULL) g = strtod(at + 6, NULL);
  int leapfrog = strstr(settings, "config=3") != NULL;
  for (size_t i = 0; i < n; ++i) gamma[i] = leapfrog && i % 2 == 1 ? -g : g;
}

/* Positions from the canonical coordinates: x = q/sqrt|Γ|, y = p/(sign Γ sqrt|Γ|). */
static void positions(const double *gamma, size_t n, const double *state, double *x, double *y) {
  for (size_t i = 0; i < n; ++i) {
    double s = sqrt(fabs(gamma[i])), sg = gamma[i] > 0 ? 1.0 : -1.0;
    x[i] = state[i] / s;
    y[i] = state[n + i] / (sg * s);
  }
}

/* The canonical vector field dq/dt = ∂H/∂p, dp/dt = −∂H/∂q, mapped back to (dx/dt, dy/dt),
 * equals the Biot–Savart velocities dx_i/dt = −(1/2π) Σ Γ_j (y_i − y_j)/r², dy_i/dt =
 * (1/2π) Σ Γ_j (x_i − x_j)/r², and satisfies Kirchhoff's Γ_i dx_i/dt = ∂H/∂y_i,
 * Γ_i dy_i/dt = −∂H/∂x_i with the partial derivatives of H in the physical coordinates. */
static void check_kirchhoff(const char *settings, int perturb) {
  vortex_model vm = vortices(settings);
  const size_t n = vm.n;
  double gamma[MAXV], state[2 * MAXV], x[MAXV], y[MAXV], hq[MAXV], hp[MAXV];
  circulations(settings, n, gamma);
  memcpy(state, vm.y0, 2 * n * sizeof *state);
  if (perturb)
    for (size_t i = 0; i < 2 * n; ++i) state[i] += 0.05 * sin(3.0 * (double)i + 1.0);
  positions(gamma, n, state, x, y);
  cr_assert_eq(vm.pb->dh_dq(vm.pb->ctx, state, state + n, hq), 0);
  cr_assert_eq(vm.pb->dh_dp(vm.pb->ctx, state, state + n, hp), 0);
  for (size_t i = 0; i < n; ++i) {
    double u = 0.0, v = 0.0;
    for (size_t j = 0; j < n; ++j) {
      if (j == i) continue;
      double dx = x[i] - x[j], dy = y[i] - y[j], r2 = dx * dx + dy * dy;
      u -= gamma[j] * dy / (2.0 * 3.14159265358979323846 * r2);
      v += gamma[j] * dx / (2.0 * 3.14159265358979323846 * r2);
    }
    double s = sqrt(fabs(gamma[i])), sg = gamma[i] > 0 ? 1.0 : -1.0;
    double xdot = hp[i] / s;          /* q̇ = s ẋ = ∂H/∂p */
    double ydot = -hq[i] / (sg * s);  /* ṗ = σ s ẏ = −∂H/∂q */
    cr_expect(fabs(xdot - u) < 1e-13 * (1.0 + fabs(u)), "%s vortex %zu: dx/dt %.15g vs %.15g",
              settings, i, xdot, u);
    cr_expect(fabs(ydot - v) < 1e-13 * (1.0 + fabs(v)), "%s vortex %zu: dy/dt %.15g vs %.15g",
              settings, i, ydot, v);
    /* Kirchhoff's form itself, Γ_i dx_i/dt = ∂H/∂y_i and Γ_i dy_i/dt = −∂H/∂x_i, with the
     * partial derivatives of H(x, y) by central differences (moving vortex i by ±h in x or
     * y moves q_i by ±s h or p_i by ±σ s h) */
    const double h = 1e-6;
    double moved[2 * MAXV];
    double dh[2];
    for (size_t c = 0; c < 2; ++c) {
      double step = c == 0 ? s * h : sg * s * h, e[2];
      for (int sgn = 0; sgn < 2; ++sgn) {
        memcpy(moved, state, 2 * n * sizeof *state);
        moved[c * n + i] += sgn == 0 ? step : -step;
        e[sgn] = vm.pb->hamiltonian(vm.pb->ctx, moved, moved + n);
      }
      dh[c] = (e[0] - e[1]) / (2 * h);
    }
    cr_expect(fabs(gamma[i] * xdot - dh[1]) < 1e-8 * (1.0 + fabs(dh[1])),
              "%s vortex %zu: Γ dx/dt %.12g vs ∂H/∂y %.12g", settings, i, gamma[i] * xdot, dh[1]);
    cr_expect(fabs(gamma[i] * ydot + dh[0]) < 1e-8 * (1.0 + fabs(dh[0])),
              "%s vortex %zu: Γ dy/dt %.12g vs −∂H/∂x %.12g", settings, i, gamma[i] * ydot,
              -dh[0]);
  }
  gm_model_free(vm.model);
}

Test(vortices, canonical_form_is_kirchhoff) {
  const char *settings[] = {"config=0",          "config=0,n=5,gamma=-2", "config=1",
                            "config=2,alpha=0.4", "config=3",              "config=3,gamma=-0.3"};
  for (size_t k = 0; k < sizeof settings / sizeof settings[0]; ++k) {
    check_kirchhoff(settings[k], 0);
    check_kirchhoff(settings[k], 1);
  }
}

/* The configurations are where the documentation puts them, and H is Kirchhoff's. */
Test(vortices, configurations) {
  const double pi = 3.14159265358979323846, alpha = 0.3;
  double gamma[MAXV], x[MAXV], y[MAXV];
  /* 1: the 2nd and 4th vortices of the square turned by alpha; 2: only the 2nd */
  for (int config = 0; config <= 2; ++config) {
    char settings[64];
    snprintf(settings, sizeof settings, "config=%d,alpha=%g", config, alpha);
    vortex_model vm = vortices(settings);
    cr_assert_eq(vm.n, 4);
    circulations(settings, 4, gamma);
    positions(gamma, 4, vm.y0, x, y);
    for (size_t i = 0; i < 4; ++i) {
      double angle = pi / 2 * (double)i;
      if ((config == 1 && i % 2 == 1) || (config == 2 && i == 1)) angle += alpha;
      cr_expect(fabs(x[i] - cos(angle)) < 1e-15 && fabs(y[i] - sin(angle)) < 1e-15,
                "config %d vortex %zu at (%g, %g)", config, i, x[i], y[i]);
    }
    /* H = −(1/4π) Σ_{i≠j} Γ_iΓ_j ln r_ij: the square has four sides √2 and two diagonals 2 */
    if (config == 0) {
      double h = -(1.0 / (4 * pi)) * 2.0 * (4 * log(sqrt(2.0)) + 2 * log(2.0));
      cr_expect(fabs(gm_problem_energy(vm.pb, vm.y0) - h) < 1e-15, "H = %.17g, expected %.17g",
                gm_problem_energy(vm.pb, vm.y0), h);
    }
    gm_model_free(vm.model);
  }
  /* 3: two pairs +γ above, −γ below, half-widths 1 and 1/2 at x = 0 */
  vortex_model vm = vortices("config=3,gamma=2");
  circulations("config=3,gamma=2", 4, gamma);
  positions(gamma, 4, vm.y0, x, y);
  const double expect_y[4] = {1.0, -1.0, 0.5, -0.5};
  for (size_t i = 0; i < 4; ++i)
    cr_expect(x[i] == 0.0 && fabs(y[i] - expect_y[i]) < 1e-15, "vortex %zu at (%g, %g)", i, x[i],
              y[i]);
  /* invariants: Σ Γ x = 0, Σ Γ y = 2·(1 + 1 + 0.5 + 0.5) = 6, Σ Γ |x|² = 0 */
  const gm_problem *pb = vm.pb;
  cr_expect(fabs(pb->invariants[0].value(pb->ctx, vm.y0)) < 1e-15);
  cr_expect(fabs(pb->invariants[1].value(pb->ctx, vm.y0) - 6.0) < 1e-14);
  cr_expect(fabs(pb->invariants[2].value(pb->ctx, vm.y0)) < 1e-14);
  gm_model_free(vm.model);
}

/* Along the implicit midpoint rule, which keeps every quadratic invariant of a canonical
 * system exactly (GNI Thm. IV.2.1), the impulses and the angular impulse stay put up to the
 * Newton tolerance (measured 1e-14 and 3e-12 at the size of these sums); RK4 at a small step
 * keeps the energy to 1e-9 (measured 1e-12 and 2e-10). */
Test(vortices, invariants_along_integrations) {
  const char *settings[] = {"config=1", "config=3"};
  for (size_t k = 0; k < 2; ++k) {
    vortex_model vm = vortices(settings[k]);
    const char *methods[] = {"midpoint", "rk4"};
    for (size_t j = 0; j < 2; ++j) {
      gm_integrator *it = test_integrator(gm_method_find(methods[j]), vm.pb, 0.0, vm.y0);
      gm_monitor *mon = NULL;
      cr_assert_eq(gm_monitor_create(vm.pb, vm.y0, &mon), GM_OK);
      cr_assert_eq(gm_integrator_add_observer(it, gm_monitor_observe, mon, 1), GM_OK);
      cr_assert_eq(gm_integrator_integrate(it, 50.0, 0.01), GM_OK);
      if (j == 0)
        for (size_t i = 0; i < 3; ++i)
          cr_expect(gm_monitor_max_invariant_drift(mon, i) < 2e-11, "%s %s drift %.3e",
                    settings[k], vm.pb->invariants[i].name,
                    gm_monitor_max_invariant_drift(mon, i));
      else
        cr_expect(gm_monitor_max_rel_energy_error(mon) < 1e-9, "%s rk4 energy %.3e",
                  settings[k], gm_monitor_max_rel_energy_error(mon));
      gm_monitor_free(mon);
      gm_integrator_free(it);
    }
    gm_model_free(vm.model);
  }
}

/* Config 1 keeps its central symmetry x_3 = −x_1, x_4 = −x_2 (the flow commutes with the
 * rotation by π, and so does any Runge–Kutta method) while it leaves the square: the distance
 * between vortices 1 and 2 changes. */
Test(vortices, turned_pair_keeps_central_symmetry) {
  vortex_model vm = vortices("config=1");
  gm_integrator *it = test_integrator(gm_method_find("rk4"), vm.pb, 0.0, vm.y0);
  double dmin = 1e9, dmax = 0.0;
  for (int step = 0; step < 200; ++step) {
    cr_assert_eq(gm_integrator_run(it, 10, 0.01), GM_OK);
    const double *s = gm_integrator_state(it);
    for (size_t i = 0; i < 2; ++i) {
      cr_expect(fabs(s[i] + s[i + 2]) < 1e-13 && fabs(s[4 + i] + s[4 + i + 2]) < 1e-13,
                "symmetry lost at step %d", step);
    }
    double d = hypot(s[0] - s[1], s[4] - s[5]);
    dmin = fmin(dmin, d);
    dmax = fmax(dmax, d);
  }
  cr_expect(dmax - dmin > 0.05, "|x1 - x2| from %g to %g", dmin, dmax);
  gm_integrator_free(it);
  gm_model_free(vm.model);
}

/* Leapfrogging: the pairs keep their mirror symmetry about the x-axis, all travel in +x,
 * and the two pairs overtake each other again and again (the x-order of their centres
 * changes sign several times by t = 40). */
Test(vortices, pairs_leapfrog) {
  vortex_model vm = vortices("config=3");
  gm_integrator *it = test_integrator(gm_method_find("rk4"), vm.pb, 0.0, vm.y0);
  double gamma[4], x[4], y[4];
  circulations("config=3", 4, gamma);
  int order = 0, changes = 0;
  for (int step = 0; step < 400; ++step) {
    cr_assert_eq(gm_integrator_run(it, 10, 0.01), GM_OK);
    positions(gamma, 4, gm_integrator_state(it), x, y);
    cr_expect(fabs(x[0] - x[1]) < 1e-12 && fabs(y[0] + y[1]) < 1e-12, "pair 1 not mirrored");
    cr_expect(fabs(x[2] - x[3]) < 1e-12 && fabs(y[2] + y[3]) < 1e-12, "pair 2 not mirrored");
    int now = x[0] > x[2] ? 1 : -1;
    if (order != 0 && now != order) ++changes;
    order = now;
  }
  cr_expect(x[0] > 1.0 && x[2] > 1.0, "the pairs moved on: x = %g, %g", x[0], x[2]);
  cr_expect(changes >= 3, "the pairs overtook each other %d times", changes);
  gm_integrator_free(it);
  gm_model_free(vm.model);
}

Test(vortices, bad_parameters) {
  static const struct {
    const char *name;
    double value;
    const char *needle;
  } cases[] = {{"config", 4, "config must be 0"}, {"config", 1.5, "config must be"},
               {"n", 1, "n must be an integer from 2"}, {"n", 65, "n must be"},
               {"gamma", 0, "gamma must not be 0"}};
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
    gm_model *m = NULL;
    cr_assert_eq(gm_model_create("point-vortices", &m), GM_OK);
    cr_assert_eq(gm_model_set(m, cases[k].name, cases[k].value), GM_OK);
    cr_expect_eq(gm_model_build(m), GM_EINVAL, "%s = %g", cases[k].name, cases[k].value);
    cr_expect(strstr(gm_model_errmsg(m), cases[k].needle) != NULL, "'%s' not in: %s",
              cases[k].needle, gm_model_errmsg(m));
    gm_model_free(m);
  }
  /* n is the ring's; the other configurations have four vortices */
  gm_model *m = NULL;
  cr_assert_eq(gm_model_create("point-vortices", &m), GM_OK);
  cr_assert_eq(gm_model_set(m, "config", 3), GM_OK);
  cr_assert_eq(gm_model_set(m, "n", 6), GM_OK);
  cr_expect_eq(gm_model_build(m), GM_EINVAL);
  cr_expect(strstr(gm_model_errmsg(m), "4 vortices") != NULL, "%s", gm_model_errmsg(m));
  /* two vortices in one place: H is infinite */
  cr_assert_eq(gm_model_set(m, "config", 0), GM_OK);
  cr_assert_eq(gm_model_set(m, "n", 4), GM_OK);
  cr_assert_eq(gm_model_set(m, "q2", 1.0), GM_OK);
  cr_assert_eq(gm_model_set(m, "p2", 0.0), GM_OK);
  cr_expect_eq(gm_model_build(m), GM_EINVAL);
  cr_expect(strstr(gm_model_errmsg(m), "energy") != NULL, "%s", gm_model_errmsg(m));
  /* a changed initial state drops the ring's exact solution */
  cr_assert_eq(gm_model_set(m, "p2", 0.9), GM_OK);
  cr_assert_eq(gm_model_build(m), GM_OK, "%s", gm_model_errmsg(m));
  cr_expect_null(gm_model_problem(m)->exact);
  gm_model_free(m);
}
