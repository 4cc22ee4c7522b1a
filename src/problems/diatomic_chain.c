/* A chain of n diatomic molecules on a line (issue 12): atoms 2i−1 (mass m_a) and 2i (mass m_b)
 * form molecule i, joined by a stiff harmonic bond of frequency ω (stiffness μω², μ the reduced
 * mass); neighbouring molecules interact through soft anharmonic springs between atom 2i and
 * atom 2i+1; free ends. q are displacements from equilibrium, so
 *   W = Σ_i (μω²/2)(q_{2i} − q_{2i−1})² = ½ qᵀΩ²q,  Ω = block diag √(μω²/2)[[1, −1], [−1, 1]]
 * (Ω² = μω²[[1, −1], [−1, 1]] per block: symmetric PSD, not diagonal, and with M ≠ I the
 * mass-weighted K = M^{−1/2}Ω²M^{−1/2} has eigenvalues 0 and ω²),
 *   U = Σ_{i=1}^{n−1} (s/2) r_i² + (b/4) r_i⁴,  r_i = q_{2i+1} − q_{2i}.
 * Invariants: the total momentum (translation symmetry) and the total bond energy
 * I = Σ_i ½ μ ρ̇_i² + ½ μω² ρ_i², ρ_i = q_{2i} − q_{2i−1} (an adiabatic invariant, like I of
 * FPU). Initial state: molecule 1's bond stretched by 1/ω about its centre of mass, its first
 * atom pushed with momentum 1. */
#include <math.h>
#include <string.h>

#include "geomint/oscillatory.h"
#include "problems/internal.h"

#define DIATOMIC_MAX 16

typedef struct {
  size_t dim;
  size_t n;
  double omega, ma, mb, mu, soft, quartic;
  double mass[2 * DIATOMIC_MAX];
  double omega_matrix[4 * DIATOMIC_MAX * DIATOMIC_MAX];
  gm_split_potential split;
  gm_invariant invariants[2];
} chain;

static double kinetic(void *ctx, const double *p) {
  const chain *c = ctx;
  double t = 0.0;
  for (size_t i = 0; i < c->dim; ++i) t += p[i] * p[i] / c->mass[i];
  return 0.5 * t;
}
static int kinetic_gradient(void *ctx, const double *p, double *out) {
  const chain *c = ctx;
  for (size_t i = 0; i < c->dim; ++i) out[i] = p[i] / c->mass[i];
  return 0;
}
static int kinetic_hessian(void *ctx, const double *p, double *h) {
  (void)p;
  const chain *c = ctx;
  memset(h, 0, c->dim * c->dim * sizeof *h);
  for (size_t i = 0; i < c->dim; ++i) h[i * c->dim + i] = 1.0 / c->mass[i];
  return 0;
}
static double slow(void *ctx, const double *q) {
  const chain *c = ctx;
  double u = 0.0;
  for (size_t i = 1; i < c->n; ++i) {
    const double r = q[2 * i] - q[2 * i - 1], r2 = r * r;
    u += 0.5 * c->soft * r2 + 0.25 * c->quartic * r2 * r2;
  }
  return u;
}
static int slow_gradient(void *ctx, const double *q, double *out) {
  const chain *c = ctx;
  memset(out, 0, c->dim * sizeof *out);
  for (size_t i = 1; i < c->n; ++i) {
    const double r = q[2 * i] - q[2 * i - 1], f = c->soft * r + c->quartic * r * r * r;
    out[2 * i] += f;
    out[2 * i - 1] -= f;
  }
  return 0;
}
static double fast(void *ctx, const double *q) {
  const chain *c = ctx;
  double w = 0.0;
  for (size_t i = 0; i < c->n; ++i) {
    const double rho = q[2 * i + 1] - q[2 * i];
    w += 0.5 * c->mu * c->omega * c->omega * rho * rho;
  }
  return w;
}
static int fast_gradient(void *ctx, const double *q, double *out) {
  const chain *c = ctx;
  const double k = c->mu * c->omega * c->omega;
  for (size_t i = 0; i < c->n; ++i) {
    const double rho = q[2 * i + 1] - q[2 * i];
    out[2 * i + 1] = k * rho;
    out[2 * i] = -k * rho;
  }
  return 0;
}
static double potential(void *ctx, const double *q) { return slow(ctx, q) + fast(ctx, q); }
static int potential_gradient(void *ctx, const double *q, double *out) {
  const chain *c = ctx;
  double g[2 * DIATOMIC_MAX];
  fast_gradient(ctx, q, g);
  slow_gradient(ctx, q, out);
  for (size_t i = 0; i < c->dim; ++i) out[i] += g[i];
  return 0;
}
static int potential_hessian(void *ctx, const double *q, double *h) {
  const chain *c = ctx;
  const size_t d = c->dim;
  memset(h, 0, d * d * sizeof *h);
  const double k = c->mu * c->omega * c->omega;
  for (size_t i = 0; i < c->n; ++i) {
    const size_t a = 2 * i, b = 2 * i + 1;
    h[a * d + a] += k;
    h[b * d + b] += k;
    h[a * d + b] -= k;
    h[b * d + a] -= k;
  }
  for (size_t i = 1; i < c->n; ++i) {
    const size_t a = 2 * i - 1, b = 2 * i;
    const double r = q[b] - q[a], kk = c->soft + 3.0 * c->quartic * r * r;
    h[a * d + a] += kk;
    h[b * d + b] += kk;
    h[a * d + b] -= kk;
    h[b * d + a] -= kk;
  }
  return 0;
}

static double momentum(void *ctx, const double *y) {
  const chain *c = ctx;
  double s = 0.0;
  for (size_t i = 0; i < c->dim; ++i) s += y[c->dim + i];
  return s;
}
static double bond_energy(void *ctx, const double *y) {
  const chain *c = ctx;
  const double *q = y, *p = y + c->dim;
  double e = 0.0;
  for (size_t i = 0; i < c->n; ++i) {
    const double rho = q[2 * i + 1] - q[2 * i];
    const double rhodot = p[2 * i + 1] / c->mb - p[2 * i] / c->ma;
    e += 0.5 * c->mu * (rhodot * rhodot + c->omega * c->omega * rho * rho);
  }
  return e;
}
static const char *const invariant_names[] = {"momentum", "I"};

static gm_status prepare(void *ctx, const double *params, const char *const *texts, size_t *dim,
                         char *errmsg, size_t cap) {
  (void)ctx;
  (void)texts;
  const double n = params[0];
  if (!(n >= 1.0 && n <= DIATOMIC_MAX && n == floor(n)))
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "diatomic-chain: molecules must be an integer from 1 to %d, got %g",
                   DIATOMIC_MAX, n);
  *dim = 2 * (size_t)n;
  return GM_OK;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  (void)t0;
  chain *c = ctx;
  const size_t n = (size_t)params[0];
  if (!(params[1] > 0.0) || !(params[2] > 0.0) || !(params[3] > 0.0) || !(params[4] >= 0.0) ||
      !(params[5] >= 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "diatomic-chain: need omega, ma, mb > 0 and soft, quartic >= 0");
  c->n = n;
  c->dim = 2 * n;
  c->omega = params[1];
  c->ma = params[2];
  c->mb = params[3];
  c->soft = params[4];
  c->quartic = params[5];
  c->mu = c->ma * c->mb / (c->ma + c->mb);
  const size_t d = c->dim;
  const double w = sqrt(0.5 * c->mu) * c->omega; /* Ω block = w [[1, −1], [−1, 1]] */
  memset(c->omega_matrix, 0, sizeof c->omega_matrix);
  for (size_t i = 0; i < n; ++i) {
    const size_t a = 2 * i, b = 2 * i + 1;
    c->mass[a] = c->ma;
    c->mass[b] = c->mb;
    c->omega_matrix[a * d + a] = c->omega_matrix[b * d + b] = w;
    c->omega_matrix[a * d + b] = c->omega_matrix[b * d + a] = -w;
  }
  c->split = (gm_split_potential){slow, slow_gradient, fast, fast_gradient, NULL,
                                  c->omega_matrix, 0, c->mass};
  c->invariants[0] = (gm_invariant){"momentum", momentum};
  c->invariants[1] = (gm_invariant){"I", bond_energy};
  pb->kinetic = kinetic;
  pb->kinetic_gradient = kinetic_gradient;
  pb->kinetic_hessian = kinetic_hessian;
  pb->kinetic_is_quadratic = 1;
  pb->potential = potential;
  pb->potential_gradient = potential_gradient;
  pb->potential_hessian = potential_hessian;
  pb->split = &c->split;
  pb->n_invariants = 2;
  pb->invariants = c->invariants;
  const double stretch = 1.0 / c->omega, total = c->ma + c->mb;
  y0[0] = -stretch * c->mb / total;
  y0[1] = stretch * c->ma / total;
  y0[d] = 1.0;
  return GM_OK;
}

static const gm_param_info params[] = {
    {"molecules", 4.0, "number of molecules (1..16); 2 molecules degrees of freedom",
     GM_PARAM_NUMBER},
    {"omega", 30.0, "bond frequency", GM_PARAM_NUMBER},
    {"ma", 1.0, "mass of the first atom of each molecule", GM_PARAM_NUMBER},
    {"mb", 2.0, "mass of the second atom", GM_PARAM_NUMBER},
    {"soft", 1.0, "harmonic stiffness of the soft inter-molecular springs", GM_PARAM_NUMBER},
    {"quartic", 1.0, "quartic coefficient of the soft springs", GM_PARAM_NUMBER},
};

const gm_model_def gm_model_diatomic_chain = {
    {"diatomic-chain",
     "chain of diatomic molecules: stiff harmonic bonds W = q'Omega^2 q/2 (full Omega, masses "
     "ma, mb), soft anharmonic springs U between molecules; bond energy I",
     GM_PROBLEM_SEPARABLE, 8, 6, params, 2, invariant_names, 0},
    sizeof(chain), prepare, setup, NULL, NULL};
