/* The support-volume transfer between unrelated triangle meshes of one planar domain (seed 001
 * ch. 3, notes 001 "Remeshing / multigrid transfer"):
 *   ⟨Tω, τ⟩ = Σ_σ sgn(τ, σ) (|V_τ ∩ V_σ| / |V_σ|) ⟨ω, σ⟩.
 * For top forms the support volume V_σ of a triangle is the triangle. For 0-forms the seed's
 * formula is applied to the dual top form ⋆ω (the value times the dual cell): then
 * |V_w| (Tf)(w) = Σ_v |V_w ∩ V_v| f(v), which keeps constants (the raw formula with |V_σ| in the
 * denominator would not). V_v is cut into convex pieces, one per triangle T ∋ v: the points of T
 * closer to v than to T's other vertices (T minus two half-planes through the perpendicular
 * bisectors), which is the circumcentric dual piece |⋆v ∩ T| when T is well-centred.
 *
 * Intersections: pieces are convex polygons, so |P ∩ Q| comes from clipping P by the half-planes
 * of Q's edges (Sutherland & Hodgman, "Reentrant polygon clipping", CACM 17 (1974) 32–42) and the
 * shoelace formula. Candidate pairs come from a uniform grid of bucketed bounding boxes. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "dec/internal.h"
#include "geomint/multigrid.h"

#define MAXV 16 /* a piece has <= 5 vertices; clipping by <= 5 half-planes adds <= 5 */

typedef struct piece_set {
  size_t n;
  size_t *owner;   /* the simplex (k = 2) or vertex (k = 0) the piece belongs to */
  unsigned char *nv;
  double *xy;      /* MAXV points per piece, counterclockwise */
  double *box;     /* xmin, xmax, ymin, ymax */
  double total;
} piece_set;

static void piece_set_free(piece_set *p) {
  free(p->owner), free(p->nv), free(p->xy), free(p->box);
}

static double shoelace(size_t n, const double *p) {
  double a = 0.0;
  for (size_t i = 0; i < n; ++i) {
    size_t j = (i + 1) % n;
    a += p[2 * i] * p[2 * j + 1] - p[2 * j] * p[2 * i + 1];
  }
  return 0.5 * a;
}

/* Keep the part of polygon (n points in p) where a·x + b·y <= c; returns the new count. */
static size_t clip_halfplane(size_t n, const double *p, double a, double b, double c, double *q) {
  size_t m = 0;
  for (size_t i = 0; i < n; ++i) {
    const double *P = p + 2 * i, *Q = p + 2 * ((i + 1) % n);
    double fp = a * P[0] + b * P[1] - c, fq = a * Q[0] + b * Q[1] - c;
    if (fp <= 0.0) {
      q[2 * m] = P[0], q[2 * m + 1] = P[1], ++m;
    }
    if ((fp < 0.0 && fq > 0.0) || (fp > 0.0 && fq < 0.0)) {
      double t = fp / (fp - fq);
      q[2 * m] = P[0] + t * (Q[0] - P[0]);
      q[2 * m + 1] = P[1] + t * (Q[1] - P[1]);
      ++m;
    }
    if (m >= MAXV - 1) break;
  }
  return m;
}

/* |P ∩ Q| for convex counterclockwise polygons. */
static double overlap(size_t np, const double *P, size_t nq, const double *Q) {
  double a[2 * MAXV], b[2 * MAXV];
  memcpy(a, P, 2 * np * sizeof(double));
  size_t n = np;
  for (size_t i = 0; i < nq && n > 2; ++i) {
    const double *u = Q + 2 * i, *v = Q + 2 * ((i + 1) % nq);
    /* inside = left of u→v: (v − u) × (x − u) >= 0 ⇔ −(vy−uy) x + (vx−ux) y <= ... */
    double ex = v[0] - u[0], ey = v[1] - u[1];
    n = clip_halfplane(n, a, ey, -ex, ey * u[0] - ex * u[1], b);
    memcpy(a, b, 2 * n * sizeof(double));
  }
  return n > 2 ? shoelace(n, a) : 0.0;
}

static gm_status build_pieces(const gm_complex *cx, size_t k, piece_set *ps, gm_error *err) {
  const size_t nt = cx->count[2];
  const size_t per = k == 0 ? 3 : 1;
  memset(ps, 0, sizeof *ps);
  ps->owner = malloc(nt * per * sizeof(size_t));
  ps->nv = malloc(nt * per);
  ps->xy = malloc(nt * per * 2 * MAXV * sizeof(double));
  ps->box = malloc(nt * per * 4 * sizeof(double));
  if (!ps->owner || !ps->nv || !ps->xy || !ps->box) {
    piece_set_free(ps);
    return gm_error_set(err, GM_ENOMEM, "out of memory for %zu clipping pieces", nt * per);
  }
  for (size_t t = 0; t < nt; ++t) {
    const size_t *v = cx->simplices[2] + 3 * t;
    double tri[6];
    for (int i = 0; i < 3; ++i) tri[2 * i] = cx->x[2 * v[i]], tri[2 * i + 1] = cx->x[2 * v[i] + 1];
    size_t idx[3] = {v[0], v[1], v[2]};
    double area = shoelace(3, tri);
    if (area < 0.0) { /* counterclockwise */
      double s0 = tri[2], s1 = tri[3];
      tri[2] = tri[4], tri[3] = tri[5], tri[4] = s0, tri[5] = s1;
      idx[1] = v[2], idx[2] = v[1];
    }
    ps->total += fabs(area);
    for (size_t q = 0; q < per; ++q) {
      double *out = ps->xy + ps->n * 2 * MAXV;
      size_t m = 3;
      memcpy(out, tri, sizeof tri);
      if (k == 0) { /* Voronoi region of tri vertex q within the triangle */
        const double *P = tri + 2 * q;
        double tmp[2 * MAXV];
        for (int o = 1; o <= 2; ++o) {
          const double *A = tri + 2 * ((q + (size_t)o) % 3);
          /* |x − P|² <= |x − A|² ⇔ 2(A − P)·x <= |A|² − |P|² */
          double a = 2 * (A[0] - P[0]), b = 2 * (A[1] - P[1]);
          double c = A[0] * A[0] + A[1] * A[1] - P[0] * P[0] - P[1] * P[1];
          m = clip_halfplane(m, out, a, b, c, tmp);
          memcpy(out, tmp, 2 * m * sizeof(double));
        }
        ps->owner[ps->n] = idx[q];
      } else {
        ps->owner[ps->n] = t;
      }
      ps->nv[ps->n] = (unsigned char)m;
      double *bx = ps->box + 4 * ps->n;
      bx[0] = bx[2] = INFINITY, bx[1] = bx[3] = -INFINITY;
      for (size_t i = 0; i < m; ++i) {
        bx[0] = fmin(bx[0], out[2 * i]), bx[1] = fmax(bx[1], out[2 * i]);
        bx[2] = fmin(bx[2], out[2 * i + 1]), bx[3] = fmax(bx[3], out[2 * i + 1]);
      }
      ps->n++;
    }
  }
  return GM_OK;
}

gm_status gm_dec_transfer(const gm_complex *from, const gm_complex *to, size_t k, gm_csr **out,
                          gm_transfer_report *report, gm_error *err) {
  if (from == NULL || to == NULL || out == NULL)
    return gm_error_set(err, GM_EINVAL, "NULL argument");
  *out = NULL;
  if (from->n == 3 && from->N == 3 && to->n == 3 && to->N == 3) {
    if (k != 3)
      return gm_error_set(err, GM_EUNSUPPORTED,
                          "the tetrahedral clipping transfer carries top (3-)forms, not %zu-forms",
                          k);
    return dec_transfer_tets(from, to, out, report, err);
  }
  if (from->n != 2 || from->N != 2 || to->n != 2 || to->N != 2)
    return gm_error_set(err, GM_EUNSUPPORTED,
                        "the clipping transfer is for triangle meshes of the plane (dim 2 in R^2) "
                        "or tetrahedral meshes of space (dim 3 in R^3), not dim %zu in R^%zu to "
                        "dim %zu in R^%zu",
                        from->n, from->N, to->n, to->N);
  if (k != 0 && k != 2)
    return gm_error_set(err, GM_EUNSUPPORTED,
                        "the clipping transfer carries 0-forms and top (2-)forms, not %zu-forms", k);
  piece_set A, B;
  gm_status st = build_pieces(from, k, &A, err);
  if (st != GM_OK) return st;
  st = build_pieces(to, k, &B, err);
  if (st != GM_OK) {
    piece_set_free(&A);
    return st;
  }
  /* uniform grid over the union of the boxes, about one target piece per cell */
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (size_t i = 0; i < B.n; ++i) {
    lo[0] = fmin(lo[0], B.box[4 * i]), hi[0] = fmax(hi[0], B.box[4 * i + 1]);
    lo[1] = fmin(lo[1], B.box[4 * i + 2]), hi[1] = fmax(hi[1], B.box[4 * i + 3]);
  }
  size_t g = (size_t)ceil(sqrt((double)B.n));
  if (g < 1) g = 1;
  const double wx = (hi[0] - lo[0]) / (double)g, wy = (hi[1] - lo[1]) / (double)g;
  size_t *start = calloc(g * g + 1, sizeof(size_t)), *bucket = NULL, *stamp = NULL;
  size_t n_trip = 0, cap = 0;
  size_t *rows = NULL, *cols = NULL;
  double *vals = NULL;
  gm_csr *M = NULL;
#define CELL(v, l, w) \
  ((w) > 0.0 ? (size_t)fmin((double)(g - 1), fmax(0.0, floor(((v) - (l)) / (w)))) : 0)
  if (start == NULL) goto oom;
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < B.n; ++i) {
      const double *bx = B.box + 4 * i;
      for (size_t cy = CELL(bx[2], lo[1], wy); cy <= CELL(bx[3], lo[1], wy); ++cy)
        for (size_t cxi = CELL(bx[0], lo[0], wx); cxi <= CELL(bx[1], lo[0], wx); ++cxi) {
          if (pass == 0)
            start[cy * g + cxi + 1]++;
          else
            bucket[start[cy * g + cxi]++] = i;
        }
    }
    if (pass == 0) {
      for (size_t c = 0; c < g * g; ++c) start[c + 1] += start[c];
      bucket = malloc((start[g * g] ? start[g * g] : 1) * sizeof(size_t));
      if (bucket == NULL) goto oom;
    } else {
      for (size_t c = g * g; c > 0; --c) start[c] = start[c - 1];
      start[0] = 0;
    }
  }
  stamp = malloc((B.n ? B.n : 1) * sizeof(size_t));
  if (stamp == NULL) goto oom;
  for (size_t i = 0; i < B.n; ++i) stamp[i] = SIZE_MAX;
  double sum = 0.0;
  size_t pairs = 0;
  for (size_t a = 0; a < A.n; ++a) {
    const double *bx = A.box + 4 * a;
    if (bx[1] < lo[0] || bx[0] > hi[0] || bx[3] < lo[1] || bx[2] > hi[1]) continue;
    for (size_t cy = CELL(bx[2], lo[1], wy); cy <= CELL(bx[3], lo[1], wy); ++cy)
      for (size_t cxi = CELL(bx[0], lo[0], wx); cxi <= CELL(bx[1], lo[0], wx); ++cxi)
        for (size_t p = start[cy * g + cxi]; p < start[cy * g + cxi + 1]; ++p) {
          size_t b = bucket[p];
          if (stamp[b] == a) continue;
          stamp[b] = a;
          const double *bb = B.box + 4 * b;
          if (bb[1] < bx[0] || bb[0] > bx[1] || bb[3] < bx[2] || bb[2] > bx[3]) continue;
          double ar = overlap(A.nv[a], A.xy + a * 2 * MAXV, B.nv[b], B.xy + b * 2 * MAXV);
          if (!(ar > 0.0)) continue;
          if (n_trip == cap) {
            cap = cap ? 2 * cap : 1024;
            size_t *r2 = realloc(rows, cap * sizeof(size_t)), *c2 = NULL;
            if (r2) rows = r2;
            c2 = r2 ? realloc(cols, cap * sizeof(size_t)) : NULL;
            if (c2) cols = c2;
            double *v2 = c2 ? realloc(vals, cap * sizeof(double)) : NULL;
            if (v2 == NULL) goto oom;
            vals = v2;
          }
          rows[n_trip] = B.owner[b], cols[n_trip] = A.owner[a], vals[n_trip++] = ar;
          sum += ar;
          ++pairs;
        }
  }
#undef CELL
  if (report) {
    report->volume_from = A.total, report->volume_to = B.total;
    report->volume_overlap = sum, report->pairs = pairs;
  }
  const double tol = 1e-10;
  if (fabs(A.total - sum) > tol * A.total || fabs(B.total - sum) > tol * B.total) {
    st = gm_error_set(err, GM_EINVAL,
                      "the meshes cover different domains: |from| = %.17g, |to| = %.17g, their "
                      "overlap %.17g (relative mismatch %.3g, above %.0e)",
                      A.total, B.total, sum,
                      fmax(fabs(A.total - sum) / A.total, fabs(B.total - sum) / B.total), tol);
    goto done;
  }
  st = gm_csr_from_triplets(to->count[k], from->count[k], n_trip, rows, cols, vals, &M, err);
  if (st != GM_OK) goto done;
  {
    /* normalise: by the measured |V_σ| (columns) for top forms, by |V_τ| (rows) for 0-forms */
    const size_t nd = k == 2 ? M->n_cols : M->n_rows;
    double *s = calloc(nd ? nd : 1, sizeof(double));
    if (s == NULL) goto oom;
    for (size_t i = 0; i < M->n_rows; ++i)
      for (size_t p = M->row_start[i]; p < M->row_start[i + 1]; ++p)
        s[k == 2 ? M->col[p] : i] += M->val[p];
    for (size_t i = 0; i < nd; ++i) s[i] = s[i] > 0.0 ? 1.0 / s[i] : 0.0;
    if (k == 2)
      gm_csr_scale_cols(M, s);
    else
      gm_csr_scale_rows(M, s);
    free(s);
  }
  *out = M, M = NULL;
  st = GM_OK;
  goto done;
oom:
  st = gm_error_set(err, GM_ENOMEM, "out of memory in the clipping transfer");
done:
  gm_csr_free(M);
  free(start), free(bucket), free(stamp), free(rows), free(cols), free(vals);
  piece_set_free(&A), piece_set_free(&B);
  return st;
}
