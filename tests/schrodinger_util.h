/* Shared setup of the Schrödinger tests: potentials, eigenstates, the coherent state. */
#ifndef GM_TEST_SCHRODINGER_UTIL_H
#define GM_TEST_SCHRODINGER_UTIL_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "geomint/geomint.h"

#define SCH_PI 3.14159265358979323846

/* Harmonic V = x²/2: eigenstates φ_k = (2^k k!)^{-1/2} π^{-1/4} H_k(x) e^{-x²/2}, E_k = k + ½.
 * Pöschl–Teller V = −3 sech²x (λ = 2): φ0 = √(3/4) sech²x (E = −2), φ1 = √(3/2) tanh x sech x
 * (E = −½). */
typedef enum { SCH_HARMONIC, SCH_POSCHL_TELLER } sch_potential;

static inline double sch_V(sch_potential p, double x) {
  return p == SCH_HARMONIC ? 0.5 * x * x : -3.0 / (cosh(x) * cosh(x));
}

static inline double sch_phi(sch_potential p, int k, double x) {
  if (p == SCH_POSCHL_TELLER)
    return k == 0 ? sqrt(0.75) / (cosh(x) * cosh(x)) : sqrt(1.5) * tanh(x) / cosh(x);
  double h0 = 1.0, h1 = 2.0 * x, hk = k == 0 ? h0 : h1, f = 1.0;
  for (int j = 2; j <= k; j++) {
    hk = 2.0 * x * h1 - 2.0 * (j - 1) * h0;
    h0 = h1;
    h1 = hk;
  }
  for (int j = 1; j <= k; j++) f *= 2.0 * j;
  return hk / sqrt(f) * pow(SCH_PI, -0.25) * exp(-0.5 * x * x);
}

static inline double sch_E(sch_potential p, int k) {
  return p == SCH_HARMONIC ? k + 0.5 : (k == 0 ? -2.0 : -0.5);
}

/* Grids x_j = −length/2 + j·length/n: V and φ_k (complex, interleaved); owned. */
static inline double *sch_grid_V(sch_potential p, size_t n, double length) {
  double *V = malloc(n * sizeof *V);
  cr_assert_not_null(V);
  for (size_t j = 0; j < n; j++) V[j] = sch_V(p, -0.5 * length + (double)j * length / (double)n);
  return V;
}
static inline double *sch_grid_phi(sch_potential p, int k, size_t n, double length) {
  double *f = calloc(2 * n, sizeof *f);
  cr_assert_not_null(f);
  for (size_t j = 0; j < n; j++)
    f[2 * j] = sch_phi(p, k, -0.5 * length + (double)j * length / (double)n);
  return f;
}

/* Coherent state of V = x²/2 (q = a cos t, p = −a sin t), derived by substitution:
 * ψ = π^{-1/4} exp(−(x − q)²/2 + i p x + i(−t/2 + (a²/4) sin 2t)). */
static inline void sch_coherent(double a, double x, double t, double *re, double *im) {
  double q = a * cos(t), p = -a * sin(t);
  double mod = pow(SCH_PI, -0.25) * exp(-0.5 * (x - q) * (x - q));
  double ph = p * x - 0.5 * t + 0.25 * a * a * sin(2.0 * t);
  *re = mod * cos(ph);
  *im = mod * sin(ph);
}

#endif
