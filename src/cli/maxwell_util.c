/* Shared by the maxwell subcommands: a wall clock, progress on a terminal, and harminv with
 * the filter the summaries use. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli/maxwell.h"
#include "geomint/experiments.h"

double mx_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void mx_progress_start(mx_progress *p, size_t total) {
  p->enabled = isatty(STDERR_FILENO);
  p->t_start = mx_now();
  p->total = total;
}

void mx_progress_show(mx_progress *p, size_t done) {
  if (!p->enabled || p->total == 0) return;
  double elapsed = mx_now() - p->t_start;
  double frac = (double)done / (double)p->total;
  double eta = frac > 0 ? elapsed * (1 - frac) / frac : 0;
  fprintf(stderr, "\r  step %zu / %zu (%3.0f%%), %.1f s, about %.0f s left   ", done, p->total,
          100 * frac, elapsed, eta);
  fflush(stderr);
}

void mx_progress_end(mx_progress *p) {
  if (!p->enabled) return;
  fputs("\r\033[K", stderr); /* clear the progress line */
  fflush(stderr);
}

size_t mx_resonances(const double *signal, size_t n, double dt, double f_min, double f_max,
                     gm_harminv_mode *modes, size_t cap, char *msg, size_t msg_cap) {
  return mx_resonances_with(signal, n, dt, f_min, f_max, NULL, modes, cap, msg, msg_cap);
}

size_t mx_resonances_with(const double *signal, size_t n, double dt, double f_min, double f_max,
                          const mx_harminv_params *hp, gm_harminv_mode *modes, size_t cap,
                          char *msg, size_t msg_cap) {
  gm_error err = {{0}};
  size_t kept = 0;
  msg[0] = '\0';
  if (gm_experiment_resonances_with(signal, n, dt, f_min, f_max, hp, modes, cap, &kept, &err) !=
      GM_OK)
    snprintf(msg, msg_cap, "%s", err.message);
  return kept;
}

int mx_make_dir(const char *command, const char *dir) {
  return mx_make_option_dir(command, "--out", dir);
}

int mx_make_option_dir(const char *command, const char *option, const char *dir) {
  struct stat sb;
  if (stat(dir, &sb) == 0) {
    if (S_ISDIR(sb.st_mode) && access(dir, W_OK) == 0) return CLI_EXIT_OK;
    cli_error(command, "%s %s: not a writable directory", option, dir);
    return CLI_EXIT_FAILURE;
  }
  if (mkdir(dir, 0777) != 0) {
    cli_error(command, "cannot create directory %s: %s", dir, strerror(errno));
    return CLI_EXIT_FAILURE;
  }
  return CLI_EXIT_OK;
}

const char *mx_path(char *buf, size_t cap, const char *dir, const char *name) {
  snprintf(buf, cap, "%s/%s", dir, name);
  return buf;
}
