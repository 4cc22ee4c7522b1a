/* The kick's sums (lanes.h), instantiated by lanes2.c and lanes4.c as ROW_SUMS and
 * CENTRAL_TERMS. Both use four lanes in either instantiation (v4), so the order of every sum,
 * and the result, is the same on every CPU.
 *
 * ROW_SUMS: the Newtonian accelerations of n point masses (G, masses m),
 *   a_i = Σ_{j≠i} G m_j (q_j − q_i)/|q_j − q_i|³,
 * with the positions in separate arrays x, y, z (and m) of np ≥ n entries, np a multiple of
 * 4 (entries from n on are ignored), a in the usual layout (3 values a body), acc 3 np
 * doubles of scratch. Each pair once, four at a time: the bodies go in chunks of four, and the
 * pairs of two chunks A, B are the lanes of A against B rotated by 0..3 lanes (within a chunk:
 * rotations 1 and half of 2), the reactions rotated back into B's sums. A kick's cost is its
 * square roots and divisions, which queue on the one divider, and a vector of four takes it as
 * long as one double (measured on this machine: 2.5 ns a square root, 1.3 ns a division, for
 * 1, 2 or 4 lanes); sums stay in registers (a scatter of each pair's reaction into a_j waited
 * on memory: no faster than scalar code). Returns 1 when two bodies coincide, else 0.
 *
 * CENTRAL_TERMS: out_k = μ_k x_k/|x_k|³, k < count (the Kepler terms of a Jacobi kick), out in
 * the usual layout; 1 when some x_k = 0. */
#include <string.h>

#include "celestial/lanes.h"

/* lane l of the result is lane (l + r) mod 4 of v */
#if defined(__clang__)
#define ROT(v, a, b, c, d) __builtin_shufflevector(v, v, a, b, c, d)
#else
#define ROT(v, a, b, c, d) __builtin_shuffle(v, (v4i){a, b, c, d})
#endif
static inline v4 rot(v4 v, int r) {
  switch (r & 3) { /* r is a constant at every call, so this is one permutation */
  case 1: return ROT(v, 1, 2, 3, 0);
  case 2: return ROT(v, 2, 3, 0, 1);
  case 3: return ROT(v, 3, 0, 1, 2);
  default: return v;
  }
}

typedef struct {
  v4 x, y, z, gm; /* positions and G m of four bodies */
  v4i real;       /* lanes that are bodies (not padding) */
} chunk;

/* Bodies k..k+3; padding lanes (past n) read as 0, whatever the arrays hold. */
static inline chunk load_chunk(size_t n, size_t k, const double *x, const double *y,
                               const double *z, const double *m, double G) {
  chunk c;
  const v4i index = {(long long)k, (long long)k + 1, (long long)k + 2, (long long)k + 3};
  c.real = index < (long long)n;
  c.x = (v4)((v4i)v4_load(x + k) & c.real);
  c.y = (v4)((v4i)v4_load(y + k) & c.real);
  c.z = (v4)((v4i)v4_load(z + k) & c.real);
  c.gm = (v4)((v4i)(v4_splat(G) * v4_load(m + k)) & c.real);
  return c;
}

/* The pairs (lane l of A, lane (l + r) mod 4 of B), those in `use`: A's pull sums into (ax,
 * ay, az), the reactions on B, rotated back into B's lane order, into (bx, by, bz). */
static inline void pairs(const chunk *A, const chunk *B, int r, v4i use, v4 *ax, v4 *ay,
                         v4 *az, v4 *bx, v4 *by, v4 *bz, v4i *coincide) {
  const v4 one = v4_splat(1.0);
  const v4i out = ~(use & A->real & (v4i)rot((v4)B->real, r));
  const v4 dx = rot(B->x, r) - A->x, dy = rot(B->y, r) - A->y, dz = rot(B->z, r) - A->z;
  v4 s = dx * dx + dy * dy + dz * dz;
  s = (v4)(((v4i)s & ~out) | ((v4i)one & out));
  *coincide |= (s == 0.0) & ~out;
  const v4 w = (v4)((v4i)(one / (s * v4_sqrt(s))) & ~out);
  const v4 fa = rot(B->gm, r) * w, fb = A->gm * w;
  *ax += fa * dx;
  *ay += fa * dy;
  *az += fa * dz;
  *bx -= rot(fb * dx, 4 - r);
  *by -= rot(fb * dy, 4 - r);
  *bz -= rot(fb * dz, 4 - r);
}

int ROW_SUMS(size_t n, size_t np, const double *x, const double *y, const double *z,
             const double *m, double G, double *a, double *acc) {
  const v4i all = {-1, -1, -1, -1}, first2 = {-1, -1, 0, 0}, none = {0, 0, 0, 0};
  const v4 zero = v4_splat(0.0);
  v4i coincide = none;
  const size_t nc = np / 4;
  /* accumulators of the chunks, whole vectors in acc (x, y, z of chunk c at 12c) */
  for (size_t c = 0; c < 3 * nc; ++c) memcpy(acc + 4 * c, &zero, sizeof zero);
  for (size_t ca = 0; ca < nc; ++ca) {
    const chunk A = load_chunk(n, 4 * ca, x, y, z, m, G);
    v4 ax = v4_load(acc + 12 * ca), ay = v4_load(acc + 12 * ca + 4),
       az = v4_load(acc + 12 * ca + 8);
    /* within the chunk: rotation 1 gives pairs (0,1), (1,2), (2,3), (3,0); rotation 2 gives
     * (0,2), (1,3) in lanes 0 and 1 (and the same pairs again in lanes 2 and 3) */
    pairs(&A, &A, 1, all, &ax, &ay, &az, &ax, &ay, &az, &coincide);
    pairs(&A, &A, 2, first2, &ax, &ay, &az, &ax, &ay, &az, &coincide);
    for (size_t cb = ca + 1; cb < nc; ++cb) {
      const chunk B = load_chunk(n, 4 * cb, x, y, z, m, G);
      v4 bx = v4_load(acc + 12 * cb), by = v4_load(acc + 12 * cb + 4),
         bz = v4_load(acc + 12 * cb + 8);
      pairs(&A, &B, 0, all, &ax, &ay, &az, &bx, &by, &bz, &coincide);
      pairs(&A, &B, 1, all, &ax, &ay, &az, &bx, &by, &bz, &coincide);
      pairs(&A, &B, 2, all, &ax, &ay, &az, &bx, &by, &bz, &coincide);
      pairs(&A, &B, 3, all, &ax, &ay, &az, &bx, &by, &bz, &coincide);
      memcpy(acc + 12 * cb, &bx, sizeof bx);
      memcpy(acc + 12 * cb + 4, &by, sizeof by);
      memcpy(acc + 12 * cb + 8, &bz, sizeof bz);
    }
    for (size_t l = 0; l < 4 && 4 * ca + l < n; ++l) {
      a[3 * (4 * ca + l)] = ax[l];
      a[3 * (4 * ca + l) + 1] = ay[l];
      a[3 * (4 * ca + l) + 2] = az[l];
    }
  }
  return (coincide[0] | coincide[1] | coincide[2] | coincide[3]) != 0;
}

int CENTRAL_TERMS(size_t count, const double *x, const double *y, const double *z,
                  const double *mu, double *out) {
  const v4 one = v4_splat(1.0);
  const v4i none = {0, 0, 0, 0};
  v4i zero = none;
  for (size_t k = 0; k < count; k += 4) {
    const v4i index = {(long long)k, (long long)k + 1, (long long)k + 2, (long long)k + 3};
    const v4i pad = index >= (long long)count;
    const v4 X = v4_load(x + k), Y = v4_load(y + k), Z = v4_load(z + k);
    v4 s = X * X + Y * Y + Z * Z;
    s = (v4)(((v4i)s & ~pad) | ((v4i)one & pad));
    zero |= s == 0.0;
    const v4 f = v4_load(mu + k) / (s * v4_sqrt(s));
    for (size_t j = 0; j < 4 && k + j < count; ++j) {
      out[3 * (k + j)] = f[j] * X[j];
      out[3 * (k + j) + 1] = f[j] * Y[j];
      out[3 * (k + j) + 2] = f[j] * Z[j];
    }
  }
  return (zero[0] | zero[1] | zero[2] | zero[3]) != 0;
}
