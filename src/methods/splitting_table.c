/* Splitting (drift–kick) methods for separable H = T(p) + V(q). A step is, for each stage i,
 * drift q += a_i h ∇T(p), then kick p -= b_i h ∇V(q). */
#include "methods/internal.h"

/* Symplectic Euler A, position first: q_{n+1} = q_n + h ∇T(p_n), p_{n+1} = p_n − h ∇V(q_{n+1}).
 * Hairer, Lubich & Wanner, GNI 2nd ed. (2006), §VI.3, eq. (3.2) (the adjoint of (3.1)). */
static const double euler_a_a[] = {1.0};
static const double euler_a_b[] = {1.0};

/* Symplectic Euler B, momentum first: p_{n+1} = p_n − h ∇V(q_n), q_{n+1} = q_n + h ∇T(p_{n+1}).
 * GNI (2006), §VI.3, eq. (3.1); seed 004 eq. (24) as reconstructed in the notes. */
static const double euler_b_a[] = {0.0, 1.0};
static const double euler_b_b[] = {1.0, 0.0};

/* Störmer–Verlet, velocity form (kick ½, drift 1, kick ½). GNI (2006), §VI.3, eq. (3.4);
 * Verlet, Phys. Rev. 159 (1967) 98. */
static const double verlet_a[] = {0.0, 1.0};
static const double verlet_b[] = {0.5, 0.5};

/* Störmer–Verlet, position form (drift ½, kick 1, drift ½). GNI (2006), §VI.3, eq. (3.5). */
static const double verlet_position_a[] = {0.5, 0.5};
static const double verlet_position_b[] = {1.0, 0.0};

#define SPLIT(name, order, stages, flags, a, b, desc, ref) \
  {name, GM_FAMILY_SPLITTING, order, stages, flags, GM_PROBLEM_SEPARABLE, a, b, NULL, desc, ref}

const gm_method gm_splitting_methods[] = {
    SPLIT("symplectic-euler-a", 1, 1, GM_SYMPLECTIC | GM_EXPLICIT, euler_a_a, euler_a_b,
          "symplectic Euler, drift then kick",
          "Hairer, Lubich & Wanner, GNI (2006), eq. (VI.3.2)"),
    SPLIT("symplectic-euler-b", 1, 2, GM_SYMPLECTIC | GM_EXPLICIT, euler_b_a, euler_b_b,
          "symplectic Euler, kick then drift",
          "Hairer, Lubich & Wanner, GNI (2006), eq. (VI.3.1)"),
    SPLIT("verlet", 2, 2, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT | GM_FSAL, verlet_a, verlet_b,
          "Stormer-Verlet, velocity form (kick-drift-kick), one force per step",
          "Verlet, Phys. Rev. 159 (1967); Hairer, Lubich & Wanner, GNI (2006), eq. (VI.3.4)"),
    SPLIT("verlet-position", 2, 2, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT, verlet_position_a,
          verlet_position_b, "Stormer-Verlet, position form (drift-kick-drift)",
          "Hairer, Lubich & Wanner, GNI (2006), eq. (VI.3.5)"),
};
const size_t gm_n_splitting_methods = sizeof gm_splitting_methods / sizeof gm_splitting_methods[0];
