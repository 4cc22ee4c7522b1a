/* A 3-D rectangular PEC cavity rung by a short current pulse: the resonances harminv finds in
 * a probe signal against the analytic ones, f = ½ |(m/a, n/b, p/c)| (units with c = 1).
 *
 *   ./example_yee_cavity
 *
 * The plan/execute shape of every geomint field solver: describe the grid and materials,
 * create (all allocation and precomputation), add sources and probes, advance, read. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "geomint/geomint.h"

int main(void) {
  const double a = 1.0, b = 0.8, c = 0.6, h = 1.0 / 20.0;
  gm_yee_grid grid = {GM_YEE_3D, {20, 16, 12}, {h, h, h}, {0.0, 0.0, 0.0}};
  gm_yee_options opt = gm_yee_defaults(); /* PEC on every face, dt = 0.99 × Courant limit */
  opt.courant = 0.5;
  gm_yee *s = NULL;
  gm_error err;
  if (gm_yee_create(&grid, NULL, &opt, &s, &err) != GM_OK) {
    fprintf(stderr, "yee: %s\n", err.message);
    return 1;
  }
  /* a Gaussian pulse around f = 1.2 on three dipoles, to ring modes of every polarization */
  const double width = 1.0 / (2.0 * 3.14159265358979 * 0.3);
  const gm_waveform pulse = {GM_WAVE_GAUSSIAN, 1.0, 1.2, width, 6.0 * width, 0.0, NULL, NULL};
  const double where[3][3] = {{0.377, 0.233, 0.128}, {0.613, 0.346, 0.205}, {0.211, 0.457, 0.233}};
  for (int k = 0; k < 3; ++k) {
    gm_point_source dipole = {(gm_yee_component)k, {where[k][0], where[k][1], where[k][2]},
                              GM_SOURCE_SOFT, pulse};
    if (gm_yee_add_point_source(s, &dipole, NULL) != GM_OK) {
      fprintf(stderr, "source: %s\n", gm_yee_errmsg(s));
      return 1;
    }
  }
  const double dt = gm_yee_dt(s);
  gm_yee_advance(s, (size_t)ceil(12.0 * width / dt)); /* let the pulse end */
  const size_t n = (size_t)(100.0 / dt);
  const double at[3] = {0.371, 0.489, 0.161};
  gm_yee_add_probe(s, GM_EZ, at, n, NULL);
  if (gm_yee_advance(s, n) != GM_OK) {
    fprintf(stderr, "advance: %s\n", gm_yee_errmsg(s));
    return 1;
  }
  const double *ez;
  size_t m;
  gm_yee_probe_samples(s, 0, &m, NULL, &ez, NULL);
  /* the first difference drops the static field the pulse's small net charge leaves */
  double *sig = malloc(m * sizeof(double));
  for (size_t i = 0; i + 1 < m; ++i) sig[i] = ez[i + 1] - ez[i];
  gm_harminv_mode modes[64];
  size_t found = 0;
  if (gm_harminv(m - 1, sig, NULL, dt, 0.6, 1.6, 0, 64, modes, &found, &err) != GM_OK) {
    fprintf(stderr, "harminv: %s\n", err.message);
    return 1;
  }
  printf("%zu steps of dt = %.5f; Ez probe; harminv modes in [0.6, 1.6] with error < 1e-4:\n", gm_yee_step(s), dt);
  printf("  %-12s %-12s %-10s %9s   %-7s  %s\n", "f (harminv)", "f (analytic)", "(m n p)",
         "rel. diff", "|amp|", "harminv error");
  for (size_t i = 0; i < found; ++i) {
    if (modes[i].error > 1e-4) continue; /* harminv's own figure of merit: not resolved */
    /* the analytic mode nearest to it */
    double best = INFINITY;
    int bm[3] = {0, 0, 0};
    for (int p = 0; p <= 4; ++p)
      for (int q = 0; q <= 4; ++q)
        for (int r = 0; r <= 4; ++r) {
          if ((p == 0) + (q == 0) + (r == 0) > 1) continue;
          const double f = 0.5 * sqrt(p * p / (a * a) + q * q / (b * b) + r * r / (c * c));
          if (fabs(f - modes[i].frequency) < fabs(best - modes[i].frequency)) {
            best = f;
            bm[0] = p;
            bm[1] = q;
            bm[2] = r;
          }
        }
    printf("  %-12.6f %-12.6f (%d %d %d)    %9.2e   %.1e  %.1e\n", modes[i].frequency, best,
           bm[0], bm[1], bm[2], (modes[i].frequency - best) / best, modes[i].amplitude,
           modes[i].error);
  }
  free(sig);
  gm_yee_free(s);
  return 0;
}
