/* Total-field/scattered-field plane wave along a grid axis (Taflove & Hagness 3rd ed. ch. 5).
 * The incident field is computed by a 1-D Yee grid with the same h and Δt in the background
 * medium, so it obeys the same discrete dispersion as the 3-D grid along an axis and the
 * corrections cancel it outside the box to round-off.
 *
 * The corrections are derived, not tabulated: every curl term of every E and H update that
 * couples a total-field location to a scattered-field one (or back) gets the incident value of
 * its neighbour added (TF target) or subtracted (SF target), with that term's coefficient.
 * Incident wave: E = e(x_a) p̂, H = h(x_a) q̂ with q̂ = â × p̂; Maxwell with ∂ only along a gives
 *   ε ∂_t e = −∂_a h,   μ ∂_t h = −∂_a e   (h = ±e/η for travel along ±a). */
#include <math.h>
#include <stdlib.h>

#include "fields/internal.h"

#define AUX_MARGIN 4  /* cells between the driven node and the box's entry face */

void yee_tfsf_free(yee_tfsf *t) {
  free(t->e);
  free(t->h);
  free(t->ca_e);
  free(t->cb_e);
  free(t->ca_h);
  free(t->cb_h);
  yee_tfsf_corr *cs[2] = {&t->ecorr, &t->hcorr};
  for (int i = 0; i < 2; ++i) {
    free(cs[i]->comp);
    free(cs[i]->target);
    free(cs[i]->aux);
    free(cs[i]->coef);
    free(cs[i]->frac);
  }
}

int yee_tfsf_push_corr(yee_tfsf_corr *c, size_t *cap, int comp, size_t target, size_t aux,
                       double coef) {
  if (c->n == *cap) {
    const size_t nc = *cap ? 2 * *cap : 256;
    int *a = realloc(c->comp, nc * sizeof *a);
    if (a) c->comp = a;
    size_t *b = realloc(c->target, nc * sizeof *b);
    if (b) c->target = b;
    size_t *d = realloc(c->aux, nc * sizeof *d);
    if (d) c->aux = d;
    double *e = realloc(c->coef, nc * sizeof *e);
    if (e) c->coef = e;
    if (!a || !b || !d || !e) return -1;
    if (c->frac != NULL) {
      double *f = realloc(c->frac, nc * sizeof *f);
      if (f == NULL) return -1;
      c->frac = f;
    }
    *cap = nc;
  }
  c->comp[c->n] = comp;
  c->target[c->n] = target;
  c->aux[c->n] = aux;
  c->coef[c->n] = coef;
  ++c->n;
  return 0;
}

/* The four curl terms of component c at ijk (neighbour component, offset along its axis,
   coefficient), as the update kernels apply them. */
void yee_curl_terms(const gm_yee *s, int c, const long ijk[3], yee_curl_term terms[4]) {
  const int A = c % 3, B = (A + 1) % 3, C = (A + 2) % 3;
  const int ise = yee_is_e(c);
  const size_t q = yee_idx(&s->L, ijk[0], ijk[1], ijk[2]);
  const double cb = ise ? yee_medium_cb_e(s, c, q) : yee_medium_cb_h(s, c, q);
  const double ib = ise ? s->inv_e[B][ijk[B] + (long)s->L.offset[B]]
                        : s->inv_h[B][ijk[B] + (long)s->L.offset[B]];
  const double ic = ise ? s->inv_e[C][ijk[C] + (long)s->L.offset[C]]
                        : s->inv_h[C][ijk[C] + (long)s->L.offset[C]];
  if (ise) { /* E += cb [(H_C[q] − H_C[q−s_B]) ib − (H_B[q] − H_B[q−s_C]) ic] */
    terms[0] = (yee_curl_term){3 + C, B, 0, cb * ib};
    terms[1] = (yee_curl_term){3 + C, B, -1, -cb * ib};
    terms[2] = (yee_curl_term){3 + B, C, 0, -cb * ic};
    terms[3] = (yee_curl_term){3 + B, C, -1, cb * ic};
  } else { /* H −= cb [(E_C[q+s_B] − E_C[q]) ib − (E_B[q+s_C] − E_B[q]) ic] */
    terms[0] = (yee_curl_term){C, B, 1, -cb * ib};
    terms[1] = (yee_curl_term){C, B, 0, cb * ib};
    terms[2] = (yee_curl_term){B, C, 1, cb * ic};
    terms[3] = (yee_curl_term){B, C, 0, -cb * ic};
  }
}

/* The background medium of a TF/SF box: the cell at its lower corner. */
void yee_tfsf_background(const gm_yee *s, const size_t lo[3], double *eps, double *mu) {
  *eps = s->eps0;
  *mu = s->mu0;
  if (s->eps_cell) {
    const size_t cell = lo[0] + s->L.n[0] * (lo[1] + s->L.n[1] * lo[2]);
    *eps = s->eps_cell[cell];
    *mu = s->mu_cell[cell];
  }
}

/* The 1-D auxiliary grid of t->n_aux nodes with spacing d (drive at node 0) and its update
 * coefficients: matched graded loss (σ* = σ μ/ε, graded as the cube of depth) over
 * the last YEE_TFSF_AUX_PML nodes, ending in e = 0. 0, or −1 when out of memory. */
int yee_tfsf_aux_grid(yee_tfsf *t, double d, double dt, double eps, double mu) {
  t->drive = 0;
  t->e = calloc(t->n_aux, sizeof(double));
  t->h = calloc(t->n_aux, sizeof(double));
  t->ca_e = calloc(t->n_aux, sizeof(double));
  t->cb_e = calloc(t->n_aux, sizeof(double));
  t->ca_h = calloc(t->n_aux, sizeof(double));
  t->cb_h = calloc(t->n_aux, sizeof(double));
  if (!t->e || !t->h || !t->ca_e || !t->cb_e || !t->ca_h || !t->cb_h) return -1;
  t->inv_h = 1.0 / d;
  const double smax = 0.8 * 4.0 / (d * sqrt(eps * mu)) * eps;
  const size_t pml0 = t->n_aux - 1 - YEE_TFSF_AUX_PML;
  for (size_t j = 0; j < t->n_aux; ++j) {
    const double de = j > pml0 ? (double)(j - pml0) / YEE_TFSF_AUX_PML : 0.0;
    const double dh =
        (double)j + 0.5 > (double)pml0 ? ((double)j + 0.5 - (double)pml0) / YEE_TFSF_AUX_PML : 0.0;
    const double se = smax * de * de * de, sh = smax * dh * dh * dh * mu / eps;
    const double ae = se * dt / (2.0 * eps), ah = sh * dt / (2.0 * mu);
    t->ca_e[j] = (1.0 - ae) / (1.0 + ae);
    t->cb_e[j] = dt / eps / (1.0 + ae);
    t->ca_h[j] = (1.0 - ah) / (1.0 + ah);
    t->cb_h[j] = dt / mu / (1.0 + ah);
  }
  return 0;
}

/* Position of component c at index ijk in cell units, inside the closed TF box [lo, hi]? */
int yee_tfsf_in_box(const gm_yee *s, const size_t lo[3], const size_t hi[3], int c,
                    const long ijk[3]) {
  double sh[3];
  gm_yee_component_shift(s->L.dim, (gm_yee_component)c, sh);
  for (int a = 0; a < s->n_axes; ++a) {
    const double x = (double)ijk[a] + sh[a];
    if (x < (double)lo[a] || x > (double)hi[a]) return 0;
  }
  return 1;
}

gm_status gm_yee_add_plane_wave(gm_yee *s, const gm_plane_wave *w, size_t *id) {
  if (s == NULL || w == NULL) return GM_EINVAL;
  char *msg = s->errmsg;
  const size_t cap_msg = sizeof s->errmsg;
  const int a = w->axis, p = (int)w->polarization;
  if (a < 0 || a >= s->n_axes)
    return gm_fail(msg, cap_msg, GM_EINVAL, "plane wave: axis %d is not an axis of the grid", a);
  if (w->sign != 1 && w->sign != -1)
    return gm_fail(msg, cap_msg, GM_EINVAL, "plane wave: sign must be +1 or -1 (got %d)", w->sign);
  if ((unsigned)p >= 3 || p == a || !s->active[p])
    return gm_fail(msg, cap_msg, GM_EINVAL,
                   "plane wave: polarization must be an E component across the axis that the "
                   "grid has");
  const int r = 3 - a - p; /* q̂ = â × p̂ = ±r̂ */
  const double qsign = ((a + 1) % 3 == p) ? 1.0 : -1.0;
  if (!s->active[3 + r])
    return gm_fail(msg, cap_msg, GM_EINVAL, "plane wave: the grid lacks the H component of it");
  gm_error e;
  if (gm_waveform_check(&w->wave, &e) != GM_OK)
    return gm_fail(msg, cap_msg, GM_EINVAL, "plane wave: %s", e.message);
  for (int b = 0; b < s->n_axes; ++b)
    if (!(w->lo[b] >= 1 && w->lo[b] < w->hi[b] && w->hi[b] + 1 <= s->L.n[b]))
      return gm_fail(msg, cap_msg, GM_EINVAL,
                     "plane wave: the box must satisfy 1 <= lo < hi <= n - 1 on every axis "
                     "(axis %d: lo %zu, hi %zu, n %zu)",
                     b, w->lo[b], w->hi[b], s->L.n[b]);
  double eps, mu;
  yee_tfsf_background(s, w->lo, &eps, &mu);
  yee_tfsf t = {0};
  t.wave = w->wave;
  const long span = (long)(w->hi[a] - w->lo[a]);
  t.n_aux = (size_t)(span + 2 * AUX_MARGIN + YEE_TFSF_AUX_PML + 1);
  /* global node x ↔ aux node j: x = x0 + j (sign +1) or x = x0 − j (sign −1) */
  const long x0 = w->sign > 0 ? (long)w->lo[a] - AUX_MARGIN : (long)w->hi[a] + AUX_MARGIN;
  const double dt = s->dt;
  if (yee_tfsf_aux_grid(&t, s->L.h[a], dt, eps, mu) != 0) {
    yee_tfsf_free(&t);
    return gm_fail(msg, cap_msg, GM_ENOMEM, "plane wave: out of memory");
  }
  /* Along −a the aux grid runs backwards, so its d along j is −d along x: flip h's sign and
   * store h_aux = −h for the incident H. */
  const double hflip = (double)w->sign;
  size_t cap_e = 0, cap_h = 0;
  for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
    if (!s->active[c]) continue;
    const yee_box *bx = &s->upd[c];
    const int ise = yee_is_e(c);
    for (long k = (long)bx->lo[2]; k < (long)(bx->lo[2] + bx->cnt[2]); ++k)
      for (long j = (long)bx->lo[1]; j < (long)(bx->lo[1] + bx->cnt[1]); ++j)
        for (long i = (long)bx->lo[0]; i < (long)(bx->lo[0] + bx->cnt[0]); ++i) {
          const long ijk[3] = {i, j, k};
          /* only locations within one cell of the box can couple across it */
          int near = 1;
          for (int b = 0; b < s->n_axes; ++b)
            near &= ijk[b] + 1 >= (long)w->lo[b] && ijk[b] <= (long)w->hi[b] + 1;
          if (!near) continue;
          const int tf = yee_tfsf_in_box(s, w->lo, w->hi, c, ijk);
          const size_t q = yee_idx(&s->L, i, j, k);
          yee_curl_term terms[4];
          yee_curl_terms(s, c, ijk, terms);
          for (int m = 0; m < 4; ++m) {
            const int nc = terms[m].comp;
            if (nc != (ise ? 3 + r : p)) continue; /* the incident field has one E, one H */
            if (terms[m].axis >= s->n_axes) continue; /* no variation along an absent axis */
            long nb[3] = {i, j, k};
            if (terms[m].axis < s->n_axes) nb[terms[m].axis] += terms[m].shift;
            if (yee_tfsf_in_box(s, w->lo, w->hi, nc, nb) == tf) continue;
            /* aux index of the neighbour's position along a (E nodes at x, H at x + ½) */
            const long xg = nb[a];
            const long jaux = w->sign > 0 ? xg - x0 : x0 - xg - (ise ? 1 : 0);
            if (jaux < 0 || jaux >= (long)t.n_aux - 1) {
              yee_tfsf_free(&t);
              return gm_fail(msg, cap_msg, GM_EINVAL, "plane wave: internal aux index error");
            }
            /* incident value of the neighbour: E_p = e, H_r = qsign · h (h_aux flipped) */
            const double inc_scale = ise ? qsign * hflip : 1.0;
            const double coef = (tf ? 1.0 : -1.0) * terms[m].coef * inc_scale;
            if (yee_tfsf_push_corr(ise ? &t.ecorr : &t.hcorr, ise ? &cap_e : &cap_h, c, q, (size_t)jaux,
                          coef) != 0) {
              yee_tfsf_free(&t);
              return gm_fail(msg, cap_msg, GM_ENOMEM, "plane wave: out of memory");
            }
          }
        }
  }
  yee_tfsf *grown = realloc(s->tfsf, (s->n_tfsf + 1) * sizeof *grown);
  if (grown == NULL) {
    yee_tfsf_free(&t);
    return gm_fail(msg, cap_msg, GM_ENOMEM, "plane wave: out of memory");
  }
  s->tfsf = grown;
  s->tfsf[s->n_tfsf] = t;
  if (id) *id = s->n_tfsf;
  ++s->n_tfsf;
  return GM_OK;
}

/* target += coef · incident, the incident value read from one aux node or (oblique waves)
 * interpolated linearly between two or by the cubic through four. */
static void apply_corr(gm_yee *s, const yee_tfsf_corr *c, const double *aux) {
  if (c->frac == NULL) {
    for (size_t l = 0; l < c->n; ++l) s->f[0][c->comp[l]][c->target[l]] += c->coef[l] * aux[c->aux[l]];
  } else if (!c->cubic) {
    for (size_t l = 0; l < c->n; ++l) {
      const size_t j = c->aux[l];
      const double w = c->frac[l];
      s->f[0][c->comp[l]][c->target[l]] += c->coef[l] * ((1.0 - w) * aux[j] + w * aux[j + 1]);
    }
  } else { /* 4-point Lagrange through nodes j − 1 … j + 2 at j + w */
    for (size_t l = 0; l < c->n; ++l) {
      const size_t j = c->aux[l];
      const double w = c->frac[l], wp = w + 1.0, wm = w - 1.0, wmm = w - 2.0;
      const double v = -w * wm * wmm / 6.0 * aux[j - 1] + wp * wm * wmm / 2.0 * aux[j] -
                       wp * w * wmm / 2.0 * aux[j + 1] + wp * w * wm / 6.0 * aux[j + 2];
      s->f[0][c->comp[l]][c->target[l]] += c->coef[l] * v;
    }
  }
}

void yee_tfsf_apply(gm_yee *s, int e_field) {
  for (size_t i = 0; i < s->n_tfsf; ++i) {
    yee_tfsf *t = &s->tfsf[i];
    const size_t n = t->n_aux;
    if (e_field) {
      /* corrections with the incident H^n, then the aux E to n + ½ */
      apply_corr(s, &t->ecorr, t->h);
      for (size_t j = 1; j + 1 < n; ++j)
        t->e[j] = t->ca_e[j] * t->e[j] - t->cb_e[j] * (t->h[j] - t->h[j - 1]) * t->inv_h;
      t->e[n - 1] = 0.0;
      t->e[t->drive] = gm_waveform_value(&t->wave, ((double)s->step + 0.5) * s->dt);
    } else {
      apply_corr(s, &t->hcorr, t->e);
      for (size_t j = 0; j + 1 < n; ++j)
        t->h[j] = t->ca_h[j] * t->h[j] - t->cb_h[j] * (t->e[j + 1] - t->e[j]) * t->inv_h;
    }
  }
}
