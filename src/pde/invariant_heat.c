/* The heat equation u_t = ν u_xx with the scaling group (t, x, u) ↦ (e^{2a}t, e^{a}x, u), seed
 * 004's first illustration of invariant schemes (notes/003-004 §2.4: FTCS on an orthogonal
 * regular mesh). FTCS is already invariant under this group when the mesh scales with it;
 * invariantizing it through the frame that normalises the spacing to 1 must give the same
 * scheme (a test) — the second user of the general piece, after Burgers. */
#include <math.h>
#include <stdio.h>

#include "pde/invariant_internal.h"

/* (u^{n+1}_j − uⁿ_j)/k − ν D₂uⁿ = 0 (notes §2.4). */
static double heat_ftcs_residual(const gm_inv_stencil *m, double nu, double dn[3]) {
  double k = m->next[1].t - m->old[1].t;
  dn[0] = dn[2] = 0.0;
  dn[1] = 1.0 / k;
  return (m->next[1].u - m->old[1].u) / k - nu * gm_inv_d2(m->old);
}

/* von Neumann: 2νk/h² ≤ 1. */
static double heat_ftcs_bound(double h, double umax, double nu) {
  (void)umax;
  return nu > 0.0 ? h * h / (2.0 * nu) : INFINITY;
}

const gm_inv_scheme gm_inv_heat_ftcs = {"heat-ftcs", "heat", 1, heat_ftcs_residual,
                                        heat_ftcs_bound, "k <= h^2/(2 nu)",
                                        "notes/003-004 §2.4 (seed 004)"};

/* g(a) = scaling(a₃)∘g₂(a₂)∘g₁(a₁). */
static int heat_act(const double *a, gm_inv_point p, gm_inv_point *out, double *du) {
  double e = exp(a[2]);
  *out = (gm_inv_point){e * e * (p.t + a[0]), e * (p.x + a[1]), p.u};
  if (du != NULL) *du = 1.0;
  return 0;
}

static int heat_act_inverse(const double *a, gm_inv_point p, gm_inv_point *out, double *du) {
  double e = exp(-a[2]);
  *out = (gm_inv_point){e * e * p.t - a[0], e * p.x - a[1], p.u};
  if (du != NULL) *du = 1.0;
  return 0;
}

/* Cross-section {tⁿ_j = 0, xⁿ_j = 0, ½(x_{j+1} − x_{j−1}) = 1}. */
static int heat_frame(const gm_inv_stencil *m, double *a, char *why, size_t cap) {
  double w = 0.5 * (m->old[2].x - m->old[0].x);
  if (!(w > 0.0) || !isfinite(w)) {
    snprintf(why, cap, "the layer's spacing %g is not positive", w);
    return 1;
  }
  a[0] = -m->old[1].t;
  a[1] = -m->old[1].x;
  a[2] = -log(w);
  return 0;
}

const gm_inv_group gm_inv_heat_scaling = {
    "heat-scaling", "heat", 3, "a1 (time), a2 (space), a3 (scaling)", heat_act,
    heat_act_inverse, heat_frame, "notes/003-004 §2.4 (the seed's heat illustration)"};

double gm_inv_heat_kernel_u(double t, double x, const void *ctx) {
  const gm_inv_heat_kernel *h = ctx;
  double tau = t + h->t0;
  return exp(-x * x / (4.0 * h->nu * tau)) / sqrt(tau);
}
