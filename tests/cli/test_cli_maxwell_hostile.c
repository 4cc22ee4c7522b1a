/* `geomint maxwell run` and `geomint run` on hostile input (issue 26, hardening items 1, 2, 3,
 * 7, 8): each file in tests/data/hostile/mx_*.json exits 2 with one clean line naming the key
 * and the value or size; a run whose results are not finite or whose harminv fails never exits
 * 0; `--threads 0` and a step count past 10^15 are refused. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli_harness.h"

TestSuite(cli_maxwell_hostile, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

static void expect_one_clean_line(const char *err) {
  cr_expect_eq(count_lines(err), 1, "one line on stderr: %s", err);
  for (const char *c = err; *c; ++c)
    cr_expect(*c == '\n' || ((unsigned char)*c >= 0x20 && (unsigned char)*c != 0x7f),
              "control byte %#x on stderr", (unsigned char)*c);
}

static void expect_usage_error(const char *file, const char *extra, const char *needle) {
  run_output r = run_cli("maxwell run %s/tests/data/hostile/%s --out o %s", GM_SOURCE_DIR, file,
                         extra);
  cr_expect_eq(r.status, 2, "%s: exit %d, stderr %s", file, r.status, r.err);
  cr_expect(strstr(r.err, needle) != NULL, "%s: stderr '%s' lacks '%s'", file, r.err, needle);
  expect_one_clean_line(r.err);
  cr_expect_eq(r.out[0], '\0', "%s: nothing on stdout: %s", file, r.out);
  run_output_free(&r);
}

Test(cli_maxwell_hostile, every_hostile_scene_exits_2_naming_the_key) {
  static const struct { const char *file, *needle; } cases[] = {
      {"mx_cells_1e12.json", "grid.cells: 10000 x 10000 x 10000 cells: the fields, "
                             "coefficients and materials need 168.1 TB"},
      {"mx_steps_1e15.json", "run.steps: the records of 1000000000000000 steps (1 probe, "
                             "energy) need 20.0 PB"},
      {"mx_time_1e300.json", "run.time: time 1e+300 at dt = 0.0350018 is 2.86e+301 steps"},
      {"mx_dt_1e-300.json", "run.dt: time 1 at dt = 1e-300 is 1e+300 steps, more than 1e+15"},
      {"mx_eps_1e308.json", "materials[0]: medium: epsilon must be in [1e-100, 1e+100]"},
      {"mx_amp_1e308.json", "sources[0].waveform: waveform: amplitude = 1e+308"},
      {"mx_wf_delay_huge.json", "sources[0].waveform: waveform: delay = 1e+308"},
      {"mx_wf_freq_huge.json", "sources[0].waveform: waveform: frequency = 1e+308"},
      {"mx_trailing_garbage.json", "text after the end of the scene object"},
      {"mx_two_objects.json", "text after the end of the scene object"},
      {"mx_dup_grid.json", "mx_dup_grid.json: grid: given twice"},
      {"mx_courant_and_dt.json", "run: give \"dt\" or \"courant\", not both"},
      {"mx_nonutf8_in_string.json", "bytes that are not UTF-8 in a string"},
      {"mx_esc_seq_key.json", "\\x1b[31mred: unknown key"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof *cases; ++k)
    expect_usage_error(cases[k].file, "", cases[k].needle);
  /* --check reads the same way (it used to read freed memory on 10^15 cells) */
  expect_usage_error("mx_cells_1e15_check.json", "--check", "need 168.0 PB");
}

Test(cli_maxwell_hostile, a_directory_is_not_a_scene) {
  run_output r = run_cli("maxwell run . --out o");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, ". is a directory, not a file") != NULL, "%s", r.err);
  run_output_free(&r);
}

Test(cli_maxwell_hostile, threads_and_steps_out_of_range) {
  run_output r = run_cli("maxwell run %s/examples/maxwell_scene.json --threads 0",
                         GM_SOURCE_DIR);
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "--threads must be in [1, 4096], got 0") != NULL, "%s", r.err);
  run_output_free(&r);
  /* 10^16 steps ran (practically) forever; the driver's limit is 10^15 */
  r = run_cli("run kepler --steps 10000000000000000");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "--steps 10000000000000000 is more than 1e15") != NULL, "%s", r.err);
  run_output_free(&r);
}

Test(cli_maxwell_hostile, a_failed_harminv_is_a_failed_run) {
  /* harminv from t = 1.3 in a run of 20 steps (t_end = 1.40): two samples, harminv fails; the
   * summary says which probe, and the exit status is 1 (it was 0). (`after` beyond the end is
   * refused before the run: test_cli_maxwell.c) */
  FILE *f = fopen(path_in_tmp("late.json"), "w");
  cr_assert_not_null(f);
  fputs("{\"grid\": {\"dim\": \"2d-tm\", \"cells\": [10, 10], \"size\": [1, 1]},"
        " \"sources\": [{\"type\": \"point\", \"component\": \"Ez\", \"position\": [0.5, 0.5],"
        " \"waveform\": {\"kind\": \"gaussian\", \"frequency\": 1, \"width\": 0.5, \"delay\": 2}}],"
        " \"probes\": [{\"name\": \"p\", \"component\": \"Ez\", \"position\": [0.3, 0.3]}],"
        " \"output\": {\"harminv\": {\"f_min\": 0.3, \"f_max\": 2, \"after\": 1.3}},"
        " \"run\": {\"steps\": 20}}", f);
  fclose(f);
  run_output r = run_cli("maxwell run late.json --out o");
  cr_expect_eq(r.status, 1, "exit %d: %s", r.status, r.err);
  cr_expect(strstr(r.err, "probe p: harminv failed") != NULL, "%s", r.err);
  run_output_free(&r);
}

Test(cli_maxwell_hostile, vtu_prefix_folder_is_created) {
  /* docs/cli.md's `--vtu snap/s` failed on a fresh folder; it is made as --out folders are */
  run_output r = run_cli("maxwell mesh --rect 8 --t-end 0.2 --vtu snap/s");
  cr_expect_eq(r.status, 0, "%s", r.err);
  FILE *f = fopen(path_in_tmp("snap/s.pvd"), "r");
  cr_expect_not_null(f, "snap/s.pvd was not written: %s", r.err);
  if (f != NULL) fclose(f);
  run_output_free(&r);
}
