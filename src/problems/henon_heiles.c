/* Hénon–Heiles H = ½|p|² + ½(q₁² + q₂²) + λ(q₁²q₂ − q₂³/3) (Hénon & Heiles, Astron. J. 69
 * (1964) 73, with λ = 1). Default start q = (0, 0.1), p = (0.5, 0): energy ≈ 0.1297, where
 * regular and chaotic orbits coexist. */
#include "problems/internal.h"

typedef struct {
  size_t dim;
  double lambda;
} henon_heiles;

static double potential(void *ctx, const double *q) {
  const double l = ((const henon_heiles *)ctx)->lambda;
  return 0.5 * (q[0] * q[0] + q[1] * q[1]) + l * (q[0] * q[0] * q[1] - q[1] * q[1] * q[1] / 3.0);
}

static int potential_gradient(void *ctx, const double *q, double *out) {
  const double l = ((const henon_heiles *)ctx)->lambda;
  out[0] = q[0] + 2.0 * l * q[0] * q[1];
  out[1] = q[1] + l * (q[0] * q[0] - q[1] * q[1]);
  return 0;
}

static int potential_hessian(void *ctx, const double *q, double *out) {
  const double l = ((const henon_heiles *)ctx)->lambda;
  out[0] = 1.0 + 2.0 * l * q[1];
  out[1] = 2.0 * l * q[0];
  out[2] = out[1];
  out[3] = 1.0 - 2.0 * l * q[1];
  return 0;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  (void)t0;
  (void)errmsg;
  (void)cap;
  *(henon_heiles *)ctx = (henon_heiles){2, params[0]};
  gm_free_kinetic_setup(pb);
  pb->potential = potential;
  pb->potential_gradient = potential_gradient;
  pb->potential_hessian = potential_hessian;
  y0[0] = 0.0;
  y0[1] = 0.1;
  y0[2] = 0.5;
  y0[3] = 0.0;
  return GM_OK;
}

static const gm_param_info params[] = {
    {"lambda", 1.0, "strength of the cubic coupling", GM_PARAM_NUMBER}};

const gm_model_def gm_model_henon_heiles = {
    {"henon-heiles", "Henon-Heiles potential, q = (0, 0.1), p = (0.5, 0), energy 0.1297",
     GM_PROBLEM_SEPARABLE, 2, 1, params, 0, NULL, 0},
    sizeof(henon_heiles), NULL, setup, NULL, NULL};
