/* Near-integrable splittings of planetary systems, H = H_Kepler + ε H_interaction: each stage
 * is a Kepler drift by a_i h (every planet along its exact two-body orbit, gm_kepler_drift)
 * followed by an interaction kick by b_i h, in the coordinates of the row (Jacobi or
 * democratic heliocentric, coordinates.c). The coefficients are those of Laskar & Robutel's
 * SABA_n / SBAB_n (splitting_table.c computes them from the Gauss–Legendre and Gauss–Lobatto
 * nodes), whose error for this splitting is O(ε h^{2n} + ε² h²) (Laskar & Robutel, Celest.
 * Mech. Dyn. Astr. 80 (2001) 39, §3-4). SABA_1 is the Wisdom–Holman map (Wisdom & Holman,
 * Astron. J. 102 (1991) 1528): drift h/2, kick h, drift h/2.
 *
 * The wh-cK rows add a symplectic corrector (Wisdom, Holman & Touma, Fields Inst. Commun. 10
 * (1996) 217; Wisdom, Astron. J. 131 (2006) 2294; used at orders 3-17 by Rein & Tamayo, MNRAS
 * 452 (2015) 376): C = Z(a_1, b_1) ⋯ Z(a_K, b_K), Z(a, b) = X(a, b) X(−a, −b),
 * X(a, b) = drift(a h) kick(b h) drift(−a h), a_i = i α with α = sqrt(7/40) (Wisdom et al.'s
 * choice). The b_i solve Σ_i 2 b_i a_i^{2k−1}/(2k−1)! = f_k (k = 1..K), f_k the coefficients of
 * (z/2)/sinh(z/2) = 1 − z²/24 + 7z⁴/5760 − ..., which makes C ∘ WH ∘ C⁻¹ the flow of H up to
 * O(ε h^{2K+2} + ε² h²); derived exactly (α² rational) by scripts/corrector_coefficients.py,
 * whose derivation is in its header. The same b_1 = −1/(48 α) is in Wisdom et al.'s
 * third-order corrector. The integrator applies C⁻¹ when a state is set and C only to the
 * states it outputs: the internal state stays uncorrected. */
#include "celestial/internal.h"
#include "methods/internal.h"

const double gm_corrector_alpha = 0.41833001326703777398908601; /* sqrt(7/40) */

/* scripts/corrector_coefficients.py, 25 digits */
static const double corrector3_b[] = {-0.04980119205559973499870072};
static const double corrector5_b[] = {-0.08300198675933289166450119, 0.01660039735186657833290024};
static const double corrector7_b[] = {-0.1079287981862549974435318, 0.03654184649340426289462528,
                                      -0.004985362285384421155806119};
static const double corrector11_b[] = {
    -0.1451867894976854773485064,  0.07624322736257730101729523,
    -0.02461815718403989263508913, 0.004697443058459070837661466,
    -0.0004072315929570930260326564};
static const double corrector17_b[] = {
    -0.1861122075428519171830821,   0.1303857271527557873165815,
    -0.06484439772942716058736305,  0.02414352164468458212489950,
    -0.006626515413876131131098039, 0.001271999661516353179663338,
    -0.0001528727104558714767264837, 0.000008669483094674716038130045};

/* Blanes, Casas, Farrés, Laskar, Makazaga & Murua, Appl. Numer. Math. 68 (2013) 58-72: the
 * symmetric ABA methods of generalized order (10,4), (8,6,4) and (10,6,4), error
 * O(ε h^{s1} + ε² h^{s2} + ε³ h^{s3}), with 7, 7 and 8 kicks. Drift a_i then kick b_i per stage
 * (the last stage is a drift only). Literals as printed there (40 digits), cross-checked with
 * the transcription in REBOUND's SABA integrator; tests/unit/test_celestial.c checks that the
 * kicks are a quadrature rule of order s1 on [0, 1] at the drift times (the ε h^{s1}
 * conditions). */
static const double aba864_a[] = {
    0.0711334264982231177779387300061549964174, 0.241153427956640098736487795326289649618,
    0.521411761772814789212136078067994229991,  -0.333698616227678005726562603400438876027,
    -0.333698616227678005726562603400438876027, 0.521411761772814789212136078067994229991,
    0.241153427956640098736487795326289649618,  0.0711334264982231177779387300061549964174};
static const double aba864_b[] = {
    0.183083687472197221961703757166430291072,   0.310782859898574869507522291054262796375,
    -0.0265646185119588006972121379164987592663, 0.0653961422823734184559721793911134363710,
    -0.0265646185119588006972121379164987592663, 0.310782859898574869507522291054262796375,
    0.183083687472197221961703757166430291072,   0.0};
static const double aba1064_a[] = {
    0.03809449742241219545697532230863756534060, 0.1452987161169137492940200726606637497442,
    0.2076276957255412507162056113249882065158,  0.4359097036515261592231548624010651844006,
    -0.6538612258327867093807117373907094120024, 0.4359097036515261592231548624010651844006,
    0.2076276957255412507162056113249882065158,  0.1452987161169137492940200726606637497442,
    0.03809449742241219545697532230863756534060};
static const double aba1064_b[] = {
    0.09585888083707521061077150377145884776921,  0.2044461531429987806805077839164344779763,
    0.2170703479789911017143385924306336714532,   -0.01737538195906509300561788011852699719871,
    -0.01737538195906509300561788011852699719871, 0.2170703479789911017143385924306336714532,
    0.2044461531429987806805077839164344779763,   0.09585888083707521061077150377145884776921,
    0.0};
static const double aba104_a[] = {
    0.04706710064597250612947887637243678556564,  0.1847569354170881069247376193702560968574,
    0.2827060056798362053243616565541452479160,   -0.01453004174289681837857815229683813033908,
    -0.01453004174289681837857815229683813033908, 0.2827060056798362053243616565541452479160,
    0.1847569354170881069247376193702560968574,   0.04706710064597250612947887637243678556564};
static const double aba104_b[] = {
    0.1188819173681970199453503950853885936957,  0.2410504605515015657441667865901651105675,
    -0.2732866667053238060543113981664559460630, 0.8267085775712504407295884329818044835997,
    -0.2732866667053238060543113981664559460630, 0.2410504605515015657441667865901651105675,
    0.1188819173681970199453503950853885936957,  0.0};

#define BCF_REF                                                                               \
  "Blanes, Casas, Farres, Laskar, Makazaga & Murua, Appl. Numer. Math. 68 (2013) 58-72"

#define LR_REF "Laskar & Robutel, Celest. Mech. Dyn. Astr. 80 (2001) 39-62"
#define WH_REF "Wisdom & Holman, Astron. J. 102 (1991) 1528"
#define WHT_REF                                                                               \
  "Wisdom & Holman, Astron. J. 102 (1991) 1528; corrector: Wisdom, Holman & Touma, Fields "   \
  "Inst. Commun. 10 (1996) 217, Wisdom, Astron. J. 131 (2006) 2294"
#define DLL_REF                                                                               \
  "Wisdom & Holman, Astron. J. 102 (1991) 1528; coordinates: Duncan, Levison & Lee, Astron. " \
  "J. 116 (1998) 2067"

#define ROW(name_, stages_, flags_, fn_, desc, ref)                                            \
  {.name = name_, .family = GM_FAMILY_NEAR_INTEGRABLE, .order = 2, .n_stages = stages_,       \
   .flags = GM_SYMPLECTIC | GM_EXPLICIT | (flags_), .accepts = GM_PROBLEM_SEPARABLE,          \
   .compute = fn_, .description = desc, .reference = ref}

#define ROW_LITERAL(name_, stages_, a_, b_, desc, ref)                                        \
  {.name = name_, .family = GM_FAMILY_NEAR_INTEGRABLE, .order = 2, .n_stages = stages_,       \
   .flags = GM_SYMPLECTIC | GM_EXPLICIT | GM_SYMMETRIC, .accepts = GM_PROBLEM_SEPARABLE,      \
   .a = a_, .b = b_, .description = desc, .reference = ref}

#define SABA_DESC(n_, e_)                                                                     \
  "SABA_" #n_ " of Kepler drifts and interaction kicks in Jacobi coordinates: error "          \
  "O(eps h^" #e_ " + eps^2 h^2)"
#define SBAB_DESC(n_, e_)                                                                     \
  "SBAB_" #n_ " of Kepler drifts and interaction kicks in Jacobi coordinates: error "          \
  "O(eps h^" #e_ " + eps^2 h^2)"
#define SABAC_DESC(n_, e_)                                                                    \
  "SABAC_" #n_ ": SABA_" #n_ " in Jacobi coordinates with Laskar-Robutel's corrector kick of "  \
  "the eps^2 h^2 term (3 force evaluations a step): error O(eps h^" #e_ " + eps^2 h^4)"
#define WHC_DESC(k_)                                                                          \
  "Wisdom-Holman in Jacobi coordinates with the order-" #k_ " symplectic corrector at "       \
  "output times"

const gm_method gm_near_integrable_methods[] = {
    ROW("wh", 2, GM_SYMMETRIC, gm_saba_tableau,
        "Wisdom-Holman map (= SABA_1): Kepler drift h/2, kick h, drift h/2, Jacobi coordinates",
        WH_REF),
    ROW("wh-dh", 2, GM_SYMMETRIC, gm_saba_tableau,
        "Wisdom-Holman map in democratic heliocentric coordinates (kick = jump, interaction, "
        "jump)",
        DLL_REF),
    ROW("saba-2-jacobi", 3, GM_SYMMETRIC, gm_saba_tableau, SABA_DESC(2, 4), LR_REF),
    ROW("saba-3-jacobi", 4, GM_SYMMETRIC, gm_saba_tableau, SABA_DESC(3, 6), LR_REF),
    ROW("saba-4-jacobi", 5, GM_SYMMETRIC, gm_saba_tableau, SABA_DESC(4, 8), LR_REF),
    ROW("sbab-1-jacobi", 2, GM_SYMMETRIC | GM_FSAL, gm_sbab_tableau, SBAB_DESC(1, 2), LR_REF),
    ROW("sbab-2-jacobi", 3, GM_SYMMETRIC | GM_FSAL, gm_sbab_tableau, SBAB_DESC(2, 4), LR_REF),
    ROW("sbab-3-jacobi", 4, GM_SYMMETRIC | GM_FSAL, gm_sbab_tableau, SBAB_DESC(3, 6), LR_REF),
    ROW("sbab-4-jacobi", 5, GM_SYMMETRIC | GM_FSAL, gm_sbab_tableau, SBAB_DESC(4, 8), LR_REF),
    ROW("wh-c3", 2, 0, gm_saba_tableau, WHC_DESC(3), WHT_REF),
    ROW("wh-c5", 2, 0, gm_saba_tableau, WHC_DESC(5), WHT_REF),
    ROW("wh-c7", 2, 0, gm_saba_tableau, WHC_DESC(7), WHT_REF),
    ROW("wh-c11", 2, 0, gm_saba_tableau, WHC_DESC(11), WHT_REF),
    ROW("wh-c17", 2, 0, gm_saba_tableau, WHC_DESC(17), WHT_REF),
    ROW("sabac-1-jacobi", 2, GM_SYMMETRIC, gm_saba_tableau, SABAC_DESC(1, 2), LR_REF),
    ROW("sabac-2-jacobi", 3, GM_SYMMETRIC, gm_saba_tableau, SABAC_DESC(2, 4), LR_REF),
    ROW("sabac-3-jacobi", 4, GM_SYMMETRIC, gm_saba_tableau, SABAC_DESC(3, 6), LR_REF),
    ROW("sabac-4-jacobi", 5, GM_SYMMETRIC, gm_saba_tableau, SABAC_DESC(4, 8), LR_REF),
    ROW_LITERAL("aba-10-4", 8, aba104_a, aba104_b,
                "Blanes et al. ABA(10,4), 7 kicks, Jacobi: error O(eps h^10 + eps^2 h^4)",
                BCF_REF),
    ROW_LITERAL("aba-8-6-4", 8, aba864_a, aba864_b,
                "Blanes et al. ABA(8,6,4), 7 kicks, Jacobi: error O(eps h^8 + eps^2 h^6 + "
                "eps^3 h^4)",
                BCF_REF),
    ROW_LITERAL("aba-10-6-4", 9, aba1064_a, aba1064_b,
                "Blanes et al. ABA(10,6,4), 8 kicks, Jacobi: error O(eps h^10 + eps^2 h^6 + "
                "eps^3 h^4)",
                BCF_REF),
};
const size_t gm_n_near_integrable_methods =
    sizeof gm_near_integrable_methods / sizeof gm_near_integrable_methods[0];

#define J GM_COORDINATES_JACOBI
static const gm_near_integrable_traits traits[] = {
    {J, 0, NULL, 0.0},
    {GM_COORDINATES_DEMOCRATIC_HELIOCENTRIC, 0, NULL, 0.0},
    {J, 0, NULL, 0.0},
    {J, 0, NULL, 0.0},
    {J, 0, NULL, 0.0},
    {J, 0, NULL, 0.0},
    {J, 0, NULL, 0.0},
    {J, 0, NULL, 0.0},
    {J, 0, NULL, 0.0},
    {J, 1, corrector3_b, 0.0},
    {J, 2, corrector5_b, 0.0},
    {J, 3, corrector7_b, 0.0},
    {J, 5, corrector11_b, 0.0},
    {J, 8, corrector17_b, 0.0},
    /* SABAC_n: g_n of Laskar & Robutel (2001), §4: 1/12, (2 − √3)/24, (54 − 13√15)/648 and
     * the printed value for n = 4 (the ε² h² coefficient g h² {{A,B},B} of SABA_n) */
    {J, 0, NULL, 1.0 / 12.0},
    {J, 0, NULL, 0.01116454968463011276968973577058865137738},
    {J, 0, NULL, 0.005634593363122809402267823769797538671562},
    {J, 0, NULL, 0.003396775048208601331532157783492144},
    {J, 0, NULL, 0.0},
    {J, 0, NULL, 0.0},
    {J, 0, NULL, 0.0},
};
_Static_assert(sizeof traits / sizeof traits[0] ==
                   sizeof gm_near_integrable_methods / sizeof gm_near_integrable_methods[0],
               "one traits entry per near-integrable row");

const gm_near_integrable_traits *gm_near_integrable_traits_of(const gm_method *m) {
  if (m == NULL || m < gm_near_integrable_methods ||
      m >= gm_near_integrable_methods + gm_n_near_integrable_methods)
    return NULL;
  return &traits[m - gm_near_integrable_methods];
}

gm_coordinates gm_method_coordinates(const gm_method *m) {
  const gm_near_integrable_traits *t = gm_near_integrable_traits_of(m);
  return t != NULL ? t->coordinates : (gm_coordinates)0;
}

int gm_method_corrector_order(const gm_method *m) {
  const gm_near_integrable_traits *t = gm_near_integrable_traits_of(m);
  return t != NULL && t->n_corrector > 0 ? (int)(2 * t->n_corrector + 1) : 0;
}
