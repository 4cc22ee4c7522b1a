/* geomint oscillatory EXPERIMENT: the experiments of seed 000 ch. 2 (Stern's thesis, Figs.
 * 2.1–2.3; notes E1–E3) and a work–precision comparison on FPU, with the rows of the
 * oscillatory family (issue 12): data, figures and a table. */
#include <cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "geomint/experiments.h"

static const char usage[] =
    "usage: geomint oscillatory EXPERIMENT [--out DIR] [--points N] [--no-plot] [--json]\n\n"
    "Experiments with split potentials V = U + W (seed 000 ch. 2, docs/oscillatory.md):\n"
    "  resonance       toy problem U = q^2/2, W = omega^2 q^2/2 from q = 0, p = 1: max |H - H0|\n"
    "                  over T = 1000 with h = 0.1 against omega h / pi in (0, 4.5] (N points,\n"
    "                  default 900), for imex and impulse (r-RESPA) with 100 substeps (Fig 2.1)\n"
    "  fpu             FPU (l = 3, omega = 50), T = 200: the oscillatory energies I1, I2, I3 and\n"
    "                  I for verlet h = 0.001 (reference) and h = 0.03, imex h = 0.03, 0.1, 0.15\n"
    "                  (Fig 2.2)\n"
    "  fpu-long        the same to T = 4000 for imex h = 0.1, the trig-* rows h = 0.1 and\n"
    "                  vti h = 0.05 (Fig 2.3)\n"
    "  work-precision  FPU, T = 200: error of the slow components and of I at T against the\n"
    "                  step, for every oscillatory row, verlet and the best composition\n"
    "  step-scan       FPU, T = 200: for each oscillatory row the largest step (h = 200/n,\n"
    "                  0.04 to 0.3, 2% apart) with I error <= 1e-2; table only, not in 'all'\n"
    "  multiscale      the multiscale variational integrator on the stiff spring pendulum\n"
    "                  (seed 001 5.7.2) against vi-midpoint and imex, and 1-D MsFEM against P1\n"
    "                  (seed 001 5.7.1): tables only\n"
    "  all             all of them\n"
    "Writes CSV files and gnuplot scripts into DIR and draws PNG figures; prints a table.\n\n"
    "options:\n"
    "  --out DIR    output directory, created if missing (default oscillatory-output)\n"
    "  --points N   resonance: number of values of omega h / pi (default 900, at most 20000:\n"
    "               about 17 ms each)\n"
    "  --no-plot    write the data only\n"
    "  --json       (resonance, fpu, fpu-long) print one JSON object instead of the text\n";

#define CMD "oscillatory"

static int make_directory(const char *dir) {
  if (mkdir(dir, 0777) == 0 || errno == EEXIST) {
    struct stat sb;
    if (stat(dir, &sb) == 0 && S_ISDIR(sb.st_mode)) return CLI_EXIT_OK;
  }
  cli_error(CMD, "cannot create the directory '%s': %s", dir, strerror(errno));
  return CLI_EXIT_FAILURE;
}

static int run_gnuplot_script(const char *script) {
  char cmd[4200];
  snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", script);
  if (system(cmd) != 0) {
    cli_error(CMD, "gnuplot failed on %s", script);
    return CLI_EXIT_FAILURE;
  }
  return CLI_EXIT_OK;
}

static FILE *open_file(const char *path) {
  FILE *f = fopen(path, "w");
  if (f == NULL) cli_error(CMD, "cannot write %s: %s", path, strerror(errno));
  return f;
}

/* Create an integrator of `method` (with `substeps` > 0 for impulse rows) at the model's
 * initial state; prints the error. */
static double wall_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static gm_integrator *start(const gm_model *model, const char *method, size_t substeps) {
  const gm_method *m = cli_find_method(CMD, method);
  if (m == NULL) return NULL;
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  if (gm_integrator_create(m, gm_model_problem(model), &it, &err) != GM_OK) {
    cli_error(CMD, "%s: %s", method, err.message);
    return NULL;
  }
  double t0, y0[64];
  gm_model_initial_state(model, &t0, y0);
  gm_integrator_set_state(it, t0, y0);
  if (substeps > 0 && gm_oscillatory_set_substeps(it, substeps) != GM_OK) {
    cli_error(CMD, "%s", gm_integrator_errmsg(it));
    gm_integrator_free(it);
    return NULL;
  }
  return it;
}

/* ---- E1: resonance (src/experiments/resonance.c) -------------------------------------------- */

static int experiment_resonance(const char *dir, size_t n_points, int plot, int json) {
  gm_resonance_result r;
  gm_error err = {{0}};
  gm_status st = gm_experiment_resonance(n_points, dir, &r, &err);
  if (st != GM_OK) {
    cli_error(CMD, "%s", err.message);
    return st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  char csv[4096], script[4096];
  snprintf(csv, sizeof csv, "%s/resonance.csv", dir);
  if (json) {
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "experiment", "resonance");
    cJSON_AddNumberToObject(j, "points", (double)(r.n_points + r.n_near));
    cJSON_AddItemToObject(j, "imex_min", cli_json_number(r.imex_min));
    cJSON_AddItemToObject(j, "imex_max", cli_json_number(r.imex_max));
    cJSON_AddItemToObject(j, "impulse_max", cli_json_number(r.impulse_max));
    cJSON_AddNumberToObject(j, "impulse_max_at", r.impulse_max_at);
    cJSON_AddNumberToObject(j, "impulse_spikes", (double)r.impulse_spikes);
    cJSON_AddNumberToObject(j, "impulse_blowups", (double)r.impulse_blowups);
    cJSON_AddItemToObject(j, "spikes_near", cli_json_numbers(r.spike_near, r.n_spike_near));
    cJSON_AddNumberToObject(j, "wall_s", r.wall_s);
    cJSON_AddStringToObject(j, "csv", csv);
    const int rc = cli_json_print(j);
    if (rc != CLI_EXIT_OK) return rc;
  } else {
  printf("resonance (seed 000 Fig 2.1): toy problem, h = 0.1, T = 1000, %zu values of "
         "omega h/pi in (0, 4.5] (+ %zu within 0.005 of 1, 2, 3, 4)\n",
         r.n_points, r.n_near);
  printf("  imex:               max |H - H0| from %.4e to %.4e (ratio %.2f)\n", r.imex_min,
         r.imex_max, r.imex_max / r.imex_min);
  printf("  impulse (n = 100):  max |H - H0| up to %.3e at omega h/pi = %.4f; %zu values "
         "above 1 (%zu blow-ups), near omega h/pi =",
         r.impulse_max, r.impulse_max_at, r.impulse_spikes, r.impulse_blowups);
  for (size_t i = 0; i < r.n_spike_near; ++i) printf(" %g", r.spike_near[i]);
  printf("\n  data: %s\n", csv);
  }
  if (!plot) return CLI_EXIT_OK;
  snprintf(script, sizeof script, "%s/resonance.gp", dir);
  FILE *g = open_file(script);
  if (g == NULL) return CLI_EXIT_FAILURE;
  fprintf(g, "set terminal pngcairo size 960,560 font ',11'\nset datafile separator ','\n"
             "set output '%s/resonance.png'\nset grid\nset key top left\nset logscale y\n"
             "set format y '10^{%%L}'\nset yrange [1e-5:1e11]\nset xrange [0:4.5]\n"
             "set xlabel 'omega h / pi'\nset ylabel 'max |H - H_0| over T = 1000'\n"
             "set title 'Resonance: U = q^2/2, W = omega^2 q^2/2, h = 0.1 (blow-ups drawn at "
             "1e10)'\n"
             "plot '%s' every ::1 using 1:4 with lines lw 1.2 title 'impulse / r-RESPA, 100 "
             "substeps', '%s' every ::1 using 1:3 with lines lw 2 title 'variational IMEX'\n",
          dir, csv, csv);
  fclose(g);
  return run_gnuplot_script(script);
}

/* ---- E2, E3: FPU ------------------------------------------------------------------------- */

static int open_fpu(gm_model **model) {
  return cli_open_model(CMD, "fpu", &(cli_settings){0, {NULL}}, model);
}

static int fpu_figure(const char *dir, const char *name, const char *title,
                      const gm_fpu_result *r) {
  char script[4096];
  snprintf(script, sizeof script, "%s/%s.gp", dir, name);
  FILE *g = open_file(script);
  if (g == NULL) return CLI_EXIT_FAILURE;
  const size_t rows = (r->n_runs + 1) / 2;
  fprintf(g, "set terminal pngcairo size 1100,%zu font ',10'\nset datafile separator ','\n"
             "set output '%s/%s.png'\nset multiplot layout %zu,2 title '%s'\n"
             "set xrange [0:%g]\nset yrange [0:1.5]\nset key top right horizontal\n",
          260 * rows + 40, dir, name, rows, title, r->t_end);
  for (size_t k = 0; k < r->n_runs; ++k)
    fprintf(g, "set title '%s'\nplot '%s' every ::1 using 1:2 with lines title 'I_1', '' every "
               "::1 using 1:3 with lines title 'I_2', '' every ::1 using 1:4 with lines title "
               "'I_3', '' every ::1 using 1:5 with lines lw 1.5 lc rgb 'black' title 'I'\n",
            r->runs[k].title, r->runs[k].csv);
  fprintf(g, "unset multiplot\n");
  fclose(g);
  return run_gnuplot_script(script);
}

static int fpu_json(const char *name, const gm_fpu_result *r) {
  cJSON *j = cJSON_CreateObject();
  cJSON_AddStringToObject(j, "experiment", name);
  cJSON_AddNumberToObject(j, "t_end", r->t_end);
  cJSON_AddNumberToObject(j, "sample", r->sample);
  cJSON *runs = cJSON_AddArrayToObject(j, "runs");
  for (size_t k = 0; k < r->n_runs; ++k) {
    const gm_fpu_run_result *o = &r->runs[k];
    cJSON *x = cJSON_CreateObject();
    cJSON_AddStringToObject(x, "method", o->method);
    cJSON_AddNumberToObject(x, "h", o->h);
    cJSON_AddNumberToObject(x, "steps", (double)o->steps);
    cJSON_AddItemToObject(x, "max_abs_dH", cli_json_number(o->max_abs_dh));
    cJSON_AddItemToObject(x, "max_abs_dI", cli_json_number(o->max_abs_di));
    cJSON_AddItemToObject(x, "max_abs_dev_reference", cli_json_number(o->max_abs_dev));
    cJSON_AddItemToObject(x, "t_exchange", cli_json_number(o->t_exchange));
    if (!r->long_run) cJSON_AddItemToObject(x, "I_at_150", cli_json_numbers(o->at150, 3));
    cJSON_AddStringToObject(x, "csv", o->csv);
    cJSON_AddItemToArray(runs, x);
  }
  cJSON_AddNumberToObject(j, "wall_s", r->wall_s);
  return cli_json_print(j);
}

/* E2, E3 (src/experiments/fpu.c): the table, or --json, and the figure */
static int experiment_fpu(const char *dir, int plot, int long_run, int json) {
  const char *name = long_run ? "fpu-long" : "fpu";
  static gm_fpu_result r;
  gm_error err = {{0}};
  gm_status st = gm_experiment_fpu(long_run, dir, &r, &err);
  if (st != GM_OK) {
    cli_error(CMD, "%s", err.message);
    return st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  if (json) {
    const int rc = fpu_json(name, &r);
    if (rc != CLI_EXIT_OK) return rc;
  } else {
    printf("%s (seed 000 Fig %s): FPU l = 3, omega = 50, T = %g; I = I1 + I2 + I3, I(0) = 1\n",
           name, long_run ? "2.3" : "2.2", r.t_end);
    printf("  %-24s %7s %11s %11s %14s %9s   %s\n", "method", "h", "max |dH|", "max |dI|",
           "max |Ij - ref|", "t(I3>.5)", "I1, I2, I3 at t = 150");
    for (size_t k = 0; k < r.n_runs; ++k) {
      const gm_fpu_run_result *o = &r.runs[k];
      char dev[32];
      snprintf(dev, sizeof dev, k == 0 ? "(reference)" : "%.3e", o->max_abs_dev);
      printf("  %-24s %7g %11.3e %11.3e %14s %9.1f   %.3f %.3f %.3f\n", o->method, o->h,
             o->max_abs_dh, o->max_abs_di, dev, o->t_exchange, o->at150[0], o->at150[1],
             o->at150[2]);
    }
  }
  if (!plot) return CLI_EXIT_OK;
  return fpu_figure(dir, name,
                    long_run ? "FPU, T = 4000: oscillatory energies"
                             : "FPU, T = 200: oscillatory energies",
                    &r);
}

/* ---- work–precision on FPU --------------------------------------------------------------- */

/* Averages of I over the blocks [2k, 2k + 2) of T = 200: I oscillates by O(1/ω) about its
 * slow evolution, with the phase of the fast oscillation, which no method with a large step
 * reproduces; its block averages are what a long step can and should get right. */
#define WP_BLOCKS 100
typedef struct {
  const gm_problem *pb;
  double sum[WP_BLOCKS];
  size_t count[WP_BLOCKS];
} block_average;

static int average_i(void *ctx, size_t step, double t, const double *y) {
  (void)step;
  block_average *b = ctx;
  long k = (long)floor(t / 2.0 + 1e-9);
  if (k >= 0 && k < WP_BLOCKS) {
    b->sum[k] += b->pb->invariants[3].value(b->pb->ctx, y);
    b->count[k]++;
  }
  return 0;
}

/* State at T = 200 and the block averages of I; returns 0 when the run failed. */
static int fpu_final_n(const gm_model *model, const char *method, size_t substeps, double h,
                       double *y, double *means, gm_stats *stats) {
  gm_integrator *it = start(model, method, substeps);
  if (it == NULL) return 0;
  block_average b;
  memset(&b, 0, sizeof b);
  b.pb = gm_model_problem(model);
  gm_integrator_add_observer(it, average_i, &b, 1);
  gm_status st = gm_integrator_run(it, (size_t)llround(200.0 / h), h);
  if (st == GM_OK) memcpy(y, gm_integrator_state(it), 12 * sizeof *y);
  for (size_t k = 0; k < WP_BLOCKS; ++k) means[k] = b.count[k] ? b.sum[k] / (double)b.count[k] : NAN;
  *stats = gm_integrator_stats(it);
  gm_integrator_free(it);
  return st == GM_OK;
}

static int fpu_final(const gm_model *model, const char *method, double h, double *y,
                     double *means, gm_stats *stats) {
  return fpu_final_n(model, method, 0, h, y, means, stats);
}

/* ---- the step that reaches I error 1e-2, on a fine grid ------------------------------------
 * Steps h = 200/n for n = 5000 down to 667 (h = 0.04 … 0.3, every n with h·ω/π on a 1 %
 * grid, plus n = 1000: h = 0.2 exactly); the I error as in work-precision (block averages
 * against blanes-moan-6, h = 0.0002). For each row: the first step above 2/ω = 0.04 where the
 * I error exceeds 1e-2, the largest step with I error ≤ 1e-2, the error at 5 × 2/ω = 0.2 and
 * the share of the scanned steps in [0.2, 0.3] that reach 1e-2. The fast resonances hω = kπ of
 * FPU's ω = 50 are at h = 0.0628 k. */
static int experiment_step_scan(const char *dir, int json) {
  static const struct {
    const char *name;
    size_t substeps;
  } rows[] = {{"imex", 0},
              {"impulse", 0},
              {"impulse", 50},
              {"mollified-impulse-sinc", 0},
              {"mollified-impulse-sinc", 10},
              {"mollified-impulse-sinc", 50},
              {"trig-gautschi", 0},
              {"trig-deuflhard", 0},
              {"trig-garcia-archilla", 0},
              {"trig-hochbruck-lubich", 0},
              {"trig-hairer-lubich", 0},
              {"vti", 0}};
  enum { N_ROWS = sizeof rows / sizeof rows[0] };
  gm_model *model = NULL;
  int rc = open_fpu(&model);
  if (rc != CLI_EXIT_OK) return rc;
  double ref[12], ref_means[WP_BLOCKS];
  gm_stats stats;
  if (!fpu_final(model, "blanes-moan-6", 0.0002, ref, ref_means, &stats)) {
    gm_model_free(model);
    return CLI_EXIT_FAILURE;
  }
  char csv[4096];
  snprintf(csv, sizeof csv, "%s/step-scan.csv", dir);
  FILE *f = open_file(csv);
  if (f == NULL) {
    gm_model_free(model);
    return CLI_EXIT_FAILURE;
  }
  fprintf(f, "method,substeps,h,h_omega_over_pi,I_error\n");
  cJSON *jrows = json ? cJSON_CreateArray() : NULL;
  if (!json) {
  printf("step-scan: FPU (l = 3, omega = 50), T = 200; I error as in work-precision; steps\n"
         "  h = 200/n from 2/omega = 0.04 to 0.3 (h*omega/pi on a 1%% grid, and h = 0.2);\n"
         "  resonances h*omega = k*pi at h = 0.0628 k\n");
  printf("  %-24s %4s %12s %10s %8s %12s %12s\n", "method", "n", "first fail h", "largest h",
         "h/(2/w)", "I err at 0.2", "pass >= 0.2");
  }
  const double t_scan = wall_now();
  for (size_t r = 0; r < N_ROWS; ++r) {
    double largest = 0.0, first_fail = NAN, at_02 = NAN;
    size_t n_above = 0, pass_above = 0;
    long n_prev = 0;
    for (double x = 0.64; x <= 4.8 + 1e-9; x += 0.01) { /* x = hω/π */
      long n = lround(200.0 * 50.0 / (3.14159265358979323846 * x));
      if (n_prev > 1000 && n < 1000) n = 1000, x -= 0.01; /* h = 0.2 itself */
      if (n == n_prev) continue;
      n_prev = n;
      const double h = 200.0 / (double)n;
      double y[12], means[WP_BLOCKS], ierr = INFINITY;
      if (fpu_final_n(model, rows[r].name, rows[r].substeps, h, y, means, &stats)) {
        ierr = 0.0;
        for (size_t b = 0; b < WP_BLOCKS; ++b) ierr = fmax(ierr, fabs(means[b] - ref_means[b]));
        if (!isfinite(ierr)) ierr = INFINITY;
      }
      fprintf(f, "%s,%zu,%.6g,%.6g,%.6e\n", rows[r].name, rows[r].substeps, h,
              h * 50.0 / 3.14159265358979323846, isinf(ierr) ? 1e10 : ierr);
      if (ierr <= 1e-2) largest = fmax(largest, h);
      else if (isnan(first_fail)) first_fail = h;
      if (n == 1000) at_02 = ierr;
      if (n <= 1000) {
        n_above++;
        if (ierr <= 1e-2) pass_above++;
      }
    }
    if (json) {
      cJSON *j = cJSON_CreateObject();
      cJSON_AddStringToObject(j, "method", rows[r].name);
      cJSON_AddNumberToObject(j, "substeps", (double)rows[r].substeps);
      cJSON_AddItemToObject(j, "first_fail_h", cli_json_number(first_fail));
      cJSON_AddItemToObject(j, "largest_h", cli_json_number(largest));
      cJSON_AddItemToObject(j, "i_error_at_0.2", cli_json_number(at_02));
      cJSON_AddNumberToObject(j, "pass_above_0.2", (double)pass_above);
      cJSON_AddNumberToObject(j, "steps_above_0.2", (double)n_above);
      cJSON_AddItemToArray(jrows, j);
    } else {
      printf("  %-24s %4zu %12.4g %10.4g %8.2f %12.3e %6zu of %zu\n", rows[r].name,
             rows[r].substeps, first_fail, largest, largest / 0.04, at_02, pass_above, n_above);
    }
  }
  fclose(f);
  gm_model_free(model);
  if (json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddItemToObject(o, "rows", jrows);
    cJSON_AddNumberToObject(o, "wall_s", wall_now() - t_scan);
    cJSON_AddStringToObject(o, "csv", csv);
    return cli_json_print(o);
  }
  printf("  (n: impulse substeps, 0 = the row's default; data: %s)\n", csv);
  return CLI_EXIT_OK;
}

static int experiment_work_precision(const char *dir, int plot, int json) {
  static const char *const rows[] = {"imex",
                                     "impulse",
                                     "mollified-impulse-sinc",
                                     "trig-gautschi",
                                     "trig-deuflhard",
                                     "trig-garcia-archilla",
                                     "trig-hochbruck-lubich",
                                     "trig-hairer-lubich",
                                     "vti",
                                     "verlet",
                                     "blanes-moan-4",
                                     "yoshida-4",
                                     "suzuki-4",
                                     "kahan-li-6",
                                     "blanes-moan-6"};
  enum { N_ROWS = sizeof rows / sizeof rows[0], N_OSC = 9, N_H = 12 };
  /* steps 200/n: from 0.25 down to 0.0005 */
  static const double hs[N_H] = {0.25, 0.2, 0.16, 0.125, 0.1, 0.08, 0.05, 0.025, 0.01, 0.005,
                                 0.002, 0.001};
  gm_model *model = NULL;
  int rc = open_fpu(&model);
  if (rc != CLI_EXIT_OK) return rc;
  const gm_problem *pb = gm_model_problem(model);
  double ref[12], ref_means[WP_BLOCKS];
  gm_stats stats;
  if (!fpu_final(model, "blanes-moan-6", 0.0002, ref, ref_means, &stats)) {
    gm_model_free(model);
    return CLI_EXIT_FAILURE;
  }
  const double i_ref = pb->invariants[3].value(pb->ctx, ref); /* I(T) */
  char csv[4096];
  snprintf(csv, sizeof csv, "%s/work-precision.csv", dir);
  FILE *f = open_file(csv);
  if (f == NULL) {
    gm_model_free(model);
    return CLI_EXIT_FAILURE;
  }
  fprintf(f, "method,h,slow_error,I_error,I_T_error,force_evals\n");
  cJSON *jrows = json ? cJSON_CreateArray() : NULL;
  const double t_wp = wall_now();
  if (!json) {
  printf("work-precision: FPU (l = 3, omega = 50), T = 200, against blanes-moan-6 h = 0.0002;\n"
         "  I error = max over the blocks [2k, 2k+2) of |mean I - mean I_ref|; I(T) error =\n"
         "  |I(T) - I_ref(T)|; slow error = max |x0, y0 - ref| at T. Verlet's stability limit\n"
         "  2/omega = 0.04, 5x that = 0.2\n");
  printf("  %-24s %9s %8s %11s %11s %11s %10s\n", "method", "largest h", "h/(2/w)", "I err",
         "I(T) err", "slow err", "evals/step");
  }
  double best_h_comp = 0.0;
  const char *best_comp = NULL;
  double best_evals = INFINITY;
  for (size_t r = 0; r < N_ROWS; ++r) {
    double largest = 0.0, i_err_there = NAN, it_there = NAN, slow_there = NAN, evals = NAN;
    for (size_t k = 0; k < N_H; ++k) {
      double y[12], means[WP_BLOCKS];
      double slow = INFINITY, ierr = INFINITY, iterr = INFINITY;
      if (fpu_final(model, rows[r], hs[k], y, means, &stats)) {
        slow = ierr = 0.0;
        for (size_t i = 0; i < 3; ++i)
          slow = fmax(slow, fmax(fabs(y[i] - ref[i]), fabs(y[6 + i] - ref[6 + i])));
        for (size_t b = 0; b < WP_BLOCKS; ++b) ierr = fmax(ierr, fabs(means[b] - ref_means[b]));
        iterr = fabs(pb->invariants[3].value(pb->ctx, y) - i_ref);
        if (!isfinite(slow) || !isfinite(ierr) || !isfinite(iterr))
          slow = ierr = iterr = INFINITY;
      }
      fprintf(f, "%s,%g,%.6e,%.6e,%.6e,%zu\n", rows[r], hs[k], isinf(slow) ? 1e10 : slow,
              isinf(ierr) ? 1e10 : ierr, isinf(iterr) ? 1e10 : iterr, stats.force_evals);
      if (ierr <= 1e-2 && hs[k] > largest) {
        largest = hs[k];
        i_err_there = ierr;
        it_there = iterr;
        slow_there = slow;
        evals = (double)stats.force_evals / (200.0 / hs[k]);
      }
    }
    if (r >= N_OSC + 1 && largest > 0.0) { /* compositions: fewest evaluations */
      double total = evals * 200.0 / largest;
      if (total < best_evals) {
        best_evals = total;
        best_comp = rows[r];
        best_h_comp = largest;
      }
    }
    if (json) {
      cJSON *j = cJSON_CreateObject();
      cJSON_AddStringToObject(j, "method", rows[r]);
      cJSON_AddItemToObject(j, "largest_h", cli_json_number(largest));
      cJSON_AddItemToObject(j, "i_error", cli_json_number(i_err_there));
      cJSON_AddItemToObject(j, "i_t_error", cli_json_number(it_there));
      cJSON_AddItemToObject(j, "slow_error", cli_json_number(slow_there));
      cJSON_AddItemToObject(j, "evals_per_step", cli_json_number(evals));
      cJSON_AddItemToArray(jrows, j);
    } else {
      printf("  %-24s %9g %8.2f %11.3e %11.3e %11.3e %10.0f\n", rows[r], largest,
             largest / 0.04, i_err_there, it_there, slow_there, evals);
    }
  }
  fclose(f);
  gm_model_free(model);
  if (json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddItemToObject(o, "rows", jrows);
    cJSON_AddStringToObject(o, "best_composition", best_comp ? best_comp : "none");
    cJSON_AddNumberToObject(o, "best_composition_h", best_h_comp);
    cJSON_AddNumberToObject(o, "wall_s", wall_now() - t_wp);
    cJSON_AddStringToObject(o, "csv", csv);
    if (plot) {
      char png[4200];
      snprintf(png, sizeof png, "%s/work-precision.png", dir);
      cJSON_AddStringToObject(o, "plot", png);
    }
    const int rc_json = cli_json_print(o);
    if (rc_json != CLI_EXIT_OK) return rc_json;
  } else {
  printf("  (largest h: the largest step of the grid with I error <= 1e-2)\n  best composition: %s (h = %g)\n  data: %s\n",
         best_comp ? best_comp : "none", best_h_comp, csv);
  }
  if (!plot) return CLI_EXIT_OK;
  char script[4096];
  snprintf(script, sizeof script, "%s/work-precision.gp", dir);
  FILE *g = open_file(script);
  if (g == NULL) return CLI_EXIT_FAILURE;
  fprintf(g, "set terminal pngcairo size 1200,520 font ',10'\nset datafile separator ','\n"
             "set output '%s/work-precision.png'\nset multiplot layout 1,2 title 'FPU (omega = "
             "50), T = 200: error against step size'\n"
             "set logscale xy\nset grid\nset xlabel 'h'\nset format y '10^{%%L}'\n"
             "set yrange [1e-8:10]\nset key bottom right font ',8'\n"
             "set arrow from 0.04, graph 0 to 0.04, graph 1 nohead dt 2\n"
             "set arrow from 0.2, graph 0 to 0.2, graph 1 nohead dt 3\n",
          dir);
  for (int panel = 0; panel < 2; ++panel) {
    fprintf(g, "set title '%s (dashed: 2/omega and 5 x 2/omega)'\nset ylabel '%s'\nplot ",
            panel == 0 ? "I, block averages over 2 time units" : "slow components at T",
            panel == 0 ? "max |mean I - mean I_ref|" : "max |x0, y0 - ref|");
    for (size_t r = 0; r < N_ROWS; ++r) {
      if (r > N_OSC && !(strcmp(rows[r], "verlet") == 0 ||
                         (best_comp && strcmp(rows[r], best_comp) == 0)))
        continue;
      fprintf(g, "%s'%s' using (strcol(1) eq '%s' ? $2 : 1/0):%d with linespoints %s title '%s'",
              r ? ", " : "", csv, rows[r], panel == 0 ? 4 : 3,
              r == N_OSC ? "lw 2.5 dt 2 lc rgb 'gray40'"
                         : (r > N_OSC ? "lw 2.5 lc rgb 'black'" : "lw 1.2"),
              rows[r]);
    }
    fprintf(g, "\n");
  }
  fprintf(g, "unset multiplot\n");
  fclose(g);
  return run_gnuplot_script(script);
}

/* ---- multiscale: the multiscale VI, MsFEM (src/experiments/multiscale.c) ------------------ */

static void multiscale_cell(char *buf, size_t cap, const gm_multiscale_cell *c, size_t n,
                            int of_n) {
  if (c->status == 0)
    snprintf(buf, cap, "da %.1e dth %.1e", c->da, c->dtheta);
  else if (c->status < 0)
    snprintf(buf, cap, "failed");
  else if (of_n)
    snprintf(buf, cap, "Newton fails at step %zu of %zu", c->step + 1, n);
  else
    snprintf(buf, cap, "Newton fails, step %zu", c->step + 1);
}

static int multiscale_json(const gm_multiscale_result *r) {
  static const char *const columns[5] = {"msvi_additive", "vi_midpoint_polar", "imex_cartesian",
                                         "msvi_product_l_plus_a", "msvi_product_a"};
  cJSON *o = cJSON_CreateObject();
  cJSON *rows = cJSON_AddArrayToObject(o, "spring_pendulum");
  for (size_t i = 0; i < GM_MULTISCALE_T; ++i)
    for (size_t j = 0; j < GM_MULTISCALE_H; ++j) {
      cJSON *row = cJSON_CreateObject();
      cJSON_AddNumberToObject(row, "t_end", r->t_end[i]);
      cJSON_AddNumberToObject(row, "h", r->h[j]);
      cJSON_AddNumberToObject(row, "steps", (double)r->steps[i][j]);
      for (int c = 0; c < 5; ++c) {
        const gm_multiscale_cell *x = &r->cells[i][j][c];
        cJSON *cell = cJSON_AddObjectToObject(row, columns[c]);
        cJSON_AddBoolToObject(cell, "ran", x->status == 0);
        if (x->status == 0) {
          cJSON_AddItemToObject(cell, "a_error", cli_json_number(x->da));
          cJSON_AddItemToObject(cell, "theta_error", cli_json_number(x->dtheta));
        } else if (x->status > 0) {
          cJSON_AddNumberToObject(cell, "newton_failed_at_step", (double)(x->step + 1));
        }
      }
      cJSON_AddItemToArray(rows, row);
    }
  rows = cJSON_AddArrayToObject(o, "msfem");
  for (size_t i = 0; i < GM_MULTISCALE_MSFEM; ++i) {
    cJSON *row = cJSON_CreateObject();
    cJSON_AddNumberToObject(row, "n", (double)r->msfem_n[i]);
    cJSON_AddItemToObject(row, "p1_nodal_error", cli_json_number(r->msfem_p1_error[i]));
    cJSON_AddItemToArray(rows, row);
  }
  cJSON_AddNumberToObject(o, "wall_s", r->wall_s);
  return cli_json_print(o);
}

static int experiment_multiscale(int json) {
  gm_multiscale_result r;
  gm_error err = {{0}};
  if (gm_experiment_multiscale(&r, &err) != GM_OK) {
    cli_error(CMD, "multiscale: %s", err.message);
    return CLI_EXIT_FAILURE;
  }
  if (json) return multiscale_json(&r);
  printf("multiscale VI (seed 001 5.7.2): stiff spring pendulum m = 1, g = 9.81, k = 1e4, l = 1,\n"
         "  theta0 = 1 at rest; fast period 2 pi/100 = 0.063; errors at T against\n"
         "  vi-galerkin-gauss-2 with h = 1e-4 (4th order, h omega = 0.01)\n");
  printf("  %5s %6s %7s | %-21s | %-21s | %-21s | %-21s | %s\n", "T", "h", "h omega",
         "msvi (additive)", "vi-midpoint (polar)", "imex (Cartesian)", "msvi, product on l+a",
         "msvi, product on a (seed)");
  for (size_t i = 0; i < GM_MULTISCALE_T; ++i)
    for (size_t j = 0; j < GM_MULTISCALE_H; ++j) {
      char c[5][64];
      for (int k = 0; k < 5; ++k)
        multiscale_cell(c[k], sizeof c[k], &r.cells[i][j][k], r.steps[i][j], k == 4);
      printf("  %5g %6g %7g | %-21s | %-21s | %-21s | %-21s | %s\n", r.t_end[i], r.h[j],
             100.0 * r.h[j], c[0], c[1], c[2], c[3], c[4]);
    }
  printf("MsFEM (seed 001 5.7.1): (a(x/eps) u')' = x^2, a = 10/(1 + 0.95 sin 2 pi y), eps = 0.025;\n"
         "  l-infinity nodal error (max |u| = 3.9e-3)\n  %6s %8s %12s %12s\n",
         "N", "h/eps", "MsFEM", "P1");
  for (size_t i = 0; i < GM_MULTISCALE_MSFEM; ++i)
    printf("  %6zu %8.2f %12s %12.3e\n", r.msfem_n[i], 1.0 / (0.025 * (double)r.msfem_n[i]),
           "(reference)", r.msfem_p1_error[i]);
  printf("  (the MsFEM nodal values agree with the closed-form solution to 6.5e-17:\n"
         "   tests/unit/test_msfem.c; here they are the reference for P1)\n");
  return CLI_EXIT_OK;
}

static int oscillatory_main(int argc, char **argv) {
  const char *dir = "oscillatory-output";
  size_t points = 900;
  int no_plot = 0, json = 0;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &dir, 0},
                          {"--points", CLI_ARG_COUNT, &points, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0}};
  const char *positional[1];
  size_t n_positional = 0;
  int rc = cli_parse(CMD, argc, argv, options, sizeof options / sizeof options[0], positional,
                     1, &n_positional);
  if (rc == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  if (n_positional != 1) {
    cli_error(CMD, "which experiment? resonance, fpu, fpu-long, work-precision, multiscale or all");
    return CLI_EXIT_USAGE;
  }
  const char *ex = positional[0];
  const int all = strcmp(ex, "all") == 0;
  if (!all && strcmp(ex, "resonance") != 0 && strcmp(ex, "fpu") != 0 &&
      strcmp(ex, "fpu-long") != 0 && strcmp(ex, "work-precision") != 0 &&
      strcmp(ex, "step-scan") != 0 &&
      strcmp(ex, "multiscale") != 0) {
    cli_error(CMD,
              "unknown experiment '%s': resonance, fpu, fpu-long, work-precision, multiscale or "
              "all",
              ex);
    return CLI_EXIT_USAGE;
  }
  if (points == 0 || points > GM_RESONANCE_MAX_POINTS) {
    cli_error(CMD,
              "--points %zu: must be in [1, %d] (each point is two runs of 10^4 steps, about "
              "17 ms; %d points take about 6 minutes)",
              points, GM_RESONANCE_MAX_POINTS, GM_RESONANCE_MAX_POINTS);
    return CLI_EXIT_USAGE;
  }
  if (json && all) {
    cli_error(CMD, "--json prints one object for one experiment: name it instead of 'all'");
    return CLI_EXIT_USAGE;
  }
  if (options[1].seen && !all && strcmp(ex, "resonance") != 0) {
    cli_error(CMD, "--points is an option of 'resonance' (and 'all'), not of '%s'", ex);
    return CLI_EXIT_USAGE;
  }
  if (!no_plot && !cli_gnuplot_available()) {
    cli_error(CMD, "gnuplot is not installed (or not on PATH): use --no-plot for data only");
    return CLI_EXIT_USAGE;
  }
  if ((rc = make_directory(dir)) != CLI_EXIT_OK) return rc;
  if (all || strcmp(ex, "resonance") == 0) rc = experiment_resonance(dir, points, !no_plot, json);
  if (rc == CLI_EXIT_OK && (all || strcmp(ex, "fpu") == 0)) rc = experiment_fpu(dir, !no_plot, 0, json);
  if (rc == CLI_EXIT_OK && (all || strcmp(ex, "fpu-long") == 0))
    rc = experiment_fpu(dir, !no_plot, 1, json);
  if (rc == CLI_EXIT_OK && (all || strcmp(ex, "work-precision") == 0))
    rc = experiment_work_precision(dir, !no_plot, json);
  if (rc == CLI_EXIT_OK && (all || strcmp(ex, "multiscale") == 0)) rc = experiment_multiscale(json);
  if (rc == CLI_EXIT_OK && strcmp(ex, "step-scan") == 0) rc = experiment_step_scan(dir, json);
  return rc;
}

const cli_command cli_oscillatory_command = {
    CMD, "experiments with oscillatory problems: resonance, FPU, work-precision", usage,
    oscillatory_main};
