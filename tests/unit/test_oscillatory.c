/* The oscillatory rows (issue 12): bad input, the reductions of IMEX (to Verlet when ∇W = 0,
 * to implicit midpoint when ∇U = 0), its three equivalent forms, exactness of the
 * trigonometric rows when U = 0, the variational trigonometric integrator = the HLW form with
 * the same filters, and seed 000 Thm 2.2.3 (IMEX on the toy problem stable iff h ≤ 2). */
#include "test_util.h"

static const gm_method *row(const char *name) {
  const gm_method *m = gm_method_find(name);
  cr_assert_not_null(m, "%s", name);
  return m;
}

/* max |y_a − y_b| after n steps of h of two integrators from the same state */
static double run_and_compare(gm_integrator *a, gm_integrator *b, size_t n, double h) {
  cr_assert_eq(gm_integrator_run(a, n, h), GM_OK, "%s", gm_integrator_errmsg(a));
  cr_assert_eq(gm_integrator_run(b, n, h), GM_OK, "%s", gm_integrator_errmsg(b));
  const double *ya = gm_integrator_state(a), *yb = gm_integrator_state(b);
  double e = 0.0;
  for (size_t i = 0; i < gm_integrator_state_size(a); ++i) e = fmax(e, fabs(ya[i] - yb[i]));
  return e;
}

/* ---- a hand-made split problem: d = 2, U = ½|q|² + ¼ q1⁴ + q1 q2³/3 ... ------------------- */

typedef struct {
  size_t dim;
  double omega[4];
  double mass[2];
  int fast_nonlinear; /* W = ¼ k (q1² + q2² − 1)² ... instead of ½ qᵀΩ²q */
  int slow_off;       /* U = 0 */
  gm_split_potential split;
} custom;

static double u_of(const custom *c, const double *q) {
  if (c->slow_off) return 0.0;
  return 0.5 * (q[0] * q[0] + q[1] * q[1]) + 0.25 * pow(q[0], 4) + q[0] * pow(q[1], 3) / 3.0;
}
static void u_grad(const custom *c, const double *q, double *g) {
  if (c->slow_off) {
    g[0] = g[1] = 0.0;
    return;
  }
  g[0] = q[0] + pow(q[0], 3) + pow(q[1], 3) / 3.0;
  g[1] = q[1] + q[0] * q[1] * q[1];
}
static double w_of(const custom *c, const double *q) {
  if (c->fast_nonlinear) {
    const double e = q[0] * q[0] + q[1] * q[1] - 1.0;
    return 25.0 * e * e;
  }
  double s = 0.0; /* ½ qᵀΩ²q = ½ |Ωq|² */
  for (int i = 0; i < 2; ++i) {
    double r = c->omega[2 * i] * q[0] + c->omega[2 * i + 1] * q[1];
    s += r * r;
  }
  return 0.5 * s;
}
static void w_grad(const custom *c, const double *q, double *g) {
  if (c->fast_nonlinear) {
    const double e = q[0] * q[0] + q[1] * q[1] - 1.0;
    g[0] = 100.0 * e * q[0];
    g[1] = 100.0 * e * q[1];
    return;
  }
  double r[2];
  for (int i = 0; i < 2; ++i) r[i] = c->omega[2 * i] * q[0] + c->omega[2 * i + 1] * q[1];
  for (int j = 0; j < 2; ++j) g[j] = c->omega[j] * r[0] + c->omega[2 + j] * r[1];
}
static double cu(void *ctx, const double *q) { return u_of(ctx, q); }
static int cug(void *ctx, const double *q, double *g) {
  u_grad(ctx, q, g);
  return 0;
}
static double cw(void *ctx, const double *q) { return w_of(ctx, q); }
static int cwg(void *ctx, const double *q, double *g) {
  w_grad(ctx, q, g);
  return 0;
}
static double cv(void *ctx, const double *q) { return u_of(ctx, q) + w_of(ctx, q); }
static int cvg(void *ctx, const double *q, double *g) {
  double a[2];
  u_grad(ctx, q, g);
  w_grad(ctx, q, a);
  g[0] += a[0];
  g[1] += a[1];
  return 0;
}
static double ck(void *ctx, const double *p) {
  const custom *c = ctx;
  return 0.5 * (p[0] * p[0] / c->mass[0] + p[1] * p[1] / c->mass[1]);
}
static int ckg(void *ctx, const double *p, double *g) {
  const custom *c = ctx;
  g[0] = p[0] / c->mass[0];
  g[1] = p[1] / c->mass[1];
  return 0;
}

static gm_problem custom_problem(custom *c) {
  c->dim = 2;
  if (c->mass[0] == 0.0) c->mass[0] = c->mass[1] = 1.0;
  c->split = (gm_split_potential){cu, cug, cw, cwg, NULL,
                                  c->fast_nonlinear ? NULL : c->omega, 0, c->mass};
  gm_problem pb = {0};
  pb.kind = GM_PROBLEM_SEPARABLE;
  pb.dim = 2;
  pb.ctx = c;
  pb.kinetic = ck;
  pb.kinetic_gradient = ckg;
  pb.potential = cv;
  pb.potential_gradient = cvg;
  pb.kinetic_is_quadratic = 1;
  pb.split = &c->split;
  return pb;
}

/* ---- bad input ------------------------------------------------------------------------- */

static gm_status create_error(const char *method, const gm_problem *pb, gm_error *err) {
  gm_integrator *it = NULL;
  gm_status st = gm_integrator_create(row(method), pb, &it, err);
  gm_integrator_free(it);
  return st;
}

Test(oscillatory, bad_input) {
  gm_error err = {{0}};
  custom c = {.omega = {10.0, 1.0, 0.0, 5.0}, .mass = {1.0, 2.0}}; /* not symmetric */
  gm_problem pb = custom_problem(&c);
  cr_expect_eq(create_error("imex", &pb, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "not symmetric") != NULL, "%s", err.message);
  c.omega[1] = c.omega[2] = 10.0; /* eigenvalues 15 and −5: not PSD */
  pb = custom_problem(&c);
  cr_expect_eq(create_error("trig-gautschi", &pb, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "not positive semidefinite") != NULL, "%s", err.message);
  c.omega[1] = c.omega[2] = 1.0;
  pb = custom_problem(&c);
  cr_expect_eq(create_error("trig-gautschi", &pb, &err), GM_OK, "%s", err.message);
  c.mass[1] = -1.0;
  pb = custom_problem(&c);
  cr_expect_eq(create_error("imex", &pb, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "mass") != NULL, "%s", err.message);
  c.mass[1] = 2.0;
  /* a filter asked of a problem without a fast quadratic part */
  test_model ssp = test_model_make("stiff-spring-pendulum");
  const char *filtered[] = {"trig-gautschi", "trig-hairer-lubich", "vti", "vti-scalar",
                            "mollified-impulse-sinc"};
  for (size_t i = 0; i < sizeof filtered / sizeof filtered[0]; ++i) {
    cr_expect_eq(create_error(filtered[i], ssp.problem, &err), GM_EUNSUPPORTED, "%s",
                 filtered[i]);
    cr_expect(strstr(err.message, "no fast quadratic part") != NULL, "%s", err.message);
  }
  /* a problem without a split */
  test_model kepler = test_model_make("kepler");
  cr_expect_eq(create_error("imex", kepler.problem, &err), GM_EUNSUPPORTED);
  cr_expect(strstr(err.message, "split potential") != NULL, "%s", err.message);
  /* n = 0 substeps; options of the wrong row */
  test_model toy = test_model_make("toy-resonance");
  gm_integrator *it = test_integrator(row("impulse"), toy.problem, toy.t0, toy.y0);
  cr_expect_eq(gm_oscillatory_set_substeps(it, 0), GM_EINVAL);
  cr_expect(strstr(gm_integrator_errmsg(it), "substeps") != NULL);
  cr_expect_eq(gm_oscillatory_set_substeps(it, 3), GM_OK);
  cr_expect_eq(gm_oscillatory_set_imex_form(it, GM_IMEX_LINEAR_SOLVE), GM_EUNSUPPORTED);
  gm_integrator_free(it);
  it = test_integrator(row("imex"), ssp.problem, ssp.t0, ssp.y0);
  cr_expect_eq(gm_oscillatory_set_substeps(it, 4), GM_EUNSUPPORTED);
  cr_expect_eq(gm_oscillatory_set_imex_form(it, GM_IMEX_MODIFIED_FREQUENCY), GM_EUNSUPPORTED);
  cr_expect(strstr(gm_integrator_errmsg(it), "quadratic") != NULL);
  cr_expect_eq(gm_oscillatory_set_filters(it, gm_sinc, gm_sinc), GM_EUNSUPPORTED);
  gm_integrator_free(it);
  /* vti where sinc(hω) < 0: an error, not NaN */
  it = test_integrator(row("vti"), toy.problem, toy.t0, toy.y0);
  cr_expect_eq(gm_integrator_step(it, 0.4), GM_EDOMAIN); /* hω = 4 ∈ (π, 2π) */
  cr_expect(strstr(gm_integrator_errmsg(it), "sinc(hω)") != NULL, "%s", gm_integrator_errmsg(it));
  cr_expect_eq(gm_integrator_state(it)[0], toy.y0[0]);
  cr_expect_eq(gm_integrator_step(it, 0.2), GM_OK); /* hω = 2 */
  gm_integrator_free(it);
  /* vti-scalar is for one degree of freedom */
  test_model fpu = test_model_make("fpu");
  cr_expect_eq(create_error("vti-scalar", fpu.problem, &err), GM_EUNSUPPORTED);
  gm_model_free(fpu.model);
  gm_model_free(toy.model);
  gm_model_free(kepler.model);
  gm_model_free(ssp.model);
}

/* ---- reductions ------------------------------------------------------------------------ */

Test(oscillatory, imex_is_verlet_without_fast_force) {
  custom c = {.omega = {0.0, 0.0, 0.0, 0.0}, .mass = {1.0, 3.0}};
  gm_problem pb = custom_problem(&c);
  const double y0[4] = {0.3, -0.4, 0.7, 0.2};
  gm_integrator *a = test_integrator(row("imex"), &pb, 0.0, y0);
  gm_integrator *b = test_integrator(row("verlet"), &pb, 0.0, y0);
  double e = run_and_compare(a, b, 1000, 0.05);
  cr_expect_leq(e, 1e-13, "imex vs verlet with W = 0: %.2e", e);
  gm_integrator_free(a);
  gm_integrator_free(b);
  /* and through the toy problem with omega = 0 */
  test_model toy = test_model_with("toy-resonance", "omega", 0.0);
  a = test_integrator(row("imex"), toy.problem, toy.t0, toy.y0);
  b = test_integrator(row("verlet"), toy.problem, toy.t0, toy.y0);
  e = run_and_compare(a, b, 1000, 0.3);
  cr_expect_leq(e, 1e-13, "toy: %.2e", e);
  gm_integrator_free(a);
  gm_integrator_free(b);
  gm_model_free(toy.model);
}

Test(oscillatory, imex_is_midpoint_without_slow_force) {
  /* quadratic W (full Ω, masses) and nonlinear W (Newton) */
  for (int nonlinear = 0; nonlinear <= 1; ++nonlinear) {
    custom c = {.omega = {4.0, 1.0, 1.0, 3.0}, .mass = {1.0, 2.0}, .slow_off = 1,
                .fast_nonlinear = nonlinear};
    gm_problem pb = custom_problem(&c);
    const double y0[4] = {1.1, -0.4, 0.7, 0.2};
    gm_integrator *a = test_integrator(row("imex"), &pb, 0.0, y0);
    gm_integrator *b = test_integrator(row("midpoint"), &pb, 0.0, y0);
    cr_assert_eq(gm_integrator_set_solver(b, GM_SOLVER_NEWTON), GM_OK);
    double e = run_and_compare(a, b, 500, 0.02);
    cr_expect_leq(e, 1e-12, "imex vs midpoint with U = 0 (W %s): %.2e",
                  nonlinear ? "nonlinear" : "quadratic", e);
    gm_integrator_free(a);
    gm_integrator_free(b);
  }
}

static double imex_form_run(const test_model *tm, gm_imex_form form, double h, size_t n,
                            double *y) {
  gm_integrator *it = test_integrator(row("imex"), tm->problem, tm->t0, tm->y0);
  cr_assert_eq(gm_oscillatory_set_imex_form(it, form), GM_OK, "%s", gm_integrator_errmsg(it));
  cr_assert_eq(gm_integrator_run(it, n, h), GM_OK, "%s", gm_integrator_errmsg(it));
  memcpy(y, gm_integrator_state(it), tm->n * sizeof *y);
  gm_integrator_free(it);
  return 0.0;
}

Test(oscillatory, imex_three_forms_agree) {
  /* FPU (diagonal Ω, M = I) and the diatomic chain (full Ω, masses 1 and 2), hω = 5 and 3 */
  const struct {
    const char *name;
    double h;
  } cases[] = {{"fpu", 0.1}, {"diatomic-chain", 0.1}};
  for (size_t c = 0; c < 2; ++c) {
    test_model tm = test_model_make(cases[c].name);
    double ya[64], yb[64], yc[64];
    imex_form_run(&tm, GM_IMEX_LINEAR_SOLVE, cases[c].h, 2000, ya);
    imex_form_run(&tm, GM_IMEX_MODIFIED_MASS, cases[c].h, 2000, yb);
    imex_form_run(&tm, GM_IMEX_MODIFIED_FREQUENCY, cases[c].h, 2000, yc);
    double eab = 0.0, eac = 0.0, scale = gm_norm_inf_test(tm.n, ya);
    for (size_t i = 0; i < tm.n; ++i) {
      eab = fmax(eab, fabs(ya[i] - yb[i]));
      eac = fmax(eac, fabs(ya[i] - yc[i]));
    }
    cr_expect_leq(eab, 1e-10 * scale, "%s: linear solve vs modified mass %.2e", cases[c].name,
                  eab);
    cr_expect_leq(eac, 1e-10 * scale, "%s: linear solve vs modified frequency %.2e",
                  cases[c].name, eac);
    gm_model_free(tm.model);
  }
}

/* With U = 0 (toy, c = 0) the trigonometric rows are the exact flow. */
Test(oscillatory, trigonometric_exact_without_slow_force) {
  test_model tm = test_model_with("toy-resonance", "c", 0.0);
  const char *rows[] = {"trig-gautschi",      "trig-deuflhard",     "trig-garcia-archilla",
                        "trig-hochbruck-lubich", "trig-hairer-lubich", "vti", "vti-scalar"};
  const double h = 0.27; /* hω = 2.7 < π */
  double exact[2];
  tm.problem->exact(tm.problem->ctx, 1000 * h, exact);
  for (size_t i = 0; i < sizeof rows / sizeof rows[0]; ++i) {
    gm_integrator *it = test_integrator(row(rows[i]), tm.problem, tm.t0, tm.y0);
    cr_assert_eq(gm_integrator_run(it, 1000, h), GM_OK, "%s", gm_integrator_errmsg(it));
    const double *y = gm_integrator_state(it);
    double e = fmax(fabs(y[0] - exact[0]), fabs(y[1] - exact[1]) / 10.0);
    cr_expect_leq(e, 1e-12, "%s with U = 0: error %.2e after 1000 steps", rows[i], e);
    gm_integrator_free(it);
  }
  /* imex is not exact there (its frequency is 2 arctan(hω/2)/h): the check can fail */
  gm_integrator *it = test_integrator(row("imex"), tm.problem, tm.t0, tm.y0);
  cr_assert_eq(gm_integrator_run(it, 1000, h), GM_OK);
  cr_expect_gt(fabs(gm_integrator_state(it)[0] - exact[0]), 1e-3);
  gm_integrator_free(it);
  gm_model_free(tm.model);
}

/* The exact filters of the variational trigonometric integrator, as an HLW pair. */
static double phi_exact(double xi) { return gm_sinc(0.5 * xi) / sqrt(gm_sinc(xi)); }
static double psi_exact(double xi) { return phi_exact(xi) * gm_sinc(xi); }

Test(oscillatory, vti_equals_hlw_form_with_exact_filters) {
  const struct {
    const char *name, *param;
    double value, h;
  } cases[] = {{"fpu", NULL, 0, 0.05},             /* hω = 2.5 */
               {"diatomic-chain", NULL, 0, 0.08},  /* hω = 2.4, full Ω, masses */
               {"toy-resonance", "quartic", 1.0, 0.2}};
  for (size_t c = 0; c < 3; ++c) {
    test_model tm = test_model_with(cases[c].name, cases[c].param, cases[c].value);
    gm_integrator *a = test_integrator(row("vti"), tm.problem, tm.t0, tm.y0);
    gm_integrator *b = test_integrator(row("trig-gautschi"), tm.problem, tm.t0, tm.y0);
    cr_assert_eq(gm_oscillatory_set_filters(b, phi_exact, psi_exact), GM_OK);
    double e = run_and_compare(a, b, 200, cases[c].h); /* FPU amplifies round-off later on */
    cr_expect_leq(e, 1e-12, "%s: vti vs HLW form with the exact filters: %.2e", cases[c].name, e);
    gm_integrator_free(a);
    gm_integrator_free(b);
    if (tm.problem->dim == 1) { /* the scalar family with the exact Φ is the same method */
      a = test_integrator(row("vti-scalar"), tm.problem, tm.t0, tm.y0);
      b = test_integrator(row("vti"), tm.problem, tm.t0, tm.y0);
      cr_assert_eq(gm_oscillatory_set_filters(a, phi_exact, NULL), GM_OK);
      e = run_and_compare(a, b, 200, cases[c].h);
      cr_expect_leq(e, 1e-12, "vti-scalar with exact Φ vs vti: %.2e", e);
      gm_integrator_free(a);
      gm_integrator_free(b);
    }
    gm_model_free(tm.model);
  }
}

/* Seed 000 Thm 2.2.3: on U = ½q², W = ½ω²q², IMEX is linearly stable iff h ≤ 2, for every ω.
 * The step is linear with determinant 1 (symplectic), so it is stable iff |trace| ≤ 2; the
 * one-step matrix comes from stepping the unit vectors. */
static double imex_trace(double omega, double h) {
  test_model tm = test_model_with("toy-resonance", "omega", omega);
  double tr = 0.0, det_cols[2][2];
  for (int j = 0; j < 2; ++j) {
    double y[2] = {j == 0, j == 1};
    gm_integrator *it = test_integrator(row("imex"), tm.problem, 0.0, y);
    cr_assert_eq(gm_integrator_step(it, h), GM_OK);
    det_cols[j][0] = gm_integrator_state(it)[0];
    det_cols[j][1] = gm_integrator_state(it)[1];
    tr += gm_integrator_state(it)[j];
    gm_integrator_free(it);
  }
  double det = det_cols[0][0] * det_cols[1][1] - det_cols[0][1] * det_cols[1][0];
  cr_expect(fabs(det - 1.0) < 1e-12, "det = %.17g", det);
  gm_model_free(tm.model);
  return tr;
}

Test(oscillatory, imex_stable_iff_h_at_most_2) {
  const double omegas[] = {0.0, 0.3, 1.0, 3.14, 10.0, 100.0, 1e3, 1e5};
  const double stable[] = {0.1, 0.5, 1.0, 1.5, 1.9, 1.99};
  const double unstable[] = {2.01, 2.1, 2.5, 4.0};
  for (size_t i = 0; i < sizeof omegas / sizeof omegas[0]; ++i) {
    for (size_t k = 0; k < sizeof stable / sizeof stable[0]; ++k) {
      double tr = imex_trace(omegas[i], stable[k]);
      cr_expect_lt(fabs(tr), 2.0, "omega %g, h %g: |trace| = %.6f", omegas[i], stable[k], tr);
    }
    for (size_t k = 0; k < sizeof unstable / sizeof unstable[0]; ++k) {
      double tr = imex_trace(omegas[i], unstable[k]);
      cr_expect_gt(fabs(tr), 2.0, "omega %g, h %g: |trace| = %.6f", omegas[i], unstable[k], tr);
    }
  }
  /* impulse (r-RESPA) is not: at h = 0.1, ωh/π just below 1 it is unstable (seed 000 E1) */
  test_model tm = test_model_with("toy-resonance", "omega", 0.999 * 3.14159265358979323846 / 0.1);
  gm_integrator *it = test_integrator(row("impulse"), tm.problem, tm.t0, tm.y0);
  cr_assert_eq(gm_oscillatory_set_substeps(it, 100), GM_OK);
  gm_status st = gm_integrator_run(it, 10000, 0.1);
  double q = st == GM_OK ? fabs(gm_integrator_state(it)[0]) : INFINITY;
  cr_expect_gt(q, 10.0, "impulse near resonance stays bounded: |q| = %g", q);
  gm_integrator_free(it);
  gm_model_free(tm.model);
}
