/* Primal–primal wedge products (seed 001 §3.8 (i) and (ii)), flat and sharp (seed 001 §3.7,
 * corrected as in Hirani, "Discrete exterior calculus", PhD thesis, Caltech 2003, §5).
 *
 * The wedge sums over the permutations τ of the vertices of σ = [v_0..v_p], p = k + l. A term
 * depends on τ only through the vertex sets A = {τ0..τk} and B = {τk..τp} and the sign of τ
 * times the parities that sort the two tuples, so the (A, B, coefficient) triples are tabulated
 * once per (k, l) and each simplex costs a handful of multiply-adds. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dec/internal.h"

typedef struct {
  unsigned a, b;   /* vertex position masks of the α face and the β face */
  unsigned shared; /* position of the shared vertex τ(k) */
  double coef;     /* Σ sign(τ) · parity(sort front) · parity(sort back) */
} wedge_term;

static int perm_parity(const size_t *t, size_t m) {
  int par = 0;
  for (size_t i = 0; i < m; ++i)
    for (size_t j = i + 1; j < m; ++j) par ^= t[i] > t[j];
  return par;
}

/* Enumerate the permutations of 0..p in lexicographic order and merge equal (A, B) terms. */
static size_t wedge_terms(size_t k, size_t l, wedge_term *terms) {
  const size_t p = k + l, m = p + 1;
  size_t perm[GM_LOCAL_MAX], nt = 0;
  for (size_t i = 0; i < m; ++i) perm[i] = i;
  for (;;) {
    int s = perm_parity(perm, m);
    int sf = perm_parity(perm, k + 1);
    int sb = perm_parity(perm + k, l + 1);
    double c = ((s ^ sf ^ sb) & 1) ? -1.0 : 1.0;
    unsigned a = 0, b = 0;
    for (size_t i = 0; i <= k; ++i) a |= 1u << perm[i];
    for (size_t i = k; i <= p; ++i) b |= 1u << perm[i];
    size_t q = 0;
    while (q < nt && !(terms[q].a == a && terms[q].b == b)) ++q;
    if (q == nt) {
      terms[nt].a = a;
      terms[nt].b = b;
      terms[nt].shared = (unsigned)perm[k];
      terms[nt].coef = 0.0;
      ++nt;
    }
    terms[q].coef += c;
    /* next permutation */
    size_t i = m - 1;
    while (i > 0 && perm[i - 1] > perm[i]) --i;
    if (i == 0) break;
    size_t j = m - 1;
    while (perm[j] < perm[i - 1]) --j;
    size_t t = perm[i - 1];
    perm[i - 1] = perm[j];
    perm[j] = t;
    for (size_t a0 = i, b0 = m - 1; a0 < b0; ++a0, --b0) {
      t = perm[a0];
      perm[a0] = perm[b0];
      perm[b0] = t;
    }
  }
  /* drop cancelled terms */
  size_t w = 0;
  for (size_t q = 0; q < nt; ++q)
    if (terms[q].coef != 0.0) terms[w++] = terms[q];
  return w;
}

static const double factorial_table[] = {1.0, 1.0, 2.0, 6.0, 24.0};

/* Value of cochain a (degree d) on the face of simplex s (degree p) given by mask, in the
 * ascending orientation of that face. */
static double face_value(const gm_complex *cx, size_t p, size_t s, size_t d, unsigned mask,
                         const double *a) {
  size_t f = gm_local_face(cx, p, s, mask);
  return a[f] * gm_simplex_sign(cx, d, f);
}

static gm_status wedge_impl(const gm_complex *cx, const gm_geometry *g, size_t k,
                            const double *alpha, size_t l, const double *beta, double *out) {
  if (cx == NULL || alpha == NULL || beta == NULL || out == NULL) return GM_EINVAL;
  const size_t n = cx->n, p = k + l;
  if (p > n) return GM_EINVAL;
  wedge_term terms[24];
  const size_t nt = wedge_terms(k, l, terms);
  const size_t N = cx->N;
  for (size_t s = 0; s < cx->count[p]; ++s) {
    double w[GM_LOCAL_MAX];
    if (g != NULL && p > 0) {
      double pts[GM_LOCAL_MAX * GM_DEC_MAX_EMBED], pieces[16];
      gm_gather_points(cx, p, cx->simplices[p] + s * (p + 1), pts);
      gm_local_dual_pieces(N, p, pts, GM_DUAL_CIRCUMCENTRIC, pieces);
      double vol = gm_local_volume(N, p, pts);
      for (size_t i = 0; i <= p; ++i) w[i] = pieces[1u << i] / vol / factorial_table[p];
    } else {
      for (size_t i = 0; i <= p; ++i) w[i] = 1.0 / factorial_table[p + 1];
    }
    double sum = 0.0;
    for (size_t q = 0; q < nt; ++q)
      sum += terms[q].coef * w[terms[q].shared] * face_value(cx, p, s, k, terms[q].a, alpha) *
             face_value(cx, p, s, l, terms[q].b, beta);
    out[s] = sum * gm_simplex_sign(cx, p, s);
  }
  return GM_OK;
}

gm_status gm_dec_wedge(const gm_complex *cx, size_t k, const double *alpha, size_t l,
                       const double *beta, double *out) {
  return wedge_impl(cx, NULL, k, alpha, l, beta, out);
}

gm_status gm_dec_wedge_circumcentric(const gm_geometry *g, size_t k, const double *alpha,
                                     size_t l, const double *beta, double *out) {
  if (g == NULL) return GM_EINVAL;
  return wedge_impl(g->cx, g, k, alpha, l, beta, out);
}

gm_status gm_dec_flat(const gm_geometry *g, const double *X, double *alpha) {
  if (g == NULL || X == NULL || alpha == NULL) return GM_EINVAL;
  const gm_complex *cx = g->cx;
  const size_t n = cx->n, N = cx->N, ne = cx->count[1], nl = gm_binomial(n + 1, 2);
  double *sumabs = calloc(ne ? ne : 1, sizeof(double));
  double *plain = calloc(ne ? ne : 1, sizeof(double));
  unsigned char *ncof = calloc(ne ? ne : 1, 1);
  if (!sumabs || !plain || !ncof) {
    free(sumabs), free(plain), free(ncof);
    return GM_ENOMEM;
  }
  for (size_t e = 0; e < ne; ++e) alpha[e] = 0.0;
  size_t idx[6];
  double pieces[6];
  for (size_t T = 0; T < cx->count[n]; ++T) {
    gm_complex_local_faces(cx, T, 1, idx);
    gm_geometry_dual_pieces(g, T, 1, pieces);
    const double *XT = X + T * N;
    for (size_t i = 0; i < nl; ++i) {
      size_t e = idx[i];
      const double *a = cx->x + cx->simplices[1][2 * e] * N, *b = cx->x + cx->simplices[1][2 * e + 1] * N;
      double xe = 0.0;
      for (size_t j = 0; j < N; ++j) xe += XT[j] * (b[j] - a[j]);
      alpha[e] += pieces[i] * xe;
      plain[e] += xe;
      sumabs[e] += fabs(pieces[i]);
      ncof[e]++;
    }
  }
  for (size_t e = 0; e < ne; ++e) {
    double d = g->dual[1][e];
    if (fabs(d) <= 1e-12 * sumabs[e])
      alpha[e] = plain[e] / (double)ncof[e];
    else
      alpha[e] /= d;
  }
  free(sumabs), free(plain), free(ncof);
  return GM_OK;
}

gm_status gm_dec_sharp(const gm_geometry *g, const double *alpha, double *X) {
  if (g == NULL || X == NULL || alpha == NULL) return GM_EINVAL;
  const gm_complex *cx = g->cx;
  const size_t n = cx->n, N = cx->N, nv = cx->count[0];
  double *acc_vol = calloc(nv * N + nv, sizeof(double)); /* volume-weighted fallback + Σ|T| */
  double *sumabs = calloc(nv ? nv : 1, sizeof(double));
  if (!acc_vol || !sumabs) {
    free(acc_vol), free(sumabs);
    return GM_ENOMEM;
  }
  double *vsum = acc_vol + nv * N;
  for (size_t i = 0; i < nv * N; ++i) X[i] = 0.0;
  double p[GM_LOCAL_MAX * GM_DEC_MAX_EMBED], grad[GM_LOCAL_MAX * GM_DEC_MAX_EMBED], pieces[4];
  for (size_t T = 0; T < cx->count[n]; ++T) {
    const size_t *t = cx->simplices[n] + T * (n + 1);
    gm_gather_points(cx, n, t, p);
    if (!gm_local_barycentric_gradients(N, n, p, grad)) {
      free(acc_vol), free(sumabs);
      return GM_EINVAL;
    }
    gm_geometry_dual_pieces(g, T, 0, pieces);
    const double vol = g->primal[n][T];
    for (size_t a = 0; a <= n; ++a) {
      double v[GM_DEC_MAX_EMBED] = {0};
      for (size_t b = 0; b <= n; ++b) {
        if (b == a) continue;
        unsigned mask = (1u << a) | (1u << b);
        size_t e = gm_local_face(cx, n, T, mask);
        double val = alpha[e] * (a < b ? 1.0 : -1.0); /* ⟨α, [v_a, v_b]⟩ */
        for (size_t j = 0; j < N; ++j) v[j] += val * grad[b * N + j];
      }
      const size_t va = t[a];
      for (size_t j = 0; j < N; ++j) {
        X[va * N + j] += pieces[a] * v[j];
        acc_vol[va * N + j] += vol * v[j];
      }
      sumabs[va] += fabs(pieces[a]);
      vsum[va] += vol;
    }
  }
  for (size_t v = 0; v < nv; ++v) {
    double d = g->dual[0][v];
    for (size_t j = 0; j < N; ++j) {
      if (fabs(d) <= 1e-12 * sumabs[v])
        X[v * N + j] = acc_vol[v * N + j] / vsum[v];
      else
        X[v * N + j] /= d;
    }
  }
  free(acc_vol), free(sumabs);
  return GM_OK;
}
