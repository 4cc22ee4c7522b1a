/* --json with one vocabulary (issue 26): each command that gained it prints exactly one JSON
 * object whose numbers are the run's (wall_s, steps, max_... and rel_... as run names them). */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "cli/cli_harness.h"

TestSuite(cli_json, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

/* measured: 198 steps, Gauss drift 9.99e-16, final leapfrog energy 9.6e-16 from the initial */
Test(cli_json, maxwell_mesh) {
  run_output r = run_cli("maxwell mesh --rect 8 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_eq(json_number(o, "steps"), 198);
  cr_expect_eq(json_number(o, "faces"), 102);
  cr_expect_str_eq(json_string(o, "scheme"), "leapfrog");
  cr_expect_lt(json_number(o, "max_gauss_drift"), 1e-14);
  cr_expect_lt(json_number(o, "rel_leapfrog_energy_error_final"), 1e-14);
  cr_expect_eq(json_number(o, "max_abs_div_b"), 0.0);
  cr_expect_gt(json_number(o, "max_rel_plain_energy_deviation"), 0.5); /* measured 0.945 */
  cr_expect_geq(json_number(o, "wall_s"), 0.0);
  cJSON_Delete(o);
  run_output_free(&r);
  r = run_cli("maxwell mesh --rect 8 --avi --t-end 1 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  o = parse_json(r.out);
  cr_expect_str_eq(json_string(o, "scheme"), "avi");
  /* measured: 23 664 face updates, as many as uniform stepping on this uniform mesh */
  cr_expect_eq(json_number(o, "face_updates"), 23664);
  cr_expect_geq(json_number(o, "uniform_face_updates"), json_number(o, "face_updates"));
  cJSON_Delete(o);
  run_output_free(&r);
}

/* measured: NLS soliton, preissmann, 20 steps: charge 1.99287415, max error 0.05529 */
Test(cli_json, pde_run) {
  run_output r = run_cli("pde run nls --json --out nls.csv");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_eq(json_number(o, "steps"), 20);
  cr_expect_float_eq(json_number(o, "charge"), 1.9928741484, 1e-9);
  cr_expect_float_eq(json_number(o, "max_abs_error"), 0.0552889, 1e-6);
  cr_expect_lt(json_number(o, "rel_energy_change"), 5e-3); /* measured 3.88e-3 */
  cr_expect_str_eq(json_string(o, "csv"), "nls.csv");
  cr_expect_geq(json_number(o, "wall_s"), 0.0);
  cJSON_Delete(o);
  run_output_free(&r);
}

/* 57 points: imex 1.25303e-3 .. 1.25313e-3, impulse 1.347e13 at 0.9995 */
Test(cli_json, oscillatory_resonance) {
  run_output r = run_cli("oscillatory resonance --points 9 --no-plot --json --out o");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_eq(json_number(o, "points"), 57);
  cr_expect_float_eq(json_number(o, "imex_max"), 1.25313e-3, 1e-8);
  cr_expect_gt(json_number(o, "impulse_max"), 1e13);
  cr_expect_eq(json_number(o, "impulse_max_at"), 0.9995);
  cJSON_Delete(o);
  run_output_free(&r);
  r = run_cli("oscillatory fpu --json --no-plot --out o");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "--json") != NULL, "%s", r.err);
  run_output_free(&r);
}
