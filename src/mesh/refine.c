/* Regular (red) refinement of triangle and tetrahedral meshes.
 *
 * Triangles: each triangle is cut into four by its edge midpoints (the three corner triangles
 * are copies of the parent scaled by 1/2, the middle one is the parent rotated by π and scaled).
 * Tetrahedra: Bey's rule (J. Bey, "Tetrahedral grid refinement", Computing 55 (1995) 355–378,
 * §2, Algorithm "RegularRefinement"): with x_ij the midpoint of edge (x_i, x_j) of the cell
 * (x_0, x_1, x_2, x_3), the children, in this vertex order, are the four corner tetrahedra
 *   (x0, x01, x02, x03), (x01, x1, x12, x13), (x02, x12, x2, x23), (x03, x13, x23, x3)
 * and the four tetrahedra of the inner octahedron cut along the diagonal x02–x13:
 *   (x01, x02, x03, x13), (x01, x02, x12, x13), (x02, x03, x13, x23), (x02, x12, x13, x23).
 * Bey proves that repeating the rule with the children in this vertex order produces at most
 * three congruence classes per initial cell (so the meshes do not degenerate). The rule depends
 * on the vertex order; before refining, each input cell is relabelled by at most one
 * transposition (of x1,x2 or of x2,x3) when that makes its diagonal x02–x13 strictly shorter
 * (the shortest-diagonal choice of the octahedron; ties keep the given order, then the x1,x2
 * swap). On a Kuhn cube mesh whose odd tetrahedra were stored with two vertices swapped for a
 * positive orientation, this restores the path order, and every level is again a Kuhn mesh.
 *
 * Numbering (gm_refinement in geomint/multigrid.h relies on it): fine vertex v < V is coarse
 * vertex v, fine vertex V + e is the midpoint of coarse edge e (edges numbered as in the
 * complex, gm_complex_simplices(cx, 1)); the children of coarse cell c are fine cells
 * 2^n c .. 2^n c + 2^n − 1 and inherit its tag. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/internal.h"
#include "geomint/mesh.h"

static size_t physical_memory_bytes(void) {
  long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || size <= 0) return (size_t)8 << 30;
  return (size_t)pages * (size_t)size;
}

/* Bytes of the fine mesh: coordinates, cells and tags (the only allocation of the refinement
 * besides the coarse complex, which exists already when this is called). */
static double fine_mesh_bytes(size_t N, size_t dim, double nv, double ne, double nc) {
  const double cells = nc * (double)((size_t)1 << dim);
  return (nv + ne) * (double)N * 8.0 + cells * ((double)(dim + 1) * 8.0 + (double)sizeof(int));
}

gm_status gm_mesh_refine_estimate(const gm_mesh *coarse, size_t levels, double *bytes,
                                  gm_error *err) {
  if (coarse == NULL || bytes == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  if (coarse->dim != 2 && coarse->dim != 3)
    return gm_error_set(err, GM_EUNSUPPORTED,
                        "red refinement is for triangles and tetrahedra, not %zu-cells",
                        coarse->dim);
  /* Edge and face counts from the cells: every edge of a manifold mesh is counted by the cells
   * around it, so use the upper bounds E <= C(n+1,2) C and F <= (n+1) C, then the exact
   * recurrences of red refinement for the later levels: V' = V + E, E' = 2E + 3F (+ T in 3-D),
   * F' = 4F + 8T, C' = 2^n C. */
  const size_t n = coarse->dim;
  double nv = (double)coarse->n_vertices, nc = (double)coarse->n_cells;
  double ne = nc * (n == 2 ? 3.0 : 6.0), nf = nc * (n == 2 ? 1.0 : 4.0);
  double total = 0.0;
  for (size_t l = 0; l < levels; ++l) {
    total = fine_mesh_bytes(coarse->N, n, nv, ne, nc);
    double nv2 = nv + ne;
    double ne2 = n == 2 ? 2 * ne + 3 * nc : 2 * ne + 3 * nf + nc;
    double nf2 = n == 2 ? 4 * nc : 4 * nf + 8 * nc;
    nv = nv2, ne = ne2, nf = nf2, nc *= (double)((size_t)1 << n);
  }
  *bytes = total;
  return GM_OK;
}

/* |x_p + x_q − x_r − x_s|²: four times the squared length of the diagonal m(p,q)–m(r,s). */
static double diagonal2(const double *x, size_t N, const size_t *v, int p, int q, int r, int s) {
  double sum = 0.0;
  for (size_t j = 0; j < N; ++j) {
    double d = x[v[p] * N + j] + x[v[q] * N + j] - x[v[r] * N + j] - x[v[s] * N + j];
    sum += d * d;
  }
  return sum;
}

gm_status gm_mesh_refine(const gm_mesh *coarse, size_t max_bytes, gm_mesh **fine, gm_error *err) {
  if (coarse == NULL || fine == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  *fine = NULL;
  const size_t n = coarse->dim, N = coarse->N;
  double need = 0.0;
  gm_status st = gm_mesh_refine_estimate(coarse, 1, &need, err);
  if (st != GM_OK) return st;
  if (max_bytes == 0) max_bytes = physical_memory_bytes();
  if (need > (double)max_bytes)
    return gm_error_set(err, GM_ENOMEM,
                        "refining %zu cells into %.0f needs about %.3g bytes for the fine mesh, "
                        "more than the limit of %zu bytes",
                        coarse->n_cells, (double)coarse->n_cells * (double)((size_t)1 << n), need,
                        max_bytes);
  gm_complex *cx = NULL;
  st = gm_mesh_complex(coarse, &cx, err);
  if (st != GM_OK) return st;
  const size_t nv = coarse->n_vertices, ne = gm_complex_count(cx, 1), nc = coarse->n_cells;
  const size_t per = (size_t)1 << n;
  gm_mesh *m = NULL;
  st = gm_mesh_create(N, nv + ne, n, nc * per, &m);
  if (st != GM_OK) {
    gm_complex_free(cx);
    return gm_error_set(err, st, "cannot allocate the refined mesh (%zu vertices, %zu cells)",
                        nv + ne, nc * per);
  }
  memcpy(m->x, coarse->x, nv * N * sizeof(double));
  const size_t *edges = gm_complex_simplices(cx, 1);
  for (size_t e = 0; e < ne; ++e)
    for (size_t j = 0; j < N; ++j)
      m->x[(nv + e) * N + j] = 0.5 * (coarse->x[edges[2 * e] * N + j] +
                                      coarse->x[edges[2 * e + 1] * N + j]);
  for (size_t c = 0; c < nc; ++c) {
    size_t v[4];
    memcpy(v, coarse->cells + c * (n + 1), (n + 1) * sizeof(size_t));
    if (n == 3) {
      double d1 = diagonal2(coarse->x, N, v, 0, 2, 1, 3);
      double d2 = diagonal2(coarse->x, N, v, 0, 1, 2, 3); /* after swapping x1, x2 */
      double d3 = diagonal2(coarse->x, N, v, 0, 3, 1, 2); /* after swapping x2, x3 */
      if (d2 < d1 && d2 <= d3) {
        size_t s = v[1];
        v[1] = v[2], v[2] = s;
      } else if (d3 < d1 && d3 < d2) {
        size_t s = v[2];
        v[2] = v[3], v[3] = s;
      }
    }
    /* mid[i][j]: fine index of the midpoint of (x_i, x_j), mid[i][i] = x_i. The cell's edges
     * come from gm_complex_local_faces (lexicographic pairs of its ascending vertices). */
    static const int pair_index[2][4][4] = {{{0, 0, 1, 0}, {0, 0, 2, 0}, {1, 2, 0, 0}, {0}},
                                            {{0, 0, 1, 2}, {0, 0, 3, 4}, {1, 3, 0, 5},
                                             {2, 4, 5, 0}}};
    size_t local_edges[6], pos[4] = {0, 0, 0, 0};
    gm_complex_local_faces(cx, c, 1, local_edges);
    const size_t *asc = gm_complex_simplices(cx, n) + c * (n + 1);
    size_t mid[4][4];
    for (size_t i = 0; i <= n; ++i) {
      mid[i][i] = v[i];
      for (size_t q = 0; q <= n; ++q)
        if (asc[q] == v[i]) pos[i] = q;
    }
    for (size_t i = 0; i <= n; ++i)
      for (size_t j = i + 1; j <= n; ++j)
        mid[i][j] = mid[j][i] = nv + local_edges[pair_index[n - 2][pos[i]][pos[j]]];
    size_t *out = m->cells + c * per * (n + 1);
    if (n == 2) {
      static const int tri[4][3][2] = {{{0, 0}, {0, 1}, {0, 2}},
                                       {{0, 1}, {1, 1}, {1, 2}},
                                       {{0, 2}, {1, 2}, {2, 2}},
                                       {{0, 1}, {1, 2}, {0, 2}}};
      for (int t = 0; t < 4; ++t)
        for (int q = 0; q < 3; ++q) out[3 * t + q] = mid[tri[t][q][0]][tri[t][q][1]];
    } else {
      static const int tet[8][4][2] = {{{0, 0}, {0, 1}, {0, 2}, {0, 3}},
                                       {{0, 1}, {1, 1}, {1, 2}, {1, 3}},
                                       {{0, 2}, {1, 2}, {2, 2}, {2, 3}},
                                       {{0, 3}, {1, 3}, {2, 3}, {3, 3}},
                                       {{0, 1}, {0, 2}, {0, 3}, {1, 3}},
                                       {{0, 1}, {0, 2}, {1, 2}, {1, 3}},
                                       {{0, 2}, {0, 3}, {1, 3}, {2, 3}},
                                       {{0, 2}, {1, 2}, {1, 3}, {2, 3}}};
      for (int t = 0; t < 8; ++t)
        for (int q = 0; q < 4; ++q) out[4 * t + q] = mid[tet[t][q][0]][tet[t][q][1]];
    }
    for (size_t t = 0; t < per; ++t) m->cell_tags[c * per + t] = coarse->cell_tags[c];
  }
  gm_complex_free(cx);
  *fine = m;
  return GM_OK;
}
