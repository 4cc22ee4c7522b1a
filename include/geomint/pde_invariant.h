/* geomint pde: Lie-symmetry-preserving (invariant) finite-difference schemes by moving frames
 * (seed 004 "Invariant integrators"; notes/003-004 §2.4; Kim, BIT 47 (2007) 525 and
 * Physica D 237 (2008) 243; Chhay & Hamdouni, C. R. Mécanique 338 (2010) 97; Chhay, Hoarau,
 * Hamdouni & Sagaut, J. Comput. Phys. 230 (2011) 2174). Derivations: docs/pde.md.
 *
 * The pieces, each general (Burgers is the first user, the heat equation the second):
 *  - a scheme: a two-level residual N(m) on a stencil m of six points (t, x, u) — layer n at
 *    j−1, j, j+1 and layer n+1 at j−1, j, j+1 — written for stencils whose centres lie above each
 *    other (the "standard form": it reads only k = t_{n+1} − t_n and the spacings of each layer);
 *  - a group: its action on points, g·(t, x, u) = (t', x', u') with u' affine in u at fixed
 *    (t, x), and a moving frame ρ(m) (the element that takes m to a cross-section);
 *  - the invariantized scheme Ñ(m) = N(ρ(m)·m): since ρ(g·m) = ρ(m)·g⁻¹, Ñ(g·m) = Ñ(m), so the
 *    discrete solution maps to the discrete solution of the transformed data (equivariance).
 * A run marches layers of a mesh whose layers are flat (t constant) with the unknowns at the
 * interior points j = 1..n−2 of layer n+1 and the two end values given (Dirichlet data); each
 * step is a Newton solve with a tridiagonal Jacobian (one iteration is exact for an explicit
 * scheme). Pointer parameters are borrowed. Nothing here prints. */
#ifndef GEOMINT_PDE_INVARIANT_H
#define GEOMINT_PDE_INVARIANT_H

#include <stddef.h>

#include "geomint/core.h"

#ifdef __cplusplus
extern "C" {
#endif

#define GM_INV_MAX_PARAMS 6

typedef struct gm_inv_point {
  double t, x, u;
} gm_inv_point;

/* Layer n (old[0..2] = points j−1, j, j+1) and layer n+1 (next[0..2]). Explicit schemes read
 * only next[1] of the new layer. */
typedef struct gm_inv_stencil {
  gm_inv_point old[3], next[3];
} gm_inv_stencil;

/* ---- schemes -------------------------------------------------------------------------------- */
/* N(m) and ∂N/∂u of next[0], next[1], next[2] (dn[0..2]); nu ≥ 0 the viscosity. */
typedef double (*gm_inv_residual_fn)(const gm_inv_stencil *m, double nu, double dn[3]);
/* The largest stable k for spacing h, a velocity bound umax (relative to the mesh) and nu;
 * INFINITY when unconditionally stable. */
typedef double (*gm_inv_bound_fn)(double h, double umax, double nu);

typedef struct gm_inv_scheme {
  const char *name;      /* "ftcs", "lax-wendroff", "crank-nicolson", "heat-ftcs" */
  const char *equation;  /* "burgers" or "heat" */
  int is_explicit;       /* N depends on the new layer through next[1].u only, affinely */
  gm_inv_residual_fn residual;
  gm_inv_bound_fn step_bound;
  const char *bound_text; /* the bound in words, for messages */
  const char *reference;
} gm_inv_scheme;

size_t gm_inv_scheme_count(void);
const gm_inv_scheme *gm_inv_scheme_at(size_t i); /* NULL past the end */
gm_status gm_inv_scheme_find(const char *name, const gm_inv_scheme **out); /* GM_ENOTFOUND */

/* ---- groups and frames ---------------------------------------------------------------------- */
/* g(a)·p and ∂u'/∂u (du may be NULL). Returns 0, or non-zero when p is outside the domain of
 * g(a) (a projection with 1 − a₄t ≤ 0). act_inverse applies g(a)⁻¹. */
typedef int (*gm_inv_act_fn)(const double *a, gm_inv_point p, gm_inv_point *out, double *du);
/* The frame a = ρ(m) from the old layer and the position (t, x) of next[1] (values of the new
 * layer are not read: an explicit scheme stays explicit). Returns 0, or non-zero with a reason
 * in why (capacity cap) where the frame does not exist. */
typedef int (*gm_inv_frame_fn)(const gm_inv_stencil *m, double *a, char *why, size_t cap);

typedef struct gm_inv_group {
  const char *name;
  const char *equation;  /* the equation whose symmetries these are */
  size_t n_params;       /* <= GM_INV_MAX_PARAMS */
  const char *params;    /* the parameters in order, in words */
  gm_inv_act_fn act, act_inverse;
  gm_inv_frame_fn frame;
  const char *reference;
} gm_inv_group;

/* Burgers' G₀ = {g₁, g₂, g₄, g₅} (notes §2.4): a = (a₁, a₂, a₄, a₅), acting as
 * g(a) = g₄(a₄)∘g₅(a₅)∘g₂(a₂)∘g₁(a₁): t += a₁; x += a₂; (x, u) += a₅(t, 1);
 * (t, x, u) ↦ (t/(1−a₄t), x/(1−a₄t), (1−a₄t)u + a₄x). Frame: a₁ = −tⁿ_j, a₂ = −xⁿ_j,
 * a₅ = −σ/k (σ = x^{n+1}_j − xⁿ_j: the boost that stands the stencil upright), a₄ = −δ_x uⁿ_j
 * (the projection that makes the centred slope 0; exists where 1 + k δ_x uⁿ_j > 0). */
extern const gm_inv_group gm_inv_burgers_g0;
/* The heat equation u_t = ν u_xx with translations and the scaling (e^{2a₃}t, e^{a₃}x, u):
 * a = (a₁, a₂, a₃); frame a₁ = −tⁿ_j, a₂ = −xⁿ_j, a₃ = −ln h_j (spacing normalised to 1). */
extern const gm_inv_group gm_inv_heat_scaling;

/* The residual of a scheme, in standard form (group NULL) or invariantized Ñ(m) = N(ρ(m)·m),
 * with ∂/∂u of next[0..2] (chain rule through the affine u-action). GM_EDOMAIN with a message
 * where the frame does not exist or a point leaves the group's domain. */
gm_status gm_inv_residual(const gm_inv_scheme *scheme, const gm_inv_group *group, double nu,
                          const gm_inv_stencil *m, double *r, double dn[3], gm_error *err);

/* ---- exact solutions (initial and boundary data) -------------------------------------------- */
typedef double (*gm_inv_solution_fn)(double t, double x, const void *ctx);

/* Burgers' viscous front u = s − ½Δ tanh(Δ(x − x₀ − st)/(4ν)), s = ½(u_L + u_R),
 * Δ = u_L − u_R (travelling-wave solution, e.g. Whitham, Linear and Nonlinear Waves §4.3). */
typedef struct gm_inv_front {
  double u_left, u_right, x0, nu;
} gm_inv_front;
double gm_inv_burgers_front(double t, double x, const void *ctx);

/* Burgers' self-similar viscous shock, invariant under the projection group (derived in
 * docs/pde.md: w = τu − x is the projection's invariant, νw' = ½(w² − A²) in ξ = x/τ):
 * u = (x − A tanh(A x/(2ντ)))/τ, τ = t + t0. */
typedef struct gm_inv_shock {
  double A, t0, nu;
} gm_inv_shock;
double gm_inv_burgers_shock(double t, double x, const void *ctx);

/* The heat kernel u = exp(−x²/(4ν(t + t0)))/√(t + t0) of u_t = ν u_xx. */
typedef struct gm_inv_heat_kernel {
  double t0, nu;
} gm_inv_heat_kernel;
double gm_inv_heat_kernel_u(double t, double x, const void *ctx);

/* ---- runs ----------------------------------------------------------------------------------- */
typedef struct gm_inv_run_spec {
  const gm_inv_scheme *scheme;
  const gm_inv_group *frame_group; /* NULL: the standard form; else the invariantized one */
  double nu;
  size_t n;                        /* points per layer, >= 3 */
  double x_left, h, t0, k;         /* the orthogonal base mesh x_j = x_left + j h, tⁿ = t0 + nk */
  size_t n_steps;
  gm_inv_solution_fn exact;        /* initial and boundary data */
  const void *exact_ctx;
  /* Optional: the run's mesh and data are g·(base mesh, exact solution), g = g(transform_a)
   * of transform_group (NULL: g = identity). The points stay on flat layers. */
  const gm_inv_group *transform_group;
  const double *transform_a;
  int check_stability;             /* refuse a step above the scheme's bound (default 1) */
  double newton_tol;               /* default 1e-14 (relative) */
  size_t newton_max_iter;          /* default 20 */
} gm_inv_run_spec;

gm_inv_run_spec gm_inv_run_spec_defaults(void);

typedef struct gm_inv_run_stats {
  size_t steps, newton_iterations;
  double max_abs_u;   /* largest |u| over all layers */
  double step_bound;  /* the smallest stability bound met over the run */
} gm_inv_run_stats;

/* March n_steps and write the last layer: its time *t_out and its points x_out, u_out (n each;
 * any may be NULL). Errors: GM_EINVAL (NULL, n < 3, non-finite or non-positive h, k, nu < 0,
 * scheme and group of different equations, a step above the stability bound with
 * check_stability: the message gives the bound), GM_EDOMAIN (non-finite data or solution: the
 * message gives the step; a frame that does not exist: the point), GM_ENOCONV, GM_ESINGULAR,
 * GM_ENOMEM. */
gm_status gm_inv_run(const gm_inv_run_spec *spec, double *t_out, double *x_out, double *u_out,
                     gm_inv_run_stats *stats, gm_error *err);

/* Measured order of consistency: the one-step error from exact data divided by k (the local
 * truncation error, max over the layer) on the front (u_L, u_R, x0, ν) = (1, 0, 0, 0.1) over
 * [−1, 1] from t = 0.1, k = h/2, h = 0.02, 0.01, 0.005, 0.0025 (stability check off: one step);
 * *order is the least-squares slope of log τ against log h; tau (4 values) may be NULL. */
gm_status gm_inv_consistency_order(const gm_inv_scheme *scheme, const gm_inv_group *frame_group,
                                   double *order, double *tau, gm_error *err);

/* ---- the seed's experiments (docs/pde.md) --------------------------------------------------- */
/* B12, Galilean consistency: the front (u_L, u_R, x0) = (½, −½, 0) on [−2, 2] × [0, 1],
 * ν = 5e-3, h = 2e-2, k = ½h = 1e-2 (the seed's CFL ½ read as k/h); for each λ the mesh and
 * the data are boosted, (x, u) ↦ (x + λt, u + λ) — each step the frame moves by λk — the run
 * is made there (stability check off), and the last layer is mapped back by the inverse
 * boost. */
#define GM_INV_B12_N_LAMBDA 4
#define GM_INV_B12_N_SCHEMES 6 /* ftcs, lax-wendroff, crank-nicolson × {standard, invariant} */
typedef struct gm_inv_b12_row {
  const char *scheme;
  int invariant;
  double lambda;
  gm_status status;       /* GM_OK, or why the run stopped (blew up: GM_EDOMAIN) */
  size_t steps_done;
  double max_error;       /* max |u − u_exact| at t = 1 (NAN when the run stopped) */
  double max_diff_lambda0;/* max |u_λ − u_0| of the mapped-back layers (NAN likewise) */
  double overshoot;       /* max(max u − u_L, u_R − min u) at t = 1: oscillations */
  double step_bound;      /* the scheme's stability bound at the data seen */
} gm_inv_b12_row;
typedef struct gm_inv_b12 {
  size_t n;               /* points per layer (201) */
  double x[201];          /* the base mesh */
  gm_inv_b12_row rows[GM_INV_B12_N_SCHEMES * GM_INV_B12_N_LAMBDA];
  double u[GM_INV_B12_N_SCHEMES * GM_INV_B12_N_LAMBDA][201]; /* mapped back; NAN if stopped */
  double exact[201];
} gm_inv_b12;
extern const double gm_inv_b12_lambdas[GM_INV_B12_N_LAMBDA];
gm_status gm_inv_b12_run(gm_inv_b12 *out, gm_error *err);

/* B13, the projection group's self-similar shock (A, t0) = (0.5, 1) on [−1, 1], ν = 1e-2,
 * k = h = 5e-2, t = 0..2: standard against invariant FTCS. */
typedef struct gm_inv_b13 {
  size_t n; /* 41 */
  double x[41], exact[41], standard[41], invariant[41];
  double err_standard, err_invariant;         /* max |u − u_exact| at t = 2 */
  double err_shock_standard, err_shock_invariant; /* the same over |x| <= 0.2 */
} gm_inv_b13;
gm_status gm_inv_b13_run(gm_inv_b13 *out, gm_error *err);

#ifdef __cplusplus
}
#endif

#endif
