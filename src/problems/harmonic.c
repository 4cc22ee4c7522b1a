/* Harmonic oscillator H = ½p² + ½ω²q², exact solution by rotation in phase space. */
#include <math.h>

#include "problems/internal.h"

typedef struct {
  size_t dim;
  double omega, q0, p0;
} harmonic;

static double potential(void *ctx, const double *q) {
  const harmonic *h = ctx;
  return 0.5 * h->omega * h->omega * q[0] * q[0];
}

static int potential_gradient(void *ctx, const double *q, double *out) {
  const harmonic *h = ctx;
  out[0] = h->omega * h->omega * q[0];
  return 0;
}

static int potential_hessian(void *ctx, const double *q, double *out) {
  (void)q;
  const harmonic *h = ctx;
  out[0] = h->omega * h->omega;
  return 0;
}

static int exact(void *ctx, double t, double *y) {
  const harmonic *h = ctx;
  double c = cos(h->omega * t), s = sin(h->omega * t);
  y[0] = h->q0 * c + h->p0 / h->omega * s;
  y[1] = -h->q0 * h->omega * s + h->p0 * c;
  return 0;
}

static int initial_changed(void *ctx, const double *y0) {
  harmonic *h = ctx;
  h->q0 = y0[0];
  h->p0 = y0[1];
  return 1; /* the exact solution holds for every initial state */
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  harmonic *h = ctx;
  (void)t0;
  if (!(params[0] > 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL, "harmonic: omega must be positive, got %g", params[0]);
  *h = (harmonic){1, params[0], 1.0, 0.0};
  gm_free_kinetic_setup(pb);
  pb->potential = potential;
  pb->potential_gradient = potential_gradient;
  pb->potential_hessian = potential_hessian;
  pb->exact = exact;
  y0[0] = h->q0;
  y0[1] = h->p0;
  return GM_OK;
}

static const gm_param_info params[] = {{"omega", 1.0, "angular frequency", GM_PARAM_NUMBER}};

const gm_model_def gm_model_harmonic = {
    {"harmonic", "harmonic oscillator H = p^2/2 + omega^2 q^2/2, q = 1, p = 0",
     GM_PROBLEM_SEPARABLE, 1, 1, params, 0, NULL, 1},
    sizeof(harmonic), NULL, setup, initial_changed, NULL};
