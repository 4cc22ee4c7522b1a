/* The error of the near-integrable rows on the outer solar system (500 000 days) along a fine
 * grid of step counts N, next to the step-size resonance positions predicted from the periods:
 * the splitting's modified Hamiltonian has small denominators 1 − exp(i k·ω h) (Rauch & Holman,
 * AJ 117 (1999) 1087, §3, for the Wisdom–Holman map), largest at the lowest orders, i.e. where
 * the period P of a planet (or of the Jupiter–Saturn synodic angle) is close to a whole or a
 * half number of steps. For each N the columns P_Jupiter/h, P_Saturn/h and P_synodic/h are
 * printed, and the distance dN from N to the nearest predicted resonance (nearest_resonance).
 * Reference: sofroniou-spaletta-10 with compensated summation at 50 days (N = 10 000), as
 * bench_celestial_work_precision (gauss-6 at N = 8000 differs from it and from itself at
 * N = 12 000 by 5-7e-13: the stage iteration is not compensated).
 * Error: max-norm of the final positions over Pluto's distance (as bench_celestial_work_precision).
 * usage: bench_celestial_resonance [DIR [N_MIN N_MAX N_STEP [METHOD...]]] (N_STEP 0: ratio 1.01); writes
 * DIR/celestial_resonance.json. GM_BENCH_COMPENSATED=1: the rows with compensated summation. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/geomint.h"

#define T_END 500000.0
/* sidereal periods in days from the osculating semi-major axes of the initial data would
 * move with the perturbation; the mean ones (JPL) are what the resonances follow */
#define P_JUPITER 4332.59
#define P_SATURN 10759.22
#define P_SYNODIC (1.0 / (1.0 / P_JUPITER - 1.0 / P_SATURN))

static const gm_problem *pb;
static size_t n;
static double y0[64];

static int integrate(const char *name, int compensated, size_t steps, double *y) {
  const gm_method *m = gm_method_find(name);
  if (m == NULL) {
    fprintf(stderr, "unknown method %s\n", name);
    return 1;
  }
  gm_scheme sc = {m, NULL, (m->flags & GM_IMPLICIT) ? GM_SOLVER_FIXED_POINT : GM_SOLVER_DEFAULT,
                  compensated};
  gm_integrator *it = NULL;
  gm_error err;
  if (gm_integrator_create_scheme(&sc, pb, &it, &err) != GM_OK) {
    fprintf(stderr, "%s: %s\n", name, err.message);
    return 1;
  }
  gm_integrator_set_state(it, 0.0, y0);
  gm_status st = gm_integrator_run(it, steps, T_END / (double)steps);
  if (st == GM_OK) memcpy(y, gm_integrator_state(it), n * sizeof *y);
  gm_integrator_free(it);
  return st != GM_OK;
}

/* The nearest resonance to the step count N: h (k1 n_J + k2 n_S) = 2π m with h = T/N, i.e.
 * N = T (k1/P_J + k2/P_S) / m, for |k1 + k2| <= 2 (the d'Alembert rule: the coefficient of
 * exp(i(k1 λ_J + k2 λ_S)) in the interaction is of order e^{|k1+k2|}; k1 = −k2 is the synodic
 * series, which decays only like (a_J/a_S)^|k1|) and m = 1 (m = 2, the half-integer ratios,
 * gave no peaks on the scan of docs/ode-speed.md). Returns N_res − N; *j_out = k1 + k2,
 * *m_out = m, *k_out = k1. */
static double nearest_resonance(double steps, int *k_out, int *j_out, int *m_out) {
  double best = INFINITY;
  for (int m = 1; m <= 1; ++m)
    for (int j = -2; j <= 2; ++j) {
      /* N m / T = k1 (1/P_J − 1/P_S) + j / P_S */
      const double k = round((steps * m / T_END - j / P_SATURN) * P_SYNODIC);
      const double nres = T_END * (k / P_SYNODIC + j / P_SATURN) / m;
      if (fabs(nres - steps) < fabs(best)) {
        best = nres - steps;
        *k_out = (int)k;
        *j_out = j;
        *m_out = m;
      }
    }
  return best;
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, size_t count) {
  if (count == 0) return NAN;
  qsort(v, count, sizeof *v, cmp_double);
  return count % 2 ? v[count / 2] : 0.5 * (v[count / 2 - 1] + v[count / 2]);
}

int main(int argc, char **argv) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  gm_model *model = NULL;
  if (gm_model_create("outer-solar-system", &model) != GM_OK || gm_model_build(model) != GM_OK)
    return 1;
  pb = gm_model_problem(model);
  n = gm_model_state_size(model);
  double t0, y_ref[64], y[64];
  gm_model_initial_state(model, &t0, y0);
  const size_t nq = n / 2;
  if (integrate("sofroniou-spaletta-10", 1, 10000, y_ref)) return 1;
  double scale = 0.0;
  for (size_t i = 0; i < nq; ++i) scale = fmax(scale, fabs(y_ref[i]));
  const size_t n_min = argc > 4 ? (size_t)atol(argv[2]) : 1700;
  const size_t n_max = argc > 4 ? (size_t)atol(argv[3]) : 4000;
  const size_t n_step = argc > 4 ? (size_t)atol(argv[4]) : 0; /* 0: ratio 1.01 */
  const char *defaults[] = {"aba-10-4", "aba-10-6-4", "sabac-4-jacobi", "wh-c11"};
  const char **methods = argc > 5 ? (const char **)argv + 5 : defaults;
  const size_t n_methods = argc > 5 ? (size_t)(argc - 5) : sizeof defaults / sizeof *defaults;
  const char *comp_env = getenv("GM_BENCH_COMPENSATED");
  const int compensated = comp_env != NULL && strcmp(comp_env, "1") == 0;
  printf("summation: %s (GM_BENCH_COMPENSATED=1 for compensated)\n", compensated ? "compensated" : "plain");
  FILE *f = bench_open_json(argc, argv, "celestial_resonance");
  if (f == NULL) return 1;
  fprintf(f, "{\n \"benchmark\": \"celestial_resonance\",\n \"rows\": [\n");
  printf("%6s %8s %7s %7s %7s %6s %4s %2s %2s", "N", "h", "PJ/h", "PS/h", "Psyn/h", "dN", "k1",
         "j", "m");
  for (size_t k = 0; k < n_methods; ++k) printf(" %14s", methods[k]);
  printf("\n");
  int first = 1;
  static double near_err[8][4096], far_err[8][4096];
  size_t n_near = 0, n_far = 0;
  for (double nd = (double)n_min; nd <= (double)n_max;
       nd = n_step ? nd + (double)n_step : ceil(nd * 1.01)) {
    const size_t steps = (size_t)nd;
    const double h = T_END / (double)steps;
    const double rj = P_JUPITER / h, rs = P_SATURN / h, rsyn = P_SYNODIC / h;
    int k1 = 0, j = 0, m = 1;
    const double dn = nearest_resonance(nd, &k1, &j, &m);
    printf("%6zu %8.2f %7.2f %7.2f %7.2f %6.1f %4d %2d %2d", steps, h, rj, rs, rsyn, dn, k1, j, m);
    for (size_t k = 0; k < n_methods; ++k) {
      if (integrate(methods[k], compensated, steps, y)) return 1;
      double e = 0.0;
      for (size_t i = 0; i < nq; ++i) e = fmax(e, fabs(y[i] - y_ref[i]));
      e /= scale;
      printf(" %14.2e", e);
      if (k < 8 && fabs(dn) <= 1.5 && n_near < 4096) near_err[k][n_near] = e;
      if (k < 8 && fabs(dn) >= 4.0 && n_far < 4096) far_err[k][n_far] = e;
      fprintf(f, "%s  {\"method\": \"%s\", \"steps\": %zu, \"error\": %.3e, \"P_jupiter_over_h\": "
              "%.3f, \"P_saturn_over_h\": %.3f, \"P_synodic_over_h\": %.3f, \"to_resonance\": %.2f, \"k1\": %d, \"j\": %d, \"m\": %d}",
              first ? "" : ",\n", methods[k], steps, e, rj, rs, rsyn, dn, k1, j, m);
      first = 0;
    }
    printf("\n");
    if (fabs(dn) <= 1.5 && n_near < 4096) ++n_near;
    if (fabs(dn) >= 4.0 && n_far < 4096) ++n_far;
  }
  printf("median error within 1.5 steps of a resonance (%zu N) / at least 4 steps away (%zu N):\n",
         n_near, n_far);
  for (size_t k = 0; k < n_methods && k < 8; ++k) {
    const double a = median(near_err[k], n_near), b = median(far_err[k], n_far);
    printf("  %-16s %9.2e / %9.2e = %6.1f\n", methods[k], a, b, a / b);
  }
  fprintf(f, "\n ]\n}\n");
  fclose(f);
  gm_model_free(model);
  return 0;
}
