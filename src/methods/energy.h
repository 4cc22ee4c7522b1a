/* Private declarations shared by the mimetic (mimetic*.c) and discrete-gradient
 * (discrete_gradient*.c) methods. */
#ifndef GM_METHODS_ENERGY_H
#define GM_METHODS_ENERGY_H

#include "methods/internal.h"

/* The Runge–Kutta tableau of mimetic-canonical-p (seed 003 eqs. 5.16–5.32). */
gm_status gm_mimetic_canonical_tableau(const gm_method *m, gm_tableau *t);
/* Is the row a Galerkin (energy-preserving) mimetic integrator? The canonical rows are
 * Runge–Kutta methods and carry a tableau; the Galerkin rows do not. */
static inline int gm_mimetic_is_galerkin(const gm_method *m) {
  return m->family == GM_FAMILY_MIMETIC && m->compute == NULL;
}

/* The discrete gradients, in the order of their rows in gm_discrete_gradient_methods. */
typedef enum {
  GM_DG_AVERAGE_VECTOR_FIELD = 0,
  GM_DG_GONZALEZ,
  GM_DG_ITOH_ABE
} gm_discrete_gradient_kind;
gm_discrete_gradient_kind gm_discrete_gradient_kind_of(const gm_method *m);

/* The quadrature setting of gm_integrator_set_quadrature, per family. */
gm_status gm_mimetic_set_quadrature(gm_integrator *it, size_t n_points);
size_t gm_mimetic_quadrature(const gm_integrator *it);
gm_status gm_discrete_gradient_set_quadrature(gm_integrator *it, size_t n_points);
size_t gm_discrete_gradient_quadrature(const gm_integrator *it);

#endif
