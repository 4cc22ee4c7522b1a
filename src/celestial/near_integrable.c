/* Stepper of the near-integrable rows (near_integrable_table.c): Kepler drifts and interaction
 * kicks of a "central body + perturbed orbits" problem (gm_problem.celestial), in Jacobi or
 * democratic heliocentric coordinates.
 *
 * The stepper keeps its own state: the canonical positions Q and the velocities V = P/m' of
 * the row's coordinates (and, with compensated summation, their carries), converted from the
 * integrator's barycentric state only when a state is set. The integrator's state is its
 * output: converted back (through the corrector C, if the row has one) after each chunk of
 * steps that ends where an observer is due or a run ends, so correctors are applied at output
 * times only and what a run computes does not depend on how often it is observed.
 *
 * Drift (Kepler part, coefficient a):  every planet i ≥ 1 follows its two-body orbit with
 *   μ_i (system.c) for a·h; the centre of mass Q_0 moves with V_0.
 * Kick (interaction, coefficient b):
 *   Jacobi:  H_int = V(q) + Σ_{i≥1} μ_i m'_i/|Q_i| (WH91 eq. 26), so with F = −∇V(q) from the
 *            problem, V_i += b h (F_i/m_i − Σ_{j<i} F_j/η_{i−1} + μ_i Q_i/|Q_i|³): the Jacobi
 *            acceleration is the Jacobi transform of the barycentric accelerations.
 *   democratic heliocentric: the perturbation is H_int + H_sun, H_sun = |Σ_{i≥1} P_i|²/(2m_0)
 *            (DLL98 eq. 4), integrated as jump(b h/2), interaction(b h), jump(b h/2): both
 *            parts are O(ε), so this costs O(ε² h³) per kick, which the O(ε² h²) of the
 *            splitting already contains. Jump: Q_i += (b h/2) Σ_j m_j V_j/m_0; interaction:
 *            V_i += b h (F_i/m_i + G m_0 Q_i/|Q_i|³). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "celestial/internal.h"
#include "methods/internal.h"

typedef struct {
  double coef; /* a_i (drift) or b_i (kick), times h */
  int kick;
} ni_op;

typedef struct {
  const gm_celestial *sys;
  const gm_near_integrable_traits *traits;
  gm_coordinates coordinates;
  size_t n;            /* bodies */
  ni_op *ops;
  size_t n_ops;
  int fsal;            /* first and last operations are kicks */
  int force_valid;     /* accel holds the kick acceleration at the current Q */
  double *m, *eta, *mu, *mr; /* masses, interior masses, Kepler μ_i, m'_i */
  double *inv_m, *inv_eta, *m_over_eta; /* 1/m_i, 1/η_i, m_i/η_i: no division in a kick */
  double *Q, *V, *cQ, *cV;   /* internal state and its compensated-summation carries */
  double *Q_save, *V_save, *cQ_save, *cV_save; /* state before the current step */
  double *Qo, *Vo, *cQo, *cVo; /* output work: the state corrected for output */
  double *q, *grad, *accel;  /* barycentric positions, ∇V, kick acceleration */
  double *Qd, *Vd;           /* the increments of a drift */
  double *Qs, *As;           /* SABAC: perturbed positions, the acceleration at Q */
  size_t np;                 /* n rounded up to 4 */
  double *inv_r;             /* n − 1: the planets' 1/|Q_i| after the last drift of Q ... */
  int inv_r_valid;           /* ... while Q has not changed otherwise */
  int width;                 /* lanes of the vector kernels on this CPU (gm_lane_width) */
  gm_row_sums_fn *row_sums;  /* the kernels of that width */
  gm_central_terms_fn *central_terms;
  double *soa; /* 11 np: barycentric x, y, z, masses; planets' x, y, z, μ or m; 3 np scratch */
  double pending, pending_save; /* Kepler drift time owed by the last step (see internal_step) */
  int loaded;          /* Q, V hold the state of it->y (through C⁻¹) */
  double h_loaded;     /* the step the corrector of the loaded state was made for */
} ni_work;

static gm_status init(gm_integrator *it) {
  ni_work *w = calloc(1, sizeof *w);
  if (w == NULL) return GM_ENOMEM;
  it->work = w;
  const gm_problem *pb = it->problem;
  w->traits = gm_near_integrable_traits_of(it->method);
  if (w->traits == NULL)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "'%s' is not a near-integrable row",
                   it->method->name);
  if (pb->celestial == NULL)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "method '%s' needs a central body + perturbed orbits problem (e.g. "
                   "outer-solar-system, or n-body with central=1)",
                   it->method->name);
  gm_error err = {{0}};
  gm_status st = gm_celestial_validate(pb->celestial, &err);
  if (st != GM_OK) return gm_fail(it->errmsg, sizeof it->errmsg, st, "%s", err.message);
  w->sys = pb->celestial;
  w->coordinates = w->traits->coordinates;
  const size_t n = w->n = w->sys->n_bodies;
  if (pb->dim != 3 * n)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "the problem has %zu degrees of freedom, but %zu bodies in 3-D need %zu",
                   pb->dim, n, 3 * n);
  /* the operation list: drift a_i h, kick b_i h, zero coefficients skipped */
  gm_tableau *tab = NULL;
  if ((st = gm_method_tableau(it->method, &tab)) != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, st, "method '%s': no coefficients",
                   it->method->name);
  w->ops = calloc(2 * tab->n_stages, sizeof *w->ops);
  if (w->ops == NULL) {
    gm_tableau_free(tab);
    return GM_ENOMEM;
  }
  for (size_t i = 0; i < tab->n_stages; ++i) {
    const double coef[2] = {tab->a[i], tab->b[i]};
    for (int kick = 0; kick < 2; ++kick)
      if (coef[kick] != 0.0) w->ops[w->n_ops++] = (ni_op){coef[kick], kick};
  }
  gm_tableau_free(tab);
  w->fsal = w->n_ops > 1 && w->ops[0].kick && w->ops[w->n_ops - 1].kick;
  double **arrays[] = {&w->Q,  &w->V,   &w->cQ,    &w->cV,      &w->Q_save, &w->V_save,
                       &w->cQ_save, &w->cV_save, &w->Qo, &w->Vo, &w->cQo, &w->cVo,
                       &w->q,  &w->grad, &w->accel, &w->Qd, &w->Vd, &w->Qs, &w->As};
  for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; ++k)
    if ((*arrays[k] = calloc(3 * n, sizeof(double))) == NULL) return GM_ENOMEM;
  w->m = malloc(7 * n * sizeof(double));
  w->np = (n + 3) / 4 * 4;
  w->width = gm_lane_width();
  w->row_sums = w->width == 4 ? gm_row_sums4 : gm_row_sums2;
  w->central_terms = w->width == 4 ? gm_central_terms4 : gm_central_terms2;
  w->soa = calloc(11 * w->np + n, sizeof(double));
  w->inv_r = w->soa == NULL ? NULL : w->soa + 11 * w->np; /* padding stays 0 */
  if (w->m == NULL || w->soa == NULL) return GM_ENOMEM;
  w->eta = w->m + n;
  w->mu = w->m + 2 * n;
  w->mr = w->m + 3 * n;
  w->inv_m = w->m + 4 * n;
  w->inv_eta = w->m + 5 * n;
  w->m_over_eta = w->m + 6 * n;
  memcpy(w->m, w->sys->mass, n * sizeof(double));
  gm_interior_masses(n, w->m, w->eta);
  gm_kepler_parameters(w->coordinates, n, w->m, w->eta, w->sys->G, w->mu, w->mr);
  for (size_t i = 0; i < n; ++i) {
    w->inv_m[i] = 1.0 / w->m[i];
    w->inv_eta[i] = 1.0 / w->eta[i];
    w->m_over_eta[i] = w->m[i] / w->eta[i];
  }
  for (size_t i = 0; i < n; ++i) w->soa[3 * w->np + i] = w->m[i]; /* the bodies' masses */
  for (size_t i = 1; i < n; ++i) /* per planet: Jacobi's Kepler μ, or its mass */
    w->soa[7 * w->np + i - 1] = w->coordinates == GM_COORDINATES_JACOBI ? w->mu[i] : w->m[i];
  return GM_OK;
}

static void release(gm_integrator *it) {
  ni_work *w = it->work;
  if (w == NULL) return;
  double *arrays[] = {w->Q,       w->V,       w->cQ, w->cV, w->Q_save, w->V_save, w->cQ_save,
                      w->cV_save, w->Qo,      w->Vo, w->cQo, w->cVo,   w->q,      w->grad,
                      w->accel,   w->m,       w->Qd, w->Vd, w->Qs, w->As};
  for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; ++k) free(arrays[k]);
  free(w->soa);
  free(w->ops);
  free(w);
  it->work = NULL;
}

static void invalidate(gm_integrator *it) {
  ni_work *w = it->work;
  if (w != NULL) w->loaded = 0, w->force_valid = 0, w->inv_r_valid = 0, w->pending = 0.0;
}

/* x += d, compensated (GNI §VIII.5, Alg. 5.1) when c != NULL. */
static inline void add(double *x, double *c, double d) {
  if (c == NULL) {
    *x += d;
    return;
  }
  const double e = *c + d, b = *x + e;
  *c = (*x - b) + e;
  *x = b;
}

/* x[i] += s·d[i] (s = 1: d itself), i < k, compensated when c != NULL: the uncompensated loop
 * is a plain one the compiler can vectorize. */
static void add_all(size_t k, double *x, double *c, double s, const double *d) {
  if (c == NULL) {
    for (size_t i = 0; i < k; ++i) x[i] += s * d[i];
    return;
  }
  for (size_t i = 0; i < k; ++i) add(&x[i], &c[i], s * d[i]);
}

/* ---- the two flows ------------------------------------------------------------------------ */

static gm_status drift(gm_integrator *it, double *Q, double *V, double *cQ, double *cV,
                       double dt) {
  ni_work *w = it->work;
  for (int k = 0; k < 3; ++k) add(&Q[k], cQ ? &cQ[k] : NULL, dt * V[k]);
  const size_t n = w->n;
  double *dx = w->Qd, *dv = w->Vd;
  /* the kernel adds the increments itself, and for the state's own Q keeps the planets'
   * 1/|Q_i| for the next kick */
  const int own = Q == w->Q && cQ == NULL && cV == NULL;
  if (Q == w->Q) w->inv_r_valid = 0;
  gm_status st = cQ == NULL && cV == NULL
                     ? gm_kepler_drift_many_apply(w->width, n - 1, w->mu + 1, dt, Q + 3, V + 3,
                                                  own ? w->inv_r : NULL)
                     : gm_kepler_drift_many_width(w->width, n - 1, w->mu + 1, dt, Q + 3, V + 3,
                                                  dx, dv);
  if (st == GM_OK && own) w->inv_r_valid = 1;
  if (st != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, st,
                   "Kepler drift over %g failed at t = %.17g (%s)", dt, it->t, gm_strerror(st));
  if (cQ != NULL || cV != NULL) {
    add_all(3 * (n - 1), Q + 3, cQ ? cQ + 3 : NULL, 1.0, dx);
    add_all(3 * (n - 1), V + 3, cV ? cV + 3 : NULL, 1.0, dv);
  }
  w->force_valid = 0;
  return GM_OK;
}

static inline double inverse_cube(const double *x) {
  const double r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
  return 1.0 / (r2 * sqrt(r2));
}

/* Barycentric positions relative to the centre of mass from the internal Q: component k of
 * body i into q[i·body + k·comp] (body = 3, comp = 1: the usual layout; body = 1, comp = np:
 * by component, for the Newtonian sums). */
static inline void barycentric_positions(ni_work *w, const double *Q, double *q, size_t body,
                                         size_t comp) {
  const size_t n = w->n;
  /* V is translation invariant, so the positions are taken relative to the centre of mass
   * (Q_0 = 0): the centre of mass moves with the total momentum (far, over 10⁹ days: ~5000 au
   * for the outer solar system), and positions about it would lose the digits of the
   * separations that V needs. With Q_0 in, the rounding of the interaction (a difference of
   * O(1/ε) larger terms) grew linearly in t, and the energy error like t^1.6 instead of √t
   * (docs/celestial.md). */
  if (w->coordinates == GM_COORDINATES_JACOBI) {
    double R0 = 0, R1 = 0, R2 = 0; /* R_{n−1} = centre of mass, then down (coordinates.c) */
    for (size_t i = n - 1; i >= 1; --i) { /* components written out: this is on a kick's path */
      const double *Qi = Q + 3 * i, c = w->m_over_eta[i];
      R0 -= c * Qi[0], R1 -= c * Qi[1], R2 -= c * Qi[2];
      q[i * body] = Qi[0] + R0, q[i * body + comp] = Qi[1] + R1,
      q[i * body + 2 * comp] = Qi[2] + R2;
    }
    q[0] = R0, q[comp] = R1, q[2 * comp] = R2;
  } else {
    double c[3] = {0, 0, 0}, centre[3];
    const double M = w->eta[n - 1];
    for (size_t i = 1; i < n; ++i)
      for (int k = 0; k < 3; ++k) c[k] += w->m[i] * Q[3 * i + k];
    for (int k = 0; k < 3; ++k) q[(size_t)k * comp] = centre[k] = -c[k] / M;
    for (size_t i = 1; i < n; ++i)
      for (int k = 0; k < 3; ++k) q[i * body + (size_t)k * comp] = Q[3 * i + k] + centre[k];
  }
}

/* The interaction of a Newtonian problem (gm_celestial.newtonian), evaluated here with the
 * vector kernels of row_sums.h (no callback; the same terms as below):
 *   Jacobi:  acc_i = a_i − Σ_{j<i} m_j a_j/η_{i−1} + μ_i Q_i/|Q_i|³, a = −M⁻¹∇V at the
 *            barycentric positions (relative to the centre of mass: barycentric_positions);
 *   democratic heliocentric: q_i − q_j = Q_i − Q_j, and the central body's pull on planet i,
 *            −G m_0 Q_i/|Q_i|³, is the negative of the Kepler term, so both are left out and
 *            acc_i is the planets' pull alone (no cancellation of O(1/ε) larger terms). */
static gm_status newtonian_acceleration(gm_integrator *it, const double *Q) {
  ni_work *w = it->work;
  const size_t n = w->n, np = w->np;
  double *bx = w->soa, *by = bx + np, *bz = by + np, *bm = bz + np;
  double *px = bm + np, *py = px + np, *pz = py + np, *pk = pz + np;
  double *a = w->grad, *acc = w->accel, *kepler = w->Vd; /* drift scratch, free here */
  it->stats.force_evals++;
  const int dh = w->coordinates == GM_COORDINATES_DEMOCRATIC_HELIOCENTRIC;
  /* Jacobi's Kepler terms μ_i Q_i/|Q_i|³ from the 1/|Q_i| the last drift of Q left, as long as
   * Q has not changed since: its square roots and divisions were a tenth of a step of aba-10-4
   * (measured); 1/|Q_i| is the drift's own to a few ulp, like |Q_i| from Q's rounded digits */
  const int drifted = !dh && Q == w->Q && w->inv_r_valid;
  if (!drifted)
    for (size_t i = 1; i < n; ++i) {
      px[i - 1] = Q[3 * i];
      py[i - 1] = Q[3 * i + 1];
      pz[i - 1] = Q[3 * i + 2];
    }
  int coincide = 0;
  if (dh) {
    coincide = w->row_sums(n - 1, np, px, py, pz, pk, w->sys->G, acc + 3, pk + np);
  } else {
    barycentric_positions(w, Q, bx, 1, np); /* into bx, by, bz */
    if (drifted)
      for (size_t i = 1; i < n; ++i) {
        const double r = w->inv_r[i - 1], f = w->mu[i] * (r * r * r);
        for (int k = 0; k < 3; ++k) kepler[3 * (i - 1) + k] = f * Q[3 * i + k];
      }
    else
      coincide = w->central_terms(n - 1, px, py, pz, pk, kepler);
    coincide = coincide || w->row_sums(n, np, bx, by, bz, bm, w->sys->G, a, pk + np);
    double S[3]; /* Σ_{j<i} m_j a_j */
    for (int k = 0; k < 3; ++k) S[k] = w->m[0] * a[k];
    for (size_t i = 1; i < n; ++i)
      for (int k = 0; k < 3; ++k) {
        acc[3 * i + k] = a[3 * i + k] - S[k] * w->inv_eta[i - 1] + kepler[3 * (i - 1) + k];
        S[k] += w->m[i] * a[3 * i + k];
      }
  }
  if (coincide)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                   "two bodies (or a planet and its Kepler centre) are at the same position at "
                   "t = %.17g",
                   it->t);
  return GM_OK;
}

/* The interaction acceleration at positions Q, into w->accel (planets only). */
static gm_status interaction_acceleration(gm_integrator *it, const double *Q) {
  ni_work *w = it->work;
  const size_t n = w->n;
  double *g = w->grad, *acc = w->accel;
  if (w->sys->newtonian) return newtonian_acceleration(it, Q);
  barycentric_positions(w, Q, w->q, 3, 1);
  gm_status st = gm_eval_potential_gradient(it, it->t, w->q, g);
  if (st != GM_OK) return st;
  if (w->coordinates == GM_COORDINATES_JACOBI) {
    double S[3] = {g[0], g[1], g[2]}; /* Σ_{j<i} ∇_j V = −Σ_{j<i} F_j */
    for (size_t i = 1; i < n; ++i) {
      const double kepler = w->mu[i] * inverse_cube(Q + 3 * i);
      for (int k = 0; k < 3; ++k) {
        acc[3 * i + k] =
            -g[3 * i + k] * w->inv_m[i] + S[k] * w->inv_eta[i - 1] + kepler * Q[3 * i + k];
        S[k] += g[3 * i + k];
      }
    }
  } else {
    for (size_t i = 1; i < n; ++i) {
      const double kepler = w->mu[i] * inverse_cube(Q + 3 * i);
      for (int k = 0; k < 3; ++k)
        acc[3 * i + k] = -g[3 * i + k] * w->inv_m[i] + kepler * Q[3 * i + k];
    }
  }
  return GM_OK;
}

/* Democratic heliocentric jump: Q_i += dt Σ_j m_j V_j / m_0. */
static void jump(ni_work *w, double *Q, const double *V, double *cQ, double dt) {
  if (Q == w->Q) w->inv_r_valid = 0;
  double S[3] = {0, 0, 0};
  for (size_t i = 1; i < w->n; ++i)
    for (int k = 0; k < 3; ++k) S[k] += w->m[i] * V[3 * i + k];
  for (size_t i = 1; i < w->n; ++i)
    for (int k = 0; k < 3; ++k) add(&Q[3 * i + k], cQ ? &cQ[3 * i + k] : NULL, dt * S[k] / w->m[0]);
}

static gm_status kick(gm_integrator *it, double *Q, double *V, double *cQ, double *cV,
                      double dt) {
  ni_work *w = it->work;
  const int dh = w->coordinates == GM_COORDINATES_DEMOCRATIC_HELIOCENTRIC;
  if (dh) {
    jump(w, Q, V, cQ, 0.5 * dt);
    w->force_valid = 0;
  }
  if (!w->force_valid) {
    gm_status st = interaction_acceleration(it, Q);
    if (st != GM_OK) return st;
  }
  add_all(3 * (w->n - 1), V + 3, cV ? cV + 3 : NULL, dt, w->accel + 3);
  if (dh) jump(w, Q, V, cQ, 0.5 * dt);
  w->force_valid = !dh; /* the acceleration still belongs to Q */
  return GM_OK;
}

/* ---- corrector, loading and output ----------------------------------------------------- */

/* C = Z(a_1, b_1) ⋯ Z(a_K, b_K) (forward) or C⁻¹ = Z(−a_K, b_K) ⋯ Z(−a_1, b_1), with
 * Z(a, b) = drift(a h) kick(b h) drift(−2a h) kick(−b h) drift(a h). */
static gm_status corrector(gm_integrator *it, double *Q, double *V, double h, int inverse) {
  ni_work *w = it->work;
  const size_t K = w->traits->n_corrector;
  gm_status st = GM_OK;
  for (size_t j = 0; j < K && st == GM_OK; ++j) {
    const size_t i = inverse ? K - 1 - j : j;
    const double a = (inverse ? -1.0 : 1.0) * (double)(i + 1) * gm_corrector_alpha * h;
    const double b = -w->traits->corrector_b[i] * h; /* sign: see the table's comment */
    if ((st = drift(it, Q, V, NULL, NULL, a)) == GM_OK &&
        (st = kick(it, Q, V, NULL, NULL, b)) == GM_OK &&
        (st = drift(it, Q, V, NULL, NULL, -2.0 * a)) == GM_OK &&
        (st = kick(it, Q, V, NULL, NULL, -b)) == GM_OK)
      st = drift(it, Q, V, NULL, NULL, a);
  }
  w->force_valid = 0;
  return st;
}

/* SABAC (Laskar & Robutel, Celest. Mech. Dyn. Astr. 80 (2001) 39, §4): the ε² h² term of
 * SABA_n is g h² {{A,B},B}, and {{A,B},B} = K(Q) = Σ_i |∇_i B|²/m'_i depends on positions only
 * (A = Σ |P_i|²/(2m'_i) + Kepler terms, B = the interaction), so its flow is a kick:
 * P ← P − τ ∇K, ∇K = 2 H_B M⁻¹ ∇B. With the kick's acceleration a = −M⁻¹ ∇B, M⁻¹ ∇K = 2 Da[a]
 * (the derivative of a along a), taken here by a central difference of a over ±δ a, δ such
 * that no planet moves by more than 1e-5 of its distance (the difference's error, ~1e-10 and
 * ~u/(1e-5 ε) relative, is far below the term itself, which is O(ε² h³)). SABAC_n =
 * C½ SABA_n C½ with C½ = exp(−(g/2) h³ L_K); the internal state is C½⁻¹ of the output, so a step
 * is SABA_n after one full corrector (the two halves of consecutive steps merged), and the
 * output applies C½. V += sign · factor · g h³ · 2 Da[a]; sign checked against the measured
 * ε² h² term (tests/convergence/test_celestial_scaling.c). Three force evaluations. */
static gm_status sabac_kick(gm_integrator *it, double *Q, double *V, double *cV, double h,
                            double factor) {
  ni_work *w = it->work;
  const size_t n = w->n;
  gm_status st = interaction_acceleration(it, Q);
  if (st != GM_OK) return st;
  memcpy(w->As, w->accel, 3 * n * sizeof(double));
  double delta = INFINITY;
  for (size_t i = 1; i < n; ++i) {
    const double *a = w->As + 3 * i, *x = Q + 3 * i;
    const double na = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    const double nx = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (na > 0.0) delta = fmin(delta, 1e-5 * nx / na);
  }
  if (!isfinite(delta)) return GM_OK; /* no interaction: nothing to correct */
  const double coef = factor * w->traits->sabac_g * h * h * h * 2.0 / (2.0 * delta);
  for (int side = 0; side < 2; ++side) {
    memcpy(w->Qs, Q, 3 * n * sizeof(double));
    for (size_t i = 3; i < 3 * n; ++i) w->Qs[i] += (side ? -delta : delta) * w->As[i];
    if ((st = interaction_acceleration(it, w->Qs)) != GM_OK) return st;
    for (size_t i = 3; i < 3 * n; ++i)
      add(&V[i], cV ? &cV[i] : NULL, (side ? -coef : coef) * w->accel[i]);
  }
  w->force_valid = 0;
  return GM_OK;
}

/* Internal state from the barycentric y: coordinates, then C⁻¹ (made for step h). */
static gm_status load(gm_integrator *it, const double *y, double h) {
  ni_work *w = it->work;
  const size_t n = w->n;
  double *P = w->Vo; /* scratch */
  if (w->coordinates == GM_COORDINATES_JACOBI)
    gm_jacobi_from_barycentric(n, w->m, w->eta, y, y + 3 * n, w->Q, P);
  else
    gm_heliocentric_from_barycentric(n, w->m, y, y + 3 * n, w->Q, P);
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) w->V[3 * i + k] = P[3 * i + k] / w->mr[i];
  memset(w->cQ, 0, 3 * n * sizeof(double));
  memset(w->cV, 0, 3 * n * sizeof(double));
  w->force_valid = 0;
  w->inv_r_valid = 0;
  w->pending = 0.0;
  w->h_loaded = h;
  w->loaded = 1;
  if (w->traits->n_corrector > 0 || w->traits->sabac_g != 0.0) {
    gm_status st = w->traits->sabac_g != 0.0 ? sabac_kick(it, w->Q, w->V, NULL, h, -0.5)
                                             : corrector(it, w->Q, w->V, h, 1);
    if (st != GM_OK) {
      w->loaded = 0;
      return st;
    }
  }
  return GM_OK;
}

/* Apply the drift the last step owes to the internal state. */
static gm_status flush(gm_integrator *it) {
  ni_work *w = it->work;
  if (w->pending == 0.0) return GM_OK;
  gm_status st = drift(it, w->Q, w->V, it->compensated ? w->cQ : NULL,
                       it->compensated ? w->cV : NULL, w->pending);
  if (st == GM_OK) w->pending = 0.0;
  return st;
}

/* The corrector is made for one step size: a new one re-corrects the internal state. */
static gm_status change_step(gm_integrator *it, double h) {
  ni_work *w = it->work;
  gm_status st = flush(it);
  if (w->traits->sabac_g != 0.0) {
    if (st == GM_OK) st = sabac_kick(it, w->Q, w->V, NULL, w->h_loaded, 0.5);
    if (st == GM_OK) st = sabac_kick(it, w->Q, w->V, NULL, h, -0.5);
  } else {
    if (st == GM_OK) st = corrector(it, w->Q, w->V, w->h_loaded, 0);
    if (st == GM_OK) st = corrector(it, w->Q, w->V, h, 1);
  }
  if (st != GM_OK) {
    w->loaded = 0;
    return st;
  }
  w->h_loaded = h;
  return GM_OK;
}

/* The barycentric state of the internal one (through C) into y_out. */
static gm_status output(gm_integrator *it, double *y_out) {
  ni_work *w = it->work;
  const size_t n = w->n, bytes = 3 * n * sizeof(double);
  memcpy(w->Qo, w->Q, bytes);
  memcpy(w->Vo, w->V, bytes);
  if (it->compensated) /* the carries belong to the state */
    for (size_t i = 0; i < 3 * n; ++i) {
      w->Qo[i] += w->cQ[i];
      w->Vo[i] += w->cV[i];
    }
  if (w->pending != 0.0) {
    gm_status st = drift(it, w->Qo, w->Vo, NULL, NULL, w->pending);
    if (st != GM_OK) return st;
  }
  if (w->traits->n_corrector > 0) {
    gm_status st = corrector(it, w->Qo, w->Vo, w->h_loaded, 0);
    w->force_valid = 0;
    if (st != GM_OK) return st;
  }
  if (w->traits->sabac_g != 0.0) {
    gm_status st = sabac_kick(it, w->Qo, w->Vo, NULL, w->h_loaded, 0.5);
    if (st != GM_OK) return st;
  }
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) w->Vo[3 * i + k] *= w->mr[i]; /* momenta */
  if (w->coordinates == GM_COORDINATES_JACOBI)
    gm_jacobi_to_barycentric(n, w->m, w->eta, w->Qo, w->Vo, y_out, y_out + 3 * n);
  else
    gm_heliocentric_to_barycentric(n, w->m, w->Qo, w->Vo, y_out, y_out + 3 * n);
  return GM_OK;
}

/* ---- steps ------------------------------------------------------------------------------- */

/* One step of the operation list. A step that ends with a drift leaves it owed (w->pending)
 * and the next step starts with it, merged with its own first drift: two Kepler drifts of the
 * same orbit compose exactly, so ABA rows make one drift per step fewer. Outputs apply the
 * owed drift to their copy of the state, so the internal state (and the run) is the same
 * however often it is observed. */
static gm_status internal_step(gm_integrator *it, double h) {
  ni_work *w = it->work;
  double *cQ = it->compensated ? w->cQ : NULL, *cV = it->compensated ? w->cV : NULL;
  size_t k = 0, end = w->n_ops;
  if (w->traits->sabac_g != 0.0) { /* the two half correctors between steps, merged */
    gm_status st = flush(it);
    if (st == GM_OK) st = sabac_kick(it, w->Q, w->V, cV, h, 1.0);
    if (st != GM_OK) return st;
  }
  if (w->fsal && w->force_valid) { /* the first kick's acceleration is the last one's */
    add_all(3 * (w->n - 1), w->V + 3, cV ? cV + 3 : NULL, w->ops[0].coef * h, w->accel + 3);
    k = 1;
  }
  const int owes = end > 1 && !w->ops[end - 1].kick;
  if (owes) --end;
  for (; k < end; ++k) {
    const ni_op op = w->ops[k];
    double dt = op.coef * h;
    if (k == 0 && !op.kick) dt += w->pending, w->pending = 0.0;
    if (w->pending != 0.0) { /* a row that starts with a kick */
      gm_status st = flush(it);
      if (st != GM_OK) return st;
    }
    gm_status st = op.kick ? kick(it, w->Q, w->V, cQ, cV, dt) : drift(it, w->Q, w->V, cQ, cV, dt);
    if (st != GM_OK) return st;
  }
  if (owes) w->pending += w->ops[w->n_ops - 1].coef * h;
  if (!w->fsal) w->force_valid = 0;
  return GM_OK;
}

/* The state before a step, for a step that fails (the carries only where a run uses them:
 * they stay 0 otherwise). */
static void save(ni_work *w, int compensated) {
  const size_t bytes = 3 * w->n * sizeof(double);
  memcpy(w->Q_save, w->Q, bytes);
  memcpy(w->V_save, w->V, bytes);
  if (compensated) {
    memcpy(w->cQ_save, w->cQ, bytes);
    memcpy(w->cV_save, w->cV, bytes);
  }
  w->pending_save = w->pending;
}

static void restore(ni_work *w, int compensated) {
  const size_t bytes = 3 * w->n * sizeof(double);
  memcpy(w->Q, w->Q_save, bytes);
  memcpy(w->V, w->V_save, bytes);
  if (compensated) {
    memcpy(w->cQ, w->cQ_save, bytes);
    memcpy(w->cV, w->cV_save, bytes);
  }
  w->pending = w->pending_save;
  w->force_valid = 0;
  w->inv_r_valid = 0;
}

static gm_status prepare(gm_integrator *it, const double *y, double h) {
  ni_work *w = it->work;
  if (!w->loaded) return load(it, y, h);
  if ((w->traits->n_corrector > 0 || w->traits->sabac_g != 0.0) && h != w->h_loaded)
    return change_step(it, h);
  return GM_OK;
}

/* x·0 is 0 for finite x and NaN otherwise, so one sum without branches tells (checked every
 * step, to name the step where the state stopped being finite). */
static int finite_state(const ni_work *w) {
  double zero = 0.0;
  for (size_t i = 0; i < 3 * w->n; ++i) zero += w->Q[i] * 0.0 + w->V[i] * 0.0;
  return zero == 0.0;
}

static gm_status step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                      double *delta) {
  (void)t;
  ni_work *w = it->work;
  gm_status st = prepare(it, y, h);
  if (st != GM_OK) return st;
  save(w, it->compensated);
  st = internal_step(it, h);
  if (st == GM_OK && !finite_state(w))
    st = gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                 "the state became non-finite in the step from t = %.17g", it->t);
  if (st == GM_OK) st = output(it, delta != NULL ? delta : y_new);
  if (st != GM_OK) {
    restore(w, it->compensated);
    return st;
  }
  if (delta != NULL) /* the driver adds delta to y; the internal state is the reference */
    for (size_t i = 0; i < it->n; ++i) delta[i] -= y[i];
  return GM_OK;
}

/* Steps k_from+1 .. k_to in the internal state, one output at the end (or at a failure: the
 * last good step's). */
static gm_status run(gm_integrator *it, const gm_run *r, size_t k_from, size_t k_to) {
  ni_work *w = it->work;
  gm_status st = prepare(it, it->y, r->h);
  if (st != GM_OK) return st;
  size_t k = k_from + 1;
  for (; k <= k_to; ++k) {
    save(w, it->compensated);
    st = internal_step(it, r->h);
    if (st == GM_OK && !finite_state(w))
      st = gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                   "the state became non-finite in the step from t = %.17g",
                   gm_run_time(r, k - 1));
    if (st != GM_OK) {
      restore(w, it->compensated);
      break;
    }
  }
  const size_t done = k - (k_from + 1);
  if (done == 0) return st;
  char message[GM_ERRMSG_SIZE];
  memcpy(message, it->errmsg, sizeof message);
  gm_status out = output(it, it->y_next);
  if (out != GM_OK) {
    w->loaded = 0;
    return out;
  }
  double *tmp = it->y;
  it->y = it->y_next;
  it->y_next = tmp;
  it->t = gm_run_time(r, k_from + done);
  it->step_index += done;
  it->stats.steps += done;
  if (st != GM_OK) memcpy(it->errmsg, message, sizeof message);
  return st;
}

/* it keeps its own state and compensation carries, so run() serves compensated runs too */
const gm_stepper gm_near_integrable_stepper = {init, step, release, invalidate, run, NULL, 1};
