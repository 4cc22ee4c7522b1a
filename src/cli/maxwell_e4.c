/* geomint maxwell e4: seed 000 experiment E4 (src/experiments/e4.c, gm_experiment_e4) — parse,
 * run, draw the energy figure, print. */
#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/maxwell.h"
#include "geomint/experiments.h"

#define COMMAND "maxwell e4"

/* the figure: energies relative to the initial plain energy; 1 when drawn */
static int plot_energy(const gm_e4_result *e, size_t n, const char *png) {
  if (!cli_gnuplot_available()) return 0;
  double *rp = malloc(e->n_samples * sizeof *rp), *rl = malloc(e->n_samples * sizeof *rl);
  int plotted = 0;
  if (rp != NULL && rl != NULL) {
    for (size_t i = 0; i < e->n_samples; ++i) {
      rp[i] = e->plain[i] / e->plain[0];
      rl[i] = e->leapfrog[i] / e->plain[0];
    }
    mx_line lines[2] = {{"plain energy (E^{n-1/2}, H^n)", e->n_samples, e->t, rp, 0},
                        {"leapfrog energy (conserved)", e->n_samples, e->t, rl, 0}};
    char title[160];
    snprintf(title, sizeof title,
             "Seed 000 E4: PEC square, %zux%zu Yee cells, random E, dt = 0.1 CFL", n, n);
    plotted = mx_plot_lines(COMMAND, png, title, "t", "energy / initial plain energy", 0, lines,
                            2) == CLI_EXIT_OK;
  }
  free(rp), free(rl);
  return plotted;
}

int mx_e4_main(int argc, char **argv) {
  gm_e4_config config = gm_e4_defaults();
  size_t seed = 1, threads = 0;
  const char *out_dir = "maxwell-output";
  int json = 0;
  cli_option options[] = {{"--n", CLI_ARG_COUNT, &config.n, 0},
                          {"--time", CLI_ARG_DOUBLE, &config.t_end, 0},
                          {"--seed", CLI_ARG_COUNT, &seed, 0},
                          {"--out", CLI_ARG_STRING, &out_dir, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0},
                          {"--threads", CLI_ARG_COUNT, &threads, 0}};
  const char *positional[1];
  size_t n_pos = 0;
  int status = cli_parse(COMMAND, argc, argv, options, 6, positional, 0, &n_pos);
  if (status == CLI_HELP) {
    fputs(mx_usage(), stdout);
    return CLI_EXIT_OK;
  }
  if (status != CLI_EXIT_OK) return status;
  if (config.n < 2 || config.n > 2048) {
    cli_error(COMMAND, "--n must be in [2, 2048], got %zu", config.n);
    return CLI_EXIT_USAGE;
  }
  if (cli_check_positive(COMMAND, "--time", config.t_end) != CLI_EXIT_OK) return CLI_EXIT_USAGE;
  if (threads > 4096) {
    cli_error(COMMAND, "--threads %zu: at most 4096", threads);
    return CLI_EXIT_USAGE;
  }
  config.seed = seed;
  config.n_threads = (int)threads;
  if ((status = mx_make_dir(COMMAND, out_dir)) != CLI_EXIT_OK) return status;
  gm_e4_result e;
  gm_error err = {{0}};
  gm_status st = gm_experiment_e4(&config, out_dir, &e, &err);
  if (st != GM_OK) {
    /* a size or time the run refuses is bad input; anything else failed while running */
    cli_error(COMMAND, "%s", err.message);
    return st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  char csv[4096], png[4096];
  mx_path(csv, sizeof csv, out_dir, "e4-energy.csv");
  mx_path(png, sizeof png, out_dir, "e4-energy.png");
  const int plotted = plot_energy(&e, config.n, png);
  if (json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "n", (double)config.n);
    cJSON_AddNumberToObject(o, "dt", e.dt);
    cJSON_AddNumberToObject(o, "steps", (double)e.steps);
    cJSON_AddNumberToObject(o, "t_final", e.t_final);
    cJSON_AddNumberToObject(o, "seed", (double)seed);
    cJSON_AddNumberToObject(o, "plain_initial", e.plain_initial);
    cJSON_AddNumberToObject(o, "plain_mean", e.plain_mean);
    cJSON_AddNumberToObject(o, "plain_range_first_half", e.plain_range_first_half);
    cJSON_AddNumberToObject(o, "plain_range_second_half", e.plain_range_second_half);
    cJSON_AddNumberToObject(o, "leapfrog_max_rel_drift", e.leapfrog_max_rel_drift);
    cJSON_AddNumberToObject(o, "wall_s", e.wall_s);
    cJSON_AddStringToObject(o, "csv", csv);
    if (plotted) cJSON_AddStringToObject(o, "plot", png);
    status = cli_json_print(o);
  } else {
    printf("E4 (seed 000): PEC unit square, %zu x %zu cells (2-D TE), random E (seed %zu), "
           "dt = %.6g (0.1 of the Courant limit), %zu steps to t = %.6g (%.2f s)\n",
           config.n, config.n, seed, e.dt, e.steps, e.t_final, e.wall_s);
    printf("  plain energy: initial %.9g, mean %.9g; range (max - min) / mean %.3e in the "
           "first half, %.3e in the second (bounded)\n",
           e.plain_initial, e.plain_mean, e.plain_range_first_half, e.plain_range_second_half);
    printf("  leapfrog energy: max relative drift %.3e (conserved to round-off)\n",
           e.leapfrog_max_rel_drift);
    printf("  wrote %s%s%s\n", csv, plotted ? ", " : "", plotted ? png : "");
  }
  gm_e4_result_clear(&e);
  return status;
}
