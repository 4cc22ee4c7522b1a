/* Public discrete mechanics (geomint/variational.h): the PRK tableau of a Galerkin discrete
 * Lagrangian, discrete Legendre transforms of the built-in discrete Lagrangians, user discrete
 * Lagrangians and their position–momentum solver, continuous Legendre transforms, Noether
 * momenta and constraint residuals. None of these runs inside an integrator's step, so they may
 * allocate. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/variational.h"
#include "methods/variational/variational_internal.h"

#define EPS 2.220446049250313e-16
#define CBRT_EPS 6.0554544523933395e-06

/* ---- seed 001 Thm 2.12 ---------------------------------------------------------------------- */

gm_status gm_galerkin_prk_tableau(size_t n, const double *nodes, gm_tableau **out) {
  if (out == NULL) return GM_EINVAL;
  *out = NULL;
  if (n == 0 || n > 64 || nodes == NULL) return GM_EINVAL;
  gm_tableau *t = calloc(1, sizeof *t);
  if (t == NULL) return GM_ENOMEM;
  t->n_stages = n;
  t->a = calloc(n * n, sizeof(double));
  t->a_bar = calloc(n * n, sizeof(double));
  t->b = calloc(n, sizeof(double));
  t->b_bar = calloc(n, sizeof(double));
  t->c = calloc(n, sizeof(double));
  if (!t->a || !t->a_bar || !t->b || !t->b_bar || !t->c) {
    gm_tableau_free(t);
    return GM_ENOMEM;
  }
  memcpy(t->c, nodes, n * sizeof *nodes);
  double x[64], w[64], l[64];
  gm_status st = GM_OK;
  /* a_ij = ∫_0^{c_i} l_j and b_j = ∫_0^1 l_j, exactly by n-point Gauss rules (degree n − 1) */
  for (size_t i = 0; i <= n && st == GM_OK; ++i) {
    double *row = i < n ? t->a + i * n : t->b;
    if ((st = gm_gauss_legendre(n, x, w)) != GM_OK) break;
    gm_quadrature_map(n, 0.0, i < n ? nodes[i] : 1.0, x, w);
    for (size_t k = 0; k < n && st == GM_OK; ++k) {
      if ((st = gm_lagrange_basis(n, nodes, x[k], l)) != GM_OK) break;
      for (size_t j = 0; j < n; ++j) row[j] += w[k] * l[j];
    }
  }
  for (size_t i = 0; i < n && st == GM_OK; ++i)
    if (t->b[i] == 0.0) st = GM_EINVAL;
  if (st != GM_OK) {
    gm_tableau_free(t);
    return st;
  }
  for (size_t i = 0; i < n; ++i) {
    t->b_bar[i] = t->b[i];
    for (size_t j = 0; j < n; ++j) t->a_bar[i * n + j] = t->b[j] * (1.0 - t->a[j * n + i] / t->b[i]);
  }
  *out = t;
  return GM_OK;
}

/* ---- Legendre transforms of the built-in discrete Lagrangians ------------------------------ */

/* Solve the inner points of the Galerkin curve from q0 to q1 (unconstrained, unforced) and
 * leave the engine evaluated there. */
static gm_status solve_inner(vi_engine *e, const double *q0, const double *q1, double h,
                             const double *zero) {
  const size_t d = e->d, s = e->s, ni = (s - 1) * d;
  e->t = 0.0;
  e->h = h;
  e->q = q0;
  e->p = zero;
  e->forced = 0;
  e->m = 0;
  gm_status st = GM_OK;
  if (e->quadratic && (st = gm_vi_prepare_mass(e, q0)) != GM_OK) return st;
  for (size_t nu = 1; nu <= s; ++nu)
    for (size_t k = 0; k < d; ++k) e->x[(nu - 1) * d + k] = e->ctimes[nu] * (q1[k] - q0[k]);
  double eta = INFINITY, eta_prev;
  for (int iter = 0;; ++iter) {
    if ((st = gm_vi_evaluate(e, e->x, ni > 0)) != GM_OK) return st;
    if (ni == 0 || eta <= 4.0 * EPS) return GM_OK;
    if (iter >= 50)
      return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ENOCONV,
                     "the inner points of the Galerkin curve did not converge");
    for (size_t mu = 1; mu < s; ++mu)
      for (size_t nu = 1; nu < s; ++nu)
        gm_vi_block(e, mu, nu, e->jac + (mu - 1) * d * ni + (nu - 1) * d, ni);
    memcpy(e->dx, e->dS + d, ni * sizeof(double));
    if (gm_lu_factor(ni, e->jac, e->piv) != GM_OK)
      return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ESINGULAR, "singular inner-point system");
    gm_lu_solve(ni, e->jac, e->piv, e->dx);
    double dz = 0.0, zmax = fmax(gm_norm_inf(d, q0), 1e-300);
    for (size_t k = 0; k < ni; ++k) {
      e->x[k] -= e->dx[k];
      dz = fmax(dz, fabs(e->dx[k]));
    }
    eta_prev = eta;
    eta = dz / zmax;
    if (eta > 4.0 * EPS && eta <= 1e-10 && eta >= eta_prev) eta = 0.0; /* stagnated */
  }
}

static gm_status with_engine(const gm_method *method, const gm_problem *problem, double h,
                             const double *q0, const double *q1, double *p0, double *p1,
                             double *value, gm_error *err) {
  vi_rule rule;
  size_t degree;
  if (gm_vi_rule_of(method, &rule, &degree) != GM_OK)
    return gm_error_set(err, GM_EINVAL, "'%s' is no variational method",
                        method ? method->name : "(null)");
  if (problem == NULL || q0 == NULL || q1 == NULL || !(h != 0.0) || !isfinite(h))
    return gm_error_set(err, GM_EINVAL, "need a problem, q0, q1 and a finite h != 0");
  gm_status st = gm_problem_validate(problem, err);
  if (st != GM_OK) return st;
  vi_engine e;
  double *zero = calloc(problem->dim, sizeof(double));
  if (zero == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  const double alpha = (rule == VI_RULE_ALPHA && method->c != NULL) ? method->c[0] : 0.5;
  st = gm_vi_engine_init(&e, problem, rule, degree, alpha, 0, NULL, NULL);
  if (st == GM_OK) st = solve_inner(&e, q0, q1, h, zero);
  const size_t d = problem->dim;
  if (st == GM_OK) {
    for (size_t k = 0; k < d; ++k) {
      if (p0 != NULL) p0[k] = -e.dS[k];
      if (p1 != NULL) p1[k] = e.dS[e.s * d + k];
    }
    if (value != NULL) {
      double sum = 0.0, l;
      for (size_t i = 0; i < e.r && st == GM_OK; ++i)
        if ((st = gm_vi_lagrangian_at(&e, i, &l)) == GM_OK) sum += e.b[i] * l;
      *value = h * sum;
    }
  }
  if (st != GM_OK) gm_error_set(err, st, "%s: %s", method->name, e.errmsg);
  gm_vi_engine_release(&e);
  free(zero);
  return st;
}

gm_status gm_variational_legendre(const gm_method *method, const gm_problem *problem, double h,
                                  const double *q0, const double *q1, double *p0, double *p1,
                                  gm_error *err) {
  return with_engine(method, problem, h, q0, q1, p0, p1, NULL, err);
}

gm_status gm_variational_discrete_lagrangian(const gm_method *method, const gm_problem *problem,
                                             double h, const double *q0, const double *q1,
                                             double *value, gm_error *err) {
  if (value == NULL) return gm_error_set(err, GM_EINVAL, "value is NULL");
  return with_engine(method, problem, h, q0, q1, NULL, NULL, value, err);
}

/* ---- user discrete Lagrangians --------------------------------------------------------------- */

gm_status gm_discrete_legendre_minus(const gm_discrete_lagrangian *ld, double h, const double *q0,
                                     const double *q1, double *p0) {
  if (ld == NULL || ld->d1 == NULL || q0 == NULL || q1 == NULL || p0 == NULL) return GM_EINVAL;
  if (ld->d1(ld->ctx, h, q0, q1, p0) != 0) return GM_ECALLBACK;
  for (size_t k = 0; k < ld->dim; ++k) p0[k] = -p0[k];
  return GM_OK;
}

gm_status gm_discrete_legendre_plus(const gm_discrete_lagrangian *ld, double h, const double *q0,
                                    const double *q1, double *p1) {
  if (ld == NULL || ld->d2 == NULL || q0 == NULL || q1 == NULL || p1 == NULL) return GM_EINVAL;
  return ld->d2(ld->ctx, h, q0, q1, p1) != 0 ? GM_ECALLBACK : GM_OK;
}

struct gm_dl_solver {
  gm_discrete_lagrangian ld;
  size_t d;
  double *q1, *res, *jac, *fp, *fm, *dq_prev, *p1;
  int *piv;
  int have_prev;
  size_t iterations;
  char errmsg[GM_ERRMSG_SIZE];
};

gm_status gm_dl_solver_create(const gm_discrete_lagrangian *ld, gm_dl_solver **out,
                              gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (ld == NULL || ld->dim == 0 || ld->d1 == NULL || ld->d2 == NULL)
    return gm_error_set(err, GM_EINVAL,
                        "a discrete Lagrangian needs dim > 0 and both slot derivatives d1, d2");
  gm_dl_solver *s = calloc(1, sizeof *s);
  if (s == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  const size_t d = ld->dim;
  s->ld = *ld;
  s->d = d;
  s->q1 = calloc(d, sizeof(double));
  s->res = calloc(d, sizeof(double));
  s->jac = calloc(d * d, sizeof(double));
  s->fp = calloc(d, sizeof(double));
  s->fm = calloc(d, sizeof(double));
  s->dq_prev = calloc(d, sizeof(double));
  s->p1 = calloc(d, sizeof(double));
  s->piv = calloc(d, sizeof(int));
  if (!s->q1 || !s->res || !s->jac || !s->fp || !s->fm || !s->dq_prev || !s->p1 || !s->piv) {
    gm_dl_solver_free(s);
    return gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  *out = s;
  return GM_OK;
}

void gm_dl_solver_free(gm_dl_solver *s) {
  if (s == NULL) return;
  free(s->q1);
  free(s->res);
  free(s->jac);
  free(s->fp);
  free(s->fm);
  free(s->dq_prev);
  free(s->p1);
  free(s->piv);
  free(s);
}

/* ∂(D₁L_d)/∂q1 by the user's callback or central differences. */
static int d1_jacobian(gm_dl_solver *s, double h, const double *q) {
  const gm_discrete_lagrangian *ld = &s->ld;
  const size_t d = s->d;
  if (ld->d1_jacobian != NULL) return ld->d1_jacobian(ld->ctx, h, q, s->q1, s->jac);
  for (size_t j = 0; j < d; ++j) {
    const double x0 = s->q1[j], step = CBRT_EPS * fmax(fabs(x0), 1.0);
    s->q1[j] = x0 + step;
    const double hp = s->q1[j] - x0;
    int rc = ld->d1(ld->ctx, h, q, s->q1, s->fp);
    s->q1[j] = x0 - step;
    const double hm = x0 - s->q1[j];
    if (rc == 0) rc = ld->d1(ld->ctx, h, q, s->q1, s->fm);
    s->q1[j] = x0;
    if (rc != 0) return rc;
    for (size_t i = 0; i < d; ++i) s->jac[i * d + j] = (s->fp[i] - s->fm[i]) / (hp + hm);
  }
  return 0;
}

gm_status gm_dl_solver_step(gm_dl_solver *s, double h, double *q, double *p) {
  if (s == NULL || q == NULL || p == NULL) return GM_EINVAL;
  if (!(h != 0.0) || !isfinite(h))
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "step must be finite and non-zero");
  const gm_discrete_lagrangian *ld = &s->ld;
  const size_t d = s->d;
  for (size_t k = 0; k < d; ++k) s->q1[k] = q[k] + (s->have_prev ? s->dq_prev[k] : 0.0);
  double eta = INFINITY, eta_prev;
  int done = 0;
  for (int iter = 0; !done; ++iter) {
    if (iter >= 50)
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOCONV,
                     "p = -D1Ld(q, q1) did not converge in 50 Newton iterations");
    /* R = p + D₁L_d(q, q1) */
    if (ld->d1(ld->ctx, h, q, s->q1, s->res) != 0 || d1_jacobian(s, h, q) != 0)
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_ECALLBACK, "d1 or d1_jacobian failed");
    for (size_t k = 0; k < d; ++k) s->res[k] += p[k];
    if (gm_lu_factor(d, s->jac, s->piv) != GM_OK)
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_ESINGULAR,
                     "D12Ld is singular: the discrete Lagrangian is degenerate here");
    gm_lu_solve(d, s->jac, s->piv, s->res);
    double dz = 0.0, scale = 1e-300;
    for (size_t k = 0; k < d; ++k) {
      s->q1[k] -= s->res[k];
      dz = fmax(dz, fabs(s->res[k]));
      scale = fmax(scale, fmax(fabs(s->q1[k]), fabs(s->q1[k] - q[k])));
    }
    s->iterations++;
    eta_prev = eta;
    eta = dz / scale;
    if (!isfinite(eta))
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_EDOMAIN, "Newton produced %g", eta);
    done = eta <= 4.0 * EPS || (eta <= 1e-10 && eta >= eta_prev);
  }
  if (ld->d2(ld->ctx, h, q, s->q1, s->p1) != 0)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_ECALLBACK, "d2 failed");
  for (size_t k = 0; k < d; ++k) {
    s->dq_prev[k] = s->q1[k] - q[k];
    q[k] = s->q1[k];
    p[k] = s->p1[k];
  }
  s->have_prev = 1;
  s->errmsg[0] = '\0';
  return GM_OK;
}

size_t gm_dl_solver_newton_iterations(const gm_dl_solver *s) { return s ? s->iterations : 0; }
const char *gm_dl_solver_errmsg(const gm_dl_solver *s) { return s ? s->errmsg : ""; }

/* ---- continuous Legendre transform, Noether momenta, constraints --------------------------- */

gm_status gm_lagrangian_momentum(const gm_problem *pb, const double *q, const double *v,
                                 double *p) {
  if (pb == NULL || q == NULL || v == NULL || p == NULL) return GM_EINVAL;
  const size_t d = pb->dim;
  if (pb->kind == GM_PROBLEM_LAGRANGIAN)
    return pb->dl_dv(pb->ctx, q, v, p) != 0 ? GM_ECALLBACK : GM_OK;
  if (pb->kind != GM_PROBLEM_SEPARABLE || !pb->kinetic_is_quadratic) return GM_EUNSUPPORTED;
  /* M⁻¹ from ∇T(e_j), then solve M⁻¹ p = v */
  double *minv = calloc(d * d + 2 * d, sizeof(double));
  int *piv = calloc(d, sizeof(int));
  gm_status st = (minv && piv) ? GM_OK : GM_ENOMEM;
  double *e = minv + d * d, *col = e + d;
  for (size_t j = 0; j < d && st == GM_OK; ++j) {
    for (size_t k = 0; k < d; ++k) e[k] = k == j ? 1.0 : 0.0;
    if (pb->kinetic_gradient(pb->ctx, e, col) != 0) st = GM_ECALLBACK;
    for (size_t k = 0; k < d; ++k) minv[k * d + j] = col[k];
  }
  if (st == GM_OK) {
    memcpy(p, v, d * sizeof *p);
    st = gm_lu_factor(d, minv, piv);
    if (st == GM_OK) st = gm_lu_solve(d, minv, piv, p);
  }
  free(minv);
  free(piv);
  return st;
}

gm_status gm_lagrangian_velocity(const gm_problem *pb, const double *q, const double *p,
                                 double *v) {
  if (pb == NULL || q == NULL || p == NULL || v == NULL) return GM_EINVAL;
  const size_t d = pb->dim;
  if (pb->kind == GM_PROBLEM_SEPARABLE)
    return pb->kinetic_gradient(pb->ctx, p, v) != 0 ? GM_ECALLBACK : GM_OK;
  if (pb->kind != GM_PROBLEM_LAGRANGIAN) return GM_EUNSUPPORTED;
  double *buf = calloc(4 * d + d * d + 4 * d * d, sizeof(double));
  int *piv = calloc(d, sizeof(int));
  if (buf == NULL || piv == NULL) {
    free(buf);
    free(piv);
    return GM_ENOMEM;
  }
  double *r = buf, *gp = r + d, *gmv = gp + d, *w = gmv + d + d, *full = w + d * d;
  memcpy(v, p, d * sizeof *v);
  gm_status st = GM_ENOCONV;
  for (int iter = 0; iter < 50; ++iter) {
    if (pb->dl_dv(pb->ctx, q, v, r) != 0) {
      st = GM_ECALLBACK;
      break;
    }
    for (size_t i = 0; i < d; ++i) r[i] -= p[i];
    if (pb->lagrangian_hessian != NULL) {
      if (pb->lagrangian_hessian(pb->ctx, q, v, full) != 0) {
        st = GM_ECALLBACK;
        break;
      }
      for (size_t i = 0; i < d; ++i)
        for (size_t j = 0; j < d; ++j) w[i * d + j] = full[(d + i) * 2 * d + d + j];
    } else {
      for (size_t j = 0; j < d; ++j) {
        const double vj = v[j], hstep = CBRT_EPS * fmax(1.0, fabs(vj));
        v[j] = vj + hstep;
        int rc = pb->dl_dv(pb->ctx, q, v, gp);
        v[j] = vj - hstep;
        if (rc == 0) rc = pb->dl_dv(pb->ctx, q, v, gmv);
        v[j] = vj;
        if (rc != 0) {
          free(buf);
          free(piv);
          return GM_ECALLBACK;
        }
        for (size_t i = 0; i < d; ++i) w[i * d + j] = (gp[i] - gmv[i]) / (2.0 * hstep);
      }
    }
    if (gm_lu_factor(d, w, piv) != GM_OK || gm_lu_solve(d, w, piv, r) != GM_OK) {
      st = GM_ESINGULAR;
      break;
    }
    double step = 0.0, size = 1e-300;
    for (size_t i = 0; i < d; ++i) {
      v[i] -= r[i];
      step = fmax(step, fabs(r[i]));
      size = fmax(size, fabs(v[i]));
    }
    if (step <= 4.0 * EPS * size) {
      st = GM_OK;
      break;
    }
  }
  free(buf);
  free(piv);
  return st;
}

double gm_noether_momentum(const gm_problem *pb, size_t k, const double *y) {
  if (pb == NULL || y == NULL || k >= pb->n_symmetries || pb->symmetries == NULL) return NAN;
  const size_t d = pb->dim;
  double *xi = calloc(d, sizeof(double));
  if (xi == NULL) return NAN;
  double j = NAN;
  if (pb->symmetries[k].generator(pb->ctx, y, xi) == 0) {
    j = 0.0;
    for (size_t i = 0; i < d; ++i) j += y[d + i] * xi[i];
  }
  free(xi);
  return j;
}

double gm_constraint_residual(const gm_problem *pb, const double *y) {
  if (pb == NULL || y == NULL) return NAN;
  if (pb->kind != GM_PROBLEM_LAGRANGIAN || pb->n_constraints == 0) return 0.0;
  double *g = calloc(pb->n_constraints, sizeof(double));
  if (g == NULL) return NAN;
  double r = NAN;
  if (pb->constraint(pb->ctx, y, g) == 0) r = gm_norm_inf(pb->n_constraints, g);
  free(g);
  return r;
}
