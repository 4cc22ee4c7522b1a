/* How much does the convolutional PML reflect? A 2-D TM pulse (differentiated Gaussian soft
 * dipole, Ez) starts at the centre of a 40 x 40 cell interior surrounded by a CPML of d cells;
 * a probe 2 cells from the PML records Ez. The same interior inside a vacuum grid so large that
 * nothing comes back within the window gives the reference. The reflection is
 *   R = max_t |Ez_pml(t) − Ez_ref(t)| / max_t |Ez_ref(t)|   (Taflove & Hagness §7.11)
 * in dB, for several thicknesses with the default CFS parameters (gm_cpml_defaults: grading
 * m = 3, σ_max = σ_opt, κ_max = 1, α_max = 0.05).
 *
 *   example_maxwell_pml_reflection [CSV]    (CSV: the error time series at every thickness)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "geomint/geomint.h"

#define INTERIOR 40   /* cells of the interior per axis (h = 1) */
#define REF_MARGIN 200 /* cells of vacuum around the interior in the reference */
#define STEPS 600
#define DT 0.5

static const double source_x[3] = {20.0, 20.0, 0.0};
static const double probe_x[3] = {2.0, 23.0, 0.0}; /* 2 cells from the -x PML, off-centre */

/* Run the interior with margin cells of padding (CPML of that thickness, or PEC far away when
 * pml == 0) and return the probe's samples (STEPS values, malloc'd). */
static double *run(size_t margin, int pml) {
  gm_yee_grid g = {GM_YEE_2D_TM,
                   {INTERIOR + 2 * margin, INTERIOR + 2 * margin, 1},
                   {1, 1, 1},
                   {-(double)margin, -(double)margin, 0}};
  gm_yee_options opt = gm_yee_defaults();
  opt.dt = DT;
  opt.n_threads = 1;
  for (int f = 0; f < 4; ++f) {
    opt.boundary[f].kind = pml ? GM_BOUNDARY_CPML : GM_BOUNDARY_PEC;
    opt.boundary[f].pml = gm_cpml_defaults();
    opt.boundary[f].pml.thickness = margin;
  }
  gm_yee *s = NULL;
  gm_error err = {{0}};
  if (gm_yee_create(&g, NULL, &opt, &s, &err) != GM_OK) {
    fprintf(stderr, "%s\n", err.message);
    exit(1);
  }
  /* differentiated Gaussian, width 3 (spectrum peak 1/(2π·3) ≈ 0.053: 19 cells per
   * wavelength; content up to ~0.15, 7 cells per wavelength) */
  gm_point_source src = {GM_EZ, {source_x[0], source_x[1], 0}, GM_SOURCE_SOFT,
                         {GM_WAVE_DGAUSSIAN, 1.0, 0.0, 3.0, 18.0, 0.0, NULL, NULL}};
  size_t probe;
  if (gm_yee_add_point_source(s, &src, NULL) != GM_OK ||
      gm_yee_add_probe(s, GM_EZ, probe_x, STEPS, &probe) != GM_OK ||
      gm_yee_advance(s, STEPS) != GM_OK) {
    fprintf(stderr, "%s\n", gm_yee_errmsg(s));
    exit(1);
  }
  size_t n;
  const double *t, *re, *im;
  gm_yee_probe_samples(s, probe, &n, &t, &re, &im);
  double *out = malloc(STEPS * sizeof *out);
  for (size_t i = 0; i < STEPS; ++i) out[i] = i < n ? re[i] : NAN;
  gm_yee_free(s);
  return out;
}

int main(int argc, char **argv) {
  /* the reference: a wave needs ~2 × 200 cells to return, STEPS × DT = 300 is less */
  double *ref = run(REF_MARGIN, 0);
  double ref_max = 0;
  for (size_t i = 0; i < STEPS; ++i) ref_max = fmax(ref_max, fabs(ref[i]));
  FILE *csv = argc > 1 ? fopen(argv[1], "w") : NULL;
  if (argc > 1 && csv == NULL) {
    fprintf(stderr, "cannot write %s\n", argv[1]);
    return 1;
  }
  static const size_t thickness[] = {4, 6, 8, 10, 12, 16, 20};
  enum { N_T = sizeof thickness / sizeof thickness[0] };
  double *err[N_T];
  printf("CPML reflection, 2-D TM, %d x %d interior, probe 2 cells from the layer\n", INTERIOR,
         INTERIOR);
  printf("%10s %14s %10s\n", "thickness", "max|error|/max", "dB");
  for (size_t k = 0; k < N_T; ++k) {
    double *e = run(thickness[k], 1);
    double worst = 0;
    for (size_t i = 0; i < STEPS; ++i) {
      e[i] = fabs(e[i] - ref[i]) / ref_max;
      worst = fmax(worst, e[i]);
    }
    err[k] = e;
    printf("%10zu %14.3e %10.1f\n", thickness[k], worst, 20 * log10(worst));
  }
  if (csv != NULL) {
    fprintf(csv, "t,reference");
    for (size_t k = 0; k < N_T; ++k) fprintf(csv, ",d%zu", thickness[k]);
    fputc('\n', csv);
    for (size_t i = 0; i < STEPS; ++i) {
      /* Ez of step i+1 is sampled at t = (i + 1/2) DT */
      fprintf(csv, "%.9g,%.9g", ((double)i + 0.5) * DT, ref[i] / ref_max);
      for (size_t k = 0; k < N_T; ++k) fprintf(csv, ",%.9g", err[k][i]);
      fputc('\n', csv);
    }
    fclose(csv);
  }
  for (size_t k = 0; k < N_T; ++k) free(err[k]);
  free(ref);
  return 0;
}
