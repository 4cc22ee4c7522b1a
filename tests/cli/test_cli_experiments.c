/* geomint experiments list|run: the table as JSON, a run through the library (E4) and one
 * through its command, and the refusals of sizes the experiments cannot take (issue 26 items
 * 4, 5, 9). */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli_harness.h"
#include "geomint/experiments.h"

TestSuite(cli_experiments, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

Test(cli_experiments, list_json_has_every_row) {
  run_output r = run_cli("experiments list --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *a = parse_json(r.out);
  cr_assert(cJSON_IsArray(a));
  cr_expect_geq(cJSON_GetArraySize(a), 20);
  int seen_e4 = 0, seen_fpu = 0;
  const cJSON *row;
  cJSON_ArrayForEach(row, a) {
    const char *name = json_string(row, "name");
    cr_expect(strncmp(json_string(row, "command"), "geomint ", 8) == 0);
    json_string(row, "seed_result");
    json_string(row, "run_time");
    if (strcmp(name, "e4") == 0) {
      seen_e4 = 1;
      cr_expect(cJSON_IsTrue(cJSON_GetObjectItem(row, "in_library")));
      cr_expect_str_eq(json_string(row, "command"), "geomint maxwell e4");
    }
    if (strcmp(name, "fpu") == 0) seen_fpu = 1;
  }
  cr_expect(seen_e4 && seen_fpu);
  cJSON_Delete(a);
  run_output_free(&r);
}

/* the library's E4 and `maxwell e4` give the same numbers (docs/maxwell.md: 3620 steps,
 * leapfrog drift 4.108e-15) */
Test(cli_experiments, run_e4_json_equals_maxwell_e4) {
  run_output r = run_cli("experiments run e4 --out ex --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_eq(json_number(o, "steps"), 3620);
  cr_expect_lt(json_number(o, "leapfrog_max_rel_drift"), 2e-14);
  cr_expect_geq(json_number(o, "wall_s"), 0.0);
  cr_expect_eq(access(path_in_tmp("ex/e4-energy.csv"), R_OK), 0);
  run_output m = run_cli("maxwell e4 --out mx --json");
  cr_assert_eq(m.status, 0, "%s", m.err);
  cJSON *p = parse_json(m.out);
  cr_expect_eq(json_number(p, "plain_range_first_half"), json_number(o, "plain_range_first_half"));
  cr_expect_eq(json_number(p, "plain_mean"), json_number(o, "plain_mean"));
  cJSON_Delete(o);
  cJSON_Delete(p);
  run_output_free(&r);
  run_output_free(&m);
}

/* a row the command still computes runs through the command, into DIR */
Test(cli_experiments, run_through_the_command) {
  /* tent-vi still computes in its CLI command (run == NULL in the table): experiments run
   * must call that command with the output folder */
  const gm_experiment_info *row = gm_experiment_find("tent-vi");
  cr_assert(row != NULL && row->run == NULL, "tent-vi is no longer a CLI-run row: pick another");
  run_output r = run_cli("experiments run tent-vi --out tv");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect_eq(access(path_in_tmp("tv/tent-vi.csv"), R_OK), 0, "%s", r.out);
  run_output_free(&r);
}

Test(cli_experiments, unknown_names_and_options) {
  run_output r = run_cli("experiments run e44");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "did you mean") != NULL && strstr(r.err, "e4") != NULL, "%s", r.err);
  run_output_free(&r);
  r = run_cli("experiments list --json --markdown");
  cr_expect_eq(r.status, 2);
  run_output_free(&r);
  r = run_cli("experiments frobnicate");
  cr_expect_eq(r.status, 2);
  run_output_free(&r);
}

/* issue 26 item 4: sizes with a message naming the size, exit 2 */
Test(cli_experiments, e4_and_resonance_sizes_refused) {
  run_output r = run_cli("maxwell e4 --time 1e9 --out o");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "bytes") != NULL, "%s", r.err);
  cr_expect_eq(count_lines(r.err), 1);
  run_output_free(&r);
  r = run_cli("maxwell e4 --n 3 --time 1e-300 --out o");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "shorter than one step") != NULL, "%s", r.err);
  run_output_free(&r);
  r = run_cli("oscillatory resonance --points 1000000000000 --no-plot --out o");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "--points 1000000000000") != NULL, "%s", r.err);
  run_output_free(&r);
  r = run_cli("oscillatory resonance --points 10000000 --no-plot --out o");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "at most") == NULL && strstr(r.err, "[1, 20000]") != NULL, "%s", r.err);
  run_output_free(&r);
  r = run_cli("oscillatory fpu --points 5 --no-plot --out o");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "--points is an option of 'resonance'") != NULL, "%s", r.err);
  run_output_free(&r);
}
