/* gauss-prk's Newton solve is condensed to the node values (gauss_prk.c): its matrix storage is
 * O(N) — the same bytes per point at every N — and small (sine-Gordon: 2 coupled components,
 * band 7 below + 7 fill above + border 4 per condensed unknown, 2 condensed unknowns per point:
 * 304 bytes per point, against 11 520 for the interleaved band of the full (Z, Y) system it
 * replaced). Measured peak RSS at N = 10⁶ in docs/pde.md. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "geomint/pde.h"
#include "pde/internal.h"

static gm_pde *make(size_t n) {
  gm_pde_equation eq = gm_pde_sine_gordon();
  gm_pde_grid g = {n, 40.0 / (double)n, -20.0, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = 0.05;
  const gm_pde_scheme *sc = NULL;
  cr_assert_eq(gm_pde_scheme_find("gauss-prk", &sc), GM_OK);
  double *s0 = calloc(3 * n, sizeof *s0);
  for (size_t i = 0; i < n; i++) {
    double x = gm_pde_point_x(sc, &g, i);
    s0[3 * i + 1] = 4.0 * sqrt(0.75) / cosh(sqrt(0.75) * x); /* breather at t = 0 */
  }
  gm_pde *p = NULL;
  gm_error err = {0};
  cr_assert_eq(gm_pde_create(&g, &eq, sc, &o, s0, &p, &err), GM_OK, "%s", err.message);
  free(s0);
  return p;
}

static double matrix_bytes_per_point(const gm_pde *p) {
  const gm_bband *b = &p->gp_band;
  return (double)(b->n * (b->w + b->nb) * sizeof(double)) / (double)p->n;
}

Test(gauss_memory, condensed_band_is_linear_in_n) {
  gm_pde *a = make(200), *b = make(4000);
  double pa = matrix_bytes_per_point(a), pb = matrix_bytes_per_point(b);
  cr_log_info("bytes per point: %g (n = 200), %g (n = 4000)", pa, pb);
  cr_expect_eq(pa, pb);
  cr_expect_eq(pa, 304.0);
  /* and it still solves: 10 steps of the breather stay finite and the state moves */
  gm_error err = {0};
  cr_expect_eq(gm_pde_advance(a, 10, &err), GM_OK, "%s", err.message);
  gm_pde_free(a);
  gm_pde_free(b);
}
