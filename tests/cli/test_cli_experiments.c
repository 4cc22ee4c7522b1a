/* geomint experiments list|run: the table as JSON, runs through the library (E4, tent-vi, b10)
 * equal to their commands, and the refusals of sizes the experiments cannot take (issue 26 items
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
    /* no hand-written run time: a run's time is its measured wall_s */
    cr_expect(cJSON_GetObjectItem(row, "run_time") == NULL);
    if (strcmp(name, "e4") == 0) {
      seen_e4 = 1;
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

/* every row's computation is a library function (issue 26: the CLI only parses and prints) */
Test(cli_experiments, every_row_runs_in_the_library) {
  cr_expect_eq(gm_experiment_count(), 20);
  for (size_t i = 0; i < gm_experiment_count(); ++i)
    cr_expect(gm_experiment_at(i)->run != NULL, "%s has no library function",
              gm_experiment_at(i)->name);
}

/* experiments run tent-vi is pde tent-vi: the same numbers and the state file in DIR */
Test(cli_experiments, run_tent_vi_equals_its_command) {
  run_output r = run_cli("experiments run tent-vi --out tv --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect_eq(access(path_in_tmp("tv/tent-vi.csv"), R_OK), 0, "%s", r.out);
  cJSON *o = parse_json(r.out);
  run_output m = run_cli("pde tent-vi --json");
  cr_assert_eq(m.status, 0, "%s", m.err);
  cJSON *p = parse_json(m.out);
  cr_expect_eq(json_number(o, "max_abs_error"), json_number(p, "max_abs_error"));
  cr_expect_eq(json_number(o, "max_rel_energy_error"), json_number(p, "max_rel_energy_error"));
  cr_expect_eq(json_number(o, "steps"), 100);
  cJSON_Delete(o);
  cJSON_Delete(p);
  run_output_free(&r);
  run_output_free(&m);
}

/* B10 through the library: LF unstable at dt = dx, EC and MS bounded to t = 500; at 2 dx EC
 * stops early and MS reaches t = 100 (docs/pde.md) */
Test(cli_experiments, run_b10_equals_its_command) {
  run_output r = run_cli("experiments run b10 --out b --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_lt(json_number(o, "lf_1_t"), 500.0);
  cr_expect_float_eq(json_number(o, "ec_1_t"), 500.0, 1e-9);
  cr_expect_float_eq(json_number(o, "ms_1_t"), 500.0, 1e-9);
  cr_expect_lt(json_number(o, "ec_2_t"), 100.0);
  cr_expect_float_eq(json_number(o, "ms_2_t"), 100.0, 1e-9);
  cr_expect_eq(access(path_in_tmp("b/b10-ms-2.dat"), R_OK), 0);
  run_output m = run_cli("pde b10 --no-plot --out b2 --json");
  cr_assert_eq(m.status, 0, "%s", m.err);
  cJSON *p = parse_json(m.out);
  const cJSON *runs = cJSON_GetObjectItem(p, "runs");
  cr_assert(cJSON_IsArray(runs) && cJSON_GetArraySize(runs) == 5);
  cr_expect_eq(json_number(cJSON_GetArrayItem(runs, 0), "t"), json_number(o, "lf_1_t"));
  cr_expect_eq(json_number(cJSON_GetArrayItem(runs, 3), "t"), json_number(o, "ec_2_t"));
  cJSON_Delete(o);
  cJSON_Delete(p);
  run_output_free(&r);
  run_output_free(&m);
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
