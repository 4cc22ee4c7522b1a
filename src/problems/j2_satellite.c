/* A satellite about an oblate planet (seed 001 §2.9): L = ½|v|² − V(q) in R³ with
 *   V = −1/ρ + (J2/ρ³)(3z²/(2ρ²) − ½),  ρ = |q|,
 * the potential as corrected in the notes (the thesis prints +1/|q|, a repulsive Kepler term).
 * Units: planet radius 1, period 2π of the zero-altitude orbit for J2 = 0. Rotations about the
 * polar axis keep L: ξ_Q = e_z × q, Noether momentum J = x p_y − y p_x. Started on a slightly
 * inclined circular orbit of radius r0 (circular for J2 = 0). */
#include <math.h>

#include "problems/internal.h"

typedef struct {
  size_t dim;
  double j2;
} j2sat;

static double potential(const j2sat *s, const double *q) {
  const double r2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2], r = sqrt(r2);
  return -1.0 / r + s->j2 / (r2 * r) * (1.5 * q[2] * q[2] / r2 - 0.5);
}

static double lagrangian(void *ctx, const double *q, const double *v) {
  return 0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - potential(ctx, q);
}

/* ∂V/∂x_i = x_i/ρ³ + J2 [3x_i/(2ρ⁵) − 15z²x_i/(2ρ⁷)] + δ_iz 3J2 z/ρ⁵ */
static int dl_dq(void *ctx, const double *q, const double *v, double *out) {
  const j2sat *s = ctx;
  (void)v;
  const double r2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
  if (r2 == 0.0) return 1;
  const double r = sqrt(r2), r3 = r2 * r, r5 = r3 * r2, r7 = r5 * r2, z2 = q[2] * q[2];
  for (int i = 0; i < 3; ++i)
    out[i] = -(q[i] / r3 + s->j2 * (1.5 * q[i] / r5 - 7.5 * z2 * q[i] / r7));
  out[2] -= 3.0 * s->j2 * q[2] / r5;
  return 0;
}

static int dl_dv(void *ctx, const double *q, const double *v, double *out) {
  (void)ctx;
  (void)q;
  for (int i = 0; i < 3; ++i) out[i] = v[i];
  return 0;
}

/* L_qq = −∇²V, differentiating the gradient above term by term; L_vv = I */
static int hessian(void *ctx, const double *q, const double *v, double *h) {
  const j2sat *s = ctx;
  (void)v;
  const double r2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
  if (r2 == 0.0) return 1;
  const double r = sqrt(r2), r3 = r2 * r, r5 = r3 * r2, r7 = r5 * r2, r9 = r7 * r2;
  const double z = q[2], z2 = z * z, j2 = s->j2;
  for (int i = 0; i < 36; ++i) h[i] = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double dij = i == j ? 1.0 : 0.0, djz = j == 2 ? 1.0 : 0.0, diz = i == 2 ? 1.0 : 0.0;
      double hv = dij / r3 - 3.0 * q[i] * q[j] / r5;
      hv += j2 * 1.5 * (dij / r5 - 5.0 * q[i] * q[j] / r7);
      hv -= j2 * 7.5 * (2.0 * z * djz * q[i] / r7 + z2 * dij / r7 - 7.0 * z2 * q[i] * q[j] / r9);
      hv += diz * 3.0 * j2 * (djz / r5 - 5.0 * z * q[j] / r7);
      h[i * 6 + j] = -hv;
    }
  for (int i = 0; i < 3; ++i) h[(3 + i) * 6 + 3 + i] = 1.0;
  return 0;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  j2sat *s = ctx;
  (void)t0;
  if (!(params[1] > 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL, "j2-satellite: the radius r0 must be positive");
  *s = (j2sat){3, params[0]};
  pb->lagrangian = lagrangian;
  pb->dl_dq = dl_dq;
  pb->dl_dv = dl_dv;
  pb->lagrangian_hessian = hessian;
  pb->kinetic_is_quadratic = 1;
  gm_rotation_z_setup(pb);
  const double r0 = params[1], inc = params[2], vc = sqrt(1.0 / r0);
  y0[0] = r0;
  y0[1] = y0[2] = 0.0;
  y0[3] = 0.0;
  y0[4] = vc * cos(inc);
  y0[5] = vc * sin(inc);
  return GM_OK;
}

static const gm_param_info params[] = {
    {"J2", 0.05, "oblateness coefficient (Earth: about 1.08e-3)", GM_PARAM_NUMBER},
    {"r0", 1.5, "initial radius (planet radius 1)", GM_PARAM_NUMBER},
    {"inclination", 0.3, "initial inclination of the orbit (rad)", GM_PARAM_NUMBER},
};

const gm_model_def gm_model_j2_satellite = {
    {"j2-satellite",
     "satellite about an oblate planet, V = -1/r + (J2/r^3)(3z^2/(2r^2) - 1/2) (seed 001 2.9)",
     GM_PROBLEM_LAGRANGIAN, 3, 3, params, 1, gm_rotation_z_invariant_names, 0},
    sizeof(j2sat), NULL, setup, NULL, NULL};
