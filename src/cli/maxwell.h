/* Private to the `geomint maxwell` command: the JSON scene (maxwell_scene.c), the runs
 * (maxwell_run.c, maxwell_cavity.c, maxwell_e4.c) and their plots (maxwell_plot.c). */
#ifndef GM_CLI_MAXWELL_H
#define GM_CLI_MAXWELL_H

#include <stddef.h>
#include <stdio.h>

#include "cli/cli.h"

#define MX_NAME_CAP 64

typedef struct mx_probe {
  char name[MX_NAME_CAP];
  gm_yee_component component;
  double x[3];
} mx_probe;

typedef struct mx_flux {
  char name[MX_NAME_CAP];
  int axis;
  double position; /* coordinate along axis; the nearest vertex plane is used */
  size_t index;    /* that plane's index, set by mx_scene_build */
} mx_flux;

typedef struct mx_scene {
  gm_yee_grid grid;
  gm_yee_options options;
  gm_yee_materials *materials;    /* owned */
  size_t n_points, n_planes;
  gm_point_source *points;        /* owned */
  gm_plane_wave *planes;          /* owned */
  size_t *point_json, *plane_json; /* owned: index of each in the JSON "sources" array */
  size_t n_obliques;
  gm_oblique_wave *obliques;      /* owned: plane waves given by angles */
  size_t *oblique_json;           /* owned: as point_json */
  size_t n_probes, n_fluxes;
  mx_probe *probes;               /* owned */
  mx_flux *fluxes;                /* owned */
  /* run */
  size_t steps;                   /* > 0: this many steps */
  double time;                    /* steps == 0: advance to this time */
  /* output */
  size_t snapshot_every;          /* 0: no snapshots */
  unsigned snapshot_formats;      /* GM_SNAPSHOT_VTI | GM_SNAPSHOT_HDF5 */
  gm_vti_encoding encoding;
  int snapshot_materials;         /* write ε, μ, σ into the snapshots */
  size_t energy_every;            /* 0: no energy series */
  int harminv;                    /* resonances of the probe signals */
  double harminv_fmin, harminv_fmax, harminv_after;
} mx_scene;

/* Read and check a scene file. On failure returns CLI_EXIT_USAGE after writing
 * "FILE: json.path: what is wrong" (one line) into msg. */
int mx_scene_load(const char *path, mx_scene *scene, char *msg, size_t cap);
/* The same from a JSON text (name is used in messages). */
int mx_scene_parse(const char *text, const char *name, mx_scene *scene, char *msg, size_t cap);
void mx_scene_clear(mx_scene *scene);
/* Create the solver with the scene's sources and probes (probe capacity for the whole run).
 * Errors the library reports (a source outside the grid, a PML thicker than the grid, a step
 * above the Courant limit) come back as CLI_EXIT_USAGE with the JSON path of the culprit. */
int mx_scene_build(mx_scene *scene, const char *name, gm_yee **out, char *msg, size_t cap);
/* Steps the run makes (from steps or time). */
size_t mx_scene_total_steps(const mx_scene *scene, double dt);

/* The usage text of `geomint maxwell` (maxwell.c). */
const char *mx_usage(void);
/* Create directory dir when missing (its parent must exist); an exit status, the reason
 * printed on failure. */
int mx_make_dir(const char *command, const char *dir);
/* dir/name into buf. */
const char *mx_path(char *buf, size_t cap, const char *dir, const char *name);

/* ---- harminv summaries ---------------------------------------------------------------- */
/* Modes of a signal in [f_min, f_max] (harminv), kept when harminv's error estimate is below
 * 1e-4, |Q| > 1 and the amplitude above 1e-6 of the largest; ascending frequency; returns how
 * many (<= cap). On a harminv failure returns 0 with the reason in msg. */
size_t mx_resonances(const double *signal, size_t n, double dt, double f_min, double f_max,
                     gm_harminv_mode *modes, size_t cap, char *msg, size_t msg_cap);

/* ---- progress on a terminal ----------------------------------------------------------- */
typedef struct mx_progress {
  int enabled;       /* stderr is a TTY */
  double t_start;
  size_t total;
} mx_progress;
void mx_progress_start(mx_progress *p, size_t total);
void mx_progress_show(mx_progress *p, size_t done);
void mx_progress_end(mx_progress *p);
double mx_now(void);

/* ---- plots ------------------------------------------------------------------------------ */
typedef struct mx_line {
  const char *title;
  size_t n;
  const double *x, *y; /* borrowed */
  int points;          /* draw points (1) or lines (0) */
} mx_line;

/* Lines on linear axes (logy: log scale on y; non-positive values left out). */
int mx_plot_lines(const char *command, const char *png, const char *title, const char *xlabel,
                  const char *ylabel, int logy, const mx_line *lines, size_t n_lines);
/* Spectrum: the sum over n_signals signals (rows of n samples) of |DFT| (Hann window), log y,
 * on [0, f_max], with vertical marks at the given frequencies. */
int mx_plot_spectrum(const char *command, const char *png, const char *title, size_t n_signals,
                     size_t n, const double *signals, double dt, double f_max,
                     const double *marks, size_t n_marks);
/* A colour map of values[nx*ny] (x fastest) on [x0, x0 + nx hx] × [y0, y0 + ny hy]. */
int mx_plot_map(const char *command, const char *png, const char *title, const char *label,
                size_t nx, size_t ny, double x0, double y0, double hx, double hy,
                const double *values);

#endif
