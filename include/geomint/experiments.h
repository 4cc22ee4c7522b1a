/* The seeds' experiments that geomint reproduces (DESIGN §1, §5c): one row each in a table
 * (name, seed and section, what it shows, the seed's own number or figure, the command that runs
 * it) and one function that writes its data into a directory and returns its numbers. The library never
 * prints: `geomint experiments list|run` and docs/experiments.md are made from this table. */
#ifndef GEOMINT_EXPERIMENTS_H
#define GEOMINT_EXPERIMENTS_H

#include <stddef.h>
#include <stdint.h>

#include "geomint/core.h"
#include "geomint/fields.h"
#include "geomint/mesh.h"

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
  const char *doc;         /* the docs page (and section) with our figure and numbers */
  /* The computation (every row has one; the command prints the same numbers). */
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


/* ---- seed 001 §5.1: the tent-function VI on sine-Gordon ---------------------------------- */

typedef struct gm_tent_vi_config {
  int kink;     /* 0: the standing breather of frequency param; 1: the kink of speed param */
  double param; /* in (0, 1) (default 0.5) */
  size_t n;     /* points on [-20, 20), in [4, 1e8] (default 200) */
  double dt;    /* > 0 (default 0.1) */
  double t_end; /* > 0, at most 1e9 steps (default 10) */
} gm_tent_vi_config;

gm_tent_vi_config gm_tent_vi_defaults(void);

typedef struct gm_tent_vi_result {
  size_t n, steps;
  double h, dt, t;
  double energy0, energy, max_rel_energy_error; /* the strip energy at the start, the end */
  double max_abs_error;                          /* max |u - exact| at t */
  double wall_s;
} gm_tent_vi_result;

/* From the exact solution at t = 0 and dt to t_end. With csv non-NULL, writes x,u,exact at the
 * end there. */
gm_status gm_experiment_tent_vi(const gm_tent_vi_config *config, const char *csv,
                                gm_tent_vi_result *result, gm_error *err);

/* ---- seed 004 Figs 11-13: B10, the stability of LF, EC and MS ------------------------------ */

#define GM_B10_RUNS 5

typedef enum gm_b10_outcome {
  GM_B10_BOUNDED = 0, /* ran to its end */
  GM_B10_UNBOUNDED,   /* max |u| > 100 at step `step` */
  GM_B10_FAILED       /* the scheme failed at step `step` (the reason in why) */
} gm_b10_outcome;

typedef struct gm_b10_run {
  const char *scheme; /* static: lf, ec, ms */
  double ratio;       /* dt/dx */
  double t_end;
  gm_b10_outcome outcome;
  size_t step;        /* the step that ended the run (1-based), or the steps run */
  double t;           /* the time reached */
  double max_abs_u;   /* at t */
  double max_rel_energy_error; /* over the steps before the end */
  char why[GM_ERRMSG_SIZE];
} gm_b10_run;

typedef struct gm_b10_result {
  size_t n;     /* 200 */
  double h;     /* 0.2 */
  size_t n_runs;
  gm_b10_run runs[GM_B10_RUNS]; /* lf, ec, ms at dt = dx to t = 500; ec, ms at 2 dx to 100 */
  double wall_s;
} gm_b10_result;

/* The sine-Gordon breather w = 0.5 on [-20, 20), N = 200; a run stops when max |u| > 100 or the
 * scheme fails. With dir non-NULL, writes dir/b10-SCHEME-RATIO.dat (t, max|u|, relative energy
 * change, running max|u|). */
gm_status gm_experiment_b10(const char *dir, gm_b10_result *result, gm_error *err);

/* ---- seed 004 §4: the NLS two-soliton collision over many periods -------------------------- */

/* the period counted: the phase period 2 pi/(a^2 - c^2/4) of the larger soliton, a = 1,
 * c = pi/5 */
#define GM_NLS_LONG_PERIOD (2.0 * 3.14159265358979323846 / (1.0 - 3.14159265358979323846 * \
                                                               3.14159265358979323846 / 100.0))

typedef struct gm_nls_long_config {
  double periods; /* > 0 (default 1e4), at most 1e9 steps */
  size_t n;       /* points on [-20, 20), in [16, 1e5] (default 128) */
  double dt;      /* > 0 (default 0.1) */
  size_t every;   /* a row every K steps; 0: the run in 2000 rows (default 0) */
  const char *only; /* NULL both, or "preissmann" / "box-sdirk2" (borrowed) */
} gm_nls_long_config;

gm_nls_long_config gm_nls_long_defaults(void);

typedef struct gm_nls_long_scheme {
  const char *scheme; /* static; NULL: not run (--only) */
  /* max relative errors in the first and the last tenth of the run */
  double energy[2], momentum[2], charge[2];
} gm_nls_long_scheme;

typedef struct gm_nls_long_result {
  size_t n, steps, every;
  double dt, periods, t_end;
  gm_nls_long_scheme schemes[2]; /* preissmann, box-sdirk2 */
  double wall_s;
} gm_nls_long_result;

/* Preissmann (multisymplectic) against box-sdirk2 (not symplectic). With dir non-NULL, writes
 * dir/nls-long-SCHEME.dat (t/period, |dE/E|, |dP/P|, |dN/N|). */
gm_status gm_experiment_nls_long(const gm_nls_long_config *config, const char *dir,
                                 gm_nls_long_result *result, gm_error *err);

/* ---- seed 000 §3.3.4: the spectral Hodge star's dispersion --------------------------------- */

typedef struct gm_spectral_star_config {
  size_t n;       /* even, in [4, 4096] (default 64) */
  double courant; /* dt = courant h, in (0, 2/pi] (default 0.1) */
} gm_spectral_star_config;

gm_spectral_star_config gm_spectral_star_defaults(void);

/* One mode m = 1 .. n/2 - 1: relative frequency errors. */
typedef struct gm_spectral_star_mode {
  long m;
  double semi_diagonal, semi_spectral;         /* semi-discrete (Rayleigh quotient) */
  double leapfrog_diagonal, leapfrog_spectral; /* with leapfrog, measured from the phase */
  double spectral_spatial; /* (omega measured - leapfrog's omega of the exact k) / k */
} gm_spectral_star_mode;

typedef struct gm_spectral_star_result {
  size_t n, steps;
  double courant, dt, t_end;
  size_t n_modes;
  gm_spectral_star_mode *modes; /* owned: gm_spectral_star_result_clear */
  double max_rel_semi_spectral, max_rel_semi_diagonal;
  double wall_s;
} gm_spectral_star_result;

/* u_tt = *d*d u on [0, 2 pi), the diagonal and the spectral star. With dir non-NULL, writes
 * dir/spectral-star.dat. */
gm_status gm_experiment_spectral_star(const gm_spectral_star_config *config, const char *dir,
                                      gm_spectral_star_result *result, gm_error *err);
void gm_spectral_star_result_clear(gm_spectral_star_result *result);

/* ---- seed 001 §5.8: Schrödinger eigenvalues by evolution ----------------------------------- */

#define GM_SCHRODINGER_EIGEN_N 7
#define GM_SCHRODINGER_EIGEN_DT 4

typedef struct gm_schrodinger_eigen_result {
  /* against N: harmonic E1, E3 (box 20) at n_harmonic[i]; Poschl-Teller E0 (box 40) at
   * n_pt[i], E1 (box 60) at 1.5 n_pt[i]; |E_N - E| */
  size_t n_harmonic[GM_SCHRODINGER_EIGEN_N], n_pt[GM_SCHRODINGER_EIGEN_N];
  double err_n[GM_SCHRODINGER_EIGEN_N][4];
  /* against dt: |Omega - 3.5| of harmonic phi_3, N = 64, T = 8: VI, split-step */
  double dt[GM_SCHRODINGER_EIGEN_DT], err_vi[GM_SCHRODINGER_EIGEN_DT],
      err_split_step[GM_SCHRODINGER_EIGEN_DT];
  double order_vi, order_split_step; /* the last two dt's log2 ratio */
  double wall_s;
} gm_schrodinger_eigen_result;

/* The pseudospectral VI (and Strang split-step) on V = x^2/2 and V = -3 sech^2 x. With dir
 * non-NULL, writes dir/schrodinger-eigen-n.dat and dir/schrodinger-eigen-dt.dat. */
gm_status gm_experiment_schrodinger_eigen(const char *dir, gm_schrodinger_eigen_result *result,
                                          gm_error *err);

/* ---- seed 001 §5.7: the multiscale VI, MsFEM ---------------------------------------------- */

#define GM_MULTISCALE_T 2
#define GM_MULTISCALE_H 4
#define GM_MULTISCALE_MSFEM 7

/* One column of the multiscale table: errors of a and theta at T against the reference, or
 * the step at which it failed (status 1: Newton failed at `step`; -1: the run failed). */
typedef struct gm_multiscale_cell {
  int status;
  size_t step;
  double da, dtheta;
} gm_multiscale_cell;

typedef struct gm_multiscale_result {
  double t_end[GM_MULTISCALE_T], h[GM_MULTISCALE_H];
  size_t steps[GM_MULTISCALE_T][GM_MULTISCALE_H];
  /* msvi additive, vi-midpoint (polar), imex (Cartesian), msvi product on l + a, msvi product
   * on a (the seed's) */
  gm_multiscale_cell cells[GM_MULTISCALE_T][GM_MULTISCALE_H][5];
  size_t msfem_n[GM_MULTISCALE_MSFEM];
  double msfem_p1_error[GM_MULTISCALE_MSFEM]; /* P1's nodal error against MsFEM's exact nodes */
  double wall_s;
} gm_multiscale_result;

/* The stiff spring pendulum (m = 1, g = 9.81, k = 1e4, l = 1, theta0 = 1 at rest) against
 * vi-galerkin-gauss-2 at h = 1e-4; MsFEM against P1 on (a(x/eps) u')' = x^2. */
gm_status gm_experiment_multiscale(gm_multiscale_result *result, gm_error *err);

/* ---- seed 001 ch. 4: geometric phases against closed forms -------------------------------- */

#define GM_PHASES_ROWS 12

typedef struct gm_phases_row {
  const char *what, *how; /* static */
  int mesh;               /* 1: a tet-mesh row (error = max |angle - deficit|, one level) */
  double closed, computed;
  double error[2];        /* at the two levels (error[1] NAN for a mesh row) */
  char levels[160];
} gm_phases_row;

typedef struct gm_phases_result {
  size_t n_rows;
  gm_phases_row rows[GM_PHASES_ROWS];
  double rigid_period, rigid_dynamic, rigid_solid_angle; /* Montgomery's terms */
  double max_error;  /* the largest error of any row at its finest level */
  double wall_s;
} gm_phases_result;

/* Foucault, a spherical cap, Montgomery's rigid-body phase, a shape loop of the double
 * spherical pendulum, two tet-mesh Levi-Civita holonomies. With dir non-NULL, also the
 * convergence data dir/phases-convergence.csv. */
gm_status gm_experiment_phases(const char *dir, gm_phases_result *result, gm_error *err);

/* ---- harminv, filtered ------------------------------------------------------------------- */

/* harminv's basis size (0: its default) and the filter on the modes it returns (the scene
 * keys output.harminv.basis, max_error, min_q, min_amplitude). */
typedef struct gm_resonance_params {
  size_t basis;
  double max_error, min_q, min_amplitude;
} gm_resonance_params;

/* basis 0, max_error 1e-4, min_q 1, min_amplitude 1e-6 */
gm_resonance_params gm_resonance_params_defaults(void);

/* Modes of a signal in [f_min, f_max] (gm_harminv), kept when harminv's error estimate is
 * below max_error, |Q| > min_q and the amplitude above min_amplitude of the largest (params
 * NULL: the defaults); ascending frequency; *n_modes <= cap. */
gm_status gm_experiment_resonances_with(const double *signal, size_t n, double dt, double f_min,
                                        double f_max, const gm_resonance_params *params,
                                        gm_harminv_mode *modes, size_t cap, size_t *n_modes,
                                        gm_error *err);
/* gm_experiment_resonances_with and the defaults */
gm_status gm_experiment_resonances(const double *signal, size_t n, double dt, double f_min,
                                   double f_max, gm_harminv_mode *modes, size_t cap,
                                   size_t *n_modes, gm_error *err);

/* ---- seed 000 §3.4.1: the rectangular PEC cavity on Yee's grid ---------------------------- */

#define GM_CAVITY_CHECK 10
#define GM_CAVITY_BAND 400

typedef struct gm_cavity_config {
  int dim;        /* 2 (TM in [0,1]x[0,0.8]) or 3 ([0,1]x[0,0.8]x[0,0.6]) (default 3) */
  size_t n;       /* cells per axis, [4, 256] in 3-D, [4, 4096] in 2-D (default 16) */
  double periods; /* of the lowest mode, in [10, 1e5] (default 200) */
  int n_threads;  /* 0: OpenMP's default */
  /* called now and then with the steps done and their total; non-zero stops the run */
  int (*progress)(void *ctx, double done, double total);
  void *progress_ctx;
} gm_cavity_config;

gm_cavity_config gm_cavity_defaults(void);

typedef struct gm_cavity_mode {
  int m[3];
  double analytic, yee; /* f = 1/2 sqrt(sum (m/L)^2); Yee's discrete dispersion relation */
  int found;
  gm_harminv_mode computed;
} gm_cavity_mode;

typedef struct gm_cavity_result {
  int dim;
  size_t n, cells, steps;
  double dt, f_max; /* f_max: the top of harminv's band */
  size_t n_modes;
  gm_cavity_mode modes[GM_CAVITY_CHECK];
  size_t n_found, n_harminv, spurious, n_probes;
  /* the probes' E from the end of the pulse on: n_probes rows of n_signal samples (owned:
   * gm_cavity_result_clear) */
  size_t n_signal;
  double *signals;
  double max_rel_error_yee, max_rel_error_analytic; /* over the modes found */
  double wall_s;
} gm_cavity_result;

/* A band-limited pulse rings the cavity; harminv of each E probe; the first 10 distinct modes
 * against the analytic and the Yee frequencies. */
gm_status gm_experiment_cavity(const gm_cavity_config *config, gm_cavity_result *result,
                               gm_error *err);
void gm_cavity_result_clear(gm_cavity_result *result);


/* ---- seed 000 §3.4.2 (E5's claim): PEC cavities on tetrahedral meshes ---------------------- */

#define GM_MESH_CAVITY_MAX_LEVELS 6
#define GM_MESH_CAVITY_MAX_MODES 128
#define GM_MESH_CAVITY_MAX_UNIQ 16
#define GM_MESH_CAVITY_MAX_T_END 1e4 /* the probe signals are kept in memory */

typedef struct gm_mesh_cavity_config {
  const char *shape;    /* "box", "cylinder" or "sphere" (default "box") */
  const char *mesh_dir; /* cylinder, sphere: mesh_dir/cavity_SHAPE_K.msh (default "examples") */
  size_t levels;        /* resolutions, 1..6 (default 3) */
  size_t n0;            /* box: cubes along x at level 1, 3..40 (default 5) */
  size_t n_first;       /* the band covers the first n_first resonances (default 10) */
  int diagonal;         /* the circumcentric diagonal star instead of the Whitney star */
  double t_end;         /* record length, (0, 1e4] (default 150) */
  uint64_t seed;        /* sources and probes (default 11) */
  /* called with the steps done and planned at each level; non-zero stops the run */
  int (*progress)(void *ctx, double done, double total);
  void *progress_ctx;
} gm_mesh_cavity_config;

gm_mesh_cavity_config gm_mesh_cavity_defaults(void);

typedef struct gm_mesh_cavity_level {
  double h;                 /* box: 1/(n0 k); files: the mean edge length */
  size_t n_tetrahedra, n_edges;
  double dt;
  size_t n_peaks, in_band;  /* peaks found; analytic modes in the band with multiplicity */
  double peaks[GM_MESH_CAVITY_MAX_MODES]; /* spatial frequencies (dispersion undone) */
  int spurious_peak[GM_MESH_CAVITY_MAX_MODES]; /* farther than 5 % from every resonance */
  size_t spurious;
} gm_mesh_cavity_level;

typedef struct gm_mesh_cavity_result {
  gm_mesh_cavity_run run; /* the ringing's settings (its progress fields unset) */
  size_t levels;
  gm_mesh_cavity_level level[GM_MESH_CAVITY_MAX_LEVELS];
  size_t n_uniq;            /* distinct resonances of the band */
  double uniq[GM_MESH_CAVITY_MAX_UNIQ];
  int mult[GM_MESH_CAVITY_MAX_UNIQ];
  /* relative error per resonance and level of the nearest peak, and of the farthest of the
   * peaks nearest to it (a multiplet split by the mesh); NAN: not found at that level */
  double nearest[GM_MESH_CAVITY_MAX_UNIQ][GM_MESH_CAVITY_MAX_LEVELS];
  double farthest[GM_MESH_CAVITY_MAX_UNIQ][GM_MESH_CAVITY_MAX_LEVELS];
  /* least-squares slopes of log |error| against log h over the levels where it was found
   * (NAN with fewer than two) */
  double rate_nearest[GM_MESH_CAVITY_MAX_UNIQ], rate_farthest[GM_MESH_CAVITY_MAX_UNIQ];
  double band_max[GM_MESH_CAVITY_MAX_LEVELS]; /* the largest farthest-peak error per level */
  double band_rate;                           /* its slope (NAN with one level) */
  size_t spurious;                            /* over all levels */
  double wall_s;
} gm_mesh_cavity_result;

/* Per level: the mesh (box: gm_mesh_bcc; else the file), the leapfrog rung by current pulses
 * (gm_mesh_maxwell_cavity_modes), harminv's peaks mapped to spatial frequencies and compared
 * with the analytic resonances (gm_cavity_*_resonances). GM_EINVAL for bad input or a missing
 * mesh file; GM_EDOMAIN when a run blew up. */
gm_status gm_experiment_mesh_cavity(const gm_mesh_cavity_config *config,
                                    gm_mesh_cavity_result *result, gm_error *err);


/* ---- E5 (seed 000 §3.4.3, Fig 3.9): the AVI on a Gmsh box cavity ------------------------- */

#define GM_E5_MAX_MODES 64

typedef struct gm_e5_config {
  double t_end;     /* the resonance runs' length, > 0 (default 8) */
  uint64_t seed;    /* of the random initial E (default 1) */
  double f_max;     /* the analytic resonances up to f_max (default 2) */
  double fraction;  /* the AVI's faces at this fraction of their local limit (default 0.25) */
  double sample_dt; /* the AVI's probe interval (default 0.005) */
  double t_compare; /* the cost comparison's final time (default 1) */
  /* called now and then with the work done and its (estimated) total; non-zero stops */
  int (*progress)(void *ctx, double done, double total);
  void *progress_ctx;
} gm_e5_config;

gm_e5_config gm_e5_defaults(void);

/* harminv's peaks (error < 1e-3, merged within 0.3 %) of the three E probes against the
 * analytic resonances */
typedef struct gm_e5_spectrum {
  size_t n_peaks;
  double peaks[GM_E5_MAX_MODES], nearest[GM_E5_MAX_MODES], rel_error[GM_E5_MAX_MODES];
  size_t matched;  /* of the first n_check analytic resonances, seen within 5 % */
  size_t spurious; /* peaks farther than 5 % from every resonance */
  double worst;    /* the largest error of the other peaks */
} gm_e5_spectrum;

typedef struct gm_e5_run {
  int ran;
  double dt;            /* the step (the AVI: its smallest face step) */
  size_t steps, avi_groups, face_updates, edge_updates;
  double cpu_s;
  gm_e5_spectrum spectrum;
  double energy0, energy, max_rel_energy_error, max_energy_ratio; /* plain energy, 1000 samples */
  double max_div_b, gauss_drift;
  size_t n_samples;     /* per probe */
  double sample_dt;
  double *signals;      /* owned: E_x, E_y, E_z at the probe, n_samples each */
} gm_e5_run;

typedef struct gm_e5_result {
  double L[3], probe[3];
  size_t n_analytic, n_check;
  double analytic[GM_E5_MAX_MODES];
  double f_lo, f_top;   /* harminv's band */
  size_t n_tetrahedra, n_edges, n_faces;
  double volume_min, volume_max;
  int positive;         /* the circumcentric stars are positive: the AVI runs */
  char star_message[GM_ERRMSG_SIZE]; /* why not */
  int have_limits;
  double cfl_limit, face_limit_min, face_limit_max, face_limit_median;
  size_t small_faces;   /* below 1/4 of the median */
  gm_e5_run avi, whitney;
  /* the cost to t_compare: uniform leapfrog (diagonal star) at the AVI's smallest step, the
   * AVI, the Whitney leapfrog at its own step */
  double uniform_dt, uniform_face_updates, uniform_cpu_s;
  size_t uniform_steps, avi_face_updates, whitney_steps;
  double avi_cpu_s, whitney_cpu_s;
  double wall_s;
} gm_e5_result;

/* Seed 000 E5 on a tetrahedral mesh of a box (borrowed; examples/e5_cavity.msh): the stars
 * checked, the AVI and the Whitney-star leapfrog from a random E, harminv at one point against
 * the box's analytic resonances, the invariants, and the cost against uniform stepping. A
 * blow-up (the AVI's plain energy above 10 x its start, or non-finite energy) is GM_EDOMAIN
 * with the time and the ratio. */
gm_status gm_experiment_e5(const gm_mesh *mesh, const gm_e5_config *config,
                           gm_e5_result *result, gm_error *err);
void gm_e5_result_clear(gm_e5_result *result);

#ifdef __cplusplus
}
#endif

#endif
