/* Free rigid body (Euler top): H = Σ_a Π_a²/(2 I_a) on T*SO(3), principal axes as body frame.
 * The default spins mostly about the intermediate axis (I₂ = 2 of 1, 2, 3), so Π flips
 * between ±e₂ (the Dzhanibekov or tennis-racket effect). Invariants: the Casimir |Π| and the
 * spatial angular momentum R Π (Noether, left invariance). The period of Π(t) has a closed form
 * in the complete elliptic integral K (Landau & Lifshitz, Mechanics (1976), §37):
 * gm_free_rigid_body_period. */
#include <math.h>

#include "geomint/lie.h"
#include "problems/rigid.h"

typedef struct {
  gm_rigid rb;
} free_body;

static const gm_invariant invariants[] = {
    {"casimir", gm_rigid_casimir},
    {"L-space-x", gm_rigid_spatial_momentum_x},
    {"L-space-y", gm_rigid_spatial_momentum_y},
    {"L-space-z", gm_rigid_spatial_momentum_z}};
static const char *const invariant_names[] = {"casimir", "L-space-x", "L-space-y", "L-space-z"};

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  free_body *fb = ctx;
  (void)t0;
  gm_status st = gm_rigid_setup(&fb->rb, 3, params, 0.0, pb, errmsg, cap);
  if (st != GM_OK) return st;
  pb->n_invariants = sizeof invariants / sizeof invariants[0];
  pb->invariants = invariants;
  gm_rigid_initial(&fb->rb, params + 6, params + 3, y0);
  return GM_OK;
}

/* K(k) = π / (2 AGM(1, √(1 − k²))) (Abramowitz & Stegun 17.6) */
static double elliptic_k(double k) {
  double a = 1.0, b = sqrt(1.0 - k * k);
  for (int i = 0; i < 40 && fabs(a - b) > 1e-17 * a; ++i) {
    double an = 0.5 * (a + b);
    b = sqrt(a * b);
    a = an;
  }
  return 0.5 * 3.14159265358979323846 / a;
}

double gm_free_rigid_body_period(const double inertia[3], const double pi[3]) {
  int o[3] = {0, 1, 2}; /* sort the axes by moment */
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      if (inertia[o[j]] < inertia[o[i]]) {
        int t = o[i];
        o[i] = o[j];
        o[j] = t;
      }
  const double i1 = inertia[o[0]], i2 = inertia[o[1]], i3 = inertia[o[2]];
  if (!(i1 > 0.0) || !(i1 < i2) || !(i2 < i3)) return NAN;
  double e2 = 0.0, m2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    e2 += pi[a] * pi[a] / inertia[a];
    m2 += pi[a] * pi[a];
  }
  double lambda, k2;
  if (m2 > e2 * i2) { /* about the largest axis side of the separatrix */
    lambda = sqrt((i3 - i2) * (m2 - e2 * i1) / (i1 * i2 * i3));
    k2 = (i2 - i1) * (e2 * i3 - m2) / ((i3 - i2) * (m2 - e2 * i1));
  } else {
    lambda = sqrt((i2 - i1) * (e2 * i3 - m2) / (i1 * i2 * i3));
    k2 = (i3 - i2) * (m2 - e2 * i1) / ((i2 - i1) * (e2 * i3 - m2));
  }
  if (!(k2 >= 0.0 && k2 < 1.0) || !(lambda > 0.0)) return NAN; /* separatrix or a steady spin */
  return 4.0 * elliptic_k(sqrt(k2)) / lambda;
}

static const gm_param_info params[] = {
    {"I1", 1.0, "principal moment of inertia about body axis 1", GM_PARAM_NUMBER},
    {"I2", 2.0, "principal moment about axis 2 (intermediate by default)", GM_PARAM_NUMBER},
    {"I3", 3.0, "principal moment about axis 3", GM_PARAM_NUMBER},
    {"Pi1", 0.05, "initial body angular momentum, component 1", GM_PARAM_NUMBER},
    {"Pi2", 1.0, "initial body angular momentum, component 2", GM_PARAM_NUMBER},
    {"Pi3", 0.05, "initial body angular momentum, component 3", GM_PARAM_NUMBER},
    {"r1", 0.0, "initial attitude R = exp(r), rotation vector component 1", GM_PARAM_NUMBER},
    {"r2", 0.0, "rotation vector component 2", GM_PARAM_NUMBER},
    {"r3", 0.0, "rotation vector component 3", GM_PARAM_NUMBER}};

const gm_model_def gm_model_free_rigid_body = {
    {"rigid-body", "free rigid body on SO(3), I = (1, 2, 3), spinning near the intermediate axis",
     GM_PROBLEM_RIGID_BODY, 3, sizeof params / sizeof params[0], params,
     sizeof invariant_names / sizeof invariant_names[0], invariant_names, 0},
    sizeof(free_body), NULL, setup, NULL, NULL};
