/* KdV u_t + u u_x + u_xxx = 0 in the multisymplectic framework: the Preissmann box of Ascher &
 * McLachlan (2004) on s = (φ, u, v, w) with the gauge pinned (φ₀ⁿ⁺¹ = φ₀ⁿ), and Zabusky–Kruskal
 * (1965), against the soliton u = 3c sech²(√c (x − ct)/2) on [−20, 20) periodic (c = 1, centre
 * −2 at t = 0; the tail there is ~2e-7): orders in t and x, the multisymplectic law per cell,
 * the mass to round-off, energy and momentum monitors. */
#include "pde_util.h"

#define KDV_C 1.0
#define KDV_X0 (-2.0)

static double kdv_u(double x, double t) {
  double xi = 0.5 * sqrt(KDV_C) * (x - KDV_X0 - KDV_C * t);
  return 3.0 * KDV_C / (cosh(xi) * cosh(xi));
}

/* s = (φ, u, v, w) at t: φ by the trapezoidal rule from its exact value at x0 (so the box's
 * consistency h Σ ū = twist holds exactly), v = u_x, w = cu/2; returns the twist */
static double kdv_data(size_t n, double h, double t, double *s) {
  double xi0 = 0.5 * sqrt(KDV_C) * (-PDE_L - KDV_X0 - KDV_C * t);
  double phi = 6.0 * sqrt(KDV_C) * (tanh(xi0) + 1.0), tw = 0.0;
  for (size_t i = 0; i < n; i++) {
    double x = -PDE_L + (double)i * h, u = kdv_u(x, t), un = kdv_u(x + h, t);
    double xi = 0.5 * sqrt(KDV_C) * (x - KDV_X0 - KDV_C * t);
    s[4 * i] = phi;
    s[4 * i + 1] = u;
    s[4 * i + 2] = -u * sqrt(KDV_C) * tanh(xi);
    s[4 * i + 3] = 0.5 * KDV_C * u;
    (void)un;
  }
  for (size_t i = 0; i < n; i++) {
    double d = 0.5 * h * (s[4 * i + 1] + s[4 * ((i + 1) % n) + 1]);
    tw += d;
    if (i + 1 < n) s[4 * (i + 1)] = s[4 * i] + d;
  }
  return tw;
}

typedef struct kdv_result {
  double error, mass_drift, energy_drift, momentum_drift, ms;
  double *u; /* final u (owned) */
} kdv_result;

static kdv_result kdv_run(const char *scheme, size_t n, double dt, double T, int keep) {
  double h = 2.0 * PDE_L / (double)n;
  gm_pde_equation eq = gm_pde_kdv();
  const gm_pde_scheme *s = NULL;
  cr_assert_eq(gm_pde_scheme_find(scheme, &s), GM_OK);
  double *s0 = calloc(4 * n, sizeof *s0);
  gm_pde_grid g = {n, h, -PDE_L, {0}};
  g.twist[0] = kdv_data(n, h, 0.0, s0);
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = dt;
  o.track_variations = strcmp(scheme, "preissmann") == 0;
  gm_pde *p = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_create(&g, &eq, s, &o, s0, &p, &err), GM_OK, "%s", err.message);
  kdv_result r = {0};
  double m0 = gm_pde_mass(p), e0 = gm_pde_energy(p), i0 = gm_pde_momentum(p);
  size_t steps = (size_t)llround(T / dt);
  for (size_t k = 0; k < steps; k++) {
    cr_assert_eq(gm_pde_advance(p, 1, &err), GM_OK, "%s", err.message);
    r.mass_drift = fmax(r.mass_drift, fabs(gm_pde_mass(p) - m0) / fabs(m0));
    r.energy_drift = fmax(r.energy_drift, fabs(gm_pde_energy(p) - e0) / fabs(e0));
    r.momentum_drift = fmax(r.momentum_drift, fabs(gm_pde_momentum(p) - i0) / fabs(i0));
    r.ms = fmax(r.ms, gm_pde_ms_residual(p, NULL));
  }
  const double *st = gm_pde_state(p);
  if (keep) r.u = calloc(n, sizeof *r.u);
  for (size_t i = 0; i < n; i++) {
    r.error = fmax(r.error, fabs(st[4 * i + 1] - kdv_u(-PDE_L + (double)i * h, gm_pde_time(p))));
    if (keep) r.u[i] = st[4 * i + 1];
  }
  free(s0);
  gm_pde_free(p);
  return r;
}

Test(pde_kdv, preissmann_soliton_order_and_laws) {
  /* joint refinement Δt = Δx/2 */
  kdv_result a = kdv_run("preissmann", 200, 0.1, 4.0, 0), b = kdv_run("preissmann", 400, 0.05, 4.0, 0);
  double order = log2(a.error / b.error);
  cr_log_info("KdV Preissmann, dt = dx/2, T = 4: errors %.3e, %.3e, order %.3f; mass drift "
              "%.1e, %.1e; energy %.2e, %.2e; momentum %.2e, %.2e; ms residual %.1e, %.1e",
              a.error, b.error, order, a.mass_drift, b.mass_drift, a.energy_drift,
              b.energy_drift, a.momentum_drift, b.momentum_drift, a.ms, b.ms);
  cr_assert(order > 1.9 && order < 2.15, "joint order %.3f", order);
  cr_assert(a.ms <= 1e-12 && b.ms <= 1e-12, "ms residual %.2e %.2e", a.ms, b.ms);
  cr_assert(a.mass_drift < 1e-13 && b.mass_drift < 1e-13, "mass %.2e %.2e", a.mass_drift,
            b.mass_drift);
  /* energy and momentum are not exact for the box: their errors fall at second order */
  cr_assert(b.energy_drift < a.energy_drift / 3.0 && b.momentum_drift < a.momentum_drift / 3.0,
            "energy %.2e -> %.2e, momentum %.2e -> %.2e", a.energy_drift, b.energy_drift,
            a.momentum_drift, b.momentum_drift);
}

Test(pde_kdv, preissmann_time_and_space_orders) {
  /* time: fixed grid n = 200, Δt = 0.2, 0.1 against Δt = 0.0125 */
  kdv_result ref = kdv_run("preissmann", 200, 0.0125, 2.0, 1);
  double et[2];
  for (int k = 0; k < 2; k++) {
    kdv_result r = kdv_run("preissmann", 200, 0.2 / (1 << k), 2.0, 1);
    et[k] = 0.0;
    for (size_t i = 0; i < 200; i++) et[k] = fmax(et[k], fabs(r.u[i] - ref.u[i]));
    free(r.u);
  }
  free(ref.u);
  /* space: Δt = 0.01 fixed (time error ~1e-4 of the space error), n = 100 → 200 */
  kdv_result a = kdv_run("preissmann", 100, 0.01, 2.0, 0), b = kdv_run("preissmann", 200, 0.01, 2.0, 0);
  double ot = log2(et[0] / et[1]), ox = log2(a.error / b.error);
  cr_log_info("KdV Preissmann: time errors %.3e, %.3e (order %.3f); space errors %.3e, %.3e "
              "(order %.3f)", et[0], et[1], ot, a.error, b.error, ox);
  cr_assert(ot > 1.9 && ot < 2.15, "time order %.3f", ot);
  cr_assert(ox > 1.9 && ox < 2.15, "space order %.3f", ox);
}

Test(pde_kdv, zabusky_kruskal_order) {
  /* Δt at 0.8 of the stability bound: the time error (Δt ~ Δx³) is invisible, the order is
   * the space order */
  double e[2], mass[2];
  for (int k = 0; k < 2; k++) {
    size_t n = 200u << k;
    double h = 2.0 * PDE_L / (double)n;
    double dt = 0.8 / (1.5 * sqrt(3.0) / (h * h * h) + 3.0 * KDV_C / h);
    dt = 2.0 / ceil(2.0 / dt);
    kdv_result r = kdv_run("zk", n, dt, 2.0, 0);
    e[k] = r.error;
    mass[k] = r.mass_drift;
  }
  double order = log2(e[0] / e[1]);
  cr_log_info("KdV Zabusky-Kruskal, dt = 0.8 of the bound, T = 2: errors %.3e, %.3e, order %.3f;"
              " mass drift %.1e, %.1e", e[0], e[1], order, mass[0], mass[1]);
  cr_assert(order > 1.9 && order < 2.15, "order %.3f", order);
  cr_assert(mass[0] < 1e-13 && mass[1] < 1e-13, "mass %.2e %.2e", mass[0], mass[1]);
}

Test(pde_kdv, bad_input) {
  gm_pde_equation eq = gm_pde_kdv();
  const gm_pde_scheme *zk = NULL, *box = NULL, *eb = NULL;
  gm_pde_scheme_find("zk", &zk);
  gm_pde_scheme_find("preissmann", &box);
  gm_pde_scheme_find("euler-box", &eb);
  size_t n = 200;
  double h = 0.2, *s0 = calloc(4 * n, sizeof *s0);
  gm_pde_grid g = {n, h, -PDE_L, {0}};
  g.twist[0] = kdv_data(n, h, 0.0, s0);
  gm_pde_options o = gm_pde_options_defaults();
  gm_pde *p = NULL;
  gm_error err = {{0}};
  o.dt = 0.01; /* > the ZK bound 2.9e-3 */
  cr_assert_eq(gm_pde_create(&g, &eq, zk, &o, s0, &p, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "stability bound") != NULL, "%s", err.message);
  cr_assert_eq(gm_pde_create(&g, &eq, eb, &o, s0, &p, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "gauge") != NULL, "%s", err.message);
  g.twist[0] += 1e-3;
  cr_assert_eq(gm_pde_create(&g, &eq, box, &o, s0, &p, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "twist") != NULL, "%s", err.message);
  gm_pde_equation sg = gm_pde_sine_gordon();
  double *z = calloc(3 * n, sizeof *z);
  cr_assert_eq(gm_pde_create(&g, &sg, zk, &o, z, &p, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "KdV") != NULL, "%s", err.message);
  cr_assert_null(p);
  free(z);
  free(s0);
}
