/* The method registry: unique names, lookup, and the conditions every row's coefficients must
 * satisfy (checked for every row, so a new row is checked when it is added): consistency,
 * the declared order through Butcher's simplifying assumptions for Runge–Kutta rows, the
 * symplecticity conditions, and flags that agree with the coefficients. */
#include "test_util.h"

Test(methods, names_unique_and_found) {
  size_t n = gm_method_count();
  cr_assert_geq(n, 7);
  for (size_t i = 0; i < n; ++i) {
    const gm_method *m = gm_method_at(i);
    cr_expect_eq(gm_method_find(m->name), m, "%s", m->name);
    cr_expect(m->reference != NULL && strlen(m->reference) > 10, "%s cites no source", m->name);
    cr_expect(m->order >= 1 && m->n_stages >= 1, "%s", m->name);
    for (const char *c = m->name; *c; ++c)
      cr_expect((*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || *c == '-', "%s", m->name);
    for (size_t j = i + 1; j < n; ++j) cr_expect_str_neq(m->name, gm_method_at(j)->name);
  }
  cr_expect_null(gm_method_at(n));
  cr_expect_null(gm_method_find("no-such-method"));
  cr_expect_null(gm_method_find(NULL));
  const char *required[] = {"euler", "rk4", "symplectic-euler-a", "symplectic-euler-b",
                            "verlet", "verlet-position", "midpoint"};
  for (size_t i = 0; i < sizeof required / sizeof required[0]; ++i)
    cr_expect_not_null(gm_method_find(required[i]), "%s", required[i]);
}

static double sum(const double *v, size_t n) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += v[i];
  return s;
}

static gm_tableau *tableau_of(const gm_method *m) {
  gm_tableau *t = NULL;
  cr_assert_eq(gm_method_tableau(m, &t), GM_OK, "%s", m->name);
  return t;
}

/* B(p): Σ b_i c_i^{k−1} = 1/k for k ≤ p, and C(η): Σ_j a_ij c_j^{k−1} = c_i^k / k for k ≤ η.
 * With D(ζ), B(p), C(η), p ≤ min(η + ζ + 1, 2η + 2) gives order p (Butcher 1964; HNW I,
 * Thm II.7.4). For collocation methods C(s) holds, and B(2s) (Gauss) or B(2s−2) (Lobatto)
 * gives the order; for explicit rows we check B(order) and C(1). */
static double b_defect(const gm_tableau *t, int p) {
  double worst = 0.0;
  for (int k = 1; k <= p; ++k) {
    double s = 0.0;
    for (size_t i = 0; i < t->n_stages; ++i) s += t->b[i] * pow(t->c[i], k - 1);
    worst = fmax(worst, fabs(s - 1.0 / k));
  }
  return worst;
}

static double c_defect(const gm_tableau *t, const double *a, int eta) {
  const size_t s = t->n_stages;
  double worst = 0.0;
  for (int k = 1; k <= eta; ++k)
    for (size_t i = 0; i < s; ++i) {
      double v = 0.0;
      for (size_t j = 0; j < s; ++j) v += a[i * s + j] * pow(t->c[j], k - 1);
      worst = fmax(worst, fabs(v - pow(t->c[i], k) / k));
    }
  return worst;
}

/* b_i ā_ij + b̄_j a_ji − b_i b̄_j = 0 (GNI (2006), Thm VI.4.3 and VI.4.6). */
static double symplectic_defect(const gm_tableau *t, const double *a, const double *b,
                                const double *a_bar, const double *b_bar) {
  const size_t s = t->n_stages;
  double worst = 0.0;
  for (size_t i = 0; i < s; ++i)
    for (size_t j = 0; j < s; ++j)
      worst = fmax(worst, fabs(b[i] * a_bar[i * s + j] + b_bar[j] * a[j * s + i] - b[i] * b_bar[j]));
  return worst;
}

Test(methods, runge_kutta_rows) {
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (m->family != GM_FAMILY_EXPLICIT_RK && m->family != GM_FAMILY_IMPLICIT_RK &&
        m->family != GM_FAMILY_PARTITIONED_RK)
      continue;
    gm_tableau *t = tableau_of(m);
    const size_t s = t->n_stages;
    const int collocation = m->compute != NULL;
    const int eta = collocation ? (int)s : 1;
    /* tolerances: round-off of coefficients computed from nodes, growing with the powers */
    cr_expect_leq(b_defect(t, m->order), 1e-13, "%s: B(%d) defect %.2e", m->name, m->order,
                  b_defect(t, m->order));
    cr_expect_leq(c_defect(t, t->a, eta), 1e-13, "%s: C(%d) defect %.2e", m->name, eta,
                  c_defect(t, t->a, eta));
    if (collocation && m->family == GM_FAMILY_IMPLICIT_RK) /* Gauss: B(2s) exactly */
      cr_expect_eq(m->order, 2 * (int)s, "%s", m->name);
    if (m->family == GM_FAMILY_EXPLICIT_RK)
      for (size_t r = 0; r < s; ++r)
        for (size_t j = r; j < s; ++j) cr_expect_eq(t->a[r * s + j], 0.0, "%s explicit", m->name);
    if (m->flags & GM_SYMPLECTIC) {
      const double *a_bar = m->family == GM_FAMILY_PARTITIONED_RK ? t->a_bar : t->a;
      const double *b_bar = m->family == GM_FAMILY_PARTITIONED_RK ? t->b_bar : t->b;
      double defect = symplectic_defect(t, t->a, t->b, a_bar, b_bar);
      cr_expect_leq(defect, 1e-14, "%s: symplecticity condition defect %.2e", m->name, defect);
    }
    cr_expect_eq((m->flags & GM_EXPLICIT) != 0, m->family == GM_FAMILY_EXPLICIT_RK, "%s",
                 m->name);
    gm_tableau_free(t);
  }
}

/* A sequence of operations is symmetric when it is a palindrome. */
static int palindrome(const double *ops, size_t k) {
  size_t lo = 0, hi = k;
  while (lo < hi && ops[lo] == 0.0) ++lo;
  while (hi > lo && ops[hi - 1] == 0.0) --hi;
  for (size_t i = lo, j = hi ? hi - 1 : 0; i < j; ++i, --j)
    if (fabs(ops[i] - ops[j]) > 1e-15) return 0;
  return 1;
}

Test(methods, splitting_rows) {
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (m->family != GM_FAMILY_SPLITTING) continue;
    gm_tableau *t = tableau_of(m);
    const size_t s = t->n_stages;
    cr_expect(fabs(sum(t->a, s) - 1.0) < 1e-14, "%s: sum a = %.17g", m->name, sum(t->a, s));
    cr_expect(fabs(sum(t->b, s) - 1.0) < 1e-14, "%s: sum b = %.17g", m->name, sum(t->b, s));
    cr_expect(m->flags & GM_SYMPLECTIC, "%s: splittings of Hamiltonian flows are symplectic",
              m->name);
    double ops[256];
    cr_assert_leq(2 * s, 256);
    for (size_t k = 0; k < s; ++k) {
      ops[2 * k] = t->a[k];
      ops[2 * k + 1] = -t->b[k]; /* the sign tells kicks from drifts */
    }
    cr_expect_eq((m->flags & GM_SYMMETRIC) != 0, palindrome(ops, 2 * s), "%s symmetry flag",
                 m->name);
    int fsal = t->a[0] == 0.0 && t->b[s - 1] != 0.0;
    cr_expect_eq((m->flags & GM_FSAL) != 0, fsal, "%s FSAL flag", m->name);
    gm_tableau_free(t);
  }
}

/* Compositions: Σγ = 1; symmetric when γ is a palindrome; order 4 needs Σγ³ = 0 and order 6
 * also Σγ⁵ = 0 for symmetric compositions (GNI (2006), §V.3.2, eq. (3.5)–(3.6)). */
Test(methods, composition_rows) {
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (m->family != GM_FAMILY_COMPOSITION) continue;
    gm_tableau *t = tableau_of(m);
    const size_t s = t->n_stages;
    double s1 = 0, s3 = 0, s5 = 0, scale = 0;
    for (size_t k = 0; k < s; ++k) {
      double g = t->gamma[k];
      s1 += g;
      s3 += g * g * g;
      s5 += g * g * g * g * g;
      scale = fmax(scale, fabs(g));
    }
    cr_expect(fabs(s1 - 1.0) < 1e-14, "%s: sum gamma = %.17g", m->name, s1);
    cr_expect_eq((m->flags & GM_SYMMETRIC) != 0, palindrome(t->gamma, s), "%s", m->name);
    if (m->order >= 4) cr_expect(fabs(s3) < 1e-13 * pow(scale, 3), "%s: sum γ³ = %.2e", m->name, s3);
    if (m->order >= 6 && (m->flags & GM_SYMMETRIC))
      cr_expect(fabs(s5) < 1e-12 * pow(scale, 5), "%s: sum γ⁵ = %.2e", m->name, s5);
    cr_expect_not_null(gm_method_find(m->basic), "%s: default basic method", m->name);
    gm_tableau_free(t);
  }
}

Test(methods, names_of_families_and_flags) {
  cr_expect_str_eq(gm_method_family_name(GM_FAMILY_SPLITTING), "splitting");
  cr_expect_str_eq(gm_method_family_name(GM_FAMILY_COMPOSITION), "composition");
  cr_expect_str_eq(gm_method_flag_name(0), "symplectic");
  cr_expect_null(gm_method_flag_name(GM_N_METHOD_FLAGS));
  gm_solver s;
  cr_expect_eq(gm_solver_find("fixed-point", &s), GM_OK);
  cr_expect_eq(s, GM_SOLVER_FIXED_POINT);
  cr_expect_str_eq(gm_solver_name(GM_SOLVER_SIMPLIFIED_NEWTON), "simplified-newton");
  cr_expect_eq(gm_solver_find("bisection", &s), GM_ENOTFOUND);
}
