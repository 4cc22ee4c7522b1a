/* Geometry of a single simplex [p_0..p_m] (m <= 3) in R^N: volume, circumcenter with its
 * barycentric coordinates, gradients of the barycentric coordinates, and the signed pieces of the
 * dual cells inside the simplex.
 *
 * Circumcenters are computed relative to p_0 with the cross-product formulas of Shewchuk
 * ("Lecture notes on geometric robustness", 2013, §"circumcenters"): for a triangle
 * c − p0 = ((|a|² b − |b|² a) × (a × b)) / (2 |a × b|²), for a tetrahedron
 * c − p0 = (|a|² (b × c) + |b|² (c × a) + |c|² (a × b)) / (2 a·(b × c)), with a, b, c the edge
 * vectors from p0. Their denominators are squared volumes computed from cross products, not from
 * |a|²|b|² − (a·b)², so thin simplices lose no accuracy to cancellation. For N > 3 the Gram system
 * (e_i·e_j) a = ½|e_i|² is solved instead (less accurate for thin simplices).
 *
 * Dual pieces (circumcentric): the dual cell of a k-face s inside the simplex is the union of the
 * simplices [c(s_k), c(s_{k+1}), .., c(s_m)] over all chains s = s_k ⊂ s_{k+1} ⊂ .. ⊂ s_m (seed
 * 001 §3.3). Consecutive circumcenters differ by a vector orthogonal to aff(s_j), so each such
 * simplex has volume Π_j |c(s_{j+1}) − c(s_j)| / (m−k)!; its sign is the product of the signs of
 * the barycentric coordinate of c(s_{j+1}) for the vertex of s_{j+1} not in s_j (Hirani,
 * Kalyanaraman, VanderZee, "Delaunay Hodge star", CAD 45 (2013), §3). With signed heights
 * h(s_j, s_{j+1}) this is P(s) = Σ_{v ∉ s} h(s, s ∪ v) P(s ∪ v), P(S) = 1, |⋆s ∩ S| = P(s)/(m−k)!.
 * Barycentric duals use barycenters and the (unsigned) volumes of the same chain simplices. */
#include <math.h>
#include <string.h>

#include "dec/internal.h"

static void cross3(const double *a, const double *b, double *c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Edge vectors e_i = p_i − p_0 padded to 3 components (N <= 3). */
static void edges3(size_t N, size_t m, const double *p, double e[3][3]) {
  memset(e, 0, 9 * sizeof(double));
  for (size_t i = 1; i <= m; ++i)
    for (size_t j = 0; j < N; ++j) e[i - 1][j] = p[i * N + j] - p[j];
}

/* Solve the m×m system g a = r (m <= 3) by Gaussian elimination with partial pivoting;
 * returns 0 when singular. */
static int small_solve(size_t m, double g[3][3], double *r) {
  for (size_t c = 0; c < m; ++c) {
    size_t piv = c;
    for (size_t i = c + 1; i < m; ++i)
      if (fabs(g[i][c]) > fabs(g[piv][c])) piv = i;
    if (g[piv][c] == 0.0) return 0;
    if (piv != c) {
      for (size_t j = 0; j < m; ++j) {
        double t = g[c][j];
        g[c][j] = g[piv][j];
        g[piv][j] = t;
      }
      double t = r[c];
      r[c] = r[piv];
      r[piv] = t;
    }
    for (size_t i = c + 1; i < m; ++i) {
      double f = g[i][c] / g[c][c];
      for (size_t j = c; j < m; ++j) g[i][j] -= f * g[c][j];
      r[i] -= f * r[c];
    }
  }
  for (size_t c = m; c-- > 0;) {
    for (size_t j = c + 1; j < m; ++j) r[c] -= g[c][j] * r[j];
    r[c] /= g[c][c];
  }
  return 1;
}

static double gram_det_volume(size_t N, size_t m, const double *p) {
  /* sqrt(det G)/m! with G = EᵀE, by elimination (N > 3 fallback) */
  double g[3][3];
  for (size_t i = 0; i < m; ++i)
    for (size_t j = 0; j < m; ++j) {
      double s = 0.0;
      for (size_t q = 0; q < N; ++q) s += (p[(i + 1) * N + q] - p[q]) * (p[(j + 1) * N + q] - p[q]);
      g[i][j] = s;
    }
  double det = 1.0;
  for (size_t c = 0; c < m; ++c) {
    size_t piv = c;
    for (size_t i = c + 1; i < m; ++i)
      if (fabs(g[i][c]) > fabs(g[piv][c])) piv = i;
    if (g[piv][c] == 0.0) return 0.0;
    if (piv != c)
      for (size_t j = 0; j < m; ++j) {
        double t = g[c][j];
        g[c][j] = g[piv][j];
        g[piv][j] = t;
      }
    det *= g[c][c];
    for (size_t i = c + 1; i < m; ++i) {
      double f = g[i][c] / g[c][c];
      for (size_t j = c; j < m; ++j) g[i][j] -= f * g[c][j];
    }
  }
  double fact = m == 3 ? 6.0 : (double)(m ? m : 1);
  return det > 0.0 ? sqrt(det) / fact : 0.0;
}

double gm_local_volume(size_t N, size_t m, const double *p) {
  if (m == 0) return 1.0;
  if (N > 3) return gram_det_volume(N, m, p);
  double e[3][3], n[3];
  edges3(N, m, p, e);
  if (m == 1) return sqrt(dot3(e[0], e[0]));
  cross3(e[0], e[1], n);
  if (m == 2) return 0.5 * sqrt(dot3(n, n));
  return fabs(dot3(e[2], n)) / 6.0;
}

double gm_local_circumcenter(size_t N, size_t m, const double *p, double *c, double *bary) {
  if (m == 0) {
    memcpy(c, p, N * sizeof(double));
    bary[0] = 1.0;
    return 1.0;
  }
  if (m == 1) {
    for (size_t j = 0; j < N; ++j) c[j] = 0.5 * (p[j] + p[N + j]);
    bary[0] = bary[1] = 0.5;
    double span = 0.0, d2 = 0.0; /* scaled by a power of two, as below */
    for (size_t j = 0; j < N; ++j) span = fmax(span, fabs(p[N + j] - p[j]));
    if (!(span > 0.0) || !isfinite(span)) return span;
    int ex;
    frexp(span, &ex);
    const double scale = ldexp(1.0, ex);
    for (size_t j = 0; j < N; ++j) {
      double d = (p[N + j] - p[j]) / scale;
      d2 += d * d;
    }
    return sqrt(d2) * scale;
  }
  double a[3] = {0, 0, 0};
  double vol;
  if (N <= 3) {
    double e[3][3], r[3], t[3], u[3], n[3];
    edges3(N, m, p, e);
    /* Work on the edges divided by a power of two near their size: exact, so ordinary simplices
     * give bitwise the same numbers, while |a|², |a × b|² and the volume no longer overflow or
     * underflow for coordinates of 1e100 (or 1e-100); the volume is scaled back at the end. */
    double span = 0.0;
    for (size_t i = 0; i < m; ++i)
      for (size_t j = 0; j < 3; ++j) span = fmax(span, fabs(e[i][j]));
    if (!(span > 0.0) || !isfinite(span)) return 0.0;
    int ex;
    frexp(span, &ex);
    const double scale = ldexp(1.0, ex);
    for (size_t i = 0; i < m; ++i)
      for (size_t j = 0; j < 3; ++j) e[i][j] /= scale;
    const double volume_scale = m == 2 ? scale * scale : scale * scale * scale;
    if (m == 2) {
      cross3(e[0], e[1], n);
      double nn = dot3(n, n);
      vol = 0.5 * sqrt(nn);
      if (nn == 0.0) return 0.0;
      double aa = dot3(e[0], e[0]), bb = dot3(e[1], e[1]);
      for (size_t j = 0; j < 3; ++j) t[j] = aa * e[1][j] - bb * e[0][j];
      cross3(t, n, r);
      for (size_t j = 0; j < 3; ++j) r[j] /= 2.0 * nn;
      cross3(r, e[1], u);
      a[0] = dot3(u, n) / nn;
      cross3(e[0], r, u);
      a[1] = dot3(u, n) / nn;
      vol *= volume_scale;
    } else {
      double bc[3], ca[3], ab[3];
      cross3(e[1], e[2], bc);
      cross3(e[2], e[0], ca);
      cross3(e[0], e[1], ab);
      double D = dot3(e[0], bc);
      vol = fabs(D) / 6.0;
      if (D == 0.0) return 0.0;
      double aa = dot3(e[0], e[0]), bb = dot3(e[1], e[1]), cc = dot3(e[2], e[2]);
      for (size_t j = 0; j < 3; ++j) r[j] = (aa * bc[j] + bb * ca[j] + cc * ab[j]) / (2.0 * D);
      a[0] = dot3(r, bc) / D;
      a[1] = dot3(r, ca) / D;
      a[2] = dot3(r, ab) / D;
      vol *= volume_scale;
    }
  } else {
    double g[3][3], r[3];
    for (size_t i = 0; i < m; ++i) {
      for (size_t j = 0; j < m; ++j) {
        double s = 0.0;
        for (size_t q = 0; q < N; ++q) s += (p[(i + 1) * N + q] - p[q]) * (p[(j + 1) * N + q] - p[q]);
        g[i][j] = s;
      }
      r[i] = 0.5 * g[i][i];
    }
    vol = gram_det_volume(N, m, p);
    if (!small_solve(m, g, r)) return 0.0;
    for (size_t i = 0; i < m; ++i) a[i] = r[i];
  }
  double s = 0.0;
  for (size_t i = 0; i < m; ++i) {
    bary[i + 1] = a[i];
    s += a[i];
  }
  bary[0] = 1.0 - s;
  for (size_t j = 0; j < N; ++j) {
    double v = p[j];
    for (size_t i = 0; i < m; ++i) v += a[i] * (p[(i + 1) * N + j] - p[j]);
    c[j] = v;
  }
  return vol;
}

int gm_local_barycentric_gradients(size_t N, size_t m, const double *p, double *grad) {
  /* ∇λ_i = Σ_j (G^{-1})_{ij} e_j for i >= 1, ∇λ_0 = −Σ_i ∇λ_i, with G = EᵀE */
  double g[3][3], inv[3][3];
  for (size_t i = 0; i < m; ++i)
    for (size_t j = 0; j < m; ++j) {
      double s = 0.0;
      for (size_t q = 0; q < N; ++q) s += (p[(i + 1) * N + q] - p[q]) * (p[(j + 1) * N + q] - p[q]);
      g[i][j] = s;
    }
  for (size_t c = 0; c < m; ++c) {
    double gg[3][3], r[3] = {0, 0, 0};
    memcpy(gg, g, sizeof gg);
    r[c] = 1.0;
    if (!small_solve(m, gg, r)) return 0;
    for (size_t i = 0; i < m; ++i) inv[i][c] = r[i];
  }
  for (size_t q = 0; q < N; ++q) grad[q] = 0.0;
  for (size_t i = 0; i < m; ++i)
    for (size_t q = 0; q < N; ++q) {
      double s = 0.0;
      for (size_t j = 0; j < m; ++j) s += inv[i][j] * (p[(j + 1) * N + q] - p[q]);
      grad[(i + 1) * N + q] = s;
      grad[q] -= s;
    }
  return 1;
}

static size_t popcount(unsigned s) {
  size_t c = 0;
  for (; s; s &= s - 1) ++c;
  return c;
}

static const double factorial[] = {1.0, 1.0, 2.0, 6.0};

/* Barycentric dual: sum over chains s = s_k ⊂ .. ⊂ S of the volumes of [b(s_k), .., b(S)]. */
static double bary_chain(size_t N, size_t m, const double *centers, unsigned s, unsigned full,
                         double *pts, size_t depth) {
  memcpy(pts + depth * N, centers + s * N, N * sizeof(double));
  if (s == full) return depth == 0 ? 1.0 : gm_local_volume(N, depth, pts);
  double sum = 0.0;
  for (size_t v = 0; v <= m; ++v)
    if (!(s & (1u << v))) sum += bary_chain(N, m, centers, s | (1u << v), full, pts, depth + 1);
  return sum;
}

void gm_local_dual_pieces(size_t N, size_t m, const double *p, gm_dual_kind kind, double *pieces) {
  const unsigned full = (1u << (m + 1)) - 1;
  double centers[16 * 8], bary[16][GM_LOCAL_MAX], sub[GM_LOCAL_MAX * 8];
  /* N <= 8 supported for local work arrays */
  for (unsigned s = 1; s <= full; ++s) {
    size_t q = 0;
    for (size_t v = 0; v <= m; ++v)
      if (s & (1u << v)) memcpy(sub + (q++) * N, p + v * N, N * sizeof(double));
    if (kind == GM_DUAL_BARYCENTRIC) {
      for (size_t j = 0; j < N; ++j) {
        double t = 0.0;
        for (size_t i = 0; i < q; ++i) t += sub[i * N + j];
        centers[s * N + j] = t / (double)q;
      }
    } else {
      gm_local_circumcenter(N, q - 1, sub, centers + s * N, bary[s]);
    }
  }
  if (kind == GM_DUAL_BARYCENTRIC) {
    double pts[GM_LOCAL_MAX * 8];
    for (unsigned s = 1; s <= full; ++s) pieces[s] = bary_chain(N, m, centers, s, full, pts, 0);
    return;
  }
  double P[16];
  P[full] = 1.0;
  for (size_t size = m; size >= 1; --size)
    for (unsigned s = 1; s < full; ++s) {
      if (popcount(s) != size) continue;
      double sum = 0.0;
      for (size_t v = 0; v <= m; ++v) {
        if (s & (1u << v)) continue;
        unsigned t = s | (1u << v);
        /* position of v among the vertices of t: index of its barycentric coordinate */
        size_t pos = popcount(t & ((1u << v) - 1));
        double d2 = 0.0;
        for (size_t j = 0; j < N; ++j) {
          double dd = centers[t * N + j] - centers[s * N + j];
          d2 += dd * dd;
        }
        double lam = bary[t][pos];
        double h = lam > 0.0 ? sqrt(d2) : lam < 0.0 ? -sqrt(d2) : 0.0;
        sum += h * P[t];
      }
      P[s] = sum;
    }
  for (unsigned s = 1; s <= full; ++s) pieces[s] = P[s] / factorial[m + 1 - popcount(s)];
}
