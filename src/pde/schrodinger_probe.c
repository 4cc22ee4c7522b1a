/* Eigenvalues of i ψ_t = Hψ by evolution: the phase of ⟨φ, ψ(t)⟩ turns at the rate of the
 * eigenvalue whose eigenstate φ approximates (other components enter the phase at second order
 * in their amplitude and average out in the fit). The frequency measured is the scheme's, so
 * the scheme's dispersion relation is inverted to give the eigenvalue of the semi-discrete H. */
#include <math.h>

#include "pde/internal.h"

gm_status gm_schrodinger_eigenvalue(size_t n, double x0, double length, const double *V,
                                    const double *phi, const gm_schrodinger_options *options,
                                    double T, double *E_out, double *omega_out, gm_error *err) {
  if (E_out == NULL || options == NULL)
    return gm_error_set(err, GM_EINVAL, "schrodinger: NULL argument");
  if (!(isfinite(T) && options->dt > 0.0 && T >= 2.0 * options->dt))
    return gm_error_set(err, GM_EINVAL, "schrodinger: T = %g must be >= 2 dt", T);
  gm_schrodinger *s = NULL;
  gm_status st = gm_schrodinger_create(n, x0, length, V, phi, options, &s, err);
  if (st != GM_OK) return st;
  size_t steps = (size_t)llround(T / options->dt);
  double c[2], prev_re, prev_im, theta = 0.0;
  gm_schrodinger_overlap(s, phi, c);
  prev_re = c[0];
  prev_im = c[1];
  /* running sums of the least-squares fit θ = a + b t (the point t = 0, θ = 0 included) */
  double st_ = 0.0, sth = 0.0, stt = 0.0, sthh = 0.0, cnt = 1.0;
  for (size_t l = 1; l <= steps; l++) {
    st = gm_schrodinger_advance(s, 1, err);
    if (st != GM_OK) {
      gm_schrodinger_free(s);
      return st;
    }
    gm_schrodinger_overlap(s, phi, c);
    /* increment arg(c_l / c_{l−1}) in (−π, π]: |ΩΔt| < √3 for the VI */
    theta += atan2(c[1] * prev_re - c[0] * prev_im, c[0] * prev_re + c[1] * prev_im);
    prev_re = c[0];
    prev_im = c[1];
    double t = (double)l * options->dt;
    st_ += t;
    sth += theta;
    stt += t * t;
    sthh += t * theta;
    cnt += 1.0;
  }
  gm_schrodinger_free(s);
  double slope = (cnt * sthh - st_ * sth) / (cnt * stt - st_ * st_);
  double omega = -slope;
  if (omega_out != NULL) *omega_out = omega;
  *E_out = gm_schrodinger_energy_from_frequency(options->scheme, omega, options->dt);
  return GM_OK;
}
