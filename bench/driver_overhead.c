/* Overhead of the integrator driver: Störmer–Verlet through gm_integrator_run against a bare
 * loop written here that makes the same force calls (same callbacks, same arithmetic, one
 * force per step thanks to first-same-as-last), on Kepler and on 100 bodies with pairwise
 * gravity. Reports the ratio library/bare (target ≤ 1.10) and checks both end in the same
 * state bit for bit. Times are thread CPU times, the best of several alternating repeats. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/geomint.h"

/* ---- 100 bodies in 3-D with pairwise Newtonian gravity (G = 1, softening ε) ------------ */
typedef struct {
  size_t dim; /* 3 N */
  size_t n_bodies;
  double *mass;
  double eps2;
} nbody;

static double nbody_kinetic(void *ctx, const double *p) {
  const nbody *nb = ctx;
  double t = 0;
  for (size_t i = 0; i < nb->n_bodies; ++i)
    for (size_t k = 0; k < 3; ++k) t += p[3 * i + k] * p[3 * i + k] / (2 * nb->mass[i]);
  return t;
}
static int nbody_velocity(void *ctx, const double *p, double *v) {
  const nbody *nb = ctx;
  for (size_t i = 0; i < nb->n_bodies; ++i)
    for (size_t k = 0; k < 3; ++k) v[3 * i + k] = p[3 * i + k] / nb->mass[i];
  return 0;
}
static double nbody_potential(void *ctx, const double *q) {
  const nbody *nb = ctx;
  double v = 0;
  for (size_t i = 0; i < nb->n_bodies; ++i)
    for (size_t j = i + 1; j < nb->n_bodies; ++j) {
      double dx = q[3 * i] - q[3 * j], dy = q[3 * i + 1] - q[3 * j + 1], dz = q[3 * i + 2] - q[3 * j + 2];
      v -= nb->mass[i] * nb->mass[j] / sqrt(dx * dx + dy * dy + dz * dz + nb->eps2);
    }
  return v;
}
static int nbody_gradient(void *ctx, const double *q, double *g) {
  const nbody *nb = ctx;
  memset(g, 0, nb->dim * sizeof *g);
  for (size_t i = 0; i < nb->n_bodies; ++i)
    for (size_t j = i + 1; j < nb->n_bodies; ++j) {
      double d[3] = {q[3 * i] - q[3 * j], q[3 * i + 1] - q[3 * j + 1], q[3 * i + 2] - q[3 * j + 2]};
      double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + nb->eps2;
      double s = nb->mass[i] * nb->mass[j] / (r2 * sqrt(r2));
      for (size_t k = 0; k < 3; ++k) {
        g[3 * i + k] += s * d[k];
        g[3 * j + k] -= s * d[k];
      }
    }
  return 0;
}

/* ---- the bare loop: kick ½, drift, kick ½, the last force reused -------------------------- */
static void bare_verlet(const gm_problem *pb, double *y, size_t steps, double h, double *force,
                        double *velocity) {
  const size_t d = pb->dim;
  double *q = y, *p = y + d;
  pb->potential_gradient(pb->ctx, q, force);
  for (size_t s = 0; s < steps; ++s) {
    for (size_t i = 0; i < d; ++i) p[i] = p[i] + (-0.5 * h) * force[i];
    pb->kinetic_gradient(pb->ctx, p, velocity);
    for (size_t i = 0; i < d; ++i) q[i] = q[i] + h * velocity[i];
    pb->potential_gradient(pb->ctx, q, force);
    for (size_t i = 0; i < d; ++i) p[i] = p[i] + (-0.5 * h) * force[i];
  }
}

typedef struct {
  const char *name;
  double bare_s, library_s, ratio;
  size_t steps;
  int identical;
} result;

static result measure(const char *name, const gm_problem *pb, const double *y0, double h,
                      size_t steps, int repeats) {
  const size_t n = gm_problem_state_size(pb);
  double *y = malloc(n * sizeof *y), *force = malloc(n * sizeof *force),
         *velocity = malloc(n * sizeof *velocity);
  result r = {name, INFINITY, INFINITY, 0, steps, 0};
  gm_integrator *it = NULL;
  gm_error err;
  if (gm_integrator_create(gm_method_find("verlet"), pb, &it, &err) != GM_OK) {
    fprintf(stderr, "%s\n", err.message);
    exit(1);
  }
  for (int rep = 0; rep < repeats; ++rep) { /* alternate, keep the best of each */
    memcpy(y, y0, n * sizeof *y);
    double t0 = bench_cpu_now();
    bare_verlet(pb, y, steps, h, force, velocity);
    r.bare_s = fmin(r.bare_s, bench_cpu_now() - t0);
    gm_integrator_set_state(it, 0.0, y0);
    t0 = bench_cpu_now();
    if (gm_integrator_run(it, steps, h) != GM_OK) {
      fprintf(stderr, "%s\n", gm_integrator_errmsg(it));
      exit(1);
    }
    r.library_s = fmin(r.library_s, bench_cpu_now() - t0);
  }
  r.identical = memcmp(y, gm_integrator_state(it), n * sizeof *y) == 0;
  r.ratio = r.library_s / r.bare_s;
  gm_integrator_free(it);
  free(y);
  free(force);
  free(velocity);
  return r;
}

int main(int argc, char **argv) {
  result res[2];
  /* Kepler, e = 0.6 */
  gm_model *kepler = NULL;
  gm_model_create("kepler", &kepler);
  gm_model_build(kepler);
  double t0, yk[4];
  gm_model_initial_state(kepler, &t0, yk);
  res[0] = measure("kepler", gm_model_problem(kepler), yk, 0.01, 500000, 21);

  /* 100 bodies: a cold random cluster (fixed seed), unit total mass */
  enum { N = 100 };
  static double mass[N], y[6 * N];
  unsigned long long seed = 42;
  for (size_t i = 0; i < N; ++i) {
    mass[i] = 1.0 / N;
    for (size_t k = 0; k < 3; ++k) {
      seed = seed * 6364136223846793005ull + 1442695040888963407ull;
      y[3 * i + k] = (double)(seed >> 11) / 9007199254740992.0 - 0.5;
      y[3 * N + 3 * i + k] = 0.0;
    }
  }
  nbody nb = {3 * N, N, mass, 1e-4};
  gm_problem pb = {0};
  pb.kind = GM_PROBLEM_SEPARABLE;
  pb.dim = 3 * N;
  pb.ctx = &nb;
  pb.kinetic = nbody_kinetic;
  pb.potential = nbody_potential;
  pb.kinetic_gradient = nbody_velocity;
  pb.potential_gradient = nbody_gradient;
  res[1] = measure("100-body", &pb, y, 1e-3, 500, 21);

  printf("%-10s %10s %12s %12s %8s %10s\n", "problem", "steps", "bare [s]", "library [s]",
         "ratio", "identical");
  for (size_t i = 0; i < 2; ++i)
    printf("%-10s %10zu %12.4f %12.4f %8.3f %10s\n", res[i].name, res[i].steps, res[i].bare_s,
           res[i].library_s, res[i].ratio, res[i].identical ? "yes" : "NO");
  FILE *f = bench_open_json(argc, argv, "driver_overhead");
  if (f != NULL) {
    fprintf(f, "{\n  \"benchmark\": \"driver_overhead\",\n  \"method\": \"verlet\",\n"
               "  \"floor\": \"bare loop with the same force calls\",\n  \"target_ratio\": 1.10,\n"
               "  \"rows\": [\n");
    for (size_t i = 0; i < 2; ++i) {
      fprintf(f, "    {\"problem\": \"%s\", \"steps\": %zu, ", res[i].name, res[i].steps);
      bench_json_timing(f, res[i].bare_s, res[i].library_s, res[i].ratio, res[i].identical,
                        i + 1 == 2);
    }
    bench_close_json(f);
  }
  gm_model_free(kepler);
  return res[0].identical && res[1].identical ? 0 : 1;
}
