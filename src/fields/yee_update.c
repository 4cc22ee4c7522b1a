/* The Yee updates (seed 000 §3.4.1, notes A10), as d on the primal/dual grid followed by the
 * material Hodge stars:
 *
 *   Ampère, dG = 𝒥 on the dual cell of each primal edge (seed 000 §3.4.1, the D_x update
 *   "(D_x^{n+½} − D_x^{n−½})/Δt = ∂_y H_z − ∂_z H_y − J_x", D_y and D_z cyclically):
 *     curl = (d̃ H)_e = (H_c[q] − H_c[q − s_b]) / h_b − (H_b[q] − H_b[q − s_c]) / h_c
 *     E_a ← ca·E_a + cb·curl,  cb = Δt ⋆_ε⁻¹ / (1 + σΔt/2ε),  ca = (1 − σΔt/2ε)/(1 + σΔt/2ε)
 *   (σ = 0: ca = 1 and this is D^{n+½} = D^{n−½} + Δt d̃H^n with E = ⋆_ε⁻¹ D; the σ term is the
 *   time-centred conduction current of Taflove & Hagness eq. 3.28.)
 *
 *   Faraday, dF = 0 on each primal face (seed 000 §3.4.1, the B_x update
 *   "(B_x^{n+1} − B_x^n)/Δt = ∂_z E_y − ∂_y E_z", B_y and B_z cyclically):
 *     curl = (d E)_f = (E_c[q + s_b] − E_c[q]) / h_b − (E_b[q + s_c] − E_b[q]) / h_c
 *     H_a ← H_a − cbh·curl,  cbh = Δt ⋆_μ⁻¹
 *
 * (a, b, c) runs over (x, y, z) cyclically. 1/h is 1/(κ h) inside CPML layers (Roden & Gedney
 * 2000); the ψ terms are added by separate slab loops (yee_cpml.c). On an axis the dimension
 * lacks the stride is 0, so the difference is exactly 0. One kernel per component and per
 * choice of (uniform/per-location coefficients, lossless/lossy) is selected at create time:
 * no branch on options inside the loops. OpenMP over the two outer loops (z, y rows). */
#include "fields/internal.h"

#define E_KERNEL(NAME, A, B, C, INVB, INVC, UPDATE)                                           \
  static void NAME(gm_yee *s, int p) {                                                        \
    const yee_box *bx = &s->upd[A];                                                           \
    double *restrict E = s->f[p][A];                                                          \
    const double *restrict Hc = s->f[p][3 + C];                                               \
    const double *restrict Hb = s->f[p][3 + B];                                               \
    const long sb = s->s[B], sc = s->s[C];                                                    \
    const double *restrict cbv = s->cb[A];                                                    \
    const double *restrict cav = s->ca[A];                                                    \
    const double cb0 = s->cb0[A], ca0 = s->ca0;                                               \
    const double *ix = s->inv_e[0] + s->L.offset[0], *iy = s->inv_e[1] + s->L.offset[1];      \
    const double *iz = s->inv_e[2] + s->L.offset[2];                                          \
    const long i0 = (long)bx->lo[0], i1 = i0 + (long)bx->cnt[0];                              \
    const long j0 = (long)bx->lo[1], j1 = j0 + (long)bx->cnt[1];                              \
    const long k0 = (long)bx->lo[2], k1 = k0 + (long)bx->cnt[2];                              \
    const int nt = s->n_threads;                                                              \
    const size_t work = bx->cnt[0] * bx->cnt[1] * bx->cnt[2];                                 \
    (void)cbv; (void)cav; (void)cb0; (void)ca0; (void)ix; (void)iy; (void)iz;                 \
    YEE_OMP(omp parallel for collapse(2) schedule(static) num_threads(nt)                     \
                if (work > YEE_OMP_MIN))                                                      \
    for (long k = k0; k < k1; ++k)                                                            \
      for (long j = j0; j < j1; ++j) {                                                        \
        const long row = (long)yee_idx(&s->L, 0, j, k);                                       \
        for (long i = i0; i < i1; ++i) {                                                      \
          const long q = row + i;                                                             \
          const double curl = (Hc[q] - Hc[q - sb]) * (INVB) - (Hb[q] - Hb[q - sc]) * (INVC);  \
          UPDATE;                                                                             \
        }                                                                                     \
      }                                                                                       \
  }

#define H_KERNEL(NAME, A, B, C, INVB, INVC, UPDATE)                                           \
  static void NAME(gm_yee *s, int p) {                                                        \
    const yee_box *bx = &s->upd[3 + A];                                                       \
    double *restrict H = s->f[p][3 + A];                                                      \
    const double *restrict Ec = s->f[p][C];                                                   \
    const double *restrict Eb = s->f[p][B];                                                   \
    const long sb = s->s[B], sc = s->s[C];                                                    \
    const double *restrict cbv = s->cb[3 + A];                                                \
    const double cb0 = s->cb0[3 + A];                                                         \
    const double *ix = s->inv_h[0] + s->L.offset[0], *iy = s->inv_h[1] + s->L.offset[1];      \
    const double *iz = s->inv_h[2] + s->L.offset[2];                                          \
    const long i0 = (long)bx->lo[0], i1 = i0 + (long)bx->cnt[0];                              \
    const long j0 = (long)bx->lo[1], j1 = j0 + (long)bx->cnt[1];                              \
    const long k0 = (long)bx->lo[2], k1 = k0 + (long)bx->cnt[2];                              \
    const int nt = s->n_threads;                                                              \
    const size_t work = bx->cnt[0] * bx->cnt[1] * bx->cnt[2];                                 \
    (void)cbv; (void)cb0; (void)ix; (void)iy; (void)iz;                                       \
    YEE_OMP(omp parallel for collapse(2) schedule(static) num_threads(nt)                     \
                if (work > YEE_OMP_MIN))                                                      \
    for (long k = k0; k < k1; ++k)                                                            \
      for (long j = j0; j < j1; ++j) {                                                        \
        const long row = (long)yee_idx(&s->L, 0, j, k);                                       \
        for (long i = i0; i < i1; ++i) {                                                      \
          const long q = row + i;                                                             \
          const double curl = (Ec[q + sb] - Ec[q]) * (INVB) - (Eb[q + sc] - Eb[q]) * (INVC);  \
          UPDATE;                                                                             \
        }                                                                                     \
      }                                                                                       \
  }

#define E_UNIFORM E[q] += cb0 * curl
#define E_UNIFORM_LOSSY E[q] = ca0 * E[q] + cb0 * curl
#define E_ARRAY E[q] += cbv[q] * curl
#define E_ARRAY_LOSSY E[q] = cav[q] * E[q] + cbv[q] * curl
#define H_UNIFORM H[q] -= cb0 * curl
#define H_ARRAY H[q] -= cbv[q] * curl

/* Ex: b = y, c = z; Ey: b = z, c = x; Ez: b = x, c = y. */
#define E_FAMILY(SUFFIX, UPDATE)                                                              \
  E_KERNEL(ex_##SUFFIX, 0, 1, 2, iy[j], iz[k], UPDATE)                                        \
  E_KERNEL(ey_##SUFFIX, 1, 2, 0, iz[k], ix[i], UPDATE)                                        \
  E_KERNEL(ez_##SUFFIX, 2, 0, 1, ix[i], iy[j], UPDATE)
#define H_FAMILY(SUFFIX, UPDATE)                                                              \
  H_KERNEL(hx_##SUFFIX, 0, 1, 2, iy[j], iz[k], UPDATE)                                        \
  H_KERNEL(hy_##SUFFIX, 1, 2, 0, iz[k], ix[i], UPDATE)                                        \
  H_KERNEL(hz_##SUFFIX, 2, 0, 1, ix[i], iy[j], UPDATE)

E_FAMILY(uniform, E_UNIFORM)
E_FAMILY(uniform_lossy, E_UNIFORM_LOSSY)
E_FAMILY(array, E_ARRAY)
E_FAMILY(array_lossy, E_ARRAY_LOSSY)
H_FAMILY(uniform, H_UNIFORM)
H_FAMILY(array, H_ARRAY)

void yee_select_kernels(gm_yee *s) {
  typedef void (*kernel)(gm_yee *, int);
  static const kernel e_tab[4][3] = {{ex_uniform, ey_uniform, ez_uniform},
                                     {ex_uniform_lossy, ey_uniform_lossy, ez_uniform_lossy},
                                     {ex_array, ey_array, ez_array},
                                     {ex_array_lossy, ey_array_lossy, ez_array_lossy}};
  static const kernel h_tab[2][3] = {{hx_uniform, hy_uniform, hz_uniform},
                                     {hx_array, hy_array, hz_array}};
  const int row = (s->uniform ? 0 : 2) + (s->lossy ? 1 : 0);
  for (int a = 0; a < 3; ++a) {
    s->update_e[a] = s->active[a] ? e_tab[row][a] : NULL;
    s->update_h[a] = s->active[3 + a] ? h_tab[s->uniform ? 0 : 1][a] : NULL;
  }
}

void yee_update_e(gm_yee *s) {
  for (int p = 0; p < s->n_parts; ++p)
    for (int a = 0; a < 3; ++a)
      if (s->update_e[a]) s->update_e[a](s, p);
}

void yee_update_h(gm_yee *s) {
  for (int p = 0; p < s->n_parts; ++p)
    for (int a = 0; a < 3; ++a)
      if (s->update_h[a]) s->update_h[a](s, p);
}
