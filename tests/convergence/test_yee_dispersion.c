/* Numerical dispersion of plane waves on periodic grids equals Yee's dispersion relation
 * (Taflove & Hagness eq. 4.12 in 2-D, 4.28 in 3-D):
 *   (sin(ωΔt/2)/(cΔt))² = Σ_a (sin(k_a h_a/2)/h_a)²
 * to 1e-10 at several angles, cell aspect ratios and Courant numbers. The frequency is read off
 * the run exactly: the Fourier amplitude a_n of a field component at wave vector k is
 * α + β e^{iωnΔt} + γ e^{−iωnΔt} (the static part α from a non-solenoidal start), so the
 * differences b_n = a_{n+1} − a_n obey b_{n+1} + b_{n−1} = 2 cos(ωΔt) b_n. Also the Bloch
 * boundary: on a complex (Bloch k) grid the same holds for k = the Bloch wave vector. */
#include <complex.h>

#include "yee_util.h"

typedef struct wave {
  double k[3];
} wave;

static double cos_kx(void *ctx, const double x[3]) {
  const wave *w = ctx;
  return cos(w->k[0] * x[0] + w->k[1] * x[1] + w->k[2] * x[2]);
}
static double sin_kx(void *ctx, const double x[3]) {
  const wave *w = ctx;
  return sin(w->k[0] * x[0] + w->k[1] * x[1] + w->k[2] * x[2]);
}

/* Σ f e^{−ik·x} over the unique locations of component c (periodic: index n is a copy). */
static double complex fourier(const gm_yee *s, gm_yee_component c, const double *k) {
  gm_yee_layout L;
  gm_yee_get_layout(s, &L);
  double sh[3];
  size_t cnt[3];
  gm_yee_component_shift(L.dim, c, sh);
  gm_yee_component_count(&L, c, cnt);
  const double *re = gm_yee_field(s, c, 0), *im = gm_yee_field(s, c, 1);
  const size_t axes = gm_yee_dim_axes(L.dim);
  double complex sum = 0.0;
  for (size_t kk = 0; kk < (axes > 2 ? L.n[2] : 1); ++kk)
    for (size_t j = 0; j < (axes > 1 ? L.n[1] : 1); ++j)
      for (size_t i = 0; i < L.n[0]; ++i) {
        const size_t ijk[3] = {i, j, kk};
        double phase = 0.0;
        for (size_t a = 0; a < axes; ++a) phase += k[a] * (L.origin[a] + ((double)ijk[a] + sh[a]) * L.h[a]);
        const size_t q = gm_yee_index(&L, (long)i, (long)j, (long)kk);
        const double complex v = re[q] + (im ? I * im[q] : 0.0);
        sum += v * cexp(-I * phase);
      }
  (void)cnt;
  return sum;
}

/* ω of the watched component c: a coarse θ = ωΔt from b_0, b_1, b_2, then the Chebyshev form
 * b_{2m} + b_0 = 2 cos(mθ) b_m with mθ ≈ π/3, which is well conditioned. */
static double measured_omega(gm_yee *s, gm_yee_component c, const double *k) {
  double complex a[4];
  for (int n = 0; n < 4; ++n) {
    a[n] = fourier(s, c, k);
    if (n < 3) cr_assert_eq(gm_yee_advance(s, 1), GM_OK);
  }
  const double complex c1 = (a[3] - a[2] + a[1] - a[0]) / (2.0 * (a[2] - a[1]));
  const double coarse = acos(fmax(-1.0, fmin(1.0, creal(c1))));
  cr_assert(coarse > 1e-3 && coarse < 3.0, "coarse omega dt %g", coarse);
  size_t m = (size_t)lround(YEE_TEST_PI / (3.0 * coarse));
  if (m < 3) { /* θ > π/7.5: the m = 1 formula is already well conditioned */
    cr_assert_lt(fabs(cimag(c1)), 1e-9, "a single frequency (imaginary part %g)", cimag(c1));
    return coarse / gm_yee_dt(s);
  }
  const double complex b0 = a[1] - a[0];
  cr_assert_eq(gm_yee_advance(s, m - 3), GM_OK); /* now at step m */
  const double complex am0 = fourier(s, c, k);
  cr_assert_eq(gm_yee_advance(s, 1), GM_OK);
  const double complex bm = fourier(s, c, k) - am0;
  cr_assert_eq(gm_yee_advance(s, m - 1), GM_OK);
  const double complex a2m = fourier(s, c, k);
  cr_assert_eq(gm_yee_advance(s, 1), GM_OK);
  const double complex b2m = fourier(s, c, k) - a2m;
  const double complex cm = (b2m + b0) / (2.0 * bm);
  cr_assert_lt(fabs(cimag(cm)), 1e-9, "a single frequency (imaginary part %g)", cimag(cm));
  return acos(creal(cm)) / ((double)m * gm_yee_dt(s));
}

static double yee_omega(size_t axes, const double *k, const double *h, double dt) {
  return 2.0 * YEE_TEST_PI * yee_discrete_frequency(axes, k, h, dt);
}

static void check(gm_yee_dim dim, const size_t *n, const double *h, const int *m, double courant,
                  double *worst) {
  const size_t axes = gm_yee_dim_axes(dim);
  gm_yee_grid g = {dim, {n[0], n[1], n[2]}, {h[0], h[1], h[2]}, {0.13, -0.2, 0.05}};
  gm_yee_options o = gm_yee_defaults();
  o.courant = courant;
  o.n_threads = 1;
  for (int f = 0; f < 6; ++f) o.boundary[f].kind = GM_BOUNDARY_PERIODIC;
  gm_yee *s = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_create(&g, NULL, &o, &s, &err), GM_OK, "%s", err.message);
  wave w = {{0, 0, 0}};
  for (size_t a = 0; a < axes; ++a) w.k[a] = 2.0 * YEE_TEST_PI * m[a] / ((double)n[a] * h[a]);
  /* start: E across k (and, in 3-D, a second E component: the static part is allowed) */
  const gm_yee_component c = dim == GM_YEE_2D_TE ? GM_EX : GM_EZ;
  cr_assert_eq(gm_yee_set_field_fn(s, c, 0, cos_kx, &w), GM_OK);
  if (dim == GM_YEE_3D) cr_assert_eq(gm_yee_set_field_fn(s, GM_EX, 0, cos_kx, &w), GM_OK);
  if (dim == GM_YEE_2D_TE) cr_assert_eq(gm_yee_set_field_fn(s, GM_EY, 0, cos_kx, &w), GM_OK);
  /* watch a transverse component: Hz in TE (Ex or Ey may be purely longitudinal) */
  const double om = measured_omega(s, dim == GM_YEE_2D_TE ? GM_HZ : c, w.k);
  const double oy = yee_omega(axes, w.k, h, gm_yee_dt(s));
  const double kk = sqrt(w.k[0] * w.k[0] + w.k[1] * w.k[1] + w.k[2] * w.k[2]);
  const double rel = fabs(om - oy) / oy;
  cr_log_info("%zu-D k = (%d,%d,%d) h = (%g,%g,%g) S = %.2f: omega %.15f, Yee %.15f, rel %.2e; "
              "continuum |k| %.6f",
              axes, m[0], m[1], m[2], h[0], h[1], h[2], courant, om, oy, rel, kk);
  cr_assert_lt(rel, 1e-10);
  cr_assert_gt(fabs(om - kk) / kk, 1e-5, "the grid disperses: the test can tell");
  *worst = fmax(*worst, rel);
  gm_yee_free(s);
}

Test(yee_dispersion, plane_waves_2d_and_3d) {
  const double courants[3] = {0.3, 0.7, 0.99};
  const int m2[4][3] = {{1, 0, 0}, {1, 1, 0}, {2, 1, 0}, {3, 1, 0}};
  const int m3[3][3] = {{1, 1, 1}, {2, 1, 0}, {1, 2, 3}};
  double worst = 0.0;
  for (int ci = 0; ci < 3; ++ci) {
    for (int q = 0; q < 4; ++q) {
      const size_t n[3] = {24, 20, 1};
      const double h[3] = {0.05, 0.06, 1.0};
      check(GM_YEE_2D_TM, n, h, m2[q], courants[ci], &worst);
      check(GM_YEE_2D_TE, n, h, m2[q], courants[ci], &worst);
    }
    for (int q = 0; q < 3; ++q) {
      const size_t n[3] = {10, 9, 8};
      const double h[3] = {0.1, 0.11, 0.125};
      check(GM_YEE_3D, n, h, m3[q], courants[ci], &worst);
    }
    const size_t n1[3] = {40, 1, 1};
    const double h1[3] = {0.025, 1, 1};
    const int m1[3] = {3, 0, 0};
    check(GM_YEE_1D, n1, h1, m1, courants[ci], &worst);
  }
  cr_log_info("worst relative difference from Yee's dispersion relation: %.2e", worst);
}

/* Bloch-periodic 2-D grid: a wave e^{ik·x} with k the Bloch vector (no whole period fits the
 * cell) is an eigenmode only if the boundary applies the right phase. */
Test(yee_dispersion, bloch_phase) {
  const double courants[2] = {0.5, 0.95};
  for (int ci = 0; ci < 2; ++ci) {
    gm_yee_grid g = {GM_YEE_2D_TM, {16, 12, 1}, {0.0625, 0.07, 1}, {0, 0, 0}};
    gm_yee_options o = gm_yee_defaults();
    o.courant = courants[ci];
    o.n_threads = 1;
    for (int f = 0; f < 4; ++f) o.boundary[f].kind = GM_BOUNDARY_PERIODIC;
    o.bloch_k[0] = 1.9;
    o.bloch_k[1] = -2.7;
    gm_yee *s = NULL;
    gm_error err = {{0}};
    cr_assert_eq(gm_yee_create(&g, NULL, &o, &s, &err), GM_OK, "%s", err.message);
    gm_yee_layout L;
    gm_yee_get_layout(s, &L);
    cr_assert_eq(L.complex_fields, 1);
    wave w = {{1.9, -2.7, 0}};
    cr_assert_eq(gm_yee_set_field_fn(s, GM_EZ, 0, cos_kx, &w), GM_OK);
    cr_assert_eq(gm_yee_set_field_fn(s, GM_EZ, 1, sin_kx, &w), GM_OK);
    const double om = measured_omega(s, GM_EZ, w.k);
    const double h[3] = {0.0625, 0.07, 1};
    const double oy = yee_omega(2, w.k, h, gm_yee_dt(s));
    cr_log_info("Bloch k = (1.9, -2.7), S = %.2f: omega %.15f, Yee %.15f", courants[ci], om, oy);
    cr_assert_lt(fabs(om - oy) / oy, 1e-10);
    /* and the energy (both parts) is conserved */
    gm_yee_energy e0, e1;
    gm_yee_get_energy(s, &e0);
    cr_assert_eq(gm_yee_advance(s, 2000), GM_OK);
    gm_yee_get_energy(s, &e1);
    cr_assert_lt(fabs(e1.leapfrog - e0.leapfrog), 1e-12 * e0.leapfrog);
    gm_yee_free(s);
  }
}

/* A wrong phase is detected: the same start on a Bloch grid with another k is not one wave. */
Test(yee_dispersion, bloch_phase_mismatch_detected) {
  gm_yee_grid g = {GM_YEE_2D_TM, {16, 12, 1}, {0.0625, 0.07, 1}, {0, 0, 0}};
  gm_yee_options o = gm_yee_defaults();
  o.n_threads = 1;
  for (int f = 0; f < 4; ++f) o.boundary[f].kind = GM_BOUNDARY_PERIODIC;
  o.bloch_k[0] = 1.5;
  gm_yee *s = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_create(&g, NULL, &o, &s, &err), GM_OK, "%s", err.message);
  wave w = {{1.9, 0, 0}};
  cr_assert_eq(gm_yee_set_field_fn(s, GM_EZ, 0, cos_kx, &w), GM_OK);
  cr_assert_eq(gm_yee_set_field_fn(s, GM_EZ, 1, sin_kx, &w), GM_OK);
  double complex a[4];
  for (int n = 0; n < 4; ++n) {
    a[n] = fourier(s, GM_EZ, w.k);
    gm_yee_advance(s, 1);
  }
  const double complex c2 = (a[3] - a[2] + a[1] - a[0]) / (2.0 * (a[2] - a[1]));
  cr_assert_gt(fabs(cimag(c2)) + fabs(creal(c2) - cos(yee_omega(2, w.k, (double[]){0.0625, 0.07, 1}, gm_yee_dt(s)) * gm_yee_dt(s))), 1e-6);
  gm_yee_free(s);
}
