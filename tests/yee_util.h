/* Helpers shared by the Yee solver tests. */
#ifndef GM_TEST_YEE_UTIL_H
#define GM_TEST_YEE_UTIL_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/geomint.h"

#define YEE_TEST_PI 3.14159265358979323846

/* A deterministic generator (splitmix64) for random initial fields in [−½, ½). */
typedef struct yee_rng {
  uint64_t state;
} yee_rng;

static inline double yee_rng_fill(void *ctx, const double x[3]) {
  (void)x;
  yee_rng *r = ctx;
  uint64_t z = (r->state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return (double)(z >> 11) / 9007199254740992.0 - 0.5;
}

/* A solver on an nx×ny×nz grid of cell size h, the same boundary on every face. */
static inline gm_yee *yee_make(gm_yee_dim dim, size_t nx, size_t ny, size_t nz, double h,
                               gm_yee_boundary_kind bc, double courant, int threads) {
  gm_yee_grid g = {dim, {nx, ny, nz}, {h, h, h}, {0, 0, 0}};
  gm_yee_options o = gm_yee_defaults();
  o.courant = courant;
  o.n_threads = threads;
  for (int f = 0; f < 6; ++f) o.boundary[f].kind = bc;
  gm_yee *s = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_create(&g, NULL, &o, &s, &err), GM_OK, "%s", err.message);
  return s;
}

/* Random values on every component the grid has (part 0), from seed. */
static inline void yee_randomize(gm_yee *s, uint64_t seed, int e_only) {
  yee_rng r = {seed};
  for (int c = 0; c < (e_only ? 3 : GM_YEE_N_COMPONENTS); ++c) {
    gm_yee_layout L;
    gm_yee_get_layout(s, &L);
    if (!gm_yee_dim_has(L.dim, (gm_yee_component)c)) continue;
    cr_assert_eq(gm_yee_set_field_fn(s, (gm_yee_component)c, 0, yee_rng_fill, &r), GM_OK);
  }
}

/* Frequency of the Yee mode with wave numbers k (per axis) on cell sizes h with step dt
 * (Taflove & Hagness eq. 4.12): (sin(ωΔt/2)/Δt)² = Σ_a (sin(k_a h_a/2)/h_a)², c = 1. */
static inline double yee_discrete_frequency(size_t axes, const double *k, const double *h,
                                            double dt) {
  double s = 0.0;
  for (size_t a = 0; a < axes; ++a) {
    const double v = sin(0.5 * k[a] * h[a]) / h[a];
    s += v * v;
  }
  return 2.0 * asin(dt * sqrt(s)) / dt / (2.0 * YEE_TEST_PI);
}

#endif
