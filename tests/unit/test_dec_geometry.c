/* Geometry and Hodge stars: closed forms on the regular triangle and tetrahedron, the cotangent
 * formula, volume identities, ⋆⋆ = ±1, boundary duals, Whitney mass matrices, bad simplices. */
#include <string.h>

#include "dec_util.h"

static gm_complex *single(size_t N, size_t n, const double *x) {
  size_t t[4] = {0, 1, 2, 3};
  gm_complex *cx = NULL;
  cr_assert_eq(gm_complex_create(N, n + 1, x, n, 1, t, &cx, NULL), GM_OK);
  return cx;
}

Test(dec_geometry, regular_triangle_in_space_matches_closed_forms) {
  const double a = 1.3;
  /* an equilateral triangle tilted in R^3 */
  double x[9] = {0, 0, 0, a, 0, 0, a / 2, a * sqrt(3.0) / 2, 0};
  const double c = cos(0.7), s = sin(0.7);
  for (int v = 0; v < 3; ++v) { /* rotate about the x axis and translate */
    double y = x[3 * v + 1], z = x[3 * v + 2];
    x[3 * v + 1] = c * y - s * z + 5.0;
    x[3 * v + 2] = s * y + c * z - 2.0;
  }
  gm_complex *cx = single(3, 2, x);
  gm_geometry *g = test_geometry(cx);
  const double area = sqrt(3.0) / 4 * a * a;
  for (size_t v = 0; v < 3; ++v)
    cr_expect_float_eq(gm_geometry_hodge_star(g, 0)[v], area / 3, 1e-14);
  for (size_t e = 0; e < 3; ++e)
    cr_expect_float_eq(gm_geometry_hodge_star(g, 1)[e], 1.0 / (2.0 * sqrt(3.0)), 1e-14);
  cr_expect_float_eq(gm_geometry_hodge_star(g, 2)[0], 1.0 / area, 1e-14);
  gm_geometry_free(g);
  gm_complex_free(cx);
}

Test(dec_geometry, regular_tetrahedron_matches_closed_forms) {
  const double a = 0.8;
  const double x[12] = {a, a, a, a, -a, -a, -a, a, -a, -a, -a, a}; /* edge 2√2 a */
  const double e = 2.0 * sqrt(2.0) * a;
  gm_complex *cx = single(3, 3, x);
  gm_geometry *g = test_geometry(cx);
  const double vol = e * e * e / (6.0 * sqrt(2.0));
  const double r_in = e / (2.0 * sqrt(6.0)), r_face = e / (2.0 * sqrt(3.0));
  for (size_t v = 0; v < 4; ++v) cr_expect_float_eq(gm_geometry_hodge_star(g, 0)[v], vol / 4, 1e-14);
  /* |⋆e ∩ T| = two right triangles with legs r_face and r_in */
  for (size_t k = 0; k < 6; ++k)
    cr_expect_float_eq(gm_geometry_hodge_star(g, 1)[k], r_face * r_in / e, 1e-14);
  for (size_t f = 0; f < 4; ++f)
    cr_expect_float_eq(gm_geometry_hodge_star(g, 2)[f], r_in / (sqrt(3.0) / 4 * e * e), 1e-14);
  cr_expect_float_eq(gm_geometry_hodge_star(g, 3)[0], 1.0 / vol, 1e-14);
  gm_geometry_free(g);
  gm_complex_free(cx);
}

/* Σ_σ |σ| |⋆σ| = C(n, k) |K| for every k, with signed dual volumes (each top simplex is cut into
 * C(n, k) layers of pyramids over its k-faces). */
static void check_volume_identity(const gm_geometry *g, double tol) {
  const gm_complex *cx = gm_geometry_complex(g);
  const size_t n = gm_complex_dim(cx);
  double total = 0.0;
  for (size_t t = 0; t < gm_complex_count(cx, n); ++t) total += gm_geometry_primal_volumes(g, n)[t];
  static const double binom[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
  for (size_t k = 0; k <= n; ++k) {
    double s = 0.0;
    for (size_t i = 0; i < gm_complex_count(cx, k); ++i)
      s += gm_geometry_primal_volumes(g, k)[i] * gm_geometry_dual_volumes(g, k)[i];
    cr_expect(fabs(s - binom[n][k] * total) <= tol * total, "k = %zu: %.17g vs %.17g", k, s,
              binom[n][k] * total);
  }
}

Test(dec_geometry, volume_identity_on_perturbed_meshes) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_rectangle(0, 2, 0, 1, 12, 7, GM_DIAGONAL_ALTERNATE, &m, NULL), GM_OK);
  gm_complex *cx = test_complex(m);
  test_jiggle(m, cx, 1.0 / 7, 0.25, 11);
  gm_complex_free(cx);
  cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  cr_expect_gt(gm_geometry_negative_duals(g, 1), 0, "the perturbed mesh should have obtuse pairs");
  check_volume_identity(g, 1e-13);
  gm_geometry_free(g), gm_complex_free(cx), gm_mesh_free(m);
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_box(lo, hi, 4, 4, 4, GM_BOX_FIVE, &m, NULL), GM_OK);
  cx = test_complex(m);
  test_jiggle(m, cx, 0.25, 0.15, 5);
  gm_complex_free(cx);
  cx = test_complex(m);
  g = test_geometry(cx);
  check_volume_identity(g, 1e-13);
  gm_geometry_free(g), gm_complex_free(cx), gm_mesh_free(m);
}

static double cot_at(const double *a, const double *b, const double *c) {
  double u[3], v[3];
  for (int j = 0; j < 3; ++j) u[j] = b[j] - a[j], v[j] = c[j] - a[j];
  double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
  return (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) / sqrt(x * x + y * y + z * z);
}

/* ⋆_1 = ½ (cot α + cot β) (Pinkall–Polthier 1993; Meyer et al. 2003): the DEC 0-form Laplacian
 * d_0ᵀ ⋆_1 d_0 is the cotangent Laplacian. */
static void check_cotan(const gm_mesh *m) {
  gm_complex *cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  const size_t ne = gm_complex_count(cx, 1);
  double *cot = calloc(ne, sizeof(double));
  double p[3][3];
  for (size_t t = 0; t < gm_complex_count(cx, 2); ++t) {
    const size_t *s = gm_complex_simplices(cx, 2) + 3 * t;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) p[i][j] = j < (int)m->N ? m->x[m->N * s[i] + (size_t)j] : 0.0;
    }
    for (int i = 0; i < 3; ++i) {
      size_t ends[2] = {s[(i + 1) % 3], s[(i + 2) % 3]};
      size_t e = gm_complex_find(cx, 1, ends);
      cot[e] += 0.5 * cot_at(p[i], p[(i + 1) % 3], p[(i + 2) % 3]);
    }
  }
  double err = 0.0, scale = 0.0;
  for (size_t e = 0; e < ne; ++e) {
    err = fmax(err, fabs(cot[e] - gm_geometry_hodge_star(g, 1)[e]));
    scale = fmax(scale, fabs(cot[e]));
  }
  cr_expect_leq(err, 1e-12 * scale, "cotangent mismatch %.3g (scale %.3g)", err, scale);
  /* and the assembled Laplacian has off-diagonal entries −⋆_1 */
  gm_csr *L = NULL;
  cr_assert_eq(gm_dec_stiffness(g, 0, &L, NULL), GM_OK);
  const size_t *ev = gm_complex_simplices(cx, 1);
  double err2 = 0.0;
  for (size_t e = 0; e < ne; ++e) err2 = fmax(err2, fabs(gm_csr_get(L, ev[2 * e], ev[2 * e + 1]) + cot[e]));
  cr_expect_leq(err2, 1e-12 * scale);
  gm_csr_free(L);
  free(cot);
  gm_geometry_free(g);
  gm_complex_free(cx);
}

Test(dec_geometry, laplacian_equals_cotangent_laplacian) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_rectangle(-1, 1, 0, 1, 9, 6, GM_DIAGONAL_ALTERNATE, &m, NULL), GM_OK);
  gm_complex *cx = test_complex(m);
  test_jiggle(m, cx, 1.0 / 6, 0.3, 3);
  gm_complex_free(cx);
  check_cotan(m);
  gm_mesh_free(m);
  cr_assert_eq(gm_mesh_icosphere(2.0, 2, &m, NULL), GM_OK);
  check_cotan(m);
  gm_mesh_free(m);
  cr_assert_eq(gm_mesh_torus(1.0, 0.4, 14, 8, &m, NULL), GM_OK);
  check_cotan(m);
  gm_mesh_free(m);
}

Test(dec_geometry, double_star_sign_on_well_centred_meshes) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_icosphere(1.0, 2, &m, NULL), GM_OK);
  gm_complex *cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  for (size_t k = 0; k <= 2; ++k) {
    cr_expect_eq(gm_geometry_negative_duals(g, k), 0, "icosphere is well-centred");
    double sign = (k * (2 - k)) % 2 ? -1.0 : 1.0;
    for (size_t i = 0; i < gm_complex_count(cx, k); ++i) {
      double ss = gm_geometry_hodge_star(g, k)[i] * gm_geometry_dual_hodge_star(g, k, i);
      cr_expect(fabs(ss - sign) <= 4e-16, "k=%zu: ⋆⋆ = %.17g", k, ss);
    }
  }
  gm_geometry_free(g), gm_complex_free(cx), gm_mesh_free(m);
  /* a single regular tetrahedron is well-centred: ⋆⋆ = (−1)^{k(3−k)} = +1 for all k */
  const double x[12] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
  cx = single(3, 3, x);
  g = test_geometry(cx);
  for (size_t k = 0; k <= 3; ++k)
    for (size_t i = 0; i < gm_complex_count(cx, k); ++i)
      cr_expect(fabs(gm_geometry_hodge_star(g, k)[i] * gm_geometry_dual_hodge_star(g, k, i) - 1.0) <= 4e-16);
  gm_geometry_free(g), gm_complex_free(cx);
}

Test(dec_geometry, boundary_dual_volumes) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_rectangle(0, 3, 0, 2, 6, 4, GM_DIAGONAL_RIGHT, &m, NULL), GM_OK);
  gm_complex *cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  const double *bd = gm_geometry_boundary_dual_volumes(g, 0);
  const unsigned char *b = gm_complex_boundary_mask(cx, 0);
  double perimeter = 0.0;
  for (size_t v = 0; v < m->n_vertices; ++v) {
    perimeter += bd[v];
    if (!b[v]) cr_expect_eq(bd[v], 0.0);
  }
  cr_expect_float_eq(perimeter, 10.0, 1e-13);
  /* corner vertex (0,0): half of each adjacent boundary edge */
  cr_expect_float_eq(bd[0], 0.25 + 0.25, 1e-14);
  /* total dual area = area of the rectangle: the dual is restricted to the domain */
  double area = 0.0;
  for (size_t v = 0; v < m->n_vertices; ++v) area += gm_geometry_dual_volumes(g, 0)[v];
  cr_expect_float_eq(area, 6.0, 1e-13);
  gm_geometry_free(g), gm_complex_free(cx), gm_mesh_free(m);
}

Test(dec_geometry, barycentric_dual_option) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, 5, 5, GM_DIAGONAL_RIGHT, &m, NULL), GM_OK);
  gm_complex *cx = test_complex(m);
  test_jiggle(m, cx, 0.2, 0.3, 9);
  gm_complex_free(cx);
  cx = test_complex(m);
  gm_geometry_options o = gm_geometry_defaults();
  o.dual = GM_DUAL_BARYCENTRIC;
  gm_geometry *g = NULL;
  cr_assert_eq(gm_geometry_create(cx, &o, &g, NULL), GM_OK);
  /* barycentric dual of a vertex: a third of each triangle around it; all positive */
  double *third = calloc(m->n_vertices, sizeof(double));
  for (size_t t = 0; t < gm_complex_count(cx, 2); ++t)
    for (int i = 0; i < 3; ++i)
      third[gm_complex_simplices(cx, 2)[3 * t + (size_t)i]] += gm_geometry_primal_volumes(g, 2)[t] / 3;
  for (size_t v = 0; v < m->n_vertices; ++v)
    cr_expect_float_eq(gm_geometry_dual_volumes(g, 0)[v], third[v], 1e-14);
  for (size_t k = 0; k <= 2; ++k) cr_expect_eq(gm_geometry_negative_duals(g, k), 0);
  free(third);
  gm_geometry_free(g), gm_complex_free(cx), gm_mesh_free(m);
}

Test(dec_geometry, whitney_mass_matrices) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_rectangle(0, 2, 0, 1, 6, 4, GM_DIAGONAL_ALTERNATE, &m, NULL), GM_OK);
  gm_complex *cx = test_complex(m);
  test_jiggle(m, cx, 0.25, 0.2, 21);
  gm_complex_free(cx);
  cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  const size_t nv = gm_complex_count(cx, 0), ne = gm_complex_count(cx, 1), nt = gm_complex_count(cx, 2);
  gm_csr *M0 = NULL, *M1 = NULL, *M2 = NULL;
  cr_assert_eq(gm_geometry_whitney_mass(g, 0, &M0), GM_OK);
  cr_assert_eq(gm_geometry_whitney_mass(g, 1, &M1), GM_OK);
  cr_assert_eq(gm_geometry_whitney_mass(g, 2, &M2), GM_OK);
  cr_expect_leq(gm_csr_asymmetry(M0), 1e-15);
  cr_expect_leq(gm_csr_asymmetry(M1), 1e-15);
  /* 1ᵀ M0 1 = area; M2 = diag(1/|T|) */
  double *ones = malloc(nv * sizeof(double)), *y = malloc(nv * sizeof(double));
  for (size_t v = 0; v < nv; ++v) ones[v] = 1.0;
  gm_csr_matvec(M0, 1.0, ones, 0.0, y);
  double area = 0.0;
  for (size_t v = 0; v < nv; ++v) area += y[v];
  cr_expect_float_eq(area, 2.0, 1e-13);
  for (size_t t = 0; t < nt; ++t)
    cr_expect_float_eq(gm_csr_get(M2, t, t), 1.0 / gm_geometry_primal_volumes(g, 2)[t], 1e-10);
  /* Whitney 1-forms reproduce constant forms: for ω = 2dx − dy, αᵀ M1 α = ∫|ω|² = 5·area */
  double *alpha = malloc(ne * sizeof(double)), *Ma = malloc(ne * sizeof(double));
  const size_t *e = gm_complex_simplices(cx, 1);
  for (size_t i = 0; i < ne; ++i)
    alpha[i] = 2.0 * (m->x[2 * e[2 * i + 1]] - m->x[2 * e[2 * i]]) -
               (m->x[2 * e[2 * i + 1] + 1] - m->x[2 * e[2 * i] + 1]);
  gm_csr_matvec(M1, 1.0, alpha, 0.0, Ma);
  cr_expect_float_eq(test_dot(ne, alpha, Ma), 5.0 * 2.0, 1e-12);
  free(ones), free(y), free(alpha), free(Ma);
  gm_csr_free(M0), gm_csr_free(M1), gm_csr_free(M2);
  gm_geometry_free(g), gm_complex_free(cx), gm_mesh_free(m);
}

Test(dec_geometry, circumcenter_of_a_thin_triangle_far_from_the_origin) {
  /* a sliver at 1e6 from the origin: relative-to-vertex formulas keep ~1e-7 relative accuracy
   * of the circumcenter offset where absolute-coordinate formulas lose everything */
  const double off = 1e6;
  const double x[6] = {off, off, off + 1.0, off, off + 0.5, off + 1e-3};
  gm_complex *cx = single(2, 2, x);
  gm_geometry *g = test_geometry(cx);
  const double *c = gm_geometry_centers(g, 2);
  /* exact for the represented vertices: height hh (exact difference), y = (hh² − 1/4)/(2 hh) */
  const double hh = x[5] - off;
  double cy = (hh * hh - 0.25) / (2.0 * hh);
  cr_expect_float_eq(c[0] - off, 0.5, 1e-9);
  cr_expect(fabs((c[1] - off) - cy) <= 1e-9 * fabs(cy), "%.17g vs %.17g", c[1] - off, cy);
  gm_geometry_free(g), gm_complex_free(cx);
}

Test(dec_geometry, degenerate_and_inverted_simplices_are_errors) {
  const double flat[6] = {0, 0, 1, 1, 2, 2};
  gm_complex *cx = single(2, 2, flat);
  gm_geometry *g = NULL;
  gm_error err = {{0}};
  cr_expect_eq(gm_geometry_create(cx, NULL, &g, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "degenerate triangle 0") != NULL, "%s", err.message);
  gm_complex_free(cx);
  /* a fold: the middle vertex of a strip pushed across so that one triangle flips */
  const double x[10] = {0, 0, 1, 0, 0, 1, 1, 1, 2.5, 0.5};
  const size_t t[9] = {0, 1, 2, 1, 3, 2, 1, 4, 3};
  cr_assert_eq(gm_complex_create(2, 5, x, 2, 3, t, &cx, NULL), GM_OK);
  double y[10];
  memcpy(y, x, sizeof y);
  cr_expect_eq(gm_geometry_create(cx, NULL, &g, &err), GM_OK, "%s", err.message);
  gm_geometry_free(g);
  gm_complex_free(cx);
  y[8] = 0.7, y[9] = 0.5; /* vertex 4 moved across edge (1,3): triangle (1,4,3) folds over */
  cr_assert_eq(gm_complex_create(2, 5, y, 2, 3, t, &cx, NULL), GM_OK);
  cr_expect_eq(gm_geometry_create(cx, NULL, &g, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "inverted") != NULL, "%s", err.message);
  gm_geometry_options o = gm_geometry_defaults();
  o.allow_inverted = 1;
  cr_expect_eq(gm_geometry_create(cx, &o, &g, &err), GM_OK);
  cr_expect_eq(gm_geometry_inverted_count(g), 1);
  gm_geometry_free(g);
  gm_complex_free(cx);
}
