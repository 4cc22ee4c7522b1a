/* Band structures with the Yee solver: the resonant frequencies of a Bloch-periodic cell at one
 * wave vector k (docs/maxwell.md, "Band structures"). Random-phase Gaussian dipoles at random
 * points ring the cell; random probes record the complex fields; each probe's signal is mixed
 * down, low-pass filtered and decimated to the band before harminv (the signal is band-limited,
 * so this loses nothing and makes harminv's basis and work small); a frequency is accepted when
 * at least two probes see it. */
#ifndef GEOMINT_YEE_BANDS_H
#define GEOMINT_YEE_BANDS_H

#include <stddef.h>
#include <stdint.h>

#include "geomint/core.h"
#include "geomint/fields.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gm_yee_bands_run {
  double f_min, f_max; /* band searched (cycles per unit time); 0 <= f_min < f_max required */
  double time;         /* analysed time after the sources end; <= 0: 80 / f_max */
  size_t n_sources;    /* random dipoles (default 6) */
  size_t n_probes;     /* random probes (default 8, 1..64) */
  uint64_t seed;       /* positions and phases (default 7) */
  size_t n_basis;      /* harminv basis per probe; 0: from the signal (1.1 per Fourier bin of
                          the band, at least 4 per band asked for + 8) */
  double max_error;    /* harminv error estimate accepted (default 1e-5) */
} gm_yee_bands_run;

gm_yee_bands_run gm_yee_bands_run_defaults(void);

/* What one k point's measurement did. */
typedef struct gm_yee_bands_info {
  size_t n_found;    /* distinct frequencies seen by >= 2 probes (1 probe: by it), in the band */
  size_t n_extra;    /* frequencies seen by one probe only (rejected as spurious) */
  size_t n_lost;     /* bands asked for minus those found (0 when enough were found) */
  size_t n_basis;    /* harminv basis size used */
  size_t decimation; /* time steps per analysed sample */
  size_t n_samples;  /* analysed samples per probe */
  size_t n_steps;    /* Yee steps run */
} gm_yee_bands_info;

/* The lowest n_bands distinct resonant frequencies in [f_min, f_max] of the grid (every
 * present axis periodic) with materials (borrowed; NULL: vacuum) and options (borrowed; its
 * bloch_k is replaced), at Bloch wave vector k (MEEP's convention: cycles per unit length,
 * i.e. units of 2π/a for a lattice constant a = 1; bloch_k = 2π k). freq[n_bands] receives
 * them ascending, NaN for the lost ones. A degenerate multiplet is one frequency. Errors
 * (GM_EINVAL): a non-periodic axis, a bad band or run field, f_max above the decimated
 * Nyquist limit of the step, a basis that cannot hold the bands asked for; as gm_yee_create;
 * GM_ENOMEM. */
gm_status gm_yee_bands_at(const gm_yee_grid *grid, const gm_yee_materials *materials,
                          const gm_yee_options *options, const double k[3], size_t n_bands,
                          const gm_yee_bands_run *run, double *freq, gm_yee_bands_info *info,
                          gm_error *err);

/* Band-limit and decimate a complex signal x (n samples, step dt) to [f_min, f_max]: mixed down
 * by the band centre, Blackman-windowed sinc low-pass, every `decimation`-th output kept, then
 * shifted up by `shift` so the band sits at [shift − b, shift + b] (b the half width) inside
 * [0, Nyquist of the decimated step]. Writes at most cap samples to yr, yi; returns how many,
 * and decimation/shift through the pointers. A mode e^{(2πif − γ)t} of x becomes one at
 * f − f_c + shift with the same γ. Exposed for tests. */
size_t gm_yee_bands_decimate(size_t n, const double *xr, const double *xi, double dt, double f_min,
                             double f_max, size_t cap, double *yr, double *yi,
                             size_t *decimation, double *shift);

#ifdef __cplusplus
}
#endif

#endif
