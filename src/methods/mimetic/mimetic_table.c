/* The mimetic spectral element time integrators of seed 003 (Palha & Gerritsma, "A mimetic
 * spectral element solver for Hamiltonian systems"), one row per polynomial degree p of the
 * trajectory in a time element (order 2p):
 *  - mimetic-canonical-p (MCI, eq. 5.10, with the metric factor Δt/2 of the notes restored):
 *    the canonical Hodge star, a collocation at the p Gauss points; a Runge–Kutta method equal
 *    to p-stage Gauss–Legendre collocation (Remark 2), hence symplectic (Theorem 3) and
 *    symmetric;
 *  - mimetic-galerkin-p (MGI, eq. 5.15): the Galerkin Hodge star; the right-hand side tested
 *    against the dual basis, N = diag(w) (eq. 5.39). For canonical Hamiltonian systems it keeps
 *    H exactly (Theorem 4) when the integrals are exact; it is Hairer's energy-preserving
 *    variant of collocation (Hairer, JNAIAM 5 (2010) 73, Remark 3), and for p = 1 the average
 *    vector field method. Symmetric, not symplectic. */
#include "methods/energy.h"

#define MIMETIC_REF "Palha & Gerritsma, mimetic spectral element solver for Hamiltonian systems (seed 003)"

#define CANONICAL(p_, name_)                                                                  \
  {.name = name_, .family = GM_FAMILY_MIMETIC, .order = 2 * (p_), .n_stages = (p_),           \
   .flags = GM_SYMPLECTIC | GM_SYMMETRIC | GM_IMPLICIT, .accepts = GM_PROBLEM_FIRST_ORDER,    \
   .compute = gm_mimetic_canonical_tableau,                                                   \
   .description = "mimetic canonical integrator (MCI), degree " #p_                           \
                  " in time; = Gauss collocation, " #p_ " stages",                            \
   .reference = MIMETIC_REF ", eq. (5.10), Remark 2, Theorem 3"}

#define GALERKIN(p_, name_)                                                                   \
  {.name = name_, .family = GM_FAMILY_MIMETIC, .order = 2 * (p_), .n_stages = (p_),           \
   .flags = GM_SYMMETRIC | GM_IMPLICIT | GM_ENERGY_PRESERVING,                                \
   .accepts = GM_PROBLEM_FIRST_ORDER,                                                         \
   .description = "mimetic Galerkin integrator (MGI), degree " #p_                            \
                  " in time; keeps H of canonical systems",                                   \
   .reference = MIMETIC_REF ", eq. (5.15), Theorem 4; Hairer, JNAIAM 5 (2010) 73"}

const gm_method gm_mimetic_methods[] = {
    CANONICAL(1, "mimetic-canonical-1"), CANONICAL(2, "mimetic-canonical-2"),
    CANONICAL(3, "mimetic-canonical-3"), CANONICAL(4, "mimetic-canonical-4"),
    CANONICAL(5, "mimetic-canonical-5"), CANONICAL(6, "mimetic-canonical-6"),
    GALERKIN(1, "mimetic-galerkin-1"),   GALERKIN(2, "mimetic-galerkin-2"),
    GALERKIN(3, "mimetic-galerkin-3"),   GALERKIN(4, "mimetic-galerkin-4"),
    GALERKIN(5, "mimetic-galerkin-5"),   GALERKIN(6, "mimetic-galerkin-6"),
};
const size_t gm_n_mimetic_methods = sizeof gm_mimetic_methods / sizeof gm_mimetic_methods[0];
