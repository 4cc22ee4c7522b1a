/* Discrete gradient methods for Poisson systems y' = S(y)∇H(y), S skew-symmetric:
 *   y_{n+1} = y_n + h S((y_n + y_{n+1})/2) ∇̄H(y_n, y_{n+1}),
 * where the discrete gradient satisfies ∇̄H(y, y')·(y' − y) = H(y') − H(y) and ∇̄H(y, y) =
 * ∇H(y). Then H(y_{n+1}) − H(y_n) = h ∇̄Hᵀ S ∇̄H = 0 for every step size (McLachlan, Quispel &
 * Robidoux, Phil. Trans. R. Soc. A 357 (1999) 1021). Canonical Hamiltonian problems use
 * S = J⁻¹. None is symplectic; the average vector field and Gonzalez's discrete gradient are
 * symmetric (order 2); Itoh and Abe's is not (order 1). */
#include "methods/energy.h"

#define DG_FLAGS (GM_IMPLICIT | GM_ENERGY_PRESERVING)

const gm_method gm_discrete_gradient_methods[] = {
    /* ∇̄H = ∫_0^1 ∇H(y + s(y' − y)) ds, by Gauss quadrature (option); with constant S this is
     * the average vector field method, and mimetic-galerkin-1. */
    {.name = "avf", .family = GM_FAMILY_DISCRETE_GRADIENT, .order = 2, .n_stages = 1,
     .flags = DG_FLAGS | GM_SYMMETRIC, .accepts = GM_PROBLEM_POISSON,
     .description = "average vector field: discrete gradient int_0^1 grad H, energy exact",
     .reference = "Quispel & McLaren, J. Phys. A 41 (2008) 045206; McLachlan, Quispel & "
                  "Robidoux, Phil. Trans. R. Soc. A 357 (1999) 1021 (mean value discrete gradient)"},
    /* ∇̄H = ∇H(ȳ) + [H(y') − H(y) − ∇H(ȳ)·Δ] Δ / |Δ|², ȳ = (y + y')/2, Δ = y' − y. */
    {.name = "discrete-gradient-gonzalez", .family = GM_FAMILY_DISCRETE_GRADIENT, .order = 2,
     .n_stages = 1, .flags = DG_FLAGS | GM_SYMMETRIC, .accepts = GM_PROBLEM_POISSON,
     .description = "Gonzalez's midpoint discrete gradient, energy exact",
     .reference = "Gonzalez, J. Nonlinear Sci. 6 (1996) 449; McLachlan, Quispel & Robidoux, Phil. "
                  "Trans. R. Soc. A 357 (1999) 1021 (midpoint discrete gradient)"},
    /* ∇̄H_i = [H(y'_1..y'_i, y_{i+1}..y_n) − H(y'_1..y'_{i−1}, y_i..y_n)] / (y'_i − y_i). */
    {.name = "discrete-gradient-itoh-abe", .family = GM_FAMILY_DISCRETE_GRADIENT, .order = 1,
     .n_stages = 1, .flags = DG_FLAGS, .accepts = GM_PROBLEM_POISSON,
     .description = "Itoh-Abe coordinate-increment discrete gradient, energy exact",
     .reference = "Itoh & Abe, J. Comput. Phys. 76 (1988) 85; McLachlan, Quispel & Robidoux, Phil. "
                  "Trans. R. Soc. A 357 (1999) 1021 (coordinate increment discrete gradient)"},
};
const size_t gm_n_discrete_gradient_methods =
    sizeof gm_discrete_gradient_methods / sizeof gm_discrete_gradient_methods[0];

gm_discrete_gradient_kind gm_discrete_gradient_kind_of(const gm_method *m) {
  return (gm_discrete_gradient_kind)(m - gm_discrete_gradient_methods);
}
