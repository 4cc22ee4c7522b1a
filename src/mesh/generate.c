/* Mesh generators: structured rectangles and boxes with several cutting patterns, annulus,
 * icosphere, torus. Cells come out positively oriented (counterclockwise in the plane, positive
 * volume in space, outward normals on closed surfaces). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/mesh.h"

static gm_status alloc_mesh(size_t N, size_t nv, size_t dim, size_t nc, gm_mesh **out,
                            gm_error *err) {
  gm_status st = gm_mesh_create(N, nv, dim, nc, out);
  if (st != GM_OK) return gm_error_set(err, st, "cannot allocate a mesh of %zu cells", nc);
  return GM_OK;
}

static int finite_range(double a, double b) { return isfinite(a) && isfinite(b) && b > a; }

gm_status gm_mesh_rectangle(double x0, double x1, double y0, double y1, size_t nx, size_t ny,
                            gm_diagonal pattern, gm_mesh **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (!finite_range(x0, x1) || !finite_range(y0, y1))
    return gm_error_set(err, GM_EINVAL, "empty or non-finite rectangle [%g,%g]x[%g,%g]", x0, x1,
                        y0, y1);
  if (nx < 1 || ny < 1 || nx > 1u << 20 || ny > 1u << 20)
    return gm_error_set(err, GM_EINVAL, "cell counts %zu x %zu out of range", nx, ny);
  const double hx = (x1 - x0) / (double)nx, hy = (y1 - y0) / (double)ny;
  gm_mesh *m = NULL;
  gm_status st;
  if (pattern != GM_DIAGONAL_ACUTE) {
    if (pattern > GM_DIAGONAL_ACUTE) return gm_error_set(err, GM_EINVAL, "unknown pattern %d", (int)pattern);
    st = alloc_mesh(2, (nx + 1) * (ny + 1), 2, 2 * nx * ny, &m, err);
    if (st != GM_OK) return st;
    for (size_t j = 0; j <= ny; ++j)
      for (size_t i = 0; i <= nx; ++i) {
        m->x[2 * (j * (nx + 1) + i)] = i == nx ? x1 : x0 + (double)i * hx;
        m->x[2 * (j * (nx + 1) + i) + 1] = j == ny ? y1 : y0 + (double)j * hy;
      }
    size_t *c = m->cells;
    for (size_t j = 0; j < ny; ++j)
      for (size_t i = 0; i < nx; ++i) {
        size_t a = j * (nx + 1) + i, b = a + 1, d = a + nx + 1, e = d + 1; /* a b / d e */
        int right = pattern == GM_DIAGONAL_RIGHT ||
                    (pattern == GM_DIAGONAL_ALTERNATE && ((i + j) & 1) == 0);
        if (right) { /* diagonal a-e */
          c[0] = a, c[1] = b, c[2] = e, c[3] = a, c[4] = e, c[5] = d;
        } else { /* diagonal b-d */
          c[0] = a, c[1] = b, c[2] = d, c[3] = b, c[4] = e, c[5] = d;
        }
        c += 6;
      }
    *out = m;
    return GM_OK;
  }
  /* ACUTE: even rows have nx+1 vertices, odd rows nx+2 (ends plus shifted midpoints) */
  size_t nv = 0;
  size_t *row_start = malloc((ny + 2) * sizeof(size_t));
  if (row_start == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  for (size_t j = 0; j <= ny; ++j) {
    row_start[j] = nv;
    nv += (j & 1) ? nx + 2 : nx + 1;
  }
  st = alloc_mesh(2, nv, 2, ny * (2 * nx + 1), &m, err);
  if (st != GM_OK) {
    free(row_start);
    return st;
  }
  for (size_t j = 0; j <= ny; ++j) {
    double y = j == ny ? y1 : y0 + (double)j * hy;
    size_t r = row_start[j];
    if (j & 1) {
      m->x[2 * r] = x0, m->x[2 * r + 1] = y;
      for (size_t i = 0; i < nx; ++i)
        m->x[2 * (r + 1 + i)] = x0 + ((double)i + 0.5) * hx, m->x[2 * (r + 1 + i) + 1] = y;
      m->x[2 * (r + nx + 1)] = x1, m->x[2 * (r + nx + 1) + 1] = y;
    } else {
      for (size_t i = 0; i <= nx; ++i)
        m->x[2 * (r + i)] = i == nx ? x1 : x0 + (double)i * hx, m->x[2 * (r + i) + 1] = y;
    }
  }
  size_t *c = m->cells;
#define TRI(p, q, s) (c[0] = (p), c[1] = (q), c[2] = (s), c += 3)
  for (size_t j = 0; j < ny; ++j) {
    size_t lo = row_start[j], hi = row_start[j + 1];
    if ((j & 1) == 0) { /* bottom even (B_0..B_nx), top odd (T_0..T_{nx+1}) */
      TRI(lo, hi + 1, hi);
      for (size_t i = 0; i < nx; ++i) TRI(lo + i, lo + i + 1, hi + i + 1);
      for (size_t i = 0; i + 1 < nx; ++i) TRI(lo + i + 1, hi + i + 2, hi + i + 1);
      TRI(lo + nx, hi + nx + 1, hi + nx);
    } else { /* bottom odd (O_0..O_{nx+1}), top even (E_0..E_nx) */
      TRI(lo, lo + 1, hi);
      for (size_t i = 0; i < nx; ++i) TRI(lo + i + 1, hi + i + 1, hi + i);
      for (size_t i = 0; i + 1 < nx; ++i) TRI(lo + i + 1, lo + i + 2, hi + i + 1);
      TRI(lo + nx, lo + nx + 1, hi + nx);
    }
  }
#undef TRI
  free(row_start);
  *out = m;
  return GM_OK;
}

/* Make every tetrahedron positively oriented (swap two vertices when needed). */
static void orient_tets(gm_mesh *m) {
  for (size_t t = 0; t < m->n_cells; ++t) {
    size_t *c = m->cells + 4 * t;
    const double *p0 = m->x + 3 * c[0];
    double e[3][3];
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) e[i][j] = m->x[3 * c[i + 1] + j] - p0[j];
    double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                 e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                 e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
    if (det < 0.0) {
      size_t s = c[1];
      c[1] = c[2];
      c[2] = s;
    }
  }
}

gm_status gm_mesh_box(const double lo[3], const double hi[3], size_t nx, size_t ny, size_t nz,
                      gm_box_pattern pattern, gm_mesh **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (lo == NULL || hi == NULL) return gm_error_set(err, GM_EINVAL, "box corners are NULL");
  for (int d = 0; d < 3; ++d)
    if (!finite_range(lo[d], hi[d]))
      return gm_error_set(err, GM_EINVAL, "empty or non-finite box along axis %d", d);
  if (nx < 1 || ny < 1 || nz < 1 || nx > 4096 || ny > 4096 || nz > 4096)
    return gm_error_set(err, GM_EINVAL, "cell counts %zu x %zu x %zu out of range", nx, ny, nz);
  if (pattern != GM_BOX_KUHN && pattern != GM_BOX_FIVE)
    return gm_error_set(err, GM_EINVAL, "unknown box pattern %d", (int)pattern);
  const size_t per = pattern == GM_BOX_KUHN ? 6 : 5;
  const size_t sx = nx + 1, sxy = (nx + 1) * (ny + 1);
  gm_mesh *m = NULL;
  gm_status st = alloc_mesh(3, sxy * (nz + 1), 3, per * nx * ny * nz, &m, err);
  if (st != GM_OK) return st;
  const size_t n[3] = {nx, ny, nz};
  double h[3];
  for (int d = 0; d < 3; ++d) h[d] = (hi[d] - lo[d]) / (double)n[d];
  for (size_t k = 0; k <= nz; ++k)
    for (size_t j = 0; j <= ny; ++j)
      for (size_t i = 0; i <= nx; ++i) {
        const size_t idx[3] = {i, j, k};
        double *x = m->x + 3 * (k * sxy + j * sx + i);
        for (int d = 0; d < 3; ++d) x[d] = idx[d] == n[d] ? hi[d] : lo[d] + (double)idx[d] * h[d];
      }
  static const int perms[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  /* corners of the 5-tetrahedron split, as bit patterns (x = 1, y = 2, z = 4) */
  static const int five[5][4] = {{1, 2, 4, 7}, {0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}};
  size_t *c = m->cells;
  for (size_t k = 0; k < nz; ++k)
    for (size_t j = 0; j < ny; ++j)
      for (size_t i = 0; i < nx; ++i) {
        size_t base = k * sxy + j * sx + i;
        const size_t step[3] = {1, sx, sxy};
        if (pattern == GM_BOX_KUHN) {
          for (int p = 0; p < 6; ++p) {
            size_t v = base;
            c[0] = v;
            for (int q = 0; q < 3; ++q) {
              v += step[perms[p][q]];
              c[q + 1] = v;
            }
            if (p >= 3) { /* odd permutation: negative orientation, swap */
              size_t s = c[1];
              c[1] = c[2];
              c[2] = s;
            }
            c += 4;
          }
        } else {
          int mirror = (int)((i + j + k) & 1);
          for (int t = 0; t < 5; ++t) {
            for (int q = 0; q < 4; ++q) {
              int bits = five[t][q];
              if (mirror) bits ^= 1;
              c[q] = base + (size_t)(bits & 1) * step[0] + (size_t)((bits >> 1) & 1) * step[1] +
                     (size_t)((bits >> 2) & 1) * step[2];
            }
            c += 4;
          }
        }
      }
  if (pattern == GM_BOX_FIVE) orient_tets(m);
  *out = m;
  return GM_OK;
}

/* Triangles between consecutive staggered rings i and i+1 of n vertices each (ring i+1 shifted
 * by +1/2 step when i is even, −1/2 when odd); periodic rings when `closed`. */
static void stagger_strips(size_t *c, size_t n_rings, size_t n, int closed) {
  (void)closed;
  for (size_t i = 0; i < n_rings; ++i) {
    size_t a0 = i * n, b0 = ((i + 1) % (closed == 2 ? n_rings : n_rings + 1)) * n;
    for (size_t j = 0; j < n; ++j) {
      size_t jn = (j + 1) % n;
      size_t mj = (i & 1) == 0 ? j : jn; /* outer vertex between inner j and j+1 */
      size_t mn = (mj + 1) % n;
      c[0] = a0 + j, c[1] = b0 + mj, c[2] = a0 + jn;
      c[3] = a0 + jn, c[4] = b0 + mj, c[5] = b0 + mn;
      c += 6;
    }
  }
}

gm_status gm_mesh_annulus(double r_in, double r_out, size_t n_radial, size_t n_angular,
                          gm_mesh **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (!(r_in > 0.0) || !finite_range(r_in, r_out))
    return gm_error_set(err, GM_EINVAL, "radii must satisfy 0 < r_in < r_out (got %g, %g)", r_in,
                        r_out);
  if (n_radial < 1 || n_angular < 3 || n_radial > 1u << 20 || n_angular > 1u << 20)
    return gm_error_set(err, GM_EINVAL, "need n_radial >= 1 and n_angular >= 3");
  gm_mesh *m = NULL;
  gm_status st = alloc_mesh(2, (n_radial + 1) * n_angular, 2, 2 * n_radial * n_angular, &m, err);
  if (st != GM_OK) return st;
  /* rings staggered by half an angular step: nearly isosceles, acute triangles when the radial
   * step exceeds half the angular one */
  const double dth = 2.0 * GM_PI / (double)n_angular;
  for (size_t i = 0; i <= n_radial; ++i) {
    double r = i == n_radial ? r_out : r_in + (r_out - r_in) * (double)i / (double)n_radial;
    for (size_t j = 0; j < n_angular; ++j) {
      double th = ((double)j + 0.5 * (double)(i & 1)) * dth;
      m->x[2 * (i * n_angular + j)] = r * cos(th);
      m->x[2 * (i * n_angular + j) + 1] = r * sin(th);
    }
  }
  stagger_strips(m->cells, n_radial, n_angular, 1);
  *out = m;
  return GM_OK;
}

static int cmp_pair(const void *pa, const void *pb) {
  const size_t *a = pa, *b = pb;
  if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
  if (a[1] != b[1]) return a[1] < b[1] ? -1 : 1;
  return 0;
}

static size_t edge_rank(const size_t *edges, size_t ne, size_t a, size_t b) {
  size_t key[2] = {a < b ? a : b, a < b ? b : a};
  size_t lo = 0, hi = ne;
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (cmp_pair(edges + 2 * mid, key) < 0)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

/* Make every triangle of a closed surface around the origin outward oriented. */
static void orient_outward(gm_mesh *m) {
  for (size_t t = 0; t < m->n_cells; ++t) {
    size_t *c = m->cells + 3 * t;
    const double *a = m->x + 3 * c[0], *b = m->x + 3 * c[1], *d = m->x + 3 * c[2];
    double det = a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
                 a[2] * (b[0] * d[1] - b[1] * d[0]);
    if (det < 0.0) {
      size_t s = c[1];
      c[1] = c[2];
      c[2] = s;
    }
  }
}

gm_status gm_mesh_icosphere(double radius, size_t subdivisions, gm_mesh **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (!(radius > 0.0) || !isfinite(radius))
    return gm_error_set(err, GM_EINVAL, "radius must be positive and finite");
  if (subdivisions > 9) return gm_error_set(err, GM_EINVAL, "at most 9 subdivisions");
  const double phi = (1.0 + sqrt(5.0)) / 2.0;
  static const int verts[12][3] = {{-1, 1, 0}, {1, 1, 0},  {-1, -1, 0}, {1, -1, 0},
                                   {0, -1, 1}, {0, 1, 1},  {0, -1, -1}, {0, 1, -1},
                                   {1, 0, -1}, {1, 0, 1},  {-1, 0, -1}, {-1, 0, 1}};
  static const size_t faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  size_t nv = 12, nf = 20;
  double *x = malloc(nv * 3 * sizeof(double));
  size_t *f = malloc(nf * 3 * sizeof(size_t));
  if (!x || !f) {
    free(x), free(f);
    return gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  for (size_t v = 0; v < 12; ++v) {
    /* (0, ±1, ±φ) and its cyclic permutations; the table stores ±1 for the φ slot pattern */
    double p[3];
    for (int d = 0; d < 3; ++d) p[d] = (double)verts[v][d];
    /* vertices 0-3: (±1, ±φ, 0); 4-7: (0, ±1, ±φ); 8-11: (±φ, 0, ±1) */
    if (v < 4) p[1] *= phi;
    else if (v < 8) p[2] *= phi;
    else p[0] *= phi;
    double r = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (int d = 0; d < 3; ++d) x[3 * v + d] = p[d] / r;
  }
  memcpy(f, faces, sizeof faces);
  for (size_t s = 0; s < subdivisions; ++s) {
    size_t *edges = malloc(3 * nf * 2 * sizeof(size_t));
    if (edges == NULL) {
      free(x), free(f);
      return gm_error_set(err, GM_ENOMEM, "out of memory");
    }
    for (size_t t = 0; t < nf; ++t)
      for (int i = 0; i < 3; ++i) {
        size_t a = f[3 * t + i], b = f[3 * t + (i + 1) % 3];
        edges[6 * t + 2 * i] = a < b ? a : b;
        edges[6 * t + 2 * i + 1] = a < b ? b : a;
      }
    qsort(edges, 3 * nf, 2 * sizeof(size_t), cmp_pair);
    size_t ne = 0;
    for (size_t e = 0; e < 3 * nf; ++e)
      if (ne == 0 || cmp_pair(edges + 2 * e, edges + 2 * (ne - 1)) != 0) {
        edges[2 * ne] = edges[2 * e];
        edges[2 * ne + 1] = edges[2 * e + 1];
        ++ne;
      }
    double *x2 = realloc(x, (nv + ne) * 3 * sizeof(double));
    size_t *f2 = malloc(4 * nf * 3 * sizeof(size_t));
    if (!x2 || !f2) {
      free(x2 ? x2 : x), free(f2), free(f), free(edges);
      return gm_error_set(err, GM_ENOMEM, "out of memory");
    }
    x = x2;
    for (size_t e = 0; e < ne; ++e) {
      double p[3], r = 0.0;
      for (int d = 0; d < 3; ++d) {
        p[d] = x[3 * edges[2 * e] + d] + x[3 * edges[2 * e + 1] + d];
        r += p[d] * p[d];
      }
      r = sqrt(r);
      for (int d = 0; d < 3; ++d) x[3 * (nv + e) + d] = p[d] / r;
    }
    for (size_t t = 0; t < nf; ++t) {
      size_t a = f[3 * t], b = f[3 * t + 1], c = f[3 * t + 2];
      size_t ab = nv + edge_rank(edges, ne, a, b), bc = nv + edge_rank(edges, ne, b, c),
             ca = nv + edge_rank(edges, ne, c, a);
      size_t *o = f2 + 12 * t;
      o[0] = a, o[1] = ab, o[2] = ca;
      o[3] = ab, o[4] = b, o[5] = bc;
      o[6] = ca, o[7] = bc, o[8] = c;
      o[9] = ab, o[10] = bc, o[11] = ca;
    }
    free(edges);
    free(f);
    f = f2;
    nv += ne;
    nf *= 4;
  }
  gm_mesh *m = NULL;
  gm_status st = alloc_mesh(3, nv, 2, nf, &m, err);
  if (st == GM_OK) {
    for (size_t i = 0; i < 3 * nv; ++i) m->x[i] = radius * x[i];
    memcpy(m->cells, f, nf * 3 * sizeof(size_t));
    orient_outward(m);
    *out = m;
  }
  free(x);
  free(f);
  return st;
}

gm_status gm_mesh_torus(double R, double r, size_t n_major, size_t n_minor, gm_mesh **out,
                        gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (!(r > 0.0) || !finite_range(r, R))
    return gm_error_set(err, GM_EINVAL, "radii must satisfy 0 < r < R (got R = %g, r = %g)", R, r);
  if (n_major < 4 || n_minor < 3 || n_major > 1u << 16 || n_minor > 1u << 16 || (n_major & 1))
    return gm_error_set(err, GM_EINVAL,
                        "need an even n_major >= 4 (staggered rings) and n_minor >= 3");
  gm_mesh *m = NULL;
  gm_status st = alloc_mesh(3, n_major * n_minor, 2, 2 * n_major * n_minor, &m, err);
  if (st != GM_OK) return st;
  for (size_t i = 0; i < n_major; ++i) {
    double th = 2.0 * GM_PI * (double)i / (double)n_major;
    for (size_t j = 0; j < n_minor; ++j) {
      double ph = 2.0 * GM_PI * ((double)j + 0.5 * (double)(i & 1)) / (double)n_minor;
      double *x = m->x + 3 * (i * n_minor + j);
      x[0] = (R + r * cos(ph)) * cos(th);
      x[1] = (R + r * cos(ph)) * sin(th);
      x[2] = r * sin(ph);
    }
  }
  /* rings around the major circle, staggered like the annulus; (θ, φ) is a positive chart for
   * the outward normal */
  stagger_strips(m->cells, n_major, n_minor, 2);
  *out = m;
  return GM_OK;
}
