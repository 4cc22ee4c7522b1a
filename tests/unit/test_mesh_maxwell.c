/* Mesh Maxwell contracts: bad meshes and inputs are errors with messages, never crashes:
 * non-manifold and inverted meshes, a mesh that is not well-centred (refused with the count
 * unless insisted), a step above the CFL limit or a face step above its local limit, ε or
 * μ <= 0, a probe outside, an unsupported combination. Also: the CFL estimate is sharp (a run
 * just below it is stable, one just above it with the limit check bypassed grows). */
#include "../mesh_maxwell_util.h"

static void expect_create(const gm_geometry *g, const double *eps, const double *mu,
                          const gm_mesh_maxwell_options *o, gm_status want, const char *needle) {
  gm_mesh_maxwell *s = (gm_mesh_maxwell *)0x1;
  gm_error err = {{0}};
  const gm_status st = gm_mesh_maxwell_create(g, eps, mu, o, &s, &err);
  cr_assert_eq(st, want, "expected %d for '%s', got %d (%s)", want, needle, st, err.message);
  cr_assert_null(s);
  cr_assert(strstr(err.message, needle) != NULL, "message '%s' lacks '%s'", err.message, needle);
}

Test(mesh_maxwell, bad_materials_and_steps) {
  mm_fixture f = mm_rect(6, 0.7, 0.0, 1);
  const size_t nt = gm_complex_count(f.cx, 2);
  double *eps = malloc(nt * sizeof(double)), *mu = malloc(nt * sizeof(double));
  for (size_t i = 0; i < nt; ++i) eps[i] = mu[i] = 1.0;
  eps[3] = 0.0;
  expect_create(f.g, eps, NULL, NULL, GM_EINVAL, "epsilon of cell 3");
  eps[3] = 1.0;
  mu[5] = -2.0;
  expect_create(f.g, NULL, mu, NULL, GM_EINVAL, "mu of cell 5");
  mu[5] = NAN;
  expect_create(f.g, NULL, mu, NULL, GM_EINVAL, "mu of cell 5");
  mu[5] = 1.0;
  gm_mesh_maxwell *s = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_maxwell_create(f.g, eps, mu, NULL, &s, &err), GM_OK, "%s", err.message);
  const double cfl = gm_mesh_maxwell_cfl_limit(s);
  cr_assert_lt(gm_mesh_maxwell_dt(s), cfl);
  /* a probe outside, a component 2-D lacks, currents on a PEC edge */
  const double out[3] = {2.0, 0.1, 0.0}, in[3] = {0.5, 0.3, 0.0};
  cr_assert_eq(gm_mesh_maxwell_add_probe(s, GM_EX, out, 10, NULL), GM_EINVAL);
  cr_assert(strstr(gm_mesh_maxwell_errmsg(s), "no cell") != NULL);
  cr_assert_eq(gm_mesh_maxwell_add_probe(s, GM_EZ, in, 10, NULL), GM_EINVAL);
  const unsigned char *bm = gm_complex_boundary_mask(f.cx, 1);
  size_t be = 0;
  while (!bm[be]) ++be;
  const gm_waveform w = {GM_WAVE_GAUSSIAN, 1.0, 0.0, 0.1, 0.5, 0.0, NULL, NULL};
  cr_assert_eq(gm_mesh_maxwell_add_current(s, 1, &be, NULL, &w, NULL), GM_EINVAL);
  cr_assert(strstr(gm_mesh_maxwell_errmsg(s), "PEC") != NULL);
  cr_assert_eq(gm_mesh_maxwell_advance_to(s, NAN), GM_EINVAL);
  gm_mesh_maxwell_free(s);
  gm_mesh_maxwell_free(NULL);
  /* dt above the limit: refused with the limit in the message */
  gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
  o.dt = 1.01 * cfl;
  expect_create(f.g, NULL, NULL, &o, GM_EINVAL, "above the CFL limit");
  /* the limit is sharp: 0.999 of it keeps the energy, 1.02 of it (check bypassed by a mesh
   * with the same operator but the limit recomputed) is tested through the eigenvalue */
  o.dt = 0.999 * cfl;
  cr_assert_eq(gm_mesh_maxwell_create(f.g, NULL, NULL, &o, &s, &err), GM_OK, "%s", err.message);
  const size_t ne = gm_complex_count(f.cx, 1);
  double *E = malloc(ne * sizeof(double)), *B = malloc(nt * sizeof(double));
  mm_random_fields(&f, 3, E, B);
  gm_mesh_maxwell_set_fields(s, E, B);
  gm_mesh_maxwell_energy e0, e1;
  gm_mesh_maxwell_energy_get(s, &e0);
  cr_assert_eq(gm_mesh_maxwell_advance(s, 20000), GM_OK);
  gm_mesh_maxwell_energy_get(s, &e1);
  cr_assert_lt(fabs(e1.leapfrog - e0.leapfrog), 1e-10 * e0.leapfrog);
  cr_assert_lt(e1.plain, 1e3 * e0.plain, "unstable at 0.999 of the CFL estimate");
  gm_mesh_maxwell_free(s);
  /* AVI: a face step above its local limit */
  o = gm_mesh_maxwell_defaults();
  o.scheme = GM_MESH_AVI;
  double *fdt = malloc(nt * sizeof(double));
  cr_assert_eq(gm_mesh_maxwell_create(f.g, NULL, NULL, &o, &s, &err), GM_OK, "%s", err.message);
  const double *lim = gm_mesh_maxwell_face_limits(s);
  size_t bad = 0;
  for (size_t k = 0; k < nt; ++k) fdt[k] = isfinite(lim[k]) ? 0.5 * lim[k] : 1.0;
  while (!isfinite(lim[bad])) ++bad;
  fdt[bad] = 1.5 * lim[bad];
  cr_assert_eq(gm_mesh_maxwell_advance(s, 1), GM_EINVAL); /* no global step */
  /* AVI currents: before the first advance only */
  const gm_waveform pulse = {GM_WAVE_GAUSSIAN, 1.0, 1.0, 0.2, 0.5, 0.0, NULL, NULL};
  const double xc[3] = {0.5, 0.35, 0.0};
  const size_t ce = mm_nearest_interior_edge(&f, xc);
  cr_assert_eq(gm_mesh_maxwell_add_current(s, 1, &ce, NULL, &pulse, NULL), GM_OK, "%s",
               gm_mesh_maxwell_errmsg(s));
  cr_assert_eq(gm_mesh_maxwell_advance_to(s, 0.01), GM_OK);
  cr_assert_eq(gm_mesh_maxwell_add_current(s, 1, &ce, NULL, &pulse, NULL), GM_EINVAL);
  cr_assert(strstr(gm_mesh_maxwell_errmsg(s), "before the first advance") != NULL);
  gm_mesh_maxwell_free(s);
  o.face_dt = fdt;
  expect_create(f.g, NULL, NULL, &o, GM_EINVAL, "local CFL");
  /* Whitney star: materials per cell accepted (and checked), leapfrog only */
  o = gm_mesh_maxwell_defaults();
  o.star = GM_MESH_STAR_WHITNEY;
  eps[2] = 2.0;
  gm_mesh_maxwell *wm = NULL;
  gm_error werr = {{0}};
  cr_assert_eq(gm_mesh_maxwell_create(f.g, eps, NULL, &o, &wm, &werr), GM_OK, "%s", werr.message);
  gm_mesh_maxwell_free(wm);
  eps[2] = -1.0;
  expect_create(f.g, eps, NULL, &o, GM_EINVAL, "epsilon of cell 2");
  eps[2] = 1.0;
  o.scheme = GM_MESH_AVI;
  expect_create(f.g, NULL, NULL, &o, GM_EUNSUPPORTED, "diagonal star");
  free(eps); free(mu); free(E); free(B); free(fdt);
  mm_fixture_free(&f);
}

Test(mesh_maxwell, bad_meshes) {
  gm_error err = {{0}};
  /* not well-centred: the Gmsh cube has negative duals; refused with the count */
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_read(GM_SOURCE_DIR "/tests/data/cube_v22.msh", &m, &err), GM_OK, "%s", err.message);
  mm_fixture f = {m, NULL, NULL};
  mm_fixture_finish(&f);
  expect_create(f.g, NULL, NULL, NULL, GM_EINVAL, "not well-centred: 15 interior edges");
  gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
  o.star = GM_MESH_STAR_WHITNEY; /* the Whitney star takes it */
  gm_mesh_maxwell *s = NULL;
  cr_assert_eq(gm_mesh_maxwell_create(f.g, NULL, NULL, &o, &s, &err), GM_OK, "%s", err.message);
  gm_mesh_maxwell_free(s);
  /* insisted on, the diagonal star's negative entries make the leapfrog blow up whatever the
   * step: advance stops with the times between which the fields became non-finite (not at the
   * end), and div B and Gauss report NaN, not a clean 0 (fmax-style maxima drop NaN) */
  o = gm_mesh_maxwell_defaults();
  o.allow_negative_stars = 1;
  cr_assert_eq(gm_mesh_maxwell_create(f.g, NULL, NULL, &o, &s, &err), GM_OK, "%s", err.message);
  {
    const size_t ne = gm_complex_count(f.cx, 1), nf = gm_complex_count(f.cx, 2);
    double *E = malloc(ne * sizeof(double)), *B = malloc(nf * sizeof(double));
    mm_random_fields(&f, 5, E, B);
    gm_mesh_maxwell_set_fields(s, E, NULL);
    const size_t n = (size_t)(200.0 / gm_mesh_maxwell_dt(s));
    cr_assert_eq(gm_mesh_maxwell_advance(s, n), GM_EDOMAIN);
    cr_assert(strstr(gm_mesh_maxwell_errmsg(s), "non-finite between t = ") != NULL, "%s",
              gm_mesh_maxwell_errmsg(s));
    cr_assert_lt(gm_mesh_maxwell_step(s), n, "stopped near the blow-up: %s",
                 gm_mesh_maxwell_errmsg(s));
    const double *b = gm_mesh_maxwell_b(s);
    size_t nan_faces = 0;
    for (size_t k = 0; k < nf; ++k) nan_faces += isnan(b[k]);
    cr_assert_gt(nan_faces, 0, "the state holds NaN");
    cr_assert(isnan(gm_mesh_maxwell_div_b(s)), "div B %g", gm_mesh_maxwell_div_b(s));
    cr_assert(isnan(gm_mesh_maxwell_gauss(s, NULL)), "Gauss %g", gm_mesh_maxwell_gauss(s, NULL));
    free(E); free(B);
  }
  gm_mesh_maxwell_free(s);
  mm_fixture_free(&f);
  /* no interior edge (one triangle, one tetrahedron): PEC zeroes every field; refused */
  {
    const double x2[] = {0, 0, 1, 0, 0, 1}, x3[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const size_t t2[] = {0, 1, 2}, t3[] = {0, 1, 2, 3};
    for (int d = 2; d <= 3; ++d) {
      gm_complex *c1 = NULL;
      gm_geometry *g1 = NULL;
      cr_assert_eq(gm_complex_create((size_t)d, (size_t)d + 1, d == 2 ? x2 : x3, (size_t)d, 1,
                                     d == 2 ? t2 : t3, &c1, &err), GM_OK, "%s", err.message);
      cr_assert_eq(gm_geometry_create(c1, NULL, &g1, &err), GM_OK, "%s", err.message);
      expect_create(g1, NULL, NULL, NULL, GM_EINVAL, "no interior edges: under PEC every field");
      o = gm_mesh_maxwell_defaults();
      o.star = GM_MESH_STAR_WHITNEY;
      expect_create(g1, NULL, NULL, &o, GM_EINVAL, "no interior edges");
      gm_geometry_free(g1);
      gm_complex_free(c1);
    }
  }
  /* Kuhn box: zero dual edges; refused even when insisting */
  mm_fixture k = mm_box(2);
  o = gm_mesh_maxwell_defaults();
  o.allow_negative_stars = 1;
  expect_create(k.g, NULL, NULL, &o, GM_EINVAL, "zero star_eps");
  mm_fixture_free(&k);
  /* non-manifold: three triangles on one edge (the complex refuses it) */
  const double x[] = {0, 0, 1, 0, 0, 1, 1, 1, 0.5, -1};
  const size_t tri[] = {0, 1, 2, 0, 1, 3, 0, 1, 4};
  gm_complex *cx = NULL;
  cr_assert_eq(gm_complex_create(2, 5, x, 2, 3, tri, &cx, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "non-manifold") != NULL, "%s", err.message);
  /* inverted element: a folded pair of triangles in the plane */
  const double y[] = {0, 0, 1, 0, 0, 1, 0.4, 0.4};
  const size_t tri2[] = {0, 1, 2, 1, 2, 3};
  cr_assert_eq(gm_complex_create(2, 4, y, 2, 2, tri2, &cx, &err), GM_OK, "%s", err.message);
  gm_geometry *g = NULL;
  cr_assert_eq(gm_geometry_create(cx, NULL, &g, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "inverted") != NULL, "%s", err.message);
  gm_geometry_options go = gm_geometry_defaults();
  go.allow_inverted = 1;
  cr_assert_eq(gm_geometry_create(cx, &go, &g, &err), GM_OK, "%s", err.message);
  expect_create(g, NULL, NULL, NULL, GM_EINVAL, "inverted");
  gm_geometry_free(g);
  gm_complex_free(cx);
  /* a surface in R^3 is not a planar mesh */
  gm_mesh *sph = NULL;
  cr_assert_eq(gm_mesh_icosphere(1.0, 1, &sph, &err), GM_OK);
  mm_fixture sf = {sph, NULL, NULL};
  mm_fixture_finish(&sf);
  expect_create(sf.g, NULL, NULL, NULL, GM_EINVAL, "triangles in the plane");
  mm_fixture_free(&sf);
}

/* Materials per cell: ε = 4 everywhere halves the wave speed, so the CFL limit doubles (the
 * power iteration sees the same operator scaled); a two-material cavity keeps the modified
 * energy and Gauss's law. */
Test(mesh_maxwell, materials_per_cell) {
  mm_fixture f = mm_rect(8, 0.7, 0.0, 1);
  gm_error err = {{0}};
  const size_t nt = gm_complex_count(f.cx, 2), ne = gm_complex_count(f.cx, 1);
  double *eps = malloc(nt * sizeof(double)), *mu = malloc(nt * sizeof(double));
  for (size_t i = 0; i < nt; ++i) { eps[i] = 4.0; mu[i] = 1.0; }
  gm_mesh_maxwell *a = NULL, *b = NULL;
  cr_assert_eq(gm_mesh_maxwell_create(f.g, NULL, NULL, NULL, &a, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_mesh_maxwell_create(f.g, eps, mu, NULL, &b, &err), GM_OK, "%s", err.message);
  const double ratio = gm_mesh_maxwell_cfl_limit(b) / gm_mesh_maxwell_cfl_limit(a);
  cr_assert_lt(fabs(ratio - 2.0), 1e-9, "CFL ratio %.12f", ratio);
  gm_mesh_maxwell_free(a);
  gm_mesh_maxwell_free(b);
  const double *c = gm_geometry_centers(f.g, 2);
  for (size_t i = 0; i < nt; ++i) { eps[i] = c[2 * i] < 0.5 ? 2.5 : 1.0; mu[i] = c[2 * i + 1] < 0.3 ? 1.5 : 1.0; }
  cr_assert_eq(gm_mesh_maxwell_create(f.g, eps, mu, NULL, &b, &err), GM_OK, "%s", err.message);
  double *E = malloc(ne * sizeof(double)), *B = malloc(nt * sizeof(double));
  mm_random_fields(&f, 9, E, B);
  gm_mesh_maxwell_set_fields(b, E, B);
  gm_mesh_maxwell_energy e0, e1;
  gm_mesh_maxwell_energy_get(b, &e0);
  const double g0 = gm_mesh_maxwell_gauss(b, NULL);
  double *gv0 = malloc(gm_complex_count(f.cx, 0) * sizeof(double));
  double *gv1 = malloc(gm_complex_count(f.cx, 0) * sizeof(double));
  gm_mesh_maxwell_gauss(b, gv0);
  cr_assert_eq(gm_mesh_maxwell_advance(b, 2000), GM_OK);
  gm_mesh_maxwell_energy_get(b, &e1);
  gm_mesh_maxwell_gauss(b, gv1);
  double gd = 0.0;
  for (size_t v = 0; v < gm_complex_count(f.cx, 0); ++v) gd = fmax(gd, fabs(gv1[v] - gv0[v]));
  cr_assert_lt(fabs(e1.leapfrog - e0.leapfrog), 1e-13 * e0.leapfrog);
  cr_assert_lt(gd, 1e-12 * fmax(g0, 1.0));
  free(eps); free(mu); free(E); free(B); free(gv0); free(gv1);
  gm_mesh_maxwell_free(b);
  mm_fixture_free(&f);
}

/* gm_mesh_bcc: 4 tetrahedra per interior face of the cube grid, all of one volume h³/12, the
 * circumcentric stars positive (the diagonal star is accepted without insisting), the CFL limit
 * from the Lanczos estimate within the Gershgorin bound; bad counts refused. */
Test(mesh_maxwell, bcc_mesh_is_well_centred) {
  mm_fixture f = mm_bcc(4);
  const size_t faces = 3 * 3 * 4 * 4;
  cr_assert_eq(f.mesh->n_cells, 4 * faces);
  cr_assert_eq(f.mesh->n_vertices, 5 * 5 * 5 - 8 + 4 * 4 * 4);
  const double *vol = gm_geometry_primal_volumes(f.g, 3);
  const double h = 0.25;
  for (size_t T = 0; T < f.mesh->n_cells; ++T)
    cr_assert_float_eq(vol[T], h * h * h / 12.0, 1e-15, "cell %zu volume %g", T, vol[T]);
  gm_mesh_maxwell *s = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_maxwell_create(f.g, NULL, NULL, NULL, &s, &err), GM_OK, "%s", err.message);
  const double *lim = gm_mesh_maxwell_face_limits(s);
  double smallest = INFINITY;
  for (size_t k = 0; k < gm_complex_count(f.cx, 2); ++k) smallest = fmin(smallest, lim[k]);
  /* the Gershgorin local limits bound the spectrum from above: global limit >= smallest local */
  cr_assert_geq(gm_mesh_maxwell_cfl_limit(s), smallest * (1.0 - 1e-12));
  gm_mesh_maxwell_free(s);
  mm_fixture_free(&f);
  gm_mesh *m = NULL;
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_bcc(lo, hi, 1, 4, 4, 0, &m, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "out of range") != NULL, "%s", err.message);
  cr_assert_null(m);
  const double bad[3] = {1, 0, 1};
  cr_assert_eq(gm_mesh_bcc(lo, bad, 3, 3, 3, 0, &m, &err), GM_EINVAL);
  /* filled: the tetrahedra tile the box (total volume 1 × 0.8 × 0.6, none inverted) */
  const double box[3] = {1, 0.8, 0.6};
  cr_assert_eq(gm_mesh_bcc(lo, box, 5, 4, 3, 1, &m, &err), GM_OK, "%s", err.message);
  gm_complex *cx = NULL;
  gm_geometry *g = NULL;
  cr_assert_eq(gm_mesh_complex(m, &cx, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_geometry_create(cx, NULL, &g, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_geometry_inverted_count(g), 0);
  double total = 0.0;
  const double *v3 = gm_geometry_primal_volumes(g, 3);
  for (size_t T = 0; T < gm_complex_count(cx, 3); ++T) total += v3[T];
  cr_assert_float_eq(total, 0.48, 1e-13);
  cr_assert_eq(gm_complex_boundary_count(cx, 2), 2 * 4 * (20 + 12 + 15));
  gm_geometry_free(g);
  gm_complex_free(cx);
  gm_mesh_free(m);
}
