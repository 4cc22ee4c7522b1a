/* Stiff spring pendulum (seed 001 §5.7.2): q = (a, θ), the stretch of the spring and the angle,
 *   x = (l + a) sin θ, y = −(l + a) cos θ,
 *   L = (m/2)(ȧ² + (l + a)² θ̇²) + m g (l + a) cos θ − (k/2) a²,
 * whose Euler–Lagrange equations are the thesis's ṗ_a = −ka + gm cos θ + m(l + a)θ̇²,
 * ṗ_θ = −gm(l + a) sin θ. The mass matrix depends on a: a general (non-quadratic) Lagrangian.
 * With m = 1, g = 9.81, k = 10000, l = 1 the spring is stiff: ε = √(mg/(kl)) = 0.0313, fast
 * frequency √(k/m) = 100. Released at rest from θ0 with the spring at its static stretch mg/k. */
#include <math.h>

#include "problems/internal.h"

typedef struct {
  size_t dim;
  double m, g, k, l;
} spring;

static double lagrangian(void *ctx, const double *q, const double *v) {
  const spring *s = ctx;
  const double r = s->l + q[0];
  return 0.5 * s->m * (v[0] * v[0] + r * r * v[1] * v[1]) + s->m * s->g * r * cos(q[1]) -
         0.5 * s->k * q[0] * q[0];
}

static int dl_dq(void *ctx, const double *q, const double *v, double *out) {
  const spring *s = ctx;
  const double r = s->l + q[0];
  out[0] = s->m * r * v[1] * v[1] + s->m * s->g * cos(q[1]) - s->k * q[0];
  out[1] = -s->m * s->g * r * sin(q[1]);
  return 0;
}

static int dl_dv(void *ctx, const double *q, const double *v, double *out) {
  const spring *s = ctx;
  const double r = s->l + q[0];
  out[0] = s->m * v[0];
  out[1] = s->m * r * r * v[1];
  return 0;
}

/* second derivatives in (a, θ, ȧ, θ̇) */
static int hessian(void *ctx, const double *q, const double *v, double *h) {
  const spring *s = ctx;
  const double r = s->l + q[0], m = s->m;
  for (int i = 0; i < 16; ++i) h[i] = 0.0;
  h[0 * 4 + 0] = m * v[1] * v[1] - s->k;
  h[0 * 4 + 1] = h[1 * 4 + 0] = -m * s->g * sin(q[1]);
  h[1 * 4 + 1] = -m * s->g * r * cos(q[1]);
  h[0 * 4 + 3] = h[3 * 4 + 0] = 2.0 * m * r * v[1];
  h[2 * 4 + 2] = m;
  h[3 * 4 + 3] = m * r * r;
  return 0;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  spring *s = ctx;
  (void)t0;
  if (!(params[0] > 0.0) || !(params[2] > 0.0) || !(params[3] > 0.0) || !(params[1] >= 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL, "spring-pendulum: need m, k, l > 0 and g >= 0");
  *s = (spring){2, params[0], params[1], params[2], params[3]};
  pb->lagrangian = lagrangian;
  pb->dl_dq = dl_dq;
  pb->dl_dv = dl_dv;
  pb->lagrangian_hessian = hessian;
  y0[0] = s->m * s->g / s->k;
  y0[1] = params[4];
  y0[2] = y0[3] = 0.0;
  return GM_OK;
}

/* shared with the Cartesian form (stiff_spring_pendulum.c): one system, one set of defaults */
const gm_param_info gm_spring_pendulum_params[] = {
    {"m", 1.0, "mass", GM_PARAM_NUMBER},
    {"g", 9.81, "gravity", GM_PARAM_NUMBER},
    {"k", 10000.0, "spring constant (stiff)", GM_PARAM_NUMBER},
    {"l", 1.0, "rest length", GM_PARAM_NUMBER},
    {"theta0", 1.0, "initial angle", GM_PARAM_NUMBER},
};

const gm_model_def gm_model_spring_pendulum = {
    {"spring-pendulum",
     "stiff spring pendulum in (a, theta), L = m(a'^2 + (l+a)^2 theta'^2)/2 + m g (l+a) cos "
     "theta - k a^2/2 (seed 001 5.7.2)",
     GM_PROBLEM_LAGRANGIAN, 2, 5, gm_spring_pendulum_params, 0, NULL, 0},
    sizeof(spring), NULL, setup, NULL, NULL};
