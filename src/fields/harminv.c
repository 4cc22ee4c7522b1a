/* Resonances of a sampled signal with libharminv (Mandelshtam & Taylor 1997 filter
 * diagonalization, the tool MEEP uses): frequencies, decay rates, Q, amplitudes. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>

#include <harminv.h>

#include "fields/internal.h"

static int by_frequency(const void *a, const void *b) {
  const double fa = ((const gm_harminv_mode *)a)->frequency;
  const double fb = ((const gm_harminv_mode *)b)->frequency;
  return (fa > fb) - (fa < fb);
}

gm_status gm_harminv(size_t n, const double *re, const double *im, double dt, double f_min,
                     double f_max, size_t n_basis, size_t max_modes, gm_harminv_mode *modes,
                     size_t *n_modes, gm_error *err) {
  if (n_modes) *n_modes = 0;
  if (re == NULL || (modes == NULL && max_modes > 0) || n_modes == NULL)
    return gm_error_set(err, GM_EINVAL, "harminv: NULL argument");
  if (n < 8) return gm_error_set(err, GM_EINVAL, "harminv: need at least 8 samples (got %zu)", n);
  if (n > 0x7fffffff) return gm_error_set(err, GM_EINVAL, "harminv: too many samples");
  if (!(dt > 0.0) || !isfinite(dt))
    return gm_error_set(err, GM_EINVAL, "harminv: dt must be > 0 and finite (got %g)", dt);
  const double nyquist = 0.5 / dt;
  if (!(f_min >= 0.0) || !(f_max > f_min) || !(f_max <= nyquist * (1.0 + 1e-12)) ||
      !isfinite(f_max))
    return gm_error_set(err, GM_EINVAL,
                        "harminv: need 0 <= f_min < f_max <= 1/(2 dt) = %g (got %g, %g)",
                        nyquist, f_min, f_max);
  harminv_complex *sig = malloc(n * sizeof *sig);
  if (sig == NULL) return gm_error_set(err, GM_ENOMEM, "harminv: out of memory");
  for (size_t i = 0; i < n; ++i) {
    const double r = re[i], m = im ? im[i] : 0.0;
    if (!isfinite(r) || !isfinite(m)) {
      free(sig);
      return gm_error_set(err, GM_EINVAL, "harminv: sample %zu is not finite", i);
    }
    sig[i] = r + I * m;
  }
  /* The harminv library ends the process (exit(1) from its LAPACK error check) on a signal that
   * is zero: refuse it here; and scale a signal of extreme magnitude by its largest sample so
   * that it does not under- or overflow in harminv's matrices (amplitudes are scaled back;
   * other signals are passed unscaled, so their modes are bitwise as before). */
  double smax = 0.0;
  for (size_t i = 0; i < n; ++i) smax = fmax(smax, cabs(sig[i]));
  if (!(smax > 0.0)) {
    free(sig);
    return gm_error_set(err, GM_EDOMAIN,
                        "harminv: the signal is zero (%zu samples): no field reached the probe "
                        "in the analysed window", n);
  }
  if (smax > 1e-100 && smax < 1e100)
    smax = 1.0;
  else
    for (size_t i = 0; i < n; ++i) sig[i] /= smax;
  /* default basis size as the harminv program chooses it: density 1.1 per Fourier bin of the
   * band, at least 2 and at most 300 */
  size_t nf = n_basis;
  if (nf == 0) {
    const double bins = 1.1 * (f_max - f_min) * dt * (double)n;
    nf = bins < 2.0 ? 2 : (bins > 300.0 ? 300 : (size_t)ceil(bins));
  }
  /* harminv works in units of the sampling step: frequency × dt */
  harminv_data d = harminv_data_create((int)n, sig, f_min * dt, f_max * dt, (int)nf);
  if (d == NULL) {
    free(sig);
    return gm_error_set(err, GM_ENOMEM, "harminv: could not create its data");
  }
  harminv_solve(d);
  const int nfound = harminv_get_num_freqs(d);
  gm_harminv_mode *all = malloc(((size_t)(nfound > 0 ? nfound : 0) + 1) * sizeof *all);
  if (all == NULL) {
    harminv_data_destroy(d);
    free(sig);
    return gm_error_set(err, GM_ENOMEM, "harminv: out of memory");
  }
  size_t m = 0;
  for (int k = 0; k < nfound; ++k) {
    const double f = harminv_get_freq(d, k) / dt;
    if (im == NULL && f < 0.0) continue; /* real signal: each mode appears at ±f */
    harminv_complex amp;
    harminv_get_amplitude(&amp, d, k);
    gm_harminv_mode md;
    md.frequency = im == NULL ? fabs(f) : f;
    md.decay = harminv_get_decay(d, k) / dt;
    md.q = harminv_get_Q(d, k);
    md.amplitude = cabs(amp) * smax;
    md.phase = carg(amp);
    md.error = harminv_get_freq_error(d, k);
    if (md.frequency < f_min || md.frequency > f_max) continue;
    all[m++] = md;
  }
  qsort(all, m, sizeof *all, by_frequency);
  const size_t keep = m < max_modes ? m : max_modes;
  for (size_t k = 0; k < keep; ++k) modes[k] = all[k];
  *n_modes = keep;
  free(all);
  harminv_data_destroy(d);
  free(sig);
  return GM_OK;
}
