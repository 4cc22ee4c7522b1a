/* Dispersive media (yee_dispersive.c) in 1-D against the analytic Fresnel and transfer-matrix
 * results: a Drude half-space's reflection and a Lorentz slab's transmission spectra, each
 * from a normalisation run (vacuum) and a run with the medium, through DFT flux planes
 * (yee_dft.c). Each is compared with the formula evaluated with ε(f) of the continuous medium
 * and with ε_d(f) of the discretised one (gm_medium_epsilon with dt: the continuous ε at
 * tan(πfΔt)/(πΔt)); the latter also takes the Yee wave number in the medium,
 * sin(k̃h/2) = (h/Δt) √ε_d sin(πfΔt) (Taflove & Hagness eq. 4.12 with ε_d), for the phase. */
#include <complex.h>
#include <stdio.h>

#include "yee_util.h"

#define N_FREQ 33

static const double h = 0.005;

typedef struct spectra {
  double trans[N_FREQ], refl[N_FREQ], dt;
} spectra;

/* One run: cells in [lo, hi] painted with (medium, poles) when n_poles > 0 (else vacuum). */
static void run(const gm_medium *md, size_t n_poles, const gm_pole *poles, double lo_x,
                double hi_x, const double *freq, gm_yee_dft_flux *refl_incident, spectra *out,
                gm_yee_dft_flux **keep) {
  gm_yee_grid g = {GM_YEE_1D, {1200, 1, 1}, {h, 1, 1}, {0, 0, 0}};
  gm_yee_materials *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_materials_create(&g, &m, &err), GM_OK);
  if (n_poles > 0) {
    cr_assert_eq(gm_yee_materials_set_poles(m, n_poles, poles), GM_OK, "%s",
                 gm_yee_materials_errmsg(m));
    const double lo[3] = {lo_x, 0, 0}, hi[3] = {hi_x, 0, 0};
    cr_assert_eq(gm_yee_paint_box(m, lo, hi, md), GM_OK);
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
  out->dt = gm_yee_dt(s);
  cr_assert_eq(gm_yee_advance_to(s, 80.0), GM_OK, "%s", gm_yee_errmsg(s));
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

static double complex eps_of(const gm_medium *md, size_t n, const gm_pole *p, double f,
                             double dt) {
  double e[2];
  gm_error err = {{0}};
  cr_assert_eq(gm_medium_epsilon(md, n, p, f, dt, e, &err), GM_OK, "%s", err.message);
  return e[0] + I * e[1];
}

/* Wave number in a medium of permittivity eps at f: continuous 2πf√ε, or the Yee one. */
static double complex wavenumber(double complex eps, double f, double dt) {
  if (dt == 0.0) return 2 * YEE_TEST_PI * f * csqrt(eps);
  return 2.0 / h * casin(h / dt * csqrt(eps) * sin(YEE_TEST_PI * f * dt));
}

/* Slab of thickness d (d = INFINITY: half-space) between vacua: reflectance and transmittance
 * (Born & Wolf §1.6 with one layer: r = (r₁ + r₂e^{2iδ})/(1 + r₁r₂e^{2iδ}), t = t₁t₂e^{iδ}/(…)). */
static void slab_rt(double complex eps, double f, double dt, double d, double *R, double *T) {
  const double complex n = csqrt(eps);
  const double complex r1 = (1 - n) / (1 + n), r2 = -r1;
  if (isinf(d)) {
    *R = cabs(r1) * cabs(r1);
    *T = 0;
    return;
  }
  const double complex k = wavenumber(eps, f, dt), ph = cexp(I * k * d);
  const double complex den = 1 + r1 * r2 * ph * ph;
  const double complex r = (r1 + r2 * ph * ph) / den;
  const double complex t = (2 / (1 + n)) * (2 * n / (1 + n)) * ph / den;
  *R = cabs(r) * cabs(r);
  *T = cabs(t) * cabs(t);
}

/* Drude half-space (f_p = 1, γ = 0.1, from x = 3 through the +x CPML) over f = 0.3 .. 0.94:
 * below and above the plasma frequency, 200 to 670 cells per vacuum wavelength. Measured max
 * |R − R_Fresnel|: continuous ε 2.0e-4, discretised ε_d 9.3e-5 (see the printout). */
Test(yee_dispersive, drude_half_space_reflection) {
  double freq[N_FREQ];
  for (int k = 0; k < N_FREQ; ++k) freq[k] = 0.3 + 0.02 * k;
  const gm_medium vac = gm_medium_vacuum();
  const gm_pole drude = {GM_POLE_DRUDE, 1.0, 0.1, 0.0};
  spectra v, d;
  gm_yee_dft_flux *inc = NULL;
  run(&vac, 0, NULL, 0, 0, freq, NULL, &v, &inc);
  run(&vac, 1, &drude, 3.0, 10.0, freq, inc, &d, NULL);
  gm_yee_dft_flux_free(inc);
  double err_c = 0, err_d = 0;
  for (int k = 0; k < N_FREQ; ++k) {
    const double R = -d.refl[k] / v.refl[k];
    double Rc, Rd, T;
    slab_rt(eps_of(&vac, 1, &drude, freq[k], 0), freq[k], 0, INFINITY, &Rc, &T);
    slab_rt(eps_of(&vac, 1, &drude, freq[k], d.dt), freq[k], d.dt, INFINITY, &Rd, &T);
    err_c = fmax(err_c, fabs(R - Rc));
    err_d = fmax(err_d, fabs(R - Rd));
  }
  printf("drude half-space: max |R - R_Fresnel| continuous eps %.3g, discretised eps %.3g\n",
         err_c, err_d);
  cr_assert_lt(err_d, 3e-4, "discretised: %g", err_d);
  cr_assert_lt(err_c, 6e-4, "continuous: %g", err_c);
  cr_assert_lt(err_d, err_c, "the discretised medium's formula should fit better");
}

/* Lorentz slab (ε∞ = 2, Δε = 1.5, f0 = 0.6, γ = 0.05; x in [3, 4]) over f = 0.3 .. 0.94,
 * across the resonance. Measured max |T − T_tm|: continuous ε 2.6e-4, discretised 3.6e-5;
 * max |R − R_tm| 3.4e-4 and 2.8e-4. */
Test(yee_dispersive, lorentz_slab_transmission) {
  double freq[N_FREQ];
  for (int k = 0; k < N_FREQ; ++k) freq[k] = 0.3 + 0.02 * k;
  const gm_medium vac = gm_medium_vacuum(), glass = {2.0, 1.0, 0.0};
  const gm_pole lorentz = {GM_POLE_LORENTZ, 0.6, 0.05, 1.5};
  spectra v, d;
  gm_yee_dft_flux *inc = NULL;
  run(&vac, 0, NULL, 0, 0, freq, NULL, &v, &inc);
  run(&glass, 1, &lorentz, 3.0, 4.0, freq, inc, &d, NULL);
  gm_yee_dft_flux_free(inc);
  double err_c = 0, err_d = 0, err_rc = 0, err_rd = 0;
  for (int k = 0; k < N_FREQ; ++k) {
    const double T = d.trans[k] / v.trans[k], R = -d.refl[k] / v.refl[k];
    double Rc, Tc, Rd, Td;
    slab_rt(eps_of(&glass, 1, &lorentz, freq[k], 0), freq[k], 0, 1.0, &Rc, &Tc);
    slab_rt(eps_of(&glass, 1, &lorentz, freq[k], d.dt), freq[k], d.dt, 1.0, &Rd, &Td);
    err_c = fmax(err_c, fabs(T - Tc));
    err_d = fmax(err_d, fabs(T - Td));
    err_rc = fmax(err_rc, fabs(R - Rc));
    err_rd = fmax(err_rd, fabs(R - Rd));
  }
  printf("lorentz slab: max |T - T_tm| continuous eps %.3g, discretised %.3g; "
         "max |R - R_tm| %.3g, %.3g\n", err_c, err_d, err_rc, err_rd);
  cr_assert_lt(err_d, 1e-4, "discretised: %g", err_d);
  cr_assert_lt(err_c, 8e-4, "continuous: %g", err_c);
  cr_assert_lt(err_d, err_c, "the discretised medium's formula should fit better");
  cr_assert_lt(err_rd, 8e-4, "discretised R: %g", err_rd);
}
