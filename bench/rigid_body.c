/* Rigid-body rows on the free rigid body (I = (1, 2, 3), near the intermediate axis):
 *  1. cost per step of every row, as a ratio to the explicit body-axis splitting measured in the
 *     same run (the floor: five exact rotations, no force, no solve);
 *  2. work–precision to 1e-10 at T = 1000: for each row the error at T (chart distance to a
 *     reference) for N = 2^k steps, and the cost of the first N reaching 1e-10; rows that would
 *     need more than 2^22 steps get the cost extrapolated from their measured order (marked).
 * Reference: lgvi-galerkin-3 with 10⁵ steps, checked against rkmk4 with 2·10⁶ (agreement
 * printed). Times are thread CPU times, best of 3; the machine is shared, so only the ratios
 * mean anything.
 * usage: bench_rigid_body [results-dir]   (writes rigid_body.json) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/geomint.h"

#define T_END 1000.0
#define TARGET 1e-10
#define MAX_K 22

static double run(const gm_method *m, const gm_problem *pb, const double *y0, size_t n,
                  double h, double *y_end) {
  gm_integrator *it = NULL;
  if (gm_integrator_create(m, pb, &it, NULL) != GM_OK) return NAN;
  gm_integrator_set_state(it, 0.0, y0);
  double t0 = bench_cpu_now();
  gm_status st = gm_integrator_run(it, n, h);
  double t = bench_cpu_now() - t0;
  if (y_end != NULL) memcpy(y_end, gm_integrator_state(it), 12 * sizeof *y_end);
  gm_integrator_free(it);
  return st == GM_OK ? t : NAN;
}

static double chart_error(const gm_problem *pb, const double *ref, const double *y) {
  double z[12], e = 0.0;
  if (gm_problem_to_chart(pb, ref, y, z) != GM_OK) return INFINITY;
  for (int i = 0; i < 12; ++i) e = fmax(e, fabs(z[i]));
  return e;
}

int main(int argc, char **argv) {
  gm_model *model = NULL;
  if (gm_model_create("rigid-body", &model) != GM_OK || gm_model_build(model) != GM_OK) return 1;
  const gm_problem *pb = gm_model_problem(model);
  double y0[12], t0, ref[12], check[12];
  gm_model_initial_state(model, &t0, y0);
  FILE *json = bench_open_json(argc, argv, "rigid_body");
  if (json == NULL) return 1;

  /* 1. cost per step against the splitting */
  const gm_method *floor_m = gm_method_find("rigid-splitting");
  printf("cost per step on the free rigid body (h = 0.01), thread CPU time, best of 3\n");
  printf("%-20s %12s %10s\n", "method", "us/step", "ratio");
  fprintf(json, "{\n  \"benchmark\": \"rigid_body\",\n  \"cost\": [\n");
  double floor_s = INFINITY;
  for (int r = 0; r < 3; ++r) floor_s = fmin(floor_s, run(floor_m, pb, y0, 400000, 0.01, NULL));
  floor_s /= 400000;
  size_t n_rows = 0, count = gm_method_count();
  for (size_t i = 0; i < count; ++i) {
    const gm_method *m = gm_method_at(i);
    if (m->family != GM_FAMILY_LIE_GROUP) continue;
    const size_t n = (m->flags & GM_EXPLICIT) || strcmp(m->name, "lgvi") == 0 ? 200000 : 20000;
    double best = INFINITY;
    for (int r = 0; r < 3; ++r) best = fmin(best, run(m, pb, y0, n, 0.01, NULL));
    best /= (double)n;
    printf("%-20s %12.3f %10.2f\n", m->name, 1e6 * best, best / floor_s);
    fprintf(json, "%s    {\"method\": \"%s\", \"us_per_step\": %.4f, \"ratio_to_splitting\": %.3f}",
            n_rows++ ? ",\n" : "", m->name, 1e6 * best, best / floor_s);
  }
  fprintf(json, "\n  ],\n");

  /* 2. work–precision to 1e-10 at T = 1000 */
  run(gm_method_find("lgvi-galerkin-3"), pb, y0, 100000, T_END / 100000, ref);
  run(gm_method_find("rkmk4"), pb, y0, 2000000, T_END / 2000000, check);
  printf("\nreference lgvi-galerkin-3 (1e5 steps) vs rkmk4 (2e6 steps) at T = %g: %.2e\n", T_END,
         chart_error(pb, ref, check));
  printf("work-precision at T = %g, target error %g\n", T_END, TARGET);
  printf("%-20s %10s %12s %12s %10s\n", "method", "steps", "error", "cpu_s", "vs split");
  fprintf(json, "  \"work_precision\": [\n");
  double split_cost = NAN;
  n_rows = 0;
  for (int pass = 0; pass < 2; ++pass) /* the splitting first: the others are ratios to it */
    for (size_t i = 0; i < count; ++i) {
      const gm_method *m = gm_method_at(i);
      if (m->family != GM_FAMILY_LIE_GROUP) continue;
      if ((pass == 0) != (m == floor_m)) continue;
      double y[12], err = INFINITY, cost = NAN, last_err = NAN;
      size_t steps = 0, k = 10;
      int extrapolated = 0;
      const size_t k_max = (m->flags & GM_EXPLICIT) || strcmp(m->name, "lgvi") == 0 ? MAX_K : 17;
      for (; k <= k_max; ++k) {
        steps = (size_t)1 << k;
        cost = run(m, pb, y0, steps, T_END / (double)steps, y);
        err = chart_error(pb, ref, y);
        if (err <= TARGET || k == k_max) break;
        last_err = err; /* the error one doubling before the last */
      }
      if (!(err <= TARGET) && isfinite(last_err)) { /* extrapolate with the measured slope */
        double slope = log2(last_err / err);          /* the order over the last doubling */
        double doublings = log2(err / TARGET) / slope;
        cost = cost * pow(2.0, doublings);
        steps = (size_t)((double)steps * pow(2.0, doublings));
        extrapolated = 1;
      }
      if (m == floor_m) split_cost = cost;
      printf("%-20s %10zu %12.2e %12.4f %10.3f%s\n", m->name, steps, extrapolated ? TARGET : err,
             cost, cost / split_cost, extrapolated ? "  (extrapolated)" : "");
      fprintf(json,
              "%s    {\"method\": \"%s\", \"steps\": %zu, \"error\": %.3e, \"cpu_s\": %.5f, "
              "\"ratio_to_splitting\": %.4f, \"extrapolated\": %s}",
              n_rows++ ? ",\n" : "", m->name, steps, extrapolated ? TARGET : err, cost,
              cost / split_cost, extrapolated ? "true" : "false");
    }
  fprintf(json, "\n  ]\n}\n");
  fclose(json);
  gm_model_free(model);
  return 0;
}
