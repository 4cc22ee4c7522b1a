/* geomint oscillatory: the resonance picture of seed 000 Fig 2.1 (IMEX flat, r-RESPA spikes
 * just below integer ωh/π), the FPU numbers of Fig 2.2 against the seed notes' independent
 * check, and bad input (exit 2). */
#include <math.h>

#include "cli/cli_harness.h"

TestSuite(oscillatory, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

Test(oscillatory, resonance_imex_flat_respa_spikes) {
  run_output r = run_cli("oscillatory resonance --points 9 --no-plot --out %s", tmpdir);
  cr_assert_eq(r.status, 0, "stderr: %s", r.err);
  double lo, hi, ratio;
  const char *line = strstr(r.out, "imex:");
  cr_assert_not_null(line, "%s", r.out);
  cr_assert_eq(sscanf(line, "imex: max |H - H0| from %lf to %lf (ratio %lf)", &lo, &hi, &ratio),
               3, "%s", line);
  /* the seed notes' independent check: 1.253e-3 for every ωh/π */
  cr_expect(fabs(lo - 1.253e-3) < 1e-6 && fabs(hi - 1.253e-3) < 1e-6, "%g .. %g", lo, hi);
  line = strstr(r.out, "impulse (n = 100):");
  cr_assert_not_null(line);
  double worst, at;
  cr_assert_eq(sscanf(line, "impulse (n = 100): max |H - H0| up to %lf at omega h/pi = %lf",
                      &worst, &at),
               2, "%s", line);
  cr_expect_gt(worst, 1e3, "no resonance spike: %s", line);
  cr_expect(at > 0.99 && at < 1.0, "the largest spike at %g, expected just below 1", at);
  char *csv = read_file(path_in_tmp("resonance.csv"));
  cr_expect_eq(count_lines(csv), 1 + 9 + 48, "rows: %zu", count_lines(csv));
  free(csv);
  run_output_free(&r);
}

Test(oscillatory, fpu_matches_the_seed_notes) {
  run_output r = run_cli("oscillatory fpu --no-plot --out %s", tmpdir);
  cr_assert_eq(r.status, 0, "stderr: %s", r.err);
  /* notes/000 E2: reference I = [0.013, 0.027, 0.957] at t = 150; IMEX h = 0.1 gives
   * [0.017, 0.018, 0.968] with max |dH| = 0.020; Verlet h = 0.03 max |dH| = 0.65 */
  cr_expect(strstr(r.out, "0.013 0.027 0.957") != NULL, "%s", r.out);
  const char *imex = strstr(r.out, "  imex                         0.1");
  cr_assert_not_null(imex, "%s", r.out);
  double h, dh, di, dev, tx, i1, i2, i3;
  cr_assert_eq(sscanf(imex, " imex %lf %lf %lf %lf %lf %lf %lf %lf", &h, &dh, &di, &dev, &tx, &i1,
                      &i2, &i3),
               8, "%s", imex);
  /* the energy exchange time scale: I3 first above 0.5 at t = 101.4 in the reference */
  cr_expect(strstr(r.out, "(reference)     101.4") != NULL, "%s", r.out);
  cr_expect(fabs(tx - 101.4) < 10.0, "imex h = 0.1: exchange at t = %g", tx);
  cr_expect(dh < 0.025 && di < 0.1, "imex h = 0.1: max |dH| %g, max |dI| %g", dh, di);
  cr_expect(fabs(i1 - 0.017) < 2e-3 && fabs(i3 - 0.968) < 2e-3, "%g %g %g", i1, i2, i3);
  const char *verlet = strstr(r.out, "  verlet                      0.03");
  cr_assert_not_null(verlet);
  cr_assert_eq(sscanf(verlet, " verlet %lf %lf", &h, &dh), 2);
  cr_expect(dh > 0.3, "verlet h = 0.03 should be poor: max |dH| = %g", dh);
  run_output_free(&r);
}

Test(oscillatory, bad_input_exits_2) {
  run_output r = run_cli("oscillatory resonanse --no-plot --out %s", tmpdir);
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "unknown experiment") != NULL, "%s", r.err);
  run_output_free(&r);
  r = run_cli("oscillatory resonance --points 0 --no-plot --out %s", tmpdir);
  cr_expect_eq(r.status, 2);
  run_output_free(&r);
}
