/* Gauss–Legendre and Gauss–Lobatto rules: known small rules, exactness on monomials up to the
 * rule's degree for n up to 64, nodes as roots of P_n (or P'_{n-1}), symmetry, mapping. */
#include <criterion/criterion.h>
#include <math.h>

#include "geomint/core.h"

#define N_MAX 64

/* Relative distance, safe at zero. */
static double rel_err(double got, double want) {
  return fabs(got - want) / fmax(fabs(want), 1e-300);
}

static void assert_close(double got, double want, double tol, const char *what) {
  cr_assert(fabs(got - want) <= tol * fmax(fabs(want), 1.0), "%s: got %.17g, want %.17g", what, got,
            want);
}

/* P_n(x) and P_n'(x) in long double, by the three-term recurrence. */
static void legendre(size_t n, long double x, long double *p, long double *dp) {
  long double a = 1.0L, b = x;
  if (n == 0) {
    *p = 1.0L;
    *dp = 0.0L;
    return;
  }
  for (size_t k = 1; k < n; ++k) {
    long double c = ((2.0L * k + 1.0L) * x * b - (long double)k * a) / (k + 1.0L);
    a = b;
    b = c;
  }
  *p = b;
  *dp = (long double)n * (a - x * b) / (1.0L - x * x);
}

/* sum_i w_i x_i^k compared with ∫_{-1}^{1} x^k dx = 2/(k+1) (k even) or 0 (k odd). */
static void assert_exact_to_degree(size_t n, const double *x, const double *w, size_t degree) {
  for (size_t k = 0; k <= degree; ++k) {
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) sum += w[i] * pow(x[i], (double)k);
    if (k % 2 == 0)
      cr_assert(rel_err(sum, 2.0 / (double)(k + 1)) <= 1e-13,
                "n=%zu: integral of x^%zu is %.17g, want %.17g", n, k, sum, 2.0 / (double)(k + 1));
    else
      cr_assert(fabs(sum) <= 1e-15, "n=%zu: integral of x^%zu is %.3g, want 0", n, k, sum);
  }
}

static void assert_symmetric_ascending(size_t n, const double *x, const double *w) {
  for (size_t i = 0; i < n; ++i) {
    cr_assert(x[i] == -x[n - 1 - i], "n=%zu: node %zu is not the mirror of node %zu", n, i,
              n - 1 - i);
    cr_assert(w[i] == w[n - 1 - i], "n=%zu: weight %zu differs from its mirror", n, i);
    cr_assert(w[i] > 0.0, "n=%zu: weight %zu = %g is not positive", n, i, w[i]);
    if (i > 0) cr_assert(x[i] > x[i - 1], "n=%zu: nodes not ascending at %zu", n, i);
  }
  cr_assert(x[0] >= -1.0 && x[n - 1] <= 1.0);
}

Test(gauss_legendre, known_small_rules) {
  double x[3], w[3];
  cr_assert_eq(gm_gauss_legendre(1, x, w), GM_OK);
  cr_assert(x[0] == 0.0 && w[0] == 2.0);

  cr_assert_eq(gm_gauss_legendre(2, x, w), GM_OK);
  assert_close(x[0], -1.0 / sqrt(3.0), 2e-16, "n=2 node 0");
  assert_close(x[1], 1.0 / sqrt(3.0), 2e-16, "n=2 node 1");
  assert_close(w[0], 1.0, 2e-16, "n=2 weight 0");
  assert_close(w[1], 1.0, 2e-16, "n=2 weight 1");

  cr_assert_eq(gm_gauss_legendre(3, x, w), GM_OK);
  assert_close(x[0], -sqrt(0.6), 2e-16, "n=3 node 0");
  cr_assert(x[1] == 0.0);
  assert_close(x[2], sqrt(0.6), 2e-16, "n=3 node 2");
  assert_close(w[0], 5.0 / 9.0, 2e-16, "n=3 weight 0");
  assert_close(w[1], 8.0 / 9.0, 2e-16, "n=3 weight 1");
  assert_close(w[2], 5.0 / 9.0, 2e-16, "n=3 weight 2");
}

Test(gauss_legendre, exact_to_degree_2n_minus_1) {
  double x[N_MAX], w[N_MAX];
  for (size_t n = 1; n <= N_MAX; ++n) {
    cr_assert_eq(gm_gauss_legendre(n, x, w), GM_OK, "n=%zu", n);
    assert_symmetric_ascending(n, x, w);
    assert_exact_to_degree(n, x, w, 2 * n - 1);
  }
}

Test(gauss_legendre, rule_is_not_exact_beyond_its_degree) {
  /* Guards the exactness test itself: degree 2n is not integrated exactly. */
  double x[5], w[5];
  cr_assert_eq(gm_gauss_legendre(5, x, w), GM_OK);
  double sum = 0.0;
  for (size_t i = 0; i < 5; ++i) sum += w[i] * pow(x[i], 10.0);
  cr_assert(rel_err(sum, 2.0 / 11.0) > 1e-4);
}

Test(gauss_legendre, nodes_are_roots_of_legendre_polynomial) {
  double x[N_MAX], w[N_MAX];
  for (size_t n = 1; n <= N_MAX; ++n) {
    cr_assert_eq(gm_gauss_legendre(n, x, w), GM_OK);
    for (size_t i = 0; i < n; ++i) {
      long double p, dp;
      legendre(n, x[i], &p, &dp);
      /* The Newton correction |P/P'| is the distance to the true root: within about one ulp. */
      long double dist = fabsl(p / dp);
      cr_assert(dist <= 2.5e-16L * fmax(fabs(x[i]), 0.05), "n=%zu node %zu off by %Lg", n, i, dist);
      /* Weight formula of Abramowitz & Stegun 25.4.29 at the (long double) root. */
      long double xr = x[i] - p / dp;
      legendre(n, xr, &p, &dp);
      long double wr = 2.0L / ((1.0L - xr * xr) * dp * dp);
      cr_assert(fabsl(w[i] - wr) <= 1e-14L * wr, "n=%zu weight %zu: %.17g vs %.17Lg", n, i, w[i],
                wr);
    }
  }
}

Test(gauss_legendre, large_n_weights_sum_to_two) {
  enum { BIG = 500 };
  static double x[BIG], w[BIG];
  cr_assert_eq(gm_gauss_legendre(BIG, x, w), GM_OK);
  assert_symmetric_ascending(BIG, x, w);
  double sum = 0.0, second = 0.0;
  for (size_t i = 0; i < BIG; ++i) {
    sum += w[i];
    second += w[i] * x[i] * x[i];
  }
  cr_assert(rel_err(sum, 2.0) <= 1e-14, "sum of weights %.17g", sum);
  cr_assert(rel_err(second, 2.0 / 3.0) <= 1e-14, "integral of x^2 %.17g", second);
}

Test(gauss_lobatto, known_small_rules) {
  double x[4], w[4];
  cr_assert_eq(gm_gauss_lobatto(2, x, w), GM_OK);
  cr_assert(x[0] == -1.0 && x[1] == 1.0 && w[0] == 1.0 && w[1] == 1.0);

  cr_assert_eq(gm_gauss_lobatto(3, x, w), GM_OK);
  cr_assert(x[0] == -1.0 && x[1] == 0.0 && x[2] == 1.0);
  assert_close(w[0], 1.0 / 3.0, 2e-16, "n=3 weight 0");
  assert_close(w[1], 4.0 / 3.0, 2e-16, "n=3 weight 1");
  assert_close(w[2], 1.0 / 3.0, 2e-16, "n=3 weight 2");

  cr_assert_eq(gm_gauss_lobatto(4, x, w), GM_OK);
  cr_assert(x[0] == -1.0 && x[3] == 1.0);
  assert_close(x[1], -1.0 / sqrt(5.0), 2e-16, "n=4 node 1");
  assert_close(x[2], 1.0 / sqrt(5.0), 2e-16, "n=4 node 2");
  assert_close(w[0], 1.0 / 6.0, 2e-16, "n=4 weight 0");
  assert_close(w[1], 5.0 / 6.0, 2e-16, "n=4 weight 1");
}

Test(gauss_lobatto, exact_to_degree_2n_minus_3) {
  double x[N_MAX], w[N_MAX];
  for (size_t n = 2; n <= N_MAX; ++n) {
    cr_assert_eq(gm_gauss_lobatto(n, x, w), GM_OK, "n=%zu", n);
    assert_symmetric_ascending(n, x, w);
    cr_assert(x[0] == -1.0 && x[n - 1] == 1.0, "n=%zu: endpoints must be exact", n);
    assert_exact_to_degree(n, x, w, 2 * n - 3);
  }
}

Test(gauss_lobatto, interior_nodes_are_roots_of_legendre_derivative) {
  double x[N_MAX], w[N_MAX];
  for (size_t n = 3; n <= N_MAX; ++n) {
    cr_assert_eq(gm_gauss_lobatto(n, x, w), GM_OK);
    size_t big_n = n - 1;
    for (size_t i = 1; i + 1 < n; ++i) {
      long double p, dp;
      legendre(big_n, x[i], &p, &dp);
      long double d2 = (2.0L * x[i] * dp - (long double)big_n * (big_n + 1.0L) * p) /
                       (1.0L - x[i] * (long double)x[i]);
      long double dist = fabsl(dp / d2);
      cr_assert(dist <= 2.5e-16L * fmax(fabs(x[i]), 0.05), "n=%zu node %zu off by %Lg", n, i, dist);
    }
  }
}

Test(quadrature, map_to_interval) {
  double x[4], w[4];
  cr_assert_eq(gm_gauss_lobatto(4, x, w), GM_OK);
  gm_quadrature_map(4, 2.0, 5.0, x, w);
  cr_assert(x[0] == 2.0 && x[3] == 5.0, "endpoints map exactly");
  double sum = 0.0, cubic = 0.0;
  for (size_t i = 0; i < 4; ++i) {
    sum += w[i];
    cubic += w[i] * x[i] * x[i] * x[i];
  }
  /* ∫_2^5 x^3 dx = (625 - 16)/4; degree 3 <= 2n-3 = 5 is exact. */
  cr_assert(rel_err(sum, 3.0) <= 1e-15);
  cr_assert(rel_err(cubic, 609.0 / 4.0) <= 1e-14, "got %.17g", cubic);

  double g[3], gw[3];
  cr_assert_eq(gm_gauss_legendre(3, g, gw), GM_OK);
  gm_quadrature_map(3, 0.0, 1.0, g, gw);
  cr_assert(fabs(g[1] - 0.5) <= 1e-16 && fabs(gw[1] - 4.0 / 9.0) <= 1e-16);
  double quintic = 0.0;
  for (size_t i = 0; i < 3; ++i) quintic += gw[i] * pow(g[i], 5.0);
  cr_assert(rel_err(quintic, 1.0 / 6.0) <= 1e-14);
}

Test(quadrature, invalid_arguments) {
  double x[2], w[2];
  cr_assert_eq(gm_gauss_legendre(0, x, w), GM_EINVAL);
  cr_assert_eq(gm_gauss_legendre(2, NULL, w), GM_EINVAL);
  cr_assert_eq(gm_gauss_legendre(2, x, NULL), GM_EINVAL);
  cr_assert_eq(gm_gauss_lobatto(0, x, w), GM_EINVAL);
  cr_assert_eq(gm_gauss_lobatto(1, x, w), GM_EINVAL);
  cr_assert_eq(gm_gauss_lobatto(2, NULL, w), GM_EINVAL);
  cr_assert_eq(gm_gauss_lobatto(2, x, NULL), GM_EINVAL);
}
