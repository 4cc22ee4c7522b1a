/* Poisson problems with manufactured solutions converge at second order on structured 2-D and
 * 3-D meshes (rates fitted by least squares of log error against log h, printed). */
#include <stdio.h>
#include <string.h>

#include "dec_util.h"

static double fitted_rate(size_t n, const double *h, const double *e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < n; ++i) {
    double x = log(h[i]), y = log(e[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

static void run_2d(gm_diagonal pattern, const char *name) {
  const size_t sizes[] = {8, 16, 32, 64};
  double h[4], emax[4], el2[4];
  for (size_t i = 0; i < 4; ++i) {
    gm_mesh *m = NULL;
    size_t ny = pattern == GM_DIAGONAL_ACUTE ? (size_t)((double)sizes[i] * 1.1547) : sizes[i];
    cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, sizes[i], ny, pattern, &m, NULL), GM_OK);
    gm_poisson_report r;
    gm_error err = {{0}};
    cr_assert_eq(gm_mesh_poisson(m, &r, NULL, &err), GM_OK, "%s", err.message);
    h[i] = r.h, emax[i] = r.error_max, el2[i] = r.error_l2;
    printf("poisson 2d %-10s h = %.4f  max error = %.3e  L2 error = %.3e\n", name, h[i], emax[i], el2[i]);
    gm_mesh_free(m);
  }
  double rmax = fitted_rate(4, h, emax), rl2 = fitted_rate(4, h, el2);
  printf("poisson 2d %-10s rates: max %.3f  L2 %.3f\n", name, rmax, rl2);
  cr_expect(rmax > 1.85 && rmax < 2.3, "%s: max-error rate %.3f", name, rmax);
  cr_expect(rl2 > 1.85 && rl2 < 2.3, "%s: L2 rate %.3f", name, rl2);
}

Test(dec_poisson, second_order_on_right_triangles) { run_2d(GM_DIAGONAL_RIGHT, "right"); }
Test(dec_poisson, second_order_on_alternating_diagonals) { run_2d(GM_DIAGONAL_ALTERNATE, "alternate"); }
Test(dec_poisson, second_order_on_acute_triangles) { run_2d(GM_DIAGONAL_ACUTE, "acute"); }

Test(dec_poisson, second_order_on_kuhn_tetrahedra) {
  const size_t sizes[] = {4, 8, 16};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  double h[3], emax[3], el2[3];
  for (size_t i = 0; i < 3; ++i) {
    gm_mesh *m = NULL;
    cr_assert_eq(gm_mesh_box(lo, hi, sizes[i], sizes[i], sizes[i], GM_BOX_KUHN, &m, NULL), GM_OK);
    gm_poisson_report r;
    gm_error err = {{0}};
    cr_assert_eq(gm_mesh_poisson(m, &r, NULL, &err), GM_OK, "%s", err.message);
    h[i] = r.h, emax[i] = r.error_max, el2[i] = r.error_l2;
    printf("poisson 3d kuhn h = %.4f  max error = %.3e  L2 error = %.3e\n", h[i], emax[i], el2[i]);
    gm_mesh_free(m);
  }
  double rmax = fitted_rate(3, h, emax), rl2 = fitted_rate(3, h, el2);
  printf("poisson 3d kuhn rates: max %.3f  L2 %.3f\n", rmax, rl2);
  cr_expect(rmax > 1.85 && rmax < 2.3, "max-error rate %.3f", rmax);
  cr_expect(rl2 > 1.85 && rl2 < 2.3, "L2 rate %.3f", rl2);
}

Test(dec_poisson, surface_meshes_are_rejected_with_a_reason) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_icosphere(1.0, 1, &m, NULL), GM_OK);
  gm_poisson_report r;
  gm_error err = {{0}};
  cr_expect_eq(gm_mesh_poisson(m, &r, NULL, &err), GM_EUNSUPPORTED);
  cr_expect(strstr(err.message, "surface") != NULL, "%s", err.message);
  gm_mesh_free(m);
}
