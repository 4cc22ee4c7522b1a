/* The C side of bench/python_overhead.py: a built-in problem run with gm_integrator_run, as
 * geomint.Integrator(...).run(steps, dt) makes it from Python, timed the same way (CPU time
 * of the thread around the run only, best of the repeats, a fresh integrator each time).
 *
 *   bench_python_c_baseline [RESULTS_DIR [PROBLEM METHOD DT STEPS REPEATS]]
 *
 * With a problem: prints one JSON object {"cpu_s", "final_q"} (%.17g). Without (make bench):
 * Kepler (verlet, dt 1e-3, 10^6 steps) and the outer solar system (verlet, dt 10, 10^5 steps)
 * into RESULTS_DIR/python_c_baseline.json. */
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "geomint/geomint.h"

static int measure(const char *problem, const char *method, double dt, size_t steps,
                   size_t repeats, double *cpu, gm_model **model_out, double **final) {
  gm_model *model;
  if (gm_model_create(problem, &model) != GM_OK || gm_model_build(model) != GM_OK) {
    fprintf(stderr, "unknown or bad problem %s\n", problem);
    return 1;
  }
  const gm_method *m = gm_method_find(method);
  if (m == NULL) {
    fprintf(stderr, "unknown method %s\n", method);
    gm_model_free(model);
    return 1;
  }
  size_t n = gm_model_state_size(model);
  double t0, *y0 = malloc(n * sizeof *y0), *y = malloc(n * sizeof *y);
  gm_model_initial_state(model, &t0, y0);
  *cpu = 1e300;
  for (size_t r = 0; r < repeats; ++r) {
    gm_integrator *it;
    gm_error err;
    if (gm_integrator_create(m, gm_model_problem(model), &it, &err) != GM_OK ||
        gm_integrator_set_state(it, t0, y0) != GM_OK) {
      fprintf(stderr, "%s\n", err.message);
      return 1;
    }
    double start = bench_cpu_now();
    gm_status st = gm_integrator_run(it, steps, dt);
    double s = bench_cpu_now() - start;
    if (st != GM_OK) {
      fprintf(stderr, "%s\n", gm_integrator_errmsg(it));
      return 1;
    }
    if (s < *cpu) *cpu = s;
    for (size_t i = 0; i < n; ++i) y[i] = gm_integrator_state(it)[i];
    gm_integrator_free(it);
  }
  free(y0);
  *model_out = model;
  *final = y;
  return 0;
}

static void print_row(FILE *f, const char *problem, const char *method, double dt, size_t steps,
                      double cpu, const gm_model *model, const double *y) {
  size_t d = gm_model_problem(model)->dim;
  fprintf(f, "{\"problem\": \"%s\", \"method\": \"%s\", \"dt\": %.17g, \"steps\": %zu, "
          "\"cpu_s\": %.9f, \"final_q\": [", problem, method, dt, steps, cpu);
  for (size_t i = 0; i < d; ++i) fprintf(f, "%s%.17g", i ? ", " : "", y[i]);
  fprintf(f, "]}");
}

int main(int argc, char **argv) {
  if (argc >= 7) {
    double cpu, *y;
    gm_model *model;
    double dt = atof(argv[4]);
    size_t steps = (size_t)atol(argv[5]), repeats = (size_t)atol(argv[6]);
    if (measure(argv[2], argv[3], dt, steps, repeats, &cpu, &model, &y)) return 1;
    print_row(stdout, argv[2], argv[3], dt, steps, cpu, model, y);
    printf("\n");
    gm_model_free(model);
    free(y);
    return 0;
  }
  FILE *f = bench_open_json(argc, argv, "python_c_baseline");
  if (f == NULL) return 1;
  fprintf(f, "{\n  \"rows\": [\n");
  const char *problems[] = {"kepler", "outer-solar-system"};
  const double dts[] = {1e-3, 10.0};
  const size_t steps[] = {1000000, 100000};
  for (int k = 0; k < 2; ++k) {
    double cpu, *y;
    gm_model *model;
    if (measure(problems[k], "verlet", dts[k], steps[k], 3, &cpu, &model, &y)) return 1;
    fprintf(f, "    ");
    print_row(f, problems[k], "verlet", dts[k], steps[k], cpu, model, y);
    fprintf(f, "%s\n", k ? "" : ",");
    printf("%s verlet %zu steps: %.4f s\n", problems[k], steps[k], cpu);
    gm_model_free(model);
    free(y);
  }
  bench_close_json(f);
  return 0;
}
