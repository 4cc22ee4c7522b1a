/* The mimetic framework on a time element (seed 003, §4): the identities of the edge basis,
 * reduction and reconstruction, and the commuting of d with both, to round-off, on the primal
 * Gauss–Lobatto and the dual extended Gauss grids of degrees 1..12; and MCI's Runge–Kutta
 * tableau (eqs. 5.16–5.32) against Gauss–Legendre collocation. */
#include <stdio.h>

#include "test_util.h"

static double poly(void *ctx, double x) { /* a fixed polynomial of degree *ctx */
  const int deg = *(const int *)ctx;
  double s = 0.0;
  for (int k = deg; k >= 0; --k) s = s * x + 0.3 + 0.17 * k * (k % 2 ? -1 : 1);
  return s;
}
static double poly_derivative(void *ctx, double x) {
  const int deg = *(const int *)ctx;
  double s = 0.0;
  for (int k = deg; k >= 1; --k) s = s * x + k * (0.3 + 0.17 * k * (k % 2 ? -1 : 1));
  return s;
}
static double smooth(void *ctx, double x) { (void)ctx; return exp(sin(2.0 * x)); }
static double smooth_derivative(void *ctx, double x) {
  (void)ctx;
  return 2.0 * cos(2.0 * x) * exp(sin(2.0 * x));
}

typedef struct {
  const gm_mimetic_grid *grid;
  size_t i;
} edge_fn;
static double edge_value(void *ctx, double x) {
  const edge_fn *e = ctx;
  double v[GM_MIMETIC_MAX_NODES];
  cr_assert_eq(gm_mimetic_edge_basis(e->grid, x, v), GM_OK);
  return v[e->i];
}

static void check_grid(const gm_mimetic_grid *g, const char *which, size_t p) {
  const size_t nn = gm_mimetic_grid_n_nodes(g), ne = gm_mimetic_grid_n_edges(g);
  cr_assert_eq(ne + 1, nn);
  double c1[GM_MIMETIC_MAX_NODES], c0[GM_MIMETIC_MAX_NODES], d0[GM_MIMETIC_MAX_NODES];
  /* (4.11): ∫ over edge j of e_i = δ_ij (e_i has degree nn − 2: nn Gauss points are exact) */
  for (size_t i = 0; i < ne; ++i) {
    edge_fn e = {g, i};
    cr_assert_eq(gm_mimetic_reduce_1form(g, edge_value, &e, nn, c1), GM_OK);
    for (size_t j = 0; j < ne; ++j)
      cr_expect_leq(fabs(c1[j] - (i == j)), 1e-13, "%s p=%zu: edge %zu of e_%zu = %.3e", which,
                    p, j, i + 1, c1[j]);
  }
  /* ℛℐ = Id for 0- and 1-cochains */
  for (size_t i = 0; i < nn; ++i) c0[i] = sin(1.0 + 3.7 * (double)i);
  for (size_t i = 0; i < nn; ++i) {
    double v;
    cr_assert_eq(gm_mimetic_reconstruct_0form(g, c0, gm_mimetic_grid_nodes(g)[i], &v), GM_OK);
    cr_expect_leq(fabs(v - c0[i]), 1e-14, "%s p=%zu: RI0 node %zu", which, p, i);
  }
  /* 1-cochain: reduce the reconstruction, edge by edge */
  for (size_t i = 0; i < ne; ++i) c1[i] = cos(0.5 + 2.3 * (double)i);
  double sum_rr = 0.0;
  for (size_t j = 0; j < ne; ++j) {
    double x[GM_MIMETIC_MAX_NODES], w[GM_MIMETIC_MAX_NODES], v, s = 0.0;
    cr_assert_eq(gm_gauss_legendre(nn, x, w), GM_OK);
    gm_quadrature_map(nn, gm_mimetic_grid_nodes(g)[j], gm_mimetic_grid_nodes(g)[j + 1], x, w);
    for (size_t k = 0; k < nn; ++k) {
      cr_assert_eq(gm_mimetic_reconstruct_1form(g, c1, x[k], &v), GM_OK);
      s += w[k] * v;
    }
    cr_expect_leq(fabs(s - c1[j]), 1e-13, "%s p=%zu: RI1 edge %zu: %.17g vs %.17g", which, p, j,
                  s, c1[j]);
    sum_rr += s;
  }
  (void)sum_rr;
  /* ℛ d = d ℛ: the edge integrals of φ' are the differences of the nodal values of φ (a
   * non-polynomial φ; 20 Gauss points per edge integrate φ' to round-off) */
  cr_assert_eq(gm_mimetic_reduce_0form(g, smooth, NULL, c0), GM_OK);
  gm_mimetic_coboundary(g, c0, d0);
  cr_assert_eq(gm_mimetic_reduce_1form(g, smooth_derivative, NULL, 20, c1), GM_OK);
  for (size_t j = 0; j < ne; ++j)
    cr_expect_leq(fabs(c1[j] - d0[j]), 1e-13, "%s p=%zu: Rd = dR on edge %zu", which, p, j);
  /* the incidence matrix is the coboundary */
  double e[GM_MIMETIC_MAX_NODES * GM_MIMETIC_MAX_NODES];
  gm_mimetic_incidence(g, e);
  for (size_t j = 0; j < ne; ++j) {
    double s = 0.0;
    for (size_t k = 0; k < nn; ++k) s += e[j * nn + k] * c0[k];
    cr_expect_eq(s, d0[j]);
  }
  /* (ℐc)' = ℐ(dc) at points off the grid, and ℐℛ reproduces polynomials of degree nn − 1 */
  int deg = (int)nn - 1;
  cr_assert_eq(gm_mimetic_reduce_0form(g, poly, &deg, c0), GM_OK);
  gm_mimetic_coboundary(g, c0, d0);
  for (int k = 0; k < 7; ++k) {
    double x = -0.97 + 0.31 * k, dl[GM_MIMETIC_MAX_NODES], dv = 0.0, v1, v0;
    cr_assert_eq(gm_mimetic_nodal_basis_derivative(g, x, dl), GM_OK);
    for (size_t i = 0; i < nn; ++i) dv += dl[i] * c0[i];
    cr_assert_eq(gm_mimetic_reconstruct_1form(g, d0, x, &v1), GM_OK);
    cr_expect_leq(fabs(dv - v1), 1e-12 * fmax(1.0, fabs(dv)), "%s p=%zu: dI = Id at %g", which,
                  p, x);
    cr_assert_eq(gm_mimetic_reconstruct_0form(g, c0, x, &v0), GM_OK);
    cr_expect_leq(fabs(v0 - poly(&deg, x)), 1e-13 * fmax(1.0, fabs(v0)), "%s p=%zu", which, p);
    cr_expect_leq(fabs(v1 - poly_derivative(&deg, x)), 1e-11 * fmax(1.0, fabs(v1)), "%s p=%zu",
                  which, p);
  }
}

Test(mimetic, identities_on_primal_and_dual_grids) {
  for (size_t p = 1; p <= 12; ++p) {
    gm_time_element *el = NULL;
    gm_error err;
    cr_assert_eq(gm_time_element_create(p, &el, &err), GM_OK, "%s", err.message);
    cr_expect_eq(gm_mimetic_grid_n_nodes(el->primal), p + 1);
    cr_expect_eq(gm_mimetic_grid_n_nodes(el->dual), p + 2);
    double wsum = 0.0;
    for (size_t j = 0; j < p; ++j) {
      wsum += el->gauss_weights[j];
      cr_expect_eq(gm_mimetic_grid_nodes(el->dual)[j + 1], el->gauss_nodes[j]);
    }
    cr_expect_leq(fabs(wsum - 2.0), 1e-14);
    check_grid(el->primal, "primal", p);
    check_grid(el->dual, "dual", p);
    gm_time_element_free(el);
  }
}

/* Seed 003 eq. (4.15)'s consequence: Σ_l (y^l − y^{l−1}) e_l = Σ_k y^k l_k' (the notes' check). */
Test(mimetic, edge_sum_is_the_nodal_derivative) {
  gm_time_element *el = NULL;
  cr_assert_eq(gm_time_element_create(2, &el, NULL), GM_OK);
  double e[4], dl[4];
  cr_assert_eq(gm_mimetic_edge_basis(el->primal, 0.3, e), GM_OK);
  cr_assert_eq(gm_mimetic_nodal_basis_derivative(el->primal, 0.3, dl), GM_OK);
  /* e_1 = −l_0', e_2 = −l_0' − l_1' = l_2' */
  cr_expect_leq(fabs(e[0] + dl[0]), 1e-15);
  cr_expect_leq(fabs(e[1] - dl[2]), 1e-15);
  /* p = 1: the edge function of [−1, 1] is 1/2 */
  gm_time_element_free(el);
  cr_assert_eq(gm_time_element_create(1, &el, NULL), GM_OK);
  cr_assert_eq(gm_mimetic_edge_basis(el->primal, -0.4, e), GM_OK);
  cr_expect_leq(fabs(e[0] - 0.5), 1e-15);
  gm_time_element_free(el);
}

Test(mimetic, bad_arguments) {
  gm_mimetic_grid *g = NULL;
  gm_error err;
  const double bad[4] = {-1.0, 0.5, 0.2, 1.0}, open[2] = {-0.9, 1.0};
  cr_expect_eq(gm_mimetic_grid_create(4, bad, &g, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "ascend") != NULL, "%s", err.message);
  cr_expect_eq(gm_mimetic_grid_create(2, open, &g, &err), GM_EINVAL);
  cr_expect_eq(gm_mimetic_grid_create(1, open, &g, &err), GM_EINVAL);
  cr_expect_null(g);
  gm_time_element *el = NULL;
  cr_expect_eq(gm_time_element_create(0, &el, &err), GM_EINVAL);
  cr_expect_eq(gm_time_element_create(GM_MIMETIC_MAX_NODES, &el, &err), GM_EINVAL);
  gm_mimetic_grid_free(NULL);
  gm_time_element_free(NULL);
}

/* MCI is a Runge–Kutta method (seed 003 §5.3) whose tableau is Gauss–Legendre's (Remark 2). */
Test(mimetic, canonical_tableau_is_gauss) {
  for (int p = 1; p <= 6; ++p) {
    char a[32], b[32];
    snprintf(a, sizeof a, "mimetic-canonical-%d", p);
    snprintf(b, sizeof b, "gauss-%d", p);
    gm_tableau *t1 = NULL, *t2 = NULL;
    cr_assert_eq(gm_method_tableau(gm_method_find(a), &t1), GM_OK);
    cr_assert_eq(gm_method_tableau(gm_method_find(b), &t2), GM_OK);
    double d = 0.0;
    for (int i = 0; i < p; ++i) {
      d = fmax(d, fabs(t1->b[i] - t2->b[i]));
      d = fmax(d, fabs(t1->c[i] - t2->c[i]));
      for (int j = 0; j < p; ++j) d = fmax(d, fabs(t1->a[i * p + j] - t2->a[i * p + j]));
    }
    cr_expect_leq(d, 1e-15, "%s vs %s: %.2e", a, b, d);
    gm_tableau_free(t1);
    gm_tableau_free(t2);
  }
}
