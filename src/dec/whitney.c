/* Simplex quadrature, the de Rham map, Whitney interpolation, and the operators built on the
 * Whitney interpolant: interior product and Lie derivative (seed 001 §3.8).
 *
 * Whitney forms (Whitney, "Geometric integration theory", 1957; Bossavit 1988): in a top simplex
 * T with barycentric coordinates λ_i, the form of the k-face [i_0..i_k] is
 *   φ = k! Σ_j (−1)^j λ_{i_j} dλ_{i_0} ∧ .. (omit j) .. ∧ dλ_{i_k},
 * and on vectors u_1..u_k, dλ_{a_1}∧..∧dλ_{a_k}(u_1..u_k) = det[∇λ_{a_i}·u_m]. A k-form is
 * integrated over a k-simplex [q_0..q_k] as (1/k!) Σ_q w_q ω(x_q)(q_1 − q_0, .., q_k − q_0)
 * with a rule whose weights sum to 1.
 *
 * Simplex rule: the collapsed (Duffy) coordinates t_1 = u_1, t_2 = u_2 (1 − u_1),
 * t_3 = u_3 (1 − u_1)(1 − u_2) map the unit cube onto the reference simplex with Jacobian
 * Π_i (1 − u_i)^{k−i} (Stroud, "Approximate calculation of multiple integrals", 1971, §2.7 —
 * the conical product rule, here with Gauss–Legendre instead of Gauss–Jacobi points, one more
 * point per direction to absorb the Jacobian). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dec/internal.h"

static const double fact[] = {1.0, 1.0, 2.0, 6.0, 24.0};

gm_status gm_simplex_quadrature(size_t k, size_t degree, size_t *n_points, double *bary,
                                double *weights) {
  if (n_points == NULL || k > 3 || degree > 1000) return GM_EINVAL;
  const size_t m = (degree + k) / 2 + 1;
  size_t np = 1;
  for (size_t i = 0; i < k; ++i) np *= m;
  *n_points = np;
  if (bary == NULL) return GM_OK;
  if (weights == NULL) return GM_EINVAL;
  if (k == 0) {
    bary[0] = 1.0;
    weights[0] = 1.0;
    return GM_OK;
  }
  double *x = malloc(2 * m * sizeof(double));
  if (x == NULL) return GM_ENOMEM;
  double *w = x + m;
  gm_status st = gm_gauss_legendre(m, x, w);
  if (st != GM_OK) {
    free(x);
    return st;
  }
  gm_quadrature_map(m, 0.0, 1.0, x, w);
  for (size_t q = 0; q < np; ++q) {
    size_t idx = q;
    double t[3], weight = fact[k], scale = 1.0, sum = 0.0;
    for (size_t i = 0; i < k; ++i) {
      size_t a = idx % m;
      idx /= m;
      double u = x[a];
      t[i] = u * scale;
      weight *= w[a];
      for (size_t e = 0; e < k - 1 - i; ++e) weight *= 1.0 - u;
      scale *= 1.0 - u;
    }
    for (size_t i = 0; i < k; ++i) {
      bary[q * (k + 1) + i + 1] = t[i];
      sum += t[i];
    }
    bary[q * (k + 1)] = 1.0 - sum;
    weights[q] = weight;
  }
  free(x);
  return GM_OK;
}

gm_status gm_dec_de_rham(const gm_complex *cx, size_t k, gm_form_fn form, void *ctx,
                         size_t degree, double *out, gm_error *err) {
  if (cx == NULL || form == NULL || out == NULL || k > cx->n)
    return gm_error_set(err, GM_EINVAL, "de Rham map: NULL argument or degree k > n");
  const size_t N = cx->N;
  size_t np = 0;
  gm_status st = gm_simplex_quadrature(k, degree, &np, NULL, NULL);
  if (st != GM_OK) return gm_error_set(err, st, "quadrature degree %zu too large", degree);
  double *bary = malloc(np * (k + 1 + 1) * sizeof(double));
  if (bary == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory for %zu points", np);
  double *w = bary + np * (k + 1);
  st = gm_simplex_quadrature(k, degree, &np, bary, w);
  if (st != GM_OK) {
    free(bary);
    return gm_error_set(err, st, "quadrature rule failed");
  }
  double p[GM_LOCAL_MAX * GM_DEC_MAX_EMBED], u[3 * GM_DEC_MAX_EMBED], x[GM_DEC_MAX_EMBED];
  for (size_t s = 0; s < cx->count[k] && st == GM_OK; ++s) {
    gm_gather_points(cx, k, cx->simplices[k] + s * (k + 1), p);
    for (size_t i = 1; i <= k; ++i)
      for (size_t j = 0; j < N; ++j) u[(i - 1) * N + j] = p[i * N + j] - p[j];
    double sum = 0.0;
    for (size_t q = 0; q < np; ++q) {
      for (size_t j = 0; j < N; ++j) {
        double v = 0.0;
        for (size_t i = 0; i <= k; ++i) v += bary[q * (k + 1) + i] * p[i * N + j];
        x[j] = v;
      }
      double val = 0.0;
      int rc = form(ctx, x, u, &val);
      if (rc != 0) {
        st = gm_error_set(err, GM_ECALLBACK, "form callback returned %d on %zu-simplex %zu", rc,
                          k, s);
        break;
      }
      if (!isfinite(val)) {
        st = gm_error_set(err, GM_EDOMAIN, "form is not finite on %zu-simplex %zu", k, s);
        break;
      }
      sum += w[q] * val;
    }
    out[s] = sum / fact[k] * gm_simplex_sign(cx, k, s);
  }
  free(bary);
  return st;
}

/* ---- Whitney forms on one top simplex ----------------------------------------------------- */

static double det_k(size_t k, double a[3][3]) {
  if (k == 0) return 1.0;
  if (k == 1) return a[0][0];
  if (k == 2) return a[0][0] * a[1][1] - a[0][1] * a[1][0];
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
         a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

/* The local frame of top simplex T: points, barycentric gradients, local k-face masks and the
 * Whitney coefficients of α (value on each local face in its ascending orientation). */
typedef struct {
  size_t n, N, k, nl;
  double p[GM_LOCAL_MAX * GM_DEC_MAX_EMBED];
  double grad[GM_LOCAL_MAX * GM_DEC_MAX_EMBED];
  unsigned masks[6];
  double c[6];
} whitney_frame;

static void masks_of(size_t n, size_t k, unsigned *masks) {
  size_t q = 0;
  for (unsigned s = 1; s < (1u << (n + 1)); ++s)
    if ((size_t)__builtin_popcount(s) == k + 1) masks[q++] = s;
  /* lexicographic order of the position tuples (bit order of s is not lexicographic for
   * tuples): sort by tuple */
  for (size_t i = 1; i < q; ++i)
    for (size_t j = i; j > 0; --j) {
      unsigned a = masks[j - 1], b = masks[j];
      /* compare tuples: first differing lowest set bit */
      unsigned da = a & ~b, db = b & ~a;
      int a_first = (da & (~da + 1u)) < (db & (~db + 1u)); /* a has the smaller differing position */
      if (a_first) break;
      masks[j - 1] = b;
      masks[j] = a;
    }
}

static int frame_init(whitney_frame *f, const gm_complex *cx, size_t T, size_t k,
                      const double *alpha) {
  f->n = cx->n;
  f->N = cx->N;
  f->k = k;
  f->nl = gm_binomial(f->n + 1, k + 1);
  gm_gather_points(cx, f->n, cx->simplices[f->n] + T * (f->n + 1), f->p);
  if (!gm_local_barycentric_gradients(f->N, f->n, f->p, f->grad)) return 0;
  masks_of(f->n, k, f->masks);
  for (size_t i = 0; i < f->nl; ++i) {
    size_t face = gm_local_face(cx, f->n, T, f->masks[i]);
    f->c[i] = alpha[face] * gm_simplex_sign(cx, k, face);
  }
  return 1;
}

/* ω(u_1..u_k) at barycentric coordinates lam (n+1 values; or their derivatives along X for the
 * directional derivative, which replaces λ by ∇λ·X and keeps the constant dλ's). */
static double frame_eval(const whitney_frame *f, const double *lam, const double *u) {
  const size_t n = f->n, N = f->N, k = f->k;
  double D[GM_LOCAL_MAX][3];
  for (size_t a = 0; a <= n; ++a)
    for (size_t m = 0; m < k; ++m) {
      double s = 0.0;
      for (size_t j = 0; j < N; ++j) s += f->grad[a * N + j] * u[m * N + j];
      D[a][m] = s;
    }
  double total = 0.0;
  for (size_t i = 0; i < f->nl; ++i) {
    if (f->c[i] == 0.0) continue;
    size_t pos[GM_LOCAL_MAX], q = 0;
    for (size_t v = 0; v <= n; ++v)
      if (f->masks[i] & (1u << v)) pos[q++] = v;
    double sum = 0.0;
    for (size_t j = 0; j <= k; ++j) {
      double a[3][3];
      for (size_t r = 0, rr = 0; r <= k; ++r) {
        if (r == j) continue;
        for (size_t m = 0; m < k; ++m) a[rr][m] = D[pos[r]][m];
        ++rr;
      }
      sum += ((j & 1) ? -1.0 : 1.0) * lam[pos[j]] * det_k(k, a);
    }
    total += f->c[i] * sum;
  }
  return total * fact[k];
}

gm_status gm_dec_whitney_interpolate(const gm_complex *cx, size_t k, const double *alpha,
                                     size_t top, const double *bary, double *components) {
  if (cx == NULL || alpha == NULL || bary == NULL || components == NULL || k > cx->n ||
      top >= cx->count[cx->n])
    return GM_EINVAL;
  whitney_frame f;
  if (!frame_init(&f, cx, top, k, alpha)) return GM_EINVAL;
  const size_t N = cx->N;
  size_t idx[3] = {0, 1, 2}, q = 0;
  for (;;) { /* index sets i_1 < .. < i_k of 0..N−1 in lexicographic order */
    double u[3 * GM_DEC_MAX_EMBED] = {0};
    for (size_t m = 0; m < k; ++m) u[m * N + idx[m]] = 1.0;
    components[q++] = frame_eval(&f, bary, u);
    if (k == 0) break;
    size_t i = k;
    while (i-- > 0 && idx[i] == N - k + i) {
    }
    if (i == SIZE_MAX) break;
    ++idx[i];
    for (size_t j = i + 1; j < k; ++j) idx[j] = idx[j - 1] + 1;
  }
  return GM_OK;
}

/* ---- interior product and Lie derivative ------------------------------------------------- */

typedef struct {
  size_t np;
  double *bary, *w;
} rule;

static gm_status rule_make(size_t dim, size_t degree, rule *r) {
  gm_status st = gm_simplex_quadrature(dim, degree, &r->np, NULL, NULL);
  if (st != GM_OK) return st;
  r->bary = malloc(r->np * (dim + 2) * sizeof(double));
  if (r->bary == NULL) return GM_ENOMEM;
  r->w = r->bary + r->np * (dim + 1);
  return gm_simplex_quadrature(dim, degree, &r->np, r->bary, r->w);
}

static gm_status check_field(const gm_geometry *g, size_t k, size_t kmin, const double *X,
                             const double *alpha, const double *out, gm_error *err) {
  if (g == NULL || X == NULL || alpha == NULL || out == NULL)
    return gm_error_set(err, GM_EINVAL, "NULL argument");
  if (k < kmin || k > g->cx->n)
    return gm_error_set(err, GM_EINVAL, "form degree %zu out of range %zu..%zu", k, kmin,
                        g->cx->n);
  size_t bad = gm_first_nonfinite(g->cx->N * g->cx->count[0], X);
  if (bad < g->cx->N * g->cx->count[0])
    return gm_error_set(err, GM_EDOMAIN, "vector field component %zu at vertex %zu is not finite",
                        bad % g->cx->N, bad / g->cx->N);
  return GM_OK;
}

/* Point of the local face (positions pos[0..m]) at face-barycentric mu: T-barycentric lam and
 * the interpolated field Xq. */
static void face_point(const whitney_frame *f, const size_t *t, const size_t *pos, size_t m,
                       const double *mu, const double *X, double *lam, double *Xq) {
  const size_t N = f->N;
  for (size_t a = 0; a <= f->n; ++a) lam[a] = 0.0;
  for (size_t j = 0; j < N; ++j) Xq[j] = 0.0;
  for (size_t i = 0; i <= m; ++i) {
    lam[pos[i]] = mu[i];
    for (size_t j = 0; j < N; ++j) Xq[j] += mu[i] * X[t[pos[i]] * N + j];
  }
}

/* ∫ over local face pos[0..m] of top simplex T (vertices t) of the operator's integrand, by the
 * rule r on the face (the caller divides by m!). */
typedef double (*face_integral_fn)(const whitney_frame *f, const size_t *t, const size_t *pos,
                                   size_t m, const rule *r, const double *X);

/* The cochain on m-simplices whose value is the average, over the top simplices containing the
 * face and weighted by their volumes, of the integral of the Whitney interpolant of alpha (a
 * k-cochain) under the operator: the Whitney form is discontinuous across faces, and averaging
 * over all cofaces makes the result single-valued. */
static gm_status coface_average(const gm_geometry *g, size_t k, size_t m, const double *X,
                                const double *alpha, face_integral_fn integral, double *out,
                                gm_error *err) {
  const gm_complex *cx = g->cx;
  const size_t n = cx->n, nout = cx->count[m];
  double *wsum = calloc(nout ? nout : 1, sizeof(double));
  rule r = {0, NULL, NULL};
  if (wsum == NULL || rule_make(m, 2, &r) != GM_OK) {
    free(wsum), free(r.bary);
    return gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  for (size_t s = 0; s < nout; ++s) out[s] = 0.0;
  unsigned fm[6];
  masks_of(n, m, fm);
  const size_t nf = gm_binomial(n + 1, m + 1);
  gm_status st = GM_OK;
  for (size_t T = 0; T < cx->count[n]; ++T) {
    whitney_frame f;
    if (!frame_init(&f, cx, T, k, alpha)) {
      st = gm_error_set(err, GM_EINVAL, "degenerate top simplex %zu", T);
      break;
    }
    const size_t *t = cx->simplices[n] + T * (n + 1);
    const double vol = g->primal[n][T];
    for (size_t i = 0; i < nf; ++i) {
      size_t pos[GM_LOCAL_MAX], q = 0;
      for (size_t v = 0; v <= n; ++v)
        if (fm[i] & (1u << v)) pos[q++] = v;
      const double sum = integral(&f, t, pos, m, &r, X);
      size_t face = gm_local_face(cx, n, T, fm[i]);
      out[face] += vol * sum / fact[m] * gm_simplex_sign(cx, m, face);
      wsum[face] += vol;
    }
  }
  if (st == GM_OK)
    for (size_t s = 0; s < nout; ++s) out[s] /= wsum[s];
  free(wsum);
  free(r.bary);
  return st;
}

/* ∫_face i_X ω: ω(X, u_1..u_m) with u_a the face's edge vectors from its first vertex. */
static double interior_integral(const whitney_frame *f, const size_t *t, const size_t *pos,
                                size_t m, const rule *r, const double *X) {
  const size_t N = f->N;
  double u[3 * GM_DEC_MAX_EMBED], lam[GM_LOCAL_MAX];
  for (size_t a = 1; a <= m; ++a)
    for (size_t j = 0; j < N; ++j) u[a * N + j] = f->p[pos[a] * N + j] - f->p[pos[0] * N + j];
  double sum = 0.0;
  for (size_t qq = 0; qq < r->np; ++qq) {
    face_point(f, t, pos, m, r->bary + qq * (m + 1), X, lam, u); /* u_0 = X at the point */
    sum += r->w[qq] * frame_eval(f, lam, u);
  }
  return sum;
}

gm_status gm_dec_interior_product(const gm_geometry *g, size_t k, const double *X,
                                  const double *alpha, double *out, gm_error *err) {
  gm_status st = check_field(g, k, 1, X, alpha, out, err);
  if (st != GM_OK) return st;
  return coface_average(g, k, k - 1, X, alpha, interior_integral, out, err);
}

/* d/dt ∫_{φ_t(face)} ω at t = 0: the directional derivative of ω along X on the edge vectors
 * E_a, plus ω with one E_a replaced by its velocity dE_a = X(q_a) − X(q_0). */
static double lie_flow_integral(const whitney_frame *f, const size_t *t, const size_t *pos,
                                size_t k, const rule *r, const double *X) {
  const size_t n = f->n, N = f->N;
  double E[3 * GM_DEC_MAX_EMBED], dE[3 * GM_DEC_MAX_EMBED], u[3 * GM_DEC_MAX_EMBED];
  for (size_t a = 1; a <= k; ++a)
    for (size_t j = 0; j < N; ++j) {
      E[(a - 1) * N + j] = f->p[pos[a] * N + j] - f->p[pos[0] * N + j];
      dE[(a - 1) * N + j] = X[t[pos[a]] * N + j] - X[t[pos[0]] * N + j];
    }
  double sum = 0.0;
  for (size_t qq = 0; qq < r->np; ++qq) {
    double lam[GM_LOCAL_MAX], Xq[GM_DEC_MAX_EMBED], dlam[GM_LOCAL_MAX];
    face_point(f, t, pos, k, r->bary + qq * (k + 1), X, lam, Xq);
    for (size_t a = 0; a <= n; ++a) {
      double s = 0.0;
      for (size_t j = 0; j < N; ++j) s += f->grad[a * N + j] * Xq[j];
      dlam[a] = s;
    }
    double val = frame_eval(f, dlam, E); /* (D_X ω)(E_1..E_k) */
    for (size_t a = 0; a < k; ++a) {     /* Σ_a ω(E_1..dE_a..E_k) */
      memcpy(u, E, k * N * sizeof(double));
      memcpy(u + a * N, dE + a * N, N * sizeof(double));
      val += frame_eval(f, lam, u);
    }
    sum += r->w[qq] * val;
  }
  return sum;
}

gm_status gm_dec_lie_derivative(const gm_geometry *g, size_t k, const double *X,
                                const double *alpha, gm_lie_method method, double *out,
                                gm_error *err) {
  gm_status st = check_field(g, k, 0, X, alpha, out, err);
  if (st != GM_OK) return st;
  if (method == GM_LIE_ALGEBRAIC)
    return coface_average(g, k, k, X, alpha, lie_flow_integral, out, err);
  if (method != GM_LIE_CARTAN) return gm_error_set(err, GM_EINVAL, "unknown Lie derivative method");
  const gm_complex *cx = g->cx;
  const size_t n = cx->n, nk = cx->count[k];
  size_t nwork = (k < n ? cx->count[k + 1] : 0) + (k >= 1 ? cx->count[k - 1] : 0);
  double *work = malloc((nwork ? nwork : 1) * sizeof(double));
  if (work == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  for (size_t s = 0; s < nk; ++s) out[s] = 0.0;
  if (k < n) { /* i_X dα */
    gm_csr_matvec(cx->d[k], 1.0, alpha, 0.0, work);
    double *tmp = malloc((nk ? nk : 1) * sizeof(double));
    if (tmp == NULL) {
      free(work);
      return gm_error_set(err, GM_ENOMEM, "out of memory");
    }
    st = gm_dec_interior_product(g, k + 1, X, work, tmp, err);
    for (size_t s = 0; s < nk && st == GM_OK; ++s) out[s] += tmp[s];
    free(tmp);
  }
  if (k >= 1 && st == GM_OK) { /* d i_X α */
    double *ia = work + (k < n ? cx->count[k + 1] : 0);
    st = gm_dec_interior_product(g, k, X, alpha, ia, err);
    if (st == GM_OK) gm_csr_matvec(cx->d[k - 1], 1.0, ia, 1.0, out);
  }
  free(work);
  return st;
}
