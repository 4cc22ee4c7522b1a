/* Subpixel smoothing (yee_smoothing.c): the ε an edge gets where a planar interface cuts its
 * pixel (read back from the electric energy of a field on that one edge), and the scene key
 * eps_averaging. */
#include <stdio.h>

#include "yee_util.h"

/* ε of edge (i, j) of component c: the energy ½ V ε E² of E = 1 on that edge alone (2-D,
 * interior edge: V = h²). */
static double edge_epsilon(gm_yee *s, gm_yee_component c, long i, long j, double h) {
  gm_yee_layout L;
  gm_yee_get_layout(s, &L);
  double *v = calloc(L.size, sizeof *v);
  cr_assert_not_null(v);
  v[gm_yee_index(&L, i, j, 0)] = 1.0;
  cr_assert_eq(gm_yee_set_field(s, c, 0, v), GM_OK);
  gm_yee_energy e;
  cr_assert_eq(gm_yee_get_energy(s, &e), GM_OK);
  memset(v, 0, L.size * sizeof *v);
  cr_assert_eq(gm_yee_set_field(s, c, 0, v), GM_OK);
  free(v);
  return 2.0 * e.electric / (h * h);
}

/* Glass (ε = 4) for x <= 0.43 on a grid of h = 0.1: the pixel of E_x at x = 0.45 (cell 4,
 * [0.4, 0.5]) is 30 % glass and E_x is across the interface: 1/ε = 0.3/4 + 0.7/1 (the harmonic
 * mean); the pixel of E_y at x = 0.4 ([0.35, 0.45]) is 80 % glass and E_y is along it: ε = 0.8·4
 * + 0.2 (the arithmetic mean). The staircase (cell 4's centre 0.45 is outside): 1 and 2.5. */
Test(yee_smoothing, planar_interface_averages) {
  const double h = 0.1;
  gm_yee_grid g = {GM_YEE_2D_TE, {8, 8, 1}, {h, h, 1}, {0, 0, 0}};
  gm_yee_materials *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_materials_create(&g, &m, &err), GM_OK);
  const gm_medium glass = {4.0, 1.0, 0.0};
  const double lo[3] = {-1, -1, 0}, hi[3] = {0.43, 2, 0};
  cr_assert_eq(gm_yee_paint_box(m, lo, hi, &glass), GM_OK);
  for (int smooth = 0; smooth < 2; ++smooth) {
    gm_yee_options o = gm_yee_defaults();
    o.smoothing = smooth ? GM_YEE_SMOOTHING_ANISOTROPIC : GM_YEE_SMOOTHING_NONE;
    gm_yee *s = NULL;
    cr_assert_eq(gm_yee_create(&g, m, &o, &s, &err), GM_OK, "%s", err.message);
    const double ex = edge_epsilon(s, GM_EX, 4, 3, h), ey = edge_epsilon(s, GM_EY, 4, 3, h);
    const double ey5 = edge_epsilon(s, GM_EY, 5, 3, h), ex2 = edge_epsilon(s, GM_EX, 2, 3, h);
    if (smooth) {
      cr_assert_float_eq(ex, 1.0 / (0.3 / 4.0 + 0.7), 1e-9, "Ex: %.15g", ex); /* normal by differences: ~1e-11 */
      cr_assert_float_eq(ey, 0.8 * 4.0 + 0.2, 1e-9, "Ey: %.15g", ey);
    } else {
      cr_assert_float_eq(ex, 1.0, 1e-9, "Ex: %.15g", ex); /* normal by differences: ~1e-11 */
      cr_assert_float_eq(ey, 2.5, 1e-12, "Ey: %.15g", ey);
    }
    /* pixels of one medium keep it either way */
    cr_assert_float_eq(ey5, 1.0, 1e-12, "Ey at x = 0.5: %.15g", ey5);
    cr_assert_float_eq(ex2, 4.0, 1e-12, "Ex at x = 0.25: %.15g", ex2);
    gm_yee_free(s);
  }
  gm_yee_materials_free(m);
}

static const char *scene_text(const char *extra) {
  static char buf[1024];
  snprintf(buf, sizeof buf,
           "{\"grid\": {\"dim\": \"2d-tm\", \"cells\": [10, 10], \"size\": [1, 1]},%s"
           " \"run\": {\"steps\": 1}}",
           extra);
  return buf;
}

Test(yee_smoothing, scene_key_eps_averaging) {
  gm_yee_scene sc;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_scene_parse(scene_text(""), "s.json", &sc, &err), GM_OK, "%s",
               err.message);
  cr_assert_eq(sc.options.smoothing, GM_YEE_SMOOTHING_ANISOTROPIC);
  gm_yee_scene_clear(&sc);
  cr_assert_eq(gm_yee_scene_parse(scene_text(" \"eps_averaging\": false,"), "s.json", &sc, &err),
               GM_OK, "%s", err.message);
  cr_assert_eq(sc.options.smoothing, GM_YEE_SMOOTHING_NONE);
  gm_yee_scene_clear(&sc);
  cr_assert_eq(gm_yee_scene_parse(scene_text(" \"eps_averaging\": 1,"), "s.json", &sc, &err),
               GM_EINVAL);
  cr_assert(strstr(err.message, "s.json: eps_averaging: expected true or false") != NULL, "%s",
            err.message);
}
