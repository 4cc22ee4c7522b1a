/* Source time functions (Taflove & Hagness ch. 5 for the Gaussian family; the Ricker wavelet
 * is the negative normalised second derivative of a Gaussian, peak frequency f). */
#include <math.h>

#include "fields/internal.h"

double gm_waveform_value(const gm_waveform *w, double t) {
  const double tau = t - w->delay;
  switch (w->kind) {
  case GM_WAVE_GAUSSIAN: {
    const double g = exp(-tau * tau / (2.0 * w->width * w->width));
    return w->amplitude * g * cos(2.0 * GM_PI * w->frequency * tau + w->phase);
  }
  case GM_WAVE_DGAUSSIAN: {
    /* d/dt exp(−τ²/2w²) = −(τ/w²) exp(...); scaled by w·exp(½) so the peak (at τ = ∓w) is ±1. */
    const double x = tau / w->width;
    return -w->amplitude * x * exp(0.5 - 0.5 * x * x);
  }
  case GM_WAVE_RICKER: {
    const double a = GM_PI * w->frequency * tau;
    return w->amplitude * (1.0 - 2.0 * a * a) * exp(-a * a);
  }
  case GM_WAVE_CW: {
    double ramp = 1.0;
    if (t <= 0.0) {
      ramp = 0.0;
    } else if (w->width > 0.0 && t < w->width) {
      const double x = t / w->width; /* C² smoothstep 10x³ − 15x⁴ + 6x⁵ */
      ramp = x * x * x * (10.0 + x * (-15.0 + 6.0 * x));
    }
    return w->amplitude * ramp * sin(2.0 * GM_PI * w->frequency * t + w->phase);
  }
  case GM_WAVE_CUSTOM:
    return w->fn != NULL ? w->amplitude * w->fn(w->ctx, t) : NAN;
  }
  return NAN;
}

gm_status gm_waveform_check(const gm_waveform *w, gm_error *err) {
  if (w == NULL) return gm_error_set(err, GM_EINVAL, "waveform: NULL");
  if (!isfinite(w->amplitude) || !isfinite(w->frequency) || !isfinite(w->width) ||
      !isfinite(w->delay) || !isfinite(w->phase))
    return gm_error_set(err, GM_EINVAL, "waveform: a parameter is NaN or infinite");
  /* Every parameter within 1e100 (a positive width at least 1e-100): the value is formed from
   * products such as 2πf·(t − delay) and (t − delay)²/width², which overflow to inf and give
   * NaN (cos(inf), 0·inf) for values near the limits of a double, e.g. delay = 1e308. */
  const double v[5] = {w->amplitude, w->frequency, w->width, w->delay, w->phase};
  static const char *const name[5] = {"amplitude", "frequency", "width", "delay", "phase"};
  for (int k = 0; k < 5; ++k)
    if (fabs(v[k]) > 1e100)
      return gm_error_set(err, GM_EINVAL,
                          "waveform: %s = %g is beyond 1e100 (the waveform would overflow)",
                          name[k], v[k]);
  if (w->width > 0.0 && w->width < 1e-100)
    return gm_error_set(err, GM_EINVAL,
                        "waveform: width = %g is below 1e-100 (the waveform would overflow)",
                        w->width);
  switch (w->kind) {
  case GM_WAVE_GAUSSIAN:
  case GM_WAVE_DGAUSSIAN:
    if (!(w->width > 0.0))
      return gm_error_set(err, GM_EINVAL, "waveform %s: width must be > 0 (got %g)",
                          gm_waveform_kind_name(w->kind), w->width);
    if (w->frequency < 0.0)
      return gm_error_set(err, GM_EINVAL, "waveform: frequency must be >= 0 (got %g)",
                          w->frequency);
    return GM_OK;
  case GM_WAVE_RICKER:
  case GM_WAVE_CW:
    if (!(w->frequency > 0.0))
      return gm_error_set(err, GM_EINVAL, "waveform %s: frequency must be > 0 (got %g)",
                          gm_waveform_kind_name(w->kind), w->frequency);
    if (w->width < 0.0)
      return gm_error_set(err, GM_EINVAL, "waveform: width must be >= 0 (got %g)", w->width);
    return GM_OK;
  case GM_WAVE_CUSTOM:
    if (w->fn == NULL) return gm_error_set(err, GM_EINVAL, "waveform custom: no function");
    return GM_OK;
  }
  return gm_error_set(err, GM_EINVAL, "waveform: unknown kind %d", (int)w->kind);
}
