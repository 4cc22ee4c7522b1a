/* Lotka–Volterra predator–prey system u' = u(v − 2), v' = v(1 − u), a Poisson system that is
 * not canonical (seed 003 §6.2; Hairer, Lubich & Wanner, GNI (2006), §I.1.1 and §VII.2), given
 * as y' = S(y)∇H(y). Its invariant I = ln u − u + 2 ln v − v = −H is kept by the exact flow;
 * start (3, 3) as in seed 003. */
#include <math.h>

#include "problems/internal.h"

/* H(y) = −(ln u − u + 2 ln v − v), ∇H = (1 − 1/u, 1 − 2/v), S(y) = uv [[0, 1], [−1, 0]]:
 * S∇H = (uv(1 − 2/v), −uv(1 − 1/u)) = (u(v − 2), v(1 − u)) (GNI (2006),
 * §VII.2). H = −I is conserved with the invariant. */
static double energy(void *ctx, const double *y) {
  (void)ctx;
  return -(log(y[0]) - y[0] + 2.0 * log(y[1]) - y[1]);
}

static int gradient(void *ctx, const double *y, double *g) {
  (void)ctx;
  g[0] = 1.0 - 1.0 / y[0];
  g[1] = 1.0 - 2.0 / y[1];
  return 0;
}

static int hessian(void *ctx, const double *y, double *h) {
  (void)ctx;
  h[0] = 1.0 / (y[0] * y[0]);
  h[1] = 0.0;
  h[2] = 0.0;
  h[3] = 2.0 / (y[1] * y[1]);
  return 0;
}

static int structure(void *ctx, const double *y, double *s) {
  (void)ctx;
  s[0] = 0.0;
  s[1] = y[0] * y[1];
  s[2] = -y[0] * y[1];
  s[3] = 0.0;
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
  pb->poisson_energy = energy;
  pb->poisson_gradient = gradient;
  pb->poisson_hessian = hessian;
  pb->structure_matrix = structure;
  pb->n_invariants = 1;
  pb->invariants = invariants;
  y0[0] = 3.0;
  y0[1] = 3.0;
  return GM_OK;
}

const gm_model_def gm_model_lotka_volterra = {
    {"lotka-volterra",
     "predator-prey u' = u(v - 2), v' = v(1 - u) as a Poisson system: S = uv J, "
     "H = -(ln u - u + 2 ln v - v); y = (3, 3)",
     GM_PROBLEM_POISSON, 2, 0, NULL, 1, invariant_names, 0},
    sizeof(size_t), NULL, setup, NULL, NULL};
