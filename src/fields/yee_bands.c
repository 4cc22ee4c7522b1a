/* Band structures: resonances of a Bloch-periodic Yee cell at one k (include/geomint/yee_bands.h).
 * The probe signals are band-limited, so each is mixed down by the band centre, low-pass
 * filtered (Blackman-windowed sinc: Oppenheim & Schafer, Discrete-Time Signal Processing 3rd ed.
 * §7.5, transition width ≈ 5.5 / L cycles per sample for L taps) and decimated before harminv:
 * a linear time-invariant filter scales a mode's amplitude but keeps its frequency and decay,
 * and harminv's work (basis ∝ the band's Fourier bins, matrices ∝ samples × basis) shrinks by
 * the decimation factor. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fields/internal.h"
#include "geomint/yee_bands.h"

#define BANDS_MAX_PROBES 64
#define BANDS_MAX_MODES 512
#define BANDS_MAX_TAPS 200000

gm_yee_bands_run gm_yee_bands_run_defaults(void) {
  gm_yee_bands_run r;
  memset(&r, 0, sizeof r);
  r.n_sources = 6;
  r.n_probes = 8;
  r.seed = 7;
  r.max_error = 1e-4;
  return r;
}

/* Guard band g: the filter's transition is [b, b + 2g] beyond the half width b. What the
 * transition lets through (modes just outside the band, the images at −f − f_c of a complex
 * signal's negative frequencies when f_min < 2g) stays outside [−b, b] and so outside
 * harminv's band; only content beyond b + 2g could alias, and the stopband removes it. */
static double guard_of(double b) { return 0.25 * b; }

size_t gm_yee_bands_decimate(size_t n, const double *xr, const double *xi, double dt, double f_min,
                             double f_max, size_t cap, double *yr, double *yi,
                             size_t *decimation, double *shift) {
  const double b = 0.5 * (f_max - f_min), fc = 0.5 * (f_max + f_min);
  const double g = guard_of(b);
  /* the filtered content [−(b+2g), b+2g], shifted by s = b + 2g, lies in [0, 2b + 4g]: no
   * wrap when fs' > 2b + 4g. harminv's error estimate compares the eigenvalues of its one- and
   * two-sample shift matrices (u and u²), which is ambiguous above a quarter of the sampling
   * rate (measured: synthetic modes there came back with errors ≈ 1.2–1.8, below it ≈ 1e-8),
   * so the band [2g, 2b + 2g] is kept below fs'/4: fs' >= 4 (2b + 2g). */
  double dd = 1.0 / (dt * 4 * (2 * b + 2 * g));
  size_t D = dd < 1 ? 1 : (size_t)dd;
  size_t L = (size_t)ceil(5.5 / (2 * g * dt));
  if (L > BANDS_MAX_TAPS) L = BANDS_MAX_TAPS;
  L |= 1; /* odd: a symmetric filter with an integer centre */
  *decimation = D;
  *shift = b + 2 * g;
  if (n < L) return 0;
  double *h = malloc(L * sizeof *h);
  if (h == NULL) return 0;
  const double fcut = (b + g) * dt; /* cycles per sample, the 6 dB point */
  const double mid = 0.5 * (double)(L - 1);
  for (size_t j = 0; j < L; ++j) {
    const double u = (double)j - mid, x = 2 * GM_PI * (double)j / (double)(L - 1);
    const double sinc = u == 0 ? 2 * fcut : sin(2 * GM_PI * fcut * u) / (GM_PI * u);
    h[j] = sinc * (0.42 - 0.5 * cos(x) + 0.08 * cos(2 * x));
  }
  size_t m = 0;
  const double complex rot = cexp(-2 * GM_PI * I * fc * dt);
  double complex up_m = 1;
  for (size_t start = 0; start + L <= n && m < cap; start += D, ++m) {
    /* mixing phase e^{−2πi f_c t} restarted at each output from its exact value (no drift) */
    double complex ph = cexp(-2 * GM_PI * I * fc * dt * (double)start), acc = 0;
    for (size_t j = 0; j < L; ++j) {
      const double complex x = xr[start + j] + I * (xi ? xi[start + j] : 0.0);
      acc += h[j] * x * ph;
      ph *= rot;
    }
    acc *= up_m;
    up_m = cexp(2 * GM_PI * I * (*shift) * (double)D * dt * (double)(m + 1));
    yr[m] = creal(acc);
    yi[m] = cimag(acc);
  }
  free(h);
  return m;
}

/* splitmix64 (Steele, Lea & Flood 2014): positions and phases */
static double uniform(uint64_t *s) {
  uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

typedef struct seen {
  double f, error;
  size_t probe;
} seen;

static int by_f(const void *a, const void *b) {
  const double fa = ((const seen *)a)->f, fb = ((const seen *)b)->f;
  return (fa > fb) - (fa < fb);
}

static void random_point(const gm_yee_grid *g, size_t axes, uint64_t *s, double x[3]) {
  for (size_t a = 0; a < 3; ++a)
    x[a] = a < axes ? g->origin[a] + uniform(s) * (double)g->n[a] * g->h[a] : 0.0;
}

static gm_status check_input(const gm_yee_grid *grid, const gm_yee_options *options,
                             const double k[3], size_t n_bands, const gm_yee_bands_run *run,
                             double *freq, gm_error *err) {
  if (grid == NULL || options == NULL || k == NULL || run == NULL || freq == NULL)
    return gm_error_set(err, GM_EINVAL, "bands: NULL argument");
  const size_t axes = gm_yee_dim_axes(grid->dim);
  static const char names[] = "xyz";
  for (size_t a = 0; a < 3; ++a) {
    if (!isfinite(k[a]))
      return gm_error_set(err, GM_EINVAL, "bands: k[%zu] is not finite", a);
    if (a >= axes && k[a] != 0.0)
      return gm_error_set(err, GM_EINVAL, "bands: k_%c = %g on an axis the %zu-D grid lacks",
                          names[a], k[a], axes);
    if (a < axes && (options->boundary[2 * a].kind != GM_BOUNDARY_PERIODIC ||
                     options->boundary[2 * a + 1].kind != GM_BOUNDARY_PERIODIC))
      return gm_error_set(err, GM_EINVAL,
                          "bands: the %c faces must be periodic (a unit cell of the lattice)",
                          names[a]);
  }
  if (n_bands == 0 || n_bands > BANDS_MAX_MODES / 4)
    return gm_error_set(err, GM_EINVAL, "bands: need 1..%d bands (got %zu)",
                        BANDS_MAX_MODES / 4, n_bands);
  if (!(run->f_min >= 0) || !(run->f_max > run->f_min) || !isfinite(run->f_max))
    return gm_error_set(err, GM_EINVAL, "bands: need 0 <= f_min < f_max (got %g, %g)",
                        run->f_min, run->f_max);
  if (run->n_probes < 1 || run->n_probes > BANDS_MAX_PROBES || run->n_sources < 1 ||
      run->n_sources > BANDS_MAX_PROBES)
    return gm_error_set(err, GM_EINVAL, "bands: need 1..%d probes and sources (got %zu, %zu)",
                        BANDS_MAX_PROBES, run->n_probes, run->n_sources);
  if (!isfinite(run->time) || run->time > 1e9 || !(run->max_error > 0))
    return gm_error_set(err, GM_EINVAL, "bands: bad time %g or max_error %g", run->time,
                        run->max_error);
  return GM_OK;
}

gm_status gm_yee_bands_at(const gm_yee_grid *grid, const gm_yee_materials *materials,
                          const gm_yee_options *options, const double k[3], size_t n_bands,
                          const gm_yee_bands_run *run, double *freq, gm_yee_bands_info *info,
                          gm_error *err) {
  gm_status st = check_input(grid, options, k, n_bands, run, freq, err);
  if (st != GM_OK) return st;
  gm_yee_bands_info inf;
  memset(&inf, 0, sizeof inf);
  for (size_t j = 0; j < n_bands; ++j) freq[j] = NAN;
  const size_t axes = gm_yee_dim_axes(grid->dim);
  gm_yee_options opt = *options;
  for (size_t a = 0; a < 3; ++a) opt.bloch_k[a] = a < axes ? 2 * GM_PI * k[a] : 0.0;
  gm_yee *solver = NULL;
  st = gm_yee_create(grid, materials, &opt, &solver, err);
  if (st != GM_OK) return st;
  const double dt = gm_yee_dt(solver);
  const double b = 0.5 * (run->f_max - run->f_min), fc = 0.5 * (run->f_max + run->f_min);
  if (run->f_max > 0.5 / dt) {
    gm_yee_free(solver);
    return gm_error_set(err, GM_EINVAL, "bands: f_max %g is above the step's Nyquist limit %g",
                        run->f_max, 0.5 / dt);
  }
  /* Gaussian pulses on the band centre, spectrum e^{−2π²w²Δf²}: e^{−2} at the band's edges */
  const double w = 1.0 / (GM_PI * b), t_src = 12 * w;
  const double t_an = run->time > 0 ? run->time : 80.0 / run->f_max;
  const size_t n_steps = (size_t)ceil((t_src + t_an) / dt);
  if ((double)n_steps * (double)run->n_probes * 24.0 > 8e9) {
    gm_yee_free(solver);
    return gm_error_set(err, GM_EINVAL,
                        "bands: %zu steps × %zu probes need %.1f GB of records (shorten time)",
                        n_steps, run->n_probes,
                        (double)n_steps * (double)run->n_probes * 24.0 / 1e9);
  }
  uint64_t rng = run->seed;
  static const gm_yee_component e3[3] = {GM_EX, GM_EY, GM_EZ};
  static const gm_yee_component all3[6] = {GM_EX, GM_EY, GM_EZ, GM_HX, GM_HY, GM_HZ};
  const gm_yee_component c2 = grid->dim == GM_YEE_2D_TE ? GM_HZ : GM_EZ;
  for (size_t s = 0; s < run->n_sources && st == GM_OK; ++s) {
    gm_point_source src;
    memset(&src, 0, sizeof src);
    src.component = grid->dim == GM_YEE_3D ? e3[s % 3] : c2;
    random_point(grid, axes, &rng, src.x);
    src.mode = GM_SOURCE_SOFT;
    src.wave.kind = GM_WAVE_GAUSSIAN;
    src.wave.amplitude = 1;
    src.wave.frequency = fc;
    src.wave.width = w;
    src.wave.delay = 6 * w;
    src.wave.phase = 2 * GM_PI * uniform(&rng);
    st = gm_yee_add_point_source(solver, &src, NULL);
  }
  for (size_t p = 0; p < run->n_probes && st == GM_OK; ++p) {
    double x[3];
    random_point(grid, axes, &rng, x);
    st = gm_yee_add_probe(solver, grid->dim == GM_YEE_3D ? all3[p % 6] : c2, x, n_steps + 1,
                          NULL);
  }
  if (st == GM_OK) st = gm_yee_advance(solver, n_steps);
  if (st != GM_OK) {
    gm_error_set(err, st, "bands: %s", gm_yee_errmsg(solver));
    gm_yee_free(solver);
    return st;
  }
  inf.n_steps = n_steps;
  double *yr = malloc((n_steps + 1) * 2 * sizeof *yr);
  gm_harminv_mode *modes = malloc(BANDS_MAX_MODES * sizeof *modes);
  seen *all = malloc(BANDS_MAX_MODES * run->n_probes * sizeof *all);
  size_t n_all = 0;
  if (yr == NULL || modes == NULL || all == NULL) {
    st = gm_error_set(err, GM_ENOMEM, "bands: out of memory");
    goto done;
  }
  double *yi = yr + n_steps + 1;
  for (size_t p = 0; p < run->n_probes; ++p) {
    size_t n = 0, first = 0;
    const double *t = NULL, *re = NULL, *im = NULL;
    st = gm_yee_probe_samples(solver, p, &n, &t, &re, &im);
    if (st != GM_OK) {
      gm_error_set(err, st, "bands: probe %zu: %s", p, gm_yee_errmsg(solver));
      goto done;
    }
    while (first < n && t[first] < t_src) ++first;
    double shift = 0;
    size_t D = 1;
    const size_t m = gm_yee_bands_decimate(n - first, re + first, im ? im + first : NULL, dt,
                                           run->f_min, run->f_max, n_steps + 1, yr, yi, &D,
                                           &shift);
    const double dt_d = (double)D * dt;
    /* the basis: harminv's density, 1.1 per Fourier bin of the band, but never fewer than 4
     * per band asked for (a small basis loses modes silently) */
    const double bins = 1.1 * 2 * b * dt_d * (double)m;
    size_t nb = run->n_basis > 0 ? run->n_basis : (size_t)ceil(bins);
    if (run->n_basis == 0 && nb < 4 * n_bands + 8) nb = 4 * n_bands + 8;
    inf.n_basis = nb;
    inf.decimation = D;
    inf.n_samples = m;
    if (m < 8 || 2 * nb > m || nb < 2 * n_bands) {
      st = gm_error_set(err, GM_EINVAL,
                        "bands: the analysed signal (%zu samples after decimation by %zu) is too "
                        "short for a harminv basis of %zu (%zu bands): run longer (time)",
                        m, D, nb, n_bands);
      goto done;
    }
    /* harminv fits Σ a e^{−iωt}: conjugate, so that e^{+2πift} is found at +f */
    for (size_t q = 0; q < m; ++q) yi[q] = -yi[q];
    size_t nm = 0;
    st = gm_harminv(m, yr, yi, dt_d, shift - b, shift + b, nb, BANDS_MAX_MODES, modes, &nm, err);
    if (st != GM_OK) goto done;
    for (size_t j = 0; j < nm; ++j) {
      const gm_harminv_mode *md = &modes[j];
      if (!(md->error < run->max_error) || !isfinite(md->frequency) || !(fabs(md->q) > 10))
        continue;
      const double f = md->frequency - shift + fc;
      if (f < run->f_min || f > run->f_max) continue;
      all[n_all].f = f;
      all[n_all].error = md->error;
      all[n_all].probe = p;
      ++n_all;
    }
  }
  qsort(all, n_all, sizeof *all, by_f);
  /* clusters of frequencies closer than 1e-3 f_max: one resonance seen by several probes (their
   * estimates of a weakly excited mode differ by more than harminv's error) */
  const size_t need = run->n_probes >= 2 ? 2 : 1;
  size_t found = 0;
  for (size_t i = 0; i < n_all;) {
    size_t j = i + 1;
    while (j < n_all && all[j].f - all[j - 1].f < 1e-3 * run->f_max) ++j;
    unsigned long long mask = 0;
    size_t best = i;
    for (size_t q = i; q < j; ++q) {
      mask |= 1ULL << all[q].probe;
      if (all[q].error < all[best].error) best = q;
    }
    const size_t probes = (size_t)__builtin_popcountll(mask);
    if (probes >= need) {
      if (found < n_bands) freq[found] = all[best].f;
      ++found;
    } else {
      ++inf.n_extra;
    }
    i = j;
  }
  inf.n_found = found;
  inf.n_lost = found < n_bands ? n_bands - found : 0;
done:
  free(yr);
  free(modes);
  free(all);
  gm_yee_free(solver);
  if (info) *info = inf;
  return st;
}
