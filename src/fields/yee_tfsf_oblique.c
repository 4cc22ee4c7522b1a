/* Total-field/scattered-field plane wave at any angle (2-D and 3-D): the incident-field-array
 * method (Taflove & Hagness 3rd ed. §5.8–5.9). A 1-D Yee grid along the direction of travel k̂
 * carries the incident wave (e on integer nodes at half steps, h on half nodes at whole steps,
 * the same Δt); every curl term of the 2-D/3-D update that couples a total-field location to a
 * scattered-field one gets the incident value of its neighbour, found by projecting the
 * neighbour's position on k̂ and interpolating the 1-D grid (linearly as T&H, or by the cubic
 * Lagrange polynomial through four nodes, the default) (the same derivation of the
 * correction terms as the axis-aligned yee_tfsf.c, with all three incident components).
 *
 * Matched phase velocity (T&H §5.9): the 1-D grid's spacing Δ₁ is chosen so that at the match
 * frequency ω its numerical wavenumber equals the one of the 2-D/3-D Yee grid along k̂:
 *   Σ_a (sin(k k̂_a h_a / 2) / h_a)² = (sin(ωΔt/2) / (cΔt))²   (Yee's relation, T&H eq. 4.52 form)
 *   sin(k Δ₁ / 2) / Δ₁ = sin(ωΔt/2) / (cΔt)                   (the same on the 1-D grid)
 * Along an axis this gives Δ₁ = h (the axis-aligned grid). Away from the match frequency the
 * two dispersions differ at second order in h/λ; linear interpolation errs at second order
 * too, cubic at fourth: what leaks into the scattered-field region is measured in tests/invariants/
 * test_yee_tfsf_oblique.c and docs/maxwell.md.
 *
 * Incident wave (E = e(s) ê, H = h(s) ĥ, s = k̂·x, ĥ = k̂ × ê): Maxwell with ∂ only along s gives
 *   ε ∂_t e = −∂_s h,   μ ∂_t h = −∂_s e,
 * the 1-D Yee update of yee_tfsf_apply. */
#include <math.h>
#include <stdlib.h>

#include "fields/internal.h"

#define YEE_PI 3.14159265358979323846

/* sin and cos of an angle in degrees, exact at multiples of 90°. */
static void sincos_deg(double deg, double *sn, double *cs) {
  const double q = deg / 90.0;
  if (q == floor(q) && fabs(q) < 1e9) {
    static const double S[4] = {0, 1, 0, -1}, C[4] = {1, 0, -1, 0};
    long m = (long)q % 4;
    if (m < 0) m += 4;
    *sn = S[m];
    *cs = C[m];
    return;
  }
  const double r = deg * (YEE_PI / 180.0);
  *sn = sin(r);
  *cs = cos(r);
}

void gm_oblique_wave_vectors(const gm_oblique_wave *w, double k[3], double e[3], double h[3]) {
  double st, ct, sp, cp, ss, cs;
  sincos_deg(w->theta, &st, &ct);
  sincos_deg(w->phi, &sp, &cp);
  sincos_deg(w->psi, &ss, &cs);
  k[0] = st * cp;
  k[1] = st * sp;
  k[2] = ct;
  e[0] = cs * sp - ss * ct * cp;
  e[1] = -cs * cp - ss * ct * sp;
  e[2] = ss * st;
  h[0] = k[1] * e[2] - k[2] * e[1];
  h[1] = k[2] * e[0] - k[0] * e[2];
  h[2] = k[0] * e[1] - k[1] * e[0];
}

/* Yee's numerical wavenumber along k̂ at ω: the root of Σ_a (sin(k k̂_a h_a/2)/h_a)² = S², by
 * bisection on (0, k_max] where every k k̂_a h_a ≤ π (the relation is increasing there).
 * Returns NAN when ω is beyond the grid's cut-off along k̂. */
static double yee_wavenumber(const double kh[3], const double h[3], int axes, double S) {
  double kmax = INFINITY;
  for (int a = 0; a < axes; ++a)
    if (kh[a] != 0.0) kmax = fmin(kmax, YEE_PI / (fabs(kh[a]) * h[a]));
  double lo = 0.0, hi = kmax;
  for (int it = 0; it < 200; ++it) {
    const double k = 0.5 * (lo + hi);
    double f = 0.0;
    for (int a = 0; a < axes; ++a) {
      const double v = sin(0.5 * k * kh[a] * h[a]) / h[a];
      f += v * v;
    }
    if (f < S * S)
      lo = k;
    else
      hi = k;
  }
  return hi < kmax ? 0.5 * (lo + hi) : NAN;
}

/* Δ₁ with sin(kΔ₁/2)/Δ₁ = S: the left side falls from k/2 (Δ₁ → 0) to 0 (Δ₁ = 2π/k). */
static double matched_spacing(double k, double S) {
  double lo = 0.0, hi = 2.0 * YEE_PI / k;
  for (int it = 0; it < 200; ++it) {
    const double d = 0.5 * (lo + hi);
    if (sin(0.5 * k * d) / d > S)
      lo = d;
    else
      hi = d;
  }
  return 0.5 * (lo + hi);
}

gm_status gm_yee_add_oblique_wave(gm_yee *s, const gm_oblique_wave *w, size_t *id) {
  if (s == NULL || w == NULL) return GM_EINVAL;
  char *msg = s->errmsg;
  const size_t cap_msg = sizeof s->errmsg;
  const int axes = s->n_axes;
  if (axes < 2)
    return gm_fail(msg, cap_msg, GM_EINVAL,
                   "oblique wave: needs a 2-D or 3-D grid (use gm_yee_add_plane_wave in 1-D)");
  if (w->interpolation != GM_INTERP_CUBIC && w->interpolation != GM_INTERP_LINEAR)
    return gm_fail(msg, cap_msg, GM_EINVAL,
                   "oblique wave: interpolation must be cubic (0) or linear (1), got %d",
                   (int)w->interpolation);
  if (!isfinite(w->theta) || !isfinite(w->phi) || !isfinite(w->psi) ||
      !(w->match_frequency >= 0.0) || !isfinite(w->match_frequency))
    return gm_fail(msg, cap_msg, GM_EINVAL,
                   "oblique wave: theta, phi, psi and match_frequency must be finite "
                   "(match_frequency >= 0)");
  double kh[3], eh[3], hh[3];
  gm_oblique_wave_vectors(w, kh, eh, hh);
  if (axes == 2 && kh[2] != 0.0)
    return gm_fail(msg, cap_msg, GM_EINVAL,
                   "oblique wave: on a 2-D grid the wave travels in the x-y plane (theta = 90, "
                   "got %g)",
                   w->theta);
  /* the grid must hold every component the incident wave has */
  for (int c = 0; c < 3; ++c) {
    if (fabs(eh[c]) > 1e-12 && !s->active[c])
      return gm_fail(msg, cap_msg, GM_EINVAL,
                     "oblique wave: its E has a %s part the grid lacks (2-D TM: psi = 90; TE: "
                     "psi = 0)",
                     gm_yee_component_name((gm_yee_component)c));
    if (fabs(hh[c]) > 1e-12 && !s->active[3 + c])
      return gm_fail(msg, cap_msg, GM_EINVAL,
                     "oblique wave: its H has a %s part the grid lacks (2-D TM: psi = 90; TE: "
                     "psi = 0)",
                     gm_yee_component_name((gm_yee_component)(3 + c)));
  }
  gm_error e;
  if (gm_waveform_check(&w->wave, &e) != GM_OK)
    return gm_fail(msg, cap_msg, GM_EINVAL, "oblique wave: %s", e.message);
  for (int b = 0; b < axes; ++b)
    if (!(w->lo[b] >= 1 && w->lo[b] < w->hi[b] && w->hi[b] + 1 <= s->L.n[b]))
      return gm_fail(msg, cap_msg, GM_EINVAL,
                     "oblique wave: the box must satisfy 1 <= lo < hi <= n - 1 on every axis "
                     "(axis %d: lo %zu, hi %zu, n %zu)",
                     b, w->lo[b], w->hi[b], s->L.n[b]);
  double eps, mu;
  yee_tfsf_background(s, w->lo, &eps, &mu);
  const double c0 = 1.0 / sqrt(eps * mu), dt = s->dt;
  /* the match frequency: given, else the waveform's, else 1/(2π w) of a plain Gaussian */
  double f = w->match_frequency;
  if (f == 0.0) f = w->wave.frequency;
  if (f == 0.0 && w->wave.width > 0.0) f = 1.0 / (2.0 * YEE_PI * w->wave.width);
  if (f >= 0.5 / dt)
    return gm_fail(msg, cap_msg, GM_EINVAL,
                   "oblique wave: match frequency %g is not below 1/(2 dt) = %g", f, 0.5 / dt);
  double d1 = 0.0;
  if (f > 0.0) {
    const double S = sin(YEE_PI * f * dt) / (c0 * dt);
    const double k = yee_wavenumber(kh, s->L.h, axes, S);
    if (!isfinite(k))
      return gm_fail(msg, cap_msg, GM_EINVAL,
                     "oblique wave: match frequency %g is above the grid's cut-off", f);
    d1 = matched_spacing(k, S);
  } else { /* no frequency to match (custom waveform): the low-frequency limit, Δ₁ = |k̂|-weighted h */
    double m = 0.0;
    for (int a = 0; a < axes; ++a) m += kh[a] * kh[a] * s->L.h[a] * s->L.h[a];
    d1 = sqrt(m);
  }
  if (!(d1 >= c0 * dt))
    return gm_fail(msg, cap_msg, GM_EINVAL,
                   "oblique wave: the matched 1-D spacing %g is below c dt = %g (the 1-D grid "
                   "would be unstable); lower dt or the match frequency",
                   d1, c0 * dt);
  /* projections on k̂ relative to the box corner the wave reaches first */
  double xref[3] = {0, 0, 0}, smax = 0.0;
  for (int a = 0; a < axes; ++a) {
    xref[a] = (kh[a] >= 0.0 ? (double)w->lo[a] : (double)w->hi[a]) * s->L.h[a];
    smax += fabs(kh[a]) * (double)(w->hi[a] - w->lo[a]) * s->L.h[a];
  }
  double reach = 0.0; /* how far outside the box a coupled neighbour can sit, along k̂ */
  for (int a = 0; a < axes; ++a) reach += fabs(kh[a]) * s->L.h[a];
  const long j0 = (long)ceil(reach / d1) + 3; /* aux node of s = 0; node 0 is driven */
  yee_tfsf t = {0};
  t.wave = w->wave;
  t.n_aux = (size_t)(j0 + (long)ceil((smax + reach) / d1) + 3 + YEE_TFSF_AUX_PML + 1);
  t.ecorr.cubic = t.hcorr.cubic = w->interpolation != GM_INTERP_LINEAR;
  t.ecorr.frac = malloc(sizeof(double));
  t.hcorr.frac = malloc(sizeof(double));
  if (!t.ecorr.frac || !t.hcorr.frac || yee_tfsf_aux_grid(&t, d1, dt, eps, mu) != 0) {
    yee_tfsf_free(&t);
    return gm_fail(msg, cap_msg, GM_ENOMEM, "oblique wave: out of memory");
  }
  const size_t pml0 = t.n_aux - 1 - YEE_TFSF_AUX_PML; /* nodes at or past it are lossy */
  size_t cap_e = 0, cap_h = 0;
  for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
    if (!s->active[c]) continue;
    const yee_box *bx = &s->upd[c];
    const int ise = yee_is_e(c);
    for (long k = (long)bx->lo[2]; k < (long)(bx->lo[2] + bx->cnt[2]); ++k)
      for (long j = (long)bx->lo[1]; j < (long)(bx->lo[1] + bx->cnt[1]); ++j)
        for (long i = (long)bx->lo[0]; i < (long)(bx->lo[0] + bx->cnt[0]); ++i) {
          const long ijk[3] = {i, j, k};
          int near = 1; /* only locations within one cell of the box couple across it */
          for (int b = 0; b < axes; ++b)
            near &= ijk[b] + 1 >= (long)w->lo[b] && ijk[b] <= (long)w->hi[b] + 1;
          if (!near) continue;
          const int tf = yee_tfsf_in_box(s, w->lo, w->hi, c, ijk);
          const size_t q = yee_idx(&s->L, i, j, k);
          yee_curl_term terms[4];
          yee_curl_terms(s, c, ijk, terms);
          for (int m = 0; m < 4; ++m) {
            const int nc = terms[m].comp;
            const double pol = nc < 3 ? eh[nc] : hh[nc - 3];
            if (pol == 0.0 || terms[m].axis >= axes) continue;
            long nb[3] = {i, j, k};
            nb[terms[m].axis] += terms[m].shift;
            if (yee_tfsf_in_box(s, w->lo, w->hi, nc, nb) == tf) continue;
            /* the neighbour's position on k̂, in aux nodes (E nodes at integers, H at +½) */
            double sh[3], proj = 0.0;
            gm_yee_component_shift(s->L.dim, (gm_yee_component)nc, sh);
            for (int a = 0; a < axes; ++a)
              proj += kh[a] * (((double)nb[a] + sh[a]) * s->L.h[a] - xref[a]);
            const double u = proj / d1 + (double)j0 - (nc < 3 ? 0.0 : 0.5);
            const double jf = floor(u);
            if (jf < 1.0 || jf + 2.0 >= (double)pml0) {
              yee_tfsf_free(&t);
              return gm_fail(msg, cap_msg, GM_EINVAL, "oblique wave: internal aux index error");
            }
            /* incident value: E_nc = ê_nc e, H_nc = ĥ_nc h */
            const double coef = (tf ? 1.0 : -1.0) * terms[m].coef * pol;
            yee_tfsf_corr *corr = ise ? &t.ecorr : &t.hcorr;
            if (yee_tfsf_push_corr(corr, ise ? &cap_e : &cap_h, c, q, (size_t)jf, coef) != 0) {
              yee_tfsf_free(&t);
              return gm_fail(msg, cap_msg, GM_ENOMEM, "oblique wave: out of memory");
            }
            corr->frac[corr->n - 1] = u - jf;
          }
        }
  }
  yee_tfsf *grown = realloc(s->tfsf, (s->n_tfsf + 1) * sizeof *grown);
  if (grown == NULL) {
    yee_tfsf_free(&t);
    return gm_fail(msg, cap_msg, GM_ENOMEM, "oblique wave: out of memory");
  }
  s->tfsf = grown;
  s->tfsf[s->n_tfsf] = t;
  if (id) *id = s->n_tfsf;
  ++s->n_tfsf;
  return GM_OK;
}
