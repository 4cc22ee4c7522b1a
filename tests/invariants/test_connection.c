/* Discrete connections on Q = G × S, G = SO(2), SO(3) (include/geomint/reduction.h; seed 001
 * ch. 4): the local form's defining properties (A_d(q, gq) = g, equivariance), the
 * horizontal/vertical decomposition, the horizontal lift with the product on the right (notes §4),
 * the extended composition (associative, and consecutive horizontal pairs compose to the lift),
 * holonomy, the order test sup ‖A_d^E A_d⁻¹‖ ≤ c h^{k+1} for three rules of different order
 * (fitted exponents), and the discrete mechanical connection (J_d = 0 by Newton) with its order. */
#include "test_util.h"

#define PI 3.14159265358979323846

/* A nonabelian test connection on SO(3) × R²: A(x) = [a1(x) a2(x)] (3×2, row-major). */
static int conn_so3(void *ctx, const double *x, double *a) {
  (void)ctx;
  const double a1[3] = {1.0 + x[1] * x[1], 0.5 * sin(x[0]), 0.3 * x[1]};
  const double a2[3] = {0.2 * x[0], cos(x[1]), 1.0 + 0.4 * x[0] * x[1]};
  for (int r = 0; r < 3; ++r) a[2 * r] = a1[r], a[2 * r + 1] = a2[r];
  return 0;
}
/* abelian: A(x) = (x2 cos x1, 1 + x1²) on SO(2) × R² (curvature ∂1A2 − ∂2A1 ≠ 0) */
static int conn_so2(void *ctx, const double *x, double *a) {
  (void)ctx;
  a[0] = x[1] * cos(x[0]);
  a[1] = 1.0 + x[0] * x[0];
  return 0;
}

static gm_discrete_connection make(gm_group_kind g, gm_dconn_rule rule) {
  gm_discrete_connection c;
  memset(&c, 0, sizeof c);
  c.group = g;
  c.n = 2;
  c.rule = rule;
  c.connection = g == GM_GROUP_SO3 ? conn_so3 : conn_so2;
  c.substeps = 200;
  return c;
}

static void random_rot(double *r, double s) {
  const double w[3] = {0.3 * s, -0.7 * s, 0.5 + 0.2 * s};
  gm_so3_exp(w, r);
}

static double dist(const double *a, const double *b) { return gm_group_distance(GM_GROUP_SO3, a, b); }

Test(connection, local_form_properties_and_decomposition) {
  gm_discrete_connection c = make(GM_GROUP_SO3, GM_DCONN_MIDPOINT);
  const double x0[2] = {0.3, -0.2}, x1[2] = {0.5, 0.1};
  double g0[9], g1[9], g[9], h[9], ad[9], tmp[9], want[9];
  random_rot(g0, 1.0);
  random_rot(g1, -2.0);
  random_rot(g, 0.4);
  random_rot(h, 3.0);
  /* A_d(q, g q) = g */
  gm_group_mul(GM_GROUP_SO3, g, g0, tmp);
  cr_assert_eq(gm_dconn_eval(&c, x0, g0, x0, tmp, ad, NULL), GM_OK);
  cr_expect_lt(dist(ad, g), 1e-14, "A_d(q, gq) = g: %.3g", dist(ad, g));
  /* equivariance A_d(h q0, h q1) = h A_d(q0, q1) h⁻¹ */
  double hg0[9], hg1[9], ad2[9], hi[9];
  gm_group_mul(GM_GROUP_SO3, h, g0, hg0);
  gm_group_mul(GM_GROUP_SO3, h, g1, hg1);
  cr_assert_eq(gm_dconn_eval(&c, x0, g0, x1, g1, ad, NULL), GM_OK);
  cr_assert_eq(gm_dconn_eval(&c, x0, hg0, x1, hg1, ad2, NULL), GM_OK);
  gm_group_inv(GM_GROUP_SO3, h, hi);
  gm_group_mul(GM_GROUP_SO3, h, ad, want);
  gm_group_mul(GM_GROUP_SO3, want, hi, want);
  cr_expect_lt(dist(ad2, want), 1e-14, "equivariance %.3g", dist(ad2, want));
  /* hor has A_d = e, ver has A_d = A_d(q0, q1) */
  double ghor[9], gver[9], e[9];
  gm_so3_exp((const double[3]){0, 0, 0}, e);
  cr_assert_eq(gm_dconn_decompose(&c, x0, g0, x1, g1, ghor, gver, NULL), GM_OK);
  cr_assert_eq(gm_dconn_eval(&c, x0, g0, x1, ghor, tmp, NULL), GM_OK);
  cr_expect_lt(dist(tmp, e), 1e-14, "A_d(hor) = e: %.3g", dist(tmp, e));
  cr_assert_eq(gm_dconn_eval(&c, x0, g0, x0, gver, tmp, NULL), GM_OK);
  cr_expect_lt(dist(tmp, ad), 1e-14, "A_d(ver) = A_d: %.3g", dist(tmp, ad));
  /* the pure group case (n = 0): A_d(g0, g1) = g1 g0⁻¹ */
  gm_discrete_connection pure;
  memset(&pure, 0, sizeof pure);
  pure.group = GM_GROUP_SO3;
  cr_assert_eq(gm_dconn_eval(&pure, NULL, g0, NULL, g1, ad, NULL), GM_OK);
  gm_group_inv(GM_GROUP_SO3, g0, tmp);
  gm_group_mul(GM_GROUP_SO3, g1, tmp, want);
  cr_expect_lt(dist(ad, want), 1e-15, "pure group case %.3g", dist(ad, want));
  /* continuous limit: log A_d(q0, q(t))/t → ġg⁻¹ + Ad_g A(x)ẋ, error O(t) */
  const double xd[2] = {0.7, -0.4}, wd[3] = {0.2, 0.1, -0.3};
  double prev = 0.0;
  for (int l = 0; l < 3; ++l) {
    const double t = 1e-2 / (1 << (2 * l));
    double xt[2] = {x0[0] + t * xd[0], x0[1] + t * xd[1]}, gt[9], w[3], a[6], ax[3], gax[3];
    gm_so3_exp((const double[3]){t * wd[0], t * wd[1], t * wd[2]}, tmp);
    gm_group_mul(GM_GROUP_SO3, tmp, g0, gt);
    cr_assert_eq(gm_dconn_eval(&c, x0, g0, xt, gt, ad, NULL), GM_OK);
    gm_so3_log(ad, w);
    conn_so3(NULL, x0, a);
    for (int r = 0; r < 3; ++r) ax[r] = a[2 * r] * xd[0] + a[2 * r + 1] * xd[1];
    gm_mat3_vec(g0, ax, gax); /* Ad_g on so(3) ≅ R³ is R */
    double err = 0.0;
    for (int r = 0; r < 3; ++r) err = fmax(err, fabs(w[r] / t - (wd[r] + gax[r])));
    cr_log_info("continuous limit, t = %.3g: %.3g", t, err);
    if (l > 0) cr_expect(err < 0.3 * prev, "d/dt A_d -> connection: %.3g then %.3g", prev, err);
    prev = err;
  }
}

/* path on R²: a closed curve x(s) = (0.2 + 0.3 cos s, −0.1 + 0.2 sin 2s + 0.1 sin s) */
static void loop_points(size_t N, double *pts) {
  for (size_t i = 0; i <= N; ++i) {
    const double s = 2.0 * PI * (double)(i % N) / (double)N;
    pts[2 * i] = 0.2 + 0.3 * cos(s);
    pts[2 * i + 1] = -0.1 + 0.2 * sin(2 * s) + 0.1 * sin(s);
  }
}

Test(connection, horizontal_lift_composition_and_holonomy) {
  gm_discrete_connection c = make(GM_GROUP_SO3, GM_DCONN_MAGNUS4);
  enum { N = 24 };
  double pts[2 * (N + 1)], g[9 * (N + 1)], g0[9], tmp[9], e[9];
  loop_points(N, pts);
  gm_so3_exp((const double[3]){0, 0, 0}, e);
  random_rot(g0, 0.8);
  cr_assert_eq(gm_dconn_lift(&c, N + 1, pts, g0, g, NULL), GM_OK);
  /* every segment of the lift is horizontal (the product on the right; from g0 ≠ e the printed
   * order (A_l ⋯ A_0)⁻¹ h0 of Remark 4.2 fails this) */
  double worst = 0.0, wrong = 0.0, prod[9];
  memcpy(prod, e, sizeof prod);
  for (size_t l = 0; l < N; ++l) {
    cr_assert_eq(gm_dconn_eval(&c, pts + 2 * l, g + 9 * l, pts + 2 * l + 2, g + 9 * l + 9, tmp, NULL), GM_OK);
    worst = fmax(worst, dist(tmp, e));
    double a[9];
    cr_assert_eq(gm_dconn_local(&c, pts + 2 * l, pts + 2 * l + 2, a, NULL), GM_OK);
    gm_group_mul(GM_GROUP_SO3, a, prod, prod);
  }
  double pinv[9], left[9], right[9];
  gm_group_inv(GM_GROUP_SO3, prod, pinv);
  gm_group_mul(GM_GROUP_SO3, pinv, g0, left);
  gm_group_mul(GM_GROUP_SO3, g0, pinv, right);
  wrong = dist(left, g + 9 * N);
  cr_log_info("lift: max |A_d| on segments %.3g; end vs g0 (A..A)^-1 %.3g, vs (A..A)^-1 g0 %.3g",
              worst, dist(right, g + 9 * N), wrong);
  cr_expect_lt(worst, 1e-13);
  cr_expect_lt(dist(right, g + 9 * N), 1e-13);
  cr_expect_gt(wrong, 1e-3, "the two orders differ for this nonabelian loop");
  /* holonomy from e, and the lift from g0 ends at g0 hol (the lift is G-equivariant) */
  double hol[9];
  cr_assert_eq(gm_dconn_holonomy(&c, N + 1, pts, hol, NULL), GM_OK);
  gm_group_mul(GM_GROUP_SO3, g0, hol, tmp);
  cr_expect_lt(dist(tmp, g + 9 * N), 1e-13);
  double hw[3];
  gm_so3_log(hol, hw);
  cr_log_info("holonomy angle %.6f", gm_vec3_norm(hw));
  cr_expect_gt(gm_vec3_norm(hw), 1e-3, "a curved connection has holonomy");
  /* consecutive horizontal pairs compose to (q0, q_N); composition is associative */
  double acc[9];
  memcpy(acc, g + 9, sizeof acc);
  for (size_t l = 1; l < N; ++l) {
    cr_assert_eq(gm_dconn_compose(&c, pts, g, pts + 2 * l, acc, pts + 2 * l, g + 9 * l,
                                  pts + 2 * l + 2, g + 9 * l + 9, acc, NULL), GM_OK);
  }
  cr_expect_lt(dist(acc, g + 9 * N), 1e-13, "composed lift %.3g", dist(acc, g + 9 * N));
  double ga[9], gb[9], gc[9], gd[9], ab[9], abc1[9], bc[9], abc2[9];
  random_rot(ga, 0.1);
  random_rot(gb, 0.9);
  random_rot(gc, -1.3);
  random_rot(gd, 2.2);
  const double *xa = pts, *xb = pts + 6, *xc = pts + 12, *xd = pts + 20;
  /* (q, p)·(p', r) with p' ≠ p in the same fibre, then ·(r', s) */
  cr_assert_eq(gm_dconn_compose(&c, xa, ga, xb, gb, xb, gc, xc, gd, ab, NULL), GM_OK);
  cr_assert_eq(gm_dconn_compose(&c, xa, ga, xc, ab, xc, gb, xd, gc, abc1, NULL), GM_OK);
  cr_assert_eq(gm_dconn_compose(&c, xb, gc, xc, gd, xc, gb, xd, gc, bc, NULL), GM_OK);
  cr_assert_eq(gm_dconn_compose(&c, xa, ga, xb, gb, xb, gc, xd, bc, abc2, NULL), GM_OK);
  cr_expect_lt(dist(abc1, abc2), 1e-14, "associativity %.3g", dist(abc1, abc2));
  /* bad input */
  gm_error err;
  double open[2 * (N + 1)];
  memcpy(open, pts, sizeof open);
  open[2 * N] += 1e-6;
  cr_expect_eq(gm_dconn_holonomy(&c, N + 1, open, hol, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "does not close") != NULL, "%s", err.message);
  cr_expect_eq(gm_dconn_compose(&c, xa, ga, xb, gb, xc, gc, xd, gd, ab, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "do not compose") != NULL, "%s", err.message);
  gm_discrete_connection bad = c;
  bad.connection = NULL;
  cr_expect_eq(gm_dconn_holonomy(&bad, N + 1, pts, hol, &err), GM_EINVAL);
}

/* sup over directions v of ‖A^E(x, x + hv) A(x, x + hv)⁻¹‖, fitted exponent over h = 0.2..0.025 */
static double fitted_order(gm_group_kind grp, gm_dconn_rule rule, double *last) {
  gm_discrete_connection ex = make(grp, GM_DCONN_TRANSPORT), c = make(grp, rule);
  const double x[2] = {0.3, -0.2};
  double lh[4], ld[4];
  for (int l = 0; l < 4; ++l) {
    const double h = 0.2 / (1 << l);
    double sup = 0.0;
    for (int k = 0; k < 8; ++k) {
      const double a = PI * k / 8.0, x1[2] = {x[0] + h * cos(a), x[1] + h * sin(a)};
      double d;
      cr_assert_eq(gm_dconn_defect(&ex, &c, x, x1, &d, NULL), GM_OK);
      sup = fmax(sup, d);
    }
    lh[l] = log(h);
    ld[l] = log(sup);
    *last = sup;
  }
  double mh = 0, md = 0, sxy = 0, sxx = 0;
  for (int l = 0; l < 4; ++l) mh += lh[l] / 4, md += ld[l] / 4;
  for (int l = 0; l < 4; ++l) sxy += (lh[l] - mh) * (ld[l] - md), sxx += (lh[l] - mh) * (lh[l] - mh);
  return sxy / sxx;
}

Test(connection, order_test_against_the_exact_connection) {
  static const struct {
    gm_dconn_rule rule;
    const char *name;
    double order; /* k + 1 */
  } rules[] = {{GM_DCONN_LEFT, "left", 2}, {GM_DCONN_MIDPOINT, "midpoint", 3}, {GM_DCONN_MAGNUS4, "magnus4", 5}};
  for (int g = 0; g < 2; ++g) {
    const gm_group_kind grp = g ? GM_GROUP_SO3 : GM_GROUP_SO2;
    for (size_t i = 0; i < 3; ++i) {
      double last;
      const double p = fitted_order(grp, rules[i].rule, &last);
      cr_log_info("%s %s: fitted exponent %.3f (k + 1 = %.0f), defect at h = 0.025 %.3g",
                  g ? "SO(3)" : "SO(2)", rules[i].name, p, rules[i].order, last);
      cr_expect(fabs(p - rules[i].order) < 0.3, "%s %s: exponent %.3f, expected %.0f",
                g ? "SO(3)" : "SO(2)", rules[i].name, p, rules[i].order);
    }
  }
}

/* ---- the discrete mechanical connection ---------------------------------------------------- */

/* L = ½(Ω + A(x)ẋ)ᵀ𝕀(x)(Ω + A(x)ẋ) + ½|ẋ|² on SO(3) × R², Ω = g⁻¹ġ: J = 0 iff Ω = −A(x)ẋ, so
 * the mechanical connection is conn_so3. L_d by the trapezoidal rule (order 2) with
 * Ω = w/h, f = g0⁻¹g1 = exp(w); the body momentum dexp_w^{−T} ∂L_d/∂w (h = 1, the scale
 * drops out) vanishes iff J_d does. 𝕀 = diag(1 + x1², 2 + 0.5 sin x2, 1 + x1). */
static void inertia(const double *x, double *in) {
  in[0] = 1.0 + x[0] * x[0];
  in[1] = 2.0 + 0.5 * sin(x[1]);
  in[2] = 1.0 + x[0];
}

static int momentum_trapezoid(void *ctx, const double *x0, const double *x1, const double *w, double *j) {
  (void)ctx;
  double dl[3] = {0, 0, 0};
  const double dx[2] = {x1[0] - x0[0], x1[1] - x0[1]};
  for (int e = 0; e < 2; ++e) {
    const double *x = e ? x1 : x0;
    double a[6], in[3];
    conn_so3(NULL, x, a);
    inertia(x, in);
    for (int r = 0; r < 3; ++r) dl[r] += 0.5 * in[r] * (w[r] + a[2 * r] * dx[0] + a[2 * r + 1] * dx[1]);
  }
  double d[9];
  gm_so3_dexp_inv(w, d);
  gm_mat3_tvec(d, dl, j);
  return 0;
}

Test(connection, discrete_mechanical_connection) {
  gm_discrete_connection mech;
  memset(&mech, 0, sizeof mech);
  mech.group = GM_GROUP_SO3;
  mech.n = 2;
  mech.rule = GM_DCONN_MECHANICAL;
  mech.momentum = momentum_trapezoid;
  /* closed form of J_d = 0: w = −(𝕀0 + 𝕀1)⁻¹(𝕀0 A0 + 𝕀1 A1)Δx, A(x0, x1) = exp(−w) */
  const double x0[2] = {0.3, -0.2}, x1[2] = {0.45, -0.05};
  double a[9], want[9], w[3], a0[6], a1[6], i0[3], i1[3];
  cr_assert_eq(gm_dconn_local(&mech, x0, x1, a, NULL), GM_OK);
  conn_so3(NULL, x0, a0);
  conn_so3(NULL, x1, a1);
  inertia(x0, i0);
  inertia(x1, i1);
  for (int r = 0; r < 3; ++r)
    w[r] = (i0[r] * (a0[2 * r] * 0.15 + a0[2 * r + 1] * 0.15) + i1[r] * (a1[2 * r] * 0.15 + a1[2 * r + 1] * 0.15)) /
           (i0[r] + i1[r]);
  gm_so3_exp(w, want);
  cr_expect_lt(dist(a, want), 1e-13, "Newton vs closed form %.3g", dist(a, want));
  /* its order against the exact connection of the continuous mechanical connection */
  gm_discrete_connection ex = make(GM_GROUP_SO3, GM_DCONN_TRANSPORT);
  double lh[4], ld[4], last = 0;
  for (int l = 0; l < 4; ++l) {
    const double h = 0.2 / (1 << l);
    double sup = 0.0;
    for (int k = 0; k < 8; ++k) {
      const double t = PI * k / 8.0, y1[2] = {x0[0] + h * cos(t), x0[1] + h * sin(t)};
      double d;
      cr_assert_eq(gm_dconn_defect(&ex, &mech, x0, y1, &d, NULL), GM_OK);
      sup = fmax(sup, d);
    }
    lh[l] = log(h), ld[l] = log(sup), last = sup;
  }
  double mh = 0, md = 0, sxy = 0, sxx = 0;
  for (int l = 0; l < 4; ++l) mh += lh[l] / 4, md += ld[l] / 4;
  for (int l = 0; l < 4; ++l) sxy += (lh[l] - mh) * (ld[l] - md), sxx += (lh[l] - mh) * (lh[l] - mh);
  cr_log_info("mechanical (trapezoidal L_d, order 2): fitted exponent %.3f, defect at h = 0.025 %.3g",
              sxy / sxx, last);
  cr_expect(fabs(sxy / sxx - 3.0) < 0.3, "mechanical connection exponent %.3f, expected 3", sxy / sxx);
  /* group-regularity fails where 𝕀0 + 𝕀1 is singular and 𝕀0A0Δx + 𝕀1A1Δx is not (third
   * component, x1 = −1.5 and −0.5): J_d = 0 has no solution, Newton says where */
  gm_error err;
  const double b0[2] = {-1.5, 0.2}, b1[2] = {-0.5, 0.3};
  cr_expect_eq(gm_dconn_local(&mech, b0, b1, a, &err), GM_ENOCONV);
  cr_log_info("%s", err.message);
  cr_expect(strstr(err.message, "x0 = (-1.5, 0.2)") != NULL && strstr(err.message, "x1 = (-0.5, 0.3)") != NULL,
            "%s", err.message);
}
