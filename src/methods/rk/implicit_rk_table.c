/* Implicit Runge–Kutta methods, solved by Newton's method. */
#include "methods/internal.h"

/* Implicit midpoint rule y_{n+1} = y_n + h f((y_n + y_{n+1})/2): the one-stage Gauss method.
 * Symplectic and symmetric; keeps quadratic invariants exactly. Hairer, Lubich & Wanner, GNI
 * 2nd ed. (2006), §VI.3 (symplecticity) and §IV.2 (quadratic invariants); seed 004 eq. (25) as
 * reconstructed in the notes. */
static const double midpoint_a[] = {0.5};
static const double midpoint_b[] = {1.0};
static const double midpoint_c[] = {0.5};

/* Gauss–Legendre collocation with s stages: order 2s, symplectic, symmetric, keeps quadratic
 * invariants (Butcher 1964; GNI (2006), §II.1.3, Thm IV.2.1, Thm VI.4.2). Coefficients from the
 * Gauss nodes at create time (collocation.c), for any s; the table lists s ≤ 8 (order 16),
 * beyond which double precision leaves nothing to gain. */
#define GAUSS(s_, name_)                                                                      \
  {.name = name_, .family = GM_FAMILY_IMPLICIT_RK, .order = 2 * (s_), .n_stages = (s_),       \
   .flags = GM_SYMPLECTIC | GM_SYMMETRIC | GM_IMPLICIT, .accepts = GM_PROBLEM_FIRST_ORDER,    \
   .compute = gm_gauss_tableau,                                                               \
   .description = "Gauss-Legendre collocation, " #s_ " stages, order " #s_ "x2",              \
   .reference = "Butcher, Math. Comp. 18 (1964) 50; Hairer, Lubich & Wanner, GNI (2006), "    \
                "Sect. II.1.3, VI.4"}

const gm_method gm_implicit_rk_methods[] = {
    {.name = "midpoint", .family = GM_FAMILY_IMPLICIT_RK, .order = 2, .n_stages = 1,
     .flags = GM_SYMPLECTIC | GM_SYMMETRIC | GM_IMPLICIT, .accepts = GM_PROBLEM_FIRST_ORDER,
     .a = midpoint_a, .b = midpoint_b, .c = midpoint_c,
     .description = "implicit midpoint rule (Gauss, 1 stage), Newton per step",
     .reference = "Hairer, Lubich & Wanner, GNI (2006), Sect. VI.3 and IV.2"},
    GAUSS(1, "gauss-1"), GAUSS(2, "gauss-2"), GAUSS(3, "gauss-3"), GAUSS(4, "gauss-4"),
    GAUSS(5, "gauss-5"), GAUSS(6, "gauss-6"), GAUSS(7, "gauss-7"), GAUSS(8, "gauss-8"),
};
const size_t gm_n_implicit_rk_methods =
    sizeof gm_implicit_rk_methods / sizeof gm_implicit_rk_methods[0];
