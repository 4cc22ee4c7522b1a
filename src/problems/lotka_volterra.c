/* Lotka–Volterra predator–prey system u' = u(v − 2), v' = v(1 − u), a Poisson system that is
 * not canonical (seed 003 §6.2; Hairer, Lubich & Wanner, GNI (2006), §I.1.1). Its invariant
 * I = ln u − u + 2 ln v − v is kept by the exact flow; start (3, 3) as in seed 003. */
#include <math.h>

#include "problems/internal.h"

static int rhs(void *ctx, double t, const double *y, double *f) {
  (void)ctx;
  (void)t;
  f[0] = y[0] * (y[1] - 2.0);
  f[1] = y[1] * (1.0 - y[0]);
  return 0;
}

static int rhs_jacobian(void *ctx, double t, const double *y, double *jac) {
  (void)ctx;
  (void)t;
  jac[0] = y[1] - 2.0;
  jac[1] = y[0];
  jac[2] = -y[1];
  jac[3] = 1.0 - y[0];
  return 0;
}

static double invariant(void *ctx, const double *y) {
  (void)ctx;
  return log(y[0]) - y[0] + 2.0 * log(y[1]) - y[1];
}

static const gm_invariant invariants[] = {{"invariant", invariant}};
static const char *const invariant_names[] = {"invariant"};

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  (void)ctx;
  (void)params;
  (void)t0;
  (void)errmsg;
  (void)cap;
  pb->rhs = rhs;
  pb->rhs_jacobian = rhs_jacobian;
  pb->n_invariants = 1;
  pb->invariants = invariants;
  y0[0] = 3.0;
  y0[1] = 3.0;
  return GM_OK;
}

const gm_model_def gm_model_lotka_volterra = {
    {"lotka-volterra",
     "predator-prey u' = u(v - 2), v' = v(1 - u), y = (3, 3); invariant ln u - u + 2 ln v - v",
     GM_PROBLEM_FIRST_ORDER, 2, 0, NULL, 1, invariant_names, 0},
    sizeof(size_t), NULL, setup, NULL, NULL};
