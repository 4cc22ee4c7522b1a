/* PEC cavity resonances on a mesh (issue 11, "3-D PEC cavity"): the analytic resonances of the
 * box, the circular cylinder and the sphere, and the ring-down measurement — a leapfrog run
 * excited by Gaussian current pulses on a few pseudo-random interior edges, E_x, E_y, E_z
 * probed at a few pseudo-random interior points and summed with pseudo-random weights (so no mode is
 * missed by a node or a cancellation), harminv in bands of the summed signal. */
#define _XOPEN_SOURCE 700 /* jn() from <math.h> (POSIX, hidden by -std=c11) */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/dec.h"
#include "fields/internal.h"

static void sort_doubles(double *f, size_t n) {
  for (size_t i = 1; i < n; ++i) /* insertion sort: a few hundred values at most */
    for (size_t j = i; j > 0 && f[j] < f[j - 1]; --j) {
      const double t = f[j];
      f[j] = f[j - 1];
      f[j - 1] = t;
    }
}

/* Push f (with multiplicity mult) if below f_max and there is room; counts every mode. */
static void push(double f, int mult, double f_max, double *out, size_t cap, size_t *n,
                 size_t *total) {
  if (!(f <= f_max)) return;
  for (int k = 0; k < mult; ++k) {
    if (*n < cap) out[(*n)++] = f;
    ++*total;
  }
}

gm_status gm_cavity_box_resonances(const double L[3], double f_max, size_t cap, double *f,
                                   size_t *n_out, gm_error *err) {
  if (!L || !f || !n_out || !(L[0] > 0 && L[1] > 0 && L[2] > 0) || !(f_max > 0) ||
      !isfinite(f_max))
    return gm_error_set(err, GM_EINVAL, "cavity box: sides and f_max must be positive");
  /* f = ½ √((l/a)² + (m/b)² + (n/c)²) (c = 1). TE_lmn (E ⊥ z) needs n >= 1 and (l, m) ≠ 0;
   * TM_lmn needs l, m >= 1: so two polarisations when l, m, n >= 1, one when exactly one index
   * is 0, none when two are (E would vanish identically). */
  size_t n = 0, total = 0;
  const int lmax[3] = {(int)(2 * f_max * L[0]) + 1, (int)(2 * f_max * L[1]) + 1,
                       (int)(2 * f_max * L[2]) + 1};
  for (int l = 0; l <= lmax[0]; ++l)
    for (int m = 0; m <= lmax[1]; ++m)
      for (int p = 0; p <= lmax[2]; ++p) {
        const int zeros = (l == 0) + (m == 0) + (p == 0);
        if (zeros >= 2) continue;
        const double a = l / L[0], b = m / L[1], c = p / L[2];
        push(0.5 * sqrt(a * a + b * b + c * c), zeros == 0 ? 2 : 1, f_max, f, cap, &n, &total);
      }
  if (total > cap)
    return gm_error_set(err, GM_EINVAL, "cavity box: %zu resonances below %g, room for %zu",
                        total, f_max, cap);
  sort_doubles(f, n);
  *n_out = n;
  return GM_OK;
}

/* J_m'(x) = (J_{m−1}(x) − J_{m+1}(x)) / 2, J_0' = −J_1. */
static double bessel(int m, int deriv, double x) {
  if (!deriv) return jn(m, x);
  return m == 0 ? -jn(1, x) : 0.5 * (jn(m - 1, x) - jn(m + 1, x));
}

/* Positive zeros of J_m (deriv 0) or J_m' (deriv 1) below x_max, by a scan in steps of 0.02
 * (zeros of J_m and J_m' are > 1 apart) and bisection to round-off. x = 0 is excluded. */
static size_t bessel_zeros(int m, int deriv, double x_max, double *z, size_t cap) {
  size_t n = 0;
  double a = 0.02, fa = bessel(m, deriv, a);
  for (double b = a + 0.02; b <= x_max + 0.02 && n < cap; b += 0.02) {
    const double fb = bessel(m, deriv, b);
    if (fa == 0.0 || (fa < 0) != (fb < 0)) {
      double lo = a, hi = b, flo = fa;
      for (int it = 0; it < 100 && hi - lo > 1e-15 * hi; ++it) {
        const double mid = 0.5 * (lo + hi), fm = bessel(m, deriv, mid);
        if ((fm < 0) == (flo < 0)) { lo = mid; flo = fm; } else hi = mid;
      }
      const double r = 0.5 * (lo + hi);
      if (r <= x_max) z[n++] = r;
    }
    a = b;
    fa = fb;
  }
  return n;
}

gm_status gm_cavity_cylinder_resonances(double R, double H, double f_max, size_t cap, double *f,
                                        size_t *n_out, gm_error *err) {
  if (!f || !n_out || !(R > 0) || !(H > 0) || !(f_max > 0) || !isfinite(R) || !isfinite(H) ||
      !isfinite(f_max))
    return gm_error_set(err, GM_EINVAL, "cavity cylinder: R, H and f_max must be positive");
  /* Pozar, Microwave Engineering §6.4: TM_mnp: f = (1/2π) √((j_mn/R)² + (pπ/H)²), p >= 0;
   * TE_mnp: j'_mn instead of j_mn, p >= 1; two polarisations (cos mφ, sin mφ) when m >= 1. */
  const double kmax = 2.0 * GM_PI * f_max, xmax = kmax * R;
  size_t n = 0, total = 0;
  double z[64];
  for (int m = 0; m <= (int)xmax + 1; ++m)
    for (int te = 0; te < 2; ++te) {
      const size_t nz = bessel_zeros(m, te, xmax, z, 64);
      if (nz == 64)
        return gm_error_set(err, GM_EINVAL, "cavity cylinder: f_max·R = %g is too large",
                            f_max * R);
      for (size_t i = 0; i < nz; ++i)
        for (int p = te; p <= (int)(kmax * H / GM_PI) + 1; ++p) {
          const double kr = z[i] / R, kz = p * GM_PI / H;
          push(sqrt(kr * kr + kz * kz) / (2.0 * GM_PI), m == 0 ? 1 : 2, f_max, f, cap, &n, &total);
        }
    }
  if (total > cap)
    return gm_error_set(err, GM_EINVAL, "cavity cylinder: %zu resonances below %g, room for %zu",
                        total, f_max, cap);
  sort_doubles(f, n);
  *n_out = n;
  return GM_OK;
}

/* Spherical Bessel j_l(x) and j_{l−1}(x) (l >= 1, 0 < x <= 60) by Miller's algorithm (DLMF
 * §3.6(iii): upward recurrence loses digits for x < l, downward is stable for the minimal
 * solution j): j_{k−1} = (2k+1)/x j_k − j_{k+1} (DLMF 10.51.1) from j_{L+1} = 0, j_L = tiny, L
 * 40 above l + x, normalised by the exact j_0 = sin x/x or j_1 = sin x/x² − cos x/x (DLMF
 * 10.49.3), whichever is larger. */
static void sph_bessel(int l, double x, double *jl, double *jlm1) {
  const int L = l + (int)x + 40;
  double up = 0.0, cur = 1e-30, vl = 0.0, vlm1 = 0.0, v1 = 0.0;
  for (int k = L; k >= 1; --k) { /* cur = j_k, up = j_{k+1} (unnormalised) */
    const double down = (2.0 * k + 1.0) / x * cur - up;
    if (k == l) vl = cur, vlm1 = down;
    if (k == 1) v1 = cur;
    up = cur;
    cur = down;
    if (fabs(cur) > 1e200) { /* rescale everything kept so far */
      up *= 1e-200, cur *= 1e-200, vl *= 1e-200, vlm1 *= 1e-200, v1 *= 1e-200;
    }
  }
  /* cur = j_0, v1 = j_1 (unnormalised) */
  const double j0 = sin(x) / x, j1 = sin(x) / (x * x) - cos(x) / x;
  const double scale = fabs(j0) > fabs(j1) ? j0 / cur : j1 / v1;
  *jl = vl * scale;
  *jlm1 = vlm1 * scale;
}

/* TE_l (te = 1): j_l(x); TM_l: d/dx[x j_l(x)] = x j_{l−1}(x) − l j_l(x) (from
 * j_l' = j_{l−1} − (l+1)/x j_l, DLMF 10.51.2). */
static double sphere_char(int l, int te, double x) {
  double jl, jlm1;
  sph_bessel(l, x, &jl, &jlm1);
  return te ? jl : x * jlm1 - l * jl;
}

/* Zeros of sphere_char(l, te, ·) in (1, x_max], scanned in steps of 0.02 (both families have no
 * zero below 2.7 for l >= 1 and consecutive zeros are > 1 apart) and bisected to round-off. */
static size_t sphere_zeros(int l, int te, double x_max, double *z, size_t cap) {
  size_t n = 0;
  double a = 1.0, fa = sphere_char(l, te, a);
  for (double b = a + 0.02; b <= x_max + 0.02 && n < cap; b += 0.02) {
    const double fb = sphere_char(l, te, b);
    if (fa == 0.0 || (fa < 0) != (fb < 0)) {
      double lo = a, hi = b, flo = fa;
      for (int it = 0; it < 100 && hi - lo > 1e-15 * hi; ++it) {
        const double mid = 0.5 * (lo + hi), fm = sphere_char(l, te, mid);
        if ((fm < 0) == (flo < 0)) { lo = mid; flo = fm; } else hi = mid;
      }
      const double r = 0.5 * (lo + hi);
      if (r <= x_max) z[n++] = r;
    }
    a = b;
    fa = fb;
  }
  return n;
}

gm_status gm_cavity_sphere_resonances(double a, double f_max, size_t cap, double *f,
                                      size_t *n_out, gm_error *err) {
  if (!f || !n_out || !(a > 0) || !(f_max > 0) || !isfinite(a) || !isfinite(f_max))
    return gm_error_set(err, GM_EINVAL, "cavity sphere: radius and f_max must be positive");
  /* Jackson, Classical Electrodynamics §8.9 / Harrington, Time-Harmonic Electromagnetic Fields
   * §6.7: TE_lnp: j_l(x) = 0, TM_lnp: [x j_l(x)]' = 0, f = x/(2πa), l >= 1, each (2l+1)-fold
   * (the azimuthal index m = −l..l). */
  const double xmax = 2.0 * GM_PI * f_max * a;
  if (xmax > 60.0)
    return gm_error_set(err, GM_EINVAL, "cavity sphere: 2π f_max a = %g is too large (> 60)",
                        xmax);
  size_t n = 0, total = 0;
  double z[64];
  for (int l = 1; l <= (int)xmax + 1; ++l)
    for (int te = 0; te < 2; ++te) {
      const size_t nz = sphere_zeros(l, te, xmax, z, 64);
      for (size_t i = 0; i < nz; ++i)
        push(z[i] / (2.0 * GM_PI * a), 2 * l + 1, f_max, f, cap, &n, &total);
    }
  if (total > cap)
    return gm_error_set(err, GM_EINVAL, "cavity sphere: %zu resonances below %g, room for %zu",
                        total, f_max, cap);
  sort_doubles(f, n);
  *n_out = n;
  return GM_OK;
}

gm_mesh_cavity_run gm_mesh_cavity_run_defaults(void) {
  gm_mesh_cavity_run r;
  memset(&r, 0, sizeof r);
  r.t_end = 60.0;
  r.f_min = 0.3;
  r.f_max = 2.0;
  r.band = 0.5;
  r.n_sources = 6;
  r.n_probes = 4;
  r.seed = 11;
  r.pulse_width = 0.0;
  r.max_error = 1e-3;
  r.min_amplitude = 0.01;
  return r;
}

static double rnd(uint64_t *z) { /* splitmix64 in [0, 1) */
  uint64_t x = (*z += 0x9e3779b97f4a7c15ull);
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  x ^= x >> 31;
  return (double)(x >> 11) / 9007199254740992.0;
}

gm_status gm_mesh_maxwell_cavity_modes(const gm_geometry *g,
                                       const gm_mesh_maxwell_options *options,
                                       const gm_mesh_cavity_run *run, size_t cap,
                                       gm_harminv_mode *modes, size_t *n_modes, double *dt_out,
                                       gm_error *err) {
  if (!g || !run || !modes || !n_modes)
    return gm_error_set(err, GM_EINVAL, "mesh cavity: NULL argument");
  const gm_complex *cx = gm_geometry_complex(g);
  const size_t dim = gm_complex_dim(cx);
  const size_t N = gm_complex_embedding_dim(cx);
  if (dim < 2 || dim > 3 || N != dim)
    return gm_error_set(err, GM_EINVAL,
                        "mesh cavity: needs triangles in the plane or tetrahedra in space");
  if (!(run->t_end > 0) || !(run->f_min >= 0) || !(run->f_max > run->f_min) ||
      !(run->band > 0) || run->n_sources == 0 || run->n_probes == 0 || run->n_probes > 64 ||
      !(run->pulse_width >= 0))
    return gm_error_set(err, GM_EINVAL,
                        "mesh cavity: need t_end > 0, 0 <= f_min < f_max, band > 0, "
                        "1..64 probes, >= 1 source, pulse_width >= 0");
  gm_mesh_maxwell *s = NULL;
  gm_status st = gm_mesh_maxwell_create(g, NULL, NULL, options, &s, err);
  if (st != GM_OK) return st;
  const double dt = gm_mesh_maxwell_dt(s);
  if (dt_out) *dt_out = dt;
  if (run->f_max > 0.5 / dt) {
    gm_mesh_maxwell_free(s);
    return gm_error_set(err, GM_EINVAL, "mesh cavity: f_max %g above the Nyquist limit %g",
                        run->f_max, 0.5 / dt);
  }
  const size_t ne = gm_complex_count(cx, 1), nt = gm_complex_count(cx, dim);
  const unsigned char *bm = gm_complex_boundary_mask(cx, 1);
  const size_t *tv = gm_complex_simplices(cx, dim);
  const double *X = gm_complex_coordinates(cx);
  uint64_t z = run->seed;
  const size_t steps = (size_t)ceil(run->t_end / dt);
  size_t *edges = malloc(run->n_sources * sizeof *edges);
  double *w = malloc(run->n_sources * sizeof *w);
  double *sum = calloc(steps, sizeof *sum);
  if (!edges || !w || !sum) {
    free(edges), free(w), free(sum), gm_mesh_maxwell_free(s);
    return gm_error_set(err, GM_ENOMEM, "mesh cavity: out of memory");
  }
  size_t ni = 0;
  for (size_t e = 0; e < ne; ++e) ni += !bm[e];
  if (ni == 0) {
    free(edges), free(w), free(sum), gm_mesh_maxwell_free(s);
    return gm_error_set(err, GM_EINVAL, "mesh cavity: the mesh has no interior edge");
  }
  for (size_t k = 0; k < run->n_sources; ++k) { /* the k-th random interior edge */
    size_t pick = (size_t)(rnd(&z) * (double)ni), e = 0;
    for (;; ++e)
      if (!bm[e] && pick-- == 0) break;
    edges[k] = e;
    w[k] = rnd(&z) < 0.5 ? -1.0 - rnd(&z) : 1.0 + rnd(&z);
  }
  /* A Gaussian pulse on a carrier at the band's centre, spectral width (f_max − f_min)/2.5
   * unless given: the modes far above the band, which the mesh has in thousands, are barely
   * excited, so they do not leak into harminv's bands. */
  const double width = run->pulse_width > 0
                           ? run->pulse_width
                           : 2.5 / (2.0 * GM_PI * (run->f_max - run->f_min));
  const gm_waveform wave = {GM_WAVE_GAUSSIAN, 1.0, 0.5 * (run->f_min + run->f_max), width,
                            6.0 * width, 0.0, NULL, NULL};
  st = gm_mesh_maxwell_add_current(s, run->n_sources, edges, w, &wave, NULL);
  if (st != GM_OK) gm_error_set(err, st, "%s", gm_mesh_maxwell_errmsg(s));
  double pw[3 * 64];
  /* 3-D: E_x, E_y, E_z; 2-D (TE): E_x, E_y, H_z */
  const gm_yee_component comp[2][3] = {{GM_EX, GM_EY, GM_HZ}, {GM_EX, GM_EY, GM_EZ}};
  for (size_t p = 0; p < run->n_probes && st == GM_OK; ++p) { /* a random point in a random cell */
    const size_t t = (size_t)(rnd(&z) * (double)nt);
    double b[4], bs = 0.0, x[3] = {0, 0, 0};
    for (size_t i = 0; i <= dim; ++i) bs += (b[i] = 0.2 + rnd(&z));
    for (size_t i = 0; i <= dim; ++i)
      for (size_t c = 0; c < dim; ++c) x[c] += b[i] / bs * X[dim * tv[(dim + 1) * t + i] + c];
    for (int c = 0; c < 3 && st == GM_OK; ++c) {
      pw[3 * p + c] = rnd(&z) - 0.5;
      st = gm_mesh_maxwell_add_probe(s, comp[dim - 2][c], x, steps, NULL);
      if (st != GM_OK) gm_error_set(err, st, "%s", gm_mesh_maxwell_errmsg(s));
    }
  }
  const size_t chunk = run->progress && steps >= 200 ? steps / 200 : steps;
  for (size_t done = 0; st == GM_OK && done < steps;) {
    const size_t k = steps - done < chunk ? steps - done : chunk;
    st = gm_mesh_maxwell_advance(s, k);
    if (st != GM_OK) {
      gm_error_set(err, st, "%s", gm_mesh_maxwell_errmsg(s));
      break;
    }
    done += k;
    if (run->progress && run->progress(run->progress_ctx, (double)done, (double)steps) != 0)
      st = gm_error_set(err, GM_ECALLBACK, "mesh cavity: stopped by the progress callback at "
                        "step %zu of %zu", done, steps);
  }
  size_t n = steps;
  for (size_t id = 0; id < 3 * run->n_probes && st == GM_OK; ++id) {
    size_t m;
    const double *v;
    gm_mesh_maxwell_probe_samples(s, id, &m, NULL, &v);
    if (m < n) n = m;
    for (size_t i = 0; i < n; ++i) sum[i] += pw[id] * v[i];
  }
  /* harminv fits decaying sinusoids: skip the samples while the source is on (12 widths). */
  const size_t skip = (size_t)ceil(12.0 * width / dt);
  if (st == GM_OK && n < skip + 64)
    st = gm_error_set(err, GM_EINVAL, "mesh cavity: t_end too short for the pulse");
  /* The pulse leaves a static field (its net charge): a constant, removed with the mean. */
  double mean = 0.0;
  for (size_t i = skip; st == GM_OK && i < n; ++i) mean += sum[i] / (double)(n - skip);
  for (size_t i = skip; st == GM_OK && i < n; ++i) sum[i] -= mean;
  size_t count = 0;
  double peak = 0.0;
  for (double lo = run->f_min; st == GM_OK && lo < run->f_max - 1e-12; lo += run->band) {
    gm_harminv_mode buf[128];
    size_t nm = 0;
    /* Bands overlap by a fifth of their width on each side and keep only the modes in their
     * core, so a mode on a band edge (where harminv's filter is weakest) is not lost. */
    const double hi = fmin(lo + run->band, run->f_max), margin = 0.2 * run->band;
    st = gm_harminv(n - skip, sum + skip, NULL, dt, fmax(0.0, lo - margin),
                    fmin(hi + margin, 0.5 / dt), 0, 128, buf, &nm, err);
    for (size_t i = 0; st == GM_OK && i < nm; ++i) {
      if (!(buf[i].error < run->max_error)) continue;
      if (buf[i].frequency < lo || buf[i].frequency >= hi) continue;
      if (count == cap) {
        st = gm_error_set(err, GM_EINVAL, "mesh cavity: more than %zu modes", cap);
        break;
      }
      modes[count++] = buf[i];
      peak = fmax(peak, buf[i].amplitude);
    }
  }
  size_t kept = 0;
  for (size_t i = 0; st == GM_OK && i < count; ++i)
    if (modes[i].amplitude >= run->min_amplitude * peak) modes[kept++] = modes[i];
  *n_modes = st == GM_OK ? kept : 0;
  free(edges), free(w), free(sum);
  gm_mesh_maxwell_free(s);
  return st;
}

double gm_leapfrog_space_frequency(double f, double dt) {
  /* Leapfrog dispersion: sin(ω Δt/2) = (Δt/2) √λ, so the spatial eigenfrequency √λ / 2π is
   * sin(π f Δt) / (π Δt) (Taflove & Hagness §4.3). */
  return sin(GM_PI * f * dt) / (GM_PI * dt);
}
