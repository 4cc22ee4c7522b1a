/* Cost per step of the mimetic integrators against Gauss collocation at the same degree p, on
 * the pendulum (k = 10) and Kepler (e = 0.6), dt = 0.1, default solvers (simplified Newton);
 * and of avf against the implicit midpoint rule on Hénon–Heiles (dt = 0.1). Everything is
 * measured in the same run: the ratios are the results. Targets: mimetic-canonical-p at most
 * 1.2 × gauss-p (it is the same method, solved for nodal values instead of stage increments);
 * mimetic-galerkin-p pays for its quadrature: 2p + 6 evaluations of f per iteration instead of
 * p, and it iterates to round-off (energy), so its factor is reported, with the force
 * evaluations per step that explain it. Times are thread CPU times, best of 5 repeats. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/geomint.h"

#define REPEATS 5

typedef struct {
  double seconds_per_step, forces_per_step, iterations_per_step;
} cost;

static cost measure(const char *method, const gm_model *model, size_t steps, double dt) {
  const gm_problem *pb = gm_model_problem(model);
  double t0, y0[16];
  gm_model_initial_state(model, &t0, y0);
  cost best = {INFINITY, 0, 0};
  for (int r = 0; r < REPEATS; ++r) {
    gm_integrator *it = NULL;
    gm_error err;
    if (gm_integrator_create(gm_method_find(method), pb, &it, &err) != GM_OK) {
      fprintf(stderr, "%s: %s\n", method, err.message);
      return best;
    }
    gm_integrator_set_state(it, t0, y0);
    double start = bench_cpu_now();
    gm_status st = gm_integrator_run(it, steps, dt);
    double elapsed = bench_cpu_now() - start;
    if (st != GM_OK) fprintf(stderr, "%s: %s\n", method, gm_integrator_errmsg(it));
    gm_stats s = gm_integrator_stats(it);
    if (elapsed / (double)steps < best.seconds_per_step)
      best = (cost){elapsed / (double)steps, (double)s.force_evals / (double)steps,
                    (double)(s.newton_iterations + s.fixed_point_iterations) / (double)steps};
    gm_integrator_free(it);
  }
  return best;
}

static gm_model *open_model(const char *name, const char *param, double value) {
  gm_model *m = NULL;
  gm_model_create(name, &m);
  if (param != NULL) gm_model_set(m, param, value);
  gm_model_build(m);
  return m;
}

int main(int argc, char **argv) {
  FILE *json = bench_open_json(argc, argv, "mimetic_cost");
  if (json == NULL) return 1;
  gm_model *problems[2] = {open_model("pendulum", "k", 10.0), open_model("kepler", "e", 0.6)};
  const char *problem_names[2] = {"pendulum", "kepler"};
  const size_t steps = 20000;
  int ok = 1;
  fprintf(json, "{\n  \"benchmark\": \"mimetic_cost\",\n  \"dt\": 0.1,\n  \"steps\": %zu,\n"
                "  \"rows\": [\n", steps);
  printf("%-9s %2s %12s %12s %12s %8s %8s %22s\n", "problem", "p", "gauss us", "MCI us",
         "MGI us", "MCI/G", "MGI/G", "f/step G, MCI, MGI");
  int first = 1;
  for (int k = 0; k < 2; ++k)
    for (int p = 1; p <= 4; ++p) {
      char g[32], c[32], gl[32];
      snprintf(g, sizeof g, "gauss-%d", p);
      snprintf(c, sizeof c, "mimetic-canonical-%d", p);
      snprintf(gl, sizeof gl, "mimetic-galerkin-%d", p);
      cost cg = measure(g, problems[k], steps, 0.1), cc = measure(c, problems[k], steps, 0.1),
           cm = measure(gl, problems[k], steps, 0.1);
      double rc = cc.seconds_per_step / cg.seconds_per_step,
             rm = cm.seconds_per_step / cg.seconds_per_step;
      ok = ok && rc <= 1.2;
      printf("%-9s %2d %12.3f %12.3f %12.3f %8.2f %8.2f %7.1f %6.1f %6.1f\n", problem_names[k], p,
             1e6 * cg.seconds_per_step, 1e6 * cc.seconds_per_step, 1e6 * cm.seconds_per_step, rc,
             rm, cg.forces_per_step, cc.forces_per_step, cm.forces_per_step);
      fprintf(json,
              "%s    {\"problem\": \"%s\", \"p\": %d, \"gauss_s_per_step\": %.4e, "
              "\"mci_s_per_step\": %.4e, \"mgi_s_per_step\": %.4e, \"mci_over_gauss\": %.3f, "
              "\"mgi_over_gauss\": %.3f, \"forces_per_step\": [%.2f, %.2f, %.2f], "
              "\"iterations_per_step\": [%.2f, %.2f, %.2f]}",
              first ? "" : ",\n", problem_names[k], p, cg.seconds_per_step, cc.seconds_per_step,
              cm.seconds_per_step, rc, rm, cg.forces_per_step, cc.forces_per_step,
              cm.forces_per_step, cg.iterations_per_step, cc.iterations_per_step,
              cm.iterations_per_step);
      first = 0;
    }
  gm_model *hh = open_model("henon-heiles", NULL, 0.0);
  cost mid = measure("midpoint", hh, steps, 0.1), avf = measure("avf", hh, steps, 0.1);
  double ra = avf.seconds_per_step / mid.seconds_per_step;
  printf("\nhenon-heiles: midpoint %.3f us/step (%.1f f), avf %.3f us/step (%.1f grad H), "
         "avf/midpoint %.2f\n",
         1e6 * mid.seconds_per_step, mid.forces_per_step, 1e6 * avf.seconds_per_step,
         avf.forces_per_step, ra);
  fprintf(json,
          "\n  ],\n  \"henon_heiles\": {\"midpoint_s_per_step\": %.4e, \"avf_s_per_step\": %.4e, "
          "\"avf_over_midpoint\": %.3f, \"forces_per_step\": [%.2f, %.2f]},\n"
          "  \"mci_target\": 1.2,\n  \"mci_within_target\": %s\n}\n",
          mid.seconds_per_step, avf.seconds_per_step, ra, mid.forces_per_step,
          avf.forces_per_step, ok ? "true" : "false");
  fclose(json);
  printf("MCI within 1.2 x gauss-p: %s\n", ok ? "yes" : "NO");
  for (int k = 0; k < 2; ++k) gm_model_free(problems[k]);
  gm_model_free(hh);
  return 0;
}
