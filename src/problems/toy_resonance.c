/* The toy resonance problem of seed 000 §2.2.3–2.2.4 (Fig. 2.1; notes E1): one degree of
 * freedom, M = 1, slow U = ½ c q² (+ ¼ b q⁴, b = 0 by default) and fast W = ½ ω² q², so
 * H = ½p² + ½(c + ω²)q². With b = 0 linear, with exact solution q = q0 cos νt + (p0/ν) sin νt, ν = √(c + ω²). It is where impulse methods
 * resonate (hω near multiples of π) and where Thm 2.2.3 (IMEX stable iff h ≤ 2 for every ω,
 * c = 1) is checked. c = 0 (U = 0) and ω = 0 (W = 0) are allowed: the reductions of IMEX to
 * implicit midpoint and to Verlet. Initial state q0 = 0, p0 = 1 (the seed gives none). */
#include <math.h>

#include "geomint/oscillatory.h"
#include "problems/internal.h"

typedef struct {
  size_t dim;
  double c, omega, b, q0, p0;
  double omega_diag[1];
  gm_split_potential split;
} toy;

static double slow(void *ctx, const double *q) {
  const toy *s = ctx;
  const double q2 = q[0] * q[0];
  return 0.5 * s->c * q2 + 0.25 * s->b * q2 * q2;
}
static int slow_gradient(void *ctx, const double *q, double *out) {
  const toy *s = ctx;
  out[0] = (s->c + s->b * q[0] * q[0]) * q[0];
  return 0;
}
static double fast(void *ctx, const double *q) {
  const toy *s = ctx;
  return 0.5 * s->omega * s->omega * q[0] * q[0];
}
static int fast_gradient(void *ctx, const double *q, double *out) {
  const toy *s = ctx;
  out[0] = s->omega * s->omega * q[0];
  return 0;
}
static double potential(void *ctx, const double *q) { return slow(ctx, q) + fast(ctx, q); }
static int potential_gradient(void *ctx, const double *q, double *out) {
  const toy *s = ctx;
  out[0] = (s->c + s->b * q[0] * q[0] + s->omega * s->omega) * q[0];
  return 0;
}
static int potential_hessian(void *ctx, const double *q, double *out) {
  const toy *s = ctx;
  out[0] = s->c + 3.0 * s->b * q[0] * q[0] + s->omega * s->omega;
  return 0;
}

static int exact(void *ctx, double t, double *y) {
  const toy *s = ctx;
  const double nu = sqrt(s->c + s->omega * s->omega);
  if (nu == 0.0) {
    y[0] = s->q0 + s->p0 * t;
    y[1] = s->p0;
    return 0;
  }
  const double cs = cos(nu * t), sn = sin(nu * t);
  y[0] = s->q0 * cs + s->p0 / nu * sn;
  y[1] = -s->q0 * nu * sn + s->p0 * cs;
  return 0;
}

static int initial_changed(void *ctx, const double *y0) {
  toy *s = ctx;
  s->q0 = y0[0];
  s->p0 = y0[1];
  return 1;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  (void)t0;
  toy *s = ctx;
  if (!(params[0] >= 0.0) || !(params[1] >= 0.0) || !(params[2] >= 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL, "toy-resonance: need c, omega, quartic >= 0");
  s->dim = 1;
  s->c = params[0];
  s->omega = params[1];
  s->b = params[2];
  s->omega_diag[0] = s->omega;
  s->split = (gm_split_potential){slow, slow_gradient, fast, fast_gradient, NULL,
                                  s->omega_diag, 1, NULL};
  gm_free_kinetic_setup(pb);
  pb->potential = potential;
  pb->potential_gradient = potential_gradient;
  pb->potential_hessian = potential_hessian;
  if (s->b == 0.0) pb->exact = exact;
  pb->split = &s->split;
  s->q0 = y0[0] = 0.0;
  s->p0 = y0[1] = 1.0;
  return GM_OK;
}

static const gm_param_info params[] = {
    {"c", 1.0, "slow stiffness: U = c q^2/2", GM_PARAM_NUMBER},
    {"omega", 10.0, "fast frequency: W = omega^2 q^2/2", GM_PARAM_NUMBER},
    {"quartic", 0.0, "b in U = c q^2/2 + b q^4/4 (0: linear, exact solution)", GM_PARAM_NUMBER},
};

const gm_model_def gm_model_toy_resonance = {
    {"toy-resonance",
     "split potential U = c q^2/2 (slow), W = omega^2 q^2/2 (fast); the resonance test of "
     "seed 000 2.2.3",
     GM_PROBLEM_SEPARABLE, 1, 3, params, 0, NULL, 1},
    sizeof(toy), NULL, setup, initial_changed, NULL};
