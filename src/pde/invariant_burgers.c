/* Burgers' equation u_t + u u_x = ν u_xx: the standard FTCS, Lax–Wendroff and Crank–Nicolson
 * residuals, its symmetry group G₀ = {g₁, g₂, g₄, g₅} with the moving frame of docs/pde.md, and
 * two exact solutions. The symmetries are notes/003-004 §2.4 (seed 004 "Invariant
 * integrators", g₁–g₅); the frame's normalisation a₁ = −tⁿ_j, a₂ = −xⁿ_j is the seed's; the
 * choice of a₄, a₅ is derived in docs/pde.md (§ "Invariant schemes", the cross-section
 * {t = 0, x = 0, σ = 0, D₁u = 0}) and agrees with the seed's summary of Chhay & Hamdouni (2010):
 * a₅ drops out on an orthogonal mesh, and with a₄ the convective term vanishes. */
#include <math.h>
#include <stdio.h>

#include "pde/invariant_internal.h"

/* ---- schemes in standard form (they read k and the spacings only) --------------------------- */

/* FTCS, notes §2.4: (u^{n+1}_j − uⁿ_j)/k + uⁿ_j D₁uⁿ − ν D₂uⁿ = 0. */
static double ftcs_residual(const gm_inv_stencil *m, double nu, double dn[3]) {
  double k = m->next[1].t - m->old[1].t;
  dn[0] = dn[2] = 0.0;
  dn[1] = 1.0 / k;
  return (m->next[1].u - m->old[1].u) / k + m->old[1].u * gm_inv_d1(m->old) -
         nu * gm_inv_d2(m->old);
}

/* FTCS for the frozen-coefficient u_t + c u_x = ν u_xx is stable iff C² ≤ 2d ≤ 1, C = ck/h,
 * d = νk/h² (Hindmarsh, Gresho & Griffiths, Int. J. Numer. Meth. Fluids 4 (1984) 853), that is
 * k ≤ min(h²/(2ν), 2ν/c²). */
static double ftcs_bound(double h, double umax, double nu) {
  double b = nu > 0.0 ? h * h / (2.0 * nu) : INFINITY;
  if (umax > 0.0) b = fmin(b, 2.0 * nu / (umax * umax));
  return b;
}

/* Lax–Wendroff in conservation form for the flux f = u²/2 (Lax & Wendroff, Comm. Pure Appl.
 * Math. 13 (1960) 217; the Jacobian A = f'(u) averaged on the half points) with the centred
 * viscous term of FTCS: (u^{n+1} − uⁿ)/k + (f₊ − f₋)/(x₊ − x₋)
 * − k[A₊(f₊ − f₀)/h₊ − A₋(f₀ − f₋)/h₋]/(h₊ + h₋) − ν D₂uⁿ = 0, A± = ½(u₀ + u±). The k²u_tt
 * term covers the convection only, so the scheme is first order in k when ν > 0. */
static double lw_residual(const gm_inv_stencil *m, double nu, double dn[3]) {
  const gm_inv_point *p = m->old;
  double k = m->next[1].t - p[1].t;
  double hm = p[1].x - p[0].x, hp = p[2].x - p[1].x;
  double fm = 0.5 * p[0].u * p[0].u, f0 = 0.5 * p[1].u * p[1].u, fp = 0.5 * p[2].u * p[2].u;
  double Am = 0.5 * (p[1].u + p[0].u), Ap = 0.5 * (p[1].u + p[2].u);
  dn[0] = dn[2] = 0.0;
  dn[1] = 1.0 / k;
  return (m->next[1].u - p[1].u) / k + (fp - fm) / (hp + hm) -
         k * (Ap * (fp - f0) / hp - Am * (f0 - fm) / hm) / (hp + hm) - nu * gm_inv_d2(p);
}

/* LW is FTCS with the diffusion ν + ½c²k, so the FTCS condition becomes c²k² + 2νk ≤ h²
 * (Hindmarsh et al. 1984 §3): k ≤ h²/(ν + √(ν² + c²h²)). */
static double lw_bound(double h, double umax, double nu) {
  double b = h * h / (nu + sqrt(nu * nu + umax * umax * h * h));
  return isfinite(b) ? b : INFINITY;
}

/* Crank–Nicolson: the trapezoidal average of the FTCS space operator on both layers,
 * (u^{n+1}_j − uⁿ_j)/k + ½[u D₁u − ν D₂u]ⁿ + ½[u D₁u − ν D₂u]^{n+1} = 0 (Crank & Nicolson, Proc.
 * Camb. Phil. Soc. 43 (1947) 50; one of the three schemes of the seed's Test 1). */
static double cn_residual(const gm_inv_stencil *m, double nu, double dn[3]) {
  const gm_inv_point *o = m->old, *q = m->next;
  double k = q[1].t - o[1].t;
  double Hm = q[1].x - q[0].x, Hp = q[2].x - q[1].x, W = q[2].x - q[0].x;
  double d1n = gm_inv_d1(q);
  dn[0] = 0.5 * (-q[1].u / W - nu * 2.0 / (Hm * (Hp + Hm)));
  dn[1] = 1.0 / k + 0.5 * (d1n + nu * 2.0 * (1.0 / Hp + 1.0 / Hm) / (Hp + Hm));
  dn[2] = 0.5 * (q[1].u / W - nu * 2.0 / (Hp * (Hp + Hm)));
  return (q[1].u - o[1].u) / k + 0.5 * (o[1].u * gm_inv_d1(o) - nu * gm_inv_d2(o)) +
         0.5 * (q[1].u * d1n - nu * gm_inv_d2(q));
}

/* Trapezoidal in time, centred in space: A-stable for the frozen-coefficient problem. */
static double cn_bound(double h, double umax, double nu) {
  (void)h, (void)umax, (void)nu;
  return INFINITY;
}

const gm_inv_scheme gm_inv_ftcs = {
    "ftcs", "burgers", 1, ftcs_residual, ftcs_bound, "k <= min(h^2/(2 nu), 2 nu/max|u|^2)",
    "notes/003-004 §2.4 (seed 004); Hindmarsh, Gresho & Griffiths 1984 for the bound"};
const gm_inv_scheme gm_inv_lax_wendroff = {
    "lax-wendroff", "burgers", 1, lw_residual, lw_bound,
    "max|u|^2 k^2 + 2 nu k <= h^2", "Lax & Wendroff 1960, viscous term centred"};
const gm_inv_scheme gm_inv_crank_nicolson = {
    "crank-nicolson", "burgers", 0, cn_residual, cn_bound, "unconditionally stable",
    "Crank & Nicolson 1947; seed 004 Test 1"};

/* ---- the group G₀ and its frame ------------------------------------------------------------- */

/* g(a) = g₄(a₄)∘g₅(a₅)∘g₂(a₂)∘g₁(a₁), a = (a₁, a₂, a₄, a₅); the one-parameter groups of notes
 * §2.4: g₁ (t + a₁), g₂ (x + a₂), g₅ (t, x + a₅t, u + a₅), g₄ (t/(1−a₄t), x/(1−a₄t),
 * (1−a₄t)u + a₄x). */
static int g0_act(const double *a, gm_inv_point p, gm_inv_point *out, double *du) {
  double t = p.t + a[0], x = p.x + a[1];
  x += a[3] * t;
  double u = p.u + a[3];
  double s = 1.0 - a[2] * t;
  if (!(s > 0.0)) return 1;
  *out = (gm_inv_point){t / s, x / s, s * u + a[2] * x};
  if (du != NULL) *du = s;
  return 0;
}

/* g(a)⁻¹ = g₁(−a₁)∘g₂(−a₂)∘g₅(−a₅)∘g₄(−a₄). */
static int g0_act_inverse(const double *a, gm_inv_point p, gm_inv_point *out, double *du) {
  double s = 1.0 + a[2] * p.t;
  if (!(s > 0.0)) return 1;
  double t = p.t / s, x = p.x / s, u = s * p.u - a[2] * p.x;
  x -= a[3] * t;
  u -= a[3];
  *out = (gm_inv_point){t - a[0], x - a[1], u};
  if (du != NULL) *du = s;
  return 0;
}

/* The cross-section {tⁿ_j = 0, xⁿ_j = 0, σ = 0, D₁uⁿ = 0} (docs/pde.md): translate the centre to
 * the origin (the seed's a₁ = −tⁿ_j, a₂ = −xⁿ_j), boost by a₅ = −σ/k so that x^{n+1}_j sits
 * above it, then project with a₄ = −D₁uⁿ: at t = 0 the projection leaves x alone and adds a₄x
 * to u, so the slope becomes 0; the new layer moves to t̂ = k/(1 + kD₁uⁿ), which needs
 * 1 + kD₁uⁿ > 0 — where it fails, the frame does not exist. */
static int g0_frame(const gm_inv_stencil *m, double *a, char *why, size_t cap) {
  const gm_inv_point *o = m->old;
  double k = m->next[1].t - o[1].t, sigma = m->next[1].x - o[1].x;
  if (!(k > 0.0)) {
    snprintf(why, cap, "the new layer is not later (k = %g)", k);
    return 1;
  }
  if (!(o[2].x > o[1].x && o[1].x > o[0].x)) {
    snprintf(why, cap, "the layer's points are not increasing");
    return 1;
  }
  double d1 = gm_inv_d1(o); /* the boost and translations leave D₁u unchanged */
  if (!(1.0 + k * d1 > 0.0)) {
    snprintf(why, cap, "1 + k u_x = %.6g <= 0 (k = %.6g, centred u_x = %.6g): the projection "
             "normalising u_x to 0 would send the new layer through t = infinity", 1.0 + k * d1,
             k, d1);
    return 1;
  }
  a[0] = -o[1].t;
  a[1] = -o[1].x;
  a[2] = -d1;
  a[3] = -sigma / k;
  return 0;
}

const gm_inv_group gm_inv_burgers_g0 = {
    "burgers-g0", "burgers", 4, "a1 (time), a2 (space), a4 (projection), a5 (Galilean boost)",
    g0_act, g0_act_inverse, g0_frame,
    "notes/003-004 §2.4 (g1, g2, g4, g5); frame derived in docs/pde.md"};

/* ---- exact solutions ------------------------------------------------------------------------ */
double gm_inv_burgers_front(double t, double x, const void *ctx) {
  const gm_inv_front *f = ctx;
  double s = 0.5 * (f->u_left + f->u_right), d = f->u_left - f->u_right;
  return s - 0.5 * d * tanh(d * (x - f->x0 - s * t) / (4.0 * f->nu));
}

double gm_inv_burgers_shock(double t, double x, const void *ctx) {
  const gm_inv_shock *s = ctx;
  double tau = t + s->t0;
  return (x - s->A * tanh(s->A * x / (2.0 * s->nu * tau))) / tau;
}
