/* Kepler (e = 0.6) with Störmer–Verlet for 100 orbits through the public API. */
#include <geomint/geomint.h>
#include <stdio.h>

int main(void) {
  gm_model *kepler;
  gm_integrator *it;
  gm_error err;
  double t0, y0[4];
  if (gm_model_create("kepler", &kepler) || gm_model_set(kepler, "e", 0.6) || gm_model_build(kepler)) return 1;
  const gm_problem *problem = gm_model_problem(kepler);
  gm_model_initial_state(kepler, &t0, y0);
  if (gm_integrator_create(gm_method_find("verlet"), problem, &it, &err)) return fprintf(stderr, "%s\n", err.message), 1;
  gm_integrator_set_state(it, t0, y0);
  if (gm_integrator_integrate(it, 200 * 3.141592653589793, 0.01)) return fprintf(stderr, "%s\n", gm_integrator_errmsg(it)), 1;
  double h0 = gm_problem_energy(problem, y0), h = gm_problem_energy(problem, gm_integrator_state(it));
  printf("relative energy error after 100 orbits: %.2e\n", (h - h0) / h0);
  gm_integrator_free(it);
  gm_model_free(kepler);
  return 0;
}
