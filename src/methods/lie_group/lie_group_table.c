/* Lie group integrators for rigid bodies on SO(3) (× R³) as method rows. The state is
 * (R, x, Π, p) (geomint/ode.h, GM_PROBLEM_RIGID_BODY); every row keeps R on SO(3) by
 * construction (products of exact rotations; no projection anywhere). */
#include "methods/lie_group/lie_group.h"

#define RIGID GM_PROBLEM_RIGID_BODY

/* Classical Runge–Kutta (Kutta 1901) as RKMK (Munthe-Kaas, BIT 38 (1998) 92, Algorithm 1
 * with the exact dexp⁻¹ of so(3)): order 4 */
static const double rk4_a[] = {0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1, 0};
static const double rk4_b[] = {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6};
static const double rk4_c[] = {0, 0.5, 0.5, 1};

/* Crouch & Grossman, J. Nonlinear Sci. 3 (1993) 1, third-order method with three stages
 * (the coefficients as tabulated by Owren & Marthinsen, BIT 39 (1999) 116, §5). Besides the
 * classical conditions of order 3 they satisfy the extra condition of frozen-flow methods
 * Σ b_i² c_i + 2 Σ_{i<j} b_i c_i b_j = 1/3 (checked in tests/unit/test_lie_methods.c). */
static const double cg3_a[] = {0, 0, 0, 0.75, 0, 0, 119.0 / 216, 17.0 / 108, 0};
static const double cg3_b[] = {13.0 / 51, -2.0 / 3, 24.0 / 17};
static const double cg3_c[] = {0, 0.75, 17.0 / 24};

/* Galerkin Lie group variational integrators (seed 001 §5.3): degree-s curves in the
 * exponential chart at R_k, s Gauss points: order 2s (measured in tests/convergence). The
 * stationarity conditions are derived in lie_galerkin.c and docs/lie-groups.md. */
#define GALERKIN(s_, order_, name_)                                                           \
  {.name = name_, .family = GM_FAMILY_LIE_GROUP, .order = (order_), .n_stages = (s_),         \
   .flags = GALERKIN_FLAGS_##s_, .accepts = RIGID,                                           \
   .description = "Galerkin Lie group variational integrator, degree " #s_                    \
                  " in the exponential chart, " #s_ " Gauss points",                          \
   .reference = "Leok, thesis (2004), Sect. 5.3 (conditions re-derived, see docs/lie-groups.md)"}
/* The discrete Euler–Poincaré equations of the same discrete Lagrangian for free bodies
 * (seed 001 §5.4), reconstruction R_{k+1} = R_k f_k. */
#define DEP(s_, order_, name_)                                                                \
  {.name = name_, .family = GM_FAMILY_LIE_GROUP, .order = (order_), .n_stages = (s_),         \
   .flags = GALERKIN_FLAGS_##s_, .accepts = RIGID,                                           \
   .description = "discrete Euler-Poincare (free bodies), degree " #s_ ", " #s_               \
                  " Gauss points; R_{k+1} = R_k f_k",                                         \
   .reference = "Leok, thesis (2004), Sect. 5.4 (f = g_k^-1 g_k+1, seeds/notes/001 Sect. 4)"}
/* s = 1 follows a one-parameter subgroup, the same curve seen from either end: symmetric.
 * For s >= 2 the chart at R_k and at R_{k+1} give different curves: not symmetric (measured,
 * tests/invariants/test_reversible.c). */
#define GALERKIN_FLAGS_1 (GM_SYMPLECTIC | GM_SYMMETRIC | GM_IMPLICIT)
#define GALERKIN_FLAGS_2 (GM_SYMPLECTIC | GM_IMPLICIT)
#define GALERKIN_FLAGS_3 (GM_SYMPLECTIC | GM_IMPLICIT)

const gm_method gm_lie_group_methods[] = {
    {.name = "lgvi", .family = GM_FAMILY_LIE_GROUP, .order = 2, .n_stages = 1,
     .flags = GM_SYMPLECTIC | GM_SYMMETRIC | GM_IMPLICIT, .accepts = RIGID,
     .description = "Lie group variational integrator: F_k in SO(3) by Newton in so(3)",
     .reference = "Lee, Leok & McClamroch, Comput. Methods Appl. Mech. Eng. 196 (2007) 2907, "
                  "eqs. (44)-(47); Proc. ACC (2005) 962 (3-D pendulum)"},
    {.name = "rkmk4", .family = GM_FAMILY_LIE_GROUP, .order = 4, .n_stages = 4,
     .flags = GM_EXPLICIT, .accepts = RIGID, .a = rk4_a, .b = rk4_b, .c = rk4_c,
     .description = "Runge-Kutta-Munthe-Kaas with the classical RK4 tableau",
     .reference = "Munthe-Kaas, BIT 38 (1998) 92; Iserles et al., Acta Numer. 9 (2000) 215, "
                  "Sect. 5.3"},
    {.name = "crouch-grossman-3", .family = GM_FAMILY_LIE_GROUP, .order = 3, .n_stages = 3,
     .flags = GM_EXPLICIT, .accepts = RIGID, .a = cg3_a, .b = cg3_b, .c = cg3_c,
     .description = "Crouch-Grossman: products of exponentials of frozen stage velocities",
     .reference = "Crouch & Grossman, J. Nonlinear Sci. 3 (1993) 1; Owren & Marthinsen, BIT 39 "
                  "(1999) 116"},
    {.name = "rigid-splitting", .family = GM_FAMILY_LIE_GROUP, .order = 2, .n_stages = 5,
     .flags = GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT, .accepts = RIGID,
     .description = "kick, exact rotations about the body axes 1-2-3-2-1 (Strang), kick; "
                    "needs principal axes (diagonal J)",
     .reference = "McLachlan, Phys. Rev. Lett. 71 (1993) 3043; Touma & Wisdom, Astron. J. 107 "
                  "(1994) 1189; Dullweber, Leimkuhler & McLachlan, J. Chem. Phys. 107 (1997) "
                  "5840"},
    GALERKIN(1, 2, "lgvi-galerkin-1"),
    GALERKIN(2, 4, "lgvi-galerkin-2"),
    GALERKIN(3, 6, "lgvi-galerkin-3"),
    DEP(1, 2, "dep-1"),
    DEP(2, 4, "dep-2"),
    DEP(3, 6, "dep-3"),
};
const size_t gm_n_lie_group_methods = sizeof gm_lie_group_methods / sizeof gm_lie_group_methods[0];

static const gm_lie_scheme schemes[] = {
    GM_LIE_LGVI,     GM_LIE_RKMK,     GM_LIE_CROUCH_GROSSMAN, GM_LIE_SPLITTING,
    GM_LIE_GALERKIN, GM_LIE_GALERKIN, GM_LIE_GALERKIN,        GM_LIE_DEP,
    GM_LIE_DEP,      GM_LIE_DEP};
_Static_assert(sizeof schemes / sizeof schemes[0] ==
                   sizeof gm_lie_group_methods / sizeof gm_lie_group_methods[0],
               "one scheme per row");

gm_lie_scheme gm_lie_scheme_of(const gm_method *m) {
  for (size_t i = 0; i < gm_n_lie_group_methods; ++i)
    if (m == &gm_lie_group_methods[i]) return schemes[i];
  return (gm_lie_scheme)0;
}
