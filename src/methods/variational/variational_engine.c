/* The Galerkin discrete Lagrangian and its position–momentum step (seed 001 §2.4, §2.8, §5.2;
 * Marsden & West, Acta Numerica 10 (2001) 357, §2.6 and §3.5).
 *
 * On a step of size h from (q_k, p_k) the path is the polynomial of degree s through the control
 * points q^0 = q_k, q^1, ..., q^s = q_{k+1} at the times d_ν h, q(τh) = Σ_ν φ_ν(τ) q^ν, and
 *   S(q^0, ..., q^s) = h Σ_i b_i L(Q_i, V_i),  Q_i = q(c_i h),  V_i = q'(c_i h)
 * with an r-point quadrature (c_i, b_i). The discrete Lagrangian is L_d(q_k, q_{k+1}) = ext S over
 * the inner points (seed 001 §1B). With dS_μ = ∂S/∂q^μ + f^μ, where the discrete force
 * f^μ = h Σ_i b_i φ_μ(c_i) F(t + c_i h, Q_i, V_i) is the quadrature of the virtual work ∫F·δq
 * (discrete Lagrange–d'Alembert, seed 001 §2.8.2; Marsden & West §3.2), one step solves
 *   p_k + dS_0 + G(q^0)ᵀλ^0 = 0,          (discrete Legendre transform p_k = −D₁L_d − F_d⁻)
 *   dS_ν + G(q^ν)ᵀλ^ν = 0,  ν = 1..s−1,     (the inner points: stationarity of S)
 *   g(q^ν) = 0,             ν = 1..s,       (holonomic constraints, inner points included)
 * for q^1..q^s and the multipliers λ^0..λ^{s−1} (seed 001 §2.8.1: constrained DEL with the
 * inner stage points also carrying multipliers), then
 *   p_{k+1} = dS_s + G(q^s)ᵀμ = p_k + h Σ_i b_i (L_q + F)(Q_i, V_i) + Σ_{ν<s} G(q^ν)ᵀλ^ν + G(q^s)ᵀμ
 * (Σ_ν φ_ν = 1 and Σ_ν φ'_ν = 0 give the second form), with μ chosen so that the velocity of
 * p_{k+1} is tangent to the constraint, G(q_{k+1}) v = 0 (the RATTLE-type projection of
 * Marsden & West §3.5.2: the two multipliers μ_k + λ_k make the constrained DEL
 * D₂L_d + D₁L_d + G(q_k)ᵀΛ_k = 0). Unknowns are stored as increments z^ν = q^ν − q_k. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "methods/variational/variational_internal.h"

#define EPS 2.220446049250313e-16
#define CBRT_EPS 6.0554544523933395e-06
#define NEWTON_MAX_ITERATIONS 50
#define FIXED_POINT_MAX_ITERATIONS 200

static double *dalloc(size_t n) { return calloc(n ? n : 1, sizeof(double)); }

gm_status gm_vi_engine_init(vi_engine *e, const gm_problem *pb, vi_rule rule, size_t degree,
                            double alpha, size_t extra_unknowns, gm_stats *stats, char *errmsg) {
  memset(e, 0, sizeof *e);
  e->pb = pb;
  e->stats = stats != NULL ? stats : &e->own_stats;
  e->errmsg = errmsg != NULL ? errmsg : e->own_errmsg;
  e->errmsg[0] = '\0';
  if (pb->kind == GM_PROBLEM_SEPARABLE) {
    if (!pb->kinetic_is_quadratic)
      return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_EUNSUPPORTED,
                     "variational integrators take a separable problem as the Lagrangian "
                     "L = v'Mv/2 - V(q): its kinetic energy must be quadratic, T = p'M^-1p/2 "
                     "(kinetic_is_quadratic)");
    e->separable = e->quadratic = 1;
  } else if (pb->kind == GM_PROBLEM_LAGRANGIAN) {
    e->quadratic = pb->kinetic_is_quadratic != 0;
    e->m = pb->n_constraints;
    e->forced = pb->force != NULL;
  } else {
    return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_EUNSUPPORTED,
                   "variational integrators need a Lagrangian or a separable problem");
  }
  const size_t d = pb->dim, s = degree, m = e->m;
  if (s < 1 || s > 32)
    return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_EINVAL, "degree %zu out of range 1..32", s);
  e->d = d;
  e->s = s;
  e->r = rule == VI_RULE_LOBATTO ? s + 1 : (rule == VI_RULE_ALPHA ? 1 : s);
  const size_t r = e->r, sp = s + 1, nw = 2 * d + m;
  e->ctimes = dalloc(sp);
  e->c = dalloc(r);
  e->b = dalloc(r);
  e->phi = dalloc(r * sp);
  e->dphi = dalloc(r * sp);
  e->extrap = dalloc(s * s);
  e->ginv = dalloc(s * s);
  e->mass = dalloc(d * d);
  e->mass_inv = dalloc(d * d);
  e->Q = dalloc(r * d);
  e->V = dalloc(r * d);
  e->Lq = dalloc(r * d);
  e->Lv = dalloc(r * d);
  e->F = dalloc(r * d);
  e->hess = dalloc(r * 4 * d * d);
  e->dS = dalloc(sp * d);
  e->gjac = dalloc(sp * m * d);
  e->gval = dalloc(sp * m);
  e->w1 = dalloc(nw);
  e->w2 = dalloc(nw);
  e->w3 = dalloc(nw);
  e->w4 = dalloc(nw);
  e->wdd = dalloc(nw * nw);
  e->wpiv = calloc(nw, sizeof(int));
  e->n_x = s * d + s * m + extra_unknowns;
  e->x = dalloc(e->n_x);
  e->dx = dalloc(e->n_x);
  e->res = dalloc(e->n_x);
  e->x_start = dalloc(e->n_x);
  e->jac = dalloc(e->n_x * e->n_x);
  e->piv = calloc(e->n_x, sizeof(int));
  double *gm = dalloc(s * s);
  if (!e->ctimes || !e->c || !e->b || !e->phi || !e->dphi || !e->extrap || !e->ginv ||
      !e->mass || !e->mass_inv || !e->Q || !e->V || !e->Lq || !e->Lv || !e->F || !e->hess ||
      !e->dS || !e->gjac || !e->gval || !e->w1 || !e->w2 || !e->w3 || !e->w4 || !e->wdd ||
      !e->wpiv || !e->x || !e->dx || !e->res || !e->x_start || !e->jac || !e->piv || !gm) {
    free(gm);
    return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ENOMEM, "out of memory");
  }
  /* control times: Gauss–Lobatto nodes (well-conditioned interpolation for any s) */
  double wts[64];
  gm_status st = GM_OK;
  if (sp == 2) {
    e->ctimes[0] = 0.0;
    e->ctimes[1] = 1.0;
  } else if ((st = gm_gauss_lobatto(sp, e->ctimes, wts)) == GM_OK) {
    gm_quadrature_map(sp, 0.0, 1.0, e->ctimes, wts);
  }
  if (st == GM_OK) {
    switch (rule) {
      case VI_RULE_GAUSS:
        if ((st = gm_gauss_legendre(r, e->c, e->b)) == GM_OK) gm_quadrature_map(r, 0, 1, e->c, e->b);
        break;
      case VI_RULE_LOBATTO:
        memcpy(e->c, e->ctimes, sp * sizeof *e->c);
        if (sp == 2) {
          e->b[0] = e->b[1] = 0.5;
        } else if ((st = gm_gauss_lobatto(r, e->c, e->b)) == GM_OK) {
          gm_quadrature_map(r, 0, 1, e->c, e->b);
          memcpy(e->c, e->ctimes, sp * sizeof *e->c); /* the very same nodes */
        }
        break;
      case VI_RULE_ALPHA:
        if (!(alpha >= 0.0 && alpha <= 1.0)) {
          free(gm);
          return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_EINVAL,
                         "alpha must be in [0, 1], got %g", alpha);
        }
        e->c[0] = alpha;
        e->b[0] = 1.0;
        break;
    }
  }
  for (size_t i = 0; i < r && st == GM_OK; ++i) {
    st = gm_lagrange_basis(sp, e->ctimes, e->c[i], e->phi + i * sp);
    if (st == GM_OK) st = gm_lagrange_basis_derivative(sp, e->ctimes, e->c[i], e->dphi + i * sp);
  }
  /* extrapolation of the previous step's polynomial to the new control times */
  double vals[64];
  for (size_t nu = 1; nu <= s && st == GM_OK; ++nu) {
    st = gm_lagrange_basis(sp, e->ctimes, 1.0 + e->ctimes[nu], vals);
    for (size_t mu = 1; mu <= s; ++mu)
      e->extrap[(nu - 1) * s + mu - 1] = vals[mu] - (mu == s ? 1.0 : 0.0);
  }
  /* G_{μν} = Σ_i b_i φ'_μ(c_i) φ'_ν(c_i), μ = 0..s−1, ν = 1..s: the leading (1/h) G ⊗ M part of
   * the Jacobian; invertible because the full stiffness matrix has rank s with kernel 1 */
  for (size_t mu = 0; mu < s; ++mu)
    for (size_t nu = 1; nu <= s; ++nu) {
      double g = 0.0;
      for (size_t i = 0; i < r; ++i) g += e->b[i] * e->dphi[i * sp + mu] * e->dphi[i * sp + nu];
      gm[mu * s + nu - 1] = g;
    }
  if (st == GM_OK) st = gm_lu_factor(s, gm, e->piv);
  for (size_t j = 0; j < s && st == GM_OK; ++j) {
    for (size_t k = 0; k < s; ++k) vals[k] = k == j ? 1.0 : 0.0;
    st = gm_lu_solve(s, gm, e->piv, vals);
    for (size_t k = 0; k < s; ++k) e->ginv[k * s + j] = vals[k]; /* (G⁻¹)_{ν−1, μ} */
  }
  free(gm);
  if (st != GM_OK)
    return gm_fail(e->errmsg, GM_ERRMSG_SIZE, st, "cannot build the Galerkin rule of degree %zu",
                   s);
  if (e->separable) {
    /* ∇T(p) = M⁻¹p is linear: its columns are ∇T(e_j) */
    for (size_t j = 0; j < d; ++j) {
      for (size_t k = 0; k < d; ++k) e->w1[k] = k == j ? 1.0 : 0.0;
      if (pb->kinetic_gradient(pb->ctx, e->w1, e->w2) != 0)
        return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ECALLBACK, "kinetic_gradient failed");
      for (size_t k = 0; k < d; ++k) e->mass_inv[k * d + j] = e->w2[k];
    }
    memcpy(e->wdd, e->mass_inv, d * d * sizeof(double));
    if (gm_lu_factor(d, e->wdd, e->wpiv) != GM_OK)
      return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ESINGULAR,
                     "the kinetic energy is degenerate: its Hessian M^-1 is singular");
    for (size_t j = 0; j < d; ++j) {
      for (size_t k = 0; k < d; ++k) e->w1[k] = k == j ? 1.0 : 0.0;
      gm_lu_solve(d, e->wdd, e->wpiv, e->w1);
      for (size_t k = 0; k < d; ++k) e->mass[k * d + j] = e->w1[k];
    }
    e->diagonal = 1;
    for (size_t i = 0; i < d; ++i)
      for (size_t j = 0; j < d; ++j)
        if (i != j && (e->mass_inv[i * d + j] != 0.0)) e->diagonal = 0;
    if (e->diagonal)
      for (size_t i = 0; i < d; ++i) e->mass[i * d + i] = 1.0 / e->mass_inv[i * d + i];
    e->mass_ready = 1;
  }
  return GM_OK;
}

void gm_vi_engine_release(vi_engine *e) {
  if (e == NULL) return;
  double *arrays[] = {e->ctimes, e->c,  e->b,   e->phi,  e->dphi, e->extrap, e->ginv,
                      e->mass,   e->mass_inv, e->Q, e->V, e->Lq, e->Lv, e->F, e->hess, e->dS,
                      e->gjac,   e->gval, e->w1,  e->w2,   e->w3,   e->w4, e->wdd, e->x,
                      e->dx,     e->res,  e->jac, e->x_start};
  for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; ++k) free(arrays[k]);
  free(e->wpiv);
  free(e->piv);
  memset(e, 0, sizeof *e);
}

static gm_status callback_failed(vi_engine *e, const char *name, int rc) {
  return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ECALLBACK, "callback %s returned %d at t = %.17g",
                 name, rc, e->t);
}

/* M of a quadratic Lagrangian problem: ∂L/∂v is linear in v, M e_j = L_v(q, e_j) − L_v(q, 0). */
gm_status gm_vi_prepare_mass(vi_engine *e, const double *q) {
  if (e->mass_ready) return GM_OK;
  const gm_problem *pb = e->pb;
  const size_t d = e->d;
  memset(e->w1, 0, d * sizeof(double));
  int rc = pb->dl_dv(pb->ctx, q, e->w1, e->w3);
  for (size_t j = 0; j < d && rc == 0; ++j) {
    e->w1[j] = 1.0;
    rc = pb->dl_dv(pb->ctx, q, e->w1, e->w2);
    e->w1[j] = 0.0;
    for (size_t k = 0; k < d; ++k) e->mass[k * d + j] = e->w2[k] - e->w3[k];
  }
  if (rc != 0) return callback_failed(e, "dl_dv", rc);
  memcpy(e->wdd, e->mass, d * d * sizeof(double));
  if (gm_lu_factor(d, e->wdd, e->wpiv) != GM_OK)
    return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ESINGULAR,
                   "the Lagrangian is degenerate: d2L/dv2 is singular");
  for (size_t j = 0; j < d; ++j) {
    for (size_t k = 0; k < d; ++k) e->w1[k] = k == j ? 1.0 : 0.0;
    gm_lu_solve(d, e->wdd, e->wpiv, e->w1);
    for (size_t k = 0; k < d; ++k) e->mass_inv[k * d + j] = e->w1[k];
  }
  e->diagonal = 1;
  for (size_t i = 0; i < d; ++i)
    for (size_t j = 0; j < d; ++j)
      if (i != j && e->mass[i * d + j] != 0.0) e->diagonal = 0;
  if (e->diagonal)
    for (size_t i = 0; i < d; ++i) e->mass_inv[i * d + i] = 1.0 / e->mass[i * d + i];
  e->mass_ready = 1;
  return GM_OK;
}

/* out = M x (or M⁻¹ x) */
static void mass_apply(const vi_engine *e, const double *mat, const double *x, double *out) {
  const size_t d = e->d;
  if (e->diagonal) {
    for (size_t i = 0; i < d; ++i) out[i] = mat[i * d + i] * x[i];
    return;
  }
  for (size_t i = 0; i < d; ++i) {
    double sum = 0.0;
    for (size_t j = 0; j < d; ++j) sum += mat[i * d + j] * x[j];
    out[i] = sum;
  }
}

/* L_q and L_v at (Q, V). */
static gm_status eval_derivatives(vi_engine *e, const double *Q, const double *V, double *lq,
                                  double *lv) {
  const gm_problem *pb = e->pb;
  int rc;
  if (e->separable) {
    if ((rc = pb->potential_gradient(pb->ctx, Q, lq)) != 0)
      return callback_failed(e, "potential_gradient", rc);
    for (size_t k = 0; k < e->d; ++k) lq[k] = -lq[k];
    mass_apply(e, e->mass, V, lv);
    return GM_OK;
  }
  if ((rc = pb->dl_dq(pb->ctx, Q, V, lq)) != 0) return callback_failed(e, "dl_dq", rc);
  if ((rc = pb->dl_dv(pb->ctx, Q, V, lv)) != 0) return callback_failed(e, "dl_dv", rc);
  return GM_OK;
}

/* The 2d × 2d Hessian of L (plus the force Jacobians in the L_q rows) at point i. */
static gm_status eval_hessian(vi_engine *e, size_t i) {
  const gm_problem *pb = e->pb;
  const size_t d = e->d, n2 = 2 * d;
  double *H = e->hess + i * n2 * n2, *Q = e->Q + i * d, *V = e->V + i * d;
  double *gp = e->w1, *gm = e->w2, *vp = e->w3, *vm = e->w4;
  int rc = 0, fd = 0;
  memset(H, 0, n2 * n2 * sizeof *H);
  if (pb->lagrangian_hessian != NULL && !e->separable) {
    if ((rc = pb->lagrangian_hessian(pb->ctx, Q, V, H)) != 0)
      return callback_failed(e, "lagrangian_hessian", rc);
  } else if (e->separable && pb->potential_hessian != NULL) {
    if ((rc = pb->potential_hessian(pb->ctx, Q, e->wdd)) != 0)
      return callback_failed(e, "potential_hessian", rc);
    for (size_t a = 0; a < d; ++a)
      for (size_t c = 0; c < d; ++c) H[a * n2 + c] = -e->wdd[a * d + c];
  } else {
    /* central differences of (L_q, L_v) over (q, v); only q for a quadratic L */
    fd = 1;
    const size_t ncol = e->quadratic ? d : n2;
    for (size_t j = 0; j < ncol; ++j) {
      double *x = j < d ? Q + j : V + (j - d);
      const double x0 = *x, step = CBRT_EPS * fmax(fabs(x0), 1.0);
      *x = x0 + step;
      const double hp = *x - x0;
      gm_status st = eval_derivatives(e, Q, V, gp, vp);
      *x = x0 - step;
      const double hm = x0 - *x;
      if (st == GM_OK) st = eval_derivatives(e, Q, V, gm, vm);
      *x = x0;
      if (st != GM_OK) return st;
      for (size_t a = 0; a < d; ++a) {
        H[a * n2 + j] = (gp[a] - gm[a]) / (hp + hm);
        H[(d + a) * n2 + j] = (vp[a] - vm[a]) / (hp + hm);
      }
    }
  }
  if (e->quadratic) {
    if (!e->separable && pb->lagrangian_hessian == NULL) { /* L_vq = 0 for constant M */
      for (size_t a = 0; a < d; ++a)
        for (size_t c = 0; c < d; ++c) H[(d + a) * n2 + c] = 0.0;
    }
    for (size_t a = 0; a < d; ++a)
      for (size_t c = 0; c < d; ++c) {
        H[a * n2 + d + c] = 0.0;
        H[(d + a) * n2 + c] = 0.0;
        H[(d + a) * n2 + d + c] = e->mass[a * d + c];
      }
  }
  if (e->forced) { /* ∂F/∂q, ∂F/∂v by central differences, added to the L_q rows */
    fd = 1;
    const double tf = e->t + e->c[i] * e->h;
    for (size_t j = 0; j < n2; ++j) {
      double *x = j < d ? Q + j : V + (j - d);
      const double x0 = *x, step = CBRT_EPS * fmax(fabs(x0), 1.0);
      *x = x0 + step;
      const double hp = *x - x0;
      rc = pb->force(pb->ctx, tf, Q, V, gp);
      *x = x0 - step;
      const double hm = x0 - *x;
      if (rc == 0) rc = pb->force(pb->ctx, tf, Q, V, gm);
      *x = x0;
      if (rc != 0) return callback_failed(e, "force", rc);
      for (size_t a = 0; a < d; ++a) H[a * n2 + j] += (gp[a] - gm[a]) / (hp + hm);
    }
  }
  e->stats->jacobian_evals++;
  if (fd) e->stats->fd_jacobians++;
  return GM_OK;
}

gm_status gm_vi_evaluate(vi_engine *e, const double *z, int with_hessian) {
  const gm_problem *pb = e->pb;
  const size_t d = e->d, s = e->s, r = e->r, sp = s + 1, m = e->m;
  const double h = e->h;
  double lscale = gm_norm_inf(d, e->p);
  for (size_t i = 0; i < r; ++i) {
    double *Q = e->Q + i * d, *V = e->V + i * d;
    const double *ph = e->phi + i * sp, *dp = e->dphi + i * sp;
    for (size_t k = 0; k < d; ++k) {
      double qs = 0.0, vs = 0.0;
      for (size_t nu = 1; nu <= s; ++nu) {
        qs += ph[nu] * z[(nu - 1) * d + k];
        vs += dp[nu] * z[(nu - 1) * d + k];
      }
      Q[k] = e->q[k] + qs;
      V[k] = vs / h;
    }
    e->stats->force_evals++;
    gm_status st = eval_derivatives(e, Q, V, e->Lq + i * d, e->Lv + i * d);
    if (st != GM_OK) return st;
    if (e->forced) {
      int rc = pb->force(pb->ctx, e->t + e->c[i] * h, Q, V, e->F + i * d);
      if (rc != 0) return callback_failed(e, "force", rc);
    }
    lscale = fmax(lscale, gm_norm_inf(d, e->Lv + i * d));
    if (with_hessian && (st = eval_hessian(e, i)) != GM_OK) return st;
  }
  e->lscale = lscale;
  for (size_t mu = 0; mu <= s; ++mu)
    for (size_t k = 0; k < d; ++k) {
      double sq = 0.0, sv = 0.0;
      for (size_t i = 0; i < r; ++i) {
        double f = e->Lq[i * d + k] + (e->forced ? e->F[i * d + k] : 0.0);
        sq += e->b[i] * e->phi[i * sp + mu] * f;
        sv += e->b[i] * e->dphi[i * sp + mu] * e->Lv[i * d + k];
      }
      e->dS[mu * d + k] = h * sq + sv;
    }
  for (size_t mu = 0; mu <= s && m > 0; ++mu) {
    double *qmu = e->w1;
    for (size_t k = 0; k < d; ++k) qmu[k] = e->q[k] + (mu > 0 ? z[(mu - 1) * d + k] : 0.0);
    int rc = pb->constraint(pb->ctx, qmu, e->gval + mu * m);
    if (rc == 0) rc = pb->constraint_jacobian(pb->ctx, qmu, e->gjac + mu * m * d);
    if (rc != 0) return callback_failed(e, "constraint", rc);
  }
  return GM_OK;
}

void gm_vi_block(const vi_engine *e, size_t mu, size_t nu, double *out, size_t ld) {
  const size_t d = e->d, r = e->r, sp = e->s + 1, n2 = 2 * d;
  const double h = e->h;
  for (size_t a = 0; a < d; ++a)
    for (size_t c = 0; c < d; ++c) out[a * ld + c] = 0.0;
  for (size_t i = 0; i < r; ++i) {
    const double pm = e->phi[i * sp + mu], pn = e->phi[i * sp + nu];
    const double dm = e->dphi[i * sp + mu], dn = e->dphi[i * sp + nu], bi = e->b[i];
    const double wA = bi * h * pm * pn, wB = bi * pm * dn, wC = bi * dm * pn, wD = bi * dm * dn / h;
    const double *H = e->hess + i * n2 * n2;
    for (size_t a = 0; a < d; ++a)
      for (size_t c = 0; c < d; ++c)
        out[a * ld + c] += wA * H[a * n2 + c] + wB * H[a * n2 + d + c] +
                           wC * H[(d + a) * n2 + c] + wD * H[(d + a) * n2 + d + c];
  }
}

gm_status gm_vi_lagrangian_at(vi_engine *e, size_t i, double *value) {
  const gm_problem *pb = e->pb;
  const size_t d = e->d;
  const double *Q = e->Q + i * d, *V = e->V + i * d;
  if (e->separable) {
    mass_apply(e, e->mass, V, e->w1);
    double t = 0.0;
    for (size_t k = 0; k < d; ++k) t += V[k] * e->w1[k];
    *value = 0.5 * t - pb->potential(pb->ctx, Q);
  } else {
    *value = pb->lagrangian(pb->ctx, Q, V);
  }
  return isfinite(*value) ? GM_OK
                          : gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_EDOMAIN,
                                    "the Lagrangian is %g at a quadrature point", *value);
}

/* Residual of the step (see the top of the file) at the last evaluation, x = (z, λ). */
static void residual(vi_engine *e, const double *x, double *res) {
  const size_t d = e->d, s = e->s, m = e->m, sd = s * d;
  for (size_t mu = 0; mu < s; ++mu)
    for (size_t k = 0; k < d; ++k) {
      double v = e->dS[mu * d + k] + (mu == 0 ? e->p[k] : 0.0);
      for (size_t a = 0; a < m; ++a)
        v += e->gjac[(mu * m + a) * d + k] * x[sd + mu * m + a];
      res[mu * d + k] = v;
    }
  for (size_t nu = 1; nu <= s; ++nu)
    for (size_t a = 0; a < m; ++a) res[sd + (nu - 1) * m + a] = e->gval[nu * m + a];
}

/* ∂(G(q)ᵀλ)/∂q at q = q_k + z^μ by central differences of the constraint Jacobian, added to
 * the block at jac (row stride ld). */
static gm_status constraint_curvature(vi_engine *e, const double *z, size_t mu, const double *lam,
                                      double *jac, size_t ld) {
  const gm_problem *pb = e->pb;
  const size_t d = e->d, m = e->m;
  double *qv = e->w1, *gp = e->wdd, *gmj = e->wdd + m * d;
  for (size_t k = 0; k < d; ++k) qv[k] = e->q[k] + z[(mu - 1) * d + k];
  if (pb->constraint_hessian != NULL) { /* analytic Σ_a λ_a ∇²g_a(q), d × d in wdd */
    double *hess = e->wdd;
    int rc = pb->constraint_hessian(pb->ctx, qv, lam, hess);
    if (rc != 0) return callback_failed(e, "constraint_hessian", rc);
    for (size_t k = 0; k < d; ++k)
      for (size_t j = 0; j < d; ++j) jac[k * ld + j] += hess[k * d + j];
    return GM_OK;
  }
  for (size_t j = 0; j < d; ++j) {
    const double x0 = qv[j], step = CBRT_EPS * fmax(fabs(x0), 1.0);
    qv[j] = x0 + step;
    const double hp = qv[j] - x0;
    int rc = pb->constraint_jacobian(pb->ctx, qv, gp);
    qv[j] = x0 - step;
    const double hm = x0 - qv[j];
    if (rc == 0) rc = pb->constraint_jacobian(pb->ctx, qv, gmj);
    qv[j] = x0;
    if (rc != 0) return callback_failed(e, "constraint_jacobian", rc);
    for (size_t k = 0; k < d; ++k) {
      double sum = 0.0;
      for (size_t a = 0; a < m; ++a) sum += (gp[a * d + k] - gmj[a * d + k]) * lam[a];
      jac[k * ld + j] += sum / (hp + hm);
    }
  }
  e->stats->fd_jacobians++;
  return GM_OK;
}

static gm_status assemble_jacobian(vi_engine *e, const double *x, double *jac) {
  const size_t d = e->d, s = e->s, m = e->m, sd = s * d, n = sd + s * m;
  memset(jac, 0, n * n * sizeof *jac);
  for (size_t mu = 0; mu < s; ++mu)
    for (size_t nu = 1; nu <= s; ++nu) gm_vi_block(e, mu, nu, jac + mu * d * n + (nu - 1) * d, n);
  for (size_t mu = 0; mu < s && m > 0; ++mu) {
    for (size_t k = 0; k < d; ++k)
      for (size_t a = 0; a < m; ++a)
        jac[(mu * d + k) * n + sd + mu * m + a] = e->gjac[(mu * m + a) * d + k];
    if (mu > 0) {
      gm_status st = constraint_curvature(e, x, mu, x + sd + mu * m,
                                          jac + mu * d * n + (mu - 1) * d, n);
      if (st != GM_OK) return st;
    }
  }
  for (size_t nu = 1; nu <= s && m > 0; ++nu)
    for (size_t a = 0; a < m; ++a)
      for (size_t k = 0; k < d; ++k)
        jac[(sd + (nu - 1) * m + a) * n + (nu - 1) * d + k] = e->gjac[(nu * m + a) * d + k];
  return GM_OK;
}

gm_status gm_vi_solve(vi_engine *e, int newton, int simplified) {
  const size_t d = e->d, s = e->s, m = e->m, sd = s * d, n = sd + s * m;
  const double h = e->h;
  const size_t max_iter = newton ? NEWTON_MAX_ITERATIONS : FIXED_POINT_MAX_ITERATIONS;
  double eta = INFINITY, eta_prev = INFINITY;
  size_t growth = 0, iter = 0;
  int done = 0;
  const double gnorm = m > 0 ? fmax(gm_norm_inf(m * d, e->gjac), 1e-300) : 0.0;
  gm_status st = GM_OK;
  for (;; ++iter) {
    const int hess = newton && (!simplified || iter == 0);
    if ((st = gm_vi_evaluate(e, e->x, hess)) != GM_OK) break;
    if (done) break;
    if (iter >= max_iter) {
      st = gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ENOCONV,
                   "%s did not converge in %zu iterations (last scaled increment %.1e)",
                   newton ? "Newton's method" : "the kinetic-block iteration", max_iter, eta);
      break;
    }
    residual(e, e->x, e->res);
    if (newton) {
      if (hess) {
        if ((st = assemble_jacobian(e, e->x, e->jac)) != GM_OK) break;
        if (gm_lu_factor(n, e->jac, e->piv) != GM_OK) {
          st = gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ESINGULAR,
                       "the Jacobian of the discrete Euler-Lagrange equations is singular");
          break;
        }
      }
      memcpy(e->dx, e->res, n * sizeof *e->dx);
      gm_lu_solve(n, e->jac, e->piv, e->dx);
    } else {
      /* Δz^ν = h Σ_μ (G⁻¹)_{νμ} M⁻¹ R_μ */
      for (size_t mu = 0; mu < s; ++mu) mass_apply(e, e->mass_inv, e->res + mu * d, e->dx + mu * d);
      memcpy(e->res, e->dx, sd * sizeof *e->dx);
      for (size_t nu = 0; nu < s; ++nu)
        for (size_t k = 0; k < d; ++k) {
          double sum = 0.0;
          for (size_t mu = 0; mu < s; ++mu) sum += e->ginv[nu * s + mu] * e->res[mu * d + k];
          e->dx[nu * d + k] = h * sum;
        }
    }
    double dz = 0.0, zmax = gm_norm_inf(d, e->q), dl = 0.0;
    for (size_t k = 0; k < sd; ++k) {
      e->x[k] -= e->dx[k];
      dz = fmax(dz, fabs(e->dx[k]));
      zmax = fmax(zmax, fabs(e->x[k]));
    }
    for (size_t k = sd; k < n; ++k) {
      e->x[k] -= e->dx[k];
      dl = fmax(dl, fabs(e->dx[k]));
    }
    eta_prev = eta;
    eta = fmax(dz / fmax(zmax, 1e-300), m > 0 ? dl * gnorm / fmax(e->lscale, 1e-300) : 0.0);
    if (!isfinite(eta)) {
      st = gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_EDOMAIN, "the iteration produced %g", eta);
      break;
    }
    if (eta <= 4.0 * EPS || (eta <= 1e-10 && eta >= eta_prev)) done = 1;
    growth = eta > eta_prev ? growth + 1 : 0;
    if (!newton && growth >= 3 && eta > 1e-8) {
      st = gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ENOCONV,
                   "the kinetic-block iteration diverges (h = %g too large for it)", h);
      break;
    }
  }
  if (newton)
    e->stats->newton_iterations += iter;
  else
    e->stats->fixed_point_iterations += iter;
  return st;
}

gm_status gm_vi_momentum_increment(vi_engine *e, double *dp) {
  const gm_problem *pb = e->pb;
  const size_t d = e->d, s = e->s, m = e->m, r = e->r, sd = s * d;
  const double h = e->h;
  for (size_t k = 0; k < d; ++k) {
    double sum = 0.0;
    for (size_t i = 0; i < r; ++i)
      sum += e->b[i] * (e->Lq[i * d + k] + (e->forced ? e->F[i * d + k] : 0.0));
    double cons = 0.0;
    for (size_t mu = 0; mu < s; ++mu)
      for (size_t a = 0; a < m; ++a) cons += e->gjac[(mu * m + a) * d + k] * e->x[sd + mu * m + a];
    dp[k] = h * sum + cons;
  }
  if (m == 0) return GM_OK;
  /* tangency: find μ with G(q_{k+1}) v = 0, v the velocity of p̃ + G(q_{k+1})ᵀμ */
  const double *G = e->gjac + s * m * d;
  double *pt = e->w4, *mu = e->w3;
  for (size_t k = 0; k < d; ++k) pt[k] = e->p[k] + dp[k];
  const size_t nk = d + m;
  if (e->quadratic) {
    /* (G M⁻¹ Gᵀ) μ = −G M⁻¹ p̃ */
    double *a = e->wdd, *gm_row = e->w1, *tmp = e->w2;
    mass_apply(e, e->mass_inv, pt, tmp);
    for (size_t i = 0; i < m; ++i) {
      double sum = 0.0;
      for (size_t k = 0; k < d; ++k) sum += G[i * d + k] * tmp[k];
      mu[i] = -sum;
    }
    for (size_t j = 0; j < m; ++j) {
      mass_apply(e, e->mass_inv, G + j * d, gm_row);
      for (size_t i = 0; i < m; ++i) {
        double sum = 0.0;
        for (size_t k = 0; k < d; ++k) sum += G[i * d + k] * gm_row[k];
        a[i * m + j] = sum;
      }
    }
    if (gm_lu_factor(m, a, e->wpiv) != GM_OK || gm_lu_solve(m, a, e->wpiv, mu) != GM_OK)
      return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ESINGULAR,
                     "the constraints are not independent at t = %.17g (G M^-1 G' singular)",
                     e->t + h);
  } else {
    /* Newton on (v, μ): L_v(q1, v) − p̃ − Gᵀμ = 0, G v = 0 */
    double *q1 = e->x_start, *v = e->w2, *rhs = e->w1;
    for (size_t k = 0; k < d; ++k) q1[k] = e->q[k] + e->x[(s - 1) * d + k];
    memcpy(v, e->V + (r - 1) * d, d * sizeof *v);
    memset(mu, 0, m * sizeof *mu);
    int converged = 0;
    for (int iter = 0; iter < 30 && !converged; ++iter) {
      int rc = pb->dl_dv(pb->ctx, q1, v, rhs);
      if (rc != 0) return callback_failed(e, "dl_dv", rc);
      for (size_t k = 0; k < d; ++k) {
        double g = 0.0;
        for (size_t a = 0; a < m; ++a) g += G[a * d + k] * mu[a];
        rhs[k] -= pt[k] + g;
      }
      for (size_t a = 0; a < m; ++a) {
        double g = 0.0;
        for (size_t k = 0; k < d; ++k) g += G[a * d + k] * v[k];
        rhs[d + a] = g;
      }
      /* L_vv at (q1, v) from the Hessian routine at a scratch quadrature slot */
      memcpy(e->Q, q1, d * sizeof *q1);
      memcpy(e->V, v, d * sizeof *v);
      gm_status st = eval_hessian(e, 0);
      if (st != GM_OK) return st;
      const double *H = e->hess;
      double *a = e->wdd;
      memset(a, 0, nk * nk * sizeof *a);
      for (size_t i = 0; i < d; ++i) {
        for (size_t j = 0; j < d; ++j) a[i * nk + j] = H[(d + i) * 2 * d + d + j];
        for (size_t j = 0; j < m; ++j) {
          a[i * nk + d + j] = -G[j * d + i];
          a[(d + j) * nk + i] = G[j * d + i];
        }
      }
      if (gm_lu_factor(nk, a, e->wpiv) != GM_OK || gm_lu_solve(nk, a, e->wpiv, rhs) != GM_OK)
        return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ESINGULAR,
                       "the momentum projection is singular at t = %.17g", e->t + h);
      double step = 0.0;
      for (size_t k = 0; k < d; ++k) {
        v[k] -= rhs[k];
        step = fmax(step, fabs(rhs[k]) / fmax(gm_norm_inf(d, v), 1e-300));
      }
      for (size_t a2 = 0; a2 < m; ++a2) mu[a2] -= rhs[d + a2];
      converged = step <= 4.0 * EPS;
    }
  }
  for (size_t k = 0; k < d; ++k) {
    double g = 0.0;
    for (size_t a = 0; a < m; ++a) g += G[a * d + k] * mu[a];
    dp[k] += g;
  }
  return GM_OK;
}
