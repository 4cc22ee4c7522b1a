/* Maxwell on the 2+1 prismal spacetime complex as one sparse solve (seed 000 §3.4.4): dF = 0 on
 * every prism and dG = 𝒥 on every interior spatial edge (Ampère) and temporal edge (Gauss, not
 * imposed) hold to round-off on the solution, with and without currents; and on this prismal
 * complex the solve is the Bossavit–Kettunen leapfrog (the same B^n and E^{n+½}). */
#include "../mesh_maxwell_util.h"

static void check_spacetime(int with_current) {
  mm_fixture f = mm_rect(6, 0.7, 0.0, 1);
  gm_error err = {{0}};
  const size_t ne = gm_complex_count(f.cx, 1), nf = gm_complex_count(f.cx, 2), N = 40;
  double *E0 = malloc(ne * sizeof(double)), *B0 = malloc(nf * sizeof(double));
  mm_random_fields(&f, 3, E0, B0);
  gm_mesh_maxwell *lf = NULL;
  cr_assert_eq(gm_mesh_maxwell_create(f.g, NULL, NULL, NULL, &lf, &err), GM_OK, "%s", err.message);
  const double dt = gm_mesh_maxwell_dt(lf);
  double *J = calloc(N * ne, sizeof(double));
  const gm_waveform wave = {GM_WAVE_GAUSSIAN, 3.0, 1.5, 0.2, 0.8, 0.0, NULL, NULL};
  if (with_current) {
    const double x1[3] = {0.31, 0.23, 0}, x2[3] = {0.62, 0.41, 0};
    const size_t edges[2] = {mm_nearest_interior_edge(&f, x1), mm_nearest_interior_edge(&f, x2)};
    const double w[2] = {1.0, -0.7};
    cr_assert_eq(gm_mesh_maxwell_add_current(lf, 2, edges, w, &wave, NULL), GM_OK);
    for (size_t n = 1; n < N; ++n)
      for (int k = 0; k < 2; ++k) J[n * ne + edges[k]] = w[k] * gm_waveform_value(&wave, (double)n * dt);
  }
  /* leapfrog: (B⁰, E^{−½}) → after one step E^{½}: the spacetime's initial data */
  cr_assert_eq(gm_mesh_maxwell_set_fields(lf, E0, B0), GM_OK);
  cr_assert_eq(gm_mesh_maxwell_advance(lf, 1), GM_OK);
  double *Eh = malloc(ne * sizeof(double));
  memcpy(Eh, gm_mesh_maxwell_e(lf), ne * sizeof(double));
  double *B = malloc((N + 1) * nf * sizeof(double)), *E = malloc(N * ne * sizeof(double));
  gm_mesh_maxwell_spacetime_residuals res;
  cr_assert_eq(gm_mesh_maxwell_spacetime(f.g, NULL, NULL, N, dt, B0, Eh, with_current ? J : NULL,
                                         B, E, &res, &err), GM_OK, "%s", err.message);
  /* the leapfrog's later steps against the solve */
  double db = 0.0, de = 0.0, sb = 0.0, se = 0.0;
  for (size_t n = 1; n < N; ++n) {
    const double *Bl = gm_mesh_maxwell_b(lf), *El;
    for (size_t k = 0; k < nf; ++k) { db = fmax(db, fabs(B[n * nf + k] - Bl[k])); sb = fmax(sb, fabs(Bl[k])); }
    cr_assert_eq(gm_mesh_maxwell_advance(lf, 1), GM_OK);
    El = gm_mesh_maxwell_e(lf);
    for (size_t e = 0; e < ne; ++e) { de = fmax(de, fabs(E[n * ne + e] - El[e])); se = fmax(se, fabs(El[e])); }
  }
  fprintf(stderr, "mesh_maxwell spacetime 2+1 (%s), %zu unknowns: residual dF %.2e, dG Ampère "
          "%.2e, dG Gauss %.2e; vs leapfrog max|ΔB|/max|B| %.2e, max|ΔE|/max|E| %.2e\n",
          with_current ? "currents" : "no source", res.unknowns, res.dF, res.dG_ampere,
          res.dG_gauss, db / sb, de / se);
  cr_assert_lt(res.dF, 1e-13);
  cr_assert_lt(res.dG_ampere, 1e-13);
  cr_assert_lt(res.dG_gauss, 1e-12);
  cr_assert_lt(db / sb, 1e-11);
  cr_assert_lt(de / se, 1e-11);
  free(E0); free(B0); free(J); free(Eh); free(B); free(E);
  gm_mesh_maxwell_free(lf);
  mm_fixture_free(&f);
}

Test(mesh_maxwell_spacetime, solve_holds_df_and_dg) {
  check_spacetime(0);
  check_spacetime(1);
}

Test(mesh_maxwell_spacetime, bad_input) {
  mm_fixture f = mm_rect(4, 0.7, 0.0, 1), b = mm_bcc(2);
  gm_error err = {{0}};
  double x[4096] = {0};
  cr_assert_eq(gm_mesh_maxwell_spacetime(f.g, NULL, NULL, 0, 0.01, x, x, NULL, x, x, NULL, &err),
               GM_EINVAL);
  cr_assert_eq(gm_mesh_maxwell_spacetime(b.g, NULL, NULL, 2, 0.01, x, x, NULL, x, x, NULL, &err),
               GM_EINVAL);
  cr_assert(strstr(err.message, "2+1") != NULL, "%s", err.message);
  mm_fixture_free(&f);
  mm_fixture_free(&b);
}
