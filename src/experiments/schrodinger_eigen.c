/* Seed 001 §5.8: the pseudospectral Schrödinger VI (and Strang split-step Fourier) on
 * i psi_t = -psi_xx/2 + V psi, periodic: eigenvalues from the phase of an evolved eigenstate
 * (gm_schrodinger_eigenvalue), against N and dt. V = x^2/2 on [-10, 10) (Hermite functions,
 * E_k = k + 1/2) and the Poschl-Teller well V = -3 sech^2 x on [-20, 20) (lambda = 2:
 * E_0 = -2 with phi_0 = sqrt(3/4) sech^2 x, E_1 = -1/2 with phi_1 = sqrt(3/2) tanh x sech x). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/pde_spectral.h"

#define SE_PI 3.14159265358979323846
#define HO_BOX 20.0
#define PT_BOX 40.0

static double potential(int pt, double x) { return pt ? -3.0 / (cosh(x) * cosh(x)) : 0.5 * x * x; }

static double eigenstate(int pt, int k, double x) {
  if (pt) return k == 0 ? sqrt(0.75) / (cosh(x) * cosh(x)) : sqrt(1.5) * tanh(x) / cosh(x);
  double h0 = 1.0, h1 = 2.0 * x, hk = k == 0 ? h0 : h1, f = 1.0;
  for (int j = 2; j <= k; j++) {
    hk = 2.0 * x * h1 - 2.0 * (j - 1) * h0;
    h0 = h1;
    h1 = hk;
  }
  for (int j = 1; j <= k; j++) f *= 2.0 * j;
  return hk / sqrt(f) * pow(SE_PI, -0.25) * exp(-0.5 * x * x);
}

static gm_status eigenvalue(int pt, int k, size_t n, double box, gm_schrodinger_scheme sc,
                            double dt, double T, double *E, double *omega, gm_error *err) {
  double *V = malloc(n * sizeof *V), *phi = calloc(2 * n, sizeof *phi);
  if (V == NULL || phi == NULL) {
    free(V);
    free(phi);
    return gm_error_set(err, GM_ENOMEM, "schrodinger-eigen: out of memory");
  }
  for (size_t j = 0; j < n; j++) {
    double x = -0.5 * box + (double)j * box / (double)n;
    V[j] = potential(pt, x);
    phi[2 * j] = eigenstate(pt, k, x);
  }
  gm_schrodinger_options o = gm_schrodinger_options_defaults();
  o.scheme = sc;
  o.dt = dt;
  gm_status st = gm_schrodinger_eigenvalue(n, -0.5 * box, box, V, phi, &o, T, E, omega, err);
  free(V);
  free(phi);
  return st;
}

static gm_status write_tables(const gm_schrodinger_eigen_result *r, const char *dir,
                              gm_error *err) {
  char path[GM_EXPERIMENT_PATH_SIZE];
  FILE *f = NULL;
  if (gm_experiment_path(path, sizeof path, dir, "schrodinger-eigen-n.dat") != GM_OK ||
      (f = fopen(path, "w")) == NULL)
    return gm_error_set(err, GM_EIO, "cannot write '%s/schrodinger-eigen-n.dat'", dir);
  fprintf(f, "# N_harmonic err_E1 err_E3 N_pt err_E0 err_E1(box 60, 1.5 N)\n");
  for (int i = 0; i < GM_SCHRODINGER_EIGEN_N; i++)
    fprintf(f, "%zu %.6e %.6e %zu %.6e %.6e\n", r->n_harmonic[i], r->err_n[i][0], r->err_n[i][1],
            r->n_pt[i], r->err_n[i][2], r->err_n[i][3]);
  if (fclose(f) != 0) return gm_error_set(err, GM_EIO, "cannot write '%s'", path);
  if (gm_experiment_path(path, sizeof path, dir, "schrodinger-eigen-dt.dat") != GM_OK ||
      (f = fopen(path, "w")) == NULL)
    return gm_error_set(err, GM_EIO, "cannot write '%s/schrodinger-eigen-dt.dat'", dir);
  fprintf(f, "# dt err_vi err_split_step\n");
  for (int i = 0; i < GM_SCHRODINGER_EIGEN_DT; i++)
    fprintf(f, "%g %.6e %.6e\n", r->dt[i], r->err_vi[i], r->err_split_step[i]);
  if (fclose(f) != 0) return gm_error_set(err, GM_EIO, "cannot write '%s'", path);
  return GM_OK;
}

gm_status gm_experiment_schrodinger_eigen(const char *dir, gm_schrodinger_eigen_result *r,
                                          gm_error *err) {
  *r = (gm_schrodinger_eigen_result){0};
  const double t0 = gm_experiment_clock();
  static const size_t nh[GM_SCHRODINGER_EIGEN_N] = {16, 24, 32, 40, 48, 56, 64};
  static const size_t np[GM_SCHRODINGER_EIGEN_N] = {32, 64, 96, 128, 160, 192, 224};
  gm_status st;
  for (int i = 0; i < GM_SCHRODINGER_EIGEN_N; i++) {
    double E, om;
    r->n_harmonic[i] = nh[i];
    r->n_pt[i] = np[i];
    if ((st = eigenvalue(0, 1, nh[i], HO_BOX, GM_SCHRODINGER_VI, 0.01, 10.0, &E, &om, err)))
      return st;
    r->err_n[i][0] = fabs(E - 1.5);
    if ((st = eigenvalue(0, 3, nh[i], HO_BOX, GM_SCHRODINGER_VI, 0.01, 10.0, &E, &om, err)))
      return st;
    r->err_n[i][1] = fabs(E - 3.5);
    if ((st = eigenvalue(1, 0, np[i], PT_BOX, GM_SCHRODINGER_VI, 0.005, 10.0, &E, &om, err)))
      return st;
    r->err_n[i][2] = fabs(E + 2.0);
    if ((st = eigenvalue(1, 1, np[i] * 3 / 2, 1.5 * PT_BOX, GM_SCHRODINGER_VI, 0.005, 10.0, &E,
                         &om, err)))
      return st;
    r->err_n[i][3] = fabs(E + 0.5);
  }
  /* the frequency error of harmonic phi_3 (no inversion: the time error itself) */
  double dt = 0.016;
  for (int i = 0; i < GM_SCHRODINGER_EIGEN_DT; i++, dt /= 2.0) {
    double E, om_vi, om_ss;
    if ((st = eigenvalue(0, 3, 64, HO_BOX, GM_SCHRODINGER_VI, dt, 8.0, &E, &om_vi, err)))
      return st;
    if ((st = eigenvalue(0, 3, 64, HO_BOX, GM_SCHRODINGER_SPLIT_STEP, dt, 8.0, &E, &om_ss, err)))
      return st;
    r->dt[i] = dt;
    r->err_vi[i] = fabs(om_vi - 3.5);
    r->err_split_step[i] = fabs(om_ss - 3.5);
  }
  const int last = GM_SCHRODINGER_EIGEN_DT - 1;
  r->order_vi = log2(r->err_vi[last - 1] / r->err_vi[last]);
  r->order_split_step = log2(r->err_split_step[last - 1] / r->err_split_step[last]);
  if (dir != NULL && (st = write_tables(r, dir, err)) != GM_OK) return st;
  r->wall_s = gm_experiment_clock() - t0;
  return GM_OK;
}

gm_status gm_experiment_run_schrodinger_eigen(const char *dir, gm_experiment_result *result,
                                              gm_error *err) {
  gm_schrodinger_eigen_result r;
  gm_status st = gm_experiment_schrodinger_eigen(dir, &r, err);
  if (st != GM_OK) return st;
  const int last = GM_SCHRODINGER_EIGEN_N - 1;
  gm_experiment_add(result, "harmonic_e1_error_n64", r.err_n[last][0]);
  gm_experiment_add(result, "harmonic_e3_error_n64", r.err_n[last][1]);
  gm_experiment_add(result, "poschl_teller_e0_error_n224", r.err_n[last][2]);
  gm_experiment_add(result, "poschl_teller_e1_error_n336", r.err_n[last][3]);
  gm_experiment_add(result, "order_vi", r.order_vi);
  gm_experiment_add(result, "order_split_step", r.order_split_step);
  gm_experiment_add(result, "wall_s", r.wall_s);
  gm_experiment_file(result, dir, "schrodinger-eigen-n.dat");
  gm_experiment_file(result, dir, "schrodinger-eigen-dt.dat");
  return GM_OK;
}
