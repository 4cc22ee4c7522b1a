/* Scene files of the Yee solver: one JSON object with the grid, materials, boundaries, PML,
 * sources, probes, flux planes, output and run length (docs/maxwell.md lists every key). Read by
 * the library so that the CLI (`geomint maxwell run`), C programs and the Python package load
 * the same files; every error names the JSON path of the bad value, e.g.
 * "scene.json: sources[1].position[2]: expected a number", and unknown keys are errors with the
 * nearest known key, so that a typo never silently falls back to a default. */
#ifndef GEOMINT_YEE_SCENE_H
#define GEOMINT_YEE_SCENE_H

#include <stddef.h>

#include "geomint/core.h"
#include "geomint/fields.h"
#include "geomint/io.h"

#ifdef __cplusplus
extern "C" {
#endif

#define GM_YEE_SCENE_NAME_CAP 64

typedef struct gm_yee_scene_probe {
  char name[GM_YEE_SCENE_NAME_CAP];
  gm_yee_component component;
  double x[3];
} gm_yee_scene_probe;

typedef struct gm_yee_scene_flux {
  char name[GM_YEE_SCENE_NAME_CAP];
  int axis;
  double position; /* coordinate along axis; the nearest vertex plane is used */
  size_t index;    /* that plane's index, set by gm_yee_scene_build */
} gm_yee_scene_flux;

typedef struct gm_yee_scene {
  gm_yee_grid grid;
  gm_yee_options options;
  gm_yee_materials *materials;    /* owned */
  double unit_um;                 /* micrometres per length unit (key "unit_um", default 1): the
                                     material library's frequencies depend on it */
  size_t n_points, n_planes;
  gm_point_source *points;        /* owned */
  gm_plane_wave *planes;          /* owned */
  size_t *point_json, *plane_json; /* owned: index of each in the JSON "sources" array */
  size_t n_obliques;
  gm_oblique_wave *obliques;      /* owned: plane waves given by angles */
  size_t *oblique_json;           /* owned: as point_json */
  size_t n_probes, n_fluxes;
  gm_yee_scene_probe *probes;               /* owned */
  gm_yee_scene_flux *fluxes;                /* owned */
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
  /* output.harminv's other parameters (docs/maxwell.md): the basis size (0: harminv's
   * default, 1.1 per Fourier bin of the band) and the filter on the modes it returns: error
   * estimate below max_error (default 1e-4), |Q| above min_q (default 1), amplitude at least
   * min_amplitude times the strongest (default 1e-6) */
  size_t harminv_basis;
  double harminv_max_error, harminv_min_q, harminv_min_amplitude;
  /* "dft": flux spectra of every flux plane at dft_n frequencies evenly in [dft_fmin, dft_fmax]
   * (dft_n = 0: none), the normalisation file to write (dft_save) or to subtract
   * (dft_subtract; paths as given, relative to the working directory; owned, may be NULL) */
  size_t dft_n;
  double dft_fmin, dft_fmax;
  char *dft_save, *dft_subtract;
  /* made by gm_yee_scene_build when dft_n > 0: one per flux plane (owned; observers of the
   * solver built with them, so free the solver first or not advance it after the clear) */
  gm_yee_dft_flux **dft;
} gm_yee_scene;

/* Read and check a scene file into *scene (which owns what it holds afterwards; release with
 * gm_yee_scene_clear). On failure *scene is empty and err says "FILE: json.path: what is wrong"
 * in one line: GM_EIO (cannot read the file), GM_EINVAL (not a valid scene), GM_ENOMEM. */
gm_status gm_yee_scene_load(const char *path, gm_yee_scene *scene, gm_error *err);
/* The same from a JSON text (borrowed; name is used in messages). */
gm_status gm_yee_scene_parse(const char *text, const char *name, gm_yee_scene *scene,
                             gm_error *err);
/* Frees what the scene owns and empties it; an empty (zeroed) scene is fine. */
void gm_yee_scene_clear(gm_yee_scene *scene);
/* Create the solver (owned by the caller) with the scene's sources and probes (probe capacity
 * for the whole run). Errors the solver reports (a source outside the grid, a PML thicker than
 * the grid, a step above the Courant limit) come back as GM_EINVAL with the JSON path of the
 * culprit in err. */
gm_status gm_yee_scene_build(gm_yee_scene *scene, const char *name, gm_yee **out,
                             gm_error *err);
/* Steps the run makes (from steps or time). */
size_t gm_yee_scene_total_steps(const gm_yee_scene *scene, double dt);

#ifdef __cplusplus
}
#endif

#endif
