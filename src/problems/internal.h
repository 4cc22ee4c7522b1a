/* Private declarations of the problem library. Each problem is one file defining a
 * gm_model_def; model.c turns a definition and parameter values into a gm_problem. */
#ifndef GM_PROBLEMS_INTERNAL_H
#define GM_PROBLEMS_INTERNAL_H

#include "core/internal.h"
#include "geomint/problems.h"

typedef struct gm_model_def {
  gm_model_info info;
  size_t ctx_size;  /* bytes of the problem context, allocated and zeroed by model.c */
  /* Optional: work out the degrees of freedom for the parameters (info.default_dim when NULL).
   * params are in info.params order; texts likewise, NULL where a text parameter is unset (and
   * for number parameters). What it reads or draws (a file of bodies, a random sample) may be
   * kept in ctx for setup, to be freed by release. */
  gm_status (*prepare)(void *ctx, const double *params, const char *const *texts, size_t *dim,
                       char *errmsg, size_t cap);
  /* Check the parameters (in info.params order), fill ctx, the callbacks of problem (kind,
   * dim and ctx are set already) and the default initial state. */
  gm_status (*setup)(void *ctx, const double *params, gm_problem *problem, double *t0,
                     double *y0, char *errmsg, size_t cap);
  /* Optional: the initial state was changed by the user (q1=..., p1=...); return 0 when the
   * problem's exact solution no longer applies. */
  int (*initial_changed)(void *ctx, const double *y0);
  /* Optional: free what prepare or setup allocated inside ctx (not ctx itself). Called on a
   * zeroed ctx too, when prepare failed before allocating. */
  void (*release)(void *ctx);
} gm_model_def;

/* Free-particle kinetic energy T(p) = ½|p|² with unit masses, shared by several problems.
 * Their contexts must begin with the number of degrees of freedom (a size_t).
 * gm_free_kinetic_setup sets the three callbacks and kinetic_is_quadratic. */
void gm_free_kinetic_setup(gm_problem *pb);
double gm_free_kinetic(void *ctx, const double *p);
int gm_free_kinetic_gradient(void *ctx, const double *p, double *out);
int gm_free_kinetic_hessian(void *ctx, const double *p, double *hessian);

/* Newtonian gravity of point masses in 3-D (gravity.c), shared by outer-solar-system and n-body:
 *   H = Σ_i |p_i|²/(2 m_i) − G Σ_{i<j} m_i m_j / sqrt(|q_i − q_j|² + ε²),
 * q and p stored body by body (x1 y1 z1 x2 ...), p_i = m_i v_i. The problem's context must
 * begin with a gm_gravity. A collision (r = 0 with ε = 0) is a failed evaluation. */
typedef struct gm_gravity {
  size_t dim;           /* 3 n_bodies */
  size_t n_bodies;
  double G;             /* gravitational constant */
  double softening2;    /* ε² >= 0 */
  const double *mass;   /* n_bodies masses > 0, owned by the problem's context */
} gm_gravity;

/* Set the gravity callbacks of pb and its six invariants: the components of the total linear
 * momentum Σ p_i and of the angular momentum Σ q_i × p_i (Noether: translations, rotations). */
void gm_gravity_setup(gm_problem *pb);
#define GM_GRAVITY_N_INVARIANTS 6
extern const char *const gm_gravity_invariant_names[GM_GRAVITY_N_INVARIANTS];

/* Rotation about the z axis (rotation_z.c), shared by the problems whose q is k points in R³:
 * sets the symmetry ξ_Q = e_z × q_i and its Noether momentum, both named "angular-momentum-z".
 * The context must begin with the number of degrees of freedom 3k (a size_t). */
void gm_rotation_z_setup(gm_problem *pb);
extern const char *const gm_rotation_z_invariant_names[1];

extern const gm_model_def gm_model_harmonic;
extern const gm_model_def gm_model_pendulum;
extern const gm_model_def gm_model_kepler;
extern const gm_model_def gm_model_henon_heiles;
extern const gm_model_def gm_model_lotka_volterra;
extern const gm_model_def gm_model_outer_solar_system;
extern const gm_model_def gm_model_n_body;
extern const gm_model_def gm_model_point_vortices;
extern const gm_model_def gm_model_fpu;
/* Lagrangian problems (issue 4) */
extern const gm_model_def gm_model_spherical_pendulum;
extern const gm_model_def gm_model_double_spherical_pendulum;
extern const gm_model_def gm_model_spring_pendulum;
extern const gm_model_def gm_model_j2_satellite;
extern const gm_model_def gm_model_damped_oscillator;
/* Rigid bodies on SO(3) (× R³) (issue 13; shared helpers in problems/rigid.h) */
extern const gm_model_def gm_model_free_rigid_body;
extern const gm_model_def gm_model_heavy_top;
extern const gm_model_def gm_model_pendulum_3d;
extern const gm_model_def gm_model_satellite;
extern const gm_model_def gm_model_central_body;
/* split potentials U + W (issue 12) */
extern const gm_model_def gm_model_toy_resonance;
extern const gm_model_def gm_model_stiff_spring_pendulum;
/* m, g, k, l, theta0: the spring pendulum in either form (spring_pendulum.c) */
extern const gm_param_info gm_spring_pendulum_params[5];
extern const gm_model_def gm_model_diatomic_chain;

#endif
