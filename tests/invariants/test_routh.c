/* Routh reduction by an abelian symmetry (include/geomint/reduction.h; seed 001 ch. 2): the
 * discrete Routh equations are the shape rows of the DEL on J_d = μ, RSPRK (eq. 2.5.14) equals
 * the SPRK on the classical Routhian (eq. 2.7.5) up to σ(x, s) = (x, s + μA(x)), the reduced
 * order is the order of L_d, and the double spherical pendulum's 𝕀, A, β_μ are the closed forms
 * (β_μ as corrected in the seed notes §4). */
#include "test_util.h"

static gm_routh_j2_params j2p = {0.05};
static gm_routh_dsp_params dspp = {1.0, 0.7, 1.0, 0.8, 9.81};

static gm_tableau *galerkin(size_t s) {
  static const double nodes[3][3] = {{0.5}, {0.21132486540518711775, 0.78867513459481288225},
                                     {0.11270166537925831148, 0.5, 0.88729833462074168852}};
  gm_tableau *t = NULL;
  cr_assert_eq(gm_galerkin_prk_tableau(s, nodes[s - 1], &t), GM_OK);
  return t;
}

Test(routh, dsp_locked_inertia_connection_and_beta) {
  gm_routh_system sys;
  gm_routh_double_spherical_pendulum(&dspp, &sys);
  const double mu[1] = {0.9}, x[3] = {0.6, 0.5, 1.1};
  double in, a[3], beta[9];
  cr_assert_eq(gm_routh_connection(&sys, mu, x, &in, a, NULL, NULL, NULL, NULL, NULL), GM_OK);
  const double m1 = dspp.m1, m2 = dspp.m2, r1 = x[0], r2 = x[1], c = cos(x[2]), s = sin(x[2]);
  const double I = m1 * r1 * r1 + m2 * (r1 * r1 + r2 * r2 + 2 * r1 * r2 * c);
  const double ae[3] = {-m2 / I * r2 * s, m2 / I * r1 * s, m2 / I * (r2 * r2 + r1 * r2 * c)};
  cr_expect(fabs(in - I) < 1e-13, "locked inertia %.17g vs %.17g", in, I);
  for (int i = 0; i < 3; ++i) cr_expect(fabs(a[i] - ae[i]) < 1e-13, "A[%d] %.17g vs %.17g", i, a[i], ae[i]);
  /* β_μ = (2μ m1 m2 r1 r2/𝕀²) dφ∧(r2 dr1 − r1 dr2): β_φr1 = f r2, β_φr2 = −f r1 */
  cr_assert_eq(gm_routh_magnetic(&sys, mu, x, beta, NULL), GM_OK);
  const double f = 2 * mu[0] * m1 * m2 * r1 * r2 / (I * I);
  const double want[9] = {0, 0, -f * r2, 0, 0, f * r1, f * r2, -f * r1, 0};
  for (int i = 0; i < 9; ++i)
    cr_expect(fabs(beta[i] - want[i]) < 1e-8, "beta[%d] %.12g vs %.12g", i, beta[i], want[i]);
}

/* the DR equations against the x-rows of the DEL on J_d = μ, along an unreduced trajectory */
static void check_dr_is_del(gm_routh_system *sys, const double *q0, const double *px0,
                            double mu, double h) {
  const size_t k = sys->k, n = sys->n, N = k + n;
  gm_discrete_lagrangian ld;
  gm_routh_midpoint_lagrangian(sys, &ld);
  gm_dl_solver *solver = NULL;
  cr_assert_eq(gm_dl_solver_create(&ld, &solver, NULL), GM_OK);
  double q[4][8], p[8];
  memcpy(q[0], q0, N * sizeof(double));
  p[0] = mu;
  memcpy(p + 1, px0, n * sizeof(double));
  for (int s = 1; s < 4; ++s) {
    memcpy(q[s], q[s - 1], N * sizeof(double));
    cr_assert_eq(gm_dl_solver_step(solver, h, q[s], p), GM_OK, "%s", gm_dl_solver_errmsg(solver));
  }
  gm_dl_solver_free(solver);
  gm_routh_discrete *d = NULL;
  const double muv[1] = {mu};
  cr_assert_eq(gm_routh_discrete_create(&ld, sys, muv, NULL, &d, NULL), GM_OK);
  double worst_psi = 0, worst_res = 0, worst_diff = 0, scale = 0;
  for (int s = 0; s + 2 < 4; ++s) {
    double psi, res[8], psi2;
    cr_assert_eq(gm_routh_psi(d, h, q[s] + k, q[s + 1] + k, 0, &psi), GM_OK);
    worst_psi = fmax(worst_psi, fabs(psi - (q[s + 1][0] - q[s][0])));
    (void)psi2;
    cr_assert_eq(gm_routh_discrete_residual(d, h, q[s] + k, q[s + 1] + k, q[s + 2] + k, NULL, res),
                 GM_OK);
    for (size_t i = 0; i < n; ++i) worst_res = fmax(worst_res, fabs(res[i]));
    /* at perturbed shape points: DR residual = x-rows of D₂L_d(q_{k−1}, q_k) + D₁L_d(q_k, q_{k+1})
     * with θ from ψ_μ (θ_{k−1} = 0) */
    double xm[8], x[8], xp[8], pa, pb, qa[8], qb[8], qc[8], g1[8], g2[8];
    for (size_t i = 0; i < n; ++i) {
      xm[i] = q[s][k + i] + 1e-3 * (double)(i + 1);
      x[i] = q[s + 1][k + i] - 2e-3;
      xp[i] = q[s + 2][k + i] + 1.5e-3 * (double)i;
    }
    cr_assert_eq(gm_routh_discrete_residual(d, h, xm, x, xp, NULL, res), GM_OK);
    cr_assert_eq(gm_routh_psi(d, h, xm, x, 0, &pa), GM_OK);
    cr_assert_eq(gm_routh_psi(d, h, x, xp, 0, &pb), GM_OK);
    qa[0] = 0;
    qb[0] = pa;
    qc[0] = pa + pb;
    memcpy(qa + 1, xm, n * sizeof(double));
    memcpy(qb + 1, x, n * sizeof(double));
    memcpy(qc + 1, xp, n * sizeof(double));
    cr_assert_eq(ld.d2(ld.ctx, h, qa, qb, g2), 0);
    cr_assert_eq(ld.d1(ld.ctx, h, qb, qc, g1), 0);
    for (size_t i = 0; i < n; ++i) {
      const double del = g2[k + i] + g1[k + i];
      worst_diff = fmax(worst_diff, fabs(res[i] - del));
      scale = fmax(scale, fabs(g2[k + i]));
    }
    /* θ-rows: J_d = μ on both sides */
    cr_expect(fabs(g2[0] - mu) < 1e-13 * (1 + fabs(mu)) && fabs(g1[0] + mu) < 1e-13 * (1 + fabs(mu)),
              "theta rows %.3g %.3g", g2[0] - mu, g1[0] + mu);
  }
  cr_log_info("psi %.3g, DR residual %.3g, DR - DEL_x %.3g (scale %.3g)", worst_psi, worst_res,
              worst_diff, scale);
  cr_expect(worst_psi < 1e-13, "psi vs theta increment: %.3g", worst_psi);
  cr_expect(worst_res < 1e-11 * (1 + scale), "DR residual on the DEL trajectory: %.3g", worst_res);
  cr_expect(worst_diff < 1e-13 * (1 + scale), "DR - DEL_x: %.3g (scale %.3g)", worst_diff, scale);
  /* the DR step reproduces x_2 and θ_2 from (x_0, x_1) */
  double x2[8], th = q[1][0];
  memcpy(x2, q[1] + k, n * sizeof(double));
  cr_assert_eq(gm_routh_discrete_step(d, h, q[0] + k, q[1] + k, x2, &th, NULL), GM_OK, "%s",
               gm_routh_discrete_errmsg(d));
  double e = fabs(th - q[2][0]);
  for (size_t i = 0; i < n; ++i) e = fmax(e, fabs(x2[i] - q[2][k + i]));
  cr_expect(e < 1e-11, "DR step vs DEL step: %.3g", e);
  gm_routh_discrete_free(d);
}

Test(routh, discrete_routh_is_shape_part_of_del_j2) {
  gm_routh_system sys;
  gm_routh_j2_satellite(&j2p, &sys);
  const double r0 = 1.5, vc = sqrt(1 / r0), q0[3] = {0.0, r0, 0.0}, px[2] = {0.02, vc * sin(0.3)};
  check_dr_is_del(&sys, q0, px, r0 * vc * cos(0.3), 0.3);
}

Test(routh, discrete_routh_is_shape_part_of_del_dsp) {
  gm_routh_system sys;
  gm_routh_double_spherical_pendulum(&dspp, &sys);
  const double q0[4] = {0.0, 0.6, 0.5, 1.0}, px[3] = {0.1, -0.2, 0.3};
  check_dr_is_del(&sys, q0, px, 0.8, 0.05);
}

Test(routh, rsprk_equals_classical_up_to_momentum_shift) {
  gm_routh_system sys;
  gm_routh_double_spherical_pendulum(&dspp, &sys);
  const double mu[1] = {0.8};
  for (size_t st = 1; st <= 3; ++st) {
    gm_tableau *t = galerkin(st);
    gm_rsprk *a = NULL, *b = NULL;
    cr_assert_eq(gm_rsprk_create(&sys, t, GM_ROUTH_RSPRK, mu, &a, NULL), GM_OK);
    cr_assert_eq(gm_rsprk_create(&sys, t, GM_ROUTH_CLASSICAL, mu, &b, NULL), GM_OK);
    double x[3] = {0.6, 0.5, 1.0}, s[3] = {0.1, -0.2, 0.3}, xc[3], y[3], th = 0, thc = 0;
    memcpy(xc, x, sizeof x);
    cr_assert_eq(gm_routh_lift_momentum(&sys, mu, x, s, y, NULL), GM_OK);
    double worst = 0;
    for (int i = 0; i < 100; ++i) {
      cr_assert_eq(gm_rsprk_step(a, 0.02, x, s, &th), GM_OK, "%s", gm_rsprk_errmsg(a));
      cr_assert_eq(gm_rsprk_step(b, 0.02, xc, y, &thc), GM_OK, "%s", gm_rsprk_errmsg(b));
      double ys[3];
      cr_assert_eq(gm_routh_lift_momentum(&sys, mu, x, s, ys, NULL), GM_OK);
      for (int j = 0; j < 3; ++j) worst = fmax(worst, fmax(fabs(x[j] - xc[j]), fabs(ys[j] - y[j])));
      worst = fmax(worst, fabs(th - thc));
    }
    cr_log_info("%zu stages: RSPRK vs classical %.3g", st, worst);
    cr_expect(worst < 1e-12, "%zu stages: RSPRK vs classical SPRK differ by %.3g", st, worst);
    gm_rsprk_free(a);
    gm_rsprk_free(b);
    gm_tableau_free(t);
  }
}

/* reduced order = order of L_d: RSPRK with s Gauss points has order 2s on the J2 satellite */
static double rsprk_error(gm_routh_system *sys, gm_tableau *t, const double *mu, double h, int n,
                          const double *xr, const double *sr) {
  gm_rsprk *r = NULL;
  cr_assert_eq(gm_rsprk_create(sys, t, GM_ROUTH_RSPRK, mu, &r, NULL), GM_OK);
  double x[2] = {1.5, 0.0}, s[2] = {0.02, sqrt(1 / 1.5) * sin(0.3)};
  for (int i = 0; i < n; ++i) cr_assert_eq(gm_rsprk_step(r, h, x, s, NULL), GM_OK);
  gm_rsprk_free(r);
  return fmax(fmax(fabs(x[0] - xr[0]), fabs(x[1] - xr[1])), fmax(fabs(s[0] - sr[0]), fabs(s[1] - sr[1])));
}

Test(routh, reduced_order_is_order_of_ld) {
  gm_routh_system sys;
  gm_routh_j2_satellite(&j2p, &sys);
  const double mu[1] = {1.5 * sqrt(1 / 1.5) * cos(0.3)}, T = 3.0;
  gm_tableau *ref = galerkin(3);
  double xr[2], sr[2];
  {
    gm_rsprk *r = NULL;
    cr_assert_eq(gm_rsprk_create(&sys, ref, GM_ROUTH_RSPRK, mu, &r, NULL), GM_OK);
    xr[0] = 1.5;
    xr[1] = 0.0;
    sr[0] = 0.02;
    sr[1] = sqrt(1 / 1.5) * sin(0.3);
    for (int i = 0; i < 600; ++i) cr_assert_eq(gm_rsprk_step(r, T / 600, xr, sr, NULL), GM_OK);
    gm_rsprk_free(r);
  }
  for (size_t st = 1; st <= 2; ++st) {
    gm_tableau *t = galerkin(st);
    const int n1 = 15, n2 = 30;
    const double e1 = rsprk_error(&sys, t, mu, T / n1, n1, xr, sr);
    const double e2 = rsprk_error(&sys, t, mu, T / n2, n2, xr, sr);
    const double p = log(e1 / e2) / log(2.0);
    cr_log_info("%zu stages: order %.3f (%.3g, %.3g)", st, p, e1, e2);
    cr_expect(fabs(p - 2.0 * (double)st) < 0.3, "%zu stages: measured order %.3f (errors %.3g, %.3g)",
              st, p, e1, e2);
    gm_tableau_free(t);
  }
  gm_tableau_free(ref);
}

Test(routh, mu_inconsistent_with_state_is_refused) {
  gm_routh_system sys;
  gm_routh_j2_satellite(&j2p, &sys);
  const double mu[1] = {1.0}, x[2] = {1.5, 0.0}, pt[1] = {1.1}, px[2] = {0, 0};
  double s[2];
  gm_error err;
  cr_expect_eq(gm_routh_reduce_momentum(&sys, mu, x, pt, px, s, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "inconsistent") != NULL, "%s", err.message);
}

Test(routh, dsp_metric_derivative_matches_differences) {
  gm_routh_system sys, fd;
  gm_routh_double_spherical_pendulum(&dspp, &sys);
  fd = sys;
  fd.metric_dx = NULL;
  const double mu[1] = {0.8}, x[3] = {0.6, 0.5, 1.0};
  double da[9], dfa[9], k1[9], k2[9];
  cr_assert_eq(gm_routh_connection(&sys, mu, x, NULL, NULL, k1, da, NULL, NULL, NULL), GM_OK);
  cr_assert_eq(gm_routh_connection(&fd, mu, x, NULL, NULL, k2, dfa, NULL, NULL, NULL), GM_OK);
  for (int i = 0; i < 9; ++i) cr_expect(fabs(da[i] - dfa[i]) < 1e-8, "dA[%d] %.12g vs %.12g", i, da[i], dfa[i]);
}

/* Thm 2.17, forces: midpoint forces F̂¹ = F̂² = −(h/2)∇W(x̄) give the same DR step as adding W to
 * the potential (the midpoint L_d of V + W differs by −hW(x̄)) */
typedef struct {
  gm_routh_system base;
  double c;
} with_field;
static double wf_potential(void *ctx, const double *x) {
  const with_field *w = ctx;
  return w->base.potential(w->base.ctx, x) + w->c * x[1];
}
static int wf_potential_dx(void *ctx, const double *x, double *g) {
  const with_field *w = ctx;
  if (w->base.potential_dx(w->base.ctx, x, g)) return 1;
  g[1] += w->c;
  return 0;
}
static int wf_metric(void *ctx, const double *x, double *m) {
  const with_field *w = ctx;
  return w->base.metric(w->base.ctx, x, m);
}
static int field_force(void *ctx, double h, const double *x0, const double *x1, double *f) {
  (void)x0;
  (void)x1;
  f[0] = 0.0;
  f[1] = -0.5 * h * ((const with_field *)ctx)->c;
  return 0;
}

Test(routh, forces_in_the_discrete_routh_equations) {
  with_field w;
  gm_routh_j2_satellite(&j2p, &w.base);
  w.c = 0.3;
  gm_routh_system sw = {.k = 1, .n = 2, .ctx = &w, .metric = wf_metric, .metric_dx = NULL,
                        .potential = wf_potential, .potential_dx = wf_potential_dx};
  gm_discrete_lagrangian lw, lb;
  gm_routh_midpoint_lagrangian(&sw, &lw);
  gm_routh_midpoint_lagrangian(&w.base, &lb);
  const double mu[1] = {1.2}, h = 0.1;
  gm_routh_discrete_options opts = {.force1 = field_force, .force2 = field_force, .ctx = &w};
  gm_routh_discrete *a = NULL, *b = NULL;
  cr_assert_eq(gm_routh_discrete_create(&lw, &sw, mu, NULL, &a, NULL), GM_OK);
  cr_assert_eq(gm_routh_discrete_create(&lb, &w.base, mu, &opts, &b, NULL), GM_OK);
  double xm[2] = {1.5, 0.0}, x[2] = {1.502, 0.04}, xa[2] = {1.504, 0.08}, xb[2] = {1.504, 0.08};
  double ta = 0, tb = 0;
  cr_assert_eq(gm_routh_discrete_step(a, h, xm, x, xa, &ta, NULL), GM_OK, "%s", gm_routh_discrete_errmsg(a));
  cr_assert_eq(gm_routh_discrete_step(b, h, xm, x, xb, &tb, NULL), GM_OK, "%s", gm_routh_discrete_errmsg(b));
  const double e = fmax(fmax(fabs(xa[0] - xb[0]), fabs(xa[1] - xb[1])), fabs(ta - tb));
  cr_log_info("forces: DR step with force vs with potential: %.3g", e);
  cr_expect(e < 1e-11, "forced vs potential step differ by %.3g", e);
  gm_routh_discrete_free(a);
  gm_routh_discrete_free(b);
}

/* Thm 2.17, constraints: ĝ(x) = r − R on the equator; the orbit is the circle r = R, z = 0,
 * θ advances by hμ/R² per step (midpoint: J_d = R²ψ/h) and the multiplier is the r-row of the
 * DEL, λ = −h(μ²/R³ − ∂_rV(R, 0)), ∂_rV = 1/R² + 1.5 J2/R⁴ */
static int circle_g(void *ctx, const double *x, double *g) {
  g[0] = x[0] - *(const double *)ctx;
  return 0;
}
static int circle_dg(void *ctx, const double *x, double *j) {
  (void)ctx;
  (void)x;
  j[0] = 1.0;
  j[1] = 0.0;
  return 0;
}

Test(routh, constraints_in_the_discrete_routh_equations) {
  gm_routh_system sys;
  gm_routh_j2_satellite(&j2p, &sys);
  gm_discrete_lagrangian ld;
  gm_routh_midpoint_lagrangian(&sys, &ld);
  double R = 1.3;
  const double mu[1] = {0.9}, h = 0.2;
  gm_routh_discrete_options opts = {.n_constraints = 1, .constraint = circle_g,
                                    .constraint_jacobian = circle_dg, .ctx = &R};
  gm_routh_discrete *d = NULL;
  cr_assert_eq(gm_routh_discrete_create(&ld, &sys, mu, &opts, &d, NULL), GM_OK);
  double xm[2] = {R, 0.0}, x[2] = {R, 0.0}, th = 0.0, lam = 0.0, worst_g = 0, worst_th = 0,
         worst_l = 0;
  const double lam_exact = -h * (mu[0] * mu[0] / (R * R * R) - 1.0 / (R * R) - 1.5 * j2p.j2 / (R * R * R * R));
  for (int k = 0; k < 20; ++k) {
    double xp[2] = {x[0] + 0.01, x[1]}, th0 = th;
    cr_assert_eq(gm_routh_discrete_step(d, h, xm, x, xp, &th, &lam), GM_OK, "%s", gm_routh_discrete_errmsg(d));
    worst_g = fmax(worst_g, fabs(xp[0] - R) + fabs(xp[1]));
    worst_th = fmax(worst_th, fabs(th - th0 - h * mu[0] / (R * R)));
    worst_l = fmax(worst_l, fabs(lam - lam_exact));
    memcpy(xm, x, sizeof x);
    memcpy(x, xp, sizeof x);
  }
  cr_log_info("constraints: |g| %.3g, theta increment %.3g, lambda %.3g (exact %.6f)", worst_g,
              worst_th, worst_l, lam_exact);
  cr_expect(worst_g < 1e-12, "constraint residual %.3g", worst_g);
  cr_expect(worst_th < 1e-12, "theta increment error %.3g", worst_th);
  cr_expect(worst_l < 1e-8, "multiplier error %.3g", worst_l);
  gm_routh_discrete_free(d);
}

#define ROUTH_PI 3.14159265358979323846
/* Holonomy of a shape loop of the double spherical pendulum at μ = 0 (the discrete mechanical
 * connection of the midpoint L_d, J_d = 0): converges to the geometric phase −∮A(x)·dx with the
 * order of L_d (2); reference by the 4096-point trapezoid rule in the loop parameter (spectral
 * for a smooth periodic integrand). A loop that does not close is refused. */
static void dsp_loop(double t, double *x, double *dx) {
  x[0] = 0.5 + 0.2 * cos(t);
  x[1] = 0.4 + 0.1 * sin(2 * t);
  x[2] = 1.0 + 0.8 * sin(t);
  if (dx) {
    dx[0] = -0.2 * sin(t);
    dx[1] = 0.2 * cos(2 * t);
    dx[2] = 0.8 * cos(t);
  }
}

Test(routh, holonomy_of_a_shape_loop_at_mu_zero) {
  gm_routh_system sys;
  gm_routh_double_spherical_pendulum(&dspp, &sys);
  const double mu[1] = {0.0};
  double exact = 0.0;
  const int nref = 4096;
  for (int i = 0; i < nref; ++i) {
    double x[3], dx[3], a[3];
    dsp_loop(2 * ROUTH_PI * i / nref, x, dx);
    cr_assert_eq(gm_routh_connection(&sys, mu, x, NULL, a, NULL, NULL, NULL, NULL, NULL), GM_OK);
    exact -= (a[0] * dx[0] + a[1] * dx[1] + a[2] * dx[2]) * 2 * ROUTH_PI / nref;
  }
  gm_discrete_lagrangian ld;
  gm_routh_midpoint_lagrangian(&sys, &ld);
  gm_routh_discrete *d = NULL;
  cr_assert_eq(gm_routh_discrete_create(&ld, &sys, mu, NULL, &d, NULL), GM_OK);
  double err[3];
  for (int l = 0; l < 3; ++l) {
    const size_t n = (size_t)16 << l;
    double loop[(128 + 1) * 3], angle;
    for (size_t i = 0; i <= n; ++i) dsp_loop(2 * ROUTH_PI * (double)(i % n) / (double)n, loop + 3 * i, NULL);
    cr_assert_eq(gm_routh_holonomy(d, 0.1, n + 1, loop, &angle), GM_OK, "%s", gm_routh_discrete_errmsg(d));
    err[l] = fabs(angle - exact);
  }
  const double p1 = log2(err[0] / err[1]), p2 = log2(err[1] / err[2]);
  cr_log_info("holonomy: phase %.10f, errors %.3g %.3g %.3g, orders %.3f %.3f", exact, err[0],
              err[1], err[2], p1, p2);
  cr_expect(fabs(exact) > 0.05, "the loop encloses curvature: phase %.3g", exact);
  cr_expect(fabs(p2 - 2.0) < 0.2, "holonomy order %.3f", p2);
  double openloop[9] = {0.5, 0.4, 1.0, 0.6, 0.4, 1.0, 0.5, 0.4, 1.1}, a;
  cr_expect_eq(gm_routh_holonomy(d, 0.1, 3, openloop, &a), GM_EINVAL);
  cr_expect(strstr(gm_routh_discrete_errmsg(d), "does not close") != NULL, "%s", gm_routh_discrete_errmsg(d));
  gm_routh_discrete_free(d);
}

/* RSPRK and the classical SPRK with the tableaux of the registry's variational rows */
Test(routh, rsprk_with_registry_rows) {
  gm_routh_system sys;
  gm_routh_double_spherical_pendulum(&dspp, &sys);
  const double mu[1] = {0.8};
  const char *rows[] = {"vi-midpoint", "vi-trapezoidal", "vi-galerkin-gauss-2",
                        "vi-galerkin-lobatto-2", "vi-galerkin-gauss-3"};
  for (size_t m = 0; m < sizeof rows / sizeof rows[0]; ++m) {
    gm_tableau *t = NULL;
    cr_assert_eq(gm_method_tableau(gm_method_find(rows[m]), &t), GM_OK, "%s", rows[m]);
    gm_rsprk *a = NULL, *b = NULL;
    cr_assert_eq(gm_rsprk_create(&sys, t, GM_ROUTH_RSPRK, mu, &a, NULL), GM_OK);
    cr_assert_eq(gm_rsprk_create(&sys, t, GM_ROUTH_CLASSICAL, mu, &b, NULL), GM_OK);
    double x[3] = {0.6, 0.5, 1.0}, s[3] = {0.1, -0.2, 0.3}, xc[3], y[3];
    memcpy(xc, x, sizeof x);
    cr_assert_eq(gm_routh_lift_momentum(&sys, mu, x, s, y, NULL), GM_OK);
    const double e0 = gm_routh_energy(&sys, mu, x, s);
    double worst = 0, de = 0;
    for (int i = 0; i < 100; ++i) {
      cr_assert_eq(gm_rsprk_step(a, 0.02, x, s, NULL), GM_OK, "%s: %s", rows[m], gm_rsprk_errmsg(a));
      cr_assert_eq(gm_rsprk_step(b, 0.02, xc, y, NULL), GM_OK, "%s: %s", rows[m], gm_rsprk_errmsg(b));
      double ys[3];
      cr_assert_eq(gm_routh_lift_momentum(&sys, mu, x, s, ys, NULL), GM_OK);
      for (int j = 0; j < 3; ++j) worst = fmax(worst, fmax(fabs(x[j] - xc[j]), fabs(ys[j] - y[j])));
      de = fmax(de, fabs(gm_routh_energy(&sys, mu, x, s) - e0));
    }
    cr_log_info("%s: RSPRK vs classical %.3g, energy error %.3g", rows[m], worst, de);
    cr_expect(worst < 1e-12, "%s: RSPRK vs classical SPRK differ by %.3g", rows[m], worst);
    gm_rsprk_free(a);
    gm_rsprk_free(b);
    gm_tableau_free(t);
  }
}

/* ψ_μ where the group-regularity fails (locked inertia r̄² = 0 at the step's midpoint): an
 * error that names the shape points, not a wrong number */
Test(routh, psi_group_regularity_failure_is_reported) {
  gm_routh_system sys;
  gm_routh_j2_satellite(&j2p, &sys);
  gm_discrete_lagrangian ld;
  gm_routh_midpoint_lagrangian(&sys, &ld);
  const double mu[1] = {1.0}, x0[2] = {1.0, 0.5}, x1[2] = {-1.0, 0.5};
  gm_routh_discrete *d = NULL;
  cr_assert_eq(gm_routh_discrete_create(&ld, &sys, mu, NULL, &d, NULL), GM_OK);
  double psi = 0.3;
  cr_expect_eq(gm_routh_psi(d, 0.1, x0, x1, 1, &psi), GM_ENOCONV);
  cr_expect(strstr(gm_routh_discrete_errmsg(d), "x0 = (1") != NULL, "%s", gm_routh_discrete_errmsg(d));
  gm_routh_discrete_free(d);
}

/* The discrete mechanical connection (J_d = 0, seed 001 ch. 4; notes §1F): ψ_0(x0, x1) of the
 * midpoint L_d against the exact group increment of the μ = 0 flow from x0 to x1 = x(h)
 * (RSPRK with 3 Gauss points on 20 substeps): a local error O(h^{r+1}), r = 2 the order of L_d */
Test(routh, discrete_mechanical_connection_order) {
  gm_routh_system sys;
  gm_routh_double_spherical_pendulum(&dspp, &sys);
  const double mu[1] = {0.0};
  gm_tableau *t = galerkin(3);
  gm_rsprk *r = NULL;
  cr_assert_eq(gm_rsprk_create(&sys, t, GM_ROUTH_RSPRK, mu, &r, NULL), GM_OK);
  gm_discrete_lagrangian ld;
  gm_routh_midpoint_lagrangian(&sys, &ld);
  gm_routh_discrete *d = NULL;
  cr_assert_eq(gm_routh_discrete_create(&ld, &sys, mu, NULL, &d, NULL), GM_OK);
  const double x0[3] = {0.6, 0.5, 1.0}, xd[3] = {0.3, -0.2, 0.5};
  double kin[9], s0[3];
  cr_assert_eq(gm_routh_connection(&sys, mu, x0, NULL, NULL, kin, NULL, NULL, NULL, NULL), GM_OK);
  for (int i = 0; i < 3; ++i) s0[i] = kin[3 * i] * xd[0] + kin[3 * i + 1] * xd[1] + kin[3 * i + 2] * xd[2];
  double err[3];
  for (int l = 0; l < 3; ++l) {
    const double h = 0.1 / (double)(1 << l);
    double x[3], s[3], th = 0.0, psi;
    memcpy(x, x0, sizeof x);
    memcpy(s, s0, sizeof s);
    for (int k = 0; k < 20; ++k) cr_assert_eq(gm_rsprk_step(r, h / 20, x, s, &th), GM_OK);
    cr_assert_eq(gm_routh_psi(d, h, x0, x, 0, &psi), GM_OK, "%s", gm_routh_discrete_errmsg(d));
    err[l] = fabs(psi - th);
  }
  const double p1 = log2(err[0] / err[1]), p2 = log2(err[1] / err[2]);
  cr_log_info("discrete mechanical connection: errors %.3g %.3g %.3g, orders %.3f %.3f", err[0],
              err[1], err[2], p1, p2);
  cr_expect(fabs(p2 - 3.0) < 0.3, "local order %.3f, expected 3", p2);
  gm_routh_discrete_free(d);
  gm_rsprk_free(r);
  gm_tableau_free(t);
}

/* The discrete mechanical connection of the 2-point Gauss Galerkin L_d (order 4), as a
 * gm_discrete_connection callback: J_d(q0, q1) = 0 at μ = 0 holds exactly for the pairs of one
 * RSPRK step at μ = 0 (p_θ = μ is kept), so for given (x0, x1) Newton's method on the initial
 * reduced momentum s0 (difference Jacobian) finds the step that lands on x1, and its θ-increment
 * Δθ is the group element: θ1 = θ0 + Δθ, i.e. A(x0, x1) = −Δθ on SO(2) (g1 = g0 A⁻¹). Its
 * order against the exact flow is the order of L_d: local error O(h⁵). */
typedef struct {
  gm_routh_system *sys;
  gm_rsprk *r;
  double h;
} galerkin_conn;

static int galerkin_local(void *ctx, const double *x0, const double *x1, double *a) {
  galerkin_conn *g = ctx;
  const double mu[1] = {0.0};
  double kin[9], xm[3], s[3], dx[3];
  for (int i = 0; i < 3; ++i) xm[i] = 0.5 * (x0[i] + x1[i]), dx[i] = (x1[i] - x0[i]) / g->h;
  if (gm_routh_connection(g->sys, mu, xm, NULL, NULL, kin, NULL, NULL, NULL, NULL) != GM_OK) return -1;
  for (int i = 0; i < 3; ++i) s[i] = kin[3 * i] * dx[0] + kin[3 * i + 1] * dx[1] + kin[3 * i + 2] * dx[2];
  for (int it = 0; it < 30; ++it) {
    double x[3], sv[3], th = 0.0, f[3], jac[9];
    memcpy(x, x0, sizeof x), memcpy(sv, s, sizeof sv);
    if (gm_rsprk_step(g->r, g->h, x, sv, &th) != GM_OK) return -1;
    double res = 0.0;
    for (int i = 0; i < 3; ++i) f[i] = x[i] - x1[i], res = fmax(res, fabs(f[i]));
    if (res < 1e-15) {
      a[0] = -th;
      return 0;
    }
    for (int j = 0; j < 3; ++j) {
      const double d = 1e-7 * (1.0 + fabs(s[j]));
      double xp[3], sp[3], tp = 0.0;
      memcpy(xp, x0, sizeof xp), memcpy(sp, s, sizeof sp);
      sp[j] += d;
      if (gm_rsprk_step(g->r, g->h, xp, sp, &tp) != GM_OK) return -1;
      for (int i = 0; i < 3; ++i) jac[3 * i + j] = (xp[i] - x[i]) / d;
    }
    if (gm_dense_solve(3, jac, f) != GM_OK) return -1;
    double step = 0.0;
    for (int i = 0; i < 3; ++i) s[i] -= f[i], step = fmax(step, fabs(f[i]));
    if (step < 1e-16 * (1.0 + fabs(s[0]) + fabs(s[1]) + fabs(s[2]))) {
      memcpy(x, x0, sizeof x), memcpy(sv, s, sizeof sv), th = 0.0;
      if (gm_rsprk_step(g->r, g->h, x, sv, &th) != GM_OK) return -1;
      a[0] = -th;
      return 0;
    }
  }
  return -1;
}

Test(routh, galerkin_mechanical_connection_order) {
  gm_routh_system sys;
  gm_routh_double_spherical_pendulum(&dspp, &sys);
  const double mu[1] = {0.0};
  gm_tableau *t3 = galerkin(3), *t2 = galerkin(2);
  gm_rsprk *ref = NULL, *r2 = NULL;
  cr_assert_eq(gm_rsprk_create(&sys, t3, GM_ROUTH_RSPRK, mu, &ref, NULL), GM_OK);
  cr_assert_eq(gm_rsprk_create(&sys, t2, GM_ROUTH_RSPRK, mu, &r2, NULL), GM_OK);
  galerkin_conn g = {&sys, r2, 0.0};
  gm_discrete_connection c;
  memset(&c, 0, sizeof c);
  c.group = GM_GROUP_SO2;
  c.n = 3;
  c.rule = GM_DCONN_CALLBACK;
  c.local = galerkin_local;
  c.ctx = &g;
  const double x0[3] = {0.6, 0.5, 1.0}, xd[3] = {0.3, -0.2, 0.5};
  double kin[9], s0[3];
  cr_assert_eq(gm_routh_connection(&sys, mu, x0, NULL, NULL, kin, NULL, NULL, NULL, NULL), GM_OK);
  for (int i = 0; i < 3; ++i) s0[i] = kin[3 * i] * xd[0] + kin[3 * i + 1] * xd[1] + kin[3 * i + 2] * xd[2];
  double err[5];
  for (int l = 0; l < 5; ++l) {
    const double h = 0.2 / (double)(1 << l);
    double x[3], s[3], th = 0.0, a;
    memcpy(x, x0, sizeof x), memcpy(s, s0, sizeof s);
    for (int k = 0; k < 40; ++k) cr_assert_eq(gm_rsprk_step(ref, h / 40, x, s, &th), GM_OK);
    g.h = h;
    gm_error e;
    cr_assert_eq(gm_dconn_local(&c, x0, x, &a, &e), GM_OK, "%s", e.message);
    err[l] = fabs(-a - th);
  }
  const double p3 = log2(err[2] / err[3]), p4 = log2(err[3] / err[4]);
  cr_log_info("mechanical connection of the Gauss-2 Galerkin L_d (order 4): errors %.3g %.3g %.3g %.3g %.3g "
              "(h = 0.2 .. 0.0125), local orders %.3f %.3f %.3f %.3f", err[0], err[1], err[2], err[3], err[4],
              log2(err[0] / err[1]), log2(err[1] / err[2]), p3, p4);
  cr_expect(fabs(p4 - 5.0) < 0.4, "local order %.3f, expected 5", p4);
  gm_rsprk_free(ref);
  gm_rsprk_free(r2);
  gm_tableau_free(t3);
  gm_tableau_free(t2);
}

/* Fig. 2.8–2.9's contrast (seed 001 §2.10): on the double spherical pendulum away from the chart's
 * singularity (μ = 6, x0 = (0.7, 0.6, 1.0) at rest: min r_i = 0.34), the 4th-order RSPRK's energy
 * error is bounded and RK4 on the unreduced system at h/4 (four times the steps) drifts linearly.
 * Max |E − E0|/|E0| over the first and last tenth of t = 0..500, h = 0.05. */
static double dsp_full_energy(const gm_routh_system *sys, const double *y) {
  double m[16], v[4];
  cr_assert_eq(sys->metric(sys->ctx, y + 1, m), 0);
  memcpy(v, y + 4, sizeof v);
  cr_assert_eq(gm_dense_solve(4, m, v), GM_OK);
  double e = sys->potential(sys->ctx, y + 1);
  for (int i = 0; i < 4; ++i) e += 0.5 * y[4 + i] * v[i];
  return e;
}

Test(routh, dsp_energy_bounded_vs_rk4_drift, .timeout = 120) {
  gm_routh_dsp_params p = {1.0, 1.0, 1.0, 1.0, 9.81};
  gm_routh_system sys;
  gm_routh_double_spherical_pendulum(&p, &sys);
  const double mu[1] = {6.0}, h = 0.05, t_end = 500.0;
  gm_tableau *t = NULL;
  cr_assert_eq(gm_method_tableau(gm_method_find("vi-galerkin-gauss-2"), &t), GM_OK);
  gm_rsprk *ra = NULL;
  cr_assert_eq(gm_rsprk_create(&sys, t, GM_ROUTH_RSPRK, mu, &ra, NULL), GM_OK);
  double x[3] = {0.7, 0.6, 1.0}, s[3] = {0, 0, 0}, y[3], full[8] = {0};
  cr_assert_eq(gm_routh_lift_momentum(&sys, mu, x, s, y, NULL), GM_OK);
  memcpy(full + 1, x, sizeof x);
  full[4] = mu[0];
  memcpy(full + 5, y, sizeof y);
  const double e0 = gm_routh_energy(&sys, mu, x, s), e0f = dsp_full_energy(&sys, full);
  cr_expect(fabs(e0 - e0f) < 1e-13 * fabs(e0), "reduced and full energies agree at t = 0");
  const size_t n = (size_t)llround(t_end / h);
  double win[2][10] = {{0}}, r_min = 1.0;
  for (size_t i = 1; i <= n; ++i) {
    cr_assert_eq(gm_rsprk_step(ra, h, x, s, NULL), GM_OK, "%s", gm_rsprk_errmsg(ra));
    for (int q = 0; q < 4; ++q) {
      double k[4][8], w[8];
      const double hh = h / 4, c[4] = {0, 0.5, 0.5, 1};
      for (int st = 0; st < 4; ++st) {
        for (int j = 0; j < 8; ++j) w[j] = full[j] + (st ? c[st] * hh * k[st - 1][j] : 0.0);
        cr_assert_eq(gm_routh_full_rhs(&sys, w, k[st], NULL), GM_OK);
      }
      for (int j = 0; j < 8; ++j) full[j] += hh / 6 * (k[0][j] + 2 * k[1][j] + 2 * k[2][j] + k[3][j]);
    }
    const size_t wi = (i - 1) * 10 / n;
    win[0][wi] = fmax(win[0][wi], fabs(gm_routh_energy(&sys, mu, x, s) - e0) / fabs(e0));
    win[1][wi] = fmax(win[1][wi], fabs(dsp_full_energy(&sys, full) - e0f) / fabs(e0f));
    r_min = fmin(r_min, fmin(x[0], x[1]));
  }
  cr_log_info("DSP mu = 6, h = 0.05, t = 0..500 (min r_i %.3f): max |dE|/|E0| RSPRK first/last tenth "
              "%.3g / %.3g, RK4 at h/4 %.3g / %.3g", r_min, win[0][0], win[0][9], win[1][0], win[1][9]);
  cr_expect_gt(r_min, 0.2, "the run stays away from the chart's singularity");
  cr_expect_lt(win[0][9], 1.5 * win[0][0], "RSPRK energy error bounded: %.3g then %.3g", win[0][0], win[0][9]);
  cr_expect_gt(win[1][9], 5.0 * win[1][0], "RK4 energy error drifts: %.3g then %.3g", win[1][0], win[1][9]);
  cr_expect_gt(win[1][9], 2.0 * win[0][9], "RK4 at h/4 ends above RSPRK: %.3g vs %.3g", win[1][9], win[0][9]);
  gm_rsprk_free(ra);
  gm_tableau_free(t);
}
