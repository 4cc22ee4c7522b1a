/* The spectral Hodge star of seed 000 §3.3.4 against the diagonal star on the 1-D periodic wave
 * equation u_tt = ⋆d⋆d u with d topological: the symbol of ⋆d⋆d on every Fourier mode (the
 * spectral star's is −κ² to round-off, the diagonal's −(2/h)² sin²(κh/2)), and the phase of a
 * travelling mode after leapfrog steps against the exact wave. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "geomint/geomint.h"

#define TWO_PI 6.283185307179586

static gm_wave1d *solver(gm_hodge_kind k, size_t n, double dt, long m, double omega_d) {
  double L = TWO_PI, h = L / (double)n, kap = (double)m;
  double *u = malloc(n * sizeof *u), *v = malloc(n * sizeof *v);
  /* the scheme's forward mode: u = cos κx, v = (sin(ω_dΔt)/Δt) sin κx (kick–drift–kick) */
  for (size_t j = 0; j < n; j++) {
    u[j] = cos(kap * (double)j * h);
    v[j] = sin(omega_d * dt) / dt * sin(kap * (double)j * h);
  }
  gm_wave1d *w = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_wave1d_create(n, L, k, dt, u, v, &w, &err), GM_OK, "%s", err.message);
  free(u);
  free(v);
  return w;
}

Test(pde_spectral_star, symbol_of_star_d_star_d) {
  size_t n = 64;
  double L = TWO_PI, worst_spec = 0.0, worst_diag_vs_own = 0.0, diag_err_m8 = 0.0;
  double *u = malloc(n * sizeof *u), *lu = malloc(n * sizeof *lu), *v = calloc(n, sizeof *v);
  gm_error err = {{0}};
  for (int kind = 0; kind < 2; kind++) {
    gm_wave1d *w = NULL;
    cr_assert_eq(gm_wave1d_create(n, L, (gm_hodge_kind)kind, 0.01, v, v, &w, &err), GM_OK);
    for (long m = 1; m < (long)n / 2; m++) {
      for (size_t j = 0; j < n; j++) u[j] = cos((double)m * L * (double)j / (double)n + 0.3);
      gm_wave1d_laplacian(w, u, lu);
      double num = 0.0, den = 0.0, res = 0.0;
      for (size_t j = 0; j < n; j++) {
        num += u[j] * lu[j];
        den += u[j] * u[j];
      }
      double sym = num / den, own = gm_wave1d_symbol((gm_hodge_kind)kind, n, L, m);
      for (size_t j = 0; j < n; j++) res = fmax(res, fabs(lu[j] - own * u[j]));
      double rel_exact = fabs(sym + (double)(m * m)) / (double)(m * m);
      if (kind == GM_HODGE_SPECTRAL) worst_spec = fmax(worst_spec, rel_exact);
      if (kind == GM_HODGE_DIAGONAL) {
        worst_diag_vs_own = fmax(worst_diag_vs_own, res / fabs(own));
        if (m == 8) diag_err_m8 = rel_exact;
      }
    }
    gm_wave1d_free(w);
  }
  cr_log_info("symbol of *d*d on N = 64, m = 1..31: spectral star vs -k^2 worst relative %.2e; "
              "diagonal star vs -(2/h)^2 sin^2(kh/2) %.2e, vs -k^2 at m = 8: %.3e "
              "((kh)^2/12 = %.3e)",
              worst_spec, worst_diag_vs_own, diag_err_m8,
              pow(8.0 * TWO_PI / 64.0, 2) / 12.0);
  cr_expect_leq(worst_spec, 1e-12, "spectral symbol %.3e", worst_spec);
  cr_expect_leq(worst_diag_vs_own, 1e-12, "diagonal symbol %.3e", worst_diag_vs_own);
  cr_expect(diag_err_m8 > 1e-2, "diagonal dispersion error at m = 8: %.3e", diag_err_m8);
  free(u);
  free(lu);
  free(v);
}

/* The phase of ⟨u, cos κx⟩ + i⟨u, sin κx⟩ accumulated over the steps: ω = φ/T. */
static double measured_omega(gm_wave1d *w, size_t n, long m, size_t steps, double dt) {
  double phase = 0.0, pc = 1.0, ps = 0.0;
  gm_error err = {{0}};
  for (size_t k = 0; k < steps; k++) {
    cr_assert_eq(gm_wave1d_advance(w, 1, &err), GM_OK, "%s", err.message);
    const double *u = gm_wave1d_u(w);
    double c = 0.0, s = 0.0;
    for (size_t j = 0; j < n; j++) {
      double x = TWO_PI * (double)j / (double)n;
      c += u[j] * cos((double)m * x);
      s += u[j] * sin((double)m * x);
    }
    phase += atan2(s * pc - c * ps, c * pc + s * ps);
    pc = c;
    ps = s;
  }
  return phase / ((double)steps * dt);
}

Test(pde_spectral_star, phase_error_of_a_resolved_mode) {
  /* N = 64 on [0, 2π), mode m = 8 (8 points a wavelength), Δt = h/10, T ≈ 10 */
  size_t n = 64, steps = 1019;
  long m = 8;
  double h = TWO_PI / (double)n, dt = h / 10.0, k = (double)m;
  double om_leap = 2.0 / dt * asin(0.5 * dt * k); /* leapfrog with the exact symbol */
  double om_diag_pred = 2.0 / dt * asin(dt / h * sin(0.5 * k * h));
  gm_wave1d *spec = solver(GM_HODGE_SPECTRAL, n, dt, m, om_leap);
  gm_wave1d *diag = solver(GM_HODGE_DIAGONAL, n, dt, m, om_diag_pred);
  double T = (double)steps * dt;
  double om_s = measured_omega(spec, n, m, steps, dt), om_d = measured_omega(diag, n, m, steps, dt);
  double spatial_s = fabs(om_s - om_leap) * T, spatial_d = fabs(om_d - om_leap) * T;
  cr_log_info("mode m = 8, N = 64, dt = h/10, T = %.3f: phase error vs the exact wave: spectral "
              "%.3e rad, diagonal %.3e rad; vs leapfrog with the exact symbol (the spatial part): "
              "spectral %.2e rad, diagonal %.3e rad",
              T, fabs(om_s - k) * T, fabs(om_d - k) * T, spatial_s, spatial_d);
  cr_expect_leq(spatial_s, 1e-11, "spectral spatial phase error %.3e", spatial_s);
  cr_expect_geq(spatial_d / fmax(spatial_s, 1e-300), 1e8, "ratio");
  cr_expect_leq(fabs(om_s - k) * 50.0, fabs(om_d - k), "total: spectral 50x better");
  double e0 = gm_wave1d_energy(spec);
  cr_expect(isfinite(e0));
  gm_wave1d_free(spec);
  gm_wave1d_free(diag);
}

Test(pde_spectral_star, cfl_refused) {
  size_t n = 16;
  double u[16] = {0}, h = TWO_PI / 16.0;
  gm_wave1d *w = NULL;
  gm_error err = {{0}};
  cr_expect_eq(gm_wave1d_create(n, TWO_PI, GM_HODGE_SPECTRAL, 0.7 * h, u, u, &w, &err), GM_EINVAL);
  cr_expect_eq(gm_wave1d_create(n, TWO_PI, GM_HODGE_DIAGONAL, 0.7 * h, u, u, &w, &err), GM_OK);
  gm_wave1d_free(w);
  cr_expect_eq(gm_wave1d_create(15, TWO_PI, GM_HODGE_DIAGONAL, 0.1, u, u, &w, &err), GM_EINVAL);
}
