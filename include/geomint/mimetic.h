/* geomint mimetic: the mimetic spectral framework on a one-dimensional element, and the time
 * integrators built on it.
 *
 * Source: A. Palha and M. Gerritsma, "A mimetic spectral element solver for Hamiltonian
 * systems" (seed 003), §4 (the framework) and §5 (the integrators). On the reference element
 * ξ ∈ [−1, 1]:
 *   - a grid is n+1 ascending nodes ξ_0 = −1 < … < ξ_n = 1 and the n edges [ξ_{i−1}, ξ_i];
 *   - 0-forms are expanded in the nodal (Lagrange) basis l_i(ξ), l_i(ξ_j) = δ_ij;
 *   - 1-forms g(ξ) dξ are expanded in the edge (histopolation) basis (seed 003 eq. 4.10)
 *       e_i(ξ) = −Σ_{k=0}^{i−1} l_k'(ξ),  i = 1..n,  with  ∫_{ξ_{j−1}}^{ξ_j} e_i dξ = δ_ij (4.11);
 *   - the reduction ℛ samples a 0-form at the nodes and integrates a 1-form over the edges
 *     (4.1); the reconstruction ℐ expands a cochain in the basis; ℛℐ = Id;
 *   - the incidence matrix (the coboundary d of cochains) maps nodal values to edge values,
 *     (d c)_i = c_i − c_{i−1}; it commutes with ℛ and ℐ: ℛ(dφ) = d ℛφ and (ℐc)' = ℐ(d c)
 *     (the edge-basis identity d l_i = e_i − e_{i+1}, eq. 4.15).
 * A time element of degree p has the primal Gauss–Lobatto grid (p+1 nodes) and the dual
 * "extended Gauss" grid (the p Gauss–Legendre nodes and the two endpoints, §4.4.2).
 *
 * Everything here is independent of the ODE driver except the last section (the integrators
 * mimetic-canonical-p and mimetic-galerkin-p). Pointers are borrowed unless said otherwise;
 * nothing prints. */
#ifndef GEOMINT_MIMETIC_H
#define GEOMINT_MIMETIC_H

#include <stddef.h>

#include "geomint/core.h"
#include "geomint/ode.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest number of nodes of a grid (degree 63). */
#define GM_MIMETIC_MAX_NODES 64

/* ---- a grid on [−1, 1] ------------------------------------------------------------------ */

typedef struct gm_mimetic_grid gm_mimetic_grid;

/* A grid on n_nodes (2 ≤ n_nodes ≤ GM_MIMETIC_MAX_NODES) strictly ascending nodes (copied),
 * the first −1 and the last 1. GM_EINVAL with a message in err otherwise. */
gm_status gm_mimetic_grid_create(size_t n_nodes, const double *nodes, gm_mimetic_grid **out,
                                 gm_error *err);
void gm_mimetic_grid_free(gm_mimetic_grid *grid);
size_t gm_mimetic_grid_n_nodes(const gm_mimetic_grid *grid);
size_t gm_mimetic_grid_n_edges(const gm_mimetic_grid *grid);  /* n_nodes − 1 */
const double *gm_mimetic_grid_nodes(const gm_mimetic_grid *grid); /* borrowed */

/* Nodal basis l_0..l_n at ξ (n_nodes values written), and its derivative l_0'..l_n'. */
gm_status gm_mimetic_nodal_basis(const gm_mimetic_grid *grid, double xi, double *values);
gm_status gm_mimetic_nodal_basis_derivative(const gm_mimetic_grid *grid, double xi,
                                            double *values);
/* Edge basis e_1..e_n at ξ (n_edges values written; values[i−1] = e_i(ξ)). */
gm_status gm_mimetic_edge_basis(const gm_mimetic_grid *grid, double xi, double *values);

/* The incidence matrix E (n_edges × n_nodes, row-major): E[i][i] = −1, E[i][i+1] = 1, so that
 * the coboundary of a 0-cochain c is E c. */
void gm_mimetic_incidence(const gm_mimetic_grid *grid, double *incidence);
/* c1 = E c0: (c1)_i = (c0)_{i+1} − (c0)_i, i = 0..n_edges−1. */
void gm_mimetic_coboundary(const gm_mimetic_grid *grid, const double *c0, double *c1);

/* A scalar function of ξ (a 0-form, or the density g of a 1-form g dξ). */
typedef double (*gm_scalar_fn)(void *ctx, double xi);
/* Reduction of a 0-form: its values at the nodes (n_nodes written). */
gm_status gm_mimetic_reduce_0form(const gm_mimetic_grid *grid, gm_scalar_fn f, void *ctx,
                                  double *c0);
/* Reduction of a 1-form g dξ: ∫ g over each edge by an n_quad-point Gauss rule per edge
 * (exact for polynomial g of degree ≤ 2 n_quad − 1); n_edges written. */
gm_status gm_mimetic_reduce_1form(const gm_mimetic_grid *grid, gm_scalar_fn g, void *ctx,
                                  size_t n_quad, double *c1);
/* Reconstruction at ξ: Σ c0_i l_i(ξ), and Σ c1_i e_i(ξ) (the density of the 1-form). */
gm_status gm_mimetic_reconstruct_0form(const gm_mimetic_grid *grid, const double *c0, double xi,
                                       double *value);
gm_status gm_mimetic_reconstruct_1form(const gm_mimetic_grid *grid, const double *c1, double xi,
                                       double *value);

/* ---- a time element of degree p --------------------------------------------------------- */

typedef struct gm_time_element {
  size_t degree;                 /* p ≥ 1 */
  gm_mimetic_grid *primal;       /* owned: the p+1 Gauss–Lobatto–Legendre nodes */
  gm_mimetic_grid *dual;         /* owned: −1, the p Gauss–Legendre nodes, 1 (p+2 nodes) */
  double *gauss_nodes;           /* owned: the p interior dual nodes τ̃_1..τ̃_p, ascending */
  double *gauss_weights;         /* owned: their Gauss weights w_1..w_p (sum 2) */
} gm_time_element;

/* 1 ≤ degree ≤ GM_MIMETIC_MAX_NODES − 2. */
gm_status gm_time_element_create(size_t degree, gm_time_element **out, gm_error *err);
void gm_time_element_free(gm_time_element *element);

/* ---- the mimetic time integrators (rows mimetic-canonical-p and mimetic-galerkin-p) ------ */

/* Dense output of a mimetic integrator: the polynomial y_h(t) = Σ_k y^k l_k(τ) of the last
 * step taken (τ = 2(t − t_n)/h − 1 on the step from t_n to t_n + h), evaluated at t (written
 * into y, gm_problem_state_size values). t should lie in the last step (values outside it are
 * extrapolations). GM_EUNSUPPORTED for other methods, GM_EINVAL before the first step or after
 * gm_integrator_set_state. */
gm_status gm_mimetic_dense_output(const gm_integrator *it, double t, double *y);

/* Number of Gauss points of the quadrature of the Galerkin integrals: ∫ f(y_h(τ)) l̃_j(τ) dτ of
 * mimetic-galerkin-p, and ∫_0^1 ∇H(y_0 + s(y_1 − y_0)) ds of avf (n_points ≥ 1). The default
 * (GM_QUADRATURE_DEFAULT) is 2p + 6 points for mimetic-galerkin-p and 8 for avf (= p = 1): the
 * integrand is a polynomial of degree pν − 1 when H is a polynomial of degree ν, so the default
 * is exact, and H is kept to round-off, for every polynomial H of degree ν ≤ 4 + 12/p (quartic
 * potentials at any p; ν ≤ 16 for avf). For a non-polynomial H the quadrature error makes the
 * energy error O((hω)^{2Q}) per step instead of 0; see docs/mimetic.md for measured values.
 * GM_EUNSUPPORTED for methods without such an integral. */
#define GM_QUADRATURE_DEFAULT 0
gm_status gm_integrator_set_quadrature(gm_integrator *it, size_t n_points);
/* The number of points in use (0 for methods without the option). */
size_t gm_integrator_quadrature(const gm_integrator *it);

#ifdef __cplusplus
}
#endif
#endif
