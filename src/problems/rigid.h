/* Private helpers of the rigid-body problems (rigid.c). A rigid problem's context begins with
 * a gm_rigid, which its invariants read. State y = (R, x, Π, p) as in geomint/ode.h. */
#ifndef GM_PROBLEMS_RIGID_H
#define GM_PROBLEMS_RIGID_H

#include "problems/internal.h"

typedef struct gm_rigid {
  size_t dim;      /* 3 or 6 */
  size_t nt, pi;   /* translational dimension (0 or 3) and the offset of Π in y */
  double j[9];     /* diagonal inertia */
  double mass;
} gm_rigid;

/* Fill rb and the rigid-body part of pb (inertia diag(I1, I2, I3), mass, state space). */
gm_status gm_rigid_setup(gm_rigid *rb, size_t dim, const double inertia[3], double mass,
                         gm_problem *pb, char *errmsg, size_t cap);
/* R₀ = exp(rotvec), Π₀ = pi (x₀, p₀ untouched). */
void gm_rigid_initial(const gm_rigid *rb, const double rotvec[3], const double pi[3],
                      double *y0);

/* Invariants: |Π|, the components of the total angular momentum in space R Π (+ x × p), and
 * the body-axis-3 component Π₃. ctx begins with a gm_rigid. */
double gm_rigid_casimir(void *ctx, const double *y);
double gm_rigid_spatial_momentum_x(void *ctx, const double *y);
double gm_rigid_spatial_momentum_y(void *ctx, const double *y);
double gm_rigid_spatial_momentum_z(void *ctx, const double *y);
double gm_rigid_body_axis_momentum(void *ctx, const double *y);

/* Uniform gravity −g e₃ on a body with its centre of mass at ρ (body frame) from the pivot:
 * V = m g e₃·(R ρ), body gradient g = m g ρ × Rᵀe₃. */
typedef struct gm_rigid_gravity_field {
  double mg;
  double rho[3];
} gm_rigid_gravity_field;
double gm_rigid_gravity(const gm_rigid_gravity_field *f, const double *r);
void gm_rigid_gravity_gradient(const gm_rigid_gravity_field *f, const double *r, double g[3]);

/* The tidal (gravity-gradient) term V = k Γ·JΓ, Γ = Rᵀu, and its body gradient 2k JΓ × Γ. */
double gm_rigid_tidal(const double j[9], double k, const double *r, const double u[3]);
void gm_rigid_tidal_gradient(const double j[9], double k, const double *r, const double u[3],
                             double g[3]);

#endif
