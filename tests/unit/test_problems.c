/* The problem library: analytic derivatives agree with finite differences, exact solutions
 * solve the equations and keep the invariants, and parameters are checked. */
#include <stdio.h>
#include <stdlib.h>

#include "test_util.h"

/* ---- a model of any size, with settings "name=value,name=value" --------------------------- */

typedef struct built_model {
  gm_model *model;
  const gm_problem *pb;
  size_t n; /* state size */
  double t0;
  double *y0;
} built_model;

static built_model build_model(const char *name, const char *settings) {
  built_model bm = {0};
  cr_assert_eq(gm_model_create(name, &bm.model), GM_OK, "model %s", name);
  char buf[256];
  snprintf(buf, sizeof buf, "%s", settings != NULL ? settings : "");
  for (char *item = strtok(buf, ","); item != NULL; item = strtok(NULL, ",")) {
    char *eq = strchr(item, '=');
    cr_assert_not_null(eq, "%s", item);
    *eq = '\0';
    cr_assert_eq(gm_model_set(bm.model, item, strtod(eq + 1, NULL)), GM_OK, "%s",
                 gm_model_errmsg(bm.model));
  }
  cr_assert_eq(gm_model_build(bm.model), GM_OK, "%s %s: %s", name, buf,
               gm_model_errmsg(bm.model));
  bm.pb = gm_model_problem(bm.model);
  bm.n = gm_model_state_size(bm.model);
  bm.y0 = calloc(bm.n, sizeof *bm.y0);
  cr_assert_not_null(bm.y0);
  gm_model_initial_state(bm.model, &bm.t0, bm.y0);
  return bm;
}

static void free_model(built_model *bm) {
  gm_model_free(bm->model);
  free(bm->y0);
}

static double *alloc_doubles(size_t n) {
  double *x = calloc(n ? n : 1, sizeof *x);
  cr_assert_not_null(x);
  return x;
}

/* ∇H in (q, p) for both Hamiltonian kinds. */
static int energy_gradient(const gm_problem *pb, const double *y, double *g) {
  const size_t d = pb->dim;
  if (pb->kind == GM_PROBLEM_SEPARABLE)
    return pb->potential_gradient(pb->ctx, y, g) | pb->kinetic_gradient(pb->ctx, y + d, g + d);
  return pb->dh_dq(pb->ctx, y, y + d, g) | pb->dh_dp(pb->ctx, y, y + d, g + d);
}

/* ∇²H in (q, p), 2d×2d; separable: the two blocks of V and T. */
static int energy_hessian(const gm_problem *pb, const double *y, double *h) {
  const size_t d = pb->dim, m = 2 * d;
  if (pb->kind != GM_PROBLEM_SEPARABLE) {
    cr_assert_not_null(pb->hamiltonian_hessian);
    return pb->hamiltonian_hessian(pb->ctx, y, y + d, h);
  }
  cr_assert_not_null(pb->potential_hessian);
  cr_assert_not_null(pb->kinetic_hessian);
  double *block = alloc_doubles(d * d);
  memset(h, 0, m * m * sizeof *h);
  int rc = pb->potential_hessian(pb->ctx, y, block);
  for (size_t i = 0; i < d; ++i)
    for (size_t j = 0; j < d; ++j) h[i * m + j] = block[i * d + j];
  rc |= pb->kinetic_hessian(pb->ctx, y + d, block);
  for (size_t i = 0; i < d; ++i)
    for (size_t j = 0; j < d; ++j) h[(d + i) * m + d + j] = block[i * d + j];
  free(block);
  return rc;
}

/* max |x_i| over i in [lo, hi) */
static double max_abs(const double *x, size_t lo, size_t hi) {
  double s = 0.0;
  for (size_t i = lo; i < hi; ++i) s = fmax(s, fabs(x[i]));
  return s;
}

/* The analytic gradient and Hessian of H agree with central differences of H and of the
 * gradient, at a state near the model's initial one. Quantities of very different sizes live
 * in q and p (the solar system: forces ~1e-8, velocities ~1e-3), so steps and tolerances scale
 * with each block: the step with the size of the block's coordinates, the tolerance with the
 * largest entry of the gradient block (or Hessian block) compared. */
static void check_energy_derivatives(const char *name, const char *settings) {
  built_model bm = build_model(name, settings);
  const gm_problem *pb = bm.pb;
  const size_t d = pb->dim, m = 2 * d;
  double *y = alloc_doubles(m), *yp = alloc_doubles(m), *g = alloc_doubles(m),
         *gp = alloc_doubles(m), *gm = alloc_doubles(m), *hess = alloc_doubles(m * m);
  double yscale[2], gscale[2];
  for (size_t b = 0; b < 2; ++b) {
    yscale[b] = max_abs(bm.y0, b * d, (b + 1) * d);
    if (yscale[b] == 0.0) yscale[b] = 1.0;
  }
  for (size_t i = 0; i < m; ++i)
    y[i] = bm.y0[i] + 0.01 * (double)((7 * i) % 5 + 1) * yscale[i / d];
  cr_assert_eq(energy_gradient(pb, y, g), 0, "%s", name);
  cr_assert_eq(energy_hessian(pb, y, hess), 0, "%s", name);
  for (size_t b = 0; b < 2; ++b) gscale[b] = max_abs(g, b * d, (b + 1) * d);
  double hscale[2][2] = {{0, 0}, {0, 0}}; /* largest entry of each d×d block */
  for (size_t i = 0; i < m; ++i)
    for (size_t j = 0; j < m; ++j)
      hscale[i / d][j / d] = fmax(hscale[i / d][j / d], fabs(hess[i * m + j]));
  for (size_t j = 0; j < m; ++j) {
    const double h = 1e-6 * yscale[j / d];
    memcpy(yp, y, m * sizeof *y);
    yp[j] = y[j] + h;
    double ep = gm_problem_energy(pb, yp);
    cr_assert_eq(energy_gradient(pb, yp, gp), 0);
    yp[j] = y[j] - h;
    double em = gm_problem_energy(pb, yp);
    cr_assert_eq(energy_gradient(pb, yp, gm), 0);
    double fd = (ep - em) / (2 * h);
    cr_expect(fabs(fd - g[j]) <= 1e-6 * (fabs(g[j]) + gscale[j / d]),
              "%s %s: dH/dy%zu analytic %.12g, differences %.12g", name, settings, j + 1, g[j], fd);
    /* column j of the Hessian; block (i/d, j/d) compared with its own largest entry */
    for (size_t i = 0; i < m; ++i) {
      double fdh = (gp[i] - gm[i]) / (2 * h), scale = hscale[i / d][j / d];
      cr_expect(fabs(fdh - hess[i * m + j]) <= 1e-5 * (fabs(hess[i * m + j]) + scale),
                "%s %s: Hessian (%zu,%zu) analytic %.12g, differences %.12g", name, settings, i,
                j, hess[i * m + j], fdh);
    }
  }
  free(y);
  free(yp);
  free(g);
  free(gp);
  free(gm);
  free(hess);
  free_model(&bm);
}

Test(problems, gradients_and_hessians_match_differences) {
  for (size_t k = 0; k < gm_model_count(); ++k) {
    const gm_model_info *info = gm_model_info_at(k);
    if (info->kind == GM_PROBLEM_FIRST_ORDER || info->kind == GM_PROBLEM_POISSON ||
        info->kind == GM_PROBLEM_LAGRANGIAN || info->kind == GM_PROBLEM_RIGID_BODY)
      continue;
    check_energy_derivatives(info->name, NULL); /* Poisson (lotka-volterra): its own test;
                                                   Lagrangians: test_problems_lagrangian.c;
                                                   rigid bodies: test_problems_rigid.c */
  }
}

/* Variants the defaults do not reach: softening, few bodies, other configurations, mixed signs
 * of the circulations, other chain lengths. */
Test(problems, gradients_and_hessians_of_variants) {
  static const char *const variants[][2] = {
      {"n-body", "n=7,eps=0.1"},
      {"n-body", "n=5,cluster=0,seed=3"},
      {"n-body", "n=4,G=2.5"},
      {"point-vortices", "config=1"},
      {"point-vortices", "config=2,alpha=0.3"},
      {"point-vortices", "config=3,gamma=0.7"},
      {"point-vortices", "config=0,n=7,gamma=-1.5"},
      {"fpu", "l=1"},
      {"fpu", "l=5,omega=7"},
      {"kepler", "e=0.2"},
  };
  for (size_t k = 0; k < sizeof variants / sizeof variants[0]; ++k)
    check_energy_derivatives(variants[k][0], variants[k][1]);
}

/* The exact solution starts at y0, solves y' = J⁻¹∇H (checked by central differences in t)
 * and keeps the energy and the invariants. */
static void check_exact_solution(const char *name, const char *settings) {
  built_model bm = build_model(name, settings);
  const gm_problem *pb = bm.pb;
  cr_assert_not_null(pb->exact, "%s", name);
  const size_t d = pb->dim, n = bm.n;
  double *y = alloc_doubles(n), *yp = alloc_doubles(n), *ym = alloc_doubles(n),
         *grad = alloc_doubles(n);
  cr_assert_eq(pb->exact(pb->ctx, 0.0, y), 0);
  for (size_t i = 0; i < n; ++i) cr_expect(fabs(y[i] - bm.y0[i]) < 1e-14, "%s y(0)", name);
  double h0 = gm_problem_energy(pb, bm.y0);
  for (double t = 0.3; t < 20.0; t += 1.7) {
    const double dt = 1e-5;
    pb->exact(pb->ctx, t, y);
    pb->exact(pb->ctx, t + dt, yp);
    pb->exact(pb->ctx, t - dt, ym);
    cr_assert_eq(energy_gradient(pb, y, grad), 0);
    for (size_t i = 0; i < d; ++i) {
      cr_expect(fabs((yp[i] - ym[i]) / (2 * dt) - grad[d + i]) < 1e-7, "%s %s q' at t=%g", name,
                settings, t);
      cr_expect(fabs((yp[d + i] - ym[d + i]) / (2 * dt) + grad[i]) < 1e-7, "%s %s p' at t=%g",
                name, settings, t);
    }
    cr_expect(fabs(gm_problem_energy(pb, y) - h0) < 1e-13 * fmax(1.0, fabs(h0)), "%s energy",
              name);
    for (size_t j = 0; j < pb->n_invariants; ++j)
      cr_expect(fabs(pb->invariants[j].value(pb->ctx, y) -
                     pb->invariants[j].value(pb->ctx, bm.y0)) < 1e-13,
                "%s invariant %s", name, pb->invariants[j].name);
  }
  free(y);
  free(yp);
  free(ym);
  free(grad);
  free_model(&bm);
}

Test(problems, exact_solutions_solve_the_equations) {
  for (size_t k = 0; k < gm_model_count(); ++k) {
    const gm_model_info *info = gm_model_info_at(k);
    built_model bm = build_model(info->name, NULL);
    cr_expect_eq(bm.pb->exact != NULL, info->has_exact, "%s", info->name);
    free_model(&bm);
    /* Lagrangian problems' exact solutions: tests/unit/test_problems_lagrangian.c */
    if (info->has_exact && info->kind != GM_PROBLEM_LAGRANGIAN)
      check_exact_solution(info->name, NULL);
  }
  /* rings of other sizes and of negative circulation turn the other way round */
  check_exact_solution("point-vortices", "n=5,gamma=-2");
  check_exact_solution("point-vortices", "n=2,gamma=3");
  check_exact_solution("kepler", "e=0.9");
}

Test(problems, info_matches_problem) {
  cr_assert_geq(gm_model_count(), 9);
  for (size_t k = 0; k < gm_model_count(); ++k) {
    const gm_model_info *info = gm_model_info_at(k);
    cr_expect_eq(gm_model_info_find(info->name), info);
    built_model bm = build_model(info->name, NULL);
    cr_expect_eq(bm.pb->dim, info->default_dim, "%s", info->name);
    cr_expect_eq(bm.pb->kind, info->kind, "%s", info->name);
    cr_expect_eq(bm.pb->n_invariants, info->n_invariants, "%s", info->name);
    for (size_t j = 0; j < info->n_invariants; ++j)
      cr_expect_str_eq(bm.pb->invariants[j].name, info->invariant_names[j]);
    cr_expect_eq(gm_problem_validate(bm.pb, NULL), GM_OK);
    /* every parameter reads back its default (text parameters: NaN, they are no numbers) */
    for (size_t j = 0; j < info->n_params; ++j) {
      double v = gm_model_param(bm.model, info->params[j].name);
      if (info->params[j].type == GM_PARAM_TEXT)
        cr_expect(isnan(v), "%s %s", info->name, info->params[j].name);
      else
        cr_expect_eq(v, info->params[j].default_value, "%s %s", info->name,
                     info->params[j].name);
    }
    free_model(&bm);
  }
  cr_expect_null(gm_model_info_at(gm_model_count()));
}

Test(problems, kepler_defaults_and_parameters) {
  gm_model *m = NULL;
  cr_assert_eq(gm_model_create("kepler", &m), GM_OK);
  cr_expect_eq(gm_model_set(m, "e", 0.3), GM_OK);
  cr_assert_eq(gm_model_build(m), GM_OK);
  double t0, y[4];
  gm_model_initial_state(m, &t0, y);
  cr_expect_float_eq(y[0], 0.7, 1e-15);
  cr_expect_float_eq(y[3], sqrt(1.3 / 0.7), 1e-15);
  cr_expect_float_eq(gm_problem_energy(gm_model_problem(m), y), -0.5, 1e-15);
  /* changing an initial value drops the exact solution, which assumed the default start */
  cr_expect_eq(gm_model_set(m, "p2", 1.2), GM_OK);
  cr_assert_eq(gm_model_build(m), GM_OK);
  cr_expect_null(gm_model_problem(m)->exact);
  gm_model_initial_state(m, &t0, y);
  cr_expect_eq(y[3], 1.2);
  gm_model_free(m);
}

/* First-order problems: the analytic Jacobian agrees with central differences of f. */
Test(problems, first_order_jacobians_match_differences) {
  for (size_t k = 0; k < gm_model_count(); ++k) {
    if (gm_model_info_at(k)->kind != GM_PROBLEM_FIRST_ORDER) continue;
    built_model bm = build_model(gm_model_info_at(k)->name, NULL);
    const gm_problem *pb = bm.pb;
    const size_t n = bm.n;
    double *y = alloc_doubles(n), *yp = alloc_doubles(n), *fp = alloc_doubles(n),
           *fm = alloc_doubles(n), *jac = alloc_doubles(n * n);
    memcpy(y, bm.y0, n * sizeof *y);
    y[0] += 0.2;
    cr_assert_not_null(pb->rhs_jacobian);
    cr_assert_eq(pb->rhs_jacobian(pb->ctx, 0.0, y, jac), 0);
    for (size_t j = 0; j < n; ++j) {
      memcpy(yp, y, n * sizeof *y);
      yp[j] = y[j] + 1e-6;
      pb->rhs(pb->ctx, 0.0, yp, fp);
      yp[j] = y[j] - 1e-6;
      pb->rhs(pb->ctx, 0.0, yp, fm);
      for (size_t i = 0; i < n; ++i)
        cr_expect(fabs((fp[i] - fm[i]) / 2e-6 - jac[i * n + j]) < 1e-7, "%s jacobian (%zu,%zu)",
                  gm_model_info_at(k)->name, i, j);
    }
    free(y);
    free(yp);
    free(fp);
    free(fm);
    free(jac);
    free_model(&bm);
  }
}

/* Lotka–Volterra's invariant is kept by an accurate integration (RK4, small steps) and
 * splitting methods refuse the problem (it is not separable Hamiltonian). As a Poisson system,
 * S∇H is the predator–prey field u' = u(v − 2), v' = v(1 − u), and H = −invariant. */
Test(problems, lotka_volterra_invariant_and_kind) {
  test_model tm = test_model_make("lotka-volterra");
  cr_expect_eq(tm.problem->kind, GM_PROBLEM_POISSON);
  const double y[2] = {0.7, 2.9};
  double g[2], s[4];
  cr_assert_eq(tm.problem->poisson_gradient(tm.problem->ctx, y, g), 0);
  cr_assert_eq(tm.problem->structure_matrix(tm.problem->ctx, y, s), 0);
  cr_expect_leq(fabs(s[0] * g[0] + s[1] * g[1] - y[0] * (y[1] - 2.0)), 1e-15);
  cr_expect_leq(fabs(s[2] * g[0] + s[3] * g[1] - y[1] * (1.0 - y[0])), 1e-15);
  cr_expect_leq(fabs(tm.problem->poisson_energy(tm.problem->ctx, y) +
                     tm.problem->invariants[0].value(tm.problem->ctx, y)), 1e-15);
  cr_expect(!test_accepts(gm_method_find("verlet"), tm.problem));
  gm_integrator *it = test_integrator(gm_method_find("rk4"), tm.problem, 0.0, tm.y0);
  gm_monitor *mon = NULL;
  cr_assert_eq(gm_monitor_create(tm.problem, tm.y0, &mon), GM_OK);
  cr_assert_eq(gm_integrator_add_observer(it, gm_monitor_observe, mon, 1), GM_OK);
  cr_assert_eq(gm_integrator_integrate(it, 20.0, 1e-3), GM_OK);
  cr_expect_lt(gm_monitor_max_invariant_drift(mon, 0), 1e-10, "%.2e",
               gm_monitor_max_invariant_drift(mon, 0));
  gm_monitor_free(mon);
  gm_integrator_free(it);
  gm_model_free(tm.model);
}

Test(problems, singular_initial_state_is_an_error) {
  gm_model *m = NULL;
  cr_assert_eq(gm_model_create("kepler", &m), GM_OK);
  cr_expect_eq(gm_model_set(m, "q1", 0.0), GM_OK);
  cr_expect_eq(gm_model_build(m), GM_EINVAL); /* q = 0: V = −inf */
  cr_expect(strstr(gm_model_errmsg(m), "energy") != NULL, "%s", gm_model_errmsg(m));
  gm_model_free(m);
  cr_assert_eq(gm_model_create("lotka-volterra", &m), GM_OK);
  cr_expect_eq(gm_model_set(m, "y1", -1.0), GM_OK);
  cr_expect_eq(gm_model_build(m), GM_EINVAL); /* log of a negative population */
  gm_model_free(m);
}

Test(problems, bad_parameters_are_errors) {
  gm_model *m = NULL;
  cr_expect_eq(gm_model_create("keppler", &m), GM_ENOTFOUND);
  cr_expect_null(m);
  cr_assert_eq(gm_model_create("kepler", &m), GM_OK);
  cr_expect_eq(gm_model_set(m, "mass", 2.0), GM_EINVAL);
  cr_expect(strstr(gm_model_errmsg(m), "mass") != NULL, "%s", gm_model_errmsg(m));
  cr_expect_eq(gm_model_set(m, "q1", NAN), GM_EINVAL);
  cr_expect_eq(gm_model_set(m, "y1", 1.0), GM_EINVAL); /* Hamiltonian: q and p, not y */
  cr_expect_eq(gm_model_set(m, "q3", 1.0), GM_OK);     /* only known at build time ... */
  cr_expect_eq(gm_model_build(m), GM_EINVAL);          /* ... that kepler has 2 dof */
  cr_expect(strstr(gm_model_errmsg(m), "q3") != NULL, "%s", gm_model_errmsg(m));
  gm_model_free(m);
  cr_assert_eq(gm_model_create("kepler", &m), GM_OK);
  cr_expect_eq(gm_model_set(m, "e", 1.0), GM_OK);
  cr_expect_eq(gm_model_build(m), GM_EINVAL);
  cr_expect_null(gm_model_problem(m));
  gm_model_free(m);
  gm_model_free(NULL);
}
