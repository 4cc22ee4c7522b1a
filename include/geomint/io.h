/* geomint io: writers of integration output. A CSV writer is an observer (gm_observer_fn):
 * pass gm_csv_writer_observe and the writer to gm_integrator_add_observer. Field snapshots on
 * Cartesian grids go to VTK image data (.vti) and HDF5; probe time series to CSV. */
#ifndef GEOMINT_IO_H
#define GEOMINT_IO_H

#include <stddef.h>

#include "geomint/core.h"
#include "geomint/fields.h"
#include "geomint/ode.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gm_csv_writer gm_csv_writer;

/* Open `path` (copied; truncated); the header line, written with the first row, is
 *   t, q1..qd, p1..pd, H, rel_energy_error, <invariant names>   (Hamiltonian kinds)
 *   t, y1..yn, <invariant names>                                (first order)
 *   t, R11..R33, [x1..x3,] Pi1..Pi3, [p1..p3,] H, rel_energy_error, <invariants>  (rigid body:
 *   the state space's component names; R as its 9 entries, row by row)
 * problem is borrowed (must outlive the writer); y0 (copied into H0) is the state the relative
 * energy error |H - H0| / |H0| refers to (|H - H0| when H0 = 0). Numbers are written with %.17g.
 * Errors: GM_EINVAL (NULL or empty arguments, invalid problem), GM_EIO (cannot open or write). */
gm_status gm_csv_writer_create(const char *path, const gm_problem *problem, const double *y0,
                               gm_csv_writer **out, gm_error *err);
/* Write the rows collected so far. Rows are written whole: after a failed write (disk full,
 * file size limit) the file ends with the last whole row and the writer fails from then on
 * (GM_EIO, the message says why and how many rows the file holds). */
gm_status gm_csv_writer_flush(gm_csv_writer *writer);
/* Write what is left and close the file (what was written is kept). NULL is a no-op. */
void gm_csv_writer_free(gm_csv_writer *writer);
/* Observer: append one complete row for the state y at time t. Returns 0, or non-zero when the
 * row could not be written (the message says why; later calls fail too). */
int gm_csv_writer_observe(void *writer, size_t step, double t, const double *y);
/* Continue an existing file (a restarted run): keep its header and its whole rows up to the
 * last with t <= t_last, cut the rest, and append. The header must be the one this writer
 * would write (checked at the first row: GM_EINVAL there otherwise). */
gm_status gm_csv_writer_resume(const char *path, const gm_problem *problem, const double *y0,
                               double t_last, gm_csv_writer **out, gm_error *err);
/* The same, refusing (GM_EINVAL, the file untouched) when its last whole row at or before
 * t_last is more than max_gap before it: a file that ends long before the checkpoint is the
 * output of another run, and continuing it would make its rows jump in time. */
gm_status gm_csv_writer_resume_within(const char *path, const gm_problem *problem,
                                      const double *y0, double t_last, double max_gap,
                                      gm_csv_writer **out, gm_error *err);
/* An extra column after the invariants: fn(ctx, step, t, y) gives its value at each row
 * (name copied, ctx borrowed). Only before the first row (the header is written with it). */
typedef double (*gm_csv_column_fn)(void *ctx, size_t step, double t, const double *y);
gm_status gm_csv_writer_add_column(gm_csv_writer *writer, const char *name, gm_csv_column_fn fn,
                                   void *ctx);
/* Data rows accepted so far (the header not counted; after a failure, the rows in the file). */
size_t gm_csv_writer_rows(const gm_csv_writer *writer);
/* Column index (0-based) of the named column, or (size_t)-1 when there is none. */
size_t gm_csv_writer_column(const gm_csv_writer *writer, const char *name);
/* What failed and why, for the last error ("" when none). */
const char *gm_csv_writer_errmsg(const gm_csv_writer *writer);

/* ---- field snapshots on a box of cells: VTK image data (.vti) and HDF5 ----------------------
 * A snapshot is a set of named arrays on a uniform grid of cells: cell data (one value per cell,
 * as a cell average or a cell-centred sample) or point data (one value per grid point, the cell
 * corners). Values are ordered x fastest, then y, then z: cell (i, j, k) is entry
 * i + n[0] (j + n[1] k), point (i, j, k) is entry i + (n[0]+1) (j + (n[1]+1) k). */

#define GM_IMAGE_MAX_COMPONENTS 3

typedef struct gm_image {
  size_t dim;          /* 1, 2 or 3: the axes past dim are flat (one layer of points) */
  size_t n_cells[3];   /* cells along each of the first dim axes, >= 1 (others ignored) */
  double origin[3];    /* the corner of cell (0, 0, 0) */
  double spacing[3];   /* cell sizes along the first dim axes, > 0 and finite */
} gm_image;

typedef enum gm_image_centering { GM_IMAGE_CELL = 0, GM_IMAGE_POINT = 1 } gm_image_centering;

typedef struct gm_image_array {
  const char *name;               /* borrowed; letters, digits, '_', '-', '.', at most 63 */
  gm_image_centering centering;
  size_t n_components;            /* 1 (scalar) .. GM_IMAGE_MAX_COMPONENTS (3: a vector) */
  const double *component[GM_IMAGE_MAX_COMPONENTS]; /* borrowed, one array per component */
} gm_image_array;

/* Number of cells / points of the image (0 when the image is invalid). */
size_t gm_image_cell_count(const gm_image *image);
size_t gm_image_point_count(const gm_image *image);
/* Check an image and its arrays: positive counts and spacings, finite origin, names as above
 * and distinct, component pointers non-NULL. */
gm_status gm_image_validate(const gm_image *image, const gm_image_array *arrays,
                            size_t n_arrays, gm_error *err);

typedef enum gm_vti_encoding {
  GM_VTI_ASCII = 0,    /* text, "%.17g": exact round trip, about 3x the size of binary */
  GM_VTI_BASE64 = 1,   /* inline base64 binary (valid XML) */
  GM_VTI_APPENDED = 2  /* raw binary in an appended section: smallest and fastest */
} gm_vti_encoding;

/* Write a VTK XML ImageData file (ParaView, VisIt) with the arrays as Float64 PointData and
 * CellData, the simulation time as FieldData "TimeValue", and binary blocks with UInt64 size
 * headers in the machine's byte order. path is truncated. Errors: GM_EINVAL (bad image, arrays
 * or encoding), GM_EIO (cannot open or write; the message names the file). */
gm_status gm_vti_write(const char *path, const gm_image *image, const gm_image_array *arrays,
                       size_t n_arrays, double time, gm_vti_encoding encoding, gm_error *err);

/* Is HDF5 support compiled in (libhdf5 found when the library was configured)? */
int gm_hdf5_available(void);
/* Write the same snapshot as an HDF5 file (path truncated): root attributes "time", "origin",
 * "spacing" (3 doubles each) and "n_cells" (3 integers; 1 past dim), and one dataset per array
 * in group "/cell" or "/point", of shape [nz][ny][nx] or [nz][ny][nx][components] (C order, so
 * x is fastest as above; flat axes have extent 1). Errors: GM_EINVAL, GM_EIO, and
 * GM_EUNSUPPORTED when the library was built without HDF5. */
gm_status gm_hdf5_write(const char *path, const gm_image *image, const gm_image_array *arrays,
                        size_t n_arrays, double time, gm_error *err);

/* ---- probe time series: CSV, one whole row per write ------------------------------------- */

typedef struct gm_probe_csv gm_probe_csv;

/* Open path (copied; truncated) and write the header "t,<names...>". names: n_columns
 * borrowed strings, copied here. Errors: GM_EINVAL (NULL or empty arguments), GM_ENOMEM,
 * GM_EIO. */
gm_status gm_probe_csv_create(const char *path, size_t n_columns, const char *const *names,
                              gm_probe_csv **out, gm_error *err);
/* Close the file (what was written is kept). NULL is a no-op. */
void gm_probe_csv_free(gm_probe_csv *writer);
/* Append the row t, values[0..n_columns) ("%.17g"). Rows are buffered and reach the file only
 * as whole rows (every write ends at a line break), when the buffer (>= 64 KiB) fills, every
 * `flush_every` rows (gm_probe_csv_set_flush; default 0: never), at gm_probe_csv_flush and at
 * free. GM_EIO when the file cannot be written (later calls fail too); the message says why. */
gm_status gm_probe_csv_write(gm_probe_csv *writer, double t, const double *values);
void gm_probe_csv_set_flush(gm_probe_csv *writer, size_t flush_every);
gm_status gm_probe_csv_flush(gm_probe_csv *writer);
size_t gm_probe_csv_rows(const gm_probe_csv *writer);
size_t gm_probe_csv_columns(const gm_probe_csv *writer); /* n_columns, t not counted */
const char *gm_probe_csv_errmsg(const gm_probe_csv *writer);

/* ---- snapshots of the Yee solver (geomint/fields.h) --------------------------------------- */

/* Component c (part 0 real, 1 imaginary) averaged to cell centres: the mean over the
 * component's locations on the cell's edges (E) or faces (H), along the present axes.
 * out: one value per cell, x fastest (gm_image layout). Errors: GM_EINVAL (NULL, a component
 * the dimension lacks, part 1 of real fields). */
gm_status gm_yee_cell_average(const gm_yee *solver, gm_yee_component c, int part, double *out);

enum { GM_SNAPSHOT_VTI = 1, GM_SNAPSHOT_HDF5 = 2 }; /* formats, combined with | */

typedef struct gm_yee_writer gm_yee_writer;

/* A writer of snapshots of solver (borrowed; the same grid for every write): cell data "E" and
 * "H" (vectors averaged to cell centres, 0 for components the dimension lacks; "E_im", "H_im"
 * for complex fields) and, when materials is non-NULL (copied here), "epsilon", "mu", "sigma".
 * Each write creates <prefix>_<step, 6 digits>.vti and/or .h5 and rewrites the ParaView
 * collection <prefix>.pvd that lists every .vti written with its time. The files carry the
 * time of H (t_n); E is half a step earlier (fields.h). prefix is copied; its directory must
 * exist. Errors: GM_EINVAL (no format, bad encoding, materials of another grid),
 * GM_EUNSUPPORTED (HDF5 asked for but not built in), GM_ENOMEM. */
gm_status gm_yee_writer_create(const gm_yee *solver, const gm_yee_materials *materials,
                               const char *prefix, unsigned formats, gm_vti_encoding encoding,
                               gm_yee_writer **out, gm_error *err);
void gm_yee_writer_free(gm_yee_writer *writer);
/* Write one snapshot of the solver's current state (a second write at the same step
 * overwrites the first and is listed once). GM_EIO with a message naming the file. */
gm_status gm_yee_writer_write(gm_yee_writer *writer, const gm_yee *solver);
/* The same as an observer (gm_yee_observer_fn): returns 0, or 1 when the write failed. */
int gm_yee_writer_observe(void *writer, const gm_yee *solver);
size_t gm_yee_writer_count(const gm_yee_writer *writer); /* snapshots written */
const char *gm_yee_writer_errmsg(const gm_yee_writer *writer);

#ifdef __cplusplus
}
#endif
#endif
