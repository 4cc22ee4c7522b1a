/* Private pieces of the invariant schemes (src/pde/invariant*.c). */
#ifndef GM_PDE_INVARIANT_INTERNAL_H
#define GM_PDE_INVARIANT_INTERNAL_H

#include "geomint/pde_invariant.h"

/* The scheme rows (invariant_burgers.c, invariant_heat.c). */
extern const gm_inv_scheme gm_inv_ftcs, gm_inv_lax_wendroff, gm_inv_crank_nicolson,
    gm_inv_heat_ftcs;

/* Three-point differences on a layer p[0..2] (spacings h₋ = x₁ − x₀, h₊ = x₂ − x₁):
 * D₁u = (u₂ − u₀)/(x₂ − x₀), D₂u = 2[(u₂ − u₁)/h₊ − (u₁ − u₀)/h₋]/(h₊ + h₋); both the usual
 * centred differences on a uniform layer. */
static inline double gm_inv_d1(const gm_inv_point *p) {
  return (p[2].u - p[0].u) / (p[2].x - p[0].x);
}
static inline double gm_inv_d2(const gm_inv_point *p) {
  double hm = p[1].x - p[0].x, hp = p[2].x - p[1].x;
  return 2.0 * ((p[2].u - p[1].u) / hp - (p[1].u - p[0].u) / hm) / (hp + hm);
}

#endif
