/* Problem descriptions: kinds, state size, validation and energy. */
#include <math.h>

#include "ode/internal.h"

const char *gm_problem_kind_name(gm_problem_kind kind) {
  switch (kind) {
    case GM_PROBLEM_FIRST_ORDER:
      return "first-order";
    case GM_PROBLEM_HAMILTONIAN:
      return "hamiltonian";
    case GM_PROBLEM_SEPARABLE:
      return "separable";
    case GM_PROBLEM_POISSON:
      return "poisson";
    case GM_PROBLEM_LAGRANGIAN:
      return "lagrangian";
    case GM_PROBLEM_RIGID_BODY:
      return "rigid-body";
  }
  return "unknown";
}

static int is_hamiltonian_kind(gm_problem_kind kind) {
  return kind == GM_PROBLEM_HAMILTONIAN || kind == GM_PROBLEM_SEPARABLE;
}

int gm_problem_kind_has_momenta(gm_problem_kind kind) {
  return is_hamiltonian_kind(kind) || kind == GM_PROBLEM_LAGRANGIAN;
}

int gm_problem_has_momenta(const gm_problem *problem) {
  return problem != NULL && gm_problem_kind_has_momenta(problem->kind);
}

size_t gm_problem_state_size(const gm_problem *problem) {
  if (problem == NULL) return 0;
  if (problem->kind == GM_PROBLEM_RIGID_BODY) return 2 * problem->dim + 6; /* R is 9 numbers */
  if (problem->space != NULL) return problem->space->state_size;
  return gm_problem_has_momenta(problem) ? 2 * problem->dim : problem->dim;
}

#define REQUIRE(field)                                                                      \
  do {                                                                                      \
    if (problem->field == NULL)                                                             \
      return gm_error_set(err, GM_EINVAL, "%s problem: callback '%s' is missing",           \
                          gm_problem_kind_name(problem->kind), #field);                     \
  } while (0)

gm_status gm_problem_validate(const gm_problem *problem, gm_error *err) {
  if (problem == NULL) return gm_error_set(err, GM_EINVAL, "problem is NULL");
  if (problem->dim == 0) return gm_error_set(err, GM_EINVAL, "problem dimension is 0");
  switch (problem->kind) {
    case GM_PROBLEM_FIRST_ORDER:
      REQUIRE(rhs);
      break;
    case GM_PROBLEM_HAMILTONIAN:
      REQUIRE(hamiltonian);
      REQUIRE(dh_dq);
      REQUIRE(dh_dp);
      break;
    case GM_PROBLEM_SEPARABLE:
      REQUIRE(kinetic);
      REQUIRE(potential);
      REQUIRE(kinetic_gradient);
      REQUIRE(potential_gradient);
      break;
    case GM_PROBLEM_POISSON:
      REQUIRE(poisson_energy);
      REQUIRE(poisson_gradient);
      REQUIRE(structure_matrix);
      break;
    case GM_PROBLEM_LAGRANGIAN:
      REQUIRE(lagrangian);
      REQUIRE(dl_dq);
      REQUIRE(dl_dv);
      if (problem->n_constraints > 0) {
        REQUIRE(constraint);
        REQUIRE(constraint_jacobian);
      }
      for (size_t k = 0; k < problem->n_symmetries; ++k)
        if (problem->symmetries == NULL || problem->symmetries[k].generator == NULL ||
            problem->symmetries[k].name == NULL)
          return gm_error_set(err, GM_EINVAL, "symmetry %zu has no name or no generator", k);
      break;
    case GM_PROBLEM_RIGID_BODY: {
      gm_status st = gm_rigid_body_validate(problem, err);
      if (st != GM_OK) return st;
      break;
    }
    default:
      return gm_error_set(err, GM_EINVAL, "unknown problem kind %d", (int)problem->kind);
  }
  for (size_t k = 0; k < problem->n_invariants; ++k) {
    if (problem->invariants == NULL || problem->invariants[k].value == NULL ||
        problem->invariants[k].name == NULL)
      return gm_error_set(err, GM_EINVAL, "invariant %zu has no name or no function", k);
  }
  return GM_OK;
}

int gm_problem_has_energy(const gm_problem *problem) {
  return problem != NULL && (is_hamiltonian_kind(problem->kind) ||
                             problem->kind == GM_PROBLEM_POISSON ||
                             problem->kind == GM_PROBLEM_LAGRANGIAN ||
                             problem->kind == GM_PROBLEM_RIGID_BODY);
}

double gm_problem_energy(const gm_problem *problem, const double *y) {
  if (!gm_problem_has_energy(problem)) return NAN;
  if (problem->kind == GM_PROBLEM_POISSON) return problem->poisson_energy(problem->ctx, y);
  if (problem->kind == GM_PROBLEM_LAGRANGIAN) return gm_lagrangian_energy(problem, y);
  if (problem->kind == GM_PROBLEM_RIGID_BODY) return gm_rigid_body_energy(problem, y);
  const double *q = y, *p = y + problem->dim;
  if (problem->kind == GM_PROBLEM_SEPARABLE)
    return problem->kinetic(problem->ctx, p) + problem->potential(problem->ctx, q);
  return problem->hamiltonian(problem->ctx, q, p);
}

int gm_problem_has_jacobian(const gm_problem *problem) {
  switch (problem->kind) {
    case GM_PROBLEM_FIRST_ORDER:
      return problem->rhs_jacobian != NULL;
    case GM_PROBLEM_HAMILTONIAN:
      return problem->hamiltonian_hessian != NULL;
    case GM_PROBLEM_SEPARABLE:
      return problem->kinetic_hessian != NULL && problem->potential_hessian != NULL;
    case GM_PROBLEM_POISSON:     /* ∂(S∇H)/∂y involves ∂S/∂y: differences */
    case GM_PROBLEM_LAGRANGIAN:  /* not a first-order system for Runge–Kutta methods */
    case GM_PROBLEM_RIGID_BODY:  /* a state on a group: Lie group methods only */
      return 0;
  }
  return 0;
}
