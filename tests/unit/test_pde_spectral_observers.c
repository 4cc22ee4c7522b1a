/* Observers of the spectral solvers (Schrödinger VI and split-step, the 1-D wave equation with
 * the spectral Hodge star): called after every `every` steps with the state of that step, and a
 * non-zero return stops the run with GM_ECALLBACK; a run observed gives the same state. */
#include <complex.h>
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "geomint/pde.h"

#define N 64

typedef struct seen {
  size_t calls, last_step, stop_at;
  double last_t;
} seen;

static int see_schrodinger(gm_schrodinger *s, void *ctx) {
  seen *z = ctx;
  z->calls++;
  z->last_step = gm_schrodinger_steps(s);
  z->last_t = gm_schrodinger_time(s);
  cr_expect(isfinite(gm_schrodinger_energy(s)));
  return z->stop_at != 0 && z->last_step == z->stop_at;
}

static gm_schrodinger *make_schrodinger(gm_schrodinger_scheme scheme) {
  double V[N], psi[2 * N], L = 20.0;
  for (size_t j = 0; j < N; j++) {
    double x = -10.0 + L * (double)j / N;
    V[j] = 0.5 * x * x;
    psi[2 * j] = exp(-0.5 * (x - 1.0) * (x - 1.0));
    psi[2 * j + 1] = 0.0;
  }
  gm_schrodinger_options o = gm_schrodinger_options_defaults();
  o.scheme = scheme;
  o.dt = 0.01;
  gm_schrodinger *s = NULL;
  gm_error err = {0};
  cr_assert_eq(gm_schrodinger_create(N, -10.0, L, V, psi, &o, &s, &err), GM_OK, "%s", err.message);
  return s;
}

Test(spectral_observers, schrodinger_each_step) {
  gm_schrodinger_scheme schemes[2] = {GM_SCHRODINGER_VI, GM_SCHRODINGER_SPLIT_STEP};
  for (int k = 0; k < 2; k++) {
    gm_schrodinger *s = make_schrodinger(schemes[k]), *ref = make_schrodinger(schemes[k]);
    seen every1 = {0}, every3 = {0};
    gm_error err = {0};
    cr_assert_eq(gm_schrodinger_add_observer(s, 1, see_schrodinger, &every1, &err), GM_OK);
    cr_assert_eq(gm_schrodinger_add_observer(s, 3, see_schrodinger, &every3, &err), GM_OK);
    cr_assert_eq(gm_schrodinger_advance(s, 10, &err), GM_OK, "%s", err.message);
    cr_expect_eq(every1.calls, 10);
    cr_expect_eq(every1.last_step, 10);
    cr_expect_float_eq(every1.last_t, 0.1, 1e-15);
    cr_expect_eq(every3.calls, 3);
    cr_expect_eq(every3.last_step, 9);
    /* observing changes nothing */
    cr_assert_eq(gm_schrodinger_advance(ref, 10, &err), GM_OK);
    const double *a = gm_schrodinger_psi(s), *b = gm_schrodinger_psi(ref);
    for (size_t j = 0; j < 2 * N; j++) cr_expect_eq(a[j], b[j]);
    gm_schrodinger_free(ref);
    /* a non-zero return stops the run */
    seen stop = {0, 0, 12, 0.0};
    cr_assert_eq(gm_schrodinger_add_observer(s, 1, see_schrodinger, &stop, &err), GM_OK);
    cr_expect_eq(gm_schrodinger_advance(s, 5, &err), GM_ECALLBACK);
    cr_expect_eq(gm_schrodinger_steps(s), 12);
    cr_expect_eq(gm_schrodinger_add_observer(s, 0, see_schrodinger, &stop, &err), GM_EINVAL);
    cr_expect_eq(gm_schrodinger_add_observer(s, 1, NULL, &stop, &err), GM_EINVAL);
    gm_schrodinger_free(s);
  }
}

static int see_wave(gm_wave1d *w, void *ctx) {
  seen *z = ctx;
  z->calls++;
  z->last_t = gm_wave1d_time(w);
  cr_expect(isfinite(gm_wave1d_energy(w)));
  return 0;
}

Test(spectral_observers, wave1d_each_step) {
  double u[N], v[N], L = 2.0 * 3.14159265358979323846;
  for (size_t j = 0; j < N; j++) {
    u[j] = sin(L * (double)j / N);
    v[j] = 0.0;
  }
  gm_hodge_kind stars[2] = {GM_HODGE_DIAGONAL, GM_HODGE_SPECTRAL};
  for (int k = 0; k < 2; k++) {
    gm_wave1d *w = NULL;
    gm_error err = {0};
    cr_assert_eq(gm_wave1d_create(N, L, stars[k], 0.01, u, v, &w, &err), GM_OK, "%s", err.message);
    seen z = {0};
    cr_assert_eq(gm_wave1d_add_observer(w, 1, see_wave, &z, &err), GM_OK);
    cr_assert_eq(gm_wave1d_advance(w, 25, &err), GM_OK, "%s", err.message);
    cr_expect_eq(z.calls, 25);
    cr_expect_float_eq(z.last_t, 0.25, 1e-15);
    cr_expect_eq(gm_wave1d_add_observer(w, 0, see_wave, &z, &err), GM_EINVAL);
    gm_wave1d_free(w);
  }
}
