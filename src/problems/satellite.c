/* Satellite attitude under the gravity-gradient torque of a central mass, at a fixed point of
 * its orbit (the orbital motion neglected): with the unit vector u from the planet to the
 * satellite fixed in space, V = (3 n²/2) Γ·JΓ, Γ = Rᵀu, n² = μ/r³ (Hughes, Spacecraft
 * Attitude Dynamics (1986), §8.2; the constant term of MacCullagh's formula dropped). The body
 * gradient is 3 n² JΓ × Γ: the torque 3 n² Γ × JΓ. Invariants besides the energy: the angular
 * momentum about u, u·(R Π) (rotations about u leave V unchanged). For the coupled orbit and
 * attitude see central-body. */
#include "geomint/lie.h"
#include "problems/rigid.h"

typedef struct {
  gm_rigid rb;
  double k; /* 3 n²/2 */
} satellite;

static const double radial[3] = {1.0, 0.0, 0.0};

static double potential(void *ctx, const double *r, const double *x) {
  (void)x;
  const satellite *s = ctx;
  return gm_rigid_tidal(s->rb.j, s->k, r, radial);
}

static int potential_gradient(void *ctx, const double *r, const double *x, double *g,
                              double *fx) {
  (void)x;
  (void)fx;
  const satellite *s = ctx;
  gm_rigid_tidal_gradient(s->rb.j, s->k, r, radial, g);
  return 0;
}

static const gm_invariant invariants[] = {{"L-radial", gm_rigid_spatial_momentum_x}};
static const char *const invariant_names[] = {"L-radial"};

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  satellite *s = ctx;
  (void)t0;
  gm_status st = gm_rigid_setup(&s->rb, 3, params, 0.0, pb, errmsg, cap);
  if (st != GM_OK) return st;
  if (!(params[3] >= 0.0) || !isfinite(params[3]))
    return gm_fail(errmsg, cap, GM_EINVAL, "satellite: n2 = mu/r^3 must be >= 0, got %g",
                   params[3]);
  s->k = 1.5 * params[3];
  pb->rigid_potential = potential;
  pb->rigid_potential_gradient = potential_gradient;
  pb->n_invariants = 1;
  pb->invariants = invariants;
  const double rotvec[3] = {0.4, -0.2, 0.7}, pi0[3] = {0.3, -0.5, 0.6};
  gm_rigid_initial(&s->rb, rotvec, pi0, y0);
  return GM_OK;
}

static const gm_param_info params[] = {
    {"I1", 1.0, "principal moment of inertia about body axis 1", GM_PARAM_NUMBER},
    {"I2", 1.5, "principal moment about axis 2", GM_PARAM_NUMBER},
    {"I3", 2.0, "principal moment about axis 3", GM_PARAM_NUMBER},
    {"n2", 1.0, "mu / r^3: the squared orbital rate", GM_PARAM_NUMBER}};

const gm_model_def gm_model_satellite = {
    {"satellite", "satellite attitude with gravity-gradient torque about a fixed radial direction",
     GM_PROBLEM_RIGID_BODY, 3, sizeof params / sizeof params[0], params,
     sizeof invariant_names / sizeof invariant_names[0], invariant_names, 0},
    sizeof(satellite), NULL, setup, NULL, NULL};
