/* Rigid bodies on SO(3): the state stays on the group, the variational rows keep the Casimir
 * and the spatial angular momentum to round-off and the energy without drift, RKMK and
 * Crouch–Grossman drift, the intermediate-axis flip has the closed-form period to the method's
 * order, and the heavy top keeps its two conserved components. No row projects R back onto
 * SO(3): every update is R ← R (I + E) with E = F − I of a product of exact rotations. */
#include <float.h>

#include "test_util.h"

typedef struct {
  const gm_problem *pb;
  double e0;             /* initial energy */
  double inv0[8];        /* initial invariants */
  size_t half;           /* step index where the second half begins */
  double energy[2];      /* max |H − H0| / |H0| in each half */
  double drift[8];       /* max |I_k − I_k(0)| */
} tracker;

static int track(void *ctx, size_t step, double t, const double *y) {
  (void)t;
  tracker *tr = ctx;
  double e = fabs(gm_problem_energy(tr->pb, y) - tr->e0) / fabs(tr->e0);
  size_t h = step >= tr->half ? 1 : 0;
  tr->energy[h] = fmax(tr->energy[h], e);
  for (size_t k = 0; k < tr->pb->n_invariants && k < 8; ++k)
    tr->drift[k] =
        fmax(tr->drift[k], fabs(tr->pb->invariants[k].value(tr->pb->ctx, y) - tr->inv0[k]));
  return 0;
}

/* Run n steps of h with compensated summation or not; return the tracker and the final state. */
static tracker run_tracked(const gm_method *m, const test_model *tm, size_t n, double h,
                           int compensated, size_t every, double *y_end) {
  tracker tr;
  memset(&tr, 0, sizeof tr);
  tr.pb = tm->problem;
  tr.e0 = gm_problem_energy(tm->problem, tm->y0);
  tr.half = n / 2;
  for (size_t k = 0; k < tm->problem->n_invariants && k < 8; ++k)
    tr.inv0[k] = tm->problem->invariants[k].value(tm->problem->ctx, tm->y0);
  gm_integrator *it = test_integrator(m, tm->problem, tm->t0, tm->y0);
  cr_assert_eq(gm_integrator_set_compensated(it, compensated), GM_OK);
  cr_assert_eq(gm_integrator_add_observer(it, track, &tr, every), GM_OK);
  cr_assert_eq(gm_integrator_run(it, n, h), GM_OK, "%s: %s", m->name, gm_integrator_errmsg(it));
  memcpy(y_end, gm_integrator_state(it), tm->n * sizeof *y_end);
  gm_integrator_free(it);
  return tr;
}

/* 10⁶ steps of every row on the free rigid body (h = 0.01, T = 10⁴, about 190 flips). With
 * compensated summation of the update R + R E the orthogonality defect stays at 1e-15; without
 * it the rounding of R + R E random-walks to ~1e-13 (docs/lie-groups.md), which is asserted
 * at 1e-12 on the cheapest row only, to keep the suite's time small. */
/* The rows whose step solves at most a 3×3 system (explicit ones and lgvi) take 10⁶ steps here;
 * the Galerkin and DEP rows (a 3s-dimensional Newton solve with a difference Jacobian, 10–20 µs
 * a step) take 2·10⁴ to keep the suite's time small; their 10⁶-step numbers are measured once
 * in docs/lie-groups.md. */
static int cheap_row(const gm_method *m) {
  return (m->flags & GM_EXPLICIT) || strcmp(m->name, "lgvi") == 0;
}

Test(rigid_body, million_steps_stay_on_the_group, .timeout = 300) {
  test_model tm = test_model_make("rigid-body");
  size_t n_rows = 0;
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (!test_accepts(m, tm.problem)) continue;
    ++n_rows;
    double y[12];
    const size_t n = cheap_row(m) ? 1000000 : 20000;
    tracker tr = run_tracked(m, &tm, n, 0.01, 1, cheap_row(m) ? 1000 : 100, y);
    double defect = gm_problem_state_defect(tm.problem, y);
    cr_log_info("%s, %zu steps: |R^T R - I| = %.2e, energy %.2e / %.2e (halves), casimir %.2e, "
                "L %.2e %.2e %.2e",
                m->name, n, defect, tr.energy[0], tr.energy[1], tr.drift[0], tr.drift[1],
                tr.drift[2], tr.drift[3]);
    cr_expect_leq(defect, 1e-13, "%s: |R^T R - I| = %.2e after %zu steps", m->name, defect, n);
    if (m->flags & GM_SYMPLECTIC) {
      /* Casimir and spatial momentum: exact rotations of Π; round-off only */
      for (size_t k = 0; k < 4; ++k)
        cr_expect_leq(tr.drift[k], 5e-13, "%s: %s drifts by %.2e", m->name,
                      tm.problem->invariants[k].name, tr.drift[k]);
      /* energy bounded: no growth from the first half to the second beyond the random walk of
       * round-off, 4ε√n (Brouwer's law) */
      cr_expect_leq(tr.energy[1], 1.1 * tr.energy[0] + 4 * DBL_EPSILON * sqrt((double)n),
                    "%s: energy error %.3e in the first half, %.3e in the second", m->name,
                    tr.energy[0], tr.energy[1]);
    }
  }
  cr_expect_geq(n_rows, 4);
  /* without compensated summation, on the cheapest row */
  double y[12];
  run_tracked(gm_method_find("rigid-splitting"), &tm, 1000000, 0.01, 0, 1000000, y);
  double defect = gm_problem_state_defect(tm.problem, y);
  cr_log_info("rigid-splitting without compensation: |R^T R - I| = %.2e", defect);
  cr_expect_leq(defect, 1e-12, "uncompensated: %.2e", defect);
  gm_model_free(tm.model);
}

/* RKMK and Crouch–Grossman do not preserve the Lie–Poisson structure: with h = 0.2 their energy
 * and Casimir errors grow linearly (doubling from 5·10⁴ to 10⁵ steps), while the variational
 * rows stay bounded. 10⁵ steps (not 10⁶) suffice to show the drift. */
Test(rigid_body, rkmk_and_crouch_grossman_drift) {
  test_model tm = test_model_make("rigid-body");
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (!test_accepts(m, tm.problem)) continue;
    double y[12];
    const size_t n = cheap_row(m) ? 100000 : 10000;
    tracker tr = run_tracked(m, &tm, n, 0.2, 0, 100, y);
    cr_log_info("%s, h = 0.2: energy %.2e / %.2e, casimir %.2e", m->name, tr.energy[0],
                tr.energy[1], tr.drift[0]);
    if (m->flags & GM_SYMPLECTIC)
      cr_expect_leq(tr.energy[1], 1.1 * tr.energy[0] + 4 * DBL_EPSILON * sqrt((double)n),
                    "%s: %.3e then %.3e", m->name, tr.energy[0], tr.energy[1]);
    else {
      cr_expect_geq(tr.energy[1], 1.7 * tr.energy[0], "%s: no drift? %.3e then %.3e", m->name,
                    tr.energy[0], tr.energy[1]);
      cr_expect_geq(tr.drift[0], 1e-6, "%s: casimir drift %.3e", m->name, tr.drift[0]);
    }
  }
  gm_model_free(tm.model);
}

/* The intermediate-axis flip: Π₂ changes sign every half period T of Π(t), T = 4K(k)/λ in
 * closed form (gm_free_rigid_body_period). Integrating exactly k closed-form periods with
 * h = T/N, the numerical Π misses Π(0) by about −δ Π'(0), δ the accumulated period error
 * (the lag of the numerical flips): δ = −(Π_h(kT) − Π(0))·Π'(0)/|Π'(0)|², to O(δ²), with no
 * interpolation between steps. The period error δ/k converges at the method's order. */
static double period_error(const gm_method *m, const test_model *tm, double period, size_t k,
                           size_t n_per_period) {
  const double *j = tm->problem->inertia, *pi = tm->y0 + 9;
  const double omega[3] = {pi[0] / j[0], pi[1] / j[4], pi[2] / j[8]};
  double dpi[3];
  gm_vec3_cross(pi, omega, dpi); /* Π' = Π × Ω */
  gm_integrator *it = test_integrator(m, tm->problem, tm->t0, tm->y0);
  cr_assert_eq(gm_integrator_run(it, k * n_per_period, period / (double)n_per_period), GM_OK);
  const double *y = gm_integrator_state(it);
  double miss = 0.0;
  for (int a = 0; a < 3; ++a) miss += (y[9 + a] - pi[a]) * dpi[a];
  gm_integrator_free(it);
  return -miss / gm_vec3_dot(dpi, dpi) / (double)k;
}

Test(rigid_body, dzhanibekov_flip_period) {
  test_model tm = test_model_make("rigid-body");
  const double inertia[3] = {tm.problem->inertia[0], tm.problem->inertia[4],
                             tm.problem->inertia[8]};
  const double period = gm_free_rigid_body_period(inertia, tm.y0 + 9);
  cr_assert(period > 40.0 && period < 70.0, "closed-form period %.6f", period);
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (!test_accepts(m, tm.problem)) continue;
    /* steps per period: errors well above round-off and in the asymptotic range */
    const size_t n = m->order <= 2 ? 2048 : m->order <= 4 ? 512 : 128;
    double e1 = period_error(m, &tm, period, 2, n), e2 = period_error(m, &tm, period, 2, 2 * n);
    double rate = log2(fabs(e1 / e2));
    cr_log_info("%s: period error %.2e at h = T/%zu, %.2e at h = T/%zu: order %.2f", m->name, e1,
                n, e2, 2 * n, rate);
    cr_expect(fabs(rate - m->order) <= 0.3, "%s: period error %.3e then %.3e: order %.2f",
              m->name, e1, e2, rate);
    cr_expect_leq(fabs(e2) / period, 1e-4, "%s: relative period error %.2e", m->name,
                  fabs(e2) / period);
  }
  gm_model_free(tm.model);
}

/* Lagrange top: the angular momentum about the vertical (rotations about e₃) and about the
 * symmetry axis (I₁ = I₂) are conserved. LGVI keeps both to round-off; the splitting the
 * vertical one (its rotations about body axes 1 and 2 separately do not commute with the
 * symmetry about axis 3, so Π₃ carries an O(h²) bounded error); RKMK and Crouch–Grossman keep
 * Π₃ (Π₃' = 0 identically for I₁ = I₂) but not the vertical component. 10⁵ steps. */
Test(rigid_body, heavy_top_conserved_components) {
  test_model tm = test_model_make("heavy-top");
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (!test_accepts(m, tm.problem)) continue;
    double y[12];
    tracker tr = run_tracked(m, &tm, cheap_row(m) ? 100000 : 10000, 0.01, 0, 100, y);
    cr_log_info("%s on heavy-top: L-vertical %.2e, L-axis %.2e, energy %.2e", m->name,
                tr.drift[0], tr.drift[1], fmax(tr.energy[0], tr.energy[1]));
    if (m->flags & GM_SYMPLECTIC)
      cr_expect_leq(tr.drift[0], 1e-12, "%s: L-vertical %.2e", m->name, tr.drift[0]);
    else
      cr_expect_geq(tr.drift[0], 1e-10, "%s: L-vertical %.2e", m->name, tr.drift[0]);
    const int body_axis_splitting = (m->flags & GM_EXPLICIT) && (m->flags & GM_SYMPLECTIC);
    cr_expect_leq(tr.drift[1], body_axis_splitting ? 1e-4 : 1e-12, "%s: L-axis %.2e", m->name,
                  tr.drift[1]);
  }
  gm_model_free(tm.model);
}
