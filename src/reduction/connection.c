/* Discrete connections on a trivial principal bundle Q = G × S, G = SO(2) or SO(3) (seed 001
 * ch. 4: local form §4.2, horizontal lift Remark 4.2 with the product on the right as corrected
 * in the seed notes §4, extended composition §4.3, exact and mechanical connections §4.4; seed 000
 * §4.2.2 path connections and holonomy). Conventions in include/geomint/reduction.h. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/lie.h"
#include "geomint/reduction.h"

/* ---- the two groups --------------------------------------------------------------------- */

size_t gm_group_size(gm_group_kind g) { return g == GM_GROUP_SO2 ? 1 : g == GM_GROUP_SO3 ? 9 : 0; }
size_t gm_group_dim(gm_group_kind g) { return g == GM_GROUP_SO2 ? 1 : g == GM_GROUP_SO3 ? 3 : 0; }

void gm_group_mul(gm_group_kind g, const double *a, const double *b, double *out) {
  if (g == GM_GROUP_SO2) {
    out[0] = a[0] + b[0];
    return;
  }
  double m[9];
  gm_mat3_mul(a, b, m);
  memcpy(out, m, sizeof m);
}

void gm_group_inv(gm_group_kind g, const double *a, double *out) {
  if (g == GM_GROUP_SO2) {
    out[0] = -a[0];
    return;
  }
  double m[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[3 * i + j] = a[3 * j + i];
  memcpy(out, m, sizeof m);
}

void gm_group_exp(gm_group_kind g, const double *w, double *out) {
  if (g == GM_GROUP_SO2) {
    out[0] = w[0];
    return;
  }
  double m[9];
  gm_so3_exp(w, m);
  memcpy(out, m, sizeof m);
}

void gm_group_log(gm_group_kind g, const double *a, double *w) {
  if (g == GM_GROUP_SO2) {
    w[0] = a[0];
    return;
  }
  double v[3];
  gm_so3_log(a, v);
  memcpy(w, v, sizeof v);
}

double gm_group_distance(gm_group_kind g, const double *a, const double *b) {
  if (g == GM_GROUP_SO2) return fabs(a[0] - b[0]);
  double m[9], w[3];
  gm_mat3_mul_nt(a, b, m);
  gm_so3_log(m, w);
  return gm_vec3_norm(w);
}

/* ---- the local form A(x0, x1) by each rule ------------------------------------------------ */

static gm_status check(const gm_discrete_connection *c, gm_error *err) {
  if (c == NULL || gm_group_size(c->group) == 0 || c->n > GM_DCONN_MAX_SHAPE)
    return gm_error_set(err, GM_EINVAL,
                        "discrete connection: need a group (SO(2) or SO(3)) and n <= %d",
                        GM_DCONN_MAX_SHAPE);
  if (c->n == 0) return GM_OK; /* the pure group case: A = e, no callback */
  int ok = 0;
  switch (c->rule) {
  case GM_DCONN_CALLBACK: ok = c->local != NULL; break;
  case GM_DCONN_LEFT:
  case GM_DCONN_MIDPOINT:
  case GM_DCONN_MAGNUS4:
  case GM_DCONN_TRANSPORT: ok = c->connection != NULL; break;
  case GM_DCONN_MECHANICAL: ok = c->momentum != NULL; break;
  }
  if (!ok)
    return gm_error_set(err, GM_EINVAL,
                        "discrete connection: rule %d needs its callback (local, connection or "
                        "momentum)",
                        (int)c->rule);
  return GM_OK;
}

static void format_vec(char *buf, size_t cap, const double *x, size_t n) {
  size_t used = 0;
  for (size_t i = 0; i < n && used < cap; ++i) {
    int w = snprintf(buf + used, cap - used, "%s%.6g", i ? ", " : "(", x[i]);
    if (w < 0) break;
    used += (size_t)w;
  }
  if (used < cap) snprintf(buf + used, cap - used, ")");
}

/* ω = A(x) Δx ∈ 𝔤 (dim values) at x = x0 + t Δx */
static gm_status algebra_at(const gm_discrete_connection *c, const double *x0, const double *dx,
                            double t, double *omega, gm_error *err) {
  const size_t n = c->n, dim = gm_group_dim(c->group);
  double x[GM_DCONN_MAX_SHAPE], a[3 * GM_DCONN_MAX_SHAPE];
  for (size_t i = 0; i < n; ++i) x[i] = x0[i] + t * dx[i];
  if (c->connection(c->ctx, x, a) != 0)
    return gm_error_set(err, GM_ECALLBACK, "discrete connection: the connection callback failed");
  for (size_t r = 0; r < dim; ++r) {
    omega[r] = 0.0;
    for (size_t i = 0; i < n; ++i) omega[r] += a[r * n + i] * dx[i];
    if (!isfinite(omega[r]))
      return gm_error_set(err, GM_EDOMAIN, "discrete connection: A(x) is not finite");
  }
  return GM_OK;
}

/* U̇ = U Ξ(t), Ξ = −hat(A(x(t))Δx): the right-hand side U Ξ (SO(3)) or Ξ (SO(2)) */
static gm_status transport_rhs(const gm_discrete_connection *c, const double *x0, const double *dx,
                               double t, const double *u, double *du, gm_error *err) {
  double om[3];
  gm_status st = algebra_at(c, x0, dx, t, om, err);
  if (st != GM_OK) return st;
  if (c->group == GM_GROUP_SO2) {
    du[0] = -om[0];
    return GM_OK;
  }
  double xi[9], m[3] = {-om[0], -om[1], -om[2]};
  gm_so3_hat(m, xi);
  gm_mat3_mul(u, xi, du);
  return GM_OK;
}

static gm_status transport(const gm_discrete_connection *c, const double *x0, const double *dx,
                           double *a, gm_error *err) {
  const size_t sz = gm_group_size(c->group), m = c->substeps ? c->substeps : 64;
  double u[9], k[4][9], tmp[9];
  const double h = 1.0 / (double)m;
  gm_group_exp(c->group, (const double[3]){0, 0, 0}, u);
  for (size_t s = 0; s < m; ++s) {
    const double t = (double)s * h;
    gm_status st = transport_rhs(c, x0, dx, t, u, k[0], err);
    for (size_t i = 0; st == GM_OK && i < sz; ++i) tmp[i] = u[i] + 0.5 * h * k[0][i];
    if (st == GM_OK) st = transport_rhs(c, x0, dx, t + 0.5 * h, tmp, k[1], err);
    for (size_t i = 0; st == GM_OK && i < sz; ++i) tmp[i] = u[i] + 0.5 * h * k[1][i];
    if (st == GM_OK) st = transport_rhs(c, x0, dx, t + 0.5 * h, tmp, k[2], err);
    for (size_t i = 0; st == GM_OK && i < sz; ++i) tmp[i] = u[i] + h * k[2][i];
    if (st == GM_OK) st = transport_rhs(c, x0, dx, t + h, tmp, k[3], err);
    if (st != GM_OK) return st;
    for (size_t i = 0; i < sz; ++i) u[i] += h / 6.0 * (k[0][i] + 2.0 * k[1][i] + 2.0 * k[2][i] + k[3][i]);
  }
  gm_group_inv(c->group, u, a); /* RK4 leaves U orthogonal to O(h⁴/m⁴); Uᵀ is U⁻¹ to that order */
  return GM_OK;
}

#define NEWTON_MAX 50

static gm_status mechanical(const gm_discrete_connection *c, const double *x0, const double *x1,
                            double *a, gm_error *err) {
  const size_t dim = gm_group_dim(c->group);
  double w[3] = {0, 0, 0}, f[3], jac[9], fp[3], fm[3], res = INFINITY;
  int it = 0, small_steps = 0;
  for (; it < NEWTON_MAX; ++it) {
    if (c->momentum(c->ctx, x0, x1, w, f) != 0)
      return gm_error_set(err, GM_ECALLBACK, "discrete mechanical connection: the momentum callback failed");
    res = 0.0;
    for (size_t i = 0; i < dim; ++i) res = fmax(res, fabs(f[i]));
    if (!isfinite(res)) break;
    if (small_steps >= 2 || res == 0.0) break;
    for (size_t j = 0; j < dim; ++j) {
      const double d = 1e-6 * (1.0 + fabs(w[j])), keep = w[j];
      w[j] = keep + d;
      int bad = c->momentum(c->ctx, x0, x1, w, fp);
      w[j] = keep - d;
      bad |= c->momentum(c->ctx, x0, x1, w, fm);
      w[j] = keep;
      if (bad) return gm_error_set(err, GM_ECALLBACK, "discrete mechanical connection: the momentum callback failed");
      for (size_t i = 0; i < dim; ++i) jac[i * dim + j] = (fp[i] - fm[i]) / (2.0 * d);
    }
    double step[3] = {f[0], f[1], f[2]};
    if (gm_dense_solve(dim, jac, step) != GM_OK) {
      res = NAN; /* a singular Jacobian: group-regularity fails */
      break;
    }
    double sn = 0.0, wn = 0.0;
    for (size_t i = 0; i < dim; ++i) w[i] -= step[i], sn = fmax(sn, fabs(step[i])), wn = fmax(wn, fabs(w[i]));
    if (sn <= 1e-15 * (1.0 + wn)) ++small_steps;
  }
  if (!(small_steps >= 2 || res == 0.0)) {
    char s0[120], s1[120];
    format_vec(s0, sizeof s0, x0, c->n);
    format_vec(s1, sizeof s1, x1, c->n);
    return gm_error_set(err, GM_ENOCONV,
                        "discrete mechanical connection: J_d = 0 not solved for the group element "
                        "between x0 = %s and x1 = %s (|J_d| = %.3g after %d Newton iterations; "
                        "L_d is not group-regular there)",
                        s0, s1, res, it);
  }
  double g[9];
  gm_group_exp(c->group, w, g);
  gm_group_inv(c->group, g, a); /* A_d((x0, e), (x1, f)) = e at f = exp w, so A(x0, x1) = f⁻¹ */
  return GM_OK;
}

gm_status gm_dconn_local(const gm_discrete_connection *c, const double *x0, const double *x1,
                         double *a, gm_error *err) {
  gm_status st = check(c, err);
  if (st != GM_OK) return st;
  if ((c->n > 0 && (x0 == NULL || x1 == NULL)) || a == NULL)
    return gm_error_set(err, GM_EINVAL, "discrete connection: NULL argument");
  const size_t n = c->n;
  double dx[GM_DCONN_MAX_SHAPE], w[3];
  if (n == 0) {
    gm_group_exp(c->group, (const double[3]){0, 0, 0}, a);
    return GM_OK;
  }
  for (size_t i = 0; i < n; ++i) dx[i] = x1[i] - x0[i];
  switch (c->rule) {
  case GM_DCONN_CALLBACK:
    if (c->local(c->ctx, x0, x1, a) != 0)
      return gm_error_set(err, GM_ECALLBACK, "discrete connection: the local-form callback failed");
    return GM_OK;
  case GM_DCONN_LEFT:
  case GM_DCONN_MIDPOINT:
    st = algebra_at(c, x0, dx, c->rule == GM_DCONN_LEFT ? 0.0 : 0.5, w, err);
    if (st == GM_OK) gm_group_exp(c->group, w, a);
    return st;
  case GM_DCONN_MAGNUS4: {
    /* Blanes, Casas, Oteo & Ros, Phys. Rep. 470 (2009), eq. (253): for Y' = M(t)Y,
     * Ω = ½(M₁ + M₂) − (√3/12)[M₁, M₂]; for U' = UΞ (U = Yᵀ, M = Ξᵀ = −Ξ) this is
     * U(1) = exp(½(Ξ₁ + Ξ₂) + (√3/12)[Ξ₁, Ξ₂]); on so(3) [â, b̂] = (a × b)^. */
    const double r3 = sqrt(3.0) / 6.0;
    double o1[3], o2[3];
    st = algebra_at(c, x0, dx, 0.5 - r3, o1, err);
    if (st == GM_OK) st = algebra_at(c, x0, dx, 0.5 + r3, o2, err);
    if (st != GM_OK) return st;
    if (c->group == GM_GROUP_SO2) {
      w[0] = 0.5 * (o1[0] + o2[0]); /* A = exp(−w) with Ξ_i = −ω_i */
    } else {
      double cr[3]; /* [Ξ₁, Ξ₂] = (ω₁ × ω₂)^ since Ξ_i = −ω̂_i, so U(1) = exp(−w) with: */
      gm_vec3_cross(o1, o2, cr);
      for (int i = 0; i < 3; ++i) w[i] = 0.5 * (o1[i] + o2[i]) - sqrt(3.0) / 12.0 * cr[i];
    }
    gm_group_exp(c->group, w, a); /* U(1) = exp(−w), so A = U(1)⁻¹ = exp(w) */
    return GM_OK;
  }
  case GM_DCONN_TRANSPORT: return transport(c, x0, dx, a, err);
  case GM_DCONN_MECHANICAL: return mechanical(c, x0, x1, a, err);
  }
  return gm_error_set(err, GM_EINVAL, "discrete connection: unknown rule");
}

gm_status gm_dconn_eval(const gm_discrete_connection *c, const double *x0, const double *g0,
                        const double *x1, const double *g1, double *ad, gm_error *err) {
  double a[9], gi[9];
  gm_status st = gm_dconn_local(c, x0, x1, a, err);
  if (st != GM_OK) return st;
  if (g0 == NULL || g1 == NULL || ad == NULL)
    return gm_error_set(err, GM_EINVAL, "discrete connection: NULL argument");
  gm_group_inv(c->group, g0, gi);
  gm_group_mul(c->group, g1, a, a);
  gm_group_mul(c->group, a, gi, ad);
  return GM_OK;
}

gm_status gm_dconn_decompose(const gm_discrete_connection *c, const double *x0, const double *g0,
                             const double *x1, const double *g1, double *g_hor, double *g_ver,
                             gm_error *err) {
  double ad[9], inv[9];
  gm_status st = gm_dconn_eval(c, x0, g0, x1, g1, ad, err);
  if (st != GM_OK) return st;
  if (g_hor != NULL) {
    gm_group_inv(c->group, ad, inv);
    gm_group_mul(c->group, inv, g1, g_hor);
  }
  if (g_ver != NULL) gm_group_mul(c->group, ad, g0, g_ver);
  return GM_OK;
}

gm_status gm_dconn_lift(const gm_discrete_connection *c, size_t n_points, const double *path,
                        const double *g0, double *g, gm_error *err) {
  gm_status st = check(c, err);
  if (st != GM_OK) return st;
  if (n_points == 0 || path == NULL || g0 == NULL || g == NULL)
    return gm_error_set(err, GM_EINVAL, "horizontal lift: need a path of at least one point");
  const size_t sz = gm_group_size(c->group), n = c->n;
  memcpy(g, g0, sz * sizeof *g);
  for (size_t l = 0; l + 1 < n_points; ++l) {
    double a[9];
    st = gm_dconn_local(c, path + l * n, path + (l + 1) * n, a, err);
    if (st != GM_OK) return st;
    gm_group_inv(c->group, a, a);
    gm_group_mul(c->group, g + l * sz, a, g + (l + 1) * sz); /* the product on the right */
  }
  return GM_OK;
}

static double gap(const double *a, const double *b, size_t n, double *scale) {
  double d = 0.0, s = 0.0;
  for (size_t i = 0; i < n; ++i) d = fmax(d, fabs(a[i] - b[i])), s = fmax(s, fabs(a[i]));
  *scale = s;
  return d;
}

gm_status gm_dconn_compose(const gm_discrete_connection *c, const double *x0, const double *g0,
                           const double *x1, const double *g1, const double *y0, const double *h0,
                           const double *y1, const double *h1, double *g_out, gm_error *err) {
  gm_status st = check(c, err);
  if (st != GM_OK) return st;
  if ((c->n > 0 && (x0 == NULL || x1 == NULL || y0 == NULL || y1 == NULL)) || g0 == NULL ||
      g1 == NULL || h0 == NULL || h1 == NULL || g_out == NULL)
    return gm_error_set(err, GM_EINVAL, "extended composition: NULL argument");
  double s, d = gap(x1, y0, c->n, &s);
  if (!(d <= 1e-12 * (1.0 + s)))
    return gm_error_set(err, GM_EINVAL,
                        "extended composition: the pairs do not compose (the first ends at shape "
                        "point x1, the second starts %.3g away; need π(q1) = π(p0))",
                        d);
  double ad[9];
  st = gm_dconn_eval(c, y0, h0, x1, g1, ad, err); /* A_d(p0, q1), both in the fibre over x1 */
  if (st != GM_OK) return st;
  gm_group_mul(c->group, ad, h1, g_out);
  return GM_OK;
}

gm_status gm_dconn_holonomy(const gm_discrete_connection *c, size_t n_points, const double *loop,
                            double *hol, gm_error *err) {
  gm_status st = check(c, err);
  if (st != GM_OK) return st;
  if (n_points < 2 || loop == NULL || hol == NULL)
    return gm_error_set(err, GM_EINVAL, "holonomy: need a loop of at least two points");
  const size_t n = c->n, sz = gm_group_size(c->group);
  double s, d = gap(loop, loop + (n_points - 1) * n, n, &s);
  if (!(d <= 1e-12 * (1.0 + s)))
    return gm_error_set(err, GM_EINVAL,
                        "holonomy: the shape loop does not close (last point %.3g from the first)", d);
  double g[9], a[9];
  gm_group_exp(c->group, (const double[3]){0, 0, 0}, g);
  for (size_t l = 0; l + 1 < n_points; ++l) {
    st = gm_dconn_local(c, loop + l * n, loop + (l + 1) * n, a, err);
    if (st != GM_OK) return st;
    gm_group_inv(c->group, a, a);
    gm_group_mul(c->group, g, a, g);
  }
  memcpy(hol, g, sz * sizeof *hol);
  return GM_OK;
}

gm_status gm_dconn_defect(const gm_discrete_connection *a, const gm_discrete_connection *b,
                          const double *x0, const double *x1, double *defect, gm_error *err) {
  if (a == NULL || b == NULL || a->group != b->group || a->n != b->n || defect == NULL)
    return gm_error_set(err, GM_EINVAL, "connection defect: need two connections on one bundle");
  double la[9], lb[9];
  gm_status st = gm_dconn_local(a, x0, x1, la, err);
  if (st == GM_OK) st = gm_dconn_local(b, x0, x1, lb, err);
  if (st != GM_OK) return st;
  *defect = gm_group_distance(a->group, la, lb);
  return GM_OK;
}
