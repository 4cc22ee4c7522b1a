/* The table of the seeds' experiments (DESIGN §5c). A row's seed_result is what the seed (or,
 * where the seed leaves it open, its reading notes in seeds/notes/) reports; our numbers are in
 * the docs page of the row, each from the command named there. A run's time is measured, not
 * written here: `experiments run NAME --json` reports its wall_s. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "experiments/internal.h"

static const gm_experiment_info rows[] = {
    {"resonance", "000 §2.2, Fig 2.1 (E1)",
     "the impulse method (r-RESPA, 100 substeps) resonates near integer omega h/pi; the "
     "variational IMEX method's energy error is flat",
     "r-RESPA spikes near integer omega h/pi, IMEX nearly constant; notes' check: IMEX "
     "1.253e-3 everywhere, r-RESPA blows up at omega h/pi = 0.999-0.9995",
     "oscillatory resonance", "docs/oscillatory.md#resonance-seed-000-fig-21",
     gm_experiment_run_resonance},
    {"fpu", "000 §2.4, Fig 2.2 (E2)",
     "FPU (l = 3, omega = 50): IMEX keeps the oscillatory energy I and the springs' energy "
     "exchange at h omega = 5; Verlet degrades at h omega = 1.5",
     "notes' check at t = 150: reference I = 0.013, 0.027, 0.957; IMEX h = 0.1: 0.017, 0.018, "
     "0.968, max |dH| = 0.020; Verlet h = 0.03: max |dH| = 0.65",
     "oscillatory fpu", "docs/oscillatory.md#fpu-seed-000-figs-22-23",
     gm_experiment_run_fpu},
    {"fpu-long", "000 §2.4, Fig 2.3 (E3)",
     "IMEX h = 0.1 stays bounded to T = 4000 and keeps I; the trigonometric rows and vti beside "
     "it",
     "bounded, I correct (notes: max |dH| = 0.028, max |dI| = 0.10)", "oscillatory fpu-long",
     "docs/oscillatory.md#fpu-seed-000-figs-22-23", gm_experiment_run_fpu_long},
    {"multiscale", "001 §5.7.1-5.7.2",
     "the multiscale VI on the stiff spring pendulum against vi-midpoint and imex; 1-D MsFEM "
     "against P1",
     "MsFEM nodal error 0; the thesis reports no results of the multiscale VI",
     "oscillatory multiscale", "docs/oscillatory.md#multiscale-filon-quadrature-a-multiscale-variational-integrator-"
     "msfem-seed-001-57",
     gm_experiment_run_multiscale},
    {"e4", "000 §3.4.3, Figs 3.7-3.8 (E4)",
     "a PEC square from a random E, steps of 1/10 of the Courant limit: the plain energy "
     "oscillates, bounded; the leapfrog energy is conserved",
     "bounded, near-constant energy to t = 8 (figure; domain, cells and energy formula not "
     "given)",
     "maxwell e4", "docs/maxwell.md#seed-000-experiment-e4-geomint-maxwell-e4",
     gm_experiment_run_e4},
    {"e5", "000 §3.4.3, Fig 3.9 (E5)",
     "the AVI on a tetrahedral box refined near the walls: harminv peaks against the analytic "
     "resonances, no spurious modes, fewer updates than uniform stepping",
     "no spurious modes, fewer steps than uniform stepping (figure; dimensions not given)",
     "maxwell mesh examples/e5_cavity.msh --e5", "docs/maxwell-mesh.md", gm_experiment_run_e5},
    {"maxwell-cavity", "000 §3.4.1 (Yee)",
     "a PEC box rung by a pulse: harminv's first 10 frequencies against the analytic ones and "
     "Yee's discrete dispersion relation",
     "(a verification of the scheme; the seed derives Yee, no numbers)", "maxwell cavity",
     "docs/maxwell.md", gm_experiment_run_cavity},
    {"mesh-cavity", "000 §3.4.2, Fig 3.9 (E5)",
     "PEC box, cylinder or sphere on tetrahedra at 3 resolutions: Whitney-star leapfrog "
     "resonances, their rates, no spurious peak",
     "no spurious modes (E5's claim; the seed gives no rates)", "maxwell mesh-cavity", "docs/maxwell-mesh.md", gm_experiment_run_mesh_cavity},
    {"j2-satellite", "001 §2.9, Figs 2.2-2.5",
     "discrete Routh reduction: the discretisation's precession lives in the reconstructed "
     "angle, J2's in the shape (r, z)",
     "qualitative: the reduced view separates the two precessions (no initial data, no final "
     "time)",
     "reduction j2-satellite", "docs/reduction.md#j2-satellite-seed-001-29",
     gm_experiment_run_j2_satellite},
    {"double-spherical-pendulum", "001 §2.10, Figs 2.7-2.9",
     "4th-order RSPRK against SPRK on the classical Routhian and RK4: bounded against drifting "
     "energy; spikes at the chart's singularity",
     "(E - E0)/E0 bounded for RSPRK, drifting for RK; RSPRK and SPRK 'agree very well' (no "
     "parameters given)",
     "reduction double-spherical-pendulum", "docs/reduction.md#double-spherical-pendulum-seed-001-210",
     gm_experiment_run_double_spherical_pendulum},
    {"phases", "001 ch. 4",
     "geometric phases against closed forms: Foucault, a spherical cap, Montgomery's rigid-body "
     "phase, a shape loop, the tet-mesh Levi-Civita holonomy",
     "closed forms (the thesis has no numerical results for them)", "reduction phases", "docs/reduction.md#geometric-phases-against-closed-forms", gm_experiment_run_phases},
    {"mimetic-circular", "003 §6.1, Figs 9-10",
     "MCI and MGI keep R to round-off; explicit Euler spirals out, RK4 in; rate 4",
     "MCI, MGI keep R to machine precision; rate 4; 'symplectic Euler diverges' (a caption "
     "error: stable for dt < 2)",
     "mimetic circular", "docs/mimetic.md", gm_experiment_run_mimetic_circular},
    {"mimetic-lotka-volterra", "003 §6.2",
     "neither mimetic scheme keeps V on this Poisson system; its error grows slowly",
     "MCI, MGI and RK4 similar, V not preserved, rate 4, 'no advantage'",
     "mimetic lotka-volterra", "docs/mimetic.md", gm_experiment_run_mimetic_lotka_volterra},
    {"mimetic-pendulum", "003 §6.3, Fig 14",
     "MGI keeps H to round-off, MCI bounded; H-error orders", "MGI H exact; MCI bounded; "
     "H-error orders MCI 4, RK4 5",
     "mimetic pendulum", "docs/mimetic.md", gm_experiment_run_mimetic_pendulum},
    {"mimetic-kepler", "003 §6.4",
     "Kepler e = 0.6: MGI keeps H, MCI bounded, RK4 loses energy",
     "MGI H exact, MCI bounded; orders MCI 4, RK4 about 5", "mimetic kepler", "docs/mimetic.md", gm_experiment_run_mimetic_kepler},
    {"b10", "004 Figs 11-13",
     "sine-Gordon breather: LF unstable at dt = dx, EC and MS stable; at dt = 2 dx EC blows "
     "up, MS stays bounded",
     "dt = dx: LF unstable, EC and MS stable; dt > dx: EC blows up within the first "
     "iterations, MS 'relatively well behaved'",
     "pde b10", "docs/pde.md#b10-stability-of-lf-ec-and-ms-seed-004-figs-1113", gm_experiment_run_b10},
    {"nls-long", "004 §4 (NLS, eqs. 35-36)",
     "NLS two-soliton collisions over 10^4 periods: the multisymplectic Preissmann box keeps "
     "charge and bounds energy and momentum; box-sdirk2 drifts",
     "(the seed's NLS formulas are missing; no long-run numbers)", "pde nls-long",
     "docs/pde.md#nls-two-soliton-collision-over-104-periods", gm_experiment_run_nls_long},
    {"schrodinger-eigen", "001 §5.8",
     "the pseudospectral Schrödinger VI against split-step Fourier: eigenvalues from an evolved "
     "eigenstate's phase against N and dt",
     "no numerical results in the thesis", "pde schrodinger eigen", "docs/pde.md",
     gm_experiment_run_schrodinger_eigen},
    {"spectral-star", "000 §3.3.4",
     "the spectral Hodge star's dispersion against the diagonal star's, semi-discrete and with "
     "leapfrog",
     "no numbers (the seed defines the star)", "pde spectral-star", "docs/pde.md#spectral-hodge-star-seed-000-334", gm_experiment_run_spectral_star},
    {"tent-vi", "001 §5.1",
     "the multisymplectic VI with bilinear tents on the sine-Gordon breather: error and strip "
     "energy",
     "no numbers (the thesis derives the scheme)", "pde tent-vi", "docs/pde.md#the-multisymplectic-vi-with-bilinear-tents-seed-001-51", gm_experiment_run_tent_vi},
};
#define N_ROWS (sizeof rows / sizeof rows[0])

size_t gm_experiment_count(void) { return N_ROWS; }

const gm_experiment_info *gm_experiment_at(size_t i) { return i < N_ROWS ? &rows[i] : NULL; }

const gm_experiment_info *gm_experiment_find(const char *name) {
  if (name == NULL) return NULL;
  for (size_t i = 0; i < N_ROWS; ++i)
    if (strcmp(rows[i].name, name) == 0) return &rows[i];
  return NULL;
}

double gm_experiment_value(const gm_experiment_result *result, const char *name) {
  for (size_t i = 0; i < result->n_values; ++i)
    if (strcmp(result->names[i], name) == 0) return result->values[i];
  return NAN;
}

double gm_experiment_clock(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

gm_status gm_experiment_path(char *buf, size_t cap, const char *dir, const char *name) {
  const int n = snprintf(buf, cap, "%s/%s", dir, name);
  return n >= 0 && (size_t)n < cap ? GM_OK : GM_EINVAL;
}

void gm_experiment_add(gm_experiment_result *result, const char *name, double value) {
  if (result->n_values >= GM_EXPERIMENT_MAX_VALUES) return;
  result->names[result->n_values] = name;
  result->values[result->n_values++] = value;
}

void gm_experiment_file(gm_experiment_result *result, const char *dir, const char *name) {
  if (dir == NULL || result->n_files >= GM_EXPERIMENT_MAX_FILES) return;
  if (gm_experiment_path(result->files[result->n_files], GM_EXPERIMENT_PATH_SIZE, dir, name) ==
      GM_OK)
    result->n_files++;
}
