/* geomint celestial: planetary systems as near-integrable Hamiltonians (docs/celestial.md).
 *
 *   - the Kepler drift: the exact flow of one two-body problem x'' = −μ x/|x|³ for any conic,
 *     in universal variables (Stumpff functions), solved by Householder's fourth-order method inside a bracket;
 *   - coordinates in which H = H_Kepler + H_interaction: Jacobi (Wisdom & Holman 1991) and
 *     democratic heliocentric (Duncan, Levison & Lee 1998), with their exact transformations
 *     to and from barycentric coordinates;
 *   - the description of a "central body + perturbed orbits" problem (gm_celestial), which a
 *     separable problem carries in gm_problem.celestial; the near-integrable method rows
 *     (wh, saba-n-wh, sbab-n-wh, ..., family "near-integrable") integrate only such problems.
 *
 * State layout everywhere: n bodies in 3-D, positions body by body (x1 y1 z1 x2 ...), then
 * momenta in the same order; body 0 is the central body. */
#ifndef GEOMINT_CELESTIAL_H
#define GEOMINT_CELESTIAL_H

#include <stddef.h>

#include "geomint/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the Kepler drift ------------------------------------------------------------------ */

/* Advance x'' = −μ x/|x|³ by dt (any sign) from (x0, v0) and write the increments
 * dx = x(dt) − x0, dv = v(dt) − v0 (so that x0 + dx keeps the digits of a small increment;
 * the outputs may not alias the inputs). Any conic: elliptic, parabolic, hyperbolic, nearly
 * radial. μ > 0, |x0| > 0, all values finite; otherwise GM_EINVAL / GM_EDOMAIN. GM_ENOCONV
 * only if the bracketed iteration did not converge (not seen in the tests) and GM_EDOMAIN if a
 * hyperbolic orbit leaves the range of double precision. */
gm_status gm_kepler_drift(double mu, double dt, const double x0[3], const double v0[3],
                          double dx[3], double dv[3]);

/* The Stumpff-function form of the drift: G_k(β, s) = s^k c_k(β s²), k = 0..3, with the
 * Stumpff functions c_k(z) = Σ_j (−z)^j/(2j + k)!. Exposed for tests. */
void gm_stumpff_g(double beta, double s, double g[4]);

/* ---- coordinates -------------------------------------------------------------------------- */

typedef enum gm_coordinates {
  GM_COORDINATES_JACOBI = 1,                  /* Wisdom & Holman (1991) */
  GM_COORDINATES_DEMOCRATIC_HELIOCENTRIC = 2  /* Duncan, Levison & Lee (1998) */
} gm_coordinates;

/* "jacobi", "democratic-heliocentric" */
const char *gm_coordinates_name(gm_coordinates coordinates);

/* Barycentric (inertial) positions q and momenta p of n bodies (masses m, all > 0) to the
 * canonical coordinates (Q, P) of the kind, and back. Both are linear canonical maps:
 *   Jacobi:  Q_0 = centre of mass, Q_i = q_i − (Σ_{j<i} m_j q_j)/η_{i−1}, η_i = Σ_{j≤i} m_j;
 *            P_i = m'_i Q̇_i with m'_i = m_i η_{i−1}/η_i (P_0 = total momentum).
 *   democratic heliocentric: Q_0 = centre of mass, Q_i = q_i − q_0 (heliocentric positions);
 *            P_0 = total momentum, P_i = p_i − (m_i/M) P_0 (barycentric momenta).
 * Arrays hold 3n values; outputs may not alias inputs. GM_EINVAL for n = 0 or a mass that is
 * not positive and finite. */
gm_status gm_coordinates_from_barycentric(gm_coordinates kind, size_t n, const double *m,
                                          const double *q, const double *p, double *Q,
                                          double *P);
gm_status gm_coordinates_to_barycentric(gm_coordinates kind, size_t n, const double *m,
                                        const double *Q, const double *P, double *q, double *p);

/* ---- central body + perturbed orbits ----------------------------------------------------- */

/* What a near-integrable splitting needs to know about a separable problem besides its
 * callbacks: n bodies with masses m (body 0 central, the others its "planets") under Newtonian
 * gravity with constant G, H = Σ|p_i|²/(2 m_i) + V(q), V translation invariant. The splitting
 * takes the Kepler part from m and G, and V's gradient from the problem (potential_gradient)
 * unless newtonian is 1: then V is exactly −G Σ_{i<j} m_i m_j/|q_i − q_j| (no softening,
 * nothing added) and the splitting evaluates the interaction itself (in vector lanes, and in
 * democratic heliocentric coordinates without the central body's terms, which cancel the
 * Kepler terms exactly). Each evaluation is counted as a force evaluation either way. */
typedef struct gm_celestial {
  size_t n_bodies;      /* ≥ 2 */
  const double *mass;   /* borrowed, n_bodies masses > 0 */
  double G;             /* > 0 */
  int newtonian;        /* 1: V is point-mass gravity of these masses and nothing else */
} gm_celestial;

/* Check a description: n ≥ 2, G and masses positive and finite. err says which. */
gm_status gm_celestial_validate(const gm_celestial *c, gm_error *err);

/* The shortest orbital period among the planets of the barycentric state y = (q, p) in the
 * Kepler part of the coordinates (μ_i = G m_0 η_i/η_{i−1} in Jacobi, G m_0 in
 * democratic heliocentric); +inf when no planet is bound. Sets *n_unbound (may be NULL) to the
 * number of planets on unbound (parabolic or hyperbolic) Kepler orbits. */
double gm_celestial_shortest_period(const gm_celestial *c, gm_coordinates kind,
                                    const double *y, size_t *n_unbound);

/* ---- near-integrable rows ---------------------------------------------------------------- */

struct gm_method;
/* The coordinates a near-integrable row works in; 0 for a row of another family. */
gm_coordinates gm_method_coordinates(const struct gm_method *method);
/* The order of the row's symplectic corrector (3, 5, 7, 11, 17); 0 without one. */
int gm_method_corrector_order(const struct gm_method *method);

#ifdef __cplusplus
}
#endif
#endif
