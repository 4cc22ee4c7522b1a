/* A rigid body in a central gravity field, orbit and attitude coupled (the full body problem
 * with one body fixed: Lee, Leok & McClamroch, Comput. Methods Appl. Mech. Eng. 196 (2007)
 * 2907, with the potential truncated at second order, MacCullagh's formula):
 *   V(R, x) = −μm/r − μ tr J/(2r³) + (3μ/(2r⁵)) Γ·JΓ,   Γ = Rᵀx, r = |x|,
 * J the inertia tensor about the centre of mass. Configuration (R, x) ∈ SO(3) × R³ (as a
 * manifold SE(3)), state (R, x, Π, p). Gradients (derived by hand, checked against differences
 * in tests/unit/test_problems_rigid.c):
 *   g = (3μ/r⁵) JΓ × Γ,
 *   ∂V/∂x = μm x/r³ + (3μ tr J/(2r⁵)) x + (3μ/r⁵) R JΓ − (15μ/(2r⁷)) (Γ·JΓ) x.
 * Invariants besides the energy: the total angular momentum x × p + R Π (V(QR, Qx) = V(R, x)). */
#include "geomint/lie.h"
#include "problems/rigid.h"

typedef struct {
  gm_rigid rb;
  double mu;
} central_body;

static double potential(void *ctx, const double *r, const double *x) {
  const central_body *c = ctx;
  const double *j = c->rb.j;
  double r2 = gm_vec3_dot(x, x), rr = sqrt(r2), r3 = r2 * rr, r5 = r3 * r2;
  double tr = j[0] + j[4] + j[8];
  return -c->mu * c->rb.mass / rr - c->mu * tr / (2.0 * r3) +
         gm_rigid_tidal(j, 1.5 * c->mu / r5, r, x);
}

static int potential_gradient(void *ctx, const double *r, const double *x, double *g,
                              double *fx) {
  const central_body *c = ctx;
  const double *j = c->rb.j;
  double r2 = gm_vec3_dot(x, x), rr = sqrt(r2), r3 = r2 * rr, r5 = r3 * r2, r7 = r5 * r2;
  if (!(rr > 0.0)) return 1; /* at the centre */
  double tr = j[0] + j[4] + j[8], gamma[3], jg[3], rjg[3];
  gm_mat3_tvec(r, x, gamma);
  gm_mat3_vec(j, gamma, jg);
  gm_mat3_vec(r, jg, rjg);
  double q = gm_vec3_dot(gamma, jg);
  gm_rigid_tidal_gradient(j, 1.5 * c->mu / r5, r, x, g);
  for (int a = 0; a < 3; ++a)
    fx[a] = (c->mu * c->rb.mass / r3 + 1.5 * c->mu * tr / r5 - 7.5 * c->mu * q / r7) * x[a] +
            3.0 * c->mu / r5 * rjg[a];
  return 0;
}

static const gm_invariant invariants[] = {{"L-total-x", gm_rigid_spatial_momentum_x},
                                          {"L-total-y", gm_rigid_spatial_momentum_y},
                                          {"L-total-z", gm_rigid_spatial_momentum_z}};
static const char *const invariant_names[] = {"L-total-x", "L-total-y", "L-total-z"};

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  central_body *c = ctx;
  (void)t0;
  gm_status st = gm_rigid_setup(&c->rb, 6, params + 2, params[1], pb, errmsg, cap);
  if (st != GM_OK) return st;
  if (!(params[0] > 0.0) || !isfinite(params[0]))
    return gm_fail(errmsg, cap, GM_EINVAL, "central-body: mu must be positive, got %g",
                   params[0]);
  c->mu = params[0];
  pb->rigid_potential = potential;
  pb->rigid_potential_gradient = potential_gradient;
  pb->n_invariants = 3;
  pb->invariants = invariants;
  const double rotvec[3] = {0.2, 0.1, 0.0}, pi0[3] = {0.05, 0.1, 0.6};
  gm_rigid_initial(&c->rb, rotvec, pi0, y0);
  y0[9] = 1.0; /* x = (1, 0, 0), p = m (0, 1.1, 0.1): a slightly eccentric, inclined orbit */
  y0[16] = 1.1 * params[1];
  y0[17] = 0.1 * params[1];
  return GM_OK;
}

static const gm_param_info params[] = {
    {"mu", 1.0, "G M of the central mass", GM_PARAM_NUMBER},
    {"m", 1.0, "mass of the body", GM_PARAM_NUMBER},
    {"I1", 0.1, "principal moment of inertia about body axis 1", GM_PARAM_NUMBER},
    {"I2", 0.2, "principal moment about axis 2", GM_PARAM_NUMBER},
    {"I3", 0.3, "principal moment about axis 3", GM_PARAM_NUMBER}};

const gm_model_def gm_model_central_body = {
    {"central-body", "rigid body in a central field, orbit and attitude on SO(3) x R3 (SE(3))",
     GM_PROBLEM_RIGID_BODY, 6, sizeof params / sizeof params[0], params,
     sizeof invariant_names / sizeof invariant_names[0], invariant_names, 0},
    sizeof(central_body), NULL, setup, NULL, NULL};
