/* Split potentials V = U + W (seed 000 §2.2.1): validation, and the fast quadratic part
 * W = ½ qᵀΩ²q in the eigenbasis of the mass-weighted stiffness K = M^{−1/2} Ω² M^{−1/2},
 * computed once when an integrator is created (LAPACK dsyev through gm_symmetric_eigen). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "methods/oscillatory/oscillatory.h"

double gm_sinc(double xi) {
  const double x2 = xi * xi;
  if (x2 < 1e-8) return 1.0 - x2 / 6.0 * (1.0 - x2 / 20.0); /* error < x⁶/5040 */
  return sin(xi) / xi;
}

/* Is Ω symmetric and positive semidefinite? Writes the message when not. */
static gm_status check_omega(const gm_split_potential *s, size_t d, gm_error *err) {
  if (s->omega_is_diagonal) {
    for (size_t i = 0; i < d; ++i)
      if (!(s->omega[i] >= 0.0) || !isfinite(s->omega[i]))
        return gm_error_set(err, GM_EINVAL,
                            "split potential: the diagonal Omega must be finite and >= 0 "
                            "(positive semidefinite), entry %zu is %g",
                            i + 1, s->omega[i]);
    return GM_OK;
  }
  double scale = 0.0;
  for (size_t i = 0; i < d * d; ++i) {
    if (!isfinite(s->omega[i]))
      return gm_error_set(err, GM_EINVAL, "split potential: Omega entry (%zu, %zu) is %g",
                          i / d + 1, i % d + 1, s->omega[i]);
    scale = fmax(scale, fabs(s->omega[i]));
  }
  for (size_t i = 0; i < d; ++i)
    for (size_t j = i + 1; j < d; ++j)
      if (fabs(s->omega[i * d + j] - s->omega[j * d + i]) > 1e-12 * scale)
        return gm_error_set(err, GM_EINVAL,
                            "split potential: Omega is not symmetric: entry (%zu, %zu) = %.17g "
                            "but (%zu, %zu) = %.17g",
                            i + 1, j + 1, s->omega[i * d + j], j + 1, i + 1, s->omega[j * d + i]);
  double *a = malloc(d * d * sizeof *a), *lambda = malloc(d * sizeof *lambda);
  gm_status st = (a && lambda) ? GM_OK : GM_ENOMEM;
  if (st == GM_OK) {
    memcpy(a, s->omega, d * d * sizeof *a);
    st = gm_symmetric_eigen(d, a, lambda);
    if (st != GM_OK) gm_error_set(err, st, "split potential: eigendecomposition of Omega failed");
    else if (lambda[0] < -1e-12 * fmax(scale, fabs(lambda[d - 1])))
      st = gm_error_set(err, GM_EINVAL,
                        "split potential: Omega is not positive semidefinite: its smallest "
                        "eigenvalue is %.6g",
                        lambda[0]);
  }
  free(a);
  free(lambda);
  return st;
}

gm_status gm_split_potential_validate(const gm_problem *pb, gm_error *err) {
  if (pb == NULL) return gm_error_set(err, GM_EINVAL, "problem is NULL");
  const gm_split_potential *s = pb->split;
  if (s == NULL)
    return gm_error_set(err, GM_EUNSUPPORTED,
                        "the problem has no split potential V = U + W (gm_problem.split)");
  if (pb->kind != GM_PROBLEM_SEPARABLE || !pb->kinetic_is_quadratic)
    return gm_error_set(err, GM_EINVAL,
                        "split potential: the problem must be separable with T = ½ pᵀM⁻¹p");
  if (s->slow == NULL || s->slow_gradient == NULL)
    return gm_error_set(err, GM_EINVAL, "split potential: the slow part U or its gradient is "
                                        "missing");
  if (s->omega == NULL && (s->fast == NULL || s->fast_gradient == NULL))
    return gm_error_set(err, GM_EINVAL, "split potential: the fast part W needs its callbacks "
                                        "or a quadratic Omega");
  const size_t d = pb->dim;
  if (s->mass != NULL)
    for (size_t i = 0; i < d; ++i)
      if (!(s->mass[i] > 0.0) || !isfinite(s->mass[i]))
        return gm_error_set(err, GM_EINVAL, "split potential: mass %zu is %g, must be > 0",
                            i + 1, s->mass[i]);
  /* T = ½ pᵀM⁻¹p: ∇T(e) = M⁻¹e for e = (1, 2, ..., d) */
  double *e = malloc(d * sizeof *e), *g = malloc(d * sizeof *g);
  gm_status st = (e && g) ? GM_OK : GM_ENOMEM;
  for (size_t i = 0; st == GM_OK && i < d; ++i) e[i] = (double)(i + 1);
  if (st == GM_OK && pb->kinetic_gradient(pb->ctx, e, g) != 0)
    st = gm_error_set(err, GM_ECALLBACK, "split potential: kinetic_gradient failed");
  for (size_t i = 0; st == GM_OK && i < d; ++i) {
    double m = s->mass ? s->mass[i] : 1.0;
    if (fabs(g[i] * m - e[i]) > 1e-12 * e[i])
      st = gm_error_set(err, GM_EINVAL,
                        "split potential: the kinetic energy is not ½ pᵀM⁻¹p with the split's "
                        "mass (component %zu: dT/dp = %g, expected %g)",
                        i + 1, g[i], e[i] / m);
  }
  free(e);
  free(g);
  if (st != GM_OK) return st;
  return s->omega != NULL ? check_omega(s, d, err) : GM_OK;
}

void gm_osc_fast_release(gm_osc_fast *f) {
  free(f->msqrt);
  free(f->nu);
  free(f->basis);
  free(f->omega2);
  free(f->tmp);
  memset(f, 0, sizeof *f);
}

gm_status gm_osc_fast_create(const gm_problem *pb, gm_osc_fast *f, char *errmsg, size_t cap) {
  memset(f, 0, sizeof *f);
  gm_error err = {{0}};
  gm_status st = gm_split_potential_validate(pb, &err);
  if (st != GM_OK) return gm_fail(errmsg, cap, st, "%s", err.message);
  const gm_split_potential *s = pb->split;
  const size_t d = pb->dim;
  f->d = d;
  f->msqrt = malloc(d * sizeof *f->msqrt);
  f->tmp = malloc(d * sizeof *f->tmp);
  f->nu = calloc(d, sizeof *f->nu);
  if (!f->msqrt || !f->tmp || !f->nu) return GM_ENOMEM;
  for (size_t i = 0; i < d; ++i) f->msqrt[i] = s->mass ? sqrt(s->mass[i]) : 1.0;
  if (s->omega == NULL) return GM_OK;
  f->quadratic = 1;
  if (s->omega_is_diagonal) {
    f->omega2_diagonal = 1;
    f->omega2 = malloc(d * sizeof *f->omega2);
    if (!f->omega2) return GM_ENOMEM;
    for (size_t i = 0; i < d; ++i) {
      f->omega2[i] = s->omega[i] * s->omega[i];
      f->nu[i] = s->omega[i] / f->msqrt[i];
    }
    return GM_OK;
  }
  f->omega2 = calloc(d * d, sizeof *f->omega2);
  f->basis = malloc(d * d * sizeof *f->basis);
  if (!f->omega2 || !f->basis) return GM_ENOMEM;
  for (size_t i = 0; i < d; ++i)
    for (size_t k = 0; k < d; ++k) {
      const double a = s->omega[i * d + k];
      for (size_t j = 0; j < d; ++j) f->omega2[i * d + j] += a * s->omega[k * d + j];
    }
  for (size_t i = 0; i < d; ++i)
    for (size_t j = 0; j < d; ++j)
      f->basis[i * d + j] = f->omega2[i * d + j] / (f->msqrt[i] * f->msqrt[j]);
  st = gm_symmetric_eigen(d, f->basis, f->nu);
  if (st != GM_OK)
    return gm_fail(errmsg, cap, st, "eigendecomposition of M^-1/2 Omega^2 M^-1/2 failed");
  for (size_t k = 0; k < d; ++k) f->nu[k] = sqrt(fmax(f->nu[k], 0.0)); /* λ = ν² ≥ −round-off */
  return GM_OK;
}

/* out = Qᵀ in (or a copy without a basis) */
static void basis_transpose_apply(const gm_osc_fast *f, const double *in, double *out) {
  const size_t d = f->d;
  if (f->basis == NULL) {
    if (out != in) memcpy(out, in, d * sizeof *out);
    return;
  }
  for (size_t k = 0; k < d; ++k) {
    double s = 0.0;
    for (size_t i = 0; i < d; ++i) s += f->basis[i * d + k] * in[i];
    out[k] = s;
  }
}

/* out = Q in */
static void basis_apply(const gm_osc_fast *f, const double *in, double *out) {
  const size_t d = f->d;
  if (f->basis == NULL) {
    if (out != in) memcpy(out, in, d * sizeof *out);
    return;
  }
  for (size_t i = 0; i < d; ++i) {
    double s = 0.0;
    for (size_t k = 0; k < d; ++k) s += f->basis[i * d + k] * in[k];
    out[i] = s;
  }
}

void gm_osc_to_modal_position(const gm_osc_fast *f, const double *q, double *z) {
  for (size_t i = 0; i < f->d; ++i) f->tmp[i] = f->msqrt[i] * q[i];
  basis_transpose_apply(f, f->tmp, z);
}

void gm_osc_to_modal_momentum(const gm_osc_fast *f, const double *p, double *w) {
  for (size_t i = 0; i < f->d; ++i) f->tmp[i] = p[i] / f->msqrt[i];
  basis_transpose_apply(f, f->tmp, w);
}

void gm_osc_from_modal_position(const gm_osc_fast *f, const double *z, double *q) {
  basis_apply(f, z, f->tmp);
  for (size_t i = 0; i < f->d; ++i) q[i] = f->tmp[i] / f->msqrt[i];
}

void gm_osc_from_modal_momentum(const gm_osc_fast *f, const double *w, double *p) {
  basis_apply(f, w, f->tmp);
  for (size_t i = 0; i < f->d; ++i) p[i] = f->tmp[i] * f->msqrt[i];
}

void gm_osc_omega2_apply(const gm_osc_fast *f, const double *q, double *out) {
  const size_t d = f->d;
  if (f->omega2_diagonal) {
    for (size_t i = 0; i < d; ++i) out[i] = f->omega2[i] * q[i];
    return;
  }
  for (size_t i = 0; i < d; ++i) {
    double s = 0.0;
    for (size_t j = 0; j < d; ++j) s += f->omega2[i * d + j] * q[j];
    out[i] = s;
  }
}
