/* The vector box schemes for 𝕎 s_t + 𝕂 s_x = ∇S(s) on a periodic grid: Preissmann box
 * (multisymplectic midpoint) and Euler box, each a Newton solve per step on the whole ring with
 * the banded LU of band.c, and the tangent variations that check the discrete multisymplectic
 * conservation law cell by cell. */
#include <math.h>
#include <string.h>

#include "pde/internal.h"

/* the Euler box's rows of 𝕎₊ that are non-zero ("P" rows: they take the time step) */
static int wp_row(const gm_pde *p, size_t a) {
  for (size_t b = 0; b < p->d; b++)
    if (p->Wp[a * p->d + b] != 0.0) return 1;
  return 0;
}

/* the row replaced by the gauge condition φ₀ⁿ⁺¹ = φ₀ⁿ (equations with a potential) */
static int gauge_row(const gm_pde *p, size_t i, size_t a) {
  return p->eq.has_gauge && i == 0 && a == p->eq.gauge_phi;
}

/* band(row block i, column block j) += c·M (d×d, row-major) */
static void add_block(gm_pde *p, size_t i, size_t j, const double *M, double c) {
  size_t d = p->d;
  for (size_t a = 0; a < d; a++)
    for (size_t b = 0; b < d; b++)
      if (!gauge_row(p, i, a))
      if (M[a * d + b] != 0.0)
        gm_band_add(&p->band, p->pos[i] * d + a, p->pos[j] * d + b, c * M[a * d + b]);
}
/* only the rows a with rows[a] == sel */
static void add_block_rows(gm_pde *p, size_t i, size_t j, const double *M, double c, int sel) {
  size_t d = p->d;
  for (size_t a = 0; a < d; a++) {
    if (wp_row(p, a) != sel) continue;
    for (size_t b = 0; b < d; b++)
      if (M[a * d + b] != 0.0)
        gm_band_add(&p->band, p->pos[i] * d + a, p->pos[j] * d + b, c * M[a * d + b]);
  }
}

static void matvec_add(size_t d, const double *M, double c, const double *x, double *y) {
  for (size_t a = 0; a < d; a++) {
    double s = 0.0;
    for (size_t b = 0; b < d; b++) s += M[a * d + b] * x[b];
    y[a] += c * s;
  }
}

static double bilin(size_t d, const double *x, const double *M, const double *y) {
  double s = 0.0;
  for (size_t a = 0; a < d; a++)
    for (size_t b = 0; b < d; b++) s += x[a] * M[a * d + b] * y[b];
  return s;
}

/* ---- Preissmann:
 *   F_i = 𝕎(s̄ⁿ⁺¹ − s̄ⁿ)_{i+½}/Δt + 𝕂(s^{n+½}_{i+1} − s^{n+½}_i)/Δx − ∇S(s^{n+½}_{i+½})
 * (notes/003-004 §2.2 [R]; Bridges & Reich 2001) ------------------------------------------- */
static void preissmann_residual(gm_pde *p, const double *x, double *F) {
  size_t n = p->n, d = p->d;
  double dt = p->opt.dt, h = p->grid.h;
  double *m = p->work, *g = p->work + d;
  for (size_t i = 0; i < n; i++) {
    size_t j = (i + 1) % n;
    (void)j;
    double xj[GM_PDE_MAX_DIM], sj[GM_PDE_MAX_DIM];
    const double *xi = x + i * d, *si = p->s + i * d;
    for (size_t a = 0; a < d; a++) {
      xj[a] = gm_pde_at(p, x, i, 1, a);
      sj[a] = gm_pde_at(p, p->s, i, 1, a);
    }
    for (size_t a = 0; a < d; a++) m[a] = 0.25 * (xi[a] + xj[a] + si[a] + sj[a]);
    p->eq.gradient(m, g, p->eq.params);
    p->stats.gradient_evaluations++;
    double *Fi = F + i * d;
    for (size_t a = 0; a < d; a++) Fi[a] = -g[a];
    double tdiff[GM_PDE_MAX_DIM], xdiff[GM_PDE_MAX_DIM];
    for (size_t a = 0; a < d; a++) {
      tdiff[a] = 0.5 * ((xi[a] + xj[a]) - (si[a] + sj[a])) / dt;
      xdiff[a] = 0.5 * ((xj[a] + sj[a]) - (xi[a] + si[a])) / h;
    }
    matvec_add(d, p->eq.W, 1.0, tdiff, Fi);
    matvec_add(d, p->eq.K, 1.0, xdiff, Fi);
  }
  /* KdV-like equations: the φ row at point 0 is implied by the others (the sum of the w rows
   * minus Δt times the sum of the φ rows vanishes identically once h Σ ū = twist, which
   * create checks and the scheme keeps); it is replaced by the gauge φ₀ⁿ⁺¹ = φ₀ⁿ */
  if (p->eq.has_gauge) F[p->eq.gauge_phi] = x[p->eq.gauge_phi] - p->s[p->eq.gauge_phi];
  if (gm_pde_dirichlet(p)) {
    /* no cell n−1: its d rows hold the Dirichlet components, xᵃ = sᵃ at the ends */
    size_t k = 0, nd = (n - 1) * d;
    for (size_t a = 0; a < d; a++)
      if (p->opt.dirichlet_left & (1u << a)) F[nd + k++] = x[a] - p->s[a];
    for (size_t a = 0; a < d; a++)
      if (p->opt.dirichlet_right & (1u << a)) F[nd + k++] = x[nd + a] - p->s[nd + a];
  }
}

/* the Dirichlet rows of block n−1 in the Newton matrix (identity on the held components) */
static void dirichlet_rows(gm_pde *p) {
  size_t n = p->n, d = p->d, k = 0;
  for (size_t a = 0; a < d; a++)
    if (p->opt.dirichlet_left & (1u << a))
      gm_band_add(&p->band, p->pos[n - 1] * d + k++, p->pos[0] * d + a, 1.0);
  for (size_t a = 0; a < d; a++)
    if (p->opt.dirichlet_right & (1u << a))
      gm_band_add(&p->band, p->pos[n - 1] * d + k++, p->pos[n - 1] * d + a, 1.0);
}

/* Hessians at the cell midpoints into p->hess, then the Newton matrix ∂F/∂sⁿ⁺¹ (factored) */
static gm_status preissmann_jacobian(gm_pde *p, const double *x) {
  size_t n = p->n, d = p->d;
  double dt = p->opt.dt, h = p->grid.h;
  double *m = p->work;
  gm_band_zero(&p->band);
  for (size_t i = 0; i < n; i++) {
    size_t j = (i + 1) % n;
    if (i == n - 1 && gm_pde_dirichlet(p)) {
      dirichlet_rows(p);
      break;
    }
    for (size_t a = 0; a < d; a++)
      m[a] = 0.25 * (x[i * d + a] + gm_pde_at(p, x, i, 1, a) + p->s[i * d + a] +
                     gm_pde_at(p, p->s, i, 1, a));
    double *H = p->hess + i * d * d;
    gm_pde_hessian(p, m, H, p->work + d);
    add_block(p, i, i, p->eq.W, 0.5 / dt);
    add_block(p, i, i, p->eq.K, -0.5 / h);
    add_block(p, i, i, H, -0.25);
    add_block(p, i, j, p->eq.W, 0.5 / dt);
    add_block(p, i, j, p->eq.K, 0.5 / h);
    add_block(p, i, j, H, -0.25);
  }
  if (p->eq.has_gauge) gm_band_add(&p->band, p->pos[0] * d + p->eq.gauge_phi,
                                   p->pos[0] * d + p->eq.gauge_phi, 1.0);
  p->stats.factorizations++;
  return gm_band_factor(&p->band);
}

/* ---- Euler box (notes/003-004 §2.2 [R]): at point i,
 *   𝕎₊(sⁿ⁺¹ − sⁿ)/Δt + 𝕎₋(sⁿ − sⁿ⁻¹)/Δt + 𝕂₊(sⁿ_{i+1} − sⁿ_i)/Δx + 𝕂₋(sⁿ_i − sⁿ_{i−1})/Δx
 *     = ∇S(sⁿ_i).
 * Only the rows where 𝕎₊ ≠ 0 ("P") contain sⁿ⁺¹; the other rows ("Z") are equations at level
 * n + 1 alone. A step therefore solves for sⁿ⁺¹ the P rows at level n and the Z rows at
 * level n + 1, and the full scheme holds at every level n >= 1. -------------------------- */
static void euler_residual(gm_pde *p, const double *x, double *F) {
  size_t n = p->n, d = p->d;
  double dt = p->opt.dt, h = p->grid.h;
  double *gs = p->work, *gx = p->work + d, *t = p->work + 2 * d;
  for (size_t i = 0; i < n; i++) {
    const double *xi = x + i * d, *si = p->s + i * d, *sp = p->s_prev + i * d;
    double *Fi = F + i * d;
    p->eq.gradient(si, gs, p->eq.params);
    p->eq.gradient(xi, gx, p->eq.params);
    p->stats.gradient_evaluations += 2;
    double rp[GM_PDE_MAX_DIM] = {0}, rz[GM_PDE_MAX_DIM] = {0};
    /* P rows at level n */
    for (size_t a = 0; a < d; a++) t[a] = (xi[a] - si[a]) / dt;
    matvec_add(d, p->Wp, 1.0, t, rp);
    for (size_t a = 0; a < d; a++) t[a] = (si[a] - sp[a]) / dt;
    matvec_add(d, p->Wm, 1.0, t, rp);
    for (size_t a = 0; a < d; a++) t[a] = (gm_pde_at(p, p->s, i, 1, a) - si[a]) / h;
    matvec_add(d, p->Kp, 1.0, t, rp);
    for (size_t a = 0; a < d; a++) t[a] = (si[a] - gm_pde_at(p, p->s, i, -1, a)) / h;
    matvec_add(d, p->Km, 1.0, t, rp);
    /* Z rows at level n + 1 (𝕎₊ rows vanish there) */
    for (size_t a = 0; a < d; a++) t[a] = (xi[a] - si[a]) / dt;
    matvec_add(d, p->Wm, 1.0, t, rz);
    for (size_t a = 0; a < d; a++) t[a] = (gm_pde_at(p, x, i, 1, a) - xi[a]) / h;
    matvec_add(d, p->Kp, 1.0, t, rz);
    for (size_t a = 0; a < d; a++) t[a] = (xi[a] - gm_pde_at(p, x, i, -1, a)) / h;
    matvec_add(d, p->Km, 1.0, t, rz);
    for (size_t a = 0; a < d; a++) Fi[a] = wp_row(p, a) ? rp[a] - gs[a] : rz[a] - gx[a];
  }
}

/* Newton matrix of the Euler box; p->hess holds H(sⁿ⁺¹_i) afterwards */
static gm_status euler_jacobian(gm_pde *p, const double *x) {
  size_t n = p->n, d = p->d;
  double dt = p->opt.dt, h = p->grid.h;
  gm_band_zero(&p->band);
  for (size_t i = 0; i < n; i++) {
    size_t ip = (i + 1) % n, im = (i + n - 1) % n;
    double *H = p->hess + i * d * d;
    gm_pde_hessian(p, x + i * d, H, p->work);
    add_block_rows(p, i, i, p->Wp, 1.0 / dt, 1);
    add_block_rows(p, i, i, p->Wm, 1.0 / dt, 0);
    add_block_rows(p, i, i, p->Kp, -1.0 / h, 0);
    add_block_rows(p, i, i, p->Km, 1.0 / h, 0);
    add_block_rows(p, i, i, H, -1.0, 0);
    add_block_rows(p, i, ip, p->Kp, 1.0 / h, 0);
    add_block_rows(p, i, im, p->Km, -1.0 / h, 0);
  }
  p->stats.factorizations++;
  return gm_band_factor(&p->band);
}

static double maxabs(const double *x, size_t n) {
  double m = 0.0;
  for (size_t k = 0; k < n; k++)
    if (fabs(x[k]) > m || isnan(x[k])) m = isnan(x[k]) ? NAN : fabs(x[k]);
  return m;
}

/* solve J dx = −F with the factored band (natural ↔ interleaved order) into p->dx */
static void band_solve_natural(gm_pde *p, const double *rhs, double *out) {
  size_t n = p->n, d = p->d;
  double *b = p->dx;
  for (size_t i = 0; i < n; i++)
    for (size_t a = 0; a < d; a++) b[p->pos[i] * d + a] = rhs[i * d + a];
  gm_band_solve(&p->band, b);
  for (size_t i = 0; i < n; i++)
    for (size_t a = 0; a < d; a++) out[i * d + a] = b[p->pos[i] * d + a];
}

/* ---- tangent variations and the multisymplectic residual ------------------------------- */
static void preissmann_tangents(gm_pde *p) {
  size_t n = p->n, d = p->d;
  double dt = p->opt.dt, h = p->grid.h;
  for (int k = 0; k < 2; k++) {
    const double *U = p->tan[k][1];
    double *R = p->F; /* rhs = −J_old U, J_old blocks: −𝕎/2Δt ∓ 𝕂/2Δx − H/4 */
    for (size_t i = 0; i < n; i++) {
      size_t j = (i + 1) % n;
      const double *H = p->hess + i * d * d;
      double *Ri = R + i * d;
      for (size_t a = 0; a < d; a++) Ri[a] = 0.0;
      matvec_add(d, p->eq.W, 0.5 / dt, U + i * d, Ri);
      matvec_add(d, p->eq.K, 0.5 / h, U + i * d, Ri);
      matvec_add(d, H, 0.25, U + i * d, Ri);
      matvec_add(d, p->eq.W, 0.5 / dt, U + j * d, Ri);
      matvec_add(d, p->eq.K, -0.5 / h, U + j * d, Ri);
      matvec_add(d, H, 0.25, U + j * d, Ri);
    }
    if (p->eq.has_gauge) R[p->eq.gauge_phi] = U[p->eq.gauge_phi]; /* the pinned gauge */
    if (gm_pde_dirichlet(p)) { /* held components keep their (zero) variations */
      size_t q = 0, nd = (n - 1) * d;
      for (size_t a = 0; a < d; a++)
        if (p->opt.dirichlet_left & (1u << a)) R[nd + q++] = U[a];
      for (size_t a = 0; a < d; a++)
        if (p->opt.dirichlet_right & (1u << a)) R[nd + q++] = U[nd + a];
    }
    band_solve_natural(p, R, p->tan[k][2]);
    if (p->eq.has_gauge) {
      /* The φ row of point 0 is dropped (gauge), so it holds only through the others: up to
       * the sum of their round-off, n·ε, and the variation's mass Σ δu (zero in exact
       * arithmetic) random-walks by as much each step. Taking its mean out again (a change
       * of O(ε|U|)) keeps that row at the round-off of one step. */
      double *U1 = p->tan[k][2], mean = 0.0;
      size_t gu = p->eq.gauge_u;
      for (size_t i = 0; i < n; i++) mean += U1[i * d + gu];
      mean /= (double)n;
      for (size_t i = 0; i < n; i++) U1[i * d + gu] -= mean;
    }
  }
  /* (ω^{n+1}_{i+½} − ωⁿ_{i+½})/Δt + (κ^{n+½}_{i+1} − κ^{n+½}_i)/Δx with ω = V̄ᵀ𝕎Ū (space
   * averages), κ = (V^{n+½})ᵀ𝕂U^{n+½} (time averages) */
  const double *U0 = p->tan[0][1], *U1 = p->tan[0][2], *V0 = p->tan[1][1], *V1 = p->tan[1][2];
  double a0[GM_PDE_MAX_DIM], a1[GM_PDE_MAX_DIM], b0[GM_PDE_MAX_DIM], b1[GM_PDE_MAX_DIM];
  double ui[GM_PDE_MAX_DIM], vi[GM_PDE_MAX_DIM], uj[GM_PDE_MAX_DIM], vj[GM_PDE_MAX_DIM];
  for (size_t i = 0; i < n; i++) {
    size_t j = (i + 1) % n;
    for (size_t a = 0; a < d; a++) {
      a0[a] = 0.5 * (U0[i * d + a] + U0[j * d + a]);
      a1[a] = 0.5 * (U1[i * d + a] + U1[j * d + a]);
      b0[a] = 0.5 * (V0[i * d + a] + V0[j * d + a]);
      b1[a] = 0.5 * (V1[i * d + a] + V1[j * d + a]);
      ui[a] = 0.5 * (U0[i * d + a] + U1[i * d + a]);
      vi[a] = 0.5 * (V0[i * d + a] + V1[i * d + a]);
      uj[a] = 0.5 * (U0[j * d + a] + U1[j * d + a]);
      vj[a] = 0.5 * (V0[j * d + a] + V1[j * d + a]);
    }
    double w1 = bilin(d, b1, p->eq.W, a1) / dt, w0 = bilin(d, b0, p->eq.W, a0) / dt;
    double k1 = bilin(d, vj, p->eq.K, uj) / h, k0 = bilin(d, vi, p->eq.K, ui) / h;
    double scale = fabs(w1) + fabs(w0) + fabs(k1) + fabs(k0);
    p->msres[i] = scale > 0.0 ? fabs(w1 - w0 + k1 - k0) / scale : 0.0;
  }
  if (gm_pde_dirichlet(p)) p->msres[n - 1] = 0.0; /* no cell past the right end */
  p->ms_valid = 1;
}

static void euler_tangents(gm_pde *p) {
  size_t n = p->n, d = p->d;
  double dt = p->opt.dt, h = p->grid.h;
  for (int k = 0; k < 2; k++) {
    const double *Um = p->tan[k][0], *U = p->tan[k][1];
    double *R = p->F;
    for (size_t i = 0; i < n; i++) {
      size_t ip = (i + 1) % n, im = (i + n - 1) % n;
      double rp[GM_PDE_MAX_DIM] = {0}, rz[GM_PDE_MAX_DIM] = {0};
      double Hs[GM_PDE_MAX_DIM * GM_PDE_MAX_DIM], t[GM_PDE_MAX_DIM];
      gm_pde_hessian(p, p->s + i * d, Hs, p->work);
      /* P rows: −[−𝕎₊Uⁿ/Δt + 𝕎₋(Uⁿ − Uⁿ⁻¹)/Δt + 𝕂₊δ⁺Uⁿ + 𝕂₋δ⁻Uⁿ − H(sⁿ)Uⁿ] */
      matvec_add(d, p->Wp, -1.0 / dt, U + i * d, rp);
      for (size_t a = 0; a < d; a++) t[a] = (U[i * d + a] - Um[i * d + a]) / dt;
      matvec_add(d, p->Wm, 1.0, t, rp);
      for (size_t a = 0; a < d; a++) t[a] = (U[ip * d + a] - U[i * d + a]) / h;
      matvec_add(d, p->Kp, 1.0, t, rp);
      for (size_t a = 0; a < d; a++) t[a] = (U[i * d + a] - U[im * d + a]) / h;
      matvec_add(d, p->Km, 1.0, t, rp);
      matvec_add(d, Hs, -1.0, U + i * d, rp);
      /* Z rows: −[−𝕎₋Uⁿ/Δt] */
      matvec_add(d, p->Wm, 1.0 / dt, U + i * d, rz);
      for (size_t a = 0; a < d; a++) R[i * d + a] = wp_row(p, a) ? -rp[a] : rz[a];
    }
    band_solve_natural(p, R, p->tan[k][2]);
  }
  if (p->steps >= 1) {
    /* law at level n: (fⁿ_i − fⁿ⁻¹_i)/Δt + (gⁿ_i − gⁿ_{i−1})/Δx, with
     * fⁿ = (Vⁿ)ᵀ𝕎₊Uⁿ⁺¹ − (Uⁿ)ᵀ𝕎₊Vⁿ⁺¹ and g_i = V_iᵀ𝕂₊U_{i+1} − U_iᵀ𝕂₊V_{i+1} */
    const double *Um = p->tan[0][0], *U = p->tan[0][1], *Up = p->tan[0][2];
    const double *Vm = p->tan[1][0], *V = p->tan[1][1], *Vp = p->tan[1][2];
    for (size_t i = 0; i < n; i++) {
      size_t ip = (i + 1) % n, im = (i + n - 1) % n;
      size_t q = i * d, qp = ip * d, qm = im * d;
      double f1 = (bilin(d, V + q, p->Wp, Up + q) - bilin(d, U + q, p->Wp, Vp + q)) / dt;
      double f0 = (bilin(d, Vm + q, p->Wp, U + q) - bilin(d, Um + q, p->Wp, V + q)) / dt;
      double g1 = (bilin(d, V + q, p->Kp, U + qp) - bilin(d, U + q, p->Kp, V + qp)) / h;
      double g0 = (bilin(d, V + qm, p->Kp, U + q) - bilin(d, U + qm, p->Kp, V + q)) / h;
      double scale = fabs(f1) + fabs(f0) + fabs(g1) + fabs(g0);
      p->msres[i] = scale > 0.0 ? fabs(f1 - f0 + g1 - g0) / scale : 0.0;
    }
    p->ms_valid = 1;
  }
}

/* ---- SDIRK2 on the box semi-discretisation (not symplectic; the comparison row):
 * the Preissmann box's space part 𝕎 M_x s_t + 𝕂 D_x s = ∇S(M_x s) (M_x the two-point average,
 * D_x the difference over cell i+½) integrated in time by Alexander's two-stage L-stable,
 * stiffly accurate SDIRK of order 2 (R. Alexander, SIAM J. Numer. Anal. 14 (1977) 1006, the
 * s = 2 method: γ = 1 − 1/√2, A = [γ 0; 1−γ γ], b = (1−γ, γ)). A stage solves
 *   𝕎 M_x (X − B)/(γΔt) + 𝕂 D_x X − ∇S(M_x X) = 0
 * with B = sⁿ (stage 1) and B = sⁿ + ((1−γ)/γ)(X₁ − sⁿ) (stage 2); sⁿ⁺¹ = X₂. -------------- */
#define SDIRK_GAMMA 0.29289321881345247560 /* 1 − 1/√2 */

static void dirk_residual(gm_pde *p, const double *x, const double *B, double *F) {
  size_t n = p->n, d = p->d;
  double cw = 1.0 / (SDIRK_GAMMA * p->opt.dt), h = p->grid.h;
  double *m = p->work, *g = p->work + d;
  for (size_t i = 0; i < n; i++) {
    double t[GM_PDE_MAX_DIM], xd[GM_PDE_MAX_DIM];
    for (size_t a = 0; a < d; a++) {
      double xj = gm_pde_at(p, x, i, 1, a), bj = gm_pde_at(p, B, i, 1, a);
      m[a] = 0.5 * (x[i * d + a] + xj);
      t[a] = 0.5 * ((x[i * d + a] - B[i * d + a]) + (xj - bj)) * cw;
      xd[a] = (xj - x[i * d + a]) / h;
    }
    p->eq.gradient(m, g, p->eq.params);
    p->stats.gradient_evaluations++;
    double *Fi = F + i * d;
    for (size_t a = 0; a < d; a++) Fi[a] = -g[a];
    matvec_add(d, p->eq.W, 1.0, t, Fi);
    matvec_add(d, p->eq.K, 1.0, xd, Fi);
  }
}

static gm_status dirk_jacobian(gm_pde *p, const double *x) {
  size_t n = p->n, d = p->d;
  double cw = 1.0 / (SDIRK_GAMMA * p->opt.dt), h = p->grid.h;
  double *m = p->work;
  gm_band_zero(&p->band);
  for (size_t i = 0; i < n; i++) {
    size_t j = (i + 1) % n;
    for (size_t a = 0; a < d; a++) m[a] = 0.5 * (x[i * d + a] + gm_pde_at(p, x, i, 1, a));
    double *H = p->hess + i * d * d;
    gm_pde_hessian(p, m, H, p->work + d);
    add_block(p, i, i, p->eq.W, 0.5 * cw);
    add_block(p, i, i, p->eq.K, -1.0 / h);
    add_block(p, i, i, H, -0.5);
    add_block(p, i, j, p->eq.W, 0.5 * cw);
    add_block(p, i, j, p->eq.K, 1.0 / h);
    add_block(p, i, j, H, -0.5);
  }
  p->stats.factorizations++;
  return gm_band_factor(&p->band);
}

/* Newton for one stage, x the initial guess and the result */
static gm_status dirk_stage(gm_pde *p, const double *B, double *x, gm_error *err) {
  size_t nu = p->nu;
  double last = INFINITY;
  size_t it;
  for (it = 0; it < p->opt.newton_max_iter; it++) {
    dirk_residual(p, x, B, p->F);
    if (!isfinite(maxabs(p->F, nu)))
      return gm_error_set(err, GM_EDOMAIN, "pde %s: non-finite residual at step %zu",
                          p->scheme->name, p->steps + 1);
    if (dirk_jacobian(p, x) != GM_OK)
      return gm_error_set(err, GM_ESINGULAR, "pde %s: singular Newton matrix at step %zu",
                          p->scheme->name, p->steps + 1);
    for (size_t k = 0; k < nu; k++) p->F[k] = -p->F[k];
    band_solve_natural(p, p->F, p->F);
    for (size_t k = 0; k < nu; k++) x[k] += p->F[k];
    p->stats.newton_iterations++;
    double prev = last, scale = 1.0 + maxabs(x, nu);
    last = maxabs(p->F, nu);
    if (last <= p->opt.newton_tol * scale) break;
    if (last <= 1e-9 * scale && last >= 0.5 * prev) break;
  }
  if (it == p->opt.newton_max_iter || !isfinite(last))
    return gm_error_set(err, isfinite(last) ? GM_ENOCONV : GM_EDOMAIN,
                        "pde %s: Newton did not converge at step %zu (max|ds| = %g)",
                        p->scheme->name, p->steps + 1, last);
  if (last > p->stats.max_newton_residual) p->stats.max_newton_residual = last;
  return GM_OK;
}

static gm_status sdirk_step(gm_pde *p, gm_error *err) {
  size_t nu = p->nu;
  double *x1 = p->aux[0], *B = p->aux[1], *x = p->s_new;
  memcpy(x1, p->s, nu * sizeof *x1);
  gm_status st = dirk_stage(p, p->s, x1, err);
  if (st != GM_OK) return st;
  double c = (1.0 - SDIRK_GAMMA) / SDIRK_GAMMA;
  for (size_t k = 0; k < nu; k++) B[k] = p->s[k] + c * (x1[k] - p->s[k]);
  memcpy(x, x1, nu * sizeof *x);
  if ((st = dirk_stage(p, B, x, err)) != GM_OK) return st;
  double *tmp = p->s_prev;
  p->s_prev = p->s;
  p->s = x;
  p->s_new = tmp;
  return GM_OK;
}

gm_status gm_pde_box_step(gm_pde *p, gm_error *err) {
  if (p->scheme->kind == GM_PDE_BOX_SDIRK2) return sdirk_step(p, err);
  if (p->scheme->kind == GM_PDE_GAUSS_PRK) return gm_pde_gauss_step(p, err);
  size_t nu = p->nu;
  int pre = p->scheme->kind == GM_PDE_PREISSMANN;
  double *x = p->s_new;
  memcpy(x, p->s, nu * sizeof *x);
  double last = INFINITY;
  size_t it;
  for (it = 0; it < p->opt.newton_max_iter; it++) {
    if (pre)
      preissmann_residual(p, x, p->F);
    else
      euler_residual(p, x, p->F);
    if (isnan(maxabs(p->F, nu)) || !isfinite(maxabs(p->F, nu)))
      return gm_error_set(err, GM_EDOMAIN, "pde %s: non-finite residual at step %zu",
                          p->scheme->name, p->steps + 1);
    gm_status st = pre ? preissmann_jacobian(p, x) : euler_jacobian(p, x);
    if (st != GM_OK)
      return gm_error_set(err, st, "pde %s: singular Newton matrix at step %zu",
                          p->scheme->name, p->steps + 1);
    for (size_t k = 0; k < nu; k++) p->F[k] = -p->F[k];
    band_solve_natural(p, p->F, p->F);
    for (size_t k = 0; k < nu; k++) x[k] += p->F[k];
    p->stats.newton_iterations++;
    double prev = last;
    last = maxabs(p->F, nu);
    double scale = 1.0 + maxabs(x, nu);
    if (last <= p->opt.newton_tol * scale) break;
    /* round-off floor of the banded solve (it grows with 1/Δt and n): accept it once the
     * corrections stop shrinking below 1e-9 relative */
    if (last <= 1e-9 * scale && last >= 0.5 * prev) break;
  }
  if (it == p->opt.newton_max_iter || !isfinite(last))
    return gm_error_set(err, isfinite(last) ? GM_ENOCONV : GM_EDOMAIN,
                        "pde %s: Newton did not converge at step %zu (max|ds| = %g)",
                        p->scheme->name, p->steps + 1, last);
  if (last > p->stats.max_newton_residual) p->stats.max_newton_residual = last;
  if (p->tan[0][0] != NULL) {
    /* the linearisation at the converged sⁿ⁺¹ */
    gm_status st = pre ? preissmann_jacobian(p, x) : euler_jacobian(p, x);
    if (st != GM_OK)
      return gm_error_set(err, st, "pde %s: singular tangent matrix at step %zu",
                          p->scheme->name, p->steps + 1);
    if (pre)
      preissmann_tangents(p);
    else
      euler_tangents(p);
    for (int k = 0; k < 2; k++) {
      double *t0 = p->tan[k][0];
      p->tan[k][0] = p->tan[k][1];
      p->tan[k][1] = p->tan[k][2];
      p->tan[k][2] = t0;
    }
  }
  double *tmp = p->s_prev;
  p->s_prev = p->s;
  p->s = x;
  p->s_new = tmp;
  return GM_OK;
}
