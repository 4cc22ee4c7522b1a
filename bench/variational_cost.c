/* Cost per step of the variational Galerkin integrators against Gauss collocation of the same
 * order, on the same problem in one run: vi-galerkin-gauss-s with its default solver (on this
 * separable problem: Gauss collocation's fixed-point iteration on positions, the fast path of
 * src/methods/variational/variational.c) against gauss-s with its default solver and with its
 * positions-only fixed-point iteration named explicitly (since issue 17 the same thing), on
 * 16 bodies with softened gravity (the library's n-body model: 48 degrees of freedom). Both
 * compute the same trajectory to round-off (tests/invariants/test_variational.c), so the ratio
 * is the price of the variational formulation. Target: vi ≤ 1.2 × gauss. Reports thread CPU
 * time per step (best of 3), iterations per step and force evaluations per step. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/geomint.h"

typedef struct {
  double seconds_per_step, iterations_per_step, forces_per_step;
} cost;

static cost measure(const char *method, gm_solver solver, const gm_problem *pb, double t0,
                    const double *y0, size_t steps, double h, double *y_end) {
  cost best = {INFINITY, 0, 0};
  for (int rep = 0; rep < 3; ++rep) {
    gm_integrator *it = NULL;
    gm_error err;
    const gm_scheme scheme = {gm_method_find(method), NULL, solver, 0};
    if (gm_integrator_create_scheme(&scheme, pb, &it, &err) != GM_OK) {
      fprintf(stderr, "%s: %s\n", method, err.message);
      exit(1);
    }
    gm_integrator_set_state(it, t0, y0);
    double start = bench_cpu_now();
    if (gm_integrator_run(it, steps, h) != GM_OK) {
      fprintf(stderr, "%s: %s\n", method, gm_integrator_errmsg(it));
      exit(1);
    }
    double sec = (bench_cpu_now() - start) / (double)steps;
    gm_stats s = gm_integrator_stats(it);
    if (sec < best.seconds_per_step) {
      best.seconds_per_step = sec;
      best.iterations_per_step =
          (double)(s.newton_iterations + s.fixed_point_iterations) / (double)steps;
      best.forces_per_step = (double)s.force_evals / (double)steps;
    }
    memcpy(y_end, gm_integrator_state(it), gm_integrator_state_size(it) * sizeof *y_end);
    gm_integrator_free(it);
  }
  return best;
}

int main(int argc, char **argv) {
  gm_model *model = NULL;
  if (gm_model_create("n-body", &model) != GM_OK || gm_model_set(model, "n", 16) != GM_OK ||
      gm_model_set(model, "eps", 0.05) != GM_OK || gm_model_build(model) != GM_OK) {
    fprintf(stderr, "n-body: %s\n", gm_model_errmsg(model));
    return 1;
  }
  const gm_problem *pb = gm_model_problem(model);
  const size_t n = gm_model_state_size(model);
  double t0, *y0 = malloc(n * sizeof *y0), *ya = malloc(n * sizeof *ya),
             *yb = malloc(n * sizeof *yb), *yc = malloc(n * sizeof *yc);
  gm_model_initial_state(model, &t0, y0);
  const size_t steps = 2000;
  const double h = 1e-3;
  FILE *json = bench_open_json(argc, argv, "variational_cost");
  if (json) fprintf(json, "{\n  \"problem\": \"n-body n=16 eps=0.05\", \"steps\": %zu, \"h\": %g,\n  \"rows\": [\n", steps, h);
  printf("cost per step, n-body (16 bodies, eps = 0.05), %zu steps of %g, thread CPU time\n",
         steps, h);
  printf("%-22s %10s %8s %8s | %-10s %10s %8s %7s | %-14s %10s %7s\n", "variational", "us/step",
         "iter", "forces", "gauss", "us/step", "iter", "ratio", "gauss fp-pos", "us/step",
         "ratio");
  for (int s = 1; s <= 4; ++s) {
    char vi[64], gauss[64];
    snprintf(vi, sizeof vi, s == 1 ? "vi-midpoint" : "vi-galerkin-gauss-%d", s);
    snprintf(gauss, sizeof gauss, "gauss-%d", s);
    cost a = measure(vi, GM_SOLVER_DEFAULT, pb, t0, y0, steps, h, ya);
    cost b = measure(gauss, GM_SOLVER_DEFAULT, pb, t0, y0, steps, h, yb);
    cost c = measure(gauss, GM_SOLVER_FIXED_POINT_POSITIONS, pb, t0, y0, steps, h, yc);
    double diff = 0.0, scale = 0.0;
    for (size_t i = 0; i < n; ++i) {
      diff = fmax(diff, fabs(ya[i] - yc[i]));
      scale = fmax(scale, fabs(yc[i]));
    }
    const double r1 = a.seconds_per_step / b.seconds_per_step,
                 r2 = a.seconds_per_step / c.seconds_per_step;
    printf("%-22s %10.2f %8.2f %8.2f | %-10s %10.2f %8.2f %7.3f | %-14s %10.2f %7.3f  (same "
           "state to %.1e)\n",
           vi, 1e6 * a.seconds_per_step, a.iterations_per_step, a.forces_per_step, gauss,
           1e6 * b.seconds_per_step, b.iterations_per_step, r1, "", 1e6 * c.seconds_per_step,
           r2, diff / scale);
    if (json)
      fprintf(json,
              "    {\"variational\": \"%s\", \"gauss\": \"%s\", \"order\": %d,\n"
              "     \"vi_us_per_step\": %.4f, \"vi_iterations_per_step\": %.3f, "
              "\"vi_forces_per_step\": %.3f,\n"
              "     \"gauss_newton_us_per_step\": %.4f, \"gauss_newton_iterations_per_step\": %.3f,\n"
              "     \"gauss_fixed_point_positions_us_per_step\": %.4f, "
              "\"gauss_fixed_point_positions_iterations_per_step\": %.3f,\n"
              "     \"ratio_vi_to_gauss_newton\": %.4f, \"ratio_vi_to_gauss_fixed_point_positions\": "
              "%.4f, \"relative_state_difference\": %.3e}%s\n",
              vi, gauss, 2 * s, 1e6 * a.seconds_per_step, a.iterations_per_step,
              a.forces_per_step, 1e6 * b.seconds_per_step, b.iterations_per_step,
              1e6 * c.seconds_per_step, c.iterations_per_step, r1, r2, diff / scale,
              s < 4 ? "," : "");
  }
  if (json) {
    fprintf(json, "  ]\n}\n");
    fclose(json);
  }
  free(y0);
  free(ya);
  free(yb);
  free(yc);
  gm_model_free(model);
  return 0;
}
