/* Variational integrators: discrete Lagrangians as method rows (seed 000 §1.2.2, seed 001 §2.4
 * and §5.2, seed 004 "Variational integrators"). They integrate Lagrangian problems, and
 * separable problems with quadratic kinetic energy as L = ½vᵀMv − V(q), M⁻¹ = ∇²T. The state
 * is (q, p) with p the discrete momentum p_k = −D₁L_d(q_k, q_{k+1}) = D₂L_d(q_{k−1}, q_k).
 * n_stages is the number of quadrature points; gm_method_tableau gives the equivalent
 * partitioned Runge–Kutta tableau (seed 001 Thm 2.12). */
#include "methods/variational/variational_internal.h"

#define VI_FLAGS (GM_SYMPLECTIC | GM_SYMMETRIC | GM_IMPLICIT)
#define VI_ACCEPTS (GM_PROBLEM_SEPARABLE | GM_PROBLEM_LAGRANGIAN)

/* Degree s with s Gauss points: order 2s, equivalent to Gauss collocation (seed 001 Thm 2.12;
 * Marsden & West, Acta Numerica 10 (2001), §2.6.6; Hairer, Lubich & Wanner, GNI (2006),
 * §VI.6.3). */
#define GAUSS(s_, order_, name_)                                                              \
  {.name = name_, .family = GM_FAMILY_VARIATIONAL, .order = (order_), .n_stages = (s_),       \
   .flags = VI_FLAGS, .accepts = VI_ACCEPTS, .compute = gm_vi_gauss_tableau,                  \
   .description = "Galerkin discrete Lagrangian, degree " #s_ ", " #s_ " Gauss points",       \
   .reference = "Leok, thesis (2004), Sect. 2.4, Thm 2.12; Marsden & West, Acta Numer. 10 "   \
                "(2001), Sect. 2.6"}

/* Degree s with s + 1 Gauss–Lobatto points at the control points: order 2s; the trajectory
 * is that of the Lobatto IIIA–IIIB pair with s + 1 stages (tested for L = ½vᵀMv − V). */
#define LOBATTO(s_, order_, name_)                                                            \
  {.name = name_, .family = GM_FAMILY_VARIATIONAL, .order = (order_), .n_stages = (s_) + 1,   \
   .flags = VI_FLAGS, .accepts = VI_ACCEPTS, .compute = gm_vi_lobatto_tableau,                \
   .description = "Galerkin discrete Lagrangian, degree " #s_ ", Lobatto points",             \
   .reference = "Leok, thesis (2004), Sect. 2.4 and 5.2; Marsden & West, Acta Numer. 10 "     \
                "(2001), Sect. 2.6; GNI (2006), Sect. VI.6.3"}

/* Symplectic-energy-momentum with the Galerkin discrete Lagrangian of degree s (s Gauss points):
 * the higher-order form of seed 001 §5.5 (Leok, thesis (2004), Sect. 5.5, the time step an
 * unknown of the discrete energy equation; Kane, Marsden & Ortiz 1999 for the midpoint rule);
 * the stepper is variational_sem.c. Order 2s (measured: tests/convergence/test_order.c). */
#define SEM_GAUSS(s_, order_, name_)                                                          \
  {.name = name_, .family = GM_FAMILY_VARIATIONAL, .order = (order_), .n_stages = (s_),       \
   .flags = VI_FLAGS | GM_ENERGY_PRESERVING, .accepts = VI_ACCEPTS,                           \
   .compute = gm_vi_gauss_tableau,                                                            \
   .description = "symplectic-energy-momentum Galerkin, degree " #s_ ": steps chosen by the " \
                  "energy",                                                                   \
   .reference = "Leok, thesis (2004), Sect. 5.5 and 2.4; Kane, Marsden & Ortiz, J. Math. "    \
                "Phys. 40 (1999) 3353"}

static const double alpha_default[] = {0.25};

const gm_method gm_variational_methods[] = {
    /* L_d = (h/2)[L(q0, Δ) + L(q1, Δ)], Δ = (q1 − q0)/h: Störmer–Verlet for L = ½vᵀMv − V
     * (seed 000 §1.2.2, A2, with the factor h the notes restore) */
    {.name = "vi-trapezoidal", .family = GM_FAMILY_VARIATIONAL, .order = 2, .n_stages = 2,
     .flags = VI_FLAGS, .accepts = VI_ACCEPTS, .compute = gm_vi_lobatto_tableau,
     .description = "trapezoidal discrete Lagrangian (Stormer-Verlet for L = T - V)",
     .reference = "Stern, thesis (2009), Sect. 1.2.2; Marsden & West, Acta Numer. 10 (2001), "
                  "Sect. 2.6.2"},
    /* L_d = h L((q0 + q1)/2, Δ): the implicit midpoint rule for L = ½vᵀMv − V */
    {.name = "vi-midpoint", .family = GM_FAMILY_VARIATIONAL, .order = 2, .n_stages = 1,
     .flags = VI_FLAGS, .accepts = VI_ACCEPTS, .compute = gm_vi_gauss_tableau,
     .description = "midpoint discrete Lagrangian",
     .reference = "Stern, thesis (2009), Sect. 1.2.2; Marsden & West, Acta Numer. 10 (2001), "
                  "Sect. 2.6.3"},
    /* generalized α-rule L_d = h L((1−α)q0 + αq1, Δ); α = 1/4 here, any α in [0, 1] with
     * gm_variational_set_alpha; order 1 (2 for α = 1/2) */
    {.name = "vi-alpha", .family = GM_FAMILY_VARIATIONAL, .order = 1, .n_stages = 1,
     .flags = GM_SYMPLECTIC | GM_IMPLICIT, .accepts = VI_ACCEPTS, .c = alpha_default,
     .compute = gm_vi_alpha_tableau,
     .description = "generalized alpha-rule discrete Lagrangian, alpha = 1/4 (settable)",
     .reference = "Kane, Marsden, Ortiz & West, Int. J. Numer. Meth. Eng. 49 (2000) 1295; "
                  "Marsden & West, Acta Numer. 10 (2001), Sect. 2.6.5"},
    GAUSS(2, 4, "vi-galerkin-gauss-2"),
    GAUSS(3, 6, "vi-galerkin-gauss-3"),
    GAUSS(4, 8, "vi-galerkin-gauss-4"),
    GAUSS(5, 10, "vi-galerkin-gauss-5"),
    GAUSS(6, 12, "vi-galerkin-gauss-6"),
    LOBATTO(2, 4, "vi-galerkin-lobatto-2"),
    LOBATTO(3, 6, "vi-galerkin-lobatto-3"),
    LOBATTO(4, 8, "vi-galerkin-lobatto-4"),
    LOBATTO(5, 10, "vi-galerkin-lobatto-5"),
    /* symplectic-energy-momentum: the midpoint L_d with the time step as an unknown fixed by the
     * discrete energy equation (variational_sem.c) */
    {.name = "vi-sem-midpoint", .family = GM_FAMILY_VARIATIONAL, .order = 2, .n_stages = 1,
     .flags = VI_FLAGS | GM_ENERGY_PRESERVING, .accepts = VI_ACCEPTS,
     .compute = gm_vi_gauss_tableau,
     .description = "symplectic-energy-momentum midpoint rule: steps chosen by the energy",
     .reference = "Kane, Marsden & Ortiz, J. Math. Phys. 40 (1999) 3353; Leok, thesis (2004), "
                  "Sect. 5.5; Razafindralandy et al. (2018), Sect. 3.3"},
    SEM_GAUSS(2, 4, "vi-sem-galerkin-2"),
    SEM_GAUSS(3, 6, "vi-sem-galerkin-3"),
};
const size_t gm_n_variational_methods =
    sizeof gm_variational_methods / sizeof gm_variational_methods[0];
