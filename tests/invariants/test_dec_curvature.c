/* Discrete Gauss–Bonnet (total angle deficit = 2πχ to round-off) on sphere, torus and a disk,
 * and the Levi-Civita holonomy around each vertex equal to its angle deficit (seed 000 §4.3). */
#include "dec_util.h"

static void check_gauss_bonnet(const gm_mesh *m, long chi) {
  gm_complex *cx = test_complex(m);
  cr_assert_eq(gm_complex_euler_characteristic(cx), chi);
  double *eps = malloc(m->n_vertices * sizeof(double));
  cr_assert_eq(gm_dec_angle_deficit(cx, eps), GM_OK);
  double total = 0.0;
  for (size_t v = 0; v < m->n_vertices; ++v) total += eps[v];
  cr_expect(fabs(total - 2 * TEST_PI * (double)chi) <= 1e-12 * (double)m->n_vertices,
            "Σε = %.17g, 2πχ = %.17g", total, 2 * TEST_PI * (double)chi);
  /* holonomy = deficit (mod 2π) at every interior vertex */
  const unsigned char *b = gm_complex_boundary_mask(cx, 0);
  double worst = 0.0;
  for (size_t v = 0; v < m->n_vertices; ++v) {
    if (b[v]) continue;
    double a;
    cr_assert_eq(gm_dec_holonomy(cx, v, &a), GM_OK);
    double d = remainder(a - eps[v], 2 * TEST_PI);
    worst = fmax(worst, fabs(d));
  }
  cr_expect_leq(worst, 1e-12, "holonomy differs from the deficit by %.3g", worst);
  free(eps);
  gm_complex_free(cx);
}

Test(dec_curvature, gauss_bonnet_and_holonomy_on_sphere) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_icosphere(1.7, 3, &m, NULL), GM_OK);
  check_gauss_bonnet(m, 2);
  gm_mesh_free(m);
}

Test(dec_curvature, gauss_bonnet_and_holonomy_on_torus) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_torus(3.0, 1.0, 40, 17, &m, NULL), GM_OK);
  check_gauss_bonnet(m, 0);
  gm_mesh_free(m);
}

Test(dec_curvature, gauss_bonnet_with_boundary_turning) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_annulus(0.3, 1.0, 5, 30, &m, NULL), GM_OK);
  check_gauss_bonnet(m, 0);
  gm_mesh_free(m);
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, 4, 4, GM_DIAGONAL_RIGHT, &m, NULL), GM_OK);
  check_gauss_bonnet(m, 1);
  gm_mesh_free(m);
}
