/* The two kernels of a near-integrable step on the outer solar system (5 planets), each
 * against what it replaced, measured in the same run:
 *   - Kepler drifts of the 5 planets by 47 days (a drift of aba-10-4 at 328 days): the
 *     four-lane short path (AVX2 CPUs) against the two-lane one, and against 5 single drifts;
 *   - the Newtonian sums of a kick (6 bodies): the splitting's own (row_sums.h, each pair once,
 *     four lanes) against the problem's potential_gradient callback (scalar pairs).
 * CPU time of the thread, best of 7 repeats of 10⁶ calls. Writes DIR/celestial_kernels.json
 * (DIR = argv[1], default bench/results).
 * usage: bench_celestial_kernels [DIR] */
#include <stdio.h>
#include <string.h>

#include "bench_util.h"
#include "celestial/internal.h"
#include "geomint/geomint.h"

#define CALLS 1000000
#define REPEATS 7

static double sink;

int main(int argc, char **argv) {
  gm_model *model;
  if (gm_model_create("outer-solar-system", &model) != GM_OK || gm_model_build(model) != GM_OK)
    return 1;
  const gm_problem *pb = gm_model_problem(model);
  const gm_celestial *c = pb->celestial;
  const size_t n = c->n_bodies;
  double y[36], eta[6], mu[6], mr[6], Q[18], P[18], V[18], dx[18], dv[18];
  gm_model_initial_state(model, NULL, y);
  gm_interior_masses(n, c->mass, eta);
  gm_kepler_parameters(GM_COORDINATES_JACOBI, n, c->mass, eta, c->G, mu, mr);
  gm_jacobi_from_barycentric(n, c->mass, eta, y, y + 3 * n, Q, P);
  for (size_t i = 0; i < 3 * n; ++i) V[i] = P[i] / mr[i / 3];

  const int width = gm_lane_width();
  double drift_ns[3] = {0, 0, 0}; /* width 2, width 4 (0 if not on this CPU), single drifts */
  for (int variant = 0; variant < 3; ++variant) {
    if (variant == 1 && width != 4) continue;
    double best = 1e30;
    for (int rep = 0; rep < REPEATS; ++rep) {
      const double t0 = bench_cpu_now();
      for (int k = 0; k < CALLS; ++k) {
        if (variant < 2)
          gm_kepler_drift_many_width(variant == 0 ? 2 : 4, n - 1, mu + 1, 47.0, Q + 3, V + 3, dx,
                                     dv);
        else
          for (size_t i = 1; i < n; ++i)
            gm_kepler_drift(mu[i], 47.0, Q + 3 * i, V + 3 * i, dx + 3 * (i - 1),
                            dv + 3 * (i - 1));
        sink += dx[0];
      }
      best = fmin(best, bench_cpu_now() - t0);
    }
    drift_ns[variant] = 1e9 * best / CALLS / (double)(n - 1);
  }

  /* the kick's sums: the barycentric positions by component, as the stepper has them */
  double x[8] = {0}, yy[8] = {0}, z[8] = {0}, m[8] = {0}, a[18], acc[24], g[18];
  for (size_t i = 0; i < n; ++i) x[i] = y[3 * i], yy[i] = y[3 * i + 1], z[i] = y[3 * i + 2];
  memcpy(m, c->mass, n * sizeof *m);
  double sums_ns[2];
  for (int variant = 0; variant < 2; ++variant) {
    double best = 1e30;
    for (int rep = 0; rep < REPEATS; ++rep) {
      const double t0 = bench_cpu_now();
      for (int k = 0; k < CALLS; ++k) {
        if (variant == 0)
          (width == 4 ? gm_row_sums4 : gm_row_sums2)(n, 8, x, yy, z, m, c->G, a, acc);
        else
          pb->potential_gradient(pb->ctx, y, g);
        sink += a[0] + g[0];
      }
      best = fmin(best, bench_cpu_now() - t0);
    }
    sums_ns[variant] = 1e9 * best / CALLS;
  }

  printf("Kepler drift, 5 planets by 47 d (ns per planet): %d lanes %.1f", width == 4 ? 4 : 2,
         width == 4 ? drift_ns[1] : drift_ns[0]);
  if (width == 4) printf(", 2 lanes %.1f (ratio %.2f)", drift_ns[0], drift_ns[1] / drift_ns[0]);
  printf(", single drifts %.1f\n", drift_ns[2]);
  printf("kick sums, 6 bodies (ns): own %.1f, problem callback %.1f (ratio %.2f)\n", sums_ns[0],
         sums_ns[1], sums_ns[0] / sums_ns[1]);
  FILE *f = bench_open_json(argc, argv, "celestial_kernels");
  if (f != NULL) {
    fprintf(f, "{\"lane_width\": %d, \"drift_ns_per_planet\": {\"width2\": %.3f, \"width4\": %.3f, "
               "\"single\": %.3f}, \"kick_sums_ns\": {\"own\": %.3f, \"callback\": %.3f}}\n",
            width, drift_ns[0], drift_ns[1], drift_ns[2], sums_ns[0], sums_ns[1]);
    bench_close_json(f);
  }
  gm_model_free(model);
  return sink == 42.0;
}
