/* Simplex quadrature, the de Rham map (commutes with d), Whitney interpolation (R∘W = I,
 * constants reproduced), interior product (exact for constant forms and linear fields), Lie
 * derivative (flow and Cartan agree where they must, and converge to the smooth L_X ω). */
#include <string.h>

#include "dec_util.h"

static double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

Test(dec_quadrature, monomials_exact_up_to_the_degree) {
  for (size_t k = 1; k <= 3; ++k)
    for (size_t deg = 0; deg <= 9; ++deg) {
      size_t np = 0;
      cr_assert_eq(gm_simplex_quadrature(k, deg, &np, NULL, NULL), GM_OK);
      double *bary = malloc(np * (k + 1) * sizeof(double)), *w = malloc(np * sizeof(double));
      cr_assert_eq(gm_simplex_quadrature(k, deg, &np, bary, w), GM_OK);
      for (int a = 0; a <= (int)deg; ++a)
        for (int b = 0; a + b <= (int)deg && (k >= 2 || b == 0); ++b)
          for (int c = 0; a + b + c <= (int)deg && (k >= 3 || c == 0); ++c) {
            double s = 0.0;
            for (size_t q = 0; q < np; ++q) {
              const double *l = bary + q * (k + 1);
              double v = pow(l[1], a);
              if (k >= 2) v *= pow(l[2], b);
              if (k >= 3) v *= pow(l[3], c);
              s += w[q] * v;
            }
            s /= factorial((int)k);
            double exact = factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + (int)k);
            cr_expect_leq(fabs(s - exact), 1e-15 + 1e-13 * exact, "k=%zu deg=%zu x^%d y^%d z^%d: %.17g vs %.17g",
                          k, deg, a, b, c, s, exact);
          }
      free(bary), free(w);
    }
}

/* ---- de Rham map ------------------------------------------------------------------------- */

static int f_scalar(void *ctx, const double *x, const double *u, double *v) {
  (void)ctx, (void)u;
  *v = sin(x[0] + 0.5) * exp(0.7 * x[1]) * cos(x[2]);
  return 0;
}
static int f_gradient(void *ctx, const double *x, const double *u, double *v) {
  (void)ctx;
  double s = sin(x[0] + 0.5), c = cos(x[0] + 0.5), e = exp(0.7 * x[1]);
  double g[3] = {c * e * cos(x[2]), 0.7 * s * e * cos(x[2]), -s * e * sin(x[2])};
  *v = g[0] * u[0] + g[1] * u[1] + g[2] * u[2];
  return 0;
}
/* η = (y z, sin x, x y²) dx,dy,dz components; dη as a 2-form on (u, w) */
static int f_eta(void *ctx, const double *x, const double *u, double *v) {
  (void)ctx;
  double e[3] = {x[1] * x[2], sin(x[0]), x[0] * x[1] * x[1]};
  *v = e[0] * u[0] + e[1] * u[1] + e[2] * u[2];
  return 0;
}
static int f_deta(void *ctx, const double *x, const double *u, double *v) {
  (void)ctx;
  /* (dη)_ij = ∂_i η_j − ∂_j η_i */
  double J[3][3] = {{0, cos(x[0]), x[1] * x[1]}, {x[2], 0, 2 * x[0] * x[1]}, {x[1], 0, 0}};
  /* J[i][j] = ∂_i η_j */
  const double *a = u, *b = u + 3;
  double s = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s += (J[i][j] - J[j][i]) * a[i] * b[j];
  *v = s;
  return 0;
}

Test(dec_de_rham, commutes_with_d) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_box(lo, hi, 3, 3, 3, GM_BOX_KUHN, &m, &err), GM_OK);
  gm_complex *cx = test_complex(m);
  test_jiggle(m, cx, 1.0 / 3, 0.15, 3);
  gm_complex_free(cx);
  cx = test_complex(m);
  size_t nv = gm_complex_count(cx, 0), ne = gm_complex_count(cx, 1), nf = gm_complex_count(cx, 2);
  double *f = malloc(nv * sizeof(double)), *df = malloc(ne * sizeof(double)),
         *rdf = malloc(ne * sizeof(double));
  cr_assert_eq(gm_dec_de_rham(cx, 0, f_scalar, NULL, 0, f, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_dec_de_rham(cx, 1, f_gradient, NULL, 14, rdf, &err), GM_OK, "%s", err.message);
  gm_csr_matvec(gm_complex_d(cx, 0), 1.0, f, 0.0, df);
  double worst = 0.0;
  for (size_t i = 0; i < ne; ++i) worst = fmax(worst, fabs(df[i] - rdf[i]));
  cr_expect_leq(worst, 1e-14, "|d R f − R df| = %.3g", worst);
  double *eta = malloc(ne * sizeof(double)), *deta = malloc(nf * sizeof(double)),
         *rdeta = malloc(nf * sizeof(double));
  cr_assert_eq(gm_dec_de_rham(cx, 1, f_eta, NULL, 6, eta, &err), GM_OK);
  cr_assert_eq(gm_dec_de_rham(cx, 2, f_deta, NULL, 6, rdeta, &err), GM_OK);
  gm_csr_matvec(gm_complex_d(cx, 1), 1.0, eta, 0.0, deta);
  worst = 0.0;
  for (size_t i = 0; i < nf; ++i) worst = fmax(worst, fabs(deta[i] - rdeta[i]));
  cr_expect_leq(worst, 1e-13, "|d R η − R dη| = %.3g", worst);
  /* low degree is not enough: the check above is not vacuous */
  cr_assert_eq(gm_dec_de_rham(cx, 1, f_gradient, NULL, 1, rdf, &err), GM_OK);
  worst = 0.0;
  for (size_t i = 0; i < ne; ++i) worst = fmax(worst, fabs(df[i] - rdf[i]));
  cr_expect_geq(worst, 1e-6, "degree-1 quadrature error %.3g", worst);
  free(f), free(df), free(rdf), free(eta), free(deta), free(rdeta);
  gm_complex_free(cx);
  gm_mesh_free(m);
}

static int failing_form(void *ctx, const double *x, const double *u, double *v) {
  (void)ctx, (void)u, (void)x;
  *v = 0.0;
  return 7;
}

Test(dec_de_rham, callback_failure_is_reported) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, 2, 2, GM_DIAGONAL_RIGHT, &m, &err), GM_OK);
  gm_complex *cx = test_complex(m);
  double out[64];
  cr_expect_eq(gm_dec_de_rham(cx, 1, failing_form, NULL, 2, out, &err), GM_ECALLBACK);
  cr_expect(strstr(err.message, "returned 7") != NULL, "%s", err.message);
  gm_complex_free(cx);
  gm_mesh_free(m);
}

/* ---- Whitney interpolation ------------------------------------------------------------------ */

/* ω(u_1..u_k) from the components ω_I (I ascending, lexicographic). */
static double eval_components(size_t N, size_t k, const double *comp, const double *u) {
  if (k == 0) return comp[0];
  size_t idx[3] = {0, 1, 2}, q = 0;
  double total = 0.0;
  for (;;) {
    double a[3][3];
    for (size_t i = 0; i < k; ++i)
      for (size_t m = 0; m < k; ++m) a[i][m] = u[m * N + idx[i]];
    double det = k == 1 ? a[0][0]
                 : k == 2 ? a[0][0] * a[1][1] - a[0][1] * a[1][0]
                          : a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                                a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                                a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    total += comp[q++] * det;
    size_t i = k;
    while (i-- > 0 && idx[i] == N - k + i) {
    }
    if (i == SIZE_MAX) break;
    ++idx[i];
    for (size_t j = i + 1; j < k; ++j) idx[j] = idx[j - 1] + 1;
  }
  return total;
}

/* ∫ over each local k-face of each top simplex of W_T(α) equals α on that face. */
static void check_de_rham_of_whitney(const gm_complex *cx, size_t k) {
  const size_t n = gm_complex_dim(cx), N = gm_complex_embedding_dim(cx), nk = gm_complex_count(cx, k);
  double *a = malloc(nk * sizeof(double));
  test_random_fill(nk, a, 77 + k);
  size_t np = 0;
  gm_simplex_quadrature(k, 2, &np, NULL, NULL);
  double *qb = malloc(np * (k + 1) * sizeof(double)), *qw = malloc(np * sizeof(double));
  gm_simplex_quadrature(k, 2, &np, qb, qw);
  const size_t *tops = gm_complex_simplices(cx, n);
  const double *x = gm_complex_coordinates(cx);
  const signed char *orient = gm_complex_orientation(cx);
  double worst = 0.0;
  size_t nl = 0, idx[6];
  for (size_t T = 0; T < gm_complex_count(cx, n); ++T) {
    gm_complex_local_faces(cx, T, k, idx);
    nl = 0;
    for (unsigned mask = 1; mask < (1u << (n + 1)); ++mask) {
      if ((size_t)__builtin_popcount(mask) != k + 1) continue;
      size_t pos[4], q = 0;
      for (size_t v = 0; v <= n; ++v)
        if (mask & (1u << v)) pos[q++] = v;
      size_t face[4];
      for (size_t i = 0; i <= k; ++i) face[i] = tops[T * (n + 1) + pos[i]];
      size_t f = gm_complex_find(cx, k, face);
      double u[9];
      for (size_t i = 1; i <= k; ++i)
        for (size_t j = 0; j < N; ++j) u[(i - 1) * N + j] = x[face[i] * N + j] - x[face[0] * N + j];
      double s = 0.0;
      for (size_t qq = 0; qq < np; ++qq) {
        double bary[4] = {0, 0, 0, 0}, comp[3];
        for (size_t i = 0; i <= k; ++i) bary[pos[i]] = qb[qq * (k + 1) + i];
        cr_assert_eq(gm_dec_whitney_interpolate(cx, k, a, T, bary, comp), GM_OK);
        s += qw[qq] * eval_components(N, k, comp, u);
      }
      s /= factorial((int)k);
      double expect = a[f] * (k == n ? orient[f] : 1);
      worst = fmax(worst, fabs(s - expect));
      ++nl;
    }
  }
  cr_expect_leq(worst, 1e-13, "k=%zu: |R W α − α| = %.3g", k, worst);
  free(a), free(qb), free(qw);
}

Test(dec_whitney, de_rham_of_whitney_is_identity) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_box(lo, hi, 2, 2, 2, GM_BOX_FIVE, &m, &err), GM_OK);
  gm_complex *cx = test_complex(m);
  for (size_t k = 0; k <= 3; ++k) check_de_rham_of_whitney(cx, k);
  gm_complex_free(cx);
  gm_mesh_free(m);
  cr_assert_eq(gm_mesh_icosphere(1.0, 1, &m, &err), GM_OK);
  cx = test_complex(m);
  for (size_t k = 0; k <= 2; ++k) check_de_rham_of_whitney(cx, k);
  gm_complex_free(cx);
  gm_mesh_free(m);
}

static int const_two_form(void *ctx, const double *x, const double *u, double *v) {
  const double *w = ctx; /* components w01, w02, w12 */
  (void)x;
  const double *a = u, *b = u + 3;
  *v = w[0] * (a[0] * b[1] - a[1] * b[0]) + w[1] * (a[0] * b[2] - a[2] * b[0]) +
       w[2] * (a[1] * b[2] - a[2] * b[1]);
  return 0;
}

Test(dec_whitney, constant_forms_are_reproduced) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 2, 1};
  cr_assert_eq(gm_mesh_box(lo, hi, 2, 2, 2, GM_BOX_KUHN, &m, &err), GM_OK);
  gm_complex *cx = test_complex(m);
  const double w[3] = {0.4, -1.1, 2.3};
  size_t nf = gm_complex_count(cx, 2);
  double *a = malloc(nf * sizeof(double));
  cr_assert_eq(gm_dec_de_rham(cx, 2, const_two_form, (void *)w, 0, a, &err), GM_OK);
  double worst = 0.0;
  for (size_t T = 0; T < gm_complex_count(cx, 3); T += 7) {
    const double bary[4] = {0.1, 0.2, 0.3, 0.4};
    double comp[3];
    cr_assert_eq(gm_dec_whitney_interpolate(cx, 2, a, T, bary, comp), GM_OK);
    for (int i = 0; i < 3; ++i) worst = fmax(worst, fabs(comp[i] - w[i]));
  }
  cr_expect_leq(worst, 1e-13, "constant 2-form: %.3g", worst);
  free(a);
  gm_complex_free(cx);
  gm_mesh_free(m);
}

/* ---- interior product and Lie derivative ---------------------------------------------------- */

/* linear field X = B x + b */
static const double B2[2][2] = {{0.3, -0.8}, {0.5, 0.2}}, b2[2] = {0.7, -0.4};
static void linear_field(const gm_complex *cx, double *X) {
  const double *x = gm_complex_coordinates(cx);
  for (size_t v = 0; v < gm_complex_count(cx, 0); ++v)
    for (int i = 0; i < 2; ++i)
      X[2 * v + i] = B2[i][0] * x[2 * v] + B2[i][1] * x[2 * v + 1] + b2[i];
}

static gm_geometry *jiggled_geometry(size_t n, gm_complex **cxo, gm_mesh **mo) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, n, n, GM_DIAGONAL_ACUTE, &m, &err), GM_OK);
  gm_complex *cx = test_complex(m);
  test_jiggle(m, cx, 1.0 / (double)n, 0.15, 12);
  gm_complex_free(cx);
  cx = test_complex(m);
  *cxo = cx;
  *mo = m;
  return test_geometry(cx);
}

static int const_one_form(void *ctx, const double *x, const double *u, double *v) {
  const double *a = ctx;
  (void)x;
  *v = a[0] * u[0] + a[1] * u[1];
  return 0;
}
static int area_form(void *ctx, const double *x, const double *u, double *v) {
  (void)x;
  *v = *(const double *)ctx * (u[0] * u[3] - u[1] * u[2]);
  return 0;
}

Test(dec_interior_product, exact_for_constant_forms_and_linear_fields) {
  gm_complex *cx;
  gm_mesh *m;
  gm_geometry *g = jiggled_geometry(5, &cx, &m);
  gm_error err = {{0}};
  const size_t nv = gm_complex_count(cx, 0), ne = gm_complex_count(cx, 1), nt = gm_complex_count(cx, 2);
  const double *x = gm_complex_coordinates(cx);
  double *X = malloc(2 * nv * sizeof(double)), *a1 = malloc(ne * sizeof(double));
  double *a2 = malloc(nt * sizeof(double)), *r0 = malloc(nv * sizeof(double)), *r1 = malloc(ne * sizeof(double));
  linear_field(cx, X);
  const double c1[2] = {1.3, -0.6}, c2 = 2.5;
  cr_assert_eq(gm_dec_de_rham(cx, 1, const_one_form, (void *)c1, 0, a1, &err), GM_OK);
  cr_assert_eq(gm_dec_de_rham(cx, 2, area_form, (void *)&c2, 0, a2, &err), GM_OK);
  cr_assert_eq(gm_dec_interior_product(g, 1, X, a1, r0, &err), GM_OK, "%s", err.message);
  double worst = 0.0;
  for (size_t v = 0; v < nv; ++v) worst = fmax(worst, fabs(r0[v] - (c1[0] * X[2 * v] + c1[1] * X[2 * v + 1])));
  cr_expect_leq(worst, 1e-13, "i_X of a constant 1-form: %.3g", worst);
  /* i_X (c dx∧dy) = c (X_1 dy − X_2 dx), on an edge: c (X̄_1 E_y − X̄_2 E_x), X̄ at the midpoint */
  cr_assert_eq(gm_dec_interior_product(g, 2, X, a2, r1, &err), GM_OK, "%s", err.message);
  const size_t *e = gm_complex_simplices(cx, 1);
  worst = 0.0;
  for (size_t i = 0; i < ne; ++i) {
    size_t p = e[2 * i], q = e[2 * i + 1];
    double Xm0 = 0.5 * (X[2 * p] + X[2 * q]), Xm1 = 0.5 * (X[2 * p + 1] + X[2 * q + 1]);
    double ex = c2 * (Xm0 * (x[2 * q + 1] - x[2 * p + 1]) - Xm1 * (x[2 * q] - x[2 * p]));
    worst = fmax(worst, fabs(r1[i] - ex));
  }
  cr_expect_leq(worst, 1e-13, "i_X of a constant 2-form: %.3g", worst);
  /* non-finite field refused */
  X[3] = NAN;
  cr_expect_eq(gm_dec_interior_product(g, 1, X, a1, r0, &err), GM_EDOMAIN);
  free(X), free(a1), free(a2), free(r0), free(r1);
  gm_geometry_free(g);
  gm_complex_free(cx);
  gm_mesh_free(m);
}

Test(dec_lie_derivative, flow_and_cartan_agree_on_functions_and_densities) {
  gm_complex *cx;
  gm_mesh *m;
  gm_geometry *g = jiggled_geometry(5, &cx, &m);
  gm_error err = {{0}};
  const size_t nv = gm_complex_count(cx, 0), nt = gm_complex_count(cx, 2);
  double *X = malloc(2 * nv * sizeof(double)), *f = malloc(nv * sizeof(double));
  double *la = malloc(nv * sizeof(double)), *lc = malloc(nv * sizeof(double));
  linear_field(cx, X);
  test_random_fill(nv, f, 5);
  cr_assert_eq(gm_dec_lie_derivative(g, 0, X, f, GM_LIE_ALGEBRAIC, la, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_dec_lie_derivative(g, 0, X, f, GM_LIE_CARTAN, lc, &err), GM_OK, "%s", err.message);
  double worst = 0.0;
  for (size_t v = 0; v < nv; ++v) worst = fmax(worst, fabs(la[v] - lc[v]));
  cr_expect_leq(worst, 1e-12 * test_max_abs(nv, la), "0-forms: flow vs Cartan %.3g", worst);
  /* linear f: X·∇f exactly */
  const double *x = gm_complex_coordinates(cx);
  for (size_t v = 0; v < nv; ++v) f[v] = 2.0 * x[2 * v] - 3.0 * x[2 * v + 1] + 1.0;
  cr_assert_eq(gm_dec_lie_derivative(g, 0, X, f, GM_LIE_ALGEBRAIC, la, &err), GM_OK);
  worst = 0.0;
  for (size_t v = 0; v < nv; ++v) worst = fmax(worst, fabs(la[v] - (2.0 * X[2 * v] - 3.0 * X[2 * v + 1])));
  cr_expect_leq(worst, 1e-13, "L_X of a linear function: %.3g", worst);
  /* uniform density c dx∧dy: L_X = c div X |T| = c tr(B) |T| */
  double *a = malloc(nt * sizeof(double)), *ta = malloc(nt * sizeof(double)), *tc = malloc(nt * sizeof(double));
  const double c2 = 1.7;
  cr_assert_eq(gm_dec_de_rham(cx, 2, area_form, (void *)&c2, 0, a, &err), GM_OK);
  cr_assert_eq(gm_dec_lie_derivative(g, 2, X, a, GM_LIE_ALGEBRAIC, ta, &err), GM_OK);
  cr_assert_eq(gm_dec_lie_derivative(g, 2, X, a, GM_LIE_CARTAN, tc, &err), GM_OK);
  const double *vol = gm_geometry_primal_volumes(g, 2);
  const signed char *o = gm_complex_orientation(cx);
  double wa = 0.0, wc = 0.0;
  for (size_t t = 0; t < nt; ++t) {
    double ex = c2 * (B2[0][0] + B2[1][1]) * vol[t] * o[t] * (a[t] * o[t] > 0 ? 1 : -1);
    wa = fmax(wa, fabs(ta[t] - ex) / vol[t]);
    wc = fmax(wc, fabs(tc[t] - ex) / vol[t]);
  }
  cr_expect_leq(wa, 1e-12, "top forms, flow: %.3g", wa);
  cr_expect_leq(wc, 1e-12, "top forms, Cartan: %.3g", wc);
  free(X), free(f), free(la), free(lc), free(a), free(ta), free(tc);
  gm_geometry_free(g);
  gm_complex_free(cx);
  gm_mesh_free(m);
}

/* ω = sin y dx + cos x dy, X = (1 + y/2, 0.3 x): L_X ω = (∂_x g − c X_2) dx + (∂_y g + c X_1) dy
 * with g = i_X ω, c = ∂_x ω_y − ∂_y ω_x. */
static int omega(void *ctx, const double *x, const double *u, double *v) {
  (void)ctx;
  *v = sin(x[1]) * u[0] + cos(x[0]) * u[1];
  return 0;
}
static int lie_omega(void *ctx, const double *x, const double *u, double *v) {
  (void)ctx;
  double X1 = 1 + 0.5 * x[1], X2 = 0.3 * x[0];
  double c = -sin(x[0]) - cos(x[1]);
  double gx = 0.3 * cos(x[0]) - X2 * sin(x[0]), gy = 0.5 * sin(x[1]) + X1 * cos(x[1]);
  *v = (gx - c * X2) * u[0] + (gy + c * X1) * u[1];
  return 0;
}

static void lie_errors(size_t n, double *err_flow, double *err_cartan, double *diff) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, n, n, GM_DIAGONAL_ACUTE, &m, &err), GM_OK);
  gm_complex *cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  const size_t nv = gm_complex_count(cx, 0), ne = gm_complex_count(cx, 1);
  const double *x = gm_complex_coordinates(cx);
  double *X = malloc(2 * nv * sizeof(double)), *a = malloc(ne * sizeof(double)),
         *ex = malloc(ne * sizeof(double)), *la = malloc(ne * sizeof(double)),
         *lc = malloc(ne * sizeof(double));
  for (size_t v = 0; v < nv; ++v) {
    X[2 * v] = 1 + 0.5 * x[2 * v + 1];
    X[2 * v + 1] = 0.3 * x[2 * v];
  }
  cr_assert_eq(gm_dec_de_rham(cx, 1, omega, NULL, 8, a, &err), GM_OK);
  cr_assert_eq(gm_dec_de_rham(cx, 1, lie_omega, NULL, 8, ex, &err), GM_OK);
  cr_assert_eq(gm_dec_lie_derivative(g, 1, X, a, GM_LIE_ALGEBRAIC, la, &err), GM_OK);
  cr_assert_eq(gm_dec_lie_derivative(g, 1, X, a, GM_LIE_CARTAN, lc, &err), GM_OK);
  /* edges away from the boundary (both ends at distance >= 0.2), relative to the edge length */
  const size_t *e = gm_complex_simplices(cx, 1);
  *err_flow = *err_cartan = *diff = 0.0;
  for (size_t i = 0; i < ne; ++i) {
    const double *p = x + 2 * e[2 * i], *q = x + 2 * e[2 * i + 1];
    int inside = 1;
    for (int j = 0; j < 2; ++j)
      inside &= p[j] >= 0.2 && p[j] <= 0.8 && q[j] >= 0.2 && q[j] <= 0.8;
    if (!inside) continue;
    double len = hypot(q[0] - p[0], q[1] - p[1]);
    *err_flow = fmax(*err_flow, fabs(la[i] - ex[i]) / len);
    *err_cartan = fmax(*err_cartan, fabs(lc[i] - ex[i]) / len);
    *diff = fmax(*diff, fabs(la[i] - lc[i]) / len);
  }
  free(X), free(a), free(ex), free(la), free(lc);
  gm_geometry_free(g);
  gm_complex_free(cx);
  gm_mesh_free(m);
}

/* Measured (h = 1/10 -> 1/20, error per unit edge length on interior edges): Cartan 8.7e-4 ->
 * 2.2e-4 (second order on this structured mesh), flow 0.386 -> 0.393 (no convergence: the flow
 * derivative of the Whitney interpolant takes the endpoint values i_X α̃(v) from the two cofaces
 * of the edge only, whose O(h) errors differ between the ends by O(h); Cartan averages them
 * over the whole star of v, where the error is a smooth function of v). */
Test(dec_lie_derivative, one_forms_cartan_converges_flow_does_not) {
  double f1, c1, d1, f2, c2, d2;
  lie_errors(10, &f1, &c1, &d1);
  lie_errors(20, &f2, &c2, &d2);
  cr_log_info("flow %.3g -> %.3g, Cartan %.3g -> %.3g, difference %.3g -> %.3g", f1, f2, c1, c2, d1, d2);
  cr_expect_leq(c2, 0.3 * c1, "Cartan: %.3g -> %.3g", c1, c2);
  cr_expect_leq(c2, 1e-3, "Cartan: %.3g", c2);
  cr_expect_geq(f2, 0.8 * f1, "flow (documented inconsistency) changed: %.3g -> %.3g", f1, f2);
}
