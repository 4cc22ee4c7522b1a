/* Checkpoint and restart (gm_integrator_save / _load / _resume): a run interrupted at a random
 * step and continued from its checkpoint ends bitwise where the uninterrupted run ends, with the
 * same statistics; damaged, foreign and mismatched checkpoints are errors with a message. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "test_util.h"

typedef struct {
  size_t stop_at;
  FILE *file;
} interrupter;

/* Save at the step asked for, then stop the run (as SIGINT would). */
static int save_and_stop(void *ctx, size_t step, double t, const double *y) {
  (void)t;
  (void)y;
  interrupter *in = ctx;
  return step == in->stop_at ? 1 : 0;
}

typedef struct {
  const char *method, *basic;
  gm_solver solver;
  int compensated;
  int fixed_steps; /* 1: gm_integrator_run (N steps), 0: gm_integrator_integrate (to T) */
} case_t;

static gm_integrator *make(const case_t *c, const test_model *tm) {
  const gm_scheme sc = {gm_method_find(c->method), c->basic ? gm_method_find(c->basic) : NULL,
                        c->solver, c->compensated};
  cr_assert_not_null(sc.method, "%s", c->method);
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_integrator_create_scheme(&sc, tm->problem, &it, &err), GM_OK, "%s: %s",
               c->method, err.message);
  cr_assert_eq(gm_integrator_set_state(it, tm->t0, tm->y0), GM_OK);
  return it;
}

static gm_status go(gm_integrator *it, const case_t *c) {
  return c->fixed_steps ? gm_integrator_run(it, 300, 0.02) : gm_integrator_integrate(it, 6.1, 0.02);
}

static void expect_same_stats(const char *name, gm_stats a, gm_stats b) {
  cr_expect_eq(a.steps, b.steps, "%s: steps %zu vs %zu", name, a.steps, b.steps);
  cr_expect_eq(a.force_evals, b.force_evals, "%s: force evaluations %zu vs %zu", name,
               a.force_evals, b.force_evals);
  cr_expect_eq(a.jacobian_evals, b.jacobian_evals, "%s: Jacobians", name);
  cr_expect_eq(a.newton_iterations, b.newton_iterations, "%s: Newton iterations %zu vs %zu",
               name, a.newton_iterations, b.newton_iterations);
  cr_expect_eq(a.fixed_point_iterations, b.fixed_point_iterations,
               "%s: fixed-point iterations %zu vs %zu", name, a.fixed_point_iterations,
               b.fixed_point_iterations);
}

Test(checkpoint, restart_is_bitwise_identical) {
  static const case_t cases[] = {
      {"verlet", NULL, GM_SOLVER_DEFAULT, 0, 0},            /* explicit, FSAL force kept */
      {"rk4", NULL, GM_SOLVER_DEFAULT, 1, 1},               /* explicit, compensated carry */
      {"yoshida-6", NULL, GM_SOLVER_DEFAULT, 1, 0},         /* composition, compensated */
      {"gauss-2", NULL, GM_SOLVER_FIXED_POINT, 0, 0},       /* implicit, starting values */
      {"gauss-3", NULL, GM_SOLVER_DEFAULT, 1, 1},           /* implicit, simplified Newton */
      {"gauss-5", NULL, GM_SOLVER_FIXED_POINT_POSITIONS, 0, 1}, /* positions: stage forces kept */
      {"yoshida-4", "midpoint", GM_SOLVER_NEWTON, 0, 1},    /* composition of an implicit */
      {"mimetic-galerkin-2", NULL, GM_SOLVER_DEFAULT, 0, 0},
      {"avf", NULL, GM_SOLVER_DEFAULT, 0, 1},
      {"vi-galerkin-gauss-2", NULL, GM_SOLVER_DEFAULT, 0, 0}, /* variational */
      {"vi-midpoint", NULL, GM_SOLVER_DEFAULT, 1, 1},
      {"vi-sem-midpoint", NULL, GM_SOLVER_DEFAULT, 0, 0}, /* its own steps, to T */
  };
  test_model tm = test_model_make("kepler");
  uint64_t lcg = 20261125u;
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    const case_t *c = &cases[i];
    gm_integrator *whole = make(c, &tm);
    cr_assert_eq(go(whole, c), GM_OK, "%s: %s", c->method, gm_integrator_errmsg(whole));
    const size_t n_steps = gm_integrator_stats(whole).steps;
    for (int trial = 0; trial < 3; ++trial) {
      lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
      const size_t k = 1 + (size_t)((lcg >> 33) % (n_steps - 1)); /* a random inner step */
      /* the interrupted run: a checkpoint at step k (saved from an observer), then stopped */
      gm_integrator *first = make(c, &tm);
      interrupter in = {k, tmpfile()};
      cr_assert_not_null(in.file);
      cr_assert_eq(gm_integrator_add_observer(first, save_and_stop, &in, 1), GM_OK);
      cr_assert_eq(go(first, c), GM_ECALLBACK, "%s: not interrupted", c->method);
      cr_assert_eq(gm_integrator_stats(first).steps, k);
      const double extra = 42.5;
      cr_assert_eq(gm_integrator_save(first, in.file, &extra, sizeof extra), GM_OK, "%s: %s",
                   c->method, gm_integrator_errmsg(first));
      gm_integrator_free(first);
      rewind(in.file);
      /* a fresh integrator, restarted from the file */
      gm_integrator *second = make(c, &tm);
      double got = 0.0;
      size_t got_size = 0;
      cr_assert_eq(gm_integrator_load(second, in.file, &got, sizeof got, &got_size), GM_OK,
                   "%s: %s", c->method, gm_integrator_errmsg(second));
      cr_expect(got_size == sizeof got && got == extra);
      fclose(in.file);
      cr_assert_eq(gm_integrator_resume(second), GM_OK, "%s: %s", c->method,
                   gm_integrator_errmsg(second));
      char name[96];
      snprintf(name, sizeof name, "%s restarted at step %zu of %zu", c->method, k, n_steps);
      cr_expect_eq(gm_integrator_time(second), gm_integrator_time(whole), "%s: t %.17g vs %.17g",
                   name, gm_integrator_time(second), gm_integrator_time(whole));
      const double *a = gm_integrator_state(second), *b = gm_integrator_state(whole);
      for (size_t j = 0; j < tm.n; ++j)
        cr_expect_eq(a[j], b[j], "%s: y[%zu] %.17g vs %.17g", name, j, a[j], b[j]);
      expect_same_stats(name, gm_integrator_stats(second), gm_integrator_stats(whole));
      if (gm_integrator_chooses_steps(whole))
        cr_expect_eq(gm_variational_energy_fallbacks(second),
                     gm_variational_energy_fallbacks(whole), "%s: fallbacks", name);
      gm_integrator_free(second);
    }
    gm_integrator_free(whole);
  }
  gm_model_free(tm.model);
}

/* A checkpoint of verlet on Kepler, in memory. */
static size_t verlet_checkpoint(const test_model *tm, unsigned char *buf, size_t cap) {
  gm_integrator *it = test_integrator(gm_method_find("verlet"), tm->problem, tm->t0, tm->y0);
  cr_assert_eq(gm_integrator_run(it, 10, 0.01), GM_OK);
  FILE *f = tmpfile();
  cr_assert_eq(gm_integrator_save(it, f, NULL, 0), GM_OK);
  long size = ftell(f);
  rewind(f);
  cr_assert(size > 0 && (size_t)size <= cap);
  cr_assert_eq(fread(buf, 1, (size_t)size, f), (size_t)size);
  fclose(f);
  gm_integrator_free(it);
  return (size_t)size;
}

static gm_status load_bytes(gm_integrator *it, const unsigned char *buf, size_t size) {
  FILE *f = tmpfile();
  fwrite(buf, 1, size, f);
  rewind(f);
  gm_status st = gm_integrator_load(it, f, NULL, 0, NULL);
  fclose(f);
  return st;
}

Test(checkpoint, damaged_foreign_and_mismatched_files_are_errors) {
  test_model tm = test_model_make("kepler");
  unsigned char buf[4096];
  const size_t size = verlet_checkpoint(&tm, buf, sizeof buf);
  gm_integrator *it = test_integrator(gm_method_find("verlet"), tm.problem, tm.t0, tm.y0);
  cr_assert_eq(load_bytes(it, buf, size), GM_OK, "%s", gm_integrator_errmsg(it));
  cr_expect_eq(gm_integrator_stats(it).steps, 10);
  /* truncated anywhere */
  for (size_t cut = 0; cut < size; cut += 7) {
    cr_expect_neq(load_bytes(it, buf, cut), GM_OK, "cut at %zu of %zu", cut, size);
    cr_expect(cut < 8 || strstr(gm_integrator_errmsg(it), "truncated") != NULL, "%zu: %s", cut,
              gm_integrator_errmsg(it));
  }
  /* one flipped bit in the state */
  unsigned char bad[4096];
  memcpy(bad, buf, size);
  bad[size - 40] ^= 0x10;
  cr_expect_eq(load_bytes(it, bad, size), GM_EIO);
  cr_expect(strstr(gm_integrator_errmsg(it), "checksum") != NULL, "%s", gm_integrator_errmsg(it));
  /* a foreign file */
  const char text[] = "t,q1,q2,p1,p2\n0,0.4,0,0,2\n";
  cr_expect_eq(load_bytes(it, (const unsigned char *)text, sizeof text - 1), GM_EINVAL);
  cr_expect(strstr(gm_integrator_errmsg(it), "not a geomint checkpoint") != NULL, "%s",
            gm_integrator_errmsg(it));
  gm_integrator_free(it);
  /* another method, another problem size, other compensation */
  it = test_integrator(gm_method_find("rk4"), tm.problem, tm.t0, tm.y0);
  cr_expect_eq(load_bytes(it, buf, size), GM_EINVAL);
  cr_expect(strstr(gm_integrator_errmsg(it), "'verlet'") != NULL, "%s", gm_integrator_errmsg(it));
  gm_integrator_free(it);
  test_model hh = test_model_make("outer-solar-system");
  it = test_integrator(gm_method_find("verlet"), hh.problem, hh.t0, hh.y0);
  cr_expect_eq(load_bytes(it, buf, size), GM_EINVAL);
  cr_expect(strstr(gm_integrator_errmsg(it), "state size") != NULL, "%s",
            gm_integrator_errmsg(it));
  const double y_before = gm_integrator_state(it)[0];
  cr_expect_eq(gm_integrator_state(it)[0], y_before); /* unchanged */
  gm_integrator_free(it);
  it = test_integrator(gm_method_find("verlet"), tm.problem, tm.t0, tm.y0);
  cr_assert_eq(gm_integrator_set_compensated(it, 1), GM_OK);
  cr_expect_eq(load_bytes(it, buf, size), GM_EINVAL);
  cr_expect(strstr(gm_integrator_errmsg(it), "compensated") != NULL, "%s",
            gm_integrator_errmsg(it));
  gm_integrator_free(it);
  gm_model_free(hh.model);
  gm_model_free(tm.model);
}
