/* Geometric multigrid on red-refined tetrahedral meshes for the DEC Poisson problem (0-form
 * Laplacian d_0ᵀ ⋆_1 d_0 with Dirichlet data): the V-cycle's contraction factor, CG iteration
 * counts that do not grow with the number of levels, agreement with CHOLMOD; bad input. */
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

/* BCC cube 2×2×2 (384 tets) refined 1..4 times (up to 196 608 tets, 29 791 unknowns), V(2,2).
 * Measured: iterations 4, 6, 7, 7; contraction 0.008, 0.074, 0.098, 0.098; max |u_mg − u_chol|
 * 6.9e-11 on the finest level. */
Test(multigrid, contraction_level_independence_and_cholmod) {
  gm_mesh *m = bcc_cube(2);
  gm_error err = {{0}};
  size_t its[4];
  double mean = 0.0;
  for (size_t L = 1; L <= 4; ++L) {
    gm_poisson_options o = gm_poisson_defaults();
    o.solver = GM_POISSON_MULTIGRID;
    o.levels = L;
    o.measure_contraction = 1;
    gm_poisson_report r;
    double *u = NULL;
    cr_assert_eq(gm_mesh_poisson_solve(m, &o, &r, &u, &err), GM_OK, "%s", err.message);
    printf("multigrid L=%zu: %zu tets, %zu unknowns, %zu CG iterations, V-cycle contraction "
           "%.3f, relative residual %.2e\n",
           L, r.n_cells, r.n_unknowns, r.iterations, r.contraction, r.relative_residual);
    cr_expect_leq(r.contraction, 0.2, "L=%zu: contraction %.3f", L, r.contraction);
    cr_expect_leq(r.relative_residual, 1e-10);
    its[L - 1] = r.iterations;
    mean += (double)r.iterations / 4.0;
    if (L == 4) {
      o.solver = GM_POISSON_CHOLMOD;
      gm_poisson_report rc;
      double *v = NULL;
      cr_assert_eq(gm_mesh_poisson_solve(m, &o, &rc, &v, &err), GM_OK, "%s", err.message);
      double d = 0.0;
      for (size_t i = 0; i < r.n_vertices; ++i) d = fmax(d, fabs(u[i] - v[i]));
      printf("multigrid L=4: max |u_mg - u_cholmod| = %.3g, discretisation error %.3g\n", d,
             r.error_max);
      cr_expect_leq(d, 5e-10, "%.3g", d); /* 6.9e-11 */
      cr_expect_float_eq(rc.error_max, r.error_max, 1e-9);
      free(v);
    }
    free(u);
  }
  for (size_t L = 0; L < 4; ++L)
    cr_expect_leq(fabs((double)its[L] - mean), 2.0, "iterations %zu %zu %zu %zu", its[0], its[1],
                  its[2], its[3]);
  gm_mesh_free(m);
}

/* The Kuhn cube mesh (right-angled tetrahedra, zero dual edges): V(2,2) contracts by 0.211 on
 * three levels (measured), V(3,3) by 0.137. */
Test(multigrid, kuhn_contraction) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_box(lo, hi, 2, 2, 2, GM_BOX_KUHN, &m, &err), GM_OK);
  for (size_t nu = 2; nu <= 3; ++nu) {
    gm_poisson_options o = gm_poisson_defaults();
    o.solver = GM_POISSON_MULTIGRID;
    o.levels = 3;
    o.pre_smooth = o.post_smooth = nu;
    o.measure_contraction = 1;
    gm_poisson_report r;
    cr_assert_eq(gm_mesh_poisson_solve(m, &o, &r, NULL, &err), GM_OK, "%s", err.message);
    printf("Kuhn L=3 V(%zu,%zu): contraction %.3f, %zu iterations\n", nu, nu, r.contraction,
           r.iterations);
    cr_expect_leq(r.contraction, nu == 2 ? 0.25 : 0.2, "%.3f", r.contraction);
    cr_expect_leq(r.iterations, nu == 2 ? 11 : 10);
  }
  gm_mesh_free(m);
}

Test(multigrid, bad_input) {
  gm_error err = {{0}};
  gm_mesh *m = bcc_cube(2);
  gm_poisson_options o = gm_poisson_defaults();
  o.solver = GM_POISSON_MULTIGRID;
  gm_poisson_report r;
  cr_expect_eq(gm_mesh_poisson_solve(m, &o, &r, NULL, &err), GM_EINVAL); /* no levels */
  cr_expect_not_null(strstr(err.message, "refinement"), "%s", err.message);
  o.levels = 9;
  o.max_bytes = 1 << 30;
  cr_expect_eq(gm_mesh_poisson_solve(m, &o, &r, NULL, &err), GM_ENOMEM);
  cr_expect_not_null(strstr(err.message, "bytes"), "%s", err.message);
  gm_mesh_free(m);
  /* prolongations that do not chain */
  gm_csr *A = NULL, *P = NULL;
  cr_assert_eq(gm_csr_diagonal(4, NULL, &A), GM_OK);
  cr_assert_eq(gm_csr_create(3, 2, 0, &P), GM_OK);
  gm_multigrid *mg = NULL;
  const gm_csr *Ps[1] = {P};
  cr_expect_eq(gm_multigrid_create(A, 1, Ps, NULL, &mg, &err), GM_EINVAL);
  cr_expect_not_null(strstr(err.message, "4 rows"), "%s", err.message);
  cr_expect_null(mg);
  gm_csr_free(A), gm_csr_free(P);
}
