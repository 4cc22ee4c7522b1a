/* Mesh Maxwell (seed 000 §3.4.2–3.4.3): div B = 0 and Gauss's law div D − ρ constant to round-off
 * every step, with and without a current; charge conservation; the leapfrog's modified energy
 * constant to round-off and the plain energy bounded; the AVI with equal steps is the leapfrog;
 * the AVI keeps Gauss's law (with currents too) and a near-constant energy on a randomly
 * partitioned mesh, and with currents it is still the leapfrog at equal steps; discrete
 * integration by parts with the boundary term (seed 000 eq. 3.8) on the meshes used. */
#include "../mesh_maxwell_util.h"

typedef struct watch {
  double *gauss0, *gauss;
  size_t nv;
  double gauss_drift, divb, charge;
  double e0, leap_drift, plain_dev;
} watch;

static int watcher(void *ctx, const gm_mesh_maxwell *s) {
  watch *w = ctx;
  gm_mesh_maxwell_gauss(s, w->gauss);
  if (gm_mesh_maxwell_step(s) == 0 && gm_mesh_maxwell_time(s) == 0.0 && w->e0 == 0.0)
    memcpy(w->gauss0, w->gauss, w->nv * sizeof(double));
  for (size_t v = 0; v < w->nv; ++v) {
    const double d = fabs(w->gauss[v] - w->gauss0[v]);
    w->gauss_drift = d > w->gauss_drift ? d : w->gauss_drift;
  }
  const double db = gm_mesh_maxwell_div_b(s);
  w->divb = db > w->divb ? db : w->divb;
  const double q = fabs(gm_mesh_maxwell_charge(s));
  w->charge = q > w->charge ? q : w->charge;
  gm_mesh_maxwell_energy en;
  gm_mesh_maxwell_energy_get(s, &en);
  if (w->e0 == 0.0) w->e0 = en.leapfrog;
  const double dl = fabs(en.leapfrog - w->e0) / w->e0, dp = fabs(en.plain - w->e0) / w->e0;
  w->leap_drift = dl > w->leap_drift ? dl : w->leap_drift;
  w->plain_dev = dp > w->plain_dev ? dp : w->plain_dev;
  return 0;
}

/* Two edge currents (a Gaussian pulse) near fixed points of the unit box. */
static void add_test_current(mm_fixture *f, gm_mesh_maxwell *s) {
  const double x[3] = {0.31, 0.23, 0.17};
  size_t edges[2] = {mm_nearest_interior_edge(f, x), 0};
  const double x2[3] = {0.62, 0.41, 0.33};
  edges[1] = mm_nearest_interior_edge(f, x2);
  const double wts[2] = {1.0, -0.7};
  const gm_waveform wave = {GM_WAVE_GAUSSIAN, 3.0, 1.5, 0.2, 0.8, 0.0, NULL, NULL};
  cr_assert_eq(gm_mesh_maxwell_add_current(s, 2, edges, wts, &wave, NULL), GM_OK, "%s",
               gm_mesh_maxwell_errmsg(s));
}

static watch run_leapfrog(mm_fixture *f, gm_mesh_maxwell_star star, int with_current,
                          size_t steps) {
  gm_error err = {{0}};
  gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
  o.star = star;
  gm_mesh_maxwell *s = NULL;
  cr_assert_eq(gm_mesh_maxwell_create(f->g, NULL, NULL, &o, &s, &err), GM_OK, "%s", err.message);
  const size_t ne = gm_complex_count(f->cx, 1), nf = gm_complex_count(f->cx, 2);
  double *E = malloc(ne * sizeof(double)), *B = malloc(nf * sizeof(double));
  mm_random_fields(f, 42, E, B);
  cr_assert_eq(gm_mesh_maxwell_set_fields(s, E, B), GM_OK);
  if (with_current) add_test_current(f, s);
  watch w = {0};
  w.nv = gm_complex_count(f->cx, 0);
  w.gauss0 = calloc(w.nv, sizeof(double));
  w.gauss = calloc(w.nv, sizeof(double));
  cr_assert_eq(gm_mesh_maxwell_add_observer(s, 1, watcher, &w), GM_OK);
  cr_assert_eq(gm_mesh_maxwell_advance(s, steps), GM_OK, "%s", gm_mesh_maxwell_errmsg(s));
  free(w.gauss0); free(w.gauss); free(E); free(B);
  gm_mesh_maxwell_free(s);
  return w;
}

Test(mesh_maxwell, leapfrog_2d_invariants) {
  mm_fixture f = mm_rect(12, 0.7, 0.0, 1);
  watch a = run_leapfrog(&f, GM_MESH_STAR_DIAGONAL, 0, 3000);
  watch b = run_leapfrog(&f, GM_MESH_STAR_DIAGONAL, 1, 3000);
  fprintf(stderr, "mesh_maxwell 2-D leapfrog, 3000 steps: modified energy drift %.2e, plain "
          "energy deviation %.3f; Gauss drift %.2e (no source) %.2e (current), |Σρ| %.2e\n",
          a.leap_drift, a.plain_dev, a.gauss_drift, b.gauss_drift, b.charge);
  /* measured: modified energy drift 2.54e-15, Gauss drift 1.85e-13 / 3.66e-13 (round-off of
   * 3000 steps), plain deviation 1.776 */
  cr_assert_lt(a.leap_drift, 2e-14);
  /* grid-scale random fields at 0.9 of the CFL limit: the plain energy oscillates around the
   * modified one by up to the factor 1/(1 − 0.9) (bounded, never growing); these fields reach
   * 1.776 of it, held at 2.5 so that growth shows */
  cr_assert_lt(a.plain_dev, 2.5);
  cr_assert_lt(a.gauss_drift, 1e-12);
  cr_assert_lt(b.gauss_drift, 2e-12);
  cr_assert_lt(b.charge, 1e-13);
  mm_fixture_free(&f);
}

Test(mesh_maxwell, leapfrog_3d_whitney_invariants) {
  mm_fixture f = mm_box(5);
  watch a = run_leapfrog(&f, GM_MESH_STAR_WHITNEY, 0, 400);
  watch b = run_leapfrog(&f, GM_MESH_STAR_WHITNEY, 1, 400);
  fprintf(stderr, "mesh_maxwell 3-D leapfrog (Whitney star), 400 steps: modified energy drift "
          "%.2e, plain deviation %.3f; div B %.2e / %.2e; Gauss drift %.2e / %.2e, |Σρ| %.2e\n",
          a.leap_drift, a.plain_dev, a.divb, b.divb, a.gauss_drift, b.gauss_drift, b.charge);
  /* measured: modified energy drift 1.68e-15, plain deviation 1.028, div B 7.55e-15 /
   * 7.77e-15, Gauss drift 6.70e-15 / 8.08e-15 (round-off of 400 steps); bounds ~10x */
  cr_assert_lt(a.leap_drift, 2e-14);
  cr_assert_lt(a.plain_dev, 1.5);
  cr_assert_lt(a.divb, 8e-14);
  cr_assert_lt(b.divb, 8e-14);
  cr_assert_lt(a.gauss_drift, 8e-14);
  cr_assert_lt(b.gauss_drift, 8e-14);
  cr_assert_lt(b.charge, 1e-13);
  mm_fixture_free(&f);
}

/* With every face's step equal to the leapfrog's, the AVI's events tie and it is the leapfrog:
 * AVI from (B⁰, E^{½}) at t = (n−1)Δt against the leapfrog from (B⁰, E^{−½}) after n steps;
 * with a current, the AVI's impulses J(t_k)(t_k − t_{k−1}) are the leapfrog's Δt J^k. */
static void check_avi_equal_steps(mm_fixture f, size_t n, int with_current, const char *label) {
  gm_error err = {{0}};
  const size_t ne = gm_complex_count(f.cx, 1), nf = gm_complex_count(f.cx, 2);
  double *E = malloc(ne * sizeof(double)), *B = malloc(nf * sizeof(double));
  double *Bprev = malloc(nf * sizeof(double)), *Bavi = malloc(nf * sizeof(double));
  mm_random_fields(&f, 7, E, B);
  gm_mesh_maxwell *lf = NULL, *avi = NULL;
  cr_assert_eq(gm_mesh_maxwell_create(f.g, NULL, NULL, NULL, &lf, &err), GM_OK, "%s",
               err.message);
  /* the leapfrog's step, or the smallest local limit (a Gershgorin bound) when that is less */
  gm_mesh_maxwell_options lo = gm_mesh_maxwell_defaults();
  lo.dt = gm_mesh_maxwell_dt(lf);
  for (size_t k = 0; k < nf; ++k) lo.dt = fmin(lo.dt, gm_mesh_maxwell_face_limits(lf)[k]);
  gm_mesh_maxwell_free(lf);
  cr_assert_eq(gm_mesh_maxwell_create(f.g, NULL, NULL, &lo, &lf, &err), GM_OK, "%s",
               err.message);
  const double dt = gm_mesh_maxwell_dt(lf);
  cr_assert_eq(gm_mesh_maxwell_set_fields(lf, E, B), GM_OK);
  /* E^{½} from one leapfrog step of a copy */
  gm_mesh_maxwell *one = NULL;
  cr_assert_eq(gm_mesh_maxwell_create(f.g, NULL, NULL, &lo, &one, &err), GM_OK);
  gm_mesh_maxwell_set_fields(one, E, B);
  if (with_current) add_test_current(&f, one), add_test_current(&f, lf);
  cr_assert_eq(gm_mesh_maxwell_advance(one, 1), GM_OK);
  double *face_dt = malloc(nf * sizeof(double));
  for (size_t k = 0; k < nf; ++k) face_dt[k] = dt;
  gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
  o.scheme = GM_MESH_AVI;
  o.face_dt = face_dt;
  cr_assert_eq(gm_mesh_maxwell_create(f.g, NULL, NULL, &o, &avi, &err), GM_OK, "%s",
               err.message);
  cr_assert_eq(gm_mesh_maxwell_set_fields(avi, gm_mesh_maxwell_e(one), B), GM_OK);
  if (with_current) add_test_current(&f, avi);
  cr_assert_eq(gm_mesh_maxwell_avi_groups(avi), 1);
  cr_assert_eq(gm_mesh_maxwell_advance(lf, n - 1), GM_OK);
  memcpy(Bprev, gm_mesh_maxwell_b(lf), nf * sizeof(double));
  cr_assert_eq(gm_mesh_maxwell_advance(lf, 1), GM_OK);
  cr_assert_eq(gm_mesh_maxwell_advance_to(avi, (double)(n - 1) * dt), GM_OK);
  gm_mesh_maxwell_sync_b(avi, Bavi);
  double de = 0.0, db = 0.0, se = 0.0, sb = 0.0;
  const double *Ea = gm_mesh_maxwell_e(avi), *El = gm_mesh_maxwell_e(lf);
  for (size_t e = 0; e < ne; ++e) { de = fmax(de, fabs(Ea[e] - El[e])); se = fmax(se, fabs(El[e])); }
  for (size_t k = 0; k < nf; ++k) { db = fmax(db, fabs(Bavi[k] - Bprev[k])); sb = fmax(sb, fabs(Bprev[k])); }
  size_t fu, eu, fl, el;
  gm_mesh_maxwell_update_counts(avi, &fu, &eu);
  gm_mesh_maxwell_update_counts(lf, &fl, &el);
  fprintf(stderr, "mesh_maxwell AVI with equal steps vs leapfrog (%s%s) after %zu steps: "
          "max|ΔE|/max|E| %.2e, max|ΔB|/max|B| %.2e; face updates %zu (leapfrog %zu)\n", label,
          with_current ? ", current" : "", n, de / se, db / sb, fu, fl);
  cr_assert_lt(de / se, 1e-11);
  cr_assert_lt(db / sb, 1e-11);
  free(E); free(B); free(Bprev); free(Bavi); free(face_dt);
  gm_mesh_maxwell_free(lf); gm_mesh_maxwell_free(one); gm_mesh_maxwell_free(avi);
  mm_fixture_free(&f);
}

Test(mesh_maxwell, avi_equal_steps_is_leapfrog) {
  check_avi_equal_steps(mm_rect(10, 0.7, 0.0, 1), 500, 0, "2-D");
  check_avi_equal_steps(mm_bcc(3), 200, 0, "3-D bcc");
  check_avi_equal_steps(mm_rect(10, 0.7, 0.0, 1), 500, 1, "2-D");
  check_avi_equal_steps(mm_bcc(3), 200, 1, "3-D bcc");
}

/* AVI each face at 1/10 of its local limit (seed 000 E4) from random fields to t = T, sampled
 * every 0.05: Gauss's law, div B, energy, and the face updates against uniform stepping at the
 * smallest step. */
static double check_avi(mm_fixture f, int levels, int with_current, double T, double energy_tol,
                        const char *label) {
  gm_error err = {{0}};
  gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
  o.scheme = GM_MESH_AVI;
  o.avi_levels = levels;
  gm_mesh_maxwell *s = NULL;
  cr_assert_eq(gm_mesh_maxwell_create(f.g, NULL, NULL, &o, &s, &err), GM_OK, "%s", err.message);
  const size_t ne = gm_complex_count(f.cx, 1), nf = gm_complex_count(f.cx, 2);
  double *E = malloc(ne * sizeof(double)), *B = malloc(nf * sizeof(double));
  mm_random_fields(&f, 11, E, B);
  cr_assert_eq(gm_mesh_maxwell_set_fields(s, E, B), GM_OK);
  if (with_current) add_test_current(&f, s);
  watch w = {0};
  w.nv = gm_complex_count(f.cx, 0);
  w.gauss0 = calloc(w.nv, sizeof(double));
  w.gauss = calloc(w.nv, sizeof(double));
  cr_assert_eq(gm_mesh_maxwell_set_sample_dt(s, 0.05), GM_OK);
  cr_assert_eq(gm_mesh_maxwell_add_observer(s, 1, watcher, &w), GM_OK);
  cr_assert_eq(gm_mesh_maxwell_advance_to(s, T), GM_OK, "%s", gm_mesh_maxwell_errmsg(s));
  size_t fu, eu;
  gm_mesh_maxwell_update_counts(s, &fu, &eu);
  const double *lim = gm_mesh_maxwell_face_limits(s);
  double smallest = INFINITY;
  size_t active = 0;
  for (size_t k = 0; k < nf; ++k)
    if (isfinite(lim[k])) { smallest = fmin(smallest, 0.1 * lim[k]); ++active; }
  const double uniform = (double)active * floor(T / smallest);
  fprintf(stderr, "mesh_maxwell AVI, %s, levels %d%s, to t = %g: %zu groups, %zu face updates "
          "(uniform at the smallest step: %.0f, ratio %.3f), %zu edge updates; energy deviation "
          "%.2e; Gauss drift %.2e; div B %.2e; |Σρ| %.2e\n", label, levels,
          with_current ? ", current" : "", T, gm_mesh_maxwell_avi_groups(s), fu, uniform,
          (double)fu / uniform, eu, w.plain_dev, w.gauss_drift, w.divb, w.charge);
  cr_assert_lt(w.gauss_drift, 1e-12);
  cr_assert_lt(w.divb, 1e-12);
  cr_assert_lt(w.charge, 1e-13);
  if (!with_current) cr_assert_lt(w.plain_dev, energy_tol); /* the source changes the energy */
  if (levels) cr_assert_leq((double)fu, uniform); /* steps rounded down: at most uniform's */
  else cr_assert_lt((double)fu, uniform);
  if (levels) cr_assert_leq(gm_mesh_maxwell_avi_groups(s), 12);
  gm_mesh_maxwell_energy en;
  gm_mesh_maxwell_energy_get(s, &en);
  free(w.gauss0); free(w.gauss); free(E); free(B);
  gm_mesh_maxwell_free(s);
  mm_fixture_free(&f);
  return en.plain;
}

/* AVI on a randomly partitioned mesh, each face at 1/10 of its local limit (seed 000 E4); with
 * the steps as given and rounded to power-of-two levels. */
Test(mesh_maxwell, avi_random_mesh_invariants) {
  const double e_free = check_avi(mm_rect(10, 0.7, 0.3, 99), 0, 0, 20.0, 0.05, "random partition");
  check_avi(mm_rect(10, 0.7, 0.3, 99), 1, 0, 20.0, 0.05, "random partition");
  /* a current with 166 groups of distinct steps */
  const double e_src = check_avi(mm_rect(10, 0.7, 0.3, 99), 0, 1, 20.0, 0.05, "random partition");
  fprintf(stderr, "mesh_maxwell AVI, random partition: final energy %.6g without, %.6g with the "
          "current\n", e_free, e_src);
  cr_assert_gt(fabs(e_src - e_free), 1e-6 * e_free); /* the current did act (round-off: 1e-13) */
}

/* AVI in 3-D on the well-centred bcc tetrahedra, jittered so the face limits differ. */
Test(mesh_maxwell, avi_3d_invariants) {
  const double e_free = check_avi(mm_bcc_jittered(3, 0.08, 5), 0, 0, 3.0, 0.05, "3-D bcc jittered");
  check_avi(mm_bcc_jittered(3, 0.08, 5), 1, 0, 3.0, 0.05, "3-D bcc jittered");
  const double e_src = check_avi(mm_bcc_jittered(3, 0.08, 5), 0, 1, 3.0, 0.05, "3-D bcc jittered");
  fprintf(stderr, "mesh_maxwell AVI, 3-D bcc jittered: final energy %.6g without, %.6g with the "
          "current\n", e_free, e_src);
  cr_assert_gt(fabs(e_src - e_free), 1e-6 * e_free);
}

/* Seed 000 eq. 3.8: (dα, β)_{k+1} = (α, δ̃β)_k + ⟨α ∧ ⋆β, ∂K⟩ with boundary flux data. */
static void check_ibp(mm_fixture *f, size_t k) {
  gm_error err = {{0}};
  const size_t nk = gm_complex_count(f->cx, k), nk1 = gm_complex_count(f->cx, k + 1);
  double *a = malloc(nk * sizeof(double)), *b = malloc(nk1 * sizeof(double));
  double *flux = malloc(nk * sizeof(double)), *da = malloc(nk1 * sizeof(double));
  double *db = malloc(nk * sizeof(double));
  uint64_t z = 5;
  for (size_t i = 0; i < nk; ++i) { a[i] = mm_rand(&z); flux[i] = mm_rand(&z); }
  for (size_t i = 0; i < nk1; ++i) b[i] = mm_rand(&z);
  gm_csr_matvec(gm_complex_d(f->cx, k), 1.0, a, 0.0, da);
  cr_assert_eq(gm_dec_codifferential_boundary(f->g, k, b, flux, db, &err), GM_OK, "%s",
               err.message);
  const double *s0 = gm_geometry_hodge_star(f->g, k), *s1 = gm_geometry_hodge_star(f->g, k + 1);
  double lhs = 0.0, rhs = 0.0, scale = 0.0;
  for (size_t i = 0; i < nk1; ++i) { lhs += da[i] * s1[i] * b[i]; scale += fabs(da[i] * s1[i] * b[i]); }
  for (size_t i = 0; i < nk; ++i) rhs += a[i] * s0[i] * db[i];
  rhs += gm_dec_boundary_pairing(f->cx, k, a, flux);
  fprintf(stderr, "mesh_maxwell integration by parts (eq. 3.8), dim %zu, k = %zu: |lhs − rhs| / "
          "Σ|terms| = %.2e\n", gm_complex_dim(f->cx), k, fabs(lhs - rhs) / scale);
  cr_assert_lt(fabs(lhs - rhs), 1e-12 * scale);
  free(a); free(b); free(flux); free(da); free(db);
}

Test(mesh_maxwell, integration_by_parts) {
  mm_fixture f = mm_rect(10, 0.7, 0.0, 1), r = mm_rect(10, 0.7, 0.3, 99), b = mm_box(5);
  check_ibp(&f, 0);
  check_ibp(&f, 1);
  check_ibp(&r, 0);
  check_ibp(&r, 1);
  check_ibp(&b, 0);
  mm_fixture_free(&f); mm_fixture_free(&r); mm_fixture_free(&b);
}
