/* Kepler (e = 0.6) with Störmer–Verlet for 100 orbits through the public API. */
#include <geomint/geomint.h>
#include <stdio.h>

int main(void) {
  gm_model *kepler = NULL;
  gm_integrator *it = NULL;
  double t0, y0[4];
  if (gm_model_create("kepler", &kepler) || gm_model_set(kepler, "e", 0.6) || gm_model_build(kepler)) return 1;
  const gm_problem *problem = gm_model_problem(kepler);
  gm_model_initial_state(kepler, &t0, y0);
  gm_error err;
  if (gm_integrator_create(gm_method_find("verlet"), problem, &it, &err)) return fprintf(stderr, "%s\n", err.message), 1;
  gm_integrator_set_state(it, t0, y0);
  if (gm_integrator_integrate(it, 200.0 * 3.141592653589793, 0.01)) return fprintf(stderr, "%s\n", gm_integrator_errmsg(it)), 1;
  const double *y = gm_integrator_state(it);
  printf("q = (%.6f, %.6f)  energy error = %.2e\n", y[0], y[1], gm_problem_energy(problem, y) - gm_problem_energy(problem, y0));
  gm_integrator_free(it);
  gm_model_free(kepler);
  return 0;
}
