/* Yee solver contracts: bad input is an error with a message (never a crash), names and
 * layouts, waveforms, probes and observers, harminv on a known signal. */
#include <stdio.h>

#include "yee_util.h"

static gm_yee_grid grid3(void) {
  return (gm_yee_grid){GM_YEE_3D, {8, 6, 5}, {0.1, 0.1, 0.1}, {0, 0, 0}};
}

static void expect_create_error(const gm_yee_grid *g, const gm_yee_materials *m,
                                const gm_yee_options *o, const char *needle) {
  gm_yee *s = (gm_yee *)0x1;
  gm_error err = {{0}};
  const gm_status st = gm_yee_create(g, m, o, &s, &err);
  cr_assert_eq(st, GM_EINVAL, "expected GM_EINVAL for '%s', got %d", needle, st);
  cr_assert_null(s);
  cr_assert(strstr(err.message, needle) != NULL, "message '%s' lacks '%s'", err.message, needle);
}

Test(yee, bad_grids_are_errors) {
  gm_yee_grid g = grid3();
  g.n[1] = 0;
  expect_create_error(&g, NULL, NULL, "zero cells along y");
  g = grid3();
  g.h[2] = -0.1;
  expect_create_error(&g, NULL, NULL, "cell size along z");
  g = grid3();
  g.h[0] = NAN;
  expect_create_error(&g, NULL, NULL, "cell size along x");
  g = grid3();
  g.dim = (gm_yee_dim)9;
  expect_create_error(&g, NULL, NULL, "unknown dimension");
  expect_create_error(NULL, NULL, NULL, "grid: NULL");
}

Test(yee, bad_media_are_errors) {
  gm_yee_grid g = grid3();
  gm_yee_materials *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_materials_create(&g, &m, &err), GM_OK);
  const double lo[3] = {0, 0, 0}, hi[3] = {0.3, 0.3, 0.3}, c[3] = {0.4, 0.3, 0.25};
  const gm_medium bad_eps = {0.0, 1.0, 0.0}, neg_mu = {1.0, -2.0, 0.0}, nan_eps = {NAN, 1, 0},
                  neg_sigma = {1, 1, -1}, inf_mu = {1, INFINITY, 0};
  cr_assert_eq(gm_yee_paint_box(m, lo, hi, &bad_eps), GM_EINVAL);
  cr_assert(strstr(gm_yee_materials_errmsg(m), "epsilon must be in [1e-100, 1e+100] (got 0)"));
  cr_assert_eq(gm_yee_paint_sphere(m, c, 0.2, &neg_mu), GM_EINVAL);
  cr_assert(strstr(gm_yee_materials_errmsg(m), "mu must be in [1e-100, 1e+100] (got -2)"));
  cr_assert_eq(gm_yee_materials_fill(m, &nan_eps), GM_EINVAL);
  cr_assert(strstr(gm_yee_materials_errmsg(m), "epsilon"));
  cr_assert_eq(gm_yee_paint_box(m, lo, hi, &neg_sigma), GM_EINVAL);
  cr_assert(strstr(gm_yee_materials_errmsg(m), "sigma"));
  const double ax[3] = {0, 0, 1};
  cr_assert_eq(gm_yee_paint_cylinder(m, c, ax, 0.1, 0.2, &inf_mu), GM_EINVAL);
  const double zero[3] = {0, 0, 0};
  const gm_medium ok = {2, 1, 0};
  cr_assert_eq(gm_yee_paint_cylinder(m, c, zero, 0.1, 0.2, &ok), GM_EINVAL);
  cr_assert(strstr(gm_yee_materials_errmsg(m), "zero vector"));
  cr_assert_eq(gm_yee_paint_box(m, hi, lo, &ok), GM_EINVAL, "lo > hi");
  /* per-cell arrays: one NaN rejects the whole paint and names the cell */
  const size_t nc = gm_yee_materials_n_cells(m);
  cr_assert_eq(nc, 8 * 6 * 5);
  double *eps = malloc(nc * sizeof(double));
  for (size_t i = 0; i < nc; ++i) eps[i] = 1.0 + (double)i / (double)nc;
  eps[17] = NAN;
  cr_assert_eq(gm_yee_paint_cells(m, eps, NULL, NULL), GM_EINVAL);
  cr_assert(strstr(gm_yee_materials_errmsg(m), "cell 17"), "%s", gm_yee_materials_errmsg(m));
  cr_assert_eq(gm_yee_materials_epsilon(m)[16], 1.0, "nothing painted");
  eps[17] = -1.0;
  cr_assert_eq(gm_yee_paint_cells(m, eps, NULL, NULL), GM_EINVAL);
  eps[17] = 1.5;
  cr_assert_eq(gm_yee_paint_cells(m, eps, NULL, NULL), GM_OK);
  cr_assert_eq(gm_yee_materials_epsilon(m)[17], 1.5);
  free(eps);
  /* materials of another grid */
  gm_yee_grid other = grid3();
  other.n[0] = 9;
  expect_create_error(&other, m, NULL, "another grid");
  gm_yee_materials_free(m);
  gm_yee_materials_free(NULL);
}

Test(yee, painting_follows_cell_centres) {
  gm_yee_grid g = {GM_YEE_2D_TM, {10, 10, 1}, {0.1, 0.1, 1}, {0, 0, 0}};
  gm_yee_materials *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_materials_create(&g, &m, &err), GM_OK);
  const gm_medium glass = {4.0, 1.0, 0.0};
  const double c[3] = {0.5, 0.5, 0.0}, ax[3] = {0, 0, 1};
  cr_assert_eq(gm_yee_paint_cylinder(m, c, ax, 0.25, 1.0, &glass), GM_OK);
  size_t inside = 0;
  for (size_t i = 0; i < gm_yee_materials_n_cells(m); ++i) inside += gm_yee_materials_epsilon(m)[i] == 4.0;
  /* cell centres 0.05 + 0.1 i within 0.25 of 0.5: offsets (±0.05|±0.15)² pairs, 4 + 8 + 4 */
  cr_assert_eq(inside, 16, "got %zu", inside);
  gm_yee_materials_free(m);
}

Test(yee, bad_options_are_errors) {
  gm_yee_grid g = grid3();
  gm_yee_options o = gm_yee_defaults();
  double limit;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_courant_limit(&g, NULL, &limit, &err), GM_OK);
  cr_assert_float_eq(limit, 0.1 / sqrt(3.0), 1e-15);
  o.dt = limit * 1.001;
  expect_create_error(&g, NULL, &o, "above the Courant limit");
  {
    gm_yee *s = NULL;
    gm_yee_create(&g, NULL, &o, &s, &err);
    char expect[64];
    snprintf(expect, sizeof expect, "%.17g", limit);
    cr_assert(strstr(err.message, expect), "the message prints the limit: %s", err.message);
  }
  o.dt = limit; /* exactly at the limit is allowed */
  gm_yee *s = NULL;
  cr_assert_eq(gm_yee_create(&g, NULL, &o, &s, &err), GM_OK, "%s", err.message);
  gm_yee_free(s);
  gm_yee_free(NULL);
  o = gm_yee_defaults();
  o.courant = 1.5;
  expect_create_error(&g, NULL, &o, "courant");
  o = gm_yee_defaults();
  o.boundary[GM_FACE_XLO].kind = GM_BOUNDARY_PERIODIC;
  expect_create_error(&g, NULL, &o, "both must be periodic");
  o = gm_yee_defaults();
  o.bloch_k[1] = 1.0;
  expect_create_error(&g, NULL, &o, "needs periodic");
  o = gm_yee_defaults();
  o.boundary[GM_FACE_ZLO].kind = GM_BOUNDARY_CPML;
  o.boundary[GM_FACE_ZHI].kind = GM_BOUNDARY_CPML;
  o.boundary[GM_FACE_ZLO].pml.thickness = 3;
  o.boundary[GM_FACE_ZHI].pml.thickness = 2;
  expect_create_error(&g, NULL, &o, "leave no interior");
  o.boundary[GM_FACE_ZHI].pml.thickness = 0;
  expect_create_error(&g, NULL, &o, "thickness 0");
  o.boundary[GM_FACE_ZHI].pml.thickness = 1;
  o.boundary[GM_FACE_ZHI].pml.kappa_max = 0.5;
  expect_create_error(&g, NULL, &o, "kappa_max >= 1");
  /* a material slower than vacuum raises the limit; a faster one (εμ < 1) lowers it */
  gm_yee_materials *m = NULL;
  cr_assert_eq(gm_yee_materials_create(&g, &m, &err), GM_OK);
  const gm_medium fast = {0.25, 1.0, 0.0};
  const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0.1};
  cr_assert_eq(gm_yee_paint_box(m, lo, hi, &fast), GM_OK);
  double lim2;
  cr_assert_eq(gm_yee_courant_limit(&g, m, &lim2, &err), GM_OK);
  cr_assert_float_eq(lim2, 0.5 * limit, 1e-15);
  o = gm_yee_defaults();
  o.dt = 0.9 * limit;
  expect_create_error(&g, m, &o, "Courant");
  gm_yee_materials_free(m);
}

Test(yee, bad_sources_probes_and_fields_are_errors) {
  gm_yee_grid g = grid3();
  gm_yee_options o = gm_yee_defaults();
  o.n_threads = 1;
  gm_yee *s = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_create(&g, NULL, &o, &s, &err), GM_OK);
  const gm_waveform w = {GM_WAVE_GAUSSIAN, 1.0, 1.0, 0.2, 1.0, 0.0, NULL, NULL};
  gm_point_source ps = {GM_EZ, {2.0, 0.3, 0.2}, GM_SOURCE_SOFT, w};
  cr_assert_eq(gm_yee_add_point_source(s, &ps, NULL), GM_EINVAL);
  cr_assert(strstr(gm_yee_errmsg(s), "outside the grid"), "%s", gm_yee_errmsg(s));
  ps.x[0] = NAN;
  cr_assert_eq(gm_yee_add_point_source(s, &ps, NULL), GM_EINVAL);
  ps.x[0] = 0.0; /* Ez on the x = 0 PEC wall: never updated */
  cr_assert_eq(gm_yee_add_point_source(s, &ps, NULL), GM_EINVAL);
  cr_assert(strstr(gm_yee_errmsg(s), "PEC"), "%s", gm_yee_errmsg(s));
  ps.x[0] = 0.4;
  ps.wave.width = 0.0;
  cr_assert_eq(gm_yee_add_point_source(s, &ps, NULL), GM_EINVAL);
  cr_assert(strstr(gm_yee_errmsg(s), "width"), "%s", gm_yee_errmsg(s));
  ps.wave = w;
  ps.component = (gm_yee_component)7;
  cr_assert_eq(gm_yee_add_point_source(s, &ps, NULL), GM_EINVAL);
  ps.component = GM_EZ;
  size_t id = 99;
  cr_assert_eq(gm_yee_add_point_source(s, &ps, &id), GM_OK, "%s", gm_yee_errmsg(s));
  cr_assert_eq(id, 0);
  const size_t edges[] = {3, 3, 9};
  gm_current cur = {GM_EZ, 1, edges, NULL, w};
  cr_assert_eq(gm_yee_add_current(s, &cur, NULL), GM_EINVAL);
  cr_assert(strstr(gm_yee_errmsg(s), "outside the grid"), "%s", gm_yee_errmsg(s));
  cur.component = GM_HX;
  cr_assert_eq(gm_yee_add_current(s, &cur, NULL), GM_EINVAL);
  const double out[3] = {-1, 0, 0}, in[3] = {0.4, 0.3, 0.2};
  cr_assert_eq(gm_yee_add_probe(s, GM_HX, out, 10, NULL), GM_EINVAL);
  cr_assert_eq(gm_yee_add_probe(s, GM_HX, in, 10, &id), GM_OK);
  cr_assert_eq(gm_yee_advance(s, 11), GM_EINVAL, "the probe has room for 10");
  cr_assert(strstr(gm_yee_errmsg(s), "probe 0"), "%s", gm_yee_errmsg(s));
  cr_assert_eq(gm_yee_step(s), 0, "nothing ran");
  cr_assert_eq(gm_yee_advance(s, 10), GM_OK);
  size_t n;
  const double *t, *re, *im;
  cr_assert_eq(gm_yee_probe_samples(s, id, &n, &t, &re, &im), GM_OK);
  cr_assert_eq(n, 10);
  cr_assert_null(im);
  cr_assert_float_eq(t[9], 10 * gm_yee_dt(s), 1e-15, "H at whole steps");
  gm_yee_layout L;
  gm_yee_get_layout(s, &L);
  double *v = calloc(L.size, sizeof(double));
  v[3] = NAN;
  cr_assert_eq(gm_yee_set_field(s, GM_EX, 0, v), GM_EDOMAIN);
  cr_assert_eq(gm_yee_set_field(s, GM_EX, 1, v), GM_EINVAL, "no imaginary part");
  free(v);
  gm_plane_wave pw = {0, 1, GM_EX, {1, 1, 1}, {5, 4, 3}, w};
  cr_assert_eq(gm_yee_add_plane_wave(s, &pw, NULL), GM_EINVAL, "polarization along the axis");
  pw.polarization = GM_EZ;
  pw.hi[0] = 8;
  cr_assert_eq(gm_yee_add_plane_wave(s, &pw, NULL), GM_EINVAL, "box touches the face");
  cr_assert_eq(gm_yee_add_observer(s, 0, NULL, NULL), GM_EINVAL);
  gm_yee_free(s);
  /* a 2-D TM grid has no Ex */
  gm_yee_grid g2 = {GM_YEE_2D_TM, {8, 8, 1}, {0.1, 0.1, 1}, {0, 0, 0}};
  cr_assert_eq(gm_yee_create(&g2, NULL, NULL, &s, &err), GM_OK);
  ps.component = GM_EX;
  cr_assert_eq(gm_yee_add_point_source(s, &ps, NULL), GM_EINVAL);
  cr_assert(strstr(gm_yee_errmsg(s), "no component"), "%s", gm_yee_errmsg(s));
  cr_assert_null(gm_yee_field(s, GM_EX, 0));
  cr_assert_not_null(gm_yee_field(s, GM_EZ, 0));
  gm_yee_free(s);
}

Test(yee, names_round_trip) {
  for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
    gm_yee_component back;
    cr_assert_eq(gm_yee_component_find(gm_yee_component_name((gm_yee_component)c), &back), GM_OK);
    cr_assert_eq((int)back, c);
  }
  gm_yee_component cc;
  cr_assert_eq(gm_yee_component_find("hz", &cc), GM_OK);
  cr_assert_eq(cc, GM_HZ);
  cr_assert_eq(gm_yee_component_find("Bx", &cc), GM_ENOTFOUND);
  for (int k = 0; k <= GM_WAVE_CUSTOM; ++k) {
    gm_waveform_kind back;
    cr_assert_eq(gm_waveform_kind_find(gm_waveform_kind_name((gm_waveform_kind)k), &back), GM_OK);
    cr_assert_eq((int)back, k);
  }
  for (int k = 0; k <= GM_BOUNDARY_CPML; ++k) {
    gm_yee_boundary_kind back;
    cr_assert_eq(gm_yee_boundary_kind_find(gm_yee_boundary_kind_name((gm_yee_boundary_kind)k), &back),
                 GM_OK);
    cr_assert_eq((int)back, k);
  }
  cr_assert_null(gm_yee_component_name((gm_yee_component)6));
  cr_assert_eq(gm_yee_dim_axes(GM_YEE_2D_TE), 2);
  cr_assert(gm_yee_dim_has(GM_YEE_2D_TE, GM_HZ) && !gm_yee_dim_has(GM_YEE_2D_TE, GM_EZ));
  cr_assert(gm_yee_dim_has(GM_YEE_1D, GM_HY) && !gm_yee_dim_has(GM_YEE_1D, GM_HX));
}

static double ramp_probe(void *ctx, double t) {
  (void)ctx;
  return t;
}

Test(yee, waveforms) {
  const gm_waveform g = {GM_WAVE_GAUSSIAN, 2.0, 0.0, 0.5, 1.0, 0.0, NULL, NULL};
  cr_assert_float_eq(gm_waveform_value(&g, 1.0), 2.0, 1e-15);
  cr_assert_float_eq(gm_waveform_value(&g, 1.5), 2.0 * exp(-0.5), 1e-15);
  const gm_waveform dg = {GM_WAVE_DGAUSSIAN, 1.0, 0.0, 0.5, 1.0, 0.0, NULL, NULL};
  cr_assert_float_eq(gm_waveform_value(&dg, 0.5), 1.0, 1e-15, "peak +1 at t0 - w");
  cr_assert_float_eq(gm_waveform_value(&dg, 1.0), 0.0, 1e-15);
  const gm_waveform rk = {GM_WAVE_RICKER, 1.0, 2.0, 0.0, 1.0, 0.0, NULL, NULL};
  cr_assert_float_eq(gm_waveform_value(&rk, 1.0), 1.0, 1e-15);
  /* Ricker zero crossings at τ = ±1/(√2 π f) */
  cr_assert_float_eq(gm_waveform_value(&rk, 1.0 + 1.0 / (sqrt(2.0) * YEE_TEST_PI * 2.0)), 0.0, 1e-15);
  const gm_waveform cw = {GM_WAVE_CW, 1.0, 0.25, 2.0, 0.0, 0.0, NULL, NULL};
  cr_assert_eq(gm_waveform_value(&cw, -1.0), 0.0);
  cr_assert_float_eq(gm_waveform_value(&cw, 1.0), 0.5 * sin(2 * YEE_TEST_PI * 0.25), 1e-15,
                     "ramp at its midpoint is ½");
  cr_assert_float_eq(gm_waveform_value(&cw, 3.0), sin(2 * YEE_TEST_PI * 0.75), 1e-15);
  const gm_waveform cu = {GM_WAVE_CUSTOM, 3.0, 0, 0, 0, 0, ramp_probe, NULL};
  cr_assert_float_eq(gm_waveform_value(&cu, 0.25), 0.75, 1e-15);
  gm_error err;
  gm_waveform bad = cu;
  bad.fn = NULL;
  cr_assert_eq(gm_waveform_check(&bad, &err), GM_EINVAL);
  bad = rk;
  bad.frequency = 0;
  cr_assert_eq(gm_waveform_check(&bad, &err), GM_EINVAL);
  bad = g;
  bad.delay = INFINITY;
  cr_assert_eq(gm_waveform_check(&bad, &err), GM_EINVAL);
}

Test(yee, layout_and_field_access) {
  gm_yee *s = yee_make(GM_YEE_3D, 4, 3, 2, 0.5, GM_BOUNDARY_PEC, 0.9, 1);
  gm_yee_layout L;
  gm_yee_get_layout(s, &L);
  cr_assert_eq(L.extent[0], 6);
  cr_assert_eq(L.extent[1], 5);
  cr_assert_eq(L.extent[2], 4);
  cr_assert_eq(L.size, 6 * 5 * 4);
  cr_assert_eq(gm_yee_index(&L, -1, -1, -1), 0);
  cr_assert_eq(gm_yee_index(&L, 0, 0, 0), 1 + 6 + 30);
  size_t cnt[3];
  gm_yee_component_count(&L, GM_EX, cnt);
  cr_assert(cnt[0] == 4 && cnt[1] == 4 && cnt[2] == 3);
  gm_yee_component_count(&L, GM_HX, cnt);
  cr_assert(cnt[0] == 5 && cnt[1] == 3 && cnt[2] == 2);
  double sh[3];
  gm_yee_component_shift(L.dim, GM_HY, sh);
  cr_assert(sh[0] == 0.5 && sh[1] == 0.0 && sh[2] == 0.5);
  /* set from a function and read back at a location */
  cr_assert_eq(gm_yee_set_field_fn(s, GM_EY, 0, yee_rng_fill, &(yee_rng){3}), GM_OK);
  const double x[3] = {1.0, 0.75, 0.5}; /* Ey location (2, 1, 1): x = 1, y = 0.75, z = 0.5 */
  cr_assert_eq(gm_yee_field_at(s, GM_EY, 0, x), gm_yee_field(s, GM_EY, 0)[gm_yee_index(&L, 2, 1, 1)]);
  /* tangential E on the PEC walls was zeroed */
  cr_assert_eq(gm_yee_field(s, GM_EY, 0)[gm_yee_index(&L, 0, 1, 1)], 0.0);
  cr_assert_eq(gm_yee_field(s, GM_EY, 0)[gm_yee_index(&L, 2, 1, 0)], 0.0);
  cr_assert(isnan(gm_yee_field_at(s, GM_EY, 1, x)), "no imaginary part");
  size_t arrays;
  const size_t bytes = gm_yee_memory(s, &arrays);
  cr_assert_eq(arrays, 7, "six fields and the zero array (uniform vacuum: no coefficient arrays)");
  cr_assert_geq(bytes, 7 * L.size * sizeof(double));
  gm_yee_free(s);
}

typedef struct count_ctx {
  size_t calls, last;
} count_ctx;

static int count_calls(void *ctx, const gm_yee *s) {
  count_ctx *c = ctx;
  ++c->calls;
  c->last = gm_yee_step(s);
  return c->last >= 40 ? 7 : 0;
}

Test(yee, observers_independent_of_how_the_run_is_split) {
  gm_yee *a = yee_make(GM_YEE_2D_TE, 6, 6, 1, 0.1, GM_BOUNDARY_PEC, 0.9, 1);
  gm_yee *b = yee_make(GM_YEE_2D_TE, 6, 6, 1, 0.1, GM_BOUNDARY_PEC, 0.9, 1);
  count_ctx ca = {0, 0}, cb = {0, 0};
  cr_assert_eq(gm_yee_add_observer(a, 5, count_calls, &ca), GM_OK);
  cr_assert_eq(gm_yee_add_observer(b, 5, count_calls, &cb), GM_OK);
  cr_assert_eq(gm_yee_advance(a, 30), GM_OK);
  for (int i = 0; i < 10; ++i) cr_assert_eq(gm_yee_advance(b, 3), GM_OK);
  cr_assert_eq(ca.calls, 7, "steps 0, 5, ..., 30");
  cr_assert_eq(cb.calls, ca.calls);
  cr_assert_eq(gm_yee_advance(a, 20), GM_ECALLBACK, "the observer stops the run at step 40");
  cr_assert_eq(gm_yee_step(a), 40);
  cr_assert(strstr(gm_yee_errmsg(a), "returned 7"), "%s", gm_yee_errmsg(a));
  cr_assert_eq(gm_yee_advance_to(b, 20.5 * gm_yee_dt(b)), GM_OK, "in the past: nothing to do");
  cr_assert_eq(gm_yee_step(b), 30);
  cr_assert_eq(gm_yee_advance_to(b, 38.5 * gm_yee_dt(b)), GM_OK);
  cr_assert_eq(gm_yee_step(b), 38);
  gm_yee_free(a);
  gm_yee_free(b);
}

Test(yee, harminv_recovers_known_modes) {
  const size_t n = 1500;
  const double dt = 0.05;
  double *x = malloc(n * sizeof(double));
  for (size_t i = 0; i < n; ++i) {
    const double t = (double)i * dt;
    x[i] = 1.5 * cos(2 * YEE_TEST_PI * 0.8 * t + 0.3) * exp(-0.02 * t) +
           0.4 * cos(2 * YEE_TEST_PI * 1.3 * t - 1.0);
  }
  gm_harminv_mode m[10];
  size_t nm = 0;
  gm_error err = {{0}};
  cr_assert_eq(gm_harminv(n, x, NULL, dt, 0.2, 2.0, 0, 10, m, &nm, &err), GM_OK, "%s", err.message);
  cr_assert_eq(nm, 2);
  cr_assert_float_eq(m[0].frequency, 0.8, 1e-9);
  cr_assert_float_eq(m[0].decay, 0.02, 1e-9);
  cr_assert_float_eq(m[0].q, YEE_TEST_PI * 0.8 / 0.02, 1e-5);
  cr_assert_float_eq(m[0].amplitude, 0.75, 1e-8, "a real cosine splits into ±f halves");
  cr_assert_float_eq(m[1].frequency, 1.3, 1e-9);
  cr_assert_lt(fabs(m[1].decay), 1e-9);
  cr_assert_eq(gm_harminv(5, x, NULL, dt, 0.2, 2.0, 0, 10, m, &nm, &err), GM_EINVAL);
  cr_assert_eq(gm_harminv(n, x, NULL, dt, 0.2, 20.0, 0, 10, m, &nm, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "1/(2 dt)"), "%s", err.message);
  x[7] = NAN;
  cr_assert_eq(gm_harminv(n, x, NULL, dt, 0.2, 2.0, 0, 10, m, &nm, &err), GM_EINVAL);
  free(x);
}

/* A hard source sets its field to the waveform at that field's time; a soft H source is a
 * magnetic current: it changes div B by the magnetic charge it moves (an E source does not). */
Test(yee, hard_and_magnetic_sources) {
  gm_yee *s = yee_make(GM_YEE_3D, 8, 8, 8, 0.1, GM_BOUNDARY_PEC, 0.9, 1);
  const gm_waveform w = {GM_WAVE_CW, 0.7, 1.3, 0.5, 0.0, 0.2, NULL, NULL};
  gm_point_source hard = {GM_EY, {0.4, 0.35, 0.4}, GM_SOURCE_HARD, w};
  cr_assert_eq(gm_yee_add_point_source(s, &hard, NULL), GM_OK, "%s", gm_yee_errmsg(s));
  gm_point_source mag = {GM_HZ, {0.25, 0.55, 0.3}, GM_SOURCE_SOFT,
                         {GM_WAVE_GAUSSIAN, 1.0, 0.0, 0.1, 0.5, 0.0, NULL, NULL}};
  cr_assert_eq(gm_yee_add_point_source(s, &mag, NULL), GM_OK, "%s", gm_yee_errmsg(s));
  cr_assert_eq(gm_yee_advance(s, 37), GM_OK);
  cr_assert_eq(gm_yee_field_at(s, GM_EY, 0, hard.x), gm_waveform_value(&w, gm_yee_time_e(s)),
               "exactly the waveform at t_e");
  double divb;
  cr_assert_eq(gm_yee_div_b(s, NULL, &divb), GM_OK);
  /* ∫ M dt = 0.1 √(2π) over a face of area h²: div B = ± that / h in the two cells beside */
  const double expect = 0.1 * sqrt(2.0 * YEE_TEST_PI) / 0.1;
  cr_log_info("magnetic current: max |div B| %.12g, expected %.12g", divb, expect);
  cr_assert_lt(fabs(divb - expect), 1e-4 * expect);
  gm_yee_free(s);
}
