/* Private declarations of the celestial module (Kepler drift, coordinates, near-integrable
 * splittings). Never installed. */
#ifndef GM_CELESTIAL_INTERNAL_H
#define GM_CELESTIAL_INTERNAL_H

#include "core/internal.h"
#include "geomint/celestial.h"

/* Coordinate maps with precomputed interior masses eta[i] = m_0 + … + m_i (coordinates.c);
 * the public gm_coordinates_* wrap them. Outputs may not alias inputs. */
void gm_interior_masses(size_t n, const double *m, double *eta);
void gm_jacobi_from_barycentric(size_t n, const double *m, const double *eta, const double *q,
                                const double *p, double *Q, double *P);
void gm_jacobi_to_barycentric(size_t n, const double *m, const double *eta, const double *Q,
                              const double *P, double *q, double *p);
void gm_heliocentric_from_barycentric(size_t n, const double *m, const double *q,
                                      const double *p, double *Q, double *P);
void gm_heliocentric_to_barycentric(size_t n, const double *m, const double *Q, const double *P,
                                    double *q, double *p);

/* 1/k!, k = 2..27 (kepler.c) */
extern const double gm_inverse_factorial[26];

/* The vector kernels (lanes.h) at 2 and 4 lanes (lanes2.c, lanes4.c). The short path of the
 * drift for count ≤ VW KEPLER_MAX_GROUPS orbits, VW = 2 or 4 (kepler_short.h; done[k]: whether
 * orbit k's drift was made, else it needs the iteration). The kick's Newtonian accelerations
 * from positions in separate x, y, z arrays of np entries (np a multiple of 4, np ≥ n; acc:
 * 3 np of scratch), and
 * its Kepler terms μ_k x_k/|x_k|³ (row_sums.h; 1 when a distance is zero). */
#define KEPLER_MAX_GROUPS 8
typedef void gm_kepler_short_fn(size_t count, const double *mu, double dt, const double *x,
                                const double *v, double *dx, double *dv, int apply,
                                double *ir, int *done);
gm_kepler_short_fn gm_kepler_short2, gm_kepler_short4;
typedef int gm_row_sums_fn(size_t n, size_t np, const double *x, const double *y,
                           const double *z, const double *m, double G, double *a, double *acc);
gm_row_sums_fn gm_row_sums2, gm_row_sums4;
typedef int gm_central_terms_fn(size_t count, const double *x, const double *y, const double *z,
                                const double *mu, double *out);
gm_central_terms_fn gm_central_terms2, gm_central_terms4;

/* The width the module uses on this CPU (kepler.c): 4 with AVX2 (where the build has the AVX2
 * kernels), else 2. Results are bitwise the same for both. */
int gm_lane_width(void);
static inline int gm_row_sums(size_t n, size_t np, const double *x, const double *y,
                              const double *z, const double *m, double G, double *a,
                              double *acc) {
  return (gm_lane_width() == 4 ? gm_row_sums4 : gm_row_sums2)(n, np, x, y, z, m, G, a, acc);
}
static inline int gm_central_terms(size_t count, const double *x, const double *y,
                                   const double *z, const double *mu, double *out) {
  return (gm_lane_width() == 4 ? gm_central_terms4 : gm_central_terms2)(count, x, y, z, mu, out);
}

/* gm_kepler_drift_many with a given width, 2 or 4 (tests compare the two). */
gm_status gm_kepler_drift_many_width(int width, size_t n, const double *mu, double dt,
                                     const double *x, const double *v, double *dx, double *dv);
/* The same drifts applied in place: x += dx, v += dv (each sum rounded once, as the caller's
 * own would be), for runs without compensated summation; 1/|x| at the end into ir[k] unless
 * ir is NULL (the end point's distance, which the drift has, to a few ulp: the Kepler terms
 * of the next kick). */
gm_status gm_kepler_drift_many_apply(int width, size_t n, const double *mu, double dt, double *x,
                                     double *v, double *ir);

/* gm_kepler_drift for n orbits (x, v, dx, dv: n 3-vectors; mu: n values) by the same dt, their
 * iterations interleaved (kepler.c). Same results as n calls. */
gm_status gm_kepler_drift_many(size_t n, const double *mu, double dt, const double *x,
                               const double *v, double *dx, double *dv);

/* The Kepler part of the coordinates (system.c): μ_i of planet i's two-body problem and the
 * mass m'_i with P_i = m'_i Q̇_i (index 0: μ = 0, the total mass). */
void gm_kepler_parameters(gm_coordinates kind, size_t n, const double *m, const double *eta,
                          double G, double *mu, double *reduced_mass);

/* The coordinates and corrector of a near-integrable row (near_integrable_table.c); NULL for
 * a row of another family. n_corrector = 0: no corrector. */
typedef struct gm_near_integrable_traits {
  gm_coordinates coordinates;
  size_t n_corrector;        /* K: stages Z(a_i, b_i), i = 1..K */
  const double *corrector_b; /* b_1..b_K (a_i = i·alpha) */
  double sabac_g;            /* ≠ 0: Laskar–Robutel's corrector kick of SABAC_n (its g) */
} gm_near_integrable_traits;
const gm_near_integrable_traits *gm_near_integrable_traits_of(const struct gm_method *m);
extern const double gm_corrector_alpha;

#endif
