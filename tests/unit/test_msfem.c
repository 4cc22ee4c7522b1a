/* 1-D multiscale finite elements (seed 001 §5.7.1, App. C): for (a(x/ε) u′)′ = x² with
 * a(y) = 10/(1 + 0.95 sin 2πy), ε = 0.025, u(0) = u(1) = 0, the multiscale shape functions give
 * the exact nodal values (l∞ nodal error at round-off) on meshes that do not resolve ε, while
 * standard P1 elements are O(1) wrong there and converge only once h ≪ ε. The exact solution:
 * a u′ = x³/3 + C, so u = (1/10)[x⁴/12 + Cx + 0.95 (I₃(x)/3 + C I₀(x))], I_m = ∫_0^x s^m sin(ks),
 * k = 2π/ε, C from u(1) = 0. */
#include "test_util.h"

#define EPS 0.025

static double coeff(void *ctx, double x) {
  (void)ctx;
  return 10.0 / (1.0 + 0.95 * sin(2.0 * 3.14159265358979323846 * x / EPS));
}
static double load(void *ctx, double x) {
  (void)ctx;
  return x * x;
}

/* I_m(x) = ∫_0^x s^m sin(ks) ds, J_m = ∫_0^x s^m cos(ks) ds, m = 0..3 */
static void moments(double x, double k, double *im, double *jm) {
  im[0] = (1.0 - cos(k * x)) / k;
  jm[0] = sin(k * x) / k;
  for (int m = 1; m <= 3; ++m) {
    im[m] = -pow(x, m) * cos(k * x) / k + (m / k) * jm[m - 1];
    jm[m] = pow(x, m) * sin(k * x) / k - (m / k) * im[m - 1];
  }
}

static double exact(double x) {
  const double k = 2.0 * 3.14159265358979323846 / EPS;
  double i1[4], j1[4], ix[4], jx[4];
  moments(1.0, k, i1, j1);
  const double c = -(1.0 / 12.0 + 0.95 * i1[3] / 3.0) / (1.0 + 0.95 * i1[0]);
  moments(x, k, ix, jx);
  return 0.1 * (pow(x, 4) / 12.0 + c * x + 0.95 * (ix[3] / 3.0 + c * ix[0]));
}

static double nodal_error(size_t n, int multiscale, double *scale) {
  double u[4097];
  gm_error err = {{0}};
  /* subintervals of at most ε/4 */
  size_t n_sub = (size_t)ceil(4.0 / (EPS * (double)n));
  cr_assert_eq(gm_msfem_1d(coeff, load, NULL, n, multiscale, n_sub, u, &err), GM_OK, "%s",
               err.message);
  double e = 0.0, s = 0.0;
  for (size_t i = 0; i <= n; ++i) {
    double ue = exact((double)i / (double)n);
    e = fmax(e, fabs(u[i] - ue));
    s = fmax(s, fabs(ue));
  }
  *scale = s;
  return e;
}

Test(msfem, nodal_values_exact_p1_wrong_until_h_much_smaller_than_eps) {
  const size_t coarse[] = {4, 10, 16, 37, 64};
  double scale;
  for (size_t i = 0; i < sizeof coarse / sizeof coarse[0]; ++i) {
    double ems = nodal_error(coarse[i], 1, &scale), ep1 = nodal_error(coarse[i], 0, &scale);
    cr_log_info("N = %zu (h/eps = %.2f): MsFEM %.2e, P1 %.2e (max |u| = %.3e)", coarse[i],
                1.0 / (EPS * (double)coarse[i]), ems, ep1, scale);
    cr_expect_leq(ems, 1e-13 * scale, "MsFEM N = %zu: nodal error %.2e", coarse[i], ems);
    cr_expect_geq(ep1, 0.2 * scale, "P1 N = %zu: nodal error %.2e only", coarse[i], ep1);
  }
  /* P1 converges once h ≪ ε */
  const size_t fine[] = {400, 1600};
  double e400 = nodal_error(fine[0], 0, &scale), e1600 = nodal_error(fine[1], 0, &scale);
  cr_log_info("P1 N = 400: %.2e, N = 1600: %.2e", e400, e1600);
  cr_expect_lt(e1600, 0.1 * e400, "P1 does not converge: %.2e, %.2e", e400, e1600);
  cr_expect_lt(e1600, 1e-2 * scale);
  gm_error err = {{0}};
  double u[3];
  cr_expect_eq(gm_msfem_1d(coeff, load, NULL, 0, 1, 1, u, &err), GM_EINVAL);
}
