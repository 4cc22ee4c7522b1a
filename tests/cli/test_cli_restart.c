/* Checkpoints and restart on hostile input (issue 26, hardening item 6) and the continuation of
 * a finished run: forged checkpoints with a valid checksum are checked field by field, a CSV
 * that ends before the checkpoint is not continued (and is left untouched), one file cannot be
 * two outputs, a directory or a FIFO says what it is, and `--restart` carries a finished run to
 * a later --t-end or --steps bitwise equal to the longer run without interruption. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "cli/cli_harness.h"

TestSuite(cli_restart, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

#define HOSTILE GM_SOURCE_DIR "/tests/data/hostile/"

static void expect_refused(const char *args, const char *needle) {
  run_output r = run_cli("%s", args);
  cr_expect_eq(r.status, 2, "%s: exit %d: %s", args, r.status, r.err);
  cr_expect(strstr(r.err, needle) != NULL, "%s: stderr '%s' lacks '%s'", args, r.err, needle);
  cr_expect_eq(count_lines(r.err), 1, "%s", r.err);
  run_output_free(&r);
}

Test(cli_restart, forged_checkpoints_are_checked_field_by_field) {
  /* each file has a valid FNV-1a checksum; kepler, verlet, dt 0.01, t_end 500, step 45472 */
  expect_refused("run kepler --t-end 500 --restart " HOSTILE "ck_forge_run_h_zero.ck",
                 "checkpoint: the run's step h = 0 (must be finite and non-zero)");
  expect_refused("run kepler --t-end 500 --restart " HOSTILE "ck_forge_run_h_neg.ck",
                 "checkpoint: a run from 0 to 500 with step h = -0.01 at t = 454.72 is "
                 "inconsistent");
  expect_refused("run kepler --t-end 500 --restart " HOSTILE "ck_forge_t_inf.ck",
                 "checkpoint: time t = inf");
  expect_refused("run kepler --t-end 500 --restart " HOSTILE "ck_forge_y_zero.ck",
                 "checkpoint: the state is singular for this problem (energy -inf)");
  /* a damaged dim said "state size 4, this one has 4" */
  expect_refused("run kepler --t-end 500 --restart " HOSTILE "ck_flip0.ck",
                 "a problem of dimension 4398046511106 with state size 4, this one has "
                 "dimension 2 and state size 4");
}

Test(cli_restart, a_csv_that_ends_before_the_checkpoint_is_not_continued) {
  /* ck_short.csv ends at t = 0.27 (and a cut row), the checkpoint is at t = 454.72: continuing
   * it made the rows jump from 0.27 to 454.73 */
  char cmd[1024];
  snprintf(cmd, sizeof cmd, "cp %sck_short.csv %s && chmod u+w %s", HOSTILE, path_in_tmp("x.csv"),
           path_in_tmp("x.csv"));
  cr_assert_eq(system(cmd), 0);
  expect_refused("run kepler --t-end 500 --restart " HOSTILE "ck_mid50k.ck --out x.csv",
                 "cannot continue 'x.csv': its rows end at t = 0.27000000000000002, before "
                 "t = 454.72000000000003 (more than 0.01 earlier)");
  snprintf(cmd, sizeof cmd, "cmp -s %sck_short.csv %s", HOSTILE, path_in_tmp("x.csv"));
  cr_expect_eq(system(cmd), 0, "x.csv was changed");
  /* the same checkpoint without --out continues */
  run_output r = run_cli("run kepler --t-end 500 --restart " HOSTILE "ck_mid50k.ck --json");
  cr_expect_eq(r.status, 0, "%s", r.err);
  cJSON *j = parse_json(r.out);
  cr_expect_eq(json_number(j, "restart_step"), 45472);
  cr_expect_eq(json_number(j, "steps"), 50000);
  cJSON_Delete(j);
  run_output_free(&r);
}

Test(cli_restart, one_file_is_not_two_outputs_and_a_directory_is_named) {
  expect_refused("run kepler --checkpoint f.ck --out f.ck",
                 "--checkpoint and --out name the same file (f.ck)");
  expect_refused("run kepler --restart " HOSTILE "ck_mid50k.ck --t-end 500 --out " HOSTILE
                 "ck_mid50k.ck", "--out and --restart name the same file");
  expect_refused("run kepler --restart .", "--restart . is a directory, not a file");
  /* a FIFO without a writer blocked open(2) forever: now it reads as empty, at once */
  cr_assert_eq(mkfifo(path_in_tmp("ff"), 0600), 0);
  time_t t0 = time(NULL);
  expect_refused("run kepler --restart ff", "ff: checkpoint: the file ends early");
  cr_expect_lt(time(NULL) - t0, 10);
}

/* final state of a run as JSON text */
static char *final_of(const char *args) {
  run_output r = run_cli("%s --json", args);
  cr_assert_eq(r.status, 0, "%s: %s", args, r.err);
  cJSON *j = parse_json(r.out);
  char *s = cJSON_PrintUnformatted(cJSON_GetObjectItem(j, "final"));
  cJSON_Delete(j);
  run_output_free(&r);
  return s;
}

Test(cli_restart, a_finished_run_continues_bitwise_to_a_later_end) {
  /* the finished run to t = 50 saves its last step; continued to t = 100 it is bitwise the run
   * to t = 100 (the final state printed with 17 digits, and the CSV byte for byte) */
  free(final_of("run kepler --method yoshida-4 --t-end 50 --checkpoint c.ck "
                "--every-checkpoint 1000 --out s.csv"));
  char *continued = final_of("run kepler --method yoshida-4 --t-end 100 --restart c.ck --out s.csv");
  char *whole = final_of("run kepler --method yoshida-4 --t-end 100 --out l.csv");
  cr_expect_str_eq(continued, whole);
  char cmd[1024];
  snprintf(cmd, sizeof cmd, "cmp -s %s %s", path_in_tmp("s.csv"), path_in_tmp("l.csv"));
  cr_expect_eq(system(cmd), 0, "the continued CSV differs from the uninterrupted one");
  free(continued), free(whole);
  /* with --steps, and a checkpoint in the middle of the shorter run */
  free(final_of("run henon-heiles --method verlet --steps 3000 --checkpoint d.ck "
                "--every-checkpoint 1234"));
  continued = final_of("run henon-heiles --method verlet --steps 9000 --restart d.ck");
  whole = final_of("run henon-heiles --method verlet --steps 9000");
  cr_expect_str_eq(continued, whole);
  free(continued), free(whole);
  /* another step is not the same run */
  expect_refused("run kepler --method yoshida-4 --t-end 100 --dt 0.02 --restart c.ck",
                 "the run to t = 100 has the step 0.02, the saved run 0.01");
  expect_refused("run kepler --method yoshida-4 --t-end 20 --restart c.ck",
                 "the saved run is at step 5000 (t = 50), past the end of a run of 2000 steps");
}
