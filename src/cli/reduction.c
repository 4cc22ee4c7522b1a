/* geomint reduction EXPERIMENT: the two experiments of seed 001 §2.9–2.10 (Leok, thesis (2004)) with
 * the Routh reduction API (include/geomint/reduction.h): data, figures and the measured numbers. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "cli/reduction_phases.h"

static const char usage[] =
    "usage: geomint reduction j2-satellite|double-spherical-pendulum [--out DIR] [--no-plot]\n"
    "                           [--dt H] [--t-end T] [--mu M] [--x0 LIST]\n"
    "       geomint reduction phases [--out DIR] [--no-plot]\n\n"
    "Discrete Routh reduction experiments of seed 001 (Leok, thesis 2004, sections 2.9-2.10):\n"
    "  j2-satellite     satellite about an oblate planet, J2 in {0, 0.05}, midpoint discrete\n"
    "                   Lagrangian (discrete Routh equations) at dt = 0.3 against a 6th-order\n"
    "                   RSPRK reference at dt/20; unreduced (x, y, z) and reduced (r, z) views,\n"
    "                   t = 0..150 (figures 2.2-2.5)\n"
    "  double-spherical-pendulum\n"
    "                   4th-order RSPRK against 4th-order SPRK on the classical Routhian and\n"
    "                   RK4 on the unreduced system at dt/4; dt = 0.01, t = 0..20 (figures\n"
    "                   2.7-2.9); m1 = m2 = 1, l1 = l2 = 1, g = 9.81, mu = 1; also the\n"
    "                   constrained R^3 x R^3 form (vi-galerkin-gauss-2) from the same state\n"
    "  phases           geometric phases against closed forms (seed 001 ch. 4): Foucault's\n"
    "                   pendulum and a spherical cap (Levi-Civita holonomy of the sphere),\n"
    "                   Montgomery's rigid-body phase (lgvi, lgvi-galerkin-2), a shape loop of\n"
    "                   the double spherical pendulum at mu = 0, and the tet-mesh Levi-Civita\n"
    "                   holonomy against the deficit angle; prints the table; with --out also\n"
    "                   DIR/phases-convergence.csv and .png (errors vs points / steps)\n"
    "Writes DIR/*.csv and draws DIR/*.png with gnuplot; prints the measured numbers.\n\n"
    "options:\n"
    "  --out DIR   output directory, created if missing (default reduction-output)\n"
    "  --no-plot   write the data only\n"
    "  --dt H      step size (default as above)\n"
    "  --t-end T   final time (default as above)\n"
    "  --mu M      double-spherical-pendulum: momentum level (default 1)\n"
    "  --x0 LIST   double-spherical-pendulum: r1,r2,phi,r1dot,r2dot,phidot (default\n"
    "              0.5,0.4,2,0,0,0)\n";

static int make_directory(const char *dir) {
  if (mkdir(dir, 0777) == 0 || errno == EEXIST) return 0;
  cli_error("reduction", "cannot create directory %s: %s", dir, strerror(errno));
  return 1;
}

static FILE *open_out(const char *dir, const char *name) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  if (f == NULL) cli_error("reduction", "cannot write %s: %s", path, strerror(errno));
  return f;
}

/* run a gnuplot script (text) that writes png; returns an exit status */
static int plot(const char *dir, const char *png, const char *script) {
  char path[1024], cmd[1200];
  snprintf(path, sizeof path, "%s/%s", dir, png);
  if (!cli_gnuplot_available()) {
    cli_error("reduction", "cannot draw %s: gnuplot is not installed (use --no-plot)", path);
    return CLI_EXIT_FAILURE;
  }
  snprintf(cmd, sizeof cmd, "cd '%s' && exec gnuplot >/dev/null 2>&1", dir);
  FILE *g = popen(cmd, "w");
  if (g == NULL) return CLI_EXIT_FAILURE;
  fprintf(g, "set terminal pngcairo size 1000,450 font ',10'\nset output '%s'\nset datafile separator ','\nset key top right\n%s\nunset output\n",
          png, script);
  if (pclose(g) != 0) {
    cli_error("reduction", "gnuplot failed to draw %s", path);
    return CLI_EXIT_FAILURE;
  }
  FILE *chk = fopen(path, "r");
  if (chk == NULL) {
    cli_error("reduction", "gnuplot did not write %s", path);
    return CLI_EXIT_FAILURE;
  }
  fclose(chk);
  return CLI_EXIT_OK;
}

/* ---- J2 satellite ------------------------------------------------------------------------ */

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

static int track_alloc(track *k, size_t n) {
  k->n = 0;
  k->t = malloc(n * sizeof(double));
  k->r = malloc(n * sizeof(double));
  k->z = malloc(n * sizeof(double));
  k->th = malloc(n * sizeof(double));
  return !(k->t && k->r && k->z && k->th);
}

static void track_push(track *k, double t, const double *x, double th) {
  k->t[k->n] = t;
  k->r[k->n] = x[0];
  k->z[k->n] = x[1];
  k->th[k->n] = th;
  k->n++;
}

/* initial condition: r = 1.5, z = 0, speed 1.1 v_circ, inclination 0.3 rad (inclined ellipse) */
#define J2_R0 1.5
#define J2_INC 0.3
#define J2_SPEED 1.1

static double j2_mu(void) { return J2_R0 * J2_SPEED * sqrt(1.0 / J2_R0) * cos(J2_INC); }

static int j2_reference(double j2, double h, double t_end, track *out) {
  gm_routh_j2_params p = {j2};
  gm_routh_system sys;
  gm_routh_j2_satellite(&p, &sys);
  static const double nodes[3] = {0.11270166537925831148, 0.5, 0.88729833462074168852};
  gm_tableau *t = NULL;
  gm_rsprk *r = NULL;
  const double mu[1] = {j2_mu()};
  gm_error err;
  const size_t n = (size_t)llround(t_end / h);
  if (gm_galerkin_prk_tableau(3, nodes, &t) != GM_OK ||
      gm_rsprk_create(&sys, t, GM_ROUTH_RSPRK, mu, &r, &err) != GM_OK || track_alloc(out, n + 1)) {
    gm_tableau_free(t);
    return 1;
  }
  double x[2] = {J2_R0, 0.0}, s[2] = {0.0, J2_SPEED * sqrt(1.0 / J2_R0) * sin(J2_INC)}, th = 0.0;
  track_push(out, 0.0, x, th);
  int rc = 0;
  for (size_t i = 1; i <= n && !rc; ++i) {
    if (gm_rsprk_step(r, h, x, s, &th) != GM_OK) {
      cli_error("reduction", "%s", gm_rsprk_errmsg(r));
      rc = 1;
    } else {
      track_push(out, (double)i * h, x, th);
    }
  }
  gm_rsprk_free(r);
  gm_tableau_free(t);
  return rc;
}

/* the discrete flow: the discrete Routh equations of the midpoint L_d with reconstruction; the
 * first step from the reduced Legendre transform (RSPRK with the 1-point Gauss tableau, which is
 * that L_d's push-forward); returns also the largest difference to that RSPRK along the run */
static int j2_discrete(double j2, double h, double t_end, track *out, double *dr_vs_rsprk) {
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
  if (gm_galerkin_prk_tableau(1, &half, &t) != GM_OK ||
      gm_rsprk_create(&sys, t, GM_ROUTH_RSPRK, mu, &r, NULL) != GM_OK ||
      gm_routh_discrete_create(&ld, &sys, mu, NULL, &d, NULL) != GM_OK || track_alloc(out, n + 1)) {
    gm_tableau_free(t);
    gm_rsprk_free(r);
    return 1;
  }
  double xs[2] = {J2_R0, 0.0}, s[2] = {0.0, J2_SPEED * sqrt(1.0 / J2_R0) * sin(J2_INC)}, ths = 0;
  double xm[2], x[2], xp[2], th = 0.0;
  memcpy(xm, xs, sizeof xm);
  track_push(out, 0.0, xm, th);
  int rc = gm_rsprk_step(r, h, xs, s, &ths) != GM_OK;
  memcpy(x, xs, sizeof x);
  th = ths;
  if (!rc) track_push(out, h, x, th);
  *dr_vs_rsprk = 0.0;
  for (size_t i = 2; i <= n && !rc; ++i) {
    for (int j = 0; j < 2; ++j) xp[j] = 2 * x[j] - xm[j];
    if (gm_routh_discrete_step(d, h, xm, x, xp, &th, NULL) != GM_OK) {
      cli_error("reduction", "%s", gm_routh_discrete_errmsg(d));
      rc = 1;
      break;
    }
    if (gm_rsprk_step(r, h, xs, s, &ths) != GM_OK) {
      cli_error("reduction", "%s", gm_rsprk_errmsg(r));
      rc = 1;
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
  return rc;
}

/* largest distance from the points of a to the point set of b, in the reduced (r, z) view or
 * the unreduced (x, y, z) view */
static double set_distance(const track *a, const track *b, int reduced) {
  double worst = 0.0;
  for (size_t i = 0; i < a->n; ++i) {
    double best = INFINITY;
    const double ax = a->r[i] * cos(a->th[i]), ay = a->r[i] * sin(a->th[i]);
    for (size_t j = 0; j < b->n; ++j) {
      double d2;
      if (reduced) {
        d2 = (a->r[i] - b->r[j]) * (a->r[i] - b->r[j]);
      } else {
        const double bx = b->r[j] * cos(b->th[j]), by = b->r[j] * sin(b->th[j]);
        d2 = (ax - bx) * (ax - bx) + (ay - by) * (ay - by);
      }
      d2 += (a->z[i] - b->z[j]) * (a->z[i] - b->z[j]);
      best = fmin(best, d2);
    }
    worst = fmax(worst, sqrt(best));
  }
  return worst;
}

/* the longitude of the ascending node from the last two samples' angular momentum */
static double node_longitude(const track *k, size_t i) {
  /* L = q × v with q, v from the samples i−1, i+1 (central differences in Cartesian) */
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

static double node_drift(const track *k) {
  /* unwrapped change of the node longitude from the start to the end */
  double prev = node_longitude(k, 1), total = 0.0;
  for (size_t i = 2; i + 1 < k->n; ++i) {
    const double a = node_longitude(k, i);
    total += remainder(a - prev, 2 * 3.14159265358979323846);
    prev = a;
  }
  return total;
}

static int write_track(const char *dir, const char *name, const track *k) {
  FILE *f = open_out(dir, name);
  if (f == NULL) return 1;
  fprintf(f, "t,r,z,theta,x,y\n");
  for (size_t i = 0; i < k->n; ++i)
    fprintf(f, "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", k->t[i], k->r[i], k->z[i], k->th[i],
            k->r[i] * cos(k->th[i]), k->r[i] * sin(k->th[i]));
  return fclose(f) != 0;
}

static int run_j2(const char *dir, int no_plot, double h, double t_end) {
  static const double j2s[2] = {0.0, 0.05};
  track cont[2], disc[2];
  memset(cont, 0, sizeof cont);
  memset(disc, 0, sizeof disc);
  int rc = 0;
  double dr_rsprk[2] = {0, 0};
  for (int c = 0; c < 2 && !rc; ++c) {
    rc = j2_reference(j2s[c], h / 20.0, t_end, &cont[c]) ||
         j2_discrete(j2s[c], h, t_end, &disc[c], &dr_rsprk[c]);
    if (rc) {
      cli_error("reduction", "j2-satellite run failed");
      break;
    }
    char name[64];
    snprintf(name, sizeof name, "j2-%s-continuous.csv", c ? "0.05" : "0");
    rc = write_track(dir, name, &cont[c]);
    snprintf(name, sizeof name, "j2-%s-discrete.csv", c ? "0.05" : "0");
    rc = rc || write_track(dir, name, &disc[c]);
  }
  if (!rc) {
    printf("j2-satellite: r0 = %g, inclination %g rad, speed %g v_circ, mu = %.6f, dt = %g "
           "(reference RSPRK Gauss-3 at dt/20), t = 0..%g\n",
           J2_R0, J2_INC, J2_SPEED, j2_mu(), h, t_end);
    printf("  discrete Routh equations vs RSPRK (1-point Gauss) along the run: %.3g (J2 = 0), "
           "%.3g (J2 = 0.05)\n", dr_rsprk[0], dr_rsprk[1]);
    printf("  node longitude drift over the run (rad): continuous J2=0 %.4f, J2=0.05 %.4f; "
           "discrete J2=0 %.4f, J2=0.05 %.4f\n",
           node_drift(&cont[0]), node_drift(&cont[1]), node_drift(&disc[0]), node_drift(&disc[1]));
    printf("  largest distance to the continuous J2=0 orbit      unreduced (x,y,z)  reduced (r,z)\n");
    printf("    continuous J2=0.05 (physical precession)          %10.4f        %10.4f\n",
           set_distance(&cont[1], &cont[0], 0), set_distance(&cont[1], &cont[0], 1));
    printf("    discrete J2=0 (discretisation)                    %10.4f        %10.4f\n",
           set_distance(&disc[0], &cont[0], 0), set_distance(&disc[0], &cont[0], 1));
    printf("    discrete J2=0.05                                  %10.4f        %10.4f\n",
           set_distance(&disc[1], &cont[0], 0), set_distance(&disc[1], &cont[0], 1));
    printf("  largest distance of discrete J2=0.05 to continuous J2=0.05: %.4f (unreduced), "
           "%.4f (reduced)\n", set_distance(&disc[1], &cont[1], 0), set_distance(&disc[1], &cont[1], 1));
  }
  for (int c = 0; c < 2 && !rc && !no_plot; ++c)
    for (int dsc = 0; dsc < 2 && !rc; ++dsc) {
      char png[64], script[2048];
      const char *j = c ? "0.05" : "0", *kind = dsc ? "discrete" : "continuous";
      const int fig = 2 + 2 * dsc + c;
      snprintf(png, sizeof png, "fig2.%d-j2-%s-%s.png", fig, j, kind);
      snprintf(script, sizeof script,
               "set multiplot layout 1,2 title 'Fig. 2.%d: %s flow, J2 = %s%s'\n"
               "set title 'unreduced (x, y, z)'\nset view 65,30\nset ticslevel 0\n"
               "set xlabel 'x'\nset ylabel 'y'\nset zlabel 'z'\n"
               "splot 'j2-%s-%s.csv' every ::1 using 5:6:3 with lines lw 0.6 lc rgb '#1f77b4' notitle\n"
               "set title 'reduced (r, z)'\nset xlabel 'r'\nset ylabel 'z'\nset size ratio -1\n"
               "plot 'j2-%s-%s.csv' every ::1 using 2:3 with lines lw 0.6 lc rgb '#d62728' notitle\n"
               "unset multiplot",
               fig, kind, j, dsc ? ", midpoint L_d, dt = 0.3" : " (reference)", j, kind, j, kind);
      rc = plot(dir, png, script);
    }
  for (int c = 0; c < 2; ++c) {
    track_free(&cont[c]);
    track_free(&disc[c]);
  }
  return rc ? CLI_EXIT_FAILURE : CLI_EXIT_OK;
}

/* ---- double spherical pendulum ------------------------------------------------------------ */

static gm_routh_dsp_params dsp = {1.0, 1.0, 1.0, 1.0, 9.81};
static double dsp_mu = 1.0;
#define DSP_MU dsp_mu
static double dsp_x0[6] = {0.5, 0.4, 2.0, 0.0, 0.0, 0.0};

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

/* The constrained R³ × R³ form (problem double-spherical-pendulum, vi-galerkin-gauss-2 with
 * multipliers at the control points) from the same initial state (θ = 0, ẋ given, θ̇ from μ):
 * no chart, so no spikes near r_i = 0. Writes t, (E − E0)/E0 to dsp-constrained.csv. */
static int run_constrained(const char *dir, const gm_routh_system *sys, double h, double t_end,
                           double *emax, double *e_start) {
  const double r1 = dsp_x0[0], r2 = dsp_x0[1], ph = dsp_x0[2];
  const double r1d = dsp_x0[3], r2d = dsp_x0[4], phd = dsp_x0[5];
  double in, a[3];
  const double mu[1] = {DSP_MU};
  if (gm_routh_connection(sys, mu, dsp_x0, &in, a, NULL, NULL, NULL, NULL, NULL) != GM_OK) return 1;
  const double thd = DSP_MU / in - (a[0] * r1d + a[1] * r2d + a[2] * phd);
  const double w1 = sqrt(dsp.l1 * dsp.l1 - r1 * r1), w2 = sqrt(dsp.l2 * dsp.l2 - r2 * r2);
  const double c = cos(ph), sn = sin(ph), om2 = thd + phd;
  double y[12] = {r1, 0.0, -w1, r2 * c, r2 * sn, -w2};
  const double v[6] = {r1d, r1 * thd, r1 * r1d / w1, r2d * c - r2 * sn * om2,
                       r2d * sn + r2 * c * om2, r2 * r2d / w2};
  for (int i = 0; i < 3; ++i) {
    y[6 + i] = (dsp.m1 + dsp.m2) * v[i] + dsp.m2 * v[3 + i];
    y[9 + i] = dsp.m2 * (v[i] + v[3 + i]);
  }
  gm_model *model = NULL;
  gm_integrator *it = NULL;
  gm_error err;
  const gm_method *row = gm_method_find("vi-galerkin-gauss-2");
  if (row == NULL || gm_model_create("double-spherical-pendulum", &model) != GM_OK ||
      gm_model_build(model) != GM_OK ||
      gm_integrator_create(row, gm_model_problem(model), &it, &err) != GM_OK ||
      gm_integrator_set_state(it, 0.0, y) != GM_OK) {
    cli_error("reduction", "cannot set up the constrained double spherical pendulum");
    gm_model_free(model);
    return 1;
  }
  FILE *f = open_out(dir, "dsp-constrained.csv");
  int rc = f == NULL;
  const size_t n = (size_t)llround(t_end / h);
  double e0 = NAN;
  *emax = 0.0;
  for (size_t i = 0; i <= n && !rc; ++i) {
    if (i > 0 && gm_integrator_step(it, h) != GM_OK) {
      cli_error("reduction", "constrained run failed at step %zu", i);
      rc = 1;
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
    if (i == 0) e0 = *e_start = e;
    const double de = (e - e0) / fabs(e0);
    *emax = fmax(*emax, fabs(de));
    fprintf(f, "%.8g,%.6e\n", (double)i * h, de);
  }
  if (f) fclose(f);
  gm_integrator_free(it);
  gm_model_free(model);
  return rc;
}

static int run_dsp(const char *dir, int no_plot, double h, double t_end) {
  gm_routh_system sys;
  gm_routh_double_spherical_pendulum(&dsp, &sys);
  const double mu[1] = {DSP_MU};
  const gm_method *row = gm_method_find("vi-galerkin-gauss-2");
  gm_tableau *t = NULL;
  gm_rsprk *ra = NULL, *rb = NULL;
  gm_error err;
  if (row == NULL || gm_method_tableau(row, &t) != GM_OK ||
      gm_rsprk_create(&sys, t, GM_ROUTH_RSPRK, mu, &ra, &err) != GM_OK ||
      gm_rsprk_create(&sys, t, GM_ROUTH_CLASSICAL, mu, &rb, &err) != GM_OK) {
    cli_error("reduction", "cannot set up the steppers");
    gm_tableau_free(t);
    gm_rsprk_free(ra);
    return CLI_EXIT_FAILURE;
  }
  /* initial shape and shape velocity; s = K ẋ */
  double x[3] = {dsp_x0[0], dsp_x0[1], dsp_x0[2]}, xd[3] = {dsp_x0[3], dsp_x0[4], dsp_x0[5]};
  double kin[9], s[3];
  gm_routh_connection(&sys, mu, x, NULL, NULL, kin, NULL, NULL, NULL, NULL);
  for (int i = 0; i < 3; ++i) s[i] = kin[i * 3] * xd[0] + kin[i * 3 + 1] * xd[1] + kin[i * 3 + 2] * xd[2];
  double xc[3], y[3], th = 0.0, thc = 0.0, full[8] = {0};
  memcpy(xc, x, sizeof x);
  gm_routh_lift_momentum(&sys, mu, x, s, y, NULL);
  full[0] = 0.0;
  memcpy(full + 1, x, sizeof x);
  full[4] = DSP_MU;
  memcpy(full + 5, y, sizeof y);
  const double e0 = gm_routh_energy(&sys, mu, x, s), e0f = full_energy(&sys, full);
  FILE *f = open_out(dir, "dsp.csv");
  if (f == NULL) return CLI_EXIT_FAILURE;
  fprintf(f, "t,r1,r2,phi,x2,y2,dE_rsprk,dE_sprk,dE_rk4,rel_r1,rel_r2,rel_phi,rel_E,r1_rk4,r2_rk4,phi_rk4,min_r\n");
  const size_t n = (size_t)llround(t_end / h);
  double worst[4] = {0, 0, 0, 0}, emax_a = 0, emax_rk = 0, emax_a_half = 0, r_min = INFINITY;
  double tenth[2][2] = {{0, 0}, {0, 0}}; /* max |dE| in the first and last tenth: RSPRK, RK4 */
  int rc = 0;
  for (size_t i = 0; i <= n; ++i) {
    if (i > 0) {
      if (gm_rsprk_step(ra, h, x, s, &th) != GM_OK || gm_rsprk_step(rb, h, xc, y, &thc) != GM_OK) {
        cli_error("reduction", "step %zu failed: %s %s", i, gm_rsprk_errmsg(ra), gm_rsprk_errmsg(rb));
        rc = 1;
        break;
      }
      for (int q = 0; q < 4 && !rc; ++q)
        if (rk4_step(&sys, h / 4, full)) {
          cli_error("reduction", "RK4 failed at step %zu (left the chart)", i);
          rc = 1;
        }
      if (rc) break;
    }
    double sc[3];
    gm_routh_reduce_momentum(&sys, mu, xc, mu, y, sc, NULL);
    const double ea = gm_routh_energy(&sys, mu, x, s), eb = gm_routh_energy(&sys, mu, xc, sc);
    const double ef = full_energy(&sys, full);
    const double da = (ea - e0) / fabs(e0), db = (eb - e0) / fabs(e0), dk = (ef - e0f) / fabs(e0f);
    double rel[4];
    for (int q = 0; q < 3; ++q) rel[q] = fabs(x[q] - xc[q]) / fmax(fabs(x[q]), 1e-300);
    rel[3] = fabs(ea - eb) / fabs(ea);
    for (int q = 0; q < 4; ++q) worst[q] = fmax(worst[q], rel[q]);
    emax_a = fmax(emax_a, fabs(da));
    if ((double)i * h <= 0.5 * t_end) emax_a_half = fmax(emax_a_half, fabs(da));
    emax_rk = fmax(emax_rk, fabs(dk));
    if (i > 0 && (i - 1) * 10 < n) tenth[0][0] = fmax(tenth[0][0], fabs(da)), tenth[1][0] = fmax(tenth[1][0], fabs(dk));
    if (i > 0 && (i - 1) * 10 >= 9 * n) tenth[0][1] = fmax(tenth[0][1], fabs(da)), tenth[1][1] = fmax(tenth[1][1], fabs(dk));
    r_min = fmin(r_min, fmin(x[0], x[1]));
    const double th2 = th + x[2];
    fprintf(f, "%.8g,%.12g,%.12g,%.12g,%.10g,%.10g,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.12g,%.12g,%.12g,%.6g\n",
            (double)i * h, x[0], x[1], x[2], x[1] * cos(th2), x[1] * sin(th2), da, db, dk, rel[0],
            rel[1], rel[2], rel[3], full[1], full[2], full[3], fmin(x[0], x[1]));
  }
  fclose(f);
  gm_rsprk_free(ra);
  gm_rsprk_free(rb);
  gm_tableau_free(t);
  if (rc) return CLI_EXIT_FAILURE;
  printf("double-spherical-pendulum: m1 = %g, m2 = %g, l1 = %g, l2 = %g, g = %g, mu = %g, "
         "(r1, r2, phi, r1', r2', phi')(0) = (%g, %g, %g, %g, %g, %g), dt = %g (RK4 dt/4), "
         "t = 0..%g\n",
         dsp.m1, dsp.m2, dsp.l1, dsp.l2, dsp.g, DSP_MU, dsp_x0[0], dsp_x0[1], dsp_x0[2], dsp_x0[3],
         dsp_x0[4], dsp_x0[5], h, t_end);
  printf("  max |E - E0|/|E0|: RSPRK (vi-galerkin-gauss-2) %.3g (first half %.3g), RK4 at dt/4 %.3g\n",
         emax_a, emax_a_half, emax_rk);
  printf("  max |E - E0|/|E0| in the first / last tenth of the run: RSPRK %.3g / %.3g, RK4 at dt/4 "
         "%.3g / %.3g\n",
         tenth[0][0], tenth[0][1], tenth[1][0], tenth[1][1]);
  printf("  max relative RSPRK - classical SPRK: r1 %.3g, r2 %.3g, phi %.3g, E %.3g\n", worst[0],
         worst[1], worst[2], worst[3]);
  printf("  smallest r_i along the run: %.4f\n", r_min);
  double emax_c = NAN, e0c = NAN;
  if (run_constrained(dir, &sys, h, t_end, &emax_c, &e0c)) return CLI_EXIT_FAILURE;
  printf("  constrained R3 x R3 form (vi-galerkin-gauss-2 with multipliers), same state (E0 %.12g, "
         "reduced E0 %.12g): max |E - E0|/|E0| %.3g\n", e0c, e0, emax_c);
  if (no_plot) return CLI_EXIT_OK;
  rc = plot(dir, "fig2.7-dsp-shape.png",
            "set multiplot layout 1,2 title 'Fig. 2.7: double spherical pendulum, RSPRK (4th order)'\n"
            "set xlabel 't'\nset title 'shape variables'\n"
            "plot 'dsp.csv' every ::1 using 1:2 w l t 'r1', '' every ::1 using 1:3 w l t 'r2', '' every ::1 using 1:4 w l t 'phi'\n"
            "set title 'm2 relative to m1 (x, y)'\nset xlabel 'x'\nset ylabel 'y'\nset size ratio -1\n"
            "plot 'dsp.csv' every ::1 using 5:6 w l lw 0.6 notitle\nunset multiplot");
  if (!rc)
    rc = plot(dir, "fig2.8-dsp-energy.png",
              "set multiplot layout 2,1\nset title 'Fig. 2.8: relative energy error (E - E0)/E0'\n"
              "plot 'dsp.csv' every ::1 using 1:7 w l t 'RSPRK dt', '' every ::1 using 1:9 w l t 'RK4 (unreduced) dt/4', "
              "'dsp-constrained.csv' using 1:2 w l t 'constrained R^3 x R^3, Gauss-2 dt'\n"
              "set title 'min(r1, r2): the chart (r1, r2, phi) is singular at r_i = 0'\nset xlabel 't'\nset logscale y\n"
              "plot 'dsp.csv' every ::1 using 1:17 w l lc rgb '#555555' t 'min(r1, r2)'\nunset multiplot");
  if (!rc)
    rc = plot(dir, "fig2.9-dsp-rsprk-vs-sprk.png",
              "set title 'Fig. 2.9: relative difference RSPRK vs SPRK on the classical Routhian'\n"
              "set xlabel 't'\nset logscale y\nset format y '10^{%L}'\n"
              "plot 'dsp.csv' every ::1 using 1:($10+1e-18) w l t 'r1', '' every ::1 using 1:($11+1e-18) w l t 'r2', "
              "'' every ::1 using 1:($12+1e-18) w l t 'phi', '' every ::1 using 1:($13+1e-18) w l t 'E'");
  return rc ? CLI_EXIT_FAILURE : CLI_EXIT_OK;
}

static int routh_main(int argc, char **argv) {
  const char *dir = "reduction-output";
  int no_plot = 0;
  double dt = 0.0, t_end = 0.0;
  const char *x0_text = NULL;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &dir, 0},
                          {"--mu", CLI_ARG_DOUBLE, &dsp_mu, 0},
                          {"--x0", CLI_ARG_STRING, &x0_text, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0},
                          {"--dt", CLI_ARG_DOUBLE, &dt, 0},
                          {"--t-end", CLI_ARG_DOUBLE, &t_end, 0}};
  const char *pos[1];
  size_t npos = 0;
  int rc = cli_parse("reduction", argc, argv, options, 6, pos, 1, &npos);
  if (rc == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  if (npos != 1) {
    cli_error("reduction", "expected one experiment: j2-satellite, double-spherical-pendulum or phases");
    return CLI_EXIT_USAGE;
  }
  if ((options[4].seen && cli_check_positive("reduction", "--dt", dt)) ||
      (options[5].seen && cli_check_positive("reduction", "--t-end", t_end)))
    return CLI_EXIT_USAGE;
  /* an option the experiment does not use is an error, not ignored */
  const int phases = strcmp(pos[0], "phases") == 0, j2_name = strcmp(pos[0], "j2-satellite") == 0;
  for (size_t i = 1; i < 6; ++i) {
    const int dsp_only = i == 1 || i == 2, run_only = i >= 4;
    if (options[i].seen && ((phases && (dsp_only || run_only)) || (j2_name && dsp_only))) {
      cli_error("reduction", "%s is not an option of '%s'%s", options[i].name, pos[0],
                dsp_only ? " (double-spherical-pendulum only)" : "");
      return CLI_EXIT_USAGE;
    }
  }
  if (phases) {
    rc = cli_reduction_phases();
    if (rc != CLI_EXIT_OK || !options[0].seen) return rc; /* files only with --out */
    if (make_directory(dir)) return CLI_EXIT_FAILURE;
    FILE *f = open_out(dir, "phases-convergence.csv");
    if (f == NULL) return CLI_EXIT_FAILURE;
    rc = cli_reduction_phases_convergence(f);
    if (fclose(f) != 0 && rc == CLI_EXIT_OK) rc = CLI_EXIT_FAILURE;
    if (rc != CLI_EXIT_OK || no_plot) return rc;
    return plot(dir, "phases-convergence.png",
                "set logscale xy\nset format y '10^{%L}'\nset xlabel 'points per loop / steps per period'\n"
                "set ylabel 'phase error'\nset key outside right\nset grid\n"
                "set title 'Geometric phases: error vs closed form (solid) and vs the polygon exact holonomy (dashed)'\n"
                "plot 'phases-convergence.csv' every ::1 using 1:2 w lp lw 2 t 'Foucault, midpoint conn.', "
                "'' every ::1 using 1:3 w lp lw 2 t 'Foucault, Gauss-2 conn.', "
                "'' every ::1 using 1:4 w lp dt 2 lw 2 t 'Foucault, Gauss-2 vs polygon', "
                "'' every ::1 using 1:5 w lp dt 2 lw 2 t 'DSP loop, midpoint vs polygon', "
                "'' every ::1 using 1:6 w lp dt 2 lw 2 t 'DSP loop, Gauss-2 vs polygon', "
                "'' every ::1 using 1:7 w lp lw 2 t 'rigid body, lgvi', "
                "'' every ::1 using 1:8 w lp lw 2 t 'rigid body, lgvi-galerkin-2', "
                "'' every ::1 using 1:(2e-1/$1**2) w l lc rgb '#999999' t 'N^{-2}', "
                "'' every ::1 using 1:(1e0/$1**4) w l lc rgb '#555555' t 'N^{-4}'");
  }
  const int j2 = strcmp(pos[0], "j2-satellite") == 0;
  if (!j2 && strcmp(pos[0], "double-spherical-pendulum") != 0) {
    cli_error("reduction",
              "unknown experiment '%s'; expected j2-satellite, double-spherical-pendulum or phases",
              pos[0]);
    return CLI_EXIT_USAGE;
  }
  if (!options[4].seen) dt = j2 ? 0.3 : 0.01;
  if (!options[5].seen) t_end = j2 ? 150.0 : 20.0;
  if (dt > t_end) {
    cli_error("reduction", "--dt %g is longer than the run (t-end %g)", dt, t_end);
    return CLI_EXIT_USAGE;
  }
  if (t_end / dt > 1e6) {
    cli_error("reduction", "t-end/dt = %g steps is too many (at most 1e6)", t_end / dt);
    return CLI_EXIT_USAGE;
  }
  if (x0_text != NULL) {
    double v[6];
    int used = 0;
    if (sscanf(x0_text, "%lf,%lf,%lf,%lf,%lf,%lf%n", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
               &used) != 6 || x0_text[used] != '\0' || !(v[0] > 0 && v[0] < dsp.l1) ||
        !(v[1] > 0 && v[1] < dsp.l2)) {
      cli_error("reduction", "--x0 wants r1,r2,phi,r1dot,r2dot,phidot with 0 < r_i < l_i = 1, got '%s'",
                x0_text);
      return CLI_EXIT_USAGE;
    }
    memcpy(dsp_x0, v, sizeof v);
  }
  if (!isfinite(dsp_mu)) {
    cli_error("reduction", "--mu must be finite");
    return CLI_EXIT_USAGE;
  }
  if (make_directory(dir)) return CLI_EXIT_FAILURE;
  return j2 ? run_j2(dir, no_plot, dt, t_end) : run_dsp(dir, no_plot, dt, t_end);
}

const cli_command cli_reduction_command = {"reduction",
                                       "discrete Routh reduction experiments (seed 001 2.9-2.10)",
                                       usage, routh_main};
/* The issue and seed 001 call the experiments "discrete Routh reduction": the same command under
   that name. */
const cli_command cli_routh_command = {"routh", "the same as reduction", usage, routh_main};
