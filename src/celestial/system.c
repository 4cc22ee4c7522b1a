/* The "central body + perturbed orbits" description: validation, the Kepler parameters μ_i of
 * each coordinate system, and the shortest orbital period (for the step-size warning). */
#include <math.h>
#include <stdlib.h>

#include "celestial/internal.h"

gm_status gm_celestial_validate(const gm_celestial *c, gm_error *err) {
  if (c == NULL) return gm_error_set(err, GM_EINVAL, "no central body + orbits description");
  if (c->n_bodies < 2 || c->mass == NULL)
    return gm_error_set(err, GM_EINVAL,
                        "a central body + perturbed orbits problem needs at least 2 bodies, got "
                        "%zu",
                        c->n_bodies);
  if (!(c->G > 0.0) || !isfinite(c->G))
    return gm_error_set(err, GM_EINVAL, "the gravitational constant G must be positive, got %g",
                        c->G);
  for (size_t i = 0; i < c->n_bodies; ++i)
    if (!(c->mass[i] > 0.0) || !isfinite(c->mass[i]))
      return gm_error_set(err, GM_EINVAL,
                          "body %zu has mass %g: a near-integrable splitting needs positive "
                          "masses",
                          i + 1, c->mass[i]);
  return GM_OK;
}

void gm_kepler_parameters(gm_coordinates kind, size_t n, const double *m, const double *eta,
                          double G, double *mu, double *reduced_mass) {
  mu[0] = 0.0;
  reduced_mass[0] = eta[n - 1]; /* the centre of mass moves freely with the total mass */
  for (size_t i = 1; i < n; ++i) {
    if (kind == GM_COORDINATES_JACOBI) {
      /* p'²/(2m'_i) − G m_0 m_i/r'_i: μ_i = G m_0 m_i/m'_i = G m_0 η_i/η_{i−1} (WH91 eq. 21) */
      mu[i] = G * m[0] * (eta[i] / eta[i - 1]);
      reduced_mass[i] = m[i] * (eta[i - 1] / eta[i]);
    } else {
      /* P_i²/(2m_i) − G m_0 m_i/|Q_i| (DLL98 eq. 5): μ_i = G m_0 */
      mu[i] = G * m[0];
      reduced_mass[i] = m[i];
    }
  }
}

double gm_celestial_shortest_period(const gm_celestial *c, gm_coordinates kind,
                                    const double *y, size_t *n_unbound) {
  if (n_unbound != NULL) *n_unbound = 0;
  if (gm_celestial_validate(c, NULL) != GM_OK || y == NULL) return NAN;
  const size_t n = c->n_bodies;
  double *work = malloc(9 * n * sizeof *work);
  if (work == NULL) return NAN;
  double *eta = work, *mu = work + n, *mr = work + 2 * n, *Q = work + 3 * n, *P = work + 6 * n;
  gm_interior_masses(n, c->mass, eta);
  gm_kepler_parameters(kind, n, c->mass, eta, c->G, mu, mr);
  if (kind == GM_COORDINATES_JACOBI)
    gm_jacobi_from_barycentric(n, c->mass, eta, y, y + 3 * n, Q, P);
  else
    gm_heliocentric_from_barycentric(n, c->mass, y, y + 3 * n, Q, P);
  double shortest = INFINITY;
  for (size_t i = 1; i < n; ++i) {
    const double *x = Q + 3 * i, *p = P + 3 * i;
    double r = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    double v2 = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) / (mr[i] * mr[i]);
    double beta = 2.0 * mu[i] / r - v2;
    if (!(beta > 0.0)) {
      if (n_unbound != NULL) ++*n_unbound;
      continue;
    }
    shortest = fmin(shortest, 2.0 * GM_PI * mu[i] / (beta * sqrt(beta)));
  }
  free(work);
  return shortest;
}
