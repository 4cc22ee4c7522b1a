/* Seed 000 §3.3.4: the spectral Hodge star (h sinc(k/N) per Fourier mode) against the diagonal
 * star on u_tt = *d*d u, [0, 2 pi) periodic: the relative frequency error of every mode,
 * semi-discrete (the Rayleigh quotient of *d*d on the sampled mode) and with leapfrog at
 * dt = C h (the frequency from the phase of the mode's coefficient). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/pde_spectral.h"

#define SS_PI 3.14159265358979323846

gm_spectral_star_config gm_spectral_star_defaults(void) {
  gm_spectral_star_config c = {64, 0.1};
  return c;
}

void gm_spectral_star_result_clear(gm_spectral_star_result *r) {
  if (r == NULL) return;
  free(r->modes);
  r->modes = NULL;
  r->n_modes = 0;
}

/* leapfrog run of mode m from its discrete forward mode; the frequency from the phase, followed
 * by an observer every step */
typedef struct mode_phase {
  size_t n;
  long m;
  double phase, pc, ps;
} mode_phase;

static int follow_mode(gm_wave1d *w, void *ctx) {
  mode_phase *p = ctx;
  const double *u = gm_wave1d_u(w);
  double c = 0.0, s = 0.0;
  for (size_t j = 0; j < p->n; j++) {
    double x = 2.0 * SS_PI * (double)j / (double)p->n;
    c += u[j] * cos((double)p->m * x);
    s += u[j] * sin((double)p->m * x);
  }
  p->phase += atan2(s * p->pc - c * p->ps, c * p->pc + s * p->ps);
  p->pc = c;
  p->ps = s;
  return 0;
}

static double run_mode(gm_wave1d *w, size_t n, long m, size_t steps, double dt) {
  mode_phase p = {n, m, 0.0, 1.0, 0.0};
  gm_error err = {{0}};
  if (gm_wave1d_add_observer(w, 1, follow_mode, &p, &err) != GM_OK ||
      gm_wave1d_advance(w, steps, &err) != GM_OK)
    return NAN;
  return p.phase / ((double)steps * dt);
}

gm_status gm_experiment_spectral_star(const gm_spectral_star_config *c, const char *dir,
                                      gm_spectral_star_result *r, gm_error *err) {
  *r = (gm_spectral_star_result){0};
  const size_t n = c->n;
  if (n < 4 || n % 2 != 0 || n > 4096)
    return gm_error_set(err, GM_EINVAL, "spectral-star: n = %zu must be even, >= 4 and <= 4096",
                        n);
  if (!(c->courant > 0.0 && c->courant <= 2.0 / SS_PI))
    return gm_error_set(err, GM_EINVAL, "spectral-star: courant %g must lie in (0, 2/pi] "
                        "(leapfrog with the spectral star)", c->courant);
  const double t0 = gm_experiment_clock();
  const double L = 2.0 * SS_PI, h = L / (double)n, dt = c->courant * h;
  r->n = n;
  r->courant = c->courant;
  r->dt = dt;
  r->steps = (size_t)ceil(10.0 / dt);
  r->t_end = (double)r->steps * dt;
  r->modes = calloc(n / 2, sizeof *r->modes);
  double *u = malloc(n * sizeof *u), *v = malloc(n * sizeof *v);
  gm_status st = GM_OK;
  if (r->modes == NULL || u == NULL || v == NULL) {
    st = gm_error_set(err, GM_ENOMEM, "spectral-star: out of memory");
    goto done;
  }
  for (long m = 1; m < (long)n / 2; m++) {
    double k = (double)m, res[2], sem[2];
    for (int kind = 0; kind < 2; kind++) {
      double sym = gm_wave1d_symbol((gm_hodge_kind)kind, n, L, m);
      double om_pred = 2.0 / dt * asin(0.5 * dt * sqrt(-sym));
      for (size_t j = 0; j < n; j++) {
        u[j] = cos(k * (double)j * h);
        v[j] = sin(om_pred * dt) / dt * sin(k * (double)j * h);
      }
      gm_wave1d *w = NULL;
      if ((st = gm_wave1d_create(n, L, (gm_hodge_kind)kind, dt, u, v, &w, err)) != GM_OK)
        goto done;
      gm_wave1d_laplacian(w, u, v);
      double num = 0.0, den = 0.0;
      for (size_t j = 0; j < n; j++) {
        num += u[j] * v[j];
        den += u[j] * u[j];
      }
      sem[kind] = fabs(sqrt(-num / den) - k) / k;
      res[kind] = run_mode(w, n, m, r->steps, dt);
      gm_wave1d_free(w);
    }
    const double om_leap = 2.0 / dt * asin(0.5 * dt * k);
    gm_spectral_star_mode *x = &r->modes[r->n_modes++];
    x->m = m;
    x->semi_diagonal = sem[0];
    x->semi_spectral = sem[1];
    x->leapfrog_diagonal = fabs(res[0] - k) / k;
    x->leapfrog_spectral = fabs(res[1] - k) / k;
    x->spectral_spatial = fabs(res[1] - om_leap) / k;
    r->max_rel_semi_diagonal = fmax(r->max_rel_semi_diagonal, sem[0]);
    r->max_rel_semi_spectral = fmax(r->max_rel_semi_spectral, sem[1]);
  }
  if (dir != NULL) {
    char path[GM_EXPERIMENT_PATH_SIZE];
    FILE *f = NULL;
    if (gm_experiment_path(path, sizeof path, dir, "spectral-star.dat") != GM_OK ||
        (f = fopen(path, "w")) == NULL) {
      st = gm_error_set(err, GM_EIO, "spectral-star: cannot write '%s/spectral-star.dat'", dir);
      goto done;
    }
    fprintf(f, "# m/N rel_err_semi_diag rel_err_semi_spectral rel_err_leapfrog_diag "
               "rel_err_leapfrog_spectral spatial_part_spectral (omega_measured - leapfrog(exact "
               "k))/k\n");
    for (size_t i = 0; i < r->n_modes; ++i) {
      const gm_spectral_star_mode *x = &r->modes[i];
      fprintf(f, "%.6f %.6e %.6e %.6e %.6e %.6e\n", (double)x->m / (double)n, x->semi_diagonal,
              x->semi_spectral, x->leapfrog_diagonal, x->leapfrog_spectral, x->spectral_spatial);
    }
    if (fclose(f) != 0) st = gm_error_set(err, GM_EIO, "spectral-star: cannot write '%s'", path);
  }
done:
  free(u);
  free(v);
  if (st != GM_OK) gm_spectral_star_result_clear(r);
  r->wall_s = gm_experiment_clock() - t0;
  return st;
}

gm_status gm_experiment_run_spectral_star(const char *dir, gm_experiment_result *result,
                                          gm_error *err) {
  gm_spectral_star_config c = gm_spectral_star_defaults();
  gm_spectral_star_result r;
  gm_status st = gm_experiment_spectral_star(&c, dir, &r, err);
  if (st != GM_OK) return st;
  gm_experiment_add(result, "steps", (double)r.steps);
  gm_experiment_add(result, "max_rel_frequency_error_semi_diagonal", r.max_rel_semi_diagonal);
  gm_experiment_add(result, "max_rel_frequency_error_semi_spectral", r.max_rel_semi_spectral);
  gm_experiment_add(result, "wall_s", r.wall_s);
  gm_experiment_file(result, dir, "spectral-star.dat");
  gm_spectral_star_result_clear(&r);
  return GM_OK;
}
