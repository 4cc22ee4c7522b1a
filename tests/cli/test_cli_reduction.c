/* geomint reduction: the double spherical pendulum run prints the RSPRK–SPRK agreement and writes
 * its data; the J2 run on a short interval; bad input exits 2. */
#include <criterion/criterion.h>
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cJSON.h>

#include "geomint/geomint.h"

#include "cli/cli_harness.h"

TestSuite(reduction, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

Test(reduction, dsp_rsprk_agrees_with_classical_sprk) {
  run_output r = run_cli("reduction double-spherical-pendulum --no-plot --t-end 3 --out %s", tmpdir);
  cr_assert_eq(r.status, 0, "stderr: %s", r.err);
  const char *p = strstr(r.out, "classical SPRK: r1 ");
  cr_assert_not_null(p, "%s", r.out);
  double r1 = NAN, r2 = NAN, phi = NAN, e = NAN;
  cr_assert_eq(sscanf(p, "classical SPRK: r1 %lf, r2 %lf, phi %lf, E %lf", &r1, &r2, &phi, &e), 4);
  /* measured r1 5.33e-14, r2 4.81e-14, phi 5.18e-13, E 2.28e-15: the two are the same scheme
   * in other coordinates, so the floor is the round-off of 300 steps; bounds ~5x */
  cr_expect(r1 < 3e-13 && r2 < 3e-13 && phi < 3e-12 && e < 1.2e-14, "%s", p);
  char *csv = read_file(path_in_tmp("dsp.csv"));
  cr_assert_not_null(csv);
  cr_expect_eq(count_lines(csv), 302); /* header + 301 samples */
  free(csv);
  run_output_free(&r);
}

Test(reduction, j2_discrete_routh_matches_rsprk) {
  run_output r = run_cli("reduction j2-satellite --no-plot --t-end 15 --out %s", tmpdir);
  cr_assert_eq(r.status, 0, "stderr: %s", r.err);
  const char *p = strstr(r.out, "along the run: ");
  cr_assert_not_null(p, "%s", r.out);
  double a = NAN, b = NAN;
  cr_assert_eq(sscanf(p, "along the run: %lf (J2 = 0), %lf", &a, &b), 2);
  /* measured 1.24e-14 for both (the same equations solved two ways: round-off) */
  cr_expect(a < 6e-14 && b < 6e-14, "%s", p);
  run_output_free(&r);
}

Test(reduction, bad_input_exits_2) {
  const char *bad[] = {"reduction", "reduction nope", "reduction j2-satellite --dt -1",
                       "reduction double-spherical-pendulum --x0 1.5,0.4,2,0,0,0",
                       "reduction double-spherical-pendulum --x0 0.5,0.4"};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    run_output r = run_cli("%s --out %s", bad[i], tmpdir);
    cr_expect_eq(r.status, 2, "%s: status %d, stderr %s", bad[i], r.status, r.err);
    cr_expect(count_lines(r.err) == 1, "%s: %s", bad[i], r.err);
    run_output_free(&r);
  }
}

/* the phases table: Montgomery's phase with lgvi-galerkin-2 to 2e-8 at T/256 (measured 9.13e-9),
 * lgvi at order 2, the tet-mesh holonomy equal to the deficit */
Test(reduction, phases_table) {
  run_output r = run_cli("reduction phases");
  cr_assert_eq(r.status, 0, "stderr: %s", r.err);
  double closed = NAN, got = NAN, e1 = NAN, e2 = NAN, order = NAN;
  const char *p = strstr(r.out, "lgvi-galerkin-2 ");
  cr_assert_not_null(p, "%s", r.out);
  cr_assert_eq(sscanf(p, "lgvi-galerkin-2 %lf %lf %lf %lf %lf", &closed, &got, &e1, &e2, &order), 5);
  cr_expect(e2 < 2e-8 && fabs(order - 4.0) < 0.3, "%s", p);
  p = strstr(r.out, "lgvi ");
  cr_assert_not_null(p);
  cr_assert_eq(sscanf(p, "lgvi %lf %lf %lf %lf %lf", &closed, &got, &e1, &e2, &order), 5);
  cr_expect(fabs(order - 2.0) < 0.2, "%s", p);
  for (const char *q = r.out; (q = strstr(q, "tet Levi-Civita")) != NULL; ++q) {
    cr_assert_eq(sscanf(q, "tet Levi-Civita %lf %lf %lf", &closed, &got, &e1), 3);
    cr_expect(e1 < 1e-12 && fabs(got - closed) < 1e-12, "%s", q);
  }
  run_output_free(&r);
  r = run_cli("reduction phases --no-plot --out %s", tmpdir);
  cr_assert_eq(r.status, 0, "stderr: %s", r.err);
  char *csv = read_file(path_in_tmp("phases-convergence.csv"));
  cr_assert_not_null(csv);
  cr_expect_eq(count_lines(csv), 7); /* header + N = 16 .. 512 */
  free(csv);
  run_output_free(&r);
}

/* `geomint routh` is the same command under the seed's name: same run, same printed numbers. */
Test(reduction, routh_is_reduction) {
  run_output a = run_cli("routh double-spherical-pendulum --no-plot --t-end 1 --out %s", tmpdir);
  run_output b = run_cli("reduction double-spherical-pendulum --no-plot --t-end 1 --out %s", tmpdir);
  cr_assert_eq(a.status, 0, "stderr: %s", a.err);
  cr_assert_eq(b.status, 0, "stderr: %s", b.err);
  cr_expect_str_eq(a.out, b.out);
  run_output_free(&a);
  run_output_free(&b);
}
