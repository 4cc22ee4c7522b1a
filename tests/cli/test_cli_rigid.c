/* geomint run with rigid bodies: the documented summary line, JSON keys, CSV columns (R as 9
 * columns R11..R33), list entries, and the exit status 2 for a non-orthogonal R. */
#include <criterion/criterion.h>
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cJSON.h>

#include "cli/cli_harness.h"

TestSuite(cli_rigid, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

Test(cli_rigid, run_lgvi_json_and_csv) {
  run_output r = run_cli("run rigid-body --method lgvi --dt 0.01 --steps 2000 --every 100 "
                         "--out rb.csv --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_str_eq(json_string(o, "method"), "lgvi");
  cr_expect_eq(json_number(o, "steps"), 2000);
  cr_expect_leq(json_number(o, "state_defect"), 1e-14);
  cr_expect_leq(json_number(o, "max_rel_energy_error"), 1e-13);
  const cJSON *inv = cJSON_GetObjectItem(o, "invariants");
  cr_expect_leq(json_number(inv, "casimir"), 1e-13);
  cr_expect_leq(json_number(inv, "L-space-y"), 1e-13);
  const cJSON *y = cJSON_GetObjectItem(cJSON_GetObjectItem(o, "final"), "y");
  cr_expect_eq(cJSON_GetArraySize(y), 12);
  cr_expect_eq(json_number(o, "csv_rows"), 21);
  cJSON_Delete(o);
  char *csv = read_file(path_in_tmp("rb.csv"));
  cr_assert_not_null(csv);
  cr_expect(strncmp(csv, "t,R11,R12,R13,R21,R22,R23,R31,R32,R33,Pi1,Pi2,Pi3,H,rel_energy_error,"
                         "casimir,L-space-x,L-space-y,L-space-z\n",
                    strlen("t,R11,R12,R13,R21,R22,R23,R31,R32,R33,Pi1,Pi2,Pi3,H,")) == 0,
            "%.120s", csv);
  free(csv);
  run_output_free(&r);
}

Test(cli_rigid, summary_names_the_defect) {
  run_output r = run_cli("run central-body --method rigid-splitting --dt 0.01 --steps 100");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect(strstr(r.out, "state space       |R^T R - I| = ") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "L-total-z") != NULL, "%s", r.out);
  run_output_free(&r);
}

Test(cli_rigid, bad_input_exits_2) {
  run_output r = run_cli("run rigid-body --method lgvi --set y2=0.01");
  cr_expect_eq(r.status, 2, "%s", r.out);
  cr_expect(strstr(r.err, "|R^T R - I|") != NULL, "%s", r.err);
  run_output_free(&r);
  r = run_cli("run heavy-top --method lgvi --set I1=-1");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "positive") != NULL, "%s", r.err);
  run_output_free(&r);
  r = run_cli("run kepler --method lgvi");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "rigid-body") != NULL, "%s", r.err);
  run_output_free(&r);
}

Test(cli_rigid, list_shows_rows_and_problems) {
  run_output r = run_cli("list methods");
  cr_assert_eq(r.status, 0);
  const char *rows[] = {"lgvi ", "rkmk4", "crouch-grossman-3", "rigid-splitting",
                        "lgvi-galerkin-2", "dep-3"};
  for (size_t i = 0; i < sizeof rows / sizeof rows[0]; ++i)
    cr_expect(strstr(r.out, rows[i]) != NULL, "%s missing", rows[i]);
  run_output_free(&r);
  r = run_cli("list problems");
  const char *problems[] = {"rigid-body", "heavy-top", "pendulum-3d", "satellite",
                            "central-body"};
  for (size_t i = 0; i < sizeof problems / sizeof problems[0]; ++i)
    cr_expect(strstr(r.out, problems[i]) != NULL, "%s missing", problems[i]);
  run_output_free(&r);
}
