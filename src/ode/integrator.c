/* The integrator driver: owns the state and the loop (fixed steps, exact final time),
 * compensated summation, observers and statistics. Steppers live in src/methods/<family>/. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ode/internal.h"

/* separable ⊂ Hamiltonian ⊂ Poisson ⊂ first order; Lagrangian problems only where accepted. */
static int accepts_kind(unsigned accepts, gm_problem_kind kind) {
  unsigned as = (unsigned)kind;
  if (kind == GM_PROBLEM_SEPARABLE) as |= GM_PROBLEM_HAMILTONIAN;
  if (as & GM_PROBLEM_HAMILTONIAN) as |= GM_PROBLEM_POISSON;
  if (as & GM_PROBLEM_POISSON) as |= GM_PROBLEM_FIRST_ORDER;
  return (accepts & as) != 0;
}

static void list_kinds(unsigned accepts, char *buf, size_t cap) {
  buf[0] = '\0';
  const gm_problem_kind kinds[] = {GM_PROBLEM_FIRST_ORDER, GM_PROBLEM_POISSON,
                                   GM_PROBLEM_HAMILTONIAN, GM_PROBLEM_SEPARABLE,
                                   GM_PROBLEM_LAGRANGIAN, GM_PROBLEM_RIGID_BODY};
  size_t len = 0;
  for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; ++i) {
    if (!(accepts & (unsigned)kinds[i])) continue;
    int w = snprintf(buf + len, cap - len, "%s%s", len ? ", " : "", gm_problem_kind_name(kinds[i]));
    if (w < 0 || (size_t)w >= cap - len) break;
    len += (size_t)w;
  }
}

static double *alloc_doubles(size_t n) { return calloc(n ? n : 1, sizeof(double)); }

/* A composition needs a symmetric basic method of order 2 that is not itself a composition:
 * the row's order holds for that case (GNI (2006), §V.3). */
static gm_status check_basic(const gm_method *method, const gm_method *basic, gm_error *err) {
  if (basic == NULL)
    return gm_error_set(err, GM_EINVAL, "composition '%s' needs a basic method", method->name);
  if (basic->family == GM_FAMILY_COMPOSITION || !(basic->flags & GM_SYMMETRIC) ||
      basic->order != 2)
    return gm_error_set(err, GM_EINVAL,
                        "'%s' cannot be the basic method of '%s': it must be a symmetric "
                        "method of order 2 (e.g. verlet, midpoint, lobatto-iiia-iiib-2)",
                        basic->name, method->name);
  return GM_OK;
}

static gm_status create(const gm_method *method, const gm_method *basic,
                        const gm_problem *problem, gm_integrator **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (method == NULL) return gm_error_set(err, GM_EINVAL, "method is NULL");
  gm_status st = gm_problem_validate(problem, err);
  if (st != GM_OK) return st;
  if (method->family == GM_FAMILY_COMPOSITION) {
    if ((st = check_basic(method, basic, err)) != GM_OK) return st;
  }
  const gm_method *integrates = basic != NULL ? basic : method;
  if (!accepts_kind(integrates->accepts, problem->kind)) {
    char kinds[96];
    list_kinds(integrates->accepts, kinds, sizeof kinds);
    if (basic != NULL)
      return gm_error_set(err, GM_EUNSUPPORTED,
                          "'%s' of '%s' cannot integrate a %s problem: '%s' accepts %s problems; "
                          "compose another basic method (e.g. midpoint)",
                          method->name, basic->name, gm_problem_kind_name(problem->kind),
                          basic->name, kinds);
    return gm_error_set(err, GM_EUNSUPPORTED,
                        "method '%s' cannot integrate a %s problem: it accepts %s problems",
                        method->name, gm_problem_kind_name(problem->kind), kinds);
  }
  const gm_stepper *stepper = gm_stepper_for(method, basic);
  if (stepper == NULL)
    return gm_error_set(err, GM_EINVAL, "method '%s' has no stepper for its family",
                        method->name);

  gm_integrator *it = calloc(1, sizeof *it);
  if (it == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  it->method = method;
  it->basic = basic;
  it->problem = problem;
  it->stepper = stepper;
  it->n = gm_problem_state_size(problem);
  it->dim = problem->dim;
  const size_t n = it->n;
  it->y = alloc_doubles(n);
  it->y_next = alloc_doubles(n);
  it->delta = alloc_doubles(n);
  it->carry = alloc_doubles(n);
  it->carry_next = alloc_doubles(n);
  /* O(n) here; the n×n Jacobian work only for a stepper that asks (gm_jacobian_work), and S(y)
   * only for Poisson problems, whose right-hand side needs it. */
  it->structure = alloc_doubles(problem->kind == GM_PROBLEM_POISSON ? n * n : 1);
  it->gradient = alloc_doubles(n);
  if (!it->y || !it->y_next || !it->delta || !it->carry || !it->carry_next || !it->structure ||
      !it->gradient) {
    gm_integrator_free(it);
    return gm_error_set(err, GM_ENOMEM, "out of memory for a state of size %zu", n);
  }
  st = stepper->init(it);
  if (st != GM_OK) {
    gm_error_set(err, st, "%s", it->errmsg[0] ? it->errmsg : gm_strerror(st));
    gm_integrator_free(it);
    return st;
  }
  *out = it;
  return GM_OK;
}

gm_status gm_jacobian_work(gm_integrator *it) {
  const size_t n = it->n;
  if (it->hess != NULL) return GM_OK;
  it->fd_y = alloc_doubles(n);
  it->fd_fp = alloc_doubles(n);
  it->fd_fm = alloc_doubles(n);
  it->hess = alloc_doubles(n * n);
  if (it->fd_y && it->fd_fp && it->fd_fm && it->hess) return GM_OK;
  free(it->fd_y);
  free(it->fd_fp);
  free(it->fd_fm);
  free(it->hess);
  it->fd_y = it->fd_fp = it->fd_fm = it->hess = NULL;
  return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOMEM,
                 "out of memory for the %zu x %zu Jacobian of '%s'", n, n, it->method->name);
}

gm_status gm_integrator_create(const gm_method *method, const gm_problem *problem,
                               gm_integrator **out, gm_error *err) {
  const gm_method *basic = NULL;
  if (method != NULL && method->family == GM_FAMILY_COMPOSITION) {
    basic = gm_method_find(method->basic);
    if (basic == NULL)
      return gm_error_set(err, GM_EINVAL, "composition '%s': default basic method '%s' not found",
                          method->name, method->basic ? method->basic : "(none)");
  }
  return create(method, basic, problem, out, err);
}

gm_status gm_integrator_create_scheme(const gm_scheme *scheme, const gm_problem *problem,
                                      gm_integrator **out, gm_error *err) {
  if (out != NULL) *out = NULL;
  if (scheme == NULL) return gm_error_set(err, GM_EINVAL, "scheme is NULL");
  const gm_method *m = scheme->method;
  gm_status st;
  if (scheme->basic == NULL) {
    st = gm_integrator_create(m, problem, out, err);
  } else if (m != NULL && m->family != GM_FAMILY_COMPOSITION) {
    return gm_error_set(err, GM_EINVAL, "'%s' is not a composition method: it takes no basic "
                        "method", m->name);
  } else {
    st = create(m, scheme->basic, problem, out, err);
  }
  if (st != GM_OK) return st;
  if ((st = gm_integrator_set_solver(*out, scheme->solver)) == GM_OK)
    st = gm_integrator_set_compensated(*out, scheme->compensated);
  if (st != GM_OK) {
    gm_error_set(err, st, "%s", (*out)->errmsg);
    gm_integrator_free(*out);
    *out = NULL;
  }
  return st;
}

gm_status gm_integrator_set_solver(gm_integrator *it, gm_solver solver) {
  if (it == NULL) return GM_EINVAL;
  if (solver < GM_SOLVER_DEFAULT || solver > GM_SOLVER_FIXED_POINT_POSITIONS)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "unknown solver %d", (int)solver);
  if (it->stepper->set_solver == NULL) {
    if (solver == GM_SOLVER_DEFAULT) return GM_OK;
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "method '%s' is explicit: it has no stage equations to solve", it->method->name);
  }
  return it->stepper->set_solver(it, solver);
}

gm_solver gm_integrator_solver(const gm_integrator *it) {
  return it != NULL ? it->solver : GM_SOLVER_DEFAULT;
}

static const char *const solver_names[] = {"default", "newton", "simplified-newton", "fixed-point",
                                           "fixed-point-positions"};

const char *gm_solver_name(gm_solver solver) {
  size_t i = (size_t)solver;
  return i < sizeof solver_names / sizeof solver_names[0] ? solver_names[i] : "unknown";
}

gm_status gm_solver_find(const char *name, gm_solver *out) {
  for (size_t i = 0; name != NULL && i < sizeof solver_names / sizeof solver_names[0]; ++i)
    if (strcmp(solver_names[i], name) == 0) {
      if (out != NULL) *out = (gm_solver)i;
      return GM_OK;
    }
  return GM_ENOTFOUND;
}

void gm_integrator_free(gm_integrator *it) {
  if (it == NULL) return;
  if (it->stepper != NULL && it->stepper->release != NULL) it->stepper->release(it);
  free(it->y);
  free(it->y_next);
  free(it->delta);
  free(it->carry);
  free(it->carry_next);
  free(it->fd_y);
  free(it->fd_fp);
  free(it->fd_fm);
  free(it->hess);
  free(it->structure);
  free(it->gradient);
  free(it->observers);
  free(it);
}

gm_status gm_integrator_set_state(gm_integrator *it, double t, const double *y) {
  if (it == NULL || y == NULL) return GM_EINVAL;
  if (!isfinite(t))
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN, "initial time is not finite");
  size_t bad = gm_first_nonfinite(it->n, y);
  if (bad < it->n)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                   "initial state component %zu is %g", bad + 1, y[bad]);
  double defect = gm_problem_state_defect(it->problem, y);
  if (!(defect <= GM_STATE_DEFECT_TOLERANCE))
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "initial state is not on the %s state space: %s = %.3g (tolerance %g)",
                   gm_problem_kind_name(it->problem->kind),
                   gm_problem_state_defect_name(it->problem), defect, GM_STATE_DEFECT_TOLERANCE);
  memcpy(it->y, y, it->n * sizeof *y);
  memset(it->carry, 0, it->n * sizeof *it->carry);
  it->t = t;
  it->step_index = 0;
  it->run_kind = 0;
  for (size_t k = 0; k < it->n_observers; ++k) it->observers[k].last_step = SIZE_MAX;
  if (it->stepper->invalidate != NULL) it->stepper->invalidate(it);
  it->errmsg[0] = '\0';
  return GM_OK;
}

gm_status gm_integrator_set_compensated(gm_integrator *it, int on) {
  if (it == NULL) return GM_EINVAL;
  it->compensated = on != 0;
  memset(it->carry, 0, it->n * sizeof *it->carry);
  if (it->stepper->invalidate != NULL) it->stepper->invalidate(it);
  return GM_OK;
}

gm_status gm_integrator_add_observer(gm_integrator *it, gm_observer_fn fn, void *ctx,
                                     size_t every) {
  if (it == NULL) return GM_EINVAL;
  if (fn == NULL)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "observer function is NULL");
  if (every == 0)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "observer interval must be >= 1");
  gm_observer_entry *grown = realloc(it->observers, (it->n_observers + 1) * sizeof *grown);
  if (grown == NULL) return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOMEM, "out of memory");
  it->observers = grown;
  it->observers[it->n_observers++] = (gm_observer_entry){fn, ctx, every, SIZE_MAX};
  return GM_OK;
}

/* Call the observers due at the current step (all of them when `all`), each once per step. */
static gm_status notify(gm_integrator *it, int all) {
  for (size_t k = 0; k < it->n_observers; ++k) {
    gm_observer_entry *o = &it->observers[k];
    if (o->last_step == it->step_index) continue;
    if (!all && it->step_index % o->every != 0) continue;
    o->last_step = it->step_index;
    int rc = o->fn(o->ctx, it->step_index, it->t, it->y);
    if (rc != 0)
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_ECALLBACK,
                     "observer %zu returned %d at t = %.17g", k + 1, rc, it->t);
  }
  return GM_OK;
}

gm_status gm_nonfinite_state(gm_integrator *it, size_t component, double t_new) {
  if (it->stepper->invalidate != NULL) it->stepper->invalidate(it);
  char name[32] = "";
  if (gm_problem_has_momenta(it->problem))
    snprintf(name, sizeof name, " (%c%zu)", component < it->dim ? 'q' : 'p',
             component % it->dim + 1);
  return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                 "state component %zu%s became %g in step %zu, from t = %.17g to t = %.17g",
                 component + 1, name, it->y_next[component], it->step_index + 1, it->t, t_new);
}

/* Advance one step of size h to the time t_new; the state is unchanged on failure. */
static gm_status advance(gm_integrator *it, double h, double t_new) {
  it->h_taken = NAN;
  if (!it->compensated) {
    gm_status st = it->stepper->step(it, it->t, h, it->y, it->y_next, NULL);
    if (st == GM_OK && !isnan(it->h_taken)) t_new = it->t + it->h_taken;
    return st != GM_OK ? st : gm_commit_step(it, t_new);
  }
  gm_status st = it->stepper->step(it, it->t, h, it->y, NULL, it->delta);
  if (st != GM_OK) return st;
  if (!isnan(it->h_taken)) t_new = it->t + it->h_taken;
  /* Compensated summation, Hairer–Lubich–Wanner GNI (2006) §VIII.5, Algorithm 5.1:
   * the rounding error of y + Δy is carried into the next step. */
  for (size_t i = 0; i < it->n; ++i) {
    double e = it->carry[i] + it->delta[i];
    double b = it->y[i] + e;
    it->carry_next[i] = (it->y[i] - b) + e;
    it->y_next[i] = b;
  }
  st = gm_commit_step(it, t_new);
  if (st == GM_OK) {
    double *tmp = it->carry;
    it->carry = it->carry_next;
    it->carry_next = tmp;
  }
  return st;
}

static gm_status check_step(gm_integrator *it, double h) {
  if (!isfinite(h) || h == 0.0)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "step size must be finite and non-zero, got %g", h);
  return GM_OK;
}

gm_status gm_integrator_step(gm_integrator *it, double h) {
  if (it == NULL) return GM_EINVAL;
  gm_status st = check_step(it, h);
  if (st == GM_OK) st = notify(it, it->step_index == 0);
  if (st == GM_OK) st = advance(it, h, it->t + h);
  if (st == GM_OK) st = notify(it, 0);
  return st;
}

/* The step index (since set_state) at which the next observer is due, after `from`. */
static size_t next_observation(const gm_integrator *it, size_t from) {
  size_t next = SIZE_MAX;
  for (size_t k = 0; k < it->n_observers; ++k) {
    size_t every = it->observers[k].every, due = (from / every + 1) * every;
    if (due < next) next = due;
  }
  return next;
}

/* Steps k_from+1 .. k_to of the run, one at a time or by the stepper's own loop. */
static gm_status run_chunk(gm_integrator *it, const gm_run *run, size_t k_from, size_t k_to) {
  if (it->stepper->run != NULL && (!it->compensated || it->stepper->run_compensates))
    return it->stepper->run(it, run, k_from, k_to);
  gm_status st = GM_OK;
  for (size_t k = k_from + 1; k <= k_to && st == GM_OK; ++k)
    st = advance(it, run->h, gm_run_time(run, k));
  return st;
}

/* n steps of size h from the current time; times are t0 + k·h (no accumulated drift), the
 * last is t_last exactly. Observers are called between chunks of steps, so how often a run
 * is observed never changes what it computes. */
static gm_status run_steps_from(gm_integrator *it, const gm_run *run_in, size_t k0) {
  const gm_run run = *run_in;
  const size_t n_steps = run.n_steps;
  it->run = run;
  it->run_start = it->step_index - k0;
  it->run_kind = 1;
  gm_status st = notify(it, it->step_index == 0);
  for (size_t k = k0; k < n_steps && st == GM_OK;) {
    size_t due = next_observation(it, it->step_index) - it->step_index;
    size_t k_to = due < n_steps - k ? k + due : n_steps;
    st = run_chunk(it, &run, k, k_to);
    k = k_to;
    if (st == GM_OK) st = notify(it, 0);
  }
  if (st == GM_OK) st = notify(it, 1);
  return st;
}

static gm_status run_steps(gm_integrator *it, size_t n_steps, double h, double t_last) {
  const gm_run run = {it->t, h, t_last, n_steps};
  return run_steps_from(it, &run, 0);
}

gm_status gm_integrator_run(gm_integrator *it, size_t n_steps, double h) {
  if (it == NULL) return GM_EINVAL;
  gm_status st = check_step(it, h);
  if (st != GM_OK) return st;
  if ((double)n_steps > 1e15) /* as gm_integrator_integrate: a count past it is an overflow */
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "%zu steps requested: more than 1e15", n_steps);
  return run_steps(it, n_steps, h, it->t + (double)n_steps * h);
}

int gm_integrator_chooses_steps(const gm_integrator *it) {
  const gm_stepper_state *extra = it != NULL ? gm_stepper_state_of(it->stepper) : NULL;
  return extra != NULL && extra->chooses_steps;
}

/* A method that chooses its own steps (vi-sem-*): steps until the first that reaches or passes
 * t_end (its last step is not shortened: that would break the energy equation it solves). */
static gm_status run_to_first_reaching(gm_integrator *it, double t_end, double h) {
  it->run = (gm_run){it->t, h, t_end, 0};
  it->run_start = it->step_index;
  it->run_kind = 2;
  gm_status st = notify(it, it->step_index == 0);
  /* steps that collapse (no root of the energy equation near the previous step) must not run
   * forever: at most 1000 times the steps of size h, and 10^15 */
  const double planned = ceil((t_end - it->t) / h);
  const size_t max_steps = (size_t)fmin(1e15, 1000.0 * planned + 1000.0);
  for (size_t k = 0; st == GM_OK && it->t < t_end; ++k) {
    if (k >= max_steps)
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOCONV,
                     "'%s': %zu steps of its own size (the last %.3g) did not reach t = %.17g "
                     "from the step %g asked for: the steps collapsed",
                     it->method->name, k, it->h_taken, t_end, h);
    st = advance(it, h, it->t + h);
    if (st == GM_OK) st = notify(it, 0);
  }
  if (st == GM_OK) st = notify(it, 1);
  return st;
}


gm_status gm_integrator_integrate(gm_integrator *it, double t_end, double h) {
  if (it == NULL) return GM_EINVAL;
  if (!isfinite(h) || h <= 0.0)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "step size must be positive and finite, got %g", h);
  if (!isfinite(t_end) || t_end <= it->t)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "final time %g must be finite and after the current time %g", t_end, it->t);
  if (gm_integrator_chooses_steps(it)) return run_to_first_reaching(it, t_end, h);
  double ratio = (t_end - it->t) / h;
  /* A ratio a few ulps above an integer is that integer: no sliver step at the end. */
  double n_real = ceil(ratio - 1e-9 * fmax(1.0, ratio));
  if (n_real < 1.0) n_real = 1.0;
  if (n_real > 1e15)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "%.3g steps requested: step size too small for this interval", n_real);
  size_t n_steps = (size_t)n_real;
  return run_steps(it, n_steps, (t_end - it->t) / (double)n_steps, t_end);
}

gm_status gm_integrator_resume(gm_integrator *it) {
  if (it == NULL) return GM_EINVAL;
  if (it->run_kind == 2) return run_to_first_reaching(it, it->run.t_last, it->run.h);
  if (it->run_kind != 1 || it->step_index < it->run_start ||
      it->step_index - it->run_start > it->run.n_steps)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "no run to resume: load a checkpoint taken during gm_integrator_run or "
                   "gm_integrator_integrate");
  return run_steps_from(it, &it->run, it->step_index - it->run_start);
}

gm_status gm_integrator_extend_run(gm_integrator *it, size_t n_steps, double t_end, double h) {
  if (it == NULL) return GM_EINVAL;
  if (it->run_kind != 1 || it->step_index < it->run_start ||
      it->step_index - it->run_start > it->run.n_steps)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "no run to extend: load a checkpoint taken during or at the end of "
                   "gm_integrator_run or gm_integrator_integrate");
  const size_t k = it->step_index - it->run_start;
  const double t0 = it->run.t0;
  gm_status st = check_step(it, h);
  if (st != GM_OK) return st;
  /* the run gm_integrator_run / _integrate would have made from the same start */
  gm_run run;
  if (n_steps > 0) {
    if ((double)n_steps > 1e15)
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                     "%zu steps requested: more than 1e15", n_steps);
    run = (gm_run){t0, h, t0 + (double)n_steps * h, n_steps};
  } else {
    if (!isfinite(t_end) || !(t_end > t0))
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                     "final time %g must be finite and after the run's start %g", t_end, t0);
    const double ratio = (t_end - t0) / h;
    double n_real = ceil(ratio - 1e-9 * fmax(1.0, ratio)); /* as gm_integrator_integrate */
    if (n_real < 1.0) n_real = 1.0;
    if (n_real > 1e15)
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                     "%.3g steps requested: step size too small for this interval", n_real);
    run = (gm_run){t0, (t_end - t0) / n_real, t_end, (size_t)n_real};
  }
  /* the steps taken so far are those of the new run only with the same step, bitwise */
  if (run.h != it->run.h)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "the run to t = %.17g has the step %.17g, the saved run %.17g: the steps "
                   "taken are not those of the new run (give the same --dt)",
                   run.t_last, run.h, it->run.h);
  if (k > run.n_steps)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "the saved run is at step %zu (t = %.17g), past the end of a run of %zu "
                   "steps to t = %.17g", k, it->t, run.n_steps, run.t_last);
  it->run = run;
  it->t = gm_run_time(&run, k); /* a finished run stood at its t_last: the new grid's time */
  return GM_OK;
}

double gm_integrator_run_end_time(const gm_integrator *it) {
  return it != NULL && it->run_kind != 0 ? it->run.t_last : NAN;
}

double gm_integrator_time(const gm_integrator *it) { return it ? it->t : NAN; }
const double *gm_integrator_state(const gm_integrator *it) { return it ? it->y : NULL; }
size_t gm_integrator_state_size(const gm_integrator *it) { return it ? it->n : 0; }
gm_stats gm_integrator_stats(const gm_integrator *it) {
  gm_stats none = {0};
  return it ? it->stats : none;
}
void gm_integrator_reset_stats(gm_integrator *it) {
  if (it != NULL) memset(&it->stats, 0, sizeof it->stats);
}
const char *gm_integrator_errmsg(const gm_integrator *it) { return it ? it->errmsg : ""; }
