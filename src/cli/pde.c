/* geomint pde: multisymplectic PDE integrators (src/pde). `run` (pde_run.c) integrates one
 * equation from its exact solution; `b10` is seed 004's stability experiment
 * (Figs. 11–13): LF/EC/MS at Δt = Δx and EC/MS at Δt = 2Δx, with one figure. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "cli/pde_spectral.h"

static const char usage[] =
    "usage: geomint pde run sine-gordon|kdv|nls [--scheme NAME] [--n N] [--dt DT] [--T T]\n"
    "                       [--dirichlet] [--out FILE.csv] [--vtk FILE.vti] ... (pde run --help)\n"
    "       geomint pde b10 [--out DIR] [--no-plot]\n"
    "       geomint pde nls-long [--periods P] [--n N] [--dt DT] [--every K] [--out DIR]\n"
    "                            [--no-plot] [--only preissmann|box-sdirk2] [--plot-only]\n"
    "\n"
    "Sine-Gordon u_tt - u_xx + sin u = 0 on [-20, 20) periodic, started from the standing\n"
    "breather u = 4 atan((k/w) sin(w t) / cosh(k x)), k = sqrt(1 - w^2), at t = 0 (u = 0,\n"
    "u_t = 4k sech(kx)); default w = 0.5.\n"
    "run: one scheme from the exact solution (breather, KdV or NLS soliton); see pde run --help.\n"
    "b10: N = 200 (dx = 0.2): LF, EC, MS with dt = dx up to t = 500, EC and MS with dt = 2 dx\n"
    "     up to t = 100; a run that leaves |u| <= 100 or fails stops there. Writes\n"
    "     DIR/b10-*.dat and draws DIR/b10.png (running max of max|u| against t).\n"
    "nls-long: NLS two-soliton collision (a = 1, 0.8, c = +-pi/5, [-20, 20) periodic) over P\n"
    "     phase periods 2 pi/(1 - pi^2/100) of the larger soliton (default 1e4; N 128, dt 0.1):\n"
    "     preissmann (multisymplectic) against box-sdirk2 (same box in space, SDIRK2 in time,\n"
    "     not symplectic); writes DIR/nls-long-*.dat (periods, |dE/E|, |dP/P|, |dN/N| every K\n"
    "     steps) and DIR/nls-long.png. --only runs one scheme; --plot-only draws the figure\n"
    "     from the .dat files already in DIR (two --only runs in parallel, then the plot).\n";

#define L_HALF 20.0

static double *breather_data(size_t n, double omega) {
  double h = 2.0 * L_HALF / (double)n, k = sqrt(1.0 - omega * omega);
  double *s = calloc(3 * n, sizeof *s);
  if (s == NULL) return NULL;
  for (size_t i = 0; i < n; i++) s[3 * i + 1] = 4.0 * k / cosh(k * (-L_HALF + (double)i * h));
  return s;
}

static int make_solver(const char *cmd, const char *scheme_name, size_t n, double dt,
                       double omega, gm_pde **out) {
  const gm_pde_scheme *scheme = NULL;
  if (gm_pde_scheme_find(scheme_name, &scheme) != GM_OK) {
    cli_error(cmd, "unknown scheme '%s': preissmann, euler-box, lf, ec or ms", scheme_name);
    return CLI_EXIT_USAGE;
  }
  gm_pde_equation eq = gm_pde_sine_gordon();
  gm_pde_grid g = {n, 2.0 * L_HALF / (double)n, -L_HALF, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = dt;
  double *s0 = breather_data(n, omega);
  if (s0 == NULL) {
    cli_error(cmd, "out of memory");
    return CLI_EXIT_FAILURE;
  }
  gm_error err = {{0}};
  gm_status st = gm_pde_create(&g, &eq, scheme, &o, s0, out, &err);
  free(s0);
  if (st != GM_OK) {
    cli_error(cmd, "%s", err.message);
    return st == GM_ENOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
  }
  return CLI_EXIT_OK;
}

/* ---- B10 --------------------------------------------------------------------------------- */
typedef struct b10_run {
  const char *scheme;
  double ratio, T; /* Δt/Δx, end time */
} b10_run;

static const b10_run b10_runs[] = {{"lf", 1.0, 500.0}, {"ec", 1.0, 500.0}, {"ms", 1.0, 500.0},
                                   {"ec", 2.0, 100.0}, {"ms", 2.0, 100.0}};
#define N_B10 (sizeof b10_runs / sizeof b10_runs[0])

static double max_abs_u(const gm_pde *p) {
  const double *s = gm_pde_state(p);
  double m = 0.0;
  for (size_t i = 0; i < gm_pde_n(p); i++) m = fmax(m, fabs(s[3 * i]));
  return m;
}

static int b10_one(const b10_run *r, const char *dir, char *summary, size_t cap) {
  size_t n = 200;
  double h = 2.0 * L_HALF / (double)n, dt = r->ratio * h;
  gm_pde *p = NULL;
  int rc = make_solver("pde b10", r->scheme, n, dt, 0.5, &p);
  if (rc != CLI_EXIT_OK) return rc;
  char path[4200];
  snprintf(path, sizeof path, "%s/b10-%s-%g.dat", dir, r->scheme, r->ratio);
  FILE *f = fopen(path, "w");
  if (f == NULL) {
    cli_error("pde b10", "cannot write '%s': %s", path, strerror(errno));
    gm_pde_free(p);
    return CLI_EXIT_FAILURE;
  }
  fprintf(f, "# t max|u| relative-energy-change running-max|u| (%s, dt/dx = %g)\n", r->scheme,
          r->ratio);
  double e0 = gm_pde_energy(p), emax = 0.0, run_max = 0.0;
  size_t steps = (size_t)llround(r->T / dt), every = r->ratio > 1.0 ? 1 : 5;
  const char *outcome = NULL;
  gm_error err = {{0}};
  size_t k;
  for (k = 0; k < steps; k++) {
    gm_status st = gm_pde_advance(p, 1, &err);
    if (st != GM_OK) {
      outcome = "failed";
      break;
    }
    double m = max_abs_u(p), de = fabs(gm_pde_energy(p) - e0) / fabs(e0);
    run_max = fmax(run_max, m);
    if ((k + 1) % every == 0 || m > 100.0)
      fprintf(f, "%g %.6e %.6e %.6e\n", gm_pde_time(p), m, de, run_max);
    if (m > 100.0) {
      outcome = "unbounded";
      break;
    }
    emax = fmax(emax, de);
  }
  fclose(f);
  if (outcome == NULL)
    snprintf(summary, cap, "%-3s dt/dx = %g: bounded to t = %g (max|u| %.3f, max relative "
             "energy change %.2e)", r->scheme, r->ratio, gm_pde_time(p), max_abs_u(p), emax);
  else if (strcmp(outcome, "failed") == 0)
    snprintf(summary, cap, "%-3s dt/dx = %g: fails at step %zu (t = %g): %.300s", r->scheme,
             r->ratio, k + 1, (double)(k + 1) * dt, err.message);
  else
    snprintf(summary, cap, "%-3s dt/dx = %g: |u| > 100 at step %zu (t = %g)", r->scheme,
             r->ratio, k + 1, gm_pde_time(p));
  gm_pde_free(p);
  return CLI_EXIT_OK;
}

static int b10_plot(const char *dir) {
  char script[4200], cmd[8600];
  snprintf(script, sizeof script, "%s/b10.gp", dir);
  FILE *g = fopen(script, "w");
  if (g == NULL) {
    cli_error("pde b10", "cannot write '%s': %s", script, strerror(errno));
    return CLI_EXIT_FAILURE;
  }
  fprintf(g,
          "set terminal pngcairo size 1200,500 font ',10'\n"
          "set output '%s/b10.png'\n"
          "set multiplot layout 1,2 title 'B10: sine-Gordon breather (w = 0.5), [-20,20) "
          "periodic, N = 200, dx = 0.2'\n"
          "set logscale y\nset xlabel 't'\nset ylabel 'max |u| over x and over times <= t'\n"
          "set key top left\n"
          "set yrange [1:1e3]\n"
          "set title 'dt = dx'\n"
          "plot '%s/b10-lf-1.dat' u 1:4 w l lw 2 lc 1 t 'LF', '%s/b10-ec-1.dat' u 1:4 w l lw 2 "
          "lc 2 t 'EC', '%s/b10-ms-1.dat' u 1:4 w l lw 2 dt 2 lc 3 t 'MS'\n"
          "set title 'dt = 2 dx (LF refused: CFL)'\n"
          "plot '%s/b10-ec-2.dat' u 1:4 w lp lw 2 lc 2 t 'EC', '%s/b10-ms-2.dat' u 1:4 w l lw 2 "
          "dt 2 lc 3 t 'MS'\n"
          "unset multiplot\n",
          dir, dir, dir, dir, dir, dir);
  fclose(g);
  snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", script);
  if (system(cmd) != 0) {
    cli_error("pde b10", "gnuplot failed on %s", script);
    return CLI_EXIT_FAILURE;
  }
  printf("  figure: %s/b10.png\n", dir);
  return CLI_EXIT_OK;
}

static int pde_b10(int argc, char **argv) {
  const char *dir = "pde-output";
  int no_plot = 0;
  size_t n_pos = 0;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &dir, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0}};
  int rc = cli_parse("pde b10", argc, argv, options, 2, NULL, 0, &n_pos);
  if (rc == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  if (strchr(dir, '\'') != NULL) {
    cli_error("pde b10", "--out: the directory name may not contain a quote");
    return CLI_EXIT_USAGE;
  }
  if (!no_plot && !cli_gnuplot_available()) {
    cli_error("pde b10", "gnuplot is not installed (or not on PATH): use --no-plot");
    return CLI_EXIT_FAILURE;
  }
  if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
    cli_error("pde b10", "cannot create the directory '%s': %s", dir, strerror(errno));
    return CLI_EXIT_FAILURE;
  }
  printf("B10 (seed 004 Figs. 11-13): sine-Gordon breather w = 0.5 on [-20, 20), N = 200\n");
  for (size_t k = 0; k < N_B10; k++) {
    char summary[512];
    if ((rc = b10_one(&b10_runs[k], dir, summary, sizeof summary)) != CLI_EXIT_OK) return rc;
    printf("  %s\n", summary);
  }
  return no_plot ? CLI_EXIT_OK : b10_plot(dir);
}

int cli_pde_nls_long(int argc, char **argv); /* pde_nls.c */
int cli_pde_run(int argc, char **argv);      /* pde_run.c */
int cli_pde_invariant(int argc, char **argv); /* pde_invariant.c */
extern const char cli_pde_invariant_usage[];
int cli_pde_moving_mesh(int argc, char **argv); /* pde_moving_mesh.c */
extern const char cli_pde_moving_mesh_usage[];

static int pde_main(int argc, char **argv) {
  if (argc >= 1 && strcmp(argv[0], "nls-long") == 0) {
    for (int k = 1; k < argc; k++)
      if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
        fputs(usage, stdout);
        return CLI_EXIT_OK;
      }
    return cli_pde_nls_long(argc - 1, argv + 1);
  }
  if (argc >= 1 && strcmp(argv[0], "run") == 0) return cli_pde_run(argc - 1, argv + 1);
  if (argc >= 1 && strcmp(argv[0], "b10") == 0) return pde_b10(argc - 1, argv + 1);
  if (argc >= 1 && strcmp(argv[0], "invariant") == 0)
    return cli_pde_invariant(argc - 1, argv + 1);
  if (argc >= 1 && strcmp(argv[0], "moving-mesh") == 0)
    return cli_pde_moving_mesh(argc - 1, argv + 1);
  if (argc >= 1 && strcmp(argv[0], "schrodinger") == 0)
    return cli_pde_schrodinger(argc - 1, argv + 1);
  if (argc >= 1 && strcmp(argv[0], "spectral-star") == 0)
    return cli_pde_spectral_star(argc - 1, argv + 1);
  if (argc >= 1 && strcmp(argv[0], "tent-vi") == 0) return cli_pde_tent_vi(argc - 1, argv + 1);
  if (argc >= 1 && (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0)) {
    fputs(usage, stdout);
    fputs(cli_pde_spectral_usage, stdout);
    fputs(cli_pde_invariant_usage, stdout);
    fputs(cli_pde_moving_mesh_usage, stdout);
    return CLI_EXIT_OK;
  }
  cli_error("pde", "which subcommand? run, b10, nls-long, schrodinger, spectral-star, tent-vi or "
            "invariant, moving-mesh "
            "(see geomint pde --help)");
  return CLI_EXIT_USAGE;
}

const cli_command cli_pde_command = {
    "pde", "multisymplectic PDE schemes: sine-Gordon runs and the B10 stability experiment",
    usage, pde_main};
