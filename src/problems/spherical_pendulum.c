/* Spherical pendulum as a constrained system in R³ (seed 001 §2.10, the single pendulum of the
 * double one): L = ½m|v|² − m g z with g(q) = ½(|q|² − l²) = 0. Rotations about the vertical
 * leave L and the constraint invariant: ξ_Q(q) = e_z × q, whose Noether momentum is the vertical
 * angular momentum J = p·ξ_Q = x p_y − y p_x. Released at the polar angle θ0 from the downward
 * vertical with the azimuthal rate ω0. */
#include <math.h>

#include "problems/internal.h"

typedef struct {
  size_t dim;
  double m, l, g;
} spherical;

static double lagrangian(void *ctx, const double *q, const double *v) {
  const spherical *s = ctx;
  return 0.5 * s->m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - s->m * s->g * q[2];
}

static int dl_dq(void *ctx, const double *q, const double *v, double *out) {
  const spherical *s = ctx;
  (void)q;
  (void)v;
  out[0] = out[1] = 0.0;
  out[2] = -s->m * s->g;
  return 0;
}

static int dl_dv(void *ctx, const double *q, const double *v, double *out) {
  const spherical *s = ctx;
  (void)q;
  for (int i = 0; i < 3; ++i) out[i] = s->m * v[i];
  return 0;
}

static int hessian(void *ctx, const double *q, const double *v, double *h) {
  const spherical *s = ctx;
  (void)q;
  (void)v;
  for (int i = 0; i < 36; ++i) h[i] = 0.0;
  for (int i = 0; i < 3; ++i) h[(3 + i) * 6 + 3 + i] = s->m;
  return 0;
}

static int constraint(void *ctx, const double *q, double *g) {
  const spherical *s = ctx;
  g[0] = 0.5 * (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - s->l * s->l);
  return 0;
}

static int constraint_jacobian(void *ctx, const double *q, double *jac) {
  (void)ctx;
  for (int i = 0; i < 3; ++i) jac[i] = q[i];
  return 0;
}

/* λ ∇²g = λ I₃ */
static int constraint_hessian(void *ctx, const double *q, const double *lambda, double *out) {
  (void)ctx;
  (void)q;
  for (int i = 0; i < 9; ++i) out[i] = 0.0;
  for (int i = 0; i < 3; ++i) out[4 * i] = lambda[0];
  return 0;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  spherical *s = ctx;
  (void)t0;
  if (!(params[0] > 0.0) || !(params[1] > 0.0) || !(params[2] >= 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "spherical-pendulum: need m > 0, l > 0 and g >= 0 (got %g, %g, %g)",
                   params[0], params[1], params[2]);
  *s = (spherical){3, params[0], params[1], params[2]};
  pb->lagrangian = lagrangian;
  pb->dl_dq = dl_dq;
  pb->dl_dv = dl_dv;
  pb->lagrangian_hessian = hessian;
  pb->kinetic_is_quadratic = 1;
  pb->n_constraints = 1;
  pb->constraint = constraint;
  pb->constraint_jacobian = constraint_jacobian;
  pb->constraint_hessian = constraint_hessian;
  gm_rotation_z_setup(pb);
  const double th = params[3], w = params[4];
  y0[0] = s->l * sin(th);
  y0[1] = 0.0;
  y0[2] = -s->l * cos(th);
  y0[3] = 0.0; /* p = m v, v = ω0 e_z × q (tangent to the sphere) */
  y0[4] = s->m * w * y0[0];
  y0[5] = 0.0;
  return GM_OK;
}

static const gm_param_info params[] = {
    {"m", 1.0, "mass", GM_PARAM_NUMBER},
    {"l", 1.0, "length: |q| = l", GM_PARAM_NUMBER},
    {"g", 9.81, "gravity (along -z)", GM_PARAM_NUMBER},
    {"theta0", 1.0, "initial angle from the downward vertical", GM_PARAM_NUMBER},
    {"omega0", 2.0, "initial azimuthal angular velocity", GM_PARAM_NUMBER},
};

const gm_model_def gm_model_spherical_pendulum = {
    {"spherical-pendulum",
     "spherical pendulum in R^3 with |q| = l as a holonomic constraint, L = m|v|^2/2 - m g z",
     GM_PROBLEM_LAGRANGIAN, 3, 5, params, 1, gm_rotation_z_invariant_names, 0},
    sizeof(spherical), NULL, setup, NULL, NULL};
