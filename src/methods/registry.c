/* The method registry: all tables seen as one list, looked up by name. */
#include <string.h>

#include "methods/internal.h"

typedef struct {
  const gm_method *rows;
  const size_t *count;
} table_ref;

static const table_ref tables[] = {
    {gm_explicit_rk_methods, &gm_n_explicit_rk_methods},
    {gm_splitting_methods, &gm_n_splitting_methods},
    {gm_implicit_rk_methods, &gm_n_implicit_rk_methods},
    {gm_composition_methods, &gm_n_composition_methods},
    {gm_partitioned_rk_methods, &gm_n_partitioned_rk_methods},
    {gm_mimetic_methods, &gm_n_mimetic_methods},
    {gm_discrete_gradient_methods, &gm_n_discrete_gradient_methods},
    {gm_variational_methods, &gm_n_variational_methods},
    {gm_lie_group_methods, &gm_n_lie_group_methods},
    {gm_oscillatory_methods, &gm_n_oscillatory_methods},
    {gm_near_integrable_methods, &gm_n_near_integrable_methods},
};
static const size_t n_tables = sizeof tables / sizeof tables[0];

size_t gm_method_count(void) {
  size_t n = 0;
  for (size_t t = 0; t < n_tables; ++t) n += *tables[t].count;
  return n;
}

const gm_method *gm_method_at(size_t index) {
  for (size_t t = 0; t < n_tables; ++t) {
    if (index < *tables[t].count) return &tables[t].rows[index];
    index -= *tables[t].count;
  }
  return NULL;
}

const gm_method *gm_method_find(const char *name) {
  if (name == NULL) return NULL;
  for (size_t i = 0, n = gm_method_count(); i < n; ++i) {
    const gm_method *m = gm_method_at(i);
    if (strcmp(m->name, name) == 0) return m;
  }
  return NULL;
}

const char *gm_method_family_name(gm_method_family family) {
  switch (family) {
    case GM_FAMILY_EXPLICIT_RK:
      return "explicit-rk";
    case GM_FAMILY_SPLITTING:
      return "splitting";
    case GM_FAMILY_IMPLICIT_RK:
      return "implicit-rk";
    case GM_FAMILY_COMPOSITION:
      return "composition";
    case GM_FAMILY_PARTITIONED_RK:
      return "partitioned-rk";
    case GM_FAMILY_MIMETIC:
      return "mimetic";
    case GM_FAMILY_DISCRETE_GRADIENT:
      return "discrete-gradient";
    case GM_FAMILY_VARIATIONAL:
      return "variational";
    case GM_FAMILY_LIE_GROUP:
      return "lie-group";
    case GM_FAMILY_OSCILLATORY:
      return "oscillatory";
    case GM_FAMILY_NEAR_INTEGRABLE:
      return "near-integrable";
  }
  return "unknown";
}

const char *gm_method_flag_name(size_t bit) {
  static const char *const names[GM_N_METHOD_FLAGS] = {
      "symplectic", "symmetric", "explicit", "implicit", "energy-preserving", "fsal"};
  return bit < GM_N_METHOD_FLAGS ? names[bit] : NULL;
}

const gm_stepper *gm_stepper_for(const gm_method *method, const gm_method *basic) {
  switch (method->family) {
    case GM_FAMILY_EXPLICIT_RK:
      return &gm_explicit_rk_stepper;
    case GM_FAMILY_SPLITTING:
      return &gm_splitting_stepper;
    case GM_FAMILY_IMPLICIT_RK:
    case GM_FAMILY_PARTITIONED_RK:
      return &gm_implicit_rk_stepper;
    case GM_FAMILY_COMPOSITION:
      if (basic == NULL) return NULL;
      return basic->family == GM_FAMILY_SPLITTING ? &gm_splitting_stepper
                                                  : &gm_composition_stepper;
    case GM_FAMILY_MIMETIC:
      return &gm_mimetic_stepper;
    case GM_FAMILY_DISCRETE_GRADIENT:
      return &gm_discrete_gradient_stepper;
    case GM_FAMILY_VARIATIONAL: /* symplectic-energy-momentum rows choose their own steps */
      return (method->flags & GM_ENERGY_PRESERVING) ? &gm_sem_stepper : &gm_variational_stepper;
    case GM_FAMILY_LIE_GROUP:
      return &gm_lie_group_stepper;
    case GM_FAMILY_OSCILLATORY:
      return &gm_oscillatory_stepper;
    case GM_FAMILY_NEAR_INTEGRABLE:
      return &gm_near_integrable_stepper;
  }
  return NULL;
}
