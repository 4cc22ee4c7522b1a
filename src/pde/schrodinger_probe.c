/* Eigenvalues of i ψ_t = Hψ by evolution: the phase of ⟨φ, ψ(t)⟩ turns at the rate of the
 * eigenvalue whose eigenstate φ approximates (other components enter the phase at second order
 * in their amplitude and average out in the fit). The frequency measured is the scheme's, so
 * the scheme's dispersion relation is inverted to give the eigenvalue of the semi-discrete H. */
#include <math.h>

#include "pde/internal.h"

/* the phase of ⟨φ, ψ⟩ followed step by step and the running sums of the least-squares fit
 * θ = a + b t (the point t = 0, θ = 0 included), updated by an observer every step */
typedef struct phase_fit {
  const double *phi;
  double dt, prev_re, prev_im, theta;
  double st, sth, stt, sthh, cnt;
} phase_fit;

static int follow_phase(gm_schrodinger *s, void *ctx) {
  phase_fit *f = ctx;
  double c[2];
  gm_schrodinger_overlap(s, f->phi, c);
  /* increment arg(c_l / c_{l−1}) in (−π, π]: |ΩΔt| < √3 for the VI */
  f->theta += atan2(c[1] * f->prev_re - c[0] * f->prev_im, c[0] * f->prev_re + c[1] * f->prev_im);
  f->prev_re = c[0];
  f->prev_im = c[1];
  double t = (double)gm_schrodinger_steps(s) * f->dt;
  f->st += t;
  f->sth += f->theta;
  f->stt += t * t;
  f->sthh += t * f->theta;
  f->cnt += 1.0;
  return 0;
}

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
  double c[2];
  gm_schrodinger_overlap(s, phi, c);
  phase_fit f = {phi, options->dt, c[0], c[1], 0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
  st = gm_schrodinger_add_observer(s, 1, follow_phase, &f, err);
  if (st == GM_OK) st = gm_schrodinger_advance(s, steps, err);
  gm_schrodinger_free(s);
  if (st != GM_OK) return st;
  double st_ = f.st, sth = f.sth, stt = f.stt, sthh = f.sthh, cnt = f.cnt;
  double slope = (cnt * sthh - st_ * sth) / (cnt * stt - st_ * st_);
  double omega = -slope;
  if (omega_out != NULL) *omega_out = omega;
  *E_out = gm_schrodinger_energy_from_frequency(options->scheme, omega, options->dt);
  return GM_OK;
}
