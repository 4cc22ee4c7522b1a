/* SO(3), SE(3) and quaternions against references in long double (64-bit mantissa: 2^11
 * times finer than double) and against identities. Errors are in units of ε = 2^-52 relative
 * to the size of the result (the entries of a rotation are ≤ 1); the worst case over all
 * samples is printed (with --verbose) and asserted. The samples include angles within 1e-8 of 0
 * and of π. */
#include <float.h>

#include "test_util.h"

#define EPS DBL_EPSILON
#define GM_PI_TEST 3.14159265358979323846

/* Angles that stress each branch: tiny, the series/closed-form switch points, near π. */
static const double angles[] = {0.0,  1e-300, 1e-12, 1e-8, 3e-5,  1e-4, 0.1,
                                0.99, 1.0,    1.7,   2.0,  2.094, 2.1,  2.5,
                                3.0,  GM_PI_TEST - 1e-4, GM_PI_TEST - 1e-6,
                                GM_PI_TEST - 1e-8, GM_PI_TEST - 1e-12};
#define N_ANGLES (sizeof angles / sizeof angles[0])
static const double axes[][3] = {{1, 0, 0},        {0, 0, 1}, {0.6, -0.8, 0}, {1, 2, 3},
                                 {-0.3, 0.1, 0.95}, {1, 1, -1}};
#define N_AXES (sizeof axes / sizeof axes[0])

static void sample(size_t a, size_t k, double w[3]) {
  const double *n = axes[k];
  double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int i = 0; i < 3; ++i) w[i] = angles[a] * (n[i] / len);
}

/* long double Rodrigues: R = I + sin θ/θ ŵ + 2 sin²(θ/2)/θ² ŵ² */
static void exp_ld2(const double w[3], long double r[9], long double m1[9]) {
  long double x = w[0], y = w[1], z = w[2];
  long double t = sqrtl(x * x + y * y + z * z);
  long double a = t == 0 ? 1.0L : sinl(t) / t, b = t == 0 ? 0.5L : 2 * powl(sinl(t / 2) / t, 2);
  long double W[9] = {0, -z, y, z, 0, -x, -y, x, 0}, W2[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      W2[3 * i + j] = 0;
      for (int k = 0; k < 3; ++k) W2[3 * i + j] += W[3 * i + k] * W[3 * k + j];
    }
  for (int k = 0; k < 9; ++k) {
    m1[k] = a * W[k] + b * W2[k];
    r[k] = (k % 4 == 0 ? 1.0L : 0.0L) + m1[k];
  }
}

static void exp_ld(const double w[3], long double r[9]) {
  long double m1[9];
  exp_ld2(w, r, m1);
}

/* Σ_k M^k/(k+1)! (n×n, long double), 60 terms: converges for the norms used here */
static void phi1_ld(size_t n, const long double *m, long double *out) {
  long double term[36], next[36];
  for (size_t i = 0; i < n * n; ++i) term[i] = out[i] = (i % (n + 1) == 0) ? 1.0L : 0.0L;
  for (int k = 1; k < 60; ++k) {
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < n; ++j) {
        long double s = 0;
        for (size_t l = 0; l < n; ++l) s += term[i * n + l] * m[l * n + j];
        next[i * n + j] = s / (k + 1);
      }
    for (size_t i = 0; i < n * n; ++i) {
      term[i] = next[i];
      out[i] += term[i];
    }
  }
}

static double err_ulps(size_t n, const double *x, const long double *ref, double scale) {
  double e = 0.0;
  for (size_t i = 0; i < n; ++i) e = fmax(e, (double)fabsl((long double)x[i] - ref[i]));
  return e / (EPS * scale);
}

static double worst_exp, worst_log, worst_dexp, worst_dexp_inv, worst_cayley, worst_quat;

Test(lie, so3_exp_log_against_long_double) {
  for (size_t a = 0; a < N_ANGLES; ++a)
    for (size_t k = 0; k < N_AXES; ++k) {
      double w[3], r[9], e[9], back[3];
      long double ref[9], refm1[9];
      sample(a, k, w);
      gm_so3_exp(w, r);
      exp_ld2(w, ref, refm1);
      worst_exp = fmax(worst_exp, err_ulps(9, r, ref, 1.0));
      /* exp(w) − I relative to |w| (its size) */
      gm_so3_expm1(w, e);
      if (angles[a] > 0) worst_exp = fmax(worst_exp, err_ulps(9, e, refm1, angles[a]));
      /* log of the correctly rounded rotation: the rounding of R moves the angle by ~ε, so the
       * error is measured relative to max(|w|, 1) near π and to |w| elsewhere */
      double rr[9];
      for (int i = 0; i < 9; ++i) rr[i] = (double)ref[i];
      gm_so3_log(rr, back);
      long double wl[3] = {w[0], w[1], w[2]};
      if (angles[a] > 0)
        worst_log = fmax(worst_log, err_ulps(3, back, wl, angles[a]));
      else
        cr_expect(back[0] == 0 && back[1] == 0 && back[2] == 0);
    }
  cr_log_info("so3 exp (and exp - I relative to |w|): worst %.2f eps", worst_exp);
  cr_log_info("so3 log(exp w) relative to |w|: worst %.2f eps", worst_log);
  cr_expect_leq(worst_exp, 4.0, "exp: %.2f eps", worst_exp);
  cr_expect_leq(worst_log, 4.0, "log: %.2f eps", worst_log);
}

Test(lie, so3_log_half_turn_both_signs) {
  double w[3] = {0.0, GM_PI_TEST, 0.0}, r[9], back[3];
  gm_so3_exp(w, r);
  gm_so3_log(r, back);
  cr_expect(fabs(fabs(back[1]) - GM_PI_TEST) <= 4 * EPS && fabs(back[0]) <= 4 * EPS &&
                fabs(back[2]) <= 4 * EPS,
            "log of a half turn: (%g, %g, %g)", back[0], back[1], back[2]);
}

Test(lie, so3_dexp_against_series) {
  for (size_t a = 0; a < N_ANGLES; ++a)
    for (size_t k = 0; k < N_AXES; ++k) {
      double w[3], d[9], di[9], prod[9];
      long double m[9], ref[9];
      sample(a, k, w);
      m[0] = m[4] = m[8] = 0;
      m[1] = -w[2];
      m[2] = w[1];
      m[3] = w[2];
      m[5] = -w[0];
      m[6] = -w[1];
      m[7] = w[0];
      phi1_ld(3, m, ref);
      gm_so3_dexp(w, d);
      worst_dexp = fmax(worst_dexp, err_ulps(9, d, ref, 1.0));
      /* dexp⁻¹ dexp = I */
      gm_so3_dexp_inv(w, di);
      gm_mat3_mul(di, d, prod);
      long double eye[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
      double scale = 1.0;
      for (int i = 0; i < 9; ++i) scale = fmax(scale, fabs(di[i]));
      worst_dexp_inv = fmax(worst_dexp_inv, err_ulps(9, prod, eye, scale));
    }
  cr_log_info("so3 dexp vs series: worst %.2f eps; dexp_inv dexp - I: %.2f eps", worst_dexp,
              worst_dexp_inv);
  cr_expect_leq(worst_dexp, 4.0);
  cr_expect_leq(worst_dexp_inv, 4.0);
}

Test(lie, so3_dexp_is_the_derivative_of_exp) {
  /* d/dt exp(w + t v)|0 exp(w)ᵀ = hat(dexp_w v), by a 4th-order central difference */
  const double w[3] = {0.7, -1.1, 0.4}, v[3] = {0.3, 0.2, -0.5}, h = 1e-3;
  double d[9], dv[3], rp[9], rm[9], rp2[9], rm2[9], r[9], der[9], x[9], got[3];
  double wp[3], wm[3], wp2[3], wm2[3];
  for (int i = 0; i < 3; ++i) {
    wp[i] = w[i] + h * v[i];
    wm[i] = w[i] - h * v[i];
    wp2[i] = w[i] + 2 * h * v[i];
    wm2[i] = w[i] - 2 * h * v[i];
  }
  gm_so3_exp(wp, rp);
  gm_so3_exp(wm, rm);
  gm_so3_exp(wp2, rp2);
  gm_so3_exp(wm2, rm2);
  gm_so3_exp(w, r);
  for (int i = 0; i < 9; ++i) der[i] = (-rp2[i] + 8 * rp[i] - 8 * rm[i] + rm2[i]) / (12 * h);
  gm_mat3_mul_nt(der, r, x);
  gm_so3_vee(x, got);
  gm_so3_dexp(w, d);
  gm_mat3_vec(d, v, dv);
  for (int i = 0; i < 3; ++i)
    cr_expect(fabs(got[i] - dv[i]) < 1e-11, "%d: %g vs %g", i, got[i], dv[i]);
}

Test(lie, so3_cayley) {
  for (size_t a = 0; a < N_ANGLES; ++a)
    for (size_t k = 0; k < N_AXES; ++k) {
      double w[3], r[9], back[3];
      sample(a, k, w);
      for (int i = 0; i < 3; ++i) w[i] *= 1.7; /* the Cayley parameter is unbounded */
      gm_so3_cayley(w, r);
      cr_expect_leq(gm_so3_orthogonality_defect(r), 4 * EPS);
      /* reference (I − ŵ/2)⁻¹(I + ŵ/2) = I + 4/(4+|w|²)(ŵ + ŵ²/2) in long double */
      long double x = w[0], y = w[1], z = w[2], t2 = x * x + y * y + z * z, c = 4 / (4 + t2);
      long double W[9] = {0, -z, y, z, 0, -x, -y, x, 0}, ref[9];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          long double s = 0;
          for (int l = 0; l < 3; ++l) s += W[3 * i + l] * W[3 * l + j];
          ref[3 * i + j] = (i == j) + c * (W[3 * i + j] + s / 2);
        }
      worst_cayley = fmax(worst_cayley, err_ulps(9, r, ref, 1.0));
      cr_assert_eq(gm_so3_cayley_inverse(r, back), GM_OK);
      long double wl[3] = {w[0], w[1], w[2]};
      /* relative to |w| times the condition number 1 + |w|²/4 of cay⁻¹ at the rounded R */
      double cw = 1.7 * angles[a];
      if (angles[a] > 0)
        worst_cayley = fmax(worst_cayley, err_ulps(3, back, wl, cw * (1.0 + 0.25 * cw * cw)));
    }
  double half_turn[9] = {1, 0, 0, 0, -1, 0, 0, 0, -1}, w[3];
  cr_expect_eq(gm_so3_cayley_inverse(half_turn, w), GM_EDOMAIN);
  cr_log_info("cayley and its inverse: worst %.2f eps", worst_cayley);
  cr_expect_leq(worst_cayley, 4.0);
}

/* 4×4 matrix exponential of hat(ξ) by its Taylor series in long double */
static void se3_exp_ld(const double xi[6], long double r[9], long double t[3]) {
  long double m[16] = {0, -xi[2], xi[1], xi[3], xi[2], 0, -xi[0], xi[4],
                       -xi[1], xi[0], 0, xi[5], 0, 0, 0, 0};
  long double term[16], next[16], sum[16];
  for (int i = 0; i < 16; ++i) term[i] = sum[i] = (i % 5 == 0);
  for (int k = 1; k < 60; ++k) {
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        long double s = 0;
        for (int l = 0; l < 4; ++l) s += term[4 * i + l] * m[4 * l + j];
        next[4 * i + j] = s / k;
      }
    for (int i = 0; i < 16; ++i) sum[i] += (term[i] = next[i]);
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[3 * i + j] = sum[4 * i + j];
    t[i] = sum[4 * i + 3];
  }
}

Test(lie, se3_exp_log_dexp) {
  double worst_se3 = 0.0, worst_se3_dexp = 0.0;
  const double v[3] = {0.4, -1.3, 2.2};
  for (size_t a = 0; a < N_ANGLES; ++a)
    for (size_t k = 0; k < N_AXES; ++k) {
      double xi[6], r[9], t[3], back[6], d[36], di[36];
      sample(a, k, xi);
      for (int i = 0; i < 3; ++i) xi[3 + i] = v[i];
      gm_se3_exp(xi, r, t);
      long double rl[9], tl[3];
      se3_exp_ld(xi, rl, tl);
      worst_se3 = fmax(worst_se3, err_ulps(9, r, rl, 1.0));
      worst_se3 = fmax(worst_se3, err_ulps(3, t, tl, 2.6));
      gm_se3_log(r, t, back);
      long double xl[6];
      for (int i = 0; i < 6; ++i) xl[i] = xi[i];
      /* near π, A(ω)⁻¹ amplifies the ε-perturbation of R in the translation part */
      worst_se3 = fmax(worst_se3, err_ulps(6, back, xl, fmax(angles[a], 2.6)));
      long double ad[36];
      double adm[36];
      gm_se3_ad(xi, adm);
      for (int i = 0; i < 36; ++i) ad[i] = adm[i];
      long double ref[36];
      phi1_ld(6, ad, ref);
      gm_se3_dexp(xi, d);
      worst_se3_dexp = fmax(worst_se3_dexp, err_ulps(36, d, ref, 2.6));
      /* dexp⁻¹ dexp = I */
      gm_se3_dexp_inv(xi, di);
      long double prod[36], eye[36];
      double prodd[36];
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
          long double s = 0;
          for (int l = 0; l < 6; ++l) s += (long double)di[6 * i + l] * d[6 * l + j];
          prod[6 * i + j] = s;
          prodd[6 * i + j] = (double)s;
          eye[6 * i + j] = i == j;
        }
      (void)prod;
      double scale = 1.0;
      for (int i = 0; i < 36; ++i) scale = fmax(scale, fabs(di[i]) * 2.6);
      worst_se3_dexp = fmax(worst_se3_dexp, err_ulps(36, prodd, eye, scale));
    }
  cr_log_info("se3 exp, log: worst %.2f eps; dexp vs series, dexp_inv dexp - I: %.2f eps",
              worst_se3, worst_se3_dexp);
  cr_expect_leq(worst_se3, 4.0);
  cr_expect_leq(worst_se3_dexp, 4.0);
}

Test(lie, se3_adjoint_identities) {
  /* exp(Ad_g ξ) = g exp(ξ) g⁻¹ and Ad_g ad_ξ Ad_g⁻¹ = ad_{Ad_g ξ} */
  const double xi[6] = {0.3, -0.7, 1.1, 0.5, 2.0, -1.0}, eta[6] = {-1.2, 0.4, 0.9, 0.1, -0.3, 2.0};
  double gr[9], gt[3], ad_g[36], axi[6], r1[9], t1[3], r2[9], t2[3], gi_r[9], gi_t[3];
  gm_se3_exp(eta, gr, gt);
  gm_se3_Ad(gr, gt, ad_g);
  for (int i = 0; i < 6; ++i) {
    axi[i] = 0;
    for (int j = 0; j < 6; ++j) axi[i] += ad_g[6 * i + j] * xi[j];
  }
  gm_se3_exp(axi, r1, t1);
  gm_se3_exp(xi, r2, t2);
  gm_se3_inverse(gr, gt, gi_r, gi_t);
  gm_se3_compose(gr, gt, r2, t2, r2, t2);
  gm_se3_compose(r2, t2, gi_r, gi_t, r2, t2);
  for (int i = 0; i < 9; ++i) cr_expect(fabs(r1[i] - r2[i]) < 1e-14);
  for (int i = 0; i < 3; ++i) cr_expect(fabs(t1[i] - t2[i]) < 1e-13);
  double a1[36], a2[36], ad_x[36], ad_ax[36], ad_gi[36];
  gm_se3_ad(xi, ad_x);
  gm_se3_ad(axi, ad_ax);
  gm_se3_Ad(gi_r, gi_t, ad_gi);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      a1[6 * i + j] = 0;
      for (int l = 0; l < 6; ++l) a1[6 * i + j] += ad_g[6 * i + l] * ad_x[6 * l + j];
    }
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      a2[6 * i + j] = 0;
      for (int l = 0; l < 6; ++l) a2[6 * i + j] += a1[6 * i + l] * ad_gi[6 * l + j];
    }
  for (int i = 0; i < 36; ++i) cr_expect(fabs(a2[i] - ad_ax[i]) < 1e-13, "%d", i);
  /* SO(3): exp(R w) = R exp(w) Rᵀ */
  double r[9], rw[3], e1[9], e2[9];
  gm_so3_exp(eta, r);
  gm_mat3_vec(r, xi, rw);
  gm_so3_exp(rw, e1);
  gm_so3_exp(xi, e2);
  gm_mat3_mul(r, e2, e2);
  gm_mat3_mul_nt(e2, r, e2);
  for (int i = 0; i < 9; ++i) cr_expect(fabs(e1[i] - e2[i]) < 1e-15);
}

Test(lie, quaternions) {
  for (size_t a = 0; a < N_ANGLES; ++a)
    for (size_t k = 0; k < N_AXES; ++k) {
      double w[3], q[4], r[9], q2[4], back[3];
      long double ref[9];
      sample(a, k, w);
      gm_quat_from_rotvec(w, q);
      gm_quat_to_matrix(q, r);
      exp_ld(w, ref);
      worst_quat = fmax(worst_quat, err_ulps(9, r, ref, 1.0));
      double rr[9];
      for (int i = 0; i < 9; ++i) rr[i] = (double)ref[i];
      gm_quat_from_matrix(rr, q2);
      /* same rotation: q2 = ±q */
      double s = q[0] * q2[0] + q[1] * q2[1] + q[2] * q2[2] + q[3] * q2[3] < 0 ? -1.0 : 1.0;
      double e = 0;
      for (int i = 0; i < 4; ++i) e = fmax(e, fabs(q[i] - s * q2[i]));
      worst_quat = fmax(worst_quat, e / EPS);
      gm_quat_to_rotvec(q, back);
      long double wl[3] = {w[0], w[1], w[2]};
      if (angles[a] > 0) worst_quat = fmax(worst_quat, err_ulps(3, back, wl, angles[a]));
    }
  /* product of quaternions = product of rotations */
  double w1[3] = {0.3, 1.2, -0.4}, w2[3] = {-2.0, 0.5, 0.7}, q1[4], q2[4], q12[4], r1[9], r2[9],
         r12[9], rq[9];
  gm_quat_from_rotvec(w1, q1);
  gm_quat_from_rotvec(w2, q2);
  gm_quat_mul(q1, q2, q12);
  gm_so3_exp(w1, r1);
  gm_so3_exp(w2, r2);
  gm_mat3_mul(r1, r2, r12);
  gm_quat_to_matrix(q12, rq);
  for (int i = 0; i < 9; ++i) cr_expect(fabs(rq[i] - r12[i]) < 4 * EPS);
  cr_log_info("quaternion conversions: worst %.2f eps", worst_quat);
  cr_expect_leq(worst_quat, 4.0);
}
