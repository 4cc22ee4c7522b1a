/* Implicit Runge–Kutta methods, solved by Newton's method. */
#include "methods/internal.h"

/* Implicit midpoint rule y_{n+1} = y_n + h f((y_n + y_{n+1})/2): the one-stage Gauss method.
 * Symplectic and symmetric; keeps quadratic invariants exactly. Hairer, Lubich & Wanner, GNI
 * 2nd ed. (2006), §VI.3 (symplecticity) and §IV.2 (quadratic invariants); seed 004 eq. (25) as
 * reconstructed in the notes. */
static const double midpoint_a[] = {0.5};
static const double midpoint_b[] = {1.0};
static const double midpoint_c[] = {0.5};

const gm_method gm_implicit_rk_methods[] = {
    {"midpoint", GM_FAMILY_IMPLICIT_RK, 2, 1, GM_SYMPLECTIC | GM_SYMMETRIC | GM_IMPLICIT,
     GM_PROBLEM_FIRST_ORDER, midpoint_a, midpoint_b, midpoint_c,
     "implicit midpoint rule (Gauss, 1 stage), Newton per step",
     "Hairer, Lubich & Wanner, GNI (2006), Sect. VI.3 and IV.2"},
};
const size_t gm_n_implicit_rk_methods =
    sizeof gm_implicit_rk_methods / sizeof gm_implicit_rk_methods[0];
