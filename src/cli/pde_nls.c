/* geomint pde nls-long: the NLS two-soliton collision over many periods, the multisymplectic
 * Preissmann box against box-sdirk2 (the same box in space, a non-symplectic order-2 SDIRK in
 * time), with the relative errors of energy, momentum and charge against t and one figure. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"

#define NLS_L 20.0
#define NLS_PI 3.14159265358979323846

/* two solitons ψ_k = a_k sech(a_k (x − x_k)) exp(i c_k x / 2); c_k = ±π/5 makes exp(icx/2)
 * periodic on [−20, 20); the pair meets every 40/(2π/5) ≈ 31.8 time units */
static const double sol_a[2] = {1.0, 0.8}, sol_c[2] = {NLS_PI / 5.0, -NLS_PI / 5.0},
                    sol_x[2] = {-10.0, 10.0};
/* the period counted: the phase period 2π/(a² − c²/4) of the larger soliton */
#define NLS_PERIOD (2.0 * NLS_PI / (1.0 - NLS_PI * NLS_PI / 100.0))

static void two_soliton(double x, double *s) {
  for (int a = 0; a < 4; a++) s[a] = 0.0;
  for (int k = 0; k < 2; k++) {
    /* the nearest periodic image */
    double y = x - sol_x[k];
    y -= 2.0 * NLS_L * floor((y + NLS_L) / (2.0 * NLS_L));
    double A = sol_a[k], amp = A / cosh(A * y), dam = -A * tanh(A * y) * amp;
    double th = sol_c[k] * x / 2.0, c = cos(th), sn = sin(th), w = sol_c[k] / 2.0;
    s[0] += amp * c;
    s[1] += amp * sn;
    s[2] += dam * c - amp * sn * w;
    s[3] += dam * sn + amp * c * w;
  }
}

typedef struct nls_long_result {
  double e_first, e_last, p_first, p_last, q_first, q_last; /* max errors, first/last tenth */
} nls_long_result;

static int nls_long_one(const char *scheme_name, size_t n, double dt, size_t steps,
                        size_t every, const char *path, nls_long_result *res) {
  const gm_pde_scheme *scheme = NULL;
  gm_pde_scheme_find(scheme_name, &scheme);
  gm_pde_equation eq = gm_pde_nls();
  double h = 2.0 * NLS_L / (double)n;
  gm_pde_grid g = {n, h, -NLS_L, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = dt;
  double *s0 = calloc(4 * n, sizeof *s0);
  if (s0 == NULL) {
    cli_error("pde nls-long", "out of memory");
    return CLI_EXIT_FAILURE;
  }
  for (size_t i = 0; i < n; i++) two_soliton(-NLS_L + (double)i * h, s0 + 4 * i);
  gm_pde *p = NULL;
  gm_error err = {{0}};
  gm_status st = gm_pde_create(&g, &eq, scheme, &o, s0, &p, &err);
  free(s0);
  if (st != GM_OK) {
    cli_error("pde nls-long", "%s", err.message);
    return st == GM_ENOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
  }
  FILE *f = fopen(path, "w");
  if (f == NULL) {
    cli_error("pde nls-long", "cannot write '%s': %s", path, strerror(errno));
    gm_pde_free(p);
    return CLI_EXIT_FAILURE;
  }
  fprintf(f, "# %s: t/period |dE/E| |dP/P| |dN/N| (n = %zu, dt = %g)\n", scheme_name, n, dt);
  double e0 = gm_pde_cell_energy(p), p0 = gm_pde_cell_momentum(p), q0 = gm_pde_norm(p);
  memset(res, 0, sizeof *res);
  int rc = CLI_EXIT_OK;
  for (size_t k = 0; k < steps; k += every) {
    size_t m = steps - k < every ? steps - k : every;
    if (gm_pde_advance(p, m, &err) != GM_OK) {
      cli_error("pde nls-long", "%s: %s", scheme_name, err.message);
      rc = CLI_EXIT_FAILURE;
      break;
    }
    double de = fabs(gm_pde_cell_energy(p) - e0) / fabs(e0);
    double dp = fabs(gm_pde_cell_momentum(p) - p0) / fabs(p0);
    double dq = fabs(gm_pde_norm(p) - q0) / fabs(q0);
    fprintf(f, "%.6f %.6e %.6e %.6e\n", gm_pde_time(p) / NLS_PERIOD, de, dp, dq);
    size_t done = k + m;
    if (done <= steps / 10) {
      res->e_first = fmax(res->e_first, de);
      res->p_first = fmax(res->p_first, dp);
      res->q_first = fmax(res->q_first, dq);
    }
    if (done > steps - steps / 10) {
      res->e_last = fmax(res->e_last, de);
      res->p_last = fmax(res->p_last, dp);
      res->q_last = fmax(res->q_last, dq);
    }
  }
  fclose(f);
  gm_pde_free(p);
  return rc;
}

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

int cli_pde_nls_long(int argc, char **argv) {
  const char *dir = "pde-output";
  size_t n = 128, every = 0, n_pos = 0;
  double periods = 1e4, dt = 0.1;
  int no_plot = 0, plot_only = 0;
  const char *only = NULL;
  cli_option options[] = {{"--only", CLI_ARG_STRING, &only, 0},
                          {"--plot-only", CLI_ARG_FLAG, &plot_only, 0},
                          {"--periods", CLI_ARG_DOUBLE, &periods, 0},
                          {"--n", CLI_ARG_COUNT, &n, 0},
                          {"--dt", CLI_ARG_DOUBLE, &dt, 0},
                          {"--every", CLI_ARG_COUNT, &every, 0},
                          {"--out", CLI_ARG_STRING, &dir, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0}};
  int rc = cli_parse("pde nls-long", argc, argv, options, 8, NULL, 0, &n_pos);
  if (rc == CLI_HELP) {
    fputs("usage: geomint pde nls-long [--periods P] [--n N] [--dt DT] [--every K] [--out DIR]\n"
          "                            [--no-plot] [--only preissmann|box-sdirk2] [--plot-only]\n"
          "(see 'geomint pde --help' and docs/pde.md)\n",
          stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  if (options[5].seen && every == 0) {
    cli_error("pde nls-long", "--every 0: rows are written every K >= 1 steps (default: the run "
              "in 2000 rows)");
    return CLI_EXIT_USAGE;
  }
  if (cli_check_positive("pde nls-long", "--dt", dt) != CLI_EXIT_OK ||
      cli_check_positive("pde nls-long", "--periods", periods) != CLI_EXIT_OK ||
      cli_check_step_count("pde nls-long", periods * NLS_PERIOD, dt) != CLI_EXIT_OK)
    return CLI_EXIT_USAGE;
  if (n < 16 || n > 100000) {
    cli_error("pde nls-long", "--n must lie in 16..100000 (got %zu)", n);
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
  if (only != NULL && strcmp(only, "preissmann") != 0 && strcmp(only, "box-sdirk2") != 0) {
    cli_error("pde nls-long", "--only takes preissmann or box-sdirk2 (got '%s')", only);
    return CLI_EXIT_USAGE;
  }
  if (plot_only && no_plot) {
    cli_error("pde nls-long", "--plot-only and --no-plot exclude each other");
    return CLI_EXIT_USAGE;
  }
  size_t steps = (size_t)llround(periods * NLS_PERIOD / dt);
  if (steps < 10) steps = 10;
  if (every == 0) every = steps / 2000 > 0 ? steps / 2000 : 1;
  if (!plot_only)
    printf("NLS two-soliton collision (a = 1, 0.8; c = +-pi/5) on [-20, 20), n = %zu, dt = %g, "
         "%g periods (%.4g time units, %zu steps)\n",
         n, dt, periods, (double)steps * dt, steps);
  const char *names[2] = {"preissmann", "box-sdirk2"};
  for (int k = 0; k < 2 && !plot_only; k++) {
    if (only != NULL && strcmp(only, names[k]) != 0) continue;
    char path[4200];
    snprintf(path, sizeof path, "%s/nls-long-%s.dat", dir, names[k]);
    nls_long_result r;
    if ((rc = nls_long_one(names[k], n, dt, steps, every, path, &r)) != CLI_EXIT_OK) return rc;
    printf("  %-10s max relative error, first / last tenth: energy %.3e / %.3e, momentum "
           "%.3e / %.3e, charge %.3e / %.3e\n",
           names[k], r.e_first, r.e_last, r.p_first, r.p_last, r.q_first, r.q_last);
  }
  if (no_plot) return CLI_EXIT_OK;
  char png[4200];
  snprintf(png, sizeof png, "%s/nls-long.png", dir);
  rc = cli_plot_custom("pde nls-long", png, "NLS two-soliton collision: Preissmann box vs box-sdirk2",
                       nls_plot_body, dir);
  if (rc == CLI_EXIT_OK) printf("  figure: %s\n", png);
  return rc;
}
