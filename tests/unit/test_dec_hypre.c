/* hypre's algebraic multigrid on DEC systems: BoomerAMG-CG for the 0-form Poisson problem and
 * AMS-CG for the 1-form curl–curl problem (curl curl E + E = f, E × n = 0, known E on a cube)
 * agree with CHOLMOD to the requested tolerance; built without hypre, the calls say so. */
#include <stdio.h>
#include <string.h>

#include "dec_util.h"
#include "geomint/multigrid.h"

static gm_mesh *bcc_cube(size_t n) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_bcc(lo, hi, n, n, n, 0, &m, &err), GM_OK, "%s", err.message);
  return m;
}

/* BCC 2×2×2 refined 3 times (24 576 tets, 3 375 unknowns). Measured: 8 iterations, relative
 * residual 4.3e-11, max |u_amg − u_chol| 4.3e-11 (the solution's scale is 1). */
Test(hypre, boomeramg_poisson_agrees_with_cholmod) {
  gm_mesh *m = bcc_cube(2);
  gm_error err = {{0}};
  gm_poisson_options o = gm_poisson_defaults();
  o.levels = 3;
  o.solver = GM_POISSON_HYPRE;
  gm_poisson_report r, rc;
  double *u = NULL, *v = NULL;
  gm_status st = gm_mesh_poisson_solve(m, &o, &r, &u, &err);
  if (!gm_hypre_available()) {
    cr_expect_eq(st, GM_EUNSUPPORTED);
    cr_expect_not_null(strstr(err.message, "libhypre-dev"), "%s", err.message);
    gm_mesh_free(m);
    return;
  }
  cr_assert_eq(st, GM_OK, "%s", err.message);
  o.solver = GM_POISSON_CHOLMOD;
  cr_assert_eq(gm_mesh_poisson_solve(m, &o, &rc, &v, &err), GM_OK, "%s", err.message);
  double d = 0.0;
  for (size_t i = 0; i < r.n_vertices; ++i) d = fmax(d, fabs(u[i] - v[i]));
  printf("BoomerAMG-CG: %zu unknowns, %zu iterations, relative residual %.2e, max |u - u_chol| "
         "%.2e\n",
         r.n_unknowns, r.iterations, r.relative_residual, d);
  cr_expect_leq(r.relative_residual, 1e-10);
  cr_expect_leq(d, 2e-10, "%.3g", d);
  cr_expect_leq(r.iterations, 12, "%zu", r.iterations);
  free(u), free(v);
  gm_mesh_free(m);
}

/* Curl–curl on the BCC meshes 4³ and 8³ of the unit cube (576 and 5 376 tets; the domain is the
 * cube minus the boundary pyramids, so the boundary edges carry E's exact integrals). Measured:
 * AMS-CG to 1e-10 in 15 and 20 iterations; max |e_ams − e_chol| / max |e| 8.0e-11, 1.7e-10; the
 * error against the exact integrals (per unit length) 2.68e-2 → 7.50e-3 (second order). */
Test(hypre, ams_curlcurl_agrees_with_cholmod) {
  double err_prev = 0.0;
  for (size_t n = 4; n <= 8; n *= 2) {
    gm_mesh *m = bcc_cube(n);
    gm_error err = {{0}};
    gm_curlcurl_report rc, ra;
    double *ec = NULL, *ea = NULL;
    cr_assert_eq(gm_mesh_curlcurl_solve(m, GM_CURLCURL_CHOLMOD, 1e-10, &rc, &ec, &err), GM_OK,
                 "%s", err.message);
    gm_status st = gm_mesh_curlcurl_solve(m, GM_CURLCURL_HYPRE, 1e-10, &ra, &ea, &err);
    if (!gm_hypre_available()) {
      cr_expect_eq(st, GM_EUNSUPPORTED, "%s", err.message);
      free(ec);
      gm_mesh_free(m);
      continue;
    }
    cr_assert_eq(st, GM_OK, "%s", err.message);
    double d = 0.0, scale = 0.0;
    for (size_t e = 0; e < rc.n_edges; ++e) d = fmax(d, fabs(ea[e] - ec[e])), scale = fmax(scale, fabs(ec[e]));
    printf("curl-curl BCC %zu^3: %zu tets, %zu edge unknowns, CHOLMOD error %.3e (h %.3f), AMS "
           "%zu iterations, relative residual %.2e, max |e_ams - e_chol| / max |e| = %.2e\n",
           n, rc.n_cells, rc.n_unknowns, rc.error_max, rc.h, ra.iterations, ra.relative_residual,
           d / scale);
    cr_expect_leq(d / scale, 1e-9, "%.3g", d / scale);
    cr_expect_leq(ra.relative_residual, 1e-10);
    cr_expect_leq(ra.iterations, 26, "%zu", ra.iterations);
    cr_expect_float_eq(ra.error_max, rc.error_max, 1e-7);
    if (n == 8) cr_expect_lt(rc.error_max, 0.35 * err_prev, "%.3g then %.3g", err_prev, rc.error_max);
    err_prev = rc.error_max;
    free(ec), free(ea);
    gm_mesh_free(m);
  }
}

Test(hypre, bad_input) {
  gm_error err = {{0}};
  gm_csr *A = NULL, *G = NULL;
  cr_assert_eq(gm_csr_diagonal(4, NULL, &A), GM_OK);
  cr_assert_eq(gm_csr_create(3, 2, 0, &G), GM_OK);
  double b[4] = {1, 1, 1, NAN}, x[4] = {0}, xyz[6] = {0};
  gm_hypre_report r;
  gm_status st = gm_hypre_boomeramg_pcg(A, b, x, 1e-10, 0, &r, &err);
  cr_expect_eq(st, gm_hypre_available() ? GM_EDOMAIN : GM_EUNSUPPORTED, "%s", err.message);
  b[3] = 1.0;
  st = gm_hypre_ams_pcg(A, G, xyz, b, x, 1e-10, 0, &r, &err);
  cr_expect_eq(st, gm_hypre_available() ? GM_EINVAL : GM_EUNSUPPORTED, "%s", err.message);
  if (gm_hypre_available()) cr_expect_not_null(strstr(err.message, "4 rows"), "%s", err.message);
  gm_csr_free(A), gm_csr_free(G);
}
