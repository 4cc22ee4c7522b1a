/* T(p) = ½|p|² with unit masses. */
#include <string.h>

#include "problems/internal.h"

double gm_free_kinetic(void *ctx, const double *p) {
  const size_t d = *(const size_t *)ctx;
  double t = 0.0;
  for (size_t i = 0; i < d; ++i) t += p[i] * p[i];
  return 0.5 * t;
}

int gm_free_kinetic_gradient(void *ctx, const double *p, double *out) {
  const size_t d = *(const size_t *)ctx;
  memcpy(out, p, d * sizeof *p);
  return 0;
}

int gm_free_kinetic_hessian(void *ctx, const double *p, double *hessian) {
  (void)p;
  const size_t d = *(const size_t *)ctx;
  memset(hessian, 0, d * d * sizeof *hessian);
  for (size_t i = 0; i < d; ++i) hessian[i * d + i] = 1.0;
  return 0;
}

/* Declared in methods/internal.h: the steppers skip the call (and its copy) for this T. */
int gm_kinetic_is_identity(const gm_problem *problem) {
  return problem->kinetic_gradient == gm_free_kinetic_gradient &&
         *(const size_t *)problem->ctx == problem->dim;
}

void gm_free_kinetic_setup(gm_problem *pb) {
  pb->kinetic = gm_free_kinetic;
  pb->kinetic_gradient = gm_free_kinetic_gradient;
  pb->kinetic_hessian = gm_free_kinetic_hessian;
  pb->kinetic_is_quadratic = 1;
}
