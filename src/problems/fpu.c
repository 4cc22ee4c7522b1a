/* The Fermi–Pasta–Ulam problem of Hairer, Lubich & Wanner, GNI (2006), §I.5.1 and §XIII.2.1,
 * as used in seed 000 §2.2.4 (Stern's thesis, Fig. 2.2; notes/000-stern-thesis.md "E2 FPU"):
 * a chain of 2ℓ unit masses joined alternately by stiff linear springs (stiffness ω²/2) and
 * soft nonlinear springs (quartic potential), both ends fixed,
 *   H = ½ Σ_{i=1}^{2ℓ} p_i² + (ω²/4) Σ_{i=1}^{ℓ} (q_{2i} − q_{2i−1})²
 *       + Σ_{i=0}^{ℓ} (q_{2i+1} − q_{2i})⁴,      q_0 = q_{2ℓ+1} = 0.
 *
 * Coordinates. We use the rotated coordinates of HLW §I.5.1 (the seed's text omits the
 * transform; the notes restore it): for i = 1..ℓ
 *   x_{0,i} = (q_{2i} + q_{2i−1})/√2  (centre of the stiff spring, slow),
 *   x_{1,i} = (q_{2i} − q_{2i−1})/√2  (its elongation, fast),
 * and y_{0,i}, y_{1,i} from p in the same way. The map is orthogonal, so it is canonical and
 * the kinetic energy stays ½|y|². With the convention x_{·,0} = x_{·,ℓ+1} = 0 and
 *   w_k = (x_{0,k+1} − x_{1,k+1}) − (x_{0,k} + x_{1,k}) = √2 (q_{2k+1} − q_{2k}),  k = 0..ℓ,
 * the Hamiltonian is
 *   H = ½|y|² + (ω²/2) Σ_i x_{1,i}² + ¼ Σ_{k=0}^{ℓ} w_k⁴.
 * The state is q = (x_{0,1..ℓ}, x_{1,1..ℓ}), p = (y_{0,1..ℓ}, y_{1,1..ℓ}): the stiff part is
 * the diagonal quadratic (ω²/2)|x₁|², which is what the methods for oscillatory problems
 * (HLW Ch. XIII, the IMEX method of seed 000) split off, and it is where the initial data and
 * the invariants are stated. Gradient and Hessian of the quartic part: ∂(¼w⁴) = w³ ∇w and
 * ∂²(¼w⁴) = 3w² ∇w ∇wᵀ, ∇w_k having entries +1 (x_{0,k+1}), −1 (x_{1,k+1}), −1 (x_{0,k}),
 * −1 (x_{1,k}).
 *
 * Initial data (HLW §I.5.1, seed 000): x_{0,1} = 1, y_{0,1} = 1, x_{1,1} = 1/ω, y_{1,1} = 1,
 * all others 0; ℓ = 3, ω = 50. Monitored quantities: the energies of the stiff springs
 * I_j = ½(y_{1,j}² + ω² x_{1,j}²), which exchange energy on the time scale ω, and their sum
 * I = Σ I_j, an adiabatic invariant (conserved up to O(1/ω) over very long times; HLW §I.5.1
 * and Ch. XIII); I(0) = 1. */
#include <math.h>
#include <string.h>

#include "geomint/oscillatory.h"
#include "problems/internal.h"

#define FPU_MAX_SPRINGS 16

typedef struct {
  size_t dim; /* 2ℓ, first for gm_free_kinetic */
  size_t n_springs;
  double omega;
  gm_invariant invariants[FPU_MAX_SPRINGS + 1];
  /* the split V = U + W (issue 12): U the quartic soft springs, W = (ω²/2)|x₁|² = ½ qᵀΩ²q with
   * the diagonal Ω = diag(0, ..., 0, ω, ..., ω) */
  double omega_diag[2 * FPU_MAX_SPRINGS];
  gm_split_potential split;
} fpu;

/* x_{0,i} and x_{1,i}, i = 0..ℓ+1, zero at the fixed ends. */
static double x0(const fpu *f, const double *q, size_t i) {
  return (i >= 1 && i <= f->n_springs) ? q[i - 1] : 0.0;
}
static double x1(const fpu *f, const double *q, size_t i) {
  return (i >= 1 && i <= f->n_springs) ? q[f->n_springs + i - 1] : 0.0;
}

/* w_k and the (at most four) indices into q of ∇w_k with their signs; returns how many. */
static double soft_spring(const fpu *f, const double *q, size_t k, size_t index[4],
                          double sign[4], size_t *count) {
  const size_t l = f->n_springs;
  size_t c = 0;
  if (k + 1 <= l) {
    index[c] = k;  /* x_{0,k+1} */
    sign[c++] = 1.0;
    index[c] = l + k; /* x_{1,k+1} */
    sign[c++] = -1.0;
  }
  if (k >= 1) {
    index[c] = k - 1; /* x_{0,k} */
    sign[c++] = -1.0;
    index[c] = l + k - 1; /* x_{1,k} */
    sign[c++] = -1.0;
  }
  *count = c;
  return (x0(f, q, k + 1) - x1(f, q, k + 1)) - (x0(f, q, k) + x1(f, q, k));
}

static double potential(void *ctx, const double *q) {
  const fpu *f = ctx;
  const size_t l = f->n_springs;
  double stiff = 0.0, soft = 0.0;
  for (size_t i = 0; i < l; ++i) stiff += q[l + i] * q[l + i];
  for (size_t k = 0; k <= l; ++k) {
    size_t index[4], count;
    double sign[4];
    double w = soft_spring(f, q, k, index, sign, &count), w2 = w * w;
    soft += w2 * w2;
  }
  return 0.5 * f->omega * f->omega * stiff + 0.25 * soft;
}

static int potential_gradient(void *ctx, const double *q, double *out) {
  const fpu *f = ctx;
  const size_t l = f->n_springs;
  for (size_t i = 0; i < l; ++i) {
    out[i] = 0.0;
    out[l + i] = f->omega * f->omega * q[l + i];
  }
  for (size_t k = 0; k <= l; ++k) {
    size_t index[4], count;
    double sign[4];
    double w = soft_spring(f, q, k, index, sign, &count), w3 = w * w * w;
    for (size_t a = 0; a < count; ++a) out[index[a]] += sign[a] * w3;
  }
  return 0;
}

static int potential_hessian(void *ctx, const double *q, double *hessian) {
  const fpu *f = ctx;
  const size_t l = f->n_springs, d = f->dim;
  memset(hessian, 0, d * d * sizeof *hessian);
  for (size_t i = 0; i < l; ++i) hessian[(l + i) * d + l + i] = f->omega * f->omega;
  for (size_t k = 0; k <= l; ++k) {
    size_t index[4], count;
    double sign[4];
    double w = soft_spring(f, q, k, index, sign, &count), c = 3.0 * w * w;
    for (size_t a = 0; a < count; ++a)
      for (size_t b = 0; b < count; ++b) hessian[index[a] * d + index[b]] += c * sign[a] * sign[b];
  }
  return 0;
}

static double slow(void *ctx, const double *q) {
  const fpu *f = ctx;
  double soft = 0.0;
  for (size_t k = 0; k <= f->n_springs; ++k) {
    size_t index[4], count;
    double sign[4];
    double w = soft_spring(f, q, k, index, sign, &count), w2 = w * w;
    soft += w2 * w2;
  }
  return 0.25 * soft;
}

static int slow_gradient(void *ctx, const double *q, double *out) {
  const fpu *f = ctx;
  memset(out, 0, f->dim * sizeof *out);
  for (size_t k = 0; k <= f->n_springs; ++k) {
    size_t index[4], count;
    double sign[4];
    double w = soft_spring(f, q, k, index, sign, &count), w3 = w * w * w;
    for (size_t a = 0; a < count; ++a) out[index[a]] += sign[a] * w3;
  }
  return 0;
}

static double fast(void *ctx, const double *q) {
  const fpu *f = ctx;
  double s = 0.0;
  for (size_t i = 0; i < f->n_springs; ++i) s += q[f->n_springs + i] * q[f->n_springs + i];
  return 0.5 * f->omega * f->omega * s;
}

static int fast_gradient(void *ctx, const double *q, double *out) {
  const fpu *f = ctx;
  for (size_t i = 0; i < f->dim; ++i) out[i] = f->omega_diag[i] * f->omega_diag[i] * q[i];
  return 0;
}

/* I_j = ½(y_{1,j}² + ω² x_{1,j}²), j = 1..ℓ */
static double oscillatory_energy(const fpu *f, const double *y, size_t j) {
  const size_t l = f->n_springs;
  double x = y[l + j - 1], v = y[2 * l + l + j - 1];
  return 0.5 * (v * v + f->omega * f->omega * x * x);
}

static double total_oscillatory_energy(void *ctx, const double *y) {
  const fpu *f = ctx;
  double s = 0.0;
  for (size_t j = 1; j <= f->n_springs; ++j) s += oscillatory_energy(f, y, j);
  return s;
}

/* One function per spring: an invariant sees only (ctx, y). */
#define FPU_ENERGY(j) \
  static double energy_##j(void *ctx, const double *y) { return oscillatory_energy(ctx, y, j); }
FPU_ENERGY(1)
FPU_ENERGY(2)
FPU_ENERGY(3)
FPU_ENERGY(4)
FPU_ENERGY(5)
FPU_ENERGY(6)
FPU_ENERGY(7)
FPU_ENERGY(8)
FPU_ENERGY(9)
FPU_ENERGY(10)
FPU_ENERGY(11)
FPU_ENERGY(12)
FPU_ENERGY(13)
FPU_ENERGY(14)
FPU_ENERGY(15)
FPU_ENERGY(16)
#undef FPU_ENERGY

static double (*const energy_of_spring[FPU_MAX_SPRINGS])(void *, const double *) = {
    energy_1,  energy_2,  energy_3,  energy_4,  energy_5,  energy_6,  energy_7,  energy_8,
    energy_9,  energy_10, energy_11, energy_12, energy_13, energy_14, energy_15, energy_16};
static const char *const spring_names[FPU_MAX_SPRINGS] = {
    "I1", "I2", "I3", "I4", "I5", "I6", "I7", "I8",
    "I9", "I10", "I11", "I12", "I13", "I14", "I15", "I16"};
/* the names with default parameters (ℓ = 3) */
static const char *const invariant_names[] = {"I1", "I2", "I3", "I"};

static gm_status prepare(void *ctx, const double *params, const char *const *texts, size_t *dim,
                         char *errmsg, size_t cap) {
  (void)ctx;
  (void)texts;
  const double l = params[0];
  if (!(l >= 1.0 && l <= FPU_MAX_SPRINGS && l == floor(l)))
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "fpu: l (the number of stiff springs) must be an integer from 1 to %d, got %g",
                   FPU_MAX_SPRINGS, l);
  *dim = 2 * (size_t)l;
  return GM_OK;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  (void)t0;
  fpu *f = ctx;
  const size_t l = (size_t)params[0];
  const double omega = params[1];
  if (!(omega > 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL, "fpu: omega must be positive, got %g", omega);
  f->dim = 2 * l;
  f->n_springs = l;
  f->omega = omega;
  for (size_t j = 0; j < l; ++j)
    f->invariants[j] = (gm_invariant){spring_names[j], energy_of_spring[j]};
  f->invariants[l] = (gm_invariant){"I", total_oscillatory_energy};
  gm_free_kinetic_setup(pb);
  pb->potential = potential;
  pb->potential_gradient = potential_gradient;
  pb->potential_hessian = potential_hessian;
  for (size_t i = 0; i < 2 * l; ++i) f->omega_diag[i] = i < l ? 0.0 : omega;
  f->split = (gm_split_potential){slow, slow_gradient, fast, fast_gradient, NULL, f->omega_diag,
                                  1, NULL};
  pb->split = &f->split;
  pb->n_invariants = l + 1;
  pb->invariants = f->invariants;
  /* q = (x0, x1), p = (y0, y1) */
  y0[0] = 1.0;                /* x_{0,1} */
  y0[l] = 1.0 / omega;        /* x_{1,1} */
  y0[2 * l] = 1.0;            /* y_{0,1} */
  y0[2 * l + l] = 1.0;        /* y_{1,1} */
  return GM_OK;
}

static const gm_param_info params[] = {
    {"l", 3.0, "number of stiff springs (1..16); 2l degrees of freedom", GM_PARAM_NUMBER},
    {"omega", 50.0, "frequency of the stiff springs", GM_PARAM_NUMBER}};

const gm_model_def gm_model_fpu = {
    {"fpu",
     "Fermi-Pasta-Ulam chain of HLW I.5.1 in rotated coordinates q = (x0, x1), p = (y0, y1); "
     "stiff-spring energies I_j",
     GM_PROBLEM_SEPARABLE, 6, 2, params, 4, invariant_names, 0},
    sizeof(fpu), prepare, setup, NULL, NULL};
