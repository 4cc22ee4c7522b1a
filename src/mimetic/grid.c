/* The mimetic spectral framework on [−1, 1] (seed 003, Palha & Gerritsma, §4): nodal and edge
 * bases of a grid, reduction, reconstruction and the incidence matrix; and the time element
 * with its primal Gauss–Lobatto and dual extended Gauss grids (§4.4). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/mimetic.h"

struct gm_mimetic_grid {
  size_t n;       /* nodes */
  double *nodes;
};

gm_status gm_mimetic_grid_create(size_t n_nodes, const double *nodes, gm_mimetic_grid **out,
                                 gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (nodes == NULL) return gm_error_set(err, GM_EINVAL, "nodes are NULL");
  if (n_nodes < 2 || n_nodes > GM_MIMETIC_MAX_NODES)
    return gm_error_set(err, GM_EINVAL, "a grid needs 2 to %d nodes, got %zu",
                        GM_MIMETIC_MAX_NODES, n_nodes);
  if (nodes[0] != -1.0 || nodes[n_nodes - 1] != 1.0)
    return gm_error_set(err, GM_EINVAL, "a grid on [-1, 1] must start at -1 and end at 1 "
                        "(got %g and %g)", nodes[0], nodes[n_nodes - 1]);
  for (size_t i = 1; i < n_nodes; ++i)
    if (!(nodes[i] > nodes[i - 1]))
      return gm_error_set(err, GM_EINVAL, "grid nodes must ascend strictly: node %zu (%g) "
                          "after %g", i, nodes[i], nodes[i - 1]);
  gm_mimetic_grid *g = calloc(1, sizeof *g);
  if (g == NULL || (g->nodes = malloc(n_nodes * sizeof(double))) == NULL) {
    free(g);
    return gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  g->n = n_nodes;
  memcpy(g->nodes, nodes, n_nodes * sizeof(double));
  *out = g;
  return GM_OK;
}

void gm_mimetic_grid_free(gm_mimetic_grid *grid) {
  if (grid == NULL) return;
  free(grid->nodes);
  free(grid);
}

size_t gm_mimetic_grid_n_nodes(const gm_mimetic_grid *grid) { return grid ? grid->n : 0; }
size_t gm_mimetic_grid_n_edges(const gm_mimetic_grid *grid) { return grid ? grid->n - 1 : 0; }
const double *gm_mimetic_grid_nodes(const gm_mimetic_grid *grid) {
  return grid ? grid->nodes : NULL;
}

gm_status gm_mimetic_nodal_basis(const gm_mimetic_grid *grid, double xi, double *values) {
  if (grid == NULL || values == NULL) return GM_EINVAL;
  return gm_lagrange_basis(grid->n, grid->nodes, xi, values);
}

gm_status gm_mimetic_nodal_basis_derivative(const gm_mimetic_grid *grid, double xi,
                                            double *values) {
  if (grid == NULL || values == NULL) return GM_EINVAL;
  return gm_lagrange_basis_derivative(grid->n, grid->nodes, xi, values);
}

/* e_i = −Σ_{k<i} l_k' (seed 003 eq. 4.10): a running sum of the nodal derivatives. */
gm_status gm_mimetic_edge_basis(const gm_mimetic_grid *grid, double xi, double *values) {
  if (grid == NULL || values == NULL) return GM_EINVAL;
  double dl[GM_MIMETIC_MAX_NODES];
  gm_status st = gm_lagrange_basis_derivative(grid->n, grid->nodes, xi, dl);
  if (st != GM_OK) return st;
  double sum = 0.0;
  for (size_t i = 1; i < grid->n; ++i) {
    sum -= dl[i - 1];
    values[i - 1] = sum;
  }
  return GM_OK;
}

void gm_mimetic_incidence(const gm_mimetic_grid *grid, double *incidence) {
  const size_t n = grid->n;
  memset(incidence, 0, (n - 1) * n * sizeof *incidence);
  for (size_t i = 0; i + 1 < n; ++i) {
    incidence[i * n + i] = -1.0;
    incidence[i * n + i + 1] = 1.0;
  }
}

void gm_mimetic_coboundary(const gm_mimetic_grid *grid, const double *c0, double *c1) {
  for (size_t i = 0; i + 1 < grid->n; ++i) c1[i] = c0[i + 1] - c0[i];
}

gm_status gm_mimetic_reduce_0form(const gm_mimetic_grid *grid, gm_scalar_fn f, void *ctx,
                                  double *c0) {
  if (grid == NULL || f == NULL || c0 == NULL) return GM_EINVAL;
  for (size_t i = 0; i < grid->n; ++i) c0[i] = f(ctx, grid->nodes[i]);
  return GM_OK;
}

gm_status gm_mimetic_reduce_1form(const gm_mimetic_grid *grid, gm_scalar_fn g, void *ctx,
                                  size_t n_quad, double *c1) {
  if (grid == NULL || g == NULL || c1 == NULL || n_quad == 0 || n_quad > 256) return GM_EINVAL;
  double x[256], w[256];
  for (size_t i = 0; i + 1 < grid->n; ++i) {
    gm_status st = gm_gauss_legendre(n_quad, x, w);
    if (st != GM_OK) return st;
    gm_quadrature_map(n_quad, grid->nodes[i], grid->nodes[i + 1], x, w);
    double sum = 0.0;
    for (size_t k = 0; k < n_quad; ++k) sum += w[k] * g(ctx, x[k]);
    c1[i] = sum;
  }
  return GM_OK;
}

gm_status gm_mimetic_reconstruct_0form(const gm_mimetic_grid *grid, const double *c0, double xi,
                                       double *value) {
  if (grid == NULL || c0 == NULL || value == NULL) return GM_EINVAL;
  double l[GM_MIMETIC_MAX_NODES];
  gm_status st = gm_lagrange_basis(grid->n, grid->nodes, xi, l);
  if (st != GM_OK) return st;
  double sum = 0.0;
  for (size_t i = 0; i < grid->n; ++i) sum += c0[i] * l[i];
  *value = sum;
  return GM_OK;
}

gm_status gm_mimetic_reconstruct_1form(const gm_mimetic_grid *grid, const double *c1, double xi,
                                       double *value) {
  if (grid == NULL || c1 == NULL || value == NULL) return GM_EINVAL;
  double e[GM_MIMETIC_MAX_NODES];
  gm_status st = gm_mimetic_edge_basis(grid, xi, e);
  if (st != GM_OK) return st;
  double sum = 0.0;
  for (size_t i = 0; i + 1 < grid->n; ++i) sum += c1[i] * e[i];
  *value = sum;
  return GM_OK;
}

gm_status gm_time_element_create(size_t degree, gm_time_element **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (degree < 1 || degree + 2 > GM_MIMETIC_MAX_NODES)
    return gm_error_set(err, GM_EINVAL, "a time element needs degree 1 to %d, got %zu",
                        GM_MIMETIC_MAX_NODES - 2, degree);
  const size_t p = degree;
  gm_time_element *e = calloc(1, sizeof *e);
  double lobatto[GM_MIMETIC_MAX_NODES], lobatto_w[GM_MIMETIC_MAX_NODES];
  double dual[GM_MIMETIC_MAX_NODES];
  if (e == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  e->degree = p;
  e->gauss_nodes = malloc(p * sizeof(double));
  e->gauss_weights = malloc(p * sizeof(double));
  gm_status st = GM_ENOMEM;
  if (e->gauss_nodes == NULL || e->gauss_weights == NULL) goto fail;
  if ((st = gm_gauss_lobatto(p + 1, lobatto, lobatto_w)) != GM_OK ||
      (st = gm_gauss_legendre(p, e->gauss_nodes, e->gauss_weights)) != GM_OK) {
    gm_time_element_free(e);
    return gm_error_set(err, st, "quadrature nodes of degree %zu: %s", degree, gm_strerror(st));
  }
  lobatto[0] = -1.0; /* exact endpoints */
  lobatto[p] = 1.0;
  dual[0] = -1.0;
  for (size_t j = 0; j < p; ++j) dual[j + 1] = e->gauss_nodes[j];
  dual[p + 1] = 1.0;
  if ((st = gm_mimetic_grid_create(p + 1, lobatto, &e->primal, err)) != GM_OK) goto fail;
  if ((st = gm_mimetic_grid_create(p + 2, dual, &e->dual, err)) != GM_OK) goto fail;
  *out = e;
  return GM_OK;
fail: /* out of memory, or the grid's own message is in err */
  gm_time_element_free(e);
  return st == GM_ENOMEM ? gm_error_set(err, st, "out of memory") : st;
}

void gm_time_element_free(gm_time_element *element) {
  if (element == NULL) return;
  gm_mimetic_grid_free(element->primal);
  gm_mimetic_grid_free(element->dual);
  free(element->gauss_nodes);
  free(element->gauss_weights);
  free(element);
}
