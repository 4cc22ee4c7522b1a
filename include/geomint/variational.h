/* geomint variational: discrete mechanics around the variational integrators (the vi-* rows of
 * the method registry, family "variational").
 *
 * A discrete Lagrangian L_d(q0, q1; h) ≈ ∫_0^h L(q, q') dt defines the discrete Legendre
 * transforms p0 = −D₁L_d(q0, q1), p1 = D₂L_d(q0, q1) and the symplectic map (q0, p0) ↦ (q1, p1)
 * (seed 001 §2.3; Marsden & West, Acta Numerica 10 (2001) 357). Here:
 *   - the Legendre transforms of the built-in Galerkin discrete Lagrangians, and the partitioned
 *     Runge–Kutta tableau equivalent to a Galerkin discrete Lagrangian (seed 001 Thm 2.12);
 *   - user-supplied discrete Lagrangians with their slot derivatives, and a solver that steps
 *     them in position–momentum form;
 *   - continuous Legendre transforms (start from (q0, v0)), Noether momenta p·ξ_Q(q), and the
 *     constraint residual. */
#ifndef GEOMINT_VARIATIONAL_H
#define GEOMINT_VARIATIONAL_H

#include <stddef.h>

#include "geomint/core.h"
#include "geomint/methods.h"
#include "geomint/ode.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Galerkin discrete Lagrangians --------------------------------------------------------- */

/* The partitioned Runge–Kutta method (a, b, c for q; a_bar, b_bar for p) whose trajectory is
 * that of the Galerkin discrete Lagrangian with velocity polynomial interpolated on the n
 * distinct nodes c_1..c_n in [0, 1] (positions of degree n) and the interpolatory quadrature on
 * them (seed 001 Thm 2.12): b_i = ∫_0^1 l_i, a_ij = ∫_0^{c_i} l_j, ā_ij = b_j (1 − a_ji / b_i),
 * b̄ = b, l_j the Lagrange polynomials on the nodes. Gauss nodes give Gauss collocation. Free
 * with gm_tableau_free. GM_EINVAL for repeated nodes or a zero weight. */
gm_status gm_galerkin_prk_tableau(size_t n, const double *nodes, gm_tableau **out);

/* Discrete Legendre transforms of a variational row's discrete Lagrangian on a problem (a
 * Lagrangian one, or separable with quadratic kinetic energy, as L = ½vᵀMv − V):
 * p0 = −D₁L_d(q0, q1), p1 = D₂L_d(q0, q1) (either may be NULL), the inner control points of the
 * Galerkin curve solved by Newton's method. Forces and constraints are not included. */
gm_status gm_variational_legendre(const gm_method *method, const gm_problem *problem, double h,
                                  const double *q0, const double *q1, double *p0, double *p1,
                                  gm_error *err);

/* The discrete Lagrangian L_d(q0, q1; h) itself (same conditions). */
gm_status gm_variational_discrete_lagrangian(const gm_method *method, const gm_problem *problem,
                                             double h, const double *q0, const double *q1,
                                             double *value, gm_error *err);

/* α of a vi-alpha integrator (α in [0, 1]; 1/2 is the midpoint rule). */
gm_status gm_variational_set_alpha(gm_integrator *it, double alpha);

/* Symplectic-energy-momentum integrators (vi-sem-*): the discrete energy E_d their steps keep
 * (set by the first step, NaN before it or for other methods), E_d − E of the last step (round-off
 * unless the least-squares fallback was needed), and how many steps needed that fallback. */
double gm_variational_discrete_energy(const gm_integrator *it);
double gm_variational_last_energy_error(const gm_integrator *it);
size_t gm_variational_energy_fallbacks(const gm_integrator *it);
/* Steps where the energy equation fixed the step size only to worse than 1e-3 relative (its
 * h-derivative at the rounding level of E_d), so the previous step size was kept (0 for other
 * methods); see docs/variational.md. */
size_t gm_variational_unresolved_steps(const gm_integrator *it);
/* The largest |E_d − E| over the steps since the energy was set (NaN before it or for other
 * methods): what `geomint run` reports, relative to |E|, as the discrete energy error. */
double gm_variational_max_energy_error(const gm_integrator *it);

/* ---- user-supplied discrete Lagrangians ---------------------------------------------------- */

typedef struct gm_discrete_lagrangian {
  size_t dim;
  void *ctx; /* borrowed; passed to every callback */
  /* optional: L_d(q0, q1; h) */
  double (*value)(void *ctx, double h, const double *q0, const double *q1);
  /* required: the slot derivatives D₁L_d and D₂L_d (dim values each) */
  int (*d1)(void *ctx, double h, const double *q0, const double *q1, double *out);
  int (*d2)(void *ctx, double h, const double *q0, const double *q1, double *out);
  /* optional: ∂(D₁L_d)/∂q1 (dim × dim, row-major) for Newton's method; central differences of
   * d1 otherwise */
  int (*d1_jacobian)(void *ctx, double h, const double *q0, const double *q1, double *jac);
} gm_discrete_lagrangian;

/* p0 = −D₁L_d(q0, q1) and p1 = D₂L_d(q0, q1). GM_ECALLBACK when the callback fails. */
gm_status gm_discrete_legendre_minus(const gm_discrete_lagrangian *ld, double h, const double *q0,
                                     const double *q1, double *p0);
gm_status gm_discrete_legendre_plus(const gm_discrete_lagrangian *ld, double h, const double *q0,
                                    const double *q1, double *p1);

/* Steps a user discrete Lagrangian in position–momentum form: solve p_k = −D₁L_d(q_k, q_{k+1})
 * for q_{k+1} by Newton's method, then p_{k+1} = D₂L_d(q_k, q_{k+1}). All work arrays are
 * allocated at create time. ld is borrowed. */
typedef struct gm_dl_solver gm_dl_solver;
gm_status gm_dl_solver_create(const gm_discrete_lagrangian *ld, gm_dl_solver **out,
                              gm_error *err);
void gm_dl_solver_free(gm_dl_solver *solver);
/* One step of size h from (q, p), both overwritten by (q_{k+1}, p_{k+1}); unchanged on failure.
 * The Newton iteration starts from the previous step's increment when there is one. */
gm_status gm_dl_solver_step(gm_dl_solver *solver, double h, double *q, double *p);
size_t gm_dl_solver_newton_iterations(const gm_dl_solver *solver); /* over all steps */
const char *gm_dl_solver_errmsg(const gm_dl_solver *solver);

/* ---- continuous Legendre transform, Noether momenta, constraints --------------------------- */

/* p = ∂L/∂v(q, v) (separable problems: p = M v with M = (∇²T)⁻¹): the momentum to start a
 * variational integrator from (q0, v0). */
gm_status gm_lagrangian_momentum(const gm_problem *problem, const double *q, const double *v,
                                 double *p);
/* v with ∂L/∂v(q, v) = p, by Newton's method. */
gm_status gm_lagrangian_velocity(const gm_problem *problem, const double *q, const double *p,
                                 double *v);
/* The Noether momentum J_k = p·ξ_Q(q) of the problem's symmetry k at the state y = (q, p). For
 * a G-invariant discrete Lagrangian the discrete flow keeps it exactly (discrete Noether
 * theorem, seed 001 §1A). NaN when k is out of range or the generator fails. */
double gm_noether_momentum(const gm_problem *problem, size_t k, const double *y);
/* max_i |g_i(q)| at the state y = (q, p); 0 without constraints, NaN when g fails. */
double gm_constraint_residual(const gm_problem *problem, const double *y);

#ifdef __cplusplus
}
#endif
#endif
