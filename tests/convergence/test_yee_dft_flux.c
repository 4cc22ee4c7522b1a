/* DFT flux spectra (yee_dft.c): a dielectric slab's transmission and reflection spectra from
 * a normalisation run (vacuum) and a run with the slab, against the Airy formula
 * T = 1 / (1 + F sin²(2π n d f)), F = 4R₀/(1 − R₀)², R₀ = ((n − 1)/(n + 1))², c = 1.
 * 1-D, h = 0.005: at f = 1 a wavelength in the slab (n = 2) is 100 cells. The discretised
 * slab's Airy formula takes the Yee wave number in the slab, sin(k h/2) = (n h/Δt) sin(πfΔt)
 * (Taflove & Hagness eq. 4.12), instead of 2π n f. */
#include <stdio.h>

#include "yee_util.h"

#define N_FREQ 41

typedef struct slab_run {
  double trans[N_FREQ], refl[N_FREQ];
} slab_run;

static const double h = 0.005;

/* One run (slab or vacuum). refl_incident: the vacuum run's flux object at the reflection
 * plane, subtracted before taking that spectrum (NULL: none). Keeps that object in *keep. */
static double step_dt;

static void run(int slab, const double *freq, gm_yee_dft_flux *refl_incident, slab_run *out,
                gm_yee_dft_flux **keep) {
  gm_yee_grid g = {GM_YEE_1D, {1200, 1, 1}, {h, 1, 1}, {0, 0, 0}};
  gm_yee_materials *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_materials_create(&g, &m, &err), GM_OK);
  if (slab) {
    const gm_medium glass = {4.0, 1.0, 0.0};
    const double lo[3] = {3.0, 0, 0}, hi[3] = {4.0, 0, 0};
    cr_assert_eq(gm_yee_paint_box(m, lo, hi, &glass), GM_OK);
  }
  gm_yee_options o = gm_yee_defaults();
  o.n_threads = 1;
  o.boundary[0].kind = o.boundary[1].kind = GM_BOUNDARY_CPML;
  o.boundary[0].pml.thickness = o.boundary[1].pml.thickness = 80;
  gm_yee *s = NULL;
  cr_assert_eq(gm_yee_create(&g, m, &o, &s, &err), GM_OK, "%s", err.message);
  const gm_point_source src = {GM_EZ, {1.0, 0, 0}, GM_SOURCE_SOFT,
                               {GM_WAVE_GAUSSIAN, 1.0, 0.6, 0.4, 2.4, 0.0, NULL, NULL}};
  cr_assert_eq(gm_yee_add_point_source(s, &src, NULL), GM_OK);
  gm_yee_dft_flux *ft = NULL, *fr = NULL;
  cr_assert_eq(gm_yee_dft_flux_create(s, 0, 1000, N_FREQ, freq, &ft), GM_OK, "%s",
               gm_yee_errmsg(s));
  cr_assert_eq(gm_yee_dft_flux_create(s, 0, 400, N_FREQ, freq, &fr), GM_OK, "%s",
               gm_yee_errmsg(s));
  step_dt = gm_yee_dt(s);
  cr_assert_eq(gm_yee_advance_to(s, 60.0), GM_OK);
  if (refl_incident) cr_assert_eq(gm_yee_dft_flux_subtract(fr, refl_incident), GM_OK);
  cr_assert_eq(gm_yee_dft_flux_spectrum(ft, out->trans), GM_OK);
  cr_assert_eq(gm_yee_dft_flux_spectrum(fr, out->refl), GM_OK);
  gm_yee_free(s);
  gm_yee_dft_flux_free(ft);
  if (keep)
    *keep = fr;
  else
    gm_yee_dft_flux_free(fr);
  gm_yee_materials_free(m);
}

/* Measured over f = 0.2 .. 1.0: max |T − T_Airy| 6.4e-4 (with the discretised k: 2.2e-4),
 * max |R − R_Airy| 6.4e-4, max |R + T − 1| 5.6e-8 (see the printout). */
Test(yee_dft_flux, slab_against_airy) {
  double freq[N_FREQ];
  for (int k = 0; k < N_FREQ; ++k) freq[k] = 0.2 + 0.02 * k;
  slab_run vac, sl;
  gm_yee_dft_flux *inc = NULL;
  run(0, freq, NULL, &vac, &inc);
  run(1, freq, inc, &sl, NULL);
  gm_yee_dft_flux_free(inc);
  const double n = 2.0, d = 1.0, r0 = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
  const double F = 4 * r0 / ((1 - r0) * (1 - r0));
  double et = 0, er = 0, ec = 0, ed = 0;
  for (int k = 0; k < N_FREQ; ++k) {
    const double T = sl.trans[k] / vac.trans[k], R = -sl.refl[k] / vac.refl[k];
    const double s = sin(2 * YEE_TEST_PI * n * d * freq[k]);
    const double Ta = 1.0 / (1.0 + F * s * s);
    et = fmax(et, fabs(T - Ta));
    const double kd = 2.0 / h * asin(n * h / step_dt * sin(YEE_TEST_PI * freq[k] * step_dt));
    const double sd = sin(kd * d);
    ed = fmax(ed, fabs(T - 1.0 / (1.0 + F * sd * sd)));
    er = fmax(er, fabs(R - (1 - Ta)));
    ec = fmax(ec, fabs(R + T - 1));
  }
  printf("slab: max |T - T_Airy| %.2e (discretised k: %.2e), max |R - R_Airy| %.2e, "
         "max |R + T - 1| %.2e\n", et, ed, er, ec);
  cr_assert_lt(et, 1e-3, "T error %.3e", et);
  cr_assert_lt(er, 1e-3, "R error %.3e", er);
  cr_assert_lt(ec, 1e-6, "R + T - 1: %.3e", ec);
  cr_assert_lt(ed, et, "the discretised slab's formula is not closer: %.3e", ed);
}

/* A plane in a CPML layer, at a wall, and a frequency above Nyquist are errors. */
Test(yee_dft_flux, bad_planes_and_frequencies) {
  gm_yee_grid g = {GM_YEE_1D, {100, 1, 1}, {h, 1, 1}, {0, 0, 0}};
  gm_yee_options o = gm_yee_defaults();
  o.boundary[0].kind = o.boundary[1].kind = GM_BOUNDARY_CPML;
  gm_yee *s = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_create(&g, NULL, &o, &s, &err), GM_OK, "%s", err.message);
  gm_yee_dft_flux *f = NULL;
  const double ok[1] = {1.0}, high[1] = {1e6};
  cr_assert_eq(gm_yee_dft_flux_create(s, 0, 5, 1, ok, &f), GM_EINVAL);
  cr_assert(strstr(gm_yee_errmsg(s), "CPML") != NULL, "%s", gm_yee_errmsg(s));
  cr_assert_eq(gm_yee_dft_flux_create(s, 0, 0, 1, ok, &f), GM_EINVAL);
  cr_assert_eq(gm_yee_dft_flux_create(s, 0, 50, 1, high, &f), GM_EINVAL);
  cr_assert(strstr(gm_yee_errmsg(s), "Nyquist") != NULL, "%s", gm_yee_errmsg(s));
  cr_assert_eq(gm_yee_dft_flux_create(s, 1, 50, 1, ok, &f), GM_EINVAL);
  cr_assert_eq(gm_yee_dft_flux_create(s, 0, 50, 1, ok, &f), GM_OK);
  gm_yee_free(s);
  gm_yee_dft_flux_free(f);
}
