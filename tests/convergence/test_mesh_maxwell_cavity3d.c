/* The 3-D PEC cavity verification of issue 11 ("Invariants and verification"): the analytic
 * resonances (box multiplicities, cylinder Bessel zeros), and the Whitney-star leapfrog rung
 * down by gm_mesh_maxwell_cavity_modes (current pulses on random edges, E at random points,
 * harminv, the leapfrog's dispersion undone) at three resolutions of
 *   - the box [0,1]×[0,0.75]×[0,0.5]: body-centred cubic tetrahedra with the boundary pyramids
 *     filled (so the mesh is the box), 4, 8, 12 cubes along x (a self-similar family);
 *   - the cylinder r = 0.5, height 0.6: the Gmsh meshes examples/cavity_cylinder_{1,2,3}.msh
 *     (scripts/cavity_cylinder_mesh.sh; sizes 0.14, 0.1, 0.07);
 *   - and in 2-D (TE) the rectangle [0,1]×[0,0.7] on self-similar acute meshes (diagonal star).
 * Asserted: every harminv peak below the 10th resonance lies within 5 % of an analytic one and
 * there are no more peaks than analytic modes (with multiplicity) in the band; the rates in h
 * (least squares over the three levels) exceed 1.8 as the median over the resonances found on
 * every level and for each isolated simple one (2-D: 1.75, see there). The larger run (the
 * box [0,1]×[0,0.8]×[0,0.6] at 5, 10, 15 cubes) is `geomint maxwell mesh-cavity`
 * (docs/maxwell-mesh.md). */
#include "../mesh_maxwell_util.h"

#define PI 3.14159265358979323846

Test(mesh_maxwell_cavity3d, box_resonances) {
  const double L[3] = {1.0, 0.8, 0.6};
  double f[64];
  size_t n = 0;
  gm_error err = {{0}};
  cr_assert_eq(gm_cavity_box_resonances(L, 1.45, 64, f, &n, &err), GM_OK, "%s", err.message);
  /* (1,1,0) (1,0,1) (0,1,1) (1,1,1)×2 (2,1,0) (2,0,1) (1,2,0) (2,1,1)×2 */
  const double want[] = {0.5 * sqrt(1 + 1 / 0.64), 0.5 * sqrt(1 + 1 / 0.36),
                         0.5 * sqrt(1 / 0.64 + 1 / 0.36), 0.5 * sqrt(1 + 1 / 0.64 + 1 / 0.36),
                         0.5 * sqrt(1 + 1 / 0.64 + 1 / 0.36), 0.5 * sqrt(4 + 1 / 0.64),
                         0.5 * sqrt(4 + 1 / 0.36), 0.5 * sqrt(1 + 4 / 0.64),
                         0.5 * sqrt(4 + 1 / 0.64 + 1 / 0.36), 0.5 * sqrt(4 + 1 / 0.64 + 1 / 0.36)};
  cr_assert_eq(n, 10, "%zu resonances", n);
  for (size_t i = 0; i < n; ++i) cr_expect_float_eq(f[i], want[i], 1e-12, "%zu", i);
  cr_expect_eq(gm_cavity_box_resonances(L, 10.0, 8, f, &n, &err), GM_EINVAL);
}

Test(mesh_maxwell_cavity3d, cylinder_resonances) {
  /* R = 1, H = π: f = √(x² + p²)/2π with x a Bessel zero; j_01 = 2.404825557695773,
   * j'_11 = 1.841183781340659, j_11 = 3.831705970207512, j'_21 = 3.054236928227140
   * (Abramowitz & Stegun tables 9.5). */
  double f[64];
  size_t n = 0;
  gm_error err = {{0}};
  cr_assert_eq(gm_cavity_cylinder_resonances(1.0, PI, 0.52, 64, f, &n, &err), GM_OK, "%s",
               err.message);
  const double tp = 2 * PI;
  const double want[] = {sqrt(1.841183781340659 * 1.841183781340659 + 1) / tp, /* TE111 ×2 */
                         sqrt(1.841183781340659 * 1.841183781340659 + 1) / tp,
                         2.404825557695773 / tp,                               /* TM010 */
                         sqrt(2.404825557695773 * 2.404825557695773 + 1) / tp, /* TM011 */
                         sqrt(1.841183781340659 * 1.841183781340659 + 4) / tp, /* TE112 ×2 */
                         sqrt(1.841183781340659 * 1.841183781340659 + 4) / tp,
                         sqrt(2.404825557695773 * 2.404825557695773 + 4) / tp, /* TM012 */
                         sqrt(3.054236928227140 * 3.054236928227140 + 1) / tp, /* TE211 ×2 */
                         sqrt(3.054236928227140 * 3.054236928227140 + 1) / tp};
  cr_assert_eq(n, sizeof want / sizeof want[0], "%zu resonances", n);
  size_t k = 0;
  for (size_t i = 0; i < sizeof want / sizeof want[0]; ++i) {
    cr_assert_lt(k, n);
    cr_expect_float_eq(f[k], want[i], 1e-10, "%zu: %.12f vs %.12f", i, f[k], want[i]);
    ++k;
  }
  cr_expect_eq(gm_cavity_cylinder_resonances(-1.0, 1.0, 1.0, 64, f, &n, &err), GM_EINVAL);
}

Test(mesh_maxwell_cavity3d, leapfrog_dispersion_undone) {
  /* sin(π f dt)/(π dt) → f as dt → 0, and is the ω of the spatial operator exactly. */
  cr_expect_float_eq(gm_leapfrog_space_frequency(1.0, 1e-6), 1.0, 1e-10);
  const double dt = 0.1, lam = 4.0; /* ω² = λ: sin(ωdt/2) = dt √λ / 2 */
  const double w = 2.0 / dt * asin(0.5 * dt * sqrt(lam));
  cr_expect_float_eq(gm_leapfrog_space_frequency(w / (2 * PI), dt), sqrt(lam) / (2 * PI),
                     1e-14);
}

#define LEVELS 3
#define MAXM 128

/* OpenBLAS (under CHOLMOD's supernodal solves of the Whitney star) spins its threads on these
 * small factors: on the loaded 2-core machine one thread halves the CPU time. Weak, so a BLAS
 * without the call is fine. */
extern void openblas_set_num_threads(int n) __attribute__((weak));

typedef void (*level_fn)(size_t level, mm_fixture *f, double *h);

/* The study over LEVELS meshes against the analytic list ana (na values, ascending). */
static void study(const char *name, level_fn make, const double *ana, size_t na, double t_end,
                  double min_rate) {
  if (openblas_set_num_threads) openblas_set_num_threads(1);
  gm_error err = {{0}};
  double hs[LEVELS];
  size_t next = 10;
  while (ana[next] <= ana[9] * (1 + 1e-12)) ++next;
  const double f_hi = 0.5 * (ana[9] + ana[next]);
  double uniq[10];
  int mult[10];
  size_t nu = 0;
  for (size_t j = 0; j < 10; ++j) {
    if (nu > 0 && ana[j] <= uniq[nu - 1] * (1 + 1e-12)) { ++mult[nu - 1]; continue; }
    uniq[nu] = ana[j];
    mult[nu++] = 1;
  }
  size_t in_band = 0;
  for (size_t j = 0; j < na; ++j) in_band += ana[j] >= 0.5 * ana[0] && ana[j] <= f_hi;
  gm_mesh_cavity_run run = gm_mesh_cavity_run_defaults();
  run.t_end = t_end;
  run.f_min = 0.5 * ana[0];
  run.f_max = f_hi;
  run.band = 0.2;
  run.n_sources = 12;
  run.n_probes = 8;
  double errs[10][LEVELS];
  for (size_t l = 0; l < LEVELS; ++l) {
    mm_fixture f = {0};
    make(l, &f, &hs[l]);
    gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
    if (gm_complex_dim(f.cx) == 3) o.star = GM_MESH_STAR_WHITNEY; /* 2-D: acute, diagonal */
    gm_harminv_mode modes[MAXM];
    size_t nm = 0;
    double dt = 0.0;
    cr_assert_eq(gm_mesh_maxwell_cavity_modes(f.g, &o, &run, MAXM, modes, &nm, &dt, &err), GM_OK,
                 "%s", err.message);
    mm_fixture_free(&f);
    for (size_t j = 0; j < nu; ++j) errs[j][l] = NAN;
    fprintf(stderr, "mesh_maxwell_cavity3d %s h = %.4f: %zu peaks (%zu analytic in band):", name,
            hs[l], nm, in_band);
    cr_expect_leq(nm, in_band, "%s: more peaks than analytic modes at h = %g", name, hs[l]);
    for (size_t i = 0; i < nm; ++i) {
      const double fs = gm_leapfrog_space_frequency(modes[i].frequency, dt);
      size_t best = 0;
      for (size_t j = 1; j < na; ++j)
        if (fabs(ana[j] - fs) < fabs(ana[best] - fs)) best = j;
      const double rel = (fs - ana[best]) / ana[best];
      fprintf(stderr, " %.5f(%+.1e)", fs, rel);
      cr_expect_lt(fabs(rel), 0.05, "%s: spurious peak %.5f at h = %g (nearest analytic %.5f)",
                   name, fs, hs[l], ana[best]);
      for (size_t j = 0; j < nu; ++j)
        if (ana[best] == uniq[j] && !(fabs(errs[j][l]) <= fabs(rel))) errs[j][l] = rel;
    }
    fprintf(stderr, "\n");
  }
  /* Rates: every resonance found on all levels is printed; the median of their rates and the
   * rate of each isolated simple one (no other analytic resonance within 3 %: split degenerate
   * pairs and near-coincident modes are where harminv's peaks can swap or merge) must
   * exceed 1.8. */
  double rates[10];
  size_t tracked = 0, isolated = 0;
  for (size_t j = 0; j < nu; ++j) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    size_t m = 0;
    for (size_t l = 0; l < LEVELS; ++l) {
      if (isnan(errs[j][l])) continue;
      const double x = log(hs[l]), y = log(fabs(errs[j][l]));
      sx += x, sy += y, sxx += x * x, sxy += x * y, ++m;
    }
    if (m < LEVELS) {
      fprintf(stderr, "mesh_maxwell_cavity3d %s f = %.5f (x%d): not found at every level\n",
              name, uniq[j], mult[j]);
      continue;
    }
    const double rate = (m * sxy - sx * sy) / (m * sxx - sx * sx);
    rates[tracked++] = rate;
    int alone = mult[j] == 1;
    for (size_t k = 0; k < na; ++k)
      if (ana[k] != uniq[j] && fabs(ana[k] - uniq[j]) < 0.03 * uniq[j]) alone = 0;
    fprintf(stderr, "mesh_maxwell_cavity3d %s f = %.5f (x%d%s): errors %+.2e %+.2e %+.2e, rate "
            "%.2f\n", name, uniq[j], mult[j], alone ? ", isolated" : "", errs[j][0], errs[j][1],
            errs[j][2], rate);
    if (alone) {
      ++isolated;
      cr_expect_gt(rate, min_rate, "%s f = %.5f: rate %.2f", name, uniq[j], rate);
    }
  }
  cr_assert_geq(tracked, 4, "%s: only %zu resonances found on every level", name, tracked);
  cr_expect_geq(isolated, 1, "%s: no isolated simple resonance tracked", name);
  for (size_t i = 1; i < tracked; ++i) /* insertion sort */
    for (size_t k = i; k > 0 && rates[k] < rates[k - 1]; --k) {
      const double t = rates[k];
      rates[k] = rates[k - 1];
      rates[k - 1] = t;
    }
  const double median = tracked % 2 ? rates[tracked / 2]
                                    : 0.5 * (rates[tracked / 2 - 1] + rates[tracked / 2]);
  fprintf(stderr, "mesh_maxwell_cavity3d %s: median rate %.2f over %zu resonances\n", name,
          median, tracked);
  cr_expect_gt(median, 1.8, "%s: median rate %.2f", name, median);
}

static void box_level(size_t level, mm_fixture *f, double *h) {
  const double lo[3] = {0, 0, 0}, hi[3] = {1.0, 0.75, 0.5};
  const size_t n = 4 * (level + 1);
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_bcc(lo, hi, n, n * 3 / 4, n / 2, 1, &f->mesh, &err), GM_OK, "%s",
               err.message);
  mm_fixture_finish(f);
  *h = 1.0 / (double)n;
}

Test(mesh_maxwell_cavity3d, box_bcc_whitney, .timeout = 240) {
  const double L[3] = {1.0, 0.75, 0.5};
  double ana[MAXM];
  size_t na = 0;
  gm_error err = {{0}};
  cr_assert_eq(gm_cavity_box_resonances(L, 2.5, MAXM, ana, &na, &err), GM_OK, "%s", err.message);
  study("box", box_level, ana, na, 150.0, 1.8);
}

/* h: the mean edge length of the Gmsh mesh (sizes 0.14, 0.1, 0.07 asked of Gmsh). */
static void cylinder_level(size_t level, mm_fixture *f, double *h) {
  char path[512];
  snprintf(path, sizeof path, "%s/examples/cavity_cylinder_%zu.msh", GM_SOURCE_DIR, level + 1);
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_read(path, &f->mesh, &err), GM_OK, "%s", err.message);
  mm_fixture_finish(f);
  const size_t ne = gm_complex_count(f->cx, 1);
  const double *len = gm_geometry_primal_volumes(f->g, 1);
  double s = 0.0;
  for (size_t e = 0; e < ne; ++e) s += len[e];
  *h = s / (double)ne;
}

Test(mesh_maxwell_cavity3d, cylinder_gmsh_whitney, .timeout = 240) {
  double ana[MAXM];
  size_t na = 0;
  gm_error err = {{0}};
  cr_assert_eq(gm_cavity_cylinder_resonances(0.5, 0.6, 2.0, MAXM, ana, &na, &err), GM_OK, "%s",
               err.message);
  study("cylinder", cylinder_level, ana, na, 150.0, 1.8);
}

/* 2-D TE (B_z on triangles) in [0,1]×[0,0.7], acute meshes (well-centred: diagonal star) of
 * 10, 20, 40 columns and 8, 16, 32 rows (self-similar); f = ½√(m² + (n/0.7)²), (m,n) ≠ 0. */
static void rect_level(size_t level, mm_fixture *f, double *h) {
  const size_t n = 10u << level;
  *f = mm_rect(n, 0.7, 0.0, 1);
  *h = 1.0 / (double)n;
}

Test(mesh_maxwell_cavity3d, rect_2d_acute, .timeout = 120) {
  double ana[MAXM];
  size_t na = 0;
  for (int m = 0; m < 8; ++m)
    for (int n = 0; n < 8; ++n) {
      if (m == 0 && n == 0) continue;
      const double fm = 0.5 * sqrt(m * m + n * n / 0.49);
      if (fm < 2.5) ana[na++] = fm;
    }
  for (size_t i = 1; i < na; ++i)
    for (size_t k = i; k > 0 && ana[k] < ana[k - 1]; --k) {
      const double t = ana[k];
      ana[k] = ana[k - 1];
      ana[k - 1] = t;
    }
  /* t = 400 (cheap in 2-D: a longer record, sharper peaks). The (2,0) resonance approaches
   * second order from below (pairwise rates 1.74, 1.84 at 10-20-40 columns; 1.93 at 20-40-80
   * columns, where the lowest two hit a floor of ~5e-5), so isolated resonances are held to
   * 1.75 here and the median to 1.8. */
  study("rect-2d", rect_level, ana, na, 400.0, 1.75);
}
