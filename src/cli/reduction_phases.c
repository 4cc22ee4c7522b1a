/* geomint reduction phases: geometric phases computed with the discrete connections and the
 * integrators, against their closed forms (docs/reduction.md, "Phases"; the same cases are
 * asserted in tests/invariants/test_phases.c and test_dec_levi_civita_3d.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/reduction_phases.h"

#define PI 3.14159265358979323846

static double wrap(double x) { return x - 2.0 * PI * floor((x + PI) / (2.0 * PI)); }

typedef void (*loop_fn)(size_t n, double *pts);

static double alpha_paris; /* colatitude of the Panthéon, 48.8462° N */
static void latitude(size_t n, double *pts) {
  for (size_t i = 0; i <= n; ++i) {
    const double phi = 2.0 * PI * (double)(i % n) / (double)n;
    pts[2 * i] = sin(alpha_paris) * cos(phi);
    pts[2 * i + 1] = sin(alpha_paris) * sin(phi);
  }
}
static void cap(size_t n, double *pts) { /* radius 0.3 about colatitude 0.6 */
  const double c = 0.6, b = 0.3;
  for (size_t i = 0; i <= n; ++i) {
    const double s = 2.0 * PI * (double)(i % n) / (double)n;
    pts[2 * i] = cos(b) * sin(c) + sin(b) * cos(s) * cos(c);
    pts[2 * i + 1] = sin(b) * sin(s);
  }
}

static gm_routh_dsp_params dspp = {1.0, 0.7, 1.0, 0.8, 9.81};
static gm_routh_system dsp_sys;
static int dsp_connection(void *ctx, const double *x, double *a) {
  (void)ctx;
  const double mu[1] = {0.0};
  return gm_routh_connection(&dsp_sys, mu, x, NULL, a, NULL, NULL, NULL, NULL, NULL) == GM_OK ? 0 : -1;
}
static void dsp_at(double t, double *x) {
  x[0] = 0.5 + 0.2 * cos(t);
  x[1] = 0.4 + 0.1 * sin(2 * t);
  x[2] = 1.0 + 0.8 * sin(t);
}
static void dsp_loop(size_t n, double *pts) {
  for (size_t i = 0; i <= n; ++i) dsp_at(2.0 * PI * (double)(i % n) / (double)n, pts + 3 * i);
}

static void row(const char *what, const char *how, double closed, double fine, double e1,
                double e2, const char *levels) {
  printf("%-40s %-20s %15.10f %15.10f %9.2e %9.2e %6.2f  %s\n", what, how, closed, fine, e1, e2,
         log2(e1 / e2), levels);
}

static int loop_rows(const char *what, size_t n, int (*conn)(void *, const double *, double *),
                     loop_fn f, double closed) {
  static const struct {
    gm_dconn_rule rule;
    const char *name;
  } rules[] = {{GM_DCONN_MIDPOINT, "midpoint connection"}, {GM_DCONN_MAGNUS4, "Gauss-2 connection"}};
  for (int r = 0; r < 2; ++r) {
    gm_discrete_connection c;
    memset(&c, 0, sizeof c);
    c.group = GM_GROUP_SO2;
    c.n = n;
    c.rule = rules[r].rule;
    c.connection = conn;
    gm_discrete_connection ex = c;
    ex.rule = GM_DCONN_TRANSPORT;
    ex.substeps = 16;
    double e[2], ep[2], hol = 0, holex = 0, pts[3 * 129];
    gm_error err;
    for (int l = 0; l < 2; ++l) {
      const size_t N = (size_t)64 << l;
      f(N, pts);
      if (gm_dconn_holonomy(&c, N + 1, pts, &hol, &err) != GM_OK ||
          gm_dconn_holonomy(&ex, N + 1, pts, &holex, &err) != GM_OK) {
        cli_error("reduction", "%s", err.message);
        return CLI_EXIT_FAILURE;
      }
      e[l] = fabs(hol - closed);
      ep[l] = fabs(hol - holex);
    }
    char levels[160];
    snprintf(levels, sizeof levels, "N = 64, 128 points; vs the polygon's exact holonomy %.2e %.2e, order %.2f",
             ep[0], ep[1], log2(ep[0] / ep[1]));
    row(what, rules[r].name, closed, hol, e[0], e[1], levels);
  }
  return CLI_EXIT_OK;
}

static int rigid_rows(void) {
  const double inertia[3] = {1.0, 2.0, 3.0}, pi0[3] = {0.3, 0.2, 1.0};
  double period, dyn, lambda;
  gm_error err;
  if (gm_rigid_body_phase(inertia, pi0, 0, &period, &dyn, &lambda, &err) != GM_OK) {
    cli_error("reduction", "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  const double closed = wrap(dyn - lambda);
  static const char *rows[] = {"lgvi", "lgvi-galerkin-2"};
  for (int r = 0; r < 2; ++r) {
    double e[2], got = 0;
    for (int l = 0; l < 2; ++l) {
      gm_model *model = NULL;
      const gm_problem *pb;
      gm_integrator *it = NULL;
      double t0, y0[12], m[3];
      int bad = gm_model_create("rigid-body", &model) != GM_OK ||
                gm_model_set(model, "Pi1", pi0[0]) != GM_OK || gm_model_set(model, "Pi2", pi0[1]) != GM_OK ||
                gm_model_set(model, "Pi3", pi0[2]) != GM_OK || gm_model_build(model) != GM_OK;
      if (!bad) {
        pb = gm_model_problem(model);
        gm_model_initial_state(model, &t0, y0);
        bad = gm_integrator_create(gm_method_find(rows[r]), pb, &it, &err) != GM_OK ||
              gm_integrator_set_state(it, t0, y0) != GM_OK ||
              gm_integrator_run(it, (size_t)128 << l, period / (double)(128 << l)) != GM_OK;
      }
      if (bad) {
        cli_error("reduction", "rigid-body phase with %s failed", rows[r]);
        gm_integrator_free(it);
        gm_model_free(model);
        return CLI_EXIT_FAILURE;
      }
      gm_mat3_vec(y0, y0 + 9, m);
      got = gm_so3_angle_about(y0, gm_integrator_state(it), m);
      e[l] = fabs(wrap(got - closed));
      gm_integrator_free(it);
      gm_model_free(model);
    }
    row("rigid body, Montgomery, Pi0 = (.3,.2,1)", rows[r], closed, got, e[0], e[1], "h = T/128, T/256");
  }
  printf("%-40s T = %.10f, 2ET/|m| = %.10f, solid angle %.10f\n", "", period, dyn, lambda);
  return CLI_EXIT_OK;
}

static int mesh_row(const char *what, size_t N, size_t nv, const double *x, size_t nt,
                    const size_t *top, double closed) {
  gm_complex *cx = NULL;
  gm_error err;
  if (gm_complex_create(N, nv, x, 3, nt, top, &cx, &err) != GM_OK) {
    cli_error("reduction", "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  const size_t nf = gm_complex_count(cx, 2), ne = gm_complex_count(cx, 1);
  double *R = malloc(9 * nf * sizeof *R), *ang = malloc(ne * sizeof *ang), *def = malloc(ne * sizeof *def);
  int rc = CLI_EXIT_FAILURE;
  if (R && ang && def && gm_dec_levi_civita_3d(cx, R) == GM_OK &&
      gm_dec_curvature_3d(cx, R, NULL, ang, def, &err) == GM_OK) {
    const unsigned char *bd = gm_complex_boundary_mask(cx, 1);
    double worst = 0.0, got = 0.0, dmax = 0.0;
    for (size_t e = 0; e < ne; ++e)
      if (!bd[e]) {
        worst = fmax(worst, fabs(wrap(ang[e] - def[e])));
        if (fabs(def[e]) > dmax) dmax = fabs(def[e]), got = ang[e];
      }
    printf("%-40s %-20s %15.10f %15.10f %9.2e %9s %6s  max |angle - deficit| over interior edges\n",
           what, "tet Levi-Civita", closed, got, worst, "", "");
    rc = CLI_EXIT_OK;
  }
  free(R), free(ang), free(def);
  gm_complex_free(cx);
  return rc;
}

int cli_reduction_phases(void) {
  alpha_paris = (90.0 - 48.8462) * PI / 180.0;
  printf("Geometric phases: computed vs closed form (errors at the two levels; order = log2 ratio)\n");
  printf("%-40s %-20s %15s %15s %9s %9s %6s  %s\n", "phase", "method", "closed form", "computed",
         "error 1", "error 2", "order", "levels");
  int rc = loop_rows("Foucault, Paris: -2 pi cos(alpha)", 2, gm_sphere_levi_civita, latitude,
                     -2.0 * PI * cos(alpha_paris));
  if (rc == CLI_EXIT_OK)
    rc = loop_rows("sphere cap r = 0.3: 2 pi (1 - cos r)", 2, gm_sphere_levi_civita, cap,
                   2.0 * PI * (1.0 - cos(0.3)));
  if (rc == CLI_EXIT_OK) rc = rigid_rows();
  if (rc == CLI_EXIT_OK) {
    gm_routh_double_spherical_pendulum(&dspp, &dsp_sys);
    double closed = 0.0;
    for (int i = 0; i < 4096; ++i) { /* −∮A·dx, trapezoid in t (periodic: spectral) */
      const double t = 2 * PI * i / 4096.0, dx[3] = {-0.2 * sin(t), 0.2 * cos(2 * t), 0.8 * cos(t)};
      double x[3], a[3];
      dsp_at(t, x);
      if (dsp_connection(NULL, x, a) != 0) return CLI_EXIT_FAILURE;
      closed -= (a[0] * dx[0] + a[1] * dx[1] + a[2] * dx[2]) * 2 * PI / 4096.0;
    }
    rc = loop_rows("double sph. pendulum loop, mu = 0", 3, dsp_connection, dsp_loop, closed);
  }
  if (rc == CLI_EXIT_OK) { /* cone: 7 wedges, depth 0.6, in R⁴ */
    enum { m = 7 };
    const double h = 0.6;
    double x[4 * (2 + 2 * m)];
    size_t top[4 * 3 * m], nt = 0;
    memset(x, 0, sizeof x);
    x[7] = 1.0;
    for (int j = 0; j < m; ++j) {
      double *p = x + 4 * (2 + j), *q = x + 4 * (2 + m + j);
      p[0] = q[0] = cos(2 * PI * j / m);
      p[1] = q[1] = sin(2 * PI * j / m);
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
    const double closed = 2 * PI - m * acos((cos(2 * PI / m) + h * h) / (1 + h * h));
    rc = mesh_row("cone singularity (7 wedges, R^4)", 4, 2 + 2 * m, x, nt, top, closed);
  }
  if (rc == CLI_EXIT_OK) { /* the 16-cell's boundary on S³ */
    double x[32];
    size_t top[64];
    memset(x, 0, sizeof x);
    for (int i = 0; i < 4; ++i) x[4 * (2 * i) + i] = 1.0, x[4 * (2 * i + 1) + i] = -1.0;
    for (size_t s = 0; s < 16; ++s)
      for (size_t i = 0; i < 4; ++i) top[4 * s + i] = 2 * i + ((s >> i) & 1);
    rc = mesh_row("S^3 as the 16-cell's boundary", 4, 8, x, 16, top, 2 * PI - 4 * acos(1.0 / 3.0));
  }
  return rc;
}

/* error of one discrete connection's holonomy vs a closed form (exact == NULL) or vs the
 * polygon's exact holonomy */
static double loop_error(size_t n, int (*conn)(void *, const double *, double *), loop_fn f,
                         gm_dconn_rule rule, double closed, int vs_polygon, size_t N) {
  gm_discrete_connection c;
  memset(&c, 0, sizeof c);
  c.group = GM_GROUP_SO2;
  c.n = n;
  c.rule = rule;
  c.connection = conn;
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
  const double pi0[3] = {0.3, 0.2, 1.0};
  gm_model *model = NULL;
  gm_integrator *it = NULL;
  double t0, y0[12], m[3], err = NAN;
  if (gm_model_create("rigid-body", &model) == GM_OK && gm_model_set(model, "Pi1", pi0[0]) == GM_OK &&
      gm_model_set(model, "Pi2", pi0[1]) == GM_OK && gm_model_set(model, "Pi3", pi0[2]) == GM_OK &&
      gm_model_build(model) == GM_OK) {
    gm_model_initial_state(model, &t0, y0);
    if (gm_integrator_create(gm_method_find(row), gm_model_problem(model), &it, NULL) == GM_OK &&
        gm_integrator_set_state(it, t0, y0) == GM_OK &&
        gm_integrator_run(it, n, period / (double)n) == GM_OK) {
      gm_mat3_vec(y0, y0 + 9, m);
      err = fabs(wrap(gm_so3_angle_about(y0, gm_integrator_state(it), m) - closed));
    }
  }
  gm_integrator_free(it);
  gm_model_free(model);
  return err;
}

int cli_reduction_phases_convergence(FILE *f) {
  alpha_paris = (90.0 - 48.8462) * PI / 180.0;
  gm_routh_double_spherical_pendulum(&dspp, &dsp_sys);
  const double inertia[3] = {1.0, 2.0, 3.0}, pi0[3] = {0.3, 0.2, 1.0};
  double period, dyn, lambda;
  if (gm_rigid_body_phase(inertia, pi0, 0, &period, &dyn, &lambda, NULL) != GM_OK) return CLI_EXIT_FAILURE;
  const double rb = wrap(dyn - lambda), fc = -2.0 * PI * cos(alpha_paris);
  fprintf(f, "N,foucault_midpoint,foucault_gauss2,foucault_gauss2_vs_polygon,dsp_midpoint_vs_polygon,"
             "dsp_gauss2_vs_polygon,rigid_lgvi,rigid_lgvi_galerkin2\n");
  for (size_t N = 16; N <= 512; N *= 2) {
    const double v[7] = {
        loop_error(2, gm_sphere_levi_civita, latitude, GM_DCONN_MIDPOINT, fc, 0, N),
        loop_error(2, gm_sphere_levi_civita, latitude, GM_DCONN_MAGNUS4, fc, 0, N),
        loop_error(2, gm_sphere_levi_civita, latitude, GM_DCONN_MAGNUS4, fc, 1, N),
        loop_error(3, dsp_connection, dsp_loop, GM_DCONN_MIDPOINT, 0, 1, N),
        loop_error(3, dsp_connection, dsp_loop, GM_DCONN_MAGNUS4, 0, 1, N),
        rigid_error("lgvi", N, period, rb), rigid_error("lgvi-galerkin-2", N, period, rb)};
    fprintf(f, "%zu", N);
    for (int k = 0; k < 7; ++k) fprintf(f, ",%.6e", v[k]);
    fprintf(f, "\n");
  }
  return CLI_EXIT_OK;
}

