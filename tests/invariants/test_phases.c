/* Geometric phases against closed forms (docs/reduction.md, "Phases"): Foucault's pendulum as
 * the holonomy of the sphere's Levi-Civita connection along a latitude circle (−2π cos α), a
 * loop not around the pole (its enclosed area, Gauss–Bonnet), Montgomery's rigid-body phase
 * with the lgvi row (Δθ = 2ET/‖m‖ − Λ), and the double spherical pendulum's shape-loop holonomy
 * at μ = 0 converging with each discrete connection's order. */
#include "test_util.h"

#define PI 3.14159265358979323846

static gm_discrete_connection sphere(gm_dconn_rule rule) {
  gm_discrete_connection c;
  memset(&c, 0, sizeof c);
  c.group = GM_GROUP_SO2;
  c.n = 2;
  c.rule = rule;
  c.connection = gm_sphere_levi_civita;
  return c;
}

/* the chart point of p ∈ S² (upper hemisphere) */
static void latitude_loop(double alpha, size_t n, double *pts) {
  for (size_t i = 0; i <= n; ++i) {
    const double phi = 2.0 * PI * (double)(i % n) / (double)n;
    pts[2 * i] = sin(alpha) * cos(phi);
    pts[2 * i + 1] = sin(alpha) * sin(phi);
  }
}

/* circle of angular radius beta about (sin c, 0, cos c), counterclockwise seen from outside */
static void tilted_loop(double c, double beta, size_t n, double *pts) {
  for (size_t i = 0; i <= n; ++i) {
    const double s = 2.0 * PI * (double)(i % n) / (double)n;
    const double u[3] = {cos(c), 0.0, -sin(c)}, v[3] = {0, 1, 0}, m[3] = {sin(c), 0, cos(c)};
    pts[2 * i] = cos(beta) * m[0] + sin(beta) * (cos(s) * u[0] + sin(s) * v[0]);
    pts[2 * i + 1] = cos(beta) * m[1] + sin(beta) * (cos(s) * u[1] + sin(s) * v[1]);
  }
}


/* A loop sampled at N points is a polygon in the chart: any discrete connection's holonomy
 * misses the smooth loop's closed form by the polygon's O(1/N²) (the curvature between chords
 * and curve), and misses the exact (transport) holonomy of the same polygon by N·O(h^{k+1}) =
 * O(1/N^k), k the connection's order. Both are asserted. */
static void converge(const char *what, int n_dim, void (*f)(double, double, size_t, double *),
                     int (*conn)(void *, const double *, double *), double p1, double p2,
                     double exact, double tol) {
  static const struct {
    gm_dconn_rule rule;
    const char *name;
    double order;
  } rules[] = {{GM_DCONN_MIDPOINT, "midpoint", 2}, {GM_DCONN_MAGNUS4, "gauss-2", 4}};
  for (int r = 0; r < 2; ++r) {
    gm_discrete_connection c, ex;
    memset(&c, 0, sizeof c);
    c.group = GM_GROUP_SO2;
    c.n = (size_t)n_dim;
    c.rule = rules[r].rule;
    c.connection = conn;
    ex = c;
    ex.rule = GM_DCONN_TRANSPORT;
    ex.substeps = 16;
    double err[3], errp[3], hol = 0, holex = 0;
    for (int l = 0; l < 3; ++l) {
      const size_t n = (size_t)16 << l;
      double pts[3 * 65];
      f(p1, p2, n, pts);
      cr_assert_eq(gm_dconn_holonomy(&c, n + 1, pts, &hol, NULL), GM_OK);
      cr_assert_eq(gm_dconn_holonomy(&ex, n + 1, pts, &holex, NULL), GM_OK);
      err[l] = fabs(hol - exact);
      errp[l] = fabs(hol - holex);
    }
    const double q = log2(err[1] / err[2]), qp = log2(errp[1] / errp[2]);
    cr_log_info("%s, %s: closed form %.12f, N = 64: %.12f; errors vs closed form %.3g %.3g %.3g "
                "(N = 16, 32, 64), order %.3f; vs the polygon's exact holonomy %.3g %.3g %.3g, order %.3f",
                what, rules[r].name, exact, hol, err[0], err[1], err[2], q, errp[0], errp[1], errp[2], qp);
    cr_expect(fabs(q - 2.0) < 0.2, "%s %s: order vs closed form %.3f", what, rules[r].name, q);
    cr_expect_lt(err[2], tol, "%s %s: error %.3g", what, rules[r].name, err[2]);
    cr_expect(fabs(qp - rules[r].order) < 0.3, "%s %s: order vs exact %.3f", what, rules[r].name, qp);
  }
}

static void lat_adapter(double a, double unused, size_t n, double *pts) {
  (void)unused;
  latitude_loop(a, n, pts);
}

Test(phases, foucault_pendulum) {
  /* Paris (Panthéon): latitude 48.8462°, colatitude α = 41.1538°: the plane turns by
   * 2π sin(latitude) = 2π cos α = 4.7306 rad (271.0°) clockwise per sidereal day. */
  const double alpha = (90.0 - 48.8462) * PI / 180.0;
  converge("Foucault (latitude circle, colatitude 41.15 deg)", 2, lat_adapter, gm_sphere_levi_civita, alpha, 0.0,
           -2.0 * PI * cos(alpha), 0.03);
  converge("latitude circle, colatitude 70 deg", 2, lat_adapter, gm_sphere_levi_civita, 70.0 * PI / 180.0, 0.0,
           -2.0 * PI * cos(70.0 * PI / 180.0), 0.03);
  /* a loop not around the pole: the frame does not wind, holonomy = enclosed area */
  converge("circle of radius 0.3 about colatitude 0.6", 2, tilted_loop, gm_sphere_levi_civita, 0.6, 0.3,
           2.0 * PI * (1.0 - cos(0.3)), 1e-3);
  double hol;
  gm_discrete_connection ex = sphere(GM_DCONN_TRANSPORT);
  /* a pole inside the chart is refused by the callback */
  const double through[6] = {0.1, 0.0, -0.1, 0.0, 0.1, 0.0};
  gm_error err;
  cr_expect_eq(gm_dconn_holonomy(&ex, 3, through, &hol, &err), GM_ECALLBACK);
}

/* ---- Montgomery's rigid-body phase with lgvi -------------------------------------------- */

static double wrap(double x) { return x - 2.0 * PI * floor((x + PI) / (2.0 * PI)); }

static double lgvi_phase(const char *row, const double *pi0, size_t n, double period) {
  gm_model *model = NULL;
  cr_assert_eq(gm_model_create("rigid-body", &model), GM_OK);
  const char *names[3] = {"Pi1", "Pi2", "Pi3"};
  for (int i = 0; i < 3; ++i) cr_assert_eq(gm_model_set(model, names[i], pi0[i]), GM_OK);
  cr_assert_eq(gm_model_build(model), GM_OK, "%s", gm_model_errmsg(model));
  const gm_problem *pb = gm_model_problem(model);
  double t0, y0[12];
  gm_model_initial_state(model, &t0, y0);
  gm_integrator *it = test_integrator(gm_method_find(row), pb, t0, y0);
  cr_assert_eq(gm_integrator_run(it, n, period / (double)n), GM_OK, "%s", gm_integrator_errmsg(it));
  const double *y = gm_integrator_state(it);
  double m[3];
  gm_mat3_vec(y0, y0 + 9, m); /* spatial momentum m = R Π */
  const double angle = gm_so3_angle_about(y0, y, m);
  gm_integrator_free(it);
  gm_model_free(model);
  return angle;
}

Test(phases, montgomery_rigid_body_phase) {
  const double inertia[3] = {1.0, 2.0, 3.0};
  static const double cases[2][3] = {{0.3, 0.2, 1.0}, {1.0, 0.2, 0.3}}; /* about axis 3; about axis 1 */
  for (int k = 0; k < 2; ++k) {
    double period, dyn, lambda, lam2;
    cr_assert_eq(gm_rigid_body_phase(inertia, cases[k], 0, &period, &dyn, &lambda, NULL), GM_OK);
    cr_assert_eq(gm_rigid_body_phase(inertia, cases[k], 40000, NULL, NULL, &lam2, NULL), GM_OK);
    cr_expect(fabs(lambda - lam2) < 1e-11, "solid-angle quadrature converged: %.3g", lambda - lam2);
    const double closed = wrap(dyn - lambda);
    /* the error at T/256 of each row and case, measured: lgvi 1.43e-3 and 3.28e-3,
     * lgvi-galerkin-2 9.13e-9 and 3.62e-10 (its order 4 at T/64..T/256); bounds 1.5x */
    static const struct {
      const char *row;
      double order, bound[2];
    } rows[] = {{"lgvi", 2, {2.2e-3, 5e-3}}, {"lgvi-galerkin-2", 4, {1.4e-8, 5.5e-10}}};
    for (int r = 0; r < 2; ++r) {
      double err[3], got = 0;
      for (int l = 0; l < 3; ++l) {
        got = lgvi_phase(rows[r].row, cases[k], (size_t)64 << l, period);
        err[l] = fabs(wrap(got - closed));
      }
      const double q = log2(err[1] / err[2]);
      cr_log_info("rigid body Pi0 = (%.1f, %.1f, %.1f): T = %.10f, 2ET/|m| = %.10f, Lambda = %.10f, "
                  "closed form %.10f; %s at T/256 %.10f, errors %.3g %.3g %.3g (T/64, T/128, T/256), "
                  "order %.3f (with +Lambda the miss would be %.3g)",
                  cases[k][0], cases[k][1], cases[k][2], period, dyn, lambda, closed, rows[r].row, got,
                  err[0], err[1], err[2], q, fabs(wrap(got - wrap(dyn + lambda))));
      cr_expect(fabs(q - rows[r].order) < 0.3, "%s phase order %.3f", rows[r].row, q);
      cr_expect_lt(err[2], rows[r].bound[k], "%s phase error %.3g", rows[r].row, err[2]);
    }
  }
  gm_error e;
  cr_expect_eq(gm_rigid_body_phase(inertia, (const double[3]){0, 1, 0}, 0, NULL, NULL, NULL, &e), GM_EINVAL);
}

/* ---- the double spherical pendulum at μ = 0 --------------------------------------------- */

static gm_routh_dsp_params dspp = {1.0, 0.7, 1.0, 0.8, 9.81};
static gm_routh_system dsp_sys;

static int dsp_connection(void *ctx, const double *x, double *a) {
  (void)ctx;
  const double mu[1] = {0.0};
  return gm_routh_connection(&dsp_sys, mu, x, NULL, a, NULL, NULL, NULL, NULL, NULL) == GM_OK ? 0 : -1;
}

static void dsp_loop(double t, double *x) {
  x[0] = 0.5 + 0.2 * cos(t);
  x[1] = 0.4 + 0.1 * sin(2 * t);
  x[2] = 1.0 + 0.8 * sin(t);
}

static void dsp_points(double unused1, double unused2, size_t n, double *pts) {
  (void)unused1, (void)unused2;
  for (size_t i = 0; i <= n; ++i) dsp_loop(2 * PI * (double)(i % n) / (double)n, pts + 3 * i);
}

Test(phases, double_spherical_pendulum_shape_loop) {
  gm_routh_double_spherical_pendulum(&dspp, &dsp_sys);
  /* the smooth loop's phase −∮A·dx (trapezoid in t on 4096 points: spectrally accurate for a
   * periodic integrand) */
  double exact = 0.0;
  const int nref = 4096;
  for (int i = 0; i < nref; ++i) {
    const double t = 2 * PI * i / nref;
    double x[3], a[3];
    const double dx[3] = {-0.2 * sin(t), 0.2 * cos(2 * t), 0.8 * cos(t)};
    dsp_loop(t, x);
    cr_assert_eq(dsp_connection(NULL, x, a), 0);
    exact -= (a[0] * dx[0] + a[1] * dx[1] + a[2] * dx[2]) * 2 * PI / nref;
  }
  converge("DSP shape loop (mu = 0)", 3, dsp_points, dsp_connection, 0, 0, exact, 1e-3);
  /* the midpoint L_d's discrete Routh holonomy Σ ψ_0 is the midpoint connection's holonomy */
  gm_discrete_lagrangian ld;
  gm_routh_midpoint_lagrangian(&dsp_sys, &ld);
  gm_routh_discrete *d = NULL;
  const double mu[1] = {0.0};
  cr_assert_eq(gm_routh_discrete_create(&ld, &dsp_sys, mu, NULL, &d, NULL), GM_OK);
  gm_discrete_connection c;
  memset(&c, 0, sizeof c);
  c.group = GM_GROUP_SO2;
  c.n = 3;
  c.rule = GM_DCONN_MIDPOINT;
  c.connection = dsp_connection;
  double pts[3 * 33], hol, psi_sum;
  dsp_points(0, 0, 32, pts);
  cr_assert_eq(gm_dconn_holonomy(&c, 33, pts, &hol, NULL), GM_OK);
  cr_assert_eq(gm_routh_holonomy(d, 0.1, 33, pts, &psi_sum), GM_OK);
  cr_expect(fabs(psi_sum - hol) < 1e-13, "sum psi_0 %.17g vs midpoint connection %.17g", psi_sum, hol);
  gm_routh_discrete_free(d);
}
