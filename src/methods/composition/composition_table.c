/* Composition methods: Φ_{γ_s h} ∘ … ∘ Φ_{γ_1 h} of a symmetric second-order basic method Φ
 * (by default position Verlet, drift–kick–drift: chosen by measurement, see below). All rows are symmetric compositions (γ a palindrome, Σγ = 1);
 * .order is the order reached with an order-2 symmetric basic method. Literals carry 17
 * significant digits; every set was checked against two sources and against the order
 * conditions, evaluated in 60-digit arithmetic. */
#include <math.h>

#include "methods/internal.h"

/* Triple jump: γ_1 = γ_3 = 1/(2 − 2^{1/3}), γ_2 = −2^{1/3}/(2 − 2^{1/3}) = 1 − 2γ_1.
 * Creutz & Gocksch, Phys. Rev. Lett. 63 (1989) 9; Forest & Ruth, Physica D 43 (1990) 105;
 * Yoshida, Phys. Lett. A 150 (1990) 262, Sect. 4. */
static gm_status triple_jump_tableau(const gm_method *m, gm_tableau *t) {
  if (m->n_stages != 3 || t->gamma == NULL) return GM_EINVAL;
  const double g = 1.0 / (2.0 - cbrt(2.0));
  t->gamma[0] = t->gamma[2] = g;
  t->gamma[1] = 1.0 - 2.0 * g;
  return GM_OK;
}

/* Suzuki's fractal: γ = (p, p, 1 − 4p, p, p), p = 1/(4 − 4^{1/3}).
 * Suzuki, Phys. Lett. A 146 (1990) 319. */
static gm_status suzuki_tableau(const gm_method *m, gm_tableau *t) {
  if (m->n_stages != 5 || t->gamma == NULL) return GM_EINVAL;
  const double p = 1.0 / (4.0 - cbrt(4.0));
  t->gamma[0] = t->gamma[1] = t->gamma[3] = t->gamma[4] = p;
  t->gamma[2] = 1.0 - 4.0 * p;
  return GM_OK;
}

/* Yoshida, Phys. Lett. A 150 (1990) 262, Table 1, solution A (m = 3): γ_1 = w_3, γ_2 = w_2,
 * γ_3 = w_1, γ_4 = w_0 = 1 − 2(w_1 + w_2 + w_3). The paper prints 15 digits; these are the
 * 26-digit values of GNI (2006), Sect. V.3.2 (p6 s7), which agree with the paper and with the
 * Newton-refined solution of the order conditions to every printed digit. */
static const double yoshida6_gamma[] = {
    0.78451361047755726,  0.23557321335935813, -1.1776799841788710, 1.3151863206839112,
    -1.1776799841788710,  0.23557321335935813, 0.78451361047755726,
};

/* Yoshida (1990), Table 2, solution D (m = 7): γ_1..γ_7 = w_7..w_1, γ_8 = w_0 = 1 − 2Σw_i.
 * The paper prints 15 digits (w_7 = 0.914844246229740, w_6 = 0.253693336566229,
 * w_5 = −1.44485223686048, w_4 = −0.158240635368243, w_3 = 1.93813913762276,
 * w_2 = −1.96061023297549, w_1 = 0.102799849391985), which satisfy the order-8 conditions only
 * to ~3e-12. Below: the solution of those conditions nearest to the printed values (Newton in
 * 60-digit arithmetic; it differs from them by at most 2e-13). */
static const double yoshida8_gamma[] = {
    0.91484424622979157,  0.25369333656621135,  -1.4448522368606052, -0.15824063536805018,
    1.9381391376225260,   -1.9606102329753108,  0.10279984939179644, 1.7084530707872816,
    0.10279984939179644,  -1.9606102329753108,  1.9381391376225260,  -0.15824063536805018,
    -1.4448522368606052,  0.25369333656621135,  0.91484424622979157,
};

/* Kahan & Li, Math. Comp. 66 (1997) 1089–1099 (9 stages, order 6); 26-digit values
 * as listed in GNI (2006), Sect. V.3.2 (p6 s9). */
static const double kahan_li6_gamma[] = {
    0.39216144400731414,  0.33259913678935944, -0.70624617255763936,
    0.082213596293550800, 0.79854399093482996, 0.082213596293550800,
    -0.70624617255763936, 0.33259913678935944, 0.39216144400731414,
};

/* Kahan & Li (1997) (17 stages, order 8); GNI (2006), Sect. V.3.2 (p8 s17). */
static const double kahan_li8_gamma[] = {
    0.13020248308889008,  0.56116298177510838,  -0.38947496264484729, 0.15884190655515560,
    -0.39590389413323758, 0.18453964097831571,  0.25837438768632205,  0.29501172360931030,
    -0.60550853383003451, 0.29501172360931030,  0.25837438768632205,  0.18453964097831571,
    -0.39590389413323758, 0.15884190655515560,  -0.38947496264484729, 0.56116298177510838,
    0.13020248308889008,
};

/* Sofroniou & Spaletta, Optim. Methods Softw. 20 (2005) 597–613 (35 stages, order 10);
 * GNI (2006), Sect. V.3.2 (p10 s35) gives the same values to 26 digits. */
static const double sofroniou_spaletta10_gamma[] = {
    0.078795722521686419,  0.31309610341510853,  0.027918383235078066, -0.22959284159390709,
    0.13096206107716486,   -0.26973340565451071, 0.074973343155891436, 0.11199342399981020,
    0.36613344954622675,   -0.39910563013603590, 0.10308739852747108,  0.41143087395589024,
    -0.0048663605831352618, -0.39203335370863991, 0.051942502962449647, 0.050665090759924496,
    0.049674370639729879,  0.049317735759594538, 0.049674370639729879, 0.050665090759924496,
    0.051942502962449647,  -0.39203335370863991, -0.0048663605831352618, 0.41143087395589024,
    0.10308739852747108,   -0.39910563013603590, 0.36613344954622675,  0.11199342399981020,
    0.074973343155891436,  -0.26973340565451071, 0.13096206107716486,  -0.22959284159390709,
    0.027918383235078066,  0.31309610341510853,  0.078795722521686419,
};

/* The default basic method, chosen by measurement against the other Verlet at equal force
 * evaluations (docs/work-precision.md, "Which basic method"; tests/invariants/
 * test_basic_default.c). Position Verlet (drift–kick–drift) for every row but the last: on
 * Kepler (e = 0.6, 200 periods) it is more accurate for every row (1.5–7× for the Yoshida and
 * Suzuki rows, ~100× for the Kahan–Li rows); on the outer solar system as accurate or better
 * (1.0–7×), except yoshida-6 and yoshida-8, where velocity Verlet is 1.3–1.7× better. It also
 * costs no extra evaluation with compensated summation (velocity Verlet's last force can then no
 * longer be reused by the next step). sofroniou-spaletta-10 keeps velocity Verlet: position
 * Verlet is 1.1–2.6× more accurate there, under 10 % of the work for a tenth-order method, but
 * its error then falls faster than h¹⁰ all the way down to round-off, so the row's order cannot
 * be observed (median 10.7 over nine Kepler orbits, against 10.0 with velocity Verlet). */
#define COMP_OF(name_, order_, stages_, gamma_, fn_, basic_, desc, ref)                      \
  {.name = name_, .family = GM_FAMILY_COMPOSITION, .order = order_, .n_stages = stages_,     \
   .flags = GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT, .accepts = GM_PROBLEM_SEPARABLE,     \
   .gamma = gamma_, .compute = fn_, .basic = basic_, .description = desc, .reference = ref}
#define COMP(name_, order_, stages_, gamma_, fn_, desc, ref) \
  COMP_OF(name_, order_, stages_, gamma_, fn_, "verlet-position", desc, ref)

const gm_method gm_composition_methods[] = {
    COMP("yoshida-4", 4, 3, NULL, triple_jump_tableau,
         "triple jump (Creutz-Gocksch, Forest-Ruth, Yoshida): order 4 from three basic steps",
         "Yoshida, Phys. Lett. A 150 (1990) 262, Sect. 4; Forest & Ruth, Physica D 43 (1990) "
         "105; Creutz & Gocksch, Phys. Rev. Lett. 63 (1989) 9"),
    COMP("suzuki-4", 4, 5, NULL, suzuki_tableau,
         "Suzuki's fractal fourth order, five basic steps, smaller error than the triple jump",
         "Suzuki, Phys. Lett. A 146 (1990) 319"),
    COMP("yoshida-6", 6, 7, yoshida6_gamma, NULL, "Yoshida's sixth order, solution A, seven steps",
         "Yoshida, Phys. Lett. A 150 (1990) 262, Table 1, solution A; GNI (2006), Sect. V.3.2"),
    COMP("yoshida-8", 8, 15, yoshida8_gamma, NULL,
         "Yoshida's eighth order, solution D, fifteen steps",
         "Yoshida, Phys. Lett. A 150 (1990) 262, Table 2, solution D (refined to full precision)"),
    COMP("kahan-li-6", 6, 9, kahan_li6_gamma, NULL,
         "Kahan-Li optimized sixth order, nine steps",
         "Kahan & Li, Math. Comp. 66 (1997) 1089-1099; GNI (2006), Sect. V.3.2"),
    COMP("kahan-li-8", 8, 17, kahan_li8_gamma, NULL,
         "Kahan-Li optimized eighth order, seventeen steps",
         "Kahan & Li, Math. Comp. 66 (1997) 1089-1099; GNI (2006), Sect. V.3.2"),
    COMP_OF("sofroniou-spaletta-10", 10, 35, sofroniou_spaletta10_gamma, NULL, "verlet",
         "Sofroniou-Spaletta optimized tenth order, thirty-five steps",
         "Sofroniou & Spaletta, Optim. Methods Softw. 20 (2005) 597-613; GNI (2006), Sect. V.3.2"),
};
const size_t gm_n_composition_methods =
    sizeof gm_composition_methods / sizeof gm_composition_methods[0];
