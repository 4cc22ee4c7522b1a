/* The filter pairs (ψ, φ) of the trigonometric rows (issue 12), checked against the pairs as
 * the literature writes them (GNI, Hairer, Lubich & Wanner 2006, §XIII.2.2 (A)–(E)) and against
 * properties derived independently of any table:
 *  - consistency: ψ(0) = φ(0) = 1, both even (order 2 as h → 0 with hω fixed small);
 *  - symplecticity: the one-step form GNI XIII (2.7)–(2.8) with ψ0 = cos·ψ1, ψ1 = ψ/sinc is
 *    symplectic iff ψ = sinc·φ (GNI XIII.2); the rows' GM_SYMPLECTIC flag must say exactly that;
 *  - Gautschi's ψ = sinc²(ξ/2) (A, D) makes the two-step form exact for a constant slow force:
 *    x(t) = g/ω² + a cos ωt + b sin ωt gives x(t+h) − 2cos(hω)x(t) + x(t−h) = h² sinc²(hω/2) g;
 *  - García-Archilla et al.'s φ = sinc (C) is the average of the fast flow from q at rest over
 *    [−h, h]: (1/2h)∫ cos(sω) ds = sinc(hω) (the mollifier of their mollified impulse method);
 *  - a linear slow force −λx shifts the frequency: the two-step form gives
 *    cos θ = cos ξ − ½h²λ ψφ, the exact flow cos(h√(ω² + λ)) = cos ξ − ½h²λ sinc ξ + O(λ²), so
 *    ψφ − sinc measures the error of that shift. With ψ = sinc²(ξ/2) = 1 − ξ²/12 + …, a filter
 *    φ = sinc(ξ)(1 + a sin²(ξ/2)) = 1 + (a/4 − 1/6)ξ² + … gives ψφ − sinc = (a/4 − 1/12)ξ² + O(ξ⁴):
 *    a = ⅓ is the one value for which the shift is right to O(ξ⁴) — Hochbruck & Lubich's (D). */
#include "test_util.h"

#include "methods/internal.h"
#include "methods/oscillatory/oscillatory.h"

static double sinc(double x) { return x == 0.0 ? 1.0 : sin(x) / x; }

static const gm_osc_scheme *scheme_of(const char *name, const gm_method **m_out) {
  const gm_method *m = gm_method_find(name);
  cr_assert_not_null(m, "%s", name);
  cr_assert(m >= gm_oscillatory_methods && m < gm_oscillatory_methods + gm_n_oscillatory_methods);
  const gm_osc_scheme *s = &gm_oscillatory_schemes[m - gm_oscillatory_methods];
  cr_assert_eq(s->kind, GM_OSC_TRIG, "%s", name);
  if (m_out != NULL) *m_out = m;
  return s;
}

/* The pairs as GNI §XIII.2.2 writes them, typed here independently of oscillatory_table.c. */
static double ref_psi(int k, double x) {
  switch (k) {
    case 0: return sinc(0.5 * x) * sinc(0.5 * x); /* (A) Gautschi 1961 */
    case 1: return sinc(x);                       /* (B) Deuflhard 1979 */
    case 2: return sinc(x) * sinc(x);             /* (C) García-Archilla et al. 1999 */
    case 3: return sinc(0.5 * x) * sinc(0.5 * x); /* (D) Hochbruck & Lubich 1999 */
    default: return sinc(x) * sinc(x);            /* (E) Hairer & Lubich 2000 */
  }
}
static double ref_phi(int k, double x) {
  switch (k) {
    case 2: return sinc(x);
    case 3: return sinc(x) * (1.0 + sin(0.5 * x) * sin(0.5 * x) / 3.0);
    default: return 1.0;
  }
}

static const char *const rows[] = {"trig-gautschi", "trig-deuflhard", "trig-garcia-archilla",
                                   "trig-hochbruck-lubich", "trig-hairer-lubich"};
#define N_ROWS (sizeof rows / sizeof rows[0])

Test(oscillatory_filters, pairs_are_the_literature_pairs) {
  for (size_t k = 0; k < N_ROWS; ++k) {
    const gm_osc_scheme *s = scheme_of(rows[k], NULL);
    double worst = 0.0;
    for (int i = 0; i <= 4000; ++i) {
      const double x = 0.005 * i;
      worst = fmax(worst, fabs(s->psi(x) - ref_psi((int)k, x)));
      worst = fmax(worst, fabs(s->phi(x) - ref_phi((int)k, x)));
    }
    cr_expect_leq(worst, 4e-16, "%s: filters differ from GNI XIII.2.2 by %.2e", rows[k], worst);
  }
}

Test(oscillatory_filters, consistent_and_even) {
  for (size_t k = 0; k < N_ROWS; ++k) {
    const gm_osc_scheme *s = scheme_of(rows[k], NULL);
    cr_expect_float_eq(s->psi(0.0), 1.0, 1e-15, "%s: ψ(0) = %.17g", rows[k], s->psi(0.0));
    cr_expect_float_eq(s->phi(0.0), 1.0, 1e-15, "%s: φ(0) = %.17g", rows[k], s->phi(0.0));
    for (double x = 0.1; x < 20.0; x += 0.37) {
      cr_expect_eq(s->psi(-x), s->psi(x), "%s: ψ not even at %g", rows[k], x);
      cr_expect_eq(s->phi(-x), s->phi(x), "%s: φ not even at %g", rows[k], x);
    }
    /* 1 − ψ and 1 − φ are O(ξ²): order 2 for fixed ω as h → 0 */
    const double a = (1.0 - s->psi(1e-2)) / 1e-4, b = (1.0 - s->psi(5e-3)) / 2.5e-5;
    cr_expect_leq(fabs(a - b), 1e-3 * fmax(fabs(a), 1e-3), "%s: 1 − ψ not O(ξ²)", rows[k]);
  }
}

/* GM_SYMPLECTIC ⟺ ψ = sinc·φ (GNI XIII.2): (B) and (C) only. */
Test(oscillatory_filters, symplectic_flag_iff_psi_is_sinc_phi) {
  for (size_t k = 0; k < N_ROWS; ++k) {
    const gm_method *m;
    const gm_osc_scheme *s = scheme_of(rows[k], &m);
    double dev = 0.0;
    for (int i = 1; i <= 2000; ++i) {
      const double x = 0.01 * i;
      dev = fmax(dev, fabs(s->psi(x) - sinc(x) * s->phi(x)));
    }
    cr_log_info("%s: max |psi - sinc phi| = %.2e", rows[k], dev);
    if (m->flags & GM_SYMPLECTIC)
      cr_expect_leq(dev, 1e-15, "%s is flagged symplectic but ψ − sinc·φ = %.2e", rows[k], dev);
    else
      cr_expect_gt(dev, 1e-3, "%s satisfies ψ = sinc·φ but is not flagged symplectic", rows[k]);
  }
}

/* Gautschi's ψ (A, D): the two-step form is exact for a constant slow force. */
Test(oscillatory_filters, gautschi_psi_exact_for_constant_force) {
  const char *names[] = {"trig-gautschi", "trig-hochbruck-lubich"};
  for (size_t k = 0; k < 2; ++k) {
    const gm_osc_scheme *s = scheme_of(names[k], NULL);
    for (double x = 0.05; x < 30.0; x += 0.173) {
      const double exact = (2.0 - 2.0 * cos(x)) / (x * x); /* (x(t+h) − 2cos ξ x + x(t−h))/(h²g) */
      /* 2 − 2cos ξ cancels: its rounding is ~ε/ξ² */
      cr_expect_float_eq(s->psi(x), exact, 1e-15 + 4e-16 / (x * x),
                         "%s at ξ = %g: ψ = %.17g, exact %.17g",
                         names[k], x, s->psi(x), exact);
    }
  }
}

/* García-Archilla et al. (C): φ = the average of cos(sξ) over s ∈ [−1, 1] (composite Simpson). */
Test(oscillatory_filters, garcia_archilla_phi_is_the_average_of_the_fast_flow) {
  const gm_osc_scheme *s = scheme_of("trig-garcia-archilla", NULL);
  for (double x = 0.3; x < 25.0; x += 1.7) {
    const int n = 2000;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double u = -1.0 + 2.0 * i / n, w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      sum += w * cos(u * x);
    }
    const double avg = sum * (2.0 / n) / 3.0 / 2.0;
    cr_expect_float_eq(s->phi(x), avg, 1e-9, "ξ = %g: φ = %.12g, average %.12g", x, s->phi(x),
                       avg);
  }
}

/* (ψφ − sinc)(ξ) for the (D) form with a free constant a */
static double shift_error(double a, double x) {
  const double s2 = sin(0.5 * x) * sin(0.5 * x);
  return sinc(0.5 * x) * sinc(0.5 * x) * sinc(x) * (1.0 + a * s2) - sinc(x);
}

/* Hochbruck–Lubich (D): the constant ⅓ is the one that makes the frequency shift of a linear
 * slow force right to O(ξ⁴) — the table's φ halves its error ξ⁴-fashion (ratio 16 per halving of
 * ξ), a = ½ (say) only ξ²-fashion (ratio 4), and Gautschi's (A) also only to O(ξ²). */
Test(oscillatory_filters, hochbruck_lubich_third_from_the_frequency_shift) {
  const gm_osc_scheme *s = scheme_of("trig-hochbruck-lubich", NULL);
  const double x1 = 0.04, x2 = 0.02;
  const double d1 = s->psi(x1) * s->phi(x1) - sinc(x1), d2 = s->psi(x2) * s->phi(x2) - sinc(x2);
  cr_expect(fabs(d1 / d2 - 16.0) < 0.1, "(D): ratio %.4f, expected 16 (O(ξ⁴))", d1 / d2);
  cr_expect(fabs(d1 - shift_error(1.0 / 3.0, x1)) < 1e-6 * fabs(d1), "%.3e vs %.3e", d1,
            shift_error(1.0 / 3.0, x1));
  const double r_half = shift_error(0.5, x1) / shift_error(0.5, x2);
  cr_expect(fabs(r_half - 4.0) < 0.01, "a = 1/2: ratio %.4f, expected 4 (O(ξ²))", r_half);
  const gm_osc_scheme *g = scheme_of("trig-gautschi", NULL);
  const double r_a =
      (g->psi(x1) * g->phi(x1) - sinc(x1)) / (g->psi(x2) * g->phi(x2) - sinc(x2));
  cr_expect(fabs(r_a - 4.0) < 0.01, "(A): ratio %.4f, expected 4", r_a);
  /* and Deuflhard's (B) has ψφ = sinc exactly */
  const gm_osc_scheme *b = scheme_of("trig-deuflhard", NULL);
  for (double x = 0.1; x < 20.0; x += 0.7)
    cr_expect_float_eq(b->psi(x) * b->phi(x), sinc(x), 1e-16, "(B) at %g", x);
}
