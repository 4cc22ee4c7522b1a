/* Filon–Lobatto quadrature (Filon 1928; Iserles & Nørsett, Proc. R. Soc. A 461 (2005); seed 001
 * §5.7 with the notes' corrections: l_k are the Lagrange — not Legendre — polynomials of the
 * Lobatto nodes, and the weights depend on hω). The weights b_k = ∫_0^1 l_k(x) e^{iκx} dx are
 * written on y = 2x − 1 ∈ [−1, 1], θ = κ/2: b_k = ½ e^{iθ} ∫_{−1}^{1} L_k(y) e^{iθy} dy.
 *  - |θ| ≤ 10: Gauss–Legendre with 40 points, exact to round-off for these entire integrands
 *    (the error of the m-point rule for e^{iθy} is below θ^{2m}/(2m)! ≈ 1e-19 at m = 40).
 *  - |θ| > 10: moments M_j = ∫ y^j e^{iθy} dy by M_0 = 2 sin θ/θ,
 *    M_j = (e^{iθ} − (−1)^j e^{−iθ})/(iθ) − (j/(iθ)) M_{j−1}, which amplifies errors by at most
 *    j!/θ^j < 1 here, and the monomial coefficients of L_k (a Vandermonde solve, n ≤ 8). */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "core/internal.h"

#define FILON_MAX 8
#define FILON_GAUSS 40

gm_status gm_filon_lobatto_weights(size_t n, double kappa, double *nodes, double *b_re,
                                   double *b_im) {
  if (n < 2 || n > FILON_MAX || nodes == NULL || b_re == NULL || b_im == NULL ||
      !isfinite(kappa))
    return GM_EINVAL;
  double y[FILON_MAX], w[FILON_MAX];
  gm_status st = gm_gauss_lobatto(n, y, w);
  if (st != GM_OK) return st;
  for (size_t k = 0; k < n; ++k) nodes[k] = 0.5 * (y[k] + 1.0);
  const double theta = 0.5 * kappa;
  double complex b[FILON_MAX] = {0};
  if (fabs(theta) <= 10.0) {
    double g[FILON_GAUSS], gw[FILON_GAUSS], l[FILON_MAX];
    if ((st = gm_gauss_legendre(FILON_GAUSS, g, gw)) != GM_OK) return st;
    for (size_t q = 0; q < FILON_GAUSS; ++q) {
      if ((st = gm_lagrange_basis(n, y, g[q], l)) != GM_OK) return st;
      const double complex e = gw[q] * cexp(I * theta * g[q]);
      for (size_t k = 0; k < n; ++k) b[k] += l[k] * e;
    }
  } else {
    double complex m[FILON_MAX];
    const double complex ep = cexp(I * theta), em = cexp(-I * theta);
    m[0] = 2.0 * sin(theta) / theta;
    for (size_t j = 1; j < n; ++j)
      m[j] = (ep - ((j & 1) ? -em : em)) / (I * theta) - ((double)j / (I * theta)) * m[j - 1];
    /* coefficients of L_k: V c = e_k with V_ij = y_i^j; solve all k at once through Vᵀ:
     * b_k = Σ_j c_kj M_j = (V⁻ᵀ... ) — solve Vᵀ z = M for z, then b_k = z_k */
    double vt[FILON_MAX * FILON_MAX];
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < n; ++j) vt[j * n + i] = pow(y[i], (double)j); /* (Vᵀ)_ji */
    double re[FILON_MAX], im[FILON_MAX], lu[FILON_MAX * FILON_MAX];
    int ipiv[FILON_MAX];
    memcpy(lu, vt, sizeof lu);
    if ((st = gm_lu_factor(n, lu, ipiv)) != GM_OK) return st;
    for (size_t j = 0; j < n; ++j) {
      re[j] = creal(m[j]);
      im[j] = cimag(m[j]);
    }
    if ((st = gm_lu_solve(n, lu, ipiv, re)) != GM_OK ||
        (st = gm_lu_solve(n, lu, ipiv, im)) != GM_OK)
      return st;
    for (size_t k = 0; k < n; ++k) b[k] = re[k] + I * im[k];
  }
  const double complex phase = 0.5 * cexp(I * theta);
  for (size_t k = 0; k < n; ++k) {
    const double complex v = phase * b[k];
    b_re[k] = creal(v);
    b_im[k] = cimag(v);
  }
  return GM_OK;
}

gm_status gm_filon_lobatto(size_t n, double a, double b, double omega,
                           double (*f)(void *ctx, double t), void *ctx, double *re, double *im) {
  if (f == NULL || re == NULL || im == NULL || !isfinite(a) || !isfinite(b) || !isfinite(omega))
    return GM_EINVAL;
  const double h = b - a;
  double c[FILON_MAX], br[FILON_MAX], bi[FILON_MAX];
  gm_status st = gm_filon_lobatto_weights(n, h * omega, c, br, bi);
  if (st != GM_OK) return st;
  /* ∫_a^b f(t) e^{iωt} dt = h e^{iωa} ∫_0^1 f(a + hx) e^{iωhx} dx */
  double complex s = 0.0;
  for (size_t k = 0; k < n; ++k) s += (br[k] + I * bi[k]) * f(ctx, a + h * c[k]);
  s *= h * cexp(I * omega * a);
  *re = creal(s);
  *im = cimag(s);
  return GM_OK;
}
