/* The three scalar schemes of seed 004 for a nonlinear wave equation u_tt − u_xx + V'(u) = 0
 * (sine-Gordon, V = −cos u), with the signs restored per notes/003-004 §2.2:
 *   LF: δ_t²uⁿ_i − δ_x²uⁿ_i + V'(uⁿ_i) = 0
 *   EC: the same with V'(uⁿ_i) → (V(uⁿ⁺¹_i) − V(uⁿ⁻¹_i))/(uⁿ⁺¹_i − uⁿ⁻¹_i)
 *   MS: A_x δ_t²u − A_t δ_x²u + ¼ Σ V'(ū) = 0 over the four cells around (n, i), ū the
 *       four-point cell average, A_x z = (z_{i+1} + 2z_i + z_{i−1})/4 (A_t likewise): the
 *       Preissmann box with v, w eliminated (Bridges & Reich 2001). */
#include <math.h>
#include <string.h>

#include "pde/internal.h"

static double d2V(gm_pde *p, double u) {
  double s[3] = {u, 0.0, 0.0}, H[9];
  gm_pde_hessian(p, s, H, p->work);
  return H[0];
}

static double lap(const gm_pde *p, const double *u, size_t i, double h) {
  return (gm_pde_u_at(p, u, i, 1) - 2.0 * u[i] + gm_pde_u_at(p, u, i, -1)) / (h * h);
}

gm_status gm_pde_wave_start(gm_pde *p, gm_error *err) {
  /* uⁿ = u⁰ at step 0; uⁿ⁻¹ by the backward Taylor step u⁰ − Δt u_t + ½Δt²(δ_x²u⁰ − V'(u⁰)) */
  size_t n = p->n;
  double dt = p->opt.dt;
  for (size_t i = 0; i < n; i++) p->u[i] = p->s[i * 3];
  for (size_t i = 0; i < n; i++) {
    if (gm_pde_dirichlet(p) && (i == 0 || i == n - 1)) { /* held: u_t = 0 */
      p->u_prev[i] = p->u[i];
      continue;
    }
    double acc = lap(p, p->u, i, p->grid.h) - p->eq.dV(p->u[i], p->eq.params);
    p->u_prev[i] = p->u[i] - dt * p->s[i * 3 + 1] + 0.5 * dt * dt * acc;
    if (!isfinite(p->u_prev[i]))
      return gm_error_set(err, GM_EDOMAIN, "pde: non-finite start value at point %zu", i);
  }
  gm_pde_wave_fill_state(p);
  return GM_OK;
}

void gm_pde_wave_fill_state(gm_pde *p) {
  size_t n = p->n;
  for (size_t i = 0; i < n; i++) {
    p->s[i * 3] = p->u[i];
    p->s[i * 3 + 1] = (p->u[i] - p->u_prev[i]) / p->opt.dt;
    p->s[i * 3 + 2] = (gm_pde_u_at(p, p->u, i, 1) - p->u[i]) / p->grid.h;
  }
  if (gm_pde_dirichlet(p)) p->s[(n - 1) * 3 + 2] = p->s[(n - 2) * 3 + 2]; /* no wrap */
}

/* EC's difference quotient of V and its derivative in z, between z and y */
static double ec_quot(gm_pde *p, double z, double y, double *dq) {
  double e = z - y, m = 0.5 * (z + y);
  const void *c = p->eq.params;
  if (fabs(e) < 1e-6 * (1.0 + fabs(m))) {
    *dq = 0.5 * d2V(p, m);
    return p->eq.dV(m, c); /* V'(m) = quotient + O(e²); the energy law error is O(e³) */
  }
  double q = (p->eq.V(z, c) - p->eq.V(y, c)) / e;
  *dq = (p->eq.dV(z, c) - q) / e;
  return q;
}

static gm_status ms_step(gm_pde *p, gm_error *err) {
  size_t n = p->n;
  double dt = p->opt.dt, h = p->grid.h, a = 1.0 / (dt * dt), b = 1.0 / (h * h);
  const double *um = p->u_prev, *u = p->u;
  double *x = p->u_new, *F = p->F, *dx = p->dx;
  const void *c = p->eq.params;
  for (size_t i = 0; i < n; i++) x[i] = 2.0 * u[i] - um[i];
  double last = INFINITY;
  size_t it;
  for (it = 0; it < p->opt.newton_max_iter; it++) {
    gm_band_zero(&p->band);
    for (size_t i = 0; i < n; i++) {
      size_t ip = (i + 1) % n, im = (i + n - 1) % n;
      double tt[3], xx = 0.0;
      /* neighbour values on the (twisted) ring: [0] = i−1, [1] = i, [2] = i+1 */
      double xv[3], uv[3], mv[3];
      for (int k = 0; k < 3; k++) {
        xv[k] = gm_pde_u_at(p, x, i, k - 1);
        uv[k] = gm_pde_u_at(p, u, i, k - 1);
        mv[k] = gm_pde_u_at(p, um, i, k - 1);
        tt[k] = (xv[k] - 2.0 * uv[k] + mv[k]) * a;
      }
      double Ax = 0.25 * (tt[0] + 2.0 * tt[1] + tt[2]);
      xx = 0.25 * ((xv[2] - 2.0 * xv[1] + xv[0]) + 2.0 * (uv[2] - 2.0 * uv[1] + uv[0]) +
                   (mv[2] - 2.0 * mv[1] + mv[0])) * b;
      double up_r = 0.25 * (uv[1] + uv[2] + xv[1] + xv[2]); /* (i+½, n+½) */
      double up_l = 0.25 * (uv[0] + uv[1] + xv[0] + xv[1]); /* (i−½, n+½) */
      double dn_r = 0.25 * (uv[1] + uv[2] + mv[1] + mv[2]); /* (i+½, n−½) */
      double dn_l = 0.25 * (uv[0] + uv[1] + mv[0] + mv[1]); /* (i−½, n−½) */
      if (gm_pde_dirichlet(p) && (i == 0 || i == n - 1)) { /* held end: uⁿ⁺¹ = uⁿ */
        F[i] = x[i] - u[i];
        gm_band_add(&p->band, p->pos[i], p->pos[i], 1.0);
        continue;
      }
      F[i] = Ax - xx + 0.25 * (p->eq.dV(up_r, c) + p->eq.dV(up_l, c) + p->eq.dV(dn_r, c) +
                               p->eq.dV(dn_l, c));
      double hr = d2V(p, up_r) / 16.0, hl = d2V(p, up_l) / 16.0;
      gm_band_add(&p->band, p->pos[i], p->pos[i], 0.5 * a + 0.5 * b + hr + hl);
      gm_band_add(&p->band, p->pos[i], p->pos[ip], 0.25 * a - 0.25 * b + hr);
      gm_band_add(&p->band, p->pos[i], p->pos[im], 0.25 * a - 0.25 * b + hl);
    }
    p->stats.factorizations++;
    gm_status st = gm_band_factor(&p->band);
    if (st != GM_OK)
      return gm_error_set(err, st, "pde ms: singular Newton matrix at step %zu", p->steps + 1);
    for (size_t i = 0; i < n; i++) dx[p->pos[i]] = -F[i];
    gm_band_solve(&p->band, dx);
    double prev = last;
    last = 0.0;
    double xm = 0.0;
    for (size_t i = 0; i < n; i++) {
      double d = dx[p->pos[i]];
      x[i] += d;
      if (!(fabs(d) <= last)) last = fabs(d);
      if (fabs(x[i]) > xm) xm = fabs(x[i]);
    }
    p->stats.newton_iterations++;
    if (!isfinite(last) || !isfinite(xm)) break;
    if (last <= p->opt.newton_tol * (1.0 + xm)) break;
    if (last <= 1e-9 * (1.0 + xm) && last >= 0.5 * prev) break; /* round-off floor */
  }
  if (!isfinite(last))
    return gm_error_set(err, GM_EDOMAIN, "pde ms: non-finite state at step %zu", p->steps + 1);
  if (it == p->opt.newton_max_iter)
    return gm_error_set(err, GM_ENOCONV, "pde ms: Newton did not converge at step %zu "
                        "(max|du| = %g)", p->steps + 1, last);
  if (last > p->stats.max_newton_residual) p->stats.max_newton_residual = last;
  return GM_OK;
}

gm_status gm_pde_wave_step(gm_pde *p, gm_error *err) {
  size_t n = p->n;
  double dt = p->opt.dt, h = p->grid.h;
  const void *c = p->eq.params;
  gm_status st = GM_OK;
  if (p->scheme->kind == GM_PDE_WAVE_MS) {
    st = ms_step(p, err);
    if (st != GM_OK) return st;
  } else {
    for (size_t i = 0; i < n; i++) {
      if (gm_pde_dirichlet(p) && (i == 0 || i == n - 1)) {
        p->u_new[i] = p->u[i];
        continue;
      }
      double base = 2.0 * p->u[i] - p->u_prev[i] + dt * dt * lap(p, p->u, i, h);
      if (p->scheme->kind == GM_PDE_WAVE_LF) {
        p->u_new[i] = base - dt * dt * p->eq.dV(p->u[i], c);
        continue;
      }
      /* EC: z − base + Δt² Q(z, uⁿ⁻¹) = 0 by scalar Newton from the LF value */
      double z = base - dt * dt * p->eq.dV(p->u[i], c), y = p->u_prev[i], dz = INFINITY;
      double dz_old = INFINITY;
      size_t it;
      for (it = 0; it < p->opt.newton_max_iter && isfinite(z); it++) {
        double dq, q = ec_quot(p, z, y, &dq);
        dz = -(z - base + dt * dt * q) / (1.0 + dt * dt * dq);
        z += dz;
        p->stats.newton_iterations++;
        double scale = 1.0 + fabs(z);
        if (fabs(dz) <= p->opt.newton_tol * scale) break;
        /* the difference quotient carries round-off ~ ε|V|/|z − y|: accept the floor once the
         * corrections stop shrinking below 1e-8 relative */
        if (fabs(dz) <= 1e-8 * scale && fabs(dz) >= 0.5 * dz_old) break;
        dz_old = fabs(dz);
      }
      if (!isfinite(z))
        return gm_error_set(err, GM_EDOMAIN, "pde ec: non-finite state at step %zu point %zu",
                            p->steps + 1, i);
      if (it == p->opt.newton_max_iter)
        return gm_error_set(err, GM_ENOCONV,
                            "pde ec: scalar Newton did not converge at step %zu point %zu",
                            p->steps + 1, i);
      p->u_new[i] = z;
    }
  }
  for (size_t i = 0; i < n; i++)
    if (!isfinite(p->u_new[i]))
      return gm_error_set(err, GM_EDOMAIN, "pde %s: non-finite state at step %zu point %zu",
                          p->scheme->name, p->steps + 1, i);
  double *t = p->u_prev;
  p->u_prev = p->u;
  p->u = p->u_new;
  p->u_new = t;
  gm_pde_wave_fill_state(p);
  return GM_OK;
}

double gm_pde_wave_energy(const gm_pde *p) {
  size_t n = p->n;
  double h = p->grid.h, dt = p->opt.dt, e = 0.0;
  const double *u = p->u, *um = p->u_prev;
  for (size_t i = 0; i < n; i++) {
    double ut = (u[i] - um[i]) / dt;
    e += 0.5 * ut * ut + 0.5 * (p->eq.V(u[i], p->eq.params) + p->eq.V(um[i], p->eq.params));
    if (!(gm_pde_dirichlet(p) && i == n - 1)) /* no cell past a Dirichlet right end */
      e += 0.5 * (gm_pde_u_at(p, um, i, 1) - um[i]) / h * (gm_pde_u_at(p, u, i, 1) - u[i]) / h;
  }
  return h * e;
}

double gm_pde_wave_momentum(const gm_pde *p) {
  size_t n = p->n;
  double h = p->grid.h, dt = p->opt.dt, m = 0.0;
  for (size_t i = 0; i < n; i++)
    m -= (gm_pde_u_at(p, p->u, i, 1) - gm_pde_u_at(p, p->u, i, -1)) / (2.0 * h) *
         (p->u[i] - p->u_prev[i]) / dt;
  return h * m;
}
