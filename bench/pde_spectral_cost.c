/* Cost per step of the spectral pde solvers, as ratios to floors measured in the same run
 * (thread CPU time, best of 3):
 *  - Schrödinger on the harmonic potential (box [−10, 10), coherent state a = 2) at N = 1024 and
 *    4096: Strang split-step Fourier and the pseudospectral VI (seed 001 §5.8) per step, against
 *    one complex FFT pair of size N (the floor); Δt is half the VI's stability bound √3/ρ(H);
 *  - the 1-D wave equation with the diagonal and the spectral Hodge star (N = 1024, 4096) per
 *    leapfrog step, against the diagonal star (the floor).
 * Usage: bench_pde_spectral_cost [DIR]; writes DIR/pde_spectral_cost.json. */
#include <complex.h>
#include <fftw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "geomint/geomint.h"

#define REPEATS 3
#define BOX 20.0

static double fft_pair(size_t n, size_t reps) {
  fftw_complex *a = fftw_alloc_complex(n);
  fftw_plan f = fftw_plan_dft_1d((int)n, a, a, FFTW_FORWARD, FFTW_ESTIMATE);
  fftw_plan b = fftw_plan_dft_1d((int)n, a, a, FFTW_BACKWARD, FFTW_ESTIMATE);
  for (size_t j = 0; j < n; j++) a[j] = exp(-0.01 * (double)j);
  double best = INFINITY;
  for (int r = 0; r < REPEATS; r++) {
    double t0 = bench_cpu_now();
    for (size_t k = 0; k < reps; k++) {
      fftw_execute(f);
      for (size_t j = 0; j < n; j++) a[j] *= 1.0 / (double)n;
      fftw_execute(b);
    }
    best = fmin(best, bench_cpu_now() - t0);
  }
  fftw_destroy_plan(f);
  fftw_destroy_plan(b);
  fftw_free(a);
  return best / (double)reps;
}

static double schrodinger(gm_schrodinger_scheme sc, size_t n, double dt, size_t steps,
                          double *iters) {
  double *V = malloc(n * sizeof *V), *psi = calloc(2 * n, sizeof *psi);
  for (size_t j = 0; j < n; j++) {
    double x = -0.5 * BOX + (double)j * BOX / (double)n;
    V[j] = 0.5 * x * x;
    psi[2 * j] = pow(3.141592653589793, -0.25) * exp(-0.5 * (x - 2.0) * (x - 2.0));
  }
  gm_schrodinger_options o = gm_schrodinger_options_defaults();
  o.scheme = sc;
  o.dt = dt;
  double best = INFINITY;
  for (int r = 0; r < REPEATS; r++) {
    gm_schrodinger *s = NULL;
    gm_error err;
    if (gm_schrodinger_create(n, -0.5 * BOX, BOX, V, psi, &o, &s, &err) != GM_OK) {
      fprintf(stderr, "%s\n", err.message);
      break;
    }
    gm_schrodinger_advance(s, 1, &err); /* the VI's start level */
    size_t it0 = gm_schrodinger_iterations(s);
    double t0 = bench_cpu_now();
    if (gm_schrodinger_advance(s, steps, &err) != GM_OK) fprintf(stderr, "%s\n", err.message);
    best = fmin(best, bench_cpu_now() - t0);
    *iters = (double)(gm_schrodinger_iterations(s) - it0) / (double)steps;
    gm_schrodinger_free(s);
  }
  free(V);
  free(psi);
  return best / (double)steps;
}

static double wave(gm_hodge_kind k, size_t n, size_t steps) {
  double *u = malloc(n * sizeof *u), *v = calloc(n, sizeof *v), L = 6.283185307179586;
  for (size_t j = 0; j < n; j++) u[j] = exp(-10.0 * pow(L * (double)j / (double)n - 3.0, 2));
  double h = L / (double)n, best = INFINITY;
  for (int r = 0; r < REPEATS; r++) {
    gm_wave1d *w = NULL;
    gm_error err;
    if (gm_wave1d_create(n, L, k, 0.5 * h, u, v, &w, &err) != GM_OK) {
      fprintf(stderr, "%s\n", err.message);
      break;
    }
    double t0 = bench_cpu_now();
    gm_wave1d_advance(w, steps, &err);
    best = fmin(best, bench_cpu_now() - t0);
    gm_wave1d_free(w);
  }
  free(u);
  free(v);
  return best / (double)steps;
}

int main(int argc, char **argv) {
  FILE *json = bench_open_json(argc, argv, "pde_spectral_cost");
  if (json == NULL) return 1;
  size_t sizes[2] = {1024, 4096};
  fprintf(json, "{\n  \"benchmark\": \"pde_spectral_cost\",\n  \"rows\": [\n");
  printf("%-22s %6s %12s %10s %12s\n", "solver", "N", "us/step", "x floor", "iter/step");
  int first = 1;
  for (int z = 0; z < 2; z++) {
    size_t n = sizes[z], steps = 4000000 / n;
    double kmax = 3.141592653589793 * (double)n / BOX, rho = 0.5 * kmax * kmax + 50.0;
    double dt = 0.5 * sqrt(3.0) / rho, it_vi = 0.0, it_ss = 0.0;
    double floor_s = fft_pair(n, steps);
    double ss = schrodinger(GM_SCHRODINGER_SPLIT_STEP, n, dt, steps, &it_ss);
    double vi = schrodinger(GM_SCHRODINGER_VI, n, dt, steps / 4, &it_vi);
    double wd = wave(GM_HODGE_DIAGONAL, n, steps), wsp = wave(GM_HODGE_SPECTRAL, n, steps);
    struct {
      const char *name;
      double t, floor, its;
    } rows[5] = {{"fft-pair (floor)", floor_s, floor_s, 0.0},
                 {"schrodinger split-step", ss, floor_s, 0.0},
                 {"schrodinger vi", vi, floor_s, it_vi},
                 {"wave diagonal (floor)", wd, wd, 0.0},
                 {"wave spectral star", wsp, wd, 0.0}};
    for (int r = 0; r < 5; r++) {
      printf("%-22s %6zu %12.3f %10.2f %12.2f\n", rows[r].name, n, 1e6 * rows[r].t,
             rows[r].t / rows[r].floor, rows[r].its);
      fprintf(json,
              "%s    {\"solver\": \"%s\", \"n\": %zu, \"dt\": %.6g, \"us_per_step\": %.6g, "
              "\"ratio_to_floor\": %.4g, \"iterations_per_step\": %.4g}",
              first ? "" : ",\n", rows[r].name, n, r < 3 ? dt : 0.0, 1e6 * rows[r].t,
              rows[r].t / rows[r].floor, rows[r].its);
      first = 0;
    }
  }
  fprintf(json, "\n");
  bench_close_json(json);
  return 0;
}
