/* The 1-D periodic wave equation u_tt = ⋆d⋆d u in discrete exterior calculus with d kept
 * topological and the Hodge star either diagonal or spectral (seed 000 §3.3.4, as corrected in
 * notes/000 A8).
 *
 * Primal 0-form u at x_j = jh; du on the edge [x_j, x_{j+1}] is u_{j+1} − u_j; the star takes it
 * to the dual 0-form at x_{j+½}; the dual d takes differences g_{j+½} − g_{j−½} on the dual edge
 * around x_j; a second star returns a primal 0-form. With DFT ĝ_m = Σ_j g_{j+½} e^{−iκx_j}
 * (κ = 2πm/L, the dual values indexed by their left vertex), a band-limited f has
 *   (df)^ = (e^{iκh} − 1) f̂  and  (f_x at x_{j+½})^ = iκ e^{iκh/2} f̂,
 * so the star that maps the exact edge integral to the exact midpoint value is the inverse of
 *   ⋆̂_m = (e^{iκh} − 1)/(iκ e^{iκh/2}) = 2 sin(κh/2)/κ = h sinc(m/N),  sinc x = sin(πx)/(πx),
 * real and even in m: the seed's normalisation, checked. On dual 1-forms the same symbol
 * appears ((1 − e^{−iκh})/(iκ e^{−iκh/2})). Hence ⋆d⋆d has the symbol
 *   −[2 sin(κh/2)]² / [h sinc(m/N)]² = −κ²,
 * the exact dispersion ω = |κ| for every resolved m; the diagonal star (⋆ = 1/h) gives
 * ω = (2/h) sin(κh/2). The stars are applied in Fourier space (r2c/c2r plans made at create);
 * d stays a difference in real space. */
#include <complex.h>
#include <limits.h>
#include <fftw3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pde/internal.h"

struct gm_wave1d {
  size_t n;
  double length, h, dt;
  gm_hodge_kind star;
  double *u, *v, *lu; /* owned, n each; lu = ⋆d⋆d u at the current step */
  double *edge, *dual; /* scratch (owned, n each) */
  double *rwork;       /* FFTW real buffer (owned, n) */
  fftw_complex *cwork; /* n/2 + 1 */
  double *inv_star;    /* 1/(N·⋆̂_m), m = 0..n/2 (owned) */
  fftw_plan r2c, c2r;
  size_t steps;
  struct {
    size_t every;
    gm_wave1d_observer_fn fn;
    void *ctx;
  } observers[GM_SPECTRAL_MAX_OBSERVERS];
  size_t n_observers;
};

static double sinc_normalized(double x) {
  return x == 0.0 ? 1.0 : sin(GM_PI * x) / (GM_PI * x);
}

double gm_wave1d_symbol(gm_hodge_kind star, size_t n, double length, long m) {
  double h = length / (double)n, kappa = 2.0 * GM_PI * (double)m / length;
  if (star == GM_HODGE_SPECTRAL) return -kappa * kappa;
  double s = 2.0 / h * sin(0.5 * kappa * h);
  return -s * s;
}

/* the star on n values in place: primal 1-form → dual 0-form, or dual 1-form → primal 0-form */
static void star_apply(gm_wave1d *w, double *x) {
  size_t n = w->n;
  if (w->star == GM_HODGE_DIAGONAL) {
    for (size_t j = 0; j < n; j++) x[j] /= w->h;
    return;
  }
  memcpy(w->rwork, x, n * sizeof *x);
  fftw_execute(w->r2c);
  for (size_t m = 0; m <= n / 2; m++) w->cwork[m] *= w->inv_star[m];
  fftw_execute(w->c2r);
  memcpy(x, w->rwork, n * sizeof *x);
}

void gm_wave1d_star1(gm_wave1d *w, const double *edges, double *dual) {
  memcpy(dual, edges, w->n * sizeof *edges);
  star_apply(w, dual);
}

void gm_wave1d_laplacian(gm_wave1d *w, const double *in, double *out) {
  size_t n = w->n;
  double *e = w->edge;
  for (size_t j = 0; j + 1 < n; j++) e[j] = in[j + 1] - in[j]; /* d, primal */
  e[n - 1] = in[0] - in[n - 1];
  star_apply(w, e); /* dual 0-form */
  out[0] = e[0] - e[n - 1]; /* d, dual */
  for (size_t j = 1; j < n; j++) out[j] = e[j] - e[j - 1];
  star_apply(w, out); /* primal 0-form */
}

void gm_wave1d_free(gm_wave1d *w) {
  if (w == NULL) return;
  if (w->r2c) fftw_destroy_plan(w->r2c);
  if (w->c2r) fftw_destroy_plan(w->c2r);
  free(w->u);
  free(w->v);
  free(w->lu);
  free(w->edge);
  free(w->dual);
  free(w->inv_star);
  fftw_free(w->rwork);
  fftw_free(w->cwork);
  free(w);
}

gm_status gm_wave1d_create(size_t n, double length, gm_hodge_kind star, double dt,
                           const double *u0, const double *v0, gm_wave1d **out, gm_error *err) {
  if (out == NULL || u0 == NULL || v0 == NULL)
    return gm_error_set(err, GM_EINVAL, "wave1d: NULL argument");
  *out = NULL;
  if (n < 4 || n % 2 != 0 || n > (size_t)INT_MAX) /* FFTW takes int sizes */
    return gm_error_set(err, GM_EINVAL, "wave1d: n = %zu must be even, >= 4 and <= %d", n,
                        INT_MAX);
  if (!(isfinite(length) && length > 0.0))
    return gm_error_set(err, GM_EINVAL, "wave1d: the period must be finite and > 0");
  if (star != GM_HODGE_DIAGONAL && star != GM_HODGE_SPECTRAL)
    return gm_error_set(err, GM_EINVAL, "wave1d: unknown Hodge star %d", (int)star);
  double h = length / (double)n;
  /* leapfrog is stable for Δt·max|ω| <= 2: max|ω| = 2/h (diagonal), π/h (spectral) */
  double dt_max = star == GM_HODGE_DIAGONAL ? h : 2.0 * h / GM_PI;
  if (!(isfinite(dt) && dt > 0.0 && dt <= dt_max))
    return gm_error_set(err, GM_EINVAL,
                        "wave1d: dt = %g must be > 0 and <= %.6g (the CFL bound of leapfrog with "
                        "the %s star)", dt, dt_max,
                        star == GM_HODGE_DIAGONAL ? "diagonal" : "spectral");
  for (size_t j = 0; j < n; j++)
    if (!isfinite(u0[j]) || !isfinite(v0[j]))
      return gm_error_set(err, GM_EDOMAIN, "wave1d: initial data not finite at point %zu", j);
  gm_wave1d *w = calloc(1, sizeof *w);
  if (w == NULL) return gm_error_set(err, GM_ENOMEM, "wave1d: out of memory");
  w->n = n;
  w->length = length;
  w->h = h;
  w->dt = dt;
  w->star = star;
  w->u = malloc(n * sizeof *w->u);
  w->v = malloc(n * sizeof *w->v);
  w->lu = malloc(n * sizeof *w->lu);
  w->edge = malloc(n * sizeof *w->edge);
  w->dual = malloc(n * sizeof *w->dual);
  w->inv_star = malloc((n / 2 + 1) * sizeof *w->inv_star);
  w->rwork = fftw_alloc_real(n);
  w->cwork = fftw_alloc_complex(n / 2 + 1);
  int ok = w->u && w->v && w->lu && w->edge && w->dual && w->inv_star && w->rwork && w->cwork;
  if (ok) {
    w->r2c = fftw_plan_dft_r2c_1d((int)n, w->rwork, w->cwork, FFTW_ESTIMATE);
    w->c2r = fftw_plan_dft_c2r_1d((int)n, w->cwork, w->rwork, FFTW_ESTIMATE);
    ok = w->r2c != NULL && w->c2r != NULL;
  }
  if (!ok) {
    gm_wave1d_free(w);
    return gm_error_set(err, GM_ENOMEM, "wave1d: out of memory (n = %zu)", n);
  }
  for (size_t m = 0; m <= n / 2; m++) /* c2r is unnormalised: fold 1/N in */
    w->inv_star[m] = 1.0 / (h * sinc_normalized((double)m / (double)n) * (double)n);
  memcpy(w->u, u0, n * sizeof *u0);
  memcpy(w->v, v0, n * sizeof *v0);
  gm_wave1d_laplacian(w, w->u, w->lu);
  *out = w;
  return GM_OK;
}

gm_status gm_wave1d_advance(gm_wave1d *w, size_t n_steps, gm_error *err) {
  if (w == NULL) return gm_error_set(err, GM_EINVAL, "wave1d: NULL solver");
  size_t n = w->n;
  double dt = w->dt;
  for (size_t k = 0; k < n_steps; k++) { /* kick, drift, kick */
    for (size_t j = 0; j < n; j++) {
      w->v[j] += 0.5 * dt * w->lu[j];
      w->u[j] += dt * w->v[j];
    }
    gm_wave1d_laplacian(w, w->u, w->lu);
    for (size_t j = 0; j < n; j++) w->v[j] += 0.5 * dt * w->lu[j];
    w->steps++;
    double sum = 0.0; /* NaN or ∞ anywhere makes the sum non-finite */
    for (size_t j = 0; j < n; j++) sum += (w->u[j] + w->v[j]) * 0.0;
    if (!isfinite(sum))
      return gm_error_set(err, GM_EDOMAIN, "wave1d: non-finite value at step %zu", w->steps);
    for (size_t o = 0; o < w->n_observers; o++)
      if (w->steps % w->observers[o].every == 0 && w->observers[o].fn(w, w->observers[o].ctx) != 0)
        return gm_error_set(err, GM_ECALLBACK, "wave1d: observer %zu stopped the run at step %zu",
                            o, w->steps);
  }
  return GM_OK;
}

gm_status gm_wave1d_add_observer(gm_wave1d *w, size_t every, gm_wave1d_observer_fn fn, void *ctx,
                                 gm_error *err) {
  if (w == NULL || fn == NULL) return gm_error_set(err, GM_EINVAL, "wave1d: NULL observer");
  if (every == 0) return gm_error_set(err, GM_EINVAL, "wave1d: observer interval must be >= 1");
  if (w->n_observers == GM_SPECTRAL_MAX_OBSERVERS)
    return gm_error_set(err, GM_EINVAL, "wave1d: at most %d observers", GM_SPECTRAL_MAX_OBSERVERS);
  w->observers[w->n_observers].every = every;
  w->observers[w->n_observers].fn = fn;
  w->observers[w->n_observers].ctx = ctx;
  w->n_observers++;
  return GM_OK;
}

double gm_wave1d_time(const gm_wave1d *w) { return (double)w->steps * w->dt; }
const double *gm_wave1d_u(const gm_wave1d *w) { return w->u; }
const double *gm_wave1d_v(const gm_wave1d *w) { return w->v; }

double gm_wave1d_energy(const gm_wave1d *w) {
  /* ½hΣv² + ½⟨du, ⋆du⟩ = ½hΣv² − ½hΣ u·(⋆d⋆d u) (summation by parts, ⋆ symmetric) */
  double e = 0.0;
  for (size_t j = 0; j < w->n; j++) e += w->v[j] * w->v[j] - w->u[j] * w->lu[j];
  return 0.5 * w->h * e;
}
