/* geomint lie: the rotation group SO(3), the rigid motions SE(3) and unit quaternions.
 *
 * Conventions (every function below follows them):
 *  - A 3×3 matrix is 9 doubles, row-major. A rotation R maps body to space coordinates.
 *  - hat(w) is the skew matrix with hat(w) v = w × v; vee is its inverse (of the skew part).
 *  - exp(w) = exp(hat w) is the rotation by the angle |w| about w / |w| (Rodrigues).
 *  - dexp_w = Σ_k ad_w^k / (k+1)! is the right-trivialized derivative of exp:
 *    d/dt exp(w(t)) = hat(dexp_w w') exp(w(t)); equivalently exp(−w) d/dt exp(w) =
 *    hat(dexp_{−w} w') (left-trivialized, the body angular velocity of R0 exp(w(t))).
 *    On so(3): dexp_w = I + (1 − cos θ)/θ² ŵ + (θ − sin θ)/θ³ ŵ², θ = |w|.
 *  - SE(3): an element is (R, t) acting as x ↦ R x + t; a twist is ξ = (ω, v) in R⁶ with
 *    hat ξ = [[ω̂, v], [0, 0]]; exp(ξ) = (exp ω, A(ω) v) with A(ω) = dexp_ω (Leok 2004,
 *    App. B). Ad and ad are 6×6 matrices acting on (ω, v).
 *  - A unit quaternion is (w, x, y, z) = (cos(θ/2), sin(θ/2) n) for the rotation exp(θ n).
 *  - The Cayley map is cay(w) = (I − ŵ/2)⁻¹ (I + ŵ/2) = I + 4/(4 + |w|²) (ŵ + ŵ²/2), which
 *    agrees with exp to second order; its inverse is 2 vee(R − Rᵀ) / (1 + tr R).
 * Near the angles 0 and π the coefficient functions use series or the symmetric part of R, so
 * the results keep full relative accuracy (measured in tests/unit/test_lie.c, documented in
 * docs/lie-groups.md). Nothing here allocates, prints or keeps state; outputs may not alias
 * inputs unless a comment says so. */
#ifndef GEOMINT_LIE_H
#define GEOMINT_LIE_H

#include "geomint/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- 3×3 helpers ---------------------------------------------------------------------- */
void gm_mat3_mul(const double a[9], const double b[9], double out[9]);   /* a b */
void gm_mat3_mul_tn(const double a[9], const double b[9], double out[9]); /* aᵀ b */
void gm_mat3_mul_nt(const double a[9], const double b[9], double out[9]); /* a bᵀ */
void gm_mat3_vec(const double a[9], const double v[3], double out[3]);   /* a v */
void gm_mat3_tvec(const double a[9], const double v[3], double out[3]);  /* aᵀ v */
void gm_vec3_cross(const double a[3], const double b[3], double out[3]);
double gm_vec3_dot(const double a[3], const double b[3]);
double gm_vec3_norm(const double a[3]);  /* without overflow or underflow (hypot) */
/* ‖RᵀR − I‖ in the Frobenius norm: how far R is from the orthogonal matrices. */
double gm_so3_orthogonality_defect(const double r[9]);

/* ---- so(3) and SO(3) ------------------------------------------------------------------ */
void gm_so3_hat(const double w[3], double out[9]);
/* vee of the skew part (m − mᵀ)/2 */
void gm_so3_vee(const double m[9], double out[3]);
void gm_so3_exp(const double w[3], double r[9]);
/* exp(w) − I, accurate for small w where exp(w) − I computed from exp(w) would lose digits. */
void gm_so3_expm1(const double w[3], double e[9]);
/* The rotation vector w of R with |w| ≤ π (for |w| = π either sign). R must be a rotation;
 * accurate near 0 (from the skew part) and near π (axis from the symmetric part). */
void gm_so3_log(const double r[9], double w[3]);
void gm_so3_cayley(const double w[3], double r[9]);
/* Inverse Cayley map; GM_EDOMAIN when 1 + tr R <= 0 (a half turn, where it is singular). */
gm_status gm_so3_cayley_inverse(const double r[9], double w[3]);
/* dexp_w and its inverse I − ½ŵ + (1 − (θ/2)cot(θ/2))/θ² ŵ² (singular at θ = 2π). */
void gm_so3_dexp(const double w[3], double d[9]);
void gm_so3_dexp_inv(const double w[3], double d[9]);
/* Ad_R = R (on vectors of so(3) ≅ R³), ad_w = ŵ: provided for symmetry with SE(3). */
void gm_so3_Ad(const double r[9], double out[9]);
void gm_so3_ad(const double w[3], double out[9]);
/* The coefficient functions, with series near 0: sin θ/θ, (1 − cos θ)/θ², (θ − sin θ)/θ³ and
 * (1 − (θ/2)cot(θ/2))/θ². */
double gm_so3_sinc(double theta);
double gm_so3_cosc(double theta);
double gm_so3_sinc3(double theta);
double gm_so3_dexp_inv_coefficient(double theta);

/* ---- SE(3) ---------------------------------------------------------------------------- */
/* exp(ξ) = (R, t) for the twist ξ = (ω, v). */
void gm_se3_exp(const double xi[6], double r[9], double t[3]);
/* The twist ξ = (ω, v) with exp(ξ) = (R, t), |ω| ≤ π (A(ω) is invertible for |ω| < 2π). */
void gm_se3_log(const double r[9], const double t[3], double xi[6]);
/* A(ω)⁻¹ = I − ½ω̂ + (1 − (θ/2)cot(θ/2))/θ² ω̂² (Leok 2004, App. B; the printed form agrees). */
void gm_se3_a_inv(const double w[3], double out[9]);
/* (R, t)(R2, t2) = (R R2, R t2 + t); the inverse (Rᵀ, −Rᵀ t). */
void gm_se3_compose(const double r1[9], const double t1[3], const double r2[9],
                    const double t2[3], double r[9], double t[3]);
void gm_se3_inverse(const double r[9], const double t[3], double ri[9], double ti[3]);
/* 6×6 row-major: Ad_(R,t) = [[R, 0], [t̂ R, R]], ad_ξ = [[ω̂, 0], [v̂, ω̂]]. */
void gm_se3_Ad(const double r[9], const double t[3], double out[36]);
void gm_se3_ad(const double xi[6], double out[36]);
/* dexp_ξ = [[dexp_ω, 0], [Q(ω, v), dexp_ω]] in closed form and its inverse
 * [[dexp_ω⁻¹, 0], [−dexp_ω⁻¹ Q dexp_ω⁻¹, dexp_ω⁻¹]] (6×6 row-major). */
void gm_se3_dexp(const double xi[6], double out[36]);
void gm_se3_dexp_inv(const double xi[6], double out[36]);

/* ---- unit quaternions ----------------------------------------------------------------- */
void gm_quat_mul(const double a[4], const double b[4], double out[4]);
void gm_quat_conj(const double q[4], double out[4]);
void gm_quat_from_rotvec(const double w[3], double q[4]);   /* q = exp(w/2) */
void gm_quat_to_rotvec(const double q[4], double w[3]);     /* |w| ≤ π (q and −q alike) */
void gm_quat_to_matrix(const double q[4], double r[9]);     /* q need not be normalized */
/* The unit quaternion of a rotation (Shepperd's method: the largest of the four squares), with
 * w >= 0. */
void gm_quat_from_matrix(const double r[9], double q[4]);
void gm_quat_rotate(const double q[4], const double v[3], double out[3]);

#ifdef __cplusplus
}
#endif
#endif
