/* PEC cavities on simplicial meshes (seed 000 §3.4.2): harminv frequencies of a probe signal
 * against the analytic resonances f = ½ |(m/a, n/b, p/c)|, the rate of convergence with the
 * mesh size, and no spurious modes below the 10th resonance (every well-resolved peak lies
 * within 2% of an analytic one).
 *   2-D TE (Bz on triangles, E on edges) in [0,1]×[0,0.7], acute meshes, diagonal star:
 *     modes (m, n) ≠ (0, 0).
 *   3-D [0,1]×[0,0.8]×[0,0.6], Kuhn tetrahedra (not well-centred: the diagonal star has zero
 *     entries), Whitney star: modes with at least two of m, n, p non-zero. */
#include "../mesh_maxwell_util.h"

#define MAX_ANALYTIC 64

static size_t analytic(int dim, double *f) {
  const double L[3] = {1.0, dim == 2 ? 0.7 : 0.8, 0.6};
  size_t k = 0;
  for (int m = 0; m < 6; ++m)
    for (int n = 0; n < 6; ++n)
      for (int p = 0; p < (dim == 3 ? 6 : 1); ++p) {
        const int nz = (m > 0) + (n > 0) + (p > 0);
        if (dim == 2 ? nz < 1 : nz < 2) continue;
        const double a = m / L[0], b = n / L[1], c = p / L[2];
        f[k++] = 0.5 * sqrt(a * a + b * b + c * c);
      }
  for (size_t i = 1; i < k; ++i) /* insertion sort */
    for (size_t j = i; j > 0 && f[j] < f[j - 1]; --j) { double t = f[j]; f[j] = f[j - 1]; f[j - 1] = t; }
  return k;
}

static double nearest(const double *fa, size_t na, double f) {
  double best = fa[0];
  for (size_t i = 1; i < na; ++i) if (fabs(fa[i] - f) < fabs(best - f)) best = fa[i];
  return best;
}

/* Run the cavity and return the well-resolved modes in [f_lo, f_hi]. */
static size_t cavity(int dim, size_t nx, double t_end, double f_lo, double f_hi, double *freq,
                     double *amp) {
  mm_fixture f = dim == 2 ? mm_rect(nx, 0.7, 0.0, 1) : mm_box(nx);
  gm_error err = {{0}};
  gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
  if (dim == 3) o.star = GM_MESH_STAR_WHITNEY;
  gm_mesh_maxwell *s = NULL;
  cr_assert_eq(gm_mesh_maxwell_create(f.g, NULL, NULL, &o, &s, &err), GM_OK, "%s", err.message);
  const size_t nf = gm_complex_count(f.cx, 2);
  const double dt = gm_mesh_maxwell_dt(s);
  if (dim == 2) { /* a Gaussian bump of Bz away from the symmetry lines */
    double *B = calloc(nf, sizeof(double));
    const double *c = gm_geometry_centers(f.g, 2), *a = gm_geometry_primal_volumes(f.g, 2);
    for (size_t k = 0; k < nf; ++k) {
      const double dx = c[2 * k] - 0.3, dy = c[2 * k + 1] - 0.25;
      B[k] = a[k] * exp(-(dx * dx + dy * dy) / (2 * 0.08 * 0.08));
    }
    cr_assert_eq(gm_mesh_maxwell_set_fields(s, NULL, B), GM_OK);
    free(B);
  } else { /* a Gaussian current pulse on one edge */
    const double x[3] = {0.3, 0.27, 0.19};
    const size_t e = mm_nearest_interior_edge(&f, x);
    const gm_waveform w = {GM_WAVE_GAUSSIAN, 1.0, 0.0, 0.12, 0.6, 0.0, NULL, NULL};
    cr_assert_eq(gm_mesh_maxwell_add_current(s, 1, &e, NULL, &w, NULL), GM_OK);
  }
  const size_t steps = (size_t)(t_end / dt);
  const double xp[3] = {0.61, 0.37, 0.29};
  cr_assert_eq(gm_mesh_maxwell_add_probe(s, dim == 2 ? GM_HZ : GM_EY, xp, steps, NULL), GM_OK,
               "%s", gm_mesh_maxwell_errmsg(s));
  cr_assert_eq(gm_mesh_maxwell_advance(s, steps), GM_OK, "%s", gm_mesh_maxwell_errmsg(s));
  size_t n;
  const double *v;
  gm_mesh_maxwell_probe_samples(s, 0, &n, NULL, &v);
  size_t count = 0;
  double peak = 0.0;
  gm_harminv_mode modes[64];
  const double width = 0.5;
  for (double lo = f_lo; lo < f_hi - 1e-9; lo += width) {
    size_t nm = 0;
    const double hi = fmin(lo + width, f_hi);
    cr_assert_eq(gm_harminv(n, v, NULL, dt, lo, hi, 0, 64, modes, &nm, &err), GM_OK, "%s",
                 err.message);
    for (size_t i = 0; i < nm; ++i) {
      if (modes[i].error > 1e-3) continue;
      freq[count] = modes[i].frequency;
      amp[count++] = modes[i].amplitude;
      peak = fmax(peak, modes[i].amplitude);
    }
  }
  size_t kept = 0; /* drop peaks below 1% of the largest: harminv's noise floor */
  for (size_t i = 0; i < count; ++i)
    if (amp[i] >= 0.01 * peak) { freq[kept] = freq[i]; amp[kept++] = amp[i]; }
  gm_mesh_maxwell_free(s);
  mm_fixture_free(&f);
  return kept;
}

/* Each mode that both meshes resolve, as measured (rate between the coarsest and finest mesh,
 * relative error on the finest); the test holds every one to rate − 0.3 and 1.5 × the error.
 * NAN rate: excluded from the rate, with the reason:
 *   2-D f = 0.71429, the (0, 1) mode, varies along y only: the meshes are not nested and their
 *   row count is rounded to keep the triangles near equilateral, so the triangles' aspect in y
 *   changes from mesh to mesh and its error (1.49e-3, 1.44e-3, 2.43e-3 on nx 10, 20, 40) follows
 *   that distortion, not h.
 *   3-D f = 1.15545 (1, 1, 1) and f = 1.44398: their errors grow from nx 5 to 10 (7.53e-4 →
 *   3.95e-3, 3.26e-3 → 4.36e-3); two levels of a mesh this coarse cannot show why (a
 *   neighbouring discrete mode can be the nearest peak on nx 5): not understood, so only their
 *   finest error is held. */
typedef struct expected_mode {
  int dim;
  double f, rate, finest;
} expected_mode;

static const expected_mode expected[] = {
    {2, 0.50000, 3.60, 3.89e-6},  {2, 0.71429, NAN, 2.43e-3},  {2, 0.87190, 0.88, 6.44e-4},
    {2, 1.00000, 1.38, 1.67e-4},  {2, 1.22890, 2.01, 2.39e-4},  {2, 1.42857, 2.07, 3.60e-4},
    {2, 1.50000, 1.80, 2.51e-4},  {2, 1.74379, 2.01, 5.15e-4},  {3, 0.97183, 2.10, 1.36e-3},
    {3, 1.15545, NAN, 3.95e-3},   {3, 1.30171, 2.54, 6.38e-4},  {3, 1.44398, NAN, 4.36e-3}};

/* Errors of the resonances below the 10th that both the coarsest and the finest mesh resolve;
 * rates printed. Meshes are not nested (rows are rounded to keep the triangles near
 * equilateral), so single modes can converge erratically: every tracked mode is held to its
 * measured rate and finest error (expected[] above says which are excluded from the rate). */
static void check(int dim, const size_t *nx, size_t levels, double t_end, double tol) {
  double fa[MAX_ANALYTIC * 4];
  const size_t na = analytic(dim, fa);
  const double f_lo = 0.3, f_hi = fa[9] + 0.02; /* through the 10th resonance */
  double err[10][8];
  for (size_t l = 0; l < levels; ++l) {
    double freq[256], amp[256];
    const size_t m = cavity(dim, nx[l], t_end, f_lo, f_hi, freq, amp);
    for (size_t j = 0; j < 10; ++j) err[j][l] = NAN;
    fprintf(stderr, "mesh_maxwell cavity %d-D nx = %zu:", dim, nx[l]);
    for (size_t i = 0; i < m; ++i) {
      const double fn = nearest(fa, na, freq[i]), rel = fabs(freq[i] - fn) / fn;
      fprintf(stderr, " %.5f(%.5f)", freq[i], fn);
      if (l == levels - 1)
        cr_expect_lt(rel, 0.02, "spurious or badly placed mode %.5f (nearest analytic %.5f)",
                     freq[i], fn);
      for (size_t j = 0; j < 10; ++j)
        if (fn == fa[j] && (isnan(err[j][l]) || rel < err[j][l])) err[j][l] = rel;
    }
    fprintf(stderr, "\n");
  }
  size_t tracked = 0;
  for (size_t j = 0; j < 10; ++j) {
    if (isnan(err[j][0]) || isnan(err[j][levels - 1])) continue;
    ++tracked;
    const double rate = log(err[j][0] / err[j][levels - 1]) /
                        log((double)nx[levels - 1] / (double)nx[0]);
    fprintf(stderr, "mesh_maxwell cavity %d-D f = %.5f: relative error %.2e (nx %zu) -> %.2e "
            "(nx %zu), rate %.2f\n", dim, fa[j], err[j][0], nx[0], err[j][levels - 1],
            nx[levels - 1], rate);
    cr_expect_lt(err[j][levels - 1], tol);
    /* every tracked mode against its measured rate and finest error */
    const expected_mode *e = NULL;
    for (size_t k = 0; k < sizeof expected / sizeof *expected; ++k)
      if (expected[k].dim == dim && fabs(expected[k].f - fa[j]) < 1e-4) e = &expected[k];
    cr_expect_not_null(e, "%d-D mode f = %.5f is tracked but has no measured row", dim, fa[j]);
    if (e == NULL) continue;
    cr_expect_lt(err[j][levels - 1], 1.5 * e->finest, "%d-D f = %.5f: finest error %.3e",
                 dim, fa[j], err[j][levels - 1]);
    if (!isnan(e->rate))
      cr_expect_gt(rate, e->rate - 0.3, "%d-D f = %.5f: rate %.2f (measured %.2f)", dim, fa[j],
                   rate, e->rate);
  }
  cr_assert_geq(tracked, dim == 2 ? 8 : 4, "only %zu resonances resolved on both meshes", tracked);
}

Test(mesh_maxwell_cavity, te_2d) {
  const size_t nx[] = {10, 20, 40};
  check(2, nx, 3, 60.0, 5e-3);
}

Test(mesh_maxwell_cavity, box_3d_whitney, .timeout = 120) {
  const size_t nx[] = {5, 10};
  check(3, nx, 2, 50.0, 1e-2);
}
