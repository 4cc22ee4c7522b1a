/* Rotation about the z axis for problems whose q is k points in R³ (spherical pendulums, J2
 * satellite): ξ_Q = e_z × q_i per point, Noether momentum J = Σ_i x_i p_y,i − y_i p_x,i. */
#include "problems/internal.h"

static int rotation_z(void *ctx, const double *q, double *xi) {
  const size_t d = *(const size_t *)ctx;
  for (size_t i = 0; i < d; i += 3) {
    xi[i] = -q[i + 1];
    xi[i + 1] = q[i];
    xi[i + 2] = 0.0;
  }
  return 0;
}

static double angular_momentum_z(void *ctx, const double *y) {
  const size_t d = *(const size_t *)ctx;
  const double *p = y + d;
  /* summed left to right, term by term, as the per-problem versions did: same rounding */
  double j = y[0] * p[1] - y[1] * p[0];
  for (size_t i = 3; i < d; i += 3) {
    j += y[i] * p[i + 1];
    j -= y[i + 1] * p[i];
  }
  return j;
}

const char *const gm_rotation_z_invariant_names[1] = {"angular-momentum-z"};
static const gm_symmetry symmetries[] = {{"angular-momentum-z", rotation_z}};
static const gm_invariant invariants[] = {{"angular-momentum-z", angular_momentum_z}};

void gm_rotation_z_setup(gm_problem *pb) {
  pb->n_symmetries = 1;
  pb->symmetries = symmetries;
  pb->n_invariants = 1;
  pb->invariants = invariants;
}
