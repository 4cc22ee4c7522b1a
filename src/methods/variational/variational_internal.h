/* Private engine shared by the variational steppers (variational.c, variational_sem.c) and the
 * public discrete-mechanics functions (variational_api.c): a Galerkin discrete Lagrangian of
 * degree s with an r-point quadrature, evaluated on a Lagrangian problem or on a separable one
 * seen as L = ½vᵀMv − V(q). Never installed. */
#ifndef GM_METHODS_VARIATIONAL_INTERNAL_H
#define GM_METHODS_VARIATIONAL_INTERNAL_H

#include "methods/internal.h"

/* The quadratures of the variational rows, told apart by their tableau function. */
typedef enum vi_rule {
  VI_RULE_GAUSS = 1,  /* degree s, s Gauss points (order 2s) */
  VI_RULE_LOBATTO,    /* degree s, s + 1 Gauss–Lobatto points, control points at the nodes */
  VI_RULE_ALPHA       /* degree 1, one point at α (the generalized α-rule) */
} vi_rule;

typedef struct vi_engine {
  const gm_problem *pb;
  gm_stats *stats;           /* counters (the integrator's, or the engine's own) */
  gm_stats own_stats;
  char *errmsg;              /* GM_ERRMSG_SIZE bytes */
  char own_errmsg[GM_ERRMSG_SIZE];
  size_t d, m, s, r;         /* dimension, constraints, degree, quadrature points */
  double *ctimes;            /* s + 1 control times d_ν in [0, 1], d_0 = 0, d_s = 1 */
  double *c, *b;             /* r quadrature nodes in [0, 1] and weights */
  double *phi, *dphi;        /* r × (s+1): φ_ν(c_i) and φ'_ν(c_i) (unit interval) */
  double *extrap;            /* s × s: z⁰_ν = Σ_μ extrap[ν][μ] z_prev_μ (ν, μ = 1..s) */
  double *ginv;              /* s × s inverse of G_μν = Σ_i b_i φ'_μ φ'_ν (μ < s, ν ≥ 1) */
  /* the Lagrangian */
  int separable;             /* L = ½vᵀMv − V(q) from a separable problem */
  int quadratic;             /* L = ½vᵀMv − V(q) with constant M (separable, or declared) */
  int mass_ready, diagonal;
  double *mass, *mass_inv;   /* d × d */
  int forced;
  /* per-evaluation arrays */
  double *Q, *V, *Lq, *Lv, *F; /* r × d */
  double *hess;              /* r × (2d)²: [[L_qq + F_q, L_qv + F_v], [L_vq, L_vv]] */
  double *dS;                /* (s+1) × d: ∂S/∂q^μ + f^μ */
  double *gjac;              /* (s+1) × m × d: ∂g at the control points */
  double *gval;              /* (s+1) × m */
  double *w1, *w2, *w3, *w4; /* 2d + m each */
  double *wdd;               /* (2d + m)² */
  int *wpiv;                 /* 2d + m */
  /* the Newton system */
  size_t n_x;                /* s·d + s·m (+1 for an unknown time step) */
  double *x, *dx, *res, *jac, *x_start;
  int *piv;
  /* the step being solved */
  double t, h;
  const double *q, *p;
  double lscale;             /* momentum scale of the last evaluation */
} vi_engine;

/* Rule and degree of a variational row; GM_EINVAL for other rows. */
gm_status gm_vi_rule_of(const gm_method *m, vi_rule *rule, size_t *degree);

/* Allocate everything for the rule (alpha: the node). extra_unknowns: 1 for a free time step.
 * errmsg: GM_ERRMSG_SIZE bytes, or NULL for the engine's own. */
gm_status gm_vi_engine_init(vi_engine *e, const gm_problem *pb, vi_rule rule, size_t degree,
                            double alpha, size_t extra_unknowns, gm_stats *stats, char *errmsg);
void gm_vi_engine_release(vi_engine *e);
/* Mass matrix of a quadratic Lagrangian (needs a position for Lagrangian problems). */
gm_status gm_vi_prepare_mass(vi_engine *e, const double *q);
/* Positions and velocities at the quadrature points from the increments z (s × d, z^1..z^s
 * relative to e->q), the derivatives of L there (and the forces), and dS (all s + 1 rows). */
gm_status gm_vi_evaluate(vi_engine *e, const double *z, int with_hessian);
/* Block (μ, ν) of ∂dS_μ/∂z^ν (d × d) from the Hessians of the last evaluation, into out with
 * row stride ld. */
void gm_vi_block(const vi_engine *e, size_t mu, size_t nu, double *out, size_t ld);
/* L(Q_i, V_i) at quadrature point i of the last evaluation (for energies). */
gm_status gm_vi_lagrangian_at(vi_engine *e, size_t i, double *value);
/* Solve the position–momentum step p = −dS_0 (and the inner rows, and the constraints) for
 * x = (z, λ) by Newton's method (newton != 0) or by the kinetic-block iteration, from the guess
 * in e->x. */
gm_status gm_vi_solve(vi_engine *e, int newton, int simplified);
/* p_{k+1} − p_k after a solve (with the tangency projection for constraints), into dp. */
gm_status gm_vi_momentum_increment(vi_engine *e, double *dp);

#endif
