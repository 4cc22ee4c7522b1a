/* geomint pde nls-long: the NLS two-soliton collision over many periods, the multisymplectic
 * Preissmann box against box-sdirk2 (the same box in space, a non-symplectic order-2 SDIRK in
 * time), with the relative errors of energy, momentum and charge against t and one figure. */
#include <cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "geomint/experiments.h"

typedef struct nls_plot_ctx {
  const char *dir;
  size_t column;
  const char *ylabel;
} nls_plot_ctx;

static void nls_plot_body(FILE *g, const void *ctx) {
  const char *dir = ctx;
  static const char *what[3] = {"energy", "momentum", "charge"};
  fprintf(g, "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1500,520 "
             "font 'sans,10' }\n");
  fprintf(g, "set logscale y\nset xlabel 'periods'\nset key below\nset format y '%%.0e'\n"
             "set multiplot layout 1,3\n");
  for (int k = 0; k < 3; k++)
    fprintf(g,
            "set title '%s'\nset ylabel 'relative %s error'\n"
            "plot '%s/nls-long-preissmann.dat' u 1:%d w l lc 1 t 'preissmann (multisymplectic)', "
            "'%s/nls-long-box-sdirk2.dat' u 1:%d w l lc 2 t 'box-sdirk2 (not symplectic)'\n",
            what[k], what[k], dir, k + 2, dir, k + 2);
  fprintf(g, "unset multiplot\n");
}

static cJSON *nls_pair(const double v[2]) { return cli_json_numbers(v, 2); }

static int nls_json(const gm_nls_long_result *r, const char *png) {
  cJSON *o = cJSON_CreateObject();
  cJSON_AddNumberToObject(o, "n", (double)r->n);
  cJSON_AddNumberToObject(o, "dt", r->dt);
  cJSON_AddNumberToObject(o, "periods", r->periods);
  cJSON_AddNumberToObject(o, "t_end", r->t_end);
  cJSON_AddNumberToObject(o, "steps", (double)r->steps);
  cJSON *a = cJSON_AddArrayToObject(o, "schemes");
  for (int k = 0; k < 2; ++k) {
    const gm_nls_long_scheme *x = &r->schemes[k];
    if (x->scheme == NULL) continue;
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "scheme", x->scheme);
    /* [first tenth, last tenth] */
    cJSON_AddItemToObject(j, "max_rel_energy_error", nls_pair(x->energy));
    cJSON_AddItemToObject(j, "max_rel_momentum_error", nls_pair(x->momentum));
    cJSON_AddItemToObject(j, "max_rel_charge_error", nls_pair(x->charge));
    cJSON_AddItemToArray(a, j);
  }
  cJSON_AddNumberToObject(o, "wall_s", r->wall_s);
  if (png != NULL) cJSON_AddStringToObject(o, "plot", png);
  return cli_json_print(o);
}

int cli_pde_nls_long(int argc, char **argv) {
  const char *dir = "pde-output";
  gm_nls_long_config c = gm_nls_long_defaults();
  size_t n_pos = 0;
  int no_plot = 0, plot_only = 0, json = 0;
  cli_option options[] = {{"--only", CLI_ARG_STRING, &c.only, 0},
                          {"--plot-only", CLI_ARG_FLAG, &plot_only, 0},
                          {"--periods", CLI_ARG_DOUBLE, &c.periods, 0},
                          {"--n", CLI_ARG_COUNT, &c.n, 0},
                          {"--dt", CLI_ARG_DOUBLE, &c.dt, 0},
                          {"--every", CLI_ARG_COUNT, &c.every, 0},
                          {"--out", CLI_ARG_STRING, &dir, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0}};
  int rc = cli_parse("pde nls-long", argc, argv, options, 9, NULL, 0, &n_pos);
  if (rc == CLI_HELP) {
    fputs("usage: geomint pde nls-long [--periods P] [--n N] [--dt DT] [--every K] [--out DIR]\n"
          "                            [--no-plot] [--only preissmann|box-sdirk2] [--plot-only]\n"
          "                            [--json]\n"
          "(see 'geomint pde --help' and docs/pde.md)\n",
          stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  if (options[5].seen && c.every == 0) {
    cli_error("pde nls-long", "--every 0: rows are written every K >= 1 steps (default: the run "
              "in 2000 rows)");
    return CLI_EXIT_USAGE;
  }
  if (cli_check_positive("pde nls-long", "--dt", c.dt) != CLI_EXIT_OK ||
      cli_check_positive("pde nls-long", "--periods", c.periods) != CLI_EXIT_OK ||
      cli_check_step_count("pde nls-long", c.periods * GM_NLS_LONG_PERIOD, c.dt) != CLI_EXIT_OK)
    return CLI_EXIT_USAGE;
  if (c.n < 16 || c.n > 100000) {
    cli_error("pde nls-long", "--n must lie in 16..100000 (got %zu)", c.n);
    return CLI_EXIT_USAGE;
  }
  if (strchr(dir, '\'') != NULL) {
    cli_error("pde nls-long", "--out: the directory name may not contain a quote");
    return CLI_EXIT_USAGE;
  }
  if (!no_plot && !cli_gnuplot_available()) {
    cli_error("pde nls-long", "gnuplot is not installed (or not on PATH): use --no-plot");
    return CLI_EXIT_FAILURE;
  }
  if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
    cli_error("pde nls-long", "cannot create the directory '%s': %s", dir, strerror(errno));
    return CLI_EXIT_FAILURE;
  }
  if (c.only != NULL && strcmp(c.only, "preissmann") != 0 && strcmp(c.only, "box-sdirk2") != 0) {
    cli_error("pde nls-long", "--only takes preissmann or box-sdirk2 (got '%s')", c.only);
    return CLI_EXIT_USAGE;
  }
  if (plot_only && no_plot) {
    cli_error("pde nls-long", "--plot-only and --no-plot exclude each other");
    return CLI_EXIT_USAGE;
  }
  if (plot_only && json) {
    cli_error("pde nls-long", "--plot-only prints no numbers: drop --json");
    return CLI_EXIT_USAGE;
  }
  gm_nls_long_result r;
  if (!plot_only) {
    gm_error err = {{0}};
    if (gm_experiment_nls_long(&c, dir, &r, &err) != GM_OK) {
      cli_error("pde nls-long", "%s", err.message);
      return CLI_EXIT_FAILURE;
    }
  }
  if (!plot_only && !json) {
    printf("NLS two-soliton collision (a = 1, 0.8; c = +-pi/5) on [-20, 20), n = %zu, dt = %g, "
           "%g periods (%.4g time units, %zu steps)\n",
           r.n, r.dt, r.periods, r.t_end, r.steps);
    for (int k = 0; k < 2; k++) {
      const gm_nls_long_scheme *x = &r.schemes[k];
      if (x->scheme == NULL) continue;
      printf("  %-10s max relative error, first / last tenth: energy %.3e / %.3e, momentum "
             "%.3e / %.3e, charge %.3e / %.3e\n",
             x->scheme, x->energy[0], x->energy[1], x->momentum[0], x->momentum[1], x->charge[0],
             x->charge[1]);
    }
  }
  char png[4200];
  snprintf(png, sizeof png, "%s/nls-long.png", dir);
  if (!no_plot) {
    rc = cli_plot_custom("pde nls-long", png,
                         "NLS two-soliton collision: Preissmann box vs box-sdirk2", nls_plot_body,
                         dir);
    if (rc != CLI_EXIT_OK) return rc;
    if (!json) printf("  figure: %s\n", png);
  }
  return json ? nls_json(&r, no_plot ? NULL : png) : CLI_EXIT_OK;
}
