/* Rows of the oscillatory family (issue 12) and, at the same index, the scheme and filters
 * each row uses (methods/oscillatory.h). All are of classical order 2 for a fixed Ω as h → 0;
 * what they are for is h·ω ≫ 1 (docs/oscillatory.md).
 *
 * Filter pairs (ψ, φ) of the trigonometric rows, GNI (Hairer, Lubich & Wanner 2006) §XIII.2.2,
 * methods (A)–(E); ψ0 = cos·ψ1, ψ1 = ψ/sinc (the symmetric one-step form, GNI XIII (2.10)).
 * Such a method is symplectic iff ψ = sinc·φ (GNI XIII.2): (B) and (C). The variational rows
 * are symplectic by construction (a discrete Lagrangian generates them). */
#include <math.h>

#include "methods/oscillatory/oscillatory.h"

static double one(double xi) {
  (void)xi;
  return 1.0;
}
static double sinc_(double xi) { return gm_sinc(xi); }
static double sinc2(double xi) {
  const double s = gm_sinc(xi);
  return s * s;
}
static double sinc2_half(double xi) {
  const double s = gm_sinc(0.5 * xi);
  return s * s;
}
/* Hochbruck & Lubich (1999): φ(ξ) = sinc(ξ)(1 + ⅓ sin²(ξ/2)) (GNI XIII.2.2 (D)). The constant
 * ⅓ is the one for which, with ψ = sinc²(ξ/2), ψφ = sinc(ξ) + O(ξ⁴): the frequency shift a
 * linear slow force causes is right to O(ξ⁴) (a = ½ would leave an O(ξ²) error); derived and
 * tested in tests/unit/test_oscillatory_filters.c, since the book's text could not be
 * retrieved here to compare. */
static double phi_hochbruck_lubich(double xi) {
  const double s = sin(0.5 * xi);
  return gm_sinc(xi) * (1.0 + s * s / 3.0);
}

const gm_osc_scheme gm_oscillatory_schemes[] = {
    {GM_OSC_IMEX, NULL, NULL, 0, 0},
    {GM_OSC_IMPULSE, NULL, NULL, 10, 0},
    /* n = 20 by measurement (`geomint oscillatory step-scan`, docs/oscillatory.md): A = sinc(hΩ)
     * is the average of the exact fast flow, and with n = 10 Verlet's phase (2 arcsin(hω/2n) a
     * substep: 10.47 rad instead of 10 at hω = 10) moves the numerical resonances off A's
     * zeros — I error 3.5e-2 at h = 0.2 on FPU; n = 20: 4.5e-3 */
    {GM_OSC_MOLLIFIED, sinc_, NULL, 20, 1},
    {GM_OSC_TRIG, one, sinc2_half, 0, 1},            /* (A) Gautschi */
    {GM_OSC_TRIG, one, sinc_, 0, 1},                 /* (B) Deuflhard */
    {GM_OSC_TRIG, sinc_, sinc2, 0, 1},               /* (C) García-Archilla et al. */
    {GM_OSC_TRIG, phi_hochbruck_lubich, sinc2_half, 0, 1}, /* (D) Hochbruck–Lubich */
    {GM_OSC_TRIG, one, sinc2, 0, 1},                 /* (E) Hairer–Lubich */
    {GM_OSC_VTI, NULL, NULL, 0, 1},
    {GM_OSC_VTI_SCALAR, one, NULL, 0, 1},
};

#define SPLIT GM_PROBLEM_SEPARABLE /* with gm_problem.split set (checked at create) */

const gm_method gm_oscillatory_methods[] = {
    {"imex", GM_FAMILY_OSCILLATORY, 2, 1, GM_SYMPLECTIC | GM_SYMMETRIC | GM_IMPLICIT, SPLIT,
     NULL, NULL, NULL, NULL, NULL, NULL,
     "variational IMEX: kick U by h/2, implicit midpoint on T + W, kick U by h/2 (a linear "
     "solve when W is quadratic)",
     "Zhang & Skeel, J. Comput. Chem. 18 (1997); Stern, thesis (2009) §2.2.1, Prop. 2.2.1, "
     "§2.2.5"},
    {"impulse", GM_FAMILY_OSCILLATORY, 2, 10, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT, SPLIT,
     NULL, NULL, NULL, NULL, NULL, NULL,
     "impulse / r-RESPA: kick U by h/2, n Verlet substeps of h/n on T + W (n = 10, "
     "gm_oscillatory_set_substeps), kick U by h/2",
     "Grubmüller et al., Mol. Sim. 6 (1991); Tuckerman, Berne & Martyna, J. Chem. Phys. 97 "
     "(1992); GNI VIII.4"},
    {"mollified-impulse-sinc", GM_FAMILY_OSCILLATORY, 2, 20,
     GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT, SPLIT, NULL, NULL, NULL, NULL, NULL, NULL,
     "mollified impulse: impulse on U(A q) with the long-time average A = sinc(hΩ) of the fast "
     "flow from q at rest over [−h, h]; n = 20 Verlet substeps on T + W",
     "García-Archilla, Sanz-Serna & Skeel, SIAM J. Sci. Comput. 20 (1999); GNI VIII.4, "
     "XIII.1.4"},
    {"trig-gautschi", GM_FAMILY_OSCILLATORY, 2, 1, GM_SYMMETRIC | GM_EXPLICIT, SPLIT, NULL,
     NULL, NULL, NULL, NULL, NULL,
     "trigonometric integrator, ψ = sinc²(ξ/2), φ = 1",
     "Gautschi, Numer. Math. 3 (1961); GNI XIII.2.2 (A), one-step form XIII (2.7)-(2.8)"},
    {"trig-deuflhard", GM_FAMILY_OSCILLATORY, 2, 1, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT,
     SPLIT, NULL, NULL, NULL, NULL, NULL, NULL,
     "trigonometric integrator, ψ = sinc ξ, φ = 1 (symplectic: ψ = sinc·φ, GNI XIII.2)",
     "Deuflhard, ZAMP 30 (1979); GNI XIII.2.2 (B), one-step form XIII (2.7)-(2.8)"},
    {"trig-garcia-archilla", GM_FAMILY_OSCILLATORY, 2, 1,
     GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT, SPLIT, NULL, NULL, NULL, NULL, NULL, NULL,
     "trigonometric integrator, ψ = sinc² ξ, φ = sinc ξ (the mollified impulse method with "
     "exact fast flow)",
     "García-Archilla, Sanz-Serna & Skeel, SIAM J. Sci. Comput. 20 (1999); GNI XIII.2.2 (C)"},
    {"trig-hochbruck-lubich", GM_FAMILY_OSCILLATORY, 2, 1, GM_SYMMETRIC | GM_EXPLICIT, SPLIT,
     NULL, NULL, NULL, NULL, NULL, NULL,
     "trigonometric integrator, ψ = sinc²(ξ/2), φ = sinc ξ (1 + sin²(ξ/2)/3)",
     "Hochbruck & Lubich, Numer. Math. 83 (1999); GNI XIII.2.2 (D)"},
    {"trig-hairer-lubich", GM_FAMILY_OSCILLATORY, 2, 1, GM_SYMMETRIC | GM_EXPLICIT, SPLIT, NULL,
     NULL, NULL, NULL, NULL, NULL, "trigonometric integrator, ψ = sinc² ξ, φ = 1",
     "Hairer & Lubich, SIAM J. Numer. Anal. 38 (2000); GNI XIII.2.2 (E)"},
    {"vti", GM_FAMILY_OSCILLATORY, 2, 1, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT, SPLIT,
     NULL, NULL, NULL, NULL, NULL, NULL,
     "variational trigonometric integrator, vector case: filters Φ = sinc(hΩ/2) sinc(hΩ)^(-1/2), "
     "Ψ = Φ sinc(hΩ) (needs sinc(hω) > 0 for every frequency)",
     "Stern, thesis (2009) §2.3.2 (corrections in seeds/notes/000 A6)"},
    {"vti-scalar", GM_FAMILY_OSCILLATORY, 2, 1, GM_SYMPLECTIC | GM_SYMMETRIC | GM_EXPLICIT,
     SPLIT, NULL, NULL, NULL, NULL, NULL, NULL,
     "variational trigonometric integrator, scalar case (one degree of freedom): free Φ "
     "(default 1, gm_oscillatory_set_filters), ΨΦ = sinc²(hω/2)",
     "Stern, thesis (2009) §2.3.1 (corrections in seeds/notes/000 A6)"},
};
const size_t gm_n_oscillatory_methods =
    sizeof gm_oscillatory_methods / sizeof gm_oscillatory_methods[0];
