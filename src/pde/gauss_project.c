/* Initial data for gauss-prk on the physical branch of its discrete dispersion relation.
 *
 * For a linear equation the scheme's modes are z_{m,j} = R(μH)ᵐ r_j(μH) ẑ (docs/pde.md, "The
 * discrete dispersion relation of gauss-prk"), r(ζ) = (I − ζA)⁻¹𝟙 for the 2-stage Gauss A. On
 * the ring R(μH) = e^{iθ}, θ = 2πk/M (M cells), has two roots μH = iy,
 *   y = 3(−1 ± √(1 + 4τ²/3))/τ,  τ = tan(θ/2):
 * '+' physical (y = θ + O(θ⁵)), '−' spurious (y ≈ −12/θ, a sawtooth within each cell). Which
 * root a mode has depends only on θ, not on the equation or the component, so the split of the
 * DFT over cells of (z_{m,1}, z_{m,2}) into α r(iy₊) + β r(iy₋) can be done per component, and
 * keeping α r(iy₊) removes the spurious part: exactly for linear equations, to leading order
 * otherwise. Point-sampled smooth data carry O(H³) on the spurious branch, which Δt does not
 * resolve (tests/convergence/test_pde_gauss_dispersion.c). k = 0 keeps the cell mean on
 * r = 𝟙 (the spurious root is at y = ∞, r → (−1, 1)); the Nyquist k = M/2, where the two roots
 * are ±√12, is left as it is. */
#include <complex.h>
#include <fftw3.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>

#include "pde/internal.h"

#define SQ3 1.73205080756887729353

static void r_of(double complex z, double complex r[2]) { /* (I − zA)⁻¹𝟙 */
  double complex a = 1.0 - 0.25 * z, b = -(0.25 - SQ3 / 6.0) * z, c = -(0.25 + SQ3 / 6.0) * z;
  double complex det = a * a - b * c;
  r[0] = (a - b) / det;
  r[1] = (a - c) / det;
}

gm_status gm_pde_gauss_project(const gm_pde_grid *grid, size_t dim, double *s, gm_error *err) {
  if (grid == NULL || s == NULL)
    return gm_error_set(err, GM_EINVAL, "pde gauss project: grid and data must not be NULL");
  size_t n = grid->n, M = n / 2;
  if (n < 2 || n % 2 != 0 || M > (size_t)INT_MAX)
    return gm_error_set(err, GM_EINVAL,
                        "pde gauss project: needs an even number of points >= 2 (got %zu)", n);
  if (dim < 1 || dim > GM_PDE_MAX_DIM)
    return gm_error_set(err, GM_EINVAL, "pde gauss project: dim %zu out of range 1..%d", dim,
                        GM_PDE_MAX_DIM);
  for (size_t i = 0; i < n * dim; i++)
    if (!isfinite(s[i]))
      return gm_error_set(err, GM_EDOMAIN, "pde gauss project: non-finite value at %zu", i);
  size_t K = M / 2 + 1;
  double *re = fftw_alloc_real(M);
  fftw_complex *c0 = fftw_alloc_complex(K), *c1 = fftw_alloc_complex(K);
  fftw_plan f0 = NULL, f1 = NULL, b0 = NULL, b1 = NULL;
  gm_status st = GM_OK;
  if (re == NULL || c0 == NULL || c1 == NULL) {
    st = gm_error_set(err, GM_ENOMEM, "pde gauss project: out of memory (M = %zu)", M);
    goto done;
  }
  f0 = fftw_plan_dft_r2c_1d((int)M, re, c0, FFTW_ESTIMATE);
  f1 = fftw_plan_dft_r2c_1d((int)M, re, c1, FFTW_ESTIMATE);
  b0 = fftw_plan_dft_c2r_1d((int)M, c0, re, FFTW_ESTIMATE);
  b1 = fftw_plan_dft_c2r_1d((int)M, c1, re, FFTW_ESTIMATE);
  if (f0 == NULL || f1 == NULL || b0 == NULL || b1 == NULL) {
    st = gm_error_set(err, GM_ENOMEM, "pde gauss project: FFTW plans failed (M = %zu)", M);
    goto done;
  }
  for (size_t a = 0; a < dim; a++) {
    for (size_t m = 0; m < M; m++) re[m] = s[2 * m * dim + a];
    fftw_execute(f0);
    for (size_t m = 0; m < M; m++) re[m] = s[(2 * m + 1) * dim + a];
    fftw_execute(f1);
    for (size_t k = 0; k < K; k++) {
      if (2 * k == M) continue; /* Nyquist: the two roots are symmetric, left as it is */
      double complex rp[2], rs[2];
      if (k == 0) {
        rp[0] = rp[1] = 1.0;
        rs[0] = -1.0;
        rs[1] = 1.0;
      } else {
        double th = 2.0 * GM_PI * (double)k / (double)M, t = tan(th / 2.0);
        double q = sqrt(1.0 + 4.0 * t * t / 3.0);
        r_of(I * 3.0 * (-1.0 + q) / t, rp);
        r_of(I * 3.0 * (-1.0 - q) / t, rs);
      }
      /* fftw_complex is double complex here (complex.h before fftw3.h) */
      double complex al = (c0[k] * rs[1] - c1[k] * rs[0]) / (rp[0] * rs[1] - rp[1] * rs[0]);
      c0[k] = al * rp[0];
      c1[k] = al * rp[1];
    }
    fftw_execute(b0);
    for (size_t m = 0; m < M; m++) s[2 * m * dim + a] = re[m] / (double)M;
    fftw_execute(b1);
    for (size_t m = 0; m < M; m++) s[(2 * m + 1) * dim + a] = re[m] / (double)M;
  }
done:
  if (f0) fftw_destroy_plan(f0);
  if (f1) fftw_destroy_plan(f1);
  if (b0) fftw_destroy_plan(b0);
  if (b1) fftw_destroy_plan(b1);
  fftw_free(re);
  fftw_free(c0);
  fftw_free(c1);
  return st;
}
