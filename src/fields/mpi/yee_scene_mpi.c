/* A scene file (geomint/yee_scene.h) on the distributed Yee solver: the same checks and JSON
 * paths in messages as gm_yee_scene_build, and a clear refusal of what is not distributed yet. */
#include <stdio.h>

#include "geomint/fields_mpi.h"

gm_status gm_yee_scene_build_mpi(gm_yee_scene *s, const char *name, MPI_Comm comm,
                                 const int dims[3], gm_yee_mpi **out, gm_error *error) {
  char *msg = error->message;
  const size_t cap = sizeof error->message;
  *out = NULL;
  /* every rank read the same file: these checks agree without communication */
  if (s->n_planes > 0 || s->n_obliques > 0) {
    const size_t k = s->n_planes > 0 ? s->plane_json[0] : s->oblique_json[0];
    snprintf(msg, cap, "%s: sources[%zu]: plane waves (TF/SF) are not distributed over MPI yet: "
             "run this scene on one process", name, k);
    return GM_EINVAL;
  }
  if (s->n_fluxes > 0) {
    snprintf(msg, cap, "%s: flux[0]: flux planes are not distributed over MPI yet: run this "
             "scene on one process", name);
    return GM_EINVAL;
  }
  if (s->snapshot_every > 0) {
    snprintf(msg, cap, "%s: output.snapshot_every: snapshots are not written over MPI yet "
             "(parallel VTK/HDF5): run this scene on one process or drop the snapshots", name);
    return GM_EINVAL;
  }
  gm_error err = {{0}};
  gm_yee_mpi *m = NULL;
  if (gm_yee_mpi_create(&s->grid, s->materials, &s->options, comm, dims, &m, &err) != GM_OK) {
    snprintf(msg, cap, "%s: %.400s", name, err.message);
    return GM_EINVAL;
  }
  const size_t steps = gm_yee_scene_total_steps(s, gm_yee_mpi_dt(m));
  for (size_t k = 0; k < s->n_points; ++k)
    if (gm_yee_mpi_add_point_source(m, &s->points[k], NULL) != GM_OK) {
      snprintf(msg, cap, "%s: sources[%zu]: %.400s", name, s->point_json[k], gm_yee_mpi_errmsg(m));
      gm_yee_mpi_free(m);
      return GM_EINVAL;
    }
  for (size_t k = 0; k < s->n_probes; ++k)
    if (gm_yee_mpi_add_probe(m, s->probes[k].component, s->probes[k].x, steps + 1, NULL) !=
        GM_OK) {
      snprintf(msg, cap, "%s: probes[%zu]: %.400s", name, k, gm_yee_mpi_errmsg(m));
      gm_yee_mpi_free(m);
      return GM_EINVAL;
    }
  *out = m;
  return GM_OK;
}
