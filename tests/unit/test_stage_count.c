/* Gauss and Lobatto IIIA–IIIB of any stage count (gm_method_gauss, gm_method_lobatto_iiia_iiib,
 * gm_method_create): the made row equals the table's where both exist, names and bad counts,
 * and the order beyond the table through Butcher's simplifying assumptions (Hairer, Nørsett &
 * Wanner I, Thm II.7.4: B(p), C(η), D(ζ) with p ≤ η + ζ + 1, p ≤ 2η + 2 give order p): Gauss
 * s satisfies B(2s), C(s), D(s), so its order is at least 2s (the defect of B(2s + 1), the Gauss
 * rule's error on x^2s, is 4e-27 for s = 9: below round-off, so "not more" is measured instead);
 * Lobatto IIIA s satisfies B(2s − 2), C(s) and not B(2s − 1), and the IIIB conjugate makes the
 * pair symplectic. The measured
 * orders are in tests/convergence/test_stage_count.c. */
#include "test_util.h"

static double b_defect(const gm_tableau *t, int k) {
  double s = 0.0;
  for (size_t i = 0; i < t->n_stages; ++i) s += t->b[i] * pow(t->c[i], k - 1);
  return fabs(s - 1.0 / k);
}

static double c_defect(const gm_tableau *t, int eta) {
  const size_t s = t->n_stages;
  double worst = 0.0;
  for (int k = 1; k <= eta; ++k)
    for (size_t i = 0; i < s; ++i) {
      double v = 0.0;
      for (size_t j = 0; j < s; ++j) v += t->a[i * s + j] * pow(t->c[j], k - 1);
      worst = fmax(worst, fabs(v - pow(t->c[i], k) / k));
    }
  return worst;
}

/* D(ζ): Σ_i b_i c_i^{k−1} a_ij = b_j (1 − c_j^k) / k, k ≤ ζ */
static double d_defect(const gm_tableau *t, int zeta) {
  const size_t s = t->n_stages;
  double worst = 0.0;
  for (int k = 1; k <= zeta; ++k)
    for (size_t j = 0; j < s; ++j) {
      double v = 0.0;
      for (size_t i = 0; i < s; ++i) v += t->b[i] * pow(t->c[i], k - 1) * t->a[i * s + j];
      worst = fmax(worst, fabs(v - t->b[j] * (1.0 - pow(t->c[j], k)) / k));
    }
  return worst;
}

Test(stage_count, made_rows_equal_the_table) {
  const char *names[] = {"gauss-1", "gauss-3", "gauss-8", "lobatto-iiia-iiib-2",
                         "lobatto-iiia-iiib-4"};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
    const gm_method *row = gm_method_find(names[i]);
    gm_method *m = NULL;
    gm_error err = {{0}};
    cr_assert_eq(gm_method_create(names[i], &m, &err), GM_OK, "%s", err.message);
    cr_expect_str_eq(m->name, row->name);
    cr_expect_eq(m->order, row->order, "%s", names[i]);
    cr_expect_eq(m->n_stages, row->n_stages);
    cr_expect_eq(m->flags, row->flags);
    cr_expect_eq(m->accepts, row->accepts);
    cr_expect_eq(m->family, row->family);
    gm_tableau *a = NULL, *b = NULL;
    cr_assert_eq(gm_method_tableau(row, &a), GM_OK);
    cr_assert_eq(gm_method_tableau(m, &b), GM_OK);
    const size_t s = row->n_stages;
    cr_expect_eq(memcmp(a->a, b->a, s * s * sizeof(double)), 0, "%s: A differs", names[i]);
    cr_expect_eq(memcmp(a->b, b->b, s * sizeof(double)), 0);
    gm_tableau_free(a);
    gm_tableau_free(b);
    gm_method_free(m);
  }
  gm_method_free(NULL);
}

Test(stage_count, names_and_bad_counts) {
  gm_method *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_method_create("gauss-12", &m, &err), GM_OK, "%s", err.message);
  cr_expect_str_eq(m->name, "gauss-12");
  cr_expect_eq(m->order, 24);
  cr_expect_eq(m->n_stages, 12);
  gm_method_free(m);
  cr_assert_eq(gm_method_lobatto_iiia_iiib(7, &m, &err), GM_OK);
  cr_expect_str_eq(m->name, "lobatto-iiia-iiib-7");
  cr_expect_eq(m->order, 12);
  gm_method_free(m);
  const struct {
    const char *name;
    gm_status st;
    const char *msg;
  } bad[] = {{"gauss-0", GM_EINVAL, "gauss-0: 0 stages; gauss-s is made for 1 <= s <= 64"},
             {"gauss-65", GM_EINVAL, "1 <= s <= 64"},
             {"lobatto-iiia-iiib-1", GM_EINVAL, "2 <= s <= 64"},
             {"gauss-", GM_ENOTFOUND, "is not gauss-S"},
             {"gauss-3x", GM_ENOTFOUND, "is not gauss-S"},
             {"radau-3", GM_ENOTFOUND, "is not gauss-S"}};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    memset(&err, 0, sizeof err);
    m = (gm_method *)1;
    cr_expect_eq(gm_method_create(bad[i].name, &m, &err), bad[i].st, "%s", bad[i].name);
    cr_expect_null(m, "%s", bad[i].name);
    cr_expect(strstr(err.message, bad[i].msg) != NULL, "%s: %s", bad[i].name, err.message);
  }
}

Test(stage_count, gauss_beyond_the_table_has_order_2s) {
  const size_t stages[] = {9, 10, 12, 16};
  for (size_t k = 0; k < sizeof stages / sizeof stages[0]; ++k) {
    const size_t s = stages[k];
    gm_method *m = NULL;
    gm_error err = {{0}};
    cr_assert_eq(gm_method_gauss(s, &m, &err), GM_OK, "%s", err.message);
    gm_tableau *t = NULL;
    cr_assert_eq(gm_method_tableau(m, &t), GM_OK);
    double worst_b = 0.0;
    for (int q = 1; q <= (int)(2 * s); ++q) worst_b = fmax(worst_b, b_defect(t, q));
    cr_expect_lt(worst_b, 1e-13, "gauss-%zu: B(2s) defect %.2e", s, worst_b);
    cr_expect_lt(c_defect(t, (int)s), 1e-13, "gauss-%zu: C(s) defect %.2e", s, c_defect(t, (int)s));
    cr_expect_lt(d_defect(t, (int)s), 1e-13, "gauss-%zu: D(s) defect %.2e", s, d_defect(t, (int)s));
    gm_tableau_free(t);
    gm_method_free(m);
  }
}

Test(stage_count, lobatto_beyond_the_table_has_order_2s_minus_2) {
  const size_t stages[] = {5, 6, 8};
  for (size_t k = 0; k < sizeof stages / sizeof stages[0]; ++k) {
    const size_t s = stages[k];
    gm_method *m = NULL;
    gm_error err = {{0}};
    cr_assert_eq(gm_method_lobatto_iiia_iiib(s, &m, &err), GM_OK, "%s", err.message);
    gm_tableau *t = NULL;
    cr_assert_eq(gm_method_tableau(m, &t), GM_OK);
    double worst_b = 0.0;
    for (int q = 1; q <= (int)(2 * s - 2); ++q) worst_b = fmax(worst_b, b_defect(t, q));
    cr_expect_lt(worst_b, 1e-13, "lobatto-%zu: B(2s-2) defect %.2e", s, worst_b);
    cr_expect_gt(b_defect(t, (int)(2 * s - 1)), 1e-12, "lobatto-%zu: B(2s-1) holds", s);
    cr_expect_lt(c_defect(t, (int)s), 1e-13, "lobatto-%zu: C(s)", s);
    /* b_i ā_ij + b_j a_ji − b_i b_j = 0: the pair is symplectic */
    double worst = 0.0;
    for (size_t i = 0; i < s; ++i)
      for (size_t j = 0; j < s; ++j)
        worst = fmax(worst, fabs(t->b[i] * t->a_bar[i * s + j] + t->b_bar[j] * t->a[j * s + i] -
                                 t->b[i] * t->b_bar[j]));
    cr_expect_lt(worst, 1e-14, "lobatto-%zu: symplecticity defect %.2e", s, worst);
    gm_tableau_free(t);
    gm_method_free(m);
  }
}
