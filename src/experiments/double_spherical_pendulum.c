/* Seed 001 §2.10 (Leok 2004, Figs 2.7–2.9): the double spherical pendulum under Routh reduction
 * by the rotation about the vertical. A 4th-order RSPRK (the vi-galerkin-gauss-2 tableau) on the
 * reduced system against the same tableau as an SPRK on the classical Routhian (the thesis: they
 * "agree very well") and RK4 on the unreduced system at dt/4 (whose energy drifts); and the
 * constrained R³ × R³ form (vi-galerkin-gauss-2 with multipliers) from the same state, which has
 * no chart and so no spikes where the shape chart (r1, r2, φ) is singular (r_i = 0). The thesis
 * gives no parameters; m1 = m2 = l1 = l2 = 1, g = 9.81 here. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/core.h"
#include "geomint/experiments.h"
#include "geomint/methods.h"
#include "geomint/reduction.h"

/* the parameters (the API takes a mutable pointer; never written) */
static gm_routh_dsp_params dsp = {1.0, 1.0, 1.0, 1.0, 9.81};

gm_dsp_config gm_dsp_defaults(void) {
  gm_dsp_config c = {1.0, {0.5, 0.4, 2.0, 0.0, 0.0, 0.0}, 0.01, 20.0};
  return c;
}

/* unreduced energy from the full state (θ, x, p) */
static double full_energy(const gm_routh_system *sys, const double *y) {
  double m[16], v[4];
  if (sys->metric(sys->ctx, y + 1, m)) return NAN;
  memcpy(v, y + 4, sizeof v);
  gm_dense_solve(4, m, v);
  double e = sys->potential(sys->ctx, y + 1);
  for (int i = 0; i < 4; ++i) e += 0.5 * y[4 + i] * v[i];
  return e;
}

/* classical RK4 on the unreduced equations */
static int rk4_step(const gm_routh_system *sys, double h, double *y) {
  double k1[8], k2[8], k3[8], k4[8], w[8];
  if (gm_routh_full_rhs(sys, y, k1, NULL) != GM_OK) return 1;
  for (int i = 0; i < 8; ++i) w[i] = y[i] + 0.5 * h * k1[i];
  if (gm_routh_full_rhs(sys, w, k2, NULL) != GM_OK) return 1;
  for (int i = 0; i < 8; ++i) w[i] = y[i] + 0.5 * h * k2[i];
  if (gm_routh_full_rhs(sys, w, k3, NULL) != GM_OK) return 1;
  for (int i = 0; i < 8; ++i) w[i] = y[i] + h * k3[i];
  if (gm_routh_full_rhs(sys, w, k4, NULL) != GM_OK) return 1;
  for (int i = 0; i < 8; ++i) y[i] += h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  return 0;
}

static FILE *open_in(const char *dir, const char *name, gm_error *err) {
  char path[GM_EXPERIMENT_PATH_SIZE];
  FILE *f = NULL;
  if (gm_experiment_path(path, sizeof path, dir, name) != GM_OK || (f = fopen(path, "w")) == NULL)
    gm_error_set(err, GM_EIO, "double-spherical-pendulum: cannot write %s/%s", dir, name);
  return f;
}

static gm_status close_out(FILE *f, const char *name, gm_status st, gm_error *err) {
  if (f != NULL && (ferror(f) | fclose(f)) != 0 && st == GM_OK)
    return gm_error_set(err, GM_EIO, "double-spherical-pendulum: writing %s failed", name);
  return st;
}

/* The constrained R³ × R³ form (problem double-spherical-pendulum, vi-galerkin-gauss-2 with
 * multipliers at the control points) from the same initial state (θ = 0, ẋ given, θ̇ from μ).
 * Writes t, (E − E0)/E0 to dir/dsp-constrained.csv. */
static gm_status run_constrained(const gm_dsp_config *c, const char *dir,
                                 const gm_routh_system *sys, gm_dsp_result *r, gm_error *err) {
  const double *x0 = c->x0;
  const double r1 = x0[0], r2 = x0[1], ph = x0[2], r1d = x0[3], r2d = x0[4], phd = x0[5];
  double in, a[3];
  const double mu[1] = {c->mu};
  gm_status st = gm_routh_connection(sys, mu, x0, &in, a, NULL, NULL, NULL, NULL, err);
  if (st != GM_OK) return st;
  const double thd = c->mu / in - (a[0] * r1d + a[1] * r2d + a[2] * phd);
  const double w1 = sqrt(dsp.l1 * dsp.l1 - r1 * r1), w2 = sqrt(dsp.l2 * dsp.l2 - r2 * r2);
  const double cs = cos(ph), sn = sin(ph), om2 = thd + phd;
  double y[12] = {r1, 0.0, -w1, r2 * cs, r2 * sn, -w2};
  const double v[6] = {r1d, r1 * thd, r1 * r1d / w1, r2d * cs - r2 * sn * om2,
                       r2d * sn + r2 * cs * om2, r2 * r2d / w2};
  for (int i = 0; i < 3; ++i) {
    y[6 + i] = (dsp.m1 + dsp.m2) * v[i] + dsp.m2 * v[3 + i];
    y[9 + i] = dsp.m2 * (v[i] + v[3 + i]);
  }
  gm_model *model = NULL;
  gm_integrator *it = NULL;
  st = gm_experiment_model("double-spherical-pendulum", &model, err);
  if (st == GM_OK) {
    const gm_method *row = gm_method_find("vi-galerkin-gauss-2");
    st = row ? gm_integrator_create(row, gm_model_problem(model), &it, err) : GM_EINVAL;
    if (st == GM_OK) st = gm_integrator_set_state(it, 0.0, y);
    if (st != GM_OK)
      gm_error_set(err, st, "double-spherical-pendulum: cannot set up the constrained form");
  }
  FILE *f = NULL;
  if (st == GM_OK && dir != NULL && (f = open_in(dir, "dsp-constrained.csv", err)) == NULL)
    st = GM_EIO;
  const size_t n = (size_t)llround(c->t_end / c->dt);
  double e0 = NAN;
  r->constrained_max_rel_energy_error = 0.0;
  for (size_t i = 0; i <= n && st == GM_OK; ++i) {
    if (i > 0 && (st = gm_integrator_step(it, c->dt)) != GM_OK) {
      gm_error_set(err, st, "double-spherical-pendulum: the constrained run failed at step %zu",
                   i);
      break;
    }
    const double *z = gm_integrator_state(it);
    double e = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double v1 = (z[6 + k] - z[9 + k]) / dsp.m1;
      const double v2 = (-dsp.m2 * z[6 + k] + (dsp.m1 + dsp.m2) * z[9 + k]) / (dsp.m1 * dsp.m2);
      e += 0.5 * (v1 * z[6 + k] + v2 * z[9 + k]);
    }
    e += dsp.m1 * dsp.g * z[2] + dsp.m2 * dsp.g * (z[2] + z[5]);
    if (i == 0) e0 = r->constrained_energy0 = e;
    const double de = (e - e0) / fabs(e0);
    r->constrained_max_rel_energy_error = fmax(r->constrained_max_rel_energy_error, fabs(de));
    if (f) fprintf(f, "%.8g,%.6e\n", (double)i * c->dt, de);
  }
  st = close_out(f, "dsp-constrained.csv", st, err);
  gm_integrator_free(it);
  gm_model_free(model);
  return st;
}

gm_status gm_experiment_double_spherical_pendulum(const gm_dsp_config *c, const char *dir,
                                                  gm_dsp_result *r, gm_error *err) {
  memset(r, 0, sizeof *r);
  if (!(c->dt > 0.0) || !(c->t_end > 0.0) || !isfinite(c->t_end) || !isfinite(c->mu))
    return gm_error_set(err, GM_EINVAL, "double-spherical-pendulum: dt = %g, t_end = %g must be "
                        "> 0 and finite, mu = %g finite", c->dt, c->t_end, c->mu);
  if (c->dt > c->t_end || c->t_end / c->dt > 1e6)
    return gm_error_set(err, GM_EINVAL, "double-spherical-pendulum: t_end/dt = %g steps is "
                        "outside [1, 1e6]", c->t_end / c->dt);
  for (int i = 0; i < 6; ++i)
    if (!isfinite(c->x0[i]))
      return gm_error_set(err, GM_EINVAL, "double-spherical-pendulum: x0[%d] is not finite", i);
  if (!(c->x0[0] > 0 && c->x0[0] < dsp.l1) || !(c->x0[1] > 0 && c->x0[1] < dsp.l2))
    return gm_error_set(err, GM_EINVAL, "double-spherical-pendulum: r1 = %g, r2 = %g must be in "
                        "(0, 1)", c->x0[0], c->x0[1]);
  gm_routh_system sys;
  gm_routh_double_spherical_pendulum(&dsp, &sys);
  const double mu[1] = {c->mu}, h = c->dt;
  const gm_method *row = gm_method_find("vi-galerkin-gauss-2");
  gm_tableau *t = NULL;
  gm_rsprk *ra = NULL, *rb = NULL;
  if (row == NULL || gm_method_tableau(row, &t) != GM_OK ||
      gm_rsprk_create(&sys, t, GM_ROUTH_RSPRK, mu, &ra, err) != GM_OK ||
      gm_rsprk_create(&sys, t, GM_ROUTH_CLASSICAL, mu, &rb, err) != GM_OK) {
    gm_tableau_free(t);
    gm_rsprk_free(ra);
    return gm_error_set(err, GM_EINVAL, "double-spherical-pendulum: cannot set up the steppers");
  }
  r->mu = c->mu;
  memcpy(r->x0, c->x0, sizeof r->x0);
  r->dt = h;
  r->t_end = c->t_end;
  r->m1 = dsp.m1;
  r->m2 = dsp.m2;
  r->l1 = dsp.l1;
  r->l2 = dsp.l2;
  r->g = dsp.g;
  const double wall0 = gm_experiment_clock();
  /* initial shape and shape velocity; s = K ẋ */
  double x[3] = {c->x0[0], c->x0[1], c->x0[2]}, xd[3] = {c->x0[3], c->x0[4], c->x0[5]};
  double kin[9], s[3];
  gm_routh_connection(&sys, mu, x, NULL, NULL, kin, NULL, NULL, NULL, NULL);
  for (int i = 0; i < 3; ++i)
    s[i] = kin[i * 3] * xd[0] + kin[i * 3 + 1] * xd[1] + kin[i * 3 + 2] * xd[2];
  double xc[3], y[3], th = 0.0, thc = 0.0, full[8] = {0};
  memcpy(xc, x, sizeof x);
  gm_routh_lift_momentum(&sys, mu, x, s, y, NULL);
  memcpy(full + 1, x, sizeof x);
  full[4] = c->mu;
  memcpy(full + 5, y, sizeof y);
  const double e0 = gm_routh_energy(&sys, mu, x, s), e0f = full_energy(&sys, full);
  r->energy0 = e0;
  gm_status st = GM_OK;
  FILE *f = NULL;
  if (dir != NULL && (f = open_in(dir, "dsp.csv", err)) == NULL) st = GM_EIO;
  if (f)
    fprintf(f, "t,r1,r2,phi,x2,y2,dE_rsprk,dE_sprk,dE_rk4,rel_r1,rel_r2,rel_phi,rel_E,r1_rk4,"
               "r2_rk4,phi_rk4,min_r\n");
  const size_t n = (size_t)llround(c->t_end / h);
  r->steps = n;
  r->min_r = INFINITY;
  for (size_t i = 0; i <= n && st == GM_OK; ++i) {
    if (i > 0) {
      if (gm_rsprk_step(ra, h, x, s, &th) != GM_OK || gm_rsprk_step(rb, h, xc, y, &thc) != GM_OK) {
        st = gm_error_set(err, GM_ENOCONV, "double-spherical-pendulum: step %zu failed: %s %s", i,
                          gm_rsprk_errmsg(ra), gm_rsprk_errmsg(rb));
        break;
      }
      for (int q = 0; q < 4 && st == GM_OK; ++q)
        if (rk4_step(&sys, h / 4, full))
          st = gm_error_set(err, GM_ENOCONV, "double-spherical-pendulum: RK4 failed at step %zu "
                            "(left the chart)", i);
      if (st != GM_OK) break;
    }
    double sc[3];
    gm_routh_reduce_momentum(&sys, mu, xc, mu, y, sc, NULL);
    const double ea = gm_routh_energy(&sys, mu, x, s), eb = gm_routh_energy(&sys, mu, xc, sc);
    const double ef = full_energy(&sys, full);
    const double da = (ea - e0) / fabs(e0), db = (eb - e0) / fabs(e0), dk = (ef - e0f) / fabs(e0f);
    double rel[4];
    for (int q = 0; q < 3; ++q) rel[q] = fabs(x[q] - xc[q]) / fmax(fabs(x[q]), 1e-300);
    rel[3] = fabs(ea - eb) / fabs(ea);
    for (int q = 0; q < 4; ++q) r->max_rel_rsprk_vs_sprk[q] = fmax(r->max_rel_rsprk_vs_sprk[q], rel[q]);
    r->rsprk_max_rel_energy_error = fmax(r->rsprk_max_rel_energy_error, fabs(da));
    if ((double)i * h <= 0.5 * c->t_end)
      r->rsprk_max_rel_energy_error_first_half =
          fmax(r->rsprk_max_rel_energy_error_first_half, fabs(da));
    r->rk4_max_rel_energy_error = fmax(r->rk4_max_rel_energy_error, fabs(dk));
    if (i > 0 && (i - 1) * 10 < n) {
      r->rsprk_tenths[0] = fmax(r->rsprk_tenths[0], fabs(da));
      r->rk4_tenths[0] = fmax(r->rk4_tenths[0], fabs(dk));
    }
    if (i > 0 && (i - 1) * 10 >= 9 * n) {
      r->rsprk_tenths[1] = fmax(r->rsprk_tenths[1], fabs(da));
      r->rk4_tenths[1] = fmax(r->rk4_tenths[1], fabs(dk));
    }
    r->min_r = fmin(r->min_r, fmin(x[0], x[1]));
    const double th2 = th + x[2];
    if (f)
      fprintf(f, "%.8g,%.12g,%.12g,%.12g,%.10g,%.10g,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.12g,"
                 "%.12g,%.12g,%.6g\n",
              (double)i * h, x[0], x[1], x[2], x[1] * cos(th2), x[1] * sin(th2), da, db, dk,
              rel[0], rel[1], rel[2], rel[3], full[1], full[2], full[3], fmin(x[0], x[1]));
  }
  st = close_out(f, "dsp.csv", st, err);
  gm_rsprk_free(ra);
  gm_rsprk_free(rb);
  gm_tableau_free(t);
  if (st == GM_OK) st = run_constrained(c, dir, &sys, r, err);
  r->wall_s = gm_experiment_clock() - wall0;
  return st;
}

gm_status gm_experiment_run_double_spherical_pendulum(const char *dir, gm_experiment_result *out,
                                                      gm_error *err) {
  const gm_dsp_config c = gm_dsp_defaults();
  gm_dsp_result r;
  gm_status st = gm_experiment_double_spherical_pendulum(&c, dir, &r, err);
  if (st != GM_OK) return st;
  gm_experiment_add(out, "steps", (double)r.steps);
  gm_experiment_add(out, "max_rel_energy_error_rsprk", r.rsprk_max_rel_energy_error);
  gm_experiment_add(out, "max_rel_energy_error_rk4", r.rk4_max_rel_energy_error);
  gm_experiment_add(out, "max_rel_energy_error_rsprk_last_tenth", r.rsprk_tenths[1]);
  gm_experiment_add(out, "max_rel_energy_error_rk4_last_tenth", r.rk4_tenths[1]);
  gm_experiment_add(out, "max_rel_rsprk_vs_sprk_E", r.max_rel_rsprk_vs_sprk[3]);
  gm_experiment_add(out, "max_rel_energy_error_constrained", r.constrained_max_rel_energy_error);
  gm_experiment_add(out, "min_r", r.min_r);
  gm_experiment_add(out, "wall_s", r.wall_s);
  gm_experiment_file(out, dir, "dsp.csv");
  gm_experiment_file(out, dir, "dsp-constrained.csv");
  return GM_OK;
}
