/* geomint maxwell bands: a square lattice of dielectric rods (ε = 8.9, r = 0.2a, TM, 32 cells
 * per period, smoothing on) at X and M against MPB 1.11.1 at the same resolution (the numbers
 * below are MPB's, from `mpb` on the ctl that bench/mpb_bands.py writes, k points X and M),
 * and a k path of one point refused naming the option. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>

#include <cJSON.h>

#include "cli/cli_harness.h"

TestSuite(cli_maxwell_bands, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 300);

static void write_rods(void) {
  FILE *f = fopen(path_in_tmp("rods.json"), "w");
  cr_assert_not_null(f);
  fputs("{\"grid\": {\"dim\": \"2d-tm\", \"cells\": [32, 32], \"size\": [1, 1]},\n"
        " \"materials\": [{\"shape\": \"cylinder\", \"center\": [0.5, 0.5], \"radius\": 0.2,\n"
        "                \"epsilon\": 8.9}],\n"
        " \"boundaries\": {\"x\": \"periodic\", \"y\": \"periodic\"}, \"run\": {\"time\": 1}}\n",
        f);
  fclose(f);
}

/* MPB (resolution 32, TM): X = (0.5, 0): 0.27489 0.442411 0.636827 0.773453 0.783411;
 * M = (0.5, 0.5): 0.322701 0.549016 (twice: degenerate) 0.693449 */
static const double mpb_x[5] = {0.27489, 0.442411, 0.636827, 0.773453, 0.783411};
static const double mpb_m[3] = {0.322701, 0.549016, 0.693449};

Test(cli_maxwell_bands, rods_against_mpb_at_x_and_m) {
  write_rods();
  run_output r = run_cli("maxwell bands rods.json --kx 0.5,0.5 --ky 0,0.5 --bands 5 --f-min 0.1 "
                         "--f-max 0.8 --json --no-plot --out b");
  cr_assert_eq(r.status, 0, "exit %d: %s", r.status, r.err);
  cJSON *root = parse_json(r.out);
  cr_assert_not_null(root);
  const cJSON *ks = cJSON_GetObjectItem(root, "k_points");
  cr_assert_eq(cJSON_GetArraySize(ks), 2);
  const double *refs[2] = {mpb_x, mpb_m};
  const size_t n_refs[2] = {5, 3};
  for (int p = 0; p < 2; ++p) {
    const cJSON *f = cJSON_GetObjectItem(cJSON_GetArrayItem(ks, p), "frequencies");
    /* measured: max relative difference 4.2e-3 at X (band 3), 2.5e-3 at M */
    for (size_t b = 0; b < n_refs[p]; ++b) {
      double got = cJSON_GetArrayItem(f, (int)b)->valuedouble;
      double rel = fabs(got - refs[p][b]) / refs[p][b];
      cr_expect(rel < 0.01, "k %d band %zu: %.6f against MPB %.6f (%.2e)", p, b, got,
                refs[p][b], rel);
    }
    cr_expect_eq(json_number(cJSON_GetArrayItem(ks, p), "lost"), p == 0 ? 0 : 2,
                 "X: five distinct modes; M: the degenerate pair is one, band 5 above f_max");
  }
  cJSON_Delete(root);
  run_output_free(&r);
  r = run_cli("maxwell bands rods.json --kx 0.5 --ky 0 --bands 3 --f-max 0.8 --out c --no-plot");
  cr_assert_eq(r.status, 0, "exit %d: %s", r.status, r.err);
  cr_expect_not_null(strstr(r.out, "wrote c/bands.csv"), "%s", r.out);
  char *csv = read_file(path_in_tmp("c/bands.csv"));
  cr_assert_not_null(csv);
  cr_expect_not_null(strstr(csv, "k_index,kx,ky,kz,path_distance,band1,band2,band3,found"));
  free(csv);
  run_output_free(&r);
}

Test(cli_maxwell_bands, one_point_path_is_refused) {
  write_rods();
  run_output r = run_cli("maxwell bands rods.json --k-path G --f-max 0.8 --out d");
  cr_expect_eq(r.status, 2, "exit %d: %s", r.status, r.err);
  cr_expect_not_null(strstr(r.err, "--k-path"), "%s", r.err);
  run_output_free(&r);
  r = run_cli("maxwell bands rods.json --kx 0.5,0.1 --ky 0 --f-max 0.8 --out d");
  cr_expect_eq(r.status, 2, "exit %d: %s", r.status, r.err);
  cr_expect_not_null(strstr(r.err, "--ky"), "%s", r.err);
  run_output_free(&r);
}
