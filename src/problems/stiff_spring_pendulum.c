/* Stiff spring pendulum in Cartesian coordinates as a split potential (seed 001 §5.7.2; the
 * same physics as spring-pendulum, which uses (a, θ)): q = (x, y), M = m I,
 *   U = m g y (slow),   W = (k/2)(|q| − l)² (fast, not quadratic),
 * fast frequency √(k/m) = 100 with the defaults m = 1, g = 9.81, k = 10000, l = 1. Released at
 * rest at angle θ0 with the spring at its static stretch m g / k. Methods that need W = ½qᵀΩ²q
 * (trigonometric filters) refuse it; IMEX solves its midpoint step by Newton's method. */
#include <math.h>

#include "geomint/oscillatory.h"
#include "problems/internal.h"

typedef struct {
  size_t dim;
  double m, g, k, l;
  double mass[2];
  gm_split_potential split;
} ssp;

static double kinetic(void *ctx, const double *p) {
  const ssp *s = ctx;
  return 0.5 * (p[0] * p[0] + p[1] * p[1]) / s->m;
}
static int kinetic_gradient(void *ctx, const double *p, double *out) {
  const ssp *s = ctx;
  out[0] = p[0] / s->m;
  out[1] = p[1] / s->m;
  return 0;
}
static int kinetic_hessian(void *ctx, const double *p, double *h) {
  (void)p;
  const ssp *s = ctx;
  h[0] = h[3] = 1.0 / s->m;
  h[1] = h[2] = 0.0;
  return 0;
}
static double slow(void *ctx, const double *q) {
  const ssp *s = ctx;
  return s->m * s->g * q[1];
}
static int slow_gradient(void *ctx, const double *q, double *out) {
  (void)q;
  const ssp *s = ctx;
  out[0] = 0.0;
  out[1] = s->m * s->g;
  return 0;
}
static double fast(void *ctx, const double *q) {
  const ssp *s = ctx;
  const double e = hypot(q[0], q[1]) - s->l;
  return 0.5 * s->k * e * e;
}
static int fast_gradient(void *ctx, const double *q, double *out) {
  const ssp *s = ctx;
  const double r = hypot(q[0], q[1]);
  if (r == 0.0) return 1; /* the spring's direction is undefined */
  const double c = s->k * (1.0 - s->l / r);
  out[0] = c * q[0];
  out[1] = c * q[1];
  return 0;
}
/* ∇²W = k[(1 − l/r) I + (l/r³) q qᵀ] */
static int fast_hessian(void *ctx, const double *q, double *h) {
  const ssp *s = ctx;
  const double r = hypot(q[0], q[1]);
  if (r == 0.0) return 1;
  const double a = s->k * (1.0 - s->l / r), b = s->k * s->l / (r * r * r);
  h[0] = a + b * q[0] * q[0];
  h[1] = h[2] = b * q[0] * q[1];
  h[3] = a + b * q[1] * q[1];
  return 0;
}
static double potential(void *ctx, const double *q) { return slow(ctx, q) + fast(ctx, q); }
static int potential_gradient(void *ctx, const double *q, double *out) {
  const ssp *s = ctx;
  if (fast_gradient(ctx, q, out) != 0) return 1;
  out[1] += s->m * s->g;
  return 0;
}
static int potential_hessian(void *ctx, const double *q, double *h) {
  return fast_hessian(ctx, q, h);
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  (void)t0;
  ssp *s = ctx;
  if (!(params[0] > 0.0) || !(params[2] > 0.0) || !(params[3] > 0.0) || !(params[1] >= 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL, "stiff-spring-pendulum: need m, k, l > 0, g >= 0");
  s->dim = 2;
  s->m = params[0];
  s->g = params[1];
  s->k = params[2];
  s->l = params[3];
  s->mass[0] = s->mass[1] = s->m;
  s->split = (gm_split_potential){slow, slow_gradient, fast, fast_gradient, fast_hessian,
                                  NULL, 0, s->mass};
  pb->kinetic = kinetic;
  pb->kinetic_gradient = kinetic_gradient;
  pb->kinetic_hessian = kinetic_hessian;
  pb->kinetic_is_quadratic = 1;
  pb->potential = potential;
  pb->potential_gradient = potential_gradient;
  pb->potential_hessian = potential_hessian;
  pb->split = &s->split;
  const double r = s->l + s->m * s->g / s->k, th = params[4];
  y0[0] = r * sin(th);
  y0[1] = -r * cos(th);
  y0[2] = y0[3] = 0.0;
  return GM_OK;
}

const gm_model_def gm_model_stiff_spring_pendulum = {
    {"stiff-spring-pendulum",
     "stiff spring pendulum in Cartesian q = (x, y): U = m g y (slow), W = k(|q| - l)^2/2 "
     "(fast, nonlinear) (seed 001 5.7.2)",
     GM_PROBLEM_SEPARABLE, 2, 5, gm_spring_pendulum_params, 0, NULL, 0},
    sizeof(ssp), NULL, setup, NULL, NULL};
