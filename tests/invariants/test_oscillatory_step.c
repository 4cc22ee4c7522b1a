/* Issue 12's step requirement on FPU (ℓ = 3, ω = 50, T = 200): the rows that reach an error of
 * 1e-2 in the oscillatory energy I at h = 0.2 = 5 × Verlet's stability limit 2/ω keep reaching
 * it. The I error is the one of `geomint oscillatory work-precision` / `step-scan`: the largest
 * difference of the averages of I over the blocks [2k, 2k + 2) against blanes-moan-6 (here
 * h = 0.0005; the CLI's 0.0002 changes the reference's block averages by < 1e-9). Measured
 * (docs/oscillatory.md): trig-garcia-archilla 2.2e-3, trig-hairer-lubich 3.2e-3,
 * mollified-impulse-sinc (n = 20 substeps, its default) 4.5e-3; the other rows cannot (0 of
 * the 163 scanned steps in [0.2, 0.3] reach it; the reasons are derived in the docs) — and
 * mollified-impulse-sinc with n = 10 did not (3.5e-2), which the last check keeps visible. */
#include "test_util.h"

#define BLOCKS 100

typedef struct {
  const gm_problem *pb;
  size_t i_index;
  double sum[BLOCKS];
  size_t count[BLOCKS];
} blocks;

static int average_i(void *ctx, size_t step, double t, const double *y) {
  (void)step;
  blocks *b = ctx;
  long k = (long)floor(t / 2.0 + 1e-9);
  if (k >= 0 && k < BLOCKS) {
    b->sum[k] += b->pb->invariants[b->i_index].value(b->pb->ctx, y);
    b->count[k]++;
  }
  return 0;
}

static void block_means(const test_model *tm, const char *method, size_t substeps, double h,
                        double *means) {
  gm_integrator *it = test_integrator(gm_method_find(method), tm->problem, tm->t0, tm->y0);
  if (substeps > 0) cr_assert_eq(gm_oscillatory_set_substeps(it, substeps), GM_OK);
  blocks b;
  memset(&b, 0, sizeof b);
  b.pb = tm->problem;
  for (size_t j = 0; j < tm->problem->n_invariants; ++j)
    if (strcmp(tm->problem->invariants[j].name, "I") == 0) b.i_index = j;
  cr_assert_str_eq(tm->problem->invariants[b.i_index].name, "I");
  cr_assert_eq(gm_integrator_add_observer(it, average_i, &b, 1), GM_OK);
  cr_assert_eq(gm_integrator_run(it, (size_t)llround(200.0 / h), h), GM_OK, "%s: %s", method,
               gm_integrator_errmsg(it));
  for (size_t k = 0; k < BLOCKS; ++k) means[k] = b.sum[k] / (double)b.count[k];
  gm_integrator_free(it);
}

Test(oscillatory_step, five_times_verlet_limit_on_fpu, .timeout = 300) {
  test_model tm = test_model_make("fpu");
  double ref[BLOCKS], m[BLOCKS];
  block_means(&tm, "blanes-moan-6", 0, 0.0005, ref);
  const struct {
    const char *name;
    size_t substeps;
    int meets;
  } rows[] = {{"trig-garcia-archilla", 0, 1},
              {"trig-hairer-lubich", 0, 1},
              {"mollified-impulse-sinc", 0, 1},
              {"mollified-impulse-sinc", 10, 0},
              {"imex", 0, 0}};
  for (size_t r = 0; r < sizeof rows / sizeof rows[0]; ++r) {
    block_means(&tm, rows[r].name, rows[r].substeps, 0.2, m);
    double err = 0.0;
    for (size_t k = 0; k < BLOCKS; ++k) err = fmax(err, fabs(m[k] - ref[k]));
    cr_log_info("%s (n = %zu) at h = 0.2: I error %.3e", rows[r].name, rows[r].substeps, err);
    if (rows[r].meets)
      cr_expect_leq(err, 1e-2, "%s: I error %.3e at h = 5 x 2/omega", rows[r].name, err);
    else
      cr_expect_gt(err, 1e-2, "%s (n = %zu) now reaches 1e-2 at h = 0.2 (%.3e): update the docs",
                   rows[r].name, rows[r].substeps, err);
  }
  gm_model_free(tm.model);
}
