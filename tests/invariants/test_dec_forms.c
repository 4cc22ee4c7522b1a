/* Wedge products (anticommutativity and Leibniz to round-off, and the failure of Leibniz for the
 * metric-weighted variant), flat and sharp of constant fields, the cone operator
 * (Hd + dH = I, exactness of closed forms, failure on an annulus), and discrete integration by
 * parts with its boundary term (seed 000 eq. 3.8). */
#include <string.h>

#include "dec_util.h"

static gm_mesh *jiggled_rectangle(size_t n, gm_diagonal pattern, double amount, uint64_t seed) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, n, n, pattern, &m, &err), GM_OK, "%s", err.message);
  if (amount > 0) {
    gm_complex *cx = test_complex(m);
    test_jiggle(m, cx, 1.0 / (double)n, amount, seed);
    gm_complex_free(cx);
  }
  return m;
}

static gm_mesh *jiggled_box(size_t n, double amount, uint64_t seed) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_box(lo, hi, n, n, n, GM_BOX_KUHN, &m, &err), GM_OK, "%s", err.message);
  if (amount > 0) {
    gm_complex *cx = test_complex(m);
    test_jiggle(m, cx, 1.0 / (double)n, amount, seed);
    gm_complex_free(cx);
  }
  return m;
}

static double *random_cochain(const gm_complex *cx, size_t k, uint64_t seed) {
  size_t m = gm_complex_count(cx, k);
  double *a = malloc((m ? m : 1) * sizeof(double));
  test_random_fill(m, a, seed);
  return a;
}

/* max |d(α∧β) − dα∧β − (−1)^k α∧dβ| relative to max|d(α∧β)|, for the given wedge */
static double leibniz_defect(const gm_geometry *g, int metric, size_t k, size_t l, uint64_t seed) {
  const gm_complex *cx = gm_geometry_complex(g);
  const size_t p = k + l;
  double *a = random_cochain(cx, k, seed), *b = random_cochain(cx, l, seed + 1);
  size_t mk1 = gm_complex_count(cx, k + 1), ml1 = gm_complex_count(cx, l + 1);
  size_t mp = gm_complex_count(cx, p), mp1 = gm_complex_count(cx, p + 1);
  double *da = malloc(mk1 * sizeof(double)), *db = malloc(ml1 * sizeof(double));
  double *ab = malloc(mp * sizeof(double)), *dab = malloc(mp1 * sizeof(double));
  double *t1 = malloc(mp1 * sizeof(double)), *t2 = malloc(mp1 * sizeof(double));
  gm_csr_matvec(gm_complex_d(cx, k), 1.0, a, 0.0, da);
  gm_csr_matvec(gm_complex_d(cx, l), 1.0, b, 0.0, db);
  if (metric) {
    cr_assert_eq(gm_dec_wedge_circumcentric(g, k, a, l, b, ab), GM_OK);
    cr_assert_eq(gm_dec_wedge_circumcentric(g, k + 1, da, l, b, t1), GM_OK);
    cr_assert_eq(gm_dec_wedge_circumcentric(g, k, a, l + 1, db, t2), GM_OK);
  } else {
    cr_assert_eq(gm_dec_wedge(cx, k, a, l, b, ab), GM_OK);
    cr_assert_eq(gm_dec_wedge(cx, k + 1, da, l, b, t1), GM_OK);
    cr_assert_eq(gm_dec_wedge(cx, k, a, l + 1, db, t2), GM_OK);
  }
  gm_csr_matvec(gm_complex_d(cx, p), 1.0, ab, 0.0, dab);
  double sign = (k & 1) ? -1.0 : 1.0, worst = 0.0;
  for (size_t i = 0; i < mp1; ++i) worst = fmax(worst, fabs(dab[i] - t1[i] - sign * t2[i]));
  double scale = test_max_abs(mp1, dab);
  free(a), free(b), free(da), free(db), free(ab), free(dab), free(t1), free(t2);
  return worst / scale;
}

static double anticommutativity_defect(const gm_geometry *g, int metric, size_t k, size_t l,
                                       uint64_t seed) {
  const gm_complex *cx = gm_geometry_complex(g);
  double *a = random_cochain(cx, k, seed), *b = random_cochain(cx, l, seed + 7);
  size_t mp = gm_complex_count(cx, k + l);
  double *ab = malloc(mp * sizeof(double)), *ba = malloc(mp * sizeof(double));
  if (metric) {
    cr_assert_eq(gm_dec_wedge_circumcentric(g, k, a, l, b, ab), GM_OK);
    cr_assert_eq(gm_dec_wedge_circumcentric(g, l, b, k, a, ba), GM_OK);
  } else {
    cr_assert_eq(gm_dec_wedge(cx, k, a, l, b, ab), GM_OK);
    cr_assert_eq(gm_dec_wedge(cx, l, b, k, a, ba), GM_OK);
  }
  double sign = ((k * l) & 1) ? -1.0 : 1.0, worst = 0.0;
  for (size_t i = 0; i < mp; ++i) worst = fmax(worst, fabs(ab[i] - sign * ba[i]));
  double scale = test_max_abs(mp, ab);
  free(a), free(b), free(ab), free(ba);
  return worst / scale;
}

static void check_wedge_laws(const gm_mesh *m) {
  gm_complex *cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  const size_t n = gm_complex_dim(cx);
  for (size_t k = 0; k <= n; ++k)
    for (size_t l = 0; k + l <= n; ++l) {
      double ac = anticommutativity_defect(g, 0, k, l, 11 + 3 * k + l);
      cr_expect_leq(ac, 1e-15, "n=%zu: α^%zu∧β^%zu anticommutativity defect %.3g", n, k, l, ac);
      double acm = anticommutativity_defect(g, 1, k, l, 17 + 3 * k + l);
      cr_expect_leq(acm, 1e-14, "metric wedge %zu∧%zu anticommutativity defect %.3g", k, l, acm);
      if (k + l + 1 <= n) {
        double lb = leibniz_defect(g, 0, k, l, 23 + 5 * k + l);
        cr_expect_leq(lb, 1e-14, "n=%zu: Leibniz defect for %zu∧%zu: %.3g", n, k, l, lb);
      }
    }
  gm_geometry_free(g);
  gm_complex_free(cx);
}

Test(dec_wedge, laws_on_jiggled_triangles) {
  gm_mesh *m = jiggled_rectangle(6, GM_DIAGONAL_ALTERNATE, 0.2, 5);
  check_wedge_laws(m);
  gm_mesh_free(m);
}

Test(dec_wedge, laws_on_jiggled_tetrahedra) {
  gm_mesh *m = jiggled_box(3, 0.15, 9);
  check_wedge_laws(m);
  gm_mesh_free(m);
}

Test(dec_wedge, laws_on_a_surface) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_icosphere(1.0, 1, &m, &err), GM_OK);
  check_wedge_laws(m);
  gm_mesh_free(m);
}

/* Seed 001 §3.8 (i): the metric-weighted wedge is anticommutative but Leibniz fails on generic
 * triangles (the previous part's analysis; here measured). */
Test(dec_wedge, metric_weighted_variant_breaks_leibniz) {
  gm_mesh *m = jiggled_rectangle(6, GM_DIAGONAL_ALTERNATE, 0.2, 5);
  gm_complex *cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  double d01 = leibniz_defect(g, 1, 0, 1, 3), d00 = leibniz_defect(g, 1, 0, 0, 4);
  cr_expect_geq(d01, 1e-3, "metric wedge 0∧1 Leibniz defect %.3g", d01);
  /* on edges the Voronoi fractions are 1/2 = 1/(k+l+1): 0∧0 agrees with the barycentric wedge */
  cr_expect_leq(d00, 1e-14, "metric wedge 0∧0 Leibniz defect %.3g", d00);
  gm_geometry_free(g);
  gm_complex_free(cx);
  gm_mesh_free(m);
}

/* 1 ∧ α = α and (f∧g) = fg on vertices. */
Test(dec_wedge, unit_function_is_the_identity) {
  gm_mesh *m = jiggled_box(2, 0.1, 3);
  gm_complex *cx = test_complex(m);
  for (size_t k = 0; k <= 3; ++k) {
    size_t nk = gm_complex_count(cx, k), nv = gm_complex_count(cx, 0);
    double *one = malloc(nv * sizeof(double)), *a = random_cochain(cx, k, 40 + k);
    double *out = malloc(nk * sizeof(double));
    for (size_t v = 0; v < nv; ++v) one[v] = 1.0;
    cr_assert_eq(gm_dec_wedge(cx, 0, one, k, a, out), GM_OK);
    for (size_t i = 0; i < nk; ++i) cr_expect_float_eq(out[i], a[i], 1e-15);
    free(one), free(a), free(out);
  }
  gm_complex_free(cx);
  gm_mesh_free(m);
}

/* ---- flat and sharp -------------------------------------------------------------------- */

static void check_flat_sharp_constant(const gm_mesh *m, const double *V) {
  gm_complex *cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  const size_t N = gm_complex_embedding_dim(cx), n = gm_complex_dim(cx);
  const size_t nt = gm_complex_count(cx, n), ne = gm_complex_count(cx, 1),
               nv = gm_complex_count(cx, 0);
  double *X = malloc(nt * N * sizeof(double)), *a = malloc(ne * sizeof(double));
  double *Y = malloc(nv * N * sizeof(double));
  for (size_t t = 0; t < nt; ++t) memcpy(X + t * N, V, N * sizeof(double));
  cr_assert_eq(gm_dec_flat(g, X, a), GM_OK);
  const size_t *e = gm_complex_simplices(cx, 1);
  const double *x = gm_complex_coordinates(cx);
  double worst = 0.0;
  for (size_t i = 0; i < ne; ++i) {
    double exact = 0.0;
    for (size_t j = 0; j < N; ++j) exact += V[j] * (x[e[2 * i + 1] * N + j] - x[e[2 * i] * N + j]);
    worst = fmax(worst, fabs(a[i] - exact));
  }
  cr_expect_leq(worst, 1e-14, "flat of a constant field: error %.3g", worst);
  cr_assert_eq(gm_dec_sharp(g, a, Y), GM_OK);
  worst = 0.0;
  for (size_t v = 0; v < nv; ++v)
    for (size_t j = 0; j < N; ++j) worst = fmax(worst, fabs(Y[v * N + j] - V[j]));
  cr_expect_leq(worst, 1e-12, "sharp of a constant 1-form: error %.3g", worst);
  free(X), free(a), free(Y);
  gm_geometry_free(g);
  gm_complex_free(cx);
}

Test(dec_flat_sharp, constant_fields_are_exact) {
  const double V2[2] = {0.3, -1.7}, V3[3] = {0.3, -1.7, 0.9};
  gm_mesh *m = jiggled_rectangle(5, GM_DIAGONAL_ACUTE, 0.1, 2);
  check_flat_sharp_constant(m, V2);
  gm_mesh_free(m);
  m = jiggled_rectangle(5, GM_DIAGONAL_RIGHT, 0.0, 2); /* zero dual edges on the diagonals */
  check_flat_sharp_constant(m, V2);
  gm_mesh_free(m);
  m = jiggled_box(3, 0.1, 8);
  check_flat_sharp_constant(m, V3);
  gm_mesh_free(m);
}

/* ---- cone operator ---------------------------------------------------------------------- */

static void check_cone(const gm_mesh *m) {
  gm_complex *cx = test_complex(m);
  gm_csr *H[GM_DEC_MAX_DIM + 1];
  size_t apex = SIZE_MAX;
  gm_error err = {{0}};
  cr_assert_eq(gm_dec_cone_operators(cx, H, &apex, &err), GM_OK, "%s", err.message);
  cr_assert_lt(apex, gm_complex_count(cx, 0));
  const size_t n = gm_complex_dim(cx);
  for (size_t k = 0; k <= n; ++k) {
    size_t nk = gm_complex_count(cx, k);
    double *a = random_cochain(cx, k, 100 + k), *r = calloc(nk, sizeof(double));
    if (k < n) { /* H_{k+1} d_k α */
      size_t m1 = gm_complex_count(cx, k + 1);
      double *da = malloc(m1 * sizeof(double));
      gm_csr_matvec(gm_complex_d(cx, k), 1.0, a, 0.0, da);
      gm_csr_matvec(H[k + 1], 1.0, da, 0.0, r);
      free(da);
    }
    if (k >= 1) { /* + d_{k−1} H_k α */
      size_t m0 = gm_complex_count(cx, k - 1);
      double *ha = malloc(m0 * sizeof(double));
      gm_csr_matvec(H[k], 1.0, a, 0.0, ha);
      gm_csr_matvec(gm_complex_d(cx, k - 1), 1.0, ha, 1.0, r);
      free(ha);
    }
    double worst = 0.0, shift = k == 0 ? a[apex] : 0.0;
    for (size_t i = 0; i < nk; ++i) worst = fmax(worst, fabs(r[i] - (a[i] - shift)));
    cr_expect_leq(worst, 1e-12, "n=%zu k=%zu: |Hdα + dHα − α| = %.3g", n, k, worst);
    /* Poincaré lemma: a closed k-form (k >= 1) dβ has the primitive Hdβ */
    if (k >= 1) {
      double *b = random_cochain(cx, k - 1, 300 + k), *db = malloc(nk * sizeof(double));
      size_t m0 = gm_complex_count(cx, k - 1);
      double *hb = malloc(m0 * sizeof(double)), *dhb = malloc(nk * sizeof(double));
      gm_csr_matvec(gm_complex_d(cx, k - 1), 1.0, b, 0.0, db);
      gm_csr_matvec(H[k], 1.0, db, 0.0, hb);
      gm_csr_matvec(gm_complex_d(cx, k - 1), 1.0, hb, 0.0, dhb);
      double w2 = 0.0;
      for (size_t i = 0; i < nk; ++i) w2 = fmax(w2, fabs(dhb[i] - db[i]));
      cr_expect_leq(w2, 1e-12, "k=%zu: |d H dβ − dβ| = %.3g", k, w2);
      free(b), free(db), free(hb), free(dhb);
    }
    free(a), free(r);
  }
  for (size_t k = 0; k <= GM_DEC_MAX_DIM; ++k) gm_csr_free(H[k]);
  gm_complex_free(cx);
}

Test(dec_cone, homotopy_formula_on_a_square) {
  gm_mesh *m = jiggled_rectangle(7, GM_DIAGONAL_ALTERNATE, 0.0, 1);
  check_cone(m);
  gm_mesh_free(m);
}

Test(dec_cone, homotopy_formula_on_a_cube) {
  gm_mesh *m = jiggled_box(3, 0.0, 1);
  check_cone(m);
  gm_mesh_free(m);
}

/* Seed 001 Ex. 3.18: no cone operator on a non-contractible complex. */
Test(dec_cone, annulus_is_refused) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_annulus(0.5, 1.0, 3, 12, &m, &err), GM_OK);
  gm_complex *cx = test_complex(m);
  gm_csr *H[GM_DEC_MAX_DIM + 1];
  cr_expect_eq(gm_dec_cone_operators(cx, H, NULL, &err), GM_EUNSUPPORTED);
  cr_expect(strstr(err.message, "contractible") != NULL, "%s", err.message);
  for (size_t k = 0; k <= GM_DEC_MAX_DIM; ++k) cr_expect_null(H[k]);
  gm_complex_free(cx);
  gm_mesh_free(m);
}

/* ---- integration by parts (seed 000 eq. 3.8) ----------------------------------------------- */

static void check_integration_by_parts(const gm_geometry *g) {
  const gm_complex *cx = gm_geometry_complex(g);
  const size_t n = gm_complex_dim(cx);
  gm_error err = {{0}};
  for (size_t k = 0; k < n; ++k) {
    size_t nk = gm_complex_count(cx, k), nk1 = gm_complex_count(cx, k + 1);
    double *a = random_cochain(cx, k, 7 + k), *b = random_cochain(cx, k + 1, 9 + k);
    double *flux = random_cochain(cx, k, 13 + k);
    double *da = malloc(nk1 * sizeof(double)), *db = malloc(nk * sizeof(double));
    gm_csr_matvec(gm_complex_d(cx, k), 1.0, a, 0.0, da);
    cr_assert_eq(gm_dec_codifferential_boundary(g, k, b, flux, db, &err), GM_OK, "%s", err.message);
    double lhs = test_wdot(nk1, gm_geometry_hodge_star(g, k + 1), da, b);
    double rhs1 = test_wdot(nk, gm_geometry_hodge_star(g, k), a, db);
    double bt = gm_dec_boundary_pairing(cx, k, a, flux);
    double scale = fabs(lhs) + fabs(rhs1) + fabs(bt);
    cr_expect_leq(fabs(lhs - rhs1 - bt), 1e-13 * scale,
                  "n=%zu k=%zu: (dα,β) = %.15g, (α,δβ) + boundary = %.15g + %.15g", n, k, lhs,
                  rhs1, bt);
    cr_expect_gt(fabs(bt), 1e-6 * scale, "n=%zu k=%zu: boundary term %.3g of %.3g", n, k, bt, scale);
    free(a), free(b), free(flux), free(da), free(db);
  }
}

Test(dec_integration_by_parts, boundary_term_to_round_off) {
  gm_mesh *m = jiggled_rectangle(6, GM_DIAGONAL_ACUTE, 0.1, 4);
  gm_complex *cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  check_integration_by_parts(g);
  gm_geometry_free(g);
  gm_complex_free(cx);
  gm_mesh_free(m);
  m = jiggled_box(3, 0.1, 4);
  cx = test_complex(m);
  gm_geometry_options o = gm_geometry_defaults();
  o.dual = GM_DUAL_BARYCENTRIC; /* Kuhn tetrahedra have zero circumcentric dual edges */
  g = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_geometry_create(cx, &o, &g, &err), GM_OK, "%s", err.message);
  check_integration_by_parts(g);
  gm_geometry_free(g);
  gm_complex_free(cx);
  gm_mesh_free(m);
}

/* f = sin(2x+1) cos y: −Δf = 5 f. With the outward flux of ∇f through the boundary dual cells
 * (half boundary edges), δ̃ df approximates −Δf at boundary vertices too (first order); the plain
 * adjoint δ = ⋆⁻¹dᵀ⋆ (flux 0) does not (its error grows like 1/h). Corners are left out: there
 * the two half-length dual edges meet the primal boundary edges at their ends rather than their
 * middles, an O(h) flux error on an O(h²) cell that no boundary term removes (measured: 1.06 at
 * h = 1/8, 0.97 at h = 1/16). */
static double ff(double x, double y) { return sin(2 * x + 1) * cos(y); }
static double fx(double x, double y) { return 2 * cos(2 * x + 1) * cos(y); }
static double fy(double x, double y) { return -sin(2 * x + 1) * sin(y); }

static void boundary_errors(size_t nc, double *with_flux, double *without) {
  gm_mesh *m = jiggled_rectangle(nc, GM_DIAGONAL_ACUTE, 0.0, 0);
  gm_complex *cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  const size_t nv = gm_complex_count(cx, 0), ne = gm_complex_count(cx, 1);
  const size_t *e = gm_complex_simplices(cx, 1);
  const double *x = gm_complex_coordinates(cx);
  const unsigned char *be = gm_complex_boundary_mask(cx, 1), *bv = gm_complex_boundary_mask(cx, 0);
  double *b = malloc(ne * sizeof(double)), *flux = calloc(nv, sizeof(double));
  double *r1 = malloc(nv * sizeof(double)), *r0 = malloc(nv * sizeof(double));
  double gx[5], gw[5];
  gm_gauss_legendre(5, gx, gw);
  for (size_t i = 0; i < ne; ++i) {
    const double *p = x + 2 * e[2 * i], *q = x + 2 * e[2 * i + 1];
    b[i] = ff(q[0], q[1]) - ff(p[0], p[1]);
    if (!be[i]) continue;
    /* outward normal of the boundary edge of the unit square */
    double nx = 0, ny = 0, mx = 0.5 * (p[0] + q[0]), my = 0.5 * (p[1] + q[1]);
    if (mx < 1e-12) nx = -1;
    else if (mx > 1 - 1e-12) nx = 1;
    else if (my < 1e-12) ny = -1;
    else ny = 1;
    for (int half = 0; half < 2; ++half) { /* half-edge from an end to the midpoint */
      const double *a = half ? q : p;
      size_t v = e[2 * i + half];
      double len = 0.5 * hypot(q[0] - p[0], q[1] - p[1]), s = 0.0;
      for (int j = 0; j < 5; ++j) {
        double t = 0.5 * (gx[j] + 1.0);
        double X = a[0] + t * (mx - a[0]), Y = a[1] + t * (my - a[1]);
        s += 0.5 * gw[j] * (fx(X, Y) * nx + fy(X, Y) * ny);
      }
      flux[v] += s * len;
    }
  }
  gm_error err = {{0}};
  cr_assert_eq(gm_dec_codifferential_boundary(g, 0, b, flux, r1, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_dec_codifferential_boundary(g, 0, b, NULL, r0, &err), GM_OK);
  *with_flux = *without = 0.0;
  for (size_t v = 0; v < nv; ++v) {
    const double X = x[2 * v], Y = x[2 * v + 1];
    int corner = (X < 1e-12 || X > 1 - 1e-12) && (Y < 1e-12 || Y > 1 - 1e-12);
    if (!bv[v] || corner) continue;
    double exact = 5.0 * ff(x[2 * v], x[2 * v + 1]);
    *with_flux = fmax(*with_flux, fabs(r1[v] - exact));
    *without = fmax(*without, fabs(r0[v] - exact));
  }
  free(b), free(flux), free(r1), free(r0);
  gm_geometry_free(g);
  gm_complex_free(cx);
  gm_mesh_free(m);
}

Test(dec_integration_by_parts, boundary_codifferential_is_consistent) {
  double e1a, e0a, e1b, e0b;
  boundary_errors(8, &e1a, &e0a);
  boundary_errors(16, &e1b, &e0b);
  cr_log_info("boundary vertices, with flux %.3g -> %.3g, without %.3g -> %.3g", e1a, e1b, e0a, e0b);
  cr_expect_leq(e1b, 0.6 * e1a, "with flux: %.3g -> %.3g", e1a, e1b);
  cr_expect_leq(e1b, 0.5, "with flux: %.3g", e1b);
  cr_expect_geq(e0b, 1.5 * e0a, "without flux the error grows: %.3g -> %.3g", e0a, e0b);
}
