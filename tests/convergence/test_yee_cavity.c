/* Rectangular PEC cavities in 2-D (TM) and 3-D: the first ten resonant frequencies, extracted
 * with harminv from probe signals after a broadband pulse, equal the exact frequencies of the
 * discrete Yee cavity (Taflove & Hagness eq. 4.12 with k = mπ/L) and converge to the analytic
 * ones f = ½ |(m/Lx, n/Ly, p/Lz)| at second order over four resolutions (seed 000 E5 on the
 * uniform grid). */
#include <stdio.h>

#include "yee_util.h"

typedef struct mode {
  int m[3];
  double f;
} mode;

static int by_f(const void *a, const void *b) {
  const double fa = ((const mode *)a)->f, fb = ((const mode *)b)->f;
  return (fa > fb) - (fa < fb);
}

/* The lowest n_want distinct analytic frequencies of the PEC box (TM_mn in 2-D: m, n >= 1; 3-D:
 * at most one index zero); modes that share a frequency are listed once. */
static size_t analytic_modes(size_t axes, const double *len, mode *out, size_t n_want) {
  mode all[4096];
  size_t n = 0;
  const int top = 8;
  for (int i = 0; i <= top; ++i)
    for (int j = 0; j <= top; ++j)
      for (int k = 0; k <= (axes == 3 ? top : 0); ++k) {
        const int zeros = (i == 0) + (j == 0) + (axes == 3 ? (k == 0) : 0);
        if (axes == 2 && zeros > 0) continue;
        if (axes == 3 && zeros > 1) continue;
        const double q[3] = {i / len[0], j / len[1], axes == 3 ? k / len[2] : 0.0};
        all[n].m[0] = i;
        all[n].m[1] = j;
        all[n].m[2] = k;
        all[n].f = 0.5 * sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        ++n;
      }
  qsort(all, n, sizeof *all, by_f);
  size_t m = 0;
  for (size_t i = 0; i < n && m < n_want; ++i)
    if (m == 0 || all[i].f > out[m - 1].f * (1.0 + 1e-9)) out[m++] = all[i];
  return m;
}

typedef struct cavity_result {
  double f_numeric[10], f_discrete[10], f_analytic[10];
} cavity_result;

static void run_cavity(gm_yee_dim dim, const double *len, size_t N, double T, cavity_result *res) {
  const size_t axes = gm_yee_dim_axes(dim);
  const double h = 1.0 / (double)N;
  gm_yee_grid g = {dim, {N, (size_t)lround(len[1] * N), axes == 3 ? (size_t)lround(len[2] * N) : 1},
                   {h, h, h}, {0, 0, 0}};
  gm_yee_options o = gm_yee_defaults();
  o.courant = 0.5; /* below the limit the dispersion error is larger and cleaner to fit */
  o.n_threads = 1;
  gm_yee *s = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_create(&g, NULL, &o, &s, &err), GM_OK, "%s", err.message);
  const double dt = gm_yee_dt(s);
  /* a Gaussian pulse centred in the band of the first ten modes */
  const double f0 = axes == 3 ? 1.2 : 1.65, df = axes == 3 ? 0.3 : 0.45;
  const double w = 1.0 / (2.0 * YEE_TEST_PI * df);
  const gm_waveform pulse = {GM_WAVE_GAUSSIAN, 1.0, f0, w, 6.0 * w, 0.0, NULL, NULL};
  const double src[3][3] = {{0.377, 0.291, 0.213}, {0.613, 0.433, 0.341}, {0.211, 0.571, 0.389}};
  const double prb[3][3] = {{0.713, 0.217, 0.443}, {0.291, 0.387, 0.177}, {0.371, 0.611, 0.269}};
  const int comps = 3; /* 3-D: Ex, Ey, Ez; 2-D: three Ez */
  for (int c = 0; c < comps; ++c) {
    gm_point_source ps = {axes == 3 ? (gm_yee_component)c : GM_EZ, {0}, GM_SOURCE_SOFT, pulse};
    for (int a = 0; a < 3; ++a) ps.x[a] = src[c][a] * len[a];
    cr_assert_eq(gm_yee_add_point_source(s, &ps, NULL), GM_OK, "%s", gm_yee_errmsg(s));
  }
  /* let the pulse end, then record */
  cr_assert_eq(gm_yee_advance(s, (size_t)ceil(12.0 * w / dt)), GM_OK);
  const size_t n = (size_t)(T / dt);
  for (int c = 0; c < comps; ++c) {
    double x[3];
    for (int a = 0; a < 3; ++a) x[a] = prb[c][a] * len[a];
    cr_assert_eq(gm_yee_add_probe(s, axes == 3 ? (gm_yee_component)c : GM_EZ, x, n, NULL), GM_OK);
  }
  cr_assert_eq(gm_yee_advance(s, n), GM_OK, "%s", gm_yee_errmsg(s));
  mode want[10];
  cr_assert_eq(analytic_modes(axes, len, want, 10), 10);
  const double f_lo = 0.8 * want[0].f, f_hi = 1.25 * want[9].f;
  for (int q = 0; q < 10; ++q) {
    double k[3], hh[3] = {h, h, h};
    for (int a = 0; a < 3; ++a) k[a] = want[q].m[a] * YEE_TEST_PI / len[a];
    res->f_analytic[q] = want[q].f;
    res->f_discrete[q] = yee_discrete_frequency(axes, k, hh, dt);
    res->f_numeric[q] = INFINITY;
  }
  /* harminv on each probe signal and on their sum; for each mode keep the estimate that
   * harminv itself rates best (smallest error figure) within 0.2 % of the mode */
  double best_err[10];
  for (int q = 0; q < 10; ++q) best_err[q] = INFINITY;
  double *sig = calloc(n, sizeof(double));
  for (int which = 0; which <= comps; ++which) {
    memset(sig, 0, n * sizeof(double));
    for (int c = 0; c < comps; ++c) {
      if (which < comps && c != which) continue;
      size_t m;
      const double *v;
      gm_yee_probe_samples(s, (size_t)c, &m, NULL, &v, NULL);
      cr_assert_eq(m, n);
      for (size_t i = 0; i < n; ++i) sig[i] += v[i];
    }
    /* The pulse leaves a little charge (its spectrum at f = 0), i.e. a static field: the
     * first difference removes that constant exactly and keeps every frequency. */
    for (size_t i = 0; i + 1 < n; ++i) sig[i] = sig[i + 1] - sig[i];
    gm_harminv_mode found[300];
    size_t n_found = 0;
    cr_assert_eq(gm_harminv(n - 1, sig, NULL, dt, f_lo, f_hi, 0, 300, found, &n_found, &err),
                 GM_OK, "%s", err.message);
    for (int q = 0; q < 10; ++q)
      for (size_t i = 0; i < n_found; ++i)
        if (fabs(found[i].frequency - res->f_discrete[q]) < 2e-3 * res->f_discrete[q] &&
            found[i].error < best_err[q]) {
          best_err[q] = found[i].error;
          res->f_numeric[q] = found[i].frequency;
        }
  }
  free(sig);
  gm_yee_free(s);
}

static double fit_rate(const size_t *N, const double *e) {
  /* least-squares slope of log error against log h */
  double mx = 0, my = 0, sxy = 0, sxx = 0;
  for (int l = 0; l < 4; ++l) {
    mx += log(1.0 / (double)N[l]) / 4;
    my += log(e[l]) / 4;
  }
  for (int l = 0; l < 4; ++l) {
    const double dx = log(1.0 / (double)N[l]) - mx;
    sxy += dx * (log(e[l]) - my);
    sxx += dx * dx;
  }
  return sxy / sxx;
}

static void cavity_convergence(gm_yee_dim dim, const double *len, const size_t *N, double T,
                               double discrete_tol) {
  cavity_result r[4];
  for (int l = 0; l < 4; ++l) run_cavity(dim, len, N[l], T, &r[l]);
  double mean[4] = {0, 0, 0, 0}, worst = 0.0;
  for (int q = 0; q < 10; ++q) {
    double e[4], worst_disc = 0.0;
    for (int l = 0; l < 4; ++l) {
      const double d = fabs(r[l].f_numeric[q] - r[l].f_discrete[q]) / r[l].f_discrete[q];
      worst_disc = fmax(worst_disc, d);
      e[l] = fabs(r[l].f_numeric[q] - r[l].f_analytic[q]) / r[l].f_analytic[q];
      mean[l] += e[l] / 10.0;
    }
    worst = fmax(worst, worst_disc);
    cr_log_info("%s mode %d: f = %.6f; |harminv - discrete Yee| / f <= %.2e; error vs analytic "
                "%.3e %.3e %.3e %.3e (rate %.3f)",
                dim == GM_YEE_3D ? "3-D" : "2-D", q + 1, r[0].f_analytic[q], worst_disc, e[0], e[1],
                e[2], e[3], fit_rate(N, e));
    cr_assert_lt(worst_disc, discrete_tol, "mode %d: harminv %.10f vs discrete Yee %.10f", q + 1,
                 r[3].f_numeric[q], r[3].f_discrete[q]);
  }
  const double rate = fit_rate(N, mean);
  cr_log_info("%s: mean relative error of the ten modes %.3e %.3e %.3e %.3e: rate %.3f; worst "
              "harminv - discrete %.2e",
              dim == GM_YEE_3D ? "3-D" : "2-D", mean[0], mean[1], mean[2], mean[3], rate, worst);
  cr_assert(fabs(rate - 2.0) <= 0.1, "rate %.3f", rate);
}

Test(yee_cavity, tm_2d_first_ten_modes) {
  const double len[3] = {1.0, 0.7, 1.0};
  const size_t N[4] = {20, 30, 40, 60};
  cavity_convergence(GM_YEE_2D_TM, len, N, 200.0, 1e-4);
}

Test(yee_cavity, box_3d_first_ten_modes) {
  const double len[3] = {1.0, 0.8, 0.6};
  const size_t N[4] = {15, 20, 25, 30};
  cavity_convergence(GM_YEE_3D, len, N, 150.0, 1e-4);
}
