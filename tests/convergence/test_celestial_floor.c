/* The near-integrable floor on the outer solar system (issue 25): below the old floor
 * (4e-11 … 1.5e-10, where pass and fail alternated along the step grid) the error of aba-10-4
 * still decreases by at least the method's order 4 (its ε² h⁴ term, Laskar & Robutel 2001) and
 * stays ≤ 1e-11, at steps chosen AWAY from the step-size resonances h (k1 n_J + k2 n_S) = 2π,
 * |k1 + k2| ≤ 2 (bench_celestial_resonance prints them; docs/ode-speed.md): N = 2540, 3000,
 * 3500 steps over 500 000 days lie 10.5, 9.0 and 6.9 steps from the nearest such N. At resonant
 * steps the error jumps 10–20× (e.g. N = 1930: 1.7e-10), so the test does not claim monotone
 * decrease on every grid. Compensated summation (the plain round-off floor is 1–5e-12); error:
 * max-norm of the final positions over the largest reference position, reference
 * sofroniou-spaletta-10 compensated at 50 days. */
#include <stdio.h>

#include "test_util.h"

#define T_END 500000.0

static void integrate(const char *method, const gm_problem *pb, const double *y0, size_t n,
                      size_t steps, double *out) {
  gm_scheme sc = {gm_method_find(method), NULL, GM_SOLVER_DEFAULT, 1};
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_integrator_create_scheme(&sc, pb, &it, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_integrator_set_state(it, 0.0, y0), GM_OK);
  cr_assert_eq(gm_integrator_run(it, steps, T_END / (double)steps), GM_OK, "%s",
               gm_integrator_errmsg(it));
  memcpy(out, gm_integrator_state(it), n * sizeof *out);
  gm_integrator_free(it);
}

Test(celestial_floor, aba_10_4_below_old_floor, .timeout = 120) {
  gm_model *model = NULL;
  cr_assert_eq(gm_model_create("outer-solar-system", &model), GM_OK);
  cr_assert_eq(gm_model_build(model), GM_OK);
  const gm_problem *pb = gm_model_problem(model);
  const size_t n = gm_model_state_size(model);
  double y0[64], ref[64], y[64], scale = 0.0;
  gm_model_initial_state(model, NULL, y0);
  integrate("sofroniou-spaletta-10", pb, y0, n, 10000, ref);
  for (size_t i = 0; i < n / 2; ++i) scale = fmax(scale, fabs(ref[i]));
  const size_t steps[3] = {2540, 3000, 3500};
  double e[3];
  for (int k = 0; k < 3; ++k) {
    integrate("aba-10-4", pb, y0, n, steps[k], y);
    e[k] = 0.0;
    for (size_t i = 0; i < n / 2; ++i) e[k] = fmax(e[k], fabs(y[i] - ref[i]));
    e[k] /= scale;
  }
  /* measured: 5.56e-12, 2.74e-12, 1.43e-12; slopes 4.25, 4.22 */
  for (int k = 0; k < 3; ++k)
    cr_assert(e[k] <= 1e-11 && e[k] > 1e-13, "N = %zu: error %.3e", steps[k], e[k]);
  for (int k = 0; k < 2; ++k) {
    const double slope = log(e[k] / e[k + 1]) / log((double)steps[k + 1] / (double)steps[k]);
    cr_assert(slope >= 4.0 && slope <= 4.6, "N = %zu → %zu: errors %.3e → %.3e, order %.2f",
              steps[k], steps[k + 1], e[k], e[k + 1], slope);
  }
  gm_model_free(model);
}
