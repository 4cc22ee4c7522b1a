/* Work–precision of the symplectic methods (and rk4, gauss-4 as classical and implicit peers) on
 * Kepler (e = 0.6, t_end = 100, error against the exact solution) and on the outer solar
 * system (t_end = 500 000 days, error against sofroniou-spaletta-10 with compensated summation
 * at 50 days, checked against the same at 62.5 days).
 *
 * For each method: steps dt0, dt0/r, dt0/r², ... with r = 10^(1/p) for order p (the error falls
 * by about 10 a level), dt0 found by pilot runs so the first error is near 1e-2, stopping at an
 * error below 1e-13, at round-off (two levels below 1e-9 that do not halve the best error),
 * or at a force-evaluation or CPU-time budget. gauss-4 solves its stage equations by fixed-point
 * iteration (the problems are not stiff). The error is the max-norm of y − y_ref relative to the
 * max-norm of y_ref. The ratio reported is, for each method, the
 * force evaluations it needs to reach an error of 1e-8 (log-log interpolation between the two
 * runs around it) divided by the fewest any method needs, measured in the same run; the same
 * for CPU time. Writes DIR/work_precision.json and, when gnuplot is on PATH, DIR/
 * work_precision_kepler.png and DIR/work_precision_outer_solar_system.png. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_util.h"
#include "geomint/geomint.h"

static const char *const method_names[] = {"verlet",     "yoshida-4",  "blanes-moan-4",
                                           "kahan-li-6", "blanes-moan-6", "kahan-li-8",
                                           "sofroniou-spaletta-10", "rk4", "gauss-4"};
#define N_METHODS (sizeof method_names / sizeof method_names[0])
#define MAX_LEVELS 40
#define TARGET_ERROR 1e-8
#define MAX_RUN_CPU_S 3.0 /* skip runs predicted to take longer */

typedef struct run {
  double dt, error, cpu_s;
  size_t steps, force_evals;
} run;

typedef struct sweep {
  const gm_method *method;
  size_t n;
  run runs[MAX_LEVELS];
  double evals_at_target, cpu_at_target; /* NaN when not reached */
  double evals_ratio, cpu_ratio;
} sweep;

typedef struct study {
  const char *name, *png;
  gm_model *model;
  const gm_problem *pb;
  size_t n;
  double t0, t_end, *y0, *y_ref, ref_scale;
  double budget; /* force evaluations per run */
  const char *reference;
  double reference_dt, reference_check;
  sweep sweeps[N_METHODS];
} study;

static double norm_inf(size_t n, const double *x) {
  double m = 0;
  for (size_t i = 0; i < n; ++i) m = fmax(m, fabs(x[i]));
  return m;
}

static double rel_distance(size_t n, const double *a, const double *b, double scale) {
  double m = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!isfinite(a[i])) return NAN;
    m = fmax(m, fabs(a[i] - b[i]));
  }
  return m / scale;
}

/* Integrate to t_end with steps of at most h; returns 0 on success. */
static int integrate(const study *s, const gm_method *m, int compensated, double h, double *y,
                     run *r) {
  /* implicit methods iterate to a fixed point: the problems are not stiff (GNI §VIII.6) */
  gm_scheme sc = {m, NULL, (m->flags & GM_IMPLICIT) ? GM_SOLVER_FIXED_POINT : GM_SOLVER_DEFAULT,
                  compensated};
  gm_integrator *it = NULL;
  gm_error err;
  if (gm_integrator_create_scheme(&sc, s->pb, &it, &err) != GM_OK) {
    fprintf(stderr, "%s with %s: %s\n", s->name, m->name, err.message);
    exit(1);
  }
  gm_integrator_set_state(it, s->t0, s->y0);
  double c0 = bench_cpu_now();
  gm_status st = gm_integrator_integrate(it, s->t_end, h);
  double cpu = bench_cpu_now() - c0;
  if (st == GM_OK) {
    memcpy(y, gm_integrator_state(it), s->n * sizeof *y);
    if (r != NULL) {
      gm_stats stats = gm_integrator_stats(it);
      *r = (run){(s->t_end - s->t0) / (double)stats.steps, NAN, cpu, stats.steps,
                 stats.force_evals};
    }
  }
  gm_integrator_free(it);
  return st == GM_OK ? 0 : -1;
}

static int measure(const study *s, const gm_method *m, double h, double *y, run *r) {
  if (integrate(s, m, 0, h, y, r) != 0) return -1;
  r->error = rel_distance(s->n, y, s->y_ref, s->ref_scale);
  return 0;
}

/* Pilot: the first h = T/100, T/400, ... with an error ≤ 1e-3 whose half step confirms the
 * order (error at least 2^(p−2) smaller); dt0 = h·min((1e-2/error)^(1/p), 2). */
static double find_dt0(const study *s, const gm_method *m, double *y) {
  double h = (s->t_end - s->t0) / 100.0;
  for (int k = 0; k < 24; ++k, h /= 4) {
    run a, b;
    if (measure(s, m, h, y, &a) != 0 || !(a.error <= 1e-3)) continue;
    if (measure(s, m, h / 2, y, &b) != 0) continue;
    if (!(b.error <= a.error * pow(2.0, 2 - m->order) || b.error <= 1e-11)) continue;
    return h * fmin(a.error > 0 ? pow(1e-2 / a.error, 1.0 / m->order) : 1.0, 2.0);
  }
  fprintf(stderr, "%s with %s: no pilot step converged\n", s->name, m->name);
  exit(1);
}

/* x where log y crosses log target between two runs, interpolated linearly in log-log. */
static double at_target(const sweep *w, int cpu) {
  for (size_t i = 0; i + 1 < w->n; ++i) {
    const run *a = &w->runs[i], *b = &w->runs[i + 1];
    if (a->error >= TARGET_ERROR && b->error < TARGET_ERROR) {
      double xa = cpu ? a->cpu_s : (double)a->force_evals, xb = cpu ? b->cpu_s : (double)b->force_evals;
      double f = log(a->error / TARGET_ERROR) / log(a->error / b->error);
      return exp(log(xa) + f * (log(xb) - log(xa)));
    }
  }
  return NAN;
}

static void run_sweep(study *s, sweep *w, double *y) {
  const gm_method *m = w->method;
  double dt0 = find_dt0(s, m, y), r = pow(10.0, 1.0 / m->order), per_step = 0, cpu_per_step = 0;
  w->n = 0;
  for (size_t k = 0; k < MAX_LEVELS; ++k) {
    double h = dt0 / pow(r, (double)k), steps = ceil((s->t_end - s->t0) / h);
    if (per_step > 0 && (steps * per_step > s->budget || steps * cpu_per_step > MAX_RUN_CPU_S))
      break;
    run *x = &w->runs[w->n];
    if (measure(s, m, h, y, x) != 0) {
      fprintf(stderr, "%s with %s failed at dt = %g\n", s->name, m->name, h);
      exit(1);
    }
    per_step = (double)x->force_evals / (double)x->steps;
    cpu_per_step = x->cpu_s / (double)x->steps;
    ++w->n;
    if (!(x->error > 1e-13)) break;
    if (w->n >= 3 && x->error < 1e-9) { /* round-off: two levels that do not halve the best */
      double best = x[-2].error;
      for (size_t i = 0; i + 2 < w->n; ++i) best = fmin(best, w->runs[i].error);
      if (x[-1].error > 0.5 * best && x->error > 0.5 * best) break;
    }
  }
  w->evals_at_target = at_target(w, 0);
  w->cpu_at_target = at_target(w, 1);
}

static void open_study(study *s, const char *name, const char *param, double value,
                       double t_end, double budget) {
  memset(s, 0, sizeof *s);
  s->name = name;
  if (gm_model_create(name, &s->model) != GM_OK ||
      (param != NULL && gm_model_set(s->model, param, value) != GM_OK) ||
      gm_model_build(s->model) != GM_OK) {
    fprintf(stderr, "cannot build %s\n", name);
    exit(1);
  }
  s->pb = gm_model_problem(s->model);
  s->n = gm_model_state_size(s->model);
  s->y0 = malloc(s->n * sizeof *s->y0);
  s->y_ref = malloc(s->n * sizeof *s->y_ref);
  gm_model_initial_state(s->model, &s->t0, s->y0);
  s->t_end = t_end;
  s->budget = budget;
}

static void reference_run(study *s, const char *method, double h) {
  const gm_method *m = gm_method_find(method);
  double *check = malloc(s->n * sizeof *check);
  if (m == NULL || integrate(s, m, 1, h, s->y_ref, NULL) != 0 ||
      integrate(s, m, 1, 1.25 * h, check, NULL) != 0) {
    fprintf(stderr, "%s: the reference run failed\n", s->name);
    exit(1);
  }
  s->ref_scale = norm_inf(s->n, s->y_ref);
  s->reference = method;
  s->reference_dt = h;
  s->reference_check = rel_distance(s->n, check, s->y_ref, s->ref_scale);
  free(check);
}

static void run_study(study *s) {
  double *y = malloc(s->n * sizeof *y);
  for (size_t i = 0; i < N_METHODS; ++i) {
    s->sweeps[i].method = gm_method_find(method_names[i]);
    if (s->sweeps[i].method == NULL) {
      fprintf(stderr, "no method %s\n", method_names[i]);
      exit(1);
    }
    run_sweep(s, &s->sweeps[i], y);
  }
  double best_evals = INFINITY, best_cpu = INFINITY;
  for (size_t i = 0; i < N_METHODS; ++i) {
    if (isfinite(s->sweeps[i].evals_at_target))
      best_evals = fmin(best_evals, s->sweeps[i].evals_at_target);
    if (isfinite(s->sweeps[i].cpu_at_target))
      best_cpu = fmin(best_cpu, s->sweeps[i].cpu_at_target);
  }
  for (size_t i = 0; i < N_METHODS; ++i) {
    s->sweeps[i].evals_ratio = s->sweeps[i].evals_at_target / best_evals;
    s->sweeps[i].cpu_ratio = s->sweeps[i].cpu_at_target / best_cpu;
  }
  free(y);
}

static void print_study(const study *s) {
  printf("\n%s, t_end = %g, reference: %s", s->name, s->t_end,
         s->reference ? s->reference : "exact solution");
  if (s->reference)
    printf(" (compensated, dt = %g, differs by %.1e from dt = %g)", s->reference_dt,
           s->reference_check, 1.25 * s->reference_dt);
  printf("\n%-22s %6s %12s %12s %14s %10s %12s %9s\n", "method", "runs", "best error",
         "evals@1e-8", "ratio (evals)", "cpu@1e-8", "ratio (cpu)", "");
  for (size_t i = 0; i < N_METHODS; ++i) {
    const sweep *w = &s->sweeps[i];
    double best = INFINITY;
    for (size_t k = 0; k < w->n; ++k) best = fmin(best, w->runs[k].error);
    printf("%-22s %6zu %12.3e %12.4g %14.3f %10.4f %12.3f %9s\n", w->method->name, w->n, best,
           w->evals_at_target, w->evals_ratio, w->cpu_at_target, w->cpu_ratio,
           isfinite(w->evals_at_target) ? "" : "(not reached)");
  }
}

static void json_number(FILE *f, double x) {
  if (isfinite(x))
    fprintf(f, "%.6g", x);
  else
    fputs("null", f);
}

static void write_study_json(FILE *f, const study *s) {
  fprintf(f, "    {\"problem\": \"%s\", \"t_end\": %g, \"reference\": \"%s\", ", s->name, s->t_end,
          s->reference ? s->reference : "exact");
  if (s->reference) {
    fprintf(f, "\"reference_dt\": %g, \"reference_check\": ", s->reference_dt);
    json_number(f, s->reference_check);
    fputs(", ", f);
  }
  fprintf(f, "\"force_eval_budget\": %.0f,\n     \"methods\": [\n", s->budget);
  for (size_t i = 0; i < N_METHODS; ++i) {
    const sweep *w = &s->sweeps[i];
    fprintf(f, "       {\"method\": \"%s\", \"order\": %d, \"evals_at_1e-8\": ", w->method->name,
            w->method->order);
    json_number(f, w->evals_at_target);
    fputs(", \"evals_ratio_to_best\": ", f);
    json_number(f, w->evals_ratio);
    fputs(", \"cpu_s_at_1e-8\": ", f);
    json_number(f, w->cpu_at_target);
    fputs(", \"cpu_ratio_to_best\": ", f);
    json_number(f, w->cpu_ratio);
    fputs(",\n        \"runs\": [", f);
    for (size_t k = 0; k < w->n; ++k) {
      const run *r = &w->runs[k];
      fprintf(f, "%s{\"dt\": %.6g, \"steps\": %zu, \"force_evals\": %zu, \"cpu_s\": %.6g, "
                 "\"error\": ",
              k ? ", " : "", r->dt, r->steps, r->force_evals, r->cpu_s);
      json_number(f, r->error);
      fputc('}', f);
    }
    fprintf(f, "]}%s\n", i + 1 < N_METHODS ? "," : "");
  }
  fputs("     ]}", f);
}

static int gnuplot_on_path(void) {
  const char *path = getenv("PATH");
  char file[4096];
  while (path != NULL && *path != '\0') {
    size_t len = strcspn(path, ":");
    snprintf(file, sizeof file, "%.*s/gnuplot", (int)len, path);
    if (len > 0 && access(file, X_OK) == 0) return 1;
    path += len;
    if (*path == ':') ++path;
  }
  return 0;
}

static void plot_study(const study *s, const char *dir) {
  static const char *const colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                                       "#8c564b", "#e377c2", "#000000", "#17becf"};
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "gnuplot > /dev/null 2>&1");
  FILE *g = popen(cmd, "w");
  if (g == NULL) return;
  fputs("if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
        "  set terminal pngcairo size 960,600 font 'sans,10'\n"
        "} else {\n  set terminal png size 960,600\n}\n", g);
  fprintf(g, "set output '%s/%s'\n", dir, s->png);
  fprintf(g, "set title '%s, t_end = %g: relative error against the %s' noenhanced\n", s->name,
          s->t_end, s->reference ? "reference" : "exact solution");
  fputs("set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\nset grid\n"
        "set key inside right top noenhanced box opaque\n"
        "set xlabel 'force evaluations'\nset ylabel 'relative error at t_end' noenhanced\nplot ",
        g);
  for (size_t i = 0; i < N_METHODS; ++i)
    fprintf(g, "%s'-' using 1:2 with linespoints lw 1.5 lc rgb '%s' pt %zu title '%s'",
            i ? ", " : "", colors[i % 9], i + 1, s->sweeps[i].method->name);
  fputc('\n', g);
  for (size_t i = 0; i < N_METHODS; ++i) {
    for (size_t k = 0; k < s->sweeps[i].n; ++k) {
      const run *r = &s->sweeps[i].runs[k];
      if (r->error > 0 && isfinite(r->error))
        fprintf(g, "%zu %.6g\n", r->force_evals, r->error);
    }
    fputs("e\n", g);
  }
  pclose(g);
}

int main(int argc, char **argv) {
  const char *dir = argc > 1 ? argv[1] : "bench/results";
  static study studies[2];
  double start = bench_now();
  open_study(&studies[0], "kepler", "e", 0.6, 100.0, 1e7);
  studies[0].png = "work_precision_kepler.png";
  if (gm_model_problem(studies[0].model)->exact(gm_model_problem(studies[0].model)->ctx, 100.0,
                                                studies[0].y_ref) != 0)
    return 1;
  studies[0].ref_scale = norm_inf(studies[0].n, studies[0].y_ref);
  open_study(&studies[1], "outer-solar-system", NULL, 0, 500000.0, 4e6);
  studies[1].png = "work_precision_outer_solar_system.png";
  reference_run(&studies[1], "sofroniou-spaletta-10", 50.0);

  for (size_t i = 0; i < 2; ++i) {
    run_study(&studies[i]);
    print_study(&studies[i]);
  }
  printf("\nratios: force evaluations (and CPU time) to reach a relative error of 1e-8, over "
         "the best method's; %.1f s in all\n", bench_now() - start);

  FILE *f = bench_open_json(argc, argv, "work_precision");
  if (f != NULL) {
    fprintf(f, "{\n  \"benchmark\": \"work_precision\",\n  \"target_error\": 1e-8,\n"
               "  \"error\": \"max-norm of y - y_ref relative to max-norm of y_ref at t_end\",\n"
               "  \"ratio\": \"force evaluations (cpu time) to reach target_error, log-log "
               "interpolated, over the best method's in the same run\",\n  \"studies\": [\n");
    for (size_t i = 0; i < 2; ++i) {
      write_study_json(f, &studies[i]);
      fputs(i + 1 < 2 ? ",\n" : "\n", f);
    }
    fputs("  ]\n}\n", f);
    fclose(f);
  }
  if (gnuplot_on_path())
    for (size_t i = 0; i < 2; ++i) plot_study(&studies[i], dir);
  for (size_t i = 0; i < 2; ++i) {
    free(studies[i].y0);
    free(studies[i].y_ref);
    gm_model_free(studies[i].model);
  }
  return 0;
}
