/* The multisymplectic variational integrator of seed 001 §5.1 (notes/001 §1G) for
 * u_tt − u_xx + V'(u) = 0, L = ½u_t² − ½u_x² − V(u), on a rectangular space-time mesh with
 * bilinear tent functions. On the rectangle [x_i, x_{i+1}] × [t_j, t_{j+1}], with the edge
 * differences a = u_{i,j+1} − u_{ij}, b = u_{i+1,j+1} − u_{i+1,j} (in time) and
 * c = u_{i+1,j} − u_{ij}, d = u_{i+1,j+1} − u_{i,j+1} (in space), the bilinear interpolant has
 * u_t linear in ξ between a/Δt and b/Δt, so ∫₀¹((1−ξ)a + ξb)² dξ = (a² + ab + b²)/3 gives, exactly,
 *   L_d = Δx(a² + ab + b²)/(6Δt) − Δt(c² + cd + d²)/(6Δx) − ΔxΔt·¼ΣV(corners)
 * (V by the trapezoid rule: the seed writes L_d as the exact integral, which a general V does not
 * allow; this choice makes the DEL explicit in V'). Summing ∂L_d/∂u_{ij} over the four
 * rectangles that share the node (the four-term DEL of the seed) and dividing by −ΔxΔt:
 *   (1/6)S(δ_t²u)^j_i − (1/6)(δ_x²u^{j−1} + 4δ_x²u^j + δ_x²u^{j+1})_i + V'(u^j_i) = 0,
 * S(z)_i = z_{i−1} + 4z_i + z_{i+1}. With w = u^{j+1} − 2u^j + u^{j−1} this is
 *   A w = δ_x²u^j − V'(u^j),  A = S/(6Δt²) − D/(6Δx²) (circulant, SPD),
 * D(z)_i = z_{i+1} − 2z_i + z_{i−1} = Δx² δ_x²z_i,
 * since δ_x²u^{j−1} + 4δ_x²u^j + δ_x²u^{j+1} = δ_x²w + 6δ_x²u^j. A has diagonal
 * (4/Δt² + 2/Δx²)/6 and off-diagonals (1/Δt² − 1/Δx²)/6; it is factored once (Thomas with
 * Sherman–Morrison for the corners). Von Neumann on V = 0: cos ωΔt = (2A_x − 2σ/3)/(2A_x + σ/3),
 * A_x = (2 + cos κΔx)/3, σ = (Δt/Δx)² 4 sin²(κΔx/2): |cos| <= 1 iff Δt <= Δx. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pde/internal.h"

struct gm_tentvi {
  size_t n;
  double x0, h, twist, dt;
  gm_tentvi_potential_fn V, dV, d2V;
  const void *ctx;
  double *um, *u, *rhs;           /* levels j−1 (um) and j (u); scratch (owned, n each) */
  double *cp, *z, *diagmod;       /* Thomas factors and the Sherman–Morrison vector (owned) */
  double a_diag, b_off, gamma, vz; /* A's entries, SM γ and 1 + v·z */
  double *Um, *U, *Wm, *W;        /* tangent variations (owned, NULL until set) */
  size_t steps;
};

/* δ_x²-numerator of a twisted (tw) or periodic (tw = 0) field at i */
static double d2x(const gm_tentvi *m, const double *u, size_t i, double tw) {
  size_t n = m->n;
  double left = i == 0 ? u[n - 1] - tw : u[i - 1];
  double right = i == n - 1 ? u[0] + tw : u[i + 1];
  return right - 2.0 * u[i] + left;
}

/* Thomas on T (diagonal diagmod, off-diagonal b) in place, with the stored factors cp */
static void thomas(const gm_tentvi *m, double *r) {
  size_t n = m->n;
  double b = m->b_off;
  r[0] /= m->diagmod[0];
  for (size_t i = 1; i < n; i++) r[i] = (r[i] - b * r[i - 1]) / m->diagmod[i];
  for (size_t i = n - 1; i-- > 0;) r[i] -= m->cp[i] * r[i + 1];
}

/* A x = r in place (cyclic: A = T + u vᵀ, u = (γ, 0…, b), v = (1, 0…, b/γ)) */
static void cyclic_solve(const gm_tentvi *m, double *r) {
  size_t n = m->n;
  if (m->b_off == 0.0) {
    for (size_t i = 0; i < n; i++) r[i] /= m->a_diag;
    return;
  }
  thomas(m, r);
  double f = (r[0] + m->b_off / m->gamma * r[n - 1]) / m->vz;
  for (size_t i = 0; i < n; i++) r[i] -= f * m->z[i];
}

static double second(const gm_tentvi *m, double u) {
  if (m->d2V) return m->d2V(u, m->ctx);
  double e = 1e-5 * (1.0 + fabs(u));
  return (m->dV(u + e, m->ctx) - m->dV(u - e, m->ctx)) / (2.0 * e);
}

void gm_tentvi_free(gm_tentvi *m) {
  if (m == NULL) return;
  free(m->um);
  free(m->u);
  free(m->rhs);
  free(m->cp);
  free(m->z);
  free(m->diagmod);
  free(m->Um);
  free(m->U);
  free(m->Wm);
  free(m->W);
  free(m);
}

gm_status gm_tentvi_create(size_t n, double x0, double h, double twist, double dt,
                           gm_tentvi_potential_fn V, gm_tentvi_potential_fn dV,
                           gm_tentvi_potential_fn d2V, const void *ctx, const double *u0,
                           const double *u1, gm_tentvi **out, gm_error *err) {
  if (out == NULL || V == NULL || dV == NULL || u0 == NULL || u1 == NULL)
    return gm_error_set(err, GM_EINVAL, "tentvi: NULL argument");
  *out = NULL;
  if (n < 4) return gm_error_set(err, GM_EINVAL, "tentvi: n = %zu must be >= 4", n);
  if (!(isfinite(h) && h > 0.0) || !isfinite(x0) || !isfinite(twist))
    return gm_error_set(err, GM_EINVAL, "tentvi: h must be finite and > 0");
  if (!(isfinite(dt) && dt > 0.0))
    return gm_error_set(err, GM_EINVAL, "tentvi: dt = %g must be finite and > 0", dt);
  if (dt > h)
    return gm_error_set(err, GM_EINVAL,
                        "tentvi: dt = %g > dx = %g: the tent-function VI is unstable for "
                        "dt > dx", dt, h);
  for (size_t i = 0; i < n; i++)
    if (!isfinite(u0[i]) || !isfinite(u1[i]))
      return gm_error_set(err, GM_EDOMAIN, "tentvi: initial data not finite at point %zu", i);
  gm_tentvi *m = calloc(1, sizeof *m);
  if (m == NULL) return gm_error_set(err, GM_ENOMEM, "tentvi: out of memory");
  m->n = n;
  m->x0 = x0;
  m->h = h;
  m->twist = twist;
  m->dt = dt;
  m->V = V;
  m->dV = dV;
  m->d2V = d2V;
  m->ctx = ctx;
  m->um = malloc(n * sizeof(double));
  m->u = malloc(n * sizeof(double));
  m->rhs = malloc(n * sizeof(double));
  m->cp = malloc(n * sizeof(double));
  m->z = malloc(n * sizeof(double));
  m->diagmod = malloc(n * sizeof(double));
  if (!m->um || !m->u || !m->rhs || !m->cp || !m->z || !m->diagmod) {
    gm_tentvi_free(m);
    return gm_error_set(err, GM_ENOMEM, "tentvi: out of memory (n = %zu)", n);
  }
  memcpy(m->um, u0, n * sizeof *u0);
  memcpy(m->u, u1, n * sizeof *u1);
  double it2 = 1.0 / (dt * dt), ix2 = 1.0 / (h * h);
  m->a_diag = (4.0 * it2 + 2.0 * ix2) / 6.0;
  m->b_off = (it2 - ix2) / 6.0;
  if (m->b_off != 0.0) {
    /* Sherman–Morrison: T = A with T_00 −= γ, T_{n−1,n−1} −= b²/γ; γ = −a (no cancellation) */
    double b = m->b_off;
    m->gamma = -m->a_diag;
    for (size_t i = 0; i < n; i++) m->diagmod[i] = m->a_diag;
    m->diagmod[0] -= m->gamma;
    m->diagmod[n - 1] -= b * b / m->gamma;
    /* LU of T: diagmod[i] ← pivot, cp[i] = b / pivot */
    m->cp[0] = b / m->diagmod[0];
    for (size_t i = 1; i < n; i++) {
      m->diagmod[i] -= b * m->cp[i - 1];
      m->cp[i] = b / m->diagmod[i];
    }
    for (size_t i = 0; i < n; i++) m->z[i] = 0.0;
    m->z[0] = m->gamma;
    m->z[n - 1] = b;
    thomas(m, m->z);
    m->vz = 1.0 + m->z[0] + b / m->gamma * m->z[n - 1];
  }
  m->steps = 1;
  *out = m;
  return GM_OK;
}

/* one step of the DEL for (um, u) → (u, new); lin: the linearised DEL at base (no twist, V'') */
static void del_step(gm_tentvi *m, double *um, double *u, const double *base, int lin) {
  size_t n = m->n;
  double ix2 = 1.0 / (m->h * m->h);
  for (size_t i = 0; i < n; i++) {
    double force = lin ? second(m, base[i]) * u[i] : m->dV(u[i], m->ctx);
    m->rhs[i] = d2x(m, u, i, lin ? 0.0 : m->twist) * ix2 - force;
  }
  cyclic_solve(m, m->rhs);
  for (size_t i = 0; i < n; i++) {
    double next = 2.0 * u[i] - um[i] + m->rhs[i];
    um[i] = u[i];
    u[i] = next;
  }
}

gm_status gm_tentvi_advance(gm_tentvi *m, size_t n_steps, gm_error *err) {
  if (m == NULL) return gm_error_set(err, GM_EINVAL, "tentvi: NULL solver");
  for (size_t k = 0; k < n_steps; k++) {
    if (m->U != NULL) { /* variations at the current base level, before it moves */
      del_step(m, m->Um, m->U, m->u, 1);
      del_step(m, m->Wm, m->W, m->u, 1);
    }
    del_step(m, m->um, m->u, NULL, 0);
    m->steps++;
    double sum = 0.0; /* NaN or ∞ anywhere makes the sum non-finite */
    for (size_t i = 0; i < m->n; i++) sum += m->u[i] * 0.0;
    if (!isfinite(sum))
      return gm_error_set(err, GM_EDOMAIN, "tentvi: non-finite value at step %zu", m->steps);
  }
  return GM_OK;
}

double gm_tentvi_time(const gm_tentvi *m) { return (double)m->steps * m->dt; }
const double *gm_tentvi_u(const gm_tentvi *m) { return m->u; }
const double *gm_tentvi_u_prev(const gm_tentvi *m) { return m->um; }

double gm_tentvi_energy(const gm_tentvi *m) {
  size_t n = m->n;
  double h = m->h, dt = m->dt, e = 0.0;
  for (size_t i = 0; i < n; i++) {
    size_t ip = (i + 1) % n;
    double tw = i == n - 1 ? m->twist : 0.0;
    double a = m->u[i] - m->um[i], b = m->u[ip] - m->um[ip];
    double c = m->um[ip] + tw - m->um[i], d = m->u[ip] + tw - m->u[i];
    e += h * (a * a + a * b + b * b) / (6.0 * dt * dt) + (c * c + c * d + d * d) / (6.0 * h) +
         0.5 * h * (m->V(m->um[i], m->ctx) + m->V(m->u[i], m->ctx));
  }
  return e;
}

gm_status gm_tentvi_set_variations(gm_tentvi *m, const double *U0, const double *U1,
                                   const double *W0, const double *W1, gm_error *err) {
  if (m == NULL || U0 == NULL || U1 == NULL || W0 == NULL || W1 == NULL)
    return gm_error_set(err, GM_EINVAL, "tentvi: NULL argument");
  size_t n = m->n;
  if (m->U == NULL) {
    m->Um = malloc(n * sizeof(double));
    m->U = malloc(n * sizeof(double));
    m->Wm = malloc(n * sizeof(double));
    m->W = malloc(n * sizeof(double));
    if (!m->Um || !m->U || !m->Wm || !m->W) {
      free(m->Um);
      free(m->U);
      free(m->Wm);
      free(m->W);
      m->Um = m->U = m->Wm = m->W = NULL;
      return gm_error_set(err, GM_ENOMEM, "tentvi: out of memory");
    }
  }
  memcpy(m->Um, U0, n * sizeof *U0);
  memcpy(m->U, U1, n * sizeof *U1);
  memcpy(m->Wm, W0, n * sizeof *W0);
  memcpy(m->W, W1, n * sizeof *W1);
  return GM_OK;
}

double gm_tentvi_symplectic_form(const gm_tentvi *m, double *scale) {
  if (m->U == NULL) return NAN;
  /* M = D₁D₂ L_strip: the a·b-type kinetic terms give −(Δx/(6Δt)) S, the c·d gradient cross
     terms (c on level j, d on level j+1) give +(Δt/(6Δx)) D.
     ω = Σ_i U^j_i (M W^{j+1})_i − W^j_i (M U^{j+1})_i */
  size_t n = m->n;
  double c = -m->h / (6.0 * m->dt), g = m->dt / (6.0 * m->h), w = 0.0, s = 0.0;
  for (size_t i = 0; i < n; i++) {
    size_t ip = (i + 1) % n, im = (i + n - 1) % n;
    double mw = c * (m->W[im] + 4.0 * m->W[i] + m->W[ip]) +
                g * (m->W[im] - 2.0 * m->W[i] + m->W[ip]);
    double mu = c * (m->U[im] + 4.0 * m->U[i] + m->U[ip]) +
                g * (m->U[im] - 2.0 * m->U[i] + m->U[ip]);
    double t1 = m->Um[i] * mw, t2 = m->Wm[i] * mu;
    w += t1 - t2;
    s += fabs(t1) + fabs(t2);
  }
  if (scale != NULL) *scale = s;
  return w;
}
