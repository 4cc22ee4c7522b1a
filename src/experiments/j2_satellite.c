/* Seed 001 §2.9 (Leok 2004, Figs 2.2–2.5): the J2 satellite under discrete Routh reduction.
 * The thesis gives no initial data or final time; here r = 1.5, z = 0, speed 1.1 v_circ,
 * inclination 0.3 rad (an inclined ellipse), J2 in {0, 0.05}, the midpoint discrete Lagrangian's
 * discrete Routh equations at dt against a 6th-order RSPRK (Gauss-3) reference at dt/20. The
 * reduced (r, z) view shows J2's precession in the shape; the discretisation's precession lives
 * in the reconstructed angle θ. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/experiments.h"
#include "geomint/reduction.h"

#define J2_R0 1.5
#define J2_INC 0.3
#define J2_SPEED 1.1

gm_j2_config gm_j2_defaults(void) {
  gm_j2_config c = {0.3, 150.0};
  return c;
}

typedef struct track {
  size_t n;
  double *t, *r, *z, *th;
} track;

static void track_free(track *k) {
  free(k->t);
  free(k->r);
  free(k->z);
  free(k->th);
}

static gm_status track_alloc(track *k, size_t n, gm_error *err) {
  k->n = 0;
  k->t = malloc(n * sizeof(double));
  k->r = malloc(n * sizeof(double));
  k->z = malloc(n * sizeof(double));
  k->th = malloc(n * sizeof(double));
  if (k->t && k->r && k->z && k->th) return GM_OK;
  return gm_error_set(err, GM_ENOMEM, "j2-satellite: cannot allocate a track of %zu samples", n);
}

static void track_push(track *k, double t, const double *x, double th) {
  k->t[k->n] = t;
  k->r[k->n] = x[0];
  k->z[k->n] = x[1];
  k->th[k->n] = th;
  k->n++;
}

static double j2_mu(void) { return J2_R0 * J2_SPEED * sqrt(1.0 / J2_R0) * cos(J2_INC); }

/* the reference: RSPRK with the 3-point Gauss tableau (order 6) */
static gm_status j2_reference(double j2, double h, double t_end, track *out, gm_error *err) {
  gm_routh_j2_params p = {j2};
  gm_routh_system sys;
  gm_routh_j2_satellite(&p, &sys);
  static const double nodes[3] = {0.11270166537925831148, 0.5, 0.88729833462074168852};
  gm_tableau *t = NULL;
  gm_rsprk *r = NULL;
  const double mu[1] = {j2_mu()};
  const size_t n = (size_t)llround(t_end / h);
  gm_status st = gm_galerkin_prk_tableau(3, nodes, &t);
  if (st != GM_OK) st = gm_error_set(err, st, "j2-satellite: the Gauss-3 tableau");
  if (st == GM_OK) st = gm_rsprk_create(&sys, t, GM_ROUTH_RSPRK, mu, &r, err);
  if (st == GM_OK) st = track_alloc(out, n + 1, err);
  double x[2] = {J2_R0, 0.0}, s[2] = {0.0, J2_SPEED * sqrt(1.0 / J2_R0) * sin(J2_INC)}, th = 0.0;
  if (st == GM_OK) track_push(out, 0.0, x, th);
  for (size_t i = 1; i <= n && st == GM_OK; ++i) {
    if ((st = gm_rsprk_step(r, h, x, s, &th)) != GM_OK)
      gm_error_set(err, st, "j2-satellite: reference, step %zu: %s", i, gm_rsprk_errmsg(r));
    else
      track_push(out, (double)i * h, x, th);
  }
  gm_rsprk_free(r);
  gm_tableau_free(t);
  return st;
}

/* the discrete flow: the discrete Routh equations of the midpoint L_d with reconstruction; the
 * first step from the reduced Legendre transform (RSPRK with the 1-point Gauss tableau, which is
 * that L_d's push-forward); also the largest difference to that RSPRK along the run */
static gm_status j2_discrete(double j2, double h, double t_end, track *out, double *dr_vs_rsprk,
                             gm_error *err) {
  gm_routh_j2_params p = {j2};
  gm_routh_system sys;
  gm_routh_j2_satellite(&p, &sys);
  const double half = 0.5, mu[1] = {j2_mu()};
  gm_tableau *t = NULL;
  gm_rsprk *r = NULL;
  gm_routh_discrete *d = NULL;
  gm_discrete_lagrangian ld;
  gm_routh_midpoint_lagrangian(&sys, &ld);
  const size_t n = (size_t)llround(t_end / h);
  gm_status st = gm_galerkin_prk_tableau(1, &half, &t);
  if (st != GM_OK) st = gm_error_set(err, st, "j2-satellite: the midpoint tableau");
  if (st == GM_OK) st = gm_rsprk_create(&sys, t, GM_ROUTH_RSPRK, mu, &r, err);
  if (st == GM_OK) st = gm_routh_discrete_create(&ld, &sys, mu, NULL, &d, err);
  if (st == GM_OK) st = track_alloc(out, n + 1, err);
  double xs[2] = {J2_R0, 0.0}, s[2] = {0.0, J2_SPEED * sqrt(1.0 / J2_R0) * sin(J2_INC)}, ths = 0;
  double xm[2], x[2], xp[2], th = 0.0;
  memcpy(xm, xs, sizeof xm);
  *dr_vs_rsprk = 0.0;
  if (st == GM_OK) {
    track_push(out, 0.0, xm, th);
    if ((st = gm_rsprk_step(r, h, xs, s, &ths)) != GM_OK)
      gm_error_set(err, st, "j2-satellite: first step: %s", gm_rsprk_errmsg(r));
    memcpy(x, xs, sizeof x);
    th = ths;
    if (st == GM_OK) track_push(out, h, x, th);
  }
  for (size_t i = 2; i <= n && st == GM_OK; ++i) {
    for (int j = 0; j < 2; ++j) xp[j] = 2 * x[j] - xm[j];
    if ((st = gm_routh_discrete_step(d, h, xm, x, xp, &th, NULL)) != GM_OK) {
      gm_error_set(err, st, "j2-satellite: step %zu: %s", i, gm_routh_discrete_errmsg(d));
      break;
    }
    if ((st = gm_rsprk_step(r, h, xs, s, &ths)) != GM_OK) {
      gm_error_set(err, st, "j2-satellite: step %zu: %s", i, gm_rsprk_errmsg(r));
      break;
    }
    *dr_vs_rsprk = fmax(*dr_vs_rsprk, fmax(fabs(xp[0] - xs[0]), fabs(xp[1] - xs[1])));
    *dr_vs_rsprk = fmax(*dr_vs_rsprk, fabs(th - ths));
    memcpy(xm, x, sizeof x);
    memcpy(x, xp, sizeof x);
    track_push(out, (double)i * h, x, th);
  }
  gm_routh_discrete_free(d);
  gm_rsprk_free(r);
  gm_tableau_free(t);
  return st;
}

/* largest distance from the points of a to the point set of b, in the reduced (r, z) view or
 * the unreduced (x, y, z) view; b's Cartesian points computed once (bx, by: b->n scratch) */
static double set_distance(const track *a, const track *b, int reduced, double *bx, double *by) {
  if (!reduced)
    for (size_t j = 0; j < b->n; ++j) {
      bx[j] = b->r[j] * cos(b->th[j]);
      by[j] = b->r[j] * sin(b->th[j]);
    }
  double worst = 0.0;
  for (size_t i = 0; i < a->n; ++i) {
    double best = INFINITY;
    const double ax = a->r[i] * cos(a->th[i]), ay = a->r[i] * sin(a->th[i]);
    for (size_t j = 0; j < b->n; ++j) {
      double d2;
      if (reduced)
        d2 = (a->r[i] - b->r[j]) * (a->r[i] - b->r[j]);
      else
        d2 = (ax - bx[j]) * (ax - bx[j]) + (ay - by[j]) * (ay - by[j]);
      d2 += (a->z[i] - b->z[j]) * (a->z[i] - b->z[j]);
      best = fmin(best, d2);
    }
    worst = fmax(worst, sqrt(best));
  }
  return worst;
}

/* the longitude of the ascending node from the angular momentum L = q × v, q, v from the samples
 * i−1, i, i+1 (central differences in Cartesian) */
static double node_longitude(const track *k, size_t i) {
  double q[3][3];
  for (int m = 0; m < 3; ++m) {
    const size_t j = i - 1 + (size_t)m;
    q[m][0] = k->r[j] * cos(k->th[j]);
    q[m][1] = k->r[j] * sin(k->th[j]);
    q[m][2] = k->z[j];
  }
  double v[3], L[3];
  for (int c = 0; c < 3; ++c) v[c] = q[2][c] - q[0][c];
  L[0] = q[1][1] * v[2] - q[1][2] * v[1];
  L[1] = q[1][2] * v[0] - q[1][0] * v[2];
  L[2] = q[1][0] * v[1] - q[1][1] * v[0];
  return atan2(L[0], -L[1]); /* node direction e_z × L */
}

/* unwrapped change of the node longitude from the start to the end */
static double node_drift(const track *k) {
  if (k->n < 4) return 0.0;
  double prev = node_longitude(k, 1), total = 0.0;
  for (size_t i = 2; i + 1 < k->n; ++i) {
    const double a = node_longitude(k, i);
    total += remainder(a - prev, 2 * GM_PI);
    prev = a;
  }
  return total;
}

static gm_status write_track(const char *dir, const char *name, const track *k, gm_error *err) {
  char path[GM_EXPERIMENT_PATH_SIZE];
  FILE *f = NULL;
  if (gm_experiment_path(path, sizeof path, dir, name) != GM_OK || (f = fopen(path, "w")) == NULL)
    return gm_error_set(err, GM_EIO, "j2-satellite: cannot write %s/%s", dir, name);
  fprintf(f, "t,r,z,theta,x,y\n");
  for (size_t i = 0; i < k->n; ++i)
    fprintf(f, "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", k->t[i], k->r[i], k->z[i], k->th[i],
            k->r[i] * cos(k->th[i]), k->r[i] * sin(k->th[i]));
  if ((ferror(f) | fclose(f)) != 0)
    return gm_error_set(err, GM_EIO, "j2-satellite: writing %s failed", path);
  return GM_OK;
}

gm_status gm_experiment_j2_satellite(const gm_j2_config *c, const char *dir, gm_j2_result *r,
                                     gm_error *err) {
  memset(r, 0, sizeof *r);
  if (!(c->dt > 0.0) || !(c->t_end > 0.0) || !isfinite(c->t_end))
    return gm_error_set(err, GM_EINVAL, "j2-satellite: dt = %g and t_end = %g must be > 0 and "
                        "finite", c->dt, c->t_end);
  if (c->dt > c->t_end)
    return gm_error_set(err, GM_EINVAL, "j2-satellite: dt %g is longer than the run (t_end %g)",
                        c->dt, c->t_end);
  if (c->t_end / c->dt > 1e6)
    return gm_error_set(err, GM_EINVAL, "j2-satellite: t_end/dt = %g steps is too many (at most "
                        "1e6)", c->t_end / c->dt);
  r->r0 = J2_R0;
  r->inclination = J2_INC;
  r->speed = J2_SPEED;
  r->mu = j2_mu();
  r->dt = c->dt;
  r->t_end = c->t_end;
  r->steps = (size_t)llround(c->t_end / c->dt);
  static const double j2s[2] = {0.0, 0.05};
  track cont[2], disc[2];
  memset(cont, 0, sizeof cont);
  memset(disc, 0, sizeof disc);
  gm_status st = GM_OK;
  const double t0 = gm_experiment_clock();
  for (int k = 0; k < 2 && st == GM_OK; ++k) {
    st = j2_reference(j2s[k], c->dt / 20.0, c->t_end, &cont[k], err);
    if (st == GM_OK) st = j2_discrete(j2s[k], c->dt, c->t_end, &disc[k], &r->discrete_vs_rsprk[k],
                                      err);
    if (st == GM_OK && dir != NULL) {
      char name[64];
      snprintf(name, sizeof name, "j2-%s-continuous.csv", k ? "0.05" : "0");
      st = write_track(dir, name, &cont[k], err);
      snprintf(name, sizeof name, "j2-%s-discrete.csv", k ? "0.05" : "0");
      if (st == GM_OK) st = write_track(dir, name, &disc[k], err);
    }
  }
  double *bx = NULL, *by = NULL;
  if (st == GM_OK) {
    bx = malloc(cont[0].n * sizeof *bx);
    by = malloc(cont[0].n * sizeof *by);
    if (bx == NULL || by == NULL)
      st = gm_error_set(err, GM_ENOMEM, "j2-satellite: cannot allocate %zu points", cont[0].n);
  }
  if (st == GM_OK) {
    for (int k = 0; k < 2; ++k) {
      r->node_drift_continuous[k] = node_drift(&cont[k]);
      r->node_drift_discrete[k] = node_drift(&disc[k]);
      r->continuous_j2_to_continuous_0[k] = set_distance(&cont[1], &cont[0], k, bx, by);
      r->discrete_0_to_continuous_0[k] = set_distance(&disc[0], &cont[0], k, bx, by);
      r->discrete_j2_to_continuous_0[k] = set_distance(&disc[1], &cont[0], k, bx, by);
      r->discrete_j2_to_continuous_j2[k] = set_distance(&disc[1], &cont[1], k, bx, by);
    }
  }
  free(bx);
  free(by);
  r->wall_s = gm_experiment_clock() - t0;
  for (int k = 0; k < 2; ++k) {
    track_free(&cont[k]);
    track_free(&disc[k]);
  }
  return st;
}

gm_status gm_experiment_run_j2_satellite(const char *dir, gm_experiment_result *out,
                                         gm_error *err) {
  const gm_j2_config c = gm_j2_defaults();
  gm_j2_result r;
  gm_status st = gm_experiment_j2_satellite(&c, dir, &r, err);
  if (st != GM_OK) return st;
  gm_experiment_add(out, "steps", (double)r.steps);
  gm_experiment_add(out, "node_drift_continuous_j2_0.05", r.node_drift_continuous[1]);
  gm_experiment_add(out, "node_drift_discrete_j2_0", r.node_drift_discrete[0]);
  gm_experiment_add(out, "node_drift_discrete_j2_0.05", r.node_drift_discrete[1]);
  gm_experiment_add(out, "discrete_0_to_continuous_0_unreduced", r.discrete_0_to_continuous_0[0]);
  gm_experiment_add(out, "discrete_0_to_continuous_0_reduced", r.discrete_0_to_continuous_0[1]);
  gm_experiment_add(out, "continuous_j2_to_continuous_0_unreduced",
                    r.continuous_j2_to_continuous_0[0]);
  gm_experiment_add(out, "continuous_j2_to_continuous_0_reduced",
                    r.continuous_j2_to_continuous_0[1]);
  gm_experiment_add(out, "max_discrete_vs_rsprk", fmax(r.discrete_vs_rsprk[0],
                                                       r.discrete_vs_rsprk[1]));
  gm_experiment_add(out, "wall_s", r.wall_s);
  gm_experiment_file(out, dir, "j2-0-continuous.csv");
  gm_experiment_file(out, dir, "j2-0-discrete.csv");
  gm_experiment_file(out, dir, "j2-0.05-continuous.csv");
  gm_experiment_file(out, dir, "j2-0.05-discrete.csv");
  return GM_OK;
}
