/* geomint ode: problem descriptions, the integrator driver, observers and statistics.
 *
 * A problem is a plain struct of callbacks with a void *ctx (DESIGN §5). The kinds:
 *   first order   y' = f(t, y),                           state y of length dim;
 *   Poisson       y' = S(y)∇H(y), S skew-symmetric,       state y of length dim;
 *   Hamiltonian   H(q, p) with ∇_q H and ∇_p H,           state (q, p) of length 2·dim;
 *   separable     H = T(p) + V(q) with ∇T and ∇V,         state (q, p) of length 2·dim;
 *   Lagrangian    L(q, v) with ∂L/∂q and ∂L/∂v,           state (q, p) of length 2·dim,
 *                 p = ∂L/∂v the momentum (the discrete one for variational integrators).
 * separable ⊂ Hamiltonian ⊂ Poisson (S = J⁻¹) ⊂ first order: a method that accepts a more
 * general kind integrates the more special ones. Lagrangian problems go to variational
 * integrators.
 * Callbacks returning int return 0 on success; anything else stops the run with GM_ECALLBACK. */
#ifndef GEOMINT_ODE_H
#define GEOMINT_ODE_H

#include <stddef.h>
#include <stdio.h>

#include "geomint/core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum gm_problem_kind {
  GM_PROBLEM_FIRST_ORDER = 1u << 0,
  GM_PROBLEM_HAMILTONIAN = 1u << 1,
  GM_PROBLEM_SEPARABLE = 1u << 2,
  GM_PROBLEM_POISSON = 1u << 3,
  GM_PROBLEM_LAGRANGIAN = 1u << 4,
  GM_PROBLEM_RIGID_BODY = 1u << 5 /* mechanical system on SO(3) or SO(3) × R³ (see below) */
} gm_problem_kind;
#define GM_N_PROBLEM_KINDS 6

/* "first-order", "hamiltonian", "separable", "poisson", "lagrangian", "rigid-body" */
const char *gm_problem_kind_name(gm_problem_kind kind);

/* A conserved (or monitored) quantity of the full state y. */
typedef struct gm_invariant {
  const char *name;
  double (*value)(void *ctx, const double *y);
} gm_invariant;

/* A symmetry of a Lagrangian: the infinitesimal generator ξ_Q(q) of a group action that leaves
 * L invariant. Its (discrete) Noether momentum p·ξ_Q(q) is conserved. */
typedef struct gm_symmetry {
  const char *name;
  int (*generator)(void *ctx, const double *q, double *xi);
} gm_symmetry;

/* A state that does not live in Rⁿ (DESIGN §5b): how it is stored, the dimension of the
 * manifold, a chart around any of its points, and how far a stored state is from it. Order,
 * reversibility and symplecticity are measured in the chart exactly as for Rⁿ (where the chart
 * is y − base). For phase spaces the chart coordinates are canonical (q then p), so that one
 * step's Jacobian in them satisfies JᵀΩJ = Ω for a symplectic method. All callbacks get the
 * problem's ctx; they return 0, or non-zero where the chart does not reach y. */
typedef struct gm_state_space {
  const char *name;      /* "T*SO(3)", ... */
  size_t state_size;     /* numbers stored per state */
  size_t chart_dim;      /* dimension of the manifold */
  /* z (chart_dim) = coordinates of y in the chart centred at base (z = 0 at y = base) */
  int (*to_chart)(void *ctx, const double *base, const double *y, double *z);
  /* y = the point with coordinates z in the chart centred at base */
  int (*from_chart)(void *ctx, const double *base, const double *z, double *y);
  /* distance of a stored state from the manifold (0 on it) and what it measures */
  double (*defect)(void *ctx, const double *y);
  const char *defect_name; /* "|R^T R - I|" */
  /* optional: the name of stored component i (CSV columns), e.g. "R11" or "Pi1" */
  const char *const *component_names;
} gm_state_space;

typedef struct gm_problem {
  gm_problem_kind kind;
  size_t dim;  /* first order: length of y; Hamiltonian kinds: degrees of freedom d */
  void *ctx;   /* borrowed; passed to every callback */

  /* first order (required for that kind) */
  int (*rhs)(void *ctx, double t, const double *y, double *dydt);
  /* optional: ∂f/∂y, dim×dim row-major */
  int (*rhs_jacobian)(void *ctx, double t, const double *y, double *jacobian);

  /* Hamiltonian (required for that kind) */
  double (*hamiltonian)(void *ctx, const double *q, const double *p);
  int (*dh_dq)(void *ctx, const double *q, const double *p, double *out);
  int (*dh_dp)(void *ctx, const double *q, const double *p, double *out);
  /* optional: Hessian of H in the variables (q, p), 2d×2d row-major */
  int (*hamiltonian_hessian)(void *ctx, const double *q, const double *p, double *hessian);

  /* separable (required for that kind) */
  double (*kinetic)(void *ctx, const double *p);
  double (*potential)(void *ctx, const double *q);
  int (*kinetic_gradient)(void *ctx, const double *p, double *out);
  int (*potential_gradient)(void *ctx, const double *q, double *out);
  /* optional: d×d row-major Hessians */
  int (*kinetic_hessian)(void *ctx, const double *p, double *hessian);
  int (*potential_hessian)(void *ctx, const double *q, double *hessian);

  /* Poisson (required for that kind): y' = S(y)∇H(y) */
  double (*poisson_energy)(void *ctx, const double *y);                 /* H(y) */
  int (*poisson_gradient)(void *ctx, const double *y, double *gradient); /* ∇H(y) */
  int (*structure_matrix)(void *ctx, const double *y, double *s);       /* dim×dim, skew */
  /* optional: ∇²H, dim×dim */
  int (*poisson_hessian)(void *ctx, const double *y, double *hessian);

  /* Lagrangian (required for that kind) */
  double (*lagrangian)(void *ctx, const double *q, const double *v);
  int (*dl_dq)(void *ctx, const double *q, const double *v, double *out);
  int (*dl_dv)(void *ctx, const double *q, const double *v, double *out);
  /* optional: second derivatives of L in (q, v), 2d×2d row-major */
  int (*lagrangian_hessian)(void *ctx, const double *q, const double *v, double *hessian);
  /* optional: holonomic constraints g(q) = 0 (g: R^dim → R^n_constraints) and ∂g/∂q */
  size_t n_constraints;
  int (*constraint)(void *ctx, const double *q, double *g);
  int (*constraint_jacobian)(void *ctx, const double *q, double *jacobian); /* n_c × dim */
  /* optional: the constraint curvature Σ_a λ_a ∇²g_a(q) (dim × dim) that Newton's method on a
   * constrained variational step needs; missing, central differences of constraint_jacobian are
   * used and counted in fd_jacobians */
  int (*constraint_hessian)(void *ctx, const double *q, const double *lambda, double *out);
  /* optional: a non-conservative force F(t, q, v) (Lagrange–d'Alembert) */
  int (*force)(void *ctx, double t, const double *q, const double *v, double *f);
  /* optional: symmetries of L, whose Noether momenta are monitored */
  size_t n_symmetries;
  const gm_symmetry *symmetries;   /* borrowed, n_symmetries entries */

  /* separable: set when T(p) = ½ pᵀM⁻¹p with a constant M, so ∇T is linear (it lets Gauss
   * methods iterate on positions only, GM_SOLVER_FIXED_POINT_POSITIONS) */
  int kinetic_is_quadratic;

  /* rigid body (GM_PROBLEM_RIGID_BODY): dim = 3 (attitude R ∈ SO(3)) or 6 (and a position
   * x ∈ R³); state y = (R (9, row-major, body to space), x, Π (3, body angular momentum), p),
   * Π = J Ω with Ω the body angular velocity, p = m ẋ. H = ½ Π·J⁻¹Π + |p|²/(2m) + V(R, x).
   * Equations: R' = R Ω̂, Π' = Π × Ω − g, x' = p/m, p' = −∂V/∂x, where g is the gradient of
   * V in the body frame: d/dε V(R exp(ε η̂), x)|₀ = g·η (−g is the torque). */
  double inertia[9];  /* J, symmetric positive definite (body frame, row-major) */
  double mass;        /* m > 0 when dim = 6 */
  /* optional (NULL: a free body): V(R, x) and its gradients g (body frame) and ∂V/∂x
   * (dim = 6 only; x and force_x are NULL when dim = 3) */
  double (*rigid_potential)(void *ctx, const double *r, const double *x);
  int (*rigid_potential_gradient)(void *ctx, const double *r, const double *x, double *g,
                                  double *force_x);
  /* optional, every kind: a state space other than Rⁿ (rigid bodies set one: T*SO(3)) */
  const gm_state_space *space;

  /* optional, every kind */
  size_t n_invariants;
  const gm_invariant *invariants;                 /* borrowed, n_invariants entries */
  int (*exact)(void *ctx, double t, double *y);   /* exact solution from the initial state */

  /* optional, separable: the potential split V = U + W (slow + fast) that the oscillatory
   * rows need; borrowed (geomint/oscillatory.h) */
  const struct gm_split_potential *split;
  /* optional, separable: "central body + perturbed orbits" (geomint/celestial.h): the masses
   * and G of an n-body problem whose body 0 dominates, for the near-integrable rows */
  const struct gm_celestial *celestial;           /* borrowed */
} gm_problem;

/* Length of the state vector: dim (first order, Poisson) or 2·dim (Hamiltonian kinds,
 * Lagrangian). */
size_t gm_problem_state_size(const gm_problem *problem);
/* Is the state a pair (q, p) of positions and momenta (Hamiltonian kinds, Lagrangian), rather
 * than one vector y (first order, Poisson)? Also for a kind alone. */
int gm_problem_has_momenta(const gm_problem *problem);
int gm_problem_kind_has_momenta(gm_problem_kind kind);
/* The state space: the problem's own, or NULL for Rⁿ. Chart dimension (the manifold's; the
 * state size for Rⁿ), chart coordinates of y around base (Rⁿ: z = y − base), the inverse, and
 * the distance of y from the manifold (Rⁿ: 0). */
const gm_state_space *gm_problem_space(const gm_problem *problem);
size_t gm_problem_chart_dim(const gm_problem *problem);
gm_status gm_problem_to_chart(const gm_problem *problem, const double *base, const double *y,
                              double *z);
gm_status gm_problem_from_chart(const gm_problem *problem, const double *base, const double *z,
                                double *y);
double gm_problem_state_defect(const gm_problem *problem, const double *y);
/* What the defect measures ("|R^T R - I|"; "" for Rⁿ). */
const char *gm_problem_state_defect_name(const gm_problem *problem);
/* The state space of rigid bodies with dim = 3 (T*SO(3), 12 numbers, chart dimension 6) or
 * dim = 6 (T*(SO(3) × R³), 18 numbers, chart dimension 12); NULL for other dim. Static. */
const gm_state_space *gm_rigid_body_space(size_t dim);
/* States further than this from their manifold are refused by gm_integrator_set_state. */
#define GM_STATE_DEFECT_TOLERANCE 1e-10
/* Check that the callbacks the kind requires are present. On failure the message says which. */
gm_status gm_problem_validate(const gm_problem *problem, gm_error *err);
/* Does the problem have an energy (Hamiltonian kinds, Poisson, Lagrangian)? Its value at the
 * state y (for a Lagrangian: p·v − L(q, v) with v from the Legendre transform p = ∂L/∂v). */
int gm_problem_has_energy(const gm_problem *problem);
double gm_problem_energy(const gm_problem *problem, const double *y);

/* ---- the integrator ------------------------------------------------------------------- */

struct gm_method; /* methods.h */
typedef struct gm_integrator gm_integrator;

typedef struct gm_stats {
  size_t steps;              /* steps taken */
  size_t force_evals;        /* evaluations of f, of ∇V, or of the pair (∇_q H, ∇_p H) */
  size_t jacobian_evals;     /* Jacobian or Hessian evaluations (user or finite-difference) */
  size_t fd_jacobians;       /* of those, finite-difference ones: a Hessian was missing */
  size_t newton_iterations;  /* over all implicit solves */
  size_t fixed_point_iterations;
  size_t newton_failures;    /* solves that did not converge (Newton or fixed point) */
} gm_stats;

/* How implicit methods solve their stage equations. */
typedef enum gm_solver {
  GM_SOLVER_DEFAULT = 0,            /* chosen by the problem's kind: fixed-point-positions for
                                       q'' = f(q) with a Runge–Kutta method, else fixed-point
                                       (Newton only when asked for: stiff problems) */
  GM_SOLVER_NEWTON,                 /* full Newton: Jacobians at every stage and iteration */
  GM_SOLVER_SIMPLIFIED_NEWTON,      /* one Jacobian at y_n and one LU of I − hA⊗J per step */
  GM_SOLVER_FIXED_POINT,            /* fixed-point iteration, starting from the previous step's
                                       collocation polynomial */
  GM_SOLVER_FIXED_POINT_POSITIONS   /* q'' = f(q): fixed-point iteration on the stage positions
                                       only (separable problems with quadratic T) */
} gm_solver;

/* "default", "newton", "simplified-newton", "fixed-point", "fixed-point-positions" */
const char *gm_solver_name(gm_solver solver);
/* The solver of that name; GM_ENOTFOUND when there is none. */
gm_status gm_solver_find(const char *name, gm_solver *out);

/* An observer sees the synchronized state after the steps it is called for (read-only);
 * returning non-zero stops the run with GM_ECALLBACK. */
typedef int (*gm_observer_fn)(void *ctx, size_t step, double t, const double *y);

/* Create an integrator of `method` for `problem` (both borrowed: they must outlive it).
 * Work arrays are allocated here. Fails with GM_EUNSUPPORTED when the method cannot integrate
 * the problem's kind, GM_EINVAL when a callback the method needs is missing; err says why. */
gm_status gm_integrator_create(const struct gm_method *method, const gm_problem *problem,
                               gm_integrator **out, gm_error *err);
void gm_integrator_free(gm_integrator *it);

/* Set time and state (y copied, length gm_problem_state_size). NaN or infinite → GM_EDOMAIN;
 * a state off its manifold (defect > GM_STATE_DEFECT_TOLERANCE, e.g. a non-orthogonal R) →
 * GM_EINVAL with the defect in the message. */
gm_status gm_integrator_set_state(gm_integrator *it, double t, const double *y);
/* The solver of the stage equations of an implicit method (also inside a composition).
 * GM_EUNSUPPORTED for explicit methods, or for GM_SOLVER_FIXED_POINT_POSITIONS when the
 * method is not a Runge–Kutta method or the problem is not separable with quadratic T. */
gm_status gm_integrator_set_solver(gm_integrator *it, gm_solver solver);
/* The solver in use: Runge–Kutta methods (also inside a composition) report the one they chose
 * for GM_SOLVER_DEFAULT; other families report what was set; explicit methods the default. */
gm_solver gm_integrator_solver(const gm_integrator *it);
/* A method with its choices: the basic method of a composition (NULL: the row's default; it
 * must be symmetric of order 2: verlet, midpoint, lobatto-iiia-iiib-2, ...), the solver of
 * implicit stages, and compensated summation. */
typedef struct gm_scheme {
  const struct gm_method *method;
  const struct gm_method *basic;
  gm_solver solver;
  int compensated;
} gm_scheme;

/* gm_integrator_create, then the scheme's basic method, solver and compensation. */
gm_status gm_integrator_create_scheme(const gm_scheme *scheme, const gm_problem *problem,
                                      gm_integrator **out, gm_error *err);
/* Compensated (Kahan) summation of the state update y + Δy (GNI §VIII.5). Off by default. */
gm_status gm_integrator_set_compensated(gm_integrator *it, int on);
/* Call fn(ctx, ...) at the current state now-or-at-start, every `every` steps, and after the
 * last step of each gm_integrator_run / gm_integrator_integrate. every >= 1. */
gm_status gm_integrator_add_observer(gm_integrator *it, gm_observer_fn fn, void *ctx,
                                     size_t every);

/* One step of size h (h != 0 and finite; negative h steps backwards). */
gm_status gm_integrator_step(gm_integrator *it, double h);
/* n_steps steps of size h. */
gm_status gm_integrator_run(gm_integrator *it, size_t n_steps, double h);
/* Fixed steps of equal size, at most h, ending exactly at t_end (h > 0, t_end > t). Methods
 * that choose their own step sizes (gm_integrator_chooses_steps: vi-sem-*) instead step until
 * the first step that reaches or passes t_end, and stop there: the time reached
 * (gm_integrator_time) is then t_end or up to one step later. */
gm_status gm_integrator_integrate(gm_integrator *it, double t_end, double h);
/* Does the method choose its own step sizes (the symplectic-energy-momentum rows)? */
int gm_integrator_chooses_steps(const gm_integrator *it);

/* ---- checkpoint and restart --------------------------------------------------------------- */
/* A checkpoint holds everything the next step depends on: the method (and basic method, solver,
 * compensation), the problem's state size, the time, the state, the compensated-summation
 * carry, the step counter, the statistics, the method's own state (starting values of implicit
 * solvers, the force of an FSAL splitting, the step and energy of vi-sem) and the run in
 * progress (its time grid), plus up to GM_CHECKPOINT_MAX_EXTRA bytes of the caller's own
 * (e.g. a monitor's state). Binary, in this machine's byte order, with a magic, a version and
 * a checksum (FNV-1a, 64 bits). Saved during a run (from an observer) or after it; loading it
 * into an integrator of the same method and problem and calling gm_integrator_resume continues
 * that run bitwise identically to one that was not interrupted. */
#define GM_CHECKPOINT_MAX_EXTRA 65536
/* Write a checkpoint to f (borrowed, binary). extra (copied, extra_size bytes) may be NULL. */
gm_status gm_integrator_save(gm_integrator *it, FILE *f, const void *extra, size_t extra_size);
/* Write it to path atomically (a temporary file in the same directory, then rename). */
gm_status gm_integrator_save_file(gm_integrator *it, const char *path, const void *extra,
                                  size_t extra_size);
/* Read a checkpoint into an integrator created for the same method, basic method and problem
 * size (observers may already be added; they are not called again for the saved step). A
 * truncated file, another kind of file, a checksum mismatch, another method, solver or state
 * size is GM_EIO or GM_EINVAL with a message (gm_integrator_errmsg), the integrator
 * unchanged. extra (extra_cap bytes, may be NULL) receives the caller's bytes, *extra_size
 * (may be NULL) their number. */
gm_status gm_integrator_load(gm_integrator *it, FILE *f, void *extra, size_t extra_cap,
                             size_t *extra_size);
gm_status gm_integrator_load_file(gm_integrator *it, const char *path, void *extra,
                                  size_t extra_cap, size_t *extra_size);
/* Continue the run that was in progress when the loaded checkpoint was saved (the remaining
 * steps of gm_integrator_run / gm_integrator_integrate, on the same time grid). */
gm_status gm_integrator_resume(gm_integrator *it);
/* Make the loaded run (in progress or finished) the run gm_integrator_run(n_steps, h)
 * (n_steps > 0) or gm_integrator_integrate(t_end, h) (n_steps == 0) would have made from the
 * same start, so that gm_integrator_resume continues it to the new end bitwise identically to
 * that run without interruption. GM_EINVAL (integrator unchanged) when the new run's step
 * differs from the saved one in any bit or ends before the saved step. */
gm_status gm_integrator_extend_run(gm_integrator *it, size_t n_steps, double t_end, double h);

double gm_integrator_time(const gm_integrator *it);
const double *gm_integrator_state(const gm_integrator *it); /* borrowed, valid until next call */
size_t gm_integrator_state_size(const gm_integrator *it);
gm_stats gm_integrator_stats(const gm_integrator *it);
void gm_integrator_reset_stats(gm_integrator *it);
/* What failed and why, for the last error ("" when none). */
const char *gm_integrator_errmsg(const gm_integrator *it);

/* ---- monitors: energy and invariant drift, as an observer ------------------------------ */

typedef struct gm_monitor gm_monitor;

/* Records the drift of the energy (Hamiltonian kinds) and of every declared invariant
 * relative to their values at y0 (copied). Use gm_monitor_observe as the observer function
 * and the monitor as its ctx. */
gm_status gm_monitor_create(const gm_problem *problem, const double *y0, gm_monitor **out);
void gm_monitor_free(gm_monitor *monitor);
int gm_monitor_observe(void *monitor, size_t step, double t, const double *y);
double gm_monitor_initial_energy(const gm_monitor *monitor);
/* max over observed states of |H - H0| / |H0| (|H - H0| when H0 = 0); NaN without energy */
double gm_monitor_max_rel_energy_error(const gm_monitor *monitor);
double gm_monitor_last_rel_energy_error(const gm_monitor *monitor);
/* max over observed states of |I_k - I_k(y0)| */
double gm_monitor_max_invariant_drift(const gm_monitor *monitor, size_t k);
size_t gm_monitor_n_observed(const gm_monitor *monitor);
/* gm_monitor_observe returns non-zero (stopping the run with GM_ECALLBACK) when the energy or
 * an invariant is NaN or infinite at an observed state; this says which, at which step. */
const char *gm_monitor_errmsg(const gm_monitor *monitor);
/* What the monitor has recorded, as gm_monitor_state_size doubles (for checkpoints: saved with
 * gm_integrator_save's extra bytes, loaded into a monitor created from the same y0). */
size_t gm_monitor_state_size(const gm_monitor *monitor);
void gm_monitor_state_save(const gm_monitor *monitor, double *out);
void gm_monitor_state_load(gm_monitor *monitor, const double *in);
/* The final time of the run in progress or last made (the checkpointed run after a load);
 * NaN when none. */
double gm_integrator_run_end_time(const gm_integrator *it);

/* ---- empirical order ------------------------------------------------------------------- */

#define GM_ORDER_MAX_LEVELS 16
typedef struct gm_order_result {
  size_t n_levels;
  double dts[GM_ORDER_MAX_LEVELS];
  double errors[GM_ORDER_MAX_LEVELS];  /* max-norm error of the state at t_end */
  double order;                        /* least-squares slope of log error against log dt,
                                          over the levels whose error is above round-off */
  size_t n_fitted;                     /* levels used in the fit */
  int reference_is_exact;              /* 1: the problem's exact solution; 0: a reference run */
  const struct gm_method *reference;   /* the reference method, NULL when exact */
  /* gm_order_measure_window only (zero from gm_order_measure): */
  double refinement;                   /* ratio between levels */
  size_t first_fitted;                 /* index of the first level inside the window */
  double window_top, window_bottom;    /* the asymptotic window of the declared order, as
                                          absolute errors (relative window × scale) */
  int outcome;                         /* gm_order_outcome: measured, or why not */
  double fit_deviation;                /* largest distance of a fitted error from the fitted
                                          line, in decades (log10) */
} gm_order_result;

/* Why an order could not be measured (gm_order_result.outcome). */
typedef enum gm_order_outcome {
  GM_ORDER_MEASURED = 0,      /* at least three levels inside the window: order is their slope */
  GM_ORDER_PRE_ASYMPTOTIC,    /* every error is above the window: the steps are too large */
  GM_ORDER_ROUNDOFF,          /* the errors fall below the window (round-off) before three
                                 levels land inside it: the asymptotic range of this order
                                 lies at or below round-off on this problem */
  GM_ORDER_TOO_FEW_LEVELS,    /* fewer than three levels reached the window */
  GM_ORDER_IRREGULAR,         /* the errors in the window stray from a power law by more than
                                 GM_ORDER_MAX_DEVIATION decades (round-off, solver tolerance) */
  GM_ORDER_NOT_SETTLED        /* a power law in the window, but its slope (order, kept) is not
                                 the declared order to GM_ORDER_TOLERANCE and a finer level is
                                 already below the window: round-off cuts the window before the
                                 slope can be seen to settle (pre-asymptotic errors, e.g. orders
                                 ≥ 10 on Kepler with e = 0.6) */
} gm_order_outcome;
#define GM_ORDER_MAX_DEVIATION 0.05
#define GM_ORDER_TOLERANCE 0.3

/* The asymptotic window of a method of order p, relative to the size of the solution
 * (max(1, |y0|∞)): errors between *bottom and *top are fitted. Above it the error expansion's
 * later terms still matter, below it round-off does. top = 10^−(p+2) clamped to [1e-7, 1e-3];
 * bottom = top · 10^−min(6, 2p), at least 1e-12 (the window narrows with the order: at most 6
 * decades, 2 per order). */
void gm_order_window(int order, double *top, double *bottom);

/* How gm_order_measure_window chooses its levels; zero fields are chosen automatically. */
typedef struct gm_order_plan {
  double dt0;          /* largest step; 0: the largest power of two (from min(1, T − t0))
                          whose error is at or below the top of the window */
  size_t n_levels;     /* 0: enough to span the window, at most GM_ORDER_MAX_LEVELS */
  double refinement;   /* 0: min(2, 10^(1/(2p))), half a decade of error per level */
  const struct gm_method *reference; /* borrowed; NULL: as in gm_order_measure */
  /* optional: called every few steps with the steps done and the steps planned (the total
   * grows while dt0 is searched); a non-zero return stops the measurement (GM_ECALLBACK) */
  int (*progress)(void *ctx, double steps_done, double steps_total);
  void *progress_ctx;  /* borrowed */
} gm_order_plan;

/* The order of the scheme's declared order window: levels as in gm_order_measure, chosen by
 * `plan` (NULL: all automatic), and the slope fitted over the levels whose error lies inside
 * gm_order_window(method->order) × scale, scale = max(1, |y0|∞). Without an exact solution the
 * reference run's step is halved until two runs agree to 1% of the window's bottom (or stop
 * improving). Levels whose shortened step (T − t0)/⌈(T − t0)/dt⌉ repeats the previous one are
 * skipped; dts holds the steps actually taken. Returns GM_OK both when the order was measured (outcome GM_ORDER_MEASURED, the
 * slope in out->order) and when it could not be (order NaN, outcome says why; dts and errors
 * hold what was measured). A run that fails is an error as in gm_order_measure, except that
 * once two levels are done a failing finer level ends the levels there. */
gm_status gm_order_measure_window(const gm_scheme *scheme, const gm_problem *problem, double t0,
                                  const double *y0, double t_end, const gm_order_plan *plan,
                                  gm_order_result *out, gm_error *err);

/* Integrate the scheme from (t0, y0) to t_end with steps dt0, dt0/r, dt0/r², ... (n_levels ≤
 * GM_ORDER_MAX_LEVELS; refinement r > 1, 2 is usual, less for very high orders, whose error
 * would otherwise fall from truncation to round-off within one refinement) and compare with the
 * exact solution if the problem has one, else with a run of `reference` (borrowed; NULL picks
 * the highest-order explicit method the problem accepts) at a step 64 times smaller than the
 * finest. */
gm_status gm_order_measure(const gm_scheme *scheme, const gm_problem *problem, double t0,
                           const double *y0, double t_end, double dt0, size_t n_levels,
                           double refinement, const struct gm_method *reference,
                           gm_order_result *out, gm_error *err);

#ifdef __cplusplus
}
#endif
#endif
