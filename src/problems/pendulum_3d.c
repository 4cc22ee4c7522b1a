/* 3-D pendulum: an asymmetric rigid body on a frictionless pivot in uniform gravity −g e₃,
 * its centre of mass at ρ (body frame) from the pivot: H = Σ_a Π_a²/(2 I_a) + m g e₃·(R ρ)
 * (Lee, Leok & McClamroch, Proc. ACC (2005) 962; the numbers here are ours). With an
 * asymmetric body and an offset ρ only the angular momentum about the vertical is conserved
 * besides the energy; the motion is chaotic for these values. */
#include "problems/rigid.h"

typedef struct {
  gm_rigid rb;
  gm_rigid_gravity_field gravity;
} pendulum_3d;

static double potential(void *ctx, const double *r, const double *x) {
  (void)x;
  return gm_rigid_gravity(&((const pendulum_3d *)ctx)->gravity, r);
}

static int potential_gradient(void *ctx, const double *r, const double *x, double *g,
                              double *fx) {
  (void)x;
  (void)fx;
  gm_rigid_gravity_gradient(&((const pendulum_3d *)ctx)->gravity, r, g);
  return 0;
}

static const gm_invariant invariants[] = {{"L-vertical", gm_rigid_spatial_momentum_z}};
static const char *const invariant_names[] = {"L-vertical"};

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  pendulum_3d *pd = ctx;
  (void)t0;
  gm_status st = gm_rigid_setup(&pd->rb, 3, params, 0.0, pb, errmsg, cap);
  if (st != GM_OK) return st;
  for (int k = 3; k < 7; ++k)
    if (!isfinite(params[k]))
      return gm_fail(errmsg, cap, GM_EINVAL, "pendulum-3d: parameter %d is not finite", k + 1);
  pd->gravity = (gm_rigid_gravity_field){params[3], {params[4], params[5], params[6]}};
  pb->rigid_potential = potential;
  pb->rigid_potential_gradient = potential_gradient;
  pb->n_invariants = 1;
  pb->invariants = invariants;
  const double tilt[3] = {params[7], 0.3 * params[7], 0.0};
  const double pi0[3] = {0.2, -0.1, 0.4};
  gm_rigid_initial(&pd->rb, tilt, pi0, y0);
  return GM_OK;
}

static const gm_param_info params[] = {
    {"I1", 0.13, "principal moment of inertia about body axis 1", GM_PARAM_NUMBER},
    {"I2", 0.28, "principal moment about axis 2", GM_PARAM_NUMBER},
    {"I3", 0.17, "principal moment about axis 3", GM_PARAM_NUMBER},
    {"mg", 1.0, "weight m g", GM_PARAM_NUMBER},
    {"rho1", 0.05, "centre of mass from the pivot, body frame, component 1", GM_PARAM_NUMBER},
    {"rho2", 0.0, "component 2", GM_PARAM_NUMBER},
    {"rho3", -0.3, "component 3 (negative: hanging below the pivot)", GM_PARAM_NUMBER},
    {"tilt", 1.0, "initial rotation angle about (1, 0.3, 0) (rad)", GM_PARAM_NUMBER}};

const gm_model_def gm_model_pendulum_3d = {
    {"pendulum-3d", "3-D rigid pendulum on SO(3): asymmetric body, offset centre of mass",
     GM_PROBLEM_RIGID_BODY, 3, sizeof params / sizeof params[0], params,
     sizeof invariant_names / sizeof invariant_names[0], invariant_names, 0},
    sizeof(pendulum_3d), NULL, setup, NULL, NULL};
