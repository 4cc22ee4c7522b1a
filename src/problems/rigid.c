/* Shared parts of the rigid-body problems: the set-up of the GM_PROBLEM_RIGID_BODY kind from
 * principal moments, the initial state from a rotation vector and a body angular momentum,
 * the invariants, and the two potentials they combine (uniform gravity on an offset centre of
 * mass, the gravity gradient of a central mass). */
#include <math.h>
#include <string.h>

#include "geomint/lie.h"
#include "problems/rigid.h"

gm_status gm_rigid_setup(gm_rigid *rb, size_t dim, const double inertia[3], double mass,
                         gm_problem *pb, char *errmsg, size_t cap) {
  for (int a = 0; a < 3; ++a)
    if (!(inertia[a] > 0.0) || !isfinite(inertia[a]))
      return gm_fail(errmsg, cap, GM_EINVAL,
                     "rigid body: principal moment I%d must be positive and finite, got %g",
                     a + 1, inertia[a]);
  if (dim == 6 && !(mass > 0.0 && isfinite(mass)))
    return gm_fail(errmsg, cap, GM_EINVAL, "rigid body: mass must be positive, got %g", mass);
  rb->dim = dim;
  rb->nt = dim - 3;
  rb->pi = 9 + rb->nt;
  memset(rb->j, 0, sizeof rb->j);
  for (int a = 0; a < 3; ++a) rb->j[4 * a] = inertia[a];
  rb->mass = mass;
  memcpy(pb->inertia, rb->j, sizeof rb->j);
  pb->mass = mass;
  pb->space = gm_rigid_body_space(dim);
  return GM_OK;
}

void gm_rigid_initial(const gm_rigid *rb, const double rotvec[3], const double pi[3],
                      double *y0) {
  gm_so3_exp(rotvec, y0);
  memcpy(y0 + rb->pi, pi, 3 * sizeof *pi);
}

/* ---- invariants ------------------------------------------------------------------------ */

double gm_rigid_casimir(void *ctx, const double *y) {
  const gm_rigid *rb = ctx;
  return gm_vec3_norm(y + rb->pi);
}

/* component a of the total angular momentum in space: R Π (+ x × p) */
static double spatial_momentum(const gm_rigid *rb, const double *y, int a) {
  double m[3];
  gm_mat3_vec(y, y + rb->pi, m);
  if (rb->nt) {
    double l[3];
    gm_vec3_cross(y + 9, y + rb->pi + 3, l);
    for (int c = 0; c < 3; ++c) m[c] += l[c];
  }
  return m[a];
}

double gm_rigid_spatial_momentum_x(void *ctx, const double *y) {
  return spatial_momentum(ctx, y, 0);
}
double gm_rigid_spatial_momentum_y(void *ctx, const double *y) {
  return spatial_momentum(ctx, y, 1);
}
double gm_rigid_spatial_momentum_z(void *ctx, const double *y) {
  return spatial_momentum(ctx, y, 2);
}

double gm_rigid_body_axis_momentum(void *ctx, const double *y) {
  const gm_rigid *rb = ctx;
  return y[rb->pi + 2];
}

/* ---- potentials ------------------------------------------------------------------------ */

/* V = m g e₃·(R ρ): with Γ = Rᵀe₃, V = m g ρ·Γ and, since Γ ↦ Γ − ε η × Γ under
 * R ↦ R exp(ε η̂), the body gradient is g = m g ρ × Γ. */
double gm_rigid_gravity(const gm_rigid_gravity_field *f, const double *r) {
  return f->mg * (r[6] * f->rho[0] + r[7] * f->rho[1] + r[8] * f->rho[2]);
}

void gm_rigid_gravity_gradient(const gm_rigid_gravity_field *f, const double *r, double g[3]) {
  const double gamma[3] = {r[6], r[7], r[8]}; /* Rᵀ e₃ = the third row of R */
  gm_vec3_cross(f->rho, gamma, g);
  for (int c = 0; c < 3; ++c) g[c] *= f->mg;
}

/* V = k Γ·JΓ with Γ = Rᵀu: δV = 2k JΓ·(−η × Γ) = η·(2k JΓ × Γ). */
double gm_rigid_tidal(const double j[9], double k, const double *r, const double u[3]) {
  double gamma[3], jg[3];
  gm_mat3_tvec(r, u, gamma);
  gm_mat3_vec(j, gamma, jg);
  return k * gm_vec3_dot(gamma, jg);
}

void gm_rigid_tidal_gradient(const double j[9], double k, const double *r, const double u[3],
                             double g[3]) {
  double gamma[3], jg[3];
  gm_mat3_tvec(r, u, gamma);
  gm_mat3_vec(j, gamma, jg);
  gm_vec3_cross(jg, gamma, g);
  for (int c = 0; c < 3; ++c) g[c] *= 2.0 * k;
}
