/* Heavy symmetric (Lagrange) top: a body with I₁ = I₂ spinning about its symmetry axis e₃,
 * pivoted at a fixed point a distance l below its centre of mass, in uniform gravity −g e₃:
 * H = Σ_a Π_a²/(2 I_a) + m g l e₃·(R e₃). Invariants besides the energy: the angular momentum
 * about the vertical e₃·(R Π) (rotations about the vertical) and about the symmetry axis Π₃
 * (I₁ = I₂ and the centre of mass on the axis). Default: tilted by 0.5 rad, fast spin with a
 * little nutation (Goldstein, Classical Mechanics (1980), §5.7). */
#include "problems/rigid.h"

typedef struct {
  gm_rigid rb;
  gm_rigid_gravity_field gravity;
} heavy_top;

static double potential(void *ctx, const double *r, const double *x) {
  (void)x;
  return gm_rigid_gravity(&((const heavy_top *)ctx)->gravity, r);
}

static int potential_gradient(void *ctx, const double *r, const double *x, double *g,
                              double *fx) {
  (void)x;
  (void)fx;
  gm_rigid_gravity_gradient(&((const heavy_top *)ctx)->gravity, r, g);
  return 0;
}

static const gm_invariant invariants[] = {{"L-vertical", gm_rigid_spatial_momentum_z},
                                          {"L-axis", gm_rigid_body_axis_momentum}};
static const char *const invariant_names[] = {"L-vertical", "L-axis"};

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  heavy_top *ht = ctx;
  (void)t0;
  const double inertia[3] = {params[0], params[0], params[1]};
  gm_status st = gm_rigid_setup(&ht->rb, 3, inertia, 0.0, pb, errmsg, cap);
  if (st != GM_OK) return st;
  if (!isfinite(params[2]))
    return gm_fail(errmsg, cap, GM_EINVAL, "heavy-top: mgl = %g is not finite", params[2]);
  ht->gravity = (gm_rigid_gravity_field){params[2], {0.0, 0.0, 1.0}};
  pb->rigid_potential = potential;
  pb->rigid_potential_gradient = potential_gradient;
  pb->n_invariants = sizeof invariants / sizeof invariants[0];
  pb->invariants = invariants;
  const double tilt[3] = {params[3], 0.0, 0.0};
  gm_rigid_initial(&ht->rb, tilt, params + 4, y0);
  return GM_OK;
}

static const gm_param_info params[] = {
    {"I1", 1.0, "transverse moment of inertia (I1 = I2)", GM_PARAM_NUMBER},
    {"I3", 0.5, "moment about the symmetry axis", GM_PARAM_NUMBER},
    {"mgl", 1.0, "m g l: weight times the distance of the centre of mass from the pivot",
     GM_PARAM_NUMBER},
    {"tilt", 0.5, "initial tilt of the symmetry axis from the vertical (rad, about e1)",
     GM_PARAM_NUMBER},
    {"Pi1", 0.0, "initial body angular momentum, component 1", GM_PARAM_NUMBER},
    {"Pi2", 0.3, "initial body angular momentum, component 2", GM_PARAM_NUMBER},
    {"Pi3", 2.5, "initial spin momentum about the symmetry axis", GM_PARAM_NUMBER}};

const gm_model_def gm_model_heavy_top = {
    {"heavy-top", "heavy symmetric (Lagrange) top on SO(3): I = (1, 1, 0.5), mgl = 1, tilted",
     GM_PROBLEM_RIGID_BODY, 3, sizeof params / sizeof params[0], params,
     sizeof invariant_names / sizeof invariant_names[0], invariant_names, 0},
    sizeof(heavy_top), NULL, setup, NULL, NULL};
