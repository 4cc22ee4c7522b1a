/* Multiscale variational integrator for the stiff spring pendulum (seed 001 §5.7.2; the update
 * equations, which the seed does not write, are derived in docs/oscillatory.md):
 *   L = (m/2)(ȧ² + (l + a)² θ̇²) + m g (l + a) cos θ − (k/2) a²,
 * on each step [0, h] the trial functions
 *   a(τ) = P(τ) + E(τ)(α sin ωτ + β cos ωτ),   θ(τ) = T(τ),   P, T polynomials of degree n in τ/h,
 * with the envelope E = l + P (the default: the seed's polynomial × (1 + a₀ sin ωt + a₁ cos ωt)
 * on the radius r = l + a), E = P (the same product on the stretch a, whose Newton system does
 * not converge on this problem) or E = 1 (the additive space), see docs/oscillatory.md; a
 * polynomial for the slow angle; ω fixed,
 * √(k/m) by default, where the seed would add it as an unknown. Writing
 * a = P + Re(c E e^{iωτ}) with c = β − iα, every term of L is Σ_{m=0}^{2} Re(f_m(τ) e^{imωτ}) with
 * smooth f_m, and ∫_0^h f_m e^{imωτ} dτ is taken by the n_f-point Filon–Lobatto rule at κ = mωh
 * (gm_filon_lobatto_weights). The discrete Lagrangian L_d(q0, q1) = stat S(ξ) over the trial
 * coefficients ξ with q(0) = q0, q(h) = q1; with multipliers, ∇_ξ S = λ0 ∂q(0)/∂ξ + λ1 ∂q(h)/∂ξ,
 * p0 = −D₁L_d = −λ0, p1 = D₂L_d = λ1. A step from (q0, p0) solves, by Newton's method,
 *   q_ξ(0) = q0,   ∇_ξ S(ξ) + p0·∂q(0)/∂ξ − λ1·∂q(h)/∂ξ = 0
 * for (ξ, λ1) and returns q1 = q_ξ(h), p1 = λ1. The gradient ∇_ξ S is exact (forward-mode
 * derivatives through the harmonic components); Newton differentiates it by differences. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/oscillatory.h"
#include "core/internal.h"

#define MSVI_MAX_DEG 3
#define MSVI_MAX_DOF (2 * (MSVI_MAX_DEG + 1) + 2)
#define MSVI_MAX_NODES 8

struct gm_msvi {
  gm_msvi_options o;
  size_t deg, nf, n_dof;  /* dofs: P_0..P_n, α, β, T_0..T_n */
  double h_weights;       /* h of the cached weights (NaN: none) */
  double nodes[MSVI_MAX_NODES];
  double complex b[3][MSVI_MAX_NODES]; /* Filon weights at κ = 0, ωh, 2ωh */
  gm_newton *newton;
  /* the step being solved */
  double h, q0[2], p0[2];
  double x[MSVI_MAX_DOF + 2];
  int frozen;             /* α = β = 0 imposed (the first pass of a cold start) */
  int warm;               /* x holds the last step's solution, which ended at (q_end, p_end) */
  double q_end[2], p_end[2], h_last;
  size_t iterations;      /* Newton iterations of the last step */
  char errmsg[GM_ERRMSG_SIZE];
};

/* A harmonic expansion v = c0 + Re(c1 e^{iωτ}) + Re(c2 e^{2iωτ}) at one node, with the
 * derivatives of each component with respect to the n_dof unknowns. */
typedef struct {
  double c0, d0[MSVI_MAX_DOF];
  double complex c1, d1[MSVI_MAX_DOF];
  double complex c2, d2[MSVI_MAX_DOF];
} harm;

static void harm_zero(harm *v) { memset(v, 0, sizeof *v); }

/* x·y for x, y with harmonics ≤ 1: c0 = x0y0 + ½Re(x1 ȳ1), c1 = x0y1 + x1y0, c2 = ½x1y1 */
static void harm_mul1(size_t n, const harm *x, const harm *y, harm *out) {
  harm r;
  harm_zero(&r);
  r.c0 = x->c0 * y->c0 + 0.5 * creal(x->c1 * conj(y->c1));
  r.c1 = x->c0 * y->c1 + x->c1 * y->c0;
  r.c2 = 0.5 * x->c1 * y->c1;
  for (size_t j = 0; j < n; ++j) {
    r.d0[j] = x->d0[j] * y->c0 + x->c0 * y->d0[j] +
              0.5 * creal(x->d1[j] * conj(y->c1) + x->c1 * conj(y->d1[j]));
    r.d1[j] = x->d0[j] * y->c1 + x->c0 * y->d1[j] + x->d1[j] * y->c0 + x->c1 * y->d0[j];
    r.d2[j] = 0.5 * (x->d1[j] * y->c1 + x->c1 * y->d1[j]);
  }
  *out = r;
}

/* v·s for a slow (harmonic 0) s with derivative ds */
static void harm_scale(size_t n, harm *v, double s, const double *ds) {
  for (size_t j = 0; j < n; ++j) {
    v->d0[j] = v->d0[j] * s + v->c0 * ds[j];
    v->d1[j] = v->d1[j] * s + v->c1 * ds[j];
    v->d2[j] = v->d2[j] * s + v->c2 * ds[j];
  }
  v->c0 *= s;
  v->c1 *= s;
  v->c2 *= s;
}

static void harm_axpy(size_t n, double a, const harm *x, harm *y) {
  y->c0 += a * x->c0;
  y->c1 += a * x->c1;
  y->c2 += a * x->c2;
  for (size_t j = 0; j < n; ++j) {
    y->d0[j] += a * x->d0[j];
    y->d1[j] += a * x->d1[j];
    y->d2[j] += a * x->d2[j];
  }
}

gm_msvi_options gm_msvi_defaults(void) {
  gm_msvi_options o = {1.0, 9.81, 10000.0, 1.0, 0.0, 2, 3, 2, 0};
  return o;
}

gm_status gm_msvi_create(const gm_msvi_options *options, gm_msvi **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "msvi: output pointer is NULL");
  *out = NULL;
  gm_msvi_options o = options ? *options : gm_msvi_defaults();
  if (!(o.m > 0.0) || !(o.k > 0.0) || !(o.l > 0.0) || !(o.g >= 0.0))
    return gm_error_set(err, GM_EINVAL, "msvi: need m, k, l > 0 and g >= 0");
  if (o.degree < 1 || o.degree > MSVI_MAX_DEG)
    return gm_error_set(err, GM_EINVAL, "msvi: degree must be 1..%d, got %zu", MSVI_MAX_DEG,
                        o.degree);
  if (o.filon_points < 2 || o.filon_points > MSVI_MAX_NODES)
    return gm_error_set(err, GM_EINVAL, "msvi: filon_points must be 2..%d, got %zu",
                        MSVI_MAX_NODES, o.filon_points);
  if (o.additive < 0 || o.additive > 2)
    return gm_error_set(err, GM_EINVAL, "msvi: additive must be 0, 1 or 2, got %d", o.additive);
  if (o.omega == 0.0) o.omega = sqrt(o.k / o.m);
  if (!(o.omega > 0.0) || !isfinite(o.omega))
    return gm_error_set(err, GM_EINVAL, "msvi: omega must be positive, got %g", o.omega);
  gm_msvi *vi = calloc(1, sizeof *vi);
  if (vi == NULL) return gm_error_set(err, GM_ENOMEM, "msvi: out of memory");
  vi->o = o;
  vi->deg = o.degree;
  vi->nf = o.filon_points;
  vi->n_dof = 2 * (vi->deg + 1) + 2;
  vi->h_weights = NAN;
  gm_newton_options no = gm_newton_defaults();
  no.max_iterations = 60;
  no.increment_tol = 1e-13;
  no.residual_tol = 1e-10; /* the residual is ∇S/h: a momentum, O(1) here */
  gm_status st = gm_newton_create(vi->n_dof + 2, &no, &vi->newton);
  if (st != GM_OK) {
    free(vi);
    return gm_error_set(err, st, "msvi: cannot create the Newton solver");
  }
  *out = vi;
  return GM_OK;
}

void gm_msvi_free(gm_msvi *vi) {
  if (vi == NULL) return;
  gm_newton_free(vi->newton);
  free(vi);
}

const char *gm_msvi_errmsg(const gm_msvi *vi) { return vi ? vi->errmsg : ""; }

static gm_status prepare_weights(gm_msvi *vi, double h) {
  if (h == vi->h_weights) return GM_OK;
  for (int m = 0; m < 3; ++m) {
    double re[MSVI_MAX_NODES], im[MSVI_MAX_NODES];
    gm_status st = gm_filon_lobatto_weights(vi->nf, m * vi->o.omega * h, vi->nodes, re, im);
    if (st != GM_OK) return st;
    for (size_t k = 0; k < vi->nf; ++k) vi->b[m][k] = re[k] + I * im[k];
  }
  vi->h_weights = h;
  return GM_OK;
}

/* indices into ξ */
static size_t ip(size_t j) { return j; }
static size_t ialpha(const gm_msvi *vi) { return vi->deg + 1; }
static size_t ibeta(const gm_msvi *vi) { return vi->deg + 2; }
static size_t it_(const gm_msvi *vi, size_t j) { return vi->deg + 3 + j; }

/* S(ξ) and ∇S (grad: n_dof values) */
static double action(const gm_msvi *vi, const double *xi, double *grad) {
  const size_t n = vi->n_dof, deg = vi->deg;
  const double h = vi->h, w = vi->o.omega, m = vi->o.m, g = vi->o.g, kk = vi->o.k, l = vi->o.l;
  const double alpha = xi[ialpha(vi)], beta = xi[ibeta(vi)];
  const double complex c = beta - I * alpha;
  double s = 0.0;
  memset(grad, 0, n * sizeof *grad);
  for (size_t node = 0; node < vi->nf; ++node) {
    const double x = vi->nodes[node], tau = h * x;
    /* P, P′, T, T′ and their derivatives */
    double P = 0, dP = 0, T = 0, dT = 0;
    double gP[MSVI_MAX_DOF] = {0}, gdP[MSVI_MAX_DOF] = {0}, gT[MSVI_MAX_DOF] = {0},
           gdT[MSVI_MAX_DOF] = {0};
    for (size_t j = 0; j <= deg; ++j) {
      const double xj = pow(x, (double)j), dxj = j ? (double)j * pow(x, (double)j - 1) / h : 0.0;
      P += xi[ip(j)] * xj;
      dP += xi[ip(j)] * dxj;
      T += xi[it_(vi, j)] * xj;
      dT += xi[it_(vi, j)] * dxj;
      gP[ip(j)] = xj;
      gdP[ip(j)] = dxj;
      gT[it_(vi, j)] = xj;
      gdT[it_(vi, j)] = dxj;
    }
    /* a = P + Re(cP e^{iωτ}), ȧ = P′ + Re(c(P′ + iωP) e^{iωτ}) */
    harm a, ad, r;
    harm_zero(&a);
    harm_zero(&ad);
    /* the envelope of the oscillation: l + P (product on the radius), P (product on the
     * stretch) or 1 (additive) */
    const double E = vi->o.additive == 1 ? 1.0 : (vi->o.additive == 2 ? l + P : P),
                 dE = vi->o.additive == 1 ? 0.0 : dP;
    a.c0 = P;
    a.c1 = c * E;
    ad.c0 = dP;
    ad.c1 = c * (dE + I * w * E);
    for (size_t j = 0; j < n; ++j) {
      a.d0[j] = gP[j];
      ad.d0[j] = gdP[j];
      if (vi->o.additive != 1) {
        a.d1[j] = c * gP[j];
        ad.d1[j] = c * (gdP[j] + I * w * gP[j]);
      }
    }
    a.d1[ialpha(vi)] = -I * E;
    a.d1[ibeta(vi)] = E;
    ad.d1[ialpha(vi)] = -I * (dE + I * w * E);
    ad.d1[ibeta(vi)] = dE + I * w * E;
    r = a;
    r.c0 += l;
    /* L = ½m ȧ² + ½m r² θ̇² + m g r cos θ − ½k a² */
    harm lag, tmp;
    harm_zero(&lag);
    harm_mul1(n, &ad, &ad, &tmp);
    harm_axpy(n, 0.5 * m, &tmp, &lag);
    harm_mul1(n, &r, &r, &tmp);
    double gt2[MSVI_MAX_DOF];
    for (size_t j = 0; j < n; ++j) gt2[j] = 2.0 * dT * gdT[j];
    harm_scale(n, &tmp, dT * dT, gt2);
    harm_axpy(n, 0.5 * m, &tmp, &lag);
    tmp = r;
    double gcos[MSVI_MAX_DOF];
    for (size_t j = 0; j < n; ++j) gcos[j] = -sin(T) * gT[j];
    harm_scale(n, &tmp, cos(T), gcos);
    harm_axpy(n, m * g, &tmp, &lag);
    harm_mul1(n, &a, &a, &tmp);
    harm_axpy(n, -0.5 * kk, &tmp, &lag);
    /* ∫ = h Σ_nodes [b0 c0 + Re(b1 c1) + Re(b2 c2)] (c_m carries e^{imωτ} relative to τ = 0) */
    (void)tau;
    s += h * (creal(vi->b[0][node]) * lag.c0 + creal(vi->b[1][node] * lag.c1) +
              creal(vi->b[2][node] * lag.c2));
    for (size_t j = 0; j < n; ++j)
      grad[j] += h * (creal(vi->b[0][node]) * lag.d0[j] + creal(vi->b[1][node] * lag.d1[j]) +
                      creal(vi->b[2][node] * lag.d2[j]));
  }
  return s;
}

/* end values q(0), q(h) and their gradients */
static void endpoints(const gm_msvi *vi, const double *xi, double *q0, double *q1, double *g0a,
                      double *g0t, double *g1a, double *g1t) {
  const size_t n = vi->n_dof, deg = vi->deg;
  const double wh = vi->o.omega * vi->h, sn = sin(wh), cs = cos(wh);
  const double alpha = xi[ialpha(vi)], beta = xi[ibeta(vi)];
  double Ph = 0, Th = 0;
  for (size_t j = 0; j <= deg; ++j) {
    Ph += xi[ip(j)];
    Th += xi[it_(vi, j)];
  }
  memset(g0a, 0, n * sizeof *g0a);
  memset(g0t, 0, n * sizeof *g0t);
  memset(g1a, 0, n * sizeof *g1a);
  memset(g1t, 0, n * sizeof *g1t);
  const int add = vi->o.additive == 1;
  const double shift = vi->o.additive == 2 ? vi->o.l : 0.0; /* product form in r = l + a */
  const double E0 = add ? 1.0 : shift + xi[ip(0)], Eh = add ? 1.0 : shift + Ph;
  q0[0] = xi[ip(0)] + E0 * beta;
  q0[1] = xi[it_(vi, 0)];
  g0a[ip(0)] = add ? 1.0 : 1.0 + beta;
  g0a[ibeta(vi)] = E0;
  g0t[it_(vi, 0)] = 1.0;
  const double f = alpha * sn + beta * cs;
  q1[0] = Ph + Eh * f;
  q1[1] = Th;
  for (size_t j = 0; j <= deg; ++j) {
    g1a[ip(j)] = add ? 1.0 : 1.0 + f;
    g1t[it_(vi, j)] = 1.0;
  }
  g1a[ialpha(vi)] = Eh * sn;
  g1a[ibeta(vi)] = Eh * cs;
}

/* unknowns x = (ξ, λ1); residual (q(0) − q0, ∇S + p0·∂q(0) − λ1·∂q(h)) scaled by 1/h */
static int residual(void *ctx, const double *x, double *res) {
  gm_msvi *vi = ctx;
  const size_t n = vi->n_dof;
  double grad[MSVI_MAX_DOF], q0[2], q1[2], g0a[MSVI_MAX_DOF], g0t[MSVI_MAX_DOF],
      g1a[MSVI_MAX_DOF], g1t[MSVI_MAX_DOF];
  action(vi, x, grad);
  endpoints(vi, x, q0, q1, g0a, g0t, g1a, g1t);
  const double *lam = x + n;
  res[0] = q0[0] - vi->q0[0];
  res[1] = q0[1] - vi->q0[1];
  for (size_t j = 0; j < n; ++j)
    res[2 + j] = (grad[j] + vi->p0[0] * g0a[j] + vi->p0[1] * g0t[j] - lam[0] * g1a[j] -
                  lam[1] * g1t[j]) / vi->h;
  if (vi->frozen) { /* the polynomial Galerkin problem: α = β = 0 instead of their equations */
    res[2 + ialpha(vi)] = x[ialpha(vi)];
    res[2 + ibeta(vi)] = x[ibeta(vi)];
  }
  return 0;
}

/* The previous step's curve continued to the next step: P(s) → P(s + 1), T likewise (Taylor
 * shift), (α, β) rotated by ωh and rescaled so that the oscillation P·(α sin + β cos) goes on. */
static void warm_start(gm_msvi *vi, double h) {
  const size_t deg = vi->deg, n = vi->n_dof;
  double P[MSVI_MAX_DEG + 1], T[MSVI_MAX_DEG + 1], Pn[MSVI_MAX_DEG + 1] = {0},
      Tn[MSVI_MAX_DEG + 1] = {0};
  for (size_t j = 0; j <= deg; ++j) {
    P[j] = vi->x[ip(j)];
    T[j] = vi->x[it_(vi, j)];
  }
  for (size_t j = 0; j <= deg; ++j) /* Σ_j c_j (s + 1)^j = Σ_i s^i Σ_{j≥i} C(j, i) c_j */
    for (size_t i = 0; i <= j; ++i) {
      double binom = 1.0;
      for (size_t t = 0; t < i; ++t) binom = binom * (double)(j - t) / (double)(t + 1);
      Pn[i] += binom * P[j];
      Tn[i] += binom * T[j];
    }
  const double wh = vi->o.omega * h, al = vi->x[ialpha(vi)], be = vi->x[ibeta(vi)];
  /* α sin ω(τ' + h) + β cos ω(τ' + h) = α' sin ωτ' + β' cos ωτ' */
  const double a2 = al * cos(wh) - be * sin(wh), b2 = al * sin(wh) + be * cos(wh);
  double Ph = 0.0;
  for (size_t j = 0; j <= deg; ++j) Ph += P[j];
  const double scale = 1.0; /* the envelope P(h) = Pn[0] is continued as it is */
  (void)Ph;
  for (size_t j = 0; j <= deg; ++j) {
    vi->x[ip(j)] = Pn[j];
    vi->x[it_(vi, j)] = Tn[j];
  }
  vi->x[ialpha(vi)] = a2 * scale;
  vi->x[ibeta(vi)] = b2 * scale;
  (void)n;
}

gm_status gm_msvi_step(gm_msvi *vi, double h, double *q, double *p) {
  if (vi == NULL || q == NULL || p == NULL) return GM_EINVAL;
  if (!(h > 0.0) || !isfinite(h))
    return gm_fail(vi->errmsg, sizeof vi->errmsg, GM_EINVAL, "msvi: step %g must be > 0", h);
  gm_status st = prepare_weights(vi, h);
  if (st != GM_OK) return gm_fail(vi->errmsg, sizeof vi->errmsg, st, "msvi: Filon weights");
  vi->h = h;
  memcpy(vi->q0, q, sizeof vi->q0);
  memcpy(vi->p0, p, sizeof vi->p0);
  const size_t n = vi->n_dof;
  double *x = vi->x;
  const int warm = !(vi->o.additive != 1 && vi->o.start_from_additive) && vi->warm &&
                   h == vi->h_last && memcmp(q, vi->q_end, sizeof vi->q_end) == 0 &&
                   memcmp(p, vi->p_end, sizeof vi->p_end) == 0;
  size_t iterations = 0;
  if (warm) {
    warm_start(vi, h);
    x[n] = p[0];
    x[n + 1] = p[1];
  } else {
    /* cold start: a = q0 + (slope from the momentum) τ, θ linear, λ1 = p0; first the polynomial
     * Galerkin problem (α = β = 0), then the multiscale one from its solution */
    memset(x, 0, (n + 2) * sizeof *x);
    const double r0 = vi->o.l + q[0];
    x[ip(0)] = q[0];
    x[ip(1)] = h * p[0] / vi->o.m;
    x[it_(vi, 0)] = q[1];
    x[it_(vi, 1)] = h * p[1] / (vi->o.m * r0 * r0);
    x[n] = p[0];
    x[n + 1] = p[1];
    vi->frozen = 1;
    st = gm_newton_solve(vi->newton, residual, NULL, vi, x);
    vi->frozen = 0;
    iterations = gm_newton_iterations(vi->newton);
    if (st != GM_OK) {
      vi->warm = 0;
      return gm_fail(vi->errmsg, sizeof vi->errmsg, st, "msvi: step h = %g (polynomial start): %s",
                     h, gm_newton_errmsg(vi->newton));
    }
  }
  if (vi->o.additive != 1 && vi->o.start_from_additive) {
    /* a product space started from the additive space's solution of the same step:
     * P + α sin + β cos ≈ E(α' sin + β' cos) + P with E the envelope at mid-step */
    const int mode = vi->o.additive;
    vi->o.additive = 1;
    st = gm_newton_solve(vi->newton, residual, NULL, vi, x);
    vi->o.additive = mode;
    iterations += gm_newton_iterations(vi->newton);
    if (st != GM_OK) {
      vi->warm = 0;
      return gm_fail(vi->errmsg, sizeof vi->errmsg, st, "msvi: step h = %g (additive start): %s",
                     h, gm_newton_errmsg(vi->newton));
    }
    double Pmid = 0.0;
    for (size_t j = 0; j <= vi->deg; ++j) Pmid += x[ip(j)] * pow(0.5, (double)j);
    const double Emid = (mode == 2 ? vi->o.l : 0.0) + Pmid;
    x[ialpha(vi)] /= Emid;
    x[ibeta(vi)] /= Emid;
  }
  st = gm_newton_solve(vi->newton, residual, NULL, vi, x);
  vi->iterations = iterations + gm_newton_iterations(vi->newton);
  vi->warm = 0;
  if (st != GM_OK)
    return gm_fail(vi->errmsg, sizeof vi->errmsg, st, "msvi: step h = %g: %s", h,
                   gm_newton_errmsg(vi->newton));
  double q0[2], q1[2], g[4][MSVI_MAX_DOF];
  endpoints(vi, x, q0, q1, g[0], g[1], g[2], g[3]);
  q[0] = q1[0];
  q[1] = q1[1];
  p[0] = x[n];
  p[1] = x[n + 1];
  memcpy(vi->q_end, q, sizeof vi->q_end);
  memcpy(vi->p_end, p, sizeof vi->p_end);
  vi->h_last = h;
  vi->warm = 1;
  return GM_OK;
}

size_t gm_msvi_newton_iterations(const gm_msvi *vi) { return vi ? vi->iterations : 0; }
