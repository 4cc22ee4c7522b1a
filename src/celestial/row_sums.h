/* The kick's sums (lanes.h), instantiated by lanes2.c and lanes4.c as ROW_SUMS and
 * CENTRAL_TERMS. Both use four lanes in either instantiation (v4), so the order of every sum,
 * and the result, is the same on every CPU.
 *
 * ROW_SUMS: the Newtonian accelerations of n point masses (G, masses m),
 *   a_i = Σ_{j≠i} G m_j (q_j − q_i)/|q_j − q_i|³,
 * with the positions in separate arrays x, y, z (and m) of np ≥ n entries, np a multiple of
 * 4 (entries from n on are ignored), a in the usual layout (3 values a body). Row by row, four
 * j at a time, every pair twice: a kick's cost is its square roots and divisions, which queue
 * on the one divider, and a vector of four takes it as long as one double (measured on this
 * machine: 2.5 ns a square root, 1.3 ns a division, for 1, 2 or 4 lanes); sums by rows stay in
 * registers, where the symmetric half (each pair once, scattered into a_j) waits on memory
 * (measured: no faster than scalar code). Returns 1 when two bodies coincide, else 0.
 *
 * CENTRAL_TERMS: out_k = μ_k x_k/|x_k|³, k < count (the Kepler terms of a Jacobi kick), out in
 * the usual layout; 1 when some x_k = 0. */
#include "celestial/lanes.h"

int ROW_SUMS(size_t n, size_t np, const double *x, const double *y, const double *z,
             const double *m, double G, double *a) {
  const v4 one = v4_splat(1.0), g = v4_splat(G);
  const v4i none = {0, 0, 0, 0};
  v4i coincide = none;
  for (size_t i = 0; i < n; ++i) {
    const v4 xi = v4_splat(x[i]), yi = v4_splat(y[i]), zi = v4_splat(z[i]);
    v4 ax = v4_splat(0.0), ay = ax, az = ax;
    for (size_t j = 0; j < np; j += 4) {
      const v4i index = {(long long)j, (long long)j + 1, (long long)j + 2, (long long)j + 3};
      const v4i out = (index == (long long)i) | (index >= (long long)n); /* self, padding */
      const v4 dx = v4_load(x + j) - xi, dy = v4_load(y + j) - yi, dz = v4_load(z + j) - zi;
      v4 s = dx * dx + dy * dy + dz * dz;
      s = (v4)(((v4i)s & ~out) | ((v4i)one & out));
      coincide |= s == 0.0;
      const v4 f = (v4)((v4i)(g * v4_load(m + j)) & ~out) / (s * v4_sqrt(s));
      ax += f * dx;
      ay += f * dy;
      az += f * dz;
    }
    a[3 * i] = (ax[0] + ax[1]) + (ax[2] + ax[3]);
    a[3 * i + 1] = (ay[0] + ay[1]) + (ay[2] + ay[3]);
    a[3 * i + 2] = (az[0] + az[1]) + (az[2] + az[3]);
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
