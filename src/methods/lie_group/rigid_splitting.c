/* Explicit symplectic splitting of a rigid body with principal axes as body frame (diagonal
 * J = diag(I1, I2, I3)): H = Σ_a Π_a²/(2 I_a) + |p|²/(2m) + V(R, x). Each piece has an exact
 * flow: under Π_a²/(2I_a) the body turns about its axis a at the constant rate ω = Π_a/I_a,
 * R ← R exp(tω ê_a), Π ← exp(−tω ê_a) Π (McLachlan, Phys. Rev. Lett. 71 (1993) 3043; Touma &
 * Wisdom, Astron. J. 107 (1994) 1189; Reich (1994)); under V, R and x stay and Π ← Π − t g,
 * p ← p − t ∂V/∂x (Dullweber, Leimkuhler & McLachlan, J. Chem. Phys. 107 (1997) 5840). One step
 * is the symmetric (Strang) composition
 *   kick(h/2) · drift_x(h) · rot₁(h/2) rot₂(h/2) rot₃(h) rot₂(h/2) rot₁(h/2) · kick(h/2):
 * order 2, symplectic, time reversible; each rotation keeps |Π| and R Π exactly. */
#include <math.h>
#include <string.h>

#include "methods/lie_group/lie_group.h"

/* Turn about body axis a by ω = τ Π_a/I_a: Π ← exp(−ω ê_a) Π, E ← (I + E) exp(ω ê_a) − I. */
static void rotate_about_axis(const gm_lie_work *w, int a, double tau, double *pi, double e[9]) {
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const double omega = tau * pi[a] / w->j[4 * a];
  const double s = sin(omega), cm1 = -2.0 * sin(0.5 * omega) * sin(0.5 * omega); /* cos − 1 */
  const double pb = pi[b], pc = pi[c];
  pi[b] = pb + cm1 * pb + s * pc;
  pi[c] = pc + cm1 * pc - s * pb;
  /* (I + E) Rot_a(ω) − I: columns b, c of (I + E) turn, E_col = M_col − I_col */
  for (int r = 0; r < 3; ++r) {
    const double mb = e[3 * r + b] + (r == b), mc = e[3 * r + c] + (r == c);
    /* new col b = cos ω col b + sin ω col c, new col c = −sin ω col b + cos ω col c */
    e[3 * r + b] = e[3 * r + b] + cm1 * mb + s * mc;
    e[3 * r + c] = e[3 * r + c] + cm1 * mc - s * mb;
  }
}

static gm_status kick(gm_integrator *it, const gm_lie_work *w, double t, double tau,
                      const double *r, const double *x, double *pi, double *p) {
  double g[3], fx[3];
  gm_status st = gm_lie_gradient(it, t, r, w->nt ? x : NULL, g, fx);
  if (st != GM_OK) return st;
  for (int c = 0; c < 3; ++c) pi[c] -= tau * g[c];
  if (w->nt)
    for (int c = 0; c < 3; ++c) p[c] -= tau * fx[c];
  return GM_OK;
}

gm_status gm_rigid_splitting_step(gm_integrator *it, double t, double h, const double *y,
                                  double *y_new, double e[9]) {
  gm_lie_work *w = it->work;
  const size_t nt = w->nt, pi = w->pi;
  const int free_body = it->problem->rigid_potential_gradient == NULL;
  memcpy(y_new + 9, y + 9, (it->n - 9) * sizeof *y);
  gm_status st = GM_OK;
  if (!free_body) st = kick(it, w, t, 0.5 * h, y, y + 9, y_new + pi, y_new + pi + 3);
  if (st != GM_OK) return st;
  if (nt)
    for (int c = 0; c < 3; ++c) y_new[9 + c] += h * y_new[pi + 3 + c] / w->mass;
  memset(e, 0, 9 * sizeof *e);
  rotate_about_axis(w, 0, 0.5 * h, y_new + pi, e);
  rotate_about_axis(w, 1, 0.5 * h, y_new + pi, e);
  rotate_about_axis(w, 2, h, y_new + pi, e);
  rotate_about_axis(w, 1, 0.5 * h, y_new + pi, e);
  rotate_about_axis(w, 0, 0.5 * h, y_new + pi, e);
  if (!free_body) {
    double r[9];
    gm_mat3_mul(y, e, r);
    for (int k = 0; k < 9; ++k) r[k] += y[k];
    st = kick(it, w, t + h, 0.5 * h, r, y_new + 9, y_new + pi, y_new + pi + 3);
  }
  return st;
}
