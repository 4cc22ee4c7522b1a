/* Shared setup of the pde tests: the sine-Gordon breather on a periodic grid. */
#ifndef GM_TEST_PDE_UTIL_H
#define GM_TEST_PDE_UTIL_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/geomint.h"

#define PDE_L 20.0     /* domain [−L, L), periodic; the breather's tail there is ~4e-7 */
#define PDE_OMEGA 0.5  /* breather frequency */

/* Standing breather u = 4 arctan((k/ω) sin(ωt) / cosh(kx)), k = √(1 − ω²). */
static inline double pde_breather(double x, double t) {
  double k = sqrt(1.0 - PDE_OMEGA * PDE_OMEGA);
  return 4.0 * atan(k / PDE_OMEGA * sin(PDE_OMEGA * t) / cosh(k * x));
}

/* s = (u, u_t, u_x) of the breather at t = 0 (u = 0, u_t = 4k sech(kx)); n·3 values, owned. */
static inline double *pde_breather_data(size_t n) {
  double h = 2.0 * PDE_L / (double)n, k = sqrt(1.0 - PDE_OMEGA * PDE_OMEGA);
  double *s = calloc(3 * n, sizeof *s);
  cr_assert_not_null(s);
  for (size_t i = 0; i < n; i++) s[3 * i + 1] = 4.0 * k / cosh(k * (-PDE_L + (double)i * h));
  return s;
}

static inline gm_pde *pde_breather_solver(const char *scheme, size_t n, double dt, int track) {
  gm_pde_equation eq = gm_pde_sine_gordon();
  const gm_pde_scheme *s = NULL;
  cr_assert_eq(gm_pde_scheme_find(scheme, &s), GM_OK, "scheme %s", scheme);
  gm_pde_grid g = {n, 2.0 * PDE_L / (double)n, -PDE_L, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = dt;
  o.track_variations = track;
  double *s0 = pde_breather_data(n);
  gm_pde *p = NULL;
  gm_error err = {{0}};
  gm_status st = gm_pde_create(&g, &eq, s, &o, s0, &p, &err);
  free(s0);
  cr_assert_eq(st, GM_OK, "create %s: %s", scheme, err.message);
  return p;
}

/* max_i |u_i − u_exact(x_i, t)| */
static inline double pde_breather_error(const gm_pde *p, double h) {
  const double *s = gm_pde_state(p);
  double e = 0.0, t = gm_pde_time(p);
  for (size_t i = 0; i < gm_pde_n(p); i++) {
    double d = fabs(s[3 * i] - pde_breather(-PDE_L + (double)i * h, t));
    if (d > e) e = d;
  }
  return e;
}

#endif
