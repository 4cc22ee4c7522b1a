/* The three equivalent forms of variational IMEX with a quadratic fast part (seed 000 §2.2):
 * linear solve, Verlet with the modified mass M̃ = M + (hΩ/2)², and the rotation by the
 * modified frequency. Which is fastest decides GM_IMEX_AUTO. Measured on FPU (diagonal Ω,
 * M = I) and on the diatomic chain (full Ω, masses) with 4 and 16 molecules, as thread CPU
 * time per step, and as a ratio to Verlet on the same problem and step (the floor: one force
 * evaluation per step and no linear algebra). Best of 5 repeats.
 * usage: bench_oscillatory_imex_forms [DIR]  (writes DIR/oscillatory_imex_forms.json) */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/geomint.h"

static double time_run(const gm_model *model, const char *method, int form, double h,
                       size_t steps) {
  double best = INFINITY;
  for (int rep = 0; rep < 5; ++rep) {
    gm_integrator *it = NULL;
    if (gm_integrator_create(gm_method_find(method), gm_model_problem(model), &it, NULL) !=
        GM_OK)
      return NAN;
    double t0, y0[64];
    gm_model_initial_state(model, &t0, y0);
    gm_integrator_set_state(it, t0, y0);
    if (form > 0 && gm_oscillatory_set_imex_form(it, (gm_imex_form)form) != GM_OK) return NAN;
    double c0 = bench_cpu_now();
    gm_integrator_run(it, steps, h);
    double c1 = bench_cpu_now();
    gm_integrator_free(it);
    best = fmin(best, (c1 - c0) / (double)steps);
  }
  return best;
}

int main(int argc, char **argv) {
  static const struct {
    const char *model, *param;
    double value, h;
  } cases[] = {{"fpu", NULL, 0, 0.01}, {"diatomic-chain", "molecules", 4, 0.01},
               {"diatomic-chain", "molecules", 8, 0.01}, {"diatomic-chain", "molecules", 16, 0.01}};
  static const char *const forms[] = {"auto", "linear-solve", "modified-mass",
                                      "modified-frequency"};
  FILE *json = bench_open_json(argc, argv, "oscillatory_imex_forms");
  if (json == NULL) return 1;
  fprintf(json, "{\n  \"benchmark\": \"oscillatory_imex_forms\",\n  \"rows\": [\n");
  printf("%-16s %4s %10s  %12s %12s %12s %12s\n", "problem", "dim", "verlet ns",
         "auto/verlet", "linear", "mod. mass", "mod. freq.");
  const size_t n_cases = sizeof cases / sizeof cases[0];
  for (size_t c = 0; c < n_cases; ++c) {
    gm_model *model = NULL;
    gm_model_create(cases[c].model, &model);
    if (cases[c].param) gm_model_set(model, cases[c].param, cases[c].value);
    if (gm_model_build(model) != GM_OK) return 1;
    const size_t steps = 200000;
    double verlet = time_run(model, "verlet", 0, cases[c].h, steps), t[4];
    for (int f = 0; f < 4; ++f) t[f] = time_run(model, "imex", f, cases[c].h, steps);
    printf("%-16s %4zu %10.1f  %12.2f %12.2f %12.2f %12.2f\n", cases[c].model,
           gm_model_problem(model)->dim, 1e9 * verlet, t[0] / verlet, t[1] / verlet,
           t[2] / verlet, t[3] / verlet);
    fprintf(json, "    {\"problem\": \"%s\", \"dim\": %zu, \"verlet_ns\": %.1f", cases[c].model,
            gm_model_problem(model)->dim, 1e9 * verlet);
    for (int f = 0; f < 4; ++f) fprintf(json, ", \"%s_ratio\": %.3f", forms[f], t[f] / verlet);
    fprintf(json, "}%s\n", c + 1 < n_cases ? "," : "");
    gm_model_free(model);
  }
  bench_close_json(json);
  return 0;
}
