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
  cr_expect(r1 < 1e-10 && r2 < 1e-10 && phi < 1e-9 && e < 1e-12, "%s", p);
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
  cr_expect(a < 1e-11 && b < 1e-11, "%s", p);
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
