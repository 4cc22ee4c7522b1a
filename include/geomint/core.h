/* geomint core: status codes, dense linear algebra, Newton's method, quadrature, Lagrange bases.
 *
 * Conventions (DESIGN §2–3): every fallible function returns gm_status; matrices are dense,
 * row-major, double; counts are size_t. Pointer parameters are borrowed unless a comment says
 * otherwise. Nothing here prints, exits or keeps global mutable state. */
#ifndef GEOMINT_CORE_H
#define GEOMINT_CORE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- status ---------------------------------------------------------------------------- */

/* One list generates the enum and gm_strerror. */
#define GM_STATUS_LIST(X)                                                        \
  X(GM_OK, 0, "success")                                                         \
  X(GM_EINVAL, -1, "invalid argument")                                           \
  X(GM_ENOMEM, -2, "out of memory")                                              \
  X(GM_ENOTFOUND, -3, "no such name")                                            \
  X(GM_ENOCONV, -4, "iteration did not converge")                                \
  X(GM_ESINGULAR, -5, "singular matrix")                                         \
  X(GM_ECALLBACK, -6, "a user callback reported failure")                        \
  X(GM_EDOMAIN, -7, "non-finite value")                                          \
  X(GM_EIO, -8, "input/output error")                                            \
  X(GM_EUNSUPPORTED, -9, "method cannot integrate this problem")                 \
  X(GM_ELAPACK, -10, "LAPACK reported an error")

typedef enum {
#define GM_STATUS_ENUM_(name, value, text) name = value,
  GM_STATUS_LIST(GM_STATUS_ENUM_)
#undef GM_STATUS_ENUM_
} gm_status;

/* A static English sentence for a status code ("unknown status" for codes not in the list). */
const char *gm_strerror(gm_status status);

/* Creators that fail before an object exists write the reason here (when non-NULL). */
#define GM_ERRMSG_SIZE 512
typedef struct gm_error {
  char message[GM_ERRMSG_SIZE];
} gm_error;

/* ---- "did you mean" -------------------------------------------------------------------- */

/* The i-th candidate name, NULL past the end. */
typedef const char *(*gm_name_at)(const void *ctx, size_t i);
/* Restricted Damerau–Levenshtein distance of two names (case-insensitive, at most 64 characters
 * of each are compared). */
size_t gm_edit_distance(const char *a, const char *b);
/* Writes the (at most five) candidates closest to query as "a, b, c" into buf; returns how many
 * (0: none close enough to be worth suggesting). */
size_t gm_suggest(const char *query, gm_name_at name_at, const void *ctx, char *buf, size_t cap);

/* ---- dense linear algebra (LAPACKE) ---------------------------------------------------- */

/* LU factorization with partial pivoting of the n×n row-major matrix a, in place.
 * ipiv: n pivot indices (written). GM_ESINGULAR when an exact zero pivot appears. */
gm_status gm_lu_factor(size_t n, double *a, int *ipiv);
/* Solve A x = b with the factors from gm_lu_factor; b (n values) is overwritten by x. */
gm_status gm_lu_solve(size_t n, const double *lu, const int *ipiv, double *b);
/* Solve A x = b in one call; a is destroyed, b overwritten by x. */
gm_status gm_dense_solve(size_t n, double *a, double *b);
/* Eigen-decomposition of the symmetric n×n matrix a (only its upper triangle is read).
 * eigenvalues: n values in ascending order. On return a holds the orthonormal eigenvectors
 * as columns (row-major storage: a[i*n + j] is component i of eigenvector j). */
gm_status gm_symmetric_eigen(size_t n, double *a, double *eigenvalues);

/* ---- Newton's method for F(x) = 0 ------------------------------------------------------ */

/* Residual F: R^n -> R^n and its Jacobian (row-major n×n, jac[i*n+j] = dF_i/dx_j).
 * Return 0 on success; any other value stops the solve with GM_ECALLBACK. */
typedef int (*gm_residual_fn)(void *ctx, const double *x, double *residual);
typedef int (*gm_jacobian_fn)(void *ctx, const double *x, double *jacobian);

typedef struct gm_newton_options {
  size_t max_iterations;   /* failure after this many iterations (default 30) */
  double residual_tol;     /* converged when max|F| <= residual_tol (default 0: off) */
  double increment_tol;    /* converged when max|dx| <= increment_tol * (1 + max|x|) (default 1e-14) */
  int simplified;          /* non-zero: evaluate and factor the Jacobian once per solve */
  double fd_relative_step; /* finite-difference Jacobian (when none is given): step
                              h_j = fd_relative_step * max(|x_j|, 1) (default 1e-7, one-sided) */
} gm_newton_options;

gm_newton_options gm_newton_defaults(void);

typedef struct gm_newton gm_newton;

/* A solver for systems of size n; options are copied (NULL for defaults). All work arrays are
 * allocated here, none in gm_newton_solve. */
gm_status gm_newton_create(size_t n, const gm_newton_options *options, gm_newton **out);
void gm_newton_free(gm_newton *newton);
/* Solve F(x) = 0 starting from x (overwritten with the solution; left at the last iterate on
 * failure). jacobian may be NULL: then a finite-difference Jacobian is used.
 * Errors: GM_ENOCONV (message gives iterations and residual), GM_ESINGULAR, GM_ECALLBACK,
 * GM_EDOMAIN (the residual became NaN or infinite). */
gm_status gm_newton_solve(gm_newton *newton, gm_residual_fn residual, gm_jacobian_fn jacobian,
                          void *ctx, double *x);
/* Statistics of the last solve. */
size_t gm_newton_iterations(const gm_newton *newton);
size_t gm_newton_residual_evals(const gm_newton *newton); /* including finite differences */
size_t gm_newton_jacobian_evals(const gm_newton *newton);
double gm_newton_residual_norm(const gm_newton *newton);
const char *gm_newton_errmsg(const gm_newton *newton);

/* ---- quadrature ------------------------------------------------------------------------ */

/* Gauss–Legendre rule with n >= 1 points on [-1, 1]: nodes ascending, exact for polynomials of
 * degree 2n-1. Accurate to a few ulps up to n ≈ 200 (computed in long double; tested to
 * n = 64). */
gm_status gm_gauss_legendre(size_t n, double *nodes, double *weights);
/* Gauss–Lobatto–Legendre rule with n >= 2 points on [-1, 1] (endpoints included), exact for
 * degree 2n-3. */
gm_status gm_gauss_lobatto(size_t n, double *nodes, double *weights);
/* Map a rule on [-1, 1] to [a, b] in place. */
void gm_quadrature_map(size_t n, double a, double b, double *nodes, double *weights);

/* Filon–Lobatto quadrature of oscillatory integrals (Iserles & Nørsett 2005; seed 001 §5.7):
 *   ∫_0^1 f(x) e^{iκx} dx ≈ Σ_k (b_re[k] + i b_im[k]) f(c_k),   b_k = ∫_0^1 l_k(x) e^{iκx} dx,
 * c_k the n Gauss–Lobatto nodes on [0, 1] (written), l_k their Lagrange polynomials. Exact for
 * f a polynomial of degree n − 1, for every κ. 2 ≤ n ≤ 8 (GM_EINVAL otherwise). The weights come
 * from a 40-point Gauss–Legendre rule for |κ| ≤ 20 and from the moment recurrence of
 * ∫ y^j e^{iθy} on [−1, 1] above, where it is stable. */
gm_status gm_filon_lobatto_weights(size_t n, double kappa, double *nodes, double *b_re,
                                   double *b_im);
/* ∫_a^b f(t) e^{iωt} dt by one n-point Filon–Lobatto panel; real and imaginary parts. */
gm_status gm_filon_lobatto(size_t n, double a, double b, double omega,
                           double (*f)(void *ctx, double t), void *ctx, double *re, double *im);

/* ---- Lagrange bases on arbitrary nodes ------------------------------------------------- */

/* Barycentric weights w_j = 1 / prod_{k != j}(x_j - x_k) of n distinct nodes.
 * GM_EINVAL when two nodes coincide; GM_EDOMAIN when the weights overflow (extreme n).
 * The functions below rescale internally (Berrut & Trefethen 2004) and share these errors. */
gm_status gm_lagrange_weights(size_t n, const double *nodes, double *weights);
/* Values l_j(x) of the n Lagrange basis polynomials at x (exact 0/1 at the nodes). */
gm_status gm_lagrange_basis(size_t n, const double *nodes, double x, double *values);
/* Derivatives l_j'(x) at x. */
gm_status gm_lagrange_basis_derivative(size_t n, const double *nodes, double x, double *values);
/* Differentiation matrix D (n×n row-major): D[i*n+j] = l_j'(x_i); rows sum to zero. */
gm_status gm_differentiation_matrix(size_t n, const double *nodes, double *d);

#ifdef __cplusplus
}
#endif
#endif
