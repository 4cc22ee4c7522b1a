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

#ifdef __cplusplus
}
#endif

#endif
