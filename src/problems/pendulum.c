/* Mathematical pendulum H = ½p² − k cos q (k = g/l). Seed 003 §6.3 uses k = 10, q = π/2.
 * Released at rest from |q₀| < π it swings with sin(q/2) = κ sn(K − √k t; κ), κ = sin(q₀/2):
 * the exact solution below (Lawden, Elliptic Functions and Applications (1989), §5.2). */
#include <math.h>

#include "problems/internal.h"

typedef struct {
  size_t dim;
  double k;
  double q0; /* released at rest from q0 */
} pendulum;

/* Jacobi elliptic functions sn, cn, dn of (u, modulus m) by the arithmetic–geometric mean
 * (Abramowitz & Stegun (1964), 16.4.1–16.4.4), 0 <= m < 1. */
static void jacobi_sn_cn_dn(double u, double m, double *sn, double *cn, double *dn) {
  enum { MAX_TERMS = 32 };
  double a[MAX_TERMS], c[MAX_TERMS];
  double b = sqrt(1.0 - m * m);
  a[0] = 1.0;
  c[0] = m;
  size_t n = 0;
  while (fabs(c[n]) > 1e-17 * a[n] && n + 1 < MAX_TERMS) {
    a[n + 1] = 0.5 * (a[n] + b);
    c[n + 1] = 0.5 * (a[n] - b);
    b = sqrt(a[n] * b);
    ++n;
  }
  double phi = ldexp(a[n] * u, (int)n), phi_next = phi;
  for (size_t j = n; j > 0; --j) {
    phi_next = phi;
    phi = 0.5 * (phi + asin(c[j] / a[j] * sin(phi)));
  }
  *sn = sin(phi);
  *cn = cos(phi);
  *dn = n > 0 ? cos(phi) / cos(phi_next - phi) : 1.0;
}

/* Complete elliptic integral K(m) = π / (2 AGM(1, √(1−m²))) (A&S 17.6). */
static double elliptic_k(double m) {
  double a = 1.0, b = sqrt(1.0 - m * m);
  for (int i = 0; i < 40 && fabs(a - b) > 1e-17 * a; ++i) {
    double an = 0.5 * (a + b);
    b = sqrt(a * b);
    a = an;
  }
  return 0.5 * GM_PI / a;
}

/* From rest at q0: sin(q/2) = κ sn(K − ωt), with ω = √k, κ = sin(q0/2); differentiating,
 * ½ cos(q/2) q' = −κω cn dn, and cos(q/2) = dn, so p = q' = −2κω cn(K − ωt). */
static int exact(void *ctx, double t, double *y) {
  const pendulum *pd = ctx;
  const double kappa = sin(0.5 * pd->q0), omega = sqrt(pd->k);
  double sn, cn, dn;
  jacobi_sn_cn_dn(elliptic_k(fabs(kappa)) - omega * t, fabs(kappa), &sn, &cn, &dn);
  y[0] = 2.0 * asin(kappa * sn);
  y[1] = -2.0 * kappa * omega * cn;
  return 0;
}

static int initial_changed(void *ctx, const double *y0) {
  pendulum *pd = ctx;
  pd->q0 = y0[0];
  return y0[1] == 0.0 && fabs(y0[0]) < GM_PI; /* released at rest, swinging */
}

static double potential(void *ctx, const double *q) {
  return -((const pendulum *)ctx)->k * cos(q[0]);
}

static int potential_gradient(void *ctx, const double *q, double *out) {
  out[0] = ((const pendulum *)ctx)->k * sin(q[0]);
  return 0;
}

static int potential_hessian(void *ctx, const double *q, double *out) {
  out[0] = ((const pendulum *)ctx)->k * cos(q[0]);
  return 0;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  pendulum *pd = ctx;
  (void)t0;
  if (!(params[0] > 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL, "pendulum: k must be positive, got %g", params[0]);
  *pd = (pendulum){1, params[0], 0.5 * GM_PI};
  gm_free_kinetic_setup(pb);
  pb->potential = potential;
  pb->potential_gradient = potential_gradient;
  pb->potential_hessian = potential_hessian;
  pb->exact = exact;
  y0[0] = pd->q0; /* released from horizontal: far from the linear regime */
  y0[1] = 0.0;
  return GM_OK;
}

static const gm_param_info params[] = {{"k", 1.0, "g/l: H = p^2/2 - k cos q", GM_PARAM_NUMBER}};

const gm_model_def gm_model_pendulum = {
    {"pendulum", "mathematical pendulum H = p^2/2 - k cos q, q = pi/2, p = 0",
     GM_PROBLEM_SEPARABLE, 1, 1, params, 0, NULL, 1},
    sizeof(pendulum), NULL, setup, initial_changed, NULL};
