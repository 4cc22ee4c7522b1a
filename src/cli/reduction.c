/* geomint reduction EXPERIMENT: the two experiments of seed 001 §2.9–2.10 (Leok, thesis (2004)) with
 * the Routh reduction API (include/geomint/reduction.h): data, figures and the measured numbers. */
#include <cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "cli/reduction_phases.h"
#include "geomint/experiments.h"

static const char usage[] =
    "usage: geomint reduction j2-satellite|double-spherical-pendulum [--out DIR] [--no-plot]\n"
    "                           [--dt H] [--t-end T] [--mu M] [--x0 LIST] [--json]\n"
    "       geomint reduction phases [--out DIR] [--no-plot]\n\n"
    "Discrete Routh reduction experiments of seed 001 (Leok, thesis 2004, sections 2.9-2.10):\n"
    "  j2-satellite     satellite about an oblate planet, J2 in {0, 0.05}, midpoint discrete\n"
    "                   Lagrangian (discrete Routh equations) at dt = 0.3 against a 6th-order\n"
    "                   RSPRK reference at dt/20; unreduced (x, y, z) and reduced (r, z) views,\n"
    "                   t = 0..150 (figures 2.2-2.5)\n"
    "  double-spherical-pendulum\n"
    "                   4th-order RSPRK against 4th-order SPRK on the classical Routhian and\n"
    "                   RK4 on the unreduced system at dt/4; dt = 0.01, t = 0..20 (figures\n"
    "                   2.7-2.9); m1 = m2 = 1, l1 = l2 = 1, g = 9.81, mu = 1; also the\n"
    "                   constrained R^3 x R^3 form (vi-galerkin-gauss-2) from the same state\n"
    "  phases           geometric phases against closed forms (seed 001 ch. 4): Foucault's\n"
    "                   pendulum and a spherical cap (Levi-Civita holonomy of the sphere),\n"
    "                   Montgomery's rigid-body phase (lgvi, lgvi-galerkin-2), a shape loop of\n"
    "                   the double spherical pendulum at mu = 0, and the tet-mesh Levi-Civita\n"
    "                   holonomy against the deficit angle; prints the table; with --out also\n"
    "                   DIR/phases-convergence.csv and .png (errors vs points / steps)\n"
    "Writes DIR/*.csv and draws DIR/*.png with gnuplot; prints the measured numbers.\n\n"
    "options:\n"
    "  --out DIR   output directory, created if missing (default reduction-output)\n"
    "  --no-plot   write the data only\n"
    "  --dt H      step size (default as above)\n"
    "  --t-end T   final time (default as above)\n"
    "  --mu M      double-spherical-pendulum: momentum level (default 1)\n"
    "  --x0 LIST   double-spherical-pendulum: r1,r2,phi,r1dot,r2dot,phidot (default\n"
    "              0.5,0.4,2,0,0,0)\n"
    "  --json      j2-satellite, double-spherical-pendulum: print one JSON object instead of\n"
    "              the text\n";

static int make_directory(const char *dir) {
  if (mkdir(dir, 0777) == 0 || errno == EEXIST) return 0;
  cli_error("reduction", "cannot create directory %s: %s", dir, strerror(errno));
  return 1;
}

/* run a gnuplot script (text) that writes png; returns an exit status */
static int plot(const char *dir, const char *png, const char *script) {
  char path[1024], cmd[1200];
  snprintf(path, sizeof path, "%s/%s", dir, png);
  if (!cli_gnuplot_available()) {
    cli_error("reduction", "cannot draw %s: gnuplot is not installed (use --no-plot)", path);
    return CLI_EXIT_FAILURE;
  }
  snprintf(cmd, sizeof cmd, "cd '%s' && exec gnuplot >/dev/null 2>&1", dir);
  FILE *g = popen(cmd, "w");
  if (g == NULL) return CLI_EXIT_FAILURE;
  fprintf(g, "set terminal pngcairo size 1000,450 font ',10'\nset output '%s'\nset datafile separator ','\nset key top right\n%s\nunset output\n",
          png, script);
  if (pclose(g) != 0) {
    cli_error("reduction", "gnuplot failed to draw %s", path);
    return CLI_EXIT_FAILURE;
  }
  FILE *chk = fopen(path, "r");
  if (chk == NULL) {
    cli_error("reduction", "gnuplot did not write %s", path);
    return CLI_EXIT_FAILURE;
  }
  fclose(chk);
  return CLI_EXIT_OK;
}

/* ---- J2 satellite (src/experiments/j2_satellite.c) ------------------------------------- */

static int j2_json(const gm_j2_result *r) {
  cJSON *j = cJSON_CreateObject();
  cJSON_AddStringToObject(j, "experiment", "j2-satellite");
  cJSON_AddNumberToObject(j, "mu", r->mu);
  cJSON_AddNumberToObject(j, "dt", r->dt);
  cJSON_AddNumberToObject(j, "t_end", r->t_end);
  cJSON_AddNumberToObject(j, "steps", (double)r->steps);
  cJSON_AddItemToObject(j, "max_discrete_vs_rsprk", cli_json_numbers(r->discrete_vs_rsprk, 2));
  cJSON_AddItemToObject(j, "node_drift_continuous", cli_json_numbers(r->node_drift_continuous, 2));
  cJSON_AddItemToObject(j, "node_drift_discrete", cli_json_numbers(r->node_drift_discrete, 2));
  cJSON_AddItemToObject(j, "continuous_j2_to_continuous_0",
                        cli_json_numbers(r->continuous_j2_to_continuous_0, 2));
  cJSON_AddItemToObject(j, "discrete_0_to_continuous_0",
                        cli_json_numbers(r->discrete_0_to_continuous_0, 2));
  cJSON_AddItemToObject(j, "discrete_j2_to_continuous_0",
                        cli_json_numbers(r->discrete_j2_to_continuous_0, 2));
  cJSON_AddItemToObject(j, "discrete_j2_to_continuous_j2",
                        cli_json_numbers(r->discrete_j2_to_continuous_j2, 2));
  cJSON_AddNumberToObject(j, "wall_s", r->wall_s);
  return cli_json_print(j);
}

static int run_j2(const char *dir, int no_plot, double h, double t_end, int json) {
  gm_j2_config config = {h, t_end};
  gm_j2_result r;
  gm_error err = {{0}};
  gm_status st = gm_experiment_j2_satellite(&config, dir, &r, &err);
  if (st != GM_OK) {
    cli_error("reduction", "%s", err.message);
    return st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  int rc = 0;
  if (json) {
    rc = j2_json(&r) != CLI_EXIT_OK;
  } else {
    printf("j2-satellite: r0 = %g, inclination %g rad, speed %g v_circ, mu = %.6f, dt = %g "
           "(reference RSPRK Gauss-3 at dt/20), t = 0..%g\n",
           r.r0, r.inclination, r.speed, r.mu, h, t_end);
    printf("  discrete Routh equations vs RSPRK (1-point Gauss) along the run: %.3g (J2 = 0), "
           "%.3g (J2 = 0.05)\n", r.discrete_vs_rsprk[0], r.discrete_vs_rsprk[1]);
    printf("  node longitude drift over the run (rad): continuous J2=0 %.4f, J2=0.05 %.4f; "
           "discrete J2=0 %.4f, J2=0.05 %.4f\n",
           r.node_drift_continuous[0], r.node_drift_continuous[1], r.node_drift_discrete[0],
           r.node_drift_discrete[1]);
    printf("  largest distance to the continuous J2=0 orbit      unreduced (x,y,z)  reduced (r,z)\n");
    printf("    continuous J2=0.05 (physical precession)          %10.4f        %10.4f\n",
           r.continuous_j2_to_continuous_0[0], r.continuous_j2_to_continuous_0[1]);
    printf("    discrete J2=0 (discretisation)                    %10.4f        %10.4f\n",
           r.discrete_0_to_continuous_0[0], r.discrete_0_to_continuous_0[1]);
    printf("    discrete J2=0.05                                  %10.4f        %10.4f\n",
           r.discrete_j2_to_continuous_0[0], r.discrete_j2_to_continuous_0[1]);
    printf("  largest distance of discrete J2=0.05 to continuous J2=0.05: %.4f (unreduced), "
           "%.4f (reduced)\n", r.discrete_j2_to_continuous_j2[0], r.discrete_j2_to_continuous_j2[1]);
  }
  for (int c = 0; c < 2 && !rc && !no_plot; ++c)
    for (int dsc = 0; dsc < 2 && !rc; ++dsc) {
      char png[64], script[2048];
      const char *j = c ? "0.05" : "0", *kind = dsc ? "discrete" : "continuous";
      const int fig = 2 + 2 * dsc + c;
      snprintf(png, sizeof png, "fig2.%d-j2-%s-%s.png", fig, j, kind);
      snprintf(script, sizeof script,
               "set multiplot layout 1,2 title 'Fig. 2.%d: %s flow, J2 = %s%s'\n"
               "set title 'unreduced (x, y, z)'\nset view 65,30\nset ticslevel 0\n"
               "set xlabel 'x'\nset ylabel 'y'\nset zlabel 'z'\n"
               "splot 'j2-%s-%s.csv' every ::1 using 5:6:3 with lines lw 0.6 lc rgb '#1f77b4' notitle\n"
               "set title 'reduced (r, z)'\nset xlabel 'r'\nset ylabel 'z'\nset size ratio -1\n"
               "plot 'j2-%s-%s.csv' every ::1 using 2:3 with lines lw 0.6 lc rgb '#d62728' notitle\n"
               "unset multiplot",
               fig, kind, j, dsc ? ", midpoint L_d, dt = 0.3" : " (reference)", j, kind, j, kind);
      rc = plot(dir, png, script);
    }
  return rc ? CLI_EXIT_FAILURE : CLI_EXIT_OK;
}

/* ---- double spherical pendulum (src/experiments/double_spherical_pendulum.c) ------------- */

static gm_dsp_config dsp_config; /* set by the options */

static int dsp_json(const gm_dsp_result *r) {
  cJSON *j = cJSON_CreateObject();
  cJSON_AddStringToObject(j, "experiment", "double-spherical-pendulum");
  cJSON_AddNumberToObject(j, "mu", r->mu);
  cJSON_AddItemToObject(j, "x0", cli_json_numbers(r->x0, 6));
  cJSON_AddNumberToObject(j, "dt", r->dt);
  cJSON_AddNumberToObject(j, "t_end", r->t_end);
  cJSON_AddNumberToObject(j, "steps", (double)r->steps);
  cJSON_AddItemToObject(j, "max_rel_energy_error_rsprk", cli_json_number(r->rsprk_max_rel_energy_error));
  cJSON_AddItemToObject(j, "max_rel_energy_error_rsprk_first_half",
                        cli_json_number(r->rsprk_max_rel_energy_error_first_half));
  cJSON_AddItemToObject(j, "max_rel_energy_error_rk4", cli_json_number(r->rk4_max_rel_energy_error));
  cJSON_AddItemToObject(j, "max_rel_energy_error_rsprk_tenths", cli_json_numbers(r->rsprk_tenths, 2));
  cJSON_AddItemToObject(j, "max_rel_energy_error_rk4_tenths", cli_json_numbers(r->rk4_tenths, 2));
  cJSON_AddItemToObject(j, "max_rel_rsprk_vs_sprk", cli_json_numbers(r->max_rel_rsprk_vs_sprk, 4));
  cJSON_AddItemToObject(j, "min_r", cli_json_number(r->min_r));
  cJSON_AddItemToObject(j, "max_rel_energy_error_constrained",
                        cli_json_number(r->constrained_max_rel_energy_error));
  cJSON_AddNumberToObject(j, "wall_s", r->wall_s);
  return cli_json_print(j);
}

static int run_dsp(const char *dir, int no_plot, double h, double t_end, int json) {
  gm_dsp_config c = dsp_config;
  c.dt = h;
  c.t_end = t_end;
  gm_dsp_result r;
  gm_error err = {{0}};
  gm_status st = gm_experiment_double_spherical_pendulum(&c, dir, &r, &err);
  if (st != GM_OK) {
    cli_error("reduction", "%s", err.message);
    return st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  int rc = 0;
  if (json) {
    if (dsp_json(&r) != CLI_EXIT_OK) return CLI_EXIT_FAILURE;
  } else {
  printf("double-spherical-pendulum: m1 = %g, m2 = %g, l1 = %g, l2 = %g, g = %g, mu = %g, "
         "(r1, r2, phi, r1', r2', phi')(0) = (%g, %g, %g, %g, %g, %g), dt = %g (RK4 dt/4), "
         "t = 0..%g\n",
         r.m1, r.m2, r.l1, r.l2, r.g, r.mu, r.x0[0], r.x0[1], r.x0[2], r.x0[3], r.x0[4], r.x0[5],
         h, t_end);
  printf("  max |E - E0|/|E0|: RSPRK (vi-galerkin-gauss-2) %.3g (first half %.3g), RK4 at dt/4 %.3g\n",
         r.rsprk_max_rel_energy_error, r.rsprk_max_rel_energy_error_first_half,
         r.rk4_max_rel_energy_error);
  printf("  max |E - E0|/|E0| in the first / last tenth of the run: RSPRK %.3g / %.3g, RK4 at dt/4 "
         "%.3g / %.3g\n",
         r.rsprk_tenths[0], r.rsprk_tenths[1], r.rk4_tenths[0], r.rk4_tenths[1]);
  printf("  max relative RSPRK - classical SPRK: r1 %.3g, r2 %.3g, phi %.3g, E %.3g\n",
         r.max_rel_rsprk_vs_sprk[0], r.max_rel_rsprk_vs_sprk[1], r.max_rel_rsprk_vs_sprk[2],
         r.max_rel_rsprk_vs_sprk[3]);
  printf("  smallest r_i along the run: %.4f\n", r.min_r);
  printf("  constrained R3 x R3 form (vi-galerkin-gauss-2 with multipliers), same state (E0 %.12g, "
         "reduced E0 %.12g): max |E - E0|/|E0| %.3g\n", r.constrained_energy0, r.energy0,
         r.constrained_max_rel_energy_error);
  }
  if (no_plot) return CLI_EXIT_OK;
  rc = plot(dir, "fig2.7-dsp-shape.png",
            "set multiplot layout 1,2 title 'Fig. 2.7: double spherical pendulum, RSPRK (4th order)'\n"
            "set xlabel 't'\nset title 'shape variables'\n"
            "plot 'dsp.csv' every ::1 using 1:2 w l t 'r1', '' every ::1 using 1:3 w l t 'r2', '' every ::1 using 1:4 w l t 'phi'\n"
            "set title 'm2 relative to m1 (x, y)'\nset xlabel 'x'\nset ylabel 'y'\nset size ratio -1\n"
            "plot 'dsp.csv' every ::1 using 5:6 w l lw 0.6 notitle\nunset multiplot");
  if (!rc)
    rc = plot(dir, "fig2.8-dsp-energy.png",
              "set multiplot layout 2,1\nset title 'Fig. 2.8: relative energy error (E - E0)/E0'\n"
              "plot 'dsp.csv' every ::1 using 1:7 w l t 'RSPRK dt', '' every ::1 using 1:9 w l t 'RK4 (unreduced) dt/4', "
              "'dsp-constrained.csv' using 1:2 w l t 'constrained R^3 x R^3, Gauss-2 dt'\n"
              "set title 'min(r1, r2): the chart (r1, r2, phi) is singular at r_i = 0'\nset xlabel 't'\nset logscale y\n"
              "plot 'dsp.csv' every ::1 using 1:17 w l lc rgb '#555555' t 'min(r1, r2)'\nunset multiplot");
  if (!rc)
    rc = plot(dir, "fig2.9-dsp-rsprk-vs-sprk.png",
              "set title 'Fig. 2.9: relative difference RSPRK vs SPRK on the classical Routhian'\n"
              "set xlabel 't'\nset logscale y\nset format y '10^{%L}'\n"
              "plot 'dsp.csv' every ::1 using 1:($10+1e-18) w l t 'r1', '' every ::1 using 1:($11+1e-18) w l t 'r2', "
              "'' every ::1 using 1:($12+1e-18) w l t 'phi', '' every ::1 using 1:($13+1e-18) w l t 'E'");
  return rc ? CLI_EXIT_FAILURE : CLI_EXIT_OK;
}

static int routh_main(int argc, char **argv) {
  const char *dir = "reduction-output";
  int no_plot = 0, json = 0;
  double dt = 0.0, t_end = 0.0;
  dsp_config = gm_dsp_defaults();
  const char *x0_text = NULL;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &dir, 0},
                          {"--mu", CLI_ARG_DOUBLE, &dsp_config.mu, 0},
                          {"--x0", CLI_ARG_STRING, &x0_text, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0},
                          {"--dt", CLI_ARG_DOUBLE, &dt, 0},
                          {"--t-end", CLI_ARG_DOUBLE, &t_end, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0}};
  const char *pos[1];
  size_t npos = 0;
  int rc = cli_parse("reduction", argc, argv, options, 7, pos, 1, &npos);
  if (rc == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  if (npos != 1) {
    cli_error("reduction", "expected one experiment: j2-satellite, double-spherical-pendulum or phases");
    return CLI_EXIT_USAGE;
  }
  if ((options[4].seen && cli_check_positive("reduction", "--dt", dt)) ||
      (options[5].seen && cli_check_positive("reduction", "--t-end", t_end)))
    return CLI_EXIT_USAGE;
  /* an option the experiment does not use is an error, not ignored */
  const int phases = strcmp(pos[0], "phases") == 0, j2_name = strcmp(pos[0], "j2-satellite") == 0;
  for (size_t i = 1; i < 6; ++i) {
    const int dsp_only = i == 1 || i == 2, run_only = i >= 4;
    if (options[i].seen && ((phases && (dsp_only || run_only)) || (j2_name && dsp_only))) {
      cli_error("reduction", "%s is not an option of '%s'%s", options[i].name, pos[0],
                dsp_only ? " (double-spherical-pendulum only)" : "");
      return CLI_EXIT_USAGE;
    }
  }
  if (phases) {
    if (options[0].seen && make_directory(dir)) return CLI_EXIT_FAILURE;
    rc = cli_reduction_phases(options[0].seen ? dir : NULL, json); /* files only with --out */
    if (rc != CLI_EXIT_OK || !options[0].seen || no_plot) return rc;
    return plot(dir, "phases-convergence.png",
                "set logscale xy\nset format y '10^{%L}'\nset xlabel 'points per loop / steps per period'\n"
                "set ylabel 'phase error'\nset key outside right\nset grid\n"
                "set title 'Geometric phases: error vs closed form (solid) and vs the polygon exact holonomy (dashed)'\n"
                "plot 'phases-convergence.csv' every ::1 using 1:2 w lp lw 2 t 'Foucault, midpoint conn.', "
                "'' every ::1 using 1:3 w lp lw 2 t 'Foucault, Gauss-2 conn.', "
                "'' every ::1 using 1:4 w lp dt 2 lw 2 t 'Foucault, Gauss-2 vs polygon', "
                "'' every ::1 using 1:5 w lp dt 2 lw 2 t 'DSP loop, midpoint vs polygon', "
                "'' every ::1 using 1:6 w lp dt 2 lw 2 t 'DSP loop, Gauss-2 vs polygon', "
                "'' every ::1 using 1:7 w lp lw 2 t 'rigid body, lgvi', "
                "'' every ::1 using 1:8 w lp lw 2 t 'rigid body, lgvi-galerkin-2', "
                "'' every ::1 using 1:(2e-1/$1**2) w l lc rgb '#999999' t 'N^{-2}', "
                "'' every ::1 using 1:(1e0/$1**4) w l lc rgb '#555555' t 'N^{-4}'");
  }
  const int j2 = strcmp(pos[0], "j2-satellite") == 0;
  if (!j2 && strcmp(pos[0], "double-spherical-pendulum") != 0) {
    cli_error("reduction",
              "unknown experiment '%s'; expected j2-satellite, double-spherical-pendulum or phases",
              pos[0]);
    return CLI_EXIT_USAGE;
  }
  if (!options[4].seen) dt = j2 ? 0.3 : 0.01;
  if (!options[5].seen) t_end = j2 ? 150.0 : 20.0;
  if (dt > t_end) {
    cli_error("reduction", "--dt %g is longer than the run (t-end %g)", dt, t_end);
    return CLI_EXIT_USAGE;
  }
  if (t_end / dt > 1e6) {
    cli_error("reduction", "t-end/dt = %g steps is too many (at most 1e6)", t_end / dt);
    return CLI_EXIT_USAGE;
  }
  if (x0_text != NULL) {
    double v[6];
    int used = 0;
    if (sscanf(x0_text, "%lf,%lf,%lf,%lf,%lf,%lf%n", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
               &used) != 6 || x0_text[used] != '\0' || !(v[0] > 0 && v[0] < 1.0) ||
        !(v[1] > 0 && v[1] < 1.0)) {
      cli_error("reduction", "--x0 wants r1,r2,phi,r1dot,r2dot,phidot with 0 < r_i < l_i = 1, got '%s'",
                x0_text);
      return CLI_EXIT_USAGE;
    }
    memcpy(dsp_config.x0, v, sizeof v);
  }
  if (!isfinite(dsp_config.mu)) {
    cli_error("reduction", "--mu must be finite");
    return CLI_EXIT_USAGE;
  }
  if (make_directory(dir)) return CLI_EXIT_FAILURE;
  return j2 ? run_j2(dir, no_plot, dt, t_end, json) : run_dsp(dir, no_plot, dt, t_end, json);
}

const cli_command cli_reduction_command = {"reduction",
                                       "discrete Routh reduction experiments (seed 001 2.9-2.10)",
                                       usage, routh_main};
/* The issue and seed 001 call the experiments "discrete Routh reduction": the same command under
   that name. */
const cli_command cli_routh_command = {"routh", "the same as reduction", usage, routh_main};
