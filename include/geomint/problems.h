/* geomint problems: the built-in problem library. A model is a named problem with parameters,
 * an initial state, invariants and (where one exists) an exact solution. Every derivative a
 * problem defines is analytic (second derivatives and constraint Hessians included); Newton on
 * a Poisson problem differentiates S(y)∇H(y) numerically, as ∂S/∂y has no callback. Parameters and initial values are changed by name before gm_model_build. */
#ifndef GEOMINT_PROBLEMS_H
#define GEOMINT_PROBLEMS_H

#include <stddef.h>

#include "geomint/core.h"
#include "geomint/ode.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A parameter is a number (gm_model_set) or a text such as a file name (gm_model_set_text). */
typedef enum gm_param_type { GM_PARAM_NUMBER = 0, GM_PARAM_TEXT = 1 } gm_param_type;

typedef struct gm_param_info {
  const char *name;
  double default_value;          /* numbers; unused (0) for text parameters, which are unset */
  const char *description;
  gm_param_type type;
} gm_param_info;

typedef struct gm_model_info {
  const char *name;
  const char *description;
  gm_problem_kind kind;
  size_t default_dim;            /* degrees of freedom with default parameters */
  size_t n_params;
  const gm_param_info *params;   /* physical parameters (initial values q1.., p1.. come on top) */
  size_t n_invariants;
  const char *const *invariant_names; /* besides the energy */
  int has_exact;                 /* an exact solution is available */
} gm_model_info;

size_t gm_model_count(void);
const gm_model_info *gm_model_info_at(size_t index);   /* NULL past the end */
const gm_model_info *gm_model_info_find(const char *name);

typedef struct gm_model gm_model;

/* A model with default parameters. GM_ENOTFOUND for an unknown name. */
gm_status gm_model_create(const char *name, gm_model **out);
void gm_model_free(gm_model *model);
/* Set a parameter by name, or an initial value: q1..qd, p1..pd (Hamiltonian kinds) or y1..yn.
 * Unknown name, a text parameter or a non-finite value → GM_EINVAL with a message. */
gm_status gm_model_set(gm_model *model, const char *name, double value);
/* Set a text parameter (type GM_PARAM_TEXT, e.g. the file n-body reads its bodies from); value
 * is copied, "" unsets it. Unknown name or a number parameter → GM_EINVAL with a message. */
gm_status gm_model_set_text(gm_model *model, const char *name, const char *value);
/* Check the parameters and build the problem and initial state. Must be called after the last
 * gm_model_set and before the accessors below. */
gm_status gm_model_build(gm_model *model);
const gm_problem *gm_model_problem(const gm_model *model);   /* borrowed from the model */
size_t gm_model_state_size(const gm_model *model);
/* Initial time and state (y0: gm_model_state_size entries, written). */
void gm_model_initial_state(const gm_model *model, double *t0, double *y0);
const gm_model_info *gm_model_info_of(const gm_model *model);
double gm_model_param(const gm_model *model, const char *name); /* NaN when unknown or text */
const char *gm_model_errmsg(const gm_model *model);

/* The period of the body angular momentum Π(t) of a free rigid body with distinct principal
 * moments (any order) from Π(0), in closed form: 4K(k)/λ (Landau & Lifshitz, Mechanics, §37).
 * Π₂-type flips of the intermediate axis happen every half period. NaN on the separatrix, for
 * a steady spin, or for equal moments. */
double gm_free_rigid_body_period(const double inertia[3], const double pi[3]);

#ifdef __cplusplus
}
#endif
#endif
