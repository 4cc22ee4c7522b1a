/* The method registry: unique names, lookup, and the consistency conditions of every row's
 * coefficients (checked for every row, so a new row is checked when it is added). */
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

Test(methods, runge_kutta_rows_consistent) {
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (m->family != GM_FAMILY_EXPLICIT_RK && m->family != GM_FAMILY_IMPLICIT_RK) continue;
    const size_t s = m->n_stages;
    cr_expect(fabs(sum(m->b, s) - 1.0) < 1e-15, "%s: sum b = %.17g", m->name, sum(m->b, s));
    for (size_t r = 0; r < s; ++r) {
      cr_expect(fabs(sum(m->a + r * s, s) - m->c[r]) < 1e-15, "%s: row %zu sum != c", m->name, r);
      if (m->family == GM_FAMILY_EXPLICIT_RK)
        for (size_t j = r; j < s; ++j) cr_expect_eq(m->a[r * s + j], 0.0, "%s explicit", m->name);
    }
    /* order >= 2 needs Σ b_i c_i = 1/2 */
    if (m->order >= 2) {
      double bc = 0.0;
      for (size_t r = 0; r < s; ++r) bc += m->b[r] * m->c[r];
      cr_expect(fabs(bc - 0.5) < 1e-15, "%s: sum b c = %.17g", m->name, bc);
    }
    cr_expect_eq((m->flags & GM_EXPLICIT) != 0, m->family == GM_FAMILY_EXPLICIT_RK, "%s", m->name);
  }
}

/* A splitting step is symmetric when its sequence of drifts and kicks is a palindrome. */
static int splitting_palindrome(const gm_method *m) {
  double ops[64];
  size_t k = 0;
  for (size_t i = 0; i < m->n_stages; ++i) {
    ops[k++] = m->a[i];
    ops[k++] = -m->b[i]; /* sign tells kicks from drifts */
  }
  /* drop leading and trailing zeros, then merge is unnecessary for these forms */
  size_t lo = 0, hi = k;
  while (lo < hi && ops[lo] == 0.0) ++lo;
  while (hi > lo && ops[hi - 1] == 0.0) --hi;
  for (size_t i = lo, j = hi - 1; i < j; ++i, --j)
    if (fabs(ops[i] - ops[j]) > 1e-15) return 0;
  return 1;
}

Test(methods, splitting_rows_consistent) {
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (m->family != GM_FAMILY_SPLITTING) continue;
    const size_t s = m->n_stages;
    cr_expect(fabs(sum(m->a, s) - 1.0) < 1e-14, "%s: sum a = %.17g", m->name, sum(m->a, s));
    cr_expect(fabs(sum(m->b, s) - 1.0) < 1e-14, "%s: sum b = %.17g", m->name, sum(m->b, s));
    cr_expect(m->flags & GM_SYMPLECTIC, "%s: splittings of Hamiltonian flows are symplectic",
              m->name);
    cr_expect_eq((m->flags & GM_SYMMETRIC) != 0, splitting_palindrome(m), "%s symmetry flag",
                 m->name);
    int fsal = m->a[0] == 0.0 && m->b[s - 1] != 0.0;
    cr_expect_eq((m->flags & GM_FSAL) != 0, fsal, "%s FSAL flag", m->name);
  }
}

Test(methods, names_of_families_and_flags) {
  cr_expect_str_eq(gm_method_family_name(GM_FAMILY_SPLITTING), "splitting");
  cr_expect_str_eq(gm_method_flag_name(0), "symplectic");
  cr_expect_null(gm_method_flag_name(GM_N_METHOD_FLAGS));
}
