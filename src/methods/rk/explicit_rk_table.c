/* Explicit Runge–Kutta methods: non-geometric baselines. Butcher tableaux (A row-major). */
#include "methods/internal.h"

/* Explicit Euler. Hairer, Nørsett & Wanner, Solving ODEs I (1993), §II.1, eq. (1.5). */
static const double euler_a[] = {0.0};
static const double euler_b[] = {1.0};
static const double euler_c[] = {0.0};

/* Classical fourth-order method of Kutta (1901). HNW I, Table II.1.2 (left). */
static const double rk4_a[] = {
    0.0, 0.0, 0.0, 0.0,
    0.5, 0.0, 0.0, 0.0,
    0.0, 0.5, 0.0, 0.0,
    0.0, 0.0, 1.0, 0.0,
};
static const double rk4_b[] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
static const double rk4_c[] = {0.0, 0.5, 0.5, 1.0};

#define ERK(name_, order_, stages_, a_, b_, c_, desc, ref)                                  \
  {.name = name_, .family = GM_FAMILY_EXPLICIT_RK, .order = order_, .n_stages = stages_,     \
   .flags = GM_EXPLICIT, .accepts = GM_PROBLEM_FIRST_ORDER, .a = a_, .b = b_, .c = c_,       \
   .description = desc, .reference = ref}

const gm_method gm_explicit_rk_methods[] = {
    ERK("euler", 1, 1, euler_a, euler_b, euler_c,
        "explicit Euler: non-geometric baseline, energy grows",
        "Hairer, Norsett & Wanner, Solving ODEs I (1993), eq. (II.1.5)"),
    ERK("rk4", 4, 4, rk4_a, rk4_b, rk4_c,
        "classical Runge-Kutta: accurate, not symplectic, energy drifts",
        "Kutta (1901); Hairer, Norsett & Wanner, Solving ODEs I (1993), Table II.1.2"),
};
const size_t gm_n_explicit_rk_methods =
    sizeof gm_explicit_rk_methods / sizeof gm_explicit_rk_methods[0];
