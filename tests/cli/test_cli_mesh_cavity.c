/* geomint maxwell mesh-cavity: the table prints, --plot draws, bad input is exit status 2. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli_harness.h"

/* The relative error in the first table row that starts with `row` (e.g. "| 0.76548 | 1 | "),
 * held within 5% (and 2e-5) of the measured value: the meshes in examples/ and the run are
 * deterministic, so a change in the solver, harminv or the peak matching shows here. */
static void expect_row(const char *out, const char *row, double measured) {
  const char *p = strstr(out, row);
  cr_assert_not_null(p, "no row '%s' in %s", row, out);
  double e = NAN;
  cr_assert_eq(sscanf(p + strlen(row), "%lf", &e), 1, "%s", p);
  cr_expect(fabs(e - measured) <= 0.05 * fabs(measured) + 2e-5, "%s: %.3e, measured %.3e", row,
            e, measured);
}

Test(cli_mesh_cavity, cylinder_and_sphere_one_level) {
  run_output r = run_cli("maxwell mesh-cavity --shape cylinder --levels 1 --t-end 60 --mesh-dir "
                         GM_SOURCE_DIR "/examples");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect(strstr(r.out, "| f analytic | mult. |") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "| 0.76548 | 1 |") != NULL, "%s", r.out); /* TM010: j01 / (2π·0.5) */
  cr_expect(strstr(r.out, "spurious peaks below the 10th resonance (all levels): 0\n") != NULL,
            "%s", r.out);
  /* measured (h = 0.1617, t = 60): the six peaks, and each resonance's nearest-peak error */
  cr_expect(strstr(r.out, "6 peaks (analytic modes in the band, with multiplicity: 11): 0.76133 "
                          "1.01312 1.12400 1.19703 1.28144 1.44829; spurious: 0") != NULL,
            "%s", r.out);
  static const struct { const char *row; double err; } cyl[] = {
      {"| 0.76548 | 1 | ", -5.42e-3}, {"| 1.01878 | 2 | ", -5.56e-3},
      {"| 1.13155 | 1 | ", -6.68e-3}, {"| 1.21967 | 2 | ", -1.86e-2},
      {"| 1.28047 | 2 | ", 7.61e-4},  {"| 1.47717 | 3 | ", -1.96e-2}};
  for (size_t k = 0; k < sizeof cyl / sizeof *cyl; ++k) expect_row(r.out, cyl[k].row, cyl[k].err);
  cr_expect(strstr(r.out, "largest relative error in the band: 1.96e-02") != NULL, "%s", r.out);
  run_output_free(&r);
  /* the sphere: its multiplets and the farthest-peak table */
  r = run_cli("maxwell mesh-cavity --shape sphere --levels 1 --t-end 60 --mesh-dir "
              GM_SOURCE_DIR "/examples");
  cr_assert_eq(r.status, 0, "%s", r.err);
  /* TM11, TM21, TE11 of radius 0.5: x / π with x = 2.743707, 3.870239, 4.493409 */
  cr_expect(strstr(r.out, "| 0.87335 | 3 |") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "| 1.23194 | 5 |") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "| 1.43030 | 3 |") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "farthest of the peaks nearest") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "largest relative error in the band: 2.58e-02") != NULL, "%s", r.out);
  /* measured (h = 0.1644): four peaks, none spurious; the nearest peak of each multiplet and,
   * in the second table, the farthest (TM21's five split to +6.26e-3) */
  cr_expect(strstr(r.out, "4 peaks (analytic modes in the band, with multiplicity: 11): 0.87562 "
                          "1.23067 1.23964 1.39341; spurious: 0") != NULL, "%s", r.out);
  expect_row(r.out, "| 0.87335 | 3 | ", 2.60e-3);
  expect_row(r.out, "| 1.23194 | 5 | ", -1.02e-3);
  expect_row(r.out, "| 1.43030 | 3 | ", -2.58e-2);
  const char *far = strstr(r.out, "farthest of the peaks nearest");
  cr_assert_not_null(far);
  expect_row(far, "| 1.23194 | 5 | ", 6.26e-3);
  cr_expect(strstr(r.out, "spurious peaks below the 10th resonance (all levels): 0\n") != NULL,
            "%s", r.out);
  run_output_free(&r);
  /* bad input (in the same test: the harness's output files are shared between parallel
   * tests) */
  const char *bad[] = {"--shape torus", "--levels 0", "--modes 0", "--shape sphere --modes 500",
                       "--levels 9", "--t-end -1", "--n0 1",
                       "--shape cylinder --mesh-dir /nonexistent",
                       "--shape sphere --mesh-dir /nonexistent"};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    run_output b = run_cli("maxwell mesh-cavity %s", bad[i]);
    cr_expect_eq(b.status, 2, "%s: status %d", bad[i], b.status);
    cr_expect(strstr(b.err, "maxwell mesh-cavity") != NULL, "%s: %s", bad[i], b.err);
    run_output_free(&b);
  }
}
