/* Jacobi and democratic heliocentric coordinates, to and from barycentric ones.
 *
 * Jacobi (Wisdom & Holman, Astron. J. 102 (1991) 1528, §3; Rein & Tamayo, MNRAS 452 (2015)
 * 376, §2.2): with the interior masses η_i = m_0 + … + m_i,
 *   Q_i = q_i − R_{i−1},  R_i = (η_{i−1} R_{i−1} + m_i q_i)/η_i = R_{i−1} + (m_i/η_i) Q_i,
 *   Q_0 = R_{n−1} (the centre of mass), and the conjugate momenta
 *   P_i = (η_{i−1} p_i − m_i S_{i−1})/η_i = m'_i Q̇_i,  S_i = p_0 + … + p_i,  m'_i = m_i η_{i−1}/η_i,
 *   P_0 = S_{n−1}. (P = A^{−T} p for the linear map Q = A q, so the map is canonical; the
 *   kinetic energy is Σ_{i≥1} |P_i|²/(2 m'_i) + |P_0|²/(2 η_{n−1}).)
 * Inverse, from the same recurrences run backwards: R_{i−1} = R_i − (m_i/η_i) Q_i,
 *   q_i = Q_i + R_{i−1}; S_{i−1} = (η_{i−1}/η_i) S_i − P_i, p_i = S_i − S_{i−1}.
 *
 * Democratic heliocentric (Duncan, Levison & Lee, Astron. J. 116 (1998) 2067, eqs. 2-3):
 *   Q_i = q_i − q_0 (i ≥ 1), Q_0 = centre of mass;  P_i = p_i − (m_i/M) P_0 (i ≥ 1, the
 *   barycentric momenta: p_i itself when the total momentum P_0 = Σ p_j vanishes), the
 *   conjugates of Q through p = Aᵀ P for Q = A q.
 * Inverse: q_0 = Q_0 − Σ_{i≥1} (m_i/M) Q_i, q_i = Q_i + q_0; p_i = P_i + (m_i/M) P_0,
 *   p_0 = (m_0/M) P_0 − Σ_{i≥1} P_i. Then T = |P_0|²/(2M) + Σ_{i≥1} |P_i|²/(2m_i) +
 *   |Σ_{i≥1} P_i|²/(2m_0). */
#include <math.h>
#include <stdlib.h>

#include "celestial/internal.h"

const char *gm_coordinates_name(gm_coordinates coordinates) {
  switch (coordinates) {
    case GM_COORDINATES_JACOBI:
      return "jacobi";
    case GM_COORDINATES_DEMOCRATIC_HELIOCENTRIC:
      return "democratic-heliocentric";
  }
  return "unknown";
}

static gm_status check(gm_coordinates kind, size_t n, const double *m, const void *a,
                       const void *b, const void *c, const void *d) {
  if (n == 0 || m == NULL || a == NULL || b == NULL || c == NULL || d == NULL) return GM_EINVAL;
  if (kind != GM_COORDINATES_JACOBI && kind != GM_COORDINATES_DEMOCRATIC_HELIOCENTRIC)
    return GM_EINVAL;
  for (size_t i = 0; i < n; ++i)
    if (!(m[i] > 0.0) || !isfinite(m[i])) return GM_EINVAL;
  return GM_OK;
}

void gm_jacobi_from_barycentric(size_t n, const double *m, const double *eta, const double *q,
                                const double *p, double *Q, double *P) {
  double R[3], S[3];
  for (int k = 0; k < 3; ++k) {
    R[k] = q[k];
    S[k] = p[k];
  }
  for (size_t i = 1; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      Q[3 * i + k] = q[3 * i + k] - R[k];
      P[3 * i + k] = (eta[i - 1] * p[3 * i + k] - m[i] * S[k]) / eta[i];
      R[k] += (m[i] / eta[i]) * Q[3 * i + k];
      S[k] += p[3 * i + k];
    }
  for (int k = 0; k < 3; ++k) {
    Q[k] = R[k];
    P[k] = S[k];
  }
}

void gm_jacobi_to_barycentric(size_t n, const double *m, const double *eta, const double *Q,
                              const double *P, double *q, double *p) {
  double R[3], S[3];
  for (int k = 0; k < 3; ++k) {
    R[k] = Q[k];
    S[k] = P[k];
  }
  for (size_t i = n - 1; i >= 1; --i)
    for (int k = 0; k < 3; ++k) {
      const double R_prev = R[k] - (m[i] / eta[i]) * Q[3 * i + k];
      const double S_prev = (eta[i - 1] / eta[i]) * S[k] - P[3 * i + k];
      q[3 * i + k] = Q[3 * i + k] + R_prev;
      p[3 * i + k] = S[k] - S_prev;
      R[k] = R_prev;
      S[k] = S_prev;
    }
  for (int k = 0; k < 3; ++k) {
    q[k] = R[k];
    p[k] = S[k];
  }
}

void gm_heliocentric_from_barycentric(size_t n, const double *m, const double *q, const double *p,
                              double *Q, double *P) {
  double M = 0.0, c[3] = {0, 0, 0}, S[3] = {0, 0, 0};
  for (size_t i = 0; i < n; ++i) {
    M += m[i];
    for (int k = 0; k < 3; ++k) {
      c[k] += m[i] * q[3 * i + k];
      S[k] += p[3 * i + k];
    }
  }
  for (size_t i = 1; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      Q[3 * i + k] = q[3 * i + k] - q[k];
      P[3 * i + k] = p[3 * i + k] - (m[i] / M) * S[k];
    }
  for (int k = 0; k < 3; ++k) {
    Q[k] = c[k] / M;
    P[k] = S[k];
  }
}

void gm_heliocentric_to_barycentric(size_t n, const double *m, const double *Q, const double *P,
                            double *q, double *p) {
  double M = 0.0, c[3] = {0, 0, 0}, S[3] = {0, 0, 0};
  for (size_t i = 0; i < n; ++i) M += m[i];
  for (size_t i = 1; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      c[k] += m[i] * Q[3 * i + k];
      S[k] += P[3 * i + k];
    }
  for (int k = 0; k < 3; ++k) {
    q[k] = Q[k] - c[k] / M;
    p[k] = (m[0] / M) * P[k] - S[k];
  }
  for (size_t i = 1; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      q[3 * i + k] = Q[3 * i + k] + q[k];
      p[3 * i + k] = P[3 * i + k] + (m[i] / M) * P[k];
    }
}

/* η_i = m_0 + … + m_i (allocated; NULL when out of memory) */
static double *interior_masses(size_t n, const double *m) {
  double *eta = malloc(n * sizeof *eta);
  if (eta == NULL) return NULL;
  gm_interior_masses(n, m, eta);
  return eta;
}

void gm_interior_masses(size_t n, const double *m, double *eta) {
  eta[0] = m[0];
  for (size_t i = 1; i < n; ++i) eta[i] = eta[i - 1] + m[i];
}

gm_status gm_coordinates_from_barycentric(gm_coordinates kind, size_t n, const double *m,
                                          const double *q, const double *p, double *Q,
                                          double *P) {
  gm_status st = check(kind, n, m, q, p, Q, P);
  if (st != GM_OK) return st;
  if (kind == GM_COORDINATES_DEMOCRATIC_HELIOCENTRIC) {
    gm_heliocentric_from_barycentric(n, m, q, p, Q, P);
    return GM_OK;
  }
  double *eta = interior_masses(n, m);
  if (eta == NULL) return GM_ENOMEM;
  gm_jacobi_from_barycentric(n, m, eta, q, p, Q, P);
  free(eta);
  return GM_OK;
}

gm_status gm_coordinates_to_barycentric(gm_coordinates kind, size_t n, const double *m,
                                        const double *Q, const double *P, double *q,
                                        double *p) {
  gm_status st = check(kind, n, m, Q, P, q, p);
  if (st != GM_OK) return st;
  if (kind == GM_COORDINATES_DEMOCRATIC_HELIOCENTRIC) {
    gm_heliocentric_to_barycentric(n, m, Q, P, q, p);
    return GM_OK;
  }
  double *eta = interior_masses(n, m);
  if (eta == NULL) return GM_ENOMEM;
  gm_jacobi_to_barycentric(n, m, eta, Q, P, q, p);
  free(eta);
  return GM_OK;
}
