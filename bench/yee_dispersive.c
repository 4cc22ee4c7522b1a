/* The Yee step with a Drude medium in 20 % of the cells against the vacuum step (issue 23:
 * ≥ 0.8× the vacuum cell rate). A 3-D PEC box of N³ cells (default 96), one thread, Courant
 * 0.99; the Drude medium (f_p = 0.05 per cell, γ = 0.002) fills a central cube of 20 % of the
 * cells. Two dispersive cases: ε∞ = 1 (the grid's ε is uniform, so the Yee kernels are the
 * vacuum's and only the ADE passes are extra) and ε∞ = 2 (per-edge coefficient arrays as any
 * inhomogeneous scene). Timing: CPU time of the thread, REPEATS interleaved rounds (vacuum,
 * Drude ε∞ = 1, Drude ε∞ = 2 in each), the best round of each counts.
 *
 *   bench_yee_dispersive [DIR] [N] [STEPS]      (defaults bench/results, 96, 60)
 *
 * Writes DIR/yee_dispersive.json with the rates (Mcells·steps/s) and the ratios to vacuum. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "geomint/fields.h"

#define REPEATS 5

static gm_yee *make(size_t n, int dispersive, double eps_inf) {
  gm_yee_grid g = {GM_YEE_3D, {n, n, n}, {1, 1, 1}, {0, 0, 0}};
  gm_yee_materials *m = NULL;
  gm_error err = {{0}};
  if (gm_yee_materials_create(&g, &m, &err) != GM_OK) return NULL;
  if (dispersive) {
    const gm_pole drude = {GM_POLE_DRUDE, 0.05, 0.002, 0.0};
    const gm_medium metal = {eps_inf, 1.0, 0.0};
    const double side = cbrt(0.2) * (double)n, lo0 = 0.5 * ((double)n - side);
    const double lo[3] = {lo0, lo0, lo0}, hi[3] = {lo0 + side, lo0 + side, lo0 + side};
    if (gm_yee_materials_set_poles(m, 1, &drude) != GM_OK ||
        gm_yee_paint_box(m, lo, hi, &metal) != GM_OK) {
      gm_yee_materials_free(m);
      return NULL;
    }
  }
  gm_yee_options o = gm_yee_defaults();
  o.n_threads = 1;
  o.smoothing = GM_YEE_SMOOTHING_NONE; /* a cube on cell faces: smoothing would change nothing */
  gm_yee *s = NULL;
  gm_status st = gm_yee_create(&g, m, &o, &s, &err);
  gm_yee_materials_free(m);
  if (st != GM_OK) {
    fprintf(stderr, "%s\n", err.message);
    return NULL;
  }
  const gm_point_source src = {GM_EZ, {0.3 * (double)n, 0.4 * (double)n, 0.45 * (double)n},
                               GM_SOURCE_SOFT,
                               {GM_WAVE_GAUSSIAN, 1.0, 0.05, 10.0, 40.0, 0.0, NULL, NULL}};
  gm_yee_add_point_source(s, &src, NULL);
  return s;
}

int main(int argc, char **argv) {
  const size_t n = argc > 2 ? (size_t)atol(argv[2]) : 96;
  const size_t steps = argc > 3 ? (size_t)atol(argv[3]) : 60;
  gm_yee *s[3] = {make(n, 0, 1.0), make(n, 1, 1.0), make(n, 1, 2.0)};
  if (!s[0] || !s[1] || !s[2]) return 1;
  double best[3] = {INFINITY, INFINITY, INFINITY};
  for (int r = 0; r < REPEATS; ++r)
    for (int k = 0; k < 3; ++k) {
      const double t0 = bench_cpu_now();
      if (gm_yee_advance(s[k], steps) != GM_OK) {
        fprintf(stderr, "%s\n", gm_yee_errmsg(s[k]));
        return 1;
      }
      best[k] = fmin(best[k], bench_cpu_now() - t0);
    }
  const double cells = (double)n * (double)n * (double)n * (double)steps / 1e6;
  const char *name[3] = {"vacuum", "drude_20pct_eps1", "drude_20pct_eps2"};
  printf("Yee step, %zu^3 PEC box, 1 thread, best of %d rounds of %zu steps (CPU time)\n", n,
         REPEATS, steps);
  printf("%-18s %14s %10s %9s\n", "case", "Mcells*steps/s", "vs vacuum", "one sweep");
  for (int k = 0; k < 3; ++k)
    printf("%-18s %14.1f %10.3f %9d\n", name[k], cells / best[k], best[0] / best[k],
           gm_yee_one_sweep(s[k]));
  FILE *f = bench_open_json(argc, argv, "yee_dispersive");
  if (f != NULL) {
    fprintf(f, "{\n  \"n\": %zu, \"steps\": %zu, \"repeats\": %d, \"goal_ratio\": 0.8,\n  \"rows\": [\n",
            n, steps, REPEATS);
    for (int k = 0; k < 3; ++k)
      fprintf(f, "    {\"case\": \"%s\", \"mcells_per_s\": %.3f, \"ratio\": %.4f}%s\n", name[k],
              cells / best[k], best[0] / best[k], k < 2 ? "," : "");
    bench_close_json(f);
  }
  for (int k = 0; k < 3; ++k) gm_yee_free(s[k]);
  return 0;
}
