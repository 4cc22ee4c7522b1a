/* Your own rigid body: a gm_problem of kind GM_PROBLEM_RIGID_BODY with a full (non-diagonal)
 * inertia tensor and a potential given with its body-frame gradient, integrated by the Lie
 * group variational integrator. Here a compass needle: V(R) = −k b·(R d), the body's magnetic
 * axis d aligned by a field b; the body gradient is g = −k d × (Rᵀb). State y = (R, Π). */
#include <geomint/geomint.h>
#include <stdio.h>

typedef struct {
  double k, b[3], d[3];
} compass;

static double potential(void *ctx, const double *r, const double *x) {
  const compass *c = ctx;
  double rd[3];
  (void)x;
  gm_mat3_vec(r, c->d, rd);
  return -c->k * gm_vec3_dot(c->b, rd);
}

/* d/dε V(R exp(ε η̂)) = −k b·(R (η × d)) = η·(−k d × Rᵀb) */
static int potential_gradient(void *ctx, const double *r, const double *x, double *g,
                              double *force_x) {
  const compass *c = ctx;
  double rtb[3];
  (void)x;
  (void)force_x;
  gm_mat3_tvec(r, c->b, rtb);
  gm_vec3_cross(c->d, rtb, g);
  for (int i = 0; i < 3; ++i) g[i] *= -c->k;
  return 0;
}

int main(void) {
  compass c = {2.0, {0, 0, 1}, {1, 0, 0}};
  gm_problem pb = {0};
  const double inertia[9] = {2.0, 0.3, 0.0, 0.3, 1.0, 0.1, 0.0, 0.1, 3.0};
  pb.kind = GM_PROBLEM_RIGID_BODY;
  pb.dim = 3;
  pb.ctx = &c;
  for (int i = 0; i < 9; ++i) pb.inertia[i] = inertia[i];
  pb.rigid_potential = potential;
  pb.rigid_potential_gradient = potential_gradient;
  double y[12];
  const double rotvec[3] = {0.0, 0.8, 0.0}; /* start 0.8 rad from alignment, spinning */
  gm_so3_exp(rotvec, y);
  y[9] = 0.5, y[10] = 0.0, y[11] = 0.2;
  gm_integrator *it;
  gm_error err;
  if (gm_integrator_create(gm_method_find("lgvi"), &pb, &it, &err))
    return fprintf(stderr, "%s\n", err.message), 1;
  if (gm_integrator_set_state(it, 0.0, y)) return fprintf(stderr, "%s\n", gm_integrator_errmsg(it)), 1;
  if (gm_integrator_run(it, 100000, 0.01)) return fprintf(stderr, "%s\n", gm_integrator_errmsg(it)), 1;
  const double *yt = gm_integrator_state(it);
  double h0 = gm_problem_energy(&pb, y), h = gm_problem_energy(&pb, yt);
  /* b·(R Π) is conserved: V is invariant under rotations about b */
  double m0[3], m1[3];
  gm_mat3_vec(y, y + 9, m0);
  gm_mat3_vec(yt, yt + 9, m1);
  printf("after 1e5 steps: energy error %.2e, b.(R Pi) drift %.2e, |R^T R - I| = %.2e\n",
         (h - h0) / h0, m1[2] - m0[2], gm_problem_state_defect(&pb, yt));
  gm_integrator_free(it);
  return 0;
}
