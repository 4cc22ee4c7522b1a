/* The experiments module: the table is complete and consistent, and the library's experiments
 * reproduce the numbers the docs show (docs/maxwell.md E4, docs/oscillatory.md resonance). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/experiments.h"

Test(experiments, table_rows_are_complete_and_unique) {
  const size_t n = gm_experiment_count();
  cr_assert_geq(n, 20, "%zu rows", n);
  size_t in_library = 0;
  for (size_t i = 0; i < n; ++i) {
    const gm_experiment_info *e = gm_experiment_at(i);
    cr_assert_not_null(e);
    const char *fields[] = {e->name, e->seed, e->shows, e->seed_result, e->command,
                            e->doc};
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; ++k)
      cr_expect(fields[k] != NULL && fields[k][0] != '\0', "row %s: field %zu empty", e->name, k);
    cr_expect(strncmp(e->doc, "docs/", 5) == 0, "row %s: doc %s", e->name, e->doc);
    cr_expect_eq(gm_experiment_find(e->name), e, "row %s is not found by its name", e->name);
    in_library += e->run != NULL;
  }
  cr_expect_null(gm_experiment_at(n));
  cr_expect_null(gm_experiment_find("no-such-experiment"));
  cr_expect_eq(in_library, n); /* every row computes in the library */
}

/* The default E4 run is the one docs/maxwell.md prints (measured: 3620 steps, plain ranges
 * 5.161e-2 and 9.536e-3, leapfrog drift 4.108e-15). */
Test(experiments, e4_default_run_is_the_documented_one) {
  gm_e4_config c = gm_e4_defaults();
  gm_e4_result r;
  gm_error err = {{0}};
  cr_assert_eq(gm_experiment_e4(&c, NULL, &r, &err), GM_OK, "%s", err.message);
  cr_expect_eq(r.steps, 3620);
  cr_expect_eq(r.n_samples, 3621);
  cr_expect_float_eq(r.plain_initial, 0.323183046, 1e-9);
  cr_expect_float_eq(r.plain_range_first_half, 5.161e-2, 1e-5);
  cr_expect_float_eq(r.plain_range_second_half, 9.536e-3, 1e-6);
  cr_expect_lt(r.leapfrog_max_rel_drift, 2e-14, "%g", r.leapfrog_max_rel_drift);
  /* bounded: the second half oscillates less than the first */
  cr_expect_lt(r.plain_range_second_half, r.plain_range_first_half);
  gm_e4_result_clear(&r);
  cr_expect_null(r.t);
}

Test(experiments, e4_refuses_sizes_with_a_message) {
  gm_e4_config c = gm_e4_defaults();
  gm_e4_result r;
  gm_error err = {{0}};
  c.t_end = 1e9;
  cr_expect_eq(gm_experiment_e4(&c, NULL, &r, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "bytes") != NULL, "%s", err.message);
  c.n = 3;
  c.t_end = 1e-300;
  cr_expect_eq(gm_experiment_e4(&c, NULL, &r, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "shorter than one step") != NULL, "%s", err.message);
  c = gm_e4_defaults();
  c.n = 1;
  cr_expect_eq(gm_experiment_e4(&c, NULL, &r, &err), GM_EINVAL);
  c = gm_e4_defaults();
  c.t_end = NAN;
  cr_expect_eq(gm_experiment_e4(&c, NULL, &r, &err), GM_EINVAL);
  cr_expect_eq(gm_experiment_e4(&c, "/nonexistent/dir", &r, &err), GM_EINVAL);
}

/* 9 uniform points and the 48 near the integers: IMEX flat at 1.2501e-3 .. 1.2531e-3 (the
 * notes' independent check: 1.253e-3), the impulse method blowing up just below 1 (1.347e13 at
 * omega h/pi = 0.9995 in the 948-point run). */
Test(experiments, resonance_reproduces_fig_2_1, .timeout = 60) {
  gm_resonance_result r;
  gm_error err = {{0}};
  cr_assert_eq(gm_experiment_resonance(9, NULL, &r, &err), GM_OK, "%s", err.message);
  cr_expect_eq(r.n_points + r.n_near, 57);
  cr_expect_geq(r.imex_min, 1.2500e-3, "%.6e", r.imex_min);
  cr_expect_leq(r.imex_max, 1.2532e-3, "%.6e", r.imex_max);
  cr_expect_gt(r.impulse_max, 1e12, "%g", r.impulse_max);
  cr_expect_float_eq(r.impulse_max_at, 0.9995, 1e-9);
  cr_expect_geq(r.n_spike_near, 2);
  cr_expect_float_eq(r.spike_near[0], 1.0, 0.0);
  cr_expect_eq(gm_experiment_resonance(GM_RESONANCE_MAX_POINTS + 1, NULL, &r, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "points") != NULL, "%s", err.message);
  cr_expect_eq(gm_experiment_resonance(0, NULL, &r, &err), GM_EINVAL);
}

/* E2 as docs/oscillatory.md prints it: reference I3(150) = 0.957 (notes: 0.957), IMEX h = 0.1
 * max |dH| 1.5e-2 (notes 0.020), I at t = 150 0.017 0.018 0.968, Verlet h = 0.03 0.60. */
Test(experiments, fpu_reproduces_fig_2_2, .timeout = 60) {
  static gm_fpu_result r;
  gm_error err = {{0}};
  cr_assert_eq(gm_experiment_fpu(0, NULL, &r, &err), GM_OK, "%s", err.message);
  cr_assert_eq(r.n_runs, 6);
  cr_expect_float_eq(r.runs[0].at150[2], 0.957, 5e-4, "%.4f", r.runs[0].at150[2]);
  cr_expect(isnan(r.runs[0].max_abs_dev));
  cr_expect_float_eq(r.runs[0].t_exchange, 101.4, 1e-6, "%g", r.runs[0].t_exchange);
  const gm_fpu_run_result *imex = &r.runs[3];
  cr_assert_str_eq(imex->method, "imex");
  cr_expect_eq(imex->steps, 2000);
  cr_expect_float_eq(imex->max_abs_dh, 1.5e-2, 5e-4, "%.4e", imex->max_abs_dh);
  cr_expect_float_eq(imex->at150[0], 0.017, 5e-4, "%.4f", imex->at150[0]);
  cr_expect_float_eq(imex->at150[2], 0.968, 5e-4, "%.4f", imex->at150[2]);
  cr_expect_float_eq(r.runs[1].max_abs_dh, 0.60, 5e-3, "%.4f", r.runs[1].max_abs_dh);
  cr_expect_str_eq(imex->csv, "");
  cr_expect_eq(gm_experiment_fpu(0, "/nonexistent/dir", &r, &err), GM_EIO);
  cr_expect(strstr(err.message, "cannot write") != NULL, "%s", err.message);
}

/* docs/reduction.md: node drift -1.358 rad (continuous J2 = 0.05), +0.074 (discrete J2 = 0);
 * discrete J2 = 0 from the continuous J2 = 0 orbit 0.047 unreduced, 0.0038 reduced. */
Test(experiments, j2_satellite_reproduces_the_docs, .timeout = 60) {
  gm_j2_config c = gm_j2_defaults();
  gm_j2_result r;
  gm_error err = {{0}};
  cr_assert_eq(gm_experiment_j2_satellite(&c, NULL, &r, &err), GM_OK, "%s", err.message);
  cr_expect_eq(r.steps, 500);
  cr_expect_float_eq(r.mu, 1.287048, 1e-6);
  cr_expect_float_eq(r.node_drift_continuous[1], -1.358, 5e-4, "%.4f", r.node_drift_continuous[1]);
  cr_expect_float_eq(r.node_drift_discrete[0], 0.074, 5e-4, "%.4f", r.node_drift_discrete[0]);
  cr_expect_float_eq(r.discrete_0_to_continuous_0[0], 0.047, 5e-4, "%.4f",
                     r.discrete_0_to_continuous_0[0]);
  cr_expect_float_eq(r.discrete_0_to_continuous_0[1], 0.0038, 5e-5, "%.5f",
                     r.discrete_0_to_continuous_0[1]);
  /* the docs: 2.8e-13 and 1.0e-13 */
  cr_expect_lt(r.discrete_vs_rsprk[0], 1e-12, "%g", r.discrete_vs_rsprk[0]);
  c.dt = 200.0;
  cr_expect_eq(gm_experiment_j2_satellite(&c, NULL, &r, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "longer than the run") != NULL, "%s", err.message);
  c = gm_j2_defaults();
  c.dt = NAN;
  cr_expect_eq(gm_experiment_j2_satellite(&c, NULL, &r, &err), GM_EINVAL);
}

/* docs/reduction.md: max |E - E0|/|E0| 6.5e-5 for RSPRK, 4.8e-7 for RK4 at h/4 over t = 0..20;
 * RSPRK vs SPRK E 3.4e-15; E0 = -24.9693454219 in both forms; constrained 4.1e-9. */
Test(experiments, double_spherical_pendulum_reproduces_the_docs, .timeout = 60) {
  gm_dsp_config c = gm_dsp_defaults();
  gm_dsp_result r;
  gm_error err = {{0}};
  cr_assert_eq(gm_experiment_double_spherical_pendulum(&c, NULL, &r, &err), GM_OK, "%s",
               err.message);
  cr_expect_eq(r.steps, 2000);
  cr_expect_float_eq(r.rsprk_max_rel_energy_error, 6.5e-5, 5e-7, "%.4g",
                     r.rsprk_max_rel_energy_error);
  cr_expect_float_eq(r.rk4_max_rel_energy_error, 4.8e-7, 5e-9, "%.4g", r.rk4_max_rel_energy_error);
  cr_expect_lt(r.max_rel_rsprk_vs_sprk[3], 1e-13, "%g", r.max_rel_rsprk_vs_sprk[3]);
  cr_expect_float_eq(r.energy0, -24.9693454219, 1e-9, "%.12g", r.energy0);
  cr_expect_float_eq(r.constrained_energy0, -24.9693454219, 1e-9);
  cr_expect_float_eq(r.constrained_max_rel_energy_error, 4.1e-9, 5e-11, "%.4g",
                     r.constrained_max_rel_energy_error);
  c.x0[0] = 1.5;
  cr_expect_eq(gm_experiment_double_spherical_pendulum(&c, NULL, &r, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "r1") != NULL, "%s", err.message);
}

/* docs/mimetic.md, pendulum: MCI's H error bounded at 1.5e-4 at dt = 0.1 (measured 1.465e-4),
 * MGI's at round-off (5.9e-15), H-error orders MCI 4 (4.02), RK4 4.4 (4.44), MGI no fit. */
Test(experiments, mimetic_pendulum_reproduces_the_docs) {
  static gm_mimetic_result r;
  gm_error err = {{0}};
  cr_assert_eq(gm_experiment_mimetic("pendulum", NULL, &r, &err), GM_OK, "%s", err.message);
  cr_assert_eq(r.n_runs, 2 * GM_MIMETIC_METHODS);
  const gm_mimetic_run *mci = &r.runs[GM_MIMETIC_METHODS], *mgi = &r.runs[GM_MIMETIC_METHODS + 1];
  cr_assert_str_eq(mci->method, "mimetic-canonical-2");
  cr_expect_eq(mci->dt, 0.1);
  cr_expect_float_eq(mci->max_invariant_error, 1.465e-4, 1e-6, "%.4e", mci->max_invariant_error);
  cr_expect_lt(mgi->max_invariant_error, 5e-14, "%g", mgi->max_invariant_error);
  cr_expect_float_eq(r.invariant_order[0], 4.02, 0.01, "%.3f", r.invariant_order[0]);
  cr_expect_float_eq(r.invariant_order[2], 4.44, 0.01, "%.3f", r.invariant_order[2]);
  cr_expect(isnan(r.invariant_order[1]) && r.invariant_kept[1]);
  cr_expect_eq(gm_experiment_mimetic("pendulun", NULL, &r, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "pendulun") != NULL, "%s", err.message);
}
