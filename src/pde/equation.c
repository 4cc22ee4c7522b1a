/* Equations in the form 𝕎 s_t + 𝕂 s_x = ∇S(s), and the table of schemes. */
#include <math.h>
#include <stddef.h>
#include <strings.h>

#include "pde/internal.h"

/* ---- sine-Gordon: seed 004 eq. (39), V(u) = −cos u (notes/003-004 §2.2: sign restored) ---- */
static double sg_V(double u, const void *ctx) {
  (void)ctx;
  return -cos(u);
}
static double sg_dV(double u, const void *ctx) {
  (void)ctx;
  return sin(u);
}
static double sg_S(const double *s, const void *ctx) {
  (void)ctx;
  return 0.5 * (s[1] * s[1] - s[2] * s[2]) - cos(s[0]);
}
static void sg_grad(const double *s, double *g, const void *ctx) {
  (void)ctx;
  g[0] = sin(s[0]);
  g[1] = s[1];
  g[2] = -s[2];
}
static void sg_hess(const double *s, double *H, const void *ctx) {
  (void)ctx;
  for (int k = 0; k < 9; k++) H[k] = 0.0;
  H[0] = cos(s[0]);
  H[4] = 1.0;
  H[8] = -1.0;
}

gm_pde_equation gm_pde_sine_gordon(void) {
  gm_pde_equation e = {0};
  e.name = "sine-gordon";
  e.dim = 3;
  /* rows (u, v, w): −v_t + w_x = sin u; u_t = v; −u_x = −w */
  e.W[0 * 3 + 1] = -1.0;
  e.W[1 * 3 + 0] = 1.0;
  e.K[0 * 3 + 2] = 1.0;
  e.K[2 * 3 + 0] = -1.0;
  e.S = sg_S;
  e.gradient = sg_grad;
  e.hessian = sg_hess;
  e.V = sg_V;
  e.dV = sg_dV;
  return e;
}

/* ---- NLS: Islas, Karpeev & Schober, J. Comput. Phys. 173 (2001) ------------------------- */
static double nls_S(const double *s, const void *ctx) {
  (void)ctx;
  double r = s[0] * s[0] + s[1] * s[1];
  return 0.5 * r * r + 0.5 * (s[2] * s[2] + s[3] * s[3]);
}
static void nls_grad(const double *s, double *g, const void *ctx) {
  (void)ctx;
  double r = s[0] * s[0] + s[1] * s[1];
  g[0] = 2.0 * r * s[0];
  g[1] = 2.0 * r * s[1];
  g[2] = s[2];
  g[3] = s[3];
}
static void nls_hess(const double *s, double *H, const void *ctx) {
  (void)ctx;
  double p = s[0], q = s[1], r = p * p + q * q;
  for (int k = 0; k < 16; k++) H[k] = 0.0;
  H[0] = 2.0 * r + 4.0 * p * p;
  H[1] = H[4] = 4.0 * p * q;
  H[5] = 2.0 * r + 4.0 * q * q;
  H[10] = 1.0;
  H[15] = 1.0;
}

gm_pde_equation gm_pde_nls(void) {
  gm_pde_equation e = {0};
  e.name = "nls";
  e.dim = 4;
  /* rows (p, q, v, w): q_t − v_x = 2|ψ|²p; −p_t − w_x = 2|ψ|²q; p_x = v; q_x = w */
  e.W[0 * 4 + 1] = 1.0;
  e.W[1 * 4 + 0] = -1.0;
  e.K[0 * 4 + 2] = -1.0;
  e.K[2 * 4 + 0] = 1.0;
  e.K[1 * 4 + 3] = -1.0;
  e.K[3 * 4 + 1] = 1.0;
  e.S = nls_S;
  e.gradient = nls_grad;
  e.hessian = nls_hess;
  e.has_norm = 1;
  e.norm_a = 0;
  e.norm_b = 1;
  return e;
}

gm_status gm_pde_equation_check(const gm_pde_equation *eq, gm_error *err) {
  if (eq == NULL) return gm_error_set(err, GM_EINVAL, "pde: NULL equation");
  size_t d = eq->dim;
  if (d < 1 || d > GM_PDE_MAX_DIM)
    return gm_error_set(err, GM_EINVAL, "pde: equation dim %zu outside 1..%d", d,
                        GM_PDE_MAX_DIM);
  if (eq->S == NULL || eq->gradient == NULL)
    return gm_error_set(err, GM_EINVAL, "pde: equation needs S and its gradient");
  if ((eq->V == NULL) != (eq->dV == NULL))
    return gm_error_set(err, GM_EINVAL, "pde: set both V and dV, or neither");
  if (eq->has_norm && (eq->norm_a >= d || eq->norm_b >= d || eq->norm_a == eq->norm_b))
    return gm_error_set(err, GM_EINVAL, "pde: norm components out of range");
  for (size_t i = 0; i < d; i++)
    for (size_t j = 0; j < d; j++) {
      double w = eq->W[i * d + j], wt = eq->W[j * d + i];
      double k = eq->K[i * d + j], kt = eq->K[j * d + i];
      if (!isfinite(w) || !isfinite(k) || w != -wt || k != -kt)
        return gm_error_set(err, GM_EINVAL,
                            "pde: W and K must be finite and skew (entry %zu,%zu is not)", i,
                            j);
    }
  return GM_OK;
}

void gm_pde_hessian(gm_pde *p, const double *s, double *H, double *work) {
  size_t d = p->d;
  if (p->eq.hessian != NULL) {
    p->eq.hessian(s, H, p->eq.params);
    return;
  }
  /* central differences of the gradient, symmetrised so the discrete conservation law (which
   * needs a symmetric linearisation) still holds to round-off */
  double *sp = work, *g = work + d;
  for (size_t j = 0; j < d; j++) {
    double hj = 1e-6 * (1.0 + fabs(s[j]));
    for (size_t k = 0; k < d; k++) sp[k] = s[k];
    sp[j] = s[j] + hj;
    p->eq.gradient(sp, g, p->eq.params);
    for (size_t i = 0; i < d; i++) H[i * d + j] = g[i];
    sp[j] = s[j] - hj;
    p->eq.gradient(sp, g, p->eq.params);
    for (size_t i = 0; i < d; i++) H[i * d + j] = (H[i * d + j] - g[i]) / (2.0 * hj);
  }
  for (size_t i = 0; i < d; i++)
    for (size_t j = i + 1; j < d; j++) {
      double m = 0.5 * (H[i * d + j] + H[j * d + i]);
      H[i * d + j] = H[j * d + i] = m;
    }
  p->stats.hessian_fd_evaluations++;
}

/* ---- the schemes ----------------------------------------------------------------------------- */
static const gm_pde_scheme schemes[] = {
    {"preissmann", GM_PDE_PREISSMANN, 2, 2, 1, 0, 0, 0,
     "(ω^{n+1}_{i+½} − ωⁿ_{i+½})/Δt + (κ^{n+½}_{i+1} − κ^{n+½}_i)/Δx = 0, ω from space "
     "averages, κ from time averages",
     "Preissmann box = multisymplectic midpoint: Bridges & Reich, Phys. Lett. A 284 (2001); "
     "seed 004 §2.2 [R] in notes/003-004"},
    {"euler-box", GM_PDE_EULER_BOX, 1, 2, 1, 0, 0, 0,
     "δ_t⁺(dsⁿ⁻¹∧𝕎₊dsⁿ) + δ_x⁺(ds_{i−1}∧𝕂₊ds_i) = 0",
     "Euler box: Moore & Reich, Numer. Math. 95 (2003); Bridges & Reich, J. Phys. A 39 (2006) "
     "§4; seed 004 §2.2 [R]"},
    {"lf", GM_PDE_WAVE_LF, 2, 2, 0, 0, 1, 1, "none exact (explicit leapfrog)",
     "seed 004 sine-Gordon scheme LF (notes/003-004 §2.2, signs restored)"},
    {"ec", GM_PDE_WAVE_EC, 2, 2, 0, 1, 0, 1,
     "E^{n+½} = E^{n−½} (discrete energy, see gm_pde_energy)",
     "seed 004 sine-Gordon scheme EC: V' → (V(u^{n+1}) − V(u^{n−1}))/(u^{n+1} − u^{n−1})"},
    {"ms", GM_PDE_WAVE_MS, 2, 2, 1, 0, 0, 1,
     "the Preissmann law with v, w eliminated",
     "seed 004 sine-Gordon scheme MS, nine-point standard form [R]: A_x δ_t²u − A_t δ_x²u + "
     "¼ΣV'(ū) = 0 (notes/003-004 §2.2; Bridges & Reich 2001)"},
    {"zk", GM_PDE_KDV_ZK, 2, 2, 0, 0, 1, 0,
     "none exact; h Σ u conserved on each level, h Σ u² by the semi-discretisation",
     "Zabusky & Kruskal, Phys. Rev. Lett. 15 (1965) 240, eq. (2): leapfrog with "
     "(u_{i+1}+u_i+u_{i-1})/3 in the convective term; KdV only"},
    {"box-sdirk2", GM_PDE_BOX_SDIRK2, 2, 2, 0, 0, 0, 0,
     "none (dissipative in time: the comparison for the long runs)",
     "the Preissmann box's space part W M_x s_t + K D_x s = grad S(M_x s) with Alexander's "
     "2-stage SDIRK of order 2 (gamma = 1 - 1/sqrt 2; SIAM J. Numer. Anal. 14 (1977) 1006)"},
    {"gauss-prk", GM_PDE_GAUSS_PRK, 4, 4, 1, 0, 0, 0,
     "H Σ_j b_j (ω_j^{n+1} − ω_j^n) + Δt Σ_i b_i (κ_{m+1,i} − κ_{m,i}) = 0 per cell (Gauss "
     "points z_j, nodes Y_i)",
     "2-stage Gauss–Legendre in t and x: S. Reich, J. Comput. Phys. 157 (2000) 473, "
     "eqs. (3.1)–(3.6); Bridges & Reich, J. Phys. A 39 (2006) §4.2"},
};
#define N_SCHEMES (sizeof schemes / sizeof schemes[0])

size_t gm_pde_scheme_count(void) { return N_SCHEMES; }

const gm_pde_scheme *gm_pde_scheme_at(size_t i) { return i < N_SCHEMES ? &schemes[i] : NULL; }

gm_status gm_pde_scheme_find(const char *name, const gm_pde_scheme **out) {
  if (name == NULL || out == NULL) return GM_EINVAL;
  for (size_t i = 0; i < N_SCHEMES; i++)
    if (strcasecmp(name, schemes[i].name) == 0) {
      *out = &schemes[i];
      return GM_OK;
    }
  return GM_ENOTFOUND;
}
