/* The support-volume transfer of top forms (3-forms) between unrelated tetrahedral meshes of one
 * domain (seed 001 ch. 3, notes 001 "Remeshing / multigrid transfer"): T[τ, σ] = |τ ∩ σ| / |σ|,
 * the fraction of σ's integral that lands in τ, with |σ| the measured Σ_τ |τ ∩ σ| so that the
 * total is kept to round-off.
 *
 * |τ ∩ σ|: σ is clipped by the four half-spaces of τ; after each plane the clipped body is kept
 * as a list of tetrahedra. A tetrahedron cut by a plane leaves a tetrahedron (one vertex
 * inside) or a triangular prism (two or three inside: its quadrilaterals lie in the
 * tetrahedron's faces or the plane), and a prism is three tetrahedra (a0 a1 a2 b2, a0 a1 b1 b2,
 * a0 b0 b1 b2: J. Dompierre, P. Labbé, M.-G. Vallet, R. Camarero, "How to subdivide pyramids,
 * prisms and hexahedra into tetrahedra", Proc. 8th International Meshing Roundtable, 1999,
 * §3). Candidate pairs come from a uniform grid of bucketed bounding boxes. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "dec/internal.h"
#include "geomint/multigrid.h"

#define MAXT 96 /* tetrahedra after four cuts: at most 3^4 = 81 */

typedef struct tet {
  double p[4][3];
} tet;

static double tet_volume(const tet *t) {
  double a[3], b[3], c[3];
  for (int i = 0; i < 3; ++i)
    a[i] = t->p[1][i] - t->p[0][i], b[i] = t->p[2][i] - t->p[0][i], c[i] = t->p[3][i] - t->p[0][i];
  return fabs(a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
              a[2] * (b[0] * c[1] - b[1] * c[0])) /
         6.0;
}

static void lerp(const double *x, double fx, const double *y, double fy, double *out) {
  const double t = fx / (fx - fy);
  for (int i = 0; i < 3; ++i) out[i] = x[i] + t * (y[i] - x[i]);
}

static void set_tet(tet *t, const double *a, const double *b, const double *c, const double *d) {
  memcpy(t->p[0], a, 3 * sizeof(double)), memcpy(t->p[1], b, 3 * sizeof(double));
  memcpy(t->p[2], c, 3 * sizeof(double)), memcpy(t->p[3], d, 3 * sizeof(double));
}

/* The prism with triangles a and b (a_k joined to b_k) as three tetrahedra. */
static size_t prism(const double *a0, const double *a1, const double *a2, const double *b0,
                    const double *b1, const double *b2, tet *out) {
  set_tet(out + 0, a0, a1, a2, b2);
  set_tet(out + 1, a0, a1, b1, b2);
  set_tet(out + 2, a0, b0, b1, b2);
  return 3;
}

/* The part of t where n·x <= c, as 0..3 tetrahedra in out. */
static size_t clip_tet(const tet *t, const double *n, double c, tet *out) {
  double f[4];
  int in[4], out_[4], ni = 0, no = 0;
  for (int v = 0; v < 4; ++v) {
    f[v] = n[0] * t->p[v][0] + n[1] * t->p[v][1] + n[2] * t->p[v][2] - c;
    if (f[v] <= 0.0)
      in[ni++] = v;
    else
      out_[no++] = v;
  }
  if (no == 0) return out[0] = *t, 1;
  if (ni == 0) return 0;
  const double(*p)[3] = t->p;
  if (ni == 1) {
    double q[3][3];
    for (int k = 0; k < 3; ++k) lerp(p[in[0]], f[in[0]], p[out_[k]], f[out_[k]], q[k]);
    set_tet(out, p[in[0]], q[0], q[1], q[2]);
    return 1;
  }
  if (ni == 3) { /* the tetrahedron minus the corner at the outside vertex: a prism */
    double q[3][3];
    for (int k = 0; k < 3; ++k) lerp(p[in[k]], f[in[k]], p[out_[0]], f[out_[0]], q[k]);
    return prism(p[in[0]], p[in[1]], p[in[2]], q[0], q[1], q[2], out);
  }
  /* two in, two out: the wedge between triangles (i0, q00, q01) and (i1, q10, q11) */
  double q[2][2][3];
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) lerp(p[in[a]], f[in[a]], p[out_[b]], f[out_[b]], q[a][b]);
  return prism(p[in[0]], q[0][0], q[0][1], p[in[1]], q[1][0], q[1][1], out);
}

/* The outward half-spaces n·x <= c of tetrahedron t (its four faces). */
static void half_spaces(const tet *t, double n[4][3], double c[4]) {
  for (int f = 0; f < 4; ++f) {
    const double *a = t->p[(f + 1) % 4], *b = t->p[(f + 2) % 4], *d = t->p[(f + 3) % 4];
    const double *opp = t->p[f];
    double u[3], v[3];
    for (int i = 0; i < 3; ++i) u[i] = b[i] - a[i], v[i] = d[i] - a[i];
    double m[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double cc = m[0] * a[0] + m[1] * a[1] + m[2] * a[2];
    if (m[0] * opp[0] + m[1] * opp[1] + m[2] * opp[2] > cc) /* the opposite vertex is inside */
      m[0] = -m[0], m[1] = -m[1], m[2] = -m[2], cc = -cc;
    memcpy(n[f], m, sizeof m);
    c[f] = cc;
  }
}

/* |s ∩ t| for tetrahedra s and t. */
static double overlap(const tet *s, const tet *t) {
  double n[4][3], c[4];
  half_spaces(t, n, c);
  tet a[MAXT], b[MAXT];
  size_t na = 1;
  a[0] = *s;
  for (int f = 0; f < 4 && na > 0; ++f) {
    size_t nb = 0;
    for (size_t i = 0; i < na; ++i) nb += clip_tet(&a[i], n[f], c[f], b + nb);
    memcpy(a, b, nb * sizeof(tet));
    na = nb;
  }
  double v = 0.0;
  for (size_t i = 0; i < na; ++i) v += tet_volume(&a[i]);
  return v;
}

static void get_tet(const gm_complex *cx, size_t i, tet *t, double *box) {
  const size_t *v = cx->simplices[3] + 4 * i;
  for (int a = 0; a < 4; ++a) memcpy(t->p[a], cx->x + 3 * v[a], 3 * sizeof(double));
  for (int d = 0; d < 3; ++d) {
    box[2 * d] = fmin(fmin(t->p[0][d], t->p[1][d]), fmin(t->p[2][d], t->p[3][d]));
    box[2 * d + 1] = fmax(fmax(t->p[0][d], t->p[1][d]), fmax(t->p[2][d], t->p[3][d]));
  }
}

gm_status dec_transfer_tets(const gm_complex *from, const gm_complex *to, gm_csr **out,
                            struct gm_transfer_report *report, gm_error *err) {
  const size_t na = from->count[3], nb = to->count[3];
  double *boxb = malloc((nb ? nb : 1) * 6 * sizeof(double));
  size_t *start = NULL, *bucket = NULL, *stamp = NULL, *rows = NULL, *cols = NULL;
  double *vals = NULL, *colsum = NULL;
  size_t n_trip = 0, cap = 0, pairs = 0;
  gm_csr *M = NULL;
  gm_status st = GM_OK;
  double vol_a = 0.0, vol_b = 0.0, sum = 0.0;
  if (boxb == NULL) goto oom;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < nb; ++i) {
    tet t;
    get_tet(to, i, &t, boxb + 6 * i);
    vol_b += tet_volume(&t);
    for (int d = 0; d < 3; ++d)
      lo[d] = fmin(lo[d], boxb[6 * i + 2 * d]), hi[d] = fmax(hi[d], boxb[6 * i + 2 * d + 1]);
  }
  size_t g = (size_t)ceil(cbrt((double)nb));
  if (g < 1) g = 1;
  double w[3];
  for (int d = 0; d < 3; ++d) w[d] = (hi[d] - lo[d]) / (double)g;
#define CELL(v, d) \
  (w[d] > 0.0 ? (size_t)fmin((double)(g - 1), fmax(0.0, floor(((v) - lo[d]) / w[d]))) : 0)
  start = calloc(g * g * g + 1, sizeof(size_t));
  if (start == NULL) goto oom;
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < nb; ++i) {
      const double *bx = boxb + 6 * i;
      for (size_t cz = CELL(bx[4], 2); cz <= CELL(bx[5], 2); ++cz)
        for (size_t cy = CELL(bx[2], 1); cy <= CELL(bx[3], 1); ++cy)
          for (size_t cx = CELL(bx[0], 0); cx <= CELL(bx[1], 0); ++cx) {
            size_t cell = (cz * g + cy) * g + cx;
            if (pass == 0)
              start[cell + 1]++;
            else
              bucket[start[cell]++] = i;
          }
    }
    if (pass == 0) {
      for (size_t c = 0; c < g * g * g; ++c) start[c + 1] += start[c];
      bucket = malloc((start[g * g * g] ? start[g * g * g] : 1) * sizeof(size_t));
      if (bucket == NULL) goto oom;
    } else {
      for (size_t c = g * g * g; c > 0; --c) start[c] = start[c - 1];
      start[0] = 0;
    }
  }
  stamp = malloc((nb ? nb : 1) * sizeof(size_t));
  if (stamp == NULL) goto oom;
  for (size_t i = 0; i < nb; ++i) stamp[i] = SIZE_MAX;
  for (size_t a = 0; a < na; ++a) {
    tet s, t;
    double bx[6], tb[6];
    get_tet(from, a, &s, bx);
    vol_a += tet_volume(&s);
    if (bx[1] < lo[0] || bx[0] > hi[0] || bx[3] < lo[1] || bx[2] > hi[1] || bx[5] < lo[2] ||
        bx[4] > hi[2])
      continue;
    for (size_t cz = CELL(bx[4], 2); cz <= CELL(bx[5], 2); ++cz)
      for (size_t cy = CELL(bx[2], 1); cy <= CELL(bx[3], 1); ++cy)
        for (size_t cx = CELL(bx[0], 0); cx <= CELL(bx[1], 0); ++cx) {
          const size_t cell = (cz * g + cy) * g + cx;
          for (size_t p = start[cell]; p < start[cell + 1]; ++p) {
            const size_t b = bucket[p];
            if (stamp[b] == a) continue;
            stamp[b] = a;
            const double *bb = boxb + 6 * b;
            if (bb[1] < bx[0] || bb[0] > bx[1] || bb[3] < bx[2] || bb[2] > bx[3] ||
                bb[5] < bx[4] || bb[4] > bx[5])
              continue;
            get_tet(to, b, &t, tb);
            const double v = overlap(&s, &t);
            if (!(v > 0.0)) continue;
            if (n_trip == cap) {
              cap = cap ? 2 * cap : 4096;
              size_t *r2 = realloc(rows, cap * sizeof(size_t)), *c2 = NULL;
              if (r2) rows = r2;
              c2 = r2 ? realloc(cols, cap * sizeof(size_t)) : NULL;
              if (c2) cols = c2;
              double *v2 = c2 ? realloc(vals, cap * sizeof(double)) : NULL;
              if (v2 == NULL) goto oom;
              vals = v2;
            }
            rows[n_trip] = b, cols[n_trip] = a, vals[n_trip++] = v;
            sum += v;
            ++pairs;
          }
        }
  }
#undef CELL
  if (report) {
    report->volume_from = vol_a, report->volume_to = vol_b;
    report->volume_overlap = sum, report->pairs = pairs;
  }
  const double tol = 1e-10;
  if (fabs(vol_a - sum) > tol * vol_a || fabs(vol_b - sum) > tol * vol_b) {
    st = gm_error_set(err, GM_EINVAL,
                      "the meshes cover different domains: volume |from| = %.17g, |to| = %.17g, "
                      "their overlap %.17g (relative mismatch %.3g, above %.0e)",
                      vol_a, vol_b, sum,
                      fmax(fabs(vol_a - sum) / vol_a, fabs(vol_b - sum) / vol_b), tol);
    goto done;
  }
  st = gm_csr_from_triplets(nb, na, n_trip, rows, cols, vals, &M, err);
  if (st != GM_OK) goto done;
  colsum = calloc(na ? na : 1, sizeof(double));
  if (colsum == NULL) goto oom;
  for (size_t i = 0; i < M->n_rows; ++i)
    for (size_t p = M->row_start[i]; p < M->row_start[i + 1]; ++p) colsum[M->col[p]] += M->val[p];
  for (size_t j = 0; j < na; ++j) colsum[j] = colsum[j] > 0.0 ? 1.0 / colsum[j] : 0.0;
  gm_csr_scale_cols(M, colsum);
  *out = M, M = NULL;
  goto done;
oom:
  st = gm_error_set(err, GM_ENOMEM, "out of memory in the tetrahedral clipping transfer");
done:
  gm_csr_free(M);
  free(boxb), free(start), free(bucket), free(stamp), free(rows), free(cols), free(vals);
  free(colsum);
  return st;
}
