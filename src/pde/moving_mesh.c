/* The space–time adaptive variational integrator of u_tt = u_xx (geomint/pde_moving_mesh.h).
 *
 * Discrete action (seed 004 "Variational integrators", Lagrangian (62), rectangle quadrature at
 * the corner A, forward differences): S = Σ_n Σ_j L(n, j), one term per cell with corners
 * A = (tⁿ, xⁿ_j, uⁿ_j), B = (tⁿ, xⁿ_{j+1}, uⁿ_{j+1}), C = (t^{n+1}, x^{n+1}_j, u^{n+1}_j):
 *   Δt = t^{n+1} − tⁿ, Δx = x_B − x_A, a = (u_B − u_A)/Δx (u_x on layer n),
 *   u_t = [(u_C − u_A) − a(x_C − x_A)]/Δt (along AC, the x-motion of the node taken out),
 *   L = Δt Δx ½(u_t² − a²).
 * The seed's (66)/(67a)–(67c) are ∂S/∂uⁿ_j = 0 (EL), ∂S/∂xⁿ_j = 0 (X, momentum) and
 * ∂S/∂tⁿ = 0 (E, energy: one per layer, the layers being flat); they involve strips n−1 and n
 * and are solved for layer n+1. The cell gradient below was checked against a computer-algebra
 * differentiation and the Jacobian against central differences (branch invariant-mmvi-wip;
 * tests/unit/test_pde_moving_mesh.c checks the Jacobian again).
 *
 * EQUIDISTRIBUTE adds, as Tyranowski & Desbrun's Lagrange-multiplier strategy (Mathematics 7
 * (2019) 642), the constraints gⱼ = ℓ²ⱼ − ℓ²ⱼ₋₁ = 0 on every layer, ℓ²ₖ = Δxₖ² + α²Δuₖ² the
 * squared arc length of cell k, with the terms Σₖ λⁿₖ ∂gₖ/∂(uⁿⱼ, xⁿⱼ) in the EL and X rows.
 * Unknowns of a step: u^{n+1}, x^{n+1}, λⁿ (block of 3 per node), t^{n+1} (border). On a ring
 * Σⱼ gⱼ ≡ 0, so node 0 carries no constraint (λ₀ = 0); the layer's rigid translation, which
 * every gⱼ leaves free, is fixed by the sum of the X rows, i.e. momentum conservation.
 * TIME_ADAPTIVE replaces the X rows by x^{n+1}_j = xⁿ_j and keeps EL and E: the time-adaptive
 * (energy-preserving) VI of the seed's ODE section on a fixed spatial grid. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/pde_moving_mesh.h"
#include "pde/internal.h"

enum { T0, T1, XA, XB, XC, UA, UB, UC };
enum { M_T0, M_XA, M_XB, M_UA, M_UB }; /* rows of the mixed block: layer-n variables */
enum { N_T1, N_XC, N_UC };             /* its columns: layer-(n+1) variables */

typedef struct cell {
  double g[8];    /* ∂L/∂(t0, t1, xA, xB, xC, uA, uB, uC) */
  double m[5][3]; /* ∂²L/∂(t0, xA, xB, uA, uB)∂(t1, xC, uC) */
  double ut, a, dx;
} cell;

/* The gradient of one cell and (mixed != 0) its mixed block. With Q = u_t s + Δt a,
 * s = x_C − x_A:
 *   ∂L/∂t0 = −∂L/∂t1 = ½Δx(u_t² + a²),  ∂L/∂u_C = Δx u_t,  ∂L/∂x_C = −Δx u_t a,
 *   ∂L/∂u_A = −Δx u_t + Q,  ∂L/∂u_B = −Q,
 *   ∂L/∂x_A = −½Δt(u_t² − a²) + Δx u_t a − aQ,  ∂L/∂x_B = ½Δt(u_t² − a²) + aQ. */
static void cell_eval(double t0, double t1, double xA, double xB, double xC, double uA,
                      double uB, double uC, cell *c, int mixed) {
  double dt = t1 - t0, dx = xB - xA, a = (uB - uA) / dx, s = xC - xA;
  double ut = ((uC - uA) - a * s) / dt, Q = ut * s + dt * a, lag = 0.5 * (ut * ut - a * a);
  c->ut = ut;
  c->a = a;
  c->dx = dx;
  c->g[T0] = 0.5 * dx * (ut * ut + a * a);
  c->g[T1] = -c->g[T0];
  c->g[UC] = dx * ut;
  c->g[XC] = -dx * ut * a;
  c->g[UA] = -dx * ut + Q;
  c->g[UB] = -Q;
  c->g[XA] = -dt * lag + dx * ut * a - a * Q;
  c->g[XB] = dt * lag + a * Q;
  if (!mixed) return;
  for (int y = 0; y < 3; y++) {
    /* ∂u_t, ∂s, ∂Δt with respect to t1, x_C, u_C */
    double dut = y == N_T1 ? -ut / dt : y == N_XC ? -a / dt : 1.0 / dt;
    double ds = y == N_XC ? 1.0 : 0.0, dT = y == N_T1 ? 1.0 : 0.0;
    double dQ = dut * s + ut * ds + dT * a;
    c->m[M_T0][y] = dx * ut * dut;
    c->m[M_UA][y] = -dx * dut + dQ;
    c->m[M_UB][y] = -dQ;
    c->m[M_XA][y] = -dT * lag - dt * ut * dut + dx * a * dut - a * dQ;
    c->m[M_XB][y] = dT * lag + dt * ut * dut + a * dQ;
  }
}

struct gm_moving_mesh {
  size_t n, nc; /* nodes, cells (n periodic, n − 1 Dirichlet) */
  double L;
  gm_moving_mesh_options opt;
  double t[3];         /* t of layers n−1, n, n+1 (slots rotate) */
  double *x[3], *u[3]; /* owned, n each */
  int old, cur, nxt;
  double u_end[2], x_end[2]; /* Dirichlet end values */
  cell *cells;               /* strip n (owned, nc) */
  double *gu_prev, *gx_prev; /* ∂/∂(u, x)_C of strip n−1, per node (owned, n each) */
  double *lam;               /* λⁿ (owned, n) */
  double *dgx, *dgu;         /* ∂gⱼ/∂(x, u)_{j−1, j, j+1} on layer n (owned, 3n each) */
  double *r, *bcol, *crow;   /* 3n each (owned) */
  size_t *pos;               /* ring positions (owned, n) */
  gm_band band;
  double energy, momentum;   /* of the strip between the two newest layers */
  gm_moving_mesh_stats stats;
  gm_moving_mesh_observer_fn obs;
  void *obs_ctx;
  size_t obs_every;
};

gm_moving_mesh_options gm_moving_mesh_options_defaults(void) {
  gm_moving_mesh_options o = {GM_MOVING_MESH_SEED, 0.0, 0.0, 0, 1e-12, 30};
  return o;
}

static int constrained(const gm_moving_mesh *m, size_t j) {
  if (m->opt.kind != GM_MOVING_MESH_EQUIDISTRIBUTE) return 0;
  return m->opt.dirichlet ? j >= 1 && j + 1 < m->n : j >= 1;
}
static int end_node(const gm_moving_mesh *m, size_t j) {
  return m->opt.dirichlet && (j == 0 || j + 1 == m->n);
}
/* x of node j + 1 (the ring closes with + L) */
static double x_next(const gm_moving_mesh *m, const double *x, size_t j) {
  return j + 1 == m->n ? x[0] + m->L : x[j + 1];
}
static size_t next(const gm_moving_mesh *m, size_t j) { return j + 1 == m->n ? 0 : j + 1; }
static size_t prev(const gm_moving_mesh *m, size_t j) { return j == 0 ? m->n - 1 : j - 1; }

/* Cell j of the strip between slots lo (layer n) and hi (layer n+1). */
static void strip_cell(const gm_moving_mesh *m, int lo, int hi, size_t j, cell *c, int mixed) {
  cell_eval(m->t[lo], m->t[hi], m->x[lo][j], x_next(m, m->x[lo], j), m->x[hi][j], m->u[lo][j],
            m->u[lo][next(m, j)], m->u[hi][j], c, mixed);
}

/* Energy and momentum of the strip between slots lo and hi, and its C-derivatives, which the
 * next step's EL and X rows need. */
static void strip_invariants(gm_moving_mesh *m, int lo, int hi) {
  double e = 0.0, p = 0.0;
  memset(m->gu_prev, 0, m->n * sizeof(double));
  memset(m->gx_prev, 0, m->n * sizeof(double));
  for (size_t j = 0; j < m->nc; j++) {
    cell c;
    strip_cell(m, lo, hi, j, &c, 0);
    e += c.g[T0];
    p += c.g[XC];
    m->gu_prev[j] = c.g[UC];
    m->gx_prev[j] = c.g[XC];
  }
  m->energy = e;
  m->momentum = p;
}

/* The constraint gⱼ = ℓ²ⱼ − ℓ²ⱼ₋₁ of layer slot s and (d != NULL) its derivatives with respect
 * to (x, u) of nodes j − 1, j, j + 1. */
static double constraint(const gm_moving_mesh *m, int s, size_t j, double *dx3, double *du3) {
  const double *x = m->x[s], *u = m->u[s];
  size_t jm = prev(m, j), jp = next(m, j);
  double a2 = m->opt.alpha * m->opt.alpha;
  double dxm = x[j] - (j == 0 ? x[jm] - m->L : x[jm]), dxp = x_next(m, x, j) - x[j];
  double dum = u[j] - u[jm], dup = u[jp] - u[j];
  if (dx3 != NULL) {
    dx3[0] = 2.0 * dxm;
    dx3[1] = -2.0 * dxp - 2.0 * dxm;
    dx3[2] = 2.0 * dxp;
    du3[0] = 2.0 * a2 * dum;
    du3[1] = -2.0 * a2 * (dup + dum);
    du3[2] = 2.0 * a2 * dup;
  }
  return dxp * dxp + a2 * dup * dup - dxm * dxm - a2 * dum * dum;
}

void gm_moving_mesh_free(gm_moving_mesh *m) {
  if (m == NULL) return;
  for (int k = 0; k < 3; k++) {
    free(m->x[k]);
    free(m->u[k]);
  }
  free(m->cells);
  free(m->gu_prev);
  free(m->gx_prev);
  free(m->lam);
  free(m->dgx);
  free(m->dgu);
  free(m->r);
  free(m->bcol);
  free(m->crow);
  free(m->pos);
  gm_band_release(&m->band);
  free(m);
}

double gm_moving_mesh_dt_bound(size_t n, const double *x, double length, int dirichlet) {
  if (x == NULL || n < 2) return 0.0;
  double h = INFINITY;
  for (size_t j = 0; j + 1 < n; j++) h = fmin(h, x[j + 1] - x[j]);
  if (!dirichlet) h = fmin(h, x[0] + length - x[n - 1]);
  return h;
}

gm_status gm_moving_mesh_create(size_t n, const double *x, double length, const double *u0,
                                const double *ut0, const gm_moving_mesh_options *o,
                                gm_moving_mesh **out, gm_error *err) {
  if (out != NULL) *out = NULL;
  if (out == NULL || x == NULL || u0 == NULL || ut0 == NULL || o == NULL)
    return gm_error_set(err, GM_EINVAL, "moving mesh: NULL argument");
  if (n < 4 || n > ((size_t)1 << 24))
    return gm_error_set(err, GM_EINVAL, "moving mesh: %zu nodes (need 4 .. 2^24)", n);
  if (o->kind != GM_MOVING_MESH_SEED && o->kind != GM_MOVING_MESH_EQUIDISTRIBUTE &&
      o->kind != GM_MOVING_MESH_TIME_ADAPTIVE)
    return gm_error_set(err, GM_EINVAL, "moving mesh: unknown kind %d", (int)o->kind);
  if (!o->dirichlet && !(isfinite(length) && length > 0.0))
    return gm_error_set(err, GM_EINVAL, "moving mesh: period length = %g must be finite and "
                        "> 0", length);
  if (!(isfinite(o->alpha) && o->alpha >= 0.0))
    return gm_error_set(err, GM_EINVAL, "moving mesh: alpha = %g must be finite and >= 0",
                        o->alpha);
  if (!(o->newton_tol > 0.0 && o->newton_tol < 1.0) || o->newton_max_iter == 0)
    return gm_error_set(err, GM_EINVAL, "moving mesh: newton_tol in (0, 1) and "
                        "newton_max_iter >= 1 needed (got %g, %zu)", o->newton_tol,
                        o->newton_max_iter);
  size_t bad = gm_first_nonfinite(n, x);
  if (bad != n)
    return gm_error_set(err, GM_EDOMAIN, "moving mesh: node %zu is not finite", bad);
  bad = gm_first_nonfinite(n, u0);
  if (bad == n) bad = gm_first_nonfinite(n, ut0);
  if (bad != n)
    return gm_error_set(err, GM_EDOMAIN, "moving mesh: initial data not finite at node %zu",
                        bad);
  for (size_t j = 0; j + 1 < n; j++)
    if (!(x[j + 1] > x[j]))
      return gm_error_set(err, GM_EINVAL, "moving mesh: nodes not increasing at %zu (%g, %g)",
                          j, x[j], x[j + 1]);
  double bound = gm_moving_mesh_dt_bound(n, x, length, o->dirichlet);
  if (!o->dirichlet && !(bound > 0.0))
    return gm_error_set(err, GM_EINVAL, "moving mesh: the ring does not close: x[n-1] = %g "
                        ">= x[0] + length = %g", x[n - 1], x[0] + length);
  if (!(isfinite(o->dt) && o->dt > 0.0))
    return gm_error_set(err, GM_EINVAL, "moving mesh: dt = %g must be finite and > 0", o->dt);
  if (o->dt > bound)
    return gm_error_set(err, GM_EINVAL, "moving mesh: dt = %g is above the stability bound of "
                        "the start, min dx = %g (wave speed 1)", o->dt, bound);
  gm_moving_mesh *m = calloc(1, sizeof *m);
  if (m == NULL) return gm_error_set(err, GM_ENOMEM, "moving mesh: out of memory");
  m->n = n;
  m->nc = o->dirichlet ? n - 1 : n;
  m->L = o->dirichlet ? x[n - 1] - x[0] : length;
  m->opt = *o;
  int fail = 0;
  for (int k = 0; k < 3; k++) {
    m->x[k] = malloc(n * sizeof(double));
    m->u[k] = malloc(n * sizeof(double));
    fail |= m->x[k] == NULL || m->u[k] == NULL;
  }
  m->cells = malloc(n * sizeof *m->cells);
  m->gu_prev = malloc(n * sizeof(double));
  m->gx_prev = malloc(n * sizeof(double));
  m->lam = calloc(n, sizeof(double));
  m->dgx = malloc(3 * n * sizeof(double));
  m->dgu = malloc(3 * n * sizeof(double));
  m->r = malloc(3 * n * sizeof(double));
  m->bcol = malloc(3 * n * sizeof(double));
  m->crow = malloc(3 * n * sizeof(double));
  m->pos = malloc(n * sizeof *m->pos);
  fail |= m->cells == NULL || m->gu_prev == NULL || m->gx_prev == NULL || m->lam == NULL ||
          m->dgx == NULL || m->dgu == NULL || m->r == NULL || m->bcol == NULL ||
          m->crow == NULL || m->pos == NULL;
  /* ring neighbours are at most two blocks of 3 apart: kl = ku = 3·3 − 1 */
  if (fail || gm_band_init(&m->band, 3 * n, 8, 8) != GM_OK) {
    gm_moving_mesh_free(m);
    return gm_error_set(err, GM_ENOMEM, "moving mesh: out of memory (n = %zu)", n);
  }
  gm_ring_positions(n, m->pos);
  m->old = 0;
  m->cur = 1;
  m->nxt = 2;
  double dt = o->dt;
  m->t[0] = 0.0;
  m->t[1] = dt;
  for (size_t j = 0; j < n; j++) {
    m->x[0][j] = m->x[1][j] = x[j];
    m->u[0][j] = u0[j];
    if (end_node(m, j)) {
      m->u[1][j] = u0[j];
      continue;
    }
    size_t jm = prev(m, j), jp = next(m, j);
    double hm = x[j] - (j == 0 ? x[jm] - m->L : x[jm]), hp = x_next(m, x, j) - x[j];
    double uxx = 2.0 * ((u0[jp] - u0[j]) / hp - (u0[j] - u0[jm]) / hm) / (hp + hm);
    m->u[1][j] = u0[j] + dt * ut0[j] + 0.5 * dt * dt * uxx;
  }
  m->u_end[0] = u0[0];
  m->u_end[1] = u0[n - 1];
  m->x_end[0] = x[0];
  m->x_end[1] = x[n - 1];
  strip_invariants(m, 0, 1);
  *out = m;
  return GM_OK;
}

gm_status gm_moving_mesh_set_observer(gm_moving_mesh *m, size_t every,
                                      gm_moving_mesh_observer_fn fn, void *ctx, gm_error *err) {
  if (m == NULL || (fn != NULL && every == 0))
    return gm_error_set(err, GM_EINVAL, "moving mesh: NULL solver or observer every = 0");
  m->obs = fn;
  m->obs_ctx = ctx;
  m->obs_every = every;
  return GM_OK;
}

/* Residual of layer n's equations at the iterate in slot nxt: r in ring order (u, x, λ rows
 * per node), *rt the energy row; returns the max norm of all. mixed: also the cells' mixed
 * blocks for the Jacobian. */
static double residual(gm_moving_mesh *m, double e_prev, double *rt, int mixed) {
  size_t n = m->n;
  int c = m->cur, x = m->nxt;
  for (size_t j = 0; j < m->nc; j++) strip_cell(m, c, x, j, &m->cells[j], mixed);
  double e = 0.0, rmax = 0.0;
  for (size_t j = 0; j < m->nc; j++) e += m->cells[j].g[T0];
  for (size_t j = 0; j < n; j++) {
    double *r = &m->r[3 * m->pos[j]];
    if (end_node(m, j)) {
      int k = j == 0 ? 0 : 1;
      r[0] = m->u[x][j] - m->u_end[k];
      r[1] = m->x[x][j] - m->x_end[k];
      r[2] = m->lam[j];
    } else {
      const cell *cj = &m->cells[j], *cm = &m->cells[prev(m, j)];
      r[0] = cj->g[UA] + cm->g[UB] + m->gu_prev[j];
      /* TIME_ADAPTIVE: the X row is replaced by x^{n+1}_j = xⁿ_j (the grid stays) */
      r[1] = m->opt.kind == GM_MOVING_MESH_TIME_ADAPTIVE
                 ? m->x[x][j] - m->x[c][j]
                 : cj->g[XA] + cm->g[XB] + m->gx_prev[j];
      /* Σₖ λₖ ∂gₖ/∂(u, x)ⱼ over k = j − 1, j, j + 1 (entry 2, 1, 0 of gₖ's derivatives) */
      size_t ks[3] = {prev(m, j), j, next(m, j)};
      for (int q = 0; q < 3; q++) {
        size_t k = ks[q];
        if (!constrained(m, k)) continue;
        r[0] += m->lam[k] * m->dgu[3 * k + (size_t)(2 - q)];
        r[1] += m->lam[k] * m->dgx[3 * k + (size_t)(2 - q)];
      }
      r[2] = constrained(m, j) ? constraint(m, x, j, NULL, NULL) : m->lam[j];
    }
    for (int q = 0; q < 3; q++) rmax = fmax(rmax, fabs(r[q]));
  }
  *rt = e - e_prev;
  return fmax(rmax, fabs(*rt));
}

/* The Newton matrix [A b; cᵀ d] at the iterate (after residual(..., mixed = 1)): A into the
 * band, b into bcol, c into crow; d returned. */
static double assemble(gm_moving_mesh *m) {
  size_t n = m->n;
  gm_band_zero(&m->band);
  memset(m->bcol, 0, 3 * n * sizeof(double));
  memset(m->crow, 0, 3 * n * sizeof(double));
  double d = 0.0;
  for (size_t j = 0; j < m->nc; j++) {
    const cell *cj = &m->cells[j];
    size_t c0 = 3 * m->pos[j];
    m->crow[c0] += cj->m[M_T0][N_UC];
    m->crow[c0 + 1] += cj->m[M_T0][N_XC];
    d += cj->m[M_T0][N_T1];
  }
  for (size_t j = 0; j < n; j++) {
    size_t r0 = 3 * m->pos[j], c0 = r0;
    if (end_node(m, j)) {
      for (size_t q = 0; q < 3; q++) gm_band_add(&m->band, r0 + q, c0 + q, 1.0);
      continue;
    }
    size_t jm = prev(m, j), cm0 = 3 * m->pos[jm];
    const cell *cj = &m->cells[j], *cm = &m->cells[jm];
    /* rows u_j, x_j: cell j (its C is node j) through A, cell j−1 (C = node j−1) through B */
    for (int row = 0; row < 2; row++) {
      if (row == 1 && m->opt.kind == GM_MOVING_MESH_TIME_ADAPTIVE) {
        gm_band_add(&m->band, r0 + 1, c0 + 1, 1.0);
        m->bcol[r0 + 1] = 0.0;
        continue;
      }
      int ma = row == 0 ? M_UA : M_XA, mb = row == 0 ? M_UB : M_XB;
      gm_band_add(&m->band, r0 + (size_t)row, c0, cj->m[ma][N_UC]);
      gm_band_add(&m->band, r0 + (size_t)row, c0 + 1, cj->m[ma][N_XC]);
      gm_band_add(&m->band, r0 + (size_t)row, cm0, cm->m[mb][N_UC]);
      gm_band_add(&m->band, r0 + (size_t)row, cm0 + 1, cm->m[mb][N_XC]);
      m->bcol[r0 + (size_t)row] = cj->m[ma][N_T1] + cm->m[mb][N_T1];
    }
    size_t ks[3] = {jm, j, next(m, j)};
    for (int q = 0; q < 3; q++) {
      size_t k = ks[q];
      if (!constrained(m, k)) continue;
      size_t ck = 3 * m->pos[k] + 2;
      gm_band_add(&m->band, r0, ck, m->dgu[3 * k + (size_t)(2 - q)]);
      gm_band_add(&m->band, r0 + 1, ck, m->dgx[3 * k + (size_t)(2 - q)]);
    }
    if (constrained(m, j)) {
      double dx3[3], du3[3];
      constraint(m, m->nxt, j, dx3, du3);
      for (int q = 0; q < 3; q++) {
        size_t cq = 3 * m->pos[ks[q]];
        gm_band_add(&m->band, r0 + 2, cq, du3[q]);
        gm_band_add(&m->band, r0 + 2, cq + 1, dx3[q]);
      }
    } else {
      gm_band_add(&m->band, r0 + 2, c0 + 2, 1.0);
    }
  }
  return d;
}

/* The start guess of the next step (constant velocities of t, x, u; λ = 0) and the constraint
 * derivatives of layer n; returns E^{n−1}. */
static double start_step(gm_moving_mesh *m) {
  int o = m->old, c = m->cur, x = m->nxt;
  m->t[x] = 2.0 * m->t[c] - m->t[o];
  for (size_t j = 0; j < m->n; j++) {
    m->x[x][j] = 2.0 * m->x[c][j] - m->x[o][j];
    m->u[x][j] = 2.0 * m->u[c][j] - m->u[o][j];
    m->lam[j] = 0.0;
    if (constrained(m, j)) constraint(m, c, j, &m->dgx[3 * j], &m->dgu[3 * j]);
  }
  return m->energy;
}

static gm_status one_step(gm_moving_mesh *m, gm_error *err) {
  size_t n = m->n, step = m->stats.steps + 1;
  int c = m->cur, x = m->nxt;
  double e_prev = start_step(m), rt, prev_dmax = INFINITY;
  for (size_t it = 1; it <= m->opt.newton_max_iter; it++) {
    double rmax = residual(m, e_prev, &rt, 1);
    if (!isfinite(rmax))
      return gm_error_set(err, GM_EDOMAIN, "moving mesh step %zu (t = %.9g): non-finite "
                          "residual", step, m->t[c]);
    double d = assemble(m);
    if (gm_band_factor(&m->band) != GM_OK)
      return gm_error_set(err, GM_ESINGULAR, "moving mesh step %zu (t = %.9g): the Newton "
                          "matrix is singular", step, m->t[c]);
    gm_band_solve(&m->band, m->r);    /* y = A⁻¹ r */
    gm_band_solve(&m->band, m->bcol); /* z = A⁻¹ b */
    double cy = 0.0, cz = 0.0;
    for (size_t i = 0; i < 3 * n; i++) {
      cy += m->crow[i] * m->r[i];
      cz += m->crow[i] * m->bcol[i];
    }
    if (d - cz == 0.0)
      return gm_error_set(err, GM_ESINGULAR, "moving mesh step %zu: the energy row's Schur "
                          "complement is 0", step);
    double ddt = (rt - cy) / (d - cz), dmax = fabs(ddt), vmax = fabs(m->t[x]);
    m->t[x] -= ddt;
    for (size_t j = 0; j < n; j++) {
      size_t r0 = 3 * m->pos[j];
      double du = m->r[r0] - m->bcol[r0] * ddt, dx = m->r[r0 + 1] - m->bcol[r0 + 1] * ddt;
      m->u[x][j] -= du;
      m->x[x][j] -= dx;
      m->lam[j] -= m->r[r0 + 2] - m->bcol[r0 + 2] * ddt;
      dmax = fmax(dmax, fmax(fabs(du), fabs(dx)));
      vmax = fmax(vmax, fmax(fabs(m->u[x][j]), fabs(m->x[x][j])));
    }
    m->stats.newton_iterations++;
    if (!isfinite(dmax))
      return gm_error_set(err, GM_EDOMAIN, "moving mesh step %zu (t = %.9g): non-finite Newton "
                          "update", step, m->t[c]);
    /* converged, or at the round-off floor of the banded solve (corrections below 1e-9
     * relative that no longer halve) */
    int floor = dmax < 1e-9 * (1.0 + vmax) && dmax > 0.5 * prev_dmax;
    prev_dmax = dmax;
    if (dmax <= m->opt.newton_tol * (1.0 + vmax) || floor) {
      double rfin = residual(m, e_prev, &rt, 0);
      m->stats.max_residual = fmax(m->stats.max_residual, rfin);
      if (!(m->t[x] > m->t[c]))
        return gm_error_set(err, GM_EDOMAIN, "moving mesh step %zu: t^{n+1} = %.9g is not "
                            "after t^n = %.9g", step, m->t[x], m->t[c]);
      for (size_t j = 0; j < m->nc; j++) {
        double xb = x_next(m, m->x[x], j);
        if (!(xb > m->x[x][j]))
          return gm_error_set(err, GM_EDOMAIN, "moving mesh step %zu: the grid folds at "
                              "node %zu (x = %.9g, next %.9g)", step, j, m->x[x][j], xb);
      }
      return GM_OK;
    }
  }
  return gm_error_set(err, GM_ENOCONV, "moving mesh step %zu (t = %.9g): Newton did not "
                      "converge in %zu iterations (last correction %.3g)", step, m->t[c],
                      m->opt.newton_max_iter, prev_dmax);
}

gm_status gm_moving_mesh_advance(gm_moving_mesh *m, size_t n_steps, gm_error *err) {
  if (m == NULL) return gm_error_set(err, GM_EINVAL, "moving mesh: NULL solver");
  for (size_t s = 0; s < n_steps; s++) {
    gm_status st = one_step(m, err);
    if (st != GM_OK) {
      m->stats.failed_steps++;
      return st; /* slots old, cur untouched: the last completed layers */
    }
    int o = m->old;
    m->old = m->cur;
    m->cur = m->nxt;
    m->nxt = o;
    strip_invariants(m, m->old, m->cur);
    m->stats.steps++;
    if (m->obs != NULL && m->stats.steps % m->obs_every == 0) {
      int rc = m->obs(m, m->obs_ctx);
      if (rc != 0)
        return gm_error_set(err, GM_ECALLBACK, "moving mesh: observer returned %d at step %zu",
                            rc, m->stats.steps);
    }
  }
  return GM_OK;
}

gm_status gm_moving_mesh_conditioning(gm_moving_mesh *m, double *sigma_min, double *cond,
                                      gm_error *err) {
  if (m == NULL || sigma_min == NULL || cond == NULL)
    return gm_error_set(err, GM_EINVAL, "moving mesh conditioning: NULL argument");
  if (m->n > 512)
    return gm_error_set(err, GM_EINVAL, "moving mesh conditioning: n = %zu > 512 (dense SVD)",
                        m->n);
  size_t N = 3 * m->n + 1;
  double *A = calloc(N * N, sizeof *A), *s = malloc(N * sizeof *s);
  double *sup = malloc(N * sizeof *sup);
  if (A == NULL || s == NULL || sup == NULL) {
    free(A);
    free(s);
    free(sup);
    return gm_error_set(err, GM_ENOMEM, "moving mesh conditioning: out of memory");
  }
  /* the matrix at the start guess, without disturbing the solver's layers */
  double e_prev = start_step(m), rt;
  residual(m, e_prev, &rt, 1);
  double d = assemble(m);
  const gm_band *b = &m->band;
  for (size_t r = 0; r + 1 < N; r++) {
    for (size_t c = r >= b->kl ? r - b->kl : 0; c <= r + b->ku && c + 1 < N; c++)
      A[r * N + c] = b->ab[r * b->w + (c + b->kl - r)];
    A[r * N + N - 1] = m->bcol[r];
    A[(N - 1) * N + r] = m->crow[r];
  }
  A[N * N - 1] = d;
  for (size_t r = 0; r < N; r++) {
    double mx = 0.0;
    for (size_t c = 0; c < N; c++) mx = fmax(mx, fabs(A[r * N + c]));
    if (mx > 0.0)
      for (size_t c = 0; c < N; c++) A[r * N + c] /= mx;
  }
  lapack_int info = LAPACKE_dgesvd(LAPACK_ROW_MAJOR, 'N', 'N', (lapack_int)N, (lapack_int)N, A,
                                   (lapack_int)N, s, NULL, 1, NULL, 1, sup);
  gm_status st = GM_OK;
  if (info != 0) {
    st = gm_error_set(err, GM_ENOCONV, "moving mesh conditioning: dgesvd info %d", (int)info);
  } else {
    *sigma_min = s[N - 1];
    *cond = s[N - 1] > 0.0 ? s[0] / s[N - 1] : INFINITY;
  }
  free(A);
  free(s);
  free(sup);
  return st;
}

gm_status gm_moving_mesh_equidistribute(size_t n, double x0, double length, double alpha,
                                        int dirichlet, gm_moving_mesh_fn u, const void *ctx,
                                        size_t samples, double *x, gm_error *err) {
  if (u == NULL || x == NULL)
    return gm_error_set(err, GM_EINVAL, "equidistribute: NULL argument");
  if (n < 4 || n > ((size_t)1 << 24) || samples < 16 * n || samples > ((size_t)1 << 28))
    return gm_error_set(err, GM_EINVAL, "equidistribute: n = %zu (4 .. 2^24), samples = %zu "
                        "(16n .. 2^28)", n, samples);
  if (!(isfinite(x0) && isfinite(length) && length > 0.0 && isfinite(alpha) && alpha >= 0.0))
    return gm_error_set(err, GM_EINVAL, "equidistribute: x0 = %g, length = %g (> 0), alpha = %g "
                        "(>= 0) must be finite", x0, length, alpha);
  double *s = malloc((samples + 1) * sizeof *s);
  if (s == NULL) return gm_error_set(err, GM_ENOMEM, "equidistribute: out of memory");
  double h = length / (double)samples, up = u(x0, ctx);
  s[0] = 0.0;
  for (size_t i = 1; i <= samples; i++) {
    double ui = u(x0 + (double)i * h, ctx);
    if (!isfinite(ui)) {
      free(s);
      return gm_error_set(err, GM_EDOMAIN, "equidistribute: u(%g) is not finite",
                          x0 + (double)i * h);
    }
    s[i] = s[i - 1] + sqrt(h * h + alpha * alpha * (ui - up) * (ui - up));
    up = ui;
  }
  double step = s[samples] / (double)(dirichlet ? n - 1 : n);
  size_t i = 0;
  for (size_t k = 0; k < n; k++) {
    double target = (double)k * step;
    while (i + 1 < samples && s[i + 1] < target) i++;
    double f = s[i + 1] > s[i] ? (target - s[i]) / (s[i + 1] - s[i]) : 0.0;
    x[k] = x0 + ((double)i + fmin(fmax(f, 0.0), 1.0)) * h;
  }
  if (dirichlet) x[n - 1] = x0 + length;
  free(s);
  return GM_OK;
}

size_t gm_moving_mesh_n(const gm_moving_mesh *m) { return m->n; }
double gm_moving_mesh_time(const gm_moving_mesh *m) { return m->t[m->cur]; }
const double *gm_moving_mesh_x(const gm_moving_mesh *m) { return m->x[m->cur]; }
const double *gm_moving_mesh_u(const gm_moving_mesh *m) { return m->u[m->cur]; }
double gm_moving_mesh_energy(const gm_moving_mesh *m) { return m->energy; }
double gm_moving_mesh_momentum(const gm_moving_mesh *m) { return m->momentum; }
gm_moving_mesh_stats gm_moving_mesh_get_stats(const gm_moving_mesh *m) { return m->stats; }
