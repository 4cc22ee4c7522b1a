/* Filon–Lobatto quadrature (src/core/filon.c): exact for polynomials of degree n − 1 at every
 * frequency, and its error regimes (seed 001 §5.7, notes 1G "Filon errors"), measured on one
 * panel [a, a + h] for f(t) = 1/(1 + t²):
 *   hω ≪ 1 (ω fixed, h → 0): O(h^{n+2}) for the symmetric Lobatto nodes (n = 3: 5);
 *   hω = 10 fixed, h → 0:      O(h^{n+1});
 *   h fixed, ω → ∞:            O(ω⁻²) (envelope) because the endpoints are nodes (Iserles & Nørsett 2005),
 * while the ordinary Lobatto rule of f·e^{iωt} has an O(1) error there. The reference is a
 * composite 20-point Gauss–Legendre rule with panels much shorter than the wavelength. */
#include <complex.h>

#include "test_util.h"

static double runge(void *ctx, double t) {
  (void)ctx;
  return 1.0 / (1.0 + t * t);
}

static double poly_deg;
static double monomial(void *ctx, double t) {
  (void)ctx;
  return pow(t - 0.3, poly_deg) + 0.5 * t;
}

/* ∫_a^b f e^{iωt} by composite Gauss–Legendre: panels of length ≤ min(b − a, 0.5/|ω|)/4 */
static double complex reference(double (*f)(void *, double), double a, double b, double omega) {
  double x[20], w[20];
  cr_assert_eq(gm_gauss_legendre(20, x, w), GM_OK);
  double len = (b - a) / 4;
  if (omega != 0.0) len = fmin(len, 0.5 / fabs(omega));
  size_t panels = (size_t)ceil((b - a) / len);
  double complex s = 0.0;
  for (size_t p = 0; p < panels; ++p) {
    double lo = a + (b - a) * (double)p / (double)panels, hi = a + (b - a) * (double)(p + 1) / (double)panels;
    for (size_t q = 0; q < 20; ++q) {
      double t = 0.5 * (lo + hi) + 0.5 * (hi - lo) * x[q];
      s += 0.5 * (hi - lo) * w[q] * f(NULL, t) * cexp(I * omega * t);
    }
  }
  return s;
}

static double filon_error(size_t n, double (*f)(void *, double), double a, double b,
                          double omega) {
  double re, im;
  cr_assert_eq(gm_filon_lobatto(n, a, b, omega, f, NULL, &re, &im), GM_OK);
  return cabs(re + I * im - reference(f, a, b, omega));
}

static double slope(const double *x, const double *y, size_t m) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < m; ++i) {
    double u = log(x[i]), v = log(y[i]);
    sx += u;
    sy += v;
    sxx += u * u;
    sxy += u * v;
  }
  return ((double)m * sxy - sx * sy) / ((double)m * sxx - sx * sx);
}

Test(filon, exact_for_polynomials_of_degree_n_minus_1) {
  const double omegas[] = {0.0, 0.3, 5.0, 19.9, 20.1, 25.0, 300.0, -40.0};
  for (size_t n = 2; n <= 8; ++n) {
    poly_deg = (double)(n - 1);
    for (size_t k = 0; k < sizeof omegas / sizeof omegas[0]; ++k) {
      double e = filon_error(n, monomial, 0.2, 1.2, omegas[k]);
      double scale = cabs(reference(monomial, 0.2, 1.2, 0.0));
      cr_expect_leq(e, 1e-13 * scale, "n = %zu, omega = %g: error %.2e", n, omegas[k], e);
    }
  }
  double c[8], br[8], bi[8];
  cr_expect_eq(gm_filon_lobatto_weights(1, 1.0, c, br, bi), GM_EINVAL);
  cr_expect_eq(gm_filon_lobatto_weights(9, 1.0, c, br, bi), GM_EINVAL);
  cr_expect_eq(gm_filon_lobatto_weights(3, NAN, c, br, bi), GM_EINVAL);
  /* κ = 0: the Lobatto weights */
  double y[3], w[3];
  cr_assert_eq(gm_filon_lobatto_weights(3, 0.0, c, br, bi), GM_OK);
  gm_gauss_lobatto(3, y, w);
  for (size_t k = 0; k < 3; ++k) cr_expect(fabs(br[k] - 0.5 * w[k]) < 1e-15 && bi[k] == 0.0);
}

Test(filon, error_regimes) {
  const size_t n = 3;
  double hs[5], err[5];
  /* hω ≪ 1 */
  for (size_t k = 0; k < 5; ++k) {
    hs[k] = 0.2 / pow(2.0, (double)k);
    err[k] = filon_error(n, runge, 0.3, 0.3 + hs[k], 1.0);
  }
  double p_small = slope(hs, err, 5);
  cr_expect(p_small > 4.7 && p_small < 5.3, "h omega << 1: slope %.3f, expected n + 2 = 5",
            p_small);
  /* hω = 10 */
  for (size_t k = 0; k < 5; ++k) {
    hs[k] = 0.2 / pow(2.0, (double)k);
    err[k] = filon_error(n, runge, 0.3, 0.3 + hs[k], 10.0 / hs[k]);
  }
  double p_mid = slope(hs, err, 5);
  cr_expect(p_mid > 3.7 && p_mid < 4.3, "h omega = 10: slope %.3f, expected n + 1 = 4", p_mid);
  /* h fixed, ω → ∞: the error is c_a e^{iωa} + c_b e^{iωb} over ω², whose modulus oscillates
   * with ω; its envelope (max over 8 frequencies in [ω, 2ω)) decays like ω⁻² */
  double ws[5];
  for (size_t k = 0; k < 5; ++k) {
    ws[k] = 200.0 * pow(3.0, (double)k);
    err[k] = 0.0;
    for (size_t j = 0; j < 8; ++j)
      err[k] = fmax(err[k], filon_error(n, runge, 0.3, 0.8, ws[k] * (1.0 + (double)j / 8.0)));
  }
  double p_large = slope(ws, err, 5);
  cr_log_info("Filon n = 3 slopes: %.3f (h omega << 1), %.3f (h omega = 10), %.3f (omega)",
              p_small, p_mid, p_large);
  cr_expect(p_large > -2.3 && p_large < -1.7, "h omega >> 1: slope %.3f in omega, expected -2",
            p_large);
  /* the ordinary Lobatto rule does not decay there */
  double y[3], w[3];
  gm_gauss_lobatto(3, y, w);
  gm_quadrature_map(3, 0.3, 0.8, y, w);
  double complex s = 0.0;
  const double wl = ws[4];
  for (size_t q = 0; q < 3; ++q) s += w[q] * runge(NULL, y[q]) * cexp(I * wl * y[q]);
  double e_plain = cabs(s - reference(runge, 0.3, 0.8, wl));
  cr_expect_gt(e_plain, 1e3 * err[4], "Lobatto %.2e vs Filon %.2e at omega = %g", e_plain,
               err[4], wl);
}
