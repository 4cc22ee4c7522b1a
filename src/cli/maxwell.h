/* Private to the `geomint maxwell` command: the runs (the scene file is read by the library,
 * geomint/yee_scene.h:
 * (maxwell_run.c, maxwell_cavity.c, maxwell_e4.c) and their plots (maxwell_plot.c). */
#ifndef GM_CLI_MAXWELL_H
#define GM_CLI_MAXWELL_H

#include <stddef.h>
#include <stdio.h>

#include "cli/cli.h"
#include "geomint/experiments.h"
#include "geomint/yee_scene.h"

/* The usage text of `geomint maxwell` (maxwell.c). */
const char *mx_usage(void);
/* Create directory dir when missing (its parent must exist); an exit status, the reason
 * printed on failure. */
int mx_make_dir(const char *command, const char *dir);
/* The same for the folder an option other than --out names (the message names that option). */
int mx_make_option_dir(const char *command, const char *option, const char *dir);
/* dir/name into buf. */
const char *mx_path(char *buf, size_t cap, const char *dir, const char *name);

/* ---- MPI (maxwell_run_mpi.c, built with GM_MPI) ----------------------------------------- */
/* Non-zero when this process was started by mpirun (its environment says so). */
int mx_mpi_launched(void);
/* `maxwell run` on the distributed solver: MPI_Init .. MPI_Finalize around the run. */
int mx_run_mpi_main(int argc, char **argv);

/* ---- harminv summaries ---------------------------------------------------------------- */
/* harminv's basis size (0: its default) and the filter on the modes it returns (scene keys
 * output.harminv.basis, max_error, min_q, min_amplitude). */
typedef gm_resonance_params mx_harminv_params; /* geomint/experiments.h */
size_t mx_resonances_with(const double *signal, size_t n, double dt, double f_min, double f_max,
                          const mx_harminv_params *params, gm_harminv_mode *modes, size_t cap,
                          char *msg, size_t msg_cap);
/* Modes of a signal in [f_min, f_max] (harminv), kept when harminv's error estimate is below
 * max_error, |Q| > min_q and the amplitude at least min_amplitude of the largest; ascending
 * frequency; returns how many (<= cap). On a harminv failure returns 0 with the reason in msg.
 * mx_resonances: the defaults (basis 0, 1e-4, 1, 1e-6). */
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
/* The "dft" flux spectra of a finished run: normalisation file, flux_spectra.csv/.png in out_dir
 * (maxwell_spectra.c). */
struct gm_yee_scene;
int mx_write_spectra(const char *out_dir, const struct gm_yee_scene *scene);
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
