/* Helpers shared by the mesh Maxwell tests: meshes, geometry, deterministic random fields. */
#ifndef GM_TEST_MESH_MAXWELL_UTIL_H
#define GM_TEST_MESH_MAXWELL_UTIL_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/geomint.h"

typedef struct mm_fixture {
  gm_mesh *mesh;
  gm_complex *cx;
  gm_geometry *g;
} mm_fixture;

static inline double mm_rand(uint64_t *z) {
  uint64_t x = (*z += 0x9e3779b97f4a7c15ull);
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  x ^= x >> 31;
  return (double)(x >> 11) / 9007199254740992.0 - 0.5;
}

static inline void mm_fixture_finish(mm_fixture *f) {
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_complex(f->mesh, &f->cx, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_geometry_create(f->cx, NULL, &f->g, &err), GM_OK, "%s", err.message);
}

/* [0,1]×[0,ly] with the acute pattern (well-centred inside): nx columns, rows chosen so the
 * triangles are near equilateral. warp != 0: the x and y partitions are drawn at random (the
 * vertices are moved by a random monotone piecewise-linear map, spacings in [1−warp, 1+warp]). */
static inline mm_fixture mm_rect(size_t nx, double ly, double warp, uint64_t seed) {
  mm_fixture f = {0};
  gm_error err = {{0}};
  const size_t ny = (size_t)lround(ly * 2.0 * (double)nx / sqrt(3.0));
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, ly, nx, ny, GM_DIAGONAL_ACUTE, &f.mesh, &err), GM_OK,
               "%s", err.message);
  if (warp > 0.0) {
    const size_t nb[2] = {2 * nx, ny};
    const double len[2] = {1.0, ly};
    for (int a = 0; a < 2; ++a) { /* random partition of [0, len] into nb pieces */
      double *cut = malloc((nb[a] + 1) * sizeof(double));
      cut[0] = 0.0;
      for (size_t i = 0; i < nb[a]; ++i) cut[i + 1] = cut[i] + 1.0 + 2.0 * warp * mm_rand(&seed);
      for (size_t i = 0; i <= nb[a]; ++i) cut[i] *= len[a] / cut[nb[a]];
      for (size_t v = 0; v < f.mesh->n_vertices; ++v) {
        const double u = f.mesh->x[2 * v + a] / len[a] * (double)nb[a];
        size_t i = (size_t)floor(u);
        if (i >= nb[a]) i = nb[a] - 1;
        f.mesh->x[2 * v + a] = cut[i] + (u - (double)i) * (cut[i + 1] - cut[i]);
      }
      free(cut);
    }
  }
  mm_fixture_finish(&f);
  return f;
}

/* Box [0,1]×[0,0.8]×[0,0.6] with Kuhn tetrahedra, nx cells along x. */
static inline mm_fixture mm_box(size_t nx) {
  mm_fixture f = {0};
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 0.8, 0.6};
  cr_assert_eq(gm_mesh_box(lo, hi, nx, (size_t)lround(0.8 * (double)nx),
                           (size_t)lround(0.6 * (double)nx), GM_BOX_KUHN, &f.mesh, &err),
               GM_OK, "%s", err.message);
  mm_fixture_finish(&f);
  return f;
}

/* The well-centred body-centred cubic tetrahedra of [0,1]³ with n cubes per side; jitter > 0
 * moves every vertex by up to jitter·h/2 per coordinate (seeded), so the stars and local limits
 * differ from face to face (the mesh stays well-centred for small jitter: create checks it). */
static inline mm_fixture mm_bcc_jittered(size_t n, double jitter, uint64_t seed) {
  mm_fixture f = {0};
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_bcc(lo, hi, n, n, n, 0, &f.mesh, &err), GM_OK, "%s", err.message);
  for (size_t i = 0; jitter > 0.0 && i < 3 * f.mesh->n_vertices; ++i)
    f.mesh->x[i] += jitter / (double)n * mm_rand(&seed);
  mm_fixture_finish(&f);
  return f;
}

static inline mm_fixture mm_bcc(size_t n) { return mm_bcc_jittered(n, 0.0, 0); }

static inline void mm_fixture_free(mm_fixture *f) {
  gm_geometry_free(f->g);
  gm_complex_free(f->cx);
  gm_mesh_free(f->mesh);
}

/* The interior edge whose midpoint is nearest to x. */
static inline size_t mm_nearest_interior_edge(const mm_fixture *f, const double *x) {
  const size_t n = gm_complex_dim(f->cx), ne = gm_complex_count(f->cx, 1);
  const double *X = gm_complex_coordinates(f->cx);
  const size_t *ev = gm_complex_simplices(f->cx, 1);
  const unsigned char *bm = gm_complex_boundary_mask(f->cx, 1);
  size_t best = 0;
  double bd = INFINITY;
  for (size_t e = 0; e < ne; ++e) {
    if (bm[e]) continue;
    double r2 = 0.0;
    for (size_t i = 0; i < n; ++i) {
      const double m = 0.5 * (X[ev[2 * e] * n + i] + X[ev[2 * e + 1] * n + i]) - x[i];
      r2 += m * m;
    }
    if (r2 < bd) { bd = r2; best = e; }
  }
  return best;
}

/* Random E on the edges and a divergence-free B = d₁A from a random A. */
static inline void mm_random_fields(const mm_fixture *f, uint64_t seed, double *E, double *B) {
  const size_t ne = gm_complex_count(f->cx, 1);
  double *A = malloc(ne * sizeof(double));
  for (size_t e = 0; e < ne; ++e) { E[e] = mm_rand(&seed); A[e] = mm_rand(&seed); }
  gm_csr_matvec(gm_complex_d(f->cx, 1), 1.0, A, 0.0, B);
  free(A);
}
#endif
