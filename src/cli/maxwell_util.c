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
  const mx_harminv_params def = {0, 1e-4, 1.0, 1e-6};
  return mx_resonances_with(signal, n, dt, f_min, f_max, &def, modes, cap, msg, msg_cap);
}

size_t mx_resonances_with(const double *signal, size_t n, double dt, double f_min, double f_max,
                          const mx_harminv_params *hp, gm_harminv_mode *modes, size_t cap,
                          char *msg, size_t msg_cap) {
  gm_harminv_mode all[256];
  size_t n_all = 0;
  gm_error err = {{0}};
  msg[0] = '\0';
  if (gm_harminv(n, signal, NULL, dt, f_min, f_max, hp->basis, 256, all, &n_all, &err) !=
      GM_OK) {
    snprintf(msg, msg_cap, "%s", err.message);
    return 0;
  }
  /* harminv also returns weak, badly resolved components of noise: keep a mode when its
   * error estimate is small, it is not overdamped (|Q| > 1; a lossless mode's decay is ±1e-13,
   * so Q's sign means nothing there), and its amplitude is not negligible against the
   * strongest one. */
  double a_max = 0;
  for (size_t k = 0; k < n_all; ++k)
    if (isfinite(all[k].amplitude)) a_max = fmax(a_max, all[k].amplitude);
  size_t kept = 0;
  for (size_t k = 0; k < n_all && kept < cap; ++k)
    if (all[k].error < hp->max_error && fabs(all[k].q) > hp->min_q &&
        isfinite(all[k].frequency) && all[k].amplitude >= hp->min_amplitude * a_max)
      modes[kept++] = all[k];
  return kept;
}

int mx_make_dir(const char *command, const char *dir) {
  struct stat sb;
  if (stat(dir, &sb) == 0) {
    if (S_ISDIR(sb.st_mode) && access(dir, W_OK) == 0) return CLI_EXIT_OK;
    cli_error(command, "--out %s: not a writable directory", dir);
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
