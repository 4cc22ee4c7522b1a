/* Geometric phases with closed forms: the Levi-Civita connection of the sphere as an SO(2)
 * connection (Foucault's pendulum) and Montgomery's rigid-body phase (Am. J. Phys. 59 (1991)
 * 394). Conventions in include/geomint/reduction.h. */
#include <math.h>

#include "core/internal.h"
#include "geomint/lie.h"
#include "geomint/problems.h"
#include "geomint/reduction.h"

int gm_sphere_levi_civita(void *ctx, const double *x, double *a) {
  (void)ctx;
  const double r2 = x[0] * x[0] + x[1] * x[1];
  if (!(r2 > 0.0 && r2 < 1.0)) return -1;
  const double c = sqrt(1.0 - r2) / r2; /* cos ϑ / ρ², cos ϑ = z = √(1 − ρ²) */
  a[0] = -c * x[1];                     /* dφ = (X dY − Y dX)/ρ² */
  a[1] = c * x[0];
  return 0;
}

double gm_so3_angle_about(const double r0[9], const double r1[9], const double u[3]) {
  double q[9], w[3];
  gm_mat3_mul_nt(r1, r0, q);
  w[0] = 0.5 * (q[7] - q[5]);
  w[1] = 0.5 * (q[2] - q[6]);
  w[2] = 0.5 * (q[3] - q[1]);
  const double s = gm_vec3_dot(w, u) / gm_vec3_norm(u), c = 0.5 * (q[0] + q[4] + q[8] - 1.0);
  return atan2(s, c);
}

/* Euler's equations Π' = Π × Ω, Ω = I⁻¹Π, with the solid-angle integrand (1 − cos ϑ) φ̇ about
 * axis a (cos ϑ = |Π_a|/|Π|: the cap on Π's side) as a fourth component. */
static void euler_rhs(const double *in, int a, const double *y, double *dy) {
  const double om[3] = {y[0] / in[0], y[1] / in[1], y[2] / in[2]};
  gm_vec3_cross(y, om, dy);
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const double rho2 = y[b] * y[b] + y[c] * y[c], norm = gm_vec3_norm(y);
  dy[3] = (1.0 - fabs(y[a]) / norm) * (y[b] * dy[c] - y[c] * dy[b]) / rho2;
}

gm_status gm_rigid_body_phase(const double inertia[3], const double pi[3], size_t steps,
                              double *period, double *dynamic, double *solid_angle, gm_error *err) {
  if (inertia == NULL || pi == NULL)
    return gm_error_set(err, GM_EINVAL, "rigid-body phase: NULL argument");
  const double t = gm_free_rigid_body_period(inertia, pi);
  if (!isfinite(t))
    return gm_error_set(err, GM_EINVAL,
                        "rigid-body phase: Π(t) is not periodic off a fixed point (distinct "
                        "moments needed, not on the separatrix, not a steady spin)");
  double e2 = 0.0, m2 = 0.0;
  for (int i = 0; i < 3; ++i) e2 += pi[i] * pi[i] / inertia[i], m2 += pi[i] * pi[i];
  /* the encircled axis: the largest moment when m² > 2E I_mid, else the smallest */
  int lo = 0, hi = 0;
  for (int i = 1; i < 3; ++i) {
    if (inertia[i] < inertia[lo]) lo = i;
    if (inertia[i] > inertia[hi]) hi = i;
  }
  const int mid = 3 - lo - hi, a = m2 > e2 * inertia[mid] ? hi : lo;
  const size_t n = steps ? steps : 20000;
  const double h = t / (double)n;
  double y[4] = {pi[0], pi[1], pi[2], 0.0}, k[4][4], tmp[4];
  for (size_t s = 0; s < n; ++s) {
    euler_rhs(inertia, a, y, k[0]);
    for (int i = 0; i < 4; ++i) tmp[i] = y[i] + 0.5 * h * k[0][i];
    euler_rhs(inertia, a, tmp, k[1]);
    for (int i = 0; i < 4; ++i) tmp[i] = y[i] + 0.5 * h * k[1][i];
    euler_rhs(inertia, a, tmp, k[2]);
    for (int i = 0; i < 4; ++i) tmp[i] = y[i] + h * k[2][i];
    euler_rhs(inertia, a, tmp, k[3]);
    for (int i = 0; i < 4; ++i) y[i] += h / 6.0 * (k[0][i] + 2 * k[1][i] + 2 * k[2][i] + k[3][i]);
  }
  /* orient by the encircled direction: seen from the tip of sign(Π_a) e_a */
  const double lambda = pi[a] >= 0.0 ? y[3] : -y[3];
  if (period) *period = t;
  if (dynamic) *dynamic = e2 * t / sqrt(m2); /* 2E T/‖m‖, 2E = Σ Π²/I */
  if (solid_angle) *solid_angle = lambda;
  return GM_OK;
}
