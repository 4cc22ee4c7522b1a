/* geomint pde: the space–time adaptive (moving-mesh, r-adaptive) variational integrator of the
 * wave equation u_tt = u_xx (seed 004 "Variational integrators": Lagrangian (62)
 * L = ½(u_t² − u_x²), rectangle quadrature and forward differences on a grid (tⁿ, xⁿ_j) whose
 * layers are flat in t). The discrete action varied in u, in x and in t gives the discrete
 * Euler–Lagrange (EL), momentum (X) and energy (E) equations — the seed's (66), (67a)–(67c),
 * lost in its extraction and derived in docs/pde.md — solved each step for t^{n+1}, x^{n+1}_j,
 * u^{n+1}_j by Newton with an analytic Jacobian (banded LU on the ring ordering, bordered by the
 * t^{n+1} row and column: O(n) memory and work per iteration).
 *
 * Three kinds (chosen by the caller; never a fallback from one to another; docs/pde.md has the
 * derivations and the measurements):
 * - GM_MOVING_MESH_SEED: the seed's equations as they are. Their X rows are, to leading order,
 *   −u_x times the EL rows (the continuous configurational equation is −u_x·EL) and vanish
 *   identically where u is locally constant (both 2×2 blocks of a node have determinant u_t²
 *   of its cell): the Newton matrix is singular there, nearly singular elsewhere.
 * - GM_MOVING_MESH_EQUIDISTRIBUTE: Tyranowski & Desbrun's cure ("R-adaptive multisymplectic and
 *   variational integrators", Mathematics 7 (2019) 642, their Lagrange-multiplier strategy):
 *   the mesh adaptation is a holonomic constraint on each layer, equal arc length of the cells
 *   in the metric dx² + α²du² (α = 0: uniform spacing), imposed with multipliers λⁿ_j in the EL
 *   and X equations. The constraint does not involve t and is invariant under x-translation,
 *   so Eⁿ = E^{n−1} and (periodic) Pⁿ = P^{n−1} would still hold exactly; but the layer's free
 *   translation is then fixed by the sum of the X rows alone, the seed's degeneracy again:
 *   measured, Newton fails within a few steps on the travelling pulse (it works with Dirichlet
 *   ends and α = 0, where the grid cannot move).
 * - GM_MOVING_MESH_TIME_ADAPTIVE: the X rows replaced by x^{n+1}_j = xⁿ_j (the grid stays),
 *   t^{n+1} still from the energy equation: Eⁿ = E^{n−1} to the Newton tolerance, the momentum
 *   law not imposed (its drift is measured). The regularisation that works.
 *
 * Plan/execute (DESIGN §5a): create allocates everything, advance never allocates. Pointer
 * parameters are borrowed unless said otherwise. Nothing here prints. */
#ifndef GEOMINT_PDE_MOVING_MESH_H
#define GEOMINT_PDE_MOVING_MESH_H

#include <stddef.h>

#include "geomint/core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum gm_moving_mesh_kind {
  GM_MOVING_MESH_SEED = 0,
  GM_MOVING_MESH_EQUIDISTRIBUTE = 1,
  GM_MOVING_MESH_TIME_ADAPTIVE = 2
} gm_moving_mesh_kind;

typedef struct gm_moving_mesh_options {
  gm_moving_mesh_kind kind;
  double dt;              /* the first step t¹ − t⁰ (the later ones adapt), finite, > 0 */
  double alpha;           /* EQUIDISTRIBUTE: weight of du² in the arc length, >= 0 */
  int dirichlet;          /* 0: periodic (x_{j+n} = x_j + length); 1: u and x held at both ends */
  double newton_tol;      /* max|Δ(u, x, t)| <= tol·(1 + max|u, x, t|), default 1e-12 */
  size_t newton_max_iter; /* default 30 */
} gm_moving_mesh_options;

gm_moving_mesh_options gm_moving_mesh_options_defaults(void); /* SEED, dt 0 (must be set) */

/* The largest first step the start allows: the layer-1 Taylor step and the first strip's
 * energy need Δt <= min_j Δx_j (the wave speed is 1); create refuses larger ones. */
double gm_moving_mesh_dt_bound(size_t n, const double *x, double length, int dirichlet);

typedef struct gm_moving_mesh gm_moving_mesh;

/* n nodes x (strictly increasing; periodic: x[n−1] < x[0] + length), u = u0 and u_t = ut0 there
 * (all copied). Layer 1 is the Taylor step u¹ = u⁰ + Δt u_t + ½Δt² u_xx (three-point u_xx on
 * the uneven grid; Dirichlet ends held) on the same nodes. GM_EINVAL: NULL, n < 4 or
 * > 2^24, non-increasing x, length (periodic) not finite > 0, dt not finite > 0 or above
 * gm_moving_mesh_dt_bound (the message prints it), alpha < 0 or NaN, bad Newton options;
 * GM_EDOMAIN: non-finite data; GM_ENOMEM. */
gm_status gm_moving_mesh_create(size_t n, const double *x, double length, const double *u0,
                                const double *ut0, const gm_moving_mesh_options *options,
                                gm_moving_mesh **out, gm_error *err);
void gm_moving_mesh_free(gm_moving_mesh *m);

/* Called after every `every` steps; a non-zero return stops advance with GM_ECALLBACK. */
typedef int (*gm_moving_mesh_observer_fn)(const gm_moving_mesh *m, void *ctx);
gm_status gm_moving_mesh_set_observer(gm_moving_mesh *m, size_t every,
                                      gm_moving_mesh_observer_fn fn, void *ctx, gm_error *err);

/* n_steps more layers. GM_ENOCONV (Newton: step, time, residual), GM_ESINGULAR, GM_EDOMAIN (the
 * grid folds: x_{j+1} <= x_j or t^{n+1} <= tⁿ, or a non-finite value), GM_ECALLBACK. After an
 * error the layers are the last completed ones and gm_moving_mesh_get_stats counts the failed
 * step. */
gm_status gm_moving_mesh_advance(gm_moving_mesh *m, size_t n_steps, gm_error *err);

size_t gm_moving_mesh_n(const gm_moving_mesh *m);
double gm_moving_mesh_time(const gm_moving_mesh *m);     /* t of the newest layer */
const double *gm_moving_mesh_x(const gm_moving_mesh *m); /* its nodes (borrowed until advance) */
const double *gm_moving_mesh_u(const gm_moving_mesh *m);
/* The discrete energy Eⁿ = Σ_cells ½Δx(u_t² + u_x²) and momentum Pⁿ = −Σ_cells Δx u_t u_x of
 * the strip between the two newest layers (u_t along the moving node, u_x the layer's forward
 * difference; docs/pde.md). */
double gm_moving_mesh_energy(const gm_moving_mesh *m);
double gm_moving_mesh_momentum(const gm_moving_mesh *m);

typedef struct gm_moving_mesh_stats {
  size_t steps, newton_iterations, failed_steps;
  double max_residual; /* largest final max-norm residual of the solved equations */
} gm_moving_mesh_stats;
gm_moving_mesh_stats gm_moving_mesh_get_stats(const gm_moving_mesh *m);

/* The conditioning of the next step's Newton matrix at its start guess (constant-velocity
 * extrapolation of t, x, u; λ = 0), rows scaled to unit max norm: smallest singular value
 * and 2-norm condition number. A diagnostic only (dense SVD): GM_EINVAL for n > 512. */
gm_status gm_moving_mesh_conditioning(gm_moving_mesh *m, double *sigma_min, double *cond,
                                      gm_error *err);

/* Nodes equidistributing the arc length of u on [x0, x0 + length] in the metric
 * dx² + α²du² (periodic: x[0] = x0 and the ring closes; Dirichlet: x[0] = x0,
 * x[n−1] = x0 + length), from `samples` >= 16n evaluations of u (trapezoid arc length, linear
 * inversion). The start grid of GM_MOVING_MESH_EQUIDISTRIBUTE. */
typedef double (*gm_moving_mesh_fn)(double x, const void *ctx);
gm_status gm_moving_mesh_equidistribute(size_t n, double x0, double length, double alpha,
                                        int dirichlet, gm_moving_mesh_fn u, const void *ctx,
                                        size_t samples, double *x, gm_error *err);

/* ---- the travelling-pulse experiment (docs/pde.md, `geomint pde moving-mesh`) ------------- */
/* u = exp(−(x − 10 − t)²) on [0, 20) periodic (u_t = −u_x at t = 0), or on [0, 20] with u held
 * at both ends; ramp = 1 instead takes u = sin(πx/5 − πt/5) + 2t (u_t >= 2 − π/5 > 0 everywhere:
 * no cell with u_t = 0). n nodes equidistributed for alpha (uniform for alpha = 0), first step
 * Δt = cfl·min Δx. */
typedef struct gm_moving_mesh_pulse {
  size_t n;
  double cfl;
  gm_moving_mesh_kind kind;
  double alpha;
  int dirichlet, ramp;
} gm_moving_mesh_pulse;

/* The exact (d'Alembert) solution of the pulse set-up at (x, t). */
double gm_moving_mesh_pulse_exact(const gm_moving_mesh_pulse *p, double x, double t);
/* Create the solver of the set-up (errors as gm_moving_mesh_create). */
gm_status gm_moving_mesh_pulse_create(const gm_moving_mesh_pulse *p, gm_moving_mesh **out,
                                      gm_error *err);

typedef struct gm_moving_mesh_pulse_result {
  gm_status status;  /* of the run: GM_OK or the failed step's error (message in err) */
  size_t steps;      /* completed */
  double t;          /* of the newest layer */
  double max_rel_energy, max_rel_momentum; /* max over the steps of |E − E⁰|/E⁰, |P − P⁰|/|P⁰| */
  double max_error;  /* max |u − exact| on the newest layer */
  double newton_per_step, min_dt, max_dt;
} gm_moving_mesh_pulse_result;

/* Run the set-up for `steps` steps (observer fn every step, may be NULL). A failed step is not
 * an error of this function: it ends the run and is in result->status and err's message.
 * Returns an error only for a set-up create refuses. */
gm_status gm_moving_mesh_pulse_run(const gm_moving_mesh_pulse *p, size_t steps,
                                   gm_moving_mesh_observer_fn fn, void *ctx,
                                   gm_moving_mesh_pulse_result *result, gm_error *err);

#ifdef __cplusplus
}
#endif

#endif
