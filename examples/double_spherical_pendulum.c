/* From a Lagrangian to an integrator: the double spherical pendulum in R³ × R³ (seed 001
 * §2.10), written from scratch as a user would, integrated with a variational integrator.
 *
 *   L = ½m1|v1|² + ½m2|v1 + v2|² − m1 g z1 − m2 g (z1 + z2)      (q2 relative to q1)
 *   g(q) = (½(|q1|² − l1²), ½(|q2|² − l2²)) = 0                  (holonomic constraints)
 *   ξ_Q(q) = (e_z × q1, e_z × q2)                                (rotations about the vertical)
 *
 * Build: cc double_spherical_pendulum.c -lgeomint -llapacke -lm
 * Run:   ./double_spherical_pendulum [steps] [h] > out.csv
 * Prints t, relative energy error, J_z − J_z(0), max |g(q)| every 100 steps. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "geomint/geomint.h"

typedef struct {
  size_t dim; /* unused by the library; convenient */
  double m1, m2, l1, l2, g;
} pendulum;

static void mass_times(const pendulum *s, const double *v, double *out) {
  for (int i = 0; i < 3; ++i) {
    out[i] = (s->m1 + s->m2) * v[i] + s->m2 * v[3 + i];
    out[3 + i] = s->m2 * (v[i] + v[3 + i]);
  }
}

static double lagrangian(void *ctx, const double *q, const double *v) {
  const pendulum *s = ctx;
  double mv[6], t = 0.0;
  mass_times(s, v, mv);
  for (int i = 0; i < 6; ++i) t += v[i] * mv[i];
  return 0.5 * t - s->m1 * s->g * q[2] - s->m2 * s->g * (q[2] + q[5]);
}

static int dl_dq(void *ctx, const double *q, const double *v, double *out) {
  const pendulum *s = ctx;
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

static int constraint(void *ctx, const double *q, double *g) {
  const pendulum *s = ctx;
  g[0] = 0.5 * (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - s->l1 * s->l1);
  g[1] = 0.5 * (q[3] * q[3] + q[4] * q[4] + q[5] * q[5] - s->l2 * s->l2);
  return 0;
}

static int constraint_jacobian(void *ctx, const double *q, double *jac) { /* 2 × 6 */
  (void)ctx;
  for (int i = 0; i < 12; ++i) jac[i] = 0.0;
  for (int i = 0; i < 3; ++i) {
    jac[i] = q[i];
    jac[6 + 3 + i] = q[3 + i];
  }
  return 0;
}

static int rotation_z(void *ctx, const double *q, double *xi) {
  (void)ctx;
  for (int b = 0; b < 2; ++b) {
    xi[3 * b] = -q[3 * b + 1];
    xi[3 * b + 1] = q[3 * b];
    xi[3 * b + 2] = 0.0;
  }
  return 0;
}

int main(int argc, char **argv) {
  const size_t steps = argc > 1 ? (size_t)atol(argv[1]) : 100000;
  const double h = argc > 2 ? atof(argv[2]) : 0.005;
  pendulum pd = {6, 1.0, 1.0, 1.0, 1.0, 9.81};
  const gm_symmetry symmetries[] = {{"angular-momentum-z", rotation_z}};

  gm_problem pb = {0};
  pb.kind = GM_PROBLEM_LAGRANGIAN;
  pb.dim = 6;
  pb.ctx = &pd;
  pb.lagrangian = lagrangian;
  pb.dl_dq = dl_dq;
  pb.dl_dv = dl_dv;
  pb.kinetic_is_quadratic = 1; /* L = ½vᵀMv − V(q), M constant: the fast path */
  pb.n_constraints = 2;
  pb.constraint = constraint;
  pb.constraint_jacobian = constraint_jacobian;
  pb.n_symmetries = 1;
  pb.symmetries = symmetries;

  /* initial positions on the spheres, velocities tangent to them; p = ∂L/∂v */
  double y[12], v[6];
  const double q0[6] = {sin(1.0), 0.0, -cos(1.0), 0.0, sin(0.5), -cos(0.5)};
  for (int i = 0; i < 6; ++i) y[i] = q0[i];
  v[0] = 0.0, v[1] = 1.5 * q0[0], v[2] = 0.0;                       /* 1.5 e_z × q1 */
  v[3] = 1.0 * q0[4], v[4] = cos(0.5), v[5] = sin(0.5);             /* −e_z × q2 + polar */
  if (gm_lagrangian_momentum(&pb, y, v, y + 6) != GM_OK) return 1;

  gm_integrator *it = NULL;
  gm_error err;
  if (gm_integrator_create(gm_method_find("vi-galerkin-gauss-2"), &pb, &it, &err) != GM_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  gm_integrator_set_compensated(it, 1);
  gm_integrator_set_state(it, 0.0, y);
  const double e0 = gm_problem_energy(&pb, y), j0 = gm_noether_momentum(&pb, 0, y);
  printf("t,rel_energy_error,momentum_drift,constraint_residual\n");
  for (size_t k = 0; k < steps; k += 100) {
    if (gm_integrator_run(it, 100, h) != GM_OK) {
      fprintf(stderr, "%s\n", gm_integrator_errmsg(it));
      return 1;
    }
    const double *s = gm_integrator_state(it);
    printf("%.6g,%.6e,%.6e,%.6e\n", gm_integrator_time(it), (gm_problem_energy(&pb, s) - e0) / fabs(e0),
           gm_noether_momentum(&pb, 0, s) - j0, gm_constraint_residual(&pb, s));
  }
  gm_integrator_free(it);
  return 0;
}
