/* gauss-prk's Newton solve is condensed to the node values (gauss_prk.c) and eliminated with its
 * right-hand side as the cells arrive (band_border.c): only U is kept, packed to the block
 * profile, plus the wrap-around border and a window of rows. Its storage is O(N), the same bytes
 * per point at every N (the window is constant):
 *   sine-Gordon (d_f = 2, 2 condensed unknowns per point, block 4, kl = 7): U 26 doubles per
 *   4 rows + border 4 per row: 168 bytes per point (issue 28 first cut, L and U kept: 304 + 8
 *   of pivots; the interleaved band of the full (Z, Y) system before it: 11 520);
 *   NLS (d_f = 4, 4 per point, block 8, kl = 15): U 100 per 8 rows + border 8: 656 bytes per
 *   point (first cut: 1248 + 16 of pivots).
 * Measured peak RSS at N = 10⁶ in docs/pde.md. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "geomint/pde.h"
#include "pde/internal.h"

static gm_pde *make(int nls, size_t n) {
  gm_pde_equation eq = nls ? gm_pde_nls() : gm_pde_sine_gordon();
  gm_pde_grid g = {n, 40.0 / (double)n, -20.0, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = nls ? 0.01 : 0.05;
  const gm_pde_scheme *sc = NULL;
  cr_assert_eq(gm_pde_scheme_find("gauss-prk", &sc), GM_OK);
  size_t d = eq.dim;
  double *s0 = calloc(d * n, sizeof *s0);
  for (size_t i = 0; i < n; i++) {
    double x = gm_pde_point_x(sc, &g, i);
    if (nls) { /* soliton ψ = sech x at rest: (Re ψ, Im ψ, ∂x Re ψ, ∂x Im ψ) */
      s0[d * i] = 1.0 / cosh(x);
      s0[d * i + 2] = -tanh(x) / cosh(x);
    } else {
      s0[d * i + 1] = 4.0 * sqrt(0.75) / cosh(sqrt(0.75) * x); /* breather at t = 0 */
    }
  }
  gm_pde *p = NULL;
  gm_error err = {0};
  cr_assert_eq(gm_pde_create(&g, &eq, sc, &o, s0, &p, &err), GM_OK, "%s", err.message);
  free(s0);
  return p;
}

/* the Newton matrix per point, from two sizes (the window is the same at both) */
static double matrix_bytes_per_point(int nls) {
  gm_pde *a = make(nls, 200), *b = make(nls, 4000);
  double per = (double)(gm_bband_bytes(&b->gp_band) - gm_bband_bytes(&a->gp_band)) / 3800.0;
  double window = (double)gm_bband_bytes(&a->gp_band) - 200.0 * per;
  cr_log_info("%s: %g bytes per point + a window of %g bytes", nls ? "nls" : "sine-gordon", per,
              window);
  cr_expect_lt(window, 8192.0); /* 1824 (sine-Gordon), 7488 (NLS): 3 blocks of full rows */
  /* and it still solves: 10 steps stay finite */
  gm_error err = {0};
  cr_expect_eq(gm_pde_advance(a, 10, &err), GM_OK, "%s", err.message);
  for (size_t k = 0; k < a->nu; k++) cr_assert(isfinite(a->s[k]));
  gm_pde_free(a);
  gm_pde_free(b);
  return per;
}

Test(gauss_memory, condensed_band_sine_gordon) { cr_expect_eq(matrix_bytes_per_point(0), 168.0); }

Test(gauss_memory, condensed_band_nls) { cr_expect_eq(matrix_bytes_per_point(1), 656.0); }
