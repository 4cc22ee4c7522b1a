/* Private helpers of the Routh reduction files (routh.c, routh_rsprk.c, routh_discrete.c). */
#ifndef GM_REDUCTION_INTERNAL_H
#define GM_REDUCTION_INTERNAL_H

#include "geomint/reduction.h"

/* Everything the reduced steppers need at one shape point x for one μ. */
typedef struct gm_routh_shape {
  double inertia[GM_ROUTH_MAX_GROUP * GM_ROUTH_MAX_GROUP];                 /* 𝕀 */
  double inertia_inv_mu[GM_ROUTH_MAX_GROUP];                               /* 𝕀⁻¹μ */
  double conn[GM_ROUTH_MAX_GROUP * GM_ROUTH_MAX_SHAPE];                    /* A, k×n */
  double dconn[GM_ROUTH_MAX_GROUP * GM_ROUTH_MAX_SHAPE * GM_ROUTH_MAX_SHAPE]; /* ∂A^a_i/∂x_l */
  double kinetic[GM_ROUTH_MAX_SHAPE * GM_ROUTH_MAX_SHAPE];                 /* K */
  double dkinetic[GM_ROUTH_MAX_SHAPE * GM_ROUTH_MAX_SHAPE * GM_ROUTH_MAX_SHAPE]; /* ∂_lK_ij at (l·n+i)·n+j */
  double amended, amended_grad[GM_ROUTH_MAX_SHAPE];                        /* V_μ, ∇V_μ */
} gm_routh_shape;

gm_status gm_routh_check(const gm_routh_system *sys, gm_error *err);
gm_status gm_routh_shape_eval(const gm_routh_system *sys, const double *mu, const double *x,
                              gm_routh_shape *o, gm_error *err);
/* β_ij = μ_a(∂_iA^a_j − ∂_jA^a_i) from dconn */
void gm_routh_beta(size_t k, size_t n, const double *mu, const double *dconn, double *beta);
/* Gaussian elimination with partial pivoting on a (n×n, destroyed), b (n×nrhs, overwritten by
 * the solution); nonzero when a pivot is zero. No allocation. */
int gm_routh_small_solve(size_t n, double *a, double *b, size_t nrhs);
/* ∂M/∂x_l (n blocks of (k+n)²) by the callback or central differences; nonzero on failure */
int gm_routh_metric_dx(const gm_routh_system *sys, const double *x, double *dm);

#endif
