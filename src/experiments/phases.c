/* Seed 001 ch. 4: geometric phases computed with the discrete connections and the integrators,
 * against their closed forms: Foucault's pendulum at the Panthéon (-2 pi cos alpha), parallel
 * transport round a spherical cap (2 pi (1 - cos r)), Montgomery's rigid-body phase
 * (gm_rigid_body_phase: 2ET/|m| minus the solid angle), a shape loop of the double spherical
 * pendulum (-oint A dx of its mechanical connection) and the Levi-Civita holonomy of two tet
 * meshes against their deficit angles (the same cases are asserted in
 * tests/invariants/test_phases.c and test_dec_levi_civita_3d.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/dec.h"
#include "geomint/lie.h"
#include "geomint/methods.h"
#include "geomint/reduction.h"

#define PH_PI 3.14159265358979323846
/* the colatitude of the Panthéon, 48.8462 deg N */
#define ALPHA_PARIS ((90.0 - 48.8462) * PH_PI / 180.0)

static double wrap(double x) { return x - 2.0 * PH_PI * floor((x + PH_PI) / (2.0 * PH_PI)); }

typedef void (*loop_fn)(size_t n, double *pts);
typedef int (*conn_fn)(void *ctx, const double *x, double *a);

static void latitude(size_t n, double *pts) {
  for (size_t i = 0; i <= n; ++i) {
    const double phi = 2.0 * PH_PI * (double)(i % n) / (double)n;
    pts[2 * i] = sin(ALPHA_PARIS) * cos(phi);
    pts[2 * i + 1] = sin(ALPHA_PARIS) * sin(phi);
  }
}
static void cap(size_t n, double *pts) { /* radius 0.3 about colatitude 0.6 */
  const double c = 0.6, b = 0.3;
  for (size_t i = 0; i <= n; ++i) {
    const double s = 2.0 * PH_PI * (double)(i % n) / (double)n;
    pts[2 * i] = cos(b) * sin(c) + sin(b) * cos(s) * cos(c);
    pts[2 * i + 1] = sin(b) * sin(s);
  }
}

static int dsp_connection(void *ctx, const double *x, double *a) {
  const double mu[1] = {0.0};
  return gm_routh_connection(ctx, mu, x, NULL, a, NULL, NULL, NULL, NULL, NULL) == GM_OK ? 0 : -1;
}
static void dsp_at(double t, double *x) {
  x[0] = 0.5 + 0.2 * cos(t);
  x[1] = 0.4 + 0.1 * sin(2 * t);
  x[2] = 1.0 + 0.8 * sin(t);
}
static void dsp_loop(size_t n, double *pts) {
  for (size_t i = 0; i <= n; ++i) dsp_at(2.0 * PH_PI * (double)(i % n) / (double)n, pts + 3 * i);
}

static gm_phases_row *next_row(gm_phases_result *r, const char *what, const char *how) {
  gm_phases_row *row = &r->rows[r->n_rows++];
  memset(row, 0, sizeof *row);
  row->what = what;
  row->how = how;
  return row;
}

static gm_status loop_rows(gm_phases_result *r, const char *what, size_t n, conn_fn conn,
                           void *ctx, loop_fn f, double closed, gm_error *err) {
  static const struct {
    gm_dconn_rule rule;
    const char *name;
  } rules[] = {{GM_DCONN_MIDPOINT, "midpoint connection"}, {GM_DCONN_MAGNUS4, "Gauss-2 connection"}};
  for (int k = 0; k < 2; ++k) {
    gm_discrete_connection c;
    memset(&c, 0, sizeof c);
    c.group = GM_GROUP_SO2;
    c.n = n;
    c.rule = rules[k].rule;
    c.connection = conn;
    c.ctx = ctx;
    gm_discrete_connection ex = c;
    ex.rule = GM_DCONN_TRANSPORT;
    ex.substeps = 16;
    double e[2], ep[2], hol = 0, holex = 0, pts[3 * 129];
    for (int l = 0; l < 2; ++l) {
      const size_t N = (size_t)64 << l;
      f(N, pts);
      gm_status st = gm_dconn_holonomy(&c, N + 1, pts, &hol, err);
      if (st == GM_OK) st = gm_dconn_holonomy(&ex, N + 1, pts, &holex, err);
      if (st != GM_OK) return st;
      e[l] = fabs(hol - closed);
      ep[l] = fabs(hol - holex);
    }
    gm_phases_row *row = next_row(r, what, rules[k].name);
    row->closed = closed;
    row->computed = hol;
    row->error[0] = e[0];
    row->error[1] = e[1];
    snprintf(row->levels, sizeof row->levels,
             "N = 64, 128 points; vs the polygon's exact holonomy %.2e %.2e, order %.2f", ep[0],
             ep[1], log2(ep[0] / ep[1]));
  }
  return GM_OK;
}

/* the rigid body's attitude after n steps of one period with `row`, its angle about m */
static gm_status rigid_angle(const char *row, size_t n, double period, double *angle,
                             gm_error *err) {
  const double pi0[3] = {0.3, 0.2, 1.0};
  gm_model *model = NULL;
  gm_integrator *it = NULL;
  double t0, y0[12], m[3];
  gm_status st = gm_model_create("rigid-body", &model);
  if (st == GM_OK) st = gm_model_set(model, "Pi1", pi0[0]);
  if (st == GM_OK) st = gm_model_set(model, "Pi2", pi0[1]);
  if (st == GM_OK) st = gm_model_set(model, "Pi3", pi0[2]);
  if (st == GM_OK) st = gm_model_build(model);
  if (st == GM_OK) {
    gm_model_initial_state(model, &t0, y0);
    st = gm_integrator_create(gm_method_find(row), gm_model_problem(model), &it, NULL);
  }
  if (st == GM_OK) st = gm_integrator_set_state(it, t0, y0);
  if (st == GM_OK) st = gm_integrator_run(it, n, period / (double)n);
  if (st == GM_OK) {
    gm_mat3_vec(y0, y0 + 9, m);
    *angle = gm_so3_angle_about(y0, gm_integrator_state(it), m);
  } else {
    gm_error_set(err, st, "rigid-body phase with %s failed", row);
  }
  gm_integrator_free(it);
  gm_model_free(model);
  return st;
}

static gm_status rigid_rows(gm_phases_result *r, gm_error *err) {
  const double inertia[3] = {1.0, 2.0, 3.0}, pi0[3] = {0.3, 0.2, 1.0};
  double period, dyn, lambda;
  gm_status st = gm_rigid_body_phase(inertia, pi0, 0, &period, &dyn, &lambda, err);
  if (st != GM_OK) return st;
  r->rigid_period = period;
  r->rigid_dynamic = dyn;
  r->rigid_solid_angle = lambda;
  const double closed = wrap(dyn - lambda);
  static const char *const rows[] = {"lgvi", "lgvi-galerkin-2"};
  for (int k = 0; k < 2; ++k) {
    double e[2], got = 0;
    for (int l = 0; l < 2; ++l) {
      if ((st = rigid_angle(rows[k], (size_t)128 << l, period, &got, err)) != GM_OK) return st;
      e[l] = fabs(wrap(got - closed));
    }
    gm_phases_row *row = next_row(r, "rigid body, Montgomery, Pi0 = (.3,.2,1)", rows[k]);
    row->closed = closed;
    row->computed = got;
    row->error[0] = e[0];
    row->error[1] = e[1];
    snprintf(row->levels, sizeof row->levels, "h = T/128, T/256");
  }
  return GM_OK;
}

static gm_status mesh_row(gm_phases_result *r, const char *what, size_t N, size_t nv,
                          const double *x, size_t nt, const size_t *top, double closed,
                          gm_error *err) {
  gm_complex *cx = NULL;
  gm_status st = gm_complex_create(N, nv, x, 3, nt, top, &cx, err);
  if (st != GM_OK) return st;
  const size_t nf = gm_complex_count(cx, 2), ne = gm_complex_count(cx, 1);
  double *R = malloc(9 * nf * sizeof *R), *ang = malloc(ne * sizeof *ang),
         *def = malloc(ne * sizeof *def);
  if (R == NULL || ang == NULL || def == NULL)
    st = gm_error_set(err, GM_ENOMEM, "phases: out of memory");
  if (st == GM_OK && (st = gm_dec_levi_civita_3d(cx, R)) != GM_OK)
    gm_error_set(err, st, "%s: the Levi-Civita transport failed", what);
  if (st == GM_OK) st = gm_dec_curvature_3d(cx, R, NULL, ang, def, err);
  if (st == GM_OK) {
    const unsigned char *bd = gm_complex_boundary_mask(cx, 1);
    double worst = 0.0, got = 0.0, dmax = 0.0;
    for (size_t e = 0; e < ne; ++e)
      if (!bd[e]) {
        worst = fmax(worst, fabs(wrap(ang[e] - def[e])));
        if (fabs(def[e]) > dmax) dmax = fabs(def[e]), got = ang[e];
      }
    gm_phases_row *row = next_row(r, what, "tet Levi-Civita");
    row->mesh = 1;
    row->closed = closed;
    row->computed = got;
    row->error[0] = worst;
    row->error[1] = NAN;
    snprintf(row->levels, sizeof row->levels, "max |angle - deficit| over interior edges");
  }
  free(R);
  free(ang);
  free(def);
  gm_complex_free(cx);
  return st;
}

/* cone: 7 wedges, depth 0.6, in R^4 */
static gm_status cone_row(gm_phases_result *r, gm_error *err) {
  enum { m = 7 };
  const double h = 0.6;
  double x[4 * (2 + 2 * m)];
  size_t top[4 * 3 * m], nt = 0;
  memset(x, 0, sizeof x);
  x[7] = 1.0;
  for (int j = 0; j < m; ++j) {
    double *p = x + 4 * (2 + j), *q = x + 4 * (2 + m + j);
    p[0] = q[0] = cos(2 * PH_PI * j / m);
    p[1] = q[1] = sin(2 * PH_PI * j / m);
    p[2] = q[2] = -h;
    q[3] = 1.0;
    size_t b[3] = {0, 2 + (size_t)j, 2 + (size_t)((j + 1) % m)}, u[3];
    if (b[1] > b[2]) {
      size_t t = b[1];
      b[1] = b[2];
      b[2] = t;
    }
    for (int k = 0; k < 3; ++k) u[k] = b[k] == 0 ? 1 : b[k] + m;
    const size_t tets[12] = {b[0], b[1], b[2], u[2], b[0], b[1], u[1], u[2], b[0], u[0], u[1], u[2]};
    memcpy(top + 4 * nt, tets, sizeof tets);
    nt += 3;
  }
  const double closed = 2 * PH_PI - m * acos((cos(2 * PH_PI / m) + h * h) / (1 + h * h));
  return mesh_row(r, "cone singularity (7 wedges, R^4)", 4, 2 + 2 * m, x, nt, top, closed, err);
}

/* the 16-cell's boundary on S^3 */
static gm_status sphere3_row(gm_phases_result *r, gm_error *err) {
  double x[32];
  size_t top[64];
  memset(x, 0, sizeof x);
  for (int i = 0; i < 4; ++i) x[4 * (2 * i) + i] = 1.0, x[4 * (2 * i + 1) + i] = -1.0;
  for (size_t s = 0; s < 16; ++s)
    for (size_t i = 0; i < 4; ++i) top[4 * s + i] = 2 * i + ((s >> i) & 1);
  return mesh_row(r, "S^3 as the 16-cell's boundary", 4, 8, x, 16, top,
                  2 * PH_PI - 4 * acos(1.0 / 3.0), err);
}

/* error of one discrete connection's holonomy vs a closed form or (vs_polygon) vs the
 * polygon's exact holonomy */
static double loop_error(size_t n, conn_fn conn, void *ctx, loop_fn f, gm_dconn_rule rule,
                         double closed, int vs_polygon, size_t N) {
  gm_discrete_connection c;
  memset(&c, 0, sizeof c);
  c.group = GM_GROUP_SO2;
  c.n = n;
  c.rule = rule;
  c.connection = conn;
  c.ctx = ctx;
  gm_discrete_connection ex = c;
  ex.rule = GM_DCONN_TRANSPORT;
  ex.substeps = 16;
  double *pts = malloc(3 * (N + 1) * sizeof *pts), hol = NAN, ref = closed;
  if (pts == NULL) return NAN;
  f(N, pts);
  if (gm_dconn_holonomy(&c, N + 1, pts, &hol, NULL) != GM_OK ||
      (vs_polygon && gm_dconn_holonomy(&ex, N + 1, pts, &ref, NULL) != GM_OK))
    hol = NAN;
  free(pts);
  return fabs(hol - ref);
}

static double rigid_error(const char *row, size_t n, double period, double closed) {
  double angle;
  gm_error ignored = {{0}};
  return rigid_angle(row, n, period, &angle, &ignored) == GM_OK ? fabs(wrap(angle - closed))
                                                                 : NAN;
}

static gm_status write_convergence(const gm_phases_result *r, gm_routh_system *dsp,
                                   const char *dir, gm_error *err) {
  char path[GM_EXPERIMENT_PATH_SIZE];
  FILE *f = NULL;
  if (gm_experiment_path(path, sizeof path, dir, "phases-convergence.csv") != GM_OK ||
      (f = fopen(path, "w")) == NULL)
    return gm_error_set(err, GM_EIO, "cannot write '%s/phases-convergence.csv'", dir);
  const double rb = wrap(r->rigid_dynamic - r->rigid_solid_angle);
  const double fc = -2.0 * PH_PI * cos(ALPHA_PARIS);
  fprintf(f, "N,foucault_midpoint,foucault_gauss2,foucault_gauss2_vs_polygon,dsp_midpoint_vs_polygon,"
             "dsp_gauss2_vs_polygon,rigid_lgvi,rigid_lgvi_galerkin2\n");
  for (size_t N = 16; N <= 512; N *= 2) {
    const double v[7] = {
        loop_error(2, gm_sphere_levi_civita, NULL, latitude, GM_DCONN_MIDPOINT, fc, 0, N),
        loop_error(2, gm_sphere_levi_civita, NULL, latitude, GM_DCONN_MAGNUS4, fc, 0, N),
        loop_error(2, gm_sphere_levi_civita, NULL, latitude, GM_DCONN_MAGNUS4, fc, 1, N),
        loop_error(3, dsp_connection, dsp, dsp_loop, GM_DCONN_MIDPOINT, 0, 1, N),
        loop_error(3, dsp_connection, dsp, dsp_loop, GM_DCONN_MAGNUS4, 0, 1, N),
        rigid_error("lgvi", N, r->rigid_period, rb),
        rigid_error("lgvi-galerkin-2", N, r->rigid_period, rb)};
    fprintf(f, "%zu", N);
    for (int k = 0; k < 7; ++k) fprintf(f, ",%.6e", v[k]);
    fprintf(f, "\n");
  }
  if (fclose(f) != 0) return gm_error_set(err, GM_EIO, "cannot write '%s'", path);
  return GM_OK;
}

gm_status gm_experiment_phases(const char *dir, gm_phases_result *r, gm_error *err) {
  memset(r, 0, sizeof *r);
  const double t0 = gm_experiment_clock();
  gm_routh_dsp_params dspp = {1.0, 0.7, 1.0, 0.8, 9.81};
  gm_routh_system dsp;
  gm_routh_double_spherical_pendulum(&dspp, &dsp);
  gm_status st = loop_rows(r, "Foucault, Paris: -2 pi cos(alpha)", 2, gm_sphere_levi_civita,
                           NULL, latitude, -2.0 * PH_PI * cos(ALPHA_PARIS), err);
  if (st == GM_OK)
    st = loop_rows(r, "sphere cap r = 0.3: 2 pi (1 - cos r)", 2, gm_sphere_levi_civita, NULL,
                   cap, 2.0 * PH_PI * (1.0 - cos(0.3)), err);
  if (st == GM_OK) st = rigid_rows(r, err);
  if (st == GM_OK) {
    double closed = 0.0;
    for (int i = 0; i < 4096 && st == GM_OK; ++i) { /* -oint A dx, trapezoid in t (spectral) */
      const double t = 2 * PH_PI * i / 4096.0,
                   dx[3] = {-0.2 * sin(t), 0.2 * cos(2 * t), 0.8 * cos(t)};
      double x[3], a[3];
      dsp_at(t, x);
      if (dsp_connection(&dsp, x, a) != 0)
        st = gm_error_set(err, GM_ECALLBACK, "the double spherical pendulum's connection "
                          "failed at t = %g of the shape loop", t);
      closed -= (a[0] * dx[0] + a[1] * dx[1] + a[2] * dx[2]) * 2 * PH_PI / 4096.0;
    }
    if (st == GM_OK)
      st = loop_rows(r, "double sph. pendulum loop, mu = 0", 3, dsp_connection, &dsp, dsp_loop,
                     closed, err);
  }
  if (st == GM_OK) st = cone_row(r, err);
  if (st == GM_OK) st = sphere3_row(r, err);
  if (st == GM_OK && dir != NULL) st = write_convergence(r, &dsp, dir, err);
  if (st != GM_OK) return st;
  for (size_t i = 0; i < r->n_rows; ++i)
    r->max_error = fmax(r->max_error, r->rows[i].mesh ? r->rows[i].error[0] : r->rows[i].error[1]);
  r->wall_s = gm_experiment_clock() - t0;
  return GM_OK;
}

gm_status gm_experiment_run_phases(const char *dir, gm_experiment_result *result, gm_error *err) {
  gm_phases_result r;
  gm_status st = gm_experiment_phases(dir, &r, err);
  if (st != GM_OK) return st;
  gm_experiment_add(result, "rows", (double)r.n_rows);
  gm_experiment_add(result, "max_abs_phase_error", r.max_error);
  gm_experiment_add(result, "wall_s", r.wall_s);
  gm_experiment_file(result, dir, "phases-convergence.csv");
  return GM_OK;
}
