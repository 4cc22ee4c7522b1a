/* Private declarations of the problem library. Each problem is one file defining a
 * gm_model_def; model.c turns a definition and parameter values into a gm_problem. */
#ifndef GM_PROBLEMS_INTERNAL_H
#define GM_PROBLEMS_INTERNAL_H

#include "core/internal.h"
#include "geomint/problems.h"

typedef struct gm_model_def {
  gm_model_info info;
  size_t ctx_size;  /* bytes of the problem context, allocated and zeroed by model.c */
  /* Optional: degrees of freedom for the given parameters (info.default_dim when NULL). */
  gm_status (*dimension)(const double *params, size_t *dim, char *errmsg, size_t cap);
  /* Check the parameters (in info.params order), fill ctx, the callbacks of problem (kind,
   * dim and ctx are set already) and the default initial state. */
  gm_status (*setup)(void *ctx, const double *params, gm_problem *problem, double *t0,
                     double *y0, char *errmsg, size_t cap);
  /* Optional: the initial state was changed by the user (q1=..., p1=...); return 0 when the
   * problem's exact solution no longer applies. */
  int (*initial_changed)(void *ctx, const double *y0);
} gm_model_def;

/* Free-particle kinetic energy T(p) = ½|p|² with unit masses, shared by several problems.
 * Their contexts must begin with the number of degrees of freedom (a size_t). */
double gm_free_kinetic(void *ctx, const double *p);
int gm_free_kinetic_gradient(void *ctx, const double *p, double *out);
int gm_free_kinetic_hessian(void *ctx, const double *p, double *hessian);

extern const gm_model_def gm_model_harmonic;
extern const gm_model_def gm_model_pendulum;
extern const gm_model_def gm_model_kepler;
extern const gm_model_def gm_model_henon_heiles;
extern const gm_model_def gm_model_lotka_volterra;

#endif
