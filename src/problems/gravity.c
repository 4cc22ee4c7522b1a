/* Newtonian gravity of N point masses in 3-D, shared by outer-solar-system and n-body:
 *   T(p) = Σ_i |p_i|²/(2 m_i),   V(q) = −G Σ_{i<j} m_i m_j / sqrt(|q_i − q_j|² + ε²)
 * (ε = 0: Newton's law; ε > 0: Plummer softening, Aarseth, MNRAS 126 (1963) 223). With
 * d = q_i − q_j, s = |d|² + ε² and f = G m_i m_j:
 *   ∂V/∂q_i = f d / s^{3/2}                 (and −f d / s^{3/2} for q_j),
 *   ∂²V/∂q_i² = f (I/s^{3/2} − 3 d dᵀ/s^{5/2}) = B,   ∂²V/∂q_i∂q_j = −B   (per pair).
 * The momentum maps of translations and rotations, P = Σ p_i and L = Σ q_i × p_i, are conserved
 * (Noether; Hairer, Lubich & Wanner, GNI (2006), §IV.1). */
#include <string.h>

#include "problems/internal.h"

static double kinetic(void *ctx, const double *p) {
  const gm_gravity *g = ctx;
  double t = 0.0;
  for (size_t i = 0; i < g->n_bodies; ++i) {
    const double *pi = p + 3 * i;
    t += (pi[0] * pi[0] + pi[1] * pi[1] + pi[2] * pi[2]) / (2.0 * g->mass[i]);
  }
  return t;
}

static int kinetic_gradient(void *ctx, const double *p, double *out) {
  const gm_gravity *g = ctx;
  for (size_t i = 0; i < g->n_bodies; ++i)
    for (size_t k = 0; k < 3; ++k) out[3 * i + k] = p[3 * i + k] / g->mass[i];
  return 0;
}

static int kinetic_hessian(void *ctx, const double *p, double *hessian) {
  (void)p;
  const gm_gravity *g = ctx;
  const size_t d = g->dim;
  memset(hessian, 0, d * d * sizeof *hessian);
  for (size_t i = 0; i < d; ++i) hessian[i * d + i] = 1.0 / g->mass[i / 3];
  return 0;
}

/* A collision without softening makes V infinite: −inf, which the driver reports. */
static double potential(void *ctx, const double *q) {
  const gm_gravity *g = ctx;
  double v = 0.0;
  for (size_t i = 0; i < g->n_bodies; ++i) {
    const double *qi = q + 3 * i;
    double vi = 0.0;
    for (size_t j = i + 1; j < g->n_bodies; ++j) {
      const double *qj = q + 3 * j;
      double dx = qi[0] - qj[0], dy = qi[1] - qj[1], dz = qi[2] - qj[2];
      vi += g->mass[j] / sqrt(dx * dx + dy * dy + dz * dz + g->softening2);
    }
    v += g->mass[i] * vi;
  }
  return -g->G * v;
}

static int potential_gradient(void *ctx, const double *q, double *out) {
  const gm_gravity *g = ctx;
  memset(out, 0, g->dim * sizeof *out);
  for (size_t i = 0; i < g->n_bodies; ++i) {
    const double *qi = q + 3 * i;
    double *gi = out + 3 * i;
    const double gmi = g->G * g->mass[i];
    for (size_t j = i + 1; j < g->n_bodies; ++j) {
      const double *qj = q + 3 * j;
      double *gj = out + 3 * j;
      double dx = qi[0] - qj[0], dy = qi[1] - qj[1], dz = qi[2] - qj[2];
      double s = dx * dx + dy * dy + dz * dz + g->softening2;
      if (s == 0.0) return 1;
      double f = gmi * g->mass[j] / (s * sqrt(s));
      gi[0] += f * dx;
      gi[1] += f * dy;
      gi[2] += f * dz;
      gj[0] -= f * dx;
      gj[1] -= f * dy;
      gj[2] -= f * dz;
    }
  }
  return 0;
}

static int potential_hessian(void *ctx, const double *q, double *hessian) {
  const gm_gravity *g = ctx;
  const size_t d = g->dim;
  memset(hessian, 0, d * d * sizeof *hessian);
  for (size_t i = 0; i < g->n_bodies; ++i)
    for (size_t j = i + 1; j < g->n_bodies; ++j) {
      double dv[3];
      for (size_t k = 0; k < 3; ++k) dv[k] = q[3 * i + k] - q[3 * j + k];
      double s = dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2] + g->softening2;
      if (s == 0.0) return 1;
      double f = g->G * g->mass[i] * g->mass[j], s32 = s * sqrt(s);
      for (size_t a = 0; a < 3; ++a)
        for (size_t b = 0; b < 3; ++b) {
          double block = f * ((a == b ? 1.0 : 0.0) / s32 - 3.0 * dv[a] * dv[b] / (s32 * s));
          hessian[(3 * i + a) * d + 3 * i + b] += block;
          hessian[(3 * j + a) * d + 3 * j + b] += block;
          hessian[(3 * i + a) * d + 3 * j + b] -= block;
          hessian[(3 * j + a) * d + 3 * i + b] -= block;
        }
    }
  return 0;
}

/* Component k of the total linear momentum Σ p_i. */
static double momentum(const void *ctx, const double *y, size_t k) {
  const gm_gravity *g = ctx;
  const double *p = y + g->dim;
  double s = 0.0;
  for (size_t i = 0; i < g->n_bodies; ++i) s += p[3 * i + k];
  return s;
}

/* Component k of the total angular momentum Σ q_i × p_i. */
static double angular_momentum(const void *ctx, const double *y, size_t k) {
  const gm_gravity *g = ctx;
  const double *q = y, *p = y + g->dim;
  const size_t a = (k + 1) % 3, b = (k + 2) % 3;
  double s = 0.0;
  for (size_t i = 0; i < g->n_bodies; ++i)
    s += q[3 * i + a] * p[3 * i + b] - q[3 * i + b] * p[3 * i + a];
  return s;
}

static double momentum_x(void *ctx, const double *y) { return momentum(ctx, y, 0); }
static double momentum_y(void *ctx, const double *y) { return momentum(ctx, y, 1); }
static double momentum_z(void *ctx, const double *y) { return momentum(ctx, y, 2); }
static double angular_momentum_x(void *ctx, const double *y) { return angular_momentum(ctx, y, 0); }
static double angular_momentum_y(void *ctx, const double *y) { return angular_momentum(ctx, y, 1); }
static double angular_momentum_z(void *ctx, const double *y) { return angular_momentum(ctx, y, 2); }

const char *const gm_gravity_invariant_names[GM_GRAVITY_N_INVARIANTS] = {
    "momentum-x",         "momentum-y",         "momentum-z",
    "angular-momentum-x", "angular-momentum-y", "angular-momentum-z"};

static const gm_invariant invariants[GM_GRAVITY_N_INVARIANTS] = {
    {"momentum-x", momentum_x},
    {"momentum-y", momentum_y},
    {"momentum-z", momentum_z},
    {"angular-momentum-x", angular_momentum_x},
    {"angular-momentum-y", angular_momentum_y},
    {"angular-momentum-z", angular_momentum_z}};

void gm_gravity_setup(gm_problem *pb) {
  pb->kinetic = kinetic;
  pb->kinetic_gradient = kinetic_gradient;
  pb->kinetic_hessian = kinetic_hessian;
  pb->kinetic_is_quadratic = 1; /* T = ½ pᵀM⁻¹p, M = diag(m_i) */
  pb->potential = potential;
  pb->potential_gradient = potential_gradient;
  pb->potential_hessian = potential_hessian;
  pb->n_invariants = GM_GRAVITY_N_INVARIANTS;
  pb->invariants = invariants;
}
