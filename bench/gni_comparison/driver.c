/* Hairer's GNI Fortran codes (gni_irk2.f, gni_comp.f, version of 4 Sep 2002; E. Hairer & M.
 * Hairer, "GniCodes — Matlab programs for geometric numerical integration", 2003) against
 * geomint on the rows of issue 25's table, all ratios from one run:
 *   Kepler e = 0.6, 200 periods:   IRK2 s=6 / gauss-6, IRK2 s=4 / gauss-4, COMP 817 / kahan-li-8
 *                                  at equal steps (the N for error 1e-8);
 *   outer solar system, 500 000 d: IRK2 s=6 at N = 1949 / gauss-6 at N = 1772 (each one's
 *                                  1e-10 step in the issue) and both at equal N.
 * The GNI sources are not part of geomint: bench/gni_comparison/run.sh compiles them from a
 * directory the user names and links them with this driver. The force routines handed to GNI
 * are ours (the same formulas as src/problems/kepler.c and gravity.c, as accelerations: GNI
 * integrates q'' = f(q) with p = q'). Wall time (CLOCK_MONOTONIC) and thread CPU time of the
 * integration call only, min of REPEATS interleaved runs; errors against the exact Kepler
 * solution and, for the solar system, against sofroniou-spaletta-10 with compensated summation at
 * 50 days (as bench_celestial_work_precision):
 * max-norm of the final positions, over Pluto's distance for the solar system. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/geomint.h"
#include "problems/internal.h"

#ifndef REPEATS
#define REPEATS 10
#endif

/* The GNI entry points (Fortran, default INTEGER = int, no character arguments). */
typedef void (*gni_force)(const int *n, const double *x, const double *q, double *f,
                          double *rpar, int *ipar);
typedef void (*gni_solfix)(void);
void gni_irk2_(const int *n, gni_force fcn, const int *nstep, double *x, double *p, double *q,
               const double *xend, const int *meth, gni_solfix solfix, const int *iout,
               double *rpar, int *ipar);
void gni_comp_(void (*basic)(void), const int *n, gni_force fcn, const int *nstep, double *x,
               double *p, double *q, const double *xend, const int *meth, gni_solfix solfix,
               const int *iout, double *rpar, int *ipar);
void stverl_(void); /* gni_comp.f's Störmer–Verlet, the basic method of COMP */

static long gni_evals;
static void no_output(void) {}

static void kepler_accel(const int *n, const double *x, const double *q, double *f, double *rpar,
                         int *ipar) {
  (void)n, (void)x, (void)rpar, (void)ipar;
  const double r = sqrt(q[0] * q[0] + q[1] * q[1]), r3 = r * r * r;
  f[0] = -q[0] / r3;
  f[1] = -q[1] / r3;
  ++gni_evals;
}

static size_t n_bodies;
static double body_mass[16], grav_G;

static void gravity_accel(const int *n, const double *x, const double *q, double *f,
                          double *rpar, int *ipar) {
  (void)n, (void)x, (void)rpar, (void)ipar;
  for (size_t i = 0; i < 3 * n_bodies; ++i) f[i] = 0.0;
  for (size_t i = 0; i < n_bodies; ++i)
    for (size_t j = i + 1; j < n_bodies; ++j) {
      const double dx = q[3 * i] - q[3 * j], dy = q[3 * i + 1] - q[3 * j + 1],
                   dz = q[3 * i + 2] - q[3 * j + 2];
      const double s = dx * dx + dy * dy + dz * dz, g = grav_G / (s * sqrt(s));
      const double gi = g * body_mass[j], gj = g * body_mass[i];
      f[3 * i] -= gi * dx, f[3 * i + 1] -= gi * dy, f[3 * i + 2] -= gi * dz;
      f[3 * j] += gj * dx, f[3 * j + 1] += gj * dy, f[3 * j + 2] += gj * dz;
    }
  ++gni_evals;
}

typedef struct {
  double wall, cpu, evals, error;
} timing;

static void keep_best(timing *t, double w0, double c0) {
  t->wall = fmin(t->wall, bench_now() - w0);
  t->cpu = fmin(t->cpu, bench_cpu_now() - c0);
}

/* One GNI run from (q0, v0) over [0, t_end]; the final positions in q_out. */
static void gni_run(int code, int meth, gni_force fcn, int n, const double *q0, const double *v0,
                    double t_end, int steps, double *q_out, timing *t) {
  double q[64], p[64], x = 0.0, rpar[20] = {0};
  int ipar[20] = {0}, iout = 0;
  memcpy(q, q0, (size_t)n * sizeof *q);
  memcpy(p, v0, (size_t)n * sizeof *p);
  gni_evals = 0;
  const double w0 = bench_now(), c0 = bench_cpu_now();
  if (code == 0)
    gni_irk2_(&n, fcn, &steps, &x, p, q, &t_end, &meth, no_output, &iout, rpar, ipar);
  else
    gni_comp_(stverl_, &n, fcn, &steps, &x, p, q, &t_end, &meth, no_output, &iout, rpar, ipar);
  keep_best(t, w0, c0);
  t->evals = (double)gni_evals;
  memcpy(q_out, q, (size_t)n * sizeof *q);
}

static gm_integrator *make(const char *method, const gm_problem *pb) {
  gm_integrator *it = NULL;
  gm_error err;
  const gm_method *m = gm_method_find(method);
  if (m == NULL || gm_integrator_create(m, pb, &it, &err) != GM_OK) {
    fprintf(stderr, "%s: %s\n", method, m ? err.message : "unknown method");
    exit(1);
  }
  return it;
}

static void gm_run(gm_integrator *it, const double *y0, size_t steps, double t_end, timing *t) {
  gm_integrator_set_state(it, 0.0, y0);
  gm_integrator_reset_stats(it);
  const double w0 = bench_now(), c0 = bench_cpu_now();
  if (gm_integrator_run(it, steps, t_end / (double)steps) != GM_OK) {
    fprintf(stderr, "%s\n", gm_integrator_errmsg(it));
    exit(1);
  }
  keep_best(t, w0, c0);
  t->evals = (double)gm_integrator_stats(it).force_evals;
}

static double max_diff(size_t n, const double *a, const double *b, double scale) {
  double e = 0.0;
  for (size_t i = 0; i < n; ++i) e = fmax(e, fabs(a[i] - b[i]));
  return e / scale;
}

typedef struct {
  const char *problem, *gni_name, *gm_name;
  int code, meth, gni_steps, gm_steps;
} row_def;

static const row_def rows[] = {
    {"kepler", "IRK2 s=6", "gauss-6", 0, 6, 11918, 11918},
    {"kepler", "IRK2 s=4", "gauss-4", 0, 4, 30913, 30913},
    {"kepler", "COMP 817", "kahan-li-8", 1, 817, 25548, 25548},
    {"solar", "IRK2 s=6", "gauss-6", 0, 6, 1949, 1772},
    {"solar", "IRK2 s=6", "gauss-6", 0, 6, 1772, 1772},
};
#define N_ROWS (sizeof rows / sizeof rows[0])

int main(void) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  gm_model *kepler = NULL, *solar = NULL;
  if (gm_model_create("kepler", &kepler) != GM_OK || gm_model_build(kepler) != GM_OK ||
      gm_model_create("outer-solar-system", &solar) != GM_OK || gm_model_build(solar) != GM_OK)
    return 1;
  const gm_problem *pk = gm_model_problem(kepler), *ps = gm_model_problem(solar);
  double t0, yk[4], yk_exact[4], ys[64];
  gm_model_initial_state(kepler, &t0, yk);
  gm_model_initial_state(solar, &t0, ys);
  const double tk = 200.0 * 2.0 * 3.14159265358979323846, tsol = 500000.0;
  if (pk->exact(pk->ctx, tk, yk_exact) != 0) return 1;
  const gm_gravity *grav = ps->ctx; /* the context begins with it (problems/internal.h) */
  n_bodies = grav->n_bodies;
  grav_G = grav->G;
  const int ns = (int)(3 * n_bodies);
  double vs[64];
  for (size_t i = 0; i < n_bodies; ++i) {
    body_mass[i] = grav->mass[i];
    for (int k = 0; k < 3; ++k) vs[3 * i + k] = ys[ns + 3 * i + k] / grav->mass[i];
  }
  /* the solar system's reference and Pluto's distance from the Sun at the end */
  gm_scheme sc = {gm_method_find("sofroniou-spaletta-10"), NULL, GM_SOLVER_DEFAULT, 1};
  gm_integrator *ref = NULL;
  gm_error err;
  if (gm_integrator_create_scheme(&sc, ps, &ref, &err) != GM_OK) {
    fprintf(stderr, "reference: %s\n", err.message);
    return 1;
  }
  timing tr = {INFINITY, INFINITY, 0, 0};
  gm_run(ref, ys, 10000, tsol, &tr);
  double ys_ref[64];
  memcpy(ys_ref, gm_integrator_state(ref), (size_t)ns * sizeof *ys_ref);
  gm_integrator_free(ref);
  const double *pl = ys_ref + 3 * (n_bodies - 1), *sun = ys_ref;
  const double pluto = sqrt((pl[0] - sun[0]) * (pl[0] - sun[0]) +
                            (pl[1] - sun[1]) * (pl[1] - sun[1]) + (pl[2] - sun[2]) * (pl[2] - sun[2]));

  gm_integrator *its[N_ROWS];
  timing tg[N_ROWS], tm[N_ROWS];
  double qg[N_ROWS][64];
  for (size_t k = 0; k < N_ROWS; ++k) {
    its[k] = make(rows[k].gm_name, rows[k].problem[0] == 'k' ? pk : ps);
    tg[k] = tm[k] = (timing){INFINITY, INFINITY, 0, 0};
  }
  for (int r = 0; r < REPEATS; ++r)
    for (size_t k = 0; k < N_ROWS; ++k) {
      const int is_k = rows[k].problem[0] == 'k';
      if (is_k)
        gni_run(rows[k].code, rows[k].meth, kepler_accel, 2, yk, yk + 2, tk, rows[k].gni_steps,
                qg[k], &tg[k]);
      else
        gni_run(rows[k].code, rows[k].meth, gravity_accel, ns, ys, vs, tsol, rows[k].gni_steps,
                qg[k], &tg[k]);
      gm_run(its[k], is_k ? yk : ys, (size_t)rows[k].gm_steps, is_k ? tk : tsol, &tm[k]);
    }
  printf("GNI (gfortran -O2) vs geomint, min of %d interleaved runs of the integration call\n",
         REPEATS);
  printf("%-7s %-9s %6s %9s %9s %9s %9s | %-10s %6s %9s %9s %9s %9s | %6s %6s\n", "problem",
         "GNI", "N", "wall ms", "cpu ms", "evals", "error", "geomint", "N", "wall ms", "cpu ms",
         "evals", "error", "wall", "cpu");
  for (size_t k = 0; k < N_ROWS; ++k) {
    const int is_k = rows[k].problem[0] == 'k';
    const double eg = is_k ? max_diff(2, qg[k], yk_exact, 1.0)
                           : max_diff((size_t)ns, qg[k], ys_ref, pluto);
    const double em = is_k ? max_diff(2, gm_integrator_state(its[k]), yk_exact, 1.0)
                           : max_diff((size_t)ns, gm_integrator_state(its[k]), ys_ref, pluto);
    printf("%-7s %-9s %6d %9.2f %9.2f %9.0f %9.2e | %-10s %6d %9.2f %9.2f %9.0f %9.2e | %6.3f "
           "%6.3f\n",
           rows[k].problem, rows[k].gni_name, rows[k].gni_steps, 1e3 * tg[k].wall,
           1e3 * tg[k].cpu, tg[k].evals, eg, rows[k].gm_name, rows[k].gm_steps, 1e3 * tm[k].wall,
           1e3 * tm[k].cpu, tm[k].evals, em, tm[k].wall / tg[k].wall, tm[k].cpu / tg[k].cpu);
  }
  printf("ns per force evaluation (cpu): ");
  for (size_t k = 0; k < N_ROWS; ++k)
    printf("%s%s %.1f / %s %.1f", k ? "; " : "", rows[k].gni_name, 1e9 * tg[k].cpu / tg[k].evals,
           rows[k].gm_name, 1e9 * tm[k].cpu / tm[k].evals);
  printf("\n");
  for (size_t k = 0; k < N_ROWS; ++k) gm_integrator_free(its[k]);
  gm_model_free(kepler);
  gm_model_free(solar);
  return 0;
}
