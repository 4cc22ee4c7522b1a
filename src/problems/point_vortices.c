/* N point vortices in the plane (Helmholtz 1858, Kirchhoff 1876). Vortex i at (x_i, y_i) with
 * circulation Γ_i ≠ 0 moves by the velocity the others induce (Biot–Savart),
 *   dx_i/dt = −(1/2π) Σ_{j≠i} Γ_j (y_i − y_j)/r_ij²,
 *   dy_i/dt =  (1/2π) Σ_{j≠i} Γ_j (x_i − x_j)/r_ij²,
 * which is Kirchhoff's Hamiltonian form Γ_i dx_i/dt = ∂H/∂y_i, Γ_i dy_i/dt = −∂H/∂x_i with
 *   H = −(1/4π) Σ_{i≠j} Γ_i Γ_j ln r_ij = −(1/4π) Σ_{i<j} Γ_i Γ_j ln r_ij²
 * (Newton, The N-Vortex Problem, Springer 2001, Ch. 2; seed 004, "Vortex dynamic", whose formula
 * was lost and is restored in notes/003-004-mimetic-and-review.md). The structure is not the
 * canonical one; with s_i = sqrt|Γ_i| and σ_i = sign Γ_i the coordinates
 *   q_i = s_i x_i,   p_i = σ_i s_i y_i
 * are canonical (Newton 2001, Ch. 2): dq_i/dt = ∂H/∂p_i and dp_i/dt = −∂H/∂q_i reproduce the two
 * equations above (a test checks this against Biot–Savart). H is not separable in (q, p), so
 * the problem is of the general Hamiltonian kind. Derivatives: with u = (x, y), d = u_i − u_j,
 * c = −Γ_iΓ_j/(4π), a pair contributes ∂/∂u_i = 2c d/|d|², and to the Hessian the 2×2 blocks
 * ±c (2I/|d|² − 4 d dᵀ/|d|⁴); the chain rule through the diagonal scaling gives the canonical
 * ones (∂/∂q_i = ∂/∂x_i / s_i, ∂/∂p_i = ∂/∂y_i / (σ_i s_i)).
 *
 * Invariants (the momentum maps of translations and rotations, Newton 2001, Ch. 2): the linear
 * impulse Σ Γ_i x_i = Σ σ_i s_i q_i and Σ Γ_i y_i = Σ s_i p_i, and the angular impulse
 * Σ Γ_i |x_i|² = Σ σ_i (q_i² + p_i²).
 *
 * Configurations (parameter config), circulations γ (parameter gamma):
 *   0  n identical vortices on the unit circle at angles 2πk/n (n = 4: the square of seed
 *      004). It rotates rigidly with Ω = γ(n − 1)/(4π) (J. J. Thomson 1883; Newton 2001, Ch. 2),
 *      which is the exact solution.
 *   1  the square with two opposite vortices (the 2nd and 4th) turned by the angle alpha along
 *      the circle, seed 004 Fig. 8 (alpha = π/5 there): the configuration keeps its central
 *      symmetry and the motion is quasi-periodic (Aref & Pomphrey, Phys. Lett. A 78 (1980)
 *      297).
 *   2  the square with only the 2nd vortex turned by alpha: no symmetry left, chaotic for
 *      four identical vortices (seed 004; Aref & Pomphrey 1980).
 *   3  leapfrogging: two coaxial vortex pairs (+γ above, −γ below the x-axis), half-widths 1
 *      and 1/2, side by side at x = 0; the size ratio 1/2 is above the threshold
 *      (√2 − 1)² ≈ 0.172 for leapfrogging and above 1/φ² ≈ 0.382, where it is stable (Love,
 *      Proc. London Math. Soc. 25 (1894) 185; Tophøj & Aref, Phys. Fluids 25 (2013) 014107).
 */
#include <math.h>
#include <string.h>

#include "problems/internal.h"

#define MAX_VORTICES 64

typedef struct {
  size_t dim; /* number of vortices */
  double gamma[MAX_VORTICES];
  double scale[MAX_VORTICES]; /* sqrt|Γ_i| */
  double sign[MAX_VORTICES];  /* sign Γ_i */
  /* config 0: the ring's initial angles and its rotation rate, for the exact solution */
  double angle[MAX_VORTICES];
  double omega;
} vortices;

/* Physical positions (x_i, y_i) from the canonical (q_i, p_i). */
static void positions(const vortices *v, const double *q, const double *p, double *x, double *y) {
  for (size_t i = 0; i < v->dim; ++i) {
    x[i] = q[i] / v->scale[i];
    y[i] = p[i] / (v->sign[i] * v->scale[i]);
  }
}

static double hamiltonian(void *ctx, const double *q, const double *p) {
  const vortices *v = ctx;
  double x[MAX_VORTICES], y[MAX_VORTICES], h = 0.0;
  positions(v, q, p, x, y);
  for (size_t i = 0; i < v->dim; ++i)
    for (size_t j = i + 1; j < v->dim; ++j) {
      double dx = x[i] - x[j], dy = y[i] - y[j];
      h += v->gamma[i] * v->gamma[j] * log(dx * dx + dy * dy);
    }
  return -h / (4.0 * GM_PI);
}

/* ∂H/∂x_i and ∂H/∂y_i; 1 when two vortices coincide. */
static int physical_gradient(const vortices *v, const double *q, const double *p, double *hx,
                             double *hy) {
  double x[MAX_VORTICES], y[MAX_VORTICES];
  positions(v, q, p, x, y);
  for (size_t i = 0; i < v->dim; ++i) hx[i] = hy[i] = 0.0;
  for (size_t i = 0; i < v->dim; ++i)
    for (size_t j = i + 1; j < v->dim; ++j) {
      double dx = x[i] - x[j], dy = y[i] - y[j], r2 = dx * dx + dy * dy;
      if (r2 == 0.0) return 1;
      double c = -v->gamma[i] * v->gamma[j] / (4.0 * GM_PI) * 2.0 / r2;
      hx[i] += c * dx;
      hy[i] += c * dy;
      hx[j] -= c * dx;
      hy[j] -= c * dy;
    }
  return 0;
}

static int dh_dq(void *ctx, const double *q, const double *p, double *out) {
  const vortices *v = ctx;
  double hx[MAX_VORTICES], hy[MAX_VORTICES];
  if (physical_gradient(v, q, p, hx, hy) != 0) return 1;
  for (size_t i = 0; i < v->dim; ++i) out[i] = hx[i] / v->scale[i];
  return 0;
}

static int dh_dp(void *ctx, const double *q, const double *p, double *out) {
  const vortices *v = ctx;
  double hx[MAX_VORTICES], hy[MAX_VORTICES];
  if (physical_gradient(v, q, p, hx, hy) != 0) return 1;
  for (size_t i = 0; i < v->dim; ++i) out[i] = hy[i] / (v->sign[i] * v->scale[i]);
  return 0;
}

/* Hessian in (q, p), 2N×2N: the Hessian in (x, y) scaled by the chain-rule factors. */
static int hamiltonian_hessian(void *ctx, const double *q, const double *p, double *hessian) {
  const vortices *v = ctx;
  const size_t n = v->dim, m = 2 * n;
  double x[MAX_VORTICES], y[MAX_VORTICES], factor[2 * MAX_VORTICES];
  positions(v, q, p, x, y);
  memset(hessian, 0, m * m * sizeof *hessian);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      double d[2] = {x[i] - x[j], y[i] - y[j]}, r2 = d[0] * d[0] + d[1] * d[1];
      if (r2 == 0.0) return 1;
      double c = -v->gamma[i] * v->gamma[j] / (4.0 * GM_PI);
      for (size_t a = 0; a < 2; ++a)
        for (size_t b = 0; b < 2; ++b) {
          double block = c * ((a == b ? 2.0 : 0.0) / r2 - 4.0 * d[a] * d[b] / (r2 * r2));
          /* variable a of vortex i sits at a·n + i (x block, then y block) */
          hessian[(a * n + i) * m + b * n + i] += block;
          hessian[(a * n + j) * m + b * n + j] += block;
          hessian[(a * n + i) * m + b * n + j] -= block;
          hessian[(a * n + j) * m + b * n + i] -= block;
        }
    }
  for (size_t i = 0; i < n; ++i) {
    factor[i] = 1.0 / v->scale[i];
    factor[n + i] = 1.0 / (v->sign[i] * v->scale[i]);
  }
  for (size_t a = 0; a < m; ++a)
    for (size_t b = 0; b < m; ++b) hessian[a * m + b] *= factor[a] * factor[b];
  return 0;
}

static double impulse_x(void *ctx, const double *y) {
  const vortices *v = ctx;
  double s = 0.0;
  for (size_t i = 0; i < v->dim; ++i) s += v->sign[i] * v->scale[i] * y[i];
  return s;
}

static double impulse_y(void *ctx, const double *y) {
  const vortices *v = ctx;
  double s = 0.0;
  for (size_t i = 0; i < v->dim; ++i) s += v->scale[i] * y[v->dim + i];
  return s;
}

static double angular_impulse(void *ctx, const double *y) {
  const vortices *v = ctx;
  double s = 0.0;
  for (size_t i = 0; i < v->dim; ++i) {
    double qi = y[i], pi = y[v->dim + i];
    s += v->sign[i] * (qi * qi + pi * pi);
  }
  return s;
}

static const gm_invariant invariants[] = {
    {"impulse-x", impulse_x}, {"impulse-y", impulse_y}, {"angular-impulse", angular_impulse}};
static const char *const invariant_names[] = {"impulse-x", "impulse-y", "angular-impulse"};

/* The ring turns rigidly: angle_k + Ω t on the unit circle. */
static int exact(void *ctx, double t, double *y) {
  const vortices *v = ctx;
  for (size_t i = 0; i < v->dim; ++i) {
    double a = v->angle[i] + v->omega * t;
    y[i] = v->scale[i] * cos(a);
    y[v->dim + i] = v->sign[i] * v->scale[i] * sin(a);
  }
  return 0;
}

static int initial_changed(void *ctx, const double *y0) {
  (void)ctx;
  (void)y0;
  return 0; /* the rigid rotation assumes the regular polygon */
}

enum { CONFIG_RING, CONFIG_PAIR_TURNED, CONFIG_ONE_TURNED, CONFIG_LEAPFROG, N_CONFIGS };

static gm_status prepare(void *ctx, const double *params, const char *const *texts, size_t *dim,
                         char *errmsg, size_t cap) {
  (void)ctx;
  (void)texts;
  const double config = params[0], n = params[1];
  if (!(config >= 0.0 && config < N_CONFIGS && config == floor(config)))
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "point-vortices: config must be 0 (ring), 1 (square, two opposite vortices "
                   "turned), 2 (square, one turned) or 3 (leapfrogging pairs), got %g",
                   config);
  if (!(n >= 2.0 && n <= MAX_VORTICES && n == floor(n)))
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "point-vortices: n must be an integer from 2 to %d, got %g", MAX_VORTICES, n);
  if (config != CONFIG_RING && n != 4.0)
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "point-vortices: config %g has 4 vortices; n = %g applies to config 0 (the "
                   "ring) only",
                   config, n);
  *dim = (size_t)n;
  return GM_OK;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  (void)t0;
  vortices *v = ctx;
  const int config = (int)params[0];
  const size_t n = pb->dim;
  const double alpha = params[2], gamma = params[3];
  if (!(gamma != 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL, "point-vortices: gamma must not be 0");
  v->dim = n;
  double x[MAX_VORTICES], y[MAX_VORTICES];
  for (size_t i = 0; i < n; ++i) {
    v->gamma[i] = gamma;
    v->angle[i] = 2.0 * GM_PI * (double)i / (double)n;
  }
  switch (config) {
    case CONFIG_PAIR_TURNED:
      v->angle[1] += alpha;
      v->angle[3] += alpha;
      break;
    case CONFIG_ONE_TURNED:
      v->angle[1] += alpha;
      break;
    default:
      break;
  }
  for (size_t i = 0; i < n; ++i) {
    x[i] = cos(v->angle[i]);
    y[i] = sin(v->angle[i]);
  }
  if (config == CONFIG_LEAPFROG) {
    static const double half_width[4] = {1.0, -1.0, 0.5, -0.5};
    for (size_t i = 0; i < 4; ++i) {
      v->gamma[i] = half_width[i] > 0.0 ? gamma : -gamma;
      x[i] = 0.0;
      y[i] = half_width[i];
    }
  }
  for (size_t i = 0; i < n; ++i) {
    v->scale[i] = sqrt(fabs(v->gamma[i]));
    v->sign[i] = v->gamma[i] > 0.0 ? 1.0 : -1.0;
    y0[i] = v->scale[i] * x[i];
    y0[n + i] = v->sign[i] * v->scale[i] * y[i];
  }
  v->omega = gamma * (double)(n - 1) / (4.0 * GM_PI);
  pb->hamiltonian = hamiltonian;
  pb->dh_dq = dh_dq;
  pb->dh_dp = dh_dp;
  pb->hamiltonian_hessian = hamiltonian_hessian;
  pb->n_invariants = 3;
  pb->invariants = invariants;
  if (config == CONFIG_RING) pb->exact = exact;
  return GM_OK;
}

static const gm_param_info params[] = {
    {"config", 0.0,
     "0 ring of n (square), 1 square with two opposite turned by alpha, 2 one turned, "
     "3 leapfrogging pairs",
     GM_PARAM_NUMBER},
    {"n", 4.0, "number of vortices of the ring (config 0), 2..64", GM_PARAM_NUMBER},
    {"alpha", GM_PI / 5.0, "angle the vortices of configs 1 and 2 are turned by", GM_PARAM_NUMBER},
    {"gamma", 1.0, "circulation of each vortex (leapfrog: +gamma and -gamma)", GM_PARAM_NUMBER}};

const gm_model_def gm_model_point_vortices = {
    {"point-vortices",
     "point vortices in the plane, Kirchhoff's H = -(1/4pi) sum_(i!=j) G_i G_j ln r_ij (not "
     "separable); default: the rotating square of 4",
     GM_PROBLEM_HAMILTONIAN, 4, 4, params, 3, invariant_names, 1},
    sizeof(vortices), prepare, setup, initial_changed, NULL};
