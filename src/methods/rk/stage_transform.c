/* The eigen-decomposition of a Runge–Kutta matrix that splits simplified Newton's stage system
 * (I − hA⊗J) ΔZ = −R into s/2 complex systems of size n and, for odd s, one real one
 * (Butcher (1976); Hairer & Wanner, Solving ODEs II (1996), §IV.8, as RADAU5 does): multiplied
 * by (hA)⁻¹ ⊗ I the system reads ((hA)⁻¹ ⊗ I − I ⊗ J) ΔZ = −((hA)⁻¹ ⊗ I) R, and with
 * A⁻¹ = V Λ V⁻¹ the unknowns ΔW = (V⁻¹ ⊗ I) ΔZ decouple into (λ_k/h I − J) ΔW_k = G_k. For real
 * A the eigenvalues come in conjugate pairs whose blocks are conjugate: one complex system per
 * pair, ΔZ = Σ_real v_k ΔW_k + Σ_pairs 2 Re(v_k ΔW_k). The decomposition is computed once per
 * tableau with LAPACK's dgeev; V is inverted here (s is small). */
#include <complex.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "methods/internal.h"

void gm_stage_transform_free(gm_stage_transform *t) {
  if (t == NULL) return;
  free(t->lambda);
  free(t->v);
  free(t->vinv);
  free(t->ainv);
  free(t);
}

/* Invert the complex s×s matrix a (row-major) into inv by Gauss–Jordan elimination with partial
 * pivoting; a is overwritten. */
static gm_status complex_inverse(size_t s, double complex *a, double complex *inv) {
  for (size_t i = 0; i < s; ++i)
    for (size_t j = 0; j < s; ++j) inv[i * s + j] = i == j;
  for (size_t c = 0; c < s; ++c) {
    size_t p = c;
    for (size_t r = c + 1; r < s; ++r)
      if (cabs(a[r * s + c]) > cabs(a[p * s + c])) p = r;
    if (cabs(a[p * s + c]) == 0.0) return GM_ESINGULAR;
    for (size_t j = 0; j < s; ++j) {
      double complex t = a[c * s + j];
      a[c * s + j] = a[p * s + j];
      a[p * s + j] = t;
      t = inv[c * s + j];
      inv[c * s + j] = inv[p * s + j];
      inv[p * s + j] = t;
    }
    const double complex d = a[c * s + c];
    for (size_t j = 0; j < s; ++j) {
      a[c * s + j] /= d;
      inv[c * s + j] /= d;
    }
    for (size_t r = 0; r < s; ++r) {
      if (r == c) continue;
      const double complex f = a[r * s + c];
      for (size_t j = 0; j < s; ++j) {
        a[r * s + j] -= f * a[c * s + j];
        inv[r * s + j] -= f * inv[c * s + j];
      }
    }
  }
  return GM_OK;
}

gm_status gm_stage_transform_create(size_t s, const double *a, gm_stage_transform **out) {
  *out = NULL;
  if (s == 0 || s > 64) return GM_EINVAL;
  gm_stage_transform *t = calloc(1, sizeof *t);
  double *work = calloc(s * s * 3 + 2 * s, sizeof(double));
  double complex *vfull = calloc(2 * s * s, sizeof(double complex));
  if (t == NULL || work == NULL || vfull == NULL) {
    free(work);
    free(vfull);
    gm_stage_transform_free(t);
    return GM_ENOMEM;
  }
  t->s = s;
  t->ainv = calloc(s * s, sizeof(double));
  t->lambda = calloc(s, sizeof(double complex));
  t->v = calloc(s * s, sizeof(double complex));
  t->vinv = calloc(s * s, sizeof(double complex));
  gm_status st = (t->ainv && t->lambda && t->v && t->vinv) ? GM_OK : GM_ENOMEM;
  double *copy = work, *vr = work + s * s, *m = work + 2 * s * s, *wr = work + 3 * s * s,
         *wi = wr + s;
  /* A⁻¹, column by column */
  for (size_t j = 0; j < s && st == GM_OK; ++j) {
    memcpy(copy, a, s * s * sizeof *a);
    double *col = m + j * s; /* row j of m holds column j of A⁻¹ */
    memset(col, 0, s * sizeof *col);
    col[j] = 1.0;
    st = gm_dense_solve(s, copy, col);
    for (size_t i = 0; i < s && st == GM_OK; ++i) t->ainv[i * s + j] = col[i];
  }
  if (st == GM_OK) {
    memcpy(copy, t->ainv, s * s * sizeof *copy);
    lapack_int info = LAPACKE_dgeev(LAPACK_ROW_MAJOR, 'N', 'V', (lapack_int)s, copy,
                                    (lapack_int)s, wr, wi, NULL, 1, vr, (lapack_int)s);
    if (info != 0) st = GM_ENOCONV;
  }
  /* the full complex V (column k: eigenvector k; a pair j, j+1 stores Re, Im in vr) */
  for (size_t k = 0; k < s && st == GM_OK; ++k) {
    if (wi[k] == 0.0) {
      for (size_t i = 0; i < s; ++i) vfull[i * s + k] = vr[i * s + k];
    } else if (wi[k] > 0.0 && k + 1 < s) {
      for (size_t i = 0; i < s; ++i) {
        vfull[i * s + k] = vr[i * s + k] + I * vr[i * s + k + 1];
        vfull[i * s + k + 1] = vr[i * s + k] - I * vr[i * s + k + 1];
      }
    }
  }
  double complex *vinv_full = vfull + s * s, *vcopy = t->vinv; /* vinv as scratch first */
  if (st == GM_OK) {
    memcpy(vcopy, vfull, s * s * sizeof *vcopy);
    st = complex_inverse(s, vcopy, vinv_full);
  }
  /* keep one block per real eigenvalue and per conjugate pair (the one with Im λ > 0) */
  size_t b = 0;
  for (size_t k = 0; k < s && st == GM_OK; ++k) {
    if (wi[k] < 0.0) continue;
    const int pair = wi[k] > 0.0;
    t->lambda[b] = wr[k] + I * wi[k];
    for (size_t i = 0; i < s; ++i) {
      t->v[i * s + b] = pair ? 2.0 * vfull[i * s + k] : vfull[i * s + k];
      t->vinv[b * s + i] = vinv_full[k * s + i];
    }
    if (pair)
      t->n_pairs++;
    else
      t->n_real++;
    ++b;
  }
  t->n_blocks = b;
  free(work);
  free(vfull);
  if (st != GM_OK) {
    gm_stage_transform_free(t);
    return st;
  }
  *out = t;
  return GM_OK;
}

/* ---- complex LU (row-major, partial pivoting; Golub & Van Loan (2013), Alg. 3.4.1). The
 * diagonal of U is stored inverted. ---- */

gm_status gm_complex_lu_factor(size_t n, double complex *a, int *piv) {
  for (size_t c = 0; c < n; ++c) {
    size_t p = c;
    double best = cabs(a[c * n + c]);
    for (size_t r = c + 1; r < n; ++r) {
      double v = cabs(a[r * n + c]);
      if (v > best) {
        best = v;
        p = r;
      }
    }
    if (!(best > 0.0) || !isfinite(best)) return GM_ESINGULAR;
    piv[c] = (int)p;
    if (p != c)
      for (size_t j = 0; j < n; ++j) {
        double complex t = a[c * n + j];
        a[c * n + j] = a[p * n + j];
        a[p * n + j] = t;
      }
    const double complex inv = 1.0 / a[c * n + c];
    a[c * n + c] = inv; /* the solve multiplies by it: a complex division costs a call */
    for (size_t r = c + 1; r < n; ++r) {
      const double complex f = a[r * n + c] * inv;
      a[r * n + c] = f;
      if (f != 0.0)
        for (size_t j = c + 1; j < n; ++j) a[r * n + j] -= f * a[c * n + j];
    }
  }
  return GM_OK;
}

void gm_complex_lu_solve(size_t n, const double complex *lu, const int *piv, double complex *b) {
  for (size_t i = 0; i < n; ++i) {
    size_t p = (size_t)piv[i];
    if (p != i) {
      double complex t = b[i];
      b[i] = b[p];
      b[p] = t;
    }
  }
  for (size_t i = 0; i < n; ++i) {
    double complex sum = b[i];
    for (size_t j = 0; j < i; ++j) sum -= lu[i * n + j] * b[j];
    b[i] = sum;
  }
  for (size_t i = n; i-- > 0;) {
    double complex sum = b[i];
    for (size_t j = i + 1; j < n; ++j) sum -= lu[i * n + j] * b[j];
    b[i] = sum * lu[i * n + i];
  }
}
