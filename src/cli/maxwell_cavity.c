/* geomint maxwell cavity [--dim 2|3] [--n N]: the rectangular PEC cavity check as one command
 * (the computation: gm_experiment_cavity, src/experiments/cavity.c).
 * A band-limited pulse (Gaussian on a carrier, from dipoles) rings the cavity; each E probe's signal
 * goes through harminv (separately: a sum of probes can cancel a mode), and the first 10
 * distinct resonant frequencies are compared with
 *   analytic:  f = ½ sqrt(Σ_a (m_a / L_a)²)                                (c = 1)
 *   Yee:       sin(π f Δt) / Δt = sqrt(Σ_a sin²(π m_a h_a / 2L_a) / h_a²)  (the discrete
 *              dispersion relation, Taflove & Hagness 3rd ed. eq. 4.21 with k_a = π m_a / L_a)
 * 2-D: TM (Ez, Hx, Hy) in [0,1]×[0,0.8], modes m_x, m_y ≥ 1. 3-D: [0,1]×[0,0.8]×[0,0.6],
 * modes with at least two non-zero indices (TE and TM together; the two polarizations of a
 * mode with three non-zero indices share one frequency). */
#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/maxwell.h"
#include "geomint/experiments.h"

#define COMMAND "maxwell cavity"

static int show_progress(void *ctx, double done, double total) {
  mx_progress *p = ctx;
  p->total = (size_t)total;
  mx_progress_show(p, (size_t)done);
  return 0;
}

int mx_cavity_main(int argc, char **argv) {
  size_t dim = 3, n = 16, threads = 0;
  double periods = 200;
  const char *out_dir = "maxwell-output";
  int json = 0;
  cli_option options[] = {{"--dim", CLI_ARG_COUNT, &dim, 0},
                          {"--n", CLI_ARG_COUNT, &n, 0},
                          {"--periods", CLI_ARG_DOUBLE, &periods, 0},
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
  if (dim != 2 && dim != 3) {
    cli_error(COMMAND, "--dim must be 2 or 3, got %zu", dim);
    return CLI_EXIT_USAGE;
  }
  if (n < 4 || n > (dim == 3 ? 256 : 4096)) {
    cli_error(COMMAND, "--n must be in [4, %d], got %zu", dim == 3 ? 256 : 4096, n);
    return CLI_EXIT_USAGE;
  }
  if (cli_check_positive(COMMAND, "--periods", periods) != CLI_EXIT_OK) return CLI_EXIT_USAGE;
  if (periods < 10 || periods > 1e5) {
    cli_error(COMMAND, "--periods must be in [10, 1e5], got %g", periods);
    return CLI_EXIT_USAGE;
  }
  if ((status = mx_make_dir(COMMAND, out_dir)) != CLI_EXIT_OK) return status;

  gm_cavity_config c = gm_cavity_defaults();
  c.dim = (int)dim;
  c.n = n;
  c.periods = periods;
  c.n_threads = (int)threads;
  mx_progress progress;
  mx_progress_start(&progress, 0);
  c.progress = show_progress;
  c.progress_ctx = &progress;
  gm_cavity_result r;
  gm_error err = {{0}};
  gm_status st = gm_experiment_cavity(&c, &r, &err);
  mx_progress_end(&progress);
  if (st != GM_OK) {
    cli_error(COMMAND, "%s", err.message);
    return st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  const size_t n_probes = r.n_probes, n_signal = r.n_signal;
  const double f_max = r.f_max;
  double marks[GM_CAVITY_CHECK];
  for (size_t k = 0; k < r.n_modes; ++k) marks[k] = r.modes[k].analytic;
  char png[4096], title[128];
  snprintf(title, sizeof title, "PEC cavity, %zu-D, %zu cells per axis: spectrum of the E probes",
           dim, n);
  mx_path(png, sizeof png, out_dir, "cavity-spectrum.png");
  int plot_status = cli_gnuplot_available()
                        ? mx_plot_spectrum(COMMAND, png, title, n_probes, n_signal, r.signals,
                                           r.dt, f_max, marks, r.n_modes)
                        : CLI_EXIT_FAILURE;
  gm_cavity_result_clear(&r);
  const size_t n_ok = r.n_found;

  if (json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "dim", (double)dim);
    cJSON_AddNumberToObject(o, "n", (double)n);
    cJSON_AddNumberToObject(o, "dt", r.dt);
    cJSON_AddNumberToObject(o, "steps", (double)r.steps);
    cJSON_AddNumberToObject(o, "wall_s", r.wall_s);
    cJSON_AddNumberToObject(o, "found", (double)n_ok);
    cJSON_AddNumberToObject(o, "spurious", (double)r.spurious);
    cJSON_AddNumberToObject(o, "harminv_modes", (double)r.n_harminv);
    cJSON_AddItemToObject(o, "max_rel_error_yee", cli_json_number(r.max_rel_error_yee));
    cJSON_AddItemToObject(o, "max_rel_error_analytic", cli_json_number(r.max_rel_error_analytic));
    cJSON *arr = cJSON_AddArrayToObject(o, "modes");
    for (size_t k = 0; k < r.n_modes; ++k) {
      cJSON *m = cJSON_CreateObject();
      double idx[3] = {r.modes[k].m[0], r.modes[k].m[1], r.modes[k].m[2]};
      cJSON_AddItemToObject(m, "indices", cli_json_numbers(idx, dim));
      cJSON_AddNumberToObject(m, "analytic", r.modes[k].analytic);
      cJSON_AddNumberToObject(m, "yee", r.modes[k].yee);
      if (r.modes[k].found) {
        const gm_harminv_mode *x = &r.modes[k].computed;
        cJSON_AddNumberToObject(m, "computed", x->frequency);
        cJSON_AddItemToObject(m, "q", cli_json_number(x->q));
        cJSON_AddNumberToObject(m, "rel_error_analytic", x->frequency / r.modes[k].analytic - 1);
        cJSON_AddNumberToObject(m, "rel_error_yee", x->frequency / r.modes[k].yee - 1);
      } else {
        cJSON_AddNullToObject(m, "computed");
      }
      cJSON_AddItemToArray(arr, m);
    }
    if (plot_status == CLI_EXIT_OK) cJSON_AddStringToObject(o, "plot", png);
    status = cli_json_print(o);
  } else {
    printf("PEC cavity %s, %zu-D %s, %zu cells per axis: dt %.6g, %zu steps (%.2f s)\n",
           dim == 3 ? "[0,1]x[0,0.8]x[0,0.6]" : "[0,1]x[0,0.8]", dim, dim == 3 ? "" : "TM", n,
           r.dt, r.steps, r.wall_s);
    printf("%3s %-9s %13s %13s %13s %12s %12s\n", "", "mode", "analytic", "Yee", "computed",
           "vs analytic", "vs Yee");
    for (size_t k = 0; k < r.n_modes; ++k) {
      char idx[32];
      if (dim == 3)
        snprintf(idx, sizeof idx, "(%d,%d,%d)", r.modes[k].m[0], r.modes[k].m[1], r.modes[k].m[2]);
      else
        snprintf(idx, sizeof idx, "(%d,%d)", r.modes[k].m[0], r.modes[k].m[1]);
      printf("%3zu %-9s %13.9f %13.9f ", k + 1, idx, r.modes[k].analytic, r.modes[k].yee);
      if (r.modes[k].found)
        printf("%13.9f %12.3e %12.3e\n", r.modes[k].computed.frequency,
               r.modes[k].computed.frequency / r.modes[k].analytic - 1,
               r.modes[k].computed.frequency / r.modes[k].yee - 1);
      else
        printf("%13s\n", "not found");
    }
    printf("%zu of %zu resonances found; %zu harminv modes from %zu probes, %zu of them near no "
           "Yee mode; ", n_ok, r.n_modes, r.n_harminv, n_probes, r.spurious);
    if (plot_status == CLI_EXIT_OK)
      printf("spectrum: %s\n", png);
    else
      printf("no plot (gnuplot missing or failed)\n");
  }
  if (status == CLI_EXIT_OK && n_ok < r.n_modes) status = CLI_EXIT_FAILURE;
  return status;
}
