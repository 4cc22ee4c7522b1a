/* KdV u_t + u u_x + u_xxx = 0: the equation in multisymplectic form (Ascher & McLachlan,
 * Appl. Numer. Math. 48 (2004) §2; Bridges & Reich 2001), its gauge-free invariants, and the
 * Zabusky–Kruskal scheme (Zabusky & Kruskal, Phys. Rev. Lett. 15 (1965) 240, eq. 2):
 *   u_i^{n+1} = u_i^{n−1} − (Δt/3Δx)(u_{i+1} + u_i + u_{i−1})(u_{i+1} − u_{i−1})
 *               − (Δt/Δx³)(u_{i+2} − 2u_{i+1} + 2u_{i−1} − u_{i−2})      (all at level n),
 * explicit leapfrog, second order in t and x, stable for
 *   Δt (3√3/(2Δx³) + max|u|/Δx) <= 1
 * (von Neumann on the linearisation about max|u|: the symbol of the u_xxx stencil is
 * |2 sin θ − sin 2θ|/Δx³ <= 3√3/(2Δx³), that of the convective term max|u| |sin θ|/Δx). */
#include <math.h>
#include <string.h>

#include "pde/internal.h"

/* ---- the equation: s = (φ, u, v, w) --------------------------------------------------------- */
static double kdv_S(const double *s, const void *ctx) {
  (void)ctx;
  return 0.5 * s[2] * s[2] - s[1] * s[3] + s[1] * s[1] * s[1] / 6.0;
}
static void kdv_grad(const double *s, double *g, const void *ctx) {
  (void)ctx;
  g[0] = 0.0;
  g[1] = -s[3] + 0.5 * s[1] * s[1];
  g[2] = s[2];
  g[3] = -s[1];
}
static void kdv_hess(const double *s, double *H, const void *ctx) {
  (void)ctx;
  for (int k = 0; k < 16; k++) H[k] = 0.0;
  H[1 * 4 + 1] = s[1];
  H[1 * 4 + 3] = H[3 * 4 + 1] = -1.0;
  H[2 * 4 + 2] = 1.0;
}

gm_pde_equation gm_pde_kdv(void) {
  gm_pde_equation e = {0};
  e.name = "kdv";
  e.dim = 4;
  /* rows (φ, u, v, w): ½u_t + w_x = 0; −½φ_t − v_x = −w + ½u²; u_x = v; −φ_x = −u */
  e.W[0 * 4 + 1] = 0.5;
  e.W[1 * 4 + 0] = -0.5;
  e.K[0 * 4 + 3] = 1.0;
  e.K[3 * 4 + 0] = -1.0;
  e.K[1 * 4 + 2] = -1.0;
  e.K[2 * 4 + 1] = 1.0;
  e.S = kdv_S;
  e.gradient = kdv_grad;
  e.hessian = kdv_hess;
  e.has_gauge = 1;
  e.gauge_phi = 0;
  e.gauge_u = 1;
  e.is_kdv = 1;
  return e;
}

/* ---- invariants from u alone ------------------------------------------------------------- */
static double u_of(const gm_pde *p, size_t i) {
  size_t n = p->n;
  return p->s[(i % n) * p->d + p->eq.gauge_u];
}

double gm_pde_mass(const gm_pde *p) {
  if (p == NULL || !p->eq.has_gauge) return NAN;
  double m = 0.0;
  for (size_t i = 0; i < p->n; i++)
    m += p->scheme->kind == GM_PDE_KDV_ZK ? u_of(p, i) : 0.5 * (u_of(p, i) + u_of(p, i + 1));
  return p->grid.h * m;
}

double gm_pde_kdv_energy(const gm_pde *p) {
  double e = 0.0, h = p->grid.h;
  for (size_t i = 0; i < p->n; i++) {
    double u = u_of(p, i), ux = (u_of(p, i + 1) - u) / h;
    e += u * u * u / 6.0 - 0.5 * ux * ux;
  }
  return h * e;
}

double gm_pde_kdv_momentum(const gm_pde *p) {
  double m = 0.0;
  for (size_t i = 0; i < p->n; i++) m += 0.5 * u_of(p, i) * u_of(p, i);
  return p->grid.h * m;
}

/* ---- Zabusky–Kruskal ------------------------------------------------------------------------ */
/* the right-hand side of the semi-discretisation u_t = f(u) whose leapfrog is ZK */
static void zk_rhs(const gm_pde *p, const double *u, double *f) {
  size_t n = p->n;
  double h = p->grid.h;
  for (size_t i = 0; i < n; i++) {
    double um2 = u[(i + n - 2) % n], um1 = u[(i + n - 1) % n], u0 = u[i];
    double up1 = u[(i + 1) % n], up2 = u[(i + 2) % n];
    f[i] = -(up1 + u0 + um1) * (up1 - um1) / (6.0 * h) -
           (up2 - 2.0 * up1 + 2.0 * um1 - um2) / (2.0 * h * h * h);
  }
}

double gm_pde_zk_bound(const gm_pde_grid *g, double umax) {
  double h = g->h;
  return 1.0 / (1.5 * sqrt(3.0) / (h * h * h) + umax / h);
}

/* φ (trapezoidal integral of u from φ₀, with the grid's twist closing the ring), v = δ_x⁰u,
 * w = u_xx + u²/2 (the gauge φ_t = 0) — only u is the scheme's state. */
void gm_pde_zk_fill_state(gm_pde *p) {
  size_t n = p->n, d = p->d, a = p->eq.gauge_u, f = p->eq.gauge_phi;
  double h = p->grid.h, phi = p->s[f];
  for (size_t i = 0; i < n; i++) {
    double um = p->u[(i + n - 1) % n], u0 = p->u[i], up = p->u[(i + 1) % n];
    double *si = p->s + i * d;
    si[f] = phi;
    si[a] = u0;
    if (d == 4) {
      size_t v = 2, w = 3;
      si[v] = (up - um) / (2.0 * h);
      si[w] = (up - 2.0 * u0 + um) / (h * h) + 0.5 * u0 * u0;
    }
    phi += 0.5 * h * (u0 + up);
  }
}

/* u⁻¹ by one midpoint-RK2 step of length −Δt (local error O(Δt³), so ZK stays second order) */
gm_status gm_pde_zk_start(gm_pde *p, gm_error *err) {
  size_t n = p->n;
  double dt = p->opt.dt;
  for (size_t i = 0; i < n; i++) p->u[i] = p->s[i * p->d + p->eq.gauge_u];
  zk_rhs(p, p->u, p->F);
  for (size_t i = 0; i < n; i++) p->u_new[i] = p->u[i] - 0.5 * dt * p->F[i];
  zk_rhs(p, p->u_new, p->F);
  for (size_t i = 0; i < n; i++) {
    p->u_prev[i] = p->u[i] - dt * p->F[i];
    if (!isfinite(p->u_prev[i]))
      return gm_error_set(err, GM_EDOMAIN, "pde zk: non-finite start value at point %zu", i);
  }
  gm_pde_zk_fill_state(p);
  return GM_OK;
}

gm_status gm_pde_zk_step(gm_pde *p, gm_error *err) {
  size_t n = p->n;
  double dt = p->opt.dt;
  zk_rhs(p, p->u, p->F);
  for (size_t i = 0; i < n; i++) {
    p->u_new[i] = p->u_prev[i] + 2.0 * dt * p->F[i];
    if (!isfinite(p->u_new[i]))
      return gm_error_set(err, GM_EDOMAIN, "pde zk: the state became non-finite at step %zu "
                          "(point %zu)", p->steps + 1, i);
  }
  double *t = p->u_prev;
  p->u_prev = p->u;
  p->u = p->u_new;
  p->u_new = t;
  gm_pde_zk_fill_state(p);
  return GM_OK;
}
