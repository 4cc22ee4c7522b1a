/* geomint maxwell mesh-cavity: the table prints, --plot draws, bad input is exit status 2. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli_harness.h"

Test(cli_mesh_cavity, cylinder_and_sphere_one_level) {
  run_output r = run_cli("maxwell mesh-cavity --shape cylinder --levels 1 --t-end 60 --mesh-dir "
                         GM_SOURCE_DIR "/examples");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect(strstr(r.out, "| f analytic | mult. |") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "| 0.76548 | 1 |") != NULL, "%s", r.out); /* TM010: j01 / (2π·0.5) */
  cr_expect(strstr(r.out, "spurious peaks below the 10th resonance") != NULL, "%s", r.out);
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
  cr_expect(strstr(r.out, "largest relative error in the band") != NULL, "%s", r.out);
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
