/* geomint fields over MPI: the Yee solver on a Cartesian grid of processes. Built only when
 * geomint is configured with GM_MPI (then the CMake targets define GM_HAVE_MPI for their users
 * and link MPI::MPI_C); without it this header is installed but its functions do not exist.
 *
 * Domain decomposition (DESIGN §5a): the grid's cells are split in blocks along each axis over a
 * Cartesian process grid (MPI_Dims_create / MPI_Cart_create, or dims given). Each rank holds an
 * ordinary gm_yee on its block plus one overlap cell on each side that has a neighbouring rank
 * (periodic axes wrap). After each E half step the tangential E on the outermost vertex planes
 * (the only values whose stencil leaves the block) is copied from the neighbour that owns them,
 * axis after axis (so edges and corners arrive too), with non-blocking sends and receives;
 * everything else in the block is computed locally with the same arithmetic as the whole-domain
 * solver, so fields and probes are bitwise those of a single-process run for any rank count.
 *
 * Supported across rank boundaries: PEC, PMC, CPML and periodic faces, Bloch k on axes not split
 * (dims 1 along them), materials (per cell) with subpixel smoothing (each block smooths its
 * edges and faces from the whole grid's shapes at global indices; the off-diagonal coupling of
 * E_a in the overlap cells comes from the neighbour with the tangential E), point sources (soft
 * and hard, E and H), probes, energy. Not yet: TF/SF plane waves, currents, Bloch k on a split
 * axis, flux planes (they are errors, never silently ignored).
 *
 * Every function here is collective over the communicator: all ranks call it with the same
 * arguments; a failure on any rank is returned on every rank with that rank's message
 * ("rank 2: ..."), so no rank waits for one that gave up. Pointer parameters are borrowed. */
#ifndef GEOMINT_FIELDS_MPI_H
#define GEOMINT_FIELDS_MPI_H

#include <mpi.h>

#include "geomint/fields.h"
#include "geomint/yee_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gm_yee_mpi gm_yee_mpi;

/* A distributed solver on the whole grid (copied). materials: the whole grid's media (NULL:
 * vacuum), on every rank (each rank copies the cells of its block: the memory is that of one
 * global ε, μ, σ set per rank). options as gm_yee_create's; dt <= 0 takes the Courant fraction of
 * the whole grid's limit. dims (NULL or {0,0,0}: MPI_Dims_create) gives the ranks per axis; an
 * axis with a Bloch k gets 1. comm is duplicated. Errors (GM_EINVAL): as gm_yee_create, ranks
 * that disagree on the grid or options, dims whose product is not the communicator's size, more
 * ranks along an axis than cells, a rank at a CPML face owning fewer than thickness + 1 cells
 * (the layer must not cross a rank boundary), a Bloch k on a split axis. */
gm_status gm_yee_mpi_create(const gm_yee_grid *grid, const gm_yee_materials *materials,
                            const gm_yee_options *options, MPI_Comm comm, const int dims[3],
                            gm_yee_mpi **out, gm_error *err);
/* Collective. NULL is a no-op. */
void gm_yee_mpi_free(gm_yee_mpi *m);
const char *gm_yee_mpi_errmsg(const gm_yee_mpi *m);

/* This rank's subdomain solver (borrowed; read it, do not advance it alone) and its block:
 * dims and coords of the process grid, first owned cell and owned cell count per axis, and the
 * global cell index of the local solver's cell 0 (first - 1 where an overlap cell precedes). */
const gm_yee *gm_yee_mpi_local(const gm_yee_mpi *m);
void gm_yee_mpi_block(const gm_yee_mpi *m, int dims[3], int coords[3], size_t first[3],
                      size_t owned[3], long local_origin[3]);
int gm_yee_mpi_rank(const gm_yee_mpi *m);
double gm_yee_mpi_dt(const gm_yee_mpi *m);
size_t gm_yee_mpi_step(const gm_yee_mpi *m);

/* As gm_yee_add_point_source on the whole grid (the same snapping and checks); added on every
 * rank whose block (overlap included) holds the location. id: the same on every rank. */
gm_status gm_yee_mpi_add_point_source(gm_yee_mpi *m, const gm_point_source *source, size_t *id);
/* As gm_yee_add_probe; the samples live on the rank that owns the location. */
gm_status gm_yee_mpi_add_probe(gm_yee_mpi *m, gm_yee_component c, const double x[3],
                               size_t capacity, size_t *id);
/* Gather probe id's samples to rank 0 (borrowed, valid until the next call on m); on other
 * ranks *n = 0 and the pointers are NULL. */
gm_status gm_yee_mpi_probe_samples(gm_yee_mpi *m, size_t id, size_t *n, const double **t,
                                   const double **re, const double **im);

/* Initial field from f(ctx, x) at each location (as gm_yee_set_field_fn; f is evaluated at the
 * global coordinates, so it must not depend on the rank). */
gm_status gm_yee_mpi_set_field_fn(gm_yee_mpi *m, gm_yee_component c, int part,
                                  double (*f)(void *ctx, const double x[3]), void *ctx);

/* Advance n_steps (as gm_yee_advance). */
gm_status gm_yee_mpi_advance(gm_yee_mpi *m, size_t n_steps);

/* The whole grid's layout (as gm_yee_get_layout of a single-process solver on the grid). */
void gm_yee_mpi_global_layout(const gm_yee_mpi *m, gm_yee_layout *layout);
/* Gather component c (part 0/1) into out on rank 0 (global layout size entries; locations of c
 * filled, the rest 0); out is ignored on the other ranks. */
gm_status gm_yee_mpi_gather_field(gm_yee_mpi *m, gm_yee_component c, int part, double *out);
/* Energies as gm_yee_get_energy of the whole grid, every location counted on the rank that owns
 * it, summed over ranks (MPI_Allreduce: equal to the single-process value to round-off, not
 * bitwise; the same on every rank). */
gm_status gm_yee_mpi_get_energy(gm_yee_mpi *m, gm_yee_energy *energy);

/* Checkpoint/restart (geomint/yee_checkpoint.h) of every rank's block: rank r of N writes
 * PREFIX.rank<r>of<N> (the gm_yee_checkpoint_write format of its local solver). Restart builds
 * the same distributed solver on the same number of ranks and process grid (a block of another
 * size is refused by the layout check) and reads them; the run then continues bitwise as the
 * uninterrupted one. Errors on any rank (GM_EIO, GM_EINVAL) come back on every rank. */
gm_status gm_yee_mpi_checkpoint_write(gm_yee_mpi *m, const char *prefix);
gm_status gm_yee_mpi_checkpoint_read(gm_yee_mpi *m, const char *prefix);

/* gm_yee_scene_build over MPI (collective; every rank loaded the same scene): the solver with
 * the scene's point sources and probes (room for the whole run). What the distributed solver does
 * not do yet is an error naming the JSON path (plane waves, flux planes, snapshots), never
 * ignored. Errors as gm_yee_scene_build, with "rank r: " when one rank failed. */
gm_status gm_yee_scene_build_mpi(gm_yee_scene *scene, const char *name, MPI_Comm comm,
                                 const int dims[3], gm_yee_mpi **out, gm_error *err);

/* Bytes sent by this rank per step in the E exchange (the performance model, docs/maxwell.md). */
size_t gm_yee_mpi_bytes_per_step(const gm_yee_mpi *m);

#ifdef __cplusplus
}
#endif
#endif
