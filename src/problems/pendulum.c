/* Mathematical pendulum H = ½p² − k cos q (k = g/l). Seed 003 §6.3 uses k = 10, q = π/2. */
#include <math.h>

#include "problems/internal.h"

typedef struct {
  size_t dim;
  double k;
} pendulum;

static double potential(void *ctx, const double *q) {
  return -((const pendulum *)ctx)->k * cos(q[0]);
}

static int potential_gradient(void *ctx, const double *q, double *out) {
  out[0] = ((const pendulum *)ctx)->k * sin(q[0]);
  return 0;
}

static int potential_hessian(void *ctx, const double *q, double *out) {
  out[0] = ((const pendulum *)ctx)->k * cos(q[0]);
  return 0;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  pendulum *pd = ctx;
  (void)t0;
  if (!(params[0] > 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL, "pendulum: k must be positive, got %g", params[0]);
  *pd = (pendulum){1, params[0]};
  pb->kinetic = gm_free_kinetic;
  pb->kinetic_gradient = gm_free_kinetic_gradient;
  pb->kinetic_hessian = gm_free_kinetic_hessian;
  pb->potential = potential;
  pb->potential_gradient = potential_gradient;
  pb->potential_hessian = potential_hessian;
  y0[0] = 0.5 * GM_PI; /* released from horizontal: far from the linear regime */
  y0[1] = 0.0;
  return GM_OK;
}

static const gm_param_info params[] = {{"k", 1.0, "g/l: H = p^2/2 - k cos q"}};

const gm_model_def gm_model_pendulum = {
    {"pendulum", "mathematical pendulum H = p^2/2 - k cos q, q = pi/2, p = 0",
     GM_PROBLEM_SEPARABLE, 1, 1, params, 0, NULL, 0},
    sizeof(pendulum), NULL, setup, NULL};
