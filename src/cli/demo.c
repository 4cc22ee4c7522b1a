/* geomint demo: Kepler (e = 0.6) over 1000 orbits with euler, rk4 and verlet at one step. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"

static const char usage[] =
    "usage: geomint demo [--out DIR]\n\n"
    "Integrate the Kepler problem with eccentricity 0.6 over 1000 orbits (t = 0 .. 2000 pi)\n"
    "with euler, rk4 and verlet at the same step dt = 0.01 and compare their energy errors.\n"
    "Writes DIR/kepler-METHOD.csv (every 50th step) and DIR/kepler-energy-error.png, and\n"
    "prints a table of errors, drifts and costs.\n\n"
    "options:\n"
    "  --out DIR   output directory, created if missing (default demo-output)\n";

static const char *const demo_methods[] = {"euler", "rk4", "verlet"};
#define N_DEMO_METHODS (sizeof demo_methods / sizeof demo_methods[0])
#define DEMO_ECCENTRICITY 0.6
#define DEMO_ORBITS 1000
#define DEMO_DT 0.01
#define DEMO_CSV_EVERY 50

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
  printf("Kepler, e = %.1f, %d orbits (t_end = 2000 pi), dt = %g\n\n", DEMO_ECCENTRICITY,
         DEMO_ORBITS, DEMO_DT);
  printf("%-8s  %14s  %14s  %14s  %12s  %8s\n", "method", "max rel. dH", "final rel. dH",
         "drift of L", "force evals", "wall s");
  for (size_t i = 0; i < n; ++i) {
    const cli_sim_result *r = &rows[i].result;
    double drift = l != (size_t)-1 ? gm_monitor_max_invariant_drift(r->monitor, l) : NAN;
    printf("%-8s  %14.3e  %14.3e  %14.3e  %12zu  %8.3f\n", rows[i].method->name,
           gm_monitor_max_rel_energy_error(r->monitor),
           gm_monitor_last_rel_energy_error(r->monitor), drift, r->stats.force_evals,
           r->wall_s);
  }
}

static int run_demo(const char *dir, const gm_model *model, demo_row *rows) {
  int status = CLI_EXIT_OK;
  cli_plot_series series[N_DEMO_METHODS];
  for (size_t i = 0; i < N_DEMO_METHODS && status == CLI_EXIT_OK; ++i) {
    rows[i].method = cli_find_method("demo", demo_methods[i]);
    if (rows[i].method == NULL) return CLI_EXIT_FAILURE;
    snprintf(rows[i].csv, sizeof rows[i].csv, "%s/kepler-%s.csv", dir, demo_methods[i]);
    cli_sim_config c = {{rows[i].method, NULL, GM_SOLVER_DEFAULT, 0}, model, DEMO_DT,
                        DEMO_ORBITS * two_pi, 0, 1, DEMO_CSV_EVERY, rows[i].csv, 0, NULL, 0, NULL};
    status = cli_simulate("demo", &c, &rows[i].result);
    series[i] = (cli_plot_series){rows[i].csv, demo_methods[i], rows[i].result.energy_column};
  }
  if (status != CLI_EXIT_OK) return status;
  print_table(gm_model_problem(model), rows, N_DEMO_METHODS);
  char png[4096], title[128];
  snprintf(png, sizeof png, "%s/kepler-energy-error.png", dir);
  snprintf(title, sizeof title, "Kepler, e = %.1f, dt = %g: relative energy error",
           DEMO_ECCENTRICITY, DEMO_DT);
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

const cli_command cli_demo_command = {"demo", "compare euler, rk4 and verlet on Kepler orbits",
                                      usage, demo_main};
