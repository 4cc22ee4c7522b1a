/* Cost per grid point per step of the pde schemes on sine-Gordon (breather, ω = 0.5, [−20, 20)
 * periodic, Δt = Δx/2) at N = 10⁴ and 10⁶, against the floor of one LF stencil sweep measured
 * in the same run: the ratios are the results. Thread CPU time, best of 3 repeats; steps chosen
 * so every measurement touches ~4·10⁶ point-steps (fewer at N = 10⁶ for the implicit rows).
 * Usage: bench_pde_cost [DIR] [--quick] (--quick: N = 10⁴ only). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/geomint.h"

#define REPEATS 3

static double measure(const char *scheme, size_t n, size_t steps, gm_pde_stats *stats) {
  const gm_pde_scheme *s = NULL;
  gm_pde_scheme_find(scheme, &s);
  if ((s->kind == GM_PDE_PREISSMANN || s->kind == GM_PDE_BOX_SDIRK2) && n % 2 == 0)
    n += 1; /* odd n: 𝕂 singular */
  double L = 20.0, h = 2.0 * L / (double)n, om = 0.5, k = sqrt(1.0 - om * om);
  double *s0 = calloc(3 * n, sizeof *s0);
  if (s0 == NULL) return NAN;
  gm_pde_equation eq = gm_pde_sine_gordon();
  gm_pde_grid g = {n, h, -L, {0}};
  for (size_t i = 0; i < n; i++) s0[3 * i + 1] = 4.0 * k / cosh(k * gm_pde_point_x(s, &g, i));
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = 0.5 * h;
  double best = INFINITY;
  for (int r = 0; r < REPEATS; r++) {
    gm_pde *p = NULL;
    gm_error err;
    if (gm_pde_create(&g, &eq, s, &o, s0, &p, &err) != GM_OK) {
      fprintf(stderr, "%s: %s\n", scheme, err.message);
      break;
    }
    double t0 = bench_cpu_now();
    gm_status st = gm_pde_advance(p, steps, &err);
    double el = bench_cpu_now() - t0;
    if (st != GM_OK) fprintf(stderr, "%s: %s\n", scheme, err.message);
    if (el < best) best = el;
    *stats = gm_pde_get_stats(p);
    gm_pde_free(p);
  }
  free(s0);
  return best / ((double)steps * (double)n);
}

int main(int argc, char **argv) {
  int quick = argc > 2 && strcmp(argv[2], "--quick") == 0;
  FILE *json = bench_open_json(argc, argv, "pde_cost");
  if (json == NULL) return 1;
  /* gauss-prk with few steps (about a second per step at N = 10⁴), and at N = 10⁶ only when
   * GM_PDE_COST_GAUSS_1E6=1 is set: a step takes about a minute there (its condensed Newton
   * matrix needs about 0.55 GB since issue 28; 11 GB before) */
  const char *schemes[] = {"lf", "ec", "ms", "euler-box", "preissmann", "box-sdirk2", "gauss-prk"};
  size_t sizes[] = {10000, 1000000};
  fprintf(json, "{\n  \"benchmark\": \"pde_cost\",\n  \"rows\": [\n");
  printf("%-11s %8s %12s %10s %14s\n", "scheme", "N", "ns/pt/step", "x LF", "Newton it/step");
  int first = 1;
  for (int z = 0; z < (quick ? 1 : 2); z++) {
    size_t n = sizes[z], steps_lf = 4000000 / n > 0 ? 4000000 / n : 1;
    gm_pde_stats st;
    double floor_cost = measure("lf", n, steps_lf * 4, &st);
    for (size_t q = 0; q < sizeof schemes / sizeof schemes[0]; q++) {
      size_t steps = q == 0 ? steps_lf * 4 : steps_lf;
      int gauss = strcmp(schemes[q], "gauss-prk") == 0;
      if (gauss && n > 10000 && getenv("GM_PDE_COST_GAUSS_1E6") == NULL) continue;
      if (gauss) steps = 4;
      if (steps < 2) steps = 2;
      double c = q == 0 ? floor_cost : measure(schemes[q], n, steps, &st);
      double its = q == 0 ? 0.0 : (double)st.newton_iterations / (double)st.steps;
      if (schemes[q][0] == 'e' && schemes[q][1] == 'c') its /= (double)n; /* per point */
      printf("%-11s %8zu %12.2f %10.2f %14.2f\n", schemes[q], n, 1e9 * c, c / floor_cost, its);
      fprintf(json, "%s    {\"scheme\": \"%s\", \"n\": %zu, \"ns_per_point_step\": %.4g, "
                    "\"ratio_to_lf\": %.4g, \"newton_iterations_per_step\": %.4g}",
              first ? "" : ",\n", schemes[q], n, 1e9 * c, c / floor_cost, its);
      first = 0;
    }
  }
  fprintf(json, "\n");
  bench_close_json(json);
  return 0;
}
