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

#include "geomint/core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum gm_problem_kind {
  GM_PROBLEM_FIRST_ORDER = 1u << 0,
  GM_PROBLEM_HAMILTONIAN = 1u << 1,
  GM_PROBLEM_SEPARABLE = 1u << 2,
  GM_PROBLEM_POISSON = 1u << 3,
  GM_PROBLEM_LAGRANGIAN = 1u << 4
} gm_problem_kind;
#define GM_N_PROBLEM_KINDS 5

/* "first-order", "hamiltonian", "separable", "poisson", "lagrangian" */
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
  /* optional: a non-conservative force F(t, q, v) (Lagrange–d'Alembert) */
  int (*force)(void *ctx, double t, const double *q, const double *v, double *f);
  /* optional: symmetries of L, whose Noether momenta are monitored */
  size_t n_symmetries;
  const gm_symmetry *symmetries;   /* borrowed, n_symmetries entries */

  /* separable: set when T(p) = ½ pᵀM⁻¹p with a constant M, so ∇T is linear (it lets Gauss
   * methods iterate on positions only, GM_SOLVER_FIXED_POINT_POSITIONS) */
  int kinetic_is_quadratic;

  /* optional, every kind */
  size_t n_invariants;
  const gm_invariant *invariants;                 /* borrowed, n_invariants entries */
  int (*exact)(void *ctx, double t, double *y);   /* exact solution from the initial state */
} gm_problem;

/* Length of the state vector: dim (first order, Poisson) or 2·dim (Hamiltonian kinds,
 * Lagrangian). */
size_t gm_problem_state_size(const gm_problem *problem);
/* Is the state a pair (q, p) of positions and momenta (Hamiltonian kinds, Lagrangian), rather
 * than one vector y (first order, Poisson)? Also for a kind alone. */
int gm_problem_has_momenta(const gm_problem *problem);
int gm_problem_kind_has_momenta(gm_problem_kind kind);
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

/* Set time and state (y copied, length gm_problem_state_size). NaN or infinite → GM_EDOMAIN. */
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
/* Fixed steps of equal size, at most h, ending exactly at t_end (h > 0, t_end > t). */
gm_status gm_integrator_integrate(gm_integrator *it, double t_end, double h);

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
} gm_order_result;

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
