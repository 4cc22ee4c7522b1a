/* Private declarations of the Lie group rows (lie_group_table.c) and their stepper
 * (lie_group.c, lgvi.c, rigid_splitting.c). */
#ifndef GM_METHODS_LIE_GROUP_H
#define GM_METHODS_LIE_GROUP_H

#include "geomint/lie.h"
#include "methods/internal.h"

typedef enum gm_lie_scheme {
  GM_LIE_LGVI = 1,       /* Lee, Leok & McClamroch: implicit F_k by Newton in so(3) */
  GM_LIE_RKMK,           /* Runge–Kutta–Munthe-Kaas on the exponential chart at R_k */
  GM_LIE_CROUCH_GROSSMAN,/* products of exponentials of frozen stage velocities */
  GM_LIE_SPLITTING,      /* kick, exact rotations about the body axes, kick */
  GM_LIE_GALERKIN,       /* Galerkin LGVI of degree s in the exponential chart (lie_galerkin.c) */
  GM_LIE_DEP             /* its reduced form for free bodies: discrete Euler–Poincaré */
} gm_lie_scheme;

/* The scheme of a row of gm_lie_group_methods (0 for any other method). */
gm_lie_scheme gm_lie_scheme_of(const gm_method *method);

#define GM_LIE_MAX_STAGES 8

/* The stepper's work: the body's constants and stage storage (allocated once at init). */
typedef struct gm_lie_work {
  gm_lie_scheme scheme;
  size_t nt;            /* translational degrees of freedom: 0 or 3 */
  size_t pi;            /* offset of Π in the state: 9 + nt */
  double j[9], jinv[9]; /* inertia and its inverse */
  double mass;
  int principal;        /* J is diagonal (the splitting needs principal axes) */
  gm_tableau *tableau;  /* RKMK, Crouch–Grossman */
  /* stage values: rotation vectors or body velocities, Π rates, x and p rates */
  double k_theta[GM_LIE_MAX_STAGES][3], k_pi[GM_LIE_MAX_STAGES][3];
  double k_x[GM_LIE_MAX_STAGES][3], k_p[GM_LIE_MAX_STAGES][3];
  double omega[GM_LIE_MAX_STAGES][3];
  struct gm_lie_galerkin *galerkin; /* Galerkin and DEP rows */
  double scratch[32];
} gm_lie_work;

/* V's gradients at (R, x): g in the body frame, fx = ∂V/∂x (fx untouched when nt = 0); zero
 * for a free body. Counts a force evaluation; on failure it->errmsg says which callback. */
gm_status gm_lie_gradient(gm_integrator *it, double t, const double *r, const double *x,
                          double g[3], double fx[3]);

/* The step of each scheme: y_old → y_new (R, x, Π, p); R_new = R_old + R_old E with
 * E = F − I of the step's right factor F, written to e. */
gm_status gm_lgvi_step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                       double e[9]);
/* Galerkin / DEP rows (lie_galerkin.c): set-up (reduced: the DEP form, free bodies only),
 * release and step. */
gm_status gm_lie_galerkin_init(gm_integrator *it, int reduced);
void gm_lie_galerkin_release(gm_lie_work *w);
void gm_lie_galerkin_invalidate(gm_lie_work *w); /* forget the warm start */
gm_status gm_lie_galerkin_step(gm_integrator *it, double t, double h, const double *y,
                               double *y_new, double e[9]);
gm_status gm_rigid_splitting_step(gm_integrator *it, double t, double h, const double *y,
                                  double *y_new, double e[9]);

#endif
