/* Bad input found by trying it (issue 17, items 3, 4, 8, 9): endless and huge files, control
 * bytes in messages, states off a constraint manifold, parameters that overflow. Each is an error
 * with one clear line on stderr (or a documented behaviour), never an endless run or a NaN. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli/cli_harness.h"

TestSuite(cli_hostile, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

static double seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void expect_one_clean_line(const char *err) {
  cr_expect_eq(count_lines(err), 1, "one line on stderr: %s", err);
  for (const char *c = err; *c; ++c)
    cr_expect(*c == '\n' || ((unsigned char)*c >= 0x20 && (unsigned char)*c != 0x7f),
              "control byte %#x on stderr", (unsigned char)*c);
}

Test(cli_hostile, endless_input_stops_at_once) {
  cr_assert_eq(symlink("/dev/zero", path_in_tmp("zero.msh")), 0);
  double t0 = seconds();
  run_output r = run_cli("mesh info zero.msh");
  cr_expect_neq(r.status, 0);
  cr_expect(strstr(r.err, "zero.msh: line 1: a NUL byte (binary data)") != NULL, "%s", r.err);
  expect_one_clean_line(r.err);
  run_output_free(&r);
  r = run_cli("run n-body --set file=/dev/zero --steps 1");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "/dev/zero:1: a NUL byte") != NULL, "%s", r.err);
  run_output_free(&r);
  /* a line with no end */
  FILE *f = fopen(path_in_tmp("long.txt"), "w");
  cr_assert_not_null(f);
  for (int i = 0; i < 10000; ++i) fputs("1 ", f);
  fclose(f);
  r = run_cli("run n-body --set file=long.txt --steps 1");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "long.txt:1: a line longer than 4096 bytes") != NULL, "%s", r.err);
  run_output_free(&r);
  cr_expect_lt(seconds() - t0, 20.0, "the three refusals took %.1f s", seconds() - t0);
}

Test(cli_hostile, mesh_size_limit_is_named_and_can_be_raised) {
  FILE *f = fopen(path_in_tmp("big.off"), "w");
  cr_assert_not_null(f);
  fputs("OFF\n3 1 0\n", f);
  for (int i = 0; i < 200000; ++i) fputs("# padding\n", f); /* 2 MB */
  fputs("0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", f);
  fclose(f);
  run_output r = run_cli("mesh info big.off --max-file-size 1M");
  cr_expect_neq(r.status, 0);
  cr_expect(strstr(r.err, "more than the limit of 1048576 bytes for a mesh file (raise it with "
                          "--max-file-size)") != NULL,
            "%s", r.err);
  expect_one_clean_line(r.err);
  run_output_free(&r);
  r = run_cli("mesh info big.off --max-file-size 4M --json");
  cr_expect_eq(r.status, 0, "%s", r.err);
  run_output_free(&r);
  r = run_cli("mesh info big.off --max-file-size 12X");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "--max-file-size 12X: expected a size") != NULL, "%s", r.err);
  run_output_free(&r);
}

Test(cli_hostile, file_bytes_are_escaped_on_the_terminal) {
  FILE *f = fopen(path_in_tmp("esc.off"), "w");
  cr_assert_not_null(f);
  fputs("OFF\n3 1 0\n0 0 0\n1\033]0;owned\a 0 0\n0 1 0\n3 0 1 2\n", f);
  fclose(f);
  run_output r = run_cli("mesh info esc.off");
  cr_expect_neq(r.status, 0);
  cr_expect(strstr(r.err, "found '1\\x1b]0;owned\\x07'") != NULL, "%s", r.err);
  expect_one_clean_line(r.err);
  run_output_free(&r);
  f = fopen(path_in_tmp("bodies.txt"), "w");
  cr_assert_not_null(f);
  fputs("1 0 0 0 0 0 0\n1 1\033[2J 0 0 0 0 0\n", f);
  fclose(f);
  r = run_cli("run n-body --set file=bodies.txt --steps 1");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "bodies.txt:2: '1\\x1b[2J' is not a number") != NULL, "%s", r.err);
  expect_one_clean_line(r.err);
  run_output_free(&r);
}

/* Item 8: a constrained problem starts on its constraint manifold or not at all (exit 2); a
 * state typed to 10 digits on it runs. Before, q1=5 was projected silently (energy error 1049 %). */
Test(cli_hostile, state_off_the_constraint_manifold_is_refused) {
  run_output r = run_cli("run spherical-pendulum --method vi-midpoint --set q1=5 --steps 10");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "spherical-pendulum: the initial positions are off the constraint "
                          "manifold: constraint 1 is g = 12.1, not 0") != NULL,
            "%s", r.err);
  expect_one_clean_line(r.err);
  run_output_free(&r);
  r = run_cli("run spherical-pendulum --method vi-midpoint --set p3=1 --steps 10 --json");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "the initial velocity is not tangent to the constraint manifold") != NULL,
            "%s", r.err);
  run_output_free(&r);
  r = run_cli("run double-spherical-pendulum --method vi-midpoint --set q6=0 --steps 10");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "off the constraint manifold: constraint 2") != NULL, "%s", r.err);
  run_output_free(&r);
  /* theta0 = 0.5 typed by hand: sin 0.5 = 0.4794255386, -cos 0.5 = -0.8775825619, p along y */
  r = run_cli("run spherical-pendulum --method vi-midpoint --set q1=0.4794255386 "
              "--set q3=-0.8775825619 --set p2=0.9 --steps 100 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_lt(json_number(o, "max_rel_energy_error"), 1e-4); /* measured 2.7e-5 */
  cJSON_Delete(o);
  run_output_free(&r);
}

/* Item 9: overflow is called overflow and names the value, a true singularity stays one. */
Test(cli_hostile, overflow_is_not_a_singular_point) {
  const char *cases[][2] = {
      {"run fpu --set omega=1e300 --steps 1", "the energy of the initial state is not finite (-nan): "
                                              "double precision overflows with these values (the "
                                              "most extreme: omega = 1e+300)"},
      {"run j2-satellite --set r0=1e-300 --steps 1", "(the most extreme: r0 = 1e-300)"},
      {"run kepler --set q1=0 --set q2=0 --steps 1", "the energy of the initial state is -inf (a "
                                                     "singular point)"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    run_output r = run_cli("%s", cases[i][0]);
    cr_expect_eq(r.status, 2, "%s", cases[i][0]);
    cr_expect(strstr(r.err, cases[i][1]) != NULL, "%s: %s", cases[i][0], r.err);
    if (i < 2) cr_expect(strstr(r.err, "singular") == NULL, "%s", r.err);
    run_output_free(&r);
  }
}

/* Item 9: a mesh with coordinates of 1e160 has edges of 1e160 and volumes past double: said so. */
Test(cli_hostile, mesh_quality_far_from_unit_scale) {
  FILE *f = fopen(path_in_tmp("huge.off"), "w");
  cr_assert_not_null(f);
  fputs("OFF\n4 2 0\n0 0 0\n1e160 0 0\n0 1e160 0\n1e160 1e160 0\n3 0 1 2\n3 1 3 2\n", f);
  fclose(f);
  run_output r = run_cli("mesh info huge.off --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect(fabs(json_number(o, "shortest_edge") / 1e160 - 1) < 1e-15);
  cr_expect(fabs(json_number(o, "longest_edge") / (sqrt(2.0) * 1e160) - 1) < 1e-15);
  cr_expect_eq(json_number(o, "volumes_out_of_range"), 2);
  cr_expect_eq(json_number(o, "degenerate"), 0);
  cr_expect(strstr(json_string(o, "geometry_error"), "outside double precision") != NULL);
  cJSON_Delete(o);
  run_output_free(&r);
  f = fopen(path_in_tmp("big.off"), "w");
  cr_assert_not_null(f);
  fputs("OFF\n4 2 0\n0 0 0\n1e100 0 0\n0 1e100 0\n1e100 1e100 0\n3 0 1 2\n3 1 3 2\n", f);
  fclose(f);
  r = run_cli("mesh info big.off --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  o = parse_json(r.out);
  const cJSON *s0 = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "hodge_star_min"), 0);
  cr_assert_not_null(s0);
  cr_expect(fabs(s0->valuedouble / 0.25e200 - 1) < 1e-14, "star 0 = %g", s0->valuedouble);
  const cJSON *neg = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "negative_duals"), 0);
  cr_expect_eq(neg->valuedouble, 0);
  cJSON_Delete(o);
  run_output_free(&r);
}

/* Item 11: docs/cli.md's failure example is what the program prints (it quoted 30 Newton
 * iterations where the program says 100). */
Test(cli_hostile, docs_failure_example_is_the_program_output) {
  char path[512];
  snprintf(path, sizeof path, "%s/docs/cli.md", GM_SOURCE_DIR);
  char *doc = read_file(path);
  /* (test_docs.c re-runs it too; the CSV goes to /tmp, not into the source tree) */
  const char *cmd = "$ geomint run kepler --method midpoint --set p2=0 --out /tmp/fall.csv\n";
  const char *at = strstr(doc, cmd);
  cr_assert_not_null(at, "docs/cli.md lost the failure example");
  at += strlen(cmd);
  const char *end = strchr(at, '\n');
  cr_assert_not_null(end);
  run_output r = run_cli("run kepler --method midpoint --set p2=0 --out /tmp/fall.csv");
  cr_expect_eq(r.status, 1);
  cr_expect(strncmp(r.err, at, (size_t)(end - at)) == 0 && r.err[end - at] == '\n',
            "docs: %.*s\nprogram: %s", (int)(end - at), at, r.err);
  run_output_free(&r);
  free(doc);
}

/* Item 11: Gauss and Lobatto IIIA-IIIB of any stage count by name. */
Test(cli_hostile, stage_count_by_name) {
  run_output r = run_cli("run kepler --method gauss-12 --dt 0.5 --t-end 20 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_str_eq(json_string(o, "method"), "gauss-12");
  cr_expect_lt(json_number(o, "max_rel_energy_error"), 1e-8); /* measured 8.6e-10 */
  cJSON_Delete(o);
  run_output_free(&r);
  r = run_cli("run henon-heiles --method lobatto-iiia-iiib-7 --dt 0.1 --steps 100 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  run_output_free(&r);
  r = run_cli("run kepler --method gauss-65");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "gauss-65: 65 stages; gauss-s is made for 1 <= s <= 64") != NULL, "%s",
            r.err);
  run_output_free(&r);
  r = run_cli("run kepler --method gaus-12");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "unknown method 'gaus-12'") != NULL, "%s", r.err);
  run_output_free(&r);
}

/* Issue 26 items 2-5 and 9 (inputs of ../shared/hostile/): sizes past a documented bound, step
 * counts that would overflow, NaN coordinates, and options a command would ignore are refused
 * at once with exit 2 and one line naming the option. */
Test(cli_hostile, issue26_refused_with_the_option_named) {
  static const struct {
    const char *args, *want;
  } cases[] = {
      {"maxwell mesh --rect 100000", "--rect 100000: at most 1000"},
      {"maxwell mesh --rect 8 --fraction 0 --avi", "--fraction 0: must be in"},
      {"maxwell mesh --rect 8 --dt 0", "--dt must be a positive finite number"},
      {"maxwell mesh --rect 8 --avi --fraction 1e-12", "--fraction 1e-12"},
      {"maxwell mesh --rect 8 --avi --t-end 1e15", "--t-end 1e+15 is"},
      {"maxwell mesh --rect 8 --t-end 1e15", "at most 1e+09"},
      {"maxwell mesh --rect 8 --dt 1e-300 --t-end 0.5", "steps of dt 1e-300"},
      {"maxwell mesh --rect 8 --material 0,0,1,1,1e-300,1", "--material 0,0,1,1,1e-300,1"},
      {"maxwell mesh --rect 8 --probe nan,0.2", "--probe nan,0.2: the coordinates must be"},
      {"maxwell mesh --rect 8 --courant 0.5 --avi", "--courant is not an option of --avi"},
      {"maxwell mesh-cavity --n0 2", "--n0 2: must be in [3, 40]"},
      {"maxwell mesh-cavity --t-end 1e15", "--t-end 1e+15: at most"},
      {"maxwell e4 --time 1e9", "bytes"},
      {"maxwell e4 --n 3 --time 1e-300", "shorter than one step"},
      {"oscillatory resonance --points 10000000 --no-plot", "--points 10000000: must be in"},
      {"pde run sine-gordon --T 0", "--T"},
      {"pde run sine-gordon --c 2", "--c is an option of kdv"},
      {"pde run kdv --omega 0.3", "--omega is an option of sine-gordon"},
      {"pde schrodinger eigen --n 5", "--n is an option of 'compare'"},
      {"pde nls-long --every 0 --no-plot", "--every 0"},
      {"reduction j2-satellite --mu 3", "--mu is not an option of 'j2-satellite'"},
      {"reduction j2-satellite --dt 1e300", "--dt 1e+300 is longer than the run"},
      {"reduction phases --dt 0.1", "--dt is not an option of 'phases'"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    const double t0 = seconds();
    run_output r = run_cli("%s", cases[i].args);
    cr_expect_eq(r.status, 2, "%s: exit %d, %s", cases[i].args, r.status, r.err);
    cr_expect(strstr(r.err, cases[i].want) != NULL, "%s: want '%s' in: %s", cases[i].args,
              cases[i].want, r.err);
    expect_one_clean_line(r.err);
    cr_expect_lt(seconds() - t0, 5.0, "%s took %.1f s", cases[i].args, seconds() - t0);
    run_output_free(&r);
  }
}
