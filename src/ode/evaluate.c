/* Evaluating a problem through its kind: the first-order view f = J⁻¹∇H of Hamiltonian
 * problems, their Jacobians, and the separable gradients used by splitting methods. */
#include <math.h>
#include <string.h>

#include "ode/internal.h"

gm_status gm_callback_failed(gm_integrator *it, const char *name, int code, double t) {
  return gm_fail(it->errmsg, sizeof it->errmsg, GM_ECALLBACK,
                 "callback %s returned %d at t = %.17g", name, code, t);
}

#define CALL(expr, name)                                     \
  do {                                                       \
    int rc_ = (expr);                                        \
    if (rc_ != 0) return gm_callback_failed(it, name, rc_, t);  \
  } while (0)

gm_status gm_eval_rhs(gm_integrator *it, double t, const double *y, double *f) {
  const gm_problem *pb = it->problem;
  const size_t d = pb->dim;
  it->stats.force_evals++;
  switch (pb->kind) {
    case GM_PROBLEM_FIRST_ORDER:
      CALL(pb->rhs(pb->ctx, t, y, f), "rhs");
      return GM_OK;
    case GM_PROBLEM_HAMILTONIAN:
      CALL(pb->dh_dp(pb->ctx, y, y + d, f), "dh_dp");
      CALL(pb->dh_dq(pb->ctx, y, y + d, f + d), "dh_dq");
      break;
    case GM_PROBLEM_SEPARABLE:
      CALL(pb->kinetic_gradient(pb->ctx, y + d, f), "kinetic_gradient");
      CALL(pb->potential_gradient(pb->ctx, y, f + d), "potential_gradient");
      break;
    case GM_PROBLEM_POISSON:
      CALL(pb->poisson_gradient(pb->ctx, y, it->gradient), "poisson_gradient");
      CALL(pb->structure_matrix(pb->ctx, y, it->structure), "structure_matrix");
      for (size_t i = 0; i < d; ++i) {
        double sum = 0.0;
        for (size_t j = 0; j < d; ++j) sum += it->structure[i * d + j] * it->gradient[j];
        f[i] = sum;
      }
      return GM_OK;
    case GM_PROBLEM_LAGRANGIAN:
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                     "a Lagrangian problem has no first-order right-hand side");
    case GM_PROBLEM_RIGID_BODY:
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                     "a rigid-body state lives on a group: it has no right-hand side in R^n");
  }
  for (size_t i = d; i < 2 * d; ++i) f[i] = -f[i];
  return GM_OK;
}

/* Central differences, column by column: error O(h²) with h ~ ε^{1/3} (about 1e-10 relative). */
static gm_status fd_jacobian(gm_integrator *it, double t, const double *y, double *jac) {
  const size_t n = it->n;
  const double eps_third = 6.0554544523933395e-06; /* cbrt(DBL_EPSILON) */
  memcpy(it->fd_y, y, n * sizeof *y);
  for (size_t j = 0; j < n; ++j) {
    double h = eps_third * fmax(fabs(y[j]), 1.0);
    it->fd_y[j] = y[j] + h;
    double hp = it->fd_y[j] - y[j];  /* the step actually taken */
    gm_status st = gm_eval_rhs(it, t, it->fd_y, it->fd_fp);
    if (st != GM_OK) return st;
    it->fd_y[j] = y[j] - h;
    double hm = y[j] - it->fd_y[j];
    st = gm_eval_rhs(it, t, it->fd_y, it->fd_fm);
    if (st != GM_OK) return st;
    it->fd_y[j] = y[j];
    for (size_t i = 0; i < n; ++i) jac[i * n + j] = (it->fd_fp[i] - it->fd_fm[i]) / (hp + hm);
  }
  it->stats.fd_jacobians++;
  return GM_OK;
}

/* Place the d×d block b at block (bi, bj) of the 2d×2d matrix jac, times sign. */
static void put_block(double *jac, size_t d, size_t bi, size_t bj, const double *b, double sign) {
  for (size_t i = 0; i < d; ++i)
    for (size_t j = 0; j < d; ++j) jac[(bi * d + i) * 2 * d + bj * d + j] = sign * b[i * d + j];
}

gm_status gm_eval_rhs_jacobian(gm_integrator *it, double t, const double *y, double *jac) {
  const gm_problem *pb = it->problem;
  const size_t d = pb->dim, n = it->n;
  it->stats.jacobian_evals++;
  if (!gm_problem_has_jacobian(pb)) return fd_jacobian(it, t, y, jac);
  switch (pb->kind) {
    case GM_PROBLEM_FIRST_ORDER:
      CALL(pb->rhs_jacobian(pb->ctx, t, y, jac), "rhs_jacobian");
      return GM_OK;
    case GM_PROBLEM_HAMILTONIAN:
      /* f = (H_p, −H_q), so ∂f/∂y = [[H_pq, H_pp], [−H_qq, −H_qp]]. */
      CALL(pb->hamiltonian_hessian(pb->ctx, y, y + d, it->hess), "hamiltonian_hessian");
      for (size_t i = 0; i < d; ++i)
        for (size_t j = 0; j < n; ++j) {
          jac[i * n + j] = it->hess[(d + i) * n + j];
          jac[(d + i) * n + j] = -it->hess[i * n + j];
        }
      return GM_OK;
    case GM_PROBLEM_SEPARABLE:
      /* f = (T'(p), −V'(q)), so ∂f/∂y = [[0, T''], [−V'', 0]]. */
      memset(jac, 0, n * n * sizeof *jac);
      CALL(pb->kinetic_hessian(pb->ctx, y + d, it->hess), "kinetic_hessian");
      put_block(jac, d, 0, 1, it->hess, 1.0);
      CALL(pb->potential_hessian(pb->ctx, y, it->hess), "potential_hessian");
      put_block(jac, d, 1, 0, it->hess, -1.0);
      return GM_OK;
    case GM_PROBLEM_POISSON:
    case GM_PROBLEM_LAGRANGIAN:
    case GM_PROBLEM_RIGID_BODY:
      break; /* no analytic Jacobian: handled above */
  }
  return GM_EINVAL;
}

/* ---- the Poisson view y' = S(y)∇H(y) (discrete-gradient methods) ----------------------- */

gm_status gm_eval_poisson_energy(gm_integrator *it, double t, const double *y, double *energy) {
  double e = gm_problem_energy(it->problem, y);
  if (!isfinite(e))
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                   "the energy is %g at t = %.17g", e, t);
  *energy = e;
  return GM_OK;
}

gm_status gm_eval_poisson_gradient(gm_integrator *it, double t, const double *y, double *g) {
  const gm_problem *pb = it->problem;
  const size_t d = pb->dim;
  it->stats.force_evals++;
  switch (pb->kind) {
    case GM_PROBLEM_POISSON:
      CALL(pb->poisson_gradient(pb->ctx, y, g), "poisson_gradient");
      return GM_OK;
    case GM_PROBLEM_HAMILTONIAN:
      CALL(pb->dh_dq(pb->ctx, y, y + d, g), "dh_dq");
      CALL(pb->dh_dp(pb->ctx, y, y + d, g + d), "dh_dp");
      return GM_OK;
    case GM_PROBLEM_SEPARABLE:
      CALL(pb->potential_gradient(pb->ctx, y, g), "potential_gradient");
      CALL(pb->kinetic_gradient(pb->ctx, y + d, g + d), "kinetic_gradient");
      return GM_OK;
    case GM_PROBLEM_FIRST_ORDER:
    case GM_PROBLEM_LAGRANGIAN:
    case GM_PROBLEM_RIGID_BODY:
      break;
  }
  return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                 "a %s problem has no Poisson structure", gm_problem_kind_name(pb->kind));
}

int gm_poisson_structure_is_constant(const gm_problem *problem) {
  return problem->kind == GM_PROBLEM_HAMILTONIAN || problem->kind == GM_PROBLEM_SEPARABLE;
}

gm_status gm_eval_poisson_structure(gm_integrator *it, double t, const double *y, double *s) {
  const gm_problem *pb = it->problem;
  const size_t n = it->n, d = pb->dim;
  if (pb->kind == GM_PROBLEM_POISSON) {
    CALL(pb->structure_matrix(pb->ctx, y, s), "structure_matrix");
    return GM_OK;
  }
  if (!gm_poisson_structure_is_constant(pb))
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "a %s problem has no Poisson structure", gm_problem_kind_name(pb->kind));
  /* q' = ∇_p H, p' = −∇_q H: S = J⁻¹ = [[0, I], [−I, 0]] */
  memset(s, 0, n * n * sizeof *s);
  for (size_t i = 0; i < d; ++i) {
    s[i * n + d + i] = 1.0;
    s[(d + i) * n + i] = -1.0;
  }
  return GM_OK;
}
