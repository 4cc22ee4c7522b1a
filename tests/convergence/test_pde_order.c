/* Orders of the pde schemes against the sine-Gordon breather (exact solution): joint
 * refinement Δt = Δx/2 (2 for every row on this problem), and the time order alone on a fixed
 * grid against a run with Δt/16. */
#include "pde_util.h"

static double run_error(const char *scheme, size_t n, double dt, double T) {
  gm_pde *p = pde_breather_solver(scheme, n, dt, 0);
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_advance(p, (size_t)llround(T / dt), &err), GM_OK, "%s", err.message);
  double e = pde_breather_error(p, 2.0 * PDE_L / (double)n);
  gm_pde_free(p);
  return e;
}

static void joint_order(const char *scheme, int odd, double lo, double hi) {
  size_t n1 = 200 + (size_t)odd, n2 = 400 + (size_t)odd;
  double h1 = 2.0 * PDE_L / (double)n1, h2 = 2.0 * PDE_L / (double)n2;
  double e1 = run_error(scheme, n1, 0.5 * h1, 4.0), e2 = run_error(scheme, n2, 0.5 * h2, 4.0);
  double order = log(e1 / e2) / log(h1 / h2);
  cr_log_info("%s: errors %.3e (n=%zu), %.3e (n=%zu), order %.3f", scheme, e1, n1, e2, n2, order);
  cr_assert(order > lo && order < hi, "%s: order %.3f outside (%.2f, %.2f)", scheme, order, lo,
            hi);
}

Test(pde_order, preissmann_joint) { joint_order("preissmann", 1, 1.9, 2.1); }
Test(pde_order, euler_box_joint) { joint_order("euler-box", 0, 1.9, 2.1); }
Test(pde_order, lf_joint) { joint_order("lf", 0, 1.9, 2.1); }
Test(pde_order, ec_joint) { joint_order("ec", 0, 1.9, 2.1); }
Test(pde_order, ms_joint) { joint_order("ms", 0, 1.9, 2.1); }

/* u(T) on a fixed grid: the time error alone (reference: the same scheme with Δt/16) */
static double time_order(const char *scheme, size_t n, double dt) {
  double T = 4.0;
  gm_pde *r = pde_breather_solver(scheme, n, dt / 16, 0);
  gm_pde *a = pde_breather_solver(scheme, n, dt, 0), *b = pde_breather_solver(scheme, n, dt / 2, 0);
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_advance(r, (size_t)llround(16 * T / dt), &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_pde_advance(a, (size_t)llround(T / dt), &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_pde_advance(b, (size_t)llround(2 * T / dt), &err), GM_OK, "%s", err.message);
  double ea = 0.0, eb = 0.0;
  const double *sr = gm_pde_state(r), *sa = gm_pde_state(a), *sb = gm_pde_state(b);
  for (size_t i = 0; i < n; i++) {
    ea = fmax(ea, fabs(sa[3 * i] - sr[3 * i]));
    eb = fmax(eb, fabs(sb[3 * i] - sr[3 * i]));
  }
  gm_pde_free(r);
  gm_pde_free(a);
  gm_pde_free(b);
  double order = log2(ea / eb);
  cr_log_info("%s: time errors %.3e, %.3e, order %.3f", scheme, ea, eb, order);
  return order;
}

Test(pde_order, preissmann_time) {
  double o = time_order("preissmann", 101, 0.2);
  cr_assert(o > 1.9 && o < 2.1, "order %.3f", o);
}
Test(pde_order, ms_time) {
  double o = time_order("ms", 100, 0.2);
  cr_assert(o > 1.9 && o < 2.1, "order %.3f", o);
}

/* ---- the moving kink u = 4 arctan(exp(γ(x − ct))), c = 0.5, on the ring twisted by 2π ---- */
#define KINK_C 0.5

/* staggered: the Euler box's v is δ_t⁻u and its w is δ_x⁻u, so its initial data is taken at
 * t = −Δt/2 and x − h/2 when staggered != 0 */
static double kink_error_s(const char *scheme, size_t n, double dt, double T, int staggered) {
  double h = 2.0 * PDE_L / (double)n, g = 1.0 / sqrt(1.0 - KINK_C * KINK_C);
  gm_pde_equation eq = gm_pde_sine_gordon();
  const gm_pde_scheme *s = NULL;
  cr_assert_eq(gm_pde_scheme_find(scheme, &s), GM_OK);
  gm_pde_grid grid = {n, h, -PDE_L, {2.0 * 3.141592653589793, 0.0, 0.0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = dt;
  double *s0 = calloc(3 * n, sizeof *s0);
  for (size_t i = 0; i < n; i++) {
    double x = -PDE_L + (double)i * h, xi = g * x;
    s0[3 * i] = 4.0 * atan(exp(xi));
    s0[3 * i + 1] = -2.0 * KINK_C * g / cosh(staggered ? g * (x + KINK_C * dt / 2) : xi);
    s0[3 * i + 2] = 2.0 * g / cosh(staggered ? g * (x - h / 2) : xi);
  }
  gm_pde *p = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_create(&grid, &eq, s, &o, s0, &p, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_pde_advance(p, (size_t)llround(T / dt), &err), GM_OK, "%s", err.message);
  const double *st = gm_pde_state(p);
  double e = 0.0, t = gm_pde_time(p);
  for (size_t i = 0; i < n; i++)
    e = fmax(e, fabs(st[3 * i] - 4.0 * atan(exp(g * (-PDE_L + (double)i * h - KINK_C * t)))));
  free(s0);
  gm_pde_free(p);
  return e;
}

Test(pde_order, kink_joint_all_schemes) {
  const char *names[] = {"preissmann", "euler-box", "lf", "ec", "ms"};
  for (int q = 0; q < 6; q++) {
    const char *name = names[q < 5 ? q : 1];
    int staggered = q == 1; /* q = 5: the Euler box from unstaggered data */
    size_t n1 = 200 + (q == 0), n2 = 400 + (q == 0);
    double h1 = 2.0 * PDE_L / (double)n1, h2 = 2.0 * PDE_L / (double)n2;
    double e1 = kink_error_s(name, n1, 0.5 * h1, 4.0, staggered),
           e2 = kink_error_s(name, n2, 0.5 * h2, 4.0, staggered);
    double order = log(e1 / e2) / log(h1 / h2);
    cr_log_info("kink %s%s: errors %.3e, %.3e, order %.3f", name,
                q == 1 ? " (staggered data)" : q == 5 ? " (unstaggered data)" : "", e1, e2, order);
    if (q == 5) {
      /* v⁰ = u_t(0) instead of u_t(−Δt/2): an O(Δt) velocity error that makes the run first
       * order asymptotically (the row's declared time order); measured 1.65 between n = 200
       * and 400, still on its way down, with errors 3× the staggered run's */
      cr_expect(order < 1.8, "kink euler-box unstaggered: order %.3f", order);
      continue;
    }
    cr_expect(order > 1.9 && order < 2.1, "kink %s: order %.3f", name, order);
    cr_expect(e1 < 0.1, "kink %s: error %.3e", name, e1);
  }
}
