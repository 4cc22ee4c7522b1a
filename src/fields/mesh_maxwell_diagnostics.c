/* Mesh Maxwell solver: probes (Whitney interpolation), energy, div B, Gauss's law, charge. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "fields/mesh_maxwell.h"

/* Barycentric coordinates of x in top simplex T (ascending vertex order); 1 when inside. */
static int locate(const gm_mesh_maxwell *s, size_t T, const double *x, double *bary) {
  const size_t n = s->n;
  const size_t *v = gm_complex_simplices(s->cx, n) + T * (n + 1);
  const double *X = gm_complex_coordinates(s->cx);
  double M[3][3], r[3];
  for (size_t i = 0; i < n; ++i) {
    r[i] = x[i] - X[v[0] * n + i];
    for (size_t j = 0; j < n; ++j) M[i][j] = X[v[j + 1] * n + i] - X[v[0] * n + i];
  }
  double l[3];
  if (n == 2) {
    const double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    l[0] = (r[0] * M[1][1] - r[1] * M[0][1]) / det;
    l[1] = (M[0][0] * r[1] - M[1][0] * r[0]) / det;
  } else {
    const double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                       M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                       M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
    for (size_t c = 0; c < 3; ++c) { /* Cramer */
      double A[3][3];
      memcpy(A, M, sizeof A);
      for (size_t i = 0; i < 3; ++i) A[i][c] = r[i];
      l[c] = (A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
              A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
              A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0])) / det;
    }
  }
  double l0 = 1.0;
  for (size_t i = 0; i < n; ++i) { bary[i + 1] = l[i]; l0 -= l[i]; }
  bary[0] = l0;
  for (size_t i = 0; i <= n; ++i) if (bary[i] < -1e-12) return 0;
  return 1;
}

gm_status gm_mesh_maxwell_add_probe(gm_mesh_maxwell *s, gm_yee_component c, const double x[3],
                                    size_t capacity, size_t *id) {
  const int is_e = c >= GM_EX && c <= GM_EZ, is_h = c >= GM_HX && c <= GM_HZ;
  if ((!is_e && !is_h) || (s->n == 2 && (c == GM_EZ || c == GM_HX || c == GM_HY)))
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "add_probe: component %d is not carried (2-D meshes carry Ex, Ey, Hz)", (int)c);
  if (!x || !capacity)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "add_probe: no point or capacity 0");
  mm_probe p = {c, SIZE_MAX, {0}, capacity, 0, NULL, NULL, {0, 0, 0}, s->t};
  for (size_t T = 0; T < s->nt; ++T)
    if (locate(s, T, x, p.bary)) { p.top = T; break; }
  if (p.top == SIZE_MAX)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "add_probe: the point (%g, %g, %g) lies in no cell", x[0], x[1],
                   s->n == 3 ? x[2] : 0.0);
  mm_probe *grown = realloc(s->probe, (s->n_probe + 1) * sizeof *grown);
  if (!grown) return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "add_probe: no memory");
  s->probe = grown;
  if (is_e && s->opt.scheme == GM_MESH_AVI) { /* the interval means start here */
    mm_avi_sync_a(s, s->t, s->work_e);
    gm_dec_whitney_interpolate(s->cx, 1, s->work_e, p.top, p.bary, p.a_prev);
  }
  p.t = malloc(capacity * sizeof(double));
  p.v = malloc(capacity * sizeof(double));
  if (!p.t || !p.v) {
    free(p.t); free(p.v);
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "add_probe: no memory");
  }
  s->probe[s->n_probe] = p;
  if (id) *id = s->n_probe;
  ++s->n_probe;
  return GM_OK;
}

gm_status gm_mesh_maxwell_probe_samples(const gm_mesh_maxwell *s, size_t id, size_t *n,
                                        const double **t, const double **values) {
  if (id >= s->n_probe) return GM_EINVAL;
  if (n) *n = s->probe[id].n;
  if (t) *t = s->probe[id].t;
  if (values) *values = s->probe[id].v;
  return GM_OK;
}

gm_status mm_probe_record(gm_mesh_maxwell *s, double t, const double *B) {
  for (size_t i = 0; i < s->n_probe; ++i) {
    mm_probe *p = &s->probe[i];
    if (p->n >= p->cap)
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "probe %zu is full (%zu samples)",
                     i, p->cap);
    double comp[3] = {0, 0, 0};
    double value;
    if (p->c <= GM_EZ && s->opt.scheme == GM_MESH_AVI) {
      /* the mean of E over the sampling interval, exactly −ΔA/Δt, at the interval's middle:
         under the AVI E is piecewise constant in time with jumps at the events of the fast
         cells, and a point sample aliases their modes into the band */
      gm_dec_whitney_interpolate(s->cx, 1, s->work_e, p->top, p->bary, comp);
      const int k = p->c - GM_EX;
      value = -(comp[k] - p->a_prev[k]) / (t - p->t_prev);
      p->t[p->n] = 0.5 * (t + p->t_prev);
      memcpy(p->a_prev, comp, sizeof comp);
      p->t_prev = t;
    } else if (p->c <= GM_EZ) {
      gm_dec_whitney_interpolate(s->cx, 1, s->E, p->top, p->bary, comp);
      value = comp[p->c - GM_EX];
      /* E is at t − Δt/2 in the leapfrog */
      p->t[p->n] = s->opt.scheme == GM_MESH_LEAPFROG ? t - 0.5 * s->dt : t;
    } else {
      gm_dec_whitney_interpolate(s->cx, 2, B, p->top, p->bary, comp);
      /* components ω(e_i, e_j), i < j: 2-D (xy) = Bz; 3-D (xy, xz, yz) = (Bz, −By, Bx) */
      if (s->n == 2) value = comp[0];
      else value = p->c == GM_HX ? comp[2] : p->c == GM_HY ? -comp[1] : comp[0];
      p->t[p->n] = t;
    }
    if (p->c >= GM_HX) value /= s->mu_cell[p->top]; /* H = B / μ */
    p->v[p->n++] = value;
  }
  return GM_OK;
}

void gm_mesh_maxwell_energy_get(const gm_mesh_maxwell *s, gm_mesh_maxwell_energy *en) {
  double we = 0.0, wm = 0.0;
  for (size_t e = 0; e < s->ne; ++e) we += 0.5 * s->E[e] * s->D[e]; /* D = ⋆_ε E */
  const double *B = s->B;
  if (s->opt.scheme == GM_MESH_AVI) {
    gm_mesh_maxwell_sync_b(s, s->work_f);
    B = s->work_f;
  }
  double *H = s->work_f2;
  mm_apply_nu(s, B, H);
  for (size_t f = 0; f < s->nf; ++f) wm += 0.5 * H[f] * B[f];
  double wl = we + wm;
  if (s->opt.scheme == GM_MESH_LEAPFROG) {
    /* B^{n−1} = B^n + Δt d₁E^{n−½}: ½ B^{n−1}·⋆_ν B^n */
    const gm_csr *d1 = s->d1;
    double m = 0.0;
    for (size_t f = 0; f < s->nf; ++f) {
      double curl = 0.0;
      for (size_t p = d1->row_start[f]; p < d1->row_start[f + 1]; ++p)
        curl += d1->val[p] * s->E[d1->col[p]];
      m += 0.5 * H[f] * (B[f] + s->dt * curl);
    }
    wl = we + m;
  }
  en->electric = we;
  en->magnetic = wm;
  en->plain = we + wm;
  en->leapfrog = wl;
}

double gm_mesh_maxwell_div_b(const gm_mesh_maxwell *s) {
  if (!s->d2) return 0.0;
  double *B = s->work_f;
  gm_mesh_maxwell_sync_b(s, B);
  double m = 0.0;
  const gm_csr *d2 = s->d2;
  for (size_t T = 0; T < s->nt; ++T) {
    double div = 0.0;
    for (size_t p = d2->row_start[T]; p < d2->row_start[T + 1]; ++p)
      div += d2->val[p] * B[d2->col[p]];
    if (isnan(div)) return NAN; /* a blown-up run must not report a clean invariant */
    m = fabs(div) > m ? fabs(div) : m;
  }
  return m;
}

double gm_mesh_maxwell_gauss(const gm_mesh_maxwell *s, double *out) {
  double *acc = out ? out : s->work_v;
  memset(acc, 0, s->nv * sizeof(double));
  const size_t *ev = gm_complex_simplices(s->cx, 1);
  /* div D = −d₀ᵀD; d₀ row e is −1 at the tail ev[2e], +1 at the head ev[2e+1] */
  for (size_t e = 0; e < s->ne; ++e) {
    acc[ev[2 * e]] += s->D[e];
    acc[ev[2 * e + 1]] -= s->D[e];
  }
  double m = 0.0;
  for (size_t v = 0; v < s->nv; ++v) {
    acc[v] = s->bnd_v[v] ? 0.0 : acc[v] - s->rho[v];
    m = !(fabs(acc[v]) <= m) && !isnan(m) ? fabs(acc[v]) : m; /* NaN sticks */
  }
  return m;
}

double gm_mesh_maxwell_charge(const gm_mesh_maxwell *s) {
  double q = 0.0;
  for (size_t v = 0; v < s->nv; ++v) q += s->rho[v];
  return q;
}
