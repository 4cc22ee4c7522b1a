/* Seed 001 §5.7: the multiscale variational integrator (gm_msvi, §5.7.2) on the stiff spring
 * pendulum m = 1, g = 9.81, k = 1e4, l = 1 (theta0 = 1, at rest at the static stretch; fast
 * period 2 pi/100) against vi-midpoint (polar) and imex (Cartesian), errors at T against
 * vi-galerkin-gauss-2 at h = 1e-4; and the 1-D MsFEM of §5.7.1 against P1 on
 * (a(x/eps) u')' = x^2, a = 10/(1 + 0.95 sin 2 pi y), eps = 0.025 (MsFEM's nodal values are
 * exact there: they are the reference). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/oscillatory.h"

static const double ms_t[GM_MULTISCALE_T] = {1.0, 10.0};
static const double ms_h[GM_MULTISCALE_H] = {0.2, 0.1, 0.05, 0.025};
static const size_t ms_n[GM_MULTISCALE_MSFEM] = {4, 10, 37, 64, 160, 400, 1600};

/* a and theta at T by a row of the model (spring-pendulum: polar; stiff-spring-pendulum:
 * Cartesian, converted) */
static gm_status model_row(const char *model_name, const char *method, double t_end, double h,
                           double *a, double *theta, gm_error *err) {
  gm_model *model = NULL;
  gm_integrator *it = NULL;
  gm_status st = gm_experiment_model(model_name, &model, err);
  if (st == GM_OK) st = gm_experiment_start(model, method, 0, &it, err);
  if (st == GM_OK) st = gm_integrator_integrate(it, t_end, h);
  if (st == GM_OK) {
    const double *y = gm_integrator_state(it);
    if (strcmp(model_name, "spring-pendulum") == 0) {
      *a = y[0];
      *theta = y[1];
    } else {
      *a = hypot(y[0], y[1]) - 1.0;
      *theta = atan2(y[0], -y[1]);
    }
  } else if (it != NULL) {
    gm_error_set(err, st, "%s on %s: %s", method, model_name, gm_integrator_errmsg(it));
  }
  gm_integrator_free(it);
  gm_model_free(model);
  return st;
}

/* msvi from the same initial state; returns the number of steps done (n_steps: all) */
static size_t msvi_row(int additive, double t_end, double h, double *a, double *theta) {
  gm_msvi_options o = gm_msvi_defaults();
  o.additive = additive;
  gm_msvi *vi = NULL;
  if (gm_msvi_create(&o, &vi, NULL) != GM_OK) return 0;
  double q[2] = {o.m * o.g / o.k, 1.0}, p[2] = {0.0, 0.0};
  const size_t n = (size_t)llround(t_end / h);
  size_t k = 0;
  for (; k < n; ++k)
    if (gm_msvi_step(vi, h, q, p) != GM_OK) break;
  *a = q[0];
  *theta = q[1];
  gm_msvi_free(vi);
  return k;
}

static double msfem_a(void *ctx, double x) {
  (void)ctx;
  return 10.0 / (1.0 + 0.95 * sin(2.0 * 3.14159265358979323846 * x / 0.025));
}
static double msfem_f(void *ctx, double x) {
  (void)ctx;
  return x * x;
}

gm_status gm_experiment_multiscale(gm_multiscale_result *r, gm_error *err) {
  memset(r, 0, sizeof *r);
  const double t0 = gm_experiment_clock();
  for (size_t i = 0; i < GM_MULTISCALE_T; ++i) {
    double ar, thr;
    r->t_end[i] = ms_t[i];
    gm_status st = model_row("spring-pendulum", "vi-galerkin-gauss-2", ms_t[i], 1e-4, &ar, &thr,
                             err);
    if (st != GM_OK) return st;
    for (size_t j = 0; j < GM_MULTISCALE_H; ++j) {
      const size_t n = (size_t)llround(ms_t[i] / ms_h[j]);
      r->h[j] = ms_h[j];
      r->steps[i][j] = n;
      gm_multiscale_cell *c = r->cells[i][j];
      /* columns: msvi additive, vi-midpoint, imex, msvi product on l + a, on a (the seed's) */
      static const int additive[5] = {1, -1, -1, 2, 0};
      for (int col = 0; col < 5; ++col) {
        double a = NAN, th = NAN;
        if (additive[col] >= 0) {
          const size_t done = msvi_row(additive[col], ms_t[i], ms_h[j], &a, &th);
          c[col].status = done == n ? 0 : 1;
          c[col].step = done;
        } else {
          gm_error ignored = {{0}};
          st = model_row(col == 1 ? "spring-pendulum" : "stiff-spring-pendulum",
                         col == 1 ? "vi-midpoint" : "imex", ms_t[i], ms_h[j], &a, &th, &ignored);
          c[col].status = st == GM_OK ? 0 : -1;
          c[col].step = n;
        }
        c[col].da = fabs(a - ar);
        c[col].dtheta = fabs(th - thr);
      }
    }
  }
  double exact_nodes[1601], u[1601];
  for (size_t i = 0; i < GM_MULTISCALE_MSFEM; ++i) {
    const size_t n = ms_n[i];
    r->msfem_n[i] = n;
    for (int ms = 1; ms >= 0; --ms) {
      const size_t n_sub = (size_t)ceil(4.0 / (0.025 * (double)n));
      gm_status st = gm_msfem_1d(msfem_a, msfem_f, NULL, n, ms, n_sub, u, err);
      if (st != GM_OK) return st;
      if (ms == 1) memcpy(exact_nodes, u, (n + 1) * sizeof *u); /* MsFEM nodes are exact */
    }
    double e = 0.0;
    for (size_t k = 0; k <= n; ++k) e = fmax(e, fabs(u[k] - exact_nodes[k]));
    r->msfem_p1_error[i] = e;
  }
  r->wall_s = gm_experiment_clock() - t0;
  return GM_OK;
}

gm_status gm_experiment_run_multiscale(const char *dir, gm_experiment_result *result,
                                       gm_error *err) {
  (void)dir; /* tables only */
  gm_multiscale_result r;
  gm_status st = gm_experiment_multiscale(&r, err);
  if (st != GM_OK) return st;
  /* T = 10, h = 0.025: the additive msvi and vi-midpoint (theta errors) */
  gm_experiment_add(result, "msvi_additive_theta_error_t10_h0.025",
                    r.cells[1][3][0].status == 0 ? r.cells[1][3][0].dtheta : NAN);
  gm_experiment_add(result, "vi_midpoint_theta_error_t10_h0.025",
                    r.cells[1][3][1].status == 0 ? r.cells[1][3][1].dtheta : NAN);
  gm_experiment_add(result, "imex_theta_error_t10_h0.025",
                    r.cells[1][3][2].status == 0 ? r.cells[1][3][2].dtheta : NAN);
  gm_experiment_add(result, "p1_nodal_error_n1600", r.msfem_p1_error[GM_MULTISCALE_MSFEM - 1]);
  gm_experiment_add(result, "wall_s", r.wall_s);
  return GM_OK;
}
