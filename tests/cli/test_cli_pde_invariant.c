/* geomint pde invariant: the documented numbers of B12 and B13 (docs/pde.md), files, usage. */
#include <criterion/criterion.h>

#include "cli/cli_harness.h"

TestSuite(cli_pde_invariant, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

Test(cli_pde_invariant, galilean_json) {
  run_output r = run_cli("pde invariant galilean --json --no-plot --out b12");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  const cJSON *rows = cJSON_GetObjectItem(o, "rows");
  cr_assert_eq(cJSON_GetArraySize(rows), 24);
  for (int i = 0; i < 24; i++) {
    const cJSON *w = cJSON_GetArrayItem(rows, i);
    int inv = strcmp(json_string(w, "form"), "invariant") == 0;
    double lambda = json_number(w, "lambda"), d = json_number(w, "max_abs_diff_lambda0");
    cr_assert_str_eq(json_string(w, "status"), "ok");
    if (inv) /* measured at most 7.1e-15 */
      cr_assert_leq(d, 1e-13, "%s invariant lambda %g: %g", json_string(w, "scheme"), lambda, d);
    else if (lambda > 0) /* measured at least 1.00 (the front displaced by lambda t) */
      cr_assert_geq(d, 0.5, "%s standard lambda %g: %g", json_string(w, "scheme"), lambda, d);
  }
  /* docs/pde.md: standard FTCS at lambda = 1 max error 2.675, invariant FTCS 0.0630 */
  cr_assert_float_eq(json_number(cJSON_GetArrayItem(rows, 3), "max_abs_error"), 2.675, 2e-3);
  cr_assert_float_eq(json_number(cJSON_GetArrayItem(rows, 7), "max_abs_error"), 0.06303, 1e-4);
  cJSON_Delete(o);
  run_output_free(&r);
  char *csv = read_file(path_in_tmp("b12/b12.csv"));
  cr_assert_eq(count_lines(csv), 202);
  free(csv);
}

Test(cli_pde_invariant, shock_and_orders) {
  run_output r = run_cli("pde invariant shock --json --no-plot --out b13");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  /* docs/pde.md: FTCS 4.188e-3, invariant FTCS 1.887e-3 */
  cr_assert_float_eq(json_number(o, "max_abs_error_standard"), 4.188e-3, 1e-5);
  cr_assert_float_eq(json_number(o, "max_abs_error_invariant"), 1.887e-3, 1e-5);
  cJSON_Delete(o);
  run_output_free(&r);
  r = run_cli("pde invariant orders --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  o = parse_json(r.out);
  cr_assert_eq(cJSON_GetArraySize(cJSON_GetObjectItem(o, "rows")), 6);
  cJSON_Delete(o);
  run_output_free(&r);
}

Test(cli_pde_invariant, usage) {
  run_output r = run_cli("pde invariant sideways");
  cr_assert_eq(r.status, 2);
  cr_assert(strstr(r.err, "galilean, shock or orders") != NULL, "%s", r.err);
  run_output_free(&r);
  r = run_cli("pde invariant shock --bogus");
  cr_assert_eq(r.status, 2);
  run_output_free(&r);
}
