/* The travelling-pulse set-up of the space–time adaptive VI (geomint/pde_moving_mesh.h): data,
 * exact d'Alembert solution, one run with its invariants and errors. */
#include <math.h>
#include <stdlib.h>

#include "geomint/pde_moving_mesh.h"
#include "pde/internal.h"

#define PULSE_LEN 20.0
#define RAMP_K (GM_PI / 5.0) /* two wavelengths on [0, 20) */

static double wrap(double x) {
  double y = fmod(x, PULSE_LEN);
  return y < 0.0 ? y + PULSE_LEN : y;
}

/* u(x, t) of a right-travelling wave f(x − t) (+ 2t for the ramp); the Dirichlet pulse is the
 * free one until it reaches a wall (t < 9, 4 widths away) */
double gm_moving_mesh_pulse_exact(const gm_moving_mesh_pulse *p, double x, double t) {
  if (p->ramp) return sin(RAMP_K * (x - t)) + 2.0 * t;
  double y = (p->dirichlet ? x - t : wrap(x - t)) - 0.5 * PULSE_LEN;
  return exp(-y * y);
}

static double at_zero(double x, const void *ctx) { return gm_moving_mesh_pulse_exact(ctx, x, 0.0); }

gm_status gm_moving_mesh_pulse_create(const gm_moving_mesh_pulse *p, gm_moving_mesh **out,
                                      gm_error *err) {
  if (p == NULL || out == NULL)
    return gm_error_set(err, GM_EINVAL, "moving-mesh pulse: NULL argument");
  *out = NULL;
  if (p->n < 4 || p->n > ((size_t)1 << 22))
    return gm_error_set(err, GM_EINVAL, "moving-mesh pulse: n = %zu (need 4 .. 2^22)", p->n);
  if (!(isfinite(p->cfl) && p->cfl > 0.0 && p->cfl <= 1.0))
    return gm_error_set(err, GM_EINVAL, "moving-mesh pulse: cfl = %g is not in (0, 1] (the "
                        "start's stability bound is dt <= min dx)", p->cfl);
  size_t n = p->n;
  double *x = malloc(n * sizeof *x), *u0 = malloc(n * sizeof *u0), *ut = malloc(n * sizeof *ut);
  gm_status st = GM_ENOMEM;
  if (x == NULL || u0 == NULL || ut == NULL) {
    st = gm_error_set(err, GM_ENOMEM, "moving-mesh pulse: out of memory (n = %zu)", n);
    goto done;
  }
  st = gm_moving_mesh_equidistribute(n, 0.0, PULSE_LEN, p->alpha, p->dirichlet, at_zero, p,
                                     64 * n, x, err);
  if (st != GM_OK) goto done;
  for (size_t j = 0; j < n; j++) {
    u0[j] = gm_moving_mesh_pulse_exact(p, x[j], 0.0);
    if (p->ramp) {
      ut[j] = -RAMP_K * cos(RAMP_K * x[j]) + 2.0;
    } else {
      double y = x[j] - 0.5 * PULSE_LEN;
      ut[j] = 2.0 * y * exp(-y * y); /* −u_x */
    }
  }
  gm_moving_mesh_options o = gm_moving_mesh_options_defaults();
  o.kind = p->kind;
  o.alpha = p->alpha;
  o.dirichlet = p->dirichlet;
  o.dt = p->cfl * gm_moving_mesh_dt_bound(n, x, PULSE_LEN, p->dirichlet);
  st = gm_moving_mesh_create(n, x, PULSE_LEN, u0, ut, &o, out, err);
done:
  free(x);
  free(u0);
  free(ut);
  return st;
}

gm_status gm_moving_mesh_pulse_run(const gm_moving_mesh_pulse *p, size_t steps,
                                   gm_moving_mesh_observer_fn fn, void *ctx,
                                   gm_moving_mesh_pulse_result *r, gm_error *err) {
  if (r == NULL) return gm_error_set(err, GM_EINVAL, "moving-mesh pulse: NULL result");
  gm_moving_mesh *m = NULL;
  gm_status st = gm_moving_mesh_pulse_create(p, &m, err);
  if (st != GM_OK) return st;
  if (fn != NULL) gm_moving_mesh_set_observer(m, 1, fn, ctx, NULL);
  gm_moving_mesh_pulse_result z = {0};
  *r = z;
  double e0 = gm_moving_mesh_energy(m), p0 = gm_moving_mesh_momentum(m);
  double pscale = fabs(p0) > 0.0 ? fabs(p0) : 1.0;
  r->min_dt = INFINITY;
  for (size_t s = 0; s < steps; s++) {
    double t_before = gm_moving_mesh_time(m);
    r->status = gm_moving_mesh_advance(m, 1, err);
    if (r->status != GM_OK) break;
    double dt = gm_moving_mesh_time(m) - t_before;
    r->min_dt = fmin(r->min_dt, dt);
    r->max_dt = fmax(r->max_dt, dt);
    r->max_rel_energy = fmax(r->max_rel_energy, fabs(gm_moving_mesh_energy(m) - e0) / e0);
    r->max_rel_momentum = fmax(r->max_rel_momentum, fabs(gm_moving_mesh_momentum(m) - p0) / pscale);
  }
  gm_moving_mesh_stats stats = gm_moving_mesh_get_stats(m);
  r->steps = stats.steps;
  r->t = gm_moving_mesh_time(m);
  size_t tried = stats.steps + stats.failed_steps;
  r->newton_per_step = tried > 0 ? (double)stats.newton_iterations / (double)tried : 0.0;
  const double *x = gm_moving_mesh_x(m), *u = gm_moving_mesh_u(m);
  for (size_t j = 0; j < gm_moving_mesh_n(m); j++)
    r->max_error = fmax(r->max_error, fabs(u[j] - gm_moving_mesh_pulse_exact(p, x[j], r->t)));
  gm_moving_mesh_free(m);
  return GM_OK;
}
