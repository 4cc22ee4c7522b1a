/* Kepler problem H = ½|p|² − 1/|q| in the plane, started at pericentre with semi-major axis 1
 * (period 2π): q = (1 − e, 0), p = (0, √((1+e)/(1−e))), as in Hairer, Lubich & Wanner,
 * GNI (2006), §I.2.3. Exact solution through Kepler's equation E − e sin E = t. */
#include <math.h>

#include "problems/internal.h"

typedef struct {
  size_t dim;
  double e;
} kepler;

static double radius(const double *q) { return sqrt(q[0] * q[0] + q[1] * q[1]); }

static double potential(void *ctx, const double *q) {
  (void)ctx;
  return -1.0 / radius(q);
}

/* ∇V = q/r³; a collision (r = 0) is reported as a failed evaluation. */
static int potential_gradient(void *ctx, const double *q, double *out) {
  (void)ctx;
  double r = radius(q);
  if (r == 0.0) return 1;
  double r3 = r * r * r;
  out[0] = q[0] / r3;
  out[1] = q[1] / r3;
  return 0;
}

/* ∇²V = I/r³ − 3 q qᵀ/r⁵ */
static int potential_hessian(void *ctx, const double *q, double *out) {
  (void)ctx;
  double r = radius(q);
  if (r == 0.0) return 1;
  double r3 = r * r * r, r5 = r3 * r * r;
  out[0] = 1.0 / r3 - 3.0 * q[0] * q[0] / r5;
  out[1] = -3.0 * q[0] * q[1] / r5;
  out[2] = out[1];
  out[3] = 1.0 / r3 - 3.0 * q[1] * q[1] / r5;
  return 0;
}

static double angular_momentum(void *ctx, const double *y) {
  (void)ctx;
  return y[0] * y[3] - y[1] * y[2];
}

/* |A| for the Runge–Lenz vector A = p × L − q/|q|; equals the eccentricity on the exact flow. */
static double runge_lenz(void *ctx, const double *y) {
  (void)ctx;
  double l = angular_momentum(ctx, y), r = radius(y);
  double ax = y[3] * l - y[0] / r, ay = -y[2] * l - y[1] / r;
  return sqrt(ax * ax + ay * ay);
}

static const gm_invariant invariants[] = {{"angular-momentum", angular_momentum},
                                          {"runge-lenz", runge_lenz}};
static const char *const invariant_names[] = {"angular-momentum", "runge-lenz"};

/* Newton's method on E − e sin E = M (Danby's starting value E₀ = M + 0.85 e sign(sin M)). */
static int exact(void *ctx, double t, double *y) {
  const kepler *k = ctx;
  const double e = k->e;
  double m = fmod(t, 2.0 * GM_PI);
  double ecc_anomaly = m + 0.85 * e * (sin(m) >= 0.0 ? 1.0 : -1.0);
  for (int it = 0; it < 60; ++it) {
    double f = ecc_anomaly - e * sin(ecc_anomaly) - m;
    double step = f / (1.0 - e * cos(ecc_anomaly));
    ecc_anomaly -= step;
    if (fabs(step) <= 4e-16 * fmax(1.0, fabs(ecc_anomaly))) break;
  }
  double c = cos(ecc_anomaly), s = sin(ecc_anomaly), b = sqrt(1.0 - e * e);
  double rate = 1.0 / (1.0 - e * c); /* dE/dt */
  y[0] = c - e;
  y[1] = b * s;
  y[2] = -s * rate;
  y[3] = b * c * rate;
  return 0;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  kepler *k = ctx;
  (void)t0;
  double e = params[0];
  if (!(e >= 0.0 && e < 1.0))
    return gm_fail(errmsg, cap, GM_EINVAL, "kepler: eccentricity e must be in [0, 1), got %g", e);
  *k = (kepler){2, e};
  gm_free_kinetic_setup(pb);
  pb->potential = potential;
  pb->potential_gradient = potential_gradient;
  pb->potential_hessian = potential_hessian;
  pb->n_invariants = 2;
  pb->invariants = invariants;
  pb->exact = exact;
  y0[0] = 1.0 - e;
  y0[1] = 0.0;
  y0[2] = 0.0;
  y0[3] = sqrt((1.0 + e) / (1.0 - e));
  return GM_OK;
}

static const gm_param_info params[] = {{"e", 0.6, "eccentricity, 0 <= e < 1", GM_PARAM_NUMBER}};

const gm_model_def gm_model_kepler = {
    {"kepler", "Kepler two-body problem H = p^2/2 - 1/r, started at pericentre, period 2 pi",
     GM_PROBLEM_SEPARABLE, 2, 1, params, 2, invariant_names, 1},
    sizeof(kepler), NULL, setup, NULL, NULL};
