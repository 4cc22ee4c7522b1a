/* Helpers shared by the DEC and mesh tests: build meshes, complexes and geometries or fail. */
#ifndef GM_TEST_DEC_UTIL_H
#define GM_TEST_DEC_UTIL_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "geomint/dec.h"
#include "geomint/mesh.h"
#include "geomint/sparse.h"

#define TEST_PI 3.14159265358979323846

static inline gm_complex *test_complex(const gm_mesh *m) {
  gm_complex *cx = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_complex(m, &cx, &err), GM_OK, "complex: %s", err.message);
  return cx;
}

static inline gm_geometry *test_geometry(const gm_complex *cx) {
  gm_geometry *g = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_geometry_create(cx, NULL, &g, &err), GM_OK, "geometry: %s", err.message);
  return g;
}

/* Deterministic pseudo-random numbers in [-1, 1) (splitmix64). */
static inline double test_random(uint64_t *state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (double)(z >> 11) * 0x1p-52 - 1.0;
}

static inline void test_random_fill(size_t n, double *x, uint64_t seed) {
  uint64_t s = seed;
  for (size_t i = 0; i < n; ++i) x[i] = test_random(&s);
}

/* Move interior vertices of a planar mesh by up to `amount` times the spacing h. */
static inline void test_jiggle(gm_mesh *m, const gm_complex *cx, double h, double amount,
                               uint64_t seed) {
  const unsigned char *bnd = gm_complex_boundary_mask(cx, 0);
  uint64_t s = seed;
  for (size_t v = 0; v < m->n_vertices; ++v)
    for (size_t d = 0; d < m->N; ++d) {
      double r = test_random(&s);
      if (!bnd[v]) m->x[v * m->N + d] += amount * h * r;
    }
}

static inline double test_max_abs(size_t n, const double *x) {
  double m = 0.0;
  for (size_t i = 0; i < n; ++i)
    if (fabs(x[i]) > m) m = fabs(x[i]);
  return m;
}

static inline double test_dot(size_t n, const double *a, const double *b) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

/* Weighted inner product Σ w_i a_i b_i. */
static inline double test_wdot(size_t n, const double *w, const double *a, const double *b) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += w[i] * a[i] * b[i];
  return s;
}

#endif
