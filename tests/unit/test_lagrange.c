/* Lagrange bases: barycentric weights, cardinality at the nodes, partition of unity, exact
 * interpolation and differentiation of polynomials of degree n-1, the differentiation matrix. */
#include <criterion/criterion.h>
#include <math.h>

#include "geomint/core.h"

#define N_MAX 20

/* A test polynomial of degree deg with awkward coefficients, and its derivative. */
static double poly(size_t deg, double x) {
  double p = 0.0;
  for (size_t k = deg + 1; k-- > 0;) p = p * x + (1.0 + 0.37 * (double)k) * (k % 2 ? -1.0 : 1.0);
  return p;
}

static double poly_derivative(size_t deg, double x) {
  double p = 0.0;
  for (size_t k = deg + 1; k-- > 1;)
    p = p * x + (double)k * (1.0 + 0.37 * (double)k) * (k % 2 ? -1.0 : 1.0);
  return p;
}

static void lobatto_nodes(size_t n, double *x) {
  double w[N_MAX];
  cr_assert_eq(gm_gauss_lobatto(n, x, w), GM_OK);
}

Test(lagrange, weights_of_known_nodes) {
  /* Nodes 0, 1, 3: w = 1/((0-1)(0-3)), 1/((1-0)(1-3)), 1/((3-0)(3-1)). */
  const double x[3] = {0.0, 1.0, 3.0};
  double w[3];
  cr_assert_eq(gm_lagrange_weights(3, x, w), GM_OK);
  cr_assert(fabs(w[0] - 1.0 / 3.0) <= 1e-16 && fabs(w[1] + 0.5) <= 1e-16 &&
                fabs(w[2] - 1.0 / 6.0) <= 1e-16,
            "w = %g %g %g", w[0], w[1], w[2]);
}

Test(lagrange, cardinal_at_nodes) {
  double x[N_MAX], l[N_MAX];
  for (size_t n = 2; n <= N_MAX; ++n) {
    lobatto_nodes(n, x);
    for (size_t i = 0; i < n; ++i) {
      cr_assert_eq(gm_lagrange_basis(n, x, x[i], l), GM_OK);
      for (size_t j = 0; j < n; ++j)
        cr_assert(l[j] == (i == j ? 1.0 : 0.0), "n=%zu: l_%zu(x_%zu) = %g", n, j, i, l[j]);
    }
  }
}

Test(lagrange, partition_of_unity_and_polynomial_reproduction) {
  double x[N_MAX], l[N_MAX];
  for (size_t n = 1; n <= N_MAX; ++n) {
    if (n == 1)
      x[0] = 0.3;
    else
      lobatto_nodes(n, x);
    for (double t = -1.0; t <= 1.0; t += 0.0625 + 1e-3) {
      cr_assert_eq(gm_lagrange_basis(n, x, t, l), GM_OK);
      double sum = 0.0, p = 0.0;
      for (size_t j = 0; j < n; ++j) {
        sum += l[j];
        p += l[j] * poly(n - 1, x[j]);
      }
      cr_assert(fabs(sum - 1.0) <= 1e-14, "n=%zu: sum of basis at %g is 1 + %g", n, t, sum - 1.0);
      double want = poly(n - 1, t);
      cr_assert(fabs(p - want) <= 1e-12 * fmax(1.0, fabs(want)), "n=%zu: p(%g) = %.17g, want %.17g",
                n, t, p, want);
    }
  }
}

Test(lagrange, basis_near_a_node_is_continuous) {
  double x[8], l[8];
  lobatto_nodes(8, x);
  double t = nextafter(x[3], 1.0);
  cr_assert_eq(gm_lagrange_basis(8, x, t, l), GM_OK);
  for (size_t j = 0; j < 8; ++j)
    cr_assert(fabs(l[j] - (j == 3 ? 1.0 : 0.0)) <= 1e-14, "l_%zu = %g", j, l[j]);
}

Test(lagrange, basis_derivative_differentiates_polynomials) {
  double x[N_MAX], dl[N_MAX];
  for (size_t n = 2; n <= N_MAX; ++n) {
    lobatto_nodes(n, x);
    /* Off the nodes, at the nodes, and a hair away from a node. */
    double points[] = {-0.93, -0.41, 0.05, 0.77, x[0], x[n / 2], x[n - 1], x[1] + 1e-9};
    for (size_t q = 0; q < sizeof points / sizeof *points; ++q) {
      double t = points[q];
      cr_assert_eq(gm_lagrange_basis_derivative(n, x, t, dl), GM_OK);
      double dsum = 0.0, dp = 0.0;
      for (size_t j = 0; j < n; ++j) {
        dsum += dl[j];
        dp += dl[j] * poly(n - 1, x[j]);
      }
      double want = poly_derivative(n - 1, t);
      cr_assert(fabs(dsum) <= 1e-10, "n=%zu: derivative of 1 at %g is %g", n, t, dsum);
      cr_assert(fabs(dp - want) <= 1e-10 * fmax(1.0, fabs(want)),
                "n=%zu: p'(%.17g) = %.17g, want %.17g", n, t, dp, want);
    }
  }
}

Test(lagrange, differentiation_matrix_is_exact_for_degree_n_minus_1) {
  double x[N_MAX], d[N_MAX * N_MAX], row[N_MAX];
  for (size_t n = 1; n <= N_MAX; ++n) {
    if (n == 1)
      x[0] = 0.0;
    else
      lobatto_nodes(n, x);
    cr_assert_eq(gm_differentiation_matrix(n, x, d), GM_OK);
    for (size_t deg = 0; deg < n; ++deg) {
      for (size_t i = 0; i < n; ++i) {
        double dp = 0.0, rowsum = 0.0;
        for (size_t j = 0; j < n; ++j) {
          dp += d[i * n + j] * poly(deg, x[j]);
          rowsum += d[i * n + j];
        }
        double want = poly_derivative(deg, x[i]);
        cr_assert(fabs(dp - want) <= 1e-10 * fmax(1.0, fabs(want)),
                  "n=%zu deg=%zu row %zu: %.17g, want %.17g", n, deg, i, dp, want);
        cr_assert(fabs(rowsum) <= 1e-12 * (double)n * (double)n, "n=%zu row %zu sums to %g", n, i,
                  rowsum);
      }
    }
    /* The derivative of the basis at a node is that node's row of D. */
    for (size_t i = 0; i < n; ++i) {
      cr_assert_eq(gm_lagrange_basis_derivative(n, x, x[i], row), GM_OK);
      for (size_t j = 0; j < n; ++j)
        cr_assert(fabs(row[j] - d[i * n + j]) <= 1e-13 * fmax(1.0, fabs(d[i * n + j])),
                  "n=%zu: l_%zu'(x_%zu) = %g, D = %g", n, j, i, row[j], d[i * n + j]);
    }
  }
}

Test(lagrange, lobatto_corner_entries) {
  /* On Gauss–Lobatto nodes D_00 = -N(N+1)/4 with N = n-1 (a standard result, e.g. in Canuto et al.,
   * Spectral Methods). */
  double x[N_MAX], d[N_MAX * N_MAX];
  for (size_t n = 2; n <= N_MAX; ++n) {
    lobatto_nodes(n, x);
    cr_assert_eq(gm_differentiation_matrix(n, x, d), GM_OK);
    double want = -(double)(n - 1) * (double)n / 4.0;
    cr_assert(fabs(d[0] - want) <= 1e-11 * fabs(want), "n=%zu: D_00 = %.17g, want %g", n, d[0],
              want);
    cr_assert(fabs(d[n * n - 1] + want) <= 1e-11 * fabs(want));
  }
}

Test(lagrange, coincident_nodes_and_bad_arguments) {
  const double x[3] = {0.0, 0.5, 0.5};
  double out[9];
  cr_assert_eq(gm_lagrange_weights(3, x, out), GM_EINVAL);
  cr_assert_eq(gm_lagrange_basis(3, x, 0.2, out), GM_EINVAL);
  cr_assert_eq(gm_lagrange_basis_derivative(3, x, 0.2, out), GM_EINVAL);
  cr_assert_eq(gm_differentiation_matrix(3, x, out), GM_EINVAL);
  const double good[2] = {0.0, 1.0};
  cr_assert_eq(gm_lagrange_weights(0, good, out), GM_EINVAL);
  cr_assert_eq(gm_lagrange_weights(2, NULL, out), GM_EINVAL);
  cr_assert_eq(gm_lagrange_basis(2, good, 0.5, NULL), GM_EINVAL);
  cr_assert_eq(gm_lagrange_basis(2, good, NAN, out), GM_EDOMAIN);
  const double bad[2] = {0.0, INFINITY};
  cr_assert_eq(gm_differentiation_matrix(2, bad, out), GM_EDOMAIN);
}
