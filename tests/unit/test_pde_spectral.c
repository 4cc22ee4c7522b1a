/* Bad input of the spectral pde solvers (Schrödinger, wave with a Hodge star): errors with
 * messages, never a silent blow-up. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "geomint/geomint.h"

static double V[64], psi[128];

static gm_status make(size_t n, double dt, gm_schrodinger_scheme sc, gm_error *err) {
  gm_schrodinger_options o = gm_schrodinger_options_defaults();
  o.scheme = sc;
  o.dt = dt;
  gm_schrodinger *s = NULL;
  gm_status st = gm_schrodinger_create(n, -10.0, 20.0, V, psi, &o, &s, err);
  gm_schrodinger_free(s);
  return st;
}

Test(pde_spectral, schrodinger_bad_input) {
  for (int j = 0; j < 64; j++) {
    double x = -10.0 + 20.0 * j / 64.0;
    V[j] = 0.5 * x * x;
    psi[2 * j] = exp(-0.5 * x * x);
    psi[2 * j + 1] = 0.0;
  }
  gm_error err = {{0}};
  cr_expect_eq(make(64, 0.01, GM_SCHRODINGER_VI, &err), GM_OK, "%s", err.message);
  cr_expect_eq(make(63, 0.01, GM_SCHRODINGER_VI, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "even") != NULL, "%s", err.message);
  cr_expect_eq(make(64, 0.0, GM_SCHRODINGER_SPLIT_STEP, &err), GM_EINVAL);
  cr_expect_eq(make(64, -0.1, GM_SCHRODINGER_VI, &err), GM_EINVAL);
  cr_expect_eq(make(64, NAN, GM_SCHRODINGER_VI, &err), GM_EINVAL);
  /* the VI's stability bound dt·ρ(H) < √3 (ρ ≈ 100.5 here); split-step has none */
  cr_expect_eq(make(64, 0.02, GM_SCHRODINGER_VI, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "sqrt(3)") != NULL, "%s", err.message);
  cr_expect_eq(make(64, 0.02, GM_SCHRODINGER_SPLIT_STEP, &err), GM_OK);
  psi[10] = NAN;
  cr_expect_eq(make(64, 0.01, GM_SCHRODINGER_VI, &err), GM_EDOMAIN);
  cr_expect(strstr(err.message, "point 5") != NULL, "%s", err.message);
  psi[10] = 0.0;
  V[3] = INFINITY;
  cr_expect_eq(make(64, 0.01, GM_SCHRODINGER_SPLIT_STEP, &err), GM_EDOMAIN);
  V[3] = 0.0;
}

Test(pde_spectral, schrodinger_free_particle_is_one_iteration) {
  /* V = 0: the Fourier preconditioner is the exact inverse */
  size_t n = 32;
  double v0[32] = {0}, p0[64];
  for (size_t j = 0; j < n; j++) {
    double x = 2.0 * 3.141592653589793 * (double)j / (double)n;
    p0[2 * j] = cos(3.0 * x);
    p0[2 * j + 1] = sin(3.0 * x);
  }
  gm_schrodinger_options o = gm_schrodinger_options_defaults();
  o.dt = 0.01;
  gm_schrodinger *s = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_schrodinger_create(n, 0.0, 2.0 * 3.141592653589793, v0, p0, &o, &s, &err),
               GM_OK, "%s", err.message);
  cr_assert_eq(gm_schrodinger_advance(s, 51, &err), GM_OK);
  /* 50 VI steps, each converging in <= 2 iterations (the second confirms the first) */
  cr_expect_leq(gm_schrodinger_iterations(s), 100u, "%zu", gm_schrodinger_iterations(s));
  /* plane wave e^{i3x}: E = 4.5, the VI's phase per step φ with sin φ/(2 + cos φ) = ΔtE/3 */
  double c[2];
  gm_schrodinger_overlap(s, p0, c);
  double om = -atan2(c[1], c[0]) / (51 * 0.01);
  double E = gm_schrodinger_energy_from_frequency(GM_SCHRODINGER_VI, om, 0.01);
  cr_expect(fabs(E - 4.5) < 1e-11, "E = %.15f", E);
  gm_schrodinger_free(s);
}

Test(pde_spectral, wave1d_bad_input) {
  double u[16] = {0};
  gm_wave1d *w = NULL;
  gm_error err = {{0}};
  cr_expect_eq(gm_wave1d_create(16, 1.0, GM_HODGE_SPECTRAL, 0.0, u, u, &w, &err), GM_EINVAL);
  cr_expect_eq(gm_wave1d_create(16, 1.0, GM_HODGE_SPECTRAL, 1.0 / 16, u, u, &w, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "CFL") != NULL, "%s", err.message);
  cr_expect_eq(gm_wave1d_create(16, -1.0, GM_HODGE_DIAGONAL, 0.01, u, u, &w, &err), GM_EINVAL);
  u[2] = NAN;
  cr_expect_eq(gm_wave1d_create(16, 1.0, GM_HODGE_DIAGONAL, 0.01, u, u, &w, &err), GM_EDOMAIN);
  gm_schrodinger_free(NULL);
  gm_wave1d_free(NULL);
  gm_tentvi_free(NULL);
}

static double quartic(double u, const void *c) {
  (void)c;
  return 1e3 * u * u * u * u;
}
static double dquartic(double u, const void *c) {
  (void)c;
  return 4e3 * u * u * u;
}

Test(pde_spectral, tentvi_blow_up_is_an_error) {
  /* V = 1e3 u⁴ from u = 10 with Δt = Δx = 0.1: the explicit force overflows within steps */
  double u[16];
  for (int i = 0; i < 16; i++) u[i] = 10.0 + (i % 2);
  gm_tentvi *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_tentvi_create(16, 0.0, 0.1, 0.0, 0.1, quartic, dquartic, NULL, NULL, u, u, &m,
                                &err),
               GM_OK, "%s", err.message);
  gm_status st = gm_tentvi_advance(m, 1000, &err);
  cr_expect_eq(st, GM_EDOMAIN, "status %d", (int)st);
  cr_expect(strstr(err.message, "non-finite value at step") != NULL, "%s", err.message);
  gm_tentvi_free(m);
}
