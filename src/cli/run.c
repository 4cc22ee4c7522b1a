/* geomint run PROBLEM: integrate one problem with one method; summary, JSON, CSV, plot. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cJSON.h>

#include "cli/cli.h"

static const char usage[] =
    "usage: geomint run PROBLEM [--method NAME] [--basic NAME] [--solver NAME] [--dt H]\n"
    "                   [--t-end T | --steps N] [--every K] [--out FILE.csv] [--plot FILE.png]\n"
    "                   [--set name=value ...] [--compensated] [--json]\n\n"
    "Integrate PROBLEM (see 'geomint list problems') from its initial state.\n\n"
    "options:\n"
    "  --method NAME      integration method (default verlet; see 'geomint list methods')\n"
    "  --basic NAME       the basic method of a composition (default: the row's,\n"
    "                     verlet-position; verlet for sofroniou-spaletta-10);\n"
    "                     any symmetric order-2 method, e.g. midpoint for non-separable H\n"
    "  --solver NAME      stage equations of implicit methods: newton, simplified-newton,\n"
    "                     fixed-point, fixed-point-positions (q'' = f(q)); default: the\n"
    "                     latter where it applies, else fixed-point (Newton for stiff ones)\n"
    "  --dt H             step size (default 0.01)\n"
    "  --t-end T          final time (default 10); the steps are shortened to end exactly there\n"
    "                     (vi-sem-*, which choose their own steps: the first step reaching T)\n"
    "  --steps N          take N steps of size H instead (not together with --t-end)\n"
    "  --every K          observe (monitor and CSV) every K steps (default 1 with --out or\n"
    "                     --plot; without them the energy monitor observes every K steps\n"
    "                     with K = ceil(1024 / stages of the method), at most 1/100 of the\n"
    "                     planned steps, and the last step, so that it costs under 1 % of\n"
    "                     the run: --every 1 for every step)\n"
    "  --out FILE.csv     write t, q, p (or y), H, rel_energy_error and the invariants\n"
    "  --plot FILE.png    draw the relative energy error against time with gnuplot\n"
    "  --set name=value   change a parameter or an initial value (q1.., p1.., y1..); repeatable\n"
    "  --compensated      compensated (Kahan) summation of the state update\n"
    "  --json             print one JSON object instead of the summary (also when the run\n"
    "                     fails: then with \"error\" and the statistics up to the failure)\n"
    "  --quiet            no work estimate or progress line (shown on a terminal for runs\n"
    "                     estimated to take more than 3 s)\n"
    "  --checkpoint FILE  save a checkpoint to FILE every --every-checkpoint K steps (default:\n"
    "                     only when interrupted) and when Ctrl-C stops the run\n"
    "  --every-checkpoint K  steps between checkpoints\n"
    "  --restart FILE     continue the run saved in FILE (same problem, --set, method, --basic,\n"
    "                     --solver, --compensated, --dt and --t-end or --steps); the CSV given\n"
    "                     with --out is continued after the checkpoint's last row, and the\n"
    "                     result is bitwise that of the run without interruption; a later\n"
    "                     --t-end or --steps with the same --dt continues the run (finished\n"
    "                     or not) to there, bitwise as the longer run\n\n"
    "A state, energy or invariant that becomes NaN or infinite stops the run with an error\n"
    "naming the step and the component; the CSV ends with the last finite row. Ctrl-C (SIGINT)\n"
    "stops at the next step, keeps the CSV (whole rows) and exits with status 130.\n";

typedef struct run_options {
  const char *method, *basic, *solver;
  double dt, t_end;
  size_t steps, every;
  int every_given;     /* --every was given */
  const char *out, *plot;
  cli_settings settings;
  int compensated, json, quiet;
  const char *checkpoint, *restart;
  size_t every_checkpoint;
} run_options;

/* The energy monitor's default stride without an output file: one observation (an energy and
 * the invariants, about one to two force evaluations) per about 1024 force evaluations, taking
 * the method's stage count as its evaluations per step (implicit rows make more, FSAL
 * splittings one fewer), so that it costs under 1 % of the run (issue 25; measured with
 * callgrind in docs/cli.md). Deterministic: a restarted run observes the same steps. */
#define MONITOR_EVALS_PER_OBSERVATION 1024
/* ... but never fewer than about this many observations of a run (a short run costs little
 * either way, and its maxima should not rest on a handful of states) */
#define MONITOR_MIN_OBSERVATIONS 100

static size_t monitor_stride(const gm_scheme *sc, const run_options *o) {
  size_t stages = sc->method->n_stages > 0 ? sc->method->n_stages : 1;
  size_t stride = (MONITOR_EVALS_PER_OBSERVATION + stages - 1) / stages;
  /* the planned steps: --steps, or the span to --t-end in steps of --dt (from t = 0, so that a
   * restarted run chooses the stride of the uninterrupted one) */
  double planned = o->steps > 0 ? (double)o->steps : o->t_end / o->dt;
  double cap = planned / MONITOR_MIN_OBSERVATIONS;
  if (!(cap >= 1.0)) return 1;
  return cap < (double)stride ? (size_t)cap : stride;
}

/* The monitor's stride of this run: --every's with an output file or when given. */
static size_t monitor_every(const run_options *o, const gm_scheme *sc) {
  return o->every_given || o->out != NULL || o->plot != NULL ? o->every : monitor_stride(sc, o);
}

static cJSON *final_state(const gm_problem *pb, const cli_sim_result *r) {
  cJSON *final = cJSON_CreateObject();
  cJSON_AddItemToObject(final, "t", cli_json_number(r->t_final));
  if (gm_problem_has_momenta(pb)) {
    cJSON_AddItemToObject(final, "q", cli_json_numbers(r->y_final, pb->dim));
    cJSON_AddItemToObject(final, "p", cli_json_numbers(r->y_final + pb->dim, pb->dim));
  } else {
    cJSON_AddItemToObject(final, "y", cli_json_numbers(r->y_final, r->n_state));
  }
  return final;
}

/* Near-integrable rows: the coordinates they work in, and a warning when the step is longer
 * than a quarter of the shortest orbital period (or a planet is unbound) at the start. */
typedef struct {
  const char *coordinates; /* NULL: not a near-integrable row */
  int corrector;
  double shortest_period;
  size_t n_unbound;
  char warning[256];
} celestial_note;

static celestial_note celestial_check(const gm_scheme *sc, const gm_problem *pb,
                                      const gm_model *model, double dt) {
  celestial_note c = {NULL, 0, 0.0, 0, ""};
  gm_coordinates kind = gm_method_coordinates(sc->method);
  if (kind == 0 || pb->celestial == NULL) return c;
  c.coordinates = gm_coordinates_name(kind);
  c.corrector = gm_method_corrector_order(sc->method);
  double *y0 = malloc(gm_model_state_size(model) * sizeof *y0);
  if (y0 == NULL) return c;
  gm_model_initial_state(model, NULL, y0);
  c.shortest_period = gm_celestial_shortest_period(pb->celestial, kind, y0, &c.n_unbound);
  free(y0);
  if (dt > 0.25 * c.shortest_period)
    snprintf(c.warning, sizeof c.warning,
             "dt = %g is longer than a quarter of the shortest orbital period (%.4g): the "
             "splitting's error expansion does not hold",
             dt, c.shortest_period);
  else if (c.n_unbound > 0)
    snprintf(c.warning, sizeof c.warning,
             "%zu planet(s) on unbound Kepler orbits: drifts are exact for any conic, but the "
             "perturbation need not be small",
             c.n_unbound);
  return c;
}

static int print_json(const char *problem, const gm_scheme *sc, const gm_problem *pb,
                      const run_options *o, const cli_sim_result *r, const celestial_note *cn) {
  const gm_method *m = sc->method;
  cJSON *root = cJSON_CreateObject();
  cJSON_AddStringToObject(root, "problem", problem);
  cJSON_AddStringToObject(root, "method", m->name);
  if (sc->basic != NULL) cJSON_AddStringToObject(root, "basic", sc->basic->name);
  cJSON_AddStringToObject(root, "solver", gm_solver_name(sc->solver));
  if (cn->coordinates != NULL) {
    cJSON_AddStringToObject(root, "coordinates", cn->coordinates);
    cJSON_AddNumberToObject(root, "corrector_order", cn->corrector);
    cJSON_AddItemToObject(root, "shortest_period", cli_json_number(cn->shortest_period));
    if (cn->warning[0] != '\0') cJSON_AddStringToObject(root, "warning", cn->warning);
  }
  cJSON_AddNumberToObject(root, "dt", o->dt);
  cJSON_AddNumberToObject(root, "steps", (double)r->stats.steps);
  cJSON_AddItemToObject(root, "t0", cli_json_number(r->t0));
  cJSON_AddItemToObject(root, "t_end", cli_json_number(r->t_final));
  cJSON_AddNumberToObject(root, "force_evals", (double)r->stats.force_evals);
  cJSON_AddNumberToObject(root, "jacobian_evals", (double)r->stats.jacobian_evals);
  cJSON_AddNumberToObject(root, "fd_jacobians", (double)r->stats.fd_jacobians);
  cJSON_AddNumberToObject(root, "newton_iterations", (double)r->stats.newton_iterations);
  cJSON_AddNumberToObject(root, "fixed_point_iterations",
                          (double)r->stats.fixed_point_iterations);
  cJSON_AddNumberToObject(root, "wall_s", r->wall_s);
  cJSON_AddBoolToObject(root, "compensated", o->compensated != 0);
  cJSON_AddNumberToObject(root, "every", (double)o->every);
  cJSON_AddNumberToObject(root, "monitor_every", (double)monitor_every(o, sc));
  cJSON_AddNumberToObject(root, "monitor_observations", (double)gm_monitor_n_observed(r->monitor));
  cJSON_AddItemToObject(root, "initial_energy",
                        cli_json_number(gm_monitor_initial_energy(r->monitor)));
  cJSON_AddItemToObject(root, "max_rel_energy_error",
                        cli_json_number(gm_monitor_max_rel_energy_error(r->monitor)));
  cJSON_AddItemToObject(root, "final_rel_energy_error",
                        cli_json_number(gm_monitor_last_rel_energy_error(r->monitor)));
  if (r->chooses_steps) { /* vi-sem-*: what the method keeps, and how it ended */
    cJSON_AddTrueToObject(root, "chooses_steps");
    cJSON_AddItemToObject(root, "t_end_requested", cli_json_number(o->t_end));
    cJSON_AddItemToObject(root, "discrete_energy", cli_json_number(r->discrete_energy));
    cJSON_AddItemToObject(root, "max_rel_discrete_energy_error",
                          cli_json_number(r->max_rel_discrete_energy_error));
    cJSON_AddNumberToObject(root, "energy_fallbacks", (double)r->energy_fallbacks);
    cJSON_AddNumberToObject(root, "energy_unresolved_steps", (double)r->energy_unresolved);
  }
  if (r->restarted) {
    cJSON_AddStringToObject(root, "restart", o->restart);
    cJSON_AddNumberToObject(root, "restart_step", (double)r->restart_step);
    cJSON_AddItemToObject(root, "restart_t", cli_json_number(r->restart_t));
  }
  if (o->checkpoint != NULL) {
    cJSON_AddStringToObject(root, "checkpoint", o->checkpoint);
    cJSON_AddNumberToObject(root, "checkpoints", (double)r->checkpoints);
  }
  cJSON *inv = cJSON_AddObjectToObject(root, "invariants");
  for (size_t k = 0; k < pb->n_invariants; ++k)
    cJSON_AddItemToObject(inv, pb->invariants[k].name,
                          cli_json_number(gm_monitor_max_invariant_drift(r->monitor, k)));
  if (pb->kind == GM_PROBLEM_LAGRANGIAN && pb->n_constraints > 0) /* max |g(q)| at the end */
    cJSON_AddItemToObject(root, "constraint_residual",
                          cli_json_number(gm_constraint_residual(pb, r->y_final)));
  if (gm_problem_space(pb) != NULL) /* distance from the manifold at the end: |R^T R - I| */
    cJSON_AddItemToObject(root, "state_defect",
                          cli_json_number(gm_problem_state_defect(pb, r->y_final)));
  cJSON_AddItemToObject(root, "final", final_state(pb, r));
  if (o->out != NULL) {
    cJSON_AddStringToObject(root, "csv", o->out);
    cJSON_AddNumberToObject(root, "csv_rows", (double)r->csv_rows);
  }
  if (o->plot != NULL) cJSON_AddStringToObject(root, "plot", o->plot);
  return cli_json_print(root);
}

static void print_vector(const char *label, const double *x, size_t n) {
  printf("  %-3s =", label);
  for (size_t i = 0; i < n; ++i) printf(" %.10g", x[i]);
  putchar('\n');
}

static void print_summary(const char *problem, const gm_scheme *sc, const gm_problem *pb,
                          const run_options *o, const cli_sim_result *r,
                          const celestial_note *cn) {
  const gm_method *m = sc->method;
  char name[128];
  cli_scheme_name(sc, name, sizeof name);
  printf("%s with %s (order %d, %s%s)\n", problem, name, m->order,
         gm_method_family_name(m->family), o->compensated ? ", compensated" : "");
  if (r->chooses_steps)
    printf("steps             %zu of its own size (from dt = %g), t = %g .. %.10g\n",
           r->stats.steps, o->dt, r->t0, r->t_final);
  else
    printf("steps             %zu of dt = %g, t = %g .. %.10g\n", r->stats.steps, o->dt, r->t0,
           r->t_final);
  if (r->chooses_steps && r->t_final != o->t_end && o->steps == 0)
    printf("note              %s chooses its own steps: stopped at the first step reaching "
           "--t-end %g, t = %.10g\n", m->name, o->t_end, r->t_final);
  if (r->restarted)
    printf("restarted         from %s at step %zu, t = %.10g\n", o->restart, r->restart_step,
           r->restart_t);
  if (cn->coordinates != NULL) {
    printf("coordinates       %s", cn->coordinates);
    if (cn->corrector > 0) printf(", corrector of order %d at output times", cn->corrector);
    printf("; shortest orbital period %.6g\n", cn->shortest_period);
  }
  if (cn->warning[0] != '\0') printf("warning           %s\n", cn->warning);
  if (gm_problem_has_energy(pb)) {
    printf("energy            H0 = %.10g\n", gm_monitor_initial_energy(r->monitor));
    printf("rel. energy error max %.3e, final %.3e\n",
           gm_monitor_max_rel_energy_error(r->monitor),
           gm_monitor_last_rel_energy_error(r->monitor));
  }
  if (r->chooses_steps)
    printf("discrete energy   E_d = %.10g, max |E_d - E0|/|E0| %.3e (what %s keeps), "
           "%zu least-squares fallbacks, %zu steps kept (size unresolved)\n", r->discrete_energy,
           r->max_rel_discrete_energy_error, m->name, r->energy_fallbacks, r->energy_unresolved);
  for (size_t k = 0; k < pb->n_invariants; ++k)
    printf("%-17s max drift %.3e\n", pb->invariants[k].name,
           gm_monitor_max_invariant_drift(r->monitor, k));
  const size_t every = monitor_every(o, sc);
  if (every > 1 && (gm_problem_has_energy(pb) || pb->n_invariants > 0))
    printf("monitor           the maxima are over every %zu steps and the last (%zu observed; "
           "--every 1: every step)\n", every, gm_monitor_n_observed(r->monitor));
  if (pb->kind == GM_PROBLEM_LAGRANGIAN && pb->n_constraints > 0)
    printf("constraint        max |g(q)| = %.3e at the end\n", gm_constraint_residual(pb, r->y_final));
  if (gm_problem_space(pb) != NULL)
    printf("state space       %s = %.3e at the end\n", gm_problem_state_defect_name(pb),
           gm_problem_state_defect(pb, r->y_final));
  printf("work              %zu force evaluations, %zu Newton iterations, %.3f s\n",
         r->stats.force_evals, r->stats.newton_iterations, r->wall_s);
  if (r->stats.fd_jacobians > 0)
    printf("note              %zu finite-difference Jacobians (no analytic Hessian)\n",
           r->stats.fd_jacobians);
  printf("final state at t = %.10g:\n", r->t_final);
  if (gm_problem_has_momenta(pb)) {
    print_vector("q", r->y_final, pb->dim);
    print_vector("p", r->y_final + pb->dim, pb->dim);
  } else {
    print_vector("y", r->y_final, r->n_state);
  }
  if (o->out != NULL) printf("wrote %s (%zu rows)\n", o->out, r->csv_rows);
  if (o->checkpoint != NULL)
    printf("wrote %s (%zu checkpoints)\n", o->checkpoint, r->checkpoints);
  if (o->plot != NULL) printf("wrote %s\n", o->plot);
}

/* Was the option given on the command line? */
static int seen(const cli_option *options, size_t n, const char *name) {
  for (size_t i = 0; i < n; ++i)
    if (strcmp(options[i].name, name) == 0) return options[i].seen;
  return 0;
}

/* Do a and b name one file (the same path, or the same inode when both exist)? */
static int same_file(const char *a, const char *b) {
  if (a == NULL || b == NULL) return 0;
  if (strcmp(a, b) == 0) return 1;
  struct stat sa, sb;
  return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

static int check_options(const run_options *o, const cli_option *options, size_t n_options) {
  if (cli_check_positive("run", "--dt", o->dt) != CLI_EXIT_OK) return CLI_EXIT_USAGE;
  const int t_end = seen(options, n_options, "--t-end"), steps = seen(options, n_options, "--steps");
  if (t_end && steps) {
    cli_error("run", "give either --t-end or --steps, not both");
    return CLI_EXIT_USAGE;
  }
  if (cli_check_positive("run", "--t-end", o->t_end) != CLI_EXIT_OK) return CLI_EXIT_USAGE;
  if (steps && o->steps == 0) {
    cli_error("run", "--steps must be at least 1");
    return CLI_EXIT_USAGE;
  }
  if (steps && (double)o->steps > 1e15) { /* the driver's limit (gm_integrator_integrate) */
    cli_error("run", "--steps %zu is more than 1e15", o->steps);
    return CLI_EXIT_USAGE;
  }
  if (o->every == 0) {
    cli_error("run", "--every must be at least 1");
    return CLI_EXIT_USAGE;
  }
  if (seen(options, n_options, "--every-checkpoint") && o->checkpoint == NULL) {
    cli_error("run", "--every-checkpoint needs --checkpoint FILE");
    return CLI_EXIT_USAGE;
  }
  /* one file for two outputs: the checkpoint's rename would replace the CSV (or --out would
   * overwrite the checkpoint being continued) */
  const char *files[3][2] = {{"--checkpoint", o->checkpoint}, {"--out", o->out},
                             {"--restart", o->restart}};
  for (int a = 0; a < 2; ++a)
    for (int b = a + 1; b < 3; ++b)
      if (!(a == 0 && b == 2) && same_file(files[a][1], files[b][1])) {
        cli_error("run", "%s and %s name the same file (%s)", files[a][0], files[b][0],
                  files[b][1]);
        return CLI_EXIT_USAGE;
      }
  if (o->checkpoint != NULL && o->every_checkpoint == 0) {
    if (seen(options, n_options, "--every-checkpoint")) {
      cli_error("run", "--every-checkpoint must be at least 1");
      return CLI_EXIT_USAGE;
    }
  }
  return CLI_EXIT_OK;
}

/* Integrate, then plot; returns an exit status. tmp_csv: a temporary file for the plot. */
static int run_model(const char *problem, const gm_model *model, const gm_scheme *sc,
                     const run_options *o, const char *tmp_csv) {
  const gm_problem *pb = gm_model_problem(model);
  const gm_method *m = sc->method;
  const char *csv = o->out != NULL ? o->out : tmp_csv;
  cli_sim_config c = {*sc, model, o->dt, o->t_end, o->steps, monitor_every(o, sc), o->every,
                      csv, o->quiet, o->checkpoint, o->every_checkpoint, o->restart};
  cli_sim_result r;
  int status = cli_simulate("run", &c, &r);
  if (status == CLI_EXIT_OK && o->plot != NULL) {
    char title[256];
    snprintf(title, sizeof title, "%s, %s, dt = %g", problem, m->name, o->dt);
    cli_plot_series s = {c.csv_path, m->name, r.energy_column};
    status = cli_plot_energy_error("run", o->plot, title, &s, 1);
  }
  if (status == CLI_EXIT_OK) {
    celestial_note cn = celestial_check(sc, pb, model, o->dt);
    if (o->json)
      status = print_json(problem, sc, pb, o, &r, &cn);
    else
      print_summary(problem, sc, pb, o, &r, &cn);
  } else if (o->json) {
    /* one JSON object also for a failed run: the error and what was done up to it */
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "problem", problem);
    cJSON_AddStringToObject(root, "method", m->name);
    cJSON_AddStringToObject(root, "error", r.error);
    cJSON_AddNumberToObject(root, "exit_status", status);
    if (r.ran) {
      cJSON_AddNumberToObject(root, "steps", (double)r.stats.steps);
      cJSON_AddItemToObject(root, "t0", cli_json_number(r.t0));
      cJSON_AddItemToObject(root, "t", cli_json_number(r.t_final));
      cJSON_AddNumberToObject(root, "force_evals", (double)r.stats.force_evals);
      cJSON_AddNumberToObject(root, "newton_iterations", (double)r.stats.newton_iterations);
      cJSON_AddNumberToObject(root, "newton_failures", (double)r.stats.newton_failures);
      cJSON_AddItemToObject(root, "max_rel_energy_error",
                            cli_json_number(gm_monitor_max_rel_energy_error(r.monitor)));
      cJSON_AddItemToObject(root, "final", final_state(pb, &r));
      if (o->out != NULL) {
        cJSON_AddStringToObject(root, "csv", o->out);
        cJSON_AddNumberToObject(root, "csv_rows", (double)r.csv_rows);
      }
    }
    cli_json_print(root);
  }
  cli_sim_result_clear(&r);
  return status;
}

static int run_main(int argc, char **argv) {
  run_options o = {"verlet", NULL, NULL, 0.01, 10.0, 0, 1, 0, NULL, NULL, {0, {0}}, 0, 0, 0,
                   NULL, NULL, 0};
  cli_option options[] = {
      {"--method", CLI_ARG_STRING, &o.method, 0}, {"--dt", CLI_ARG_DOUBLE, &o.dt, 0},
      {"--basic", CLI_ARG_STRING, &o.basic, 0},   {"--solver", CLI_ARG_STRING, &o.solver, 0},
      {"--t-end", CLI_ARG_DOUBLE, &o.t_end, 0},   {"--steps", CLI_ARG_COUNT, &o.steps, 0},
      {"--every", CLI_ARG_COUNT, &o.every, 0},    {"--out", CLI_ARG_STRING, &o.out, 0},
      {"--plot", CLI_ARG_STRING, &o.plot, 0},     {"--set", CLI_ARG_SETTING, &o.settings, 0},
      {"--compensated", CLI_ARG_FLAG, &o.compensated, 0},
      {"--json", CLI_ARG_FLAG, &o.json, 0},       {"--quiet", CLI_ARG_FLAG, &o.quiet, 0},
      {"--checkpoint", CLI_ARG_STRING, &o.checkpoint, 0},
      {"--every-checkpoint", CLI_ARG_COUNT, &o.every_checkpoint, 0},
      {"--restart", CLI_ARG_STRING, &o.restart, 0}};
  const char *problem[1];
  size_t n_problem = 0;
  int status = cli_parse("run", argc, argv, options, sizeof options / sizeof options[0],
                         problem, 1, &n_problem);
  if (status == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (status != CLI_EXIT_OK) return status;
  if (n_problem == 0) {
    cli_error("run", "which problem? e.g. 'geomint run kepler' (see 'geomint list problems')");
    return CLI_EXIT_USAGE;
  }
  if ((status = check_options(&o, options, sizeof options / sizeof options[0])) != CLI_EXIT_OK)
    return status;
  o.every_given = seen(options, sizeof options / sizeof options[0], "--every");
  gm_scheme scheme;
  if ((status = cli_make_scheme("run", o.method, o.basic, o.solver, o.compensated, &scheme)) !=
      CLI_EXIT_OK)
    return status;
  gm_model *model = NULL;
  if ((status = cli_open_model("run", problem[0], &o.settings, &model)) != CLI_EXIT_OK)
    return status;

  char tmp_csv[] = "/tmp/geomint-plot-XXXXXX";
  int have_tmp = 0;
  if (o.plot != NULL) {
    if (!gm_problem_has_energy(gm_model_problem(model))) {
      cli_error("run", "--plot: %s is a first-order problem without an energy to plot",
                problem[0]);
      status = CLI_EXIT_USAGE;
    } else if (!cli_gnuplot_available()) {
      cli_error("run", "--plot: gnuplot is not installed (or not on PATH)");
      status = CLI_EXIT_FAILURE;
    } else if ((status = cli_plot_check_output("run", o.plot)) != CLI_EXIT_OK) {
      /* reported */
    } else if (o.out == NULL) {
      int fd = mkstemp(tmp_csv);
      if (fd < 0) {
        cli_error("run", "--plot: cannot create a temporary file in /tmp");
        status = CLI_EXIT_FAILURE;
      } else {
        close(fd);
        have_tmp = 1;
      }
    }
  }
  if (status == CLI_EXIT_OK)
    status = run_model(problem[0], model, &scheme, &o, have_tmp ? tmp_csv : NULL);
  if (have_tmp) remove(tmp_csv);
  gm_model_free(model);
  return status;
}

const cli_command cli_run_command = {"run", "integrate a problem with a method", usage,
                                     run_main};
