/* The Kepler drift: the exact flow of x'' = −μ x/|x|³ over a time dt, for any conic.
 *
 * Universal variables (Stumpff 1959; Danby, Fundamentals of Celestial Mechanics, 2nd ed.
 * (1988) §6.9; Rein & Tamayo, MNRAS 452 (2015) 376, §2.3). With r0 = |x0|, η = x0·v0,
 * β = 2μ/r0 − |v0|² (= μ/a, > 0 for ellipses) and ζ = μ − β r0, the universal anomaly s of the
 * time t solves Kepler's equation
 *   f(s) = r0 s + η G2(s) + ζ G3(s) − t = 0,    f'(s) = r(s) = r0 + η G1 + ζ G2 > 0,
 *   f''(s) = η G0 + ζ G1,
 * where G_k(β, s) = s^k c_k(β s²) with the Stumpff functions c_k. f is increasing, so the root
 * is bracketed: Householder's fourth-order method, falling back to Newton's and then to
 * bisection whenever a step would leave the bracket, cannot fail (it only narrows the
 * bracket). Then the Gauss
 * f and g functions give the increments (Danby eqs. 6.9.22-6.9.24, written so that the small
 * quantities f − 1 and ġ − 1 are never formed by subtraction):
 *   f − 1 = −μ G2/r0,  g = r0 G1 + η G2,  ḟ = −μ G1/(r r0),  ġ − 1 = −μ G2/r,
 *   dx = (f − 1) x0 + g v0,   dv = ḟ x0 + (ġ − 1) v0.
 * All of them are functions of s only, so a rounding error in s moves the state along the
 * exact orbit (energy, angular momentum and Laplace–Runge–Lenz vector keep their digits).
 * Elliptic drifts longer than a period are first reduced modulo the period. Near β = 0
 * (parabolic) the Stumpff series are used, so nothing divides by β. */
#include <float.h>
#include <math.h>

#include "celestial/internal.h"

/* Below this |z| = |β s²| the Stumpff functions come from their series (13 terms leave a
 * truncation below 1e-19 at |z| = 2.5); above it from sin/cos or sinh/cosh, where the only
 * subtraction, y − sin y with |y| ≥ 1.58, loses less than two bits. */
#define SERIES_LIMIT 2.5
#define N_TERMS 13

/* 1/k!, k = 2..27 (rounded to double) */
const double gm_inverse_factorial[26] = {
    5.00000000000000000e-01, 1.66666666666666657e-01, 4.16666666666666644e-02,
    8.33333333333333322e-03, 1.38888888888888894e-03, 1.98412698412698413e-04,
    2.48015873015873016e-05, 2.75573192239858925e-06, 2.75573192239858883e-07,
    2.50521083854417202e-08, 2.08767569878681002e-09, 1.60590438368216133e-10,
    1.14707455977297245e-11, 7.64716373181981641e-13, 4.77947733238738525e-14,
    2.81145725434552060e-15, 1.56192069685862253e-16, 8.22063524662432950e-18,
    4.11031762331216484e-19, 1.95729410633912626e-20, 8.89679139245057408e-22,
    3.86817017063068413e-23, 1.61173757109611839e-24, 6.44695028438447359e-26,
    2.47959626322479759e-27, 9.18368986379554601e-29,
};

static inline void stumpff_g(double beta, double s, double g[4]) {
  const double z = beta * s * s;
  const double az = fabs(z);
  if (az < SERIES_LIMIT) {
    /* c2 = Σ_j (−z)^j/(2j+2)!, c3 = Σ_j (−z)^j/(2j+3)!, by Horner's rule, with N terms, the
     * fewest that leave a truncation |z|^N/(2N+2)! below 1e-17 */
    const int terms = az < 0.002 ? 4 : az < 0.02 ? 5 : az < 0.09 ? 6 : az < 0.3 ? 7
                      : az < 0.7 ? 8 : az < 1.4 ? 9 : N_TERMS;
    double c2 = gm_inverse_factorial[2 * terms - 2], c3 = gm_inverse_factorial[2 * terms - 1];
    for (int j = terms - 2; j >= 0; --j) {
      c2 = gm_inverse_factorial[2 * j] - z * c2;
      c3 = gm_inverse_factorial[2 * j + 1] - z * c3;
    }
    g[2] = s * s * c2;
    g[3] = s * s * s * c3;
    g[1] = s - beta * g[3]; /* G1 = s c1, c1 = 1 − z c3 */
    g[0] = 1.0 - beta * g[2];
  } else if (beta > 0.0) {
    const double rb = sqrt(beta), y = rb * s, sn = sin(y), half = sin(0.5 * y);
    g[0] = cos(y);
    g[1] = sn / rb;
    g[2] = 2.0 * half * half / beta; /* (1 − cos y)/β without the cancellation */
    g[3] = (y - sn) / (beta * rb);
  } else {
    const double nb = -beta, rb = sqrt(nb), y = rb * s, sh = sinh(y), half = sinh(0.5 * y);
    g[0] = cosh(y);
    g[1] = sh / rb;
    g[2] = 2.0 * half * half / nb;
    g[3] = (sh - y) / (nb * rb);
  }
}

void gm_stumpff_g(double beta, double s, double g[4]) { stumpff_g(beta, s, g); }

static double dot3(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

typedef struct {
  double r0, eta, zeta, beta, t;
} kepler_equation;

/* f(s), f'(s) = r, f''(s) */
static void evaluate(const kepler_equation *k, double s, double *f, double *df, double *d2f) {
  double g[4];
  stumpff_g(k->beta, s, g);
  *f = k->r0 * s + k->eta * g[2] + k->zeta * g[3] - k->t;
  *df = k->r0 + k->eta * g[1] + k->zeta * g[2];
  *d2f = k->eta * g[0] + k->zeta * g[1];
}

#define MAX_ITERATIONS 200

/* The root of f in the bracket [lo, hi] (f(lo) ≤ 0 ≤ f(hi) where evaluated), from s; g gets
 * G_0..G_3 at the root. Householder's fourth-order step (f‴ = ζ G0 − η β G1 costs as little
 * as the rest): from the third-order start of a short drift (error ~(n dt)⁴) one step reaches
 * round-off, and the next evaluation only confirms it, so a drift costs two evaluations of the
 * G functions. The iteration stops when the correction is below 4 ulp of s; that correction is
 * still taken, with the G functions moved along by dG_k/ds = G_{k−1}, dG_0/ds = −β G_1 (the
 * neglected O(d²) is ~1e-31 |G|): stopping before it biases s by ~1 ulp per drift (measured:
 * 3.7 times the error of 10⁵ drifts, tests/unit/test_celestial_kepler.c), and so does stopping
 * after a step merely small enough for fast convergence (5 times). */
static gm_status solve(const kepler_equation *k, double s, double lo, double hi, double *root,
                       double g[4]) {
  for (int iter = 0; iter < MAX_ITERATIONS; ++iter) {
    stumpff_g(k->beta, s, g);
    const double f = k->r0 * s + k->eta * g[2] + k->zeta * g[3] - k->t;
    const double df = k->r0 + k->eta * g[1] + k->zeta * g[2];
    const double d2f = k->eta * g[0] + k->zeta * g[1];
    const double d3f = k->zeta * g[0] - k->eta * k->beta * g[1];
    if (f == 0.0) break;
    if (f < 0.0)
      lo = s;
    else
      hi = s; /* f > 0, or NaN: an overflowing hyperbolic step is too long */
    if (!(f == f)) {
      s = 0.5 * (lo + hi);
      continue;
    }
    const double df2 = df * df;
    double next = s - (6.0 * f * df2 - 3.0 * f * f * d2f) /
                          (6.0 * df2 * df - 6.0 * f * df * d2f + f * f * d3f); /* Householder */
    const double d = next - s;
    if (fabs(d) <= 4.0 * DBL_EPSILON * fabs(s)) {
      const double g0 = g[0], g1 = g[1], g2 = g[2];
      g[3] += d * g2;
      g[2] += d * g1;
      g[1] += d * g0;
      g[0] -= k->beta * d * g1;
      s = next;
      break;
    }
    if (!(next > lo && next < hi)) next = s - f / df;      /* Newton */
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi); /* bisection */
    if (!(next > lo && next < hi)) break; /* no double left strictly inside the bracket */
    s = next;
    if (iter == MAX_ITERATIONS - 1) return GM_ENOCONV;
  }
  *root = s;
  return GM_OK;
}

/* The short path: a drift with |ΔM| < 0.3 and |β s²| < SHORT_Z from the third-order start
 * s0(t) = t/r0 − η t²/(2 r0³) + (η²/(2 r0⁵) − ζ/(6 r0⁴)) t³, whose error is small, with one
 * evaluation of the G functions instead of an iteration. A Householder step d from s0 leaves
 * an error ~K (d/s)⁴ s; the G functions are carried to s1 = s0 + d by their Taylor series to
 * d⁴ (dG_k/ds = G_{k−1}, dG_0/ds = −β G_1, so the j-th derivative of G_k is G_{k−j} with
 * G_{−1} = −β G_1, G_{−2} = −β G_0, G_{−3} = β² G_1, G_{−4} = β² G_0; with |d| ≤ SHORT_STEP
 * |s0| the first term left out is below 1e-21 of G_k), and Kepler's equation is evaluated
 * again from them (as accurate as a direct evaluation). A last Newton correction
 * d2 = −f(s1)/r(s1) is applied to s and, to first order, to G and 1/r (its square is far
 * below the ulp); that 1/r is the one the f and g functions need, so the correction costs no
 * division. A lane fails (and gm_kepler_drift iterates) when s0 was not close enough: |d| too
 * large, or a Newton correction not at round-off level (|d2| > 2^-40 |s1|).
 *
 * Two or four orbits at a time in the lanes of a vector (kepler_short.h, the width picked by
 * the CPU: gm_lane_width); each lane computes exactly what it would alone, so a single drift,
 * done as a group of copies of itself, is bitwise the drift of the same orbit in any group and
 * at either width. The G functions come from 6 terms of the Stumpff series for every lane
 * (|z| < SHORT_Z = 0.09: the first term left out, z⁶/14!, is below 1e-17 of c_2), so no
 * lane's term count depends on another's. */

int gm_lane_width(void) {
#if defined(GM_CELESTIAL_AVX2)
  return __builtin_cpu_supports("avx2") ? 4 : 2;
#else
  return 2;
#endif
}
/* dx = (f − 1) x0 + g v0, dv = ḟ x0 + (ġ − 1) v0 from the G functions at the root */
static inline void increments(double mu, const kepler_equation *k, double ir, double ri,
                              const double g[4], const double *x0, const double *v0, double *dx,
                              double *dv) {
  const double f_1 = -mu * g[2] * ir, gg = k->r0 * g[1] + k->eta * g[2];
  const double fdot = -mu * g[1] * ri * ir, gdot_1 = -mu * g[2] * ri;
  for (int i = 0; i < 3; ++i) {
    dx[i] = f_1 * x0[i] + gg * v0[i];
    dv[i] = fdot * x0[i] + gdot_1 * v0[i];
  }
}

gm_status gm_kepler_drift(double mu, double dt, const double x0[3], const double v0[3],
                          double dx[3], double dv[3]) {
  if (x0 == NULL || v0 == NULL || dx == NULL || dv == NULL) return GM_EINVAL;
  if (!(mu > 0.0) || !isfinite(mu)) return GM_EINVAL;
  if (!isfinite(dt) || !isfinite(x0[0] + x0[1] + x0[2]) || !isfinite(v0[0] + v0[1] + v0[2]))
    return GM_EDOMAIN;
  const double r0 = sqrt(dot3(x0, x0));
  if (!(r0 > 0.0)) return GM_EINVAL;
  for (int i = 0; i < 3; ++i) dx[i] = dv[i] = 0.0;
  if (dt == 0.0) return GM_OK;
  kepler_equation k;
  k.r0 = r0;
  k.eta = dot3(x0, v0);
  k.beta = 2.0 * mu / r0 - dot3(v0, v0);
  k.zeta = mu - k.beta * r0;
  k.t = dt;
  double lo, hi, s0;
  { /* the short path, as a group of copies of itself */
    int done;
    (gm_lane_width() == 4 ? gm_kepler_short4 : gm_kepler_short2)(1, &mu, dt, x0, v0, dx, dv, 0,
                                                                  NULL, &done);
    if (done) return GM_OK;
  }
  /* s(t) = t/r0 − η t²/(2 r0³) + (η²/(2 r0⁵) − ζ/(6 r0⁴)) t³ + O(t⁴), the inverse of
   * t(s) = r0 s + η s²/2 + ζ s³/6 + O(s⁴): the start for drifts short against the orbit */
  const double ir = 1.0 / r0, tr = dt * ir;
  const double series =
      tr * (1.0 + tr * (-0.5 * k.eta * ir + tr * (0.5 * k.eta * k.eta * ir * ir - k.zeta * ir / 6.0)));
  if (k.beta > 0.0) {
    /* mean anomaly of the drift M = n t, n = β^{3/2}/μ; the period 2π/n is only formed when
     * the drift may be longer (divisions dominate the cost of a short drift) */
    const double rb = sqrt(k.beta), m_mu = fabs(k.t) * k.beta * rb; /* M μ */
    if (m_mu >= 6.0 * mu) {
      const double period = 2.0 * GM_PI * mu / (k.beta * rb);
      if (fabs(k.t) >= period) k.t = fmod(k.t, period); /* the motion repeats */
      if (k.t == 0.0) return GM_OK;
    }
    const double s_period = 2.0 * GM_PI / rb; /* f(±s_period) = ±period − t */
    lo = k.t > 0.0 ? 0.0 : -s_period;
    hi = k.t > 0.0 ? s_period : 0.0;
    /* the mean-anomaly guess ΔE = M, i.e. s = t β/μ, for drifts of a sizeable arc */
    s0 = m_mu < 0.3 * mu ? series : k.t * k.beta / mu;
  } else {
    /* unbound: double the step t/r0 until f changes sign */
    double far = fabs(dt) * ir, f, df, d2f;
    int n = 0;
    for (;;) {
      evaluate(&k, dt > 0.0 ? far : -far, &f, &df, &d2f);
      if (dt > 0.0 ? !(f < 0.0) : !(f > 0.0)) break;
      if (++n > 2100) return GM_EDOMAIN;
      far *= 2.0;
    }
    lo = dt > 0.0 ? (n > 0 ? 0.5 * far : 0.0) : -far;
    hi = dt > 0.0 ? far : (n > 0 ? -0.5 * far : 0.0);
    s0 = series;
  }
  if (!(s0 > lo && s0 < hi)) s0 = 0.5 * (lo + hi);
  double s, g[4];
  gm_status st = solve(&k, s0, lo, hi, &s, g);
  if (st != GM_OK) return st;
  const double ri = 1.0 / (r0 + k.eta * g[1] + k.zeta * g[2]);
  increments(mu, &k, ir, ri, g, x0, v0, dx, dv);
  if (!isfinite(dx[0] + dx[1] + dx[2] + dv[0] + dv[1] + dv[2])) return GM_EDOMAIN;
  return GM_OK;
}

/* Drifts of n independent orbits by the same dt (x, v, dx, dv: n 3-vectors, borrowed): each
 * result is bitwise the one of gm_kepler_drift. Short drifts (the drifts of a splitting
 * method) go through the short path `width` orbits at a time; any other orbit, or one whose
 * start was not close enough, is handed to gm_kepler_drift. With apply, dx and dv are x and v
 * and receive x + dx, v + dv (and ir, unless NULL, 1/|x| at the end). */
static gm_status drift_many(int width, size_t n, const double *mu, double dt, const double *x,
                            const double *v, double *dx, double *dv, int apply, double *ir) {
  gm_kepler_short_fn *short_path = width == 4 ? gm_kepler_short4 : gm_kepler_short2;
  const size_t chunk = (width == 4 ? 4 : 2) * KEPLER_MAX_GROUPS;
  for (size_t base = 0; base < n; base += chunk) {
    const size_t m = n - base < chunk ? n - base : chunk;
    int done[4 * KEPLER_MAX_GROUPS];
    short_path(m, mu + base, dt, x + 3 * base, v + 3 * base, dx + 3 * base, dv + 3 * base, apply,
               ir != NULL ? ir + base : NULL, done);
    for (size_t j = 0; j < m; ++j) {
      if (done[j]) continue;
      const size_t i = base + j;
      double sx[3], sv[3];
      gm_status st = gm_kepler_drift(mu[i], dt, x + 3 * i, v + 3 * i, apply ? sx : dx + 3 * i,
                                     apply ? sv : dv + 3 * i);
      if (st != GM_OK) return st;
      if (!apply) continue;
      double *xi = dx + 3 * i, *vi = dv + 3 * i;
      for (int c = 0; c < 3; ++c) xi[c] += sx[c], vi[c] += sv[c];
      if (ir != NULL) ir[i] = 1.0 / sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
    }
  }
  return GM_OK;
}

gm_status gm_kepler_drift_many_width(int width, size_t n, const double *mu, double dt,
                                     const double *x, const double *v, double *dx, double *dv) {
  return drift_many(width, n, mu, dt, x, v, dx, dv, 0, NULL);
}

gm_status gm_kepler_drift_many_apply(int width, size_t n, const double *mu, double dt, double *x,
                                     double *v, double *ir) {
  return drift_many(width, n, mu, dt, x, v, x, v, 1, ir);
}

gm_status gm_kepler_drift_many(size_t n, const double *mu, double dt, const double *x,
                               const double *v, double *dx, double *dv) {
  return gm_kepler_drift_many_width(gm_lane_width(), n, mu, dt, x, v, dx, dv);
}
