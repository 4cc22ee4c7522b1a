/* geomint demo: both halves of geomint in a few seconds. Mechanics: Kepler (e = 0.6) over 1000
 * orbits with euler, verlet, rk4 and yoshida-4 at equal cost (the same number of force
 * evaluations per unit time). Fields: a Yee scene (a pulse scattering off a dielectric disk,
 * `maxwell run` with its field picture) and a structure-preserving result on a triangle mesh
 * (`maxwell mesh`: the leapfrog energy and Gauss's law kept to round-off while the plain energy
 * oscillates). DIR/README.md says in one line what each picture shows. */
#include <cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <fcntl.h>

#include "cli/cli.h"

static const char usage[] =
    "usage: geomint demo [--out DIR] [--json]\n\n"
    "Mechanics: integrate the Kepler problem with eccentricity 0.6 over 1000 orbits (t = 0 .. 2000 pi)\n"
    "at equal cost, one force evaluation per 0.005 time units: euler and verlet at dt = 0.005,\n"
    "rk4 (4 evaluations a step) at dt = 0.02, the 4th-order symplectic composition yoshida-4\n"
    "(3 a step) at dt = 0.015, and compare their energy errors. Writes DIR/kepler-METHOD.csv\n"
    "(every 0.3 time units) and DIR/kepler-energy-error.png, and prints a table of errors,\n"
    "drifts and costs, and when rk4's growing error passes the bounded ones.\n"
    "Fields: the Yee scene of examples/maxwell_scene.json (a Gaussian pulse scattering off a\n"
    "dielectric disk, CPML walls) with 'maxwell run', writing DIR/yee/ and DIR/yee-field.png;\n"
    "then 'maxwell mesh --rect 12' (a PEC cavity on triangles, random E, leapfrog to t = 8),\n"
    "writing DIR/mesh-energy.csv and DIR/mesh-energy.png. DIR/README.md lists the pictures.\n\n"
    "options:\n"
    "  --out DIR   output directory, created if missing (default demo-output)\n"
    "  --json      print one JSON object (the Kepler table, the files) instead of the text\n";

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

static int run_demo(const char *dir, const gm_model *model, demo_row *rows, int json,
                    double orbits[2], char *png, size_t png_cap) {
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
  if (!json) print_table(gm_model_problem(model), rows, N_DEMO_METHODS);
  /* where rk4's growing error passes the largest error of each symplectic method */
  const demo_row *rk4 = &rows[2];
  for (size_t j = 0; j < 2; ++j) {
    const demo_row *sym = &rows[j == 0 ? 1 : 3];
    double t = first_time_above(rk4->csv, rk4->result.energy_column,
                                gm_monitor_max_rel_energy_error(sym->result.monitor));
    orbits[j] = t / two_pi;
    if (json) continue;
    if (isnan(t))
      printf("\nrk4's energy error stays below the largest of %s over the %d orbits\n",
             sym->method->name, DEMO_ORBITS);
    else
      printf("%srk4's energy error passes the largest of %s (%.2e) after %.0f orbit%s\n",
             j == 0 ? "\n" : "", sym->method->name,
             gm_monitor_max_rel_energy_error(sym->result.monitor), orbits[j],
             round(orbits[j]) == 1.0 ? "" : "s");
  }
  char title[256];
  snprintf(png, png_cap, "%s/kepler-energy-error.png", dir);
  if (!isnan(orbits[0]))
    snprintf(title, sizeof title, "Kepler e = %.1f at equal cost (1 force per %g time units): "
             "rk4's energy error grows and passes verlet's bounded error after %.0f orbits",
             DEMO_ECCENTRICITY, DEMO_DT, orbits[0]);
  else
    snprintf(title, sizeof title, "Kepler e = %.1f at equal cost (1 force per %g time units): "
             "relative energy error", DEMO_ECCENTRICITY, DEMO_DT);
  status = cli_plot_energy_error("demo", png, title, series, N_DEMO_METHODS);
  if (status != CLI_EXIT_OK || json) return status;
  printf("\nwrote");
  for (size_t i = 0; i < N_DEMO_METHODS; ++i) printf(" %s", rows[i].csv);
  printf(" %s\n", png);
  return CLI_EXIT_OK;
}

/* The scene of examples/maxwell_scene.json without snapshots (the demo draws one picture). */
static const char yee_scene[] =
    "{\n"
    "  \"description\": \"geomint demo: examples/maxwell_scene.json without snapshots\",\n"
    "  \"grid\": {\"dim\": \"2d-tm\", \"cells\": [160, 120], \"size\": [4.0, 3.0], "
    "\"origin\": [0, 0]},\n"
    "  \"background\": {\"epsilon\": 1.0},\n"
    "  \"materials\": [\n"
    "    {\"shape\": \"cylinder\", \"center\": [2.4, 1.5], \"axis\": [0, 0, 1], \"radius\": "
    "0.45, \"epsilon\": 4.0},\n"
    "    {\"shape\": \"box\", \"lo\": [3.0, 0.4], \"hi\": [3.3, 0.9], \"epsilon\": 2.0, "
    "\"sigma\": 0.5}\n"
    "  ],\n"
    "  \"boundaries\": {\"x\": \"cpml\", \"y\": \"cpml\"},\n"
    "  \"pml\": {\"thickness\": 12, \"grading\": 3, \"kappa_max\": 1, \"alpha_max\": 0.05},\n"
    "  \"sources\": [\n"
    "    {\"type\": \"point\", \"component\": \"Ez\", \"position\": [1.0, 1.5], \"mode\": "
    "\"soft\",\n"
    "     \"waveform\": {\"kind\": \"gaussian\", \"frequency\": 1.0, \"width\": 0.5, "
    "\"delay\": 2.5}}\n"
    "  ],\n"
    "  \"probes\": [{\"name\": \"behind_disk\", \"component\": \"Ez\", \"position\": "
    "[3.1, 1.5]}],\n"
    "  \"output\": {\"energy_every\": 10},\n"
    "  \"run\": {\"time\": 16.0, \"courant\": 0.99}\n"
    "}\n";

/* Run `geomint WORDS...` (a command of this program) and return its exit status. */
static int run_command(char **argv, int argc) {
  const cli_command *c = cli_find_command(argv[0]);
  if (c == NULL) {
    cli_error("demo", "no command '%s' (a bug)", argv[0]);
    return CLI_EXIT_FAILURE;
  }
  fflush(stdout);
  return c->main(argc - 1, argv + 1);
}

/* With --json the field commands' own text is not the demo's output: stdout goes to /dev/null
 * while they run (saved: the descriptor to restore, -1 when nothing was redirected). */
static int quiet_begin(int json) {
  if (!json) return -1;
  fflush(stdout);
  const int saved = dup(STDOUT_FILENO), null = open("/dev/null", O_WRONLY);
  if (saved < 0 || null < 0 || dup2(null, STDOUT_FILENO) < 0) {
    if (null >= 0) close(null);
    if (saved >= 0) close(saved);
    return -1;
  }
  close(null);
  return saved;
}

static void quiet_end(int saved) {
  if (saved < 0) return;
  fflush(stdout);
  dup2(saved, STDOUT_FILENO);
  close(saved);
}

static int write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  int bad = f == NULL;
  if (f != NULL) {
    fputs(text, f);
    bad = ferror(f) != 0;
    bad |= fclose(f) != 0;
  }
  if (bad) cli_error("demo", "cannot write %s: %s", path, strerror(errno));
  return bad ? CLI_EXIT_FAILURE : CLI_EXIT_OK;
}

static void mesh_energy_plot(FILE *g, const void *ctx) {
  const char *csv = ctx;
  /* E0: the plain energy of the first row (t = 0, where it equals the leapfrog one) */
  fprintf(g, "set datafile separator ','\nstats '%s' every ::1::1 using 4 nooutput\n"
             "E0 = STATS_min\nset grid\nset key bottom right\nset xlabel 't'\n"
             "set ylabel 'energy / initial energy'\nset yrange [0:2.2]\n"
             "plot '%s' every ::1 using 1:($4/E0) with lines lw 1.5 title 'plain energy (E and B "
             "half a step apart): oscillates', '' every ::1 using 1:($5/E0) with lines lw 2.5 "
             "title 'leapfrog energy: conserved'\n",
          csv, csv);
}

/* run a field command; with json its own text goes to /dev/null */
static int run_quiet(char **argv, int argc, int json) {
  const int saved = quiet_begin(json);
  const int status = run_command(argv, argc);
  quiet_end(saved);
  return status;
}

static int run_fields(const char *dir, int json) {
  char scene[4096], yee_dir[4096], png[4096], csv[4096], mesh_png[4096], readme[4096];
  snprintf(scene, sizeof scene, "%s/yee-scene.json", dir);
  snprintf(yee_dir, sizeof yee_dir, "%s/yee", dir);
  snprintf(png, sizeof png, "%s/yee-field.png", dir);
  snprintf(csv, sizeof csv, "%s/mesh-energy.csv", dir);
  snprintf(mesh_png, sizeof mesh_png, "%s/mesh-energy.png", dir);
  snprintf(readme, sizeof readme, "%s/README.md", dir);
  int status = write_text(scene, yee_scene);
  if (status != CLI_EXIT_OK) return status;
  if (!json)
    printf("\nFields 1: a Yee scene (2-D TM, 160 x 120 cells, CPML): a Gaussian pulse scatters off "
         "a dielectric disk (geomint maxwell run %s --out %s --plot %s)\n", scene, yee_dir, png);
  char *yee_argv[] = {"maxwell", "run", scene, "--out", yee_dir, "--plot", png};
  if ((status = make_directory(yee_dir)) != CLI_EXIT_OK ||
      (status = run_quiet(yee_argv, 7, json)) != CLI_EXIT_OK)
    return status;
  if (!json)
    printf("\nFields 2: a PEC cavity on 250 triangles, random E, leapfrog to t = 8: the leapfrog "
         "energy and Gauss's law are kept to round-off (geomint maxwell mesh --rect 12 --energy "
         "%s)\n", csv);
  char *mesh_argv[] = {"maxwell", "mesh", "--rect", "12", "--energy", csv};
  if ((status = run_quiet(mesh_argv, 6, json)) != CLI_EXIT_OK) return status;
  status = cli_plot_custom("demo", mesh_png, "Maxwell on a triangle mesh (DEC leapfrog): the "
                           "leapfrog energy is conserved", mesh_energy_plot, csv);
  if (status != CLI_EXIT_OK) return status;
  status = write_text(readme,
                      "# geomint demo: the pictures\n\n"
                      "- `kepler-energy-error.png`: Kepler (e = 0.6) over 1000 orbits at equal "
                      "cost: euler's and rk4's energy errors grow, verlet's and yoshida-4's stay "
                      "bounded.\n"
                      "- `yee-field.png`: Ez at t = 16 of a Gaussian pulse scattering off a "
                      "dielectric disk (epsilon 4) on Yee's grid with CPML walls.\n"
                      "- `mesh-energy.png`: Maxwell on 250 triangles (DEC leapfrog, PEC, random "
                      "E): the plain energy oscillates, the leapfrog energy is conserved to "
                      "round-off.\n");
  if (status == CLI_EXIT_OK && !json) printf("\nwrote %s, %s, %s\n", png, mesh_png, readme);
  return status;
}

static int demo_json(const gm_problem *pb, const demo_row *rows, const double orbits[2],
                     const char *dir, const char *png) {
  const size_t l = cli_find_invariant(pb, "angular");
  cJSON *o = cJSON_CreateObject();
  cJSON_AddNumberToObject(o, "eccentricity", DEMO_ECCENTRICITY);
  cJSON_AddNumberToObject(o, "orbits", DEMO_ORBITS);
  cJSON *a = cJSON_AddArrayToObject(o, "kepler");
  for (size_t i = 0; i < N_DEMO_METHODS; ++i) {
    const cli_sim_result *r = &rows[i].result;
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "method", rows[i].method->name);
    cJSON_AddNumberToObject(j, "dt", DEMO_DT * demo_methods[i].forces_per_step);
    cJSON_AddNumberToObject(j, "steps", (double)r->stats.steps);
    cJSON_AddItemToObject(j, "max_rel_energy_error",
                          cli_json_number(gm_monitor_max_rel_energy_error(r->monitor)));
    cJSON_AddItemToObject(j, "final_rel_energy_error",
                          cli_json_number(gm_monitor_last_rel_energy_error(r->monitor)));
    if (l != (size_t)-1)
      cJSON_AddItemToObject(j, "angular_momentum_drift",
                            cli_json_number(gm_monitor_max_invariant_drift(r->monitor, l)));
    cJSON_AddNumberToObject(j, "force_evals", (double)r->stats.force_evals);
    cJSON_AddNumberToObject(j, "wall_s", r->wall_s);
    cJSON_AddStringToObject(j, "csv", rows[i].csv);
    cJSON_AddItemToArray(a, j);
  }
  /* rk4's error passes verlet's / yoshida-4's largest after this many orbits (null: never) */
  cJSON_AddItemToObject(o, "rk4_passes_verlet_after_orbits", cli_json_number(orbits[0]));
  cJSON_AddItemToObject(o, "rk4_passes_yoshida4_after_orbits", cli_json_number(orbits[1]));
  cJSON *files = cJSON_AddArrayToObject(o, "plots");
  static const char *const names[] = {"yee-field.png", "mesh-energy.png", "README.md"};
  cJSON_AddItemToArray(files, cJSON_CreateString(png));
  for (size_t i = 0; i < 3; ++i) {
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", dir, names[i]);
    cJSON_AddItemToArray(files, cJSON_CreateString(path));
  }
  return cli_json_print(o);
}

static int demo_main(int argc, char **argv) {
  const char *dir = "demo-output";
  int json = 0;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &dir, 0}, {"--json", CLI_ARG_FLAG, &json, 0}};
  const char *none[1];
  size_t n_none = 0;
  int status = cli_parse("demo", argc, argv, options, 2, none, 0, &n_none);
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
  double orbits[2] = {NAN, NAN};
  char png[4096];
  status = run_demo(dir, model, rows, json, orbits, png, sizeof png);
  if (status == CLI_EXIT_OK) status = run_fields(dir, json);
  if (status == CLI_EXIT_OK && json)
    status = demo_json(gm_model_problem(model), rows, orbits, dir, png);
  for (size_t i = 0; i < N_DEMO_METHODS; ++i) cli_sim_result_clear(&rows[i].result);
  gm_model_free(model);
  return status;
}

const cli_command cli_demo_command = {"demo",
                                      "Kepler at equal cost, a Yee scene, a mesh invariant: both halves in seconds",
                                      usage, demo_main};
