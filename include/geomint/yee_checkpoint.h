/* Checkpoint and restart of the Yee solver: the state a run carries from step to step (E and H,
 * the CPML convolution terms ψ, the charge booked by soft E sources, the TF/SF incident-field
 * grids, the probes' samples so far, the step counter) in one binary file, so that a run cut at a
 * wall-time limit continues bitwise as if it had never stopped. The sources' waveforms are
 * functions of t_n = n Δt, so the step counter is their phase.
 *
 * The file holds the state, not the problem: restart by building the same solver (same grid,
 * materials, options, sources, probes and observers, e.g. from the same scene file) and reading
 * the checkpoint into it. The layout (array sizes, counts of CPML slabs, sources, probes, TF/SF
 * waves) is checked, so a checkpoint of another problem is refused; materials and waveforms are
 * not (the same problem is the caller's promise). Host byte order and doubles as stored
 * (a checkpoint moves between machines of the same architecture). */
#ifndef GEOMINT_YEE_CHECKPOINT_H
#define GEOMINT_YEE_CHECKPOINT_H

#include "geomint/fields.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Write the solver's state to path (replaced atomically: written to path.tmp, then renamed).
 * GM_EIO with the reason (gm_yee_errmsg) when the file cannot be written. */
gm_status gm_yee_checkpoint_write(gm_yee *solver, const char *path);
/* Read a state written by gm_yee_checkpoint_write into a solver built for the same problem.
 * GM_EIO: unreadable or truncated file; GM_EINVAL: not a checkpoint, or one of another layout,
 * or a probe without room for the samples. The state is unchanged on every error found before
 * reading the arrays (all of the checks above but a truncated array section). */
gm_status gm_yee_checkpoint_read(gm_yee *solver, const char *path);

#ifdef __cplusplus
}
#endif
#endif
