/* The scene reader and the Yee library on hostile input (issue 26, hardening items 1, 2, 3, 7,
 * 8): every text in tests/data/hostile/mx_*.json is refused by gm_yee_scene_parse with a message
 * naming the key and the value or size, sizes are estimated before anything is allocated, and
 * the JSON grammar is enforced where cJSON is lenient. The library never crashes (run under
 * ASan in CI: the materials error path read freed memory). */
#include <criterion/criterion.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "geomint/yee_scene.h"

static char *slurp(const char *name) {
  char path[512];
  snprintf(path, sizeof path, "%s/tests/data/hostile/%s", GM_SOURCE_DIR, name);
  FILE *f = fopen(path, "rb");
  cr_assert_not_null(f, "cannot open %s", path);
  char *text = calloc(1 << 16, 1);
  cr_assert_not_null(text);
  size_t n = fread(text, 1, (1 << 16) - 1, f);
  fclose(f);
  text[n] = '\0';
  return text;
}

/* parse (and, when the text is a valid scene, build) must fail with a message holding needle */
static void expect_refused(const char *text, const char *needle) {
  gm_yee_scene sc;
  gm_error err = {{0}};
  gm_status st = gm_yee_scene_parse(text, "s.json", &sc, &err);
  if (st == GM_OK) {
    gm_yee *solver = NULL;
    st = gm_yee_scene_build(&sc, "s.json", &solver, &err);
    cr_expect_null(solver);
    gm_yee_free(solver);
    gm_yee_scene_clear(&sc);
  }
  cr_expect_eq(st, GM_EINVAL, "status %d for '%s' (%s)", st, needle, err.message);
  cr_expect(strstr(err.message, needle) != NULL, "message '%s' lacks '%s'", err.message, needle);
  for (const char *c = err.message; *c; ++c)
    cr_expect((unsigned char)*c >= 0x20 && (unsigned char)*c != 0x7f,
              "control byte %#x in '%s'", (unsigned char)*c, err.message);
}

static void expect_file_refused(const char *name, const char *needle) {
  char *text = slurp(name);
  expect_refused(text, needle);
  free(text);
}

Test(yee_scene_hostile, sizes_are_estimated_before_allocating) {
  /* 10^12 and 10^15 cells: the estimate (168 TB, 168 PB of fields, coefficients and
   * materials) names grid.cells; nothing is allocated */
  expect_file_refused("mx_cells_1e12.json", "grid.cells: 10000 x 10000 x 10000 cells: the "
                                            "fields, coefficients and materials need 168.1 TB");
  expect_file_refused("mx_cells_1e15_check.json", "grid.cells: 100000 x 100000 x 100000 cells");
  expect_file_refused("mx_grid_1000x1000x1000.json", "need 168.8 GB, more than this machine's");
  /* 10^15 steps of one probe and the energy series: 20 PB of records */
  expect_file_refused("mx_steps_1e15.json", "run.steps: the records of 1000000000000000 steps "
                                            "(1 probe, energy) need 20.0 PB");
}

Test(yee_scene_hostile, library_creators_refuse_sizes_with_bytes) {
  /* the materials error path read m->n_cells after freeing m (an ASan report); now the size
   * is refused before allocating, and an allocation failure reads nothing freed */
  gm_yee_grid g = {GM_YEE_3D, {10000, 10000, 10000}, {1e-4, 1e-4, 1e-4}, {0, 0, 0}};
  gm_yee_materials *m = (gm_yee_materials *)0x1;
  gm_error err = {{0}};
  cr_expect_eq(gm_yee_materials_create(&g, &m, &err), GM_EINVAL);
  cr_expect_null(m);
  cr_expect(strstr(err.message, "materials: epsilon, mu and sigma of 1000000000000 cells need "
                                "24.0 TB") != NULL, "%s", err.message);
  gm_yee *s = (gm_yee *)0x1;
  cr_expect_eq(gm_yee_create(&g, NULL, NULL, &s, &err), GM_EINVAL);
  cr_expect_null(s);
  cr_expect(strstr(err.message, "yee: the field and coefficient arrays of 10000 x 10000 x 10000 "
                                "cells need 168.1 TB") != NULL, "%s", err.message);
  /* a probe buffer of 10^15 samples (16 PB) */
  gm_yee_grid small = {GM_YEE_2D_TM, {8, 8, 1}, {0.1, 0.1, 1}, {0, 0, 0}};
  cr_assert_eq(gm_yee_create(&small, NULL, NULL, &s, &err), GM_OK, "%s", err.message);
  const double x[3] = {0.4, 0.4, 0};
  cr_expect_eq(gm_yee_add_probe(s, GM_EZ, x, (size_t)1e15, NULL), GM_EINVAL);
  cr_expect(strstr(gm_yee_errmsg(s), "probe: buffers of 1000000000000000 samples need 16.0 PB")
                != NULL, "%s", gm_yee_errmsg(s));
  cr_expect_eq(gm_yee_add_probe(s, GM_EZ, x, 100, NULL), GM_OK, "%s", gm_yee_errmsg(s));
  gm_yee_free(s);
}

Test(yee_scene_hostile, step_counts_that_overflow_are_refused) {
  /* time 1e300 or dt 1e-300 made (size_t) of 1e300 steps: 0 steps and exit 0 */
  expect_file_refused("mx_time_1e300.json",
                      "run.time: time 1e+300 at dt = 0.0350018 is 2.86e+301 steps, more than 1e+15");
  expect_file_refused("mx_dt_1e-300.json", "run.dt: time 1 at dt = 1e-300 is 1e+300 steps");
}

Test(yee_scene_hostile, values_that_overflow_in_the_run_are_refused) {
  /* ε = 1e308 gave an energy of NaN, an amplitude of 1e308 one of inf; a delay or frequency of
   * 1e308 made cos(inf) at step 1 */
  expect_file_refused("mx_eps_1e308.json",
                      "materials[0]: medium: epsilon must be in [1e-100, 1e+100] (got 1e+308)");
  expect_file_refused("mx_amp_1e308.json", "sources[0].waveform: waveform: amplitude = 1e+308 "
                                           "is beyond 1e100");
  expect_file_refused("mx_wf_delay_huge.json", "waveform: delay = 1e+308 is beyond 1e100");
  expect_file_refused("mx_wf_freq_huge.json", "waveform: frequency = 1e+308 is beyond 1e100");
  gm_waveform w = {.kind = GM_WAVE_GAUSSIAN, .amplitude = 1, .frequency = 1, .width = 1e-200};
  gm_error err = {{0}};
  cr_expect_eq(gm_waveform_check(&w, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "width = 1e-200 is below 1e-100") != NULL, "%s", err.message);
  w.width = 1e-50; /* within the bounds: accepted, and finite at its peak */
  cr_expect_eq(gm_waveform_check(&w, &err), GM_OK, "%s", err.message);
}

Test(yee_scene_hostile, json_text_is_strict) {
  expect_file_refused("mx_trailing_garbage.json", "line 1, column 423: not valid JSON: text "
                                                  "after the end of the scene object");
  expect_file_refused("mx_two_objects.json", "line 1, column 422: not valid JSON: text after");
  expect_file_refused("mx_dup_grid.json", "s.json: grid: given twice");
  expect_file_refused("mx_courant_and_dt.json", "run: give \"dt\" or \"courant\", not both");
  expect_file_refused("mx_nonutf8_in_string.json",
                      "line 1, column 299: not valid JSON: bytes that are not UTF-8 in a string");
  /* a raw ESC from a \u escape in a key is written \x1b in the message */
  expect_file_refused("mx_esc_seq_key.json", "s.json: \\x1b[31mred: unknown key");
  /* numbers: leading zeros, a bare decimal point, an exponent without digits */
  static const char *const base =
      "{\"grid\": {\"dim\": \"1d\", \"cells\": [%s], \"size\": [1]}, \"run\": {\"steps\": 5}}";
  static const struct { const char *number, *why; } numbers[] = {
      {"050", "line 1, column 34: not valid JSON: a number with a leading zero"},
      {"-07", "a number with a leading zero"},
      {"50.", "a decimal point without digits after it"},
      {"5e", "an exponent without digits"},
      {"-", "a minus sign without digits"}};
  char text[256];
  for (size_t k = 0; k < sizeof numbers / sizeof *numbers; ++k) {
    snprintf(text, sizeof text, base, numbers[k].number);
    expect_refused(text, numbers[k].why);
  }
  snprintf(text, sizeof text, base, "50");
  gm_yee_scene sc;
  gm_error err = {{0}};
  cr_expect_eq(gm_yee_scene_parse(text, "s.json", &sc, &err), GM_OK, "%s", err.message);
  gm_yee_scene_clear(&sc);
  snprintf(text, sizeof text, base, "2.5e-0"); /* a valid number that is not a whole count */
  expect_refused(text, "grid.cells[0]: expected a positive whole number of cells, got 2.5");
  /* a duplicate deep inside, a raw control byte in a string, an escaped one in a probe name */
  expect_refused("{\"grid\": {\"dim\": \"1d\", \"cells\": [4], \"size\": [1], \"size\": [2]}, "
                 "\"run\": {\"steps\": 5}}", "s.json: grid.size: given twice");
  expect_refused("{\"grid\": {\"dim\": \"1d\x07\", \"cells\": [4], \"size\": [1]}, "
                 "\"run\": {\"steps\": 5}}",
                 "line 1, column 21: not valid JSON: a raw control character in a string");
  expect_refused("{\"grid\": {\"dim\": \"1d\", \"cells\": [4], \"size\": [1]}, \"probes\": "
                 "[{\"name\": \"a\\u0007b\", \"component\": \"Ez\", \"position\": [0.5]}], "
                 "\"run\": {\"steps\": 5}}",
                 "probes[0].name: a probe name (a CSV column) may not hold commas, quotes or "
                 "control characters");
}

Test(yee_scene_hostile, a_directory_or_a_fifo_says_what_it_is) {
  char dir[] = "/tmp/geomint-scene-XXXXXX";
  cr_assert_not_null(mkdtemp(dir));
  gm_yee_scene sc;
  gm_error err = {{0}};
  cr_expect_eq(gm_yee_scene_load(dir, &sc, &err), GM_EIO);
  cr_expect(strstr(err.message, "is a directory, not a file") != NULL, "%s", err.message);
  /* a FIFO without a writer blocked open(2) forever; now it reads as an empty file at once */
  char fifo[300];
  snprintf(fifo, sizeof fifo, "%s/scene.json", dir);
  cr_assert_eq(mkfifo(fifo, 0600), 0, "%s", strerror(errno));
  time_t t0 = time(NULL);
  cr_expect_eq(gm_yee_scene_load(fifo, &sc, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "scene.json: the file is empty") != NULL, "%s", err.message);
  cr_expect_lt(time(NULL) - t0, 5);
  unlink(fifo);
  rmdir(dir);
}
