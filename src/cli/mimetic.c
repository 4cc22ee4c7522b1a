/* geomint mimetic EXPERIMENT: the four numerical tests of seed 003 (Palha & Gerritsma, §6),
 * with MCI and MGI of degree 2, RK4, explicit and symplectic Euler: data, figures, a table. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"

static const char usage[] =
    "usage: geomint mimetic EXPERIMENT [--out DIR] [--no-plot]\n\n"
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
    "  --no-plot   write the data only\n";

#define N_METHODS 5
static const char *const method_names[N_METHODS] = {
    "mimetic-canonical-2", "mimetic-galerkin-2", "rk4", "euler", "symplectic-euler-a"};
static const char *const method_titles[N_METHODS] = {"MCI (p=2)", "MGI (p=2)", "RK4",
                                                     "explicit Euler", "symplectic Euler"};
/* the methods of the convergence figure: MCI, MGI, RK4 */
#define N_CONVERGENCE 3
#define CONVERGENCE_LEVELS 6

typedef struct experiment {
  const char *name, *model, *setting; /* setting: one name=value, or NULL */
  double dt_phase, dt_invariant, t_end;
  size_t x, y;                        /* state components of the phase portrait */
  const char *xlabel, *ylabel;
  const char *invariant;              /* NULL: the energy; else the invariant's name */
  const char *invariant_label;
  double conv_dt0, conv_t_end;        /* convergence: steps dt0, dt0/2, ... to conv_t_end */
} experiment;

static const experiment experiments[] = {
    {"circular", "harmonic", "q1=2", 1.0, 1.0, 100.0, 0, 1, "q", "p", NULL,
     "|H - H0| (H = R^2/2)", 0.5, 10.0},
    {"lotka-volterra", "lotka-volterra", NULL, 0.3, 0.3, 60.0, 0, 1, "u (prey)", "v (predator)",
     "invariant", "|V - V0|, V = ln u - u + 2 ln v - v", 0.3, 5.0},
    {"pendulum", "pendulum", "k=10", 0.4, 0.1, 20.0, 0, 1, "q", "p", NULL, "|H - H0|", 0.2, 1.0},
    {"kepler", "kepler", "e=0.6", 0.1, 0.1, 100.0, 0, 1, "q1", "q2", NULL, "|H - H0|", 0.1, 1.0},
};
#define N_EXPERIMENTS (sizeof experiments / sizeof experiments[0])

static int make_directory(const char *dir) {
  if (mkdir(dir, 0777) == 0 || errno == EEXIST) {
    struct stat sb;
    if (stat(dir, &sb) == 0 && S_ISDIR(sb.st_mode)) return CLI_EXIT_OK;
  }
  cli_error("mimetic", "cannot create the directory '%s': %s", dir, strerror(errno));
  return CLI_EXIT_FAILURE;
}

/* The monitored invariant of the experiment at y. */
static double invariant_value(const experiment *ex, const gm_problem *pb, const double *y) {
  if (ex->invariant == NULL) return gm_problem_energy(pb, y);
  size_t k = cli_find_invariant(pb, ex->invariant);
  return k == (size_t)-1 ? NAN : pb->invariants[k].value(pb->ctx, y);
}

typedef struct trace {
  const experiment *ex;
  const gm_problem *pb;
  FILE *csv;
  double i0, max_error;
  size_t n;
} trace;

static int trace_observe(void *ctx, size_t step, double t, const double *y) {
  (void)step;
  trace *tr = ctx;
  double e = fabs(invariant_value(tr->ex, tr->pb, y) - tr->i0);
  if (!(e <= tr->max_error)) tr->max_error = isfinite(e) ? fmax(tr->max_error, e) : INFINITY;
  fprintf(tr->csv, "%.17g", t);
  for (size_t i = 0; i < tr->n; ++i) fprintf(tr->csv, ",%.17g", y[i]);
  fprintf(tr->csv, ",%.17g\n", e);
  return 0;
}

/* One run of a method; writes the CSV. Returns 0 when it ran to the end, 1 when the method
 * failed on the way (the CSV holds the steps before), -1 when it does not apply. */
static int run_one(const experiment *ex, const gm_model *model, const gm_method *m, double dt,
                   const char *csv_path, double *max_error, char *why, size_t cap) {
  const gm_problem *pb = gm_model_problem(model);
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  why[0] = '\0';
  if (gm_integrator_create(m, pb, &it, &err) != GM_OK) {
    snprintf(why, cap, "%s", err.message);
    return -1;
  }
  size_t n = gm_model_state_size(model);
  double t0, y0[16];
  gm_model_initial_state(model, &t0, y0);
  FILE *csv = fopen(csv_path, "w");
  if (csv == NULL) {
    snprintf(why, cap, "cannot write %.200s: %s", csv_path, strerror(errno));
    gm_integrator_free(it);
    return 1;
  }
  fprintf(csv, "t");
  for (size_t i = 0; i < n; ++i) fprintf(csv, ",y%zu", i + 1);
  fprintf(csv, ",invariant_error\n");
  trace tr = {ex, pb, csv, invariant_value(ex, pb, y0), 0.0, n};
  gm_integrator_set_state(it, t0, y0);
  gm_integrator_add_observer(it, trace_observe, &tr, 1);
  size_t steps = (size_t)llround(ex->t_end / dt);
  gm_status st = gm_integrator_run(it, steps, dt);
  if (st != GM_OK) snprintf(why, cap, "stopped: %s", gm_integrator_errmsg(it));
  fclose(csv);
  gm_integrator_free(it);
  *max_error = tr.max_error;
  return st == GM_OK ? 0 : 1;
}

/* Convergence: the state error at conv_t_end (exact solution or reference run) and the largest
 * invariant error over the run, for steps dt0/2^k. */
typedef struct convergence {
  double dts[CONVERGENCE_LEVELS];
  double state[N_CONVERGENCE][CONVERGENCE_LEVELS], invariant[N_CONVERGENCE][CONVERGENCE_LEVELS];
  double order[N_CONVERGENCE], invariant_order[N_CONVERGENCE];
} convergence;

static double slope(const double *x, const double *y, size_t n) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  size_t m = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!(y[i] > 1e-13 && isfinite(y[i]))) continue; /* above round-off only */
    double a = log(x[i]), b = log(y[i]);
    sx += a;
    sy += b;
    sxx += a * a;
    sxy += a * b;
    ++m;
  }
  return m >= 2 ? ((double)m * sxy - sx * sy) / ((double)m * sxx - sx * sx) : NAN;
}

static int measure_convergence(const experiment *ex, const gm_model *model, convergence *c) {
  const gm_problem *pb = gm_model_problem(model);
  double t0, y0[16];
  gm_model_initial_state(model, &t0, y0);
  for (size_t k = 0; k < N_CONVERGENCE; ++k) {
    const gm_scheme sc = {gm_method_find(method_names[k]), NULL, GM_SOLVER_DEFAULT, 0};
    gm_order_result r;
    gm_error err = {{0}};
    if (gm_order_measure(&sc, pb, t0, y0, t0 + ex->conv_t_end, ex->conv_dt0, CONVERGENCE_LEVELS,
                         2.0, gm_method_find("gauss-6"), &r, &err) != GM_OK) {
      cli_error("mimetic", "%s: convergence of %s: %s", ex->name, method_names[k], err.message);
      return CLI_EXIT_FAILURE;
    }
    for (size_t l = 0; l < CONVERGENCE_LEVELS; ++l) {
      c->dts[l] = r.dts[l];
      c->state[k][l] = r.errors[l];
      /* the invariant error: its largest value over the run at that step */
      gm_integrator *it = NULL;
      if (gm_integrator_create(sc.method, pb, &it, &err) != GM_OK) return CLI_EXIT_FAILURE;
      gm_integrator_set_state(it, t0, y0);
      double i0 = invariant_value(ex, pb, y0), worst = 0.0;
      size_t steps = (size_t)llround(ex->conv_t_end / r.dts[l]);
      for (size_t s = 0; s < steps; ++s) {
        if (gm_integrator_step(it, r.dts[l]) != GM_OK) {
          worst = NAN;
          break;
        }
        worst = fmax(worst, fabs(invariant_value(ex, pb, gm_integrator_state(it)) - i0));
      }
      c->invariant[k][l] = worst;
      gm_integrator_free(it);
    }
    c->order[k] = slope(c->dts, c->state[k], CONVERGENCE_LEVELS);
    c->invariant_order[k] = slope(c->dts, c->invariant[k], CONVERGENCE_LEVELS);
  }
  return CLI_EXIT_OK;
}

static int write_convergence_csv(const char *path, const convergence *c) {
  FILE *f = fopen(path, "w");
  if (f == NULL) {
    cli_error("mimetic", "cannot write %s: %s", path, strerror(errno));
    return CLI_EXIT_FAILURE;
  }
  fprintf(f, "dt");
  for (size_t k = 0; k < N_CONVERGENCE; ++k)
    fprintf(f, ",%s_state_error,%s_invariant_error", method_names[k], method_names[k]);
  fprintf(f, "\n");
  for (size_t l = 0; l < CONVERGENCE_LEVELS; ++l) {
    fprintf(f, "%.17g", c->dts[l]);
    for (size_t k = 0; k < N_CONVERGENCE; ++k)
      fprintf(f, ",%.17g,%.17g", c->state[k][l], c->invariant[k][l]);
    fprintf(f, "\n");
  }
  fclose(f);
  return CLI_EXIT_OK;
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

static int run_experiment(const experiment *ex, const char *dir, int plot) {
  gm_model *model = NULL;
  cli_settings settings = {ex->setting != NULL ? 1u : 0u, {ex->setting}};
  int rc = cli_open_model("mimetic", ex->model, &settings, &model);
  if (rc != CLI_EXIT_OK) return rc;
  static char csv[2 * N_METHODS][4096];
  int ran[2 * N_METHODS + 1] = {0};
  double errors[2 * N_METHODS];
  ran[2 * N_METHODS] = (int)gm_model_state_size(model); /* the CSV column of the error */
  printf("%s (seed 003 section 6): %s%s%s\n", ex->name, ex->model, ex->setting ? ", " : "",
         ex->setting ? ex->setting : "");
  printf("  %-20s %8s %16s   %s\n", "method", "dt", "max |dI|", "note");
  for (size_t pass = 0; pass < 2; ++pass) {
    double dt = pass == 0 ? ex->dt_phase : ex->dt_invariant;
    if (pass == 1 && dt == ex->dt_phase) { /* one run serves both figures */
      for (size_t k = 0; k < N_METHODS; ++k) {
        memcpy(csv[N_METHODS + k], csv[k], sizeof csv[k]);
        ran[N_METHODS + k] = ran[k];
      }
      break;
    }
    for (size_t k = 0; k < N_METHODS; ++k) {
      char why[GM_ERRMSG_SIZE + 32];
      snprintf(csv[pass * N_METHODS + k], sizeof csv[0], "%s/%s-%s-%g.csv", dir, ex->name,
               method_names[k], dt);
      int r = run_one(ex, model, gm_method_find(method_names[k]), dt, csv[pass * N_METHODS + k],
                      &errors[pass * N_METHODS + k], why, sizeof why);
      ran[pass * N_METHODS + k] = r >= 0;
      if (r < 0)
        printf("  %-20s %8g %16s   not applicable: %s\n", method_names[k], dt, "-", why);
      else
        printf("  %-20s %8g %16.3e   %s\n", method_names[k], dt, errors[pass * N_METHODS + k],
               why);
    }
  }
  convergence c;
  char conv_csv[4096];
  snprintf(conv_csv, sizeof conv_csv, "%s/%s-convergence.csv", dir, ex->name);
  if ((rc = measure_convergence(ex, model, &c)) == CLI_EXIT_OK)
    rc = write_convergence_csv(conv_csv, &c);
  if (rc == CLI_EXIT_OK) {
    printf("  convergence to t = %g, dt = %g .. %g: measured orders (state, invariant)\n",
           ex->conv_t_end, c.dts[0], c.dts[CONVERGENCE_LEVELS - 1]);
    for (size_t k = 0; k < N_CONVERGENCE; ++k) {
      /* an invariant kept to round-off at every step has no order to fit */
      char inv[32], state[32];
      int kept = 1;
      for (size_t l = 0; l < CONVERGENCE_LEVELS; ++l) kept &= c.invariant[k][l] <= 1e-13;
      if (isfinite(c.invariant_order[k]))
        snprintf(inv, sizeof inv, "%8.2f", c.invariant_order[k]);
      else
        snprintf(inv, sizeof inv, "%s", kept ? "round-off" : "   failed");
      if (isfinite(c.order[k]))
        snprintf(state, sizeof state, "%8.2f", c.order[k]);
      else
        snprintf(state, sizeof state, "%s", "   failed");
      printf("  %-20s %s %s\n", method_names[k], state, inv);
    }
  }
  if (rc == CLI_EXIT_OK && plot) {
    rc = draw(dir, ex, (const char(*)[4096])csv, ran, c.dts);
    if (rc == CLI_EXIT_OK)
      printf("  figures: %s/%s-{phase,invariant,convergence}.png\n", dir, ex->name);
  }
  gm_model_free(model);
  return rc;
}

static int mimetic_main(int argc, char **argv) {
  const char *out = "mimetic-output", *positional[1] = {NULL};
  int no_plot = 0;
  size_t n_positional = 0;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &out, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0}};
  int rc = cli_parse("mimetic", argc, argv, options, 2, positional, 1, &n_positional);
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
    if (strcmp(positional[0], experiments[k].name) == 0) chosen = k;
  if (!all && chosen == N_EXPERIMENTS) {
    cli_error("mimetic", "unknown experiment '%s': circular, lotka-volterra, pendulum, kepler "
              "or all", positional[0]);
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
    if (all || k == chosen) rc = run_experiment(&experiments[k], out, !no_plot);
  return rc;
}

const cli_command cli_mimetic_command = {
    "mimetic", "seed 003's tests: MCI, MGI, RK4, Euler on four problems, with figures", usage,
    mimetic_main};
