/* DFT flux spectra: running Fourier transforms of the tangential E and H on a vertex plane at
 * chosen frequencies, and the flux spectrum Re ∫ (Ê* × Ĥ)·n dA from them (as MEEP's flux
 * regions, Oskooi et al., CPC 181 (2010) 687, §4.4).
 *
 * Accumulated by an observer called every step: E^{n−½} at t_n − Δt/2 and H^n at t_n, each
 * transformed with its own time, Ê(f) = Σ_n E(t) e^{2πi f t} Δt, so the half-step stagger
 * needs no interpolation in time. In space, as gm_yee_poynting_flux: E_b on the plane and H_c
 * averaged over the two faces beside it share their positions in the plane. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fields/internal.h"

static const double two_pi = 6.283185307179586476925286766559;

struct gm_yee_dft_flux {
  int axis;
  size_t index, n_freq, n_points[2]; /* points per term (E_b H_c, E_c H_b) */
  double *freq;
  /* per term: E and H array indices (H: the two faces), area weights */
  size_t *e_idx[2], *h_idx[2];
  double *w[2];
  int ec[2], hc[2], n_parts;
  /* per part, term, frequency, point: re and im of Ê and Ĥ */
  double *e_re[2][2], *e_im[2][2], *h_re[2][2], *h_im[2][2];
  double dt;
  char errmsg[YEE_ERRMSG];
};

static int accumulate(void *ctx, const gm_yee *s) {
  gm_yee_dft_flux *d = ctx;
  const double te = gm_yee_time_e(s), th = gm_yee_time_h(s);
  for (int p = 0; p < d->n_parts; ++p)
    for (int t = 0; t < 2; ++t) {
      const size_t np = d->n_points[t];
      if (np == 0) continue;
      const double *E = s->f[p][d->ec[t]], *H = s->f[p][d->hc[t]];
      for (size_t k = 0; k < d->n_freq; ++k) {
        const double w = two_pi * d->freq[k];
        const double ce = cos(w * te) * d->dt, se = sin(w * te) * d->dt;
        const double ch = cos(w * th) * d->dt, sh = sin(w * th) * d->dt;
        double *er = d->e_re[p][t] + k * np, *ei = d->e_im[p][t] + k * np;
        double *hr = d->h_re[p][t] + k * np, *hi = d->h_im[p][t] + k * np;
        for (size_t i = 0; i < np; ++i) {
          const double e = E[d->e_idx[t][i]];
          const double h = 0.5 * (H[d->h_idx[t][2 * i]] + H[d->h_idx[t][2 * i + 1]]);
          er[i] += ce * e, ei[i] += se * e;
          hr[i] += ch * h, hi[i] += sh * h;
        }
      }
    }
  return 0;
}

void gm_yee_dft_flux_free(gm_yee_dft_flux *d) {
  if (d == NULL) return;
  free(d->freq);
  for (int t = 0; t < 2; ++t) {
    free(d->e_idx[t]), free(d->h_idx[t]), free(d->w[t]);
    for (int p = 0; p < 2; ++p)
      free(d->e_re[p][t]), free(d->e_im[p][t]), free(d->h_re[p][t]), free(d->h_im[p][t]);
  }
  free(d);
}

gm_status gm_yee_dft_flux_create(gm_yee *s, int axis, size_t index, size_t n_freq,
                                 const double *freq, gm_yee_dft_flux **out) {
  if (s == NULL || out == NULL) return GM_EINVAL;
  *out = NULL;
  if (axis < 0 || axis >= s->n_axes)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "dft flux: axis %d is not an axis of the grid", axis);
  const long n = (long)s->L.n[axis], m = (long)index;
  if (m < 1 || m > n - 1)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "dft flux: plane %zu must be an interior vertex plane (1..%ld)", index, n - 1);
  if (n_freq == 0 || freq == NULL)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "dft flux: no frequencies");
  const double nyquist = 0.5 / s->dt;
  for (size_t k = 0; k < n_freq; ++k)
    if (!(freq[k] >= 0.0) || !(freq[k] < nyquist))
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                     "dft flux: frequency %zu is %g; need 0 <= f < the Nyquist frequency %g", k,
                     freq[k], nyquist);
  /* a cut-off by the plane's CPML: the flux there is not the physical one */
  for (int f = 0; f < 2; ++f) {
    const gm_yee_boundary *b = &s->opt.boundary[2 * axis + f];
    if (b->kind == GM_BOUNDARY_CPML &&
        (f == 0 ? m <= (long)b->pml.thickness : m >= n - (long)b->pml.thickness))
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                     "dft flux: plane %zu lies in the %s CPML layer (%zu cells)", index,
                     f == 0 ? "lower" : "upper", b->pml.thickness);
  }
  gm_yee_dft_flux *d = calloc(1, sizeof *d);
  if (d == NULL) return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "dft flux: out of memory");
  d->axis = axis;
  d->index = index;
  d->n_freq = n_freq;
  d->n_parts = s->n_parts;
  d->dt = s->dt;
  d->freq = malloc(n_freq * sizeof *d->freq);
  if (d->freq == NULL) goto oom;
  memcpy(d->freq, freq, n_freq * sizeof *d->freq);
  const int b = (axis + 1) % 3, c = (axis + 2) % 3;
  for (int t = 0; t < 2; ++t) {
    /* S_a = E_b H_c − E_c H_b */
    d->ec[t] = t == 0 ? b : c;
    d->hc[t] = 3 + (t == 0 ? c : b);
    if (!s->active[d->ec[t]] || !s->active[d->hc[t]]) continue;
    size_t cnt[3];
    gm_yee_component_count(&s->L, (gm_yee_component)d->ec[t], cnt);
    const size_t np = cnt[b] * cnt[c];
    d->e_idx[t] = malloc(np * sizeof(size_t));
    d->h_idx[t] = malloc(2 * np * sizeof(size_t));
    d->w[t] = malloc(np * sizeof(double));
    if (!d->e_idx[t] || !d->h_idx[t] || !d->w[t]) goto oom;
    double sh[3];
    gm_yee_component_shift(s->L.dim, (gm_yee_component)d->ec[t], sh);
    size_t i = 0;
    for (long v = 0; v < (long)cnt[c]; ++v)
      for (long u = 0; u < (long)cnt[b]; ++u) {
        long e3[3];
        e3[axis] = m, e3[b] = u, e3[c] = v;
        /* area of the dual face in the plane: half at walls, once on periodic axes */
        double w = 1.0;
        for (int a = 0; a < 3; ++a) {
          if (a == axis) continue;
          w *= s->L.h[a];
          if (a >= s->n_axes || sh[a] > 0.0) continue;
          if (s->periodic[a] ? e3[a] == (long)s->L.n[a]
                             : (e3[a] == 0 || e3[a] == (long)s->L.n[a]))
            w *= s->periodic[a] ? 0.0 : 0.5;
        }
        if (w == 0.0) continue;
        d->e_idx[t][i] = yee_idx(&s->L, e3[0], e3[1], e3[2]);
        for (long dd = -1; dd <= 0; ++dd) {
          long h3[3] = {e3[0], e3[1], e3[2]};
          h3[axis] = m + dd;
          d->h_idx[t][2 * i + (size_t)(dd + 1)] = yee_idx(&s->L, h3[0], h3[1], h3[2]);
        }
        d->w[t][i] = (t == 0 ? 1.0 : -1.0) * w;
        ++i;
      }
    d->n_points[t] = i;
    for (int p = 0; p < d->n_parts; ++p) {
      d->e_re[p][t] = calloc(n_freq * i + 1, sizeof(double));
      d->e_im[p][t] = calloc(n_freq * i + 1, sizeof(double));
      d->h_re[p][t] = calloc(n_freq * i + 1, sizeof(double));
      d->h_im[p][t] = calloc(n_freq * i + 1, sizeof(double));
      if (!d->e_re[p][t] || !d->e_im[p][t] || !d->h_re[p][t] || !d->h_im[p][t]) goto oom;
    }
  }
  gm_status st = gm_yee_add_observer(s, 1, accumulate, d);
  if (st != GM_OK) {
    gm_yee_dft_flux_free(d);
    return st;
  }
  *out = d;
  return GM_OK;
oom:
  gm_yee_dft_flux_free(d);
  return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "dft flux: out of memory");
}

size_t gm_yee_dft_flux_n_freq(const gm_yee_dft_flux *d) { return d ? d->n_freq : 0; }

gm_status gm_yee_dft_flux_spectrum(const gm_yee_dft_flux *d, double *flux) {
  if (d == NULL || flux == NULL) return GM_EINVAL;
  for (size_t k = 0; k < d->n_freq; ++k) {
    double sum = 0.0;
    for (int p = 0; p < d->n_parts; ++p)
      for (int t = 0; t < 2; ++t) {
        const size_t np = d->n_points[t], o = k * np;
        for (size_t i = 0; i < np; ++i) /* Re(conj(Ê) Ĥ) */
          sum += d->w[t][i] * (d->e_re[p][t][o + i] * d->h_re[p][t][o + i] +
                               d->e_im[p][t][o + i] * d->h_im[p][t][o + i]);
      }
    flux[k] = sum;
  }
  return GM_OK;
}

gm_status gm_yee_dft_flux_subtract(gm_yee_dft_flux *d, const gm_yee_dft_flux *incident) {
  if (d == NULL || incident == NULL) return GM_EINVAL;
  int same = d->axis == incident->axis && d->index == incident->index &&
             d->n_freq == incident->n_freq && d->n_parts == incident->n_parts &&
             d->dt == incident->dt;
  for (int t = 0; t < 2 && same; ++t) same = d->n_points[t] == incident->n_points[t];
  for (size_t k = 0; k < d->n_freq && same; ++k) same = d->freq[k] == incident->freq[k];
  if (!same)
    return gm_fail(d->errmsg, sizeof d->errmsg, GM_EINVAL,
                   "dft flux: the incident run's plane, frequencies, points or step differ");
  for (int p = 0; p < d->n_parts; ++p)
    for (int t = 0; t < 2; ++t) {
      const size_t n = d->n_freq * d->n_points[t];
      for (size_t i = 0; i < n; ++i) {
        d->e_re[p][t][i] -= incident->e_re[p][t][i];
        d->e_im[p][t][i] -= incident->e_im[p][t][i];
        d->h_re[p][t][i] -= incident->h_re[p][t][i];
        d->h_im[p][t][i] -= incident->h_im[p][t][i];
      }
    }
  return GM_OK;
}

const char *gm_yee_dft_flux_errmsg(const gm_yee_dft_flux *d) { return d ? d->errmsg : ""; }

/* ---- normalisation runs through a file ------------------------------------------------------
 * Text, one flux object after the other: a line "gm-dft-flux axis index n_freq n_parts np0
 * np1 dt", the frequencies, then per part and term the four transforms (Ê re, Ê im, Ĥ re, Ĥ im),
 * every value with 17 significant digits (read back exactly). */

static int write_values(FILE *f, const double *v, size_t n) {
  for (size_t i = 0; i < n; ++i)
    if (fprintf(f, "%.17g\n", v[i]) < 0) return -1;
  return 0;
}

gm_status gm_yee_dft_flux_save(gm_yee_dft_flux *const *fluxes, size_t n, const char *path,
                               gm_error *err) {
  if (fluxes == NULL || path == NULL) return gm_error_set(err, GM_EINVAL, "dft save: NULL");
  FILE *f = fopen(path, "w");
  if (f == NULL) return gm_error_set(err, GM_EIO, "dft save: cannot write %s", path);
  int bad = fprintf(f, "gm-dft-fluxes %zu\n", n) < 0;
  for (size_t k = 0; k < n && !bad; ++k) {
    const gm_yee_dft_flux *d = fluxes[k];
    bad |= fprintf(f, "gm-dft-flux %d %zu %zu %d %zu %zu %.17g\n", d->axis, d->index,
                   d->n_freq, d->n_parts, d->n_points[0], d->n_points[1], d->dt) < 0;
    bad |= write_values(f, d->freq, d->n_freq);
    for (int p = 0; p < d->n_parts && !bad; ++p)
      for (int t = 0; t < 2 && !bad; ++t) {
        const size_t m = d->n_freq * d->n_points[t];
        if (m == 0) continue;
        bad |= write_values(f, d->e_re[p][t], m) || write_values(f, d->e_im[p][t], m) ||
               write_values(f, d->h_re[p][t], m) || write_values(f, d->h_im[p][t], m);
      }
  }
  bad |= fclose(f) != 0;
  return bad ? gm_error_set(err, GM_EIO, "dft save: writing %s failed", path) : GM_OK;
}

static int read_values(FILE *f, double *v, size_t n) {
  for (size_t i = 0; i < n; ++i)
    if (fscanf(f, "%lf", &v[i]) != 1 || !isfinite(v[i])) return -1;
  return 0;
}

gm_status gm_yee_dft_flux_subtract_file(gm_yee_dft_flux *const *fluxes, size_t n,
                                        const char *path, double *incident, gm_error *err) {
  if (fluxes == NULL || path == NULL) return gm_error_set(err, GM_EINVAL, "dft subtract: NULL");
  FILE *f = fopen(path, "r");
  if (f == NULL) return gm_error_set(err, GM_EIO, "dft subtract: cannot read %s", path);
  size_t count = 0;
  gm_status st = GM_OK;
  if (fscanf(f, " gm-dft-fluxes %zu", &count) != 1 || count != n)
    st = gm_error_set(err, GM_EINVAL,
                      "dft subtract: %s holds %zu flux planes, this run has %zu (the "
                      "normalisation run must have the same planes)", path, count, n);
  for (size_t k = 0; k < n && st == GM_OK; ++k) {
    const gm_yee_dft_flux *d = fluxes[k];
    gm_yee_dft_flux c = *d; /* the incident run's transforms, in arrays of the same shape */
    int axis = -1, parts = 0;
    size_t index = 0, nf = 0, np0 = 0, np1 = 0;
    double step = 0.0;
    if (fscanf(f, " gm-dft-flux %d %zu %zu %d %zu %zu %lf", &axis, &index, &nf, &parts, &np0,
               &np1, &step) != 7 ||
        step != d->dt || axis != d->axis || index != d->index || nf != d->n_freq || parts != d->n_parts ||
        np0 != d->n_points[0] || np1 != d->n_points[1]) {
      st = gm_error_set(err, GM_EINVAL,
                        "dft subtract: %s: flux plane %zu differs from this run's (axis, plane, "
                        "frequencies, points, time step)", path, k);
      break;
    }
    double *buf = malloc((nf + 4 * 2 * 2 * nf * (np0 + np1) + 1) * sizeof *buf);
    if (buf == NULL) {
      st = gm_error_set(err, GM_ENOMEM, "dft subtract: out of memory");
      break;
    }
    double *at = buf + nf;
    int bad = read_values(f, buf, nf);
    for (size_t i = 0; i < nf && !bad; ++i) bad = buf[i] != d->freq[i];
    for (int p = 0; p < parts && !bad; ++p)
      for (int t = 0; t < 2 && !bad; ++t) {
        const size_t m = nf * d->n_points[t];
        c.e_re[p][t] = at, c.e_im[p][t] = at + m, c.h_re[p][t] = at + 2 * m;
        c.h_im[p][t] = at + 3 * m;
        bad = m > 0 && read_values(f, at, 4 * m);
        at += 4 * m;
      }
    if (bad)
      st = gm_error_set(err, GM_EINVAL,
                        "dft subtract: %s: flux plane %zu: unreadable or different frequencies",
                        path, k);
    if (st == GM_OK && incident != NULL) gm_yee_dft_flux_spectrum(&c, incident + k * nf);
    if (st == GM_OK) gm_yee_dft_flux_subtract(fluxes[k], &c);
    free(buf);
  }
  fclose(f);
  return st;
}
