/* 1-D multiscale finite elements (Hou & Wu 1997; seed 001 §5.7.1 and App. C): (a u′)′ = f on
 * (0, 1) with homogeneous Dirichlet data. The weak form −∫ a u′ v′ = ∫ f v on the span of the
 * element-wise a-harmonic shape functions gives exact nodal values (the nodal Green's functions
 * lie in that span), against standard P1 elements whose stiffness averages a arithmetically
 * and whose error stays O(1) until the mesh resolves a's scale. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/oscillatory.h"
#include "core/internal.h"

#define MSFEM_Q 8

typedef struct {
  double (*a)(void *, double);
  double (*f)(void *, double);
  void *ctx;
  double x[MSFEM_Q], w[MSFEM_Q]; /* Gauss–Legendre on [−1, 1] */
  int bad;                       /* a ≤ 0 or not finite seen */
  double bad_x, bad_a;
} msfem;

static double coefficient(msfem *m, double x) {
  double v = m->a(m->ctx, x);
  if (!(v > 0.0) || !isfinite(v)) {
    if (!m->bad) {
      m->bad_x = x;
      m->bad_a = v;
    }
    m->bad = 1;
    return 1.0;
  }
  return v;
}

/* ∫_lo^hi 1/a by the Gauss rule */
static double inverse_integral(msfem *m, double lo, double hi) {
  double s = 0.0;
  for (size_t q = 0; q < MSFEM_Q; ++q)
    s += m->w[q] / coefficient(m, 0.5 * (lo + hi) + 0.5 * (hi - lo) * m->x[q]);
  return 0.5 * (hi - lo) * s;
}

/* Element [x0, x1]: stiffness k (the matrix k[[1, −1], [−1, 1]]) and loads ∫ f φ_left,
 * ∫ f φ_right. */
static void element(msfem *m, double x0, double x1, int multiscale, size_t n_sub, double *k,
                    double *load_left, double *load_right) {
  const double h = x1 - x0;
  double total = 0.0; /* ∫_e 1/a (multiscale) or ∫_e a (P1) */
  for (size_t s = 0; s < n_sub; ++s) {
    const double lo = x0 + h * (double)s / (double)n_sub, hi = x0 + h * (double)(s + 1) / (double)n_sub;
    if (multiscale) {
      total += inverse_integral(m, lo, hi);
    } else {
      for (size_t q = 0; q < MSFEM_Q; ++q)
        total += 0.5 * (hi - lo) * m->w[q] * coefficient(m, 0.5 * (lo + hi) + 0.5 * (hi - lo) * m->x[q]);
    }
  }
  *k = multiscale ? 1.0 / total : total / (h * h);
  double fl = 0.0, fr = 0.0, acc = 0.0; /* acc = A(lo) = ∫_{x0}^{lo} 1/a */
  for (size_t s = 0; s < n_sub; ++s) {
    const double lo = x0 + h * (double)s / (double)n_sub, hi = x0 + h * (double)(s + 1) / (double)n_sub;
    for (size_t q = 0; q < MSFEM_Q; ++q) {
      const double t = 0.5 * (lo + hi) + 0.5 * (hi - lo) * m->x[q], wq = 0.5 * (hi - lo) * m->w[q];
      const double phi_right = multiscale ? (acc + inverse_integral(m, lo, t)) / total : (t - x0) / h;
      const double ft = m->f(m->ctx, t);
      fl += wq * ft * (1.0 - phi_right);
      fr += wq * ft * phi_right;
    }
    if (multiscale) acc += inverse_integral(m, lo, hi);
  }
  *load_left = fl;
  *load_right = fr;
}

gm_status gm_msfem_1d(double (*a)(void *ctx, double x), double (*f)(void *ctx, double x),
                      void *ctx, size_t n_elements, int multiscale, size_t n_sub, double *nodal,
                      gm_error *err) {
  if (a == NULL || f == NULL || nodal == NULL)
    return gm_error_set(err, GM_EINVAL, "msfem: a, f and nodal must not be NULL");
  if (n_elements == 0 || n_sub == 0)
    return gm_error_set(err, GM_EINVAL, "msfem: need n_elements >= 1 and n_sub >= 1 (got %zu, %zu)",
                        n_elements, n_sub);
  msfem m = {a, f, ctx, {0}, {0}, 0, 0, 0};
  gm_status st = gm_gauss_legendre(MSFEM_Q, m.x, m.w);
  if (st != GM_OK) return gm_error_set(err, st, "msfem: Gauss rule failed");
  const size_t n = n_elements;
  /* tridiagonal system for the interior nodes 1..n−1: diag d, off-diagonal e (symmetric) */
  double *d = calloc(n + 1, sizeof *d), *e = calloc(n + 1, sizeof *e), *rhs = calloc(n + 1, sizeof *rhs);
  if (!d || !e || !rhs) {
    free(d);
    free(e);
    free(rhs);
    return gm_error_set(err, GM_ENOMEM, "msfem: out of memory");
  }
  for (size_t i = 0; i < n; ++i) {
    double k, fl, fr;
    element(&m, (double)i / (double)n, (double)(i + 1) / (double)n, multiscale, n_sub, &k, &fl, &fr);
    /* −K u = F: K u = −F */
    d[i] += k;
    d[i + 1] += k;
    e[i] = -k; /* coupling of nodes i and i + 1 */
    rhs[i] -= fl;
    rhs[i + 1] -= fr;
  }
  if (m.bad) {
    free(d);
    free(e);
    free(rhs);
    return gm_error_set(err, GM_EINVAL, "msfem: a(%g) = %g, must be positive and finite", m.bad_x,
                        m.bad_a);
  }
  /* Thomas algorithm on nodes 1..n−1 (u_0 = u_n = 0) */
  memset(nodal, 0, (n + 1) * sizeof *nodal);
  for (size_t i = 2; i + 1 <= n; ++i) {
    const double r = e[i - 1] / d[i - 1];
    d[i] -= r * e[i - 1];
    rhs[i] -= r * rhs[i - 1];
  }
  if (n >= 2) {
    nodal[n - 1] = rhs[n - 1] / d[n - 1];
    for (size_t i = n - 2; i >= 1; --i) nodal[i] = (rhs[i] - e[i] * nodal[i + 1]) / d[i];
  }
  free(d);
  free(e);
  free(rhs);
  return GM_OK;
}
