/* The error-scaling figure of docs/celestial.md: position error at t = 20 000 days of
 * Sun–Jupiter–Saturn (outer-solar-system planets=2) against the step, for the planets' real
 * masses (ε = 1) and for masses 1000 times smaller (ε = 1e-3), for wh, saba-2/4-jacobi, wh-c5,
 * aba-10-6-4 and sabac-2-jacobi. Reference: sofroniou-spaletta-10, compensated, 10 days. Writes
 * DIR/celestial_scaling.json and DIR/celestial_scaling.dat, and with gnuplot on PATH
 * DIR/celestial_scaling.png. usage: bench_celestial_scaling [DIR] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/geomint.h"

static const char *const methods[] = {"wh",    "saba-2-jacobi", "saba-4-jacobi",
                                      "wh-c5", "aba-10-6-4",    "sabac-2-jacobi"};
#define N_METHODS (sizeof methods / sizeof methods[0])
#define N_LEVELS 16
#define T_END 20000.0

static int integrate(const gm_problem *pb, const char *name, int comp, double h, const double *y0,
                     size_t n, double *y) {
  gm_scheme sc = {gm_method_find(name), NULL, GM_SOLVER_DEFAULT, comp};
  gm_integrator *it = NULL;
  if (gm_integrator_create_scheme(&sc, pb, &it, NULL) != GM_OK) return 1;
  gm_integrator_set_state(it, 0.0, y0);
  gm_status st = gm_integrator_integrate(it, T_END, h);
  if (st == GM_OK) memcpy(y, gm_integrator_state(it), n * sizeof *y);
  gm_integrator_free(it);
  return st != GM_OK;
}

int main(int argc, char **argv) {
  const char *dir = argc > 1 ? argv[1] : "bench/results";
  const double eps[2] = {1.0, 1e-3};
  static double err[2][N_METHODS][N_LEVELS], dt[N_LEVELS];
  for (int e = 0; e < 2; ++e) {
    gm_model *m = NULL;
    gm_model_create("outer-solar-system", &m);
    gm_model_set(m, "planets", 2);
    gm_model_set(m, "epsilon", eps[e]);
    if (gm_model_build(m) != GM_OK) return 1;
    const gm_problem *pb = gm_model_problem(m);
    size_t n = gm_model_state_size(m);
    double y0[64], ref[64], y[64], scale = 0;
    gm_model_initial_state(m, NULL, y0);
    if (integrate(pb, "sofroniou-spaletta-10", 1, 10.0, y0, n, ref)) return 1;
    for (size_t i = 0; i < n / 2; ++i) scale = fmax(scale, fabs(ref[i]));
    for (size_t k = 0; k < N_METHODS; ++k) {
      double h = 500.0;
      for (size_t l = 0; l < N_LEVELS; ++l, h /= 1.25) {
        dt[l] = h;
        double d = 0;
        if (integrate(pb, methods[k], 1, h, y0, n, y)) return 1;
        for (size_t i = 0; i < n / 2; ++i) d = fmax(d, fabs(y[i] - ref[i]));
        err[e][k][l] = fmax(d / scale, 1e-17);
      }
    }
    gm_model_free(m);
  }
  char path[1024];
  snprintf(path, sizeof path, "%s/celestial_scaling.dat", dir);
  FILE *f = fopen(path, "w");
  if (f == NULL) return 1;
  fprintf(f, "dt");
  for (int e = 0; e < 2; ++e)
    for (size_t k = 0; k < N_METHODS; ++k) fprintf(f, " %s(eps=%g)", methods[k], eps[e]);
  fprintf(f, "\n");
  for (size_t l = 0; l < N_LEVELS; ++l) {
    fprintf(f, "%.6g", dt[l]);
    for (int e = 0; e < 2; ++e)
      for (size_t k = 0; k < N_METHODS; ++k) fprintf(f, " %.4e", err[e][k][l]);
    fprintf(f, "\n");
  }
  fclose(f);
  FILE *j = bench_open_json(argc, argv, "celestial_scaling");
  if (j != NULL) {
    fprintf(j, "{\n  \"problem\": \"outer-solar-system planets=2\", \"t_end\": %g,\n  \"rows\": [\n",
            T_END);
    for (int e = 0; e < 2; ++e)
      for (size_t k = 0; k < N_METHODS; ++k) {
        fprintf(j, "    {\"method\": \"%s\", \"epsilon\": %g, \"dt\": [", methods[k], eps[e]);
        for (size_t l = 0; l < N_LEVELS; ++l) fprintf(j, "%s%.6g", l ? ", " : "", dt[l]);
        fprintf(j, "], \"error\": [");
        for (size_t l = 0; l < N_LEVELS; ++l) fprintf(j, "%s%.4e", l ? ", " : "", err[e][k][l]);
        fprintf(j, "]}%s\n", (e == 1 && k + 1 == N_METHODS) ? "" : ",");
      }
    fprintf(j, "  ]\n}\n");
    fclose(j);
  }
  if (system("command -v gnuplot > /dev/null 2>&1") == 0) {
    char cmd[4096];
    snprintf(cmd, sizeof cmd,
             "gnuplot -e \"set terminal pngcairo size 1100,480 font ',10'; "
             "set output '%s/celestial_scaling.png'; set multiplot layout 1,2; "
             "set logscale xy; set format y '%%.0e'; set xlabel 'step (days)'; "
             "set ylabel 'relative position error at t = 20000 d'; set key top left; "
             "set grid; set yrange [1e-16:1e-3]; set key autotitle columnhead; "
             "set title 'Sun-Jupiter-Saturn, real masses (eps = 1)'; "
             "plot for [c=2:7] '%s/celestial_scaling.dat' u 1:c w lp pt 7 ps 0.6 "
             "title columnhead(c), 2e-13*x**2 w l dt 2 lc 'gray' title 'slope 2'; "
             "set title 'planet masses x 1e-3 (eps = 1e-3)'; "
             "plot for [c=8:13] '%s/celestial_scaling.dat' u 1:c w lp pt 7 ps 0.6 "
             "title columnhead(c), 3e-14*x**2 w l dt 2 lc 'gray' title 'slope 2', "
             "2e-22*x**4 w l dt 4 lc 'black' title 'slope 4'; unset multiplot\"",
             dir, dir, dir);
    if (system(cmd) != 0) fprintf(stderr, "gnuplot failed\n");
  }
  printf("wrote %s/celestial_scaling.{dat,json,png}\n", dir);
  return 0;
}
