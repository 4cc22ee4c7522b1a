/* geomint io: writers of integration output. A CSV writer is an observer (gm_observer_fn):
 * pass gm_csv_writer_observe and the writer to gm_integrator_add_observer. */
#ifndef GEOMINT_IO_H
#define GEOMINT_IO_H

#include <stddef.h>

#include "geomint/core.h"
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

#ifdef __cplusplus
}
#endif
#endif
