/* Dirichlet ends: the moving sine-Gordon kink u = 4 arctan(exp(γ(x − ct))), c = 0.5, on
 * [−20, 20] with u held at 0 and 2π (no twist: the ring could not hold the kink), for lf, ec,
 * ms (u held at both ends) and the Preissmann box (u at both ends and v at the left end): order
 * 2, the ends held exactly, EC's energy to round-off, the box's multisymplectic law per cell. */
#include "pde_util.h"

#define KC 0.5

static void kink(double x, double t, double *s) {
  double g = 1.0 / sqrt(1.0 - KC * KC), xi = g * (x - KC * t);
  s[0] = 4.0 * atan(exp(xi));
  s[2] = 2.0 * g / cosh(xi);
  s[1] = -KC * s[2];
}

typedef struct dir_result {
  double error, end_drift, energy_drift, ms;
} dir_result;

static dir_result dir_run(const char *scheme, size_t n, double T) {
  double h = 2.0 * PDE_L / (double)(n - 1), dt = h / 2;
  gm_pde_equation eq = gm_pde_sine_gordon();
  const gm_pde_scheme *s = NULL;
  cr_assert_eq(gm_pde_scheme_find(scheme, &s), GM_OK);
  int box = strcmp(scheme, "preissmann") == 0;
  gm_pde_grid g = {n, h, -PDE_L, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = dt;
  o.track_variations = box;
  o.dirichlet_left = box ? 3u : 1u;
  o.dirichlet_right = 1u;
  double *s0 = calloc(3 * n, sizeof *s0);
  for (size_t i = 0; i < n; i++) kink(-PDE_L + (double)i * h, 0.0, s0 + 3 * i);
  gm_pde *p = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_create(&g, &eq, s, &o, s0, &p, &err), GM_OK, "%s: %s", scheme, err.message);
  dir_result r = {0, 0, 0, 0};
  double e0 = gm_pde_energy(p);
  size_t steps = (size_t)llround(T / dt);
  for (size_t k = 0; k < steps; k++) {
    cr_assert_eq(gm_pde_advance(p, 1, &err), GM_OK, "%s", err.message);
    const double *st = gm_pde_state(p);
    r.end_drift = fmax(r.end_drift, fmax(fabs(st[0] - s0[0]), fabs(st[3 * (n - 1)] - s0[3 * (n - 1)])));
    r.energy_drift = fmax(r.energy_drift, fabs(gm_pde_energy(p) - e0) / fabs(e0));
    r.ms = fmax(r.ms, gm_pde_ms_residual(p, NULL));
  }
  const double *st = gm_pde_state(p);
  double ex[3];
  for (size_t i = 0; i < n; i++) {
    kink(-PDE_L + (double)i * h, gm_pde_time(p), ex);
    r.error = fmax(r.error, fabs(st[3 * i] - ex[0]));
  }
  free(s0);
  gm_pde_free(p);
  return r;
}

Test(pde_dirichlet, kink_orders_and_laws) {
  const char *names[] = {"lf", "ec", "ms", "preissmann"};
  for (size_t k = 0; k < 4; k++) {
    dir_result a = dir_run(names[k], 201, 4.0), b = dir_run(names[k], 401, 4.0);
    double order = log2(a.error / b.error);
    cr_log_info("Dirichlet kink %-10s errors %.3e, %.3e, order %.3f; ends moved by %.1e; "
                "energy drift %.2e; ms residual %.1e", names[k], a.error, b.error, order,
                fmax(a.end_drift, b.end_drift), b.energy_drift, fmax(a.ms, b.ms));
    cr_assert(order > 1.9 && order < 2.15, "%s: order %.3f", names[k], order);
    cr_assert(a.end_drift == 0.0 && b.end_drift == 0.0, "%s: the ends moved", names[k]);
    if (strcmp(names[k], "ec") == 0)
      cr_assert(a.energy_drift < 1e-13 && b.energy_drift < 1e-13, "ec energy %.2e %.2e",
                a.energy_drift, b.energy_drift);
    if (strcmp(names[k], "preissmann") == 0)
      cr_assert(a.ms <= 1e-12 && b.ms <= 1e-12, "ms residual %.2e %.2e", a.ms, b.ms);
  }
}

Test(pde_dirichlet, bad_masks) {
  gm_pde_equation eq = gm_pde_sine_gordon();
  const gm_pde_scheme *pre = NULL, *eb = NULL, *ms = NULL;
  gm_pde_scheme_find("preissmann", &pre);
  gm_pde_scheme_find("euler-box", &eb);
  gm_pde_scheme_find("ms", &ms);
  size_t n = 100;
  double *s0 = calloc(3 * n, sizeof *s0);
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = 0.1;
  gm_pde *p = NULL;
  gm_error err = {{0}};
  gm_pde_grid g = {n, 0.2, 0.0, {0}};
  o.dirichlet_left = o.dirichlet_right = 1u; /* two held components, d = 3 */
  cr_assert_eq(gm_pde_create(&g, &eq, pre, &o, s0, &p, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "held components") != NULL, "%s", err.message);
  cr_assert_eq(gm_pde_create(&g, &eq, eb, &o, s0, &p, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "not implemented") != NULL, "%s", err.message);
  o.dirichlet_right = 2u; /* v, not u */
  cr_assert_eq(gm_pde_create(&g, &eq, ms, &o, s0, &p, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "bit 0") != NULL, "%s", err.message);
  o.dirichlet_right = 1u;
  g.twist[0] = 1.0;
  cr_assert_eq(gm_pde_create(&g, &eq, ms, &o, s0, &p, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "twist") != NULL, "%s", err.message);
  g.twist[0] = 0.0;
  o.dirichlet_left = 3u; /* even n is fine with Dirichlet ends */
  cr_assert_eq(gm_pde_create(&g, &eq, pre, &o, s0, &p, &err), GM_OK, "%s", err.message);
  gm_pde_free(p);
  free(s0);
}
