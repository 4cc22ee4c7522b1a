/* Symplectic-energy-momentum variational integrators: the time step is an unknown of the step
 * (Kane, Marsden & Ortiz, J. Math. Phys. 40 (1999) 3353; seed 001 §5.5 with the Galerkin L_d
 * for higher order; seed 004 "Variational integrators", rectangle and midpoint rules).
 *
 * With L_d(q_k, q_{k+1}, h_k) varied in the times as well, the discrete equations are the DEL
 * and the discrete energy equation E_d(q_k, q_{k+1}, h_k) = E_d(q_{k−1}, q_k, h_{k−1}), where
 *   E_d = −∂L_d/∂h = Σ_i b_i [∂L/∂v(Q_i, V_i)·V_i − L(Q_i, V_i)]
 * (for the Galerkin S = h Σ b_i L(Q_i, V_i) with V_i = Σ_ν φ'_ν(c_i) q^ν / h and the inner
 * points stationary; for the midpoint rule, seed 001 §1G: E_d = −L + ∂L/∂q̇·(q1 − q0)/h).
 * In position–momentum form one step solves
 *   p_k + dS_0 = 0,  dS_ν = 0 (ν = 1..s−1),  E_d(z, h_k) = E
 * for the control points and h_k by Newton's method (analytic Jacobian, including the column of
 * h and the row of E_d), then p_{k+1} = dS_s. E is the discrete energy of the first step, which
 * is taken with the step h asked for (the two-step form starts from (q_0, q_1, h_0)); the
 * energy level thus carries h² and sets the size of the later steps, which shrink where the
 * motion is fast (the pericentre of an orbit).
 * Where the energy equation has no solution near the previous step (E_d(h) − E keeps one sign,
 * typically where ∂E_d/∂h = 0), the step size minimizes (E_d(h) − E)² instead (the least-squares
 * fallback of seed 001 §5.5 / Kane, Marsden & Ortiz §4) near the previous step (see
 * least_squares_step); the energy is then kept only as well as that minimum allows, and
 * gm_variational_energy_fallbacks counts these steps. For a symmetric L_d, −h_prev is always a
 * root (the step back), so near h_prev f(h) ≈ c(h² − h_prev²) + e(h³ + h_prev³), whose forward
 * root exists unless c/(e h_prev) lies in (−3, 1): where the leading error coefficient c of the
 * energy changes sign along the orbit (Kepler with e = 0.9 near r ≈ 1.25), a few steps per
 * crossing have no root, whatever h.
 * Constraints and forces are not supported here. The sign of the step asked for sets the
 * direction of time. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/variational.h"
#include "methods/variational/variational_internal.h"

#define EPS 2.220446049250313e-16
#define SEM_MAX_ITERATIONS 40
/* the relative resolution of h below which the energy equation is not followed (see
 * solve_with_energy) */
#define SEM_RESOLUTION 1e-2
/* A root of the energy equation is the continuation of the previous step only within a factor 2
 * of it: for a symmetric L_d, f(h) ≈ c(h^p − h_prev^p) + e(h^{p+1} + h_prev^{p+1}) near h_prev,
 * whose forward root is h_prev(1 + O(h_prev)); a root farther away is another branch, and
 * following such jumps (the bound was 8) let vi-sem-galerkin-3 on Kepler e = 0.6 from h0 = 0.05
 * grow its steps to 3.1 (half the period) until the DEL had no solution. */
#define SEM_MAX_RATIO_HI 8.0
#define SEM_MAX_RATIO_LO 0.125

typedef struct {
  vi_engine e;
  size_t degree;
  int have_energy;
  double energy;      /* E, the discrete energy of the run */
  double h_prev;      /* the last step taken */
  double *z_prev, *dp;
  size_t fallbacks;
  size_t unresolved;  /* steps where the energy equation did not resolve h: h_prev kept */
  int resolve;        /* 1 while solving from the previous step (not in the fallback scan) */
  double last_energy_error;
  double max_energy_error; /* max |E_d − E| over the steps since the energy was set */
} sem_work;

static gm_status init(gm_integrator *it) {
  sem_work *w = calloc(1, sizeof *w);
  if (w == NULL) return GM_ENOMEM;
  it->work = w;
  vi_rule rule;
  if (gm_vi_rule_of(it->method, &rule, &w->degree) != GM_OK || rule != VI_RULE_GAUSS)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "'%s': no Gauss rule",
                   it->method->name);
  const gm_problem *pb = it->problem;
  if (pb->kind == GM_PROBLEM_LAGRANGIAN && (pb->n_constraints > 0 || pb->force != NULL))
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "'%s' keeps the energy of unconstrained, unforced Lagrangians; this problem "
                   "has %s", it->method->name, pb->n_constraints > 0 ? "constraints" : "a force");
  gm_status st = gm_vi_engine_init(&w->e, pb, VI_RULE_GAUSS, w->degree, 0.5, 1, &it->stats,
                                   it->errmsg);
  if (st != GM_OK) return st;
  const size_t d = it->dim, s = w->degree;
  w->z_prev = calloc(s * d, sizeof(double));
  w->dp = calloc(d, sizeof(double));
  if (!w->z_prev || !w->dp) return GM_ENOMEM;
  return GM_OK;
}

static void release(gm_integrator *it) {
  sem_work *w = it->work;
  if (w == NULL) return;
  gm_vi_engine_release(&w->e);
  free(w->z_prev);
  free(w->dp);
  free(w);
  it->work = NULL;
}

static void invalidate(gm_integrator *it) {
  sem_work *w = it->work;
  if (w != NULL) {
    w->have_energy = 0;
    w->h_prev = 0.0;
  }
}

/* E_d at the last evaluation; *size (if not NULL) gets the scale of its rounding error,
 * Σ b_i (|L_v|·|V| + |L| + |L_q|·|Q|): the terms of E_d and the change of L when Q, which the
 * DEL fix only to round-off relative to |Q|, moves by one ulp. Near a turning point on a level
 * E ≈ 0 (the pendulum released at q = π/2) |L_v·V| + |L| is 1e-5 while L = p²/2 + cos q
 * carries the absolute rounding 1e-16 of cos q: without the |L_q|·|Q| term the stopping test
 * asked for an E_d more exact than its arguments. */
static gm_status discrete_energy_sized(vi_engine *e, double *energy, double *size) {
  const size_t d = e->d;
  double sum = 0.0, mag = 0.0;
  for (size_t i = 0; i < e->r; ++i) {
    double l, pv = 0.0;
    gm_status st = gm_vi_lagrangian_at(e, i, &l);
    if (st != GM_OK) return st;
    double cond = 0.0;
    for (size_t k = 0; k < d; ++k) {
      pv += e->Lv[i * d + k] * e->V[i * d + k];
      cond += fabs(e->Lv[i * d + k] * e->V[i * d + k]) + fabs(e->Lq[i * d + k] * e->Q[i * d + k]);
    }
    sum += e->b[i] * (pv - l);
    mag += fabs(e->b[i]) * (cond + fabs(l));
  }
  *energy = sum;
  if (size != NULL) *size = mag;
  return GM_OK;
}

static gm_status discrete_energy(vi_engine *e, double *energy) {
  return discrete_energy_sized(e, energy, NULL);
}

/* Straight-line (or extrapolated) starting values for a step of size h. */
static void starting_values(sem_work *w, double h, int extrapolate) {
  vi_engine *e = &w->e;
  const size_t d = e->d, s = e->s;
  if (extrapolate) {
    for (size_t nu = 0; nu < s; ++nu)
      for (size_t k = 0; k < d; ++k) {
        double sum = 0.0;
        for (size_t mu = 0; mu < s; ++mu) sum += e->extrap[nu * s + mu] * w->z_prev[mu * d + k];
        e->x[nu * d + k] = sum;
      }
    return;
  }
  /* velocity from p = M v (quadratic) or zero */
  for (size_t k = 0; k < d; ++k) {
    double v = 0.0;
    if (e->quadratic)
      for (size_t j = 0; j < d; ++j) v += e->mass_inv[k * d + j] * e->p[j];
    for (size_t nu = 1; nu <= s; ++nu) e->x[(nu - 1) * d + k] = e->ctimes[nu] * h * v;
  }
}

/* Newton's method on h for f(h) = E_d(z(h), h) − E, where z(h) solves the DEL at the step h
 * exactly (an inner Newton solve): the coupled (z, h) system is badly conditioned, because its
 * large O(1/h) partial derivatives cancel in df/dh = O(h). df/dh is the Schur complement
 *   ∂E_d/∂h − ∂E_d/∂z (∂R/∂z)⁻¹ ∂R/∂h
 * from the analytic derivatives (columns of h: Σ_i b_i [φ_μ (L_q − L_qv V) − φ'_μ L_vv V / h];
 * row of E_d: Σ_i b_i [φ_ν (Vᵀ L_vq − L_q) + (φ'_ν / h) Vᵀ L_vv], and −Σ_i b_i Vᵀ L_vv V / h).
 * On success e->x holds z and e->h the step. */
static gm_status solve_with_energy(gm_integrator *it, sem_work *w) {
  (void)it; /* the inner solves count their iterations */
  vi_engine *e = &w->e;
  const size_t d = e->d, s = e->s, sd = s * d, n2 = 2 * d, sp = s + 1;
  double *col = e->res, *row = e->dx, *jac = e->jac;
  double step = INFINITY, step_prev = INFINITY;
  gm_status st = GM_OK;
  for (size_t iter = 0;; ++iter) {
    if ((st = gm_vi_solve(e, 1, 0)) != GM_OK) return st;
    double ed, size;
    if ((st = discrete_energy_sized(e, &ed, &size)) != GM_OK) return st;
    /* converged: the last change of h was at round-off, or the energy already is */
    if (step <= 4.0 * EPS * fabs(e->h) || fabs(ed - w->energy) <= 2.0 * EPS * fabs(w->energy))
      return GM_OK;
    /* the starting guess (±h_prev) already solves the equation to the rounding of E_d: it is
     * the root continuous with the previous step, and a Newton step on rounding error would
     * only move it (a step h then −h returned 3e-12 off for vi-sem-galerkin-2 on Kepler, 2e-10
     * for -3, instead of exactly) */
    if (iter == 0 && fabs(ed - w->energy) <= 4.0 * EPS * size) return GM_OK;
    /* With small steps df/dh = O(h) is small and h is fixed only to ε·size/|df/dh|, far above
     * ε|h|: once the changes of h stop shrinking with E_d at its rounding level, that is the
     * root (without this, such steps were counted as least-squares fallbacks that found it). */
    if (step < INFINITY && step >= step_prev && fabs(ed - w->energy) <= 16.0 * EPS * size)
      return GM_OK;
    if (iter >= SEM_MAX_ITERATIONS)
      return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ENOCONV,
                     "Newton on the energy equation did not converge (last change of h %.1e)",
                     step);
    const double h = e->h;
    for (size_t mu = 0; mu < s; ++mu)
      for (size_t nu = 1; nu <= s; ++nu) gm_vi_block(e, mu, nu, jac + mu * d * sd + (nu - 1) * d, sd);
    memset(col, 0, sd * sizeof *col);
    memset(row, 0, sd * sizeof *row);
    double dedh = 0.0;
    for (size_t i = 0; i < e->r; ++i) {
      const double *H = e->hess + i * n2 * n2, *V = e->V + i * d, *lq = e->Lq + i * d;
      const double bi = e->b[i];
      for (size_t mu = 0; mu < s; ++mu) {
        const double pm = e->phi[i * sp + mu], dm = e->dphi[i * sp + mu];
        for (size_t a = 0; a < d; ++a) {
          double qv = 0.0, vv = 0.0;
          for (size_t c = 0; c < d; ++c) {
            qv += H[a * n2 + d + c] * V[c];
            vv += H[(d + a) * n2 + d + c] * V[c];
          }
          col[mu * d + a] += bi * (pm * (lq[a] - qv) - dm * vv / h);
        }
      }
      double vlv = 0.0;
      for (size_t c = 0; c < d; ++c) {
        double vq = 0.0, vv = 0.0;
        for (size_t a = 0; a < d; ++a) {
          vq += V[a] * H[(d + a) * n2 + c];
          vv += V[a] * H[(d + a) * n2 + d + c];
        }
        vlv += vv * V[c];
        for (size_t nu = 1; nu <= s; ++nu)
          row[(nu - 1) * d + c] +=
              bi * (e->phi[i * sp + nu] * (vq - lq[c]) + e->dphi[i * sp + nu] / h * vv);
      }
      dedh -= bi * vlv / h;
    }
    if (gm_lu_factor(sd, jac, e->piv) != GM_OK)
      return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ESINGULAR, "singular DEL Jacobian");
    gm_lu_solve(sd, jac, e->piv, col); /* y = (∂R/∂z)⁻¹ ∂R/∂h = −dz/dh */
    double g = dedh;
    for (size_t k = 0; k < sd; ++k) g -= row[k] * col[k];
    /* The energy equation fixes h only to tol/|g|: where that is coarser than SEM_RESOLUTION·|h|
     * at the previous step (g = df/dh ≈ p c h^{p−1} → 0 where the leading energy-error
     * coefficient c vanishes, and for order p ≥ 4 whenever c h^p nears the rounding of E_d),
     * any h near h_prev is a root to working precision and the Newton correction is rounding
     * error divided by a vanishing g. Such corrections are not the method's: log h is neutrally
     * stable along the exact SEM trajectory (c_k h_k^p = E − H_k, so a perturbation of log h
     * persists), and following them makes log h a random walk whose steps grow as h shrinks,
     * which ends with h → 0 (the pendulum released at q = π/2, where V'' = 0 and p = 0 make
     * c = 0: vi-sem-galerkin-2 from h0 ≤ 0.004). The root continuous with the previous step is
     * then h_prev itself (counted: gm_variational_unresolved_steps). */
    if (iter == 0 && w->resolve && isfinite(g) &&
        !(SEM_RESOLUTION * fabs(g * h) >= 4.0 * EPS * size)) {
      w->unresolved++;
      return GM_OK;
    }
    if (!(fabs(g) > 0.0) || !isfinite(g))
      return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_ESINGULAR,
                     "dE_d/dh = 0: the energy equation is singular in h");
    const double dh = -(ed - w->energy) / g;
    step_prev = step;
    step = fabs(dh);
    /* h is known only to (round-off of E_d)/|df/dh|: stop when its changes stop shrinking */
    if (step > 4.0 * EPS * fabs(h) && step <= 1e-8 * fabs(h) && step >= step_prev)
      return GM_OK;
    e->h = h + dh;
    if (!isfinite(e->h) || e->h == 0.0 || (e->h > 0) != (h > 0))
      return gm_fail(e->errmsg, GM_ERRMSG_SIZE, GM_EDOMAIN,
                     "the energy equation has no root near h = %g", h);
    for (size_t k = 0; k < sd; ++k) e->x[k] -= col[k] * dh; /* z(h + dh) ≈ z − y dh */
  }
}

/* Fixed step h: solve the DEL only; the squared energy error at the solution into *phi. */
static gm_status fixed_step(gm_integrator *it, sem_work *w, double h, double *phi) {
  vi_engine *e = &w->e;
  e->h = h;
  starting_values(w, h, 0);
  gm_status st = gm_vi_solve(e, 1, 0);
  double ed = NAN;
  if (st == GM_OK) st = discrete_energy(e, &ed);
  (void)it;
  *phi = (ed - w->energy) * (ed - w->energy);
  return st;
}

/* Where the energy equation has no root near the previous step: the step that minimizes
 * (E_d(h) − E)² over h in [h_prev/1.25, 1.25 h_prev] when that minimum is interior (the least
 * squares of seed 001 §5.5), else the previous step size itself. The window is narrow and its
 * edges are never taken: without a root, (E_d(h) − E)² often falls monotonically towards h = 0,
 * and following it lets the steps collapse (seen on Kepler, e = 0.9). */
static gm_status least_squares_step(gm_integrator *it, sem_work *w, double h_prev) {
  const double sign = h_prev < 0 ? -1.0 : 1.0, a0 = log(fabs(h_prev) / 1.25),
               a1 = log(fabs(h_prev) * 1.25);
  enum { SCAN = 9 };
  double f[SCAN], best = INFINITY;
  int k_best = -1;
  for (int k = 0; k < SCAN; ++k) {
    if (fixed_step(it, w, sign * exp(a0 + (a1 - a0) * k / (SCAN - 1)), &f[k]) != GM_OK)
      f[k] = INFINITY;
    if (f[k] < best) {
      best = f[k];
      k_best = k;
    }
  }
  w->fallbacks++;
  double phi;
  if (k_best <= 0 || k_best >= SCAN - 1) return fixed_step(it, w, h_prev, &phi);
  const double g = 0.5 * (sqrt(5.0) - 1.0), du = (a1 - a0) / (SCAN - 1);
  double lo = a0 + du * (k_best - 1), hi = a0 + du * (k_best + 1);
  double u1 = hi - g * (hi - lo), u2 = lo + g * (hi - lo), f1, f2;
  if (fixed_step(it, w, sign * exp(u1), &f1) != GM_OK) f1 = INFINITY;
  if (fixed_step(it, w, sign * exp(u2), &f2) != GM_OK) f2 = INFINITY;
  for (int k = 0; k < 60 && hi - lo > 1e-14; ++k) {
    if (f1 < f2) {
      hi = u2;
      u2 = u1;
      f2 = f1;
      u1 = hi - g * (hi - lo);
      if (fixed_step(it, w, sign * exp(u1), &f1) != GM_OK) f1 = INFINITY;
    } else {
      lo = u1;
      u1 = u2;
      f1 = f2;
      u2 = lo + g * (hi - lo);
      if (fixed_step(it, w, sign * exp(u2), &f2) != GM_OK) f2 = INFINITY;
    }
  }
  return fixed_step(it, w, sign * exp(f1 < f2 ? u1 : u2), &phi);
}

static gm_status step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                      double *delta) {
  sem_work *w = it->work;
  vi_engine *e = &w->e;
  const size_t d = e->d, s = e->s;
  e->t = t;
  e->q = y;
  e->p = y + d;
  gm_status st = GM_OK;
  if (e->quadratic && (st = gm_vi_prepare_mass(e, y)) != GM_OK) return st;
  if (!w->have_energy) {
    /* the first step: the step asked for, which sets the discrete energy of the run */
    double phi;
    w->energy = 0.0;
    st = fixed_step(it, w, h, &phi);
    if (st == GM_OK) st = discrete_energy(e, &w->energy);
  } else {
    const double guess = (h < 0) == (w->h_prev < 0) ? w->h_prev : -w->h_prev;
    e->h = guess;
    starting_values(w, guess, guess == w->h_prev);
    w->resolve = 1;
    st = solve_with_energy(it, w);
    w->resolve = 0;
    const double ratio = e->h / guess;
    if (st == GM_ECALLBACK) return st;
    if (st != GM_OK || !(ratio > SEM_MAX_RATIO_LO && ratio < SEM_MAX_RATIO_HI)) st = least_squares_step(it, w, guess);
  }
  if (st == GM_OK) st = gm_vi_momentum_increment(e, w->dp);
  if (st == GM_OK) {
    double ed;
    st = discrete_energy(e, &ed);
    w->last_energy_error = ed - w->energy;
  }
  if (st != GM_OK) {
    if (st != GM_ECALLBACK) {
      it->stats.newton_failures++;
      char why[GM_ERRMSG_SIZE];
      memcpy(why, it->errmsg, sizeof why);
      gm_fail(it->errmsg, sizeof it->errmsg, st, "%s: %s in the step from t = %.17g",
              it->method->name, why, t);
    }
    return st;
  }
  const double *dq = e->x + (s - 1) * d;
  for (size_t k = 0; k < d; ++k) {
    if (delta != NULL) {
      delta[k] = dq[k];
      delta[d + k] = w->dp[k];
    } else {
      y_new[k] = y[k] + dq[k];
      y_new[d + k] = y[d + k] + w->dp[k];
    }
  }
  memcpy(w->z_prev, e->x, s * d * sizeof(double));
  w->h_prev = e->h;
  if (!w->have_energy) w->max_energy_error = 0.0;
  w->max_energy_error = fmax(w->max_energy_error, fabs(w->last_energy_error));
  w->have_energy = 1;
  it->h_taken = e->h;
  return GM_OK;
}

/* Checkpoints: what the next step depends on besides the state — the discrete energy, the last
 * step (the next one's starting guess), the last control points (extrapolated starting
 * values) — and the counters the run reports. */
typedef struct {
  double energy, h_prev, last_energy_error, max_energy_error;
  unsigned long long have_energy, fallbacks, unresolved;
} sem_saved;

static size_t state_size(const gm_integrator *it) {
  const sem_work *w = it->work;
  return sizeof(sem_saved) + w->e.s * w->e.d * sizeof(double);
}

static void state_save(const gm_integrator *it, unsigned char *out) {
  const sem_work *w = it->work;
  sem_saved v = {w->energy, w->h_prev, w->last_energy_error, w->max_energy_error,
                 (unsigned long long)w->have_energy, (unsigned long long)w->fallbacks,
                 (unsigned long long)w->unresolved};
  memcpy(out, &v, sizeof v);
  memcpy(out + sizeof v, w->z_prev, w->e.s * w->e.d * sizeof(double));
}

static gm_status state_load(gm_integrator *it, const unsigned char *in) {
  sem_work *w = it->work;
  sem_saved v;
  memcpy(&v, in, sizeof v);
  w->energy = v.energy;
  w->h_prev = v.h_prev;
  w->last_energy_error = v.last_energy_error;
  w->max_energy_error = v.max_energy_error;
  w->have_energy = v.have_energy != 0;
  w->fallbacks = (size_t)v.fallbacks;
  w->unresolved = (size_t)v.unresolved;
  memcpy(w->z_prev, in + sizeof v, w->e.s * w->e.d * sizeof(double));
  return GM_OK;
}

static gm_status set_solver(gm_integrator *it, gm_solver solver) {
  /* the step and energy equations are always solved by Newton's method; the iterative solvers
   * are accepted (and mean Newton) so that runs asking every implicit row for them work */
  if (solver == GM_SOLVER_SIMPLIFIED_NEWTON)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "'%s' solves its step and energy equations by Newton's method",
                   it->method->name);
  it->solver = solver;
  return GM_OK;
}

const gm_stepper gm_sem_stepper = {init, step, release, invalidate, NULL, set_solver, 0};
const gm_stepper_state gm_sem_stepper_state = {1, state_size, state_save, state_load};

static sem_work *sem_of(const gm_integrator *it) {
  return (it != NULL && it->stepper == &gm_sem_stepper) ? it->work : NULL;
}

double gm_variational_discrete_energy(const gm_integrator *it) {
  const sem_work *w = sem_of(it);
  return (w != NULL && w->have_energy) ? w->energy : NAN;
}

double gm_variational_last_energy_error(const gm_integrator *it) {
  const sem_work *w = sem_of(it);
  return (w != NULL && w->have_energy) ? w->last_energy_error : NAN;
}

double gm_variational_max_energy_error(const gm_integrator *it) {
  const sem_work *w = sem_of(it);
  return (w != NULL && w->have_energy) ? w->max_energy_error : NAN;
}

size_t gm_variational_energy_fallbacks(const gm_integrator *it) {
  const sem_work *w = sem_of(it);
  return w != NULL ? w->fallbacks : 0;
}

size_t gm_variational_unresolved_steps(const gm_integrator *it) {
  const sem_work *w = sem_of(it);
  return w != NULL ? w->unresolved : 0;
}
