/* Symplecticity: the Jacobian J of one step satisfies Jᵀ Ω J = Ω, Ω = [[0, I], [−I, 0]].
 * J comes from fourth-order central differences (step 1e-4: truncation and round-off both
 * near 1e-12). The base point is moved off the initial state, where explicit Euler happens to
 * be area-preserving for the pendulum (cos q = 0). Every row
 * flagged symplectic is checked on every Hamiltonian library problem it accepts; the
 * non-symplectic rows must fail the same check, so the check can fail.
 * States on a manifold (rigid bodies on T*SO(3)) are differentiated in the problem's canonical
 * chart (gm_problem_to_chart: exponential coordinates ξ with their conjugate momenta): the
 * step maps z ↦ chart_{Φ(y)}(Φ(chart_y⁻¹(z))). For Rⁿ the chart is y − base and this is the
 * plain Jacobian. */
#include "test_util.h"

#define MAX_N 24

static void one_step(const gm_method *m, const gm_problem *pb, const double *y, double h,
                     double *out) {
  gm_integrator *it = test_integrator(m, pb, 0.0, y);
  cr_assert_eq(gm_integrator_step(it, h), GM_OK, "%s", gm_integrator_errmsg(it));
  memcpy(out, gm_integrator_state(it), gm_integrator_state_size(it) * sizeof *out);
  gm_integrator_free(it);
}

/* chart coordinates (around base_out) of one step from the point z (around base_in) */
static void one_step_in_chart(const gm_method *m, const gm_problem *pb, const double *base_in,
                              const double *base_out, const double *z, double h, double *out) {
  double y[MAX_N], y1[MAX_N];
  cr_assert_eq(gm_problem_from_chart(pb, base_in, z, y), GM_OK);
  one_step(m, pb, y, h, y1);
  cr_assert_eq(gm_problem_to_chart(pb, base_out, y1, out), GM_OK);
}

/* max |Jᵀ Ω J − Ω| for one step of size h from y */
static double symplecticity_defect(const gm_method *m, const gm_problem *pb, const double *y0,
                                   double h) {
  const size_t n = gm_problem_chart_dim(pb), d = n / 2;
  double jac[MAX_N][MAX_N], z[MAX_N], y1[MAX_N], fp1[MAX_N], fp2[MAX_N], fm1[MAX_N], fm2[MAX_N];
  const double delta = 1e-4;
  cr_assert_leq(gm_problem_state_size(pb), MAX_N);
  one_step(m, pb, y0, h, y1); /* the output chart is centred at the step's image of y0 */
  for (size_t j = 0; j < n; ++j) {
    memset(z, 0, n * sizeof *z);
    z[j] = delta;
    one_step_in_chart(m, pb, y0, y1, z, h, fp1);
    z[j] = 2 * delta;
    one_step_in_chart(m, pb, y0, y1, z, h, fp2);
    z[j] = -delta;
    one_step_in_chart(m, pb, y0, y1, z, h, fm1);
    z[j] = -2 * delta;
    one_step_in_chart(m, pb, y0, y1, z, h, fm2);
    for (size_t i = 0; i < n; ++i)
      jac[i][j] = (-fp2[i] + 8 * fp1[i] - 8 * fm1[i] + fm2[i]) / (12 * delta);
  }
  double defect = 0.0;
  for (size_t a = 0; a < n; ++a)
    for (size_t b = 0; b < n; ++b) {
      /* (Jᵀ Ω J)_ab = Σ_i J_ia (Ω J)_ib with (Ω J)_ib = J_{i+d,b} (i < d), −J_{i−d,b} (i ≥ d) */
      double s = 0.0;
      for (size_t i = 0; i < n; ++i) s += jac[i][a] * (i < d ? jac[i + d][b] : -jac[i - d][b]);
      double omega = (a < d && b == a + d) ? 1.0 : (a >= d && b + d == a ? -1.0 : 0.0);
      defect = fmax(defect, fabs(s - omega));
    }
  return defect;
}

/* only_flagged: assert only the rows flagged symplectic (for one degree of freedom, where some
 * rows that are not symplectic in general preserve area, e.g. trig-gautschi = vti-scalar with
 * Φ = 1) */
static void check_model(const char *name, test_model tm, double h, int only_flagged) {
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (!test_accepts(m, tm.problem)) continue;
    if (only_flagged && !(m->flags & GM_SYMPLECTIC)) continue;
    double y[MAX_N], z[MAX_N];
    for (size_t k = 0; k < gm_problem_chart_dim(tm.problem); ++k) z[k] = 0.05 * (double)(k + 1);
    cr_assert_eq(gm_problem_from_chart(tm.problem, tm.y0, z, y), GM_OK);
    double defect = symplecticity_defect(m, tm.problem, y, h);
    cr_log_info("%s on %s: |J^T Omega J - Omega| = %.2e", m->name, name, defect);
    if (m->flags & GM_SYMPLECTIC)
      cr_expect_leq(defect, 1e-10, "%s on %s: |JᵀΩJ − Ω| = %.2e", m->name, name, defect);
    else if (m->order < 6) /* a method of order r is symplectic up to O(h^{r+1}): for r ≥ 6
                              (mimetic-galerkin-p, p ≥ 3) that is below detection here */
      cr_expect_gt(defect, 1e-8, "%s on %s is not symplectic, yet |JᵀΩJ − Ω| = %.2e", m->name,
                   name, defect);
  }
  gm_model_free(tm.model);
}

static void check_problem(const char *name, double h) {
  check_model(name, test_model_make(name), h, 0);
}

Test(symplectic, kepler) { check_problem("kepler", 0.1); }
Test(symplectic, henon_heiles) { check_problem("henon-heiles", 0.2); }
Test(symplectic, pendulum) { check_problem("pendulum", 0.5); }
/* rigid bodies in the canonical chart of T*SO(3) (× T*R³) */
Test(symplectic, rigid_body) { check_problem("rigid-body", 0.2); }
Test(symplectic, heavy_top) { check_problem("heavy-top", 0.1); }
Test(symplectic, central_body) { check_problem("central-body", 0.1); }
/* split potentials (issue 12): every row on them, the oscillatory rows included */
Test(symplectic, diatomic_chain) { check_problem("diatomic-chain", 0.05); }
Test(symplectic, fpu) { check_model("fpu", test_model_with("fpu", "omega", 10.0), 0.1, 0); }
Test(symplectic, stiff_spring_pendulum) {
  check_model("stiff-spring-pendulum", test_model_with("stiff-spring-pendulum", "k", 400.0), 0.05,
              0);
}
Test(symplectic, toy_resonance_quartic) {
  check_model("toy-resonance", test_model_with("toy-resonance", "quartic", 1.0), 0.2, 1);
}
