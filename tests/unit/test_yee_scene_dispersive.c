/* Scene keys of dispersive media ("poles", "library", "unit_um"): a scene with them builds a
 * solver with the same poles as the C API; bad values are errors naming the JSON path. */
#include <stdio.h>

#include "geomint/yee_scene.h"
#include "yee_util.h"

static const char *head =
    "{\"grid\": {\"dim\": \"1d\", \"cells\": [100], \"size\": [1.0]},"
    " \"run\": {\"steps\": 10},";

static gm_status parse(const char *materials, gm_yee_scene *sc, gm_error *err) {
  char text[2048];
  snprintf(text, sizeof text, "%s %s}", head, materials);
  return gm_yee_scene_parse(text, "s.json", sc, err);
}

static void expect_error(const char *materials, const char *path) {
  gm_yee_scene sc;
  gm_error err = {{0}};
  cr_assert_eq(parse(materials, &sc, &err), GM_EINVAL, "accepted: %s", materials);
  cr_assert(strstr(err.message, path) != NULL, "\"%s\" does not name %s", err.message, path);
}

Test(yee_scene_dispersive, bad_poles_name_the_path) {
  expect_error("\"materials\": [{\"shape\": \"box\", \"lo\": [0.2], \"hi\": [0.4], \"poles\": "
               "[{\"type\": \"lorentz\", \"frequency\": 1, \"gamma\": -0.5, \"delta_epsilon\": 2}]}]",
               "s.json: materials[0].poles[0].gamma: the damping rate must be >= 0");
  expect_error("\"materials\": [{\"shape\": \"box\", \"lo\": [0.2], \"hi\": [0.4]},"
               " {\"shape\": \"box\", \"lo\": [0.5], \"hi\": [0.6], \"poles\": "
               "[{\"type\": \"lorentz\", \"frequency\": 1, \"delta_epsilon\": 2},"
               " {\"type\": \"drude\", \"frequency\": 0}]}]",
               "s.json: materials[1].poles[1].frequency: the plasma frequency must be > 0");
  expect_error("\"background\": {\"poles\": [{\"type\": \"lorentz\", \"frequency\": 1}]}",
               "background.poles[0].delta_epsilon: missing");
  expect_error("\"background\": {\"poles\": [{\"type\": \"debye\", \"frequency\": 1}]}",
               "background.poles[0].type");
  expect_error("\"background\": {\"poles\": [{\"type\": \"drude\", \"frequency\": 1, "
               "\"delta_epsilon\": 3}]}",
               "background.poles[0].delta_epsilon: a Drude pole has no");
  expect_error("\"background\": {\"library\": \"Cu\"}", "background.library: material: no \"Cu\"");
  expect_error("\"unit_um\": -1, \"background\": {\"library\": \"Au\"}", "unit_um: must be > 0");
  expect_error("\"background\": {\"pole\": []}", "background.pole");
}

/* The scene's Drude box gives the same fields as the C API's. */
Test(yee_scene_dispersive, scene_equals_c_api) {
  gm_yee_scene sc;
  gm_error err = {{0}};
  cr_assert_eq(parse("\"materials\": [{\"shape\": \"box\", \"lo\": [0.5], \"hi\": [1.0], "
                     "\"epsilon\": 2, \"poles\": [{\"type\": \"drude\", \"frequency\": 3, "
                     "\"gamma\": 0.2}, {\"type\": \"lorentz\", \"frequency\": 4, \"gamma\": 0.1, "
                     "\"delta_epsilon\": 0.5}]}],"
                     " \"sources\": [{\"type\": \"point\", \"component\": \"Ez\", "
                     "\"position\": [0.3], \"waveform\": {\"kind\": \"gaussian\", "
                     "\"frequency\": 3, \"width\": 0.1, \"delay\": 0.4}}]",
                     &sc, &err),
               GM_OK, "%s", err.message);
  cr_assert_eq(gm_yee_materials_n_dispersive(sc.materials), 1);
  gm_yee *a = NULL;
  cr_assert_eq(gm_yee_scene_build(&sc, "s.json", &a, &err), GM_OK, "%s", err.message);

  gm_yee_grid g = {GM_YEE_1D, {100, 1, 1}, {0.01, 1, 1}, {0, 0, 0}};
  gm_yee_materials *m = NULL;
  cr_assert_eq(gm_yee_materials_create(&g, &m, &err), GM_OK);
  const gm_pole poles[2] = {{GM_POLE_DRUDE, 3, 0.2, 0}, {GM_POLE_LORENTZ, 4, 0.1, 0.5}};
  const gm_medium md = {2, 1, 0};
  const double lo[3] = {0.5, 0, 0}, hi[3] = {1.0, 0, 0};
  cr_assert_eq(gm_yee_materials_set_poles(m, 2, poles), GM_OK);
  cr_assert_eq(gm_yee_paint_box(m, lo, hi, &md), GM_OK);
  gm_yee *b = NULL;
  cr_assert_eq(gm_yee_create(&g, m, &sc.options, &b, &err), GM_OK, "%s", err.message);
  const gm_point_source src = {GM_EZ, {0.3, 0, 0}, GM_SOURCE_SOFT,
                               {GM_WAVE_GAUSSIAN, 1.0, 3.0, 0.1, 0.4, 0.0, NULL, NULL}};
  cr_assert_eq(gm_yee_add_point_source(b, &src, NULL), GM_OK);
  cr_assert_eq(gm_yee_advance(a, 300), GM_OK);
  cr_assert_eq(gm_yee_advance(b, 300), GM_OK);
  gm_yee_layout L;
  gm_yee_get_layout(a, &L);
  cr_assert_eq(memcmp(gm_yee_field(a, GM_EZ, 0), gm_yee_field(b, GM_EZ, 0), L.size * 8), 0);
  gm_yee_energy e;
  gm_yee_get_energy(a, &e);
  cr_assert_gt(e.polarization, 0.0);
  gm_yee_free(a);
  gm_yee_free(b);
  gm_yee_materials_free(m);
  gm_yee_scene_clear(&sc);

  /* the library: Au in a scene with unit_um 0.5 has 6 poles */
  cr_assert_eq(parse("\"unit_um\": 0.5, \"materials\": [{\"shape\": \"box\", \"lo\": [0.5], "
                     "\"hi\": [1.0], \"library\": \"au\"}]", &sc, &err),
               GM_OK, "%s", err.message);
  cr_assert_eq(gm_yee_materials_n_dispersive(sc.materials), 1);
  gm_yee_scene_clear(&sc);
}
