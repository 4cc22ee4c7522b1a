/* Lagrange bases on arbitrary distinct nodes, in barycentric form.
 *
 * Reference: J.-P. Berrut and L. N. Trefethen, "Barycentric Lagrange interpolation",
 * SIAM Review 46 (2004) 501–517: weights w_j = 1 / prod_{k≠j}(x_j - x_k); the "second (true)
 * barycentric formula" l_j(x) = (w_j/(x-x_j)) / sum_k (w_k/(x-x_k)); and the differentiation
 * matrix D_ij = (w_j/w_i)/(x_i-x_j), D_ii = -sum_{j≠i} D_ij.
 *
 * Only ratios of weights enter the basis and D, so internally the weights are computed from the
 * differences scaled by 4/(max - min) (the reciprocal of the interval's logarithmic capacity, as
 * Berrut & Trefethen suggest), which keeps them away from overflow and underflow for large n. */
#include <math.h>

#include "core/internal.h"

static gm_status check_nodes(size_t n, const double *nodes, const double *out) {
  if (n == 0 || nodes == NULL || out == NULL) return GM_EINVAL;
  if (gm_first_nonfinite(n, nodes) < n) return GM_EDOMAIN;
  return GM_OK;
}

/* w[j*stride] = 1 / prod_{k≠j} (scale (x_j - x_k)). GM_EINVAL for coincident nodes, GM_EDOMAIN
 * when a weight over- or underflows. */
static gm_status weights_scaled(size_t n, const double *x, double scale, double *w, size_t stride) {
  for (size_t j = 0; j < n; ++j) {
    double prod = 1.0;
    for (size_t k = 0; k < n; ++k) {
      if (k == j) continue;
      double d = x[j] - x[k];
      if (d == 0.0) return GM_EINVAL;
      prod *= scale * d;
    }
    double wj = 1.0 / prod;
    if (!isfinite(wj) || wj == 0.0) return GM_EDOMAIN;
    w[j * stride] = wj;
  }
  return GM_OK;
}

/* 4 / (max - min): see the top of this file (any positive value when n == 1). */
static double capacity_scale(size_t n, const double *x) {
  double lo = x[0], hi = x[0];
  for (size_t k = 1; k < n; ++k) {
    lo = fmin(lo, x[k]);
    hi = fmax(hi, x[k]);
  }
  return hi > lo ? 4.0 / (hi - lo) : 1.0;
}

gm_status gm_lagrange_weights(size_t n, const double *nodes, double *weights) {
  gm_status s = check_nodes(n, nodes, weights);
  return s != GM_OK ? s : weights_scaled(n, nodes, 1.0, weights, 1);
}

/* Index of the node equal to x, or n. A distance so small that w/(x - x_k) overflows counts as
 * equal: the basis there is the node's to within rounding. */
static size_t node_at(size_t n, const double *nodes, const double *w, double x) {
  for (size_t k = 0; k < n; ++k) {
    double d = x - nodes[k];
    if (d == 0.0 || isinf(w[k] / d)) return k;
  }
  return n;
}

gm_status gm_lagrange_basis(size_t n, const double *nodes, double x, double *values) {
  gm_status s = check_nodes(n, nodes, values);
  if (s != GM_OK) return s;
  if (!isfinite(x)) return GM_EDOMAIN;
  s = weights_scaled(n, nodes, capacity_scale(n, nodes), values, 1);
  if (s != GM_OK) return s;
  size_t i = node_at(n, nodes, values, x);
  if (i < n) {
    for (size_t j = 0; j < n; ++j) values[j] = j == i ? 1.0 : 0.0;
    return GM_OK;
  }
  double sum = 0.0;
  for (size_t j = 0; j < n; ++j) {
    values[j] /= x - nodes[j];
    sum += values[j];
  }
  for (size_t j = 0; j < n; ++j) values[j] /= sum;
  return GM_OK;
}

gm_status gm_lagrange_basis_derivative(size_t n, const double *nodes, double x, double *values) {
  gm_status s = check_nodes(n, nodes, values);
  if (s != GM_OK) return s;
  if (!isfinite(x)) return GM_EDOMAIN;
  s = weights_scaled(n, nodes, capacity_scale(n, nodes), values, 1);
  if (s != GM_OK) return s;
  size_t i = node_at(n, nodes, values, x);
  if (i < n) {
    /* At a node the derivative is that node's row of D (same formulas as
     * gm_differentiation_matrix), written in place over the weights: w_i is saved first and
     * each w_j is read just before values[j] is overwritten. */
    double wi = values[i], diagonal = 0.0;
    for (size_t j = 0; j < n; ++j) {
      if (j == i) continue;
      values[j] = (values[j] / wi) / (nodes[i] - nodes[j]);
      diagonal -= values[j];
    }
    values[i] = diagonal;
    return GM_OK;
  }
  /* l_j'(x) = l_j(x) sum_{k≠j} 1/(x - x_k) (logarithmic derivative of l_j). Near a node x_m the
   * large term 1/(x - x_m) multiplies the small l_j(x), j≠m, and is excluded for j = m, so no
   * cancellation occurs. */
  double sum = 0.0;
  for (size_t j = 0; j < n; ++j) {
    values[j] /= x - nodes[j];
    sum += values[j];
  }
  for (size_t j = 0; j < n; ++j) {
    double log_derivative = 0.0;
    for (size_t k = 0; k < n; ++k)
      if (k != j) log_derivative += 1.0 / (x - nodes[k]);
    values[j] = values[j] / sum * log_derivative;
  }
  return GM_OK;
}

gm_status gm_differentiation_matrix(size_t n, const double *nodes, double *d) {
  gm_status s = check_nodes(n, nodes, d);
  if (s != GM_OK) return s;
  /* The weights live on the diagonal of d until every off-diagonal entry has been computed. */
  s = weights_scaled(n, nodes, capacity_scale(n, nodes), d, n + 1);
  if (s != GM_OK) return s;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j)
      if (j != i) d[i * n + j] = (d[j * n + j] / d[i * n + i]) / (nodes[i] - nodes[j]);
  /* Negative row sum instead of sum_{k≠i} 1/(x_i-x_k): each row then differentiates constants
   * exactly, which improves accuracy (Berrut & Trefethen 2004; Baltensperger & Trefethen,
   * "Spectral differencing with a twist", SIAM J. Sci. Comput. 24 (2003) 1465). */
  for (size_t i = 0; i < n; ++i) {
    double diagonal = 0.0;
    for (size_t j = 0; j < n; ++j)
      if (j != i) diagonal -= d[i * n + j];
    d[i * n + i] = diagonal;
  }
  return GM_OK;
}
