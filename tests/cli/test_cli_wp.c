/* geomint wp: the work-precision command's JSON, its errors and force counts, the reference it
 * chooses, its plot, and the exit status of bad input (2). */
#include <criterion/criterion.h>
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cJSON.h>

#include "geomint/geomint.h"

#include "cli/cli_harness.h"

TestSuite(wp, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

/* The rows of one method, in order: at most 64. */
static size_t method_rows(const cJSON *rows, const char *method, const cJSON **out) {
  size_t n = 0;
  const cJSON *row;
  cJSON_ArrayForEach(row, rows) {
    if (strcmp(json_string(row, "method"), method) == 0 && n < 64) out[n++] = row;
  }
  return n;
}

/* ---- output ------------------------------------------------------------------------------ */

Test(wp, json_has_the_documented_keys_and_consistent_rows) {
  run_output r = run_cli("wp kepler --methods yoshida-4,rk4 --t-end 10 --levels 6 --json");
  cr_assert_eq(r.status, 0, "stderr: %s", r.err);
  cJSON *root = parse_json(r.out);
  cr_assert_str_eq(json_string(root, "problem"), "kepler");
  cr_assert_float_eq(json_number(root, "t_end"), 10.0, 1e-12);
  cr_assert_str_eq(json_string(root, "reference"), "exact");
  const cJSON *rows = cJSON_GetObjectItemCaseSensitive(root, "rows");
  cr_assert(cJSON_IsArray(rows));
  const cJSON *yoshida[64], *rk4[64];
  size_t n_yoshida = method_rows(rows, "yoshida-4", yoshida), n_rk4 = method_rows(rows, "rk4", rk4);
  cr_assert_geq(n_yoshida, 4, "yoshida-4 has only %zu rows", n_yoshida);
  cr_assert_geq(n_rk4, 4, "rk4 has only %zu rows", n_rk4);
  cr_assert_eq((size_t)cJSON_GetArraySize(rows), n_yoshida + n_rk4);
  const cJSON *row;
  cJSON_ArrayForEach(row, rows) {
    double dt = json_number(row, "dt"), steps = json_number(row, "steps");
    double evals = json_number(row, "force_evals");
    cr_assert(json_number(row, "wall_s") >= 0.0);
    cr_assert(json_number(row, "error") > 0.0);
    /* equal steps that end exactly at t_end */
    cr_assert_float_eq(dt * steps, 10.0, 1e-9);
    if (strcmp(json_string(row, "method"), "rk4") == 0)
      cr_assert_float_eq(evals, 4.0 * steps, 0.5, "rk4: %g evaluations for %g steps", evals, steps);
    else /* triple jump of position Verlet (the default basic): 3 forces a step */
      cr_assert_float_eq(evals, 3.0 * steps, 0.5, "yoshida-4: %g for %g steps", evals, steps);
  }
  cJSON_Delete(root);
  run_output_free(&r);
}

Test(wp, error_of_a_convergent_method_falls_at_its_order) {
  run_output r = run_cli("wp kepler --methods yoshida-4 --t-end 10 --levels 6 --json");
  cr_assert_eq(r.status, 0, "stderr: %s", r.err);
  cJSON *root = parse_json(r.out);
  const cJSON *rows[64];
  size_t n = method_rows(cJSON_GetObjectItemCaseSensitive(root, "rows"), "yoshida-4", rows);
  /* The sweep starts near 1e-2 and ends near 1e-13. */
  cr_assert(json_number(rows[0], "error") > 1e-4 && json_number(rows[0], "error") < 5e-2,
            "first error %g", json_number(rows[0], "error"));
  cr_assert(json_number(rows[n - 1], "error") < 1e-10, "last error %g",
            json_number(rows[n - 1], "error"));
  /* Above round-off, each level cuts the error by about 10^(11/5) = 158 (at least 50 here),
   * and the slope against the work is the order, 4. */
  size_t last = 0;
  for (size_t i = 1; i < n && json_number(rows[i], "error") > 1e-10; ++i) {
    double prev = json_number(rows[i - 1], "error"), e = json_number(rows[i], "error");
    cr_assert(e < prev / 50.0, "level %zu: error %g after %g", i, e, prev);
    last = i;
  }
  cr_assert_geq(last, 2);
  double slope = -log(json_number(rows[last], "error") / json_number(rows[0], "error")) /
                 log(json_number(rows[last], "force_evals") / json_number(rows[0], "force_evals"));
  cr_assert(fabs(slope - 4.0) < 0.4, "error ~ evals^-%.3f, expected 4", slope);
  cJSON_Delete(root);
  run_output_free(&r);
}

Test(wp, dt0_sets_the_first_step_and_the_ratio_follows_the_order) {
  /* order 2, 3 levels: steps refined by r = 10^(11/((3-1)·2)) = 10^2.75 per level */
  run_output r = run_cli("wp harmonic --methods verlet --t-end 1 --dt0 0.1 --levels 3 --json");
  cr_assert_eq(r.status, 0, "stderr: %s", r.err);
  cJSON *root = parse_json(r.out);
  const cJSON *rows[64];
  size_t n = method_rows(cJSON_GetObjectItemCaseSensitive(root, "rows"), "verlet", rows);
  cr_assert_eq(n, 3);
  cr_assert_float_eq(json_number(rows[0], "dt"), 0.1, 1e-12);
  cr_assert_float_eq(json_number(rows[1], "steps"), ceil(10.0 * pow(10.0, 2.75)), 0.5);
  /* Verlet's error is C·dt²: one level down, r² = 10^5.5 smaller within 5 % */
  double ratio = json_number(rows[0], "error") / json_number(rows[1], "error");
  cr_assert(fabs(log10(ratio) - 5.5) < 0.02, "error ratio 10^%.3f", log10(ratio));
  cJSON_Delete(root);
  run_output_free(&r);
}

Test(wp, without_an_exact_solution_the_reference_is_a_converged_high_order_run) {
  run_output r = run_cli("wp henon-heiles --methods kahan-li-8 --t-end 10 --levels 4 --json");
  cr_assert_eq(r.status, 0, "stderr: %s", r.err);
  cJSON *root = parse_json(r.out);
  cr_assert_str_eq(json_string(root, "reference"), "sofroniou-spaletta-10");
  double check = json_number(root, "reference_check");
  cr_assert(check < 1e-13, "the reference differs by %g from its check run", check);
  cr_assert(json_number(root, "reference_dt") > 0.0);
  const cJSON *rows[64];
  size_t n = method_rows(cJSON_GetObjectItemCaseSensitive(root, "rows"), "kahan-li-8", rows);
  cr_assert_geq(n, 2);
  /* kahan-li-8 converges to the reference: the last error is tiny */
  cr_assert(json_number(rows[n - 1], "error") < 1e-11, "last error %g",
            json_number(rows[n - 1], "error"));
  cJSON_Delete(root);
  run_output_free(&r);

  /* a non-separable problem: no explicit method of order 8 accepts it, gauss-8 does */
  r = run_cli("wp point-vortices --set config=1 --methods gauss-2 --t-end 1 --levels 3 --json");
  cr_assert_eq(r.status, 0, "stderr: %s", r.err);
  root = parse_json(r.out);
  cr_assert_str_eq(json_string(root, "reference"), "gauss-8");
  cJSON_Delete(root);
  run_output_free(&r);
}

Test(wp, table_names_the_reference) {
  run_output r = run_cli("wp kepler --methods verlet --t-end 1 --levels 3");
  cr_assert_eq(r.status, 0, "stderr: %s", r.err);
  cr_assert_not_null(strstr(r.out, "reference: exact solution"), "%s", r.out);
  cr_assert_not_null(strstr(r.out, "force evals"), "%s", r.out);
  run_output_free(&r);
}

Test(wp, plot_writes_a_png) {
  run_output r = run_cli("wp kepler --methods verlet,rk4 --t-end 1 --levels 3 --plot wp.png");
  if (r.status == 1 && strstr(r.err, "gnuplot") != NULL) {
    run_output_free(&r);
    remove_tmpdir();
    cr_skip_test("gnuplot is not installed");
  }
  cr_assert_eq(r.status, 0, "stderr: %s", r.err);
  char path[512];
  snprintf(path, sizeof path, "%s/wp.png", tmpdir);
  FILE *f = fopen(path, "rb");
  cr_assert_not_null(f);
  unsigned char sig[8];
  cr_assert_eq(fread(sig, 1, 8, f), 8);
  fclose(f);
  cr_assert_eq(memcmp(sig, "\x89PNG\r\n\x1a\n", 8), 0);
  struct stat sb;
  cr_assert_eq(stat(path, &sb), 0);
  cr_assert(sb.st_size > 5000, "a PNG of %ld bytes", (long)sb.st_size);
  run_output_free(&r);
}

/* ---- bad input ---------------------------------------------------------------------------- */

Test(wp, unknown_method_in_the_list_is_a_usage_error_with_suggestions) {
  run_output r = run_cli("wp kepler --methods verlet,yoshda-4 --t-end 1");
  cr_assert_eq(r.status, 2);
  cr_assert_not_null(strstr(r.err, "unknown method 'yoshda-4'"), "%s", r.err);
  cr_assert_not_null(strstr(r.err, "yoshida-4"), "%s", r.err);
  cr_assert_eq(r.out[0], '\0', "nothing on stdout: %s", r.out);
  run_output_free(&r);
}

Test(wp, empty_method_list_is_a_usage_error) {
  run_output r = run_cli("wp kepler --methods , --t-end 1");
  cr_assert_eq(r.status, 2);
  cr_assert_not_null(strstr(r.err, "empty"), "%s", r.err);
  run_output_free(&r);
  r = run_cli("wp kepler --methods '' --t-end 1");
  cr_assert_eq(r.status, 2);
  run_output_free(&r);
  r = run_cli("wp kepler --t-end 1");
  cr_assert_eq(r.status, 2);
  cr_assert_not_null(strstr(r.err, "--methods"), "%s", r.err);
  run_output_free(&r);
}

Test(wp, method_that_cannot_integrate_the_problem_is_a_usage_error) {
  run_output r = run_cli("wp lotka-volterra --methods rk4,verlet --t-end 1");
  cr_assert_eq(r.status, 2);
  cr_assert_not_null(strstr(r.err, "verlet"), "%s", r.err);
  cr_assert_not_null(strstr(r.err, "cannot integrate"), "%s", r.err);
  cr_assert_eq(r.out[0], '\0', "nothing runs before the check: %s", r.out);
  run_output_free(&r);
}

Test(wp, bad_options_are_usage_errors) {
  const char *cases[] = {"wp kepler --methods verlet --levels 1",
                         "wp kepler --methods verlet --t-end -1",
                         "wp kepler --methods verlet --dt0 0",
                         "wp kepler --methods verlet --max-evals 0",
                         "wp kepler --methods verlet --basic midpoint",
                         "wp kepler --methods verlet --reference nosuch",
                         "wp keplr --methods verlet"};
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    run_output r = run_cli("%s", cases[i]);
    cr_assert_eq(r.status, 2, "%s: exit %d, stderr %s", cases[i], r.status, r.err);
    cr_assert(r.err[0] != '\0', "%s: no message", cases[i]);
    run_output_free(&r);
  }
}

/* A sweep cut short by --max-evals is said in the JSON too (issue 17: --json dropped it). */
Test(wp, json_records_the_max_evals_stop) {
  run_output r = run_cli("wp kepler --methods verlet --t-end 10 --max-evals 100000 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *root = parse_json(r.out);
  const cJSON *stopped = cJSON_GetObjectItemCaseSensitive(root, "stopped");
  cr_assert(cJSON_IsArray(stopped) && cJSON_GetArraySize(stopped) == 1, "%s", r.out);
  const cJSON *s = cJSON_GetArrayItem(stopped, 0);
  cr_expect_str_eq(json_string(s, "method"), "verlet");
  cr_expect_str_eq(json_string(s, "limit"), "max-evals");
  cr_expect_gt(json_number(s, "predicted_force_evals"), 100000);
  cr_expect(strstr(json_string(s, "message"), "which would exceed --max-evals 100000") != NULL);
  cJSON_Delete(root);
  run_output_free(&r);
  /* the table says it on stderr */
  r = run_cli("wp kepler --methods verlet --t-end 10 --max-evals 100000");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect(strstr(r.err, "geomint wp: verlet: stopped at dt = ") != NULL, "%s", r.err);
  run_output_free(&r);
}
