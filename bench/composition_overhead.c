/* Cost per force evaluation of the composition stepper: yoshida-6 and kahan-li-8 composed with
 * their default basic method (position Verlet) through gm_integrator_run, against a bare loop
 * written here that applies the same merged kick–drift sequence with the same force calls (Kepler; 1000 bodies in a Plummer
 * sphere). Reports the ratio library/bare per force evaluation (target ≤ 1.10) and checks that
 * both end in the same state bit for bit. Thread CPU times, best of alternating repeats. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/geomint.h"

typedef struct {
  double coef[128];
  int kick[128];
  size_t n;
} op_list;

/* The method's basic steps (its default basic method's drift a_i and kick b_i coefficients)
 * scaled by each γ; consecutive kicks (drifts) of neighbouring basic steps merge (GNI (2006),
 * §V.3.1), as the library's splitting stepper does. Kick coefficients are kept positive. */
static void append_op(op_list *ops, double coef, int kick) {
  if (coef == 0.0) return;
  if (ops->n > 0 && ops->kick[ops->n - 1] == kick)
    ops->coef[ops->n - 1] += coef;
  else {
    ops->coef[ops->n] = coef;
    ops->kick[ops->n++] = kick;
  }
}

static op_list merged_ops(const gm_method *m) {
  gm_tableau *t = NULL, *basic = NULL;
  op_list ops = {{0}, {0}, 0};
  if (gm_method_tableau(m, &t) != GM_OK ||
      gm_method_tableau(gm_method_find(m->basic), &basic) != GM_OK)
    exit(1);
  for (size_t i = 0; i < t->n_stages; ++i)
    for (size_t j = 0; j < basic->n_stages; ++j) {
      append_op(&ops, t->gamma[i] * basic->a[j], 0);
      append_op(&ops, t->gamma[i] * basic->b[j], 1);
    }
  gm_tableau_free(t);
  gm_tableau_free(basic);
  return ops;
}

static size_t bare_run(const gm_problem *pb, const op_list *ops, double *y, size_t steps, double h,
                       double *force, double *velocity) {
  const size_t d = pb->dim;
  double *q = y, *p = y + d;
  /* the force of a first kick comes from the previous step's last one (first same as last) */
  const int fsal = ops->kick[0] && ops->kick[ops->n - 1];
  size_t evals = 0;
  if (fsal) {
    pb->potential_gradient(pb->ctx, q, force);
    evals = 1;
  }
  for (size_t s = 0; s < steps; ++s)
    for (size_t k = 0; k < ops->n; ++k) {
      if (ops->kick[k]) {
        if (k > 0 || !fsal) {
          pb->potential_gradient(pb->ctx, q, force);
          ++evals;
        }
        for (size_t i = 0; i < d; ++i) p[i] = p[i] + (-ops->coef[k] * h) * force[i];
      } else {
        pb->kinetic_gradient(pb->ctx, p, velocity);
        for (size_t i = 0; i < d; ++i) q[i] = q[i] + (ops->coef[k] * h) * velocity[i];
      }
    }
  return evals;
}

typedef struct {
  char name[64];
  size_t evals;
  double bare_s, library_s, ratio;
  int identical;
} row;

static row measure(const char *label, const gm_method *m, const gm_problem *pb, const double *y0,
                   double h, size_t steps, int repeats) {
  const size_t n = gm_problem_state_size(pb);
  double *y = malloc(n * sizeof *y), *f = malloc(n * sizeof *f), *v = malloc(n * sizeof *v);
  const op_list ops = merged_ops(m);
  row r;
  snprintf(r.name, sizeof r.name, "%s, %s", label, m->name);
  r.bare_s = r.library_s = INFINITY;
  gm_integrator *it = NULL;
  gm_error err;
  if (gm_integrator_create(m, pb, &it, &err) != GM_OK) {
    fprintf(stderr, "%s\n", err.message);
    exit(1);
  }
  for (int k = 0; k < repeats; ++k) {
    memcpy(y, y0, n * sizeof *y);
    double t0 = bench_cpu_now();
    r.evals = bare_run(pb, &ops, y, steps, h, f, v);
    r.bare_s = fmin(r.bare_s, bench_cpu_now() - t0);
    gm_integrator_set_state(it, 0.0, y0);
    gm_integrator_reset_stats(it);
    t0 = bench_cpu_now();
    if (gm_integrator_run(it, steps, h) != GM_OK) exit(1);
    r.library_s = fmin(r.library_s, bench_cpu_now() - t0);
  }
  r.identical = memcmp(y, gm_integrator_state(it), n * sizeof *y) == 0 &&
                gm_integrator_stats(it).force_evals == r.evals;
  r.ratio = r.library_s / r.bare_s;
  gm_integrator_free(it);
  free(y);
  free(f);
  free(v);
  return r;
}

int main(int argc, char **argv) {
  row rows[4];
  gm_model *kepler = NULL, *cluster = NULL;
  gm_model_create("kepler", &kepler);
  gm_model_build(kepler);
  gm_model_create("n-body", &cluster);
  gm_model_set(cluster, "n", 1000);
  gm_model_set(cluster, "eps", 0.01);
  if (gm_model_build(cluster) != GM_OK) {
    fprintf(stderr, "%s\n", gm_model_errmsg(cluster));
    return 1;
  }
  double t0, yk[4];
  gm_model_initial_state(kepler, &t0, yk);
  double *yc = malloc(gm_model_state_size(cluster) * sizeof *yc);
  gm_model_initial_state(cluster, &t0, yc);
  const char *methods[2] = {"yoshida-6", "kahan-li-8"};
  for (size_t i = 0; i < 2; ++i) {
    const gm_method *m = gm_method_find(methods[i]);
    rows[2 * i] = measure("kepler", m, gm_model_problem(kepler), yk, 0.01, 40000, 15);
    rows[2 * i + 1] = measure("1000 bodies", m, gm_model_problem(cluster), yc, 1e-3, 2, 5);
  }
  printf("%-28s %10s %12s %12s %8s %10s\n", "problem, method", "forces", "bare [s]",
         "library [s]", "ratio", "identical");
  for (size_t i = 0; i < 4; ++i)
    printf("%-28s %10zu %12.4f %12.4f %8.3f %10s\n", rows[i].name, rows[i].evals, rows[i].bare_s,
           rows[i].library_s, rows[i].ratio, rows[i].identical ? "yes" : "NO");
  FILE *f = bench_open_json(argc, argv, "composition_overhead");
  if (f != NULL) {
    fprintf(f, "{\n  \"benchmark\": \"composition_overhead\",\n  \"floor\": \"bare loop with the "
               "same merged kick-drift sequence and force calls\",\n  \"target_ratio\": 1.10,\n"
               "  \"rows\": [\n");
    for (size_t i = 0; i < 4; ++i) {
      fprintf(f, "    {\"case\": \"%s\", \"force_evals\": %zu, ", rows[i].name, rows[i].evals);
      bench_json_timing(f, rows[i].bare_s, rows[i].library_s, rows[i].ratio, rows[i].identical,
                        i + 1 == 4);
    }
    bench_close_json(f);
  }
  free(yc);
  gm_model_free(kepler);
  gm_model_free(cluster);
  int ok = 1;
  for (size_t i = 0; i < 4; ++i) ok &= rows[i].identical;
  return ok ? 0 : 1;
}
