/* Private parts of the integrator shared by the driver (src/ode) and the steppers
 * (src/methods). Never installed. */
#ifndef GM_ODE_INTERNAL_H
#define GM_ODE_INTERNAL_H

#include "core/internal.h"
#include "geomint/methods.h"
#include "geomint/ode.h"

typedef struct gm_observer_entry {
  gm_observer_fn fn;
  void *ctx;
  size_t every;
  size_t last_step; /* step index of its last call, SIZE_MAX when none since set_state */
} gm_observer_entry;

/* A stepper advances y_old (read-only) by h. Without compensation it writes y_new; with it
 * (delta != NULL) it writes the increment delta = y_new − y_old instead, computed so that
 * small increments keep their digits. On failure y_old is untouched and it->errmsg says why. */
/* A run of n_steps steps of size h from t0: step k ends at t0 + k·h, the last at t_last. */
typedef struct gm_run {
  double t0, h, t_last;
  size_t n_steps;
} gm_run;

static inline double gm_run_time(const gm_run *run, size_t k) {
  return k == run->n_steps ? run->t_last : run->t0 + (double)k * run->h;
}

typedef struct gm_stepper {
  gm_status (*init)(gm_integrator *it);   /* allocate it->work; every array a step needs */
  gm_status (*step)(gm_integrator *it, double t, double h, const double *y_old, double *y_new,
                    double *delta);
  void (*release)(gm_integrator *it);     /* free it->work */
  void (*invalidate)(gm_integrator *it);  /* drop caches after an external change of state */
  /* Optional: steps k_from+1 .. k_to of `run` without compensation, each committed with
   * gm_commit_step. Saves the per-step dispatch where a step costs little. */
  gm_status (*run)(gm_integrator *it, const gm_run *run, size_t k_from, size_t k_to);
  /* Optional: accept a solver for the stage equations (it->solver is set on success). */
  gm_status (*set_solver)(gm_integrator *it, gm_solver solver);
  /* Non-zero: run() also compensates when compensated summation is on (a stepper that keeps
   * its own state and carries, as the near-integrable splittings do). */
  int run_compensates;
} gm_stepper;

struct gm_integrator {
  const gm_method *method;
  const gm_method *basic;     /* composition: the basic method; NULL otherwise */
  gm_solver solver;
  const gm_problem *problem;
  const gm_stepper *stepper;
  void *work;                 /* owned by the stepper */
  size_t n;                   /* state size */
  size_t dim;                 /* problem->dim */
  double t;
  double *y, *y_next;         /* current state and the buffer the next step writes */
  double *delta, *carry, *carry_next; /* compensated summation: increment and carried error */
  int compensated;
  size_t step_index;          /* steps since the last set_state */
  gm_observer_entry *observers;
  size_t n_observers;
  gm_stats stats;
  /* Jacobian work: NULL until a stepper that evaluates Jacobians asks (gm_jacobian_work) */
  double *fd_y, *fd_fp, *fd_fm;
  double *hess;               /* 2d×2d Hessian of H (Hamiltonian kinds with a Hessian) */
  double *structure, *gradient; /* Poisson: S(y) (n×n) and ∇H(y) (n) */
  double h_taken;             /* a stepper that chooses its own step size (vi-sem-*) writes the
                                step it took here; NaN: the step asked for */
  /* the run in progress or last made (a checkpoint saves it, so that a restart continues its
   * time grid): fixed steps `run` from step index run_start, or (run_until) steps of a method
   * that chooses its own until the first reaching run.t_last */
  gm_run run;
  size_t run_start;
  int run_kind;               /* 0 none, 1 fixed steps, 2 until t_end */
  char errmsg[GM_ERRMSG_SIZE];
};

/* E = p·v − L(q, v) with v from p = ∂L/∂v(q, v) (Newton's method; src/ode/lagrangian.c).
 * NaN when the Legendre transform cannot be inverted there. */
double gm_lagrangian_energy(const gm_problem *problem, const double *y);

/* Rigid bodies (src/ode/rigid_body.c): checks of the rigid-body kind (dim, J symmetric
 * positive definite, mass), its energy, and J⁻¹ (GM_EINVAL with a message unless J is
 * symmetric positive definite; err may be NULL). */
gm_status gm_rigid_body_validate(const gm_problem *problem, gm_error *err);
double gm_rigid_body_energy(const gm_problem *problem, const double *y);
gm_status gm_rigid_inertia_inverse(const double j[9], double inv[9], gm_error *err);

/* ---- evaluations through the problem's kind (src/ode/evaluate.c) ------------------------ */
/* Each counts itself in it->stats and, on a callback failure, writes it->errmsg (naming the
 * callback, its return value and t) and returns GM_ECALLBACK. */

/* First-order right-hand side f(t, y); for Hamiltonian kinds f = (∇_p H, −∇_q H), for Poisson
 * f = S(y)∇H(y). */
gm_status gm_eval_rhs(gm_integrator *it, double t, const double *y, double *f);
/* ∂f/∂y (n×n row-major), analytic when the problem has it, else central differences. */
gm_status gm_eval_rhs_jacobian(gm_integrator *it, double t, const double *y, double *jac);
/* Report a failed user callback: writes it->errmsg, returns GM_ECALLBACK. */
gm_status gm_callback_failed(gm_integrator *it, const char *name, int code, double t);
/* Separable kinds: ∇V(q) (counted as a force evaluation) and ∇T(p). Inline: splitting
 * methods call them once per stage, and the call should cost no more than the user's. */
static inline gm_status gm_eval_potential_gradient(gm_integrator *it, double t, const double *q,
                                                   double *g) {
  const gm_problem *pb = it->problem;
  it->stats.force_evals++;
  int rc = pb->potential_gradient(pb->ctx, q, g);
  return rc == 0 ? GM_OK : gm_callback_failed(it, "potential_gradient", rc, t);
}
static inline gm_status gm_eval_kinetic_gradient(gm_integrator *it, double t, const double *p,
                                                 double *g) {
  const gm_problem *pb = it->problem;
  int rc = pb->kinetic_gradient(pb->ctx, p, g);
  return rc == 0 ? GM_OK : gm_callback_failed(it, "kinetic_gradient", rc, t);
}
/* The Poisson view y' = S(y)∇H(y) of Poisson problems and of Hamiltonian kinds (S = J⁻¹,
 * state (q, p)): the energy (GM_EDOMAIN when not finite), ∇H (counted as a force evaluation)
 * and S (n×n). Is S constant (Hamiltonian kinds)? */
gm_status gm_eval_poisson_energy(gm_integrator *it, double t, const double *y, double *energy);
gm_status gm_eval_poisson_gradient(gm_integrator *it, double t, const double *y, double *g);
gm_status gm_eval_poisson_structure(gm_integrator *it, double t, const double *y, double *s);
int gm_poisson_structure_is_constant(const gm_problem *problem);
/* Allocate the work gm_eval_rhs_jacobian needs (an n×n Hessian, 3n for differences), once:
 * steppers call it from init or set_solver when their solver uses Jacobians, never in a step.
 * Explicit methods never do, so their memory stays O(n). */
gm_status gm_jacobian_work(gm_integrator *it);
/* Does the problem provide an analytic Jacobian in its kind? */
int gm_problem_has_jacobian(const gm_problem *problem);

/* Accept the state the stepper wrote into it->y_next as the state at t_new: check it is
 * finite, then swap buffers. On failure the state stays at the last good step. */
gm_status gm_nonfinite_state(gm_integrator *it, size_t component, double t_new);
static inline gm_status gm_commit_step(gm_integrator *it, double t_new) {
  size_t bad = gm_first_nonfinite(it->n, it->y_next);
  if (bad < it->n) return gm_nonfinite_state(it, bad, t_new);
  double *tmp = it->y;
  it->y = it->y_next;
  it->y_next = tmp;
  it->t = t_new;
  it->step_index++;
  it->stats.steps++;
  return GM_OK;
}

/* What a stepper keeps between steps, beyond the state (src/methods/stepper_state.c). */
typedef struct gm_stepper_state {
  /* Non-zero when the stepper chooses its own step sizes (it writes it->h_taken): then
   * gm_integrator_integrate stops at the first step that reaches t_end. */
  int chooses_steps;
  /* Optional: the method's own state that the next step depends on (starting values, the step
   * size and energy of vi-sem, ...), saved in checkpoints: its size in bytes, and copies out
   * of and into it (the load follows a gm_integrator_set_state of the saved state). */
  size_t (*size)(const gm_integrator *it);
  void (*save)(const gm_integrator *it, unsigned char *out);
  gm_status (*load)(gm_integrator *it, const unsigned char *in);
} gm_stepper_state;

/* The stepper's extras; NULL when it keeps nothing between steps that changes the next one. */
const gm_stepper_state *gm_stepper_state_of(const gm_stepper *stepper);

/* ---- steppers (src/methods) ------------------------------------------------------------ */
/* The stepper of a method (of a composition: depends on its basic method). */
const gm_stepper *gm_stepper_for(const gm_method *method, const gm_method *basic);

#endif
