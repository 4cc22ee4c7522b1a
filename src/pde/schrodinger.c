/* Pseudospectral Schrödinger solvers for i ψ_t = −½ψ_xx + Vψ on a periodic grid (ħ = m = 1).
 *
 * VI (seed 001 §5.8, coefficients per notes/001 §4: kinetic ħ²k²Δt/(24πm), the j index, DFT
 * v̂_k = hΣ e^{−ikx_j}v_j). Derivation used here (docs/pde.md): ψ(τ) = (1−τ)ψ^l + τψ^{l+1} on
 * each step, L = (i/2)(ψ_tψ̄ − ψψ̄_t) − ⟨ψ, Hψ⟩ with ⟨a, b⟩ = hΣ ā_j b_j (trapezoid in x, exact
 * for band-limited kinetic and time terms), exact in τ (∫(1−τ)² = ∫τ² = 1/3, ∫τ(1−τ) = 1/6):
 *   L_d(a, b) = (i/2)hΣ(bā − ab̄) − (Δt/6)[2⟨a,Ha⟩ + ⟨a,Hb⟩ + ⟨b,Ha⟩ + 2⟨b,Hb⟩],
 * and ∂/∂ψ̄^l [L_d(ψ^{l−1}, ψ^l) + L_d(ψ^l, ψ^{l+1})] = 0 is
 *   (i/2)(ψ^{l+1} − ψ^{l−1}) = (Δt/6) H (ψ^{l−1} + 4ψ^l + ψ^{l+1})   (+ λ_l ψ^l, normalised).
 * The new level solves (i/2 − (Δt/6)H)ψ^{l+1} = (i/2)ψ^{l−1} + (Δt/6)H(ψ^{l−1} + 4ψ^l) by the
 * fixed point x ← P⁻¹[rhs + (Δt/6)(V − V̄)x], P = i/2 − (Δt/6)(K + V̄) diagonal in Fourier space
 * (|P| >= ½, so the contraction factor is <= Δt·max|V − V̄|/3).
 *
 * Split-step: Strang, e^{−iVΔt/2} F⁻¹ e^{−ik²Δt/2} F e^{−iVΔt/2}. */
#include <complex.h>
#include <limits.h>
#include <fftw3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pde/internal.h"

struct gm_schrodinger {
  size_t n;
  double x0, length, h, dt, vbar;
  gm_schrodinger_options opt;
  double *V;       /* owned, n */
  double *half_k2; /* ½k_m² at FFT index m (owned, n) */
  /* VI levels (rotating) and their Hψ: lev[0] = l−1, lev[1] = l, lev[2] = l+1 (owned) */
  fftw_complex *lev[3], *Hlev[3];
  fftw_complex *rhs, *x, *x1, *work; /* scratch (owned) */
  fftw_complex *expV, *expK;         /* split-step factors (owned; expK includes 1/n) */
  fftw_plan fwd, bwd;                /* in place on work */
  double norm0;
  int start_pending; /* VI: lev[2] holds ψ¹ from the RK4 start, not yet taken */
  size_t steps, iterations, ffts;
  struct {
    size_t every;
    gm_schrodinger_observer_fn fn;
    void *ctx;
  } observers[GM_SPECTRAL_MAX_OBSERVERS];
  size_t n_observers;
};

gm_schrodinger_options gm_schrodinger_options_defaults(void) {
  gm_schrodinger_options o = {GM_SCHRODINGER_VI, 0.0, 0, 1e-15, 100};
  return o;
}

static double dot_re(size_t n, double h, const fftw_complex *a, const fftw_complex *b) {
  double s = 0.0;
  for (size_t j = 0; j < n; j++) s += creal(conj(a[j]) * b[j]);
  return h * s;
}

static double complex dot(size_t n, double h, const fftw_complex *a, const fftw_complex *b) {
  double complex s = 0.0;
  for (size_t j = 0; j < n; j++) s += conj(a[j]) * b[j];
  return h * s;
}

/* out = Hx (2 FFTs); out may not alias x */
static void apply_H(gm_schrodinger *s, const fftw_complex *x, fftw_complex *out) {
  size_t n = s->n;
  memcpy(s->work, x, n * sizeof *x);
  fftw_execute(s->fwd);
  for (size_t m = 0; m < n; m++) s->work[m] *= s->half_k2[m] / (double)n;
  fftw_execute(s->bwd);
  for (size_t j = 0; j < n; j++) out[j] = s->work[j] + s->V[j] * x[j];
  s->ffts += 2;
}

/* Solve (i/2 − (Δt/6)H) x = r; x holds the initial guess. */
static gm_status vi_solve(gm_schrodinger *s, const fftw_complex *r, fftw_complex *x,
                          gm_error *err) {
  size_t n = s->n;
  double c = s->dt / 6.0, xnorm = sqrt(dot_re(n, s->h, x, x)), last = INFINITY;
  for (size_t it = 1; it <= s->opt.solve_max_iter; it++) {
    for (size_t j = 0; j < n; j++) s->work[j] = r[j] + c * (s->V[j] - s->vbar) * x[j];
    fftw_execute(s->fwd);
    for (size_t m = 0; m < n; m++)
      s->work[m] /= (0.5 * I - c * (s->half_k2[m] + s->vbar)) * (double)n;
    fftw_execute(s->bwd);
    s->ffts += 2;
    s->iterations++;
    double d = 0.0, xx = 0.0;
    for (size_t j = 0; j < n; j++) {
      double complex e = s->work[j] - x[j];
      d += creal(e) * creal(e) + cimag(e) * cimag(e);
      xx += creal(s->work[j]) * creal(s->work[j]) + cimag(s->work[j]) * cimag(s->work[j]);
      x[j] = s->work[j];
    }
    d = sqrt(s->h * d);
    xnorm = sqrt(s->h * xx);
    if (!isfinite(d))
      return gm_error_set(err, GM_EDOMAIN, "schrodinger: non-finite value at step %zu",
                          s->steps + 1);
    /* converged, or at the round-off floor (no longer halving, below 1e-12 relative) */
    if (d <= s->opt.solve_tol * xnorm || (d > 0.5 * last && d <= 1e-12 * xnorm)) return GM_OK;
    last = d;
  }
  return gm_error_set(err, GM_ENOCONV,
                      "schrodinger: inner solve not converged at step %zu (update %.3g of %.3g)",
                      s->steps + 1, last, xnorm);
}

static gm_status vi_step(gm_schrodinger *s, gm_error *err) {
  size_t n = s->n;
  double c = s->dt / 6.0;
  fftw_complex *pm = s->lev[0], *p0 = s->lev[1], *Hm = s->Hlev[0], *H0 = s->Hlev[1];
  for (size_t j = 0; j < n; j++) {
    s->rhs[j] = 0.5 * I * pm[j] + c * (Hm[j] + 4.0 * H0[j]);
    s->x[j] = pm[j] - 2.0 * I * s->dt * H0[j]; /* leapfrog predictor, O(Δt³) */
  }
  gm_status st = vi_solve(s, s->rhs, s->x, err);
  if (st != GM_OK) return st;
  if (s->opt.normalize) {
    /* ψ^{l+1} = x + λ x1, (i/2 − (Δt/6)H) x1 = ψ^l, λ real with ‖ψ^{l+1}‖² = ‖ψ⁰‖² */
    memcpy(s->x1, p0, n * sizeof *p0);
    st = vi_solve(s, p0, s->x1, err);
    if (st != GM_OK) return st;
    double a = dot_re(n, s->h, s->x1, s->x1), b = dot_re(n, s->h, s->x1, s->x);
    double cc = dot_re(n, s->h, s->x, s->x) - s->norm0, disc = b * b - a * cc;
    if (!(disc >= 0.0) || !(a > 0.0))
      return gm_error_set(err, GM_EDOMAIN,
                          "schrodinger: no real normalisation multiplier at step %zu",
                          s->steps + 1);
    double q = b + copysign(sqrt(disc), b), lambda = q != 0.0 ? -cc / q : 0.0;
    for (size_t j = 0; j < n; j++) s->x[j] += lambda * s->x1[j];
  }
  fftw_complex *t = s->lev[0], *tH = s->Hlev[0];
  s->lev[0] = s->lev[1];
  s->Hlev[0] = s->Hlev[1];
  s->lev[1] = s->lev[2];
  s->Hlev[1] = s->Hlev[2];
  s->lev[2] = t;
  s->Hlev[2] = tH;
  memcpy(s->lev[1], s->x, n * sizeof *s->x);
  apply_H(s, s->lev[1], s->Hlev[1]);
  return GM_OK;
}

static void split_step(gm_schrodinger *s) {
  size_t n = s->n;
  fftw_complex *p = s->lev[1];
  for (size_t j = 0; j < n; j++) s->work[j] = s->expV[j] * p[j];
  fftw_execute(s->fwd);
  for (size_t m = 0; m < n; m++) s->work[m] *= s->expK[m];
  fftw_execute(s->bwd);
  for (size_t j = 0; j < n; j++) p[j] = s->expV[j] * s->work[j];
  s->ffts += 2;
}

/* ψ¹ = RK4 step of ψ' = −iHψ from lev[1] into lev[2] (uses rhs, x, x1 as stages) */
static void rk4_start(gm_schrodinger *s) {
  size_t n = s->n;
  double dt = s->dt;
  fftw_complex *p = s->lev[1], *acc = s->lev[2], *k = s->x, *y = s->x1;
  apply_H(s, p, k); /* k1 = −i k */
  for (size_t j = 0; j < n; j++) {
    acc[j] = p[j] - I * dt / 6.0 * k[j];
    y[j] = p[j] - I * dt / 2.0 * k[j];
  }
  apply_H(s, y, k);
  for (size_t j = 0; j < n; j++) {
    acc[j] += -I * dt / 3.0 * k[j];
    y[j] = p[j] - I * dt / 2.0 * k[j];
  }
  apply_H(s, y, k);
  for (size_t j = 0; j < n; j++) {
    acc[j] += -I * dt / 3.0 * k[j];
    y[j] = p[j] - I * dt * k[j];
  }
  apply_H(s, y, k);
  for (size_t j = 0; j < n; j++) acc[j] += -I * dt / 6.0 * k[j];
  if (s->opt.normalize) {
    double r = sqrt(s->norm0 / dot_re(n, s->h, acc, acc));
    for (size_t j = 0; j < n; j++) acc[j] *= r;
  }
  apply_H(s, acc, s->Hlev[2]);
}

void gm_schrodinger_free(gm_schrodinger *s) {
  if (s == NULL) return;
  if (s->fwd) fftw_destroy_plan(s->fwd);
  if (s->bwd) fftw_destroy_plan(s->bwd);
  for (int k = 0; k < 3; k++) {
    fftw_free(s->lev[k]);
    fftw_free(s->Hlev[k]);
  }
  fftw_free(s->rhs);
  fftw_free(s->x);
  fftw_free(s->x1);
  fftw_free(s->work);
  fftw_free(s->expV);
  fftw_free(s->expK);
  free(s->V);
  free(s->half_k2);
  free(s);
}

gm_status gm_schrodinger_create(size_t n, double x0, double length, const double *V,
                                const double *psi0, const gm_schrodinger_options *options,
                                gm_schrodinger **out, gm_error *err) {
  if (out == NULL || V == NULL || psi0 == NULL || options == NULL)
    return gm_error_set(err, GM_EINVAL, "schrodinger: NULL argument");
  *out = NULL;
  if (n < 4 || n % 2 != 0 || n > (size_t)INT_MAX) /* FFTW takes int sizes */
    return gm_error_set(err, GM_EINVAL, "schrodinger: n = %zu must be even, >= 4 and <= %d", n,
                        INT_MAX);
  if (!(isfinite(length) && length > 0.0) || !isfinite(x0))
    return gm_error_set(err, GM_EINVAL, "schrodinger: the period must be finite and > 0");
  double dt = options->dt;
  if (!(isfinite(dt) && dt > 0.0))
    return gm_error_set(err, GM_EINVAL, "schrodinger: dt = %g must be finite and > 0", dt);
  if (options->scheme != GM_SCHRODINGER_VI && options->scheme != GM_SCHRODINGER_SPLIT_STEP)
    return gm_error_set(err, GM_EINVAL, "schrodinger: unknown scheme %d", (int)options->scheme);
  if (options->solve_max_iter < 1 || !(options->solve_tol >= 0.0))
    return gm_error_set(err, GM_EINVAL, "schrodinger: solve_max_iter >= 1, solve_tol >= 0");
  double vmin = INFINITY, vmax = -INFINITY, norm = 0.0;
  for (size_t j = 0; j < n; j++) {
    if (!isfinite(V[j]))
      return gm_error_set(err, GM_EDOMAIN, "schrodinger: V is not finite at point %zu", j);
    if (!isfinite(psi0[2 * j]) || !isfinite(psi0[2 * j + 1]))
      return gm_error_set(err, GM_EDOMAIN, "schrodinger: psi0 is not finite at point %zu", j);
    vmin = fmin(vmin, V[j]);
    vmax = fmax(vmax, V[j]);
    norm += psi0[2 * j] * psi0[2 * j] + psi0[2 * j + 1] * psi0[2 * j + 1];
  }
  double h = length / (double)n, kmax = GM_PI / h;
  if (options->scheme == GM_SCHRODINGER_VI) {
    double rho = fmax(fabs(0.5 * kmax * kmax + vmax), fabs(vmin));
    if (dt * rho >= sqrt(3.0))
      return gm_error_set(err, GM_EINVAL,
                          "schrodinger: the VI is stable only for dt*rho(H) < sqrt(3): "
                          "dt <= %.6g here (rho(H) <= %.6g)", sqrt(3.0) / rho, rho);
    if (dt * (vmax - vmin) / 6.0 >= 0.9) /* max|V − V̄| = (vmax − vmin)/2, times Δt/3 */
      return gm_error_set(err, GM_EINVAL,
                          "schrodinger: the VI's inner solve contracts only for "
                          "dt*(max V - min V)/6 < 0.9: dt < %.6g", 5.4 / (vmax - vmin));
    if (options->normalize && norm == 0.0)
      return gm_error_set(err, GM_EDOMAIN, "schrodinger: psi0 = 0 cannot be normalised");
  }
  gm_schrodinger *s = calloc(1, sizeof *s);
  if (s == NULL) return gm_error_set(err, GM_ENOMEM, "schrodinger: out of memory");
  s->n = n;
  s->x0 = x0;
  s->length = length;
  s->h = h;
  s->dt = dt;
  s->opt = *options;
  s->vbar = 0.5 * (vmin + vmax);
  s->norm0 = h * norm;
  s->V = malloc(n * sizeof *s->V);
  s->half_k2 = malloc(n * sizeof *s->half_k2);
  int ok = s->V != NULL && s->half_k2 != NULL;
  for (int k = 0; k < 3 && ok; k++) {
    s->lev[k] = fftw_alloc_complex(n);
    s->Hlev[k] = fftw_alloc_complex(n);
    ok = s->lev[k] != NULL && s->Hlev[k] != NULL;
  }
  if (ok) {
    s->rhs = fftw_alloc_complex(n);
    s->x = fftw_alloc_complex(n);
    s->x1 = fftw_alloc_complex(n);
    s->work = fftw_alloc_complex(n);
    s->expV = fftw_alloc_complex(n);
    s->expK = fftw_alloc_complex(n);
    ok = s->rhs && s->x && s->x1 && s->work && s->expV && s->expK;
  }
  if (ok) {
    /* FFTW_ESTIMATE: no timing in the planner, so runs are reproducible */
    s->fwd = fftw_plan_dft_1d((int)n, s->work, s->work, FFTW_FORWARD, FFTW_ESTIMATE);
    s->bwd = fftw_plan_dft_1d((int)n, s->work, s->work, FFTW_BACKWARD, FFTW_ESTIMATE);
    ok = s->fwd != NULL && s->bwd != NULL;
  }
  if (!ok) {
    gm_schrodinger_free(s);
    return gm_error_set(err, GM_ENOMEM, "schrodinger: out of memory (n = %zu)", n);
  }
  memcpy(s->V, V, n * sizeof *V);
  for (size_t m = 0; m < n; m++) {
    /* k_m = 2π m / length for m <= n/2, 2π(m − n)/length above; the Nyquist mode m = n/2
       gets k = π/h (trapezoid quadrature of |ψ_x|² for the real-symmetric interpolant) */
    double km = 2.0 * GM_PI * (m <= n / 2 ? (double)m : (double)m - (double)n) / length;
    s->half_k2[m] = 0.5 * km * km;
    s->expK[m] = cexp(-I * dt * s->half_k2[m]) / (double)n;
  }
  for (size_t j = 0; j < n; j++) {
    s->expV[j] = cexp(-I * 0.5 * dt * V[j]);
    s->lev[1][j] = psi0[2 * j] + I * psi0[2 * j + 1];
  }
  if (s->opt.scheme == GM_SCHRODINGER_VI) {
    apply_H(s, s->lev[1], s->Hlev[1]);
    rk4_start(s);
    s->start_pending = 1;
    if (!isfinite(creal(s->lev[2][0]))) {
      gm_schrodinger_free(s);
      return gm_error_set(err, GM_EDOMAIN, "schrodinger: non-finite start level");
    }
  }
  *out = s;
  return GM_OK;
}

gm_status gm_schrodinger_advance(gm_schrodinger *s, size_t n_steps, gm_error *err) {
  if (s == NULL) return gm_error_set(err, GM_EINVAL, "schrodinger: NULL solver");
  for (size_t k = 0; k < n_steps; k++) {
    if (s->opt.scheme == GM_SCHRODINGER_SPLIT_STEP) {
      split_step(s);
    } else if (s->start_pending) {
      fftw_complex *t = s->lev[0], *tH = s->Hlev[0];
      s->lev[0] = s->lev[1];
      s->Hlev[0] = s->Hlev[1];
      s->lev[1] = s->lev[2];
      s->Hlev[1] = s->Hlev[2];
      s->lev[2] = t;
      s->Hlev[2] = tH;
      s->start_pending = 0;
    } else {
      gm_status st = vi_step(s, err);
      if (st != GM_OK) return st;
    }
    s->steps++;
    double c = creal(s->lev[1][0]) + cimag(s->lev[1][s->n / 2]);
    if (!isfinite(c))
      return gm_error_set(err, GM_EDOMAIN, "schrodinger: non-finite psi at step %zu", s->steps);
    for (size_t o = 0; o < s->n_observers; o++)
      if (s->steps % s->observers[o].every == 0 && s->observers[o].fn(s, s->observers[o].ctx) != 0)
        return gm_error_set(err, GM_ECALLBACK, "schrodinger: observer %zu stopped the run at "
                            "step %zu", o, s->steps);
  }
  return GM_OK;
}

gm_status gm_schrodinger_add_observer(gm_schrodinger *s, size_t every,
                                      gm_schrodinger_observer_fn fn, void *ctx, gm_error *err) {
  if (s == NULL || fn == NULL) return gm_error_set(err, GM_EINVAL, "schrodinger: NULL observer");
  if (every == 0)
    return gm_error_set(err, GM_EINVAL, "schrodinger: observer interval must be >= 1");
  if (s->n_observers == GM_SPECTRAL_MAX_OBSERVERS)
    return gm_error_set(err, GM_EINVAL, "schrodinger: at most %d observers",
                        GM_SPECTRAL_MAX_OBSERVERS);
  s->observers[s->n_observers].every = every;
  s->observers[s->n_observers].fn = fn;
  s->observers[s->n_observers].ctx = ctx;
  s->n_observers++;
  return GM_OK;
}

size_t gm_schrodinger_steps(const gm_schrodinger *s) { return s->steps; }
double gm_schrodinger_time(const gm_schrodinger *s) { return (double)s->steps * s->dt; }
const double *gm_schrodinger_psi(const gm_schrodinger *s) { return (const double *)s->lev[1]; }
size_t gm_schrodinger_iterations(const gm_schrodinger *s) { return s->iterations; }
size_t gm_schrodinger_ffts(const gm_schrodinger *s) { return s->ffts; }

double gm_schrodinger_norm(const gm_schrodinger *s) {
  return dot_re(s->n, s->h, s->lev[1], s->lev[1]);
}

double gm_schrodinger_energy(gm_schrodinger *s) {
  apply_H(s, s->lev[1], s->x1);
  s->ffts -= 2; /* monitors are not counted as work */
  return dot_re(s->n, s->h, s->lev[1], s->x1) / dot_re(s->n, s->h, s->lev[1], s->lev[1]);
}

double gm_schrodinger_charge(const gm_schrodinger *s) {
  if (s->opt.scheme == GM_SCHRODINGER_SPLIT_STEP) return gm_schrodinger_norm(s);
  /* the pair (ψ⁰, ψ¹) before the first step, else (ψ^{l−1}, ψ^l) */
  int a = s->start_pending ? 1 : 0, b = s->start_pending ? 2 : 1;
  return creal(dot(s->n, s->h, s->lev[a], s->lev[b])) -
         s->dt / 3.0 * cimag(dot(s->n, s->h, s->lev[a], s->Hlev[b]));
}

void gm_schrodinger_overlap(const gm_schrodinger *s, const double *a, double *out) {
  double complex z = 0.0;
  for (size_t j = 0; j < s->n; j++) z += (a[2 * j] - I * a[2 * j + 1]) * s->lev[1][j];
  out[0] = s->h * creal(z);
  out[1] = s->h * cimag(z);
}

double gm_schrodinger_energy_from_frequency(gm_schrodinger_scheme scheme, double omega,
                                            double dt) {
  if (scheme == GM_SCHRODINGER_SPLIT_STEP) return omega;
  /* eigenmode ψ^l = z^l φ, z = e^{−iφ}, φ = ΩΔt, in (i/2)(z − 1/z) = (Δt E/6)(1/z + 4 + z):
     sin φ = (Δt E/6)(4 + 2cos φ), so E = (3/Δt) sin φ / (2 + cos φ) */
  double ph = omega * dt;
  return 3.0 / dt * sin(ph) / (2.0 + cos(ph));
}
