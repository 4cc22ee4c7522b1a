/* A geometry the seed's experiments do not cover: the lid-driven cavity at Re = 100 (unit square,
 * top wall moving at 1, ν = 0.01, seed scheme), with a scalar (θ = 1 on the lid, 0 on the
 * bottom, zero flux on the sides, κ = 0.01), run to t = 20 (steady). Against Ghia, Ghia & Shin
 * (J. Comput. Phys. 48 (1982) 387–411, Table III, Re = 100): primary vortex ψ = −0.103423 at
 * (0.6172, 0.7344). Also: total vorticity = ∮ u·t ds = −1 exactly (Stokes on the dual cells),
 * ‖δω‖∞ at round-off, θ within its boundary values (maximum principle). */
#include "../fluids_util.h"

static void cavity(size_t n, double *psi_min, double *xc, double *yc, double *vort, double *div,
                   double *th_lo, double *th_hi) {
  fl_fixture fx = fl_rect(1.0, 1.0, n);
  gm_fluid_bc bc[4];
  memset(bc, 0, sizeof bc);
  const char *names[4] = {"bottom", "right", "top", "left"};
  for (int k = 0; k < 4; ++k) {
    bc[k].group = names[k];
    bc[k].kind = GM_FLUID_WALL;
  }
  bc[2].velocity[0] = 1.0;
  bc[2].scalar = GM_SCALAR_DIRICHLET;
  bc[2].scalar_value = 1.0;
  bc[0].scalar = GM_SCALAR_DIRICHLET;
  gm_fluid_options o = gm_fluid_defaults();
  o.nu = 0.01;
  o.kappa = 0.01;
  o.dt = 0.01;
  gm_fluid *f = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_fluid_create(fx.mesh, fx.groups, 4, bc, &o, &f, &err), GM_OK, "%s", err.message);
  *div = 0.0;
  gm_fluid_diagnostics d;
  for (int s = 0; s < 20; ++s) { /* t = 20 in chunks of 100 steps, δω checked at each */
    cr_assert_eq(gm_fluid_advance(f, 100), GM_OK, "%s", gm_fluid_errmsg(f));
    gm_fluid_diagnose(f, &d);
    *div = fmax(*div, d.div_max);
  }
  const double *psi = gm_fluid_psi(f), *x = gm_complex_coordinates(gm_fluid_complex(f));
  const double *th = gm_fluid_theta(f);
  size_t best = 0, nv = gm_fluid_n_vertices(f);
  *th_lo = INFINITY;
  *th_hi = -INFINITY;
  for (size_t v = 0; v < nv; ++v) {
    if (psi[v] < psi[best]) best = v;
    *th_lo = fmin(*th_lo, th[v]);
    *th_hi = fmax(*th_hi, th[v]);
  }
  *psi_min = psi[best];
  *xc = x[2 * best];
  *yc = x[2 * best + 1];
  *vort = d.total_vorticity;
  gm_fluid_free(f);
  fl_free(&fx);
}

Test(fluids_cavity, lid_driven_re100_against_ghia, .timeout = 120) {
  const double ghia = -0.103423, gx = 0.6172, gy = 0.7344;
  /* measured |psi_min − Ghia|: 1.104e-3 (n = 32), 4.53e-4 (48); (2.07e-4 at n = 64) */
  const size_t ns[2] = {32, 48};
  const double want[2] = {1.104e-3, 4.53e-4};
  for (int i = 0; i < 2; ++i) {
    double p, xc, yc, vort, div, lo, hi;
    cavity(ns[i], &p, &xc, &yc, &vort, &div, &lo, &hi);
    cr_log_info("cavity Re = 100, n = %zu: psi_min %.6f at (%.4f, %.4f) (Ghia -0.103423 at "
                "(0.6172, 0.7344)), total vorticity %.15f, div %.1e, theta in [%.3e, %.15f]",
                ns[i], p, xc, yc, vort, div, lo, hi);
    cr_assert_leq(fabs(p - ghia), 1.5 * want[i], "n = %zu: psi_min %.6f", ns[i], p);
    cr_assert_leq(hypot(xc - gx, yc - gy), 1.5 / (double)ns[i], "vortex centre (%.4f, %.4f)", xc,
                  yc);
    cr_assert_leq(fabs(vort + 1.0), 1e-13, "total vorticity %.17g", vort);
    cr_assert_leq(div, 1e-14, "div %.3e", div);
    cr_assert(lo >= -1e-12 && hi <= 1.0 + 1e-12, "theta in [%.3e, %.17g]", lo, hi);
  }
}
