/* Write your own split potential V = U + W and integrate it with steps far beyond Verlet's
 * stability limit: two unit masses, a stiff spring between them (W = ½ qᵀΩ²q with a full,
 * symmetric positive semidefinite Ω), each in a soft anharmonic well (U). See
 * docs/oscillatory.md. */
#include <geomint/geomint.h>
#include <math.h>
#include <stdio.h>

#define OMEGA 100.0 /* the stiff frequency: Ω² = (ω²/2)[[1, −1], [−1, 1]] */

static double slow(void *ctx, const double *q) {
  (void)ctx;
  return 0.5 * (q[0] * q[0] + q[1] * q[1]) + 0.25 * (pow(q[0], 4) + pow(q[1], 4));
}
static int slow_gradient(void *ctx, const double *q, double *g) {
  (void)ctx;
  for (int i = 0; i < 2; ++i) g[i] = q[i] + q[i] * q[i] * q[i];
  return 0;
}
static double fast(void *ctx, const double *q) {
  (void)ctx;
  return 0.25 * OMEGA * OMEGA * (q[1] - q[0]) * (q[1] - q[0]);
}
static int fast_gradient(void *ctx, const double *q, double *g) {
  (void)ctx;
  g[1] = 0.5 * OMEGA * OMEGA * (q[1] - q[0]);
  g[0] = -g[1];
  return 0;
}
static double kinetic(void *ctx, const double *p) {
  (void)ctx;
  return 0.5 * (p[0] * p[0] + p[1] * p[1]);
}
static int kinetic_gradient(void *ctx, const double *p, double *g) {
  (void)ctx;
  g[0] = p[0];
  g[1] = p[1];
  return 0;
}
static double potential(void *ctx, const double *q) { return slow(ctx, q) + fast(ctx, q); }
static int potential_gradient(void *ctx, const double *q, double *g) {
  double w[2];
  slow_gradient(ctx, q, g);
  fast_gradient(ctx, q, w);
  g[0] += w[0];
  g[1] += w[1];
  return 0;
}

int main(void) {
  /* Ω = (ω/2)[[1, −1], [−1, 1]] squares to (ω²/2)[[1, −1], [−1, 1]] */
  static const double omega[4] = {OMEGA / 2, -OMEGA / 2, -OMEGA / 2, OMEGA / 2};
  const gm_split_potential split = {slow, slow_gradient, fast, fast_gradient, NULL, omega, 0, NULL};
  gm_problem pb = {0};
  pb.kind = GM_PROBLEM_SEPARABLE;
  pb.dim = 2;
  pb.kinetic = kinetic;
  pb.kinetic_gradient = kinetic_gradient;
  pb.potential = potential;
  pb.potential_gradient = potential_gradient;
  pb.kinetic_is_quadratic = 1;
  pb.split = &split;
  const double y0[4] = {1.0, 1.01, 0.0, 0.0}, h = 0.05; /* hω = 5: Verlet needs hω < 2 */
  const char *methods[] = {"imex", "trig-hairer-lubich", "verlet"};
  for (int k = 0; k < 3; ++k) {
    gm_integrator *it;
    gm_error err;
    if (gm_integrator_create(gm_method_find(methods[k]), &pb, &it, &err))
      return fprintf(stderr, "%s\n", err.message), 1;
    gm_integrator_set_state(it, 0.0, y0);
    gm_status st = gm_integrator_integrate(it, 100.0, h);
    double e = st == GM_OK ? (gm_problem_energy(&pb, gm_integrator_state(it)) -
                              gm_problem_energy(&pb, y0)) / gm_problem_energy(&pb, y0)
                           : NAN;
    printf("%-20s h = %g (h omega = %g): %s, relative energy error at t = 100: %.2e\n",
           methods[k], h, h * OMEGA, st == GM_OK ? "ok" : gm_integrator_errmsg(it), e);
    gm_integrator_free(it);
  }
  return 0;
}
