/* Dispersive media: pole checks (messages name the bad field), ε(f) of the continuous and the
 * discretised medium, the material library's unit conversion, the pole pen of the materials. */
#include <complex.h>

#include "yee_util.h"

static void expect_bad(const gm_pole *p, size_t n, const char *what) {
  gm_error err = {{0}};
  cr_assert_eq(gm_poles_check(n, p, &err), GM_EINVAL);
  cr_assert(strstr(err.message, what) != NULL, "\"%s\" lacks \"%s\"", err.message, what);
}

Test(yee_dispersive, bad_poles_name_the_field) {
  const gm_pole neg_width[1] = {{GM_POLE_LORENTZ, 1.0, -0.1, 2.0}};
  expect_bad(neg_width, 1, "poles[0].gamma");
  const gm_pole zero_plasma[2] = {{GM_POLE_LORENTZ, 1.0, 0.1, 2.0}, {GM_POLE_DRUDE, 0.0, 0.1, 0}};
  expect_bad(zero_plasma, 2, "poles[1].frequency: the plasma frequency must be > 0");
  const gm_pole no_strength[1] = {{GM_POLE_LORENTZ, 1.0, 0.1, 0.0}};
  expect_bad(no_strength, 1, "poles[0].delta_epsilon");
  const gm_pole nan_f[1] = {{GM_POLE_LORENTZ, NAN, 0.1, 1.0}};
  expect_bad(nan_f, 1, "poles[0].frequency");
  const gm_pole kind[1] = {{(gm_pole_kind)7, 1.0, 0.1, 1.0}};
  expect_bad(kind, 1, "poles[0].type");
  /* the materials' pen refuses them too, and keeps its colour */
  gm_yee_grid g = {GM_YEE_1D, {10, 1, 1}, {0.1, 1, 1}, {0, 0, 0}};
  gm_yee_materials *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_materials_create(&g, &m, &err), GM_OK);
  cr_assert_eq(gm_yee_materials_set_poles(m, 2, zero_plasma), GM_EINVAL);
  cr_assert(strstr(gm_yee_materials_errmsg(m), "poles[1].frequency") != NULL);
  cr_assert_eq(gm_yee_materials_n_dispersive(m), 0);
  gm_yee_materials_free(m);
}

Test(yee_dispersive, epsilon_continuous_and_discrete) {
  const gm_medium md = {2.0, 1.0, 0.0};
  const gm_pole p[2] = {{GM_POLE_DRUDE, 1.0, 0.0, 0}, {GM_POLE_LORENTZ, 2.0, 0.5, 3.0}};
  double e[2];
  gm_error err = {{0}};
  /* f = 0.5: 2 − 1/0.25 + 3·4/(4 − 0.25 − i 0.25) */
  cr_assert_eq(gm_medium_epsilon(&md, 2, p, 0.5, 0.0, e, &err), GM_OK);
  const double complex want = 2.0 - 4.0 + 12.0 / (3.75 - 0.25 * I);
  cr_assert_float_eq(e[0], creal(want), 1e-13);
  cr_assert_float_eq(e[1], cimag(want), 1e-13);
  /* discretised: the same at f̃ = tan(π f dt)/(π dt) */
  const double dt = 0.05, ft = tan(YEE_TEST_PI * 0.5 * dt) / (YEE_TEST_PI * dt);
  double ed[2], ec[2];
  cr_assert_eq(gm_medium_epsilon(&md, 2, p, 0.5, dt, ed, &err), GM_OK);
  cr_assert_eq(gm_medium_epsilon(&md, 2, p, ft, 0.0, ec, &err), GM_OK);
  cr_assert_float_eq(ed[0], ec[0], 1e-12);
  cr_assert_float_eq(ed[1], ec[1], 1e-12);
  cr_assert_eq(gm_medium_epsilon(&md, 2, p, 10.0, dt, ed, &err), GM_EINVAL); /* above Nyquist */
  /* conductivity: iσ/(2πf) */
  const gm_medium cond = {1.0, 1.0, 0.3};
  cr_assert_eq(gm_medium_epsilon(&cond, 0, NULL, 0.25, 0.0, e, &err), GM_OK);
  cr_assert_float_eq(e[1], 0.3 / (2 * YEE_TEST_PI * 0.25), 1e-14);
}

/* Rakić et al. (1998) LD model evaluated in eV, against the library's poles in geomint units
 * (unit 0.5 µm: f = 0.5 µm / λ). */
Test(yee_dispersive, library_units) {
  static const struct {
    const char *name;
    double wp, f0, g0, osc[5][3];
    int n;
  } ref[3] = {{"au", 9.03, 0.760, 0.053,
               {{0.024, 0.241, 0.415}, {0.010, 0.345, 0.830}, {0.071, 0.870, 2.969},
                {0.601, 2.494, 4.304}, {4.384, 2.214, 13.32}}, 5},
              {"AG", 9.01, 0.845, 0.048,
               {{0.065, 3.886, 0.816}, {0.124, 0.452, 4.481}, {0.011, 0.065, 8.185},
                {0.840, 0.916, 9.083}, {5.646, 2.419, 20.29}}, 5},
              {"Al", 14.98, 0.523, 0.047,
               {{0.227, 0.333, 0.162}, {0.050, 0.312, 1.544}, {0.166, 1.351, 1.808},
                {0.030, 3.382, 3.473}, {0, 0, 0}}, 4}};
  for (int k = 0; k < 3; ++k) {
    gm_medium md;
    gm_pole poles[GM_MATERIAL_MAX_POLES];
    size_t n = 0;
    gm_error err = {{0}};
    cr_assert_eq(gm_material_find(ref[k].name, 0.5, &md, poles, GM_MATERIAL_MAX_POLES, &n, &err),
                 GM_OK, "%s", err.message);
    cr_assert_eq(n, (size_t)ref[k].n + 1);
    for (double lambda_um = 0.3; lambda_um < 2.0; lambda_um += 0.1) {
      const double E = 1.23984198 / lambda_um; /* eV */
      double complex eps = 1.0 - ref[k].f0 * ref[k].wp * ref[k].wp / (E * (E + I * ref[k].g0));
      for (int j = 0; j < ref[k].n; ++j) {
        const double *o = ref[k].osc[j];
        eps += o[0] * ref[k].wp * ref[k].wp / (o[2] * o[2] - E * E - I * E * o[1]);
      }
      double e[2];
      cr_assert_eq(gm_medium_epsilon(&md, n, poles, 0.5 / lambda_um, 0.0, e, &err), GM_OK);
      cr_assert_float_eq(e[0], creal(eps), 1e-9 * cabs(eps), "%s at %g um", ref[k].name, lambda_um);
      cr_assert_float_eq(e[1], cimag(eps), 1e-9 * cabs(eps), "%s at %g um", ref[k].name, lambda_um);
    }
  }
  gm_medium md;
  gm_pole poles[GM_MATERIAL_MAX_POLES];
  size_t n;
  gm_error err = {{0}};
  cr_assert_eq(gm_material_find("Cu", 1.0, &md, poles, GM_MATERIAL_MAX_POLES, &n, &err),
               GM_ENOTFOUND);
  cr_assert_eq(gm_material_find("Au", -1.0, &md, poles, GM_MATERIAL_MAX_POLES, &n, &err),
               GM_EINVAL);
  cr_assert_str_eq(gm_material_name(0), "Ag");
  cr_assert_null(gm_material_name(3));
}

/* The pen: poles go with later paints only; equal pole sets are shared; no poles: no state. */
Test(yee_dispersive, pen_and_state) {
  gm_yee_grid g = {GM_YEE_1D, {20, 1, 1}, {0.1, 1, 1}, {0, 0, 0}};
  gm_yee_materials *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_materials_create(&g, &m, &err), GM_OK);
  const gm_medium vac = gm_medium_vacuum();
  const gm_pole p = {GM_POLE_DRUDE, 1.0, 0.1, 0};
  const double lo[3] = {0.5, 0, 0}, hi[3] = {1.0, 0, 0}, lo2[3] = {1.5, 0, 0}, hi2[3] = {1.8, 0, 0};
  cr_assert_eq(gm_yee_paint_box(m, lo, hi, &vac), GM_OK);
  cr_assert_eq(gm_yee_materials_n_dispersive(m), 0);
  cr_assert_eq(gm_yee_materials_set_poles(m, 1, &p), GM_OK);
  cr_assert_eq(gm_yee_paint_box(m, lo, hi, &vac), GM_OK);
  cr_assert_eq(gm_yee_materials_set_poles(m, 1, &p), GM_OK);
  cr_assert_eq(gm_yee_paint_box(m, lo2, hi2, &vac), GM_OK);
  cr_assert_eq(gm_yee_materials_n_dispersive(m), 1);
  cr_assert_eq(gm_yee_materials_set_poles(m, 0, NULL), GM_OK);
  gm_yee *s = NULL;
  cr_assert_eq(gm_yee_create(&g, m, NULL, &s, &err), GM_OK, "%s", err.message);
  /* a field set at rest leaves the medium unpolarised */
  cr_assert_eq(gm_yee_set_field_fn(s, GM_EZ, 0, yee_rng_fill, &(yee_rng){3}), GM_OK);
  gm_yee_energy e;
  cr_assert_eq(gm_yee_get_energy(s, &e), GM_OK);
  cr_assert_eq(e.polarization, 0.0);
  cr_assert_eq(gm_yee_advance(s, 50), GM_OK);
  cr_assert_eq(gm_yee_get_energy(s, &e), GM_OK);
  cr_assert_gt(e.polarization, 0.0);
  gm_yee_free(s);
  gm_yee_materials_free(m);
}
