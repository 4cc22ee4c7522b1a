/* Private helpers of the experiments module; never installed. */
#ifndef GM_EXPERIMENTS_INTERNAL_H
#define GM_EXPERIMENTS_INTERNAL_H

#include <stddef.h>

#include "geomint/experiments.h"
#include "geomint/ode.h"
#include "geomint/problems.h"

/* Monotonic wall-clock seconds (the runs' wall_s). */
double gm_experiment_clock(void);
/* dir/name into buf; GM_EINVAL when it does not fit. */
gm_status gm_experiment_path(char *buf, size_t cap, const char *dir, const char *name);
/* Append a named number (name: a static string) / a written file to a result; extra entries past
 * the capacity are dropped (the table's rows stay within it). */
void gm_experiment_add(gm_experiment_result *result, const char *name, double value);
void gm_experiment_file(gm_experiment_result *result, const char *dir, const char *name);

/* The model `name` at its defaults, built; the reason in err. */
gm_status gm_experiment_model(const char *name, gm_model **out, gm_error *err);
/* An integrator of the row `method` at the model's initial state (with substeps > 0 for the
 * impulse rows); the reason in err. */
gm_status gm_experiment_start(const gm_model *model, const char *method, size_t substeps,
                              gm_integrator **out, gm_error *err);

/* The rows' runners at their defaults (one file each). */
gm_status gm_experiment_run_e4(const char *dir, gm_experiment_result *result, gm_error *err);
gm_status gm_experiment_run_resonance(const char *dir, gm_experiment_result *result,
                                      gm_error *err);
gm_status gm_experiment_run_fpu(const char *dir, gm_experiment_result *result, gm_error *err);
gm_status gm_experiment_run_fpu_long(const char *dir, gm_experiment_result *result,
                                     gm_error *err);
gm_status gm_experiment_run_j2_satellite(const char *dir, gm_experiment_result *result,
                                         gm_error *err);
gm_status gm_experiment_run_double_spherical_pendulum(const char *dir, gm_experiment_result *result,
                                                      gm_error *err);
gm_status gm_experiment_run_mimetic_circular(const char *dir, gm_experiment_result *result,
                                             gm_error *err);
gm_status gm_experiment_run_mimetic_lotka_volterra(const char *dir, gm_experiment_result *result,
                                                   gm_error *err);
gm_status gm_experiment_run_mimetic_pendulum(const char *dir, gm_experiment_result *result,
                                             gm_error *err);
gm_status gm_experiment_run_mimetic_kepler(const char *dir, gm_experiment_result *result,
                                           gm_error *err);

gm_status gm_experiment_run_tent_vi(const char *dir, gm_experiment_result *result, gm_error *err);
gm_status gm_experiment_run_b10(const char *dir, gm_experiment_result *result, gm_error *err);
gm_status gm_experiment_run_nls_long(const char *dir, gm_experiment_result *result,
                                     gm_error *err);
gm_status gm_experiment_run_spectral_star(const char *dir, gm_experiment_result *result,
                                          gm_error *err);
gm_status gm_experiment_run_schrodinger_eigen(const char *dir, gm_experiment_result *result,
                                              gm_error *err);
gm_status gm_experiment_run_multiscale(const char *dir, gm_experiment_result *result,
                                       gm_error *err);
gm_status gm_experiment_run_phases(const char *dir, gm_experiment_result *result, gm_error *err);
gm_status gm_experiment_run_cavity(const char *dir, gm_experiment_result *result, gm_error *err);
gm_status gm_experiment_run_mesh_cavity(const char *dir, gm_experiment_result *result,
                                        gm_error *err);
gm_status gm_experiment_run_e5(const char *dir, gm_experiment_result *result, gm_error *err);

#endif
