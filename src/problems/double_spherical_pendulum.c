/* Double spherical pendulum as a constrained system in R³ × R³ (seed 001 §2.10): q1 is the first
 * mass, q2 the second relative to the first,
 *   L = ½m1|v1|² + ½m2|v1 + v2|² − m1 g z1 − m2 g (z1 + z2),
 *   g(q) = (½(|q1|² − l1²), ½(|q2|² − l2²)) = 0,
 * (the constrained R³×R³ form the notes recommend over the reduced one, whose chart is singular
 * at r_i = 0). Rotations about the vertical, ξ_Q(q) = (e_z × q1, e_z × q2), keep L and g; the
 * Noether momentum p·ξ_Q is the total vertical angular momentum
 * m1 (q1 × v1)_z + m2 ((q1 + q2) × (v1 + v2))_z. */
#include <math.h>

#include "problems/internal.h"

typedef struct {
  size_t dim;
  double m1, m2, l1, l2, g;
} double_spherical;

/* M v with M = [[m1 + m2, m2], [m2, m2]] ⊗ I₃ */
static void mass_times(const double_spherical *s, const double *v, double *out) {
  for (int i = 0; i < 3; ++i) {
    out[i] = (s->m1 + s->m2) * v[i] + s->m2 * v[3 + i];
    out[3 + i] = s->m2 * (v[i] + v[3 + i]);
  }
}

static double lagrangian(void *ctx, const double *q, const double *v) {
  const double_spherical *s = ctx;
  double mv[6], t = 0.0;
  mass_times(s, v, mv);
  for (int i = 0; i < 6; ++i) t += v[i] * mv[i];
  return 0.5 * t - s->m1 * s->g * q[2] - s->m2 * s->g * (q[2] + q[5]);
}

static int dl_dq(void *ctx, const double *q, const double *v, double *out) {
  const double_spherical *s = ctx;
  (void)q;
  (void)v;
  for (int i = 0; i < 6; ++i) out[i] = 0.0;
  out[2] = -(s->m1 + s->m2) * s->g;
  out[5] = -s->m2 * s->g;
  return 0;
}

static int dl_dv(void *ctx, const double *q, const double *v, double *out) {
  (void)q;
  mass_times(ctx, v, out);
  return 0;
}

static int hessian(void *ctx, const double *q, const double *v, double *h) {
  const double_spherical *s = ctx;
  (void)q;
  (void)v;
  for (int i = 0; i < 144; ++i) h[i] = 0.0;
  for (int i = 0; i < 3; ++i) {
    h[(6 + i) * 12 + 6 + i] = s->m1 + s->m2;
    h[(6 + i) * 12 + 9 + i] = s->m2;
    h[(9 + i) * 12 + 6 + i] = s->m2;
    h[(9 + i) * 12 + 9 + i] = s->m2;
  }
  return 0;
}

static int constraint(void *ctx, const double *q, double *g) {
  const double_spherical *s = ctx;
  g[0] = 0.5 * (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - s->l1 * s->l1);
  g[1] = 0.5 * (q[3] * q[3] + q[4] * q[4] + q[5] * q[5] - s->l2 * s->l2);
  return 0;
}

static int constraint_jacobian(void *ctx, const double *q, double *jac) {
  (void)ctx;
  for (int i = 0; i < 12; ++i) jac[i] = 0.0;
  for (int i = 0; i < 3; ++i) {
    jac[i] = q[i];
    jac[6 + 3 + i] = q[3 + i];
  }
  return 0;
}

/* λ1 ∇²g1 + λ2 ∇²g2 = diag(λ1 I₃, λ2 I₃) */
static int constraint_hessian(void *ctx, const double *q, const double *lambda, double *out) {
  (void)ctx;
  (void)q;
  for (int i = 0; i < 36; ++i) out[i] = 0.0;
  for (int i = 0; i < 3; ++i) {
    out[7 * i] = lambda[0];
    out[7 * (3 + i)] = lambda[1];
  }
  return 0;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  double_spherical *s = ctx;
  (void)t0;
  for (int i = 0; i < 4; ++i)
    if (!(params[i] > 0.0))
      return gm_fail(errmsg, cap, GM_EINVAL,
                     "double-spherical-pendulum: masses and lengths must be positive");
  if (!(params[4] >= 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL, "double-spherical-pendulum: g must be >= 0");
  *s = (double_spherical){6, params[0], params[1], params[2], params[3], params[4]};
  pb->lagrangian = lagrangian;
  pb->dl_dq = dl_dq;
  pb->dl_dv = dl_dv;
  pb->lagrangian_hessian = hessian;
  pb->kinetic_is_quadratic = 1;
  pb->n_constraints = 2;
  pb->constraint = constraint;
  pb->constraint_jacobian = constraint_jacobian;
  pb->constraint_hessian = constraint_hessian;
  gm_rotation_z_setup(pb);
  /* first link at 1 rad from the vertical in the xz-plane, second at 0.5 rad turned by 90°;
   * velocities tangent to both spheres: v1 = ω1 e_z × q1, v2 = ω2 e_z × q2 + ν t2 with t2 the
   * polar unit tangent of q2 */
  const double a1 = 1.0, a2 = 0.5, w1 = params[5], w2 = params[6], nu = 1.0;
  double q[6] = {s->l1 * sin(a1), 0.0, -s->l1 * cos(a1), 0.0, s->l2 * sin(a2),
                 -s->l2 * cos(a2)};
  double v[6] = {-w1 * q[1], w1 * q[0], 0.0, -w2 * q[4], w2 * q[3], 0.0};
  v[4] += nu * s->l2 * cos(a2);
  v[5] += nu * s->l2 * sin(a2);
  for (int i = 0; i < 6; ++i) y0[i] = q[i];
  mass_times(s, v, y0 + 6);
  return GM_OK;
}

static const gm_param_info params[] = {
    {"m1", 1.0, "first mass", GM_PARAM_NUMBER},
    {"m2", 1.0, "second mass", GM_PARAM_NUMBER},
    {"l1", 1.0, "first length", GM_PARAM_NUMBER},
    {"l2", 1.0, "second length", GM_PARAM_NUMBER},
    {"g", 9.81, "gravity (along -z)", GM_PARAM_NUMBER},
    {"omega1", 1.5, "initial azimuthal rate of the first link", GM_PARAM_NUMBER},
    {"omega2", -1.0, "initial azimuthal rate of the second link", GM_PARAM_NUMBER},
};

const gm_model_def gm_model_double_spherical_pendulum = {
    {"double-spherical-pendulum",
     "double spherical pendulum in R^3 x R^3 with two length constraints (seed 001 2.10)",
     GM_PROBLEM_LAGRANGIAN, 6, 7, params, 1, gm_rotation_z_invariant_names, 0},
    sizeof(double_spherical), NULL, setup, NULL, NULL};
