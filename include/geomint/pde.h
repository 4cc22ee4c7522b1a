/* geomint pde: multisymplectic integrators for Hamiltonian PDEs in 1+1 dimensions,
 *     𝕎 s_t + 𝕂 s_x = ∇_s S(s),   s(t, x) ∈ ℝ^d,  𝕎, 𝕂 skew d×d,
 * on a periodic grid x_i = x0 + i h, i = 0..n−1 (Bridges & Reich 2001; seed 004 §2.2 eq. 32
 * with notes/003-004 §2.2). Local conservation laws of the PDE: multisymplectic
 * ∂_t ω + ∂_x κ = 0 (34), energy ∂_t[S + ½ s_xᵀ𝕂s] + ∂_x[−½ s_tᵀ𝕂s] = 0 (35), momentum
 * ∂_t[½ s_xᵀ𝕎s] + ∂_x[−½ s_tᵀ𝕎s − S] = 0 (36).
 *
 * Plan/execute as the Yee solver (DESIGN §5a): gm_pde_create checks everything and allocates
 * everything (state, Newton work, banded LU); gm_pde_advance never allocates. Observers are
 * called every k steps. Pointer parameters are borrowed unless a comment says copied or owned.
 * Nothing here prints. */
#ifndef GEOMINT_PDE_H
#define GEOMINT_PDE_H

#include <stddef.h>

#include "geomint/core.h"
#include "geomint/pde_invariant.h" /* invariant (moving-frame) schemes for Burgers, heat */
#include "geomint/pde_moving_mesh.h" /* space–time adaptive variational integrator (wave) */
#include "geomint/pde_spectral.h"  /* Schrödinger, spectral Hodge star, tent-function VI */

#ifdef __cplusplus
extern "C" {
#endif

#define GM_PDE_MAX_DIM 6

/* ---- the equation --------------------------------------------------------------------------- */

/* S, ∇S and the Hessian ∇²S at one point s (d values). ctx is the equation's params. */
typedef double (*gm_pde_density_fn)(const double *s, const void *ctx);
typedef void (*gm_pde_gradient_fn)(const double *s, double *grad, const void *ctx);
typedef void (*gm_pde_hessian_fn)(const double *s, double *hess, const void *ctx); /* d×d */
/* The potential of a nonlinear wave equation u_tt − u_xx + V'(u) = 0 (scalar schemes). */
typedef double (*gm_pde_potential_fn)(double u, const void *ctx);

typedef struct gm_pde_equation {
  const char *name;
  size_t dim;                                   /* d, 1..GM_PDE_MAX_DIM */
  double W[GM_PDE_MAX_DIM * GM_PDE_MAX_DIM];    /* 𝕎, row-major d×d (stride d), skew */
  double K[GM_PDE_MAX_DIM * GM_PDE_MAX_DIM];    /* 𝕂, likewise */
  gm_pde_density_fn S;                          /* required */
  gm_pde_gradient_fn gradient;                  /* required */
  gm_pde_hessian_fn hessian;                    /* NULL: central differences of the gradient,
                                                   symmetrised; counted in the statistics */
  /* Wave equations only (s = (u, v = u_t, w = u_x)), for the scalar schemes LF/EC/MS: */
  gm_pde_potential_fn V, dV;                    /* NULL for other equations */
  /* Equations with a U(1) charge ∫|ψ|², ψ = s[norm_a] + i s[norm_b] (NLS): has_norm = 1. */
  int has_norm;
  size_t norm_a, norm_b;
  const void *params;                           /* borrowed, passed as ctx */
  /* Equations with a potential φ = s[gauge_phi] of a density u = s[gauge_u] (u = φ_x), as
   * KdV: φ → φ + a(t) with a compensating shift of another component is a symmetry of the
   * scheme, so the Preissmann Newton matrix has a null vector (docs/pde.md). has_gauge = 1
   * pins the gauge: the Preissmann box replaces the φ row of point 0 by φ₀ⁿ⁺¹ = φ₀ⁿ. The
   * initial data must then satisfy h Σ_i ½(u_i + u_{i+1}) = twist[gauge_phi] (the sum of the
   * w rows; checked by gm_pde_create). */
  int has_gauge;
  size_t gauge_phi, gauge_u;
  /* KdV u_t + u u_x + u_xxx = 0 in component gauge_u: the Zabusky–Kruskal row applies, and
   * gm_pde_energy / gm_pde_momentum are taken from u alone (gauge-free, see there). */
  int is_kdv;
} gm_pde_equation;

/* Sine-Gordon u_tt − u_xx + sin u = 0 (seed 004 eq. 39 with V = −cos u, sign restored per the
 * notes) as s = (u, v, w): 𝕎_uv = −1, 𝕂_uw = +1, S = ½(v² − w²) − cos u, which reads
 * −v_t + w_x = sin u, u_t = v, u_x = w. */
gm_pde_equation gm_pde_sine_gordon(void);

/* Cubic focusing NLS iψ_t + ψ_xx + 2|ψ|²ψ = 0 (Islas, Karpeev & Schober, J. Comput. Phys.
 * 173 (2001)) as s = (p, q, v, w), ψ = p + iq, v = p_x, w = q_x: 𝕎_pq = 1, 𝕂_pv = 𝕂_qw = −1,
 * S = ½(p² + q²)² + ½(v² + w²), which reads q_t − v_x = 2|ψ|²p, −p_t − w_x = 2|ψ|²q,
 * p_x = v, q_x = w. Its multisymplectic box scheme is the Preissmann row. */
gm_pde_equation gm_pde_nls(void);

/* KdV u_t + u u_x + u_xxx = 0 (Ascher & McLachlan, Appl. Numer. Math. 48 (2004) 255–269 §2;
 * Bridges & Reich 2001, in this normalisation) as s = (φ, u, v, w) with u = φ_x, v = u_x:
 * 𝕎_φu = ½, 𝕂_φw = 1, 𝕂_uv = −1, S = ½v² − uw + u³/6, which reads ½u_t + w_x = 0,
 * −½φ_t − v_x = −w + ½u², u_x = v, −φ_x = −u; eliminating φ, v, w gives KdV. The soliton is
 * u = 3c sech²(√c (x − ct)/2), φ = 6√c (tanh(√c (x − ct)/2) + 1), w = cu/2 (gauge φ_t = −cu).
 * On a periodic grid φ is twisted: twist[0] = ∫u. has_gauge (φ = 0, u = 1) and is_kdv set. */
gm_pde_equation gm_pde_kdv(void);

/* Check an equation: dim in range, 𝕎 and 𝕂 skew (exactly), S and gradient set, V and dV
 * both set or both NULL. GM_EINVAL with a message. */
gm_status gm_pde_equation_check(const gm_pde_equation *eq, gm_error *err);

/* ---- schemes as rows ------------------------------------------------------------------------ */

typedef enum gm_pde_scheme_kind {
  GM_PDE_PREISSMANN = 0, /* vector, implicit (Newton on the periodic ring, banded LU) */
  GM_PDE_EULER_BOX = 1,  /* vector, 𝕎 = 𝕎₊ + 𝕎₋, 𝕂 = 𝕂₊ + 𝕂₋ (upper/lower triangles) */
  GM_PDE_WAVE_LF = 2,    /* scalar wave equation, explicit leapfrog */
  GM_PDE_WAVE_EC = 3,    /* scalar, energy-conserving (pointwise scalar Newton) */
  GM_PDE_WAVE_MS = 4,    /* scalar, nine-point multisymplectic (Preissmann with v, w removed) */
  GM_PDE_KDV_ZK = 10,    /* KdV only: Zabusky–Kruskal explicit leapfrog in u */
  GM_PDE_BOX_SDIRK2 = 11, /* vector, implicit: the box in space, SDIRK2 in time (not
                            symplectic: the comparison row of the long NLS run) */
  GM_PDE_GAUSS_PRK = 12  /* vector, implicit: 2-stage Gauss–Legendre in t and in x (Reich
                            2000); the state lives at the spatial Gauss points, n even */
} gm_pde_scheme_kind;

typedef struct gm_pde_scheme {
  const char *name;        /* "preissmann", "euler-box", "lf", "ec", "ms" */
  gm_pde_scheme_kind kind;
  int order_t, order_x;    /* classical orders */
  int multisymplectic;     /* a discrete multisymplectic conservation law holds */
  int energy_conserving;   /* a discrete global energy is conserved exactly */
  int is_explicit;
  int scalar;              /* needs a wave equation (V, dV) */
  const char *law;         /* the discrete conservation law, in words */
  const char *reference;   /* source, equation */
} gm_pde_scheme;

size_t gm_pde_scheme_count(void);
const gm_pde_scheme *gm_pde_scheme_at(size_t i); /* NULL past the end */
/* By name (case-insensitive). GM_ENOTFOUND when none. */
gm_status gm_pde_scheme_find(const char *name, const gm_pde_scheme **out);

/* ---- the solver ----------------------------------------------------------------------------- */

typedef struct gm_pde_grid {
  size_t n;   /* grid points on the period (>= 4; odd for Preissmann when 𝕂 is singular) */
  double h;   /* Δx > 0 */
  double x0;  /* x of point 0 */
  double twist[GM_PDE_MAX_DIM]; /* s_{i+n} = s_i + twist (0: periodic). A sine-Gordon kink
                                   has twist (2π, 0, 0): u is periodic modulo 2π. */
} gm_pde_grid;

typedef struct gm_pde_options {
  double dt;               /* Δt > 0 */
  double newton_tol;       /* stop when max|Δs| <= tol·(1 + max|s|) (default 1e-13), or at
                              the round-off floor: max|Δs| <= 1e-9·(1 + max|s|) and no longer
                              halving */
  size_t newton_max_iter;  /* default 30 */
  int track_variations;    /* box schemes: carry two tangent variations U, V of the scheme
                              and record the multisymplectic residual per cell each step */
  double tangent_seed;     /* seed of the pseudo-random initial variations (default 1) */
  /* Dirichlet ends instead of the grid's ring (both 0, the default: periodic): bit a of
   * dirichlet_left / dirichlet_right holds component a at point 0 / point n−1 at its initial
   * value, and the points 0..n−1 span [x0, x0 + (n−1)h] with n − 1 cells. The scalar schemes
   * (lf, ec, ms) need bit 0 (u) at both ends. The Preissmann box needs d bits in all, which
   * replace the d equations of the missing cell: sine-Gordon u at both ends and v = u_t = 0 at
   * the left (left = 3, right = 1; then v^{n+½} = δ_t u at every node, so 0 at the right); NLS p, q
   * at both ends (3, 3). Not for euler-box, box-sdirk2, zk or equations with a gauge
   * (GM_EINVAL); the grid's twist must be 0. (Here rather than in gm_pde_grid so that
   * brace-initialised grids stay valid.) */
  unsigned dirichlet_left, dirichlet_right;
} gm_pde_options;

gm_pde_options gm_pde_options_defaults(void); /* dt 0 (must be set), tol 1e-13, 30, off, 1 */

typedef struct gm_pde gm_pde;

/* x of state point i: x0 + i h for every scheme but gauss-prk, whose points are the two
 * Gauss points of cell m = ⌊i/2⌋ = [x0 + 2mh, x0 + 2(m+1)h]: x0 + 2h(m + ½ ∓ √3/6). Sample
 * the initial data there. */
double gm_pde_point_x(const gm_pde_scheme *scheme, const gm_pde_grid *grid, size_t i);

/* gauss-prk only: moves Gauss-point data s (grid->n points × dim, in place) onto the physical
 * branch of the scheme's discrete dispersion relation, removing per component and wavenumber
 * the part on the spurious spatial branch (docs/pde.md). Point-sampled smooth data carry
 * O(H³) there, which makes fixed-grid results depend on Δt at that level. Exact for linear
 * equations, to leading order otherwise. GM_EINVAL (n odd or < 2, dim out of range, NULL),
 * GM_EDOMAIN (non-finite data), GM_ENOMEM. */
gm_status gm_pde_gauss_project(const gm_pde_grid *grid, size_t dim, double *s, gm_error *err);

/* Plan a run. s0: the initial state, n·d values, point i at s0[i·d .. i·d+d−1] (copied).
 * The scalar schemes read u = s[0] and u_t = s[1] and start with the Taylor step
 * u¹ = u⁰ + Δt u_t + ½Δt²(δ_x²u⁰ − V'(u⁰)).
 * Errors (GM_EINVAL, message in err): NULL arguments, a bad equation, n < 4, even n for the
 * Preissmann box when 𝕂 is singular (the Newton matrix is then singular on a periodic grid of
 * even n: the checkerboard (−1)^i c with 𝕂c = 0 is annihilated by the two-point averages; see
 * docs/pde.md), h or Δt not
 * finite and > 0, a scalar scheme with an equation without V, an LF step with Δt > Δx (the
 * CFL bound of its explicit wave part), a zk step above its stability bound (see kdv.c), odd n
 * for gauss-prk, an equation with a gauge whose twist is not its mass h Σ ū, bad Dirichlet
 * masks (see gm_pde_options), non-finite initial data (GM_EDOMAIN). */
gm_status gm_pde_create(const gm_pde_grid *grid, const gm_pde_equation *eq,
                        const gm_pde_scheme *scheme, const gm_pde_options *options,
                        const double *s0, gm_pde **out, gm_error *err);
void gm_pde_free(gm_pde *pde);

/* Called every `every` steps (and not at step 0); a non-zero return stops advance with
 * GM_ECALLBACK. */
typedef int (*gm_pde_observer_fn)(const gm_pde *pde, void *ctx);
gm_status gm_pde_add_observer(gm_pde *pde, size_t every, gm_pde_observer_fn fn, void *ctx,
                              gm_error *err);

/* Advance n_steps. Errors: GM_ENOCONV (Newton; message has step and residual), GM_ESINGULAR,
 * GM_EDOMAIN (the state became non-finite: message has the step), GM_ECALLBACK. After an
 * error the state is the last completed step. */
gm_status gm_pde_advance(gm_pde *pde, size_t n_steps, gm_error *err);

size_t gm_pde_steps(const gm_pde *pde);
double gm_pde_time(const gm_pde *pde);
size_t gm_pde_dim(const gm_pde *pde);
size_t gm_pde_n(const gm_pde *pde);
/* The state at the current step, n·d values (borrowed, valid until the next advance). For the
 * scalar schemes v = (uⁿ − uⁿ⁻¹)/Δt and w = (u_{i+1} − u_i)/h. */
const double *gm_pde_state(const gm_pde *pde);

/* Global monitors. Box schemes: E = h Σ_i [S(s_i) + ½ (δ_x⁺s_i)ᵀ𝕂 s_i],
 * I = h Σ_i ½ (δ_x⁺s_i)ᵀ𝕎 s_i (the densities of (35), (36)). Scalar schemes: the EC energy
 * E^{n−½} = h Σ ½((uⁿ−uⁿ⁻¹)/Δt)² + ½ δ_x⁺uⁿ⁻¹ δ_x⁺uⁿ + ½(V(uⁿ) + V(uⁿ⁻¹)) (conserved exactly
 * by EC) and I = −h Σ δ_x⁰uⁿ (uⁿ − uⁿ⁻¹)/Δt. */
double gm_pde_energy(const gm_pde *pde);
double gm_pde_momentum(const gm_pde *pde);

/* Multisymplectic residual of the last step (track_variations on, box schemes, at least two
 * steps taken for the Euler box): per cell, |R| / (sum of the |terms| of R), written to rel
 * (n values) when rel is non-NULL; returns the maximum, or −1 when not available. */
/* The charge of an equation with has_norm: box schemes h Σ_i |½(ψ_i + ψ_{i+1})|² (the
 * space-averaged ψ the Preissmann box conserves exactly), otherwise h Σ_i |ψ_i|². NAN when the
 * equation has no norm. */
double gm_pde_norm(const gm_pde *pde);

double gm_pde_ms_residual(const gm_pde *pde, double *rel);

/* The mass ∫u of an equation with a gauge (KdV): box schemes h Σ_i ½(u_i + u_{i+1}) (conserved
 * exactly by the Preissmann box: the sum of its φ rows), ZK h Σ_i u_i (conserved exactly on
 * each level). NAN for equations without a gauge. For KdV equations gm_pde_energy is
 * h Σ_i (u_i³/6 − ½(δ_x⁺u_i)²) and gm_pde_momentum h Σ_i ½u_i², the two other invariants of
 * KdV, from u alone (the box densities (35), (36) depend on the gauge of φ and w). */
double gm_pde_mass(const gm_pde *pde);

/* The densities of (35) and (36) on the cell averages s̄_{i+½} = ½(s_i + s_{i+1}) (the box's
 * own discretisation, as in gm_pde_local_residuals): E = h Σ_i [S(s̄) + ½(δ_x⁺s_i)ᵀ𝕂s̄],
 * I = h Σ_i ½(δ_x⁺s_i)ᵀ𝕎s̄. The nodal forms of gm_pde_energy see the nodal values, which on an
 * even grid carry an oscillation the box leaves free (NLS two-soliton, n = 200: nodal energy
 * error 8e-3, cell-averaged 1e-4). NAN for scalar schemes. */
double gm_pde_cell_energy(const gm_pde *pde);
double gm_pde_cell_momentum(const gm_pde *pde);

/* Local energy (35) and momentum (36) residuals of the last step per cell i+½, box schemes
 * (after at least one step): with s̄ the space average over the cell, s^{n+½} the time
 * average at a node,
 *   R_E = (E^{n+1}_{i+½} − Eⁿ_{i+½})/Δt + (F_{i+1} − F_i)/Δx,  E = S(s̄) + ½(δ_x⁺s)ᵀ𝕂s̄,
 *         F = −½(δ_t⁺s)ᵀ𝕂s^{n+½};
 *   R_I likewise with I = ½(δ_x⁺s)ᵀ𝕎s̄, G = −½(δ_t⁺s)ᵀ𝕎s^{n+½} − S(s^{n+½}).
 * Neither law is exact for the box schemes (only the multisymplectic one is): these monitor
 * the local defect, O(Δt² + Δx²) for Preissmann. energy, momentum: n values each (either may
 * be NULL). Returns GM_EUNSUPPORTED for scalar schemes or before the first step. */
gm_status gm_pde_local_residuals(const gm_pde *pde, double *energy, double *momentum);

typedef struct gm_pde_stats {
  size_t steps, newton_iterations, factorizations, hessian_fd_evaluations, gradient_evaluations;
  double max_newton_residual; /* largest final max|Δs| over the steps */
} gm_pde_stats;
gm_pde_stats gm_pde_get_stats(const gm_pde *pde);

#ifdef __cplusplus
}
#endif

#endif
