/* geomint reduction: Routh reduction by an abelian symmetry, continuous and discrete
 * (seed 001 = Leok, thesis (2004), ch. 2; corrections in the seed notes §1C, §1D and §4).
 *
 * A mechanical Lagrangian with an abelian symmetry, written in a trivialisation q = (θ, x) where
 * the group G = R^k (or the torus T^k) acts by θ ↦ θ + φ and x ∈ S is the shape:
 *   L(x, θ̇, ẋ) = ½ vᵀ M(x) v − V(x),   v = (θ̇, ẋ),   M = [[𝕀, B], [Bᵀ, M_xx]].
 * From M one gets the locked inertia 𝕀(x) (k×k), the mechanical connection in local form
 * 𝔄(θ, x)(θ̇, ẋ) = θ̇ + A(x)ẋ with A = 𝕀⁻¹B (k×n), the momentum J = ∂L/∂θ̇ = 𝕀(θ̇ + Aẋ), and on
 * J = μ the Routhian (seed 001 §2.2; L − 𝔄_μ dropped to TS)
 *   R̂^μ(x, ẋ) = ½ ẋᵀK(x)ẋ − V_μ(x),  K = M_xx − BᵀA,  V_μ = V + ½ μᵀ𝕀⁻¹μ (amended potential),
 * the magnetic 2-form β_μ = d(μA), β_ij = μ_a(∂_i A^a_j − ∂_j A^a_i), the classical Routhian
 * R̂_c = R̂^μ + μA(x)ẋ (seed 001 eq. 2.7.5) and the reduced momentum s = K ẋ = p_x − μA(x).
 * Nonabelian groups are not handled here. */
#ifndef GEOMINT_REDUCTION_H
#define GEOMINT_REDUCTION_H

#include <stddef.h>

#include "geomint/core.h"
#include "geomint/methods.h"
#include "geomint/variational.h"

#ifdef __cplusplus
extern "C" {
#endif

#define GM_ROUTH_MAX_GROUP 4 /* k ≤ 4 */
#define GM_ROUTH_MAX_SHAPE 8 /* n ≤ 8 */

typedef struct gm_routh_system {
  size_t k;  /* dimension of the abelian group (θ) */
  size_t n;  /* dimension of the shape space (x) */
  void *ctx; /* borrowed; passed to every callback */
  /* required: M(x), (k+n)×(k+n) row-major, symmetric positive definite */
  int (*metric)(void *ctx, const double *x, double *m);
  /* optional: ∂M/∂x_l for l = 0..n−1 (n blocks of (k+n)²); central differences of metric
   * otherwise (relative accuracy about 1e-10) */
  int (*metric_dx)(void *ctx, const double *x, double *dm);
  /* required: V(x) and ∇V(x) (n values) */
  double (*potential)(void *ctx, const double *x);
  int (*potential_dx)(void *ctx, const double *x, double *grad);
} gm_routh_system;

/* The shape quantities at x (any output may be NULL): 𝕀 (k×k), A (k×n), K (n×n), ∂A/∂x
 * (dA[(a·n + i)·n + l] = ∂A^a_i/∂x_l), V_μ(x) and ∇V_μ (n). GM_EINVAL for a bad system,
 * GM_ECALLBACK when a callback fails, GM_ESINGULAR when 𝕀 or K is singular. */
gm_status gm_routh_connection(const gm_routh_system *sys, const double *mu, const double *x,
                              double *locked_inertia, double *conn, double *kinetic, double *dconn,
                              double *amended, double *amended_grad, gm_error *err);

/* β_μ(x) as an n×n antisymmetric matrix, β_ij = μ_a(∂_i A^a_j − ∂_j A^a_i). */
gm_status gm_routh_magnetic(const gm_routh_system *sys, const double *mu, const double *x,
                            double *beta, gm_error *err);

/* Reduced energy H_μ(x, s) = ½ sᵀK⁻¹s + V_μ(x) (the energy of the full system on J = μ). NaN on
 * failure. */
double gm_routh_energy(const gm_routh_system *sys, const double *mu, const double *x,
                       const double *s);

/* From a full state (θ, x, p_θ, p_x) (p = M v) to the reduced one: μ = p_θ must match mu to
 * |p_θ − μ| ≤ 1e-12 (1 + |μ|), else GM_EINVAL "μ inconsistent with the initial state";
 * s = p_x − μA(x). Both directions; the lift sets p_θ = μ, p_x = s + μA(x). */
gm_status gm_routh_reduce_momentum(const gm_routh_system *sys, const double *mu, const double *x,
                                   const double *p_theta, const double *p_x, double *s,
                                   gm_error *err);
gm_status gm_routh_lift_momentum(const gm_routh_system *sys, const double *mu, const double *x,
                                 const double *s, double *p_x, gm_error *err);

/* Unreduced Hamilton equations in (θ, x, p_θ, p_x) with H = ½pᵀM⁻¹p + V (for comparisons, e.g.
 * RK4 on the full system): y has 2(k+n) entries. */
gm_status gm_routh_full_rhs(const gm_routh_system *sys, const double *y, double *dy,
                            gm_error *err);

/* ---- RSPRK and the SPRK on the classical Routhian ------------------------------------------ */

/* Partitioned Runge–Kutta steppers for the reduced system on T*S (seed 001 §2.5, §2.7):
 *   GM_ROUTH_RSPRK     eq. 2.5.14, state (x, s), s = p_x − μA(x), with the connection bracket
 *                      h Σ ã_ij μ ∂A/∂x(X_j)Ẋ_j − μ(A(X_i) − A(x0)) and the magnetic term
 *                      −i_Ẋ β_μ; it keeps Ω_S − π*β_μ;
 *   GM_ROUTH_CLASSICAL eq. 2.7.5, the same tableau on R̂_c, state (x, y), y = s + μA(x); it keeps
 *                      the canonical Ω_S.
 * The two give the same trajectory up to σ(x, s) = (x, s + μA(x)) (seed 001 §2.7). The tableau
 * is a partitioned one (a, b, c, a_bar, b_bar), e.g. from gm_galerkin_prk_tableau or a
 * vi-galerkin-* row; it is copied. Stage velocities are solved by Newton's method (difference
 * Jacobian). */
typedef enum gm_routh_form { GM_ROUTH_RSPRK = 0, GM_ROUTH_CLASSICAL = 1 } gm_routh_form;
typedef struct gm_rsprk gm_rsprk;
gm_status gm_rsprk_create(const gm_routh_system *sys, const gm_tableau *tableau,
                          gm_routh_form form, const double *mu, gm_rsprk **out, gm_error *err);
void gm_rsprk_free(gm_rsprk *r);
/* One step from (x, s) (or (x, y)), both overwritten; theta (may be NULL) is advanced by the
 * reconstruction θ1 = θ0 + h Σ b_j Θ̇_j, Θ̇_j = 𝕀⁻¹μ − A(X_j)Ẋ_j (the θ-row of the unreduced
 * SPRK, seed 001 eq. 2.5.1). Unchanged on failure (GM_ENOCONV with the step's x in the message).*/
gm_status gm_rsprk_step(gm_rsprk *r, double h, double *x, double *s, double *theta);
const char *gm_rsprk_errmsg(const gm_rsprk *r);

/* ---- discrete Routh reduction (seed 001 §2.3.2–2.3.5, Thm 2.17) ----------------------------- */

/* The midpoint (1-point Gauss Galerkin) discrete Lagrangian of the system on q = (θ, x):
 * L_d = h L((q0 + q1)/2, (q1 − q0)/h), with analytic slot derivatives. It is θ-invariant. Fills
 * ld (dim = k + n, ctx = sys, borrowed). */
void gm_routh_midpoint_lagrangian(const gm_routh_system *sys, gm_discrete_lagrangian *ld);

/* Discrete Routh data for a θ-invariant discrete Lagrangian ld on q = (θ, x) (θ the first k
 * coordinates; ld->dim = k + n), the connection A of sys and a momentum value μ. ld and sys are
 * borrowed. Optional discrete forces (reduced, shape components F̂_d^1, F̂_d^2 at (x0, x1); their
 * θ-components are taken as zero so J_d is kept, Lemma 2.15) and holonomic shape constraints
 * ĝ(x) = 0 (m ≤ n values, with Jacobian m×n). */
typedef struct gm_routh_discrete_options {
  int (*force1)(void *ctx, double h, const double *x0, const double *x1, double *f);
  int (*force2)(void *ctx, double h, const double *x0, const double *x1, double *f);
  size_t n_constraints;
  int (*constraint)(void *ctx, const double *x, double *g);
  int (*constraint_jacobian)(void *ctx, const double *x, double *jac);
  void *ctx; /* borrowed; passed to the forces and constraints */
} gm_routh_discrete_options;

typedef struct gm_routh_discrete gm_routh_discrete;
gm_status gm_routh_discrete_create(const gm_discrete_lagrangian *ld, const gm_routh_system *sys,
                                   const double *mu, const gm_routh_discrete_options *opts,
                                   gm_routh_discrete **out, gm_error *err);
void gm_routh_discrete_free(gm_routh_discrete *d);
const char *gm_routh_discrete_errmsg(const gm_routh_discrete *d);

/* ψ_μ(x0, x1) ∈ R^k solving J_d(0, x0, ψ, x1) = D₂L_d(0, x0, ψ, x1)_θ = μ by Newton's method
 * (group-regularity: GM_ENOCONV names (x0, x1) when it fails). psi holds the initial guess on
 * entry when warm != 0. */
gm_status gm_routh_psi(gm_routh_discrete *d, double h, const double *x0, const double *x1,
                       int warm, double *psi);
/* L̂_d(x0, x1) = L_d(0, x0, ψ_μ, x1) (needs ld->value); D₁L̂_d, D₂L̂_d by the chain rule with
 * Dψ_μ from the implicit function theorem; Â₁ = μ(D₁ψ_μ − A(x0)), Â₂ = μ(D₂ψ_μ + A(x1)) (derived
 * in docs/reduction.md; the thesis does not print them). Any output may be NULL. */
gm_status gm_routh_reduced_lagrangian(gm_routh_discrete *d, double h, const double *x0,
                                      const double *x1, double *value, double *d1, double *d2,
                                      double *a1, double *a2, double *psi);
/* The residual of the discrete Routh equations (2.3.29) with forces and constraint multipliers
 * λ (Thm 2.17): D₂L̂_d(x_{k−1}, x_k) + D₁L̂_d(x_k, x_{k+1}) − Â₂(x_{k−1}, x_k) − Â₁(x_k, x_{k+1})
 * + F̂²(x_{k−1}, x_k) + F̂¹(x_k, x_{k+1}) + λᵀDĝ(x_k) (n values; lambda may be NULL). */
gm_status gm_routh_discrete_residual(gm_routh_discrete *d, double h, const double *xm,
                                     const double *x, const double *xp, const double *lambda,
                                     double *res);
/* One step of the discrete Routh equations: given x_{k−1} (xm) and x_k (x), solve for x_{k+1}
 * (and λ_k with constraints, ĝ(x_{k+1}) = 0), starting from the guess in xp; θ (may be NULL) is
 * advanced by the reconstruction θ_{k+1} = θ_k + ψ_μ(x_k, x_{k+1}). lambda (may be NULL) gets λ_k. */
gm_status gm_routh_discrete_step(gm_routh_discrete *d, double h, const double *xm,
                                 const double *x, double *xp, double *theta, double *lambda);

/* Holonomy of a closed shape loop: the group drift θ_N − θ_0 = Σ_i ψ_μ(x_i, x_{i+1}) of the
 * discrete horizontal lift (μ = 0: of the discrete mechanical connection, J_d = 0, seed 001 §4
 * and notes §1F; abelian G, so the order of the product does not matter). loop holds n_points
 * shape points x_0..x_{N} (n values each) with x_N = x_0 up to 1e-12 (1 + |x_0|); GM_EINVAL
 * "shape loop does not close" otherwise. angle gets k values. */
gm_status gm_routh_holonomy(gm_routh_discrete *d, double h, size_t n_points, const double *loop,
                            double *angle);

/* ---- the two systems of seed 001 §2.9–2.10 ------------------------------------------------ */

/* Satellite about an oblate planet in cylindrical coordinates θ; x = (r, z): M = diag(r², 1, 1),
 * V = −1/ρ + (J2/ρ³)(3z²/(2ρ²) − ½), ρ² = r² + z² (the potential as corrected in notes §4);
 * μ = r²θ̇, A = 0, β_μ = 0, V_μ = V + μ²/(2r²). params is borrowed. */
typedef struct gm_routh_j2_params {
  double j2;
} gm_routh_j2_params;
void gm_routh_j2_satellite(gm_routh_j2_params *params, gm_routh_system *sys);

/* Double spherical pendulum (seed 001 §2.10): θ = θ1, x = (r1, r2, φ = θ2 − θ1), both masses
 * below their pivots (z_i = −√(l_i² − r_i²)), q2 relative to q1; M = Jᵀ M_c J from the Cartesian
 * L (∂M/∂x analytic, tested against differences), V = m1 g z1 + m2 g (z1 + z2). Its locked inertia and
 * connection are 𝕀 = m1r1² + m2(r1² + r2² + 2r1r2 cos φ), A = (m2/𝕀)(−r2 sin φ, r1 sin φ,
 * r2² + r1r2 cos φ) (tested). */
typedef struct gm_routh_dsp_params {
  double m1, m2, l1, l2, g;
} gm_routh_dsp_params;
void gm_routh_double_spherical_pendulum(gm_routh_dsp_params *params, gm_routh_system *sys);

#ifdef __cplusplus
}
#endif
#endif
