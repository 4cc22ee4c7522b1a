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

/* Ruth's third-order method. Ruth, IEEE Trans. Nucl. Sci. 30 (1983) 2669, the n = 3 scheme:
 * momentum coefficients c = (7/24, 3/4, -1/24), position coefficients d = (2/3, -2/3, 1), the
 * momentum updated first (kick c_1, drift d_1, kick c_2, ...). Not symmetric. */
static const double ruth3_a[] = {0.0, 2.0 / 3.0, -2.0 / 3.0, 1.0};
static const double ruth3_b[] = {7.0 / 24.0, 3.0 / 4.0, -1.0 / 24.0, 0.0};

/* McLachlan's optimized fourth-order symmetric method with five stages, a general splitting
 * (not RKN-only): the composition of a first-order splitting and its adjoint of McLachlan,
 * SIAM J. Sci. Comput. 16 (1995) 151-168, with the closed forms
 *   kicks  (14 - sqrt19)/108, (20 - 7 sqrt19)/108, (5 + 2 sqrt19)/27, (5 + 2 sqrt19)/27,
 *          (20 - 7 sqrt19)/108, (14 - sqrt19)/108,
 *   drifts 2/5, -1/10, 2/5, -1/10, 2/5.
 * The kicks take the outer place, so the step is FSAL: five forces per step. */
static const double mclachlan4_a[] = {0.0, 0.4, -0.1, 0.4, -0.1, 0.4};
static const double mclachlan4_b[] = {
    0.089269454226475245, -0.097336042636895508, 0.50806658841042026,
    0.50806658841042026,  -0.097336042636895508, 0.089269454226475245,
};

/* Blanes & Moan, J. Comput. Appl. Math. 142 (2002) 313-330, Table 2: the symmetric general
 * (partitioned Runge-Kutta, not RKN-only) splitting S6 of order 4 with six stages,
 * drift a_1 kick b_1 ... drift a_4 ... kick b_1 drift a_1, where a_4 = 1 - 2(a_1 + a_2 + a_3)
 * and b_3 = 1/2 - (b_1 + b_2). Literals as printed (15 digits); a_4, b_3 from the closed forms. */
static const double blanes_moan4_a[] = {
    0.0792036964311957, 0.353172906049774,  -0.0420650803577195, 0.2193769557534996,
    -0.0420650803577195, 0.353172906049774, 0.0792036964311957,
};
static const double blanes_moan4_b[] = {
    0.209515106613362, -0.143851773179818, 0.434336666566456, 0.434336666566456,
    -0.143851773179818, 0.209515106613362, 0.0,
};

/* Blanes & Moan (2002), Table 2: the symmetric general splitting S10 of order 6 with ten stages;
 * a_6 = 1 - 2(a_1 + ... + a_5), b_5 = 1/2 - (b_1 + ... + b_4). Literals as printed (15-16
 * digits); a_6, b_5 from the closed forms. */
static const double blanes_moan6_a[] = {
    0.0502627644003922, 0.413514300428344,  0.0450798897943977, -0.188054853819569,
    0.54196067845078,   -0.7255255585086898, 0.54196067845078,  -0.188054853819569,
    0.0450798897943977, 0.413514300428344,  0.0502627644003922,
};
static const double blanes_moan6_b[] = {
    0.148816447901042,  -0.132385865767784, 0.067307604692185, 0.432666402578175,
    -0.016404589403618, -0.016404589403618, 0.432666402578175, 0.067307604692185,
    -0.132385865767784, 0.148816447901042,  0.0,
};

/* Laskar & Robutel, Celest. Mech. Dyn. Astr. 80 (2001) 39-62, SABA_n: drifts between the n
 * Gauss-Legendre nodes c_1 < ... < c_n of [0, 1] (c_1, c_2 - c_1, ..., 1 - c_n), kicks with the
 * Gauss weights. n = n_stages - 1. Computed when the integrator is created; mirror-image entries
 * are made equal so that the step is exactly symmetric. */
static gm_status saba_tableau(const gm_method *m, gm_tableau *t) {
  const size_t s = m->n_stages, n = s - 1;
  if (n < 1 || t->a == NULL || t->b == NULL) return GM_EINVAL;
  gm_status st = gm_gauss_legendre(n, t->a, t->b);
  if (st != GM_OK) return st;
  gm_quadrature_map(n, 0.0, 1.0, t->a, t->b);
  t->a[n] = 1.0 - t->a[n - 1];
  for (size_t i = n - 1; i >= 1; --i) t->a[i] -= t->a[i - 1];
  t->b[n] = 0.0;
  for (size_t i = 0; i < s / 2; ++i) {
    const double a = 0.5 * (t->a[i] + t->a[n - i]);
    t->a[i] = t->a[n - i] = a;
  }
  for (size_t i = 0; i < n / 2; ++i) {
    const double b = 0.5 * (t->b[i] + t->b[n - 1 - i]);
    t->b[i] = t->b[n - 1 - i] = b;
  }
  return GM_OK;
}

/* Laskar & Robutel (2001), SBAB_n: kicks at the n + 1 Gauss-Lobatto nodes 0 = d_0 < ... < d_n = 1
 * with the Lobatto weights, drifts by the node differences d_i - d_{i-1}. n = n_stages - 1. */
static gm_status sbab_tableau(const gm_method *m, gm_tableau *t) {
  const size_t s = m->n_stages;
  if (s < 2 || t->a == NULL || t->b == NULL) return GM_EINVAL;
  gm_status st = gm_gauss_lobatto(s, t->a, t->b);
  if (st != GM_OK) return st;
  gm_quadrature_map(s, 0.0, 1.0, t->a, t->b);
  for (size_t i = s - 1; i >= 1; --i) t->a[i] -= t->a[i - 1];
  t->a[0] = 0.0;
  for (size_t i = 1; i <= (s - 1) / 2; ++i) {
    const double a = 0.5 * (t->a[i] + t->a[s - i]);
    t->a[i] = t->a[s - i] = a;
  }
  for (size_t i = 0; i < s / 2; ++i) {
    const double b = 0.5 * (t->b[i] + t->b[s - 1 - i]);
    t->b[i] = t->b[s - 1 - i] = b;
  }
  return GM_OK;
}

#define SPLIT(name_, order_, stages_, flags_, a_, b_, desc, ref)                             \
  {.name = name_, .family = GM_FAMILY_SPLITTING, .order = order_, .n_stages = stages_,       \
   .flags = flags_, .accepts = GM_PROBLEM_SEPARABLE, .a = a_, .b = b_, .description = desc,  \
   .reference = ref}

#define SPLIT_COMPUTED(name_, stages_, flags_, fn_, desc, ref)                                  \
  {.name = name_, .family = GM_FAMILY_SPLITTING, .order = 2, .n_stages = stages_,            \
   .flags = flags_, .accepts = GM_PROBLEM_SEPARABLE, .compute = fn_, .description = desc,    \
   .reference = ref}

/* SABA_n/SBAB_n have order 2, but for H = T + eps V their error is O(eps h^2n + eps^2 h^2). */
#define SABA_DESC(n_, two_n_)                                                                 \
  "Laskar-Robutel SABA_" #n_ ": order 2; error O(eps h^" #two_n_ " + eps^2 h^2) for the "       \
  "near-integrable H = T + eps V; drifts to the Gauss-Legendre nodes"
#define SBAB_DESC(n_, two_n_)                                                                 \
  "Laskar-Robutel SBAB_" #n_ ": order 2; error O(eps h^" #two_n_ " + eps^2 h^2) for the "       \
  "near-integrable H = T + eps V; kicks at the Gauss-Lobatto nodes"
#define LR_REF "Laskar & Robutel, Celest. Mech. Dyn. Astr. 80 (2001) 39-62"

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
    SPLIT("ruth-3", 3, 4, GM_SYMPLECTIC | GM_EXPLICIT, ruth3_a, ruth3_b,
          "Ruth's third-order method, three forces per step, not symmetric",
          "Ruth, IEEE Trans. Nucl. Sci. 30 (1983) 2669, the n = 3 scheme"),
    SPLIT("mclachlan-4", 4, 6, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT | GM_FSAL, mclachlan4_a,
          mclachlan4_b, "McLachlan's optimized fourth order, five stages (sqrt 19 closed form), FSAL",
          "McLachlan, SIAM J. Sci. Comput. 16 (1995) 151-168, order-4 method with m = 5"),
    SPLIT("blanes-moan-4", 4, 7, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT, blanes_moan4_a,
          blanes_moan4_b, "Blanes-Moan optimized fourth order S6 (six forces, small error constant)",
          "Blanes & Moan, J. Comput. Appl. Math. 142 (2002) 313-330, Table 2, S6"),
    SPLIT("blanes-moan-6", 6, 11, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT, blanes_moan6_a,
          blanes_moan6_b, "Blanes-Moan optimized sixth order S10 (ten forces, small error constant)",
          "Blanes & Moan, J. Comput. Appl. Math. 142 (2002) 313-330, Table 2, S10"),
    SPLIT_COMPUTED("saba-1", 2, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT, saba_tableau,
                   SABA_DESC(1, 2), LR_REF),
    SPLIT_COMPUTED("saba-2", 3, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT, saba_tableau,
                   SABA_DESC(2, 4), LR_REF),
    SPLIT_COMPUTED("saba-3", 4, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT, saba_tableau,
                   SABA_DESC(3, 6), LR_REF),
    SPLIT_COMPUTED("saba-4", 5, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT, saba_tableau,
                   SABA_DESC(4, 8), LR_REF),
    SPLIT_COMPUTED("sbab-1", 2, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT | GM_FSAL, sbab_tableau,
                   SBAB_DESC(1, 2), LR_REF),
    SPLIT_COMPUTED("sbab-2", 3, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT | GM_FSAL, sbab_tableau,
                   SBAB_DESC(2, 4), LR_REF),
    SPLIT_COMPUTED("sbab-3", 4, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT | GM_FSAL, sbab_tableau,
                   SBAB_DESC(3, 6), LR_REF),
    SPLIT_COMPUTED("sbab-4", 5, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT | GM_FSAL, sbab_tableau,
                   SBAB_DESC(4, 8), LR_REF),
};
const size_t gm_n_splitting_methods = sizeof gm_splitting_methods / sizeof gm_splitting_methods[0];

/* The SABA_n / SBAB_n coefficients for the near-integrable rows (src/celestial), which apply
 * them to Kepler drifts and interaction kicks. */
gm_status gm_saba_tableau(const gm_method *m, gm_tableau *t) { return saba_tableau(m, t); }
gm_status gm_sbab_tableau(const gm_method *m, gm_tableau *t) { return sbab_tableau(m, t); }
