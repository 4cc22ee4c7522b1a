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
