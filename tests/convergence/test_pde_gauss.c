/* The 2-stage Gauss–Legendre multisymplectic box (Reich 2000) on sine-Gordon (breather) and
 * NLS (soliton): the discrete multisymplectic law per cell, NLS's charge, the orders in t and
 * x at the Gauss points, and the even-n requirement. */
#include "pde_util.h"

#define NC (3.141592653589793 / 10.0)

static void breather_s(double x, double t, double *s) {
  double w = PDE_OMEGA, k = sqrt(1.0 - w * w), ch = cosh(k * x);
  double r = k / w * sin(w * t) / ch, den = 1.0 + r * r;
  s[0] = 4.0 * atan(r);
  s[1] = 4.0 / den * k * cos(w * t) / ch;
  s[2] = -4.0 / den * r * k * tanh(k * x);
}

static void soliton_s(double x, double t, double *s) {
  double xi = x - NC * t, amp = 1.0 / cosh(xi), th = NC * x / 2 - (NC * NC / 4 - 1.0) * t;
  double dam = -tanh(xi) / cosh(xi);
  s[0] = amp * cos(th);
  s[1] = amp * sin(th);
  s[2] = dam * cos(th) - amp * sin(th) * NC / 2;
  s[3] = dam * sin(th) + amp * cos(th) * NC / 2;
}

typedef struct g_result {
  double error, ms, charge;
  double *u; /* final first component (owned) */
} g_result;

static g_result g_run(int nls, size_t n, double dt, double T) {
  gm_pde_equation eq = nls ? gm_pde_nls() : gm_pde_sine_gordon();
  size_t d = eq.dim;
  const gm_pde_scheme *s = NULL;
  cr_assert_eq(gm_pde_scheme_find("gauss-prk", &s), GM_OK);
  gm_pde_grid g = {n, 2.0 * PDE_L / (double)n, -PDE_L, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = dt;
  o.track_variations = 1;
  double *s0 = calloc(n * d, sizeof *s0), ex[4];
  for (size_t i = 0; i < n; i++) {
    double x = gm_pde_point_x(s, &g, i);
    if (nls)
      soliton_s(x, 0.0, s0 + i * d);
    else
      breather_s(x, 0.0, s0 + i * d);
  }
  gm_pde *p = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_create(&g, &eq, s, &o, s0, &p, &err), GM_OK, "%s", err.message);
  g_result r = {0, 0, 0, calloc(n, sizeof(double))};
  double q0 = nls ? gm_pde_norm(p) : 0.0;
  size_t steps = (size_t)llround(T / dt);
  for (size_t k = 0; k < steps; k++) {
    cr_assert_eq(gm_pde_advance(p, 1, &err), GM_OK, "%s", err.message);
    r.ms = fmax(r.ms, gm_pde_ms_residual(p, NULL));
    if (nls) r.charge = fmax(r.charge, fabs(gm_pde_norm(p) - q0) / q0);
  }
  const double *st = gm_pde_state(p);
  for (size_t i = 0; i < n; i++) {
    double x = gm_pde_point_x(s, &g, i);
    if (nls) {
      soliton_s(x, gm_pde_time(p), ex);
      r.error = fmax(r.error, hypot(st[i * d] - ex[0], st[i * d + 1] - ex[1]));
    } else {
      breather_s(x, gm_pde_time(p), ex);
      r.error = fmax(r.error, fabs(st[i * d] - ex[0]));
    }
    r.u[i] = st[i * d];
  }
  free(s0);
  gm_pde_free(p);
  return r;
}

Test(pde_gauss, laws_and_charge) {
  g_result a = g_run(0, 100, 0.2, 4.0), b = g_run(1, 100, 0.2, 2.0);
  cr_log_info("gauss-prk, n = 100, dt = 0.2: sine-Gordon breather ms residual %.2e; NLS ms "
              "residual %.2e, charge drift %.2e", a.ms, b.ms, b.charge);
  cr_assert(a.ms <= 1e-12 && b.ms <= 1e-12, "ms residual %.2e %.2e", a.ms, b.ms);
  cr_assert(b.charge <= 1e-13, "charge %.2e", b.charge);
  free(a.u);
  free(b.u);
}

Test(pde_gauss, orders) {
  /* x: Δt = 0.05 (time error ~1e-7), n = 80 → 160 (cells of 1 and 0.5): the Gauss points are
   * stage values of the spatial collocation, order s + 1 = 3 there */
  g_result a = g_run(0, 80, 0.05, 2.0), b = g_run(0, 160, 0.05, 2.0);
  double ox = log2(a.error / b.error);
  /* joint, Δt = Δx/2 (Δx = h, cells of 2h), n = 100 → 200, sine-Gordon and NLS */
  g_result c = g_run(0, 100, 0.2, 2.0), e = g_run(0, 200, 0.1, 2.0);
  g_result f = g_run(1, 100, 0.2, 2.0), g = g_run(1, 200, 0.1, 2.0);
  double oj = log2(c.error / e.error), on = log2(f.error / g.error);
  /* t on a fixed grid (n = 100; Δt = 0.4, 0.2 against 0.05): logged, not asserted — the
   * differences do not converge at order 4 (docs/pde.md: a non-converging component at the
   * level of the space error) */
  g_result r = g_run(0, 100, 0.05, 4.0), t1 = g_run(0, 100, 0.4, 4.0), t2 = g_run(0, 100, 0.2, 4.0);
  double e1 = 0.0, e2 = 0.0;
  for (size_t i = 0; i < 100; i++) {
    e1 = fmax(e1, fabs(t1.u[i] - r.u[i]));
    e2 = fmax(e2, fabs(t2.u[i] - r.u[i]));
  }
  cr_log_info("gauss-prk: breather x errors %.3e, %.3e (order %.3f at the Gauss points); joint "
              "dt = dx/2: breather %.3e, %.3e (order %.3f), NLS %.3e, %.3e (order %.3f); fixed "
              "grid t differences %.3e, %.3e (ratio %.2f)", a.error, b.error, ox, c.error,
              e.error, oj, f.error, g.error, on, e1, e2, e1 / e2);
  cr_assert(ox > 2.8 && ox < 3.6, "space order %.3f", ox);
  cr_assert(oj > 2.7 && oj < 4.2 && on > 2.7 && on < 4.2, "joint orders %.3f %.3f", oj, on);
  g_result *all[] = {&a, &b, &c, &e, &f, &g, &r, &t1, &t2};
  for (size_t k = 0; k < sizeof all / sizeof all[0]; k++) free(all[k]->u);
}

Test(pde_gauss, odd_n_is_an_error) {
  gm_pde_equation eq = gm_pde_sine_gordon();
  const gm_pde_scheme *s = NULL;
  gm_pde_scheme_find("gauss-prk", &s);
  gm_pde_grid g = {101, 0.4, -PDE_L, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = 0.1;
  double *s0 = calloc(3 * 101, sizeof *s0);
  gm_pde *p = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_create(&g, &eq, s, &o, s0, &p, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "even number of points") != NULL, "%s", err.message);
  cr_assert_null(p);
  free(s0);
}
