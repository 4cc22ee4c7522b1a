/* The error of the near-integrable rows follows ε h^{2n} + ε² h² (Laskar & Robutel 2001), and
 * the symplectic correctors remove WH's ε h² term, on Sun–Jupiter–Saturn (outer-solar-system
 * planets=2) and on the outer solar system. ε is the planets' mass factor (epsilon = 1: the real
 * masses). The error is the max-norm of the positions at t_end = 20 000 days against
 * sofroniou-spaletta-10 with compensated summation at 10 days, relative to the largest
 * position. Exponents are least-squares slopes:
 *  - in h where one term dominates: ε h^{2n} for wh, saba-2, sbab-2 and wh-c3 at ε = 1e-3 and
 *    h = 240 .. 63 days (the ε h^6 and ε h^8 terms of n = 3, 4 are below round-off there, or
 *    at steps where the expansion does not hold yet); ε² h² for every other row at ε = 1 and
 *    h = 50 .. 20 days;
 *  - in ε from ε = 1e-2 → 1e-3 (wh), 1e-3 → 1e-4 (n = 2, wh-c3: the ε h^4 regime) and 1 → 0.1
 *    (the ε² h² regime);
 *  - the ε h^6 of n = 3 and the ε-linear term of n = 3, 4 in the energy error (below). */
#include <stdio.h>

#include "test_util.h"

#define T_END 20000.0

typedef struct {
  gm_model *model;
  const gm_problem *pb;
  double y0[64], ref[64];
  size_t n;
} system_t;

static void integrate(const char *method, const gm_problem *pb, const double *y0, size_t n,
                      double h, int compensated, double *out) {
  gm_scheme sc = {gm_method_find(method), NULL, GM_SOLVER_DEFAULT, compensated};
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_integrator_create_scheme(&sc, pb, &it, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_integrator_set_state(it, 0.0, y0), GM_OK);
  cr_assert_eq(gm_integrator_integrate(it, T_END, h), GM_OK, "%s", gm_integrator_errmsg(it));
  memcpy(out, gm_integrator_state(it), n * sizeof *out);
  gm_integrator_free(it);
}

static system_t make(int planets, double epsilon) {
  system_t s;
  cr_assert_eq(gm_model_create("outer-solar-system", &s.model), GM_OK);
  cr_assert_eq(gm_model_set(s.model, "planets", planets), GM_OK);
  cr_assert_eq(gm_model_set(s.model, "epsilon", epsilon), GM_OK);
  cr_assert_eq(gm_model_build(s.model), GM_OK);
  s.pb = gm_model_problem(s.model);
  s.n = gm_model_state_size(s.model);
  gm_model_initial_state(s.model, NULL, s.y0);
  integrate("sofroniou-spaletta-10", s.pb, s.y0, s.n, 10.0, 1, s.ref);
  return s;
}

static double error(const system_t *s, const char *method, double h) {
  double y[64], e = 0, scale = 0;
  integrate(method, s->pb, s->y0, s->n, h, 1, y);
  for (size_t i = 0; i < s->n / 2; ++i) {
    e = fmax(e, fabs(y[i] - s->ref[i]));
    scale = fmax(scale, fabs(s->ref[i]));
  }
  return e / scale;
}

/* The largest relative energy error over 200 000 days, the energy checked after every step.
 * The energy error has no phase drift to carry the ε h^{2n} term of the modified Hamiltonian
 * through a resonance of the step with the orbits, and its round-off floor is ~1.5e-15. */
static double energy_error(const system_t *s, const char *method, double h) {
  gm_scheme sc = {gm_method_find(method), NULL, GM_SOLVER_DEFAULT, 1};
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_integrator_create_scheme(&sc, s->pb, &it, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_integrator_set_state(it, 0.0, s->y0), GM_OK);
  const double H0 = gm_problem_energy(s->pb, s->y0);
  double worst = 0;
  for (size_t k = 0, n = (size_t)ceil(200000.0 / h); k < n; ++k) {
    cr_assert_eq(gm_integrator_step(it, h), GM_OK, "%s", gm_integrator_errmsg(it));
    worst = fmax(worst, fabs(gm_problem_energy(s->pb, gm_integrator_state(it)) - H0));
  }
  gm_integrator_free(it);
  return worst / fabs(H0);
}

/* slope of log error against log h over h0, h0/r, ..., n levels */
static double h_slope(const system_t *s, const char *method, double h0, double r, int n) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, h = h0;
  for (int k = 0; k < n; ++k, h /= r) {
    double x = log(h), y = log(error(s, method, h));
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

static void check_planets(int planets) {
  system_t e0 = make(planets, 1.0), e1 = make(planets, 0.1), e2 = make(planets, 1e-2),
           e3 = make(planets, 1e-3), e4 = make(planets, 1e-4);
  /* WH: ε h² */
  double wh_h = h_slope(&e3, "wh", 240, 1.25, 7);
  double wh_eps = log10(error(&e2, "wh", 98.3) / error(&e3, "wh", 98.3));
  printf("planets=%d wh: error ~ h^%.2f (eps = 1e-3), eps^%.2f\n", planets, wh_h, wh_eps);
  cr_expect(fabs(wh_h - 2) <= 0.15, "planets=%d wh: h^%.2f", planets, wh_h);
  cr_expect(fabs(wh_eps - 1) <= 0.1, "planets=%d wh: eps^%.2f", planets, wh_eps);
  /* ε h^4 */
  const char *fourth[] = {"saba-2-jacobi", "sbab-2-jacobi", "wh-c3"};
  for (size_t k = 0; k < 3; ++k) {
    double p = h_slope(&e3, fourth[k], 240, 1.25, 7);
    double q = log10(error(&e3, fourth[k], 154) / error(&e4, fourth[k], 154));
    printf("planets=%d %s: error ~ h^%.2f (eps = 1e-3, h = 240..63), eps^%.2f\n", planets,
           fourth[k], p, q);
    cr_expect(fabs(p - 4) <= 0.5, "planets=%d %s: h^%.2f", planets, fourth[k], p);
    cr_expect(fabs(q - 1) <= 0.2, "planets=%d %s: eps^%.2f", planets, fourth[k], q);
  }
  /* ε² h² */
  const char *second[] = {"saba-2-jacobi", "saba-3-jacobi", "saba-4-jacobi", "sbab-2-jacobi",
                          "sbab-3-jacobi", "sbab-4-jacobi", "wh-c3",         "wh-c5",
                          "wh-c7",         "wh-c11",        "wh-c17"};
  double wh_small = error(&e1, "wh", 20.48);
  for (size_t k = 0; k < sizeof second / sizeof second[0]; ++k) {
    double p = h_slope(&e0, second[k], 50, 1.25, 5);
    double small = error(&e1, second[k], 20.48);
    double q = log10(error(&e0, second[k], 20.48) / small);
    printf("planets=%d %s: error ~ h^%.2f (eps = 1, h = 50..20), eps^%.2f (1 -> 0.1); wh / "
           "this at eps = 0.1, h = 20.5: %.0f\n",
           planets, second[k], p, q, wh_small / small);
    cr_expect(fabs(p - 2) <= 0.15, "planets=%d %s: h^%.2f", planets, second[k], p);
    cr_expect(fabs(q - 2) <= 0.15, "planets=%d %s: eps^%.2f", planets, second[k], q);
    if (strncmp(second[k], "wh-c", 4) == 0) /* the corrector removed WH's ε h² term */
      cr_expect_geq(wh_small / small, 30, "planets=%d %s: only %.1f times better than wh",
                    planets, second[k], wh_small / small);
  }
  /* SABAC_n (Laskar & Robutel's corrector kick of the ε² h² term): at ε = 1, where SABA_n is
   * ε² h², SABAC_2 is h^4 (its ε h^4 and ε² h^4 terms) over h = 80 .. 33 days, and every
   * SABAC_n with n ≥ 2 is at least 100 times more accurate than SABA_n at 20.48 days */
  {
    double p = h_slope(&e0, "sabac-2-jacobi", 80, 1.25, 5);
    printf("planets=%d sabac-2-jacobi: error ~ h^%.2f (eps = 1, h = 80..33)\n", planets, p);
    cr_expect(fabs(p - 4) <= 0.3, "planets=%d sabac-2-jacobi: h^%.2f", planets, p);
    const char *saba[] = {"saba-2-jacobi", "saba-3-jacobi", "saba-4-jacobi"};
    const char *sabac[] = {"sabac-2-jacobi", "sabac-3-jacobi", "sabac-4-jacobi"};
    /* measured gains (2 and 5 planets): sabac-2 1380 and 1233; sabac-3 37488 and 37642,
     * sabac-4 32644 and 53034, whose errors (8e-15 .. 8e-16) are at round-off: the floor */
    const double min_gain[3] = {800, 2e4, 2e4};
    for (size_t k = 0; k < 3; ++k) {
      double a = error(&e0, saba[k], 20.48), b = error(&e0, sabac[k], 20.48);
      printf("planets=%d %s: error %.2e at h = 20.48, eps = 1 (%s: %.2e, %.0f times more)\n",
             planets, sabac[k], b, saba[k], a, a / b);
      cr_expect_geq(a / b, min_gain[k], "planets=%d %s: only %.1f times better than %s", planets,
                    sabac[k], a / b, saba[k]);
    }
  }
  /* Blanes et al.'s (10,4), (8,6,4), (10,6,4): their ε² terms are h^4 and h^6, so at ε = 1
   * they are 1e4-1e6 times below saba-4 at 100 days, at a few times its cost per step; their
   * exponents sit too close to round-off here to be fitted (docs/celestial.md) */
  const char *blanes[] = {"aba-10-4", "aba-8-6-4", "aba-10-6-4"};
  const double saba4 = error(&e0, "saba-4-jacobi", 102.4);
  /* measured saba-4 / row (2 and 5 planets): aba-10-4 3.5e4 and 3.7e4, aba-8-6-4 4.5e5 and
   * 4.6e5, aba-10-6-4 8.1e5 and 6.5e5; bounds ~0.55x the smaller */
  const double min_gain[3] = {2e4, 2.5e5, 3.5e5};
  for (size_t k = 0; k < 3; ++k) {
    double e = error(&e0, blanes[k], 102.4);
    printf("planets=%d %s: error %.2e at h = 102.4, eps = 1 (saba-4-jacobi: %.2e)\n", planets,
           blanes[k], e, saba4);
    cr_expect_leq(e, saba4 / min_gain[k], "planets=%d %s: %.3g against saba-4 %.3g", planets,
                  blanes[k], e, saba4);
  }
  /* The ε h^{2n} terms of n = 3, 4, in the energy error (Laskar & Robutel 2001, Figs 3-4 plot
   * the same measure): at ε = 1e-3 the ε² h² term is far below them. n = 3: slope over
   * h = 256 .. 131 days, measured 6.35 / 6.18 (saba-3, 2 / 5 planets) and 6.37 / 6.46 (sbab-3);
   * at larger steps the slope wanders (8.9, 6.1, 9.4 between 500 and 256 days: resonances of
   * the step with Jupiter's 4332-day orbit), at smaller ones the error reaches the floor.
   * ε exponent 1e-2 -> 1e-3 (n = 3 at h = 205, n = 4 at h = 400), measured saba-3 0.97 / 0.97,
   * sbab-3 1.03 / 1.02, saba-4 1.00 / 1.00, sbab-4 1.01 / 1.00: the term is linear in ε. The
   * h^8 of n = 4 is not fitted: above the floor (h >= 300 days) its slope is the resonances'
   * (10.7 over 500 .. 257 days, the error at 455 days three times that at 500). */
  const char *third[] = {"saba-3-jacobi", "sbab-3-jacobi"};
  for (size_t k = 0; k < 2; ++k) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0, h = 256;
    for (int i = 0; i < 4; ++i, h /= 1.25) {
      double x = log(h), y = log(energy_error(&e3, third[k], h));
      sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    double p = (4 * sxy - sx * sy) / (4 * sxx - sx * sx);
    printf("planets=%d %s: energy error ~ h^%.2f (eps = 1e-3, h = 256..131)\n", planets, third[k], p);
    cr_expect(fabs(p - 6) <= 0.7, "planets=%d %s: h^%.2f", planets, third[k], p);
  }
  const char *high[] = {"saba-3-jacobi", "sbab-3-jacobi", "saba-4-jacobi", "sbab-4-jacobi"};
  for (size_t k = 0; k < 4; ++k) {
    const double h = k < 2 ? 205 : 400;
    double q = log10(energy_error(&e2, high[k], h) / energy_error(&e3, high[k], h));
    printf("planets=%d %s: energy error ~ eps^%.3f (1e-2 -> 1e-3, h = %.0f)\n", planets, high[k],
           q, h);
    cr_expect(fabs(q - 1) <= 0.08, "planets=%d %s: eps^%.3f", planets, high[k], q);
  }
  system_t *all[] = {&e0, &e1, &e2, &e3, &e4};
  for (size_t k = 0; k < 5; ++k) gm_model_free(all[k]->model);
}

Test(celestial_scaling, sun_jupiter_saturn, .timeout = 300) { check_planets(2); }
Test(celestial_scaling, outer_solar_system, .timeout = 300) { check_planets(5); }
