/* Time per force evaluation of the ODE core on Kepler (e = 0.6, 200 periods), issue 25, all
 * ratios from one run (thread CPU time, min of REPEATS interleaved runs per row):
 *   - gauss-s (s = 2 … 6, default solver: fixed-point iteration on positions) against
 *     kahan-li-8 at the step counts of the table (goal ≤ 1.05);
 *   - kahan-li-8 and the outer solar system's kahan-li-8 against the plainest loop that computes
 *     the same numbers: the merged kick–drift sequence of the composition (GNI (2006), §V.3.1)
 *     with the force written inline (no callback, no counters), which must end in the same state
 *     bit for bit (goal ≤ 1.0 for the composition's time per evaluation over that loop).
 * `bench_ode_eval_cost DIR METHOD` runs METHOD once on Kepler and nothing else, printing the end
 * state in hexadecimal (for callgrind: instructions per evaluation = Ir of gm_integrator_run /
 * force evaluations; and for bitwise comparisons between builds).
 * Writes DIR/ode_eval_cost.json. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/geomint.h"
#include "problems/internal.h"

#define REPEATS 11
#define PERIODS 200.0

typedef struct {
  const char *method;
  size_t steps;
} row_def;

/* gauss-4, gauss-6, kahan-li-8: the N for error 1e-8; the others near their own 1e-8
 * step, or (gauss-2) a cost-bounded step. */
static const row_def rows[] = {{"kahan-li-8", 25548}, {"gauss-2", 60000},
                               {"gauss-3", 40000},    {"gauss-4", 30913},
                               {"gauss-5", 16000},    {"gauss-6", 11918}};
#define N_ROWS (sizeof rows / sizeof rows[0])

typedef struct {
  double coef[128];
  int kick[128];
  size_t n;
} op_list;

/* The composition's drift–kick list as the splitting stepper compiles it: the basic method's
 * coefficients (a_i drift, −b_i kick) scaled by each γ_k, neighbours of one kind merged
 * (GNI (2006), §V.3.1). */
static void append(op_list *ops, double coef, int kick) {
  if (coef == 0.0) return;
  if (ops->n > 0 && ops->kick[ops->n - 1] == kick)
    ops->coef[ops->n - 1] += coef;
  else {
    ops->coef[ops->n] = coef;
    ops->kick[ops->n++] = kick;
  }
}

static op_list merged_ops(const gm_method *m) {
  gm_tableau *outer = NULL, *basic = NULL;
  op_list ops = {{0}, {0}, 0};
  if (gm_method_tableau(m, &outer) != GM_OK ||
      gm_method_tableau(gm_method_find(m->basic), &basic) != GM_OK)
    exit(1);
  for (size_t k = 0; k < outer->n_stages; ++k)
    for (size_t i = 0; i < basic->n_stages; ++i) {
      append(&ops, outer->gamma[k] * basic->a[i], 0);
      append(&ops, -outer->gamma[k] * basic->b[i], 1);
    }
  gm_tableau_free(outer);
  gm_tableau_free(basic);
  return ops;
}

/* The Kepler force q/|q|³ as src/problems/kepler.c computes it, inline. */
static size_t plain_kepler(const op_list *ops, double *y, size_t steps, double h) {
  double q0 = y[0], q1 = y[1], p0 = y[2], p1 = y[3], f0, f1;
  size_t evals = 0;
#define KEPLER_FORCE()                                  \
  do {                                                  \
    double r = sqrt(q0 * q0 + q1 * q1), r3 = r * r * r; \
    f0 = q0 / r3;                                       \
    f1 = q1 / r3;                                       \
    ++evals;                                            \
  } while (0)
  for (size_t s = 0; s < steps; ++s)
    for (size_t k = 0; k < ops->n; ++k) {
      const double c = ops->coef[k] * h;
      if (ops->kick[k]) {
        KEPLER_FORCE();
        p0 = p0 + c * f0;
        p1 = p1 + c * f1;
      } else {
        q0 = q0 + c * p0;
        q1 = q1 + c * p1;
      }
    }
#undef KEPLER_FORCE
  y[0] = q0;
  y[1] = q1;
  y[2] = p0;
  y[3] = p1;
  return evals;
}

/* Newtonian gravity of nb bodies as src/problems/gravity.c computes it (ε = 0), inline. */
static void gravity_force(size_t nb, double G, const double *m, const double *q, double *out) {
  for (size_t i = 0; i < 3 * nb; ++i) out[i] = 0.0;
  for (size_t i = 0; i < nb; ++i) {
    const double gmi = G * m[i];
    for (size_t j = i + 1; j < nb; ++j) {
      double dx = q[3 * i] - q[3 * j], dy = q[3 * i + 1] - q[3 * j + 1],
             dz = q[3 * i + 2] - q[3 * j + 2];
      double s = dx * dx + dy * dy + dz * dz + 0.0;
      double f = gmi * m[j] / (s * sqrt(s));
      out[3 * i] += f * dx;
      out[3 * i + 1] += f * dy;
      out[3 * i + 2] += f * dz;
      out[3 * j] -= f * dx;
      out[3 * j + 1] -= f * dy;
      out[3 * j + 2] -= f * dz;
    }
  }
}

static size_t plain_gravity(const op_list *ops, size_t nb, double G, const double *m, double *y,
                            size_t steps, double h) {
  const size_t d = 3 * nb;
  double *q = y, *p = y + d, f[64];
  size_t evals = 0;
  for (size_t s = 0; s < steps; ++s)
    for (size_t k = 0; k < ops->n; ++k) {
      const double c = ops->coef[k] * h;
      if (ops->kick[k]) {
        gravity_force(nb, G, m, q, f);
        ++evals;
        for (size_t i = 0; i < d; ++i) p[i] = p[i] + c * f[i];
      } else
        for (size_t i = 0; i < d; ++i) q[i] = q[i] + c * (p[i] / m[i / 3]);
    }
  return evals;
}

typedef struct {
  double best_s, evals, error;
} timing;

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

/* One timed run of it from y0; the best time so far in *t. */
static void time_run(gm_integrator *it, const double *y0, size_t steps, double h, timing *t) {
  gm_integrator_set_state(it, 0.0, y0);
  gm_integrator_reset_stats(it);
  double c0 = bench_cpu_now();
  if (gm_integrator_run(it, steps, h) != GM_OK) {
    fprintf(stderr, "%s\n", gm_integrator_errmsg(it));
    exit(1);
  }
  t->best_s = fmin(t->best_s, bench_cpu_now() - c0);
  t->evals = (double)gm_integrator_stats(it).force_evals;
}

static double max_error(size_t n, const double *y, const double *ref) {
  double e = 0.0;
  for (size_t i = 0; i < n; ++i) e = fmax(e, fabs(y[i] - ref[i]));
  return e;
}

int main(int argc, char **argv) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  gm_model *kepler = NULL, *solar = NULL;
  if (gm_model_create("kepler", &kepler) != GM_OK || gm_model_build(kepler) != GM_OK) return 1;
  const gm_problem *pk = gm_model_problem(kepler);
  double t0, yk[4], exact[4];
  gm_model_initial_state(kepler, &t0, yk);
  const double t_end = PERIODS * 2.0 * 3.14159265358979323846;
  if (pk->exact(pk->ctx, t_end, exact) != 0) return 1;

  if (argc > 2) { /* one method, once: for callgrind */
    size_t steps = 20000;
    for (size_t k = 0; k < N_ROWS; ++k)
      if (strcmp(rows[k].method, argv[2]) == 0) steps = rows[k].steps;
    gm_integrator *it = make(argv[2], pk);
    timing t = {INFINITY, 0, 0};
    time_run(it, yk, steps, t_end / (double)steps, &t);
    const double *y = gm_integrator_state(it);
    printf("%s: %zu steps, %.0f force evaluations, error %.2e, state %a %a %a %a\n", argv[2],
           steps, t.evals, max_error(4, y, exact), y[0], y[1], y[2], y[3]);
    gm_integrator_free(it);
    gm_model_free(kepler);
    return 0;
  }

  /* the outer solar system, 500 000 days at h = 200 with kahan-li-8 */
  if (gm_model_create("outer-solar-system", &solar) != GM_OK || gm_model_build(solar) != GM_OK)
    return 1;
  const gm_problem *ps = gm_model_problem(solar);
  const size_t ns = gm_model_state_size(solar), nb = ns / 6;
  double ys[64], ts;
  gm_model_initial_state(solar, &ts, ys);
  const gm_gravity *grav = ps->ctx; /* the context begins with it (problems/internal.h) */
  const double G = grav->G, *masses = grav->mass;
  const size_t solar_steps = 2500;
  const double solar_h = 200.0;

  gm_integrator *its[N_ROWS], *it_solar = make("kahan-li-8", ps);
  timing t[N_ROWS], plain_k = {INFINITY, 0, 0}, plain_s = {INFINITY, 0, 0},
                    lib_s = {INFINITY, 0, 0};
  for (size_t k = 0; k < N_ROWS; ++k) {
    its[k] = make(rows[k].method, pk);
    t[k] = (timing){INFINITY, 0, 0};
  }
  const op_list ops = merged_ops(gm_method_find("kahan-li-8"));
  double y_plain_k[4], y_plain_s[64];
  for (int r = 0; r < REPEATS; ++r) {
    for (size_t k = 0; k < N_ROWS; ++k)
      time_run(its[k], yk, rows[k].steps, t_end / (double)rows[k].steps, &t[k]);
    memcpy(y_plain_k, yk, sizeof yk);
    double c0 = bench_cpu_now();
    plain_k.evals = (double)plain_kepler(&ops, y_plain_k, rows[0].steps,
                                         t_end / (double)rows[0].steps);
    plain_k.best_s = fmin(plain_k.best_s, bench_cpu_now() - c0);
    time_run(it_solar, ys, solar_steps, solar_h, &lib_s);
    memcpy(y_plain_s, ys, ns * sizeof *ys);
    c0 = bench_cpu_now();
    plain_s.evals = (double)plain_gravity(&ops, nb, G, masses, y_plain_s, solar_steps, solar_h);
    plain_s.best_s = fmin(plain_s.best_s, bench_cpu_now() - c0);
  }
  /* the last run of each row is the one reported: errors and bitwise comparisons */
  const int same_k = memcmp(y_plain_k, gm_integrator_state(its[0]), sizeof y_plain_k) == 0 &&
                     plain_k.evals == t[0].evals;
  const int same_s = memcmp(y_plain_s, gm_integrator_state(it_solar), ns * sizeof *ys) == 0 &&
                     plain_s.evals == lib_s.evals;
  const double per_ref = t[0].best_s / t[0].evals;
  FILE *f = bench_open_json(argc, argv, "ode_eval_cost");
  if (f == NULL) return 1;
  fprintf(f, "{\n \"benchmark\": \"ode_eval_cost\",\n \"problem\": \"kepler e=0.6, %g periods\",\n"
          " \"repeats\": %d,\n \"rows\": [\n", PERIODS, REPEATS);
  printf("Kepler e = 0.6, %g periods; thread CPU time, min of %d interleaved runs\n", PERIODS,
         REPEATS);
  printf("%-12s %8s %10s %12s %10s %10s %14s\n", "method", "steps", "evals", "evals/step",
         "ns/eval", "error", "ns/eval ratio");
  for (size_t k = 0; k < N_ROWS; ++k) {
    const double per = t[k].best_s / t[k].evals;
    const double err = max_error(4, gm_integrator_state(its[k]), exact);
    printf("%-12s %8zu %10.0f %12.3f %10.2f %10.2e %14.3f\n", rows[k].method, rows[k].steps,
           t[k].evals, t[k].evals / (double)rows[k].steps, 1e9 * per, err, per / per_ref);
    fprintf(f, "  {\"method\": \"%s\", \"steps\": %zu, \"evals\": %.0f, \"ns_per_eval\": %.3f, "
            "\"error\": %.3e, \"ratio_to_kahan_li_8\": %.4f},\n", rows[k].method, rows[k].steps,
            t[k].evals, 1e9 * per, err, per / per_ref);
  }
  const double rk = (t[0].best_s / t[0].evals) / (plain_k.best_s / plain_k.evals);
  const double rs = (lib_s.best_s / lib_s.evals) / (plain_s.best_s / plain_s.evals);
  printf("plain loop, kepler:      %.2f ns/eval; kahan-li-8 over it %.3f (same state: %s)\n",
         1e9 * plain_k.best_s / plain_k.evals, rk, same_k ? "yes" : "NO");
  printf("plain loop, outer solar system (h = %g, %zu steps): %.2f ns/eval, kahan-li-8 %.2f; "
         "over it %.3f (same state: %s)\n", solar_h, solar_steps,
         1e9 * plain_s.best_s / plain_s.evals, 1e9 * lib_s.best_s / lib_s.evals, rs,
         same_s ? "yes" : "NO");
  fprintf(f, "  {\"method\": \"plain-loop-kepler\", \"ns_per_eval\": %.3f, "
          "\"kahan_li_8_over_plain\": %.4f, \"identical\": %s},\n",
          1e9 * plain_k.best_s / plain_k.evals, rk, same_k ? "true" : "false");
  fprintf(f, "  {\"method\": \"plain-loop-outer-solar-system\", \"ns_per_eval\": %.3f, "
          "\"kahan_li_8_over_plain\": %.4f, \"identical\": %s}\n ]\n}\n",
          1e9 * plain_s.best_s / plain_s.evals, rs, same_s ? "true" : "false");
  fclose(f);
  for (size_t k = 0; k < N_ROWS; ++k) gm_integrator_free(its[k]);
  gm_integrator_free(it_solar);
  gm_model_free(kepler);
  gm_model_free(solar);
  return same_k && same_s ? 0 : 1;
}
