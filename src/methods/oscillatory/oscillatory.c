/* Stepper of the oscillatory family (issue 12) for split potentials V = U + W, p = M q̇.
 *
 *  - imex: Ψ_h = φ^U_{h/2} ∘ midpoint^{T+W}_h ∘ φ^U_{h/2} (seed 000 §2.2.1; Zhang & Skeel 1997).
 *    With W = ½ qᵀΩ²q the midpoint step is linear, in one of three equivalent forms:
 *    (a) the linear solve (M + (h²/4)Ω²)(q1 − q0) = h p⁺ − (h²/2)Ω²q0,
 *        p⁻ = p⁺ − (h/2)Ω²(q0 + q1);
 *    (b) Verlet with the modified mass M̃ = M + (hΩ/2)² on U + W (Prop. 2.2.1: the IMEX and the
 *        M̃-trapezoidal discrete Lagrangians are the same function, so are their momenta);
 *    (c) in the modal coordinates of K = M^{−1/2}Ω²M^{−1/2}, the exact rotation by
 *        θ = 2 arctan(hν/2) (§2.2.5): cos θ = (1 − (hν/2)²)/(1 + (hν/2)²),
 *        sin θ/ν = h/(1 + (hν/2)²).
 *    Otherwise Newton's method on M δ − h p⁺ + (h²/2)∇W(q0 + δ/2) = 0, δ = q1 − q0.
 *  - impulse (r-RESPA): kick U by h/2, n Verlet substeps of h/n on T + W, kick (GNI VIII.4).
 *  - mollified-impulse-*: the same on U(A q), force Aᵀ∇U(Aq), A = φ(hΩ) (mass-weighted).
 *  - trig-*: GNI XIII (2.7)–(2.8) in modal coordinates, g(q) = −∇U(q):
 *      z1 = cos(hν) z0 + ν⁻¹ sin(hν) w0 + (h²/2) ψ g(Φ q0),
 *      w1 = −ν sin(hν) z0 + cos(hν) w0 + (h/2)(ψ0 g(Φ q0) + ψ1 g(Φ q1)),
 *    ψ0 = cos ψ1, ψ1 = ψ/sinc (symmetric; singular where sinc(hν) = 0).
 *  - vti: the one-step form of the vector variational trigonometric integrator written from its
 *    discrete Legendre transforms (seed 000 §2.3.2 with the notes' corrections A6), with the
 *    exact filters Φ = sinc(hν/2)/√sinc(hν), Ψ = Φ sinc(hν):
 *      z1 = (1 − (h²/2)ΨΦν²) z0 + hΨΦ⁻¹ w0 + (h²/2)Ψ g0,
 *      w1 = −hΦ²ν²(1 − (h²/4)ΨΦν²) z0 + (1 − (h²/2)ΨΦν²) w0 + (h/2)Φ[(1 − (h²/2)ΨΦν²) g0 + g1].
 *    It coincides with trig-* for the same pair (test), but is computed from these formulas.
 *  - vti-scalar: one degree of freedom, L_h = (h/(2 sinc hν))[((x1−x0)/h)² − ν²σ²(x0² + x1²)/2
 *    − 2ΨΦ⁻¹(U(Φx0) + U(Φx1))/2·...] with ΨΦ = σ² = sinc²(hν/2), Φ free (§2.3.1). Its
 *    Legendre transforms solved for (x1, v1):
 *      x1 = x0 + h s v0 − (h²/2)ν²σ² x0 + (h²/2)Ψ g0,
 *      v1 = (x1 − x0)/(h s) − (h/(2s))ν²σ² x1 + (h/(2s))Ψ g1,      s = sinc(hν).
 *
 * The slow force at the end of a step is kept for the next one when that step starts from the
 * same positions (bitwise): one slow force per step. Coefficients that depend on h are computed
 * when h changes, never per step; nothing is allocated in a step. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "methods/oscillatory/oscillatory.h"

typedef struct {
  const gm_osc_scheme *scheme;
  gm_osc_fast fast;
  size_t substeps;
  gm_imex_form form;         /* resolved (never AUTO) */
  gm_filter_fn phi, psi;     /* current filters */
  double h_coef;             /* the coefficients below are for this h (NaN: none yet) */
  /* per mode: */
  double *c_a, *c_b, *c_c;   /* position/velocity propagators (see each scheme) */
  double *c_psi, *c_phi, *c_psi0, *c_psi1;
  double *lu;                /* imex (a), (b): LU of M + (h²/4)Ω² */
  int *ipiv;
  /* slow force cache: g_cache = −∇U (or the modal/mollified force) at positions q_cache */
  double *q_cache, *f_cache;
  int cache_valid;
  /* work */
  double *z, *w, *g0, *g1, *qf, *u, *v, *y_tmp, *y_out;
  gm_newton *newton;
  /* Newton context */
  const double *nq0, *np;
  double nh;
  gm_integrator *nit;
  int callback_rc;
} osc_work;

static const gm_osc_scheme *scheme_of(const gm_method *m) {
  return &gm_oscillatory_schemes[m - gm_oscillatory_methods];
}

static void release(gm_integrator *it) {
  osc_work *w = it->work;
  if (w == NULL) return;
  gm_osc_fast_release(&w->fast);
  double *arrays[] = {w->c_a, w->c_b, w->c_c, w->c_psi, w->c_phi, w->c_psi0, w->c_psi1,
                      w->lu, w->q_cache, w->f_cache, w->z, w->w, w->g0, w->g1, w->qf, w->u,
                      w->v, w->y_tmp, w->y_out};
  for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; ++i) free(arrays[i]);
  free(w->ipiv);
  gm_newton_free(w->newton);
  free(w);
  it->work = NULL;
}

static void invalidate(gm_integrator *it) {
  osc_work *w = it->work;
  if (w != NULL) w->cache_valid = 0;
}

static const char *name_of(const gm_integrator *it) { return it->method->name; }

/* The fastest IMEX form, measured by bench/oscillatory_imex_forms.c (docs/oscillatory.md): the
 * rotation in modal coordinates when Ω is diagonal or d ≤ 16 (its two basis changes per step
 * cost less than a solve there), Verlet with the modified mass above. */
static gm_imex_form auto_form(const gm_osc_fast *f) {
  return (f->basis == NULL || f->d <= 16) ? GM_IMEX_MODIFIED_FREQUENCY : GM_IMEX_MODIFIED_MASS;
}

static gm_status init(gm_integrator *it) {
  osc_work *w = calloc(1, sizeof *w);
  if (w == NULL) return GM_ENOMEM;
  it->work = w;
  w->scheme = scheme_of(it->method);
  const gm_problem *pb = it->problem;
  if (pb->split == NULL)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "method '%s' needs a split potential V = U + W (gm_problem.split); this "
                   "problem has none",
                   name_of(it));
  gm_status st = gm_osc_fast_create(pb, &w->fast, it->errmsg, sizeof it->errmsg);
  if (st != GM_OK) return st;
  if (w->scheme->needs_quadratic && !w->fast.quadratic)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "method '%s' filters with functions of hΩ: the problem has no fast "
                   "quadratic part W = ½ qᵀΩ²q (split->omega is NULL)",
                   name_of(it));
  const size_t d = it->dim;
  if (w->scheme->kind == GM_OSC_VTI_SCALAR && d != 1)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "method '%s' is the scalar family (seed 000 §2.3.1), for one degree of "
                   "freedom; this problem has %zu (use vti)",
                   name_of(it), d);
  w->substeps = w->scheme->substeps;
  w->phi = w->scheme->phi;
  w->psi = w->scheme->psi;
  w->h_coef = NAN;
  double **arrays[] = {&w->c_a, &w->c_b, &w->c_c, &w->c_psi, &w->c_phi, &w->c_psi0, &w->c_psi1,
                       &w->q_cache, &w->f_cache, &w->z, &w->w, &w->g0, &w->g1, &w->qf, &w->u,
                       &w->v};
  for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; ++i)
    if ((*arrays[i] = calloc(d, sizeof(double))) == NULL) return GM_ENOMEM;
  if ((w->y_tmp = calloc(d, sizeof(double))) == NULL) return GM_ENOMEM;
  if ((w->y_out = calloc(2 * d, sizeof(double))) == NULL) return GM_ENOMEM;
  if (w->scheme->kind == GM_OSC_IMEX) {
    if (w->fast.quadratic) {
      w->form = auto_form(&w->fast);
      w->lu = calloc(d * d, sizeof(double));
      w->ipiv = calloc(d, sizeof(int));
      if (!w->lu || !w->ipiv) return GM_ENOMEM;
    } else {
      gm_newton_options o = gm_newton_defaults();
      o.max_iterations = 50;
      if ((st = gm_newton_create(d, &o, &w->newton)) != GM_OK) return st;
    }
  }
  return GM_OK;
}

/* ---- forces ----------------------------------------------------------------------------- */

static gm_status slow_gradient(gm_integrator *it, double t, const double *q, double *g) {
  const gm_problem *pb = it->problem;
  it->stats.force_evals++;
  int rc = pb->split->slow_gradient(pb->ctx, q, g);
  return rc == 0 ? GM_OK : gm_callback_failed(it, "slow_gradient", rc, t);
}

static gm_status fast_gradient(gm_integrator *it, double t, const double *q, double *g) {
  osc_work *w = it->work;
  if (w->fast.quadratic) {
    gm_osc_omega2_apply(&w->fast, q, g);
    return GM_OK;
  }
  const gm_problem *pb = it->problem;
  int rc = pb->split->fast_gradient(pb->ctx, q, g);
  return rc == 0 ? GM_OK : gm_callback_failed(it, "fast_gradient", rc, t);
}

/* The force of the slow kick at q (cached): −∇U(q) (imex, impulse), −Aᵀ∇U(Aq) (mollified),
 * or modal g(Φq) (trig, vti). */
static gm_status slow_force(gm_integrator *it, double t, const double *q, double *out) {
  osc_work *w = it->work;
  const size_t d = it->dim;
  if (w->cache_valid && memcmp(q, w->q_cache, d * sizeof *q) == 0) {
    memcpy(out, w->f_cache, d * sizeof *out);
    return GM_OK;
  }
  gm_status st;
  switch (w->scheme->kind) {
    case GM_OSC_IMEX:
    case GM_OSC_IMPULSE:
      if ((st = slow_gradient(it, t, q, out)) != GM_OK) return st;
      for (size_t i = 0; i < d; ++i) out[i] = -out[i];
      break;
    case GM_OSC_MOLLIFIED: /* A = M^{−1/2} Q a(hν) Qᵀ M^{1/2}, Aᵀ = M^{1/2} Q a Qᵀ M^{−1/2} */
      gm_osc_to_modal_position(&w->fast, q, w->u);
      for (size_t k = 0; k < d; ++k) w->u[k] *= w->c_phi[k];
      gm_osc_from_modal_position(&w->fast, w->u, w->qf);
      if ((st = slow_gradient(it, t, w->qf, w->v)) != GM_OK) return st;
      gm_osc_to_modal_momentum(&w->fast, w->v, w->u);
      for (size_t k = 0; k < d; ++k) w->u[k] *= -w->c_phi[k];
      gm_osc_from_modal_momentum(&w->fast, w->u, out);
      break;
    default: /* modal g(Φq) = Qᵀ M^{−1/2} (−∇U(M^{−1/2} Q Φ z)) */
      gm_osc_to_modal_position(&w->fast, q, w->u);
      for (size_t k = 0; k < d; ++k) w->u[k] *= w->c_phi[k];
      gm_osc_from_modal_position(&w->fast, w->u, w->qf);
      if ((st = slow_gradient(it, t, w->qf, w->v)) != GM_OK) return st;
      for (size_t i = 0; i < d; ++i) w->v[i] = -w->v[i];
      gm_osc_to_modal_momentum(&w->fast, w->v, out);
      break;
  }
  memcpy(w->q_cache, q, d * sizeof *q);
  memcpy(w->f_cache, out, d * sizeof *out);
  w->cache_valid = 1;
  return GM_OK;
}

/* ---- coefficients for a step size ---------------------------------------------------------- */

static gm_status filter_value(gm_integrator *it, gm_filter_fn f, double xi, const char *which,
                              double *out) {
  double v = f(xi);
  if (!isfinite(v))
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                   "method '%s': filter %s(hω) is %g at hω = %g", name_of(it), which, v, xi);
  *out = v;
  return GM_OK;
}

static gm_status prepare(gm_integrator *it, double h) {
  osc_work *w = it->work;
  if (h == w->h_coef) return GM_OK;
  w->cache_valid = 0; /* the cached force depends on h through the filters */
  const size_t d = it->dim;
  const double *nu = w->fast.nu;
  gm_status st;
  switch (w->scheme->kind) {
    case GM_OSC_IMEX:
      if (!w->fast.quadratic) break;
      if (w->form == GM_IMEX_MODIFIED_FREQUENCY) {
        for (size_t k = 0; k < d; ++k) {
          const double r = 0.5 * h * nu[k], den = 1.0 + r * r;
          w->c_a[k] = (1.0 - r * r) / den; /* cos θ */
          w->c_b[k] = h / den;             /* sin θ / ν */
          w->c_c[k] = h * nu[k] * nu[k] / den; /* ν sin θ */
        }
      } else { /* LU of M + (h²/4)Ω² */
        const gm_osc_fast *f = &w->fast;
        memset(w->lu, 0, d * d * sizeof *w->lu);
        for (size_t i = 0; i < d; ++i) {
          w->lu[i * d + i] = f->msqrt[i] * f->msqrt[i];
          if (f->omega2_diagonal)
            w->lu[i * d + i] += 0.25 * h * h * f->omega2[i];
          else
            for (size_t j = 0; j < d; ++j) w->lu[i * d + j] += 0.25 * h * h * f->omega2[i * d + j];
        }
        if ((st = gm_lu_factor(d, w->lu, w->ipiv)) != GM_OK)
          return gm_fail(it->errmsg, sizeof it->errmsg, st, "imex: M + (hΩ/2)² is singular");
      }
      break;
    case GM_OSC_IMPULSE:
      break;
    case GM_OSC_MOLLIFIED:
      for (size_t k = 0; k < d; ++k)
        if ((st = filter_value(it, w->phi, h * nu[k], "A", &w->c_phi[k])) != GM_OK) return st;
      break;
    case GM_OSC_TRIG:
      for (size_t k = 0; k < d; ++k) {
        const double xi = h * nu[k], s = gm_sinc(xi);
        if ((st = filter_value(it, w->phi, xi, "phi", &w->c_phi[k])) != GM_OK ||
            (st = filter_value(it, w->psi, xi, "psi", &w->c_psi[k])) != GM_OK)
          return st;
        if (s == 0.0 || !isfinite(w->c_psi[k] / s))
          return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                         "method '%s': sinc(hω) = 0 at hω = %g, where ψ1 = ψ/sinc of the "
                         "one-step form (GNI XIII (2.10)) is singular; change h",
                         name_of(it), xi);
        w->c_a[k] = cos(xi);
        w->c_b[k] = h * s;                /* sin(hν)/ν */
        w->c_c[k] = nu[k] * sin(xi);      /* ν sin(hν) */
        w->c_psi1[k] = w->c_psi[k] / s;
        w->c_psi0[k] = cos(xi) * w->c_psi1[k];
      }
      break;
    case GM_OSC_VTI:
      for (size_t k = 0; k < d; ++k) {
        const double xi = h * nu[k], s = gm_sinc(xi), sh = gm_sinc(0.5 * xi);
        if (!(s > 0.0))
          return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                         "vti: sinc(hω) = %.3g <= 0 at hω = %g (ω = %g, h = %g): the exact "
                         "filter sinc(hΩ/2) sinc(hΩ)^(-1/2) does not exist there; take hω < π "
                         "or use a trig-* row",
                         s, xi, nu[k], h);
        const double Phi = sh / sqrt(s), Psi = Phi * s, n2 = nu[k] * nu[k];
        w->c_phi[k] = Phi;
        w->c_psi[k] = Psi;
        w->c_a[k] = 1.0 - 0.5 * h * h * Psi * Phi * n2;
        w->c_b[k] = h * Psi / Phi;
        w->c_c[k] = h * Phi * Phi * n2 * (1.0 - 0.25 * h * h * Psi * Phi * n2);
      }
      break;
    case GM_OSC_VTI_SCALAR: {
      const double xi = h * nu[0], s = gm_sinc(xi), sh = gm_sinc(0.5 * xi);
      if ((st = filter_value(it, w->phi, xi, "Phi", &w->c_phi[0])) != GM_OK) return st;
      if (s == 0.0 || w->c_phi[0] == 0.0)
        return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                       "vti-scalar: %s at hω = %g: the discrete Lagrangian is singular",
                       s == 0.0 ? "sinc(hω) = 0" : "Φ(hω) = 0", xi);
      w->c_psi[0] = sh * sh / w->c_phi[0]; /* ΨΦ = sinc²(hω/2) */
      w->c_a[0] = s;                       /* sinc(hω) */
      w->c_b[0] = nu[0] * nu[0] * sh * sh; /* ν²σ² */
      break;
    }
  }
  w->h_coef = h;
  return GM_OK;
}

/* ---- the schemes ------------------------------------------------------------------------- */

static int newton_residual(void *ctx, const double *delta, double *r) {
  osc_work *w = ctx;
  const size_t d = w->fast.d;
  const gm_problem *pb = w->nit->problem;
  for (size_t i = 0; i < d; ++i) w->qf[i] = w->nq0[i] + 0.5 * delta[i];
  int rc = pb->split->fast_gradient(pb->ctx, w->qf, r);
  if (rc != 0) return w->callback_rc = rc;
  for (size_t i = 0; i < d; ++i) {
    const double m = w->fast.msqrt[i] * w->fast.msqrt[i];
    r[i] = m * delta[i] - w->nh * w->np[i] + 0.5 * w->nh * w->nh * r[i];
  }
  return 0;
}

static int newton_jacobian(void *ctx, const double *delta, double *jac) {
  osc_work *w = ctx;
  const size_t d = w->fast.d;
  const gm_problem *pb = w->nit->problem;
  for (size_t i = 0; i < d; ++i) w->qf[i] = w->nq0[i] + 0.5 * delta[i];
  int rc = pb->split->fast_hessian(pb->ctx, w->qf, jac);
  if (rc != 0) return w->callback_rc = rc;
  w->nit->stats.jacobian_evals++;
  for (size_t i = 0; i < d * d; ++i) jac[i] *= 0.25 * w->nh * w->nh;
  for (size_t i = 0; i < d; ++i) jac[i * d + i] += w->fast.msqrt[i] * w->fast.msqrt[i];
  return 0;
}

/* Implicit midpoint on T + W from (q0, p⁺): writes q1 and p⁻. */
static gm_status imex_midpoint(gm_integrator *it, double t, double h, const double *q0,
                               const double *pp, double *q1, double *pm) {
  osc_work *w = it->work;
  const gm_osc_fast *f = &w->fast;
  const size_t d = it->dim;
  if (!f->quadratic) {
    for (size_t i = 0; i < d; ++i) q1[i] = h * pp[i] / (f->msqrt[i] * f->msqrt[i]); /* δ guess */
    w->nq0 = q0;
    w->np = pp;
    w->nh = h;
    w->nit = it;
    w->callback_rc = 0;
    const gm_problem *pb = it->problem;
    gm_status st = gm_newton_solve(w->newton, newton_residual,
                                   pb->split->fast_hessian ? newton_jacobian : NULL, w, q1);
    it->stats.newton_iterations += gm_newton_iterations(w->newton);
    if (st != GM_OK) {
      if (st == GM_ECALLBACK)
        return gm_callback_failed(it, "fast_gradient/fast_hessian", w->callback_rc, t);
      it->stats.newton_failures++;
      return gm_fail(it->errmsg, sizeof it->errmsg, st, "imex at t = %g, h = %g: %s", t, h,
                     gm_newton_errmsg(w->newton));
    }
    for (size_t i = 0; i < d; ++i) w->qf[i] = q0[i] + 0.5 * q1[i];
    if ((st = fast_gradient(it, t, w->qf, w->g1)) != GM_OK) return st;
    for (size_t i = 0; i < d; ++i) {
      q1[i] += q0[i];
      pm[i] = pp[i] - h * w->g1[i];
    }
    return GM_OK;
  }
  if (w->form == GM_IMEX_MODIFIED_FREQUENCY) {
    gm_osc_to_modal_position(f, q0, w->z);
    gm_osc_to_modal_momentum(f, pp, w->w);
    for (size_t k = 0; k < d; ++k) {
      const double z = w->z[k], v = w->w[k];
      w->z[k] = w->c_a[k] * z + w->c_b[k] * v;
      w->w[k] = -w->c_c[k] * z + w->c_a[k] * v;
    }
    gm_osc_from_modal_position(f, w->z, q1);
    gm_osc_from_modal_momentum(f, w->w, pm);
    return GM_OK;
  }
  /* (a) (M + (h²/4)Ω²) δ = h p⁺ − (h²/2)Ω² q0 */
  gm_osc_omega2_apply(f, q0, w->g1);
  for (size_t i = 0; i < d; ++i) w->u[i] = h * pp[i] - 0.5 * h * h * w->g1[i];
  gm_status st = gm_lu_solve(d, w->lu, w->ipiv, w->u);
  if (st != GM_OK) return gm_fail(it->errmsg, sizeof it->errmsg, st, "imex: singular solve");
  for (size_t i = 0; i < d; ++i) {
    q1[i] = q0[i] + w->u[i];
    w->v[i] = q0[i] + q1[i];
  }
  gm_osc_omega2_apply(f, w->v, w->g1);
  for (size_t i = 0; i < d; ++i) pm[i] = pp[i] - 0.5 * h * w->g1[i];
  return GM_OK;
}

static gm_status step_imex(gm_integrator *it, double t, double h, const double *y,
                           double *y1) {
  osc_work *w = it->work;
  const size_t d = it->dim;
  const double *q0 = y, *p0 = y + d;
  double *q1 = y1, *p1 = y1 + d;
  gm_status st;
  if (w->fast.quadratic && w->form == GM_IMEX_MODIFIED_MASS) {
    /* Verlet on U + W with mass M̃ = M + (hΩ/2)² (Prop. 2.2.1) */
    if ((st = slow_force(it, t, q0, w->g0)) != GM_OK) return st;
    gm_osc_omega2_apply(&w->fast, q0, w->g1);
    for (size_t i = 0; i < d; ++i) {
      p1[i] = p0[i] + 0.5 * h * (w->g0[i] - w->g1[i]);
      w->u[i] = h * p1[i];
    }
    if ((st = gm_lu_solve(d, w->lu, w->ipiv, w->u)) != GM_OK)
      return gm_fail(it->errmsg, sizeof it->errmsg, st, "imex: singular solve");
    for (size_t i = 0; i < d; ++i) q1[i] = q0[i] + w->u[i];
    if ((st = slow_force(it, t + h, q1, w->g0)) != GM_OK) return st;
    gm_osc_omega2_apply(&w->fast, q1, w->g1);
    for (size_t i = 0; i < d; ++i) p1[i] += 0.5 * h * (w->g0[i] - w->g1[i]);
    return GM_OK;
  }
  if ((st = slow_force(it, t, q0, w->g0)) != GM_OK) return st;
  for (size_t i = 0; i < d; ++i) p1[i] = p0[i] + 0.5 * h * w->g0[i]; /* p⁺ */
  memcpy(w->y_tmp, p1, d * sizeof *p1);
  if ((st = imex_midpoint(it, t, h, q0, w->y_tmp, q1, p1)) != GM_OK) return st;
  if ((st = slow_force(it, t + h, q1, w->g0)) != GM_OK) return st;
  for (size_t i = 0; i < d; ++i) p1[i] += 0.5 * h * w->g0[i];
  return GM_OK;
}

/* impulse and mollified impulse: kick, n Verlet substeps on T + W, kick */
static gm_status step_impulse(gm_integrator *it, double t, double h, const double *y,
                              double *y1) {
  osc_work *w = it->work;
  const size_t d = it->dim, n = w->substeps;
  const double *q0 = y, *p0 = y + d;
  double *q = y1, *p = y1 + d;
  const double hs = h / (double)n;
  gm_status st;
  if ((st = slow_force(it, t, q0, w->g0)) != GM_OK) return st;
  memcpy(q, q0, d * sizeof *q);
  for (size_t i = 0; i < d; ++i) p[i] = p0[i] + 0.5 * h * w->g0[i];
  if ((st = fast_gradient(it, t, q, w->g1)) != GM_OK) return st;
  for (size_t s = 0; s < n; ++s) {
    for (size_t i = 0; i < d; ++i) {
      p[i] -= 0.5 * hs * w->g1[i];
      q[i] += hs * p[i] / (w->fast.msqrt[i] * w->fast.msqrt[i]);
    }
    if ((st = fast_gradient(it, t, q, w->g1)) != GM_OK) return st;
    for (size_t i = 0; i < d; ++i) p[i] -= 0.5 * hs * w->g1[i];
  }
  if ((st = slow_force(it, t + h, q, w->g0)) != GM_OK) return st;
  for (size_t i = 0; i < d; ++i) p[i] += 0.5 * h * w->g0[i];
  return GM_OK;
}

static gm_status step_trig(gm_integrator *it, double t, double h, const double *y, double *y1) {
  osc_work *w = it->work;
  const size_t d = it->dim;
  const gm_osc_fast *f = &w->fast;
  const int vti = w->scheme->kind == GM_OSC_VTI;
  gm_status st;
  if ((st = slow_force(it, t, y, w->g0)) != GM_OK) return st;
  gm_osc_to_modal_position(f, y, w->z);
  gm_osc_to_modal_momentum(f, y + d, w->w);
  const double h2 = 0.5 * h * h;
  for (size_t k = 0; k < d; ++k) /* new modal positions into u */
    w->u[k] = w->c_a[k] * w->z[k] + w->c_b[k] * w->w[k] + h2 * w->c_psi[k] * w->g0[k];
  gm_osc_from_modal_position(f, w->u, y1);
  if ((st = slow_force(it, t + h, y1, w->g1)) != GM_OK) return st;
  for (size_t k = 0; k < d; ++k) {
    if (vti)
      w->v[k] = -w->c_c[k] * w->z[k] + w->c_a[k] * w->w[k] +
                0.5 * h * w->c_phi[k] * (w->c_a[k] * w->g0[k] + w->g1[k]);
    else
      w->v[k] = -w->c_c[k] * w->z[k] + w->c_a[k] * w->w[k] +
                0.5 * h * (w->c_psi0[k] * w->g0[k] + w->c_psi1[k] * w->g1[k]);
  }
  gm_osc_from_modal_momentum(f, w->v, y1 + d);
  return GM_OK;
}

static gm_status step_vti_scalar(gm_integrator *it, double t, double h, const double *y,
                                 double *y1) {
  osc_work *w = it->work;
  const gm_osc_fast *f = &w->fast;
  gm_status st;
  if ((st = slow_force(it, t, y, w->g0)) != GM_OK) return st;
  const double x0 = y[0] * f->msqrt[0], v0 = y[1] / f->msqrt[0];
  const double s = w->c_a[0], n2s2 = w->c_b[0], psi = w->c_psi[0];
  const double x1 = x0 + h * s * v0 - 0.5 * h * h * n2s2 * x0 + 0.5 * h * h * psi * w->g0[0];
  y1[0] = x1 / f->msqrt[0];
  if ((st = slow_force(it, t + h, y1, w->g1)) != GM_OK) return st;
  const double v1 =
      (x1 - x0) / (h * s) - h / (2.0 * s) * n2s2 * x1 + h / (2.0 * s) * psi * w->g1[0];
  y1[1] = v1 * f->msqrt[0];
  return GM_OK;
}

static gm_status step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                      double *delta) {
  osc_work *w = it->work;
  gm_status st = prepare(it, h);
  if (st != GM_OK) return st;
  /* compensated mode: the increment is the new state minus the old one, so the carried sum
   * stays right but the increment gains no digits */
  double *out = delta != NULL ? w->y_out : y_new;
  switch (w->scheme->kind) {
    case GM_OSC_IMEX:
      st = step_imex(it, t, h, y, out);
      break;
    case GM_OSC_IMPULSE:
    case GM_OSC_MOLLIFIED:
      st = step_impulse(it, t, h, y, out);
      break;
    case GM_OSC_TRIG:
    case GM_OSC_VTI:
      st = step_trig(it, t, h, y, out);
      break;
    case GM_OSC_VTI_SCALAR:
      st = step_vti_scalar(it, t, h, y, out);
      break;
  }
  if (st != GM_OK) {
    w->cache_valid = 0;
    return st;
  }
  if (delta != NULL)
    for (size_t i = 0; i < it->n; ++i) delta[i] = out[i] - y[i];
  return GM_OK;
}

const gm_stepper gm_oscillatory_stepper = {init, step, release, invalidate, NULL, NULL, 0};

/* ---- options ---------------------------------------------------------------------------- */

static osc_work *work_of(gm_integrator *it) {
  if (it == NULL || it->method == NULL || it->method->family != GM_FAMILY_OSCILLATORY)
    return NULL;
  return it->work;
}

gm_status gm_oscillatory_set_substeps(gm_integrator *it, size_t n) {
  osc_work *w = work_of(it);
  if (w == NULL || (w->scheme->kind != GM_OSC_IMPULSE && w->scheme->kind != GM_OSC_MOLLIFIED)) {
    if (it != NULL)
      gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
              "method '%s' takes no substeps (impulse rows do)", it->method->name);
    return GM_EUNSUPPORTED;
  }
  if (n == 0)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "%s: the number of substeps must be at least 1, got 0", it->method->name);
  w->substeps = n;
  return GM_OK;
}

gm_status gm_oscillatory_set_imex_form(gm_integrator *it, gm_imex_form form) {
  osc_work *w = work_of(it);
  if (w == NULL || w->scheme->kind != GM_OSC_IMEX) {
    if (it != NULL)
      gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
              "method '%s' is not imex: it has no IMEX form", it->method->name);
    return GM_EUNSUPPORTED;
  }
  if (form != GM_IMEX_AUTO && !w->fast.quadratic)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "imex: the linear forms need a fast quadratic part W = ½ qᵀΩ²q; this "
                   "problem's W is nonlinear (Newton is used)");
  if (form < GM_IMEX_AUTO || form > GM_IMEX_MODIFIED_FREQUENCY)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "imex: unknown form %d",
                   (int)form);
  if (form == GM_IMEX_AUTO) form = auto_form(&w->fast);
  w->form = form;
  w->h_coef = NAN;
  w->cache_valid = 0;
  return GM_OK;
}

gm_status gm_oscillatory_set_filters(gm_integrator *it, gm_filter_fn phi, gm_filter_fn psi) {
  osc_work *w = work_of(it);
  if (w == NULL ||
      (w->scheme->kind != GM_OSC_TRIG && w->scheme->kind != GM_OSC_VTI_SCALAR)) {
    if (it != NULL)
      gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
              "method '%s' has no free filters (trig-* and vti-scalar rows do)",
              it->method->name);
    return GM_EUNSUPPORTED;
  }
  if (phi == NULL || (w->scheme->kind == GM_OSC_TRIG) != (psi != NULL))
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "%s: give %s", it->method->name,
                   w->scheme->kind == GM_OSC_TRIG ? "both phi and psi" : "phi only (psi NULL)");
  w->phi = phi;
  if (psi != NULL) w->psi = psi;
  w->h_coef = NAN;
  w->cache_valid = 0;
  return GM_OK;
}
