/* geomint pde moving-mesh: the documented numbers (docs/pde.md), the failed steps of the seed's
 * equations reported, files, bad input. */
#include <criterion/criterion.h>
#include <math.h>

#include "cli/cli_harness.h"

TestSuite(cli_pde_moving_mesh, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

Test(cli_pde_moving_mesh, json) {
  run_output r = run_cli("pde moving-mesh --json --no-plot --steps 200 --out mm");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  const cJSON *cond = cJSON_GetObjectItem(o, "conditioning");
  cr_assert_eq(cJSON_GetArraySize(cond), 8);
  /* pulse n = 40: seed 3.75e17 (singular), time-adaptive 54 */
  const cJSON *c40 = cJSON_GetObjectItem(cJSON_GetArrayItem(cond, 1), "cond");
  cr_expect_gt(cJSON_GetArrayItem(c40, 0)->valuedouble, 1e15);
  cr_expect_lt(cJSON_GetArrayItem(c40, 2)->valuedouble, 200.0);
  const cJSON *runs = cJSON_GetObjectItem(o, "runs");
  cr_assert_eq(cJSON_GetArraySize(runs), 5);
  const cJSON *seed = cJSON_GetArrayItem(runs, 0), *ta = cJSON_GetArrayItem(runs, 3);
  cr_expect_str_eq(json_string(seed, "kind"), "seed");
  cr_expect_eq(json_number(seed, "steps"), 0.0);
  cr_expect_eq(json_number(seed, "failed_steps"), 1.0);
  cr_expect(strstr(json_string(seed, "message"), "singular") != NULL);
  cr_expect_str_eq(json_string(ta, "status"), "ok");
  cr_expect_eq(json_number(ta, "steps"), 200.0);
  cr_expect_lt(json_number(ta, "max_rel_energy"), 1e-11); /* measured 3.6e-12 over 2000 */
  const cJSON *ord = cJSON_GetObjectItem(cJSON_GetObjectItem(o, "order"), "orders");
  cr_expect(fabs(cJSON_GetArrayItem(ord, 1)->valuedouble - 2.0) <= 0.2); /* 2.01 */
  cJSON_Delete(o);
  run_output_free(&r);
}

Test(cli_pde_moving_mesh, bad_input) {
  const char *bad[] = {"--cfl nan", "--cfl 1.5", "--n -5", "--n 3", "--alpha -1", "--steps 0"};
  for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
    char line[128];
    snprintf(line, sizeof line, "pde moving-mesh --no-plot --out mm %s", bad[k]);
    run_output r = run_cli(line);
    cr_expect_eq(r.status, 2, "%s: %d", bad[k], r.status);
    cr_expect(strlen(r.err) > 0, "%s: no message", bad[k]);
    run_output_free(&r);
  }
  run_output r = run_cli("pde moving-mesh --no-plot --cfl 1.5");
  cr_expect(strstr(r.err, "dt <= min dx") != NULL, "%s", r.err);
  run_output_free(&r);
}
