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
 * no branch on options inside the loops. OpenMP over the two outer loops (z, y rows), SIMD over
 * the inner one (elementwise, no reductions: bitwise identical for any thread count). */
#include <limits.h>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <string.h>

#include "fields/internal.h"

/* Runtime CPU dispatch of the update kernels: GCC compiles each kernel for generic x86-64,
 * x86-64-v3 (AVX2) and x86-64-v4 (AVX-512) and picks one by the CPU at load time (ifunc), so a
 * generic build runs the wide kernels where the CPU has them. The project compiles with
 * -ffp-contract=off, so no clone fuses a multiply and an add: every clone rounds exactly as
 * the generic one and results do not depend on the CPU (checked by hand: the fields after 150
 * steps of a vacuum PEC box and of a CPML box with lossy media compare equal byte for byte
 * between this build, running the AVX-512 clones, and a GM_CPU_DISPATCH=OFF build;
 * docs/maxwell.md). GM_NO_CPU_DISPATCH (CMake GM_CPU_DISPATCH=OFF) turns it off. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    !defined(GM_NO_CPU_DISPATCH)
#define YEE_CLONES __attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
#else
#define YEE_CLONES
#endif

/* TEAM kernels share their rows among the threads of the enclosing parallel region (orphaned
 * `omp for`); ONE kernels run all their rows on the calling thread (the one-sweep step gives each
 * thread its own planes). */
#define YEE_FOR_TEAM YEE_OMP(omp for collapse(2) schedule(static) nowait)
#define YEE_FOR_ONE

#define E_KERNEL(MODE, NAME, A, B, C, INVB, INVC, UPDATE)                                           \
  YEE_CLONES static void NAME(gm_yee *s, int p, const yee_box *bx) {                                    \
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
    (void)cbv; (void)cav; (void)cb0; (void)ca0; (void)ix; (void)iy; (void)iz;                 \
    YEE_FOR_##MODE                                                                            \
    for (long k = k0; k < k1; ++k)                                                            \
      for (long j = j0; j < j1; ++j) {                                                        \
        const long row = (long)yee_idx(&s->L, 0, j, k);                                       \
        YEE_OMP(omp simd)                                                                     \
        for (long i = i0; i < i1; ++i) {                                                      \
          const long q = row + i;                                                             \
          const double curl = (Hc[q] - Hc[q - sb]) * (INVB) - (Hb[q] - Hb[q - sc]) * (INVC);  \
          UPDATE;                                                                             \
        }                                                                                     \
      }                                                                                       \
  }

#define H_KERNEL(MODE, NAME, A, B, C, INVB, INVC, UPDATE)                                           \
  YEE_CLONES static void NAME(gm_yee *s, int p, const yee_box *bx) {                                    \
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
    (void)cbv; (void)cb0; (void)ix; (void)iy; (void)iz;                                       \
    YEE_FOR_##MODE                                                                            \
    for (long k = k0; k < k1; ++k)                                                            \
      for (long j = j0; j < j1; ++j) {                                                        \
        const long row = (long)yee_idx(&s->L, 0, j, k);                                       \
        YEE_OMP(omp simd)                                                                     \
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
#define E_FAMILY(MODE, SUFFIX, UPDATE)                                                        \
  E_KERNEL(MODE, ex_##SUFFIX, 0, 1, 2, iy[j], iz[k], UPDATE)                                  \
  E_KERNEL(MODE, ey_##SUFFIX, 1, 2, 0, iz[k], ix[i], UPDATE)                                  \
  E_KERNEL(MODE, ez_##SUFFIX, 2, 0, 1, ix[i], iy[j], UPDATE)
#define H_FAMILY(MODE, SUFFIX, UPDATE)                                                        \
  H_KERNEL(MODE, hx_##SUFFIX, 0, 1, 2, iy[j], iz[k], UPDATE)                                  \
  H_KERNEL(MODE, hy_##SUFFIX, 1, 2, 0, iz[k], ix[i], UPDATE)                                  \
  H_KERNEL(MODE, hz_##SUFFIX, 2, 0, 1, ix[i], iy[j], UPDATE)

E_FAMILY(TEAM, uniform, E_UNIFORM)
E_FAMILY(TEAM, uniform_lossy, E_UNIFORM_LOSSY)
E_FAMILY(TEAM, array, E_ARRAY)
E_FAMILY(TEAM, array_lossy, E_ARRAY_LOSSY)
H_FAMILY(TEAM, uniform, H_UNIFORM)
H_FAMILY(TEAM, array, H_ARRAY)
E_FAMILY(ONE, uniform_1, E_UNIFORM)
E_FAMILY(ONE, uniform_lossy_1, E_UNIFORM_LOSSY)
E_FAMILY(ONE, array_1, E_ARRAY)
E_FAMILY(ONE, array_lossy_1, E_ARRAY_LOSSY)
H_FAMILY(ONE, uniform_1, H_UNIFORM)
H_FAMILY(ONE, array_1, H_ARRAY)

/* 3-D: all three components of E (or H) in one sweep, so each array is streamed once per half
 * step. Per element the arithmetic is exactly the single-component kernels' (same operations in
 * the same order), so fused and unfused runs agree bitwise. */
#define FUSED_E(MODE, NAME, UPDATE)                                                                \
  YEE_CLONES static void NAME(gm_yee *s, int p, const yee_box *bx) {                                    \
    double *restrict Ex = s->f[p][0], *restrict Ey = s->f[p][1], *restrict Ez = s->f[p][2];   \
    const double *restrict Hx = s->f[p][3], *restrict Hy = s->f[p][4];                        \
    const double *restrict Hz = s->f[p][5];                                                   \
    const long sx = s->s[0], sy = s->s[1], sz = s->s[2];                                      \
    const double *restrict cbx = s->cb[0], *restrict cby = s->cb[1], *restrict cbz = s->cb[2]; \
    const double *restrict cax = s->ca[0], *restrict cay = s->ca[1], *restrict caz = s->ca[2]; \
    const double cb0x = s->cb0[0], cb0y = s->cb0[1], cb0z = s->cb0[2], ca0 = s->ca0;          \
    const double *ix = s->inv_e[0] + s->L.offset[0], *iy = s->inv_e[1] + s->L.offset[1];      \
    const double *iz = s->inv_e[2] + s->L.offset[2];                                          \
    const long i0 = (long)bx->lo[0], i1 = i0 + (long)bx->cnt[0];                              \
    const long j0 = (long)bx->lo[1], j1 = j0 + (long)bx->cnt[1];                              \
    const long k0 = (long)bx->lo[2], k1 = k0 + (long)bx->cnt[2];                              \
    (void)cbx; (void)cby; (void)cbz; (void)cax; (void)cay; (void)caz; (void)ca0;              \
    (void)cb0x; (void)cb0y; (void)cb0z;                                                       \
    YEE_FOR_##MODE                                                                            \
    for (long k = k0; k < k1; ++k)                                                            \
      for (long j = j0; j < j1; ++j) {                                                        \
        const long row = (long)yee_idx(&s->L, 0, j, k);                                       \
        const double iyj = iy[j], izk = iz[k];                                                \
        YEE_OMP(omp simd)                                                                     \
        for (long i = i0; i < i1; ++i) {                                                      \
          const long q = row + i;                                                             \
          const double cx = (Hz[q] - Hz[q - sy]) * iyj - (Hy[q] - Hy[q - sz]) * izk;          \
          const double cy = (Hx[q] - Hx[q - sz]) * izk - (Hz[q] - Hz[q - sx]) * ix[i];        \
          const double cz = (Hy[q] - Hy[q - sx]) * ix[i] - (Hx[q] - Hx[q - sy]) * iyj;        \
          UPDATE; /* the three components, in order (comma operator) */                     \
        }                                                                                     \
      }                                                                                       \
  }

#define FUSED_H(MODE, NAME, UPDATE)                                                                \
  YEE_CLONES static void NAME(gm_yee *s, int p, const yee_box *bx) {                                    \
    double *restrict Hx = s->f[p][3], *restrict Hy = s->f[p][4], *restrict Hz = s->f[p][5];   \
    const double *restrict Ex = s->f[p][0], *restrict Ey = s->f[p][1];                        \
    const double *restrict Ez = s->f[p][2];                                                   \
    const long sx = s->s[0], sy = s->s[1], sz = s->s[2];                                      \
    const double *restrict cbx = s->cb[3], *restrict cby = s->cb[4], *restrict cbz = s->cb[5]; \
    const double cb0x = s->cb0[3], cb0y = s->cb0[4], cb0z = s->cb0[5];                        \
    const double *ix = s->inv_h[0] + s->L.offset[0], *iy = s->inv_h[1] + s->L.offset[1];      \
    const double *iz = s->inv_h[2] + s->L.offset[2];                                          \
    const long i0 = (long)bx->lo[0], i1 = i0 + (long)bx->cnt[0];                              \
    const long j0 = (long)bx->lo[1], j1 = j0 + (long)bx->cnt[1];                              \
    const long k0 = (long)bx->lo[2], k1 = k0 + (long)bx->cnt[2];                              \
    (void)cbx; (void)cby; (void)cbz; (void)cb0x; (void)cb0y; (void)cb0z;                      \
    YEE_FOR_##MODE                                                                            \
    for (long k = k0; k < k1; ++k)                                                            \
      for (long j = j0; j < j1; ++j) {                                                        \
        const long row = (long)yee_idx(&s->L, 0, j, k);                                       \
        const double iyj = iy[j], izk = iz[k];                                                \
        YEE_OMP(omp simd)                                                                     \
        for (long i = i0; i < i1; ++i) {                                                      \
          const long q = row + i;                                                             \
          const double cx = (Ez[q + sy] - Ez[q]) * iyj - (Ey[q + sz] - Ey[q]) * izk;          \
          const double cy = (Ex[q + sz] - Ex[q]) * izk - (Ez[q + sx] - Ez[q]) * ix[i];        \
          const double cz = (Ey[q + sx] - Ey[q]) * ix[i] - (Ex[q + sy] - Ex[q]) * iyj;        \
          UPDATE; /* the three components, in order (comma operator) */                     \
        }                                                                                     \
      }                                                                                       \
  }

#define E3_UNIFORM Ex[q] += cb0x * cx, Ey[q] += cb0y * cy, Ez[q] += cb0z * cz
#define E3_UNIFORM_LOSSY                                                                      \
  Ex[q] = ca0 * Ex[q] + cb0x * cx, Ey[q] = ca0 * Ey[q] + cb0y * cy, Ez[q] = ca0 * Ez[q] + cb0z * cz
#define E3_ARRAY Ex[q] += cbx[q] * cx, Ey[q] += cby[q] * cy, Ez[q] += cbz[q] * cz
#define E3_ARRAY_LOSSY                                                                        \
  Ex[q] = cax[q] * Ex[q] + cbx[q] * cx, Ey[q] = cay[q] * Ey[q] + cby[q] * cy,                 \
  Ez[q] = caz[q] * Ez[q] + cbz[q] * cz
#define H3_UNIFORM Hx[q] -= cb0x * cx, Hy[q] -= cb0y * cy, Hz[q] -= cb0z * cz
#define H3_ARRAY Hx[q] -= cbx[q] * cx, Hy[q] -= cby[q] * cy, Hz[q] -= cbz[q] * cz
#define FUSED_FAMILY(MODE, SUFFIX)                                                            \
  FUSED_E(MODE, e3_uniform##SUFFIX, E3_UNIFORM)                                               \
  FUSED_E(MODE, e3_uniform_lossy##SUFFIX, E3_UNIFORM_LOSSY)                                   \
  FUSED_E(MODE, e3_array##SUFFIX, E3_ARRAY)                                                   \
  FUSED_E(MODE, e3_array_lossy##SUFFIX, E3_ARRAY_LOSSY)                                       \
  FUSED_H(MODE, h3_uniform##SUFFIX, H3_UNIFORM)                                               \
  FUSED_H(MODE, h3_array##SUFFIX, H3_ARRAY)
FUSED_FAMILY(TEAM, )
FUSED_FAMILY(ONE, _1)

/* The box the three components share, and each component's range minus it as ≤ 6 slabs. */
static void split_ranges(gm_yee *s, int first, int fuse) {
  yee_box in = s->upd[first];
  for (int c = first; c < first + 3; ++c)
    for (int a = 0; a < 3; ++a) {
      const size_t lo = s->upd[c].lo[a] > in.lo[a] ? s->upd[c].lo[a] : in.lo[a];
      const size_t hi_c = s->upd[c].lo[a] + s->upd[c].cnt[a], hi_i = in.lo[a] + in.cnt[a];
      const size_t hi = hi_c < hi_i ? hi_c : hi_i;
      in.lo[a] = lo;
      in.cnt[a] = hi > lo ? hi - lo : 0;
    }
  const int empty = !fuse || in.cnt[0] == 0 || in.cnt[1] == 0 || in.cnt[2] == 0;
  if (empty) memset(&in, 0, sizeof in);
  s->fused_box[first / 3] = in;
  for (int c = first; c < first + 3; ++c) {
    s->n_rest[c] = 0;
    yee_box cur = s->upd[c];
    if (cur.cnt[0] == 0 || cur.cnt[1] == 0 || cur.cnt[2] == 0) continue;
    if (empty) {
      s->rest[c][s->n_rest[c]++] = cur;
      continue;
    }
    for (int a = 0; a < 3; ++a) {
      const size_t hi_c = cur.lo[a] + cur.cnt[a], hi_i = in.lo[a] + in.cnt[a];
      if (cur.lo[a] < in.lo[a]) {
        yee_box b = cur;
        b.cnt[a] = in.lo[a] - cur.lo[a];
        s->rest[c][s->n_rest[c]++] = b;
      }
      if (hi_c > hi_i) {
        yee_box b = cur;
        b.lo[a] = hi_i;
        b.cnt[a] = hi_c - hi_i;
        s->rest[c][s->n_rest[c]++] = b;
      }
      cur.lo[a] = in.lo[a];
      cur.cnt[a] = in.cnt[a];
    }
  }
}

void yee_select_kernels(gm_yee *s) {
  typedef void (*kernel)(gm_yee *, int, const yee_box *);
  static const kernel e_tab[4][3] = {{ex_uniform, ey_uniform, ez_uniform},
                                     {ex_uniform_lossy, ey_uniform_lossy, ez_uniform_lossy},
                                     {ex_array, ey_array, ez_array},
                                     {ex_array_lossy, ey_array_lossy, ez_array_lossy}};
  static const kernel h_tab[2][3] = {{hx_uniform, hy_uniform, hz_uniform},
                                     {hx_array, hy_array, hz_array}};
  static const kernel e3_tab[4] = {e3_uniform, e3_uniform_lossy, e3_array, e3_array_lossy};
  static const kernel h3_tab[2] = {h3_uniform, h3_array};
  static const kernel e1_tab[4][3] = {{ex_uniform_1, ey_uniform_1, ez_uniform_1},
                                      {ex_uniform_lossy_1, ey_uniform_lossy_1, ez_uniform_lossy_1},
                                      {ex_array_1, ey_array_1, ez_array_1},
                                      {ex_array_lossy_1, ey_array_lossy_1, ez_array_lossy_1}};
  static const kernel h1_tab[2][3] = {{hx_uniform_1, hy_uniform_1, hz_uniform_1},
                                      {hx_array_1, hy_array_1, hz_array_1}};
  static const kernel e31_tab[4] = {e3_uniform_1, e3_uniform_lossy_1, e3_array_1,
                                    e3_array_lossy_1};
  static const kernel h31_tab[2] = {h3_uniform_1, h3_array_1};
  const int row = (s->uniform ? 0 : 2) + (s->lossy ? 1 : 0);
  for (int a = 0; a < 3; ++a) {
    s->update_e[a] = s->active[a] ? e_tab[row][a] : NULL;
    s->update_h[a] = s->active[3 + a] ? h_tab[s->uniform ? 0 : 1][a] : NULL;
    s->update_e1[a] = s->active[a] ? e1_tab[row][a] : NULL;
    s->update_h1[a] = s->active[3 + a] ? h1_tab[s->uniform ? 0 : 1][a] : NULL;
  }
  const int fuse = s->L.dim == GM_YEE_3D;
  s->fused_e = fuse ? e3_tab[row] : NULL;
  s->fused_h = fuse ? h3_tab[s->uniform ? 0 : 1] : NULL;
  s->fused_e1 = fuse ? e31_tab[row] : NULL;
  s->fused_h1 = fuse ? h31_tab[s->uniform ? 0 : 1] : NULL;
  split_ranges(s, 0, fuse);
  split_ranges(s, 3, fuse);
}

/* One parallel region per half step: the three components of a field do not read each other,
 * so their loops run back to back without barriers (orphaned `omp for nowait` in the kernels);
 * the region's end is the one barrier. */
static size_t largest_box(const gm_yee *s, int first) {
  size_t w = 0;
  for (int c = first; c < first + 3; ++c) {
    const size_t v = s->upd[c].cnt[0] * s->upd[c].cnt[1] * s->upd[c].cnt[2];
    w = v > w ? v : w;
  }
  return w;
}

static void update_field(gm_yee *s, int first) {
  const int nt = s->n_threads;
  const int big = largest_box(s, first) > YEE_OMP_MIN;
  void (*const *one)(gm_yee *, int, const yee_box *) = first == 0 ? s->update_e : s->update_h;
  void (*fused)(gm_yee *, int, const yee_box *) = first == 0 ? s->fused_e : s->fused_h;
  const yee_box *fb = &s->fused_box[first / 3];
  (void)nt;
  (void)big;
  YEE_OMP(omp parallel num_threads(nt) if (big))
  for (int p = 0; p < s->n_parts; ++p) {
    if (fused != NULL && fb->cnt[0] > 0) fused(s, p, fb);
    for (int a = 0; a < 3; ++a)
      if (one[a] != NULL)
        for (size_t r = 0; r < s->n_rest[first + a]; ++r) one[a](s, p, &s->rest[first + a][r]);
  }
}

void yee_update_e(gm_yee *s) { update_field(s, 0); }
void yee_update_h(gm_yee *s) { update_field(s, 3); }

/* ---- one step as a single sweep over z planes ----
 * E at index q reads H at q and q − s (Ampère), H at q reads E at q and q + s (Faraday). So
 * in index space E plane k needs H planes k and k−1 at the old level, and H plane k−1 needs E
 * planes k−1 and k at the new level. One pass k = kmin … kmax+1 that updates E plane k, adds
 * the E sources of that plane, then updates H plane k−1 therefore computes exactly the
 * two-sweep step (each location runs the same kernel arithmetic on the same inputs: bitwise
 * identical), while the E and H planes it touches twice stay in cache: per step each field
 * array is read and written once instead of read twice. Used only where nothing else acts
 * between the two half steps across whole planes: no CPML ψ slabs, no TF/SF, no periodic
 * ghost copies (see yee_wavefront_eligible).
 *
 * Threads: thread t takes the E and H planes [a_t, a_{t+1}). Its first E plane reads H plane
 * a_t − 1, which thread t − 1 updates last; its last H plane reads E plane a_{t+1}, which thread
 * t + 1 updates first. So every thread but the first updates its first E plane, one barrier,
 * then each sweeps the rest of its planes: one barrier a step, no plane read while written. */
/* Each plane is walked in strips of rows, E strip then H strip below it: E(k, j) reads H(k − 1)
 * only at the same j and H(k − 1, j) reads E(k) only at the same j, so the strip order is free,
 * and the E(k) and H(k − 1) rows just touched stay in L2 (a 128² plane of six arrays does not).
 * Measured at load 1 on the 128³ cavity, one thread: whole planes 244–254 Mcells·steps/s, strips
 * of 8 rows 253, 16 262, 32 265–269, 48 267, 64 268 (docs/maxwell.md). */
#define YEE_STRIP_ROWS 32

/* b restricted to plane k and rows [j0, j1); 0 when that is empty. */
static int box_in_strip(const yee_box *b, long k, long j0, long j1, yee_box *out) {
  const long blo = (long)b->lo[1], bhi = blo + (long)b->cnt[1];
  const long lo = j0 > blo ? j0 : blo, hi = j1 < bhi ? j1 : bhi;
  if (b->cnt[0] == 0 || hi <= lo || k < (long)b->lo[2] || k >= (long)(b->lo[2] + b->cnt[2]))
    return 0;
  *out = *b;
  out->lo[1] = (size_t)lo;
  out->cnt[1] = (size_t)(hi - lo);
  out->lo[2] = (size_t)k;
  out->cnt[2] = 1;
  return 1;
}

static void strip_field(gm_yee *s, int first, long k, long j0, long j1) {
  void (*const *one)(gm_yee *, int, const yee_box *) = first == 0 ? s->update_e1 : s->update_h1;
  void (*fused)(gm_yee *, int, const yee_box *) = first == 0 ? s->fused_e1 : s->fused_h1;
  yee_box b;
  if (fused != NULL && box_in_strip(&s->fused_box[first / 3], k, j0, j1, &b)) fused(s, 0, &b);
  for (int a = 0; a < 3; ++a)
    if (one[a] != NULL)
      for (size_t r = 0; r < s->n_rest[first + a]; ++r)
        if (box_in_strip(&s->rest[first + a][r], k, j0, j1, &b)) one[a](s, 0, &b);
}

/* E on rows [j0, j1) of plane k and the E sources there (contiguous in memory: x fastest). */
static void strip_e(gm_yee *s, long k, long j0, long j1) {
  const long row = (long)s->L.stride[1], plane = (long)s->L.stride[2];
  strip_field(s, 0, k, j0, j1);
  const size_t lo = (size_t)((k + (long)s->L.offset[2]) * plane + (j0 + (long)s->L.offset[1]) * row);
  yee_sources_apply_plane(s, lo, (size_t)((j1 - j0) * row));
  yee_dispersive_apply_range(s, lo, (size_t)((j1 - j0) * row));
}

int yee_wavefront_eligible(const gm_yee *s) {
  if (s->L.dim != GM_YEE_3D || s->n_parts != 1 || s->n_cpml != 0 || s->n_tfsf != 0) return 0;
  if (s->fused_e1 == NULL || s->opt.sweep == GM_YEE_SWEEP_HALF_STEPS) return 0;
  if (s->aniso != NULL) return 0; /* its pass needs the whole E half step */
  for (int a = 0; a < 3; ++a)
    if (s->periodic[a]) return 0;
  return 1;
}

int gm_yee_one_sweep(const gm_yee *s) { return s != NULL && yee_wavefront_eligible(s); }

void yee_step_wavefront(gm_yee *s) {
  long k0 = LONG_MAX, k1 = LONG_MIN, jlo = LONG_MAX, jhi = LONG_MIN;
  for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c)
    if (s->upd[c].cnt[2] > 0 && s->upd[c].cnt[1] > 0) {
      k0 = (long)s->upd[c].lo[2] < k0 ? (long)s->upd[c].lo[2] : k0;
      const long hi = (long)(s->upd[c].lo[2] + s->upd[c].cnt[2]);
      k1 = hi > k1 ? hi : k1;
      jlo = (long)s->upd[c].lo[1] < jlo ? (long)s->upd[c].lo[1] : jlo;
      const long hj = (long)(s->upd[c].lo[1] + s->upd[c].cnt[1]);
      jhi = hj > jhi ? hj : jhi;
    }
  const long rows = YEE_STRIP_ROWS;
  /* threads only on grids above the OpenMP threshold, with ≥ 2 planes each */
  int nt = largest_box(s, 0) > YEE_OMP_MIN ? s->n_threads : 1;
  if (nt > (k1 - k0) / 2) nt = (int)((k1 - k0) / 2) > 1 ? (int)((k1 - k0) / 2) : 1;
  YEE_OMP(omp parallel num_threads(nt))
  {
    int t = 0, team = 1;
#ifdef _OPENMP
    t = omp_get_thread_num();
    team = omp_get_num_threads();
#endif
    const long a = k0 + (k1 - k0) * t / team, b = k0 + (k1 - k0) * (t + 1) / team;
    if (t > 0)
      for (long j = jlo; j < jhi; j += rows) strip_e(s, a, j, j + rows < jhi ? j + rows : jhi);
    YEE_OMP(omp barrier)
    for (long k = a; k <= b; ++k)
      for (long j = jlo; j < jhi; j += rows) {
        const long je = j + rows < jhi ? j + rows : jhi;
        if (k < b && (t == 0 || k > a)) strip_e(s, k, j, je);
        if (k > a) strip_field(s, 3, k - 1, j, je);
      }
  }
}
