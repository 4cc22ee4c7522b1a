/* What the energy monitor of `geomint run` costs (issue 25, goal ≤ 1 % of a run): each row runs
 * the same integration with no observer, with gm_monitor_observe every step (the CLI's default
 * before), and every K = ceil(1024 / stages) steps (the CLI's default now without an output
 * file, src/cli/run.c), and reports the time of each over the bare run (thread CPU time, min
 * of REPEATS interleaved runs). The monitor's maxima at stride K are also printed next to the
 * every-step ones (the sampled maximum is a lower bound of the every-step one).
 * Writes DIR/monitor_cost.json. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/geomint.h"

#define REPEATS 9

typedef struct {
  const char *problem, *method;
  double h;
  size_t steps;
} row_def;

static const row_def rows[] = {{"kepler", "verlet", 0.01, 200000},
                               {"kepler", "kahan-li-8", 0.05, 20000},
                               {"kepler", "gauss-6", 0.1, 10000},
                               {"outer-solar-system", "kahan-li-8", 200.0, 2500},
                               {"outer-solar-system", "gauss-6", 200.0, 2500}};
#define N_ROWS (sizeof rows / sizeof rows[0])

static size_t cli_stride(const gm_method *m) {
  const size_t stages = m->n_stages > 0 ? m->n_stages : 1;
  return (1024 + stages - 1) / stages;
}

/* One run with the monitor every `every` steps (0: none); returns its CPU time. */
static double timed_run(const gm_model *model, const gm_method *m, const row_def *d, size_t every,
                        double *max_energy) {
  const gm_problem *pb = gm_model_problem(model);
  double t0, y0[64];
  gm_model_initial_state(model, &t0, y0);
  gm_integrator *it = NULL;
  gm_monitor *mon = NULL;
  gm_error err;
  if (gm_integrator_create(m, pb, &it, &err) != GM_OK) exit(1);
  gm_integrator_set_state(it, t0, y0);
  if (every > 0 && (gm_monitor_create(pb, y0, &mon) != GM_OK ||
                    gm_integrator_add_observer(it, gm_monitor_observe, mon, every) != GM_OK))
    exit(1);
  double c0 = bench_cpu_now();
  if (gm_integrator_run(it, d->steps, d->h) != GM_OK) exit(1);
  double c1 = bench_cpu_now();
  if (mon != NULL) *max_energy = gm_monitor_max_rel_energy_error(mon);
  gm_monitor_free(mon);
  gm_integrator_free(it);
  return c1 - c0;
}

int main(int argc, char **argv) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  FILE *f = bench_open_json(argc, argv, "monitor_cost");
  if (f == NULL) return 1;
  fprintf(f, "{\n \"benchmark\": \"monitor_cost\",\n \"repeats\": %d,\n \"rows\": [\n", REPEATS);
  printf("thread CPU time, min of %d interleaved runs; ratios over the run without a monitor\n",
         REPEATS);
  printf("%-44s %10s %12s %12s %6s %14s %14s\n", "problem, method", "bare [s]", "every step",
         "every K", "K", "max every step", "max every K");
  for (size_t r = 0; r < N_ROWS; ++r) {
    gm_model *model = NULL;
    if (gm_model_create(rows[r].problem, &model) != GM_OK || gm_model_build(model) != GM_OK)
      return 1;
    const gm_method *m = gm_method_find(rows[r].method);
    const size_t k = cli_stride(m);
    double bare = INFINITY, all = INFINITY, sampled = INFINITY, e_all = NAN, e_k = NAN, unused;
    for (int rep = 0; rep < REPEATS; ++rep) {
      bare = fmin(bare, timed_run(model, m, &rows[r], 0, &unused));
      all = fmin(all, timed_run(model, m, &rows[r], 1, &e_all));
      sampled = fmin(sampled, timed_run(model, m, &rows[r], k, &e_k));
    }
    char name[96];
    snprintf(name, sizeof name, "%s, %s, %zu steps", rows[r].problem, rows[r].method,
             rows[r].steps);
    printf("%-44s %10.4f %12.4f %12.4f %6zu %14.3e %14.3e\n", name, bare, all / bare,
           sampled / bare, k, e_all, e_k);
    fprintf(f, "  {\"case\": \"%s\", \"bare_s\": %.6f, \"every_step_ratio\": %.4f, "
            "\"every_k_ratio\": %.4f, \"k\": %zu, \"max_rel_energy_every_step\": %.4e, "
            "\"max_rel_energy_every_k\": %.4e}%s\n", name, bare, all / bare, sampled / bare, k,
            e_all, e_k, r + 1 < N_ROWS ? "," : "");
    gm_model_free(model);
  }
  fprintf(f, " ]\n}\n");
  fclose(f);
  return 0;
}
