/* The stepper of the Lie group rows: set-up shared by all schemes, the explicit schemes RKMK
 * and Crouch–Grossman, and the state update R_new = R + R E (E = F − I of the step's right
 * factor F, so compensated summation sees the small increment R E with its own digits).
 *
 * Rigid-body equations (geomint/ode.h): R' = R Ω̂, Π' = Π × Ω − g(R, x), Ω = J⁻¹Π,
 * x' = p/m, p' = −∂V/∂x. */
#include <stdlib.h>
#include <string.h>

#include "methods/lie_group/lie_group.h"

gm_status gm_lie_gradient(gm_integrator *it, double t, const double *r, const double *x,
                          double g[3], double fx[3]) {
  const gm_problem *pb = it->problem;
  it->stats.force_evals++;
  if (pb->rigid_potential_gradient == NULL) {
    g[0] = g[1] = g[2] = 0.0;
    if (x != NULL) fx[0] = fx[1] = fx[2] = 0.0;
    return GM_OK;
  }
  int rc = pb->rigid_potential_gradient(pb->ctx, r, x, g, x != NULL ? fx : NULL);
  return rc == 0 ? GM_OK : gm_callback_failed(it, "rigid_potential_gradient", rc, t);
}

static gm_status init(gm_integrator *it) {
  const gm_problem *pb = it->problem;
  gm_lie_work *w = calloc(1, sizeof *w);
  if (w == NULL) return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOMEM, "out of memory");
  it->work = w;
  w->scheme = gm_lie_scheme_of(it->method);
  w->nt = pb->dim - 3;
  w->pi = 9 + w->nt;
  memcpy(w->j, pb->inertia, sizeof w->j);
  w->mass = pb->mass;
  gm_error err;
  if (gm_rigid_inertia_inverse(w->j, w->jinv, &err) != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "%s", err.message);
  w->principal = w->j[1] == 0.0 && w->j[2] == 0.0 && w->j[3] == 0.0 && w->j[5] == 0.0 &&
                 w->j[6] == 0.0 && w->j[7] == 0.0;
  if (w->scheme == GM_LIE_SPLITTING && !w->principal)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "'%s' rotates about the body axes: it needs a diagonal inertia J (principal "
                   "axes as body frame)", it->method->name);
  if (w->scheme == GM_LIE_RKMK || w->scheme == GM_LIE_CROUCH_GROSSMAN) {
    if (it->method->n_stages > GM_LIE_MAX_STAGES)
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "'%s' has %zu stages (at most %d)",
                     it->method->name, it->method->n_stages, GM_LIE_MAX_STAGES);
    gm_status st = gm_method_tableau(it->method, &w->tableau);
    if (st != GM_OK)
      return gm_fail(it->errmsg, sizeof it->errmsg, st, "cannot build the tableau of '%s'",
                     it->method->name);
  }
  if (w->scheme == GM_LIE_GALERKIN || w->scheme == GM_LIE_DEP)
    return gm_lie_galerkin_init(it, w->scheme == GM_LIE_DEP);
  if (w->scheme == 0)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "'%s' is not a Lie group row",
                   it->method->name);
  return GM_OK;
}

static void release(gm_integrator *it) {
  gm_lie_work *w = it->work;
  if (w != NULL) {
    gm_tableau_free(w->tableau);
    gm_lie_galerkin_release(w);
  }
  free(w);
  it->work = NULL;
}

/* Stage i of an explicit scheme at (R_i, x_i, Π_i, p_i): Ω_i, the rates of Π, x and p. */
static gm_status stage_rates(gm_integrator *it, gm_lie_work *w, size_t i, double t,
                             const double *r, const double *x, const double *pi,
                             const double *p) {
  double g[3], fx[3];
  gm_status st = gm_lie_gradient(it, t, r, w->nt ? x : NULL, g, fx);
  if (st != GM_OK) return st;
  gm_mat3_vec(w->jinv, pi, w->omega[i]);
  gm_vec3_cross(pi, w->omega[i], w->k_pi[i]);
  for (int a = 0; a < 3; ++a) w->k_pi[i][a] -= g[a];
  if (w->nt)
    for (int a = 0; a < 3; ++a) {
      w->k_x[i][a] = p[a] / w->mass;
      w->k_p[i][a] = -fx[a];
    }
  return GM_OK;
}

/* x_i = x0 + h Σ_j a_ij k_j over the stages j < i (vectors of 3) */
static void combine(size_t i, size_t s, const double *a, double h, const double *x0,
                    double k[][3], double out[3]) {
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (size_t j = 0; j < i; ++j) sum += a[i * s + j] * k[j][c];
    out[c] = x0[c] + h * sum;
  }
}

/* RKMK (Munthe-Kaas 1998): R = R0 exp(θ), θ' = dexp_{−θ}⁻¹ Ω (the body velocity of
 * R0 exp(θ) is dexp_{−θ} θ'), and an explicit Runge–Kutta step on (θ, x, Π, p) from θ = 0. */
static gm_status rkmk_step(gm_integrator *it, double t, double h, const double *y,
                           double *y_new, double e[9]) {
  gm_lie_work *w = it->work;
  const gm_tableau *tb = w->tableau;
  const size_t s = tb->n_stages, nt = w->nt, pi = w->pi;
  const double zero[3] = {0, 0, 0};
  for (size_t i = 0; i < s; ++i) {
    double theta[3], r[9], x[3] = {0, 0, 0}, pm[3], p[3] = {0, 0, 0}, d[9];
    combine(i, s, tb->a, h, zero, w->k_theta, theta);
    combine(i, s, tb->a, h, y + pi, w->k_pi, pm);
    if (nt) {
      combine(i, s, tb->a, h, y + 9, w->k_x, x);
      combine(i, s, tb->a, h, y + pi + 3, w->k_p, p);
    }
    gm_so3_exp(theta, r);
    gm_mat3_mul(y, r, r);
    gm_status st = stage_rates(it, w, i, t + tb->c[i] * h, r, x, pm, p);
    if (st != GM_OK) return st;
    const double minus[3] = {-theta[0], -theta[1], -theta[2]};
    gm_so3_dexp_inv(minus, d);
    gm_mat3_vec(d, w->omega[i], w->k_theta[i]);
  }
  double theta[3];
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0, spi = 0.0, sx = 0.0, sp = 0.0;
    for (size_t j = 0; j < s; ++j) {
      sum += tb->b[j] * w->k_theta[j][c];
      spi += tb->b[j] * w->k_pi[j][c];
      if (nt) {
        sx += tb->b[j] * w->k_x[j][c];
        sp += tb->b[j] * w->k_p[j][c];
      }
    }
    theta[c] = h * sum;
    y_new[pi + c] = y[pi + c] + h * spi;
    if (nt) {
      y_new[9 + c] = y[9 + c] + h * sx;
      y_new[pi + 3 + c] = y[pi + 3 + c] + h * sp;
    }
  }
  gm_so3_expm1(theta, e);
  return GM_OK;
}

/* E ← (I + E)(I + D) − I = E + D + E D: the right factor grows by exp(δ) with D = exp(δ) − I */
static void compose_right(double e[9], const double delta[3]) {
  double d[9], ed[9];
  gm_so3_expm1(delta, d);
  gm_mat3_mul(e, d, ed);
  for (int k = 0; k < 9; ++k) e[k] += d[k] + ed[k];
}

/* Crouch–Grossman: R_i = R0 exp(h a_i1 Ω_1) ⋯ exp(h a_i,i−1 Ω_i−1) (the frozen body velocities
 * act on the right, first stage innermost), R1 = R0 exp(h b_1 Ω_1) ⋯ exp(h b_s Ω_s); Π, x, p
 * as in the underlying Runge–Kutta method. */
static gm_status crouch_grossman_step(gm_integrator *it, double t, double h, const double *y,
                                      double *y_new, double e[9]) {
  gm_lie_work *w = it->work;
  const gm_tableau *tb = w->tableau;
  const size_t s = tb->n_stages, nt = w->nt, pi = w->pi;
  for (size_t i = 0; i < s; ++i) {
    double ei[9] = {0}, r[9], x[3] = {0, 0, 0}, pm[3], p[3] = {0, 0, 0};
    for (size_t j = 0; j < i; ++j) {
      const double a = h * tb->a[i * s + j];
      if (a == 0.0) continue;
      const double delta[3] = {a * w->omega[j][0], a * w->omega[j][1], a * w->omega[j][2]};
      compose_right(ei, delta);
    }
    gm_mat3_mul(y, ei, r);
    for (int k = 0; k < 9; ++k) r[k] += y[k];
    combine(i, s, tb->a, h, y + pi, w->k_pi, pm);
    if (nt) {
      combine(i, s, tb->a, h, y + 9, w->k_x, x);
      combine(i, s, tb->a, h, y + pi + 3, w->k_p, p);
    }
    gm_status st = stage_rates(it, w, i, t + tb->c[i] * h, r, x, pm, p);
    if (st != GM_OK) return st;
  }
  memset(e, 0, 9 * sizeof *e);
  for (size_t j = 0; j < s; ++j) {
    const double b = h * tb->b[j];
    const double delta[3] = {b * w->omega[j][0], b * w->omega[j][1], b * w->omega[j][2]};
    compose_right(e, delta);
  }
  for (int c = 0; c < 3; ++c) {
    double spi = 0.0, sx = 0.0, sp = 0.0;
    for (size_t j = 0; j < s; ++j) {
      spi += tb->b[j] * w->k_pi[j][c];
      if (nt) {
        sx += tb->b[j] * w->k_x[j][c];
        sp += tb->b[j] * w->k_p[j][c];
      }
    }
    y_new[pi + c] = y[pi + c] + h * spi;
    if (nt) {
      y_new[9 + c] = y[9 + c] + h * sx;
      y_new[pi + 3 + c] = y[pi + 3 + c] + h * sp;
    }
  }
  return GM_OK;
}

static gm_status step(gm_integrator *it, double t, double h, const double *y_old, double *y_new,
                      double *delta) {
  gm_lie_work *w = it->work;
  double *out = y_new != NULL ? y_new : it->y_next; /* scratch when only delta is wanted */
  double e[9];
  gm_status st;
  switch (w->scheme) {
    case GM_LIE_LGVI:
      st = gm_lgvi_step(it, t, h, y_old, out, e);
      break;
    case GM_LIE_RKMK:
      st = rkmk_step(it, t, h, y_old, out, e);
      break;
    case GM_LIE_CROUCH_GROSSMAN:
      st = crouch_grossman_step(it, t, h, y_old, out, e);
      break;
    case GM_LIE_SPLITTING:
      st = gm_rigid_splitting_step(it, t, h, y_old, out, e);
      break;
    case GM_LIE_GALERKIN:
    case GM_LIE_DEP:
      st = gm_lie_galerkin_step(it, t, h, y_old, out, e);
      break;
    default:
      st = GM_EINVAL;
  }
  if (st != GM_OK) return st;
  double re[9];
  gm_mat3_mul(y_old, e, re); /* R_new − R_old = R_old E */
  if (delta != NULL) {
    for (int k = 0; k < 9; ++k) delta[k] = re[k];
    for (size_t k = 9; k < it->n; ++k) delta[k] = out[k] - y_old[k];
  } else {
    for (int k = 0; k < 9; ++k) out[k] = y_old[k] + re[k];
  }
  return GM_OK;
}

static void invalidate(gm_integrator *it) {
  if (it->work != NULL) gm_lie_galerkin_invalidate(it->work);
}

const gm_stepper gm_lie_group_stepper = {init, step, release, invalidate, NULL, NULL, 0};
