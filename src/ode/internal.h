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
typedef struct gm_stepper {
  gm_status (*init)(gm_integrator *it);   /* allocate it->work; every array a step needs */
  gm_status (*step)(gm_integrator *it, double t, double h, const double *y_old, double *y_new,
                    double *delta);
  void (*release)(gm_integrator *it);     /* free it->work */
  void (*invalidate)(gm_integrator *it);  /* drop caches after an external change of state */
} gm_stepper;

struct gm_integrator {
  const gm_method *method;
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
  /* finite-difference Jacobian work (allocated at create when no analytic one exists) */
  double *fd_y, *fd_fp, *fd_fm;
  double *hess;               /* 2d×2d Hessian of H (Hamiltonian kinds with a Hessian) */
  char errmsg[GM_ERRMSG_SIZE];
};

/* ---- evaluations through the problem's kind (src/ode/evaluate.c) ------------------------ */
/* Each counts itself in it->stats and, on a callback failure, writes it->errmsg (naming the
 * callback, its return value and t) and returns GM_ECALLBACK. */

/* First-order right-hand side f(t, y); for Hamiltonian kinds f = (∇_p H, −∇_q H). */
gm_status gm_eval_rhs(gm_integrator *it, double t, const double *y, double *f);
/* ∂f/∂y (n×n row-major), analytic when the problem has it, else central differences. */
gm_status gm_eval_rhs_jacobian(gm_integrator *it, double t, const double *y, double *jac);
/* Separable kinds: ∇V(q) (counted as a force evaluation) and ∇T(p). */
gm_status gm_eval_potential_gradient(gm_integrator *it, double t, const double *q, double *g);
gm_status gm_eval_kinetic_gradient(gm_integrator *it, double t, const double *p, double *g);
/* Does the problem provide an analytic Jacobian in its kind? */
int gm_problem_has_jacobian(const gm_problem *problem);

/* ---- steppers (src/methods) ------------------------------------------------------------ */
const gm_stepper *gm_stepper_for(const gm_method *method);

#endif
