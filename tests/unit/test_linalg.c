/* Dense linear algebra: LU solve of non-symmetric systems (catches a transposed layout), singular
 * and non-finite input, symmetric eigen-decomposition (values, residuals, orthonormality). */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "geomint/core.h"

/* A is deliberately non-symmetric, and needs pivoting (a[0][0] = 0). */
static const double A3[9] = {0.0, 2.0,  1.0, //
                             1.0, -1.0, 3.0, //
                             4.0, 1.0,  -2.0};
static const double X3[3] = {1.0, -2.0, 3.0};

static void matvec(size_t n, const double *a, const double *x, double *y) {
  for (size_t i = 0; i < n; ++i) {
    y[i] = 0.0;
    for (size_t j = 0; j < n; ++j) y[i] += a[i * n + j] * x[j];
  }
}

Test(linalg, dense_solve_known_system) {
  double a[9], b[3];
  memcpy(a, A3, sizeof a);
  matvec(3, A3, X3, b); /* b = (-1, 12, -4) */
  cr_assert(b[0] == -1.0 && b[1] == 12.0 && b[2] == -4.0);
  cr_assert_eq(gm_dense_solve(3, a, b), GM_OK);
  for (size_t i = 0; i < 3; ++i)
    cr_assert(fabs(b[i] - X3[i]) <= 1e-14, "x[%zu] = %.17g, want %g", i, b[i], X3[i]);
}

Test(linalg, lu_factor_then_solve_several_right_hand_sides) {
  double lu[9];
  int ipiv[3];
  memcpy(lu, A3, sizeof lu);
  cr_assert_eq(gm_lu_factor(3, lu, ipiv), GM_OK);
  for (size_t k = 0; k < 3; ++k) {
    double x[3] = {0.0, 0.0, 0.0}, b[3];
    x[k] = 1.0;
    x[(k + 1) % 3] = -0.5;
    matvec(3, A3, x, b);
    cr_assert_eq(gm_lu_solve(3, lu, ipiv, b), GM_OK);
    for (size_t i = 0; i < 3; ++i) cr_assert(fabs(b[i] - x[i]) <= 1e-15, "rhs %zu comp %zu", k, i);
  }
}

Test(linalg, larger_system_residual) {
  enum { N = 80 }; /* above the stack-pivot size of gm_dense_solve */
  static double a[N * N], a0[N * N], b[N], x[N];
  for (size_t i = 0; i < N; ++i) {
    x[i] = sin(1.0 + (double)i);
    for (size_t j = 0; j < N; ++j)
      a0[i * N + j] = cos((double)(3 * i + 7 * j * j) * 0.1) + (i == j ? 4.0 : 0.0);
  }
  memcpy(a, a0, sizeof a);
  matvec(N, a0, x, b);
  cr_assert_eq(gm_dense_solve(N, a, b), GM_OK);
  for (size_t i = 0; i < N; ++i)
    cr_assert(fabs(b[i] - x[i]) <= 1e-12, "x[%zu] off by %g", i, b[i] - x[i]);
}

Test(linalg, singular_matrix) {
  double a[9] = {1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 1.0, 0.0, 1.0}, b[3] = {1.0, 2.0, 3.0};
  int ipiv[3];
  double lu[9];
  memcpy(lu, a, sizeof lu);
  cr_assert_eq(gm_lu_factor(3, lu, ipiv), GM_ESINGULAR);
  cr_assert_eq(gm_dense_solve(3, a, b), GM_ESINGULAR);
  double z[4] = {0.0, 0.0, 0.0, 0.0}, zb[2] = {1.0, 1.0};
  cr_assert_eq(gm_dense_solve(2, z, zb), GM_ESINGULAR);
}

Test(linalg, invalid_and_non_finite_input) {
  double a[4] = {1.0, 0.0, 0.0, 1.0}, b[2] = {1.0, 1.0}, ev[2];
  int ipiv[2];
  cr_assert_eq(gm_lu_factor(0, a, ipiv), GM_EINVAL);
  cr_assert_eq(gm_lu_factor(2, NULL, ipiv), GM_EINVAL);
  cr_assert_eq(gm_lu_factor(2, a, NULL), GM_EINVAL);
  cr_assert_eq(gm_lu_solve(2, a, ipiv, NULL), GM_EINVAL);
  cr_assert_eq(gm_dense_solve(0, a, b), GM_EINVAL);
  cr_assert_eq(gm_dense_solve(2, a, NULL), GM_EINVAL);
  cr_assert_eq(gm_symmetric_eigen(0, a, ev), GM_EINVAL);
  cr_assert_eq(gm_symmetric_eigen(2, a, NULL), GM_EINVAL);

  double nan_a[4] = {1.0, NAN, 0.0, 1.0};
  cr_assert_eq(gm_lu_factor(2, nan_a, ipiv), GM_EDOMAIN);
  double inf_b[2] = {1.0, INFINITY}, id[4] = {1.0, 0.0, 0.0, 1.0};
  cr_assert_eq(gm_dense_solve(2, id, inf_b), GM_EDOMAIN);
  double nan_upper[4] = {1.0, NAN, 0.0, 1.0};
  cr_assert_eq(gm_symmetric_eigen(2, nan_upper, ev), GM_EDOMAIN);
}

Test(linalg, eigen_of_2x2) {
  double a[4] = {2.0, 1.0, 1.0, 2.0}, ev[2];
  cr_assert_eq(gm_symmetric_eigen(2, a, ev), GM_OK);
  cr_assert(fabs(ev[0] - 1.0) <= 1e-15 && fabs(ev[1] - 3.0) <= 1e-15, "eigenvalues %g %g", ev[0],
            ev[1]);
  /* Eigenvector of 1 is ±(1,-1)/√2, of 3 is ±(1,1)/√2, as columns. */
  double s = 1.0 / sqrt(2.0);
  cr_assert(fabs(fabs(a[0]) - s) <= 1e-15 && fabs(a[0] + a[2]) <= 1e-15, "column 0");
  cr_assert(fabs(fabs(a[1]) - s) <= 1e-15 && fabs(a[1] - a[3]) <= 1e-15, "column 1");
}

Test(linalg, eigen_residual_orthonormality_and_upper_triangle_only) {
  enum { N = 6 };
  double a0[N * N], a[N * N], ev[N];
  for (size_t i = 0; i < N; ++i)
    for (size_t j = i; j < N; ++j)
      a0[i * N + j] = a0[j * N + i] = 1.0 / (double)(i + j + 1) + (i == j ? (double)i : 0.0);
  memcpy(a, a0, sizeof a);
  /* Garbage below the diagonal must be ignored. */
  for (size_t i = 1; i < N; ++i)
    for (size_t j = 0; j < i; ++j) a[i * N + j] = 1e3 * (double)(i + j);
  cr_assert_eq(gm_symmetric_eigen(N, a, ev), GM_OK);
  double trace = 0.0, ev_sum = 0.0;
  for (size_t i = 0; i < N; ++i) {
    trace += a0[i * N + i];
    ev_sum += ev[i];
    if (i > 0) cr_assert(ev[i] >= ev[i - 1], "eigenvalues ascending");
  }
  cr_assert(fabs(trace - ev_sum) <= 1e-13 * fabs(trace));
  for (size_t k = 0; k < N; ++k) {
    /* ||A v_k - λ_k v_k|| small, with v_k = column k. */
    for (size_t i = 0; i < N; ++i) {
      double av = 0.0;
      for (size_t j = 0; j < N; ++j) av += a0[i * N + j] * a[j * N + k];
      cr_assert(fabs(av - ev[k] * a[i * N + k]) <= 1e-13 * (double)N,
                "residual of eigenpair %zu, row %zu: %g", k, i, av - ev[k] * a[i * N + k]);
    }
    for (size_t l = 0; l < N; ++l) {
      double dot = 0.0;
      for (size_t i = 0; i < N; ++i) dot += a[i * N + k] * a[i * N + l];
      cr_assert(fabs(dot - (k == l ? 1.0 : 0.0)) <= 1e-14, "v_%zu . v_%zu = %g", k, l, dot);
    }
  }
}
