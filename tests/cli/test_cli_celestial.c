/* The CLI says which coordinates a near-integrable row used, and warns (in the summary and the
 * JSON) when the step is longer than a quarter of the shortest orbital period. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cJSON.h>

#include "cli_harness.h"

Test(cli_celestial, coordinates_and_step_warning) {
  run_output r = run_cli("run outer-solar-system --method wh-dh --dt 50 --steps 100 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_str_eq(json_string(o, "coordinates"), "democratic-heliocentric");
  cr_expect_eq(json_number(o, "corrector_order"), 0);
  double period = json_number(o, "shortest_period");
  cr_expect(fabs(period - 4332) < 20, "shortest period %g", period);
  cr_expect_null(cJSON_GetObjectItem(o, "warning"));
  cr_expect_lt(json_number(o, "max_rel_energy_error"), 1e-5);
  cJSON_Delete(o);
  run_output_free(&r);

  r = run_cli("run outer-solar-system --method wh-c11 --dt 1200 --steps 5 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  o = parse_json(r.out);
  cr_expect_str_eq(json_string(o, "coordinates"), "jacobi");
  cr_expect_eq(json_number(o, "corrector_order"), 11);
  cr_expect_not_null(strstr(json_string(o, "warning"), "quarter of the shortest orbital period"));
  cJSON_Delete(o);
  run_output_free(&r);

  r = run_cli("run outer-solar-system --set planets=2 --method saba-3-jacobi --dt 1200 --steps 5");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect_not_null(strstr(r.out, "coordinates       jacobi"), "%s", r.out);
  cr_expect_not_null(strstr(r.out, "warning"), "%s", r.out);
  run_output_free(&r);

  /* a problem without a central body: exit 2 with the reason */
  r = run_cli("run kepler --method wh --dt 0.1 --steps 10");
  cr_expect_eq(r.status, 2, "%d: %s", r.status, r.err);
  cr_expect_not_null(strstr(r.err, "central body"), "%s", r.err);
  run_output_free(&r);
  r = run_cli("run n-body --set n=3 --set cluster=0 --set central=1 --method wh --dt 0.1 --steps 1");
  cr_expect_eq(r.status, 2, "%d: %s", r.status, r.err);
  cr_expect_not_null(strstr(r.err, "heavier"), "%s", r.err);
  run_output_free(&r);
}
