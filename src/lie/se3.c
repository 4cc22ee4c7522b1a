/* SE(3): exp, log, A⁻¹, composition, Ad, ad and the closed-form dexp and dexp⁻¹.
 * exp and A⁻¹ follow Leok (2004), App. B (Tr R = 1 + 2 cos φ: seeds/notes/001 §4); the lower
 * block Q(ω, v) of dexp is the series Σ_k (ad_ξ^k)/(k+1)! summed in closed form (Barfoot &
 * Furgale, IEEE Trans. Robotics 30 (2014) 679, eq. (102), with their ρ = v and φ = ω);
 * tests/unit/test_lie.c compares it with the series. */
#include <math.h>

#include "geomint/lie.h"

void gm_se3_exp(const double xi[6], double r[9], double t[3]) {
  double a[9];
  gm_so3_exp(xi, r);
  gm_so3_dexp(xi, a);
  gm_mat3_vec(a, xi + 3, t);
}

void gm_se3_a_inv(const double w[3], double out[9]) { gm_so3_dexp_inv(w, out); }

void gm_se3_log(const double r[9], const double t[3], double xi[6]) {
  double ai[9];
  gm_so3_log(r, xi);
  gm_so3_dexp_inv(xi, ai);
  gm_mat3_vec(ai, t, xi + 3);
}

void gm_se3_compose(const double r1[9], const double t1[3], const double r2[9],
                    const double t2[3], double r[9], double t[3]) {
  double u[3];
  gm_mat3_vec(r1, t2, u);
  for (int i = 0; i < 3; ++i) u[i] += t1[i];
  gm_mat3_mul(r1, r2, r);
  for (int i = 0; i < 3; ++i) t[i] = u[i];
}

void gm_se3_inverse(const double r[9], const double t[3], double ri[9], double ti[3]) {
  double u[3];
  gm_mat3_tvec(r, t, u);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) ri[3 * i + j] = r[3 * j + i];
  for (int i = 0; i < 3; ++i) ti[i] = -u[i];
}

/* Write the 3×3 block m at block position (bi, bj) of the 6×6 out. */
static void put_block(double out[36], int bi, int bj, const double m[9]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[6 * (3 * bi + i) + 3 * bj + j] = m[3 * i + j];
}

static void zero36(double out[36]) {
  for (int k = 0; k < 36; ++k) out[k] = 0.0;
}

void gm_se3_Ad(const double r[9], const double t[3], double out[36]) {
  double th[9], tr[9];
  gm_so3_hat(t, th);
  gm_mat3_mul(th, r, tr);
  zero36(out);
  put_block(out, 0, 0, r);
  put_block(out, 1, 0, tr);
  put_block(out, 1, 1, r);
}

void gm_se3_ad(const double xi[6], double out[36]) {
  double wh[9], vh[9];
  gm_so3_hat(xi, wh);
  gm_so3_hat(xi + 3, vh);
  zero36(out);
  put_block(out, 0, 0, wh);
  put_block(out, 1, 0, vh);
  put_block(out, 1, 1, wh);
}

/* (θ² + 2 cos θ − 2)/(2θ⁴) = Σ_k (−1)^k θ^{2k}/(2k+4)! */
static double coefficient4(double theta) {
  double t2 = theta * theta;
  if (fabs(theta) >= 2.0) return (t2 + 2.0 * cos(theta) - 2.0) / (2.0 * t2 * t2);
  double term = 1.0 / 24.0, sum = term;
  for (int k = 1; k < 30 && fabs(term) > 1e-18 * sum; ++k) {
    term *= -t2 / ((2.0 * k + 3.0) * (2.0 * k + 4.0));
    sum += term;
  }
  return sum;
}

/* (2θ − 3 sin θ + θ cos θ)/(2θ⁵) = ½ Σ_k (−1)^k (2k+2) θ^{2k}/(2k+5)! */
static double coefficient5(double theta) {
  double t2 = theta * theta;
  if (fabs(theta) >= 2.5)
    return (2.0 * theta - 3.0 * sin(theta) + theta * cos(theta)) / (2.0 * t2 * t2 * theta);
  double a = 1.0 / 120.0, sum = 2.0 * a;
  for (int k = 1; k < 40 && fabs(a) > 1e-19 * sum; ++k) {
    a *= -t2 / ((2.0 * k + 4.0) * (2.0 * k + 5.0));
    sum += (2.0 * k + 2.0) * a;
  }
  return 0.5 * sum;
}

/* Q(ω, v) = ½v̂ + c3 (ω̂v̂ + v̂ω̂ + ω̂v̂ω̂) + c4 (ω̂²v̂ + v̂ω̂² − 3ω̂v̂ω̂)
 *           + c5 (ω̂v̂ω̂² + ω̂²v̂ω̂) */
static void q_block(const double xi[6], double q[9]) {
  double w[9], v[9], wv[9], vw[9], wvw[9], w2v[9], vw2[9], wvw2[9], w2vw[9];
  double theta = gm_vec3_norm(xi);
  double c3 = gm_so3_sinc3(theta), c4 = coefficient4(theta), c5 = coefficient5(theta);
  gm_so3_hat(xi, w);
  gm_so3_hat(xi + 3, v);
  gm_mat3_mul(w, v, wv);
  gm_mat3_mul(v, w, vw);
  gm_mat3_mul(wv, w, wvw);
  gm_mat3_mul(w, wv, w2v);
  gm_mat3_mul(vw, w, vw2);
  gm_mat3_mul(wvw, w, wvw2);
  gm_mat3_mul(w, wvw, w2vw);
  for (int k = 0; k < 9; ++k)
    q[k] = 0.5 * v[k] + c3 * (wv[k] + vw[k] + wvw[k]) + c4 * (w2v[k] + vw2[k] - 3.0 * wvw[k]) +
           c5 * (wvw2[k] + w2vw[k]);
}

void gm_se3_dexp(const double xi[6], double out[36]) {
  double d[9], q[9];
  gm_so3_dexp(xi, d);
  q_block(xi, q);
  zero36(out);
  put_block(out, 0, 0, d);
  put_block(out, 1, 0, q);
  put_block(out, 1, 1, d);
}

void gm_se3_dexp_inv(const double xi[6], double out[36]) {
  double di[9], q[9], m[9], lower[9];
  gm_so3_dexp_inv(xi, di);
  q_block(xi, q);
  gm_mat3_mul(di, q, m);
  gm_mat3_mul(m, di, lower);
  for (int k = 0; k < 9; ++k) lower[k] = -lower[k];
  zero36(out);
  put_block(out, 0, 0, di);
  put_block(out, 1, 0, lower);
  put_block(out, 1, 1, di);
}
