/* The energy of a Lagrangian problem in position–momentum form:
 *   E(q, p) = p·v − L(q, v)  with v solving the Legendre transform ∂L/∂v(q, v) = p,
 * found by Newton's method on v with ∂²L/∂v² (analytic from lagrangian_hessian, else central
 * differences of ∂L/∂v). Used by monitors and the CLI, never inside a step. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ode/internal.h"

/* ∂²L/∂v² (d×d) into w, from the analytic Hessian's (v, v) block or by differences. */
static int velocity_hessian(const gm_problem *pb, const double *q, double *v, double *w,
                            double *full, double *gp, double *gm) {
  const size_t d = pb->dim;
  if (pb->lagrangian_hessian != NULL) {
    if (pb->lagrangian_hessian(pb->ctx, q, v, full) != 0) return 1;
    for (size_t i = 0; i < d; ++i)
      for (size_t j = 0; j < d; ++j) w[i * d + j] = full[(d + i) * 2 * d + d + j];
    return 0;
  }
  for (size_t j = 0; j < d; ++j) {
    const double vj = v[j], h = 6.0554544523933395e-06 * fmax(1.0, fabs(vj));
    v[j] = vj + h;
    if (pb->dl_dv(pb->ctx, q, v, gp) != 0) return 1;
    v[j] = vj - h;
    if (pb->dl_dv(pb->ctx, q, v, gm) != 0) return 1;
    v[j] = vj;
    for (size_t i = 0; i < d; ++i) w[i * d + j] = (gp[i] - gm[i]) / (2.0 * h);
  }
  return 0;
}

double gm_lagrangian_energy(const gm_problem *pb, const double *y) {
  const size_t d = pb->dim;
  const double *q = y, *p = y + d;
  double *buf = malloc((4 * d + d * d + 4 * d * d + 2) * sizeof *buf);
  int *pivots = malloc(d * sizeof *pivots);
  if (buf == NULL || pivots == NULL) {
    free(buf);
    free(pivots);
    return NAN;
  }
  double *v = buf, *r = v + d, *gp = r + d, *gm = gp + d, *w = gm + d, *full = w + d * d;
  memcpy(v, p, d * sizeof *v); /* starting guess: unit mass */
  double energy = NAN;
  int converged = 0;
  for (int iter = 0; iter < 50 && !converged; ++iter) {
    if (pb->dl_dv(pb->ctx, q, v, r) != 0) break;
    double res = 0.0, scale = 1.0;
    for (size_t i = 0; i < d; ++i) {
      r[i] -= p[i];
      res = fmax(res, fabs(r[i]));
      scale = fmax(scale, fabs(p[i]));
    }
    if (res <= 4.0 * 2.220446049250313e-16 * scale) {
      converged = 1;
      break;
    }
    if (velocity_hessian(pb, q, v, w, full, gp, gm) != 0 || gm_lu_factor(d, w, pivots) != GM_OK ||
        gm_lu_solve(d, w, pivots, r) != GM_OK)
      break;
    double step = 0.0, size = 1.0;
    for (size_t i = 0; i < d; ++i) {
      v[i] -= r[i];
      step = fmax(step, fabs(r[i]));
      size = fmax(size, fabs(v[i]));
    }
    converged = step <= 1e-15 * size; /* a Newton step at round-off: quadratic convergence */
  }
  if (converged) {
    double pv = 0.0;
    for (size_t i = 0; i < d; ++i) pv += p[i] * v[i];
    energy = pv - pb->lagrangian(pb->ctx, q, v);
  }
  free(buf);
  free(pivots);
  return energy;
}
