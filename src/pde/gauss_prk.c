/* The multisymplectic Gauss–Legendre Runge–Kutta box with two stages in t and in x
 * (S. Reich, J. Comput. Phys. 157 (2000) 473, "Multi-symplectic Runge–Kutta collocation
 * methods for Hamiltonian wave equations", eqs. (3.1)–(3.6); Bridges & Reich, J. Phys. A 39
 * (2006) §4.2). On cell m = [X_m, X_m + H] and step [tⁿ, tⁿ + Δt], with the 2-stage Gauss
 * coefficients A, b, c (c = ½ ∓ √3/6) in both directions:
 *   Z_ij = z_j + Δt Σ_k a_ik ∂_tZ_kj,     z_jⁿ⁺¹ = z_j + Δt Σ_i b_i ∂_tZ_ij,
 *   Z_ij = Y_i + H Σ_k a_jk ∂_xZ_ik,      Y_{m+1,i} = Y_{m,i} + H Σ_j b_j ∂_xZ_ij,
 *   𝕎 ∂_tZ_ij + 𝕂 ∂_xZ_ij = ∇S(Z_ij),
 * z_j the state at the spatial Gauss points (tⁿ), Y_i the node values X_m at the time stages.
 * With ∂_tZ = A⁻¹(Z − z𝟙)/Δt and ∂_xZ = A⁻¹(Z − Y𝟙)/H eliminated, one step is a Newton solve
 * for (Z, Y): 6d unknowns per cell, coupled to the next cell by the continuity of Y, on the
 * periodic ring (banded LU, block size 6d). For the 2-stage Gauss method bᵀA⁻¹ = (−√3, √3)
 * (so bᵀA⁻¹𝟙 = 1 − R(∞) = 0), which gives z_jⁿ⁺¹ = z_j + √3 (Z_2j − Z_1j) and
 * Y_{m+1,i} = Y_{m,i} + √3 (Z_i2 − Z_i1).
 * Discrete multisymplectic law per cell (Reich 2000 Thm. 1: b_i a_ij + b_j a_ji = b_i b_j):
 *   H Σ_j b_j (ω_jⁿ⁺¹ − ω_jⁿ) + Δt Σ_i b_i (κ_{m+1,i} − κ_{m,i}) = 0,
 *   ω = dz∧𝕎dz at the spatial stages, κ = dY∧𝕂dY at the nodes.
 * Accuracy (derived from the scheme's Fourier modes, docs/pde.md "The discrete dispersion
 * relation of gauss-prk", checked against this code to 1e-13): order 4 in t and x for the
 * cell means ½(z_{2m} + z_{2m+1}); order 3 in x at the Gauss points (stage values). Each
 * wavenumber also has a spurious spatial root (μH ≈ −12i/(κH)); point-sampled data put O(H³)
 * on it, and Δt does not resolve its frequency, so fixed-grid Δt-differences stall there. */
#include <math.h>
#include <string.h>

#include "pde/internal.h"

#define SQ3 1.73205080756887729353
static const double A_INV[2][2] = {{3.0, -3.0 + 2.0 * SQ3}, {-3.0 - 2.0 * SQ3, 3.0}};
static const double BETA[2] = {-SQ3, SQ3}; /* bᵀA⁻¹ */

/* unknowns of cell m in natural layout: Z_ij at ((2i + j)d + a), Y_i at (4d + i d + a) */
static size_t zk(size_t d, size_t i, size_t j) { return (2 * i + j) * d; }
static size_t yk(size_t d, size_t i) { return 4 * d + i * d; }

double gm_pde_gauss_point_x(const gm_pde_grid *g, size_t i) {
  size_t m = i / 2;
  double c = (i % 2 == 0) ? 0.5 - SQ3 / 6.0 : 0.5 + SQ3 / 6.0;
  return g->x0 + 2.0 * g->h * ((double)m + c);
}

/* The initial guess of Y at node X_m: the mean of the two nearest Gauss points. */
void gm_pde_gauss_init(gm_pde *p) {
  size_t M = p->n / 2, d = p->d, B = 6 * d;
  for (size_t m = 0; m < M; m++) {
    const double *zl = p->s + ((2 * m + p->n - 1) % p->n) * d, *zr = p->s + 2 * m * d;
    for (size_t i = 0; i < 2; i++)
      for (size_t a = 0; a < d; a++) p->gp_x[m * B + yk(d, i) + a] = 0.5 * (zl[a] + zr[a]);
  }
  gm_ring_positions(M, p->pos);
}

/* A singular 𝕂 must have its kernel along coordinates (see k_free), checked by create. */
int gm_pde_gauss_kernel_ok(const gm_pde_equation *eq) {
  size_t d = eq->dim, free_n = 0, idx[GM_PDE_MAX_DIM], m = 0;
  double Kr[GM_PDE_MAX_DIM * GM_PDE_MAX_DIM];
  int piv[GM_PDE_MAX_DIM];
  for (size_t a = 0; a < d; a++) {
    int z = 1;
    for (size_t b = 0; b < d; b++)
      if (eq->K[a * d + b] != 0.0 || eq->K[b * d + a] != 0.0) z = 0;
    if (z)
      free_n++;
    else
      idx[m++] = a;
  }
  (void)free_n;
  for (size_t r = 0; r < m; r++)
    for (size_t c = 0; c < m; c++) Kr[r * m + c] = eq->K[idx[r] * d + idx[c]];
  return m == 0 || gm_lu_factor(m, Kr, piv) == GM_OK;
}

/* Components whose row and column of 𝕂 vanish (sine-Gordon's v) have no x-derivative in the
 * equations: their ∂_xZ are free, so their node values Y and continuity equations carry no
 * information, and on the ring the continuity sums Σ_m βᵀZ_m = 0 would over-determine them
 * (Σβ = 0 for an even number of stages). Their Y is set to 0 instead. */
static int k_free(const gm_pde *p, size_t a) {
  for (size_t b = 0; b < p->d; b++)
    if (p->eq.K[a * p->d + b] != 0.0 || p->eq.K[b * p->d + a] != 0.0) return 0;
  return 1;
}

static void residual(gm_pde *p, const double *x, double *F) {
  size_t M = p->n / 2, d = p->d, B = 6 * d;
  double dt = p->opt.dt, H = 2.0 * p->grid.h;
  double *g = p->work, t[GM_PDE_MAX_DIM], xs[GM_PDE_MAX_DIM];
  for (size_t m = 0; m < M; m++) {
    const double *X = x + m * B, *Xn = x + ((m + 1) % M) * B;
    const double *z = p->s + 2 * m * d; /* z_j at j d */
    double *Fm = F + m * B;
    for (size_t i = 0; i < 2; i++)
      for (size_t j = 0; j < 2; j++) {
        for (size_t a = 0; a < d; a++) {
          t[a] = 0.0;
          xs[a] = 0.0;
          for (size_t k = 0; k < 2; k++) {
            t[a] += A_INV[i][k] * (X[zk(d, k, j) + a] - z[j * d + a]) / dt;
            xs[a] += A_INV[j][k] * (X[zk(d, i, k) + a] - X[yk(d, i) + a]) / H;
          }
        }
        p->eq.gradient(X + zk(d, i, j), g, p->eq.params);
        p->stats.gradient_evaluations++;
        double *Fq = Fm + zk(d, i, j);
        for (size_t a = 0; a < d; a++) {
          double r = -g[a];
          for (size_t b = 0; b < d; b++)
            r += p->eq.W[a * d + b] * t[b] + p->eq.K[a * d + b] * xs[b];
          Fq[a] = r;
        }
      }
    for (size_t i = 0; i < 2; i++)
      for (size_t a = 0; a < d; a++) {
        double r = Xn[yk(d, i) + a] - X[yk(d, i) + a];
        for (size_t k = 0; k < 2; k++) r -= BETA[k] * (X[zk(d, i, k) + a] - X[yk(d, i) + a]);
        Fm[yk(d, i) + a] = k_free(p, a) ? X[yk(d, i) + a] : r;
      }
  }
}

/* ---- the Newton solve, condensed to the node values ------------------------------------------
 * Cell m's 4d stage rows involve only its own Z_m and Y_m; its 2d continuity rows add Y_{m+1}.
 * So per cell, with A = ∂(stage rows)/∂Z_m (4d×4d) and C = ∂(stage rows)/∂Y_m,
 *   δZ_m = A⁻¹(R^Z_m − C δY_m),
 * and the continuity rows δY_{m+1} − δY_m − Σ_k β_k δZ_{m,(i,k)} = R^Y_m become
 *   δY_{m+1} + G_m δY_m = R^Y_m − E A⁻¹R^Z_m,   G_m = −I − E A⁻¹C,   (E v)_i = −Σ_k β_k v_{(i,k)},
 * a cyclic block-bidiagonal system in the 2d_f node values of the components with an
 * x-derivative (the 𝕂-free ones have Y = 0, see k_free). Rows of cell m sit at block m + 1
 * (block 0 for the last cell), so the matrix is banded (kl = 2·2d_f − 1, ku = 0) plus the
 * wrap-around block in the last columns: gm_bband, O(N) memory, L not kept (band_border.c).
 * Same equations as the full (Z, Y) system; the elimination order differs, so results agree
 * to round-off, not bitwise. */

/* the components with an x-derivative; returns their number d_f */
static size_t k_coupled(const gm_pde *p, size_t *idx) {
  size_t df = 0;
  for (size_t a = 0; a < p->d; a++)
    if (!k_free(p, a)) idx[df++] = a;
  return df;
}

/* Cell m at iterate x: factor A (into Am, pivots piv), AinvC = A⁻¹C (4d×2d_f, column-major by
 * Y unknown) and AinvR = A⁻¹R^Z_m. */
static gm_status cell_local(gm_pde *p, const double *x, size_t m, const double *Rm, double *Am,
                            int *piv, double *AinvC, double *AinvR, const size_t *idx, size_t df) {
  size_t d = p->d, B = 6 * d, nz = 4 * d;
  double dt = p->opt.dt, H = 2.0 * p->grid.h;
  const double *W = p->eq.W, *K = p->eq.K;
  memset(Am, 0, nz * nz * sizeof *Am);
  memset(AinvC, 0, nz * 2 * df * sizeof *AinvC);
  for (size_t i = 0; i < 2; i++)
    for (size_t j = 0; j < 2; j++) {
      size_t q = zk(d, i, j);
      gm_pde_hessian(p, x + m * B + q, p->hess, p->work);
      for (size_t a = 0; a < d; a++) {
        double *row = Am + (q + a) * nz;
        for (size_t b = 0; b < d; b++) {
          for (size_t k = 0; k < 2; k++) {
            row[zk(d, k, j) + b] += W[a * d + b] * A_INV[i][k] / dt;
            row[zk(d, i, k) + b] += K[a * d + b] * A_INV[j][k] / H;
          }
          row[q + b] -= p->hess[a * d + b];
        }
        for (size_t fb = 0; fb < df; fb++) /* C: column (i, fb) */
          AinvC[(i * df + fb) * nz + q + a] =
              -K[a * d + idx[fb]] * (A_INV[j][0] + A_INV[j][1]) / H;
      }
    }
  if (gm_lu_factor(nz, Am, piv) != GM_OK) return GM_ESINGULAR;
  for (size_t c = 0; c < 2 * df; c++) gm_lu_solve(nz, Am, piv, AinvC + c * nz);
  memcpy(AinvR, Rm, nz * sizeof *AinvR); /* R^Z_m is the first 4d entries of the cell */
  gm_lu_solve(nz, Am, piv, AinvR);
  return GM_OK;
}

/* Solve J out = R at iterate x (R and out: 6d per cell, may alias): assemble the condensed
 * matrix and eliminate it with its right-hand side as the cells arrive. Cell M − 1 gives row
 * block 0; then cell m gives row block m + 1, after which column block m can be eliminated
 * (its pivot rows are in blocks m and m + 1), so only a window of rows is ever held. */
static gm_status newton_solve(gm_pde *p, const double *x, const double *R, double *out) {
  size_t M = p->n / 2, d = p->d, B = 6 * d, nz = 4 * d, idx[GM_PDE_MAX_DIM];
  size_t df = k_coupled(p, idx), nb = 2 * df;
  int piv[4 * GM_PDE_MAX_DIM];
  double *Am = p->gp_cell, *AinvC = Am + nz * nz, *AinvR = AinvC + nz * nb;
  gm_bband_reset(&p->gp_band);
  for (size_t s = 0; s < M; s++) {
    size_t m = (s + M - 1) % M;
    if (cell_local(p, x, m, R + m * B, Am, piv, AinvC, AinvR, idx, df) != GM_OK)
      return GM_ESINGULAR;
    size_t rb = ((m + 1) % M) * nb, cb = m * nb;
    for (size_t i = 0; i < 2; i++)
      for (size_t fa = 0; fa < df; fa++) {
        size_t a = idx[fa], r = rb + i * df + fa;
        /* (E v)_(i,a) = −Σ_k β_k v_{(i,k),a} */
        double ev = 0.0;
        for (size_t k = 0; k < 2; k++) ev -= BETA[k] * AinvR[zk(d, i, k) + a];
        p->gp_b[r] = R[m * B + yk(d, i) + a] - ev;
        gm_bband_add(&p->gp_band, r, r, 1.0);
        for (size_t c = 0; c < nb; c++) {
          double ec = 0.0;
          for (size_t k = 0; k < 2; k++) ec -= BETA[k] * AinvC[c * nz + zk(d, i, k) + a];
          gm_bband_add(&p->gp_band, r, cb + c, (c == i * df + fa ? -1.0 : 0.0) - ec);
        }
      }
    if (s > 0 && gm_bband_eliminate(&p->gp_band, s * nb, p->gp_b) != GM_OK) return GM_ESINGULAR;
  }
  p->stats.factorizations++;
  if (gm_bband_eliminate(&p->gp_band, M * nb, p->gp_b) != GM_OK) return GM_ESINGULAR;
  gm_bband_back(&p->gp_band, p->gp_b); /* δY (block m = Y_m) */
  for (size_t m = 0; m < M; m++) {
    if (cell_local(p, x, m, R + m * B, Am, piv, AinvC, AinvR, idx, df) != GM_OK)
      return GM_ESINGULAR;
    const double *dY = p->gp_b + m * nb;
    double yfree[2 * GM_PDE_MAX_DIM];
    for (size_t i = 0; i < 2; i++)
      for (size_t a = 0; a < d; a++) yfree[i * d + a] = R[m * B + yk(d, i) + a];
    double *o = out + m * B;
    for (size_t r = 0; r < nz; r++) {
      double v = AinvR[r];
      for (size_t c = 0; c < nb; c++) v -= AinvC[c * nz + r] * dY[c];
      o[r] = v;
    }
    for (size_t i = 0; i < 2; i++) {
      for (size_t a = 0; a < d; a++) o[yk(d, i) + a] = yfree[i * d + a]; /* free: δY = R^Y */
      for (size_t fa = 0; fa < df; fa++) o[yk(d, i) + idx[fa]] = dY[i * df + fa];
    }
  }
  return GM_OK;
}

static double maxabs(const double *x, size_t n) {
  double m = 0.0;
  for (size_t k = 0; k < n; k++) {
    if (!isfinite(x[k])) return NAN;
    if (fabs(x[k]) > m) m = fabs(x[k]);
  }
  return m;
}

/* z_jⁿ⁺¹ = z_j + Σ_k β_k (Z_kj − z_j) for every cell, from stage values X into out */
static void time_update(const gm_pde *p, const double *X, const double *z, double *out) {
  size_t M = p->n / 2, d = p->d, B = 6 * d;
  for (size_t m = 0; m < M; m++)
    for (size_t j = 0; j < 2; j++)
      for (size_t a = 0; a < d; a++) {
        size_t q = (2 * m + j) * d + a;
        double r = z[q];
        for (size_t k = 0; k < 2; k++) r += BETA[k] * (X[m * B + zk(d, k, j) + a] - z[q]);
        out[q] = r;
      }
}

static double bil(size_t d, const double *v, const double *M, const double *u) {
  double s = 0.0;
  for (size_t a = 0; a < d; a++)
    for (size_t b = 0; b < d; b++) s += v[a] * M[a * d + b] * u[b];
  return s;
}

/* tangents: J δX = −(∂F/∂zⁿ) δzⁿ, then δzⁿ⁺¹ by the time update; the law per cell */
static gm_status tangents(gm_pde *p) {
  size_t M = p->n / 2, d = p->d, B = 6 * d;
  double dt = p->opt.dt, H = 2.0 * p->grid.h;
  for (int v = 0; v < 2; v++) {
    const double *dz = p->tan[v][1];
    double *R = p->gp_F;
    memset(R, 0, M * B * sizeof *R);
    for (size_t m = 0; m < M; m++)
      for (size_t i = 0; i < 2; i++)
        for (size_t j = 0; j < 2; j++) /* ∂F_ij/∂z_j = −𝕎 (A⁻¹𝟙)_i /Δt; rhs = −that·δz */
          for (size_t a = 0; a < d; a++) {
            double r = 0.0;
            for (size_t b = 0; b < d; b++) r += p->eq.W[a * d + b] * dz[(2 * m + j) * d + b];
            R[m * B + zk(d, i, j) + a] = r * (A_INV[i][0] + A_INV[i][1]) / dt;
          }
    if (newton_solve(p, p->gp_x, R, p->gp_t[v]) != GM_OK) return GM_ESINGULAR;
    time_update(p, p->gp_t[v], dz, p->tan[v][2]);
  }
  const double *U0 = p->tan[0][1], *U1 = p->tan[0][2], *V0 = p->tan[1][1], *V1 = p->tan[1][2];
  const double *UX = p->gp_t[0], *VX = p->gp_t[1];
  for (size_t m = 0; m < M; m++) {
    size_t mn = (m + 1) % M;
    double w = 0.0, ws = 0.0, k = 0.0, ks = 0.0;
    for (size_t j = 0; j < 2; j++) {
      size_t q = (2 * m + j) * d;
      double a1 = 0.5 * H * bil(d, V1 + q, p->eq.W, U1 + q), a0 = 0.5 * H * bil(d, V0 + q, p->eq.W, U0 + q);
      w += a1 - a0;
      ws += fabs(a1) + fabs(a0);
    }
    for (size_t i = 0; i < 2; i++) {
      double c1 = 0.5 * dt * bil(d, VX + mn * B + yk(d, i), p->eq.K, UX + mn * B + yk(d, i));
      double c0 = 0.5 * dt * bil(d, VX + m * B + yk(d, i), p->eq.K, UX + m * B + yk(d, i));
      k += c1 - c0;
      ks += fabs(c1) + fabs(c0);
    }
    double scale = ws + ks;
    p->msres[2 * m] = p->msres[2 * m + 1] = scale > 0.0 ? fabs(w + k) / scale : 0.0;
  }
  p->ms_valid = 1;
  for (int v = 0; v < 2; v++) {
    double *t0 = p->tan[v][1];
    p->tan[v][1] = p->tan[v][2];
    p->tan[v][2] = t0;
  }
  return GM_OK;
}

gm_status gm_pde_gauss_step(gm_pde *p, gm_error *err) {
  size_t M = p->n / 2, d = p->d, B = 6 * d, nx = M * B;
  double *x = p->gp_x;
  /* guess: Z_ij = z_j (the Y of the last step are kept) */
  for (size_t m = 0; m < M; m++)
    for (size_t i = 0; i < 2; i++)
      for (size_t j = 0; j < 2; j++)
        memcpy(x + m * B + zk(d, i, j), p->s + (2 * m + j) * d, d * sizeof *x);
  double last = INFINITY;
  size_t it;
  for (it = 0; it < p->opt.newton_max_iter; it++) {
    residual(p, x, p->gp_F);
    if (!isfinite(maxabs(p->gp_F, nx)))
      return gm_error_set(err, GM_EDOMAIN, "pde gauss-prk: non-finite residual at step %zu",
                          p->steps + 1);
    for (size_t k = 0; k < nx; k++) p->gp_F[k] = -p->gp_F[k];
    if (newton_solve(p, x, p->gp_F, p->gp_F) != GM_OK)
      return gm_error_set(err, GM_ESINGULAR, "pde gauss-prk: singular Newton matrix at step %zu",
                          p->steps + 1);
    for (size_t k = 0; k < nx; k++) x[k] += p->gp_F[k];
    p->stats.newton_iterations++;
    double prev = last, scale = 1.0 + maxabs(x, nx);
    last = maxabs(p->gp_F, nx);
    if (last <= p->opt.newton_tol * scale) break;
    if (last <= 1e-9 * scale && last >= 0.5 * prev) break;
  }
  if (it == p->opt.newton_max_iter || !isfinite(last))
    return gm_error_set(err, isfinite(last) ? GM_ENOCONV : GM_EDOMAIN,
                        "pde gauss-prk: Newton did not converge at step %zu (max|dX| = %g)",
                        p->steps + 1, last);
  if (last > p->stats.max_newton_residual) p->stats.max_newton_residual = last;
  if (p->tan[0][0] != NULL) {
    /* the tangents use the Newton matrix at the converged iterate (each solve factors it) */
    if (tangents(p) != GM_OK)
      return gm_error_set(err, GM_ESINGULAR, "pde gauss-prk: singular tangent matrix at step %zu",
                          p->steps + 1);
  }
  time_update(p, x, p->s, p->s_new);
  double *tmp = p->s_prev;
  p->s_prev = p->s;
  p->s = p->s_new;
  p->s_new = tmp;
  return GM_OK;
}
