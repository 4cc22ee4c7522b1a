/* geomint demo: Kepler (e = 0.6) over 1000 orbits with euler, verlet, rk4 and yoshida-4 at
 * equal cost: the same number of force evaluations per unit time. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"

static const char usage[] =
    "usage: geomint demo [--out DIR]\n\n"
    "Integrate the Kepler problem with eccentricity 0.6 over 1000 orbits (t = 0 .. 2000 pi)\n"
    "at equal cost, one force evaluation per 0.005 time units: euler and verlet at dt = 0.005,\n"
    "rk4 (4 evaluations a step) at dt = 0.02, the 4th-order symplectic composition yoshida-4\n"
    "(3 a step) at dt = 0.015, and compare their energy errors. Writes DIR/kepler-METHOD.csv\n"
    "(every 0.3 time units) and DIR/kepler-energy-error.png, and prints a table of errors,\n"
    "drifts and costs, and when rk4's growing error passes the bounded ones.\n\n"
    "options:\n"
    "  --out DIR   output directory, created if missing (default demo-output)\n";

/* Equal cost: the step of each method is DEMO_DT times its force evaluations per step (verlet
 * and yoshida-4 reuse the last force of a step: FSAL), so every method makes one evaluation per
 * DEMO_DT of time. */
static const struct {
  const char *name;
  unsigned forces_per_step;
} demo_methods[] = {{"euler", 1}, {"verlet", 1}, {"rk4", 4}, {"yoshida-4", 3}};
#define N_DEMO_METHODS (sizeof demo_methods / sizeof demo_methods[0])
#define DEMO_ECCENTRICITY 0.6
#define DEMO_ORBITS 1000
#define DEMO_DT 0.005
#define DEMO_CSV_EVERY 60 /* rows every 60 DEMO_DT of time, for every method */

static const double two_pi = 6.283185307179586476925286766559;

static int make_directory(const char *dir) {
  if (mkdir(dir, 0777) == 0 || errno == EEXIST) {
    struct stat sb;
    if (stat(dir, &sb) == 0 && S_ISDIR(sb.st_mode)) return CLI_EXIT_OK;
  }
  cli_error("demo", "cannot create the directory '%s': %s", dir, strerror(errno));
  return CLI_EXIT_FAILURE;
}

/* Kepler with eccentricity 0.6, whatever the library calls that parameter. */
static int open_kepler(gm_model **model) {
  static const char *const names[] = {"e", "eccentricity"};
  const gm_model_info *info = gm_model_info_find("kepler");
  const char *param = NULL;
  for (size_t k = 0; info != NULL && k < info->n_params; ++k)
    for (size_t j = 0; j < 2; ++j)
      if (strcmp(info->params[k].name, names[j]) == 0) param = names[j];
  if (param == NULL) {
    cli_error("demo", "the problem library has no 'kepler' problem with an eccentricity");
    return CLI_EXIT_FAILURE;
  }
  char item[64];
  snprintf(item, sizeof item, "%s=%.17g", param, DEMO_ECCENTRICITY);
  cli_settings s = {1, {item}};
  return cli_open_model("demo", "kepler", &s, model);
}

typedef struct demo_row {
  const gm_method *method;
  char csv[4096];
  cli_sim_result result;
} demo_row;

static void print_table(const gm_problem *pb, const demo_row *rows, size_t n) {
  size_t l = cli_find_invariant(pb, "angular");
  printf("Kepler, e = %.1f, %d orbits (t_end = 2000 pi), equal cost: one force evaluation per "
         "%g time units\n\n", DEMO_ECCENTRICITY, DEMO_ORBITS, DEMO_DT);
  printf("%-10s  %7s  %14s  %14s  %14s  %12s  %8s\n", "method", "dt", "max rel. dH",
         "final rel. dH", "drift of L", "force evals", "wall s");
  for (size_t i = 0; i < n; ++i) {
    const cli_sim_result *r = &rows[i].result;
    double drift = l != (size_t)-1 ? gm_monitor_max_invariant_drift(r->monitor, l) : NAN;
    printf("%-10s  %7g  %14.3e  %14.3e  %14.3e  %12zu  %8.3f\n", rows[i].method->name,
           DEMO_DT * demo_methods[i].forces_per_step,
           gm_monitor_max_rel_energy_error(r->monitor),
           gm_monitor_last_rel_energy_error(r->monitor), drift, r->stats.force_evals,
           r->wall_s);
  }
}

/* The first time in the CSV at which the column exceeds level; NaN if never. */
static double first_time_above(const char *csv, size_t column, double level) {
  FILE *f = fopen(csv, "r");
  if (f == NULL) return NAN;
  char line[4096];
  double found = NAN;
  if (fgets(line, sizeof line, f) != NULL) /* header */
    while (isnan(found) && fgets(line, sizeof line, f) != NULL) {
      char *p = line;
      double t = strtod(p, &p), x = NAN;
      for (size_t c = 1; c <= column && *p == ','; ++c) x = strtod(p + 1, &p);
      if (x > level) found = t;
    }
  fclose(f);
  return found;
}

static int run_demo(const char *dir, const gm_model *model, demo_row *rows) {
  int status = CLI_EXIT_OK;
  cli_plot_series series[N_DEMO_METHODS];
  for (size_t i = 0; i < N_DEMO_METHODS && status == CLI_EXIT_OK; ++i) {
    const unsigned k = demo_methods[i].forces_per_step;
    rows[i].method = cli_find_method("demo", demo_methods[i].name);
    if (rows[i].method == NULL) return CLI_EXIT_FAILURE;
    snprintf(rows[i].csv, sizeof rows[i].csv, "%s/kepler-%s.csv", dir, demo_methods[i].name);
    cli_sim_config c = {{rows[i].method, NULL, GM_SOLVER_DEFAULT, 0}, model, DEMO_DT * k,
                        DEMO_ORBITS * two_pi, 0, 1, DEMO_CSV_EVERY / k, rows[i].csv, 0, NULL, 0,
                        NULL};
    status = cli_simulate("demo", &c, &rows[i].result);
    series[i] = (cli_plot_series){rows[i].csv, demo_methods[i].name,
                                  rows[i].result.energy_column};
  }
  if (status != CLI_EXIT_OK) return status;
  print_table(gm_model_problem(model), rows, N_DEMO_METHODS);
  /* where rk4's growing error passes the largest error of each symplectic method */
  const demo_row *rk4 = &rows[2];
  double orbits[2] = {NAN, NAN};
  for (size_t j = 0; j < 2; ++j) {
    const demo_row *sym = &rows[j == 0 ? 1 : 3];
    double t = first_time_above(rk4->csv, rk4->result.energy_column,
                                gm_monitor_max_rel_energy_error(sym->result.monitor));
    orbits[j] = t / two_pi;
    if (isnan(t))
      printf("\nrk4's energy error stays below the largest of %s over the %d orbits\n",
             sym->method->name, DEMO_ORBITS);
    else
      printf("%srk4's energy error passes the largest of %s (%.2e) after %.0f orbits\n",
             j == 0 ? "\n" : "", sym->method->name,
             gm_monitor_max_rel_energy_error(sym->result.monitor), orbits[j]);
  }
  char png[4096], title[256];
  snprintf(png, sizeof png, "%s/kepler-energy-error.png", dir);
  if (!isnan(orbits[0]))
    snprintf(title, sizeof title, "Kepler e = %.1f at equal cost (1 force per %g time units): "
             "rk4's energy error grows and passes verlet's bounded error after %.0f orbits",
             DEMO_ECCENTRICITY, DEMO_DT, orbits[0]);
  else
    snprintf(title, sizeof title, "Kepler e = %.1f at equal cost (1 force per %g time units): "
             "relative energy error", DEMO_ECCENTRICITY, DEMO_DT);
  status = cli_plot_energy_error("demo", png, title, series, N_DEMO_METHODS);
  if (status != CLI_EXIT_OK) return status;
  printf("\nwrote");
  for (size_t i = 0; i < N_DEMO_METHODS; ++i) printf(" %s", rows[i].csv);
  printf(" %s\n", png);
  return CLI_EXIT_OK;
}

static int demo_main(int argc, char **argv) {
  const char *dir = "demo-output";
  cli_option options[] = {{"--out", CLI_ARG_STRING, &dir, 0}};
  const char *none[1];
  size_t n_none = 0;
  int status = cli_parse("demo", argc, argv, options, 1, none, 0, &n_none);
  if (status == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (status != CLI_EXIT_OK) return status;
  if (strlen(dir) > 3000) {
    cli_error("demo", "--out: directory name too long");
    return CLI_EXIT_USAGE;
  }
  if ((status = make_directory(dir)) != CLI_EXIT_OK) return status;
  gm_model *model = NULL;
  if ((status = open_kepler(&model)) != CLI_EXIT_OK) return status;
  demo_row rows[N_DEMO_METHODS];
  memset(rows, 0, sizeof rows);
  status = run_demo(dir, model, rows);
  for (size_t i = 0; i < N_DEMO_METHODS; ++i) cli_sim_result_clear(&rows[i].result);
  gm_model_free(model);
  return status;
}

const cli_command cli_demo_command = {"demo",
                                      "euler, verlet, rk4 and yoshida-4 on Kepler at equal cost",
                                      usage, demo_main};
