/* geomint mimetic EXPERIMENT: the four numerical tests of seed 003 (Palha & Gerritsma, §6),
 * with MCI and MGI of degree 2, RK4, explicit and symplectic Euler: data, figures, a table. */
#include <cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "geomint/experiments.h"

static const char usage[] =
    "usage: geomint mimetic EXPERIMENT [--out DIR] [--no-plot] [--json]\n\n"
    "Reproduce a numerical test of seed 003 (Palha & Gerritsma, mimetic spectral elements for\n"
    "Hamiltonian systems, section 6) with mimetic-canonical-2 (MCI), mimetic-galerkin-2 (MGI),\n"
    "rk4, euler and symplectic-euler-a:\n"
    "  circular        harmonic oscillator from q = 2, p = 0, dt = 1, t = 0..100\n"
    "  lotka-volterra  u' = u(v - 2), v' = v(1 - u) from (3, 3), dt = 0.3, t = 0..60\n"
    "  pendulum        H = p^2/2 - 10 cos q from q = pi/2, dt = 0.4 (phase portrait) and\n"
    "                  dt = 0.1 (energy), t = 0..20\n"
    "  kepler          e = 0.6 from pericentre, dt = 0.1, t = 0..100\n"
    "  all             the four\n"
    "Writes DIR/EXP-METHOD-DT.csv (t, state, invariant error), DIR/EXP-convergence.csv, and\n"
    "draws DIR/EXP-phase.png, DIR/EXP-invariant.png and DIR/EXP-convergence.png with gnuplot;\n"
    "prints the largest invariant error of each method and the measured orders.\n\n"
    "options:\n"
    "  --out DIR   output directory, created if missing (default mimetic-output)\n"
    "  --no-plot   write the data only\n"
    "  --json      print one JSON object (one experiment, not 'all') instead of the table\n";

#define N_METHODS GM_MIMETIC_METHODS
#define N_CONVERGENCE GM_MIMETIC_CONVERGENCE
#define CONVERGENCE_LEVELS GM_MIMETIC_LEVELS
#define method_names gm_mimetic_experiment_methods
static const char *const method_titles[N_METHODS] = {"MCI (p=2)", "MGI (p=2)", "RK4",
                                                     "explicit Euler", "symplectic Euler"};
typedef gm_mimetic_info experiment;
static const char *const experiment_names[] = {"circular", "lotka-volterra", "pendulum", "kepler"};
#define N_EXPERIMENTS (sizeof experiment_names / sizeof experiment_names[0])

static int make_directory(const char *dir) {
  if (mkdir(dir, 0777) == 0 || errno == EEXIST) {
    struct stat sb;
    if (stat(dir, &sb) == 0 && S_ISDIR(sb.st_mode)) return CLI_EXIT_OK;
  }
  cli_error("mimetic", "cannot create the directory '%s': %s", dir, strerror(errno));
  return CLI_EXIT_FAILURE;
}

/* The three figures, by one gnuplot script written next to the data. */
static int draw(const char *dir, const experiment *ex, const char csv[][4096], const int *ran,
                const double *dts) {
  char script[4096];
  snprintf(script, sizeof script, "%s/%s.gp", dir, ex->name);
  FILE *g = fopen(script, "w");
  if (g == NULL) {
    cli_error("mimetic", "cannot write %s: %s", script, strerror(errno));
    return CLI_EXIT_FAILURE;
  }
  fprintf(g, "set terminal pngcairo size 900,640 font ',11'\nset datafile separator ','\n"
             "set key outside right top\nset grid\n");
  /* phase portrait */
  fprintf(g, "set output '%s/%s-phase.png'\n", dir, ex->name);
  fprintf(g, "set title 'seed 003, %s: phase portrait (dt = %g)'\n", ex->name, ex->dt_phase);
  /* the view: MCI's orbit with a margin (explicit Euler may run far away) */
  fprintf(g, "stats '%s' every ::1 using %zu:%zu nooutput\n", csv[0], ex->x + 2, ex->y + 2);
  fprintf(g, "mx = 0.5 * (STATS_max_x - STATS_min_x); my = 0.5 * (STATS_max_y - STATS_min_y)\n"
             "set xrange [STATS_min_x - mx : STATS_max_x + mx]\n"
             "set yrange [STATS_min_y - my : STATS_max_y + my]\n");
  fprintf(g, "set xlabel '%s'\nset ylabel '%s'\nset size ratio -1\nplot ", ex->xlabel,
          ex->ylabel);
  int first = 1;
  for (size_t k = 0; k < N_METHODS; ++k) {
    if (!ran[k]) continue;
    fprintf(g, "%s'%s' every ::1 using %zu:%zu with lines lw %s title '%s'", first ? "" : ", ",
            csv[k], ex->x + 2, ex->y + 2, k < 2 ? "2" : "1.3", method_titles[k]);
    first = 0;
  }
  fprintf(g, "\nset size noratio\nset autoscale xy\n");
  /* invariant error in time */
  fprintf(g, "set output '%s/%s-invariant.png'\n", dir, ex->name);
  fprintf(g, "set title 'seed 003, %s: invariant error (dt = %g)'\n", ex->name, ex->dt_invariant);
  fprintf(g, "set xlabel 't'\nset ylabel '%s'\nset logscale y\nset format y '10^{%%L}'\nplot ",
          ex->invariant_label);
  first = 1;
  for (size_t k = 0; k < N_METHODS; ++k) {
    if (!ran[N_METHODS + k]) continue;
    fprintf(g, "%s'%s' every ::1 using 1:($%zu > 1e-17 ? $%zu : 1e-17) with lines lw %s "
               "title '%s'",
            first ? "" : ", ", csv[N_METHODS + k], (size_t)ran[2 * N_METHODS] + 2,
            (size_t)ran[2 * N_METHODS] + 2, k < 2 ? "2" : "1.3", method_titles[k]);
    first = 0;
  }
  fprintf(g, "\n");
  /* convergence */
  fprintf(g, "set output '%s/%s-convergence.png'\n", dir, ex->name);
  fprintf(g, "set title 'seed 003, %s: convergence at t = %g'\nset logscale x\n", ex->name,
          ex->conv_t_end);
  fprintf(g, "set format x '10^{%%L}'\nset xlabel 'dt'\nset ylabel 'error'\nplot ");
  for (size_t k = 0; k < N_CONVERGENCE; ++k)
    fprintf(g, "%s'%s/%s-convergence.csv' every ::1 using 1:($%zu > 0 ? $%zu : 1/0) with "
               "linespoints lw 2 title '%s state', "
               "'%s/%s-convergence.csv' every ::1 using 1:($%zu > 0 ? $%zu : 1e-17) with "
               "linespoints dt 2 title '%s invariant'",
            k ? ", " : "", dir, ex->name, 2 * k + 2, 2 * k + 2, method_titles[k], dir, ex->name,
            2 * k + 3, 2 * k + 3, method_titles[k]);
  fprintf(g, ", %g * (x / %g)**4 with lines lc rgb 'gray' dt 3 title 'slope 4'\n",
          1e-3, dts[0]);
  fclose(g);
  char cmd[4200];
  snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", script);
  if (system(cmd) != 0) {
    cli_error("mimetic", "gnuplot failed on %s", script);
    return CLI_EXIT_FAILURE;
  }
  return CLI_EXIT_OK;
}

static int mimetic_json(const gm_mimetic_result *r) {
  cJSON *j = cJSON_CreateObject();
  cJSON_AddStringToObject(j, "experiment", r->info->name);
  cJSON_AddStringToObject(j, "model", r->info->model);
  cJSON *runs = cJSON_AddArrayToObject(j, "runs");
  for (size_t i = 0; i < r->n_runs; ++i) {
    const gm_mimetic_run *u = &r->runs[i];
    cJSON *x = cJSON_CreateObject();
    cJSON_AddStringToObject(x, "method", u->method);
    cJSON_AddNumberToObject(x, "dt", u->dt);
    cJSON_AddNumberToObject(x, "steps", (double)llround(r->info->t_end / u->dt));
    cJSON_AddStringToObject(x, "status", u->status == 0 ? "ok" : u->status > 0 ? "stopped"
                                                                              : "not applicable");
    if (u->status != 0) cJSON_AddStringToObject(x, "why", u->why);
    cJSON_AddItemToObject(x, "max_abs_invariant_error",
                          u->status >= 0 ? cli_json_number(u->max_invariant_error) : cJSON_CreateNull());
    if (u->csv[0] != '\0') cJSON_AddStringToObject(x, "csv", u->csv);
    cJSON_AddItemToArray(runs, x);
  }
  cJSON *conv = cJSON_AddObjectToObject(j, "convergence");
  cJSON_AddNumberToObject(conv, "t_end", r->info->conv_t_end);
  cJSON_AddItemToObject(conv, "dt", cli_json_numbers(r->dts, CONVERGENCE_LEVELS));
  for (size_t k = 0; k < N_CONVERGENCE; ++k) {
    cJSON *m = cJSON_AddObjectToObject(conv, method_names[k]);
    cJSON_AddItemToObject(m, "state_error", cli_json_numbers(r->state_error[k], CONVERGENCE_LEVELS));
    cJSON_AddItemToObject(m, "max_abs_invariant_error",
                          cli_json_numbers(r->invariant_error[k], CONVERGENCE_LEVELS));
    cJSON_AddItemToObject(m, "order", cli_json_number(r->order[k]));
    cJSON_AddItemToObject(m, "invariant_order", cli_json_number(r->invariant_order[k]));
    cJSON_AddBoolToObject(m, "invariant_at_round_off", r->invariant_kept[k]);
  }
  cJSON_AddNumberToObject(j, "wall_s", r->wall_s);
  return cli_json_print(j);
}

/* src/experiments/mimetic.c computes; here the table (or --json) and the figures */
static int run_experiment(const char *name, const char *dir, int plot, int json) {
  static gm_mimetic_result r;
  gm_error err = {{0}};
  const gm_status st = gm_experiment_mimetic(name, dir, &r, &err);
  const experiment *ex = r.info;
  if (ex == NULL) {
    cli_error("mimetic", "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  if (json) {
    if (st != GM_OK) {
      cli_error("mimetic", "%s", err.message);
      return CLI_EXIT_FAILURE;
    }
    const int rc = mimetic_json(&r);
    if (rc != CLI_EXIT_OK) return rc;
  } else {
    printf("%s (seed 003 section 6): %s%s%s\n", ex->name, ex->model, ex->setting ? ", " : "",
           ex->setting ? ex->setting : "");
    printf("  %-20s %8s %16s   %s\n", "method", "dt", "max |dI|", "note");
    for (size_t i = 0; i < r.n_runs; ++i) {
      const gm_mimetic_run *u = &r.runs[i];
      if (u->status < 0)
        printf("  %-20s %8g %16s   not applicable: %s\n", u->method, u->dt, "-", u->why);
      else
        printf("  %-20s %8g %16.3e   %s\n", u->method, u->dt, u->max_invariant_error, u->why);
    }
    if (st != GM_OK) {
      cli_error("mimetic", "%s", err.message);
      return CLI_EXIT_FAILURE;
    }
    printf("  convergence to t = %g, dt = %g .. %g: measured orders (state, invariant)\n",
           ex->conv_t_end, r.dts[0], r.dts[CONVERGENCE_LEVELS - 1]);
    for (size_t k = 0; k < N_CONVERGENCE; ++k) {
      /* an invariant kept to round-off at every step has no order to fit */
      char inv[32], state[32];
      if (isfinite(r.invariant_order[k]))
        snprintf(inv, sizeof inv, "%8.2f", r.invariant_order[k]);
      else
        snprintf(inv, sizeof inv, "%s", r.invariant_kept[k] ? "round-off" : "   failed");
      if (isfinite(r.order[k]))
        snprintf(state, sizeof state, "%8.2f", r.order[k]);
      else
        snprintf(state, sizeof state, "%s", "   failed");
      printf("  %-20s %s %s\n", method_names[k], state, inv);
    }
  }
  if (!plot) return CLI_EXIT_OK;
  /* the figures' inputs: the phase runs, the invariant runs (the same when one step serves) */
  static char csv[2 * N_METHODS][4096];
  int ran[2 * N_METHODS + 1] = {0};
  ran[2 * N_METHODS] = (int)r.state_size; /* the CSV column of the error */
  for (size_t i = 0; i < r.n_runs; ++i) {
    snprintf(csv[i], sizeof csv[i], "%s", r.runs[i].csv);
    ran[i] = r.runs[i].status >= 0;
  }
  if (r.n_runs == N_METHODS)
    for (size_t k = 0; k < N_METHODS; ++k) {
      memcpy(csv[N_METHODS + k], csv[k], sizeof csv[k]);
      ran[N_METHODS + k] = ran[k];
    }
  int rc = draw(dir, ex, (const char(*)[4096])csv, ran, r.dts);
  if (rc == CLI_EXIT_OK && !json)
    printf("  figures: %s/%s-{phase,invariant,convergence}.png\n", dir, ex->name);
  return rc;
}

static int mimetic_main(int argc, char **argv) {
  const char *out = "mimetic-output", *positional[1] = {NULL};
  int no_plot = 0, json = 0;
  size_t n_positional = 0;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &out, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0}};
  int rc = cli_parse("mimetic", argc, argv, options, 3, positional, 1, &n_positional);
  if (rc == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  if (n_positional != 1) {
    cli_error("mimetic", "which experiment? circular, lotka-volterra, pendulum, kepler or all");
    return CLI_EXIT_USAGE;
  }
  const int all = strcmp(positional[0], "all") == 0;
  size_t chosen = N_EXPERIMENTS;
  for (size_t k = 0; k < N_EXPERIMENTS; ++k)
    if (strcmp(positional[0], experiment_names[k]) == 0) chosen = k;
  if (!all && chosen == N_EXPERIMENTS) {
    cli_error("mimetic", "unknown experiment '%s': circular, lotka-volterra, pendulum, kepler "
              "or all", positional[0]);
    return CLI_EXIT_USAGE;
  }
  if (json && all) {
    cli_error("mimetic", "--json prints one experiment's object: name one, not 'all'");
    return CLI_EXIT_USAGE;
  }
  if (strchr(out, '\'') != NULL) {
    cli_error("mimetic", "--out: the directory name may not contain a quote");
    return CLI_EXIT_USAGE;
  }
  if (!no_plot && !cli_gnuplot_available()) {
    cli_error("mimetic", "gnuplot is not installed (or not on PATH): use --no-plot for data only");
    return CLI_EXIT_FAILURE;
  }
  if ((rc = make_directory(out)) != CLI_EXIT_OK) return rc;
  for (size_t k = 0; k < N_EXPERIMENTS && rc == CLI_EXIT_OK; ++k)
    if (all || k == chosen) rc = run_experiment(experiment_names[k], out, !no_plot, json);
  return rc;
}

const cli_command cli_mimetic_command = {
    "mimetic", "seed 003's tests: MCI, MGI, RK4, Euler on four problems, with figures", usage,
    mimetic_main};
