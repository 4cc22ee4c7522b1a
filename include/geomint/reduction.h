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
 * Nonabelian groups are not handled by the Routh part; the discrete connections below take
 * G = SO(2) or SO(3). */
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

/* ---- discrete connections on a trivial principal bundle Q = G × S (seed 001 ch. 4) --------
 *
 * G acts on the left, g·(h, x) = (gh, x). Groups: SO(2), an element stored as its angle (one
 * double, on the universal cover R: products add angles and holonomies are not reduced mod 2π),
 * and SO(3), a rotation matrix (9 doubles, row-major; lie.h). Lie algebras: R and R³ (hat).
 *
 * A continuous principal connection in local form (seed 001 §4.1):
 *   𝒜(x, g)(ẋ, ġ) = ġ g⁻¹ + Ad_g A(x) ẋ,   A(x): R^n → 𝔤 (a dim × n matrix),
 * so a curve is horizontal iff g⁻¹ġ = −A(x)ẋ.
 * A discrete connection in local form (seed 001 §4.2, notes §1F):
 *   A_d((x0, g0), (x1, g1)) = g1 A(x0, x1) g0⁻¹,  A(x, x) = e;
 * the pure group case (S a point) is A_d(g0, g1) = g1 g0⁻¹. hor(q0, q1) = (q0, A_d⁻¹ q1),
 * ver(q0, q1) = (q0, A_d q0). The horizontal lift of a shape path from g0 is
 *   g_{l+1} = g_l A(x_l, x_{l+1})⁻¹ = g0 (A(x_l, x_{l+1}) ⋯ A(x0, x1))⁻¹
 * (the product on the right: notes §4 corrects Remark 4.2), and the holonomy of a closed shape
 * loop is the lift's end point from g0 = e, (A_{N−1} ⋯ A_0)⁻¹ (from another g0 it is conjugated by
 * g0). Its continuous limit: d/dt A_d(q(0), q(t))|₀ = 𝒜(q̇(0)).
 *
 * Rules for the local form A(x0, x1), Δx = x1 − x0, x(t) = x0 + tΔx:
 *   GM_DCONN_CALLBACK    local(ctx, x0, x1, a) given by the user;
 *   GM_DCONN_LEFT        exp(A(x0)Δx)                               (order 1: error O(h²));
 *   GM_DCONN_MIDPOINT    exp(A(x̄)Δx), x̄ = (x0 + x1)/2             (order 2: O(h³));
 *   GM_DCONN_MAGNUS4     exp(−w), w = ½(Ω₁ + Ω₂) + (√3/12) [Ω₁, Ω₂], Ω_i = −A(x(c_i))Δx at the
 *                        Gauss points c = ½ ∓ √3/6 (the 4th-order Magnus expansion of the
 *                        horizontal equation U̇ = UΩ(t), transposed from Y' = AY; order 4: O(h⁵));
 *   GM_DCONN_TRANSPORT   the exact connection: the horizontal transport along the straight shape
 *                        segment, U(1)⁻¹ for U̇ = −U A(x(t))Δx, U(0) = e, by classical RK4 with
 *                        `substeps` steps (64 when 0) — an integrator independent of the rules
 *                        above, so the order test checks their signs too (seed 001 Ex. 4.1 with
 *                        the flat metric on the chart. exp(𝒜(loḡ(q0, q1))) with the product
 *                        metric (bi-invariant on G, flat on the chart) is not used: at
 *                        q0 = (x0, e), q1 = (x1, e) it is exp(A(x0)Δx), the LEFT rule, first
 *                        order against the transport, and for nonabelian G not of local form);
 *   GM_DCONN_MECHANICAL  the discrete mechanical connection: A_d = e iff J_d = 0 (seed 001 §4.4).
 *                        momentum(ctx, x0, x1, w, j) gives the discrete momentum J_d of the pair
 *                        ((x0, e), (x1, exp w)) (dim values, any frame: only its zero matters);
 *                        Newton's method (difference Jacobian, from w = 0) solves J_d = 0 for w
 *                        and A(x0, x1) = exp(w)⁻¹. Its order is the order of L_d. */
typedef enum gm_group_kind { GM_GROUP_SO2 = 0, GM_GROUP_SO3 = 1 } gm_group_kind;
typedef enum gm_dconn_rule {
  GM_DCONN_CALLBACK = 0,
  GM_DCONN_LEFT = 1,
  GM_DCONN_MIDPOINT = 2,
  GM_DCONN_MAGNUS4 = 3,
  GM_DCONN_TRANSPORT = 4,
  GM_DCONN_MECHANICAL = 5
} gm_dconn_rule;

#define GM_DCONN_MAX_SHAPE 8 /* n ≤ 8 */

/* Element size (1 or 9 doubles) and algebra dimension (1 or 3); 0 for an unknown group. */
size_t gm_group_size(gm_group_kind g);
size_t gm_group_dim(gm_group_kind g);
/* out = a b, out = a⁻¹, exp, log (SO(3): lie.h, |w| ≤ π; SO(2): the identity map on R). out may
 * alias the inputs. */
void gm_group_mul(gm_group_kind g, const double *a, const double *b, double *out);
void gm_group_inv(gm_group_kind g, const double *a, double *out);
void gm_group_exp(gm_group_kind g, const double *w, double *out);
void gm_group_log(gm_group_kind g, const double *a, double *w);
/* ‖log(a b⁻¹)‖ (the angle between two elements; SO(2): |a − b| on the cover). */
double gm_group_distance(gm_group_kind g, const double *a, const double *b);

typedef struct gm_discrete_connection {
  gm_group_kind group;
  size_t n;           /* shape dimension ≤ GM_DCONN_MAX_SHAPE; 0: the pure group case
                       * A_d(g0, g1) = g1 g0⁻¹ (no callback; shape arguments may be NULL) */
  gm_dconn_rule rule;
  /* GM_DCONN_CALLBACK: A(x0, x1) ∈ G (gm_group_size values). Return 0 on success. */
  int (*local)(void *ctx, const double *x0, const double *x1, double *a);
  /* LEFT, MIDPOINT, MAGNUS4, TRANSPORT: the continuous A(x), dim × n row-major. */
  int (*connection)(void *ctx, const double *x, double *a);
  /* MECHANICAL: J_d((x0, e), (x1, exp w)), dim values. */
  int (*momentum)(void *ctx, const double *x0, const double *x1, const double *w, double *j);
  size_t substeps; /* TRANSPORT: RK4 steps (64 when 0) */
  void *ctx;       /* borrowed; passed to the callbacks */
} gm_discrete_connection;

/* A(x0, x1). GM_EINVAL for a bad connection, GM_ECALLBACK when a callback fails, GM_ENOCONV
 * (MECHANICAL) naming (x0, x1) and the residual when J_d = 0 has no solution Newton finds (the
 * group-regularity of L_d fails there). */
gm_status gm_dconn_local(const gm_discrete_connection *c, const double *x0, const double *x1,
                         double *a, gm_error *err);
/* A_d((x0, g0), (x1, g1)) = g1 A(x0, x1) g0⁻¹. */
gm_status gm_dconn_eval(const gm_discrete_connection *c, const double *x0, const double *g0,
                        const double *x1, const double *g1, double *ad, gm_error *err);
/* Horizontal and vertical parts of (q0, q1): hor = (q0, (x1, A_d⁻¹ g1)), ver = (q0, (x0, A_d g0));
 * g_hor and g_ver get the group parts (either may be NULL). A_d(hor) = e, A_d(ver) = A_d. */
gm_status gm_dconn_decompose(const gm_discrete_connection *c, const double *x0, const double *g0,
                             const double *x1, const double *g1, double *g_hor, double *g_ver,
                             gm_error *err);
/* The horizontal lift of the shape path x_0..x_{N−1} (n_points × n) from g0: g gets n_points
 * elements, g_0 = g0, g_{l+1} = g_l A(x_l, x_{l+1})⁻¹. */
gm_status gm_dconn_lift(const gm_discrete_connection *c, size_t n_points, const double *path,
                        const double *g0, double *g, gm_error *err);
/* Extended composition (seed 001 §4.3): (q0, q1)·(p0, p1) = (q0, (y1, A_d(p0, q1) h1)) for pairs
 * q = ((x0, g0), (x1, g1)), p = ((y0, h0), (y1, h1)) with x1 = y0 (to 1e-12 (1 + |x1|); GM_EINVAL
 * "the pairs do not compose" otherwise). g_out gets the group part of the second point. */
gm_status gm_dconn_compose(const gm_discrete_connection *c, const double *x0, const double *g0,
                           const double *x1, const double *g1, const double *y0, const double *h0,
                           const double *y1, const double *h1, double *g_out, gm_error *err);
/* Holonomy of a closed shape loop x_0..x_N (n_points = N + 1 points, x_N = x_0 to 1e-12 (1 + |x_0|),
 * else GM_EINVAL "the shape loop does not close" with the gap): the lift's end point from e. */
gm_status gm_dconn_holonomy(const gm_discrete_connection *c, size_t n_points, const double *loop,
                            double *hol, gm_error *err);
/* The order-test defect ‖A_d^a(q0, q1) A_d^b(q0, q1)⁻¹‖ = ‖log(A^a(x0, x1) A^b(x0, x1)⁻¹)‖ (it does
 * not depend on g0, g1 for local forms; conjugation keeps the norm). */
gm_status gm_dconn_defect(const gm_discrete_connection *a, const gm_discrete_connection *b,
                          const double *x0, const double *x1, double *defect, gm_error *err);

/* ---- geometric phases with closed forms (docs/reduction.md, "Phases") ------------------------
 *
 * The Levi-Civita connection of the unit sphere as a principal SO(2) connection over the upper
 * hemisphere, in the chart x = (X, Y) (the point (X, Y, √(1 − X² − Y²))) with the frame
 * (e_ϑ, e_φ): a tangent vector at angle β from e_ϑ is parallel iff β̇ = −cos ϑ φ̇, so
 * A(x) = cos ϑ dφ = √(1 − ρ²)(X dY − Y dX)/ρ², ρ² = X² + Y² (1 × 2 row; singular at the pole,
 * where the frame is). A callback for gm_discrete_connection.connection (ctx unused). Returns −1
 * off the open hemisphere or at the pole. The holonomy of the latitude circle at colatitude α
 * (counterclockwise about the north pole) is −2π cos α: relative to the local (north, east)
 * frame a Foucault pendulum's plane turns by 2π cos α clockwise per sidereal day — 2π sin(latitude)
 * — and relative to a parallel-transported frame the loop's holonomy is 2π(1 − cos α) mod 2π, the
 * enclosed area (Gauss–Bonnet). */
int gm_sphere_levi_civita(void *ctx, const double *x, double *a);

/* Montgomery's rigid-body phase (R. Montgomery, "How much does the rigid body rotate?", Am. J.
 * Phys. 59 (1991) 394): for the free rigid body with principal moments `inertia` and initial body
 * momentum pi, Π(t) is periodic with period T (gm_free_rigid_body_period, closed form), and after
 * one period R(T) = exp(Δθ m̂) R(0), m = RΠ the spatial momentum, with
 *   Δθ = 2E T/‖m‖ − Λ  (mod 2π),
 * E the kinetic energy and Λ the solid angle of the cone spanned by Π(t) on its side of the
 * encircled principal axis, oriented by the motion (Λ > 0 when Π circles that axis
 * counterclockwise seen from its tip). period, dynamic = 2ET/‖m‖ and solid_angle = Λ are
 * written; Λ = ∮(1 − cos ϑ) dφ about the encircled axis is a quadrature along Π(t) from Euler's
 * equations (classical RK4 with `steps` steps per period, 20000 when 0; error ~ (T/steps)⁴).
 * GM_EINVAL for a separatrix, a steady spin or non-distinct moments. */
gm_status gm_rigid_body_phase(const double inertia[3], const double pi[3], size_t steps,
                              double *period, double *dynamic, double *solid_angle, gm_error *err);

/* The angle of r1 r0ᵀ about the unit axis u, in (−π, π] (r1 r0ᵀ must be a rotation about u). */
double gm_so3_angle_about(const double r0[9], const double r1[9], const double u[3]);

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
