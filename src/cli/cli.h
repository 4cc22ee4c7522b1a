/* Private declarations of the geomint program; each concern lives in its own file. */
#ifndef GM_CLI_H
#define GM_CLI_H

#include <stddef.h>
#include <stdio.h>

#include "geomint/geomint.h"

/* Exit statuses: success, a failure while running, bad input. */
#define CLI_EXIT_OK 0
#define CLI_EXIT_FAILURE 1
#define CLI_EXIT_USAGE 2
#define CLI_HELP (-1) /* the parser saw --help: print the command's usage, exit 0 */

/* ---- commands (list.c, run.c, order.c, demo.c, wp.c) -------------------------------------- */
typedef struct cli_command {
  const char *name;
  const char *summary;
  const char *usage;
  int (*main)(int argc, char **argv); /* argv[0] is the first argument after the name */
} cli_command;

extern const cli_command cli_list_command, cli_run_command, cli_order_command,
    cli_demo_command, cli_wp_command, cli_mesh_command, cli_mimetic_command;
extern const cli_command cli_oscillatory_command;
extern const cli_command cli_maxwell_command; /* maxwell.c */
extern const cli_command cli_routh_command;   /* reduction.c, alias of reduction */
extern const cli_command cli_reduction_command; /* reduction.c */
extern const cli_command cli_pde_command;
extern const cli_command cli_experiments_command; /* experiments.c */
/* The command named name (main.c), NULL if none. */
const cli_command *cli_find_command(const char *name);
extern const cli_command cli_fluid_command; /* fluid.c */

/* "geomint COMMAND: message" on stderr, one line. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void cli_error(const char *command, const char *fmt, ...);

/* ---- options (args.c) ------------------------------------------------------------------- */
#define CLI_MAX_SETTINGS 64
typedef struct cli_settings {
  size_t n;
  const char *items[CLI_MAX_SETTINGS]; /* "name=value", borrowed from argv; name and value
                                          non-empty, the value a number or a text */
} cli_settings;

typedef enum cli_arg_type {
  CLI_ARG_FLAG,     /* int: set to 1 */
  CLI_ARG_STRING,   /* const char * */
  CLI_ARG_DOUBLE,   /* double: any number, checked by the command */
  CLI_ARG_COUNT,    /* size_t: a non-negative integer */
  CLI_ARG_SETTING,  /* cli_settings: name=value, repeatable */
  CLI_ARG_LIST      /* cli_settings: any non-empty text, repeatable, in the order given */
} cli_arg_type;

typedef struct cli_option {
  const char *name; /* "--dt" */
  cli_arg_type type;
  void *target;
  int seen;         /* set by the parser */
} cli_option;

/* Parse argv into options (accepting "--name value" and "--name=value") and positional
 * arguments (at most max_positional). Returns CLI_EXIT_OK, CLI_HELP, or CLI_EXIT_USAGE after
 * printing why. */
int cli_parse(const char *command, int argc, char **argv, cli_option *options,
              size_t n_options, const char **positional, size_t max_positional,
              size_t *n_positional);
/* Split a checked "name=value" setting: name is written to buf (capacity cap); returns the
 * value's text (borrowed from item). */
const char *cli_setting_split(const char *item, char *name, size_t cap);
/* Check a step size or time given on the command line: finite and > 0. */
int cli_check_positive(const char *command, const char *option, double value);
/* Check that an interval of length `span` in steps of `dt` is at most 1e15 steps (what the
 * integrator accepts); prints the error (exit status 2) otherwise. */
int cli_check_step_count(const char *command, double span, double dt);

/* ---- suggestions (suggest.c) ------------------------------------------------------------ */
/* The i-th candidate name, NULL past the end. */
typedef gm_name_at cli_name_at;
const char *cli_method_name_at(const void *ctx, size_t i);
const char *cli_problem_name_at(const void *ctx, size_t i);
/* "unknown KIND 'query'; did you mean: a, b?" or a hint where to look, on stderr. */
void cli_unknown(const char *command, const char *kind, const char *query, cli_name_at name_at,
                 const void *ctx, const char *hint);

/* ---- problems and methods by name (setup.c) -------------------------------------------- */
/* NULL after printing an error with suggestions. */
const gm_method *cli_find_method(const char *command, const char *name);
/* Resolve --method, --basic (may be NULL) and --solver (may be NULL) into a scheme; prints the
 * error and returns CLI_EXIT_USAGE for unknown names. */
int cli_make_scheme(const char *command, const char *method, const char *basic,
                    const char *solver, int compensated, gm_scheme *out);
/* "verlet", or "yoshida-6 of midpoint" for a composition with another basic method. */
void cli_scheme_name(const gm_scheme *scheme, char *buf, size_t cap);
/* Create, set and build a model; returns an exit status (message printed on failure). */
int cli_open_model(const char *command, const char *name, const cli_settings *settings,
                   gm_model **out);
/* Index of the invariant whose name contains `part`, or (size_t)-1. */
size_t cli_find_invariant(const gm_problem *problem, const char *part);

/* ---- one integration (simulate.c) ------------------------------------------------------- */
typedef struct cli_sim_config {
  gm_scheme scheme;       /* method, basic method, solver, compensated summation */
  const gm_model *model;
  double dt;
  double t_end;           /* used when n_steps == 0: integrate to exactly t_end */
  size_t n_steps;         /* > 0: that many steps of dt */
  size_t monitor_every;
  size_t csv_every;
  const char *csv_path;   /* NULL: no CSV */
  int quiet;              /* no progress line even on a terminal */
  const char *checkpoint_path; /* NULL: no checkpoints */
  size_t checkpoint_every;     /* steps between checkpoints (also one when interrupted) */
  const char *restart_path;    /* NULL: start from the initial state */
} cli_sim_config;

typedef struct cli_sim_result {
  gm_stats stats;
  double wall_s;
  double t0, t_final;
  size_t n_state;
  double *y_final;        /* owned */
  gm_monitor *monitor;    /* owned */
  size_t csv_rows;
  size_t energy_column;   /* 0-based CSV column of rel_energy_error, (size_t)-1 if none */
  int ran;                /* the integration started: stats and the monitor are the run's */
  int chooses_steps;      /* vi-sem-*: its own steps; the fields below are set */
  double discrete_energy; /* E of the run (set by the first step) */
  double max_rel_discrete_energy_error; /* max |E_d − E| / |E| over the steps */
  size_t energy_fallbacks;
  size_t energy_unresolved; /* steps whose size the energy equation did not resolve (kept) */
  int restarted;          /* from restart_path, at restart_step / restart_t */
  size_t restart_step;
  double restart_t;
  size_t checkpoints;     /* checkpoints written */
  char error[GM_ERRMSG_SIZE + 128]; /* why it failed ("" on success) */
} cli_sim_result;

/* Run one integration; returns an exit status, printing the reason on failure (also kept in
 * result->error). The CSV is closed (and kept, ending with a whole row) in every case. SIGINT
 * stops the run at the next observation: CLI_EXIT_INTERRUPTED. */
int cli_simulate(const char *command, const cli_sim_config *config, cli_sim_result *result);
void cli_sim_result_clear(cli_sim_result *result);

/* ---- long runs: progress and SIGINT (progress.c) ---------------------------------------- */
#include <signal.h>
/* Set by SIGINT while cli_interrupt_install is in effect; runs stop at the next observation. */
extern volatile sig_atomic_t cli_interrupted;
void cli_interrupt_install(void);
void cli_interrupt_restore(void);
/* Exit status of a run stopped by SIGINT. */
#define CLI_EXIT_INTERRUPTED 130
/* The monitor's state saved in a checkpoint: at most this many doubles. */
#define CLI_MAX_MONITOR_STATE 256
/* Steps between checks of the interrupt flag and progress updates during a run. */
#define CLI_PROGRESS_EVERY 16

typedef struct cli_progress {
  const char *command;
  int enabled;         /* stderr is a terminal and not --quiet */
  double start, last_print;
  int announced, long_run, printed;
  double total_steps;  /* for cli_progress_observe: steps of this session */
  double step_offset;  /* steps done before it (a restarted run) */
} cli_progress;

void cli_progress_start(cli_progress *progress, const char *command, int quiet);
/* Report `done` of `total` steps; returns 1 when the run should stop (SIGINT). */
int cli_progress_update(cli_progress *progress, double done, double total);
/* An observer (ctx: a cli_progress with total_steps set). */
int cli_progress_observe(void *ctx, size_t step, double t, const double *y);
/* End the progress line (if one was drawn). */
void cli_progress_end(cli_progress *progress);

/* ---- JSON (json.c) ---------------------------------------------------------------------- */
struct cJSON;
/* A number, or null when x is NaN or infinite. */
struct cJSON *cli_json_number(double x);
struct cJSON *cli_json_numbers(const double *x, size_t n);
/* Print root and a newline on stdout, then free root. Returns an exit status. */
int cli_json_print(struct cJSON *root);

/* ---- plots (plot.c) --------------------------------------------------------------------- */
typedef struct cli_plot_series {
  const char *csv_path;
  const char *title;
  size_t column; /* 0-based column of the relative energy error */
} cli_plot_series;

/* Is a gnuplot program on PATH? */
int cli_gnuplot_available(void);
/* An output folder for data and gnuplot scripts: refuses a name with a quote (the scripts
 * quote it) and, unless no_plot, a machine without gnuplot; creates dir (its parent must
 * exist). Prints the error; returns an exit status. */
int cli_prepare_plot_dir(const char *cmd, const char *dir, int no_plot);
/* Can png_path be written (its directory exists and is writable)? Prints why not. */
int cli_plot_check_output(const char *command, const char *png_path);
/* Draw the relative energy errors of the series against time (log y) into png_path.
 * Returns an exit status; prints the reason on failure. */
int cli_plot_energy_error(const char *command, const char *png_path, const char *title,
                          const cli_plot_series *series, size_t n_series);

/* One line of points (x[i], y[i]), i < n; both arrays borrowed. */
typedef struct cli_xy_series {
  const char *title;
  size_t n;
  const double *x, *y;
} cli_xy_series;

/* Draw the series as lines with points on log-log axes into png_path (title and labels are
 * plain text); points that are not positive and finite are left out. Returns an exit status;
 * prints the reason on failure. */
int cli_plot_loglog(const char *command, const char *png_path, const char *title,
                    const char *xlabel, const char *ylabel, const cli_xy_series *series,
                    size_t n_series);

/* A plot of the caller's own: gnuplot gets the PNG terminal, png_path and the title, then
 * whatever body(g, ctx) writes (settings, the plot command, inline data). Returns an exit
 * status; prints the reason on failure. */
typedef void (*cli_plot_body)(FILE *g, const void *ctx);
int cli_plot_custom(const char *command, const char *png_path, const char *title,
                    cli_plot_body body, const void *ctx);

#endif
