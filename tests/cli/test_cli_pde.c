/* geomint pde: B10 reproduces seed 004's stability picture; run writes a CSV; bad input exits 2. */
#include "cli_harness.h"

TestSuite(cli_pde, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 300);

Test(cli_pde, b10_stability_picture) {
  run_output r = run_cli("pde b10 --no-plot --out b10");
  cr_assert_eq(r.status, 0, "%s", r.err);
  /* Δt = Δx: LF leaves |u| <= 100, EC and MS stay bounded; Δt = 2Δx: EC leaves within a few
   * steps (measured: step 10), MS stays bounded */
  cr_assert(strstr(r.out, "lf  dt/dx = 1: |u| > 100 at step") != NULL, "%s", r.out);
  cr_assert(strstr(r.out, "ec  dt/dx = 1: bounded to t = 500") != NULL, "%s", r.out);
  cr_assert(strstr(r.out, "ms  dt/dx = 1: bounded to t = 500") != NULL, "%s", r.out);
  cr_assert(strstr(r.out, "ms  dt/dx = 2: bounded to t = 100") != NULL, "%s", r.out);
  const char *ec2 = strstr(r.out, "ec  dt/dx = 2: |u| > 100 at step ");
  cr_assert_not_null(ec2, "%s", r.out);
  int step = atoi(ec2 + strlen("ec  dt/dx = 2: |u| > 100 at step "));
  cr_assert(step > 0 && step <= 20, "EC at dt = 2dx blew up only at step %d", step);
  char *dat = read_file(path_in_tmp("b10/b10-ms-2.dat"));
  cr_assert_not_null(dat);
  free(dat);
  run_output_free(&r);
}

Test(cli_pde, run_writes_csv) {
  run_output r = run_cli("pde run sine-gordon --scheme ec --n 200 --dt 0.1 --T 5 --out u.csv");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_assert(strstr(r.out, "max |u - exact|") != NULL, "%s", r.out);
  char *csv = read_file(path_in_tmp("u.csv"));
  cr_assert_not_null(csv);
  cr_assert_eq(count_lines(csv), 201);
  free(csv);
  run_output_free(&r);
}

Test(cli_pde, bad_input_exits_2) {
  const char *cases[] = {"pde run sine-gordon --scheme lf --dt 0.3",
                         "pde run sine-gordon --scheme preissmann --n 200",
                         "pde run sine-gordon --dt -1", "pde run sine-gordon --scheme box",
                         "pde run kdv --scheme zk --dt 0.01", "pde run kdv --c nan",
                         "pde run burgers", "pde run nls --dt 0",
                         "pde run sine-gordon --scheme gauss-prk --n 201",
                         "pde run kdv --scheme euler-box", "pde nls-long --only lf", "pde"};
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    run_output r = run_cli("%s", cases[k]);
    cr_assert_eq(r.status, 2, "'%s' exited %d: %s", cases[k], r.status, r.err);
    cr_assert(count_lines(r.err) == 1, "'%s': stderr '%s'", cases[k], r.err);
    run_output_free(&r);
  }
}

/* the shortened long run: 20 periods (the docs' run is 10⁴): the multisymplectic box keeps
 * its energy error bounded and the charge to round-off; box-sdirk2 drifts in both */
static void nls_long_numbers(const char *out, const char *name, double v[6]) {
  char key[64];
  snprintf(key, sizeof key, "  %-10s max relative error", name);
  const char *l = strstr(out, key);
  cr_assert_not_null(l, "%s", out);
  int got = sscanf(l + strlen(key),
                   ", first / last tenth: energy %lf / %lf, momentum %lf / %lf, charge %lf / %lf",
                   &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]);
  cr_assert_eq(got, 6, "%s", l);
}

Test(cli_pde, nls_long_bounded_against_drifting) {
  run_output r = run_cli("pde nls-long --periods 20 --no-plot --out nl");
  cr_assert_eq(r.status, 0, "%s", r.err);
  double b[6], s[6];
  nls_long_numbers(r.out, "preissmann", b);
  nls_long_numbers(r.out, "box-sdirk2", s);
  /* measured: preissmann energy 1.01e-3 / 8.4e-4, charge 1.4e-15 / 1.5e-15; box-sdirk2
   * energy 1.84e-3 / 2.32e-2, charge 3.2e-4 / 2.9e-3 */
  cr_assert(b[1] <= 2.0 * b[0], "preissmann energy error grew: %.3e -> %.3e", b[0], b[1]);
  cr_assert(b[4] < 1e-13 && b[5] < 1e-13, "preissmann charge %.2e %.2e", b[4], b[5]);
  cr_assert(s[1] >= 5.0 * s[0], "box-sdirk2 energy error did not drift: %.3e -> %.3e", s[0], s[1]);
  cr_assert(s[5] >= 5.0 * s[4], "box-sdirk2 charge did not drift: %.3e -> %.3e", s[4], s[5]);
  cr_assert(s[1] >= 10.0 * b[1], "last tenth: box-sdirk2 %.3e vs preissmann %.3e", s[1], b[1]);
  char *dat = read_file(path_in_tmp("nl/nls-long-box-sdirk2.dat"));
  cr_assert_not_null(dat);
  free(dat);
  run_output_free(&r);
}

Test(cli_pde, run_kdv_nls_and_vtk) {
  run_output r = run_cli("pde run kdv --scheme zk --dt 0.002 --T 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_assert(strstr(r.out, "mass 11.99999995") != NULL, "%s", r.out);
  run_output_free(&r);
  r = run_cli("pde run sine-gordon --scheme ms --dirichlet --T 2 --frames 10 --vtk sg.vti "
              "--out sg.csv");
  cr_assert_eq(r.status, 0, "%s", r.err);
  char *vti = read_file(path_in_tmp("sg.vti"));
  cr_assert_not_null(vti);
  /* 200 cells in x, 11 rows in t (t = 0 and 10 frames), cell data u, exact, error */
  cr_assert(strstr(vti, "WholeExtent=\"0 200 0 11 0 0\"") != NULL, "%.400s", vti);
  cr_assert(strstr(vti, "Name=\"error\"") != NULL);
  free(vti);
  char *csv = read_file(path_in_tmp("sg.csv"));
  cr_assert_not_null(csv);
  cr_assert_eq(count_lines(csv), 201);
  free(csv);
  run_output_free(&r);
  r = run_cli("pde run nls --T 0.5");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_assert(strstr(r.out, "charge 1.99287414843") != NULL, "%s", r.out);
  run_output_free(&r);
}

/* pde run projects gauss-prk's sampled initial data (gm_pde_gauss_project) unless
 * --no-project; measured max |psi - exact| 1.872e-3 projected, 1.891e-3 as sampled. */
Test(cli_pde, run_gauss_prk_projects_initial_data) {
  run_output r = run_cli("pde run nls --scheme gauss-prk");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_assert(strstr(r.out, "initial data projected") != NULL, "%s", r.out);
  cr_assert(strstr(r.out, "max |psi - exact| 1.872e-03") != NULL, "%s", r.out);
  run_output_free(&r);
  r = run_cli("pde run nls --scheme gauss-prk --no-project");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_assert(strstr(r.out, "projected") == NULL, "%s", r.out);
  cr_assert(strstr(r.out, "max |psi - exact| 1.891e-03") != NULL, "%s", r.out);
  run_output_free(&r);
}
