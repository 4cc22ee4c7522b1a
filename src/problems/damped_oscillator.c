/* Damped harmonic oscillator as a forced Lagrangian system (Lagrange–d'Alembert):
 * L = ½m v² − ½k q², F = −c v. Its energy E = ½mv² + ½kq² decays at the rate dE/dt = −c v².
 * Exact solution (underdamped, γ = c/(2m) < ω0 = √(k/m), ω = √(ω0² − γ²)):
 *   q(t) = e^{−γt}(q0 cos ωt + (v0 + γ q0)/ω sin ωt), p = m q'. */
#include <math.h>

#include "problems/internal.h"

typedef struct {
  size_t dim;
  double m, k, c, q0, v0;
} damped;

static double lagrangian(void *ctx, const double *q, const double *v) {
  const damped *s = ctx;
  return 0.5 * s->m * v[0] * v[0] - 0.5 * s->k * q[0] * q[0];
}

static int dl_dq(void *ctx, const double *q, const double *v, double *out) {
  (void)v;
  out[0] = -((const damped *)ctx)->k * q[0];
  return 0;
}

static int dl_dv(void *ctx, const double *q, const double *v, double *out) {
  (void)q;
  out[0] = ((const damped *)ctx)->m * v[0];
  return 0;
}

static int hessian(void *ctx, const double *q, const double *v, double *h) {
  const damped *s = ctx;
  (void)q;
  (void)v;
  h[0] = -s->k;
  h[1] = h[2] = 0.0;
  h[3] = s->m;
  return 0;
}

static int force(void *ctx, double t, const double *q, const double *v, double *f) {
  (void)t;
  (void)q;
  f[0] = -((const damped *)ctx)->c * v[0];
  return 0;
}

static int exact(void *ctx, double t, double *y) {
  const damped *s = ctx;
  const double g = s->c / (2.0 * s->m), w = sqrt(s->k / s->m - g * g);
  const double a = s->q0, b = (s->v0 + g * s->q0) / w, e = exp(-g * t);
  const double c = cos(w * t), sn = sin(w * t);
  y[0] = e * (a * c + b * sn);
  y[1] = s->m * e * (-g * (a * c + b * sn) + w * (-a * sn + b * c));
  return 0;
}

static int initial_changed(void *ctx, const double *y0) {
  damped *s = ctx;
  s->q0 = y0[0];
  s->v0 = y0[1] / s->m;
  return 1;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  damped *s = ctx;
  (void)t0;
  const double m = params[0], k = params[1], c = params[2];
  if (!(m > 0.0) || !(k > 0.0) || !(c >= 0.0) || !(c * c < 4.0 * m * k))
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "damped-oscillator: need m > 0, k > 0 and 0 <= c < 2 sqrt(mk) (underdamped)");
  *s = (damped){1, m, k, c, 1.0, 0.0};
  pb->lagrangian = lagrangian;
  pb->dl_dq = dl_dq;
  pb->dl_dv = dl_dv;
  pb->lagrangian_hessian = hessian;
  pb->kinetic_is_quadratic = 1;
  pb->force = force;
  pb->exact = exact;
  y0[0] = 1.0;
  y0[1] = 0.0;
  return GM_OK;
}

static const gm_param_info params[] = {
    {"m", 1.0, "mass", GM_PARAM_NUMBER},
    {"k", 1.0, "spring constant", GM_PARAM_NUMBER},
    {"c", 0.1, "damping coefficient: F = -c v", GM_PARAM_NUMBER},
};

const gm_model_def gm_model_damped_oscillator = {
    {"damped-oscillator", "damped oscillator L = m v^2/2 - k q^2/2 with the force F = -c v",
     GM_PROBLEM_LAGRANGIAN, 1, 3, params, 0, NULL, 1},
    sizeof(damped), NULL, setup, initial_changed, NULL};
