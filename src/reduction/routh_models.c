/* The two reduced systems of seed 001 §2.9 (J2 satellite) and §2.10 (double spherical pendulum),
 * as mechanical Lagrangians in a trivialisation (include/geomint/reduction.h). */
#include <math.h>
#include <string.h>

#include "geomint/reduction.h"

/* ---- J2 satellite: θ; x = (r, z) ----------------------------------------------------------- */

static int j2_metric(void *ctx, const double *x, double *m) {
  (void)ctx;
  memset(m, 0, 9 * sizeof(double));
  m[0] = x[0] * x[0];
  m[4] = m[8] = 1.0;
  return 0;
}
static int j2_metric_dx(void *ctx, const double *x, double *dm) {
  (void)ctx;
  memset(dm, 0, 18 * sizeof(double));
  dm[0] = 2.0 * x[0]; /* ∂M_θθ/∂r; ∂M/∂z = 0 */
  return 0;
}
static double j2_potential(void *ctx, const double *x) {
  const double j2 = ((gm_routh_j2_params *)ctx)->j2;
  const double r2 = x[0] * x[0] + x[1] * x[1], rho = sqrt(r2);
  return -1.0 / rho + j2 / (r2 * rho) * (1.5 * x[1] * x[1] / r2 - 0.5);
}
/* ∂V/∂ρ at fixed z = ρ⁻² + J2(1.5ρ⁻⁴ − 7.5z²ρ⁻⁶); ∂V/∂z adds 3J2 z ρ⁻⁵ */
static int j2_potential_dx(void *ctx, const double *x, double *g) {
  const double j2 = ((gm_routh_j2_params *)ctx)->j2;
  const double r2 = x[0] * x[0] + x[1] * x[1], rho = sqrt(r2), z = x[1];
  if (!(rho > 0.0)) return 1;
  const double dv = 1.0 / r2 + j2 * (1.5 / (r2 * r2) - 7.5 * z * z / (r2 * r2 * r2));
  g[0] = x[0] / rho * dv;
  g[1] = z / rho * dv + 3.0 * j2 * z / (r2 * r2 * rho);
  return 0;
}

void gm_routh_j2_satellite(gm_routh_j2_params *params, gm_routh_system *sys) {
  *sys = (gm_routh_system){.k = 1, .n = 2, .ctx = params, .metric = j2_metric,
                           .metric_dx = j2_metric_dx, .potential = j2_potential,
                           .potential_dx = j2_potential_dx};
}

/* ---- double spherical pendulum: θ = θ1; x = (r1, r2, φ) ------------------------------------ */

/* the 6×4 Jacobian ∂(q1, q2)/∂(θ, r1, r2, φ) at θ = 0 (M does not depend on θ) and, when dj is
 * not NULL, its derivatives ∂J/∂x_l (3 blocks of 6×4) */
static int dsp_jacobian(const gm_routh_dsp_params *p, const double *x, double j[6][4],
                        double dj[3][6][4]) {
  const double r1 = x[0], r2 = x[1], ph = x[2];
  const double w1 = p->l1 * p->l1 - r1 * r1, w2 = p->l2 * p->l2 - r2 * r2;
  if (!(w1 > 0.0) || !(w2 > 0.0)) return 1;
  const double c2 = cos(ph), s2 = sin(ph);
  memset(j, 0, 24 * sizeof(double));
  j[1][0] = r1;
  j[0][1] = 1.0;
  j[2][1] = r1 / sqrt(w1);
  j[3][0] = j[3][3] = -r2 * s2;
  j[4][0] = j[4][3] = r2 * c2;
  j[3][2] = c2;
  j[4][2] = s2;
  j[5][2] = r2 / sqrt(w2);
  if (dj) {
    memset(dj, 0, 72 * sizeof(double));
    dj[0][1][0] = 1.0;
    dj[0][2][1] = p->l1 * p->l1 / (w1 * sqrt(w1));
    dj[1][3][0] = dj[1][3][3] = -s2;
    dj[1][4][0] = dj[1][4][3] = c2;
    dj[1][5][2] = p->l2 * p->l2 / (w2 * sqrt(w2));
    dj[2][3][0] = dj[2][3][3] = -r2 * c2;
    dj[2][4][0] = dj[2][4][3] = -r2 * s2;
    dj[2][3][2] = -s2;
    dj[2][4][2] = c2;
  }
  return 0;
}

/* uᵀ M_c v over the columns cu of ju and cv of jv, M_c = [[m1 + m2, m2], [m2, m2]] ⊗ I₃ */
static double dsp_form(const gm_routh_dsp_params *p, double ju[6][4], int cu, double jv[6][4],
                       int cv) {
  const double a = p->m1 + p->m2, b = p->m2;
  double t = 0.0;
  for (int i = 0; i < 3; ++i)
    t += a * ju[i][cu] * jv[i][cv] + b * (ju[i][cu] * jv[3 + i][cv] + ju[3 + i][cu] * jv[i][cv]) +
         b * ju[3 + i][cu] * jv[3 + i][cv];
  return t;
}

static int dsp_metric(void *ctx, const double *x, double *m) {
  double j[6][4];
  if (dsp_jacobian(ctx, x, j, NULL)) return 1;
  for (int u = 0; u < 4; ++u)
    for (int v = 0; v < 4; ++v) m[u * 4 + v] = dsp_form(ctx, j, u, j, v);
  return 0;
}

/* ∂_lM = ∂_lJᵀ M_c J + Jᵀ M_c ∂_lJ */
static int dsp_metric_dx(void *ctx, const double *x, double *dm) {
  double j[6][4], dj[3][6][4];
  if (dsp_jacobian(ctx, x, j, dj)) return 1;
  for (int l = 0; l < 3; ++l)
    for (int u = 0; u < 4; ++u)
      for (int v = 0; v < 4; ++v)
        dm[l * 16 + u * 4 + v] = dsp_form(ctx, dj[l], u, j, v) + dsp_form(ctx, j, u, dj[l], v);
  return 0;
}
static double dsp_potential(void *ctx, const double *x) {
  const gm_routh_dsp_params *p = ctx;
  const double z1 = -sqrt(p->l1 * p->l1 - x[0] * x[0]), z2 = -sqrt(p->l2 * p->l2 - x[1] * x[1]);
  return p->m1 * p->g * z1 + p->m2 * p->g * (z1 + z2);
}
static int dsp_potential_dx(void *ctx, const double *x, double *g) {
  const gm_routh_dsp_params *p = ctx;
  const double w1 = p->l1 * p->l1 - x[0] * x[0], w2 = p->l2 * p->l2 - x[1] * x[1];
  if (!(w1 > 0.0) || !(w2 > 0.0)) return 1;
  g[0] = (p->m1 + p->m2) * p->g * x[0] / sqrt(w1);
  g[1] = p->m2 * p->g * x[1] / sqrt(w2);
  g[2] = 0.0;
  return 0;
}

void gm_routh_double_spherical_pendulum(gm_routh_dsp_params *params, gm_routh_system *sys) {
  *sys = (gm_routh_system){.k = 1, .n = 3, .ctx = params, .metric = dsp_metric,
                           .metric_dx = dsp_metric_dx, .potential = dsp_potential,
                           .potential_dx = dsp_potential_dx};
}
