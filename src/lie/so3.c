/* SO(3) and so(3): hat/vee, Rodrigues' exp, log, Cayley, dexp and its inverse.
 * Formulas: Rodrigues; dexp and dexp⁻¹ from Iserles, Munthe-Kaas, Nørsett & Zanna, Acta
 * Numerica 9 (2000) 215, §2.4 and Leok (2004), App. B (with Tr R = 1 + 2 cos φ, not the
 * printed 1 − 2 cos φ: seeds/notes/001 §4). Coefficients that cancel near θ = 0 are summed as
 * series below a threshold chosen so that neither branch loses more than a few ulps. */
#include <math.h>

#include "geomint/lie.h"

void gm_mat3_mul(const double a[9], const double b[9], double out[9]) {
  double r[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
  for (int k = 0; k < 9; ++k) out[k] = r[k];
}

void gm_mat3_mul_tn(const double a[9], const double b[9], double out[9]) {
  double r[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r[3 * i + j] = a[i] * b[j] + a[3 + i] * b[3 + j] + a[6 + i] * b[6 + j];
  for (int k = 0; k < 9; ++k) out[k] = r[k];
}

void gm_mat3_mul_nt(const double a[9], const double b[9], double out[9]) {
  double r[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r[3 * i + j] =
          a[3 * i] * b[3 * j] + a[3 * i + 1] * b[3 * j + 1] + a[3 * i + 2] * b[3 * j + 2];
  for (int k = 0; k < 9; ++k) out[k] = r[k];
}

void gm_mat3_vec(const double a[9], const double v[3], double out[3]) {
  double r0 = a[0] * v[0] + a[1] * v[1] + a[2] * v[2];
  double r1 = a[3] * v[0] + a[4] * v[1] + a[5] * v[2];
  double r2 = a[6] * v[0] + a[7] * v[1] + a[8] * v[2];
  out[0] = r0;
  out[1] = r1;
  out[2] = r2;
}

void gm_mat3_tvec(const double a[9], const double v[3], double out[3]) {
  double r0 = a[0] * v[0] + a[3] * v[1] + a[6] * v[2];
  double r1 = a[1] * v[0] + a[4] * v[1] + a[7] * v[2];
  double r2 = a[2] * v[0] + a[5] * v[1] + a[8] * v[2];
  out[0] = r0;
  out[1] = r1;
  out[2] = r2;
}

void gm_vec3_cross(const double a[3], const double b[3], double out[3]) {
  double c0 = a[1] * b[2] - a[2] * b[1];
  double c1 = a[2] * b[0] - a[0] * b[2];
  double c2 = a[0] * b[1] - a[1] * b[0];
  out[0] = c0;
  out[1] = c1;
  out[2] = c2;
}

double gm_vec3_dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double gm_vec3_norm(const double a[3]) { return hypot(hypot(a[0], a[1]), a[2]); }

double gm_so3_orthogonality_defect(const double r[9]) {
  double m[9], s = 0.0;
  gm_mat3_mul_tn(r, r, m);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double d = m[3 * i + j] - (i == j ? 1.0 : 0.0);
      s += d * d;
    }
  return sqrt(s);
}

void gm_so3_hat(const double w[3], double out[9]) {
  out[0] = 0.0;
  out[1] = -w[2];
  out[2] = w[1];
  out[3] = w[2];
  out[4] = 0.0;
  out[5] = -w[0];
  out[6] = -w[1];
  out[7] = w[0];
  out[8] = 0.0;
}

void gm_so3_vee(const double m[9], double out[3]) {
  out[0] = 0.5 * (m[7] - m[5]);
  out[1] = 0.5 * (m[2] - m[6]);
  out[2] = 0.5 * (m[3] - m[1]);
}

/* ---- coefficient functions ------------------------------------------------------------- */

double gm_so3_sinc(double theta) {
  double t2 = theta * theta;
  if (fabs(theta) < 1e-4) return 1.0 - t2 / 6.0 * (1.0 - t2 / 20.0);
  return sin(theta) / theta;
}

/* (1 − cos θ)/θ² = 2 sin²(θ/2)/θ²: no cancellation anywhere. */
double gm_so3_cosc(double theta) {
  if (theta == 0.0) return 0.5;
  double s = sin(0.5 * theta) / theta;
  return 2.0 * s * s;
}

/* (θ − sin θ)/θ³ = Σ_k (−1)^k θ^{2k}/(2k+3)!: the series below θ = 2 (where θ − sin θ has
 * cancelled by less than a factor 2), the closed form above. */
double gm_so3_sinc3(double theta) {
  double t2 = theta * theta;
  if (fabs(theta) >= 2.0) return (theta - sin(theta)) / (t2 * theta);
  double term = 1.0 / 6.0, sum = term;
  for (int k = 1; k < 30 && fabs(term) > 1e-18 * sum; ++k) {
    term *= -t2 / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
    sum += term;
  }
  return sum;
}

/* (1 − (θ/2)cot(θ/2))/θ² = Σ_k c_k θ^{2k}: Taylor coefficients (computed with sympy, exact
 * rationals rounded), ratio ≈ (θ/2π)² per term, so 21 terms reach 1e-21 at θ = 2. */
static const double dexp_inv_series[] = {
    0.083333333333333329,   0.0013888888888888889,  3.3068783068783071e-05,
    8.2671957671957675e-07, 2.08767569878681e-08,   5.2841901386874932e-10,
    1.3382536530684679e-11, 3.3896802963225827e-13, 8.5860620562778452e-15,
    2.1748686985580619e-16, 5.5090028283602295e-18, 1.3954464685812522e-19,
    3.5347070396294673e-21, 8.9535174270375463e-23, 2.2679524523376829e-24,
    5.7447906688722025e-26, 1.455172475614865e-27,  3.6859949406653103e-29,
    9.3367342570950451e-31, 2.36502241570063e-32,   5.9906717624821341e-34};

double gm_so3_dexp_inv_coefficient(double theta) {
  double t2 = theta * theta;
  if (fabs(theta) < 2.0) {
    const int n = (int)(sizeof dexp_inv_series / sizeof dexp_inv_series[0]);
    double s = dexp_inv_series[n - 1];
    for (int k = n - 2; k >= 0; --k) s = s * t2 + dexp_inv_series[k];
    return s;
  }
  double h = 0.5 * theta;
  return (1.0 - h * cos(h) / sin(h)) / t2;
}

/* ---- exp, log, Cayley ------------------------------------------------------------------ */

/* out = a ŵ + b ŵ² (+ I when add_identity), ŵ² = w wᵀ − |w|² I. */
static void quadratic_in_hat(const double w[3], double a, double b, int add_identity,
                             double out[9]) {
  const double t2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[3 * i + j] = b * w[i] * w[j];
  for (int i = 0; i < 3; ++i) out[4 * i] += (add_identity ? 1.0 : 0.0) - b * t2;
  out[1] -= a * w[2];
  out[2] += a * w[1];
  out[3] += a * w[2];
  out[5] -= a * w[0];
  out[6] -= a * w[1];
  out[7] += a * w[0];
}

void gm_so3_exp(const double w[3], double r[9]) {
  double theta = gm_vec3_norm(w);
  quadratic_in_hat(w, gm_so3_sinc(theta), gm_so3_cosc(theta), 1, r);
}

void gm_so3_expm1(const double w[3], double e[9]) {
  double theta = gm_vec3_norm(w);
  quadratic_in_hat(w, gm_so3_sinc(theta), gm_so3_cosc(theta), 0, e);
}

void gm_so3_log(const double r[9], double w[3]) {
  /* skew part: sin θ n; trace: 1 + 2 cos θ */
  double s[3];
  gm_so3_vee(r, s);
  double sin_t = gm_vec3_norm(s), cos_t = 0.5 * (r[0] + r[4] + r[8] - 1.0);
  double theta = atan2(sin_t, cos_t);
  if (cos_t > -0.5) { /* θ < 2π/3: w = θ/sin θ · s, well conditioned */
    double f = 1.0 / gm_so3_sinc(theta);
    for (int i = 0; i < 3; ++i) w[i] = f * s[i];
    return;
  }
  /* Near π: (R + Rᵀ)/2 − cos θ I = (1 − cos θ) n nᵀ; its largest column gives n to full
   * accuracy, the skew part only its sign. */
  double b[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      b[3 * i + j] = 0.5 * (r[3 * i + j] + r[3 * j + i]) - (i == j ? cos_t : 0.0);
  int k = 0;
  if (b[4] > b[3 * k + k]) k = 1;
  if (b[8] > b[3 * k + k]) k = 2;
  double n[3] = {b[k], b[3 + k], b[6 + k]};
  double len = gm_vec3_norm(n);
  if (gm_vec3_dot(n, s) < 0.0) len = -len;
  for (int i = 0; i < 3; ++i) w[i] = theta * n[i] / len;
}

void gm_so3_cayley(const double w[3], double r[9]) {
  double t2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  double a = 4.0 / (4.0 + t2);
  quadratic_in_hat(w, a, 0.5 * a, 1, r);
}

gm_status gm_so3_cayley_inverse(const double r[9], double w[3]) {
  double d = 1.0 + r[0] + r[4] + r[8];
  if (!(d > 0.0)) return GM_EDOMAIN;
  double s[3];
  gm_so3_vee(r, s); /* (R − Rᵀ)/2 */
  for (int i = 0; i < 3; ++i) w[i] = 4.0 * s[i] / d;
  return GM_OK;
}

void gm_so3_dexp(const double w[3], double d[9]) {
  double theta = gm_vec3_norm(w);
  quadratic_in_hat(w, gm_so3_cosc(theta), gm_so3_sinc3(theta), 1, d);
}

void gm_so3_dexp_inv(const double w[3], double d[9]) {
  double theta = gm_vec3_norm(w);
  quadratic_in_hat(w, -0.5, gm_so3_dexp_inv_coefficient(theta), 1, d);
}

void gm_so3_Ad(const double r[9], double out[9]) {
  for (int k = 0; k < 9; ++k) out[k] = r[k];
}

void gm_so3_ad(const double w[3], double out[9]) { gm_so3_hat(w, out); }
