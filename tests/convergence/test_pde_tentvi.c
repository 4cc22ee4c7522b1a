/* The multisymplectic VI with bilinear tents (seed 001 §5.1) on sine-Gordon: orders in t and x
 * against the breather and the kink, the discrete symplectic form of a time strip carried by
 * two tangent variations (conserved to round-off), the strip energy bounded. */
#include "pde_util.h"

static double sgV(double u, const void *c) {
  (void)c;
  return -cos(u);
}
static double sgdV(double u, const void *c) {
  (void)c;
  return sin(u);
}
static double sgd2V(double u, const void *c) {
  (void)c;
  return cos(u);
}

#define KINK_C 0.5
static double kink(double x, double t) {
  double g = 1.0 / sqrt(1.0 - KINK_C * KINK_C);
  return 4.0 * atan(exp(g * (x - KINK_C * t)));
}

typedef double (*exact_fn)(double x, double t);

static gm_tentvi *make(exact_fn f, size_t n, double dt, double twist) {
  double h = 2.0 * PDE_L / (double)n;
  double *u0 = malloc(n * sizeof *u0), *u1 = malloc(n * sizeof *u1);
  for (size_t i = 0; i < n; i++) {
    u0[i] = f(-PDE_L + (double)i * h, 0.0);
    u1[i] = f(-PDE_L + (double)i * h, dt);
  }
  gm_tentvi *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_tentvi_create(n, -PDE_L, h, twist, dt, sgV, sgdV, sgd2V, NULL, u0, u1, &m,
                                &err),
               GM_OK, "%s", err.message);
  free(u0);
  free(u1);
  return m;
}

static double run_error(exact_fn f, size_t n, double dt, double twist, double T) {
  gm_tentvi *m = make(f, n, dt, twist);
  gm_error err = {{0}};
  size_t steps = (size_t)llround(T / dt) - 1;
  cr_assert_eq(gm_tentvi_advance(m, steps, &err), GM_OK, "%s", err.message);
  double h = 2.0 * PDE_L / (double)n, e = 0.0, t = gm_tentvi_time(m);
  const double *u = gm_tentvi_u(m);
  for (size_t i = 0; i < n; i++) e = fmax(e, fabs(u[i] - f(-PDE_L + (double)i * h, t)));
  gm_tentvi_free(m);
  return e;
}

Test(pde_tentvi, orders_breather_and_kink) {
  const double tw[2] = {0.0, 2.0 * 3.141592653589793};
  const exact_fn fs[2] = {pde_breather, kink};
  const char *names[2] = {"breather", "kink"};
  for (int k = 0; k < 2; k++) {
    /* joint: Δt = Δx/2, n = 200 → 400, T = 4 */
    double a = run_error(fs[k], 200, 0.1, tw[k], 4.0), b = run_error(fs[k], 400, 0.05, tw[k], 4.0);
    /* space at fixed Δt = 0.02: n = 100 → 200 */
    double sa = run_error(fs[k], 100, 0.02, tw[k], 4.0);
    double sb = run_error(fs[k], 200, 0.02, tw[k], 4.0);
    double pj = log2(a / b), px = log2(sa / sb);
    cr_log_info("tent VI, %s: joint (dt = dx/2, n 200 -> 400, T 4) %.3e -> %.3e order %.3f; "
                "space (dt 0.02, n 100 -> 200) %.3e -> %.3e order %.3f",
                names[k], a, b, pj, sa, sb, px);
    cr_expect(fabs(pj - 2.0) < 0.1, "%s joint order %.3f", names[k], pj);
    cr_expect(fabs(px - 2.0) < 0.1, "%s space order %.3f", names[k], px);
  }
}

Test(pde_tentvi, time_order_on_a_fixed_grid) {
  /* n = 200 (h = 0.2), Δt = 0.2, 0.1, 0.05 against Δt = 0.2/64 on the same grid, T = 4 */
  size_t n = 200;
  double ref[200], dts[3] = {0.2, 0.1, 0.05}, e[3];
  gm_error err = {{0}};
  gm_tentvi *r = make(pde_breather, n, 0.2 / 64, 0.0);
  cr_assert_eq(gm_tentvi_advance(r, 64 * 20 - 1, &err), GM_OK);
  memcpy(ref, gm_tentvi_u(r), sizeof ref);
  gm_tentvi_free(r);
  for (int k = 0; k < 3; k++) {
    gm_tentvi *m = make(pde_breather, n, dts[k], 0.0);
    cr_assert_eq(gm_tentvi_advance(m, (size_t)llround(4.0 / dts[k]) - 1, &err), GM_OK);
    e[k] = 0.0;
    for (size_t i = 0; i < n; i++) e[k] = fmax(e[k], fabs(gm_tentvi_u(m)[i] - ref[i]));
    gm_tentvi_free(m);
  }
  double p1 = log2(e[0] / e[1]), p2 = log2(e[1] / e[2]);
  cr_log_info("tent VI breather, time on a fixed grid (n 200, dt 0.2/0.1/0.05 vs 0.2/64): "
              "%.3e %.3e %.3e, orders %.3f %.3f", e[0], e[1], e[2], p1, p2);
  cr_expect(fabs(p2 - 2.0) < 0.1, "time order %.3f", p2);
}

Test(pde_tentvi, symplectic_form_and_energy) {
  size_t n = 200, steps = 5000;
  double dt = 0.1;
  gm_tentvi *m = make(pde_breather, n, dt, 0.0);
  double U0[200], U1[200], W0[200], W1[200];
  unsigned s = 12345;
  for (size_t i = 0; i < n; i++) {
    s = s * 1103515245u + 12345u;
    U0[i] = (double)(s >> 8) / 16777216.0 - 0.5;
    s = s * 1103515245u + 12345u;
    U1[i] = (double)(s >> 8) / 16777216.0 - 0.5;
    s = s * 1103515245u + 12345u;
    W0[i] = (double)(s >> 8) / 16777216.0 - 0.5;
    s = s * 1103515245u + 12345u;
    W1[i] = (double)(s >> 8) / 16777216.0 - 0.5;
  }
  gm_error err = {{0}};
  cr_assert_eq(gm_tentvi_set_variations(m, U0, U1, W0, W1, &err), GM_OK);
  double scale = 0.0, w0 = gm_tentvi_symplectic_form(m, &scale), worst = 0.0, worst400 = 0.0;
  double e0 = gm_tentvi_energy(m), de_first = 0.0, de_last = 0.0;
  for (size_t k = 0; k < steps; k++) {
    cr_assert_eq(gm_tentvi_advance(m, 1, &err), GM_OK, "%s", err.message);
    {
      double sc = 0.0, w = gm_tentvi_symplectic_form(m, &sc);
      worst = fmax(worst, fabs(w - w0) / fmax(sc, scale));
      if (k == 399) worst400 = worst;
    }
    double de = fabs(gm_tentvi_energy(m) - e0) / fabs(e0);
    if (k < steps / 10) de_first = fmax(de_first, de);
    if (k >= steps - steps / 10) de_last = fmax(de_last, de);
  }
  cr_log_info("tent VI breather n 200, dt 0.1: symplectic form of the strip, relative change "
              "%.2e over 400 steps, %.2e over 5000 (growth not analysed); strip energy over "
              "5000 steps (T 500): max relative change "
              "%.3e in the first tenth, %.3e in the last tenth",
              worst400, worst, de_first, de_last);
  cr_expect_leq(worst400, 1e-12, "symplectic form %.3e", worst400);
  cr_expect_leq(worst, 1e-10, "symplectic form %.3e", worst);
  cr_expect_leq(de_last, 2.0 * de_first + 1e-12, "energy bounded: %.3e then %.3e", de_first,
                de_last);
  gm_tentvi_free(m);
}

Test(pde_tentvi, bad_input) {
  double u[8] = {0};
  gm_tentvi *m = NULL;
  gm_error err = {{0}};
  cr_expect_eq(gm_tentvi_create(8, 0.0, 0.1, 0.0, 0.2, sgV, sgdV, NULL, NULL, u, u, &m, &err),
               GM_EINVAL);
  cr_expect(strstr(err.message, "dt") != NULL, "%s", err.message);
  cr_expect_eq(gm_tentvi_create(8, 0.0, 0.1, 0.0, -0.05, sgV, sgdV, NULL, NULL, u, u, &m, &err),
               GM_EINVAL);
  u[3] = NAN;
  cr_expect_eq(gm_tentvi_create(8, 0.0, 0.1, 0.0, 0.05, sgV, sgdV, NULL, NULL, u, u, &m, &err),
               GM_EDOMAIN);
  cr_expect_eq(gm_tentvi_create(3, 0.0, 0.1, 0.0, 0.05, sgV, sgdV, NULL, NULL, u, u, &m, &err),
               GM_EINVAL);
}
