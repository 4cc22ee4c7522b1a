/* Bad input found by trying it (issue 17, items 3, 4, 8, 9): endless and huge files, control
 * bytes in messages, states off a constraint manifold, parameters that overflow. Each is an error
 * with one clear line on stderr (or a documented behaviour), never an endless run or a NaN. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli/cli_harness.h"

TestSuite(cli_hostile, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

static double seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void expect_one_clean_line(const char *err) {
  cr_expect_eq(count_lines(err), 1, "one line on stderr: %s", err);
  for (const char *c = err; *c; ++c)
    cr_expect(*c == '\n' || ((unsigned char)*c >= 0x20 && (unsigned char)*c != 0x7f),
              "control byte %#x on stderr", (unsigned char)*c);
}

Test(cli_hostile, endless_input_stops_at_once) {
  cr_assert_eq(symlink("/dev/zero", path_in_tmp("zero.msh")), 0);
  double t0 = seconds();
  run_output r = run_cli("mesh info zero.msh");
  cr_expect_neq(r.status, 0);
  cr_expect(strstr(r.err, "zero.msh: line 1: a NUL byte (binary data)") != NULL, "%s", r.err);
  expect_one_clean_line(r.err);
  run_output_free(&r);
  r = run_cli("run n-body --set file=/dev/zero --steps 1");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "/dev/zero:1: a NUL byte") != NULL, "%s", r.err);
  run_output_free(&r);
  /* a line with no end */
  FILE *f = fopen(path_in_tmp("long.txt"), "w");
  cr_assert_not_null(f);
  for (int i = 0; i < 10000; ++i) fputs("1 ", f);
  fclose(f);
  r = run_cli("run n-body --set file=long.txt --steps 1");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "long.txt:1: a line longer than 4096 bytes") != NULL, "%s", r.err);
  run_output_free(&r);
  cr_expect_lt(seconds() - t0, 20.0, "the three refusals took %.1f s", seconds() - t0);
}

Test(cli_hostile, mesh_size_limit_is_named_and_can_be_raised) {
  FILE *f = fopen(path_in_tmp("big.off"), "w");
  cr_assert_not_null(f);
  fputs("OFF\n3 1 0\n", f);
  for (int i = 0; i < 200000; ++i) fputs("# padding\n", f); /* 2 MB */
  fputs("0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", f);
  fclose(f);
  run_output r = run_cli("mesh info big.off --max-file-size 1M");
  cr_expect_neq(r.status, 0);
  cr_expect(strstr(r.err, "more than the limit of 1048576 bytes for a mesh file (raise it with "
                          "--max-file-size)") != NULL,
            "%s", r.err);
  expect_one_clean_line(r.err);
  run_output_free(&r);
  r = run_cli("mesh info big.off --max-file-size 4M --json");
  cr_expect_eq(r.status, 0, "%s", r.err);
  run_output_free(&r);
  r = run_cli("mesh info big.off --max-file-size 12X");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "--max-file-size 12X: expected a size") != NULL, "%s", r.err);
  run_output_free(&r);
}

Test(cli_hostile, file_bytes_are_escaped_on_the_terminal) {
  FILE *f = fopen(path_in_tmp("esc.off"), "w");
  cr_assert_not_null(f);
  fputs("OFF\n3 1 0\n0 0 0\n1\033]0;owned\a 0 0\n0 1 0\n3 0 1 2\n", f);
  fclose(f);
  run_output r = run_cli("mesh info esc.off");
  cr_expect_neq(r.status, 0);
  cr_expect(strstr(r.err, "found '1\\x1b]0;owned\\x07'") != NULL, "%s", r.err);
  expect_one_clean_line(r.err);
  run_output_free(&r);
  f = fopen(path_in_tmp("bodies.txt"), "w");
  cr_assert_not_null(f);
  fputs("1 0 0 0 0 0 0\n1 1\033[2J 0 0 0 0 0\n", f);
  fclose(f);
  r = run_cli("run n-body --set file=bodies.txt --steps 1");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "bodies.txt:2: '1\\x1b[2J' is not a number") != NULL, "%s", r.err);
  expect_one_clean_line(r.err);
  run_output_free(&r);
}
