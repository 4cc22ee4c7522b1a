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

/* The discrete energy error of the last step of a vi-sem run, |E_d − E| / |E|: a CSV column. */
static double discrete_energy_column(void *ctx, size_t step, double t, const double *y) {
  (void)t;
  (void)y;
  const gm_integrator *it = ctx;
  const double e = gm_variational_discrete_energy(it), d = gm_variational_last_energy_error(it);
  if (step == 0 || isnan(e)) return 0.0; /* no step yet: nothing to compare */
  return e != 0.0 ? fabs(d) / fabs(e) : fabs(d);
}

/* Checkpoints every K steps: the CSV so far is flushed first, the monitor's state goes into
 * the checkpoint's extra bytes. */
typedef struct checkpointer {
  gm_integrator *it;
  gm_csv_writer *csv;
  const gm_monitor *monitor;
  const char *path;
  size_t written;
  char errmsg[GM_ERRMSG_SIZE + 64];
} checkpointer;

static int save_checkpoint(checkpointer *cp) {
  double extra[CLI_MAX_MONITOR_STATE];
  const size_t n_extra = gm_monitor_state_size(cp->monitor);
  if (n_extra > CLI_MAX_MONITOR_STATE) {
    snprintf(cp->errmsg, sizeof cp->errmsg, "checkpoint: too many invariants");
    return 1;
  }
  gm_monitor_state_save(cp->monitor, extra);
  if (cp->csv != NULL && gm_csv_writer_flush(cp->csv) != GM_OK) {
    snprintf(cp->errmsg, sizeof cp->errmsg, "%s", gm_csv_writer_errmsg(cp->csv));
    return 1;
  }
  if (gm_integrator_save_file(cp->it, cp->path, extra, n_extra * sizeof *extra) != GM_OK) {
    snprintf(cp->errmsg, sizeof cp->errmsg, "%s", gm_integrator_errmsg(cp->it));
    return 1;
  }
  cp->written++;
  return 0;
}

static int observe_checkpoint(void *ctx, size_t step, double t, const double *y) {
  (void)t;
  (void)y;
  checkpointer *cp = ctx;
  return step == 0 ? 0 : save_checkpoint(cp);
}

/* Read the checkpoint into the integrator (and the monitor's state into `monitor` if given). */
static int load_checkpoint(const char *command, const cli_sim_config *c, gm_integrator *it,
                           gm_monitor *monitor, cli_sim_result *r) {
  double extra[CLI_MAX_MONITOR_STATE];
  size_t got = 0;
  if (gm_integrator_load_file(it, c->restart_path, extra, sizeof extra, &got) != GM_OK) {
    sim_error(r, command, "--restart %s", gm_integrator_errmsg(it));
    return CLI_EXIT_USAGE;
  }
  if (monitor != NULL) {
    if (got != gm_monitor_state_size(monitor) * sizeof(double)) {
      sim_error(r, command, "--restart %s: not a checkpoint of 'geomint run' for this problem",
                c->restart_path);
      return CLI_EXIT_USAGE;
    }
    gm_monitor_state_load(monitor, extra);
  }
  return CLI_EXIT_OK;
}

/* The loaded run becomes the run this command asks for: the same one, or a longer one with the
 * same step (gm_integrator_extend_run). */
static int extend_run(const char *command, const cli_sim_config *c, gm_integrator *it,
                      cli_sim_result *r) {
  if (gm_integrator_chooses_steps(it)) return CLI_EXIT_OK; /* continues to its saved end */
  if (gm_integrator_extend_run(it, c->n_steps, c->t_end, c->dt) != GM_OK) {
    sim_error(r, command, "--restart %s: %s", c->restart_path, gm_integrator_errmsg(it));
    return CLI_EXIT_USAGE;
  }
  return CLI_EXIT_OK;
}

/* Create everything the run needs; returns an exit status. */
static int prepare(const char *command, const cli_sim_config *c, const double *y0, double t0,
                   gm_integrator **it, gm_csv_writer **csv, checkpointer *cp,
                   cli_sim_result *r) {
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
  int status;
  if (c->restart_path != NULL) { /* first to learn where the run stopped */
    if ((status = load_checkpoint(command, c, *it, NULL, r)) != CLI_EXIT_OK) return status;
    /* the same run, or a longer one (a finished run continued to a later --t-end/--steps) */
    if ((status = extend_run(command, c, *it, r)) != CLI_EXIT_OK) return status;
    r->restarted = 1;
    r->restart_step = gm_integrator_stats(*it).steps;
    r->restart_t = gm_integrator_time(*it);
  }
  if (gm_monitor_create(pb, y0, &r->monitor) != GM_OK ||
      gm_integrator_add_observer(*it, gm_monitor_observe, r->monitor, c->monitor_every) !=
          GM_OK) {
    sim_error(r, command, "cannot set up the energy monitor: %s", gm_integrator_errmsg(*it));
    return CLI_EXIT_FAILURE;
  }
  if (c->csv_path != NULL) {
    /* a CSV being continued has a row at most one observation interval (--every steps)
     * before the checkpoint; vi-sem-* choose their steps: no bound */
    const double max_gap = gm_integrator_chooses_steps(*it)
                               ? INFINITY
                               : (double)c->csv_every * c->dt * (1.0 + 1e-9) +
                                     1e-12 * fabs(r->restart_t);
    st = r->restarted ? gm_csv_writer_resume_within(c->csv_path, pb, y0, r->restart_t, max_gap,
                                                    csv, &err)
                      : gm_csv_writer_create(c->csv_path, pb, y0, csv, &err);
    if (st != GM_OK) {
      sim_error(r, command, "%s", err.message);
      return st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
    }
    r->energy_column = gm_csv_writer_column(*csv, "rel_energy_error");
    if (gm_integrator_chooses_steps(*it) &&
        gm_csv_writer_add_column(*csv, "discrete_energy_error", discrete_energy_column, *it) !=
            GM_OK) {
      sim_error(r, command, "cannot add a CSV column: %s", gm_csv_writer_errmsg(*csv));
      return CLI_EXIT_FAILURE;
    }
    if (gm_integrator_add_observer(*it, gm_csv_writer_observe, *csv, c->csv_every) != GM_OK) {
      sim_error(r, command, "cannot add the CSV writer: %s", gm_integrator_errmsg(*it));
      return CLI_EXIT_FAILURE;
    }
  }
  *cp = (checkpointer){*it, *csv, r->monitor, c->checkpoint_path, 0, ""};
  /* again, now that the observers are there: they have seen the saved step */
  if (r->restarted && ((status = load_checkpoint(command, c, *it, r->monitor, r)) != CLI_EXIT_OK ||
                       (status = extend_run(command, c, *it, r)) != CLI_EXIT_OK))
    return status;
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
  checkpointer cp;
  memset(&cp, 0, sizeof cp);
  int status = prepare(command, c, y0, r->t0, &it, &csv, &cp, r);
  free(y0);
  /* then: progress and SIGINT are checked after the CSV row of a step is written */
  if (status == CLI_EXIT_OK &&
      gm_integrator_add_observer(it, cli_progress_observe, &progress, CLI_PROGRESS_EVERY) !=
          GM_OK) {
    sim_error(r, command, "cannot add the progress observer: %s", gm_integrator_errmsg(it));
    status = CLI_EXIT_FAILURE;
  }
  if (status == CLI_EXIT_OK && c->checkpoint_path != NULL && c->checkpoint_every > 0 &&
      gm_integrator_add_observer(it, observe_checkpoint, &cp, c->checkpoint_every) != GM_OK) {
    sim_error(r, command, "cannot add the checkpoint writer: %s", gm_integrator_errmsg(it));
    status = CLI_EXIT_FAILURE;
  }
  if (r->restarted) {
    progress.step_offset = (double)r->restart_step;
    progress.total_steps -= progress.step_offset;
  }
  if (status == CLI_EXIT_OK) {
    double start = now_s();
    r->ran = 1;
    cli_interrupt_install();
    gm_status st = r->restarted  ? gm_integrator_resume(it)
                   : c->n_steps > 0 ? gm_integrator_run(it, c->n_steps, c->dt)
                                    : gm_integrator_integrate(it, c->t_end, c->dt);
    cli_interrupt_restore();
    /* interrupted: a last checkpoint where the run stopped (a consistent, observed state) */
    if (st != GM_OK && cli_interrupted && c->checkpoint_path != NULL) save_checkpoint(&cp);
    r->checkpoints = cp.written;
    if (gm_integrator_chooses_steps(it)) {
      r->chooses_steps = 1;
      r->discrete_energy = gm_variational_discrete_energy(it);
      const double e = r->discrete_energy, d = gm_variational_max_energy_error(it);
      r->max_rel_discrete_energy_error = e != 0.0 ? d / fabs(e) : d;
      r->energy_fallbacks = gm_variational_energy_fallbacks(it);
      r->energy_unresolved = gm_variational_unresolved_steps(it);
    }
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
      if (cp.errmsg[0] != '\0') why = cp.errmsg;
      if (cli_interrupted) {
        snprintf(r->error, sizeof r->error,
                 "interrupted (SIGINT) at t = %.17g after %zu steps; the output ends with the "
                 "last whole row%s%s", r->t_final, r->stats.steps,
                 c->checkpoint_path != NULL ? "; continue with --restart " : "",
                 c->checkpoint_path != NULL ? c->checkpoint_path : "");
        status = CLI_EXIT_INTERRUPTED;
      } else {
        const int sampled = why == gm_monitor_errmsg(r->monitor) && c->monitor_every > 1;
        char stride[96] = "";
        if (sampled) /* the monitor saw it at its first observation since it happened */
          snprintf(stride, sizeof stride, " (the monitor observes every %zu steps)",
                   c->monitor_every);
        snprintf(r->error, sizeof r->error, "%s with %s failed at t = %.17g after %zu steps: %s%s",
                 gm_model_info_of(c->model)->name, c->scheme.method->name, r->t_final,
                 r->stats.steps, why[0] ? why : gm_strerror(st), stride);
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
