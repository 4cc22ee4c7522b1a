/* Rigid bodies on SO(3) (× R³): the state space T*SO(3) (× T*R³) with its canonical chart,
 * validation of the inertia, the energy, and the generic state-space functions of ode.h.
 *
 * Canonical chart at a base state (R_b, x_b, Π_b, p_b): R = R_b exp(ξ̂). The body angular
 * velocity of R_b exp(ξ̂(t)) is Ω = dexp_{−ξ} ξ' (geomint/lie.h), so for L = ½ Ω·JΩ − V the
 * momentum conjugate to ξ is p_ξ = ∂L/∂ξ' = dexp_{−ξ}ᵀ Π: (ξ, p_ξ) are canonical coordinates
 * on T*SO(3) near R_b. The chart is z = (ξ, x − x_b, p_ξ − Π_b, p − p_b) (a shift of the
 * momenta keeps them canonical), z = 0 at the base. */
#include <math.h>

#include "geomint/lie.h"
#include "ode/internal.h"

static double rigid_defect(void *ctx, const double *y) {
  (void)ctx;
  return gm_so3_orthogonality_defect(y);
}

/* dim 3: y = (R, Π); dim 6: y = (R, x, Π, p) */
static int chart_to(size_t dim, const double *base, const double *y, double *z) {
  const size_t nt = dim - 3, pi = 9 + nt;
  double rel[9], d[9];
  gm_mat3_mul_tn(base, y, rel);
  gm_so3_log(rel, z);
  const double minus_xi[3] = {-z[0], -z[1], -z[2]};
  gm_so3_dexp(minus_xi, d);
  gm_mat3_tvec(d, y + pi, z + dim); /* dexp_{−ξ}ᵀ Π */
  for (size_t i = 0; i < 3; ++i) z[dim + i] -= base[pi + i];
  for (size_t i = 0; i < nt; ++i) {
    z[3 + i] = y[9 + i] - base[9 + i];
    z[dim + 3 + i] = y[pi + 3 + i] - base[pi + 3 + i];
  }
  return 0;
}

static int chart_from(size_t dim, const double *base, const double *z, double *y) {
  const size_t nt = dim - 3, pi = 9 + nt;
  double e[9], di[9], m[3];
  gm_so3_exp(z, e);
  gm_mat3_mul(base, e, y);
  const double minus_xi[3] = {-z[0], -z[1], -z[2]};
  gm_so3_dexp_inv(minus_xi, di);
  for (size_t i = 0; i < 3; ++i) m[i] = z[dim + i] + base[pi + i];
  gm_mat3_tvec(di, m, y + pi); /* Π = dexp_{−ξ}⁻ᵀ p_ξ */
  for (size_t i = 0; i < nt; ++i) {
    y[9 + i] = base[9 + i] + z[3 + i];
    y[pi + 3 + i] = base[pi + 3 + i] + z[dim + 3 + i];
  }
  return 0;
}

static int to_chart3(void *ctx, const double *b, const double *y, double *z) {
  (void)ctx;
  return chart_to(3, b, y, z);
}
static int from_chart3(void *ctx, const double *b, const double *z, double *y) {
  (void)ctx;
  return chart_from(3, b, z, y);
}
static int to_chart6(void *ctx, const double *b, const double *y, double *z) {
  (void)ctx;
  return chart_to(6, b, y, z);
}
static int from_chart6(void *ctx, const double *b, const double *z, double *y) {
  (void)ctx;
  return chart_from(6, b, z, y);
}

static const char *const names3[] = {"R11", "R12", "R13", "R21", "R22", "R23",
                                     "R31", "R32", "R33", "Pi1", "Pi2", "Pi3"};
static const char *const names6[] = {"R11", "R12", "R13", "R21", "R22", "R23", "R31", "R32", "R33",
                                     "x1",  "x2",  "x3",  "Pi1", "Pi2", "Pi3", "p1",  "p2",  "p3"};

static const gm_state_space space3 = {"T*SO(3)", 12, 6, to_chart3, from_chart3, rigid_defect,
                                      "|R^T R - I|", names3};
static const gm_state_space space6 = {"T*(SO(3) x R3)", 18, 12, to_chart6, from_chart6,
                                      rigid_defect, "|R^T R - I|", names6};

const gm_state_space *gm_rigid_body_space(size_t dim) {
  return dim == 3 ? &space3 : dim == 6 ? &space6 : NULL;
}

const gm_state_space *gm_problem_space(const gm_problem *pb) {
  if (pb == NULL) return NULL;
  if (pb->space != NULL) return pb->space;
  if (pb->kind == GM_PROBLEM_RIGID_BODY) return gm_rigid_body_space(pb->dim);
  return NULL;
}

size_t gm_problem_chart_dim(const gm_problem *pb) {
  if (pb == NULL) return 0;
  const gm_state_space *s = gm_problem_space(pb);
  return s != NULL ? s->chart_dim : gm_problem_state_size(pb);
}

gm_status gm_problem_to_chart(const gm_problem *pb, const double *base, const double *y,
                              double *z) {
  if (pb == NULL || base == NULL || y == NULL || z == NULL) return GM_EINVAL;
  const gm_state_space *s = gm_problem_space(pb);
  if (s == NULL) {
    for (size_t i = 0, n = gm_problem_state_size(pb); i < n; ++i) z[i] = y[i] - base[i];
    return GM_OK;
  }
  return s->to_chart(pb->ctx, base, y, z) == 0 ? GM_OK : GM_EDOMAIN;
}

gm_status gm_problem_from_chart(const gm_problem *pb, const double *base, const double *z,
                                double *y) {
  if (pb == NULL || base == NULL || y == NULL || z == NULL) return GM_EINVAL;
  const gm_state_space *s = gm_problem_space(pb);
  if (s == NULL) {
    for (size_t i = 0, n = gm_problem_state_size(pb); i < n; ++i) y[i] = base[i] + z[i];
    return GM_OK;
  }
  return s->from_chart(pb->ctx, base, z, y) == 0 ? GM_OK : GM_EDOMAIN;
}

double gm_problem_state_defect(const gm_problem *pb, const double *y) {
  if (pb == NULL || y == NULL) return NAN;
  const gm_state_space *s = gm_problem_space(pb);
  return s != NULL && s->defect != NULL ? s->defect(pb->ctx, y) : 0.0;
}

const char *gm_problem_state_defect_name(const gm_problem *pb) {
  const gm_state_space *s = pb != NULL ? gm_problem_space(pb) : NULL;
  return s != NULL && s->defect_name != NULL ? s->defect_name : "";
}

/* J⁻¹ of a symmetric 3×3 matrix by cofactors; GM_EINVAL with a message unless J is symmetric
 * positive definite (leading minors > 0, Sylvester) and finite. */
gm_status gm_rigid_inertia_inverse(const double j[9], double inv[9], gm_error *err) {
  for (int k = 0; k < 9; ++k)
    if (!isfinite(j[k]))
      return gm_error_set(err, GM_EINVAL, "rigid body: inertia entry J%d%d is %g", k / 3 + 1,
                          k % 3 + 1, j[k]);
  double scale = 0.0;
  for (int k = 0; k < 9; ++k) scale = fmax(scale, fabs(j[k]));
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b)
      if (fabs(j[3 * a + b] - j[3 * b + a]) > 1e-14 * scale)
        return gm_error_set(err, GM_EINVAL, "rigid body: inertia J is not symmetric (J%d%d = %g, "
                            "J%d%d = %g)", a + 1, b + 1, j[3 * a + b], b + 1, a + 1, j[3 * b + a]);
  double c[9];
  c[0] = j[4] * j[8] - j[5] * j[7];
  c[1] = j[2] * j[7] - j[1] * j[8];
  c[2] = j[1] * j[5] - j[2] * j[4];
  c[3] = j[5] * j[6] - j[3] * j[8];
  c[4] = j[0] * j[8] - j[2] * j[6];
  c[5] = j[2] * j[3] - j[0] * j[5];
  c[6] = j[3] * j[7] - j[4] * j[6];
  c[7] = j[1] * j[6] - j[0] * j[7];
  c[8] = j[0] * j[4] - j[1] * j[3];
  double det = j[0] * c[0] + j[1] * c[3] + j[2] * c[6];
  double m1 = j[0], m2 = j[0] * j[4] - j[1] * j[3];
  /* relative to the scale: a singular J (det ≈ 0) is as bad as a negative one */
  if (!(m1 > 0.0) || !(m2 > 1e-12 * scale * scale) || !(det > 1e-12 * scale * scale * scale))
    return gm_error_set(err, GM_EINVAL,
                        "rigid body: inertia J must be positive definite, but its leading minors "
                        "are %g, %g, %g (singular or not positive)", m1, m2, det);
  for (int k = 0; k < 9; ++k) inv[k] = c[k] / det;
  return GM_OK;
}

gm_status gm_rigid_body_validate(const gm_problem *pb, gm_error *err) {
  if (pb->dim != 3 && pb->dim != 6)
    return gm_error_set(err, GM_EINVAL, "rigid-body problem: dim must be 3 (SO(3)) or 6 "
                        "(SO(3) x R3), got %zu", pb->dim);
  double inv[9];
  gm_status st = gm_rigid_inertia_inverse(pb->inertia, inv, err);
  if (st != GM_OK) return st;
  if (pb->dim == 6 && !(pb->mass > 0.0 && isfinite(pb->mass)))
    return gm_error_set(err, GM_EINVAL, "rigid-body problem: mass must be positive, got %g",
                        pb->mass);
  if ((pb->rigid_potential == NULL) != (pb->rigid_potential_gradient == NULL))
    return gm_error_set(err, GM_EINVAL, "rigid-body problem: give both rigid_potential and "
                        "rigid_potential_gradient, or neither (a free body)");
  return GM_OK;
}

double gm_rigid_body_energy(const gm_problem *pb, const double *y) {
  double inv[9], omega[3];
  if (gm_rigid_inertia_inverse(pb->inertia, inv, NULL) != GM_OK) return NAN;
  const size_t nt = pb->dim - 3, pi = 9 + nt;
  gm_mat3_vec(inv, y + pi, omega);
  double h = 0.5 * gm_vec3_dot(omega, y + pi);
  if (nt == 3) h += 0.5 * gm_vec3_dot(y + pi + 3, y + pi + 3) / pb->mass;
  if (pb->rigid_potential != NULL) h += pb->rigid_potential(pb->ctx, y, nt ? y + 9 : NULL);
  return h;
}
