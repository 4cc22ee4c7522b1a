/* Invariantization by a moving frame and the layer-marching driver (geomint/pde_invariant.h).
 * Ñ(m) = N(ρ(m)·m) (seed 004 "Invariant integrators", notes/003-004 §2.4; the moving frames of
 * Fels & Olver, Acta Appl. Math. 55 (1999) 127, as used by Kim, BIT 47 (2007) and Chhay &
 * Hamdouni, C. R. Mécanique 338 (2010)): nothing here knows an equation. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <strings.h>

#include "core/internal.h"
#include "geomint/pde_invariant.h"
#include "pde/invariant_internal.h"

static const gm_inv_scheme *const schemes[] = {&gm_inv_ftcs, &gm_inv_lax_wendroff,
                                               &gm_inv_crank_nicolson, &gm_inv_heat_ftcs};
#define N_SCHEMES (sizeof schemes / sizeof schemes[0])

size_t gm_inv_scheme_count(void) { return N_SCHEMES; }
const gm_inv_scheme *gm_inv_scheme_at(size_t i) { return i < N_SCHEMES ? schemes[i] : NULL; }
gm_status gm_inv_scheme_find(const char *name, const gm_inv_scheme **out) {
  if (name == NULL || out == NULL) return GM_EINVAL;
  for (size_t i = 0; i < N_SCHEMES; i++)
    if (strcasecmp(schemes[i]->name, name) == 0) {
      *out = schemes[i];
      return GM_OK;
    }
  return GM_ENOTFOUND;
}

gm_status gm_inv_residual(const gm_inv_scheme *scheme, const gm_inv_group *group, double nu,
                          const gm_inv_stencil *m, double *r, double dn[3], gm_error *err) {
  if (group == NULL) {
    *r = scheme->residual(m, nu, dn);
    return GM_OK;
  }
  double a[GM_INV_MAX_PARAMS];
  char why[160];
  if (group->frame(m, a, why, sizeof why) != 0)
    return gm_error_set(err, GM_EDOMAIN, "the %s frame does not exist at (t, x) = (%.6g, %.6g): %s",
                        group->name, m->old[1].t, m->old[1].x, why);
  gm_inv_stencil hat;
  double du[3];
  for (int i = 0; i < 3; i++) {
    if (group->act(a, m->old[i], &hat.old[i], NULL) != 0 ||
        group->act(a, m->next[i], &hat.next[i], &du[i]) != 0)
      return gm_error_set(err, GM_EDOMAIN,
                          "the %s frame at (t, x) = (%.6g, %.6g) leaves the group's domain",
                          group->name, m->old[1].t, m->old[1].x);
  }
  *r = scheme->residual(&hat, nu, dn);
  for (int i = 0; i < 3; i++) dn[i] *= du[i]; /* û = α u + β at fixed (t, x): ∂û/∂u = α */
  return GM_OK;
}

gm_inv_run_spec gm_inv_run_spec_defaults(void) {
  gm_inv_run_spec s;
  memset(&s, 0, sizeof s);
  s.check_stability = 1;
  s.newton_tol = 1e-14;
  s.newton_max_iter = 20;
  return s;
}

/* The points of layer l: g·(t0 + lk, x_left + jh, exact there). */
static gm_status make_layer(const gm_inv_run_spec *s, size_t l, double *t, double *x, double *u,
                            gm_error *err) {
  double tb = s->t0 + (double)l * s->k;
  for (size_t j = 0; j < s->n; j++) {
    gm_inv_point p = {tb, s->x_left + (double)j * s->h, s->exact(tb, s->x_left + (double)j * s->h,
                                                                 s->exact_ctx)};
    if (!isfinite(p.u))
      return gm_error_set(err, GM_EDOMAIN, "the exact solution is not finite at (t, x) = "
                          "(%.6g, %.6g)", p.t, p.x);
    if (s->transform_group != NULL &&
        s->transform_group->act(s->transform_a, p, &p, NULL) != 0)
      return gm_error_set(err, GM_EDOMAIN, "the transformation is not defined at (t, x) = "
                          "(%.6g, %.6g)", p.t, p.x);
    x[j] = p.x;
    if (u != NULL) u[j] = p.u;
    if (j == 0) *t = p.t;
    else if (fabs(p.t - *t) > 1e-12 * (1.0 + fabs(*t)))
      return gm_error_set(err, GM_EINVAL, "the transformation does not keep layer %zu flat", l);
  }
  return GM_OK;
}

static gm_status check_spec(const gm_inv_run_spec *s, gm_error *err) {
  if (s == NULL || s->scheme == NULL || s->exact == NULL)
    return gm_error_set(err, GM_EINVAL, "invariant run: NULL spec, scheme or exact solution");
  if (!isfinite(s->nu) || s->nu < 0.0)
    return gm_error_set(err, GM_EINVAL, "viscosity nu = %g: must be finite and >= 0", s->nu);
  if (s->n < 3 || s->n > ((size_t)1 << 26))
    return gm_error_set(err, GM_EINVAL, "%zu points per layer: need 3 .. 2^26", s->n);
  if (!(isfinite(s->h) && s->h > 0.0) || !(isfinite(s->k) && s->k > 0.0) || !isfinite(s->t0) ||
      !isfinite(s->x_left))
    return gm_error_set(err, GM_EINVAL, "mesh h = %g, k = %g, t0 = %g, x_left = %g: h, k must "
                        "be finite and > 0, t0, x_left finite", s->h, s->k, s->t0, s->x_left);
  if (s->frame_group != NULL && strcmp(s->frame_group->equation, s->scheme->equation) != 0)
    return gm_error_set(err, GM_EINVAL, "group %s acts on the %s equation, scheme %s is for %s",
                        s->frame_group->name, s->frame_group->equation, s->scheme->name,
                        s->scheme->equation);
  if ((s->transform_group == NULL) != (s->transform_a == NULL))
    return gm_error_set(err, GM_EINVAL, "transform_group and transform_a: both or neither");
  if (s->transform_group != NULL)
    for (size_t i = 0; i < s->transform_group->n_params; i++)
      if (!isfinite(s->transform_a[i]))
        return gm_error_set(err, GM_EINVAL, "transformation parameter %zu is not finite", i);
  if (!(s->newton_tol > 0.0) || s->newton_max_iter == 0)
    return gm_error_set(err, GM_EINVAL, "newton_tol must be > 0, newton_max_iter >= 1");
  return GM_OK;
}

/* The stencil of interior node j from layers (x0, u0) and (x1, u1). */
static void stencil_at(size_t j, double t0, const double *x0, const double *u0, double t1,
                       const double *x1, const double *u1, gm_inv_stencil *m) {
  for (int i = 0; i < 3; i++) {
    m->old[i] = (gm_inv_point){t0, x0[j - 1 + (size_t)i], u0[j - 1 + (size_t)i]};
    m->next[i] = (gm_inv_point){t1, x1[j - 1 + (size_t)i], u1[j - 1 + (size_t)i]};
  }
}

/* Refuse a step above the bound: the velocity the scheme sees relative to the mesh is u for the
 * standard form (it cannot see the mesh move) and u − σ/k for the invariant one (σ the shift of
 * node j between the layers: the frame's boost removes it). */
static gm_status check_bound(const gm_inv_run_spec *s, size_t step, double t0, const double *x0,
                             const double *u0, double t1, const double *x1, double *bound_min,
                             gm_error *err) {
  double k = t1 - t0, hmin = INFINITY, vmax = 0.0;
  for (size_t j = 0; j + 1 < s->n; j++) hmin = fmin(hmin, x0[j + 1] - x0[j]);
  for (size_t j = 0; j < s->n; j++) {
    double v = u0[j] - (s->frame_group != NULL ? (x1[j] - x0[j]) / k : 0.0);
    vmax = fmax(vmax, fabs(v));
  }
  double b = s->scheme->step_bound(hmin, vmax, s->nu);
  *bound_min = fmin(*bound_min, b);
  if (s->check_stability && k > b)
    return gm_error_set(err, GM_EINVAL, "step %zu: k = %.6g is above the stability bound "
                        "%.6g of %s (%s; h = %.6g, max|u| = %.6g, nu = %.6g)", step, k, b,
                        s->scheme->name, s->scheme->bound_text, hmin, vmax, s->nu);
  return GM_OK;
}

/* Thomas algorithm on the interior rows 1..n−2 (a: sub, b: diagonal, c: super; rhs → solution).
 * No pivoting: the Jacobians here are tridiagonal M-matrix-like near the solution; a zero pivot
 * is GM_ESINGULAR. */
static gm_status tridiagonal_solve(size_t n, double *a, double *b, const double *c, double *rhs) {
  for (size_t j = 2; j + 1 < n; j++) {
    if (b[j - 1] == 0.0 || !isfinite(b[j - 1])) return GM_ESINGULAR;
    double f = a[j] / b[j - 1];
    b[j] -= f * c[j - 1];
    rhs[j] -= f * rhs[j - 1];
  }
  if (b[n - 2] == 0.0 || !isfinite(b[n - 2])) return GM_ESINGULAR;
  rhs[n - 2] /= b[n - 2];
  for (size_t j = n - 3; j >= 1; j--) rhs[j] = (rhs[j] - c[j] * rhs[j + 1]) / b[j];
  return GM_OK;
}

static gm_status newton_step(const gm_inv_run_spec *s, size_t step, double t0, const double *x0,
                             const double *u0, double t1, const double *x1, double *u1,
                             double *w, size_t *iterations, gm_error *err) {
  size_t n = s->n;
  double *a = w, *b = w + n, *c = w + 2 * n, *r = w + 3 * n;
  for (size_t it = 1; it <= s->newton_max_iter; it++) {
    for (size_t j = 1; j + 1 < n; j++) {
      gm_inv_stencil m;
      stencil_at(j, t0, x0, u0, t1, x1, u1, &m);
      double dn[3];
      gm_status st = gm_inv_residual(s->scheme, s->frame_group, s->nu, &m, &r[j], dn, err);
      if (st != GM_OK) return st;
      a[j] = dn[0];
      b[j] = dn[1];
      c[j] = dn[2];
    }
    if (tridiagonal_solve(n, a, b, c, r) != GM_OK)
      return gm_error_set(err, GM_ESINGULAR, "step %zu: the Newton matrix of %s is singular",
                          step, s->scheme->name);
    double dmax = 0.0, umax = 0.0;
    for (size_t j = 1; j + 1 < n; j++) {
      u1[j] -= r[j];
      dmax = fmax(dmax, fabs(r[j]));
      umax = fmax(umax, fabs(u1[j]));
    }
    *iterations += 1;
    if (!isfinite(dmax))
      return gm_error_set(err, GM_EDOMAIN, "step %zu (t = %.6g): the solution of %s is not "
                          "finite (blew up)", step, t1, s->scheme->name);
    /* an explicit scheme's residual is affine in its unknown: one iteration is the solution */
    if (s->scheme->is_explicit || dmax <= s->newton_tol * (1.0 + umax)) return GM_OK;
  }
  return gm_error_set(err, GM_ENOCONV, "step %zu: Newton of %s did not converge in %zu "
                      "iterations", step, s->scheme->name, s->newton_max_iter);
}

gm_status gm_inv_run(const gm_inv_run_spec *spec, double *t_out, double *x_out, double *u_out,
                     gm_inv_run_stats *stats, gm_error *err) {
  gm_status st = check_spec(spec, err);
  if (st != GM_OK) return st;
  size_t n = spec->n;
  double *mem = malloc(9 * n * sizeof *mem); /* x0 u0 x1 u1 ub + 4n Newton work */
  if (mem == NULL) return gm_error_set(err, GM_ENOMEM, "invariant run: out of memory (n = %zu)",
                                       n);
  double *x0 = mem, *u0 = mem + n, *x1 = mem + 2 * n, *u1 = mem + 3 * n, *w = mem + 5 * n;
  double *ub = mem + 4 * n;
  gm_inv_run_stats S = {0, 0, 0.0, INFINITY};
  double t0 = 0.0, t1 = 0.0;
  st = make_layer(spec, 0, &t0, x0, u0, err);
  for (size_t j = 0; st == GM_OK && j < n; j++) S.max_abs_u = fmax(S.max_abs_u, fabs(u0[j]));
  for (size_t step = 1; st == GM_OK && step <= spec->n_steps; step++) {
    st = make_layer(spec, step, &t1, x1, ub, err);
    if (st != GM_OK) break;
    if (!(t1 > t0)) {
      st = gm_error_set(err, GM_EINVAL, "step %zu: layer time %.6g is not after %.6g", step, t1,
                        t0);
      break;
    }
    st = check_bound(spec, step, t0, x0, u0, t1, x1, &S.step_bound, err);
    if (st != GM_OK) break;
    memcpy(u1, u0, n * sizeof *u1); /* Newton's start: the old layer */
    u1[0] = ub[0];
    u1[n - 1] = ub[n - 1];
    st = newton_step(spec, step, t0, x0, u0, t1, x1, u1, w, &S.newton_iterations, err);
    if (st != GM_OK) break;
    for (size_t j = 0; j < n; j++) S.max_abs_u = fmax(S.max_abs_u, fabs(u1[j]));
    if (!isfinite(S.max_abs_u)) {
      st = gm_error_set(err, GM_EDOMAIN, "step %zu (t = %.6g): the solution of %s is not "
                        "finite (blew up)", step, t1, spec->scheme->name);
      break;
    }
    memcpy(x0, x1, n * sizeof *x0);
    memcpy(u0, u1, n * sizeof *u0);
    t0 = t1;
    S.steps = step;
  }
  if (t_out != NULL) *t_out = t0;
  if (x_out != NULL) memcpy(x_out, x0, n * sizeof *x0);
  if (u_out != NULL) memcpy(u_out, u0, n * sizeof *u0);
  if (stats != NULL) *stats = S;
  free(mem);
  return st;
}
