/* One integration with a monitor and an optional CSV writer, shared by run and demo. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli/cli.h"
#include "geomint/io.h"

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void cli_sim_result_clear(cli_sim_result *r) {
  free(r->y_final);
  gm_monitor_free(r->monitor);
  memset(r, 0, sizeof *r);
}

/* Print the one-line error and keep it in r->error (for --json). */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static void sim_error(cli_sim_result *r, const char *command, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(r->error, sizeof r->error, fmt, ap);
  va_end(ap);
  cli_error(command, "%s", r->error);
}

/* Create everything the run needs; returns an exit status. */
static int prepare(const char *command, const cli_sim_config *c, const double *y0, double t0,
                   gm_integrator **it, gm_csv_writer **csv, cli_sim_result *r) {
  const gm_problem *pb = gm_model_problem(c->model);
  const char *problem = gm_model_info_of(c->model)->name;
  gm_error err = {{0}};
  char name[128];
  cli_scheme_name(&c->scheme, name, sizeof name);
  gm_status st = gm_integrator_create_scheme(&c->scheme, pb, it, &err);
  if (st != GM_OK) {
    sim_error(r, command, "%s with %s: %s", problem, name,
              err.message[0] ? err.message : gm_strerror(st));
    return st == GM_ENOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
  }
  st = gm_integrator_set_state(*it, t0, y0);
  if (st != GM_OK) {
    sim_error(r, command, "%s: initial state: %s", problem, gm_integrator_errmsg(*it));
    return CLI_EXIT_USAGE;
  }
  if (gm_monitor_create(pb, y0, &r->monitor) != GM_OK ||
      gm_integrator_add_observer(*it, gm_monitor_observe, r->monitor, c->monitor_every) !=
          GM_OK) {
    sim_error(r, command, "cannot set up the energy monitor: %s", gm_integrator_errmsg(*it));
    return CLI_EXIT_FAILURE;
  }
  if (c->csv_path != NULL) {
    st = gm_csv_writer_create(c->csv_path, pb, y0, csv, &err);
    if (st != GM_OK) {
      sim_error(r, command, "%s", err.message);
      return CLI_EXIT_FAILURE;
    }
    r->energy_column = gm_csv_writer_column(*csv, "rel_energy_error");
    if (gm_integrator_add_observer(*it, gm_csv_writer_observe, *csv, c->csv_every) != GM_OK) {
      sim_error(r, command, "cannot add the CSV writer: %s", gm_integrator_errmsg(*it));
      return CLI_EXIT_FAILURE;
    }
  }
  return CLI_EXIT_OK;
}

int cli_simulate(const char *command, const cli_sim_config *c, cli_sim_result *r) {
  memset(r, 0, sizeof *r);
  r->energy_column = (size_t)-1;
  size_t n = gm_model_state_size(c->model);
  r->n_state = n;
  r->y_final = calloc(n, sizeof *r->y_final);
  double *y0 = calloc(n, sizeof *y0);
  if (r->y_final == NULL || y0 == NULL) {
    free(y0);
    cli_error(command, "out of memory");
    return CLI_EXIT_FAILURE;
  }
  gm_model_initial_state(c->model, &r->t0, y0);
  if (c->n_steps == 0 && !(c->t_end > r->t0)) {
    free(y0);
    snprintf(r->error, sizeof r->error, "--t-end %g is not after the initial time %g", c->t_end,
             r->t0);
    cli_error(command, "%s", r->error);
    return CLI_EXIT_USAGE;
  }
  /* the same check, and exit status, as `geomint order` for a step too small */
  if (c->n_steps == 0 && cli_check_step_count(command, c->t_end - r->t0, c->dt) != CLI_EXIT_OK) {
    free(y0);
    snprintf(r->error, sizeof r->error, "--dt %g is too small for --t-end %g", c->dt, c->t_end);
    return CLI_EXIT_USAGE;
  }
  memcpy(r->y_final, y0, n * sizeof *y0);
  r->t_final = r->t0;

  gm_integrator *it = NULL;
  gm_csv_writer *csv = NULL;
  cli_progress progress;
  cli_progress_start(&progress, command, c->quiet);
  progress.total_steps =
      c->n_steps > 0 ? (double)c->n_steps : ceil((c->t_end - r->t0) / c->dt);
  int status = prepare(command, c, y0, r->t0, &it, &csv, r);
  free(y0);
  /* last: progress and SIGINT are checked after the CSV row of a step is written */
  if (status == CLI_EXIT_OK &&
      gm_integrator_add_observer(it, cli_progress_observe, &progress, CLI_PROGRESS_EVERY) !=
          GM_OK) {
    cli_error(command, "cannot add the progress observer: %s", gm_integrator_errmsg(it));
    status = CLI_EXIT_FAILURE;
  }
  if (status == CLI_EXIT_OK) {
    double start = now_s();
    r->ran = 1;
    cli_interrupt_install();
    gm_status st = c->n_steps > 0 ? gm_integrator_run(it, c->n_steps, c->dt)
                                   : gm_integrator_integrate(it, c->t_end, c->dt);
    cli_interrupt_restore();
    cli_progress_end(&progress);
    r->wall_s = now_s() - start;
    r->stats = gm_integrator_stats(it);
    r->t_final = gm_integrator_time(it);
    memcpy(r->y_final, gm_integrator_state(it), n * sizeof *r->y_final);
    if (st == GM_OK && csv != NULL && gm_csv_writer_flush(csv) != GM_OK) st = GM_EIO;
    if (st != GM_OK) {
      const char *why = gm_integrator_errmsg(it);
      if (gm_monitor_errmsg(r->monitor)[0] != '\0') why = gm_monitor_errmsg(r->monitor);
      if (csv != NULL && gm_csv_writer_errmsg(csv)[0] != '\0') why = gm_csv_writer_errmsg(csv);
      if (cli_interrupted) {
        snprintf(r->error, sizeof r->error,
                 "interrupted (SIGINT) at t = %.17g after %zu steps; the output ends with the "
                 "last whole row", r->t_final, r->stats.steps);
        status = CLI_EXIT_INTERRUPTED;
      } else {
        snprintf(r->error, sizeof r->error, "%s with %s failed at t = %.17g after %zu steps: %s",
                 gm_model_info_of(c->model)->name, c->scheme.method->name, r->t_final,
                 r->stats.steps, why[0] ? why : gm_strerror(st));
        status = CLI_EXIT_FAILURE;
      }
      cli_error(command, "%s", r->error);
    }
  } else if (r->error[0] == '\0') {
    snprintf(r->error, sizeof r->error, "the run could not be set up (see the message above)");
  }
  if (csv != NULL) gm_csv_writer_flush(csv); /* after a failure: the rows before it, whole */
  r->csv_rows = gm_csv_writer_rows(csv);
  gm_csv_writer_free(csv);
  gm_integrator_free(it);
  return status;
}
