/* geomint oscillatory: highly oscillatory and multiscale problems (issue 12).
 *
 * Split potentials. A separable problem H = ½pᵀM⁻¹p + V(q) whose potential splits as
 * V = U + W, U slow and W fast (L = ½q̇ᵀMq̇ − U(q) − W(q); seed 000 §2.2.1), carries a
 * gm_split_potential in gm_problem.split. Every method that integrates separable problems
 * still integrates it (V = U + W is the problem's potential); the rows of family
 * "oscillatory" (variational IMEX, impulse / r-RESPA, mollified impulse, trigonometric and
 * variational trigonometric integrators) need the split, and the filtered ones a fast
 * quadratic part W = ½ qᵀΩ²q with Ω symmetric positive semidefinite, given as a matrix or a
 * diagonal. Ω (with the mass) is eigendecomposed once, when the integrator is created (LAPACK
 * dsyev); the filter values f(hν_k) are recomputed only when the step size changes.
 * gm_stats.force_evals counts the evaluations of ∇U; those of the fast part (Ω²q or ∇W, n per
 * step in the impulse rows) are not counted.
 *
 * Multiscale tools (seed 001 §5.7): Filon–Lobatto quadrature of oscillatory integrands and the
 * 1-D multiscale finite element method. */
#ifndef GEOMINT_OSCILLATORY_H
#define GEOMINT_OSCILLATORY_H

#include <stddef.h>

#include "geomint/core.h"
#include "geomint/ode.h"

#ifdef __cplusplus
extern "C" {
#endif

/* V = U + W. Callbacks take the problem's ctx. U is required; W is given by its callbacks or,
 * when omega is set, is ½ qᵀΩ²q (then fast/fast_gradient may be NULL and are not called). */
typedef struct gm_split_potential {
  double (*slow)(void *ctx, const double *q);                        /* U(q) */
  int (*slow_gradient)(void *ctx, const double *q, double *out);     /* ∇U(q) */
  double (*fast)(void *ctx, const double *q);                        /* W(q) */
  int (*fast_gradient)(void *ctx, const double *q, double *out);     /* ∇W(q) */
  int (*fast_hessian)(void *ctx, const double *q, double *hessian);  /* optional, d×d */
  /* optional fast quadratic part: Ω, borrowed; d×d row-major symmetric PSD, or its d diagonal
   * entries (≥ 0) when omega_is_diagonal */
  const double *omega;
  int omega_is_diagonal;
  /* optional diagonal mass matrix M (d entries > 0), borrowed; NULL: M = I. The problem's
   * kinetic energy must be ½ pᵀM⁻¹p (checked when an oscillatory integrator is created). */
  const double *mass;
} gm_split_potential;

/* Check a problem's split potential: separable with quadratic kinetic energy, U and W present,
 * Ω symmetric (to 1e-12 relative) and positive semidefinite (eigenvalues ≥ −1e-12·max|λ|),
 * masses positive and consistent with the kinetic energy. GM_EINVAL with a message. */
gm_status gm_split_potential_validate(const gm_problem *problem, gm_error *err);

/* Options of the oscillatory rows (after gm_integrator_create, before stepping). */

/* Number of Verlet substeps on the fast part (impulse / r-RESPA, mollified impulse).
 * n = 0 → GM_EINVAL; GM_EUNSUPPORTED for rows without substeps. */
gm_status gm_oscillatory_set_substeps(gm_integrator *it, size_t n);

/* The three equivalent forms of variational IMEX with a quadratic fast part (seed 000 §2.2):
 * the linear solve of implicit midpoint, Verlet with the modified mass M̃ = M + (hΩ/2)²
 * (Prop. 2.2.1), and the exact rotation by the modified frequency hω̃ = 2 arctan(hω/2)
 * (§2.2.5). GM_IMEX_AUTO (the default) takes the fastest measured one: the rotation when Ω is
 * diagonal or d ≤ 16, the modified mass otherwise (bench/oscillatory_imex_forms.c,
 * docs/oscillatory.md). */
typedef enum gm_imex_form {
  GM_IMEX_AUTO = 0,
  GM_IMEX_LINEAR_SOLVE,
  GM_IMEX_MODIFIED_MASS,
  GM_IMEX_MODIFIED_FREQUENCY
} gm_imex_form;
gm_status gm_oscillatory_set_imex_form(gm_integrator *it, gm_imex_form form);

/* A filter function of ξ = hν (ν an eigenfrequency of the fast part). */
typedef double (*gm_filter_fn)(double xi);

/* Replace the filters of a trigonometric row (GNI XIII (2.7)–(2.8)): φ filters the argument of
 * the slow force, ψ its weight in the position update; ψ0, ψ1 are taken as cos(ξ)ψ1 and
 * ψ(ξ)/sinc(ξ) (the symmetric choice, GNI XIII (2.10)). For the scalar variational
 * trigonometric row (vti-scalar) only φ is free and psi must be NULL (ψ = sinc²(ξ/2)/φ).
 * GM_EUNSUPPORTED for other rows. */
gm_status gm_oscillatory_set_filters(gm_integrator *it, gm_filter_fn phi, gm_filter_fn psi);

/* sinc ξ = sin ξ / ξ (1 at 0), with a series near 0. */
double gm_sinc(double xi);

/* Filon–Lobatto quadrature (the core routine behind the multiscale variational integrator) is
 * declared in geomint/core.h: gm_filon_lobatto_weights, gm_filon_lobatto. */

/* ---- 1-D multiscale finite elements (seed 001 §5.7.1, App. C) ------------------------------ */

/* Solve (a(x) u′)′ = f(x) on (0, 1), u(0) = u(1) = 0, by Galerkin on the uniform mesh of
 * n_elements elements (≥ 1), either with the multiscale shape functions (multiscale = 1): on
 * each element the solutions of (a φ′)′ = 0, φ(x) = ∫_{x_i}^x ds/a / ∫_{x_i}^{x_i+1} ds/a, so
 * the element stiffness is 1/∫_e 1/a (the harmonic mean) and the nodal values are exact; or
 * with the standard P1 hat functions (multiscale = 0, stiffness ∫_e a / h²). The integrals of
 * 1/a, a and f·φ use n_sub subintervals per element with 8-point Gauss–Legendre (choose them
 * shorter than a quarter of a's oscillation). nodal: n_elements + 1 values (written).
 * GM_EINVAL for n_elements = 0, n_sub = 0, a ≤ 0 or not finite somewhere (message in err). */
gm_status gm_msfem_1d(double (*a)(void *ctx, double x), double (*f)(void *ctx, double x),
                      void *ctx, size_t n_elements, int multiscale, size_t n_sub, double *nodal,
                      gm_error *err);

/* ---- multiscale variational integrator (seed 001 §5.7.2) --------------------------------- */

/* For the stiff spring pendulum in polar coordinates q = (a, θ), p = (m ȧ, m (l + a)² θ̇),
 * L = (m/2)(ȧ² + (l + a)²θ̇²) + m g (l + a) cos θ − (k/2)a² (the model spring-pendulum): the
 * Galerkin discrete Lagrangian on a(τ) = P(τ) + α sin ωτ + β cos ωτ (or the seed's
 * P(τ)(1 + α sin ωτ + β cos ωτ)), θ(τ) = T(τ), P and T polynomials of the given degree,
 * integrated by Filon–Lobatto quadrature; ω is fixed (0 in the options: √(k/m)). Update
 * equations and derivation: docs/oscillatory.md. */
typedef struct gm_msvi_options {
  double m, g, k, l;
  double omega;         /* 0: √(k/m) */
  size_t degree;        /* of P and T, 1..3 (default 2) */
  size_t filon_points;  /* 2..8 (default 3) */
  int additive;         /* 2 (default): the seed's product on the radius,
                           l + a = (l + P)(1 + α sin ωτ + β cos ωτ); 1: the additive space
                           a = P + α sin ωτ + β cos ωτ; 0: the seed's product on the stretch,
                           a = P (1 + α sin ωτ + β cos ωτ), whose Newton system fails to converge
                           on this problem (docs/oscillatory.md) */
  int start_from_additive; /* product spaces: start each step's Newton iteration from the
                              additive space's solution of the same step (default 0) */
} gm_msvi_options;
typedef struct gm_msvi gm_msvi;

gm_msvi_options gm_msvi_defaults(void); /* m = 1, g = 9.81, k = 10⁴, l = 1, degree 2, 3 points,
                                           product on the radius (additive = 2) */
gm_status gm_msvi_create(const gm_msvi_options *options, gm_msvi **out, gm_error *err);
void gm_msvi_free(gm_msvi *vi);
/* One step of size h from (q, p) (both 2 values, overwritten). Newton's method on the
 * discrete Euler–Lagrange system; GM_ENOCONV with a message when it fails. */
gm_status gm_msvi_step(gm_msvi *vi, double h, double *q, double *p);
const char *gm_msvi_errmsg(const gm_msvi *vi);
size_t gm_msvi_newton_iterations(const gm_msvi *vi); /* of the last step */

#ifdef __cplusplus
}
#endif
#endif
