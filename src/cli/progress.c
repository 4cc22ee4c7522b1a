/* Long runs: a work estimate and a progress line with ETA on stderr (only when stderr is a
 * terminal and --quiet is not given), and SIGINT, which stops the run cleanly at the next
 * observation so that the output written so far ends with a whole row. */
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli/cli.h"

/* A run is "long" when it is estimated to take more than this (seconds): then the estimate and
 * the progress line are shown. The estimate is made after the first half second. */
#define LONG_RUN_S 3.0
#define FIRST_ESTIMATE_S 0.5
#define REDRAW_S 0.25

volatile sig_atomic_t cli_interrupted = 0;
static struct sigaction previous_sigint;
static int sigint_installed = 0;

static void on_sigint(int sig) {
  (void)sig;
  cli_interrupted = 1;
  signal(SIGINT, SIG_DFL); /* a second Ctrl-C ends the program at once */
}

void cli_interrupt_install(void) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  cli_interrupted = 0;
  if (sigaction(SIGINT, &sa, &previous_sigint) == 0) sigint_installed = 1;
}

void cli_interrupt_restore(void) {
  if (sigint_installed) sigaction(SIGINT, &previous_sigint, NULL);
  sigint_installed = 0;
}

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void cli_progress_start(cli_progress *p, const char *command, int quiet) {
  memset(p, 0, sizeof *p);
  p->command = command;
  p->enabled = !quiet && isatty(STDERR_FILENO);
  p->start = now_s();
}

/* "2.5 s", "3.1 min", "4.2 h", "1.3e+03 days" */
static void format_duration(double s, char *buf, size_t cap) {
  if (s < 90.0)
    snprintf(buf, cap, "%.1f s", s);
  else if (s < 5400.0)
    snprintf(buf, cap, "%.1f min", s / 60.0);
  else if (s < 172800.0)
    snprintf(buf, cap, "%.1f h", s / 3600.0);
  else
    snprintf(buf, cap, "%.3g days", s / 86400.0);
}

int cli_progress_update(cli_progress *p, double done, double total) {
  if (cli_interrupted) return 1;
  if (!p->enabled || done <= 0.0) return 0;
  const double t = now_s(), elapsed = t - p->start;
  if (elapsed < FIRST_ESTIMATE_S) return 0;
  if (total < done) total = done;
  const double left = elapsed * (total - done) / done;
  char eta[32];
  format_duration(left, eta, sizeof eta);
  if (!p->long_run) { /* re-estimated at every update: `order` learns its total as it goes */
    if (elapsed + left < LONG_RUN_S) return 0;
    p->long_run = 1;
    p->announced = 1;
    char all[32];
    format_duration(elapsed + left, all, sizeof all);
    fprintf(stderr, "geomint %s: %.3g steps, estimated %s at the current rate (Ctrl-C stops "
            "and keeps what was written)\n", p->command, total, all);
  }
  if (t - p->last_print < REDRAW_S) return 0;
  p->last_print = t;
  fprintf(stderr, "\rgeomint %s: %5.1f%% of %.3g steps, %s left   ", p->command,
          100.0 * done / total, total, eta);
  fflush(stderr);
  p->printed = 1;
  return 0;
}

void cli_progress_end(cli_progress *p) {
  if (p->printed) fputc('\n', stderr);
  p->printed = 0;
}

int cli_progress_observe(void *ctx, size_t step, double t, const double *y) {
  (void)t;
  (void)y;
  cli_progress *p = ctx;
  return cli_progress_update(p, (double)step - p->step_offset, p->total_steps);
}
