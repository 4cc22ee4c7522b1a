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
  r = run_cli("oscillatory all --json --no-plot --out o"); /* one object for one experiment */
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "--json") != NULL, "%s", r.err);
  run_output_free(&r);
}

/* docs/oscillatory.md: imex h = 0.1 max |dH| 1.5e-2, I at t = 150 0.017 0.018 0.968 */
Test(cli_json, oscillatory_fpu) {
  run_output r = run_cli("oscillatory fpu --no-plot --json --out o");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_eq(json_number(o, "t_end"), 200);
  const cJSON *runs = cJSON_GetObjectItemCaseSensitive(o, "runs");
  cr_assert_eq(cJSON_GetArraySize(runs), 6);
  const cJSON *imex = cJSON_GetArrayItem(runs, 3);
  cr_expect_str_eq(json_string(imex, "method"), "imex");
  cr_expect_eq(json_number(imex, "steps"), 2000);
  cr_expect_float_eq(json_number(imex, "max_abs_dH"), 1.5e-2, 5e-4);
  const cJSON *at150 = cJSON_GetObjectItemCaseSensitive(imex, "I_at_150");
  cr_expect_float_eq(cJSON_GetArrayItem(at150, 2)->valuedouble, 0.968, 5e-4);
  cr_expect(cJSON_IsNull(cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(runs, 0),
                                                          "max_abs_dev_reference")));
  cr_expect_geq(json_number(o, "wall_s"), 0.0);
  cJSON_Delete(o);
  run_output_free(&r);
}

/* docs/reduction.md: node drift -1.358 (continuous J2 = 0.05), +0.074 (discrete J2 = 0) */
Test(cli_json, reduction_j2_satellite) {
  run_output r = run_cli("reduction j2-satellite --no-plot --json --out o");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_eq(json_number(o, "steps"), 500);
  const cJSON *c = cJSON_GetObjectItemCaseSensitive(o, "node_drift_continuous");
  const cJSON *d = cJSON_GetObjectItemCaseSensitive(o, "node_drift_discrete");
  cr_expect_float_eq(cJSON_GetArrayItem(c, 1)->valuedouble, -1.358, 5e-4);
  cr_expect_float_eq(cJSON_GetArrayItem(d, 0)->valuedouble, 0.074, 5e-4);
  cr_expect_geq(json_number(o, "wall_s"), 0.0);
  cJSON_Delete(o);
  run_output_free(&r);
}

/* docs/reduction.md: RSPRK 6.5e-5, RK4 at h/4 4.8e-7 over t = 0..20 */
Test(cli_json, reduction_double_spherical_pendulum) {
  run_output r = run_cli("reduction double-spherical-pendulum --no-plot --json --out o");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_eq(json_number(o, "steps"), 2000);
  cr_expect_float_eq(json_number(o, "max_rel_energy_error_rsprk"), 6.5e-5, 5e-7);
  cr_expect_float_eq(json_number(o, "max_rel_energy_error_rk4"), 4.8e-7, 5e-9);
  cr_expect_geq(json_number(o, "wall_s"), 0.0);
  cJSON_Delete(o);
  run_output_free(&r);
}

/* docs/mimetic.md, Kepler e = 0.6: MCI bounded at 5.5e-5, MGI 3e-15 */
Test(cli_json, mimetic_kepler) {
  run_output r = run_cli("mimetic kepler --no-plot --json --out o");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  const cJSON *runs = cJSON_GetObjectItemCaseSensitive(o, "runs");
  cr_assert_eq(cJSON_GetArraySize(runs), 5);
  const cJSON *mci = cJSON_GetArrayItem(runs, 0), *mgi = cJSON_GetArrayItem(runs, 1);
  cr_expect_str_eq(json_string(mci, "method"), "mimetic-canonical-2");
  cr_expect_eq(json_number(mci, "steps"), 1000);
  cr_expect_float_eq(json_number(mci, "max_abs_invariant_error"), 5.53e-5, 5e-7);
  cr_expect_lt(json_number(mgi, "max_abs_invariant_error"), 1e-14);
  const cJSON *conv = cJSON_GetObjectItemCaseSensitive(o, "convergence");
  cr_expect_float_eq(json_number(cJSON_GetObjectItemCaseSensitive(conv, "mimetic-canonical-2"),
                                 "order"), 4.0, 0.1);
  cr_expect_geq(json_number(o, "wall_s"), 0.0);
  cJSON_Delete(o);
  run_output_free(&r);
  r = run_cli("mimetic all --no-plot --json --out o");
  cr_expect_eq(r.status, 2);
  run_output_free(&r);
}
