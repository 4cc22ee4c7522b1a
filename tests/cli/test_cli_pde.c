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
  cr_assert(strstr(r.out, "max |u - breather|") != NULL, "%s", r.out);
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
                         "pde run kdv", "pde"};
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    run_output r = run_cli("%s", cases[k]);
    cr_assert_eq(r.status, 2, "'%s' exited %d: %s", cases[k], r.status, r.err);
    cr_assert(count_lines(r.err) == 1, "'%s': stderr '%s'", cases[k], r.err);
    run_output_free(&r);
  }
}
