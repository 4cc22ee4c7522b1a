/* gauss-prk on the linear Klein–Gordon equation u_tt = u_xx − u in the sine-Gordon form
 * s = (u, v, w): the code against the scheme's derived Fourier modes (docs/pde.md, "the
 * discrete dispersion relation of gauss-prk"), and its orders from data on the physical branch
 * against point-sampled data, which also excites the spurious spatial branch.
 *
 * Derivation (Reich 2000 eqs. (3.1)–(3.6) with 2-stage Gauss A, b, c): if the stage slopes are
 * ∂_tZ = λZ and ∂_xZ = μZ, the time stages are Z_·j = r(λΔt) z_j and the space stages
 * Z_i· = r(μH) Y_i, r(ζ) = (I − ζA)⁻¹𝟙, and z_jⁿ⁺¹ = R(λΔt) z_j, Y_{m+1} = R(μH) Y_m with
 * R(ζ) = 1 + ζbᵀr(ζ) = (1 + ζ/2 + ζ²/12)/(1 − ζ/2 + ζ²/12). So every pair (λ, μ) of the exact
 * dispersion relation det(λ𝕎 + μ𝕂 − ∇²S) = 0 (here μ² − λ² = 1) gives the discrete mode
 *   z_{m,j}ⁿ = R(λΔt)ⁿ R(μH)ᵐ r_j(μH) ẑ,   ẑ = (1, λ, μ).
 * On the ring R(μH) = e^{iκH} (κ = 2πk/L) fixes μ = iy/H with tan(κH/2) = (y/2)/(1 − y²/12):
 *   y = 3(−1 ± √(1 + 4τ²/3))/τ,  τ = tan(κH/2);
 * '+' is the physical branch, y = κH + O((κH)⁵); '−' a spurious one, y ≈ −12/(κH). */
#include <complex.h>

#include "pde_util.h"

#define SQ3 1.73205080756887729353
#define LX 6.283185307179586 /* [0, 2π), so κ = k */

static double kg_S(const double *s, const void *c) {
  (void)c;
  return 0.5 * (s[1] * s[1] - s[2] * s[2]) + 0.5 * s[0] * s[0];
}
static void kg_grad(const double *s, double *g, const void *c) {
  (void)c;
  g[0] = s[0];
  g[1] = s[1];
  g[2] = -s[2];
}
static void kg_hess(const double *s, double *h, const void *c) {
  (void)c;
  (void)s;
  memset(h, 0, 9 * sizeof *h);
  h[0] = 1.0;
  h[4] = 1.0;
  h[8] = -1.0;
}

static gm_pde *kg_solver(size_t n, double dt, const double *s0) {
  gm_pde_equation eq = gm_pde_sine_gordon(); /* same 𝕎, 𝕂; S = ½(v² − w²) + ½u² */
  eq.name = "klein-gordon";
  eq.S = kg_S;
  eq.gradient = kg_grad;
  eq.hessian = kg_hess;
  eq.V = NULL;
  eq.dV = NULL;
  const gm_pde_scheme *sc = NULL;
  cr_assert_eq(gm_pde_scheme_find("gauss-prk", &sc), GM_OK);
  gm_pde_grid g = {n, LX / (double)n, 0.0, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = dt;
  gm_pde *p = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_create(&g, &eq, sc, &o, s0, &p, &err), GM_OK, "%s", err.message);
  return p;
}

static double complex R(double complex z) { return (1.0 + z / 2 + z * z / 12) / (1.0 - z / 2 + z * z / 12); }

/* r(ζ) = (I − ζA)⁻¹𝟙 for the 2-stage Gauss A */
static void rvec(double complex z, double complex r[2]) {
  double a11 = 0.25, a12 = 0.25 - SQ3 / 6, a21 = 0.25 + SQ3 / 6, a22 = 0.25;
  double complex a = 1 - z * a11, b = -z * a12, c = -z * a21, d = 1 - z * a22, det = a * d - b * c;
  r[0] = (d - b) / det;
  r[1] = (a - c) / det;
}

static double ybranch(double kH, int spurious) {
  double t = tan(kH / 2);
  return 3.0 * (-1.0 + (spurious ? -1.0 : 1.0) * sqrt(1.0 + 4.0 * t * t / 3.0)) / t;
}

/* Adds amp × (discrete mode of wavenumber k, branch, direction sg = ±1) after `steps` steps of
 * dt (exact_t: e^{λ t} instead of R(λΔt)ⁿ, the semi-discrete solution exact in time). */
static void add_mode(size_t n, int k, int spurious, int sg, double dt, size_t steps, int exact_t,
                     double complex amp, double *out) {
  double H = 2.0 * LX / (double)n, kH = (double)k * H, y = ybranch(kH, spurious);
  double complex mu = I * y / H, lam = -I * sg * sqrt(y * y / (H * H) + 1.0), r[2];
  double complex rho = exact_t ? cexp(lam * dt * (double)steps) : cpow(R(lam * dt), (double)steps);
  rvec(mu * H, r);
  double complex zh[3] = {1.0, lam, mu};
  for (size_t m = 0; m < n / 2; m++)
    for (size_t j = 0; j < 2; j++)
      for (size_t a = 0; a < 3; a++)
        out[(2 * m + j) * 3 + a] += creal(amp * rho * cexp(I * kH * (double)m) * r[j] * zh[a]);
}

Test(pde_gauss_dispersion, code_is_the_derived_scheme) {
  double worst = 0.0;
  for (int spurious = 0; spurious < 2; spurious++)
    for (size_t n = 16; n <= 64; n *= 2) {
      double dt = 0.1, e = 0.0, sc = 0.0, *s0 = calloc(3 * n, sizeof *s0),
             *s1 = calloc(3 * n, sizeof *s1);
      for (int k = 1; k <= 2; k++)
        for (int sg = -1; sg <= 1; sg += 2) {
          add_mode(n, k, spurious, sg, dt, 0, 0, 1.0 / k, s0);
          add_mode(n, k, spurious, sg, dt, 20, 0, 1.0 / k, s1);
        }
      gm_pde *p = kg_solver(n, dt, s0);
      gm_error err = {{0}};
      cr_assert_eq(gm_pde_advance(p, 20, &err), GM_OK, "%s", err.message);
      const double *s = gm_pde_state(p);
      for (size_t i = 0; i < 3 * n; i++) {
        e = fmax(e, fabs(s[i] - s1[i]));
        sc = fmax(sc, fabs(s1[i]));
      }
      cr_log_info("gauss-prk Klein-Gordon, %s branch, n = %zu, 20 steps of 0.1: max |code − "
                  "derived mode| = %.2e (max |mode| %.2e)",
                  spurious ? "spurious" : "physical", n, e, sc);
      worst = fmax(worst, e / sc);
      gm_pde_free(p);
      free(s0);
      free(s1);
    }
  cr_assert(worst <= 1e-12, "code vs derived discrete modes: %.2e relative", worst);
}

/* The initial data: the modes k = 1, 2 of u = Σ_k cos(κx − ω_k t)/k (ω_k² = κ² + 1), either
 * point-sampled at the Gauss points or on the physical branch with the exact cell means
 * (amplitude κ'/κ, since the Gauss cell mean of r(ζ) is bᵀr(ζ) = (R(ζ) − 1)/ζ). */
static double *kg_data(size_t n, int physical) {
  double *s0 = calloc(3 * n, sizeof *s0);
  double H = 2.0 * LX / (double)n;
  if (physical) {
    for (int k = 1; k <= 2; k++) {
      double kH = (double)k * H, y = ybranch(kH, 0);
      add_mode(n, k, 0, 1, 0.1, 0, 0, y / kH / k, s0);
    }
    return s0;
  }
  const gm_pde_scheme *sc = NULL;
  gm_pde_scheme_find("gauss-prk", &sc);
  gm_pde_grid g = {n, LX / (double)n, 0.0, {0}};
  for (size_t i = 0; i < n; i++) {
    double x = gm_pde_point_x(sc, &g, i);
    for (int k = 1; k <= 2; k++) {
      double kap = (double)k, om = sqrt(kap * kap + 1.0);
      s0[3 * i] += cos(kap * x) / k;
      s0[3 * i + 1] += om * sin(kap * x) / k;
      s0[3 * i + 2] += -kap * sin(kap * x) / k;
    }
  }
  return s0;
}

/* max over cells of |Gauss cell mean of u − exact cell average| at time t */
static double cell_mean_error(const double *s, size_t n, double t) {
  double H = 2.0 * LX / (double)n, e = 0.0;
  for (size_t m = 0; m < n / 2; m++) {
    double ex = 0.0, X = H * (double)m;
    for (int k = 1; k <= 2; k++) {
      double kap = (double)k, om = sqrt(kap * kap + 1.0);
      ex += (sin(kap * (X + H) - om * t) - sin(kap * X - om * t)) / (kap * H) / k;
    }
    e = fmax(e, fabs(0.5 * (s[6 * m] + s[6 * m + 3]) - ex));
  }
  return e;
}

/* physical: 0 point-sampled, 1 physical branch, 2 point-sampled then gm_pde_gauss_project */
static double *kg_run(size_t n, double dt, double T, int physical) {
  double *s0 = kg_data(n, physical == 1);
  if (physical == 2) {
    gm_pde_grid g = {n, LX / (double)n, 0.0, {0}};
    gm_error err = {{0}};
    cr_assert_eq(gm_pde_gauss_project(&g, 3, s0, &err), GM_OK, "%s", err.message);
  }
  gm_pde *p = kg_solver(n, dt, s0);
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_advance(p, (size_t)llround(T / dt), &err), GM_OK, "%s", err.message);
  memcpy(s0, gm_pde_state(p), 3 * n * sizeof *s0);
  gm_pde_free(p);
  return s0; /* owned */
}

static double maxdiff_u(const double *a, const double *b, size_t n) {
  double e = 0.0;
  for (size_t i = 0; i < n; i++) e = fmax(e, fabs(a[3 * i] - b[3 * i]));
  return e;
}

Test(pde_gauss_dispersion, orders_on_the_physical_branch) {
  double T = 4.0;
  /* t, fixed grid n = 32: against the semi-discrete solution (exact in time) */
  size_t n = 32;
  double et[3];
  for (int q = 0; q < 3; q++) {
    double dt = 0.4 / (double)(1 << q), *s = kg_run(n, dt, T, 1), *ex = calloc(3 * n, sizeof *ex);
    for (int k = 1; k <= 2; k++) {
      double H = 2.0 * LX / (double)n, kH = (double)k * H, y = ybranch(kH, 0);
      add_mode(n, k, 0, 1, dt, (size_t)llround(T / dt), 1, y / kH / k, ex);
    }
    et[q] = maxdiff_u(s, ex, n);
    free(s);
    free(ex);
  }
  double ot1 = log2(et[0] / et[1]), ot2 = log2(et[1] / et[2]);
  /* x: Δt = 0.01 (time error ~1e-9), n = 16 → 32 → 64; cell means against the exact cell
   * averages */
  double ex_[3];
  for (int q = 0; q < 3; q++) {
    size_t nn = 16u << q;
    double *s = kg_run(nn, 0.01, T, 1);
    ex_[q] = cell_mean_error(s, nn, T);
    free(s);
  }
  double ox1 = log2(ex_[0] / ex_[1]), ox2 = log2(ex_[1] / ex_[2]);
  /* joint Δt = H/2 (H = 2h), n = 16 → 32 → 64 */
  double ej[3];
  for (int q = 0; q < 3; q++) {
    size_t nn = 16u << q;
    double H = 2.0 * LX / (double)nn, dt = T / llround(T / (0.5 * H)), *s = kg_run(nn, dt, T, 1);
    ej[q] = cell_mean_error(s, nn, T);
    free(s);
  }
  double oj1 = log2(ej[0] / ej[1]), oj2 = log2(ej[1] / ej[2]);
  cr_log_info("gauss-prk Klein-Gordon, physical-branch data, T = 4: t (n = 32, dt = 0.4, 0.2, "
              "0.1) %.3e %.3e %.3e, orders %.3f %.3f; x (cell means, dt = 0.01, n = 16, 32, "
              "64) %.3e %.3e %.3e, orders %.3f %.3f; joint dt ~ H/2 %.3e %.3e %.3e, orders %.3f "
              "%.3f",
              et[0], et[1], et[2], ot1, ot2, ex_[0], ex_[1], ex_[2], ox1, ox2, ej[0], ej[1],
              ej[2], oj1, oj2);
  cr_assert(fabs(ot2 - 4.0) <= 0.3, "time order %.3f", ot2);
  cr_assert(fabs(ox2 - 4.0) <= 0.3, "space order %.3f", ox2);
  cr_assert(fabs(oj2 - 4.0) <= 0.3, "joint order %.3f", oj2);
}

/* Amplitude at the Gauss points of the spurious-branch part of the point-sampled data (mode k
 * of kg_data): the sampled u, v of one cell, split over the four modes (physical, spurious) ×
 * (ω > 0, ω < 0) by a 4×4 complex solve; w does not enter the u, v evolution (𝕎 has no w
 * column), so it is left out. Returns Σ_± |a_±| max_j |r_j(μH)| of the spurious branch. */
static double spurious_part(size_t n, int k) {
  double H = 2.0 * LX / (double)n, kap = (double)k, om = sqrt(kap * kap + 1.0);
  double c[2] = {0.5 - SQ3 / 6, 0.5 + SQ3 / 6};
  double complex M[4][5], rs[2] = {0.0, 0.0};
  for (int j = 0; j < 2; j++) { /* rhs: e^{iκx}(1, −iω)/k at the two Gauss points of cell 0 */
    M[j][4] = cexp(I * kap * c[j] * H) / k;
    M[2 + j][4] = -I * om * M[j][4];
  }
  int col = 0;
  for (int spurious = 0; spurious < 2; spurious++)
    for (int sg = -1; sg <= 1; sg += 2, col++) {
      double y = ybranch(kap * H, spurious);
      double complex lam = -I * sg * sqrt(y * y / (H * H) + 1.0), r[2];
      rvec(I * y, r);
      if (spurious) memcpy(rs, r, sizeof rs);
      for (int j = 0; j < 2; j++) {
        M[j][col] = r[j];
        M[2 + j][col] = lam * r[j];
      }
    }
  for (int i = 0; i < 4; i++) { /* Gauss–Jordan with partial pivoting */
    int pv = i;
    for (int q = i + 1; q < 4; q++)
      if (cabs(M[q][i]) > cabs(M[pv][i])) pv = q;
    for (int j = 0; j < 5; j++) {
      double complex t = M[i][j];
      M[i][j] = M[pv][j];
      M[pv][j] = t;
    }
    for (int q = 0; q < 4; q++)
      if (q != i) {
        double complex f = M[q][i] / M[i][i];
        for (int j = 0; j < 5; j++) M[q][j] -= f * M[i][j];
      }
  }
  double amp = cabs(M[2][4] / M[2][2]) + cabs(M[3][4] / M[3][3]);
  return amp * fmax(cabs(rs[0]), cabs(rs[1]));
}

/* Point-sampled data excite the spurious branch at O(H³) at the Gauss points; its frequency
 * ~12/(κH²) is not resolved by Δt, so on a fixed grid the differences to a small-Δt reference
 * stop converging at that level, while from physical-branch data they converge at order 4. */
Test(pde_gauss_dispersion, sampled_data_stall_in_time) {
  size_t n = 32;
  double T = 4.0, d[3][3];
  for (int phys = 0; phys < 3; phys++) {
    double *ref = kg_run(n, 0.0125, T, phys);
    for (int q = 0; q < 3; q++) {
      double *s = kg_run(n, 0.2 / (double)(1 << q), T, phys);
      d[phys][q] = maxdiff_u(s, ref, n);
      free(s);
    }
    free(ref);
  }
  /* the spurious part of the data bounds the stall: two runs differ by at most twice it */
  double sp[3];
  for (int q = 0; q < 3; q++) sp[q] = spurious_part(16u << q, 1) + spurious_part(16u << q, 2);
  cr_log_info("gauss-prk Klein-Gordon: spurious-branch part of the point-sampled data at the "
              "Gauss points, n = 16, 32, 64: %.3e %.3e %.3e (orders %.3f %.3f)",
              sp[0], sp[1], sp[2], log2(sp[0] / sp[1]), log2(sp[1] / sp[2]));
  cr_assert(fabs(log2(sp[1] / sp[2]) - 3.0) <= 0.3, "spurious part order %.3f",
            log2(sp[1] / sp[2]));
  for (int q = 0; q < 3; q++)
    cr_assert(d[0][q] <= 2.0 * sp[1] && d[0][q] >= 0.1 * sp[1], "stall %.3e vs spurious part %.3e",
              d[0][q], sp[1]);
  cr_log_info("gauss-prk Klein-Gordon n = 32, max |u(dt) − u(0.0125)| at T = 4 for dt = 0.2, "
              "0.1, 0.05: sampled data %.3e %.3e %.3e (ratios %.2f %.2f); physical-branch data "
              "%.3e %.3e %.3e (ratios %.2f %.2f)",
              d[0][0], d[0][1], d[0][2], d[0][0] / d[0][1], d[0][1] / d[0][2], d[1][0], d[1][1],
              d[1][2], d[1][0] / d[1][1], d[1][1] / d[1][2]);
  cr_assert(d[0][1] / d[0][2] < 4.0, "sampled data: expected a stall, ratio %.2f",
            d[0][1] / d[0][2]);
  cr_assert(d[1][0] / d[1][1] > 12.0 && d[1][1] / d[1][2] > 12.0, "physical data ratios %.2f %.2f",
            d[1][0] / d[1][1], d[1][1] / d[1][2]);
  cr_log_info("same, point-sampled data after gm_pde_gauss_project: %.3e %.3e %.3e (ratios %.2f "
              "%.2f)", d[2][0], d[2][1], d[2][2], d[2][0] / d[2][1], d[2][1] / d[2][2]);
  cr_assert(d[2][0] / d[2][1] > 12.0 && d[2][1] / d[2][2] > 12.0, "projected data ratios %.2f %.2f",
            d[2][0] / d[2][1], d[2][1] / d[2][2]);
  /* the projection keeps physical-branch data (u, v; w is passive and left as sampled) */
  double *ph = kg_data(n, 1), *pr = kg_data(n, 1), dev = 0.0;
  gm_pde_grid g = {n, LX / (double)n, 0.0, {0}};
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_gauss_project(&g, 3, pr, &err), GM_OK, "%s", err.message);
  for (size_t i = 0; i < 3 * n; i++) dev = fmax(dev, fabs(pr[i] - ph[i]));
  cr_log_info("gm_pde_gauss_project of physical-branch data changes it by %.2e", dev);
  cr_assert(dev <= 1e-13, "projection moved physical data by %.2e", dev);
  free(ph);
  free(pr);
}

/* The same on the linear Schrödinger equation iψ_t + ψ_xx = 0 in the NLS form s = (p, q, v, w)
 * (gm_pde_nls's 𝕎, 𝕂 with S = ½(v² + w²)): for μ = iy/H the mode is ẑ = (1, −i, μ, −iμ) with
 * λ = iμ², so the spurious branch's frequency is (12/(κH²))². */
static double ls_S(const double *s, const void *c) {
  (void)c;
  return 0.5 * (s[2] * s[2] + s[3] * s[3]);
}
static void ls_grad(const double *s, double *g, const void *c) {
  (void)c;
  g[0] = g[1] = 0.0;
  g[2] = s[2];
  g[3] = s[3];
}
static void ls_hess(const double *s, double *h, const void *c) {
  (void)c;
  (void)s;
  memset(h, 0, 16 * sizeof *h);
  h[10] = h[15] = 1.0;
}

/* ψ = Σ_{k=1,2} e^{ikx}/k: point-sampled, or on the physical branch with exact cell means */
static double *ls_run(size_t n, double dt, double T, int physical) {
  double *s0 = calloc(4 * n, sizeof *s0), H = 2.0 * LX / (double)n;
  for (int k = 1; k <= 2; k++) {
    double kH = (double)k * H, y = ybranch(kH, 0);
    double complex mu = I * y / H, zh[4] = {1.0, -I, mu, -I * mu}, r[2];
    rvec(mu * H, r);
    for (size_t m = 0; m < n / 2; m++)
      for (size_t j = 0; j < 2; j++) {
        double x = H * ((double)m + (j ? 0.5 + SQ3 / 6 : 0.5 - SQ3 / 6));
        double complex ex[4] = {1.0, -I, I * k, (double)k};
        for (size_t a = 0; a < 4; a++)
          s0[(2 * m + j) * 4 + a] +=
              creal(physical ? y / kH / k * cexp(I * kH * (double)m) * r[j] * zh[a]
                             : cexp(I * k * x) / k * ex[a]);
      }
  }
  gm_pde_equation eq = gm_pde_nls();
  eq.name = "linear-schroedinger";
  eq.S = ls_S;
  eq.gradient = ls_grad;
  eq.hessian = ls_hess;
  const gm_pde_scheme *sc = NULL;
  cr_assert_eq(gm_pde_scheme_find("gauss-prk", &sc), GM_OK);
  gm_pde_grid g = {n, LX / (double)n, 0.0, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = dt;
  gm_pde *p = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_create(&g, &eq, sc, &o, s0, &p, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_pde_advance(p, (size_t)llround(T / dt), &err), GM_OK, "%s", err.message);
  memcpy(s0, gm_pde_state(p), 4 * n * sizeof *s0);
  gm_pde_free(p);
  return s0; /* owned */
}

Test(pde_gauss_dispersion, schroedinger_stall_and_order) {
  size_t n = 32;
  double T = 1.0, d[2][3];
  for (int phys = 0; phys < 2; phys++) {
    double *ref = ls_run(n, 0.003125, T, phys);
    for (int q = 0; q < 3; q++) {
      double *s = ls_run(n, 0.1 / (double)(1 << q), T, phys), e = 0.0;
      for (size_t i = 0; i < n; i++)
        e = fmax(e, hypot(s[4 * i] - ref[4 * i], s[4 * i + 1] - ref[4 * i + 1]));
      d[phys][q] = e;
      free(s);
    }
    free(ref);
  }
  cr_log_info("gauss-prk linear Schroedinger n = 32, max |ψ(dt) − ψ(0.003125)| at T = 1 for "
              "dt = 0.1, 0.05, 0.025: sampled data %.3e %.3e %.3e (ratios %.2f %.2f); "
              "physical-branch data %.3e %.3e %.3e (orders %.3f %.3f)",
              d[0][0], d[0][1], d[0][2], d[0][0] / d[0][1], d[0][1] / d[0][2], d[1][0], d[1][1],
              d[1][2], log2(d[1][0] / d[1][1]), log2(d[1][1] / d[1][2]));
  cr_assert(d[0][1] / d[0][2] < 4.0 && d[0][0] / d[0][1] < 4.0, "sampled: expected a stall");
  cr_assert(fabs(log2(d[1][0] / d[1][1]) - 4.0) <= 0.3 && fabs(log2(d[1][1] / d[1][2]) - 4.0) <= 0.3,
            "physical-branch time orders");
}
