/* The seeds' experiments that geomint reproduces (DESIGN §1, §5c): one row each in a table
 * (name, seed and section, what it shows, the seed's own number or figure, the command that runs
 * it, a typical run time) and, for the rows whose computation lives in the library, one
 * function that writes its data into a directory and returns its numbers. The library never
 * prints: `geomint experiments list|run` and docs/experiments.md are made from this table. */
#ifndef GEOMINT_EXPERIMENTS_H
#define GEOMINT_EXPERIMENTS_H

#include <stddef.h>
#include <stdint.h>

#include "geomint/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the generic form: named numbers --------------------------------------------------- */

#define GM_EXPERIMENT_MAX_VALUES 24
#define GM_EXPERIMENT_MAX_FILES 4
#define GM_EXPERIMENT_PATH_SIZE 4096

/* What a run returns: its numbers, by name (the names of the CLI's --json: wall_s, steps,
 * max_rel_*), and the files it wrote. */
typedef struct gm_experiment_result {
  size_t n_values;
  const char *names[GM_EXPERIMENT_MAX_VALUES]; /* static strings */
  double values[GM_EXPERIMENT_MAX_VALUES];
  size_t n_files;
  char files[GM_EXPERIMENT_MAX_FILES][GM_EXPERIMENT_PATH_SIZE];
} gm_experiment_result;

/* Run an experiment at its defaults, writing into dir (which must exist). */
typedef gm_status (*gm_experiment_fn)(const char *dir, gm_experiment_result *result,
                                      gm_error *err);

typedef struct gm_experiment_info {
  const char *name;        /* "e4" */
  const char *seed;        /* "000 §3.4.3, Figs 3.7-3.8": seed number, section, figure */
  const char *shows;       /* one sentence: what the experiment shows */
  const char *seed_result; /* the seed's own number or figure, as the seed (or its notes) gives it */
  const char *command;     /* the geomint command that runs it ("maxwell e4") */
  const char *run_time;    /* typical run time at the defaults, on one core ("0.8 s") */
  const char *doc;         /* the docs page (and section) with our figure and numbers */
  /* The computation, or NULL where the CLI command still holds it: then `experiments run`
   * runs `command` itself. */
  gm_experiment_fn run;
} gm_experiment_info;

size_t gm_experiment_count(void);
/* The i-th row, NULL past the end. */
const gm_experiment_info *gm_experiment_at(size_t i);
/* The row named name, NULL if there is none. */
const gm_experiment_info *gm_experiment_find(const char *name);
/* The value named name in result, NAN if it has none. */
double gm_experiment_value(const gm_experiment_result *result, const char *name);

/* ---- E4 (seed 000 §3.4.3, Figs 3.7-3.8) on Yee's grid ----------------------------------- */

typedef struct gm_e4_config {
  size_t n;         /* cells per axis of the unit square, in [2, 2048] (default 32) */
  double t_end;     /* simulated time, > 0 (default 8) */
  uint64_t seed;    /* of the random initial E (default 1) */
  int n_threads;    /* OpenMP threads of the updates, 0: OpenMP's default */
} gm_e4_config;

gm_e4_config gm_e4_defaults(void);

/* A run's numbers and its energy series (owned; gm_e4_result_clear frees them). */
typedef struct gm_e4_result {
  double dt;
  size_t steps;
  double t_final;
  double plain_initial, plain_mean;
  double plain_range_first_half, plain_range_second_half; /* (max - min) / mean per half */
  double leapfrog_max_rel_drift;
  double wall_s;
  size_t n_samples;                 /* steps + 1 */
  double *t, *plain, *leapfrog;     /* owned */
} gm_e4_result;

/* The 2-D TE PEC unit square, N x N cells, random E, steps of 1/10 of the Courant limit, to
 * t_end. With dir non-NULL, writes dir/e4-energy.csv (t, plain, leapfrog). Refuses more than
 * 1e9 steps or series larger than 1 GB (the message names the size). */
gm_status gm_experiment_e4(const gm_e4_config *config, const char *dir, gm_e4_result *result,
                           gm_error *err);
void gm_e4_result_clear(gm_e4_result *result);

/* ---- E1: resonance (seed 000 §2.2, Fig 2.1) --------------------------------------------- */

/* The largest --points the resonance scan accepts: each point is two runs of 10^4 steps (one
 * with 100 substeps), about 17 ms on one core, so this bound is about 6 minutes. */
#define GM_RESONANCE_MAX_POINTS 20000

typedef struct gm_resonance_result {
  size_t n_points, n_near;              /* uniform points, refined points near 1, 2, 3, 4 */
  double imex_min, imex_max;            /* max |H - H0| of imex over the scan */
  double impulse_max, impulse_max_at;   /* impulse (100 substeps): its largest and where */
  size_t impulse_spikes, impulse_blowups; /* values above 1 (= H0 scale), of them blow-ups */
  size_t n_spike_near;
  double spike_near[16];                /* the integers omega h/pi next to the spikes */
  double wall_s;
} gm_resonance_result;

/* Toy problem U = q^2/2, W = omega^2 q^2/2 from q = 0, p = 1, h = 0.1, T = 1000: max |H - H0|
 * of imex and of impulse with 100 substeps at n_points values of omega h/pi in (0, 4.5] plus 48
 * within 0.005 of 1..4. With dir non-NULL, writes dir/resonance.csv. n_points in
 * [1, GM_RESONANCE_MAX_POINTS]. */
gm_status gm_experiment_resonance(size_t n_points, const char *dir, gm_resonance_result *result,
                                  gm_error *err);

/* ---- E2, E3: FPU (seed 000 §2.4, Figs 2.2-2.3) ------------------------------------------ */

#define GM_FPU_MAX_RUNS 8

/* One method's run: max |H - H0| and |I - I0| over the samples, max over samples and j of
 * |I_j - I_j^ref| (NAN for the reference itself), the first sample time with I3 > 0.5 (the
 * energy exchange time scale; NAN if never), I1, I2, I3 at t = 150. */
typedef struct gm_fpu_run_result {
  const char *method; /* static strings */
  const char *title;
  double h;
  size_t steps;
  double max_abs_dh, max_abs_di, max_abs_dev, t_exchange;
  double at150[3];
  char csv[GM_EXPERIMENT_PATH_SIZE]; /* the file written, "" without a directory */
} gm_fpu_run_result;

typedef struct gm_fpu_result {
  int long_run;
  double t_end, sample;
  size_t n_runs;
  gm_fpu_run_result runs[GM_FPU_MAX_RUNS]; /* runs[0]: the Verlet h = 0.001 reference */
  double wall_s;
} gm_fpu_result;

/* FPU with l = 3, omega = 50 (HLW I.5.1). long_run = 0 (E2): T = 200 sampled every 0.6, verlet
 * h = 0.001 (reference), 0.03, imex h = 0.03, 0.1, 0.15, 0.2. long_run = 1 (E3): T = 4000
 * sampled every 1.0, the reference, imex h = 0.1, the trig-* rows h = 0.1, vti h = 0.05. With
 * dir non-NULL, writes dir/fpu[-long]-METHOD-H.csv (t, I1, I2, I3, I, abs_energy_error). */
gm_status gm_experiment_fpu(int long_run, const char *dir, gm_fpu_result *result, gm_error *err);

/* ---- J2 satellite under discrete Routh reduction (seed 001 §2.9, Figs 2.2-2.5) ------------ */

typedef struct gm_j2_config {
  double dt;    /* of the discrete Routh equations, > 0 (default 0.3); the reference uses dt/20 */
  double t_end; /* > 0, at most 1e6 steps (default 150) */
} gm_j2_config;

gm_j2_config gm_j2_defaults(void);

/* Pairs [2]: index 0 and 1 are J2 = 0 and 0.05 (node drifts, discrete_vs_rsprk) or the
 * unreduced (x, y, z) and reduced (r, z) views (the distances: the largest distance of one
 * orbit's points to the other's point set). */
typedef struct gm_j2_result {
  double r0, inclination, speed, mu; /* the initial orbit (the thesis gives none) */
  double dt, t_end;
  size_t steps;
  double discrete_vs_rsprk[2];       /* discrete Routh equations against RSPRK Gauss-1 */
  double node_drift_continuous[2], node_drift_discrete[2]; /* rad over the run */
  double continuous_j2_to_continuous_0[2]; /* the physical precession */
  double discrete_0_to_continuous_0[2];    /* the discretisation's */
  double discrete_j2_to_continuous_0[2];
  double discrete_j2_to_continuous_j2[2];
  double wall_s;
} gm_j2_result;

/* With dir non-NULL, writes dir/j2-{0,0.05}-{continuous,discrete}.csv (t, r, z, theta, x, y). */
gm_status gm_experiment_j2_satellite(const gm_j2_config *config, const char *dir,
                                     gm_j2_result *result, gm_error *err);

/* ---- double spherical pendulum under Routh reduction (seed 001 §2.10, Figs 2.7-2.9) ------- */

typedef struct gm_dsp_config {
  double mu;    /* momentum level (default 1) */
  double x0[6]; /* r1, r2, phi, r1', r2', phi' with 0 < r_i < 1 (default 0.5, 0.4, 2, 0, 0, 0) */
  double dt;    /* > 0 (default 0.01); RK4 takes dt/4 */
  double t_end; /* > 0, at most 1e6 steps (default 20) */
} gm_dsp_config;

gm_dsp_config gm_dsp_defaults(void);

typedef struct gm_dsp_result {
  double m1, m2, l1, l2, g, mu, x0[6], dt, t_end;
  size_t steps;
  double energy0;                            /* the reduced energy at the start */
  double rsprk_max_rel_energy_error, rsprk_max_rel_energy_error_first_half;
  double rk4_max_rel_energy_error;
  double rsprk_tenths[2], rk4_tenths[2];     /* max |E - E0|/|E0| in the first, last tenth */
  double max_rel_rsprk_vs_sprk[4];           /* r1, r2, phi, E */
  double min_r;                              /* smallest r_i along the run */
  double constrained_energy0, constrained_max_rel_energy_error;
  double wall_s;
} gm_dsp_result;

/* m1 = m2 = l1 = l2 = 1, g = 9.81. With dir non-NULL, writes dir/dsp.csv and
 * dir/dsp-constrained.csv. */
gm_status gm_experiment_double_spherical_pendulum(const gm_dsp_config *config, const char *dir,
                                                  gm_dsp_result *result, gm_error *err);

/* ---- seed 003 §6: the mimetic integrators' four tests ------------------------------------- */

#define GM_MIMETIC_METHODS 5     /* mimetic-canonical-2, mimetic-galerkin-2, rk4, euler, symplectic-euler-a */
#define GM_MIMETIC_CONVERGENCE 3 /* the first three: MCI, MGI, RK4 */
#define GM_MIMETIC_LEVELS 6      /* steps conv_dt0 / 2^l */

extern const char *const gm_mimetic_experiment_methods[GM_MIMETIC_METHODS];

/* One test: the model and its setting, the steps of the phase portrait and of the invariant
 * figure, the state components drawn, the invariant (NULL: the energy; else a part of an
 * invariant's name) and the convergence study's first step and final time. */
typedef struct gm_mimetic_info {
  const char *name, *model, *setting; /* setting: "name=value" as printed, or NULL */
  const char *setting_name;
  double setting_value;
  double dt_phase, dt_invariant, t_end;
  size_t x, y;
  const char *xlabel, *ylabel;
  const char *invariant;
  const char *invariant_label;
  double conv_dt0, conv_t_end;
} gm_mimetic_info;

/* circular, lotka-volterra, pendulum, kepler; NULL for another name */
const gm_mimetic_info *gm_mimetic_find(const char *name);

typedef struct gm_mimetic_run {
  const char *method; /* static */
  double dt;
  int status;         /* 0 ran to the end, 1 stopped on the way, -1 does not apply */
  char why[GM_ERRMSG_SIZE + 32]; /* the reason of status != 0 */
  double max_invariant_error;
  char csv[GM_EXPERIMENT_PATH_SIZE]; /* "" without a directory */
} gm_mimetic_run;

typedef struct gm_mimetic_result {
  const gm_mimetic_info *info;
  size_t state_size;
  size_t n_runs; /* each method at dt_phase, then (if different) at dt_invariant */
  gm_mimetic_run runs[2 * GM_MIMETIC_METHODS];
  int convergence_done;
  double dts[GM_MIMETIC_LEVELS];
  double state_error[GM_MIMETIC_CONVERGENCE][GM_MIMETIC_LEVELS];
  double invariant_error[GM_MIMETIC_CONVERGENCE][GM_MIMETIC_LEVELS];
  double order[GM_MIMETIC_CONVERGENCE], invariant_order[GM_MIMETIC_CONVERGENCE]; /* NAN: no fit */
  int invariant_kept[GM_MIMETIC_CONVERGENCE]; /* the invariant at round-off (<= 1e-13) at all steps */
  double wall_s;
} gm_mimetic_result;

/* With dir non-NULL, writes dir/NAME-METHOD-DT.csv (t, state, invariant error) and
 * dir/NAME-convergence.csv. On an error after some runs, n_runs says how many are valid. */
gm_status gm_experiment_mimetic(const char *name, const char *dir, gm_mimetic_result *result,
                                gm_error *err);

#ifdef __cplusplus
}
#endif

#endif
