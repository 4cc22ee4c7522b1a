/* geomint fluid on domains without boundary: the example case files of the periodic
 * Taylor–Green vortex (VTU pulled back to the mesh's vertices) and of the Rossby–Haurwitz wave
 * on the sphere, a periodic partner missing from the mesh (exit 2, named), and the measuring
 * commands taylor-green, shear-layer and rossby-haurwitz (docs/fluids.md). */
#include <math.h>

#include "cli_harness.h"

TestSuite(cli_fluid_closed, .init = make_tmpdir, .fini = remove_tmpdir);

Test(cli_fluid_closed, taylor_green_case_decays_at_2nu) {
  run_output r = run_cli("fluid run '%s/examples/fluid_taylor_green.json' --out tg --json",
                         GM_SOURCE_DIR);
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *root = parse_json(r.out);
  cr_expect_eq(json_number(root, "steps"), 40);
  cr_expect_eq(json_number(root, "vtu_files"), 5);
  cr_expect_leq(json_number(root, "div_max"), 1e-14);
  const cJSON *first = cJSON_GetObjectItem(root, "first"),
              *last = cJSON_GetObjectItem(root, "last");
  double e0 = json_number(first, "kinetic_energy"), e1 = json_number(last, "kinetic_energy");
  double m0 = json_number(first, "scalar_mass"), m1 = json_number(last, "scalar_mass");
  /* E(t) = E0 exp(−4νt): rate −ln(E1/E0)/(2t) = 2ν = 0.1 within 0.5 % at n = 32 (measured
   * 9.951e-2 by `geomint fluid taylor-green`); the scalar mass is conserved */
  double rate = -log(e1 / e0) / (2.0 * 2.0);
  cr_expect(fabs(rate / 0.1 - 1.0) < 7e-3, "decay rate %.6e", rate);
  cr_expect_leq(fabs(m1 / m0 - 1.0), 1e-13, "scalar mass %.17g -> %.17g", m0, m1);
  cJSON_Delete(root);
  run_output_free(&r);
  char *vtu = read_file(path_in_tmp("tg/fluid_000004.vtu"));
  /* the lattice of 32 cells: 33 × 37 mesh vertices written (the classes pulled back) */
  cr_expect(strstr(vtu, "NumberOfPoints=\"1221\"") != NULL, "%.300s", vtu);
  free(vtu);
}

Test(cli_fluid_closed, rossby_haurwitz_case_keeps_energy) {
  run_output r = run_cli("fluid run '%s/examples/fluid_rossby_haurwitz.json' --json",
                         GM_SOURCE_DIR);
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *root = parse_json(r.out);
  cr_expect_eq(json_number(root, "steps"), 100);
  const cJSON *first = cJSON_GetObjectItem(root, "first"),
              *last = cJSON_GetObjectItem(root, "last");
  double e0 = json_number(first, "kinetic_energy"), e1 = json_number(last, "kinetic_energy");
  cr_expect_leq(fabs(e1 / e0 - 1.0), 1e-13, "energy %.17g -> %.17g", e0, e1);
  cr_expect_leq(fabs(json_number(last, "total_vorticity")), 1e-13);
  cJSON_Delete(root);
  run_output_free(&r);
}

Test(cli_fluid_closed, bad_periodic_case) {
  FILE *f = fopen(path_in_tmp("bad.json"), "w");
  cr_assert_not_null(f);
  fputs("{\"mesh\": {\"periodic_square\": {\"cells\": 8}}, \"boundaries\": {\"left\": {\"type\": "
        "\"periodic\", \"partner\": \"east\"}, \"bottom\": {\"type\": \"periodic\", \"partner\": "
        "\"top\"}}, \"scheme\": \"midpoint\", \"nu\": 0.1, \"dt\": 0.05}",
        f);
  fclose(f);
  run_output r = run_cli("fluid run bad.json");
  cr_expect_eq(r.status, 2, "%s", r.err);
  cr_expect(strstr(r.err, "\"east\"") != NULL, "%s", r.err);
  run_output_free(&r);
}

Test(cli_fluid_closed, measuring_commands) {
  run_output r = run_cli("fluid taylor-green --cells 8,16 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *root = parse_json(r.out);
  /* measured 1.87 over n = 8, 16 (2.00 over 8, 16, 32) */
  cr_expect(fabs(json_number(root, "rate") - 1.87) < 0.15, "%s", r.out);
  cJSON_Delete(root);
  run_output_free(&r);
  r = run_cli("fluid shear-layer --cells 8 --steps 200 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  root = parse_json(r.out);
  cr_expect_leq(json_number(root, "energy_drift"), 1e-13, "%s", r.out);
  cJSON_Delete(root);
  run_output_free(&r);
  r = run_cli("fluid rossby-haurwitz --subdivisions 2,3 --time 2 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  root = parse_json(r.out);
  cr_expect(json_number(root, "exact") > 0.0337 && json_number(root, "exact") < 0.0338);
  cJSON_Delete(root);
  run_output_free(&r);
  r = run_cli("fluid taylor-green --scheme leapfrog");
  cr_expect_eq(r.status, 2, "%s", r.err);
  run_output_free(&r);
}
