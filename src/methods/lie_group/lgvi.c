/* Lie group variational integrator (Lee, Leok & McClamroch, Comput. Methods Appl. Mech. Eng.
 * 196 (2007) 2907, eqs. (44)–(47), here for one body in a fixed field; the attitude part is
 * also their Proc. ACC (2005) 962 3-D pendulum scheme). From the discrete Lagrangian
 *   L_d = (1/h) tr[(I − F_k) J_d] + (h/2)|Δx|²m/h² − (h/2)(V_k + V_{k+1}),  J_d = ½ tr(J) I − J,
 * with R_{k+1} = R_k F_k, the discrete Euler–Lagrange equations are
 *   h μ̂ = F_k J_d − J_d F_kᵀ,           μ = Π_k − (h/2) g_k               (implicit in F_k)
 *   R_{k+1} = R_k F_k,  x_{k+1} = x_k + (h/m)(p_k − (h/2) ∂V/∂x_k)
 *   Π_{k+1} = F_kᵀ μ − (h/2) g_{k+1},  p_{k+1} = p_k − (h/2)(∂V/∂x_k + ∂V/∂x_{k+1})
 * (g = −M, the body-frame gradient of V; their M is the moment). With F = exp(f̂) the implicit
 * equation is, in vectors (their eq. (46) with exp in place of their Cayley-free form),
 *   G(f) = a(θ) J f + b(θ) f × J f − h μ = 0,  a = sin θ/θ, b = (1 − cos θ)/θ², θ = |f|,
 * solved by Newton's method in so(3) with the analytic Jacobian
 *   ∂G/∂f = a J + b (f̂ J − (J f)^) + (a'/θ) J f fᵀ + (b'/θ) (f × J f) fᵀ.
 * Free body: Π_{k+1} = F_kᵀ Π_k keeps |Π| and the spatial momentum R Π exactly (up to the
 * rounding of the rotation), whatever the Newton tolerance. */
#include <float.h>
#include <math.h>

#include "methods/lie_group/lie_group.h"

/* a'(θ)/θ = (θ cos θ − sin θ)/θ³ and b'(θ)/θ = (θ sin θ − 2(1 − cos θ))/θ⁴ (for the Jacobian
 * only: series below θ = 0.1 are accurate to 1e-9, enough for Newton's convergence) */
static double da_over_theta(double t) {
  double t2 = t * t;
  if (t < 0.1) return -1.0 / 3.0 + t2 / 30.0 - t2 * t2 / 840.0;
  return (t * cos(t) - sin(t)) / (t2 * t);
}

static double db_over_theta(double t) {
  double t2 = t * t;
  if (t < 0.1) return -1.0 / 12.0 + t2 / 180.0 - t2 * t2 / 6720.0;
  return (t * sin(t) - 2.0 * (1.0 - cos(t))) / (t2 * t2);
}

/* Solve the 3×3 system m x = r by cofactors; 0 when m is singular. */
static int solve3(const double m[9], const double r[3], double x[3]) {
  double c0 = m[4] * m[8] - m[5] * m[7], c3 = m[5] * m[6] - m[3] * m[8],
         c6 = m[3] * m[7] - m[4] * m[6];
  double det = m[0] * c0 + m[1] * c3 + m[2] * c6;
  if (!(fabs(det) > 0.0) || !isfinite(det)) return 0;
  double c1 = m[2] * m[7] - m[1] * m[8], c4 = m[0] * m[8] - m[2] * m[6],
         c7 = m[1] * m[6] - m[0] * m[7];
  double c2 = m[1] * m[5] - m[2] * m[4], c5 = m[2] * m[3] - m[0] * m[5],
         c8 = m[0] * m[4] - m[1] * m[3];
  x[0] = (c0 * r[0] + c1 * r[1] + c2 * r[2]) / det;
  x[1] = (c3 * r[0] + c4 * r[1] + c5 * r[2]) / det;
  x[2] = (c6 * r[0] + c7 * r[1] + c8 * r[2]) / det;
  return 1;
}

#define LGVI_MAX_ITERATIONS 30

/* f with a J f + b f × J f = h μ */
static gm_status solve_f(gm_integrator *it, const gm_lie_work *w, double h, const double mu[3],
                         double f[3]) {
  const double *j = w->j;
  double hmu[3] = {h * mu[0], h * mu[1], h * mu[2]};
  gm_mat3_vec(w->jinv, hmu, f); /* first order: J f = h μ */
  double last = INFINITY, res_norm = NAN;
  for (size_t iter = 1; iter <= LGVI_MAX_ITERATIONS; ++iter) {
    it->stats.newton_iterations++;
    double theta = gm_vec3_norm(f), a = gm_so3_sinc(theta), b = gm_so3_cosc(theta);
    double jf[3], fxjf[3], res[3], jac[9], fh[9], jfh[9], fhj[9], dx[3];
    gm_mat3_vec(j, f, jf);
    gm_vec3_cross(f, jf, fxjf);
    for (int c = 0; c < 3; ++c) res[c] = a * jf[c] + b * fxjf[c] - hmu[c];
    res_norm = fmax(fabs(res[0]), fmax(fabs(res[1]), fabs(res[2])));
    double da = da_over_theta(theta), db = db_over_theta(theta);
    gm_so3_hat(f, fh);
    gm_mat3_mul(fh, j, fhj);
    gm_so3_hat(jf, jfh);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        jac[3 * r + c] = a * j[3 * r + c] + b * (fhj[3 * r + c] - jfh[3 * r + c]) +
                         da * jf[r] * f[c] + db * fxjf[r] * f[c];
    if (!solve3(jac, res, dx))
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_ESINGULAR,
                     "the Jacobian of the LGVI equation for F_k is singular at |f| = %g", theta);
    for (int c = 0; c < 3; ++c) f[c] -= dx[c];
    double step = fmax(fabs(dx[0]), fmax(fabs(dx[1]), fabs(dx[2])));
    double size = fmax(fabs(f[0]), fmax(fabs(f[1]), fabs(f[2])));
    if (!isfinite(step)) break;
    /* converged at round-off, or stagnating there (the update stopped shrinking) */
    if (step <= 4.0 * DBL_EPSILON * size || (step >= 0.5 * last && step <= 1e-13 * size))
      return GM_OK;
    last = step;
  }
  /* |a J f| ≤ ‖J‖ |sin θ|: for h|μ| beyond about the largest moment there is no solution */
  return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOCONV,
                 "Newton's method for F_k did not converge in %d iterations (residual %.3g; "
                 "h|Pi| = %.3g: the step may be too large for the body's rotation rate)",
                 LGVI_MAX_ITERATIONS, res_norm, fabs(h) * gm_vec3_norm(mu));
}

gm_status gm_lgvi_step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                       double e[9]) {
  gm_lie_work *w = it->work;
  const size_t nt = w->nt, pi = w->pi;
  double g[3], fx[3] = {0, 0, 0}, mu[3], f[3], ff[9], p_half[3] = {0, 0, 0};
  gm_status st = gm_lie_gradient(it, t, y, nt ? y + 9 : NULL, g, fx);
  if (st != GM_OK) return st;
  for (int c = 0; c < 3; ++c) mu[c] = y[pi + c] - 0.5 * h * g[c];
  st = solve_f(it, w, h, mu, f);
  if (st != GM_OK) return gm_stage_solve_failed(it, st, t, h);
  gm_so3_expm1(f, e);
  gm_so3_exp(f, ff);
  /* the new configuration, where the second half kick is evaluated */
  double r_new[9];
  gm_mat3_mul(y, e, r_new);
  for (int k = 0; k < 9; ++k) r_new[k] += y[k];
  if (nt)
    for (int c = 0; c < 3; ++c) {
      p_half[c] = y[pi + 3 + c] - 0.5 * h * fx[c];
      y_new[9 + c] = y[9 + c] + h * p_half[c] / w->mass;
    }
  st = gm_lie_gradient(it, t + h, r_new, nt ? y_new + 9 : NULL, g, fx);
  if (st != GM_OK) return st;
  gm_mat3_tvec(ff, mu, y_new + pi); /* F_kᵀ μ */
  for (int c = 0; c < 3; ++c) y_new[pi + c] -= 0.5 * h * g[c];
  if (nt)
    for (int c = 0; c < 3; ++c) y_new[pi + 3 + c] = p_half[c] - 0.5 * h * fx[c];
  return GM_OK;
}
