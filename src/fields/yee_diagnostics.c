/* Diagnostics on the discrete forms: energies (plain and the leapfrog invariant), div B on
 * primal cells (seed 000 eq. 3.10), the Gauss residual div D − ρ on dual cells (eq. 3.11), and
 * the Poynting flux through a vertex plane. None of this runs inside the time loop. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fields/internal.h"

/* (d E)_f on the face of H component c (3..5) at (i,j,k), as the H kernel computes it. */
static double curl_e(const gm_yee *s, int p, int c, long i, long j, long k) {
  const int A = c - 3, B = (A + 1) % 3, C = (A + 2) % 3;
  const long q = (long)yee_idx(&s->L, i, j, k);
  const long ijk[3] = {i, j, k};
  const double *Ec = s->f[p][C], *Eb = s->f[p][B];
  const double ib = s->inv_h[B][ijk[B] + (long)s->L.offset[B]];
  const double ic = s->inv_h[C][ijk[C] + (long)s->L.offset[C]];
  return (Ec[q + s->s[B]] - Ec[q]) * ib - (Eb[q + s->s[C]] - Eb[q]) * ic;
}

static double cbh_at(const gm_yee *s, int c, size_t q) { return s->cb[c] ? s->cb[c][q] : s->cb0[c]; }

/* Dual volume weight of a location: Π h, halved for each non-periodic axis where the location
 * is a wall node (0 or n); 0 for the duplicate node n of a periodic axis. */
double yee_dual_weight(const gm_yee *s, int c, const long ijk[3]) {
  double sh[3];
  gm_yee_component_shift(s->L.dim, (gm_yee_component)c, sh);
  double w = s->L.h[0] * s->L.h[1] * s->L.h[2];
  for (int a = 0; a < s->n_axes; ++a) {
    if (sh[a] > 0.0) continue;
    if (s->periodic[a]) {
      if (ijk[a] == (long)s->L.n[a]) return 0.0;
    } else if (ijk[a] == 0 || ijk[a] == (long)s->L.n[a]) {
      w *= 0.5;
    }
  }
  return w;
}

gm_status gm_yee_get_energy(const gm_yee *s, gm_yee_energy *en) {
  if (s == NULL || en == NULL) return GM_EINVAL;
  double we = 0.0, wh = 0.0, wl = 0.0;
  for (int p = 0; p < s->n_parts; ++p)
    for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
      if (!s->active[c]) continue;
      size_t cnt[3];
      gm_yee_component_count(&s->L, (gm_yee_component)c, cnt);
      const double *f = s->f[p][c];
      for (long k = 0; k < (long)cnt[2]; ++k)
        for (long j = 0; j < (long)cnt[1]; ++j)
          for (long i = 0; i < (long)cnt[0]; ++i) {
            const long ijk[3] = {i, j, k};
            const double w = yee_dual_weight(s, c, ijk);
            if (w == 0.0) continue;
            const size_t q = yee_idx(&s->L, i, j, k);
            const double v = f[q];
            if (c < 3) {
              we += w * yee_eps_edge(s, c, i, j, k) * v * v;
            } else {
              const double mu = yee_mu_face(s, c, i, j, k);
              wh += w * mu * v * v;
              /* H^{n−1} = H^n + Δt ⋆_μ⁻¹ d E^{n−½} (the Faraday update run backwards) */
              const double prev = v + cbh_at(s, c, q) * curl_e(s, p, c, i, j, k);
              wl += w * mu * v * prev;
            }
          }
    }
  en->electric = 0.5 * we;
  en->magnetic = 0.5 * wh;
  en->plain = en->electric + en->magnetic;
  en->leapfrog = 0.5 * (we + wl);
  en->polarization = yee_dispersive_energy(s);
  return GM_OK;
}

static int in_cpml(const gm_yee *s, int a, double x) {
  const gm_yee_boundary *lo = &s->opt.boundary[2 * a], *hi = &s->opt.boundary[2 * a + 1];
  if (lo->kind == GM_BOUNDARY_CPML && x < (double)lo->pml.thickness) return 1;
  if (hi->kind == GM_BOUNDARY_CPML && x > (double)(s->L.n[a] - hi->pml.thickness)) return 1;
  return 0;
}

gm_status gm_yee_div_b(const gm_yee *s, double *out, double *max_abs) {
  if (s == NULL) return GM_EINVAL;
  if (out) memset(out, 0, s->L.size * sizeof(double));
  double mx = 0.0;
  for (int p = 0; p < s->n_parts; ++p)
    for (long k = 0; k < (long)s->L.n[2]; ++k)
      for (long j = 0; j < (long)s->L.n[1]; ++j)
        for (long i = 0; i < (long)s->L.n[0]; ++i) {
          const long ijk[3] = {i, j, k};
          int skip = 0;
          for (int a = 0; a < s->n_axes; ++a) skip |= in_cpml(s, a, (double)ijk[a] + 0.5);
          if (skip) continue;
          double div = 0.0;
          for (int a = 0; a < s->n_axes; ++a) {
            const int c = 3 + a;
            if (!s->active[c]) continue;
            long up[3] = {i, j, k};
            up[a] += 1;
            const double b1 = yee_mu_face(s, c, up[0], up[1], up[2]) *
                              s->f[p][c][yee_idx(&s->L, up[0], up[1], up[2])];
            const double b0 = yee_mu_face(s, c, i, j, k) * s->f[p][c][yee_idx(&s->L, i, j, k)];
            div += (b1 - b0) / s->L.h[a];
          }
          if (out && p == 0) out[yee_idx(&s->L, i, j, k)] = div;
          mx = fmax(mx, fabs(div));
        }
  if (max_abs) *max_abs = mx;
  return GM_OK;
}

/* D of component a on the edge at ijk, with the images/wraps of the boundaries for the edge
 * just outside (index −1 along a). Returns re and im parts. */
static void d_edge(const gm_yee *s, int a, long ijk[3], double *re, double *im) {
  *im = 0.0;
  const long n = (long)s->L.n[a];
  double sign = 1.0, cr = 1.0, ci = 0.0;
  long q3[3] = {ijk[0], ijk[1], ijk[2]};
  if (q3[a] < 0) {
    if (s->periodic[a]) {
      q3[a] = n - 1;
      cr = s->phase_cos[a];
      ci = -s->phase_sin[a];
    } else {
      q3[a] = 0;
      sign = -1.0; /* PMC: normal D is odd about the wall */
    }
  } else if (q3[a] >= n) {
    q3[a] = n - 1;
    sign = -1.0;
  }
  const size_t q = yee_idx(&s->L, q3[0], q3[1], q3[2]);
  const double eps = yee_eps_edge(s, a, q3[0], q3[1], q3[2]);
  const double r = eps * s->f[0][a][q], m = s->n_parts == 2 ? eps * s->f[1][a][q] : 0.0;
  *re = sign * (cr * r - ci * m);
  *im = sign * (ci * r + cr * m);
}

gm_status gm_yee_gauss(const gm_yee *s, double *out, double *max_abs) {
  if (s == NULL) return GM_EINVAL;
  double *res = calloc(s->L.size, sizeof(double));
  if (res == NULL) return gm_fail(((gm_yee *)s)->errmsg, sizeof s->errmsg, GM_ENOMEM, "gauss: out of memory");
  unsigned char *skip = calloc(s->L.size, 1);
  if (skip == NULL) {
    free(res);
    return GM_ENOMEM;
  }
  double mx = 0.0;
  long cnt[3];
  for (int a = 0; a < 3; ++a)
    cnt[a] = a < s->n_axes ? (long)s->L.n[a] + (s->periodic[a] ? 0 : 1) : 1;
  for (long k = 0; k < cnt[2]; ++k)
    for (long j = 0; j < cnt[1]; ++j)
      for (long i = 0; i < cnt[0]; ++i) {
        const long ijk[3] = {i, j, k};
        const size_t v = yee_idx(&s->L, i, j, k);
        int wall = 0;
        for (int a = 0; a < s->n_axes; ++a) {
          if (in_cpml(s, a, (double)ijk[a])) wall = 1;
          if (s->periodic[a]) continue;
          const gm_yee_boundary_kind lo = s->opt.boundary[2 * a].kind,
                                     hi = s->opt.boundary[2 * a + 1].kind;
          if (ijk[a] == 0 && lo != GM_BOUNDARY_PMC) wall = 1;
          if (ijk[a] == (long)s->L.n[a] && hi != GM_BOUNDARY_PMC) wall = 1;
        }
        if (wall) {
          skip[v] = 1;
          continue;
        }
        double div = 0.0, divi = 0.0;
        for (int a = 0; a < s->n_axes; ++a) {
          if (!s->active[a]) continue;
          long up[3] = {i, j, k}, dn[3] = {i, j, k};
          dn[a] -= 1;
          double r1, i1, r0, i0;
          d_edge(s, a, up, &r1, &i1);
          d_edge(s, a, dn, &r0, &i0);
          div += (r1 - r0) / s->L.h[a];
          divi += (i1 - i0) / s->L.h[a];
        }
        res[v] = div;
        (void)divi;
        mx = fmax(mx, fabs(divi));
      }
  for (size_t i = 0; i < s->n_sources; ++i) {
    const yee_source *src = &s->sources[i];
    for (size_t l = 0; l < src->n_vertices; ++l) res[src->vertex[l]] -= src->rho[l];
  }
  for (size_t v = 0; v < s->L.size; ++v) {
    if (skip[v]) res[v] = 0.0;
    mx = fmax(mx, fabs(res[v]));
  }
  if (out) memcpy(out, res, s->L.size * sizeof(double));
  if (max_abs) *max_abs = mx;
  free(res);
  free(skip);
  return GM_OK;
}

double gm_yee_charge(const gm_yee *s) {
  double q = 0.0;
  const double vol = s->L.h[0] * s->L.h[1] * s->L.h[2];
  for (size_t i = 0; i < s->n_sources; ++i)
    for (size_t l = 0; l < s->sources[i].n_vertices; ++l) q += s->sources[i].rho[l] * vol;
  return q;
}

gm_status gm_yee_poynting_flux(const gm_yee *s, int axis, size_t index, double *flux) {
  if (s == NULL || flux == NULL) return GM_EINVAL;
  gm_yee *ms = (gm_yee *)s;
  if (axis < 0 || axis >= s->n_axes)
    return gm_fail(ms->errmsg, sizeof s->errmsg, GM_EINVAL, "flux: axis %d is not an axis of the grid", axis);
  const long n = (long)s->L.n[axis], m = (long)index;
  if (m < 1 || m > n - 1)
    return gm_fail(ms->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "flux: plane %zu must be an interior vertex plane (1..%ld)", index, n - 1);
  const int b = (axis + 1) % 3, c = (axis + 2) % 3;
  double total = 0.0;
  /* S_a = E_b H_c − E_c H_b; E_b and H_c share their positions along b and c, so do E_c, H_b */
  for (int term = 0; term < 2; ++term) {
    const int ec = term == 0 ? b : c, hc = 3 + (term == 0 ? c : b);
    const double sign = term == 0 ? 1.0 : -1.0;
    if (!s->active[ec] || !s->active[hc]) continue;
    size_t cnt[3];
    gm_yee_component_count(&s->L, (gm_yee_component)ec, cnt);
    for (int p = 0; p < s->n_parts; ++p)
      for (long v = 0; v < (long)cnt[c]; ++v)
        for (long u = 0; u < (long)cnt[b]; ++u) {
          long e3[3];
          e3[axis] = m;
          e3[b] = u;
          e3[c] = v;
          double w = yee_dual_weight(s, ec, e3) / s->L.h[axis]; /* area in the plane */
          if (w == 0.0) continue;
          const double E = s->f[p][ec][yee_idx(&s->L, e3[0], e3[1], e3[2])];
          double H = 0.0;
          for (long d = -1; d <= 0; ++d) {
            long h3[3] = {e3[0], e3[1], e3[2]};
            h3[axis] = m + d;
            const size_t q = yee_idx(&s->L, h3[0], h3[1], h3[2]);
            const double hn = s->f[p][hc][q];
            /* H at t_{n−½}: the mean of H^n and H^{n−1} = H^n + Δt ⋆_μ⁻¹ d E^{n−½} */
            const double hprev = hn + cbh_at(s, hc, q) * curl_e(s, p, hc, h3[0], h3[1], h3[2]);
            H += 0.25 * (hn + hprev);
          }
          total += sign * w * E * H;
        }
  }
  *flux = total;
  return GM_OK;
}
