/* geomint fields: field solvers. This header holds the Yee FDTD solver for Maxwell's equations
 * on Cartesian grids (1-D, 2-D TE, 2-D TM, 3-D), its materials, boundaries, sources, probes,
 * observers and diagnostics, and a harminv wrapper for resonances of a probe signal.
 *
 * Plan/execute (DESIGN §5a): gm_yee_create does all precomputation and allocation (Hodge-star
 * coefficients, CFL check, CPML profiles and auxiliary arrays); sources, probes and observers
 * are added after create, each add allocating what it needs; gm_yee_advance never allocates.
 *
 * Units: vacuum ε0 = μ0 = c = 1 (as seed 000 §3.2 and MEEP); ε, μ are relative = absolute,
 * σ is the electric conductivity (J = σE), frequencies are cycles per unit time.
 *
 * Fields as discrete forms (seed 000 §3.4.1, notes A9–A10): E (and D = ⋆_ε E) on primal edges at
 * half steps, H (and B = ⋆_μ H) on primal faces at whole steps. Arrays store point values: the
 * cochain value divided by the edge length (E) or face area (B), so the discrete d reads as
 * differences over cell sizes. State after n steps: H at t_n = nΔt and E at t_n − Δt/2.
 *
 * Pointer parameters are borrowed unless a comment says copied or owned. Nothing here prints. */
#ifndef GEOMINT_FIELDS_H
#define GEOMINT_FIELDS_H

#include <stddef.h>
#include <stdint.h>

#include "geomint/core.h"
#include "geomint/dec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- grid --------------------------------------------------------------------------------- */

/* Which fields a grid carries. 1-D: Ez, Hy varying along x. 2-D (x, y): TM = Ez, Hx, Hy;
 * TE = Hz, Ex, Ey. 3-D: all six. Axes a dimension lacks carry no variation. */
typedef enum gm_yee_dim {
  GM_YEE_1D = 1,
  GM_YEE_2D_TE = 2,
  GM_YEE_2D_TM = 3,
  GM_YEE_3D = 4
} gm_yee_dim;

typedef enum gm_yee_component {
  GM_EX = 0,
  GM_EY = 1,
  GM_EZ = 2,
  GM_HX = 3,
  GM_HY = 4,
  GM_HZ = 5
} gm_yee_component;
#define GM_YEE_N_COMPONENTS 6

/* "Ex", "Ey", ... ; NULL for an invalid value. */
const char *gm_yee_component_name(gm_yee_component c);
/* Look a component up by name ("Ex" .. "Hz", case-insensitive). GM_ENOTFOUND when none. */
gm_status gm_yee_component_find(const char *name, gm_yee_component *out);

typedef struct gm_yee_grid {
  gm_yee_dim dim;
  size_t n[3];      /* cells per axis (>= 1 on the axes the dimension has; others ignored) */
  double h[3];      /* cell size per axis (> 0 on the axes it has; others ignored: 1) */
  double origin[3]; /* coordinates of vertex (0,0,0) */
} gm_yee_grid;

/* Number of axes the dimension has (1, 2 or 3). */
size_t gm_yee_dim_axes(gm_yee_dim dim);
/* Non-zero when the dimension carries component c. */
int gm_yee_dim_has(gm_yee_dim dim, gm_yee_component c);

/* ---- materials: ε, μ, σ per cell, painted from shapes ------------------------------------- */

/* A dispersive term of ε(f) (src/fields/yee_dispersive.c), in frequency units (cycles per unit
 * time, as MEEP's susceptibilities), time dependence e^{−2πift}:
 *   Drude:   −f_p² / (f² + i γ f)              frequency = f_p (plasma), gamma = γ
 *   Lorentz:  Δε f_0² / (f_0² − f² − i γ f)    frequency = f_0 (resonance), gamma = γ,
 *                                             strength = Δε
 * so ε(f) = ε + Σ poles + iσ/(2πf) (ε the medium's epsilon, i.e. ε∞). γ >= 0 (0: lossless),
 * frequency > 0, Δε > 0 (Δε is ignored for Drude poles). */
typedef enum gm_pole_kind { GM_POLE_DRUDE = 0, GM_POLE_LORENTZ = 1 } gm_pole_kind;

typedef struct gm_pole {
  gm_pole_kind kind;
  double frequency; /* f_p (Drude) or f_0 (Lorentz), > 0 */
  double gamma;     /* damping γ in frequency units, >= 0 */
  double strength;  /* Δε of a Lorentz pole, > 0 */
} gm_pole;

typedef struct gm_medium {
  double epsilon; /* relative permittivity (ε∞ of a dispersive medium), > 0 */
  double mu;      /* relative permeability, > 0 */
  double sigma;   /* electric conductivity, >= 0 */
} gm_medium;

/* Check poles (at most 64); the message names the bad one's field, as a scene's JSON path
 * below the medium: "poles[1].gamma: the damping rate must be >= 0 and finite (got -1)". */
gm_status gm_poles_check(size_t n_poles, const gm_pole *poles, gm_error *err);
/* ε(f) of a medium with poles (real and imaginary parts, eps[2]) at frequency f > 0. dt = 0:
 * the continuous model above; dt > 0: the permittivity the Yee solver's update realises at step
 * dt, which is the continuous one at the frequency f̃ = tan(π f dt)/(π dt) for the poles and
 * the conductivity (the bilinear map of the auxiliary-differential-equation scheme,
 * yee_dispersive.c). GM_EINVAL for f <= 0, f >= 1/(2 dt), bad poles. */
gm_status gm_medium_epsilon(const gm_medium *medium, size_t n_poles, const gm_pole *poles,
                            double f, double dt, double eps[2], gm_error *err);

/* The material library (src/fields/yee_material_library.c): Lorentz–Drude fits of Rakić et al.,
 * Appl. Opt. 37 (1998) 5271, for "Ag", "Au", "Al" (case-insensitive), with lengths in units of
 * unit_um micrometres (frequencies c/unit: f = E[eV] unit_um / 1.23984198). Writes ε∞ = 1,
 * μ = 1, σ = 0 into *medium and the poles into poles[cap], their count into *n_poles
 * (GM_MATERIAL_MAX_POLES is room enough). GM_ENOTFOUND for an unknown name, GM_EINVAL for
 * unit_um <= 0 or a cap too small. gm_material_name(k) lists the names (NULL past the end). */
#define GM_MATERIAL_MAX_POLES 8
gm_status gm_material_find(const char *name, double unit_um, gm_medium *medium, gm_pole *poles,
                           size_t cap, size_t *n_poles, gm_error *err);
const char *gm_material_name(size_t k);

/* Vacuum {1, 1, 0}. */
gm_medium gm_medium_vacuum(void);

/* One medium per cell (x fastest: cell (i,j,k) at i + n0*(j + n1*k); absent axes count 1).
 * Shapes paint the cells whose centre lies inside (closed shape); later paints overwrite
 * earlier ones. A medium with ε <= 0, μ <= 0, σ < 0 or any NaN/inf is GM_EINVAL with a
 * message (gm_yee_materials_errmsg); the materials are then unchanged. */
typedef struct gm_yee_materials gm_yee_materials;

/* Vacuum everywhere on the grid (copied). Errors as gm_yee_create's grid checks. */
gm_status gm_yee_materials_create(const gm_yee_grid *grid, gm_yee_materials **out,
                                  gm_error *err);
void gm_yee_materials_free(gm_yee_materials *materials);
gm_status gm_yee_materials_fill(gm_yee_materials *m, const gm_medium *medium);
/* Axis-aligned box [lo, hi] (coordinates; lo <= hi on each axis the grid has). */
gm_status gm_yee_paint_box(gm_yee_materials *m, const double lo[3], const double hi[3],
                           const gm_medium *medium);
gm_status gm_yee_paint_sphere(gm_yee_materials *m, const double center[3], double radius,
                              const gm_medium *medium);
/* Cylinder of the given radius and height (length along its axis), centred at center, axis
 * any non-zero vector (as MEEP's Cylinder). In 2-D an axis along z paints a disk. */
gm_status gm_yee_paint_cylinder(gm_yee_materials *m, const double center[3],
                                const double axis[3], double radius, double height,
                                const gm_medium *medium);
/* Per-cell arrays (one value per cell, layout above; copied). A NULL array leaves that
 * property unchanged. Every value is checked first. */
gm_status gm_yee_paint_cells(gm_yee_materials *m, const double *epsilon, const double *mu,
                             const double *sigma);
/* Per-cell arrays (borrowed, valid while m lives), and the cell count. */
size_t gm_yee_materials_n_cells(const gm_yee_materials *m);
const double *gm_yee_materials_epsilon(const gm_yee_materials *m);
const double *gm_yee_materials_mu(const gm_yee_materials *m);
const double *gm_yee_materials_sigma(const gm_yee_materials *m);
const char *gm_yee_materials_errmsg(const gm_yee_materials *m);
/* The poles that every later paint (fill, box, sphere, cylinder) gives the cells it paints,
 * with the medium it paints (copied; n_poles = 0: no poles, the default), like a pen's
 * colour. Errors as gm_poles_check (message in gm_yee_materials_errmsg); the pen is then
 * unchanged. gm_yee_paint_cells leaves the cells' poles as they are. */
gm_status gm_yee_materials_set_poles(gm_yee_materials *m, size_t n_poles, const gm_pole *poles);
/* Number of distinct dispersive pole sets painted (0: a non-dispersive medium everywhere). */
size_t gm_yee_materials_n_dispersive(const gm_yee_materials *m);

/* ---- boundaries --------------------------------------------------------------------------- */

typedef enum gm_yee_boundary_kind {
  GM_BOUNDARY_PEC = 0,      /* tangential E = 0 (electric wall) */
  GM_BOUNDARY_PMC = 1,      /* tangential H = 0 (magnetic wall; image of H, half dual cells) */
  GM_BOUNDARY_PERIODIC = 2, /* both faces of the axis; f(x + L) = exp(i k L) f(x) (Bloch) */
  GM_BOUNDARY_CPML = 3      /* convolutional PML (Roden & Gedney 2000) backed by PEC */
} gm_yee_boundary_kind;

/* CPML parameters (Taflove & Hagness 3rd ed. §7.9–7.11). The PML occupies the outer
 * `thickness` cells of the grid on that face (they are part of n). Profiles, with ρ the depth
 * into the layer over its thickness (0 at the interface, 1 at the PEC backing):
 *   σ(ρ) = σ_max ρ^m,  κ(ρ) = 1 + (κ_max − 1) ρ^m,  α(ρ) = α_max (1 − ρ)^m_α. */
typedef struct gm_cpml {
  size_t thickness;     /* cells (>= 1) */
  double grading;       /* m (default 3) */
  double sigma_max;     /* the stretching rate σ/ε at the PEC backing (1/time); <= 0:
                           σ_opt = 0.8 (m + 1) / (h sqrt(εμ)) of the adjacent medium
                           (Taflove & Hagness eq. 7.67 in units ε0 = μ0 = 1), scaled by
                           sigma_factor */
  double sigma_factor;  /* multiplies σ_opt when sigma_max <= 0 (default 1) */
  double kappa_max;     /* >= 1 (default 1) */
  double alpha_max;     /* CFS α >= 0 (default 0.05 in units where c = 1 per unit length) */
  double alpha_grading; /* m_α (default 1) */
} gm_cpml;

/* Defaults: thickness 10, m 3, σ_opt, factor 1, κ_max 1, α_max 0.05, m_α 1. */
gm_cpml gm_cpml_defaults(void);

typedef struct gm_yee_boundary {
  gm_yee_boundary_kind kind;
  gm_cpml pml; /* read when kind == GM_BOUNDARY_CPML */
} gm_yee_boundary;

/* "pec", "pmc", "periodic", "cpml"; NULL for an invalid value. */
const char *gm_yee_boundary_kind_name(gm_yee_boundary_kind kind);
/* By name (as above, case-insensitive). GM_ENOTFOUND when none. */
gm_status gm_yee_boundary_kind_find(const char *name, gm_yee_boundary_kind *out);

/* Faces in the order −x, +x, −y, +y, −z, +z; faces of absent axes are ignored. */
enum { GM_FACE_XLO = 0, GM_FACE_XHI, GM_FACE_YLO, GM_FACE_YHI, GM_FACE_ZLO, GM_FACE_ZHI };

/* ---- options and creation ----------------------------------------------------------------- */

/* How a step walks the grid. Both compute bitwise the same fields. AUTO: a 3-D grid without
 * CPML, TF/SF or periodic faces does a step as one sweep over z planes (E plane k, then H plane
 * k−1: each array streamed once a step instead of 1.5 times; threads take slabs of planes);
 * otherwise two sweeps. HALF_STEPS: always two sweeps (E, then H). */
typedef enum gm_yee_sweep { GM_YEE_SWEEP_AUTO = 0, GM_YEE_SWEEP_HALF_STEPS = 1 } gm_yee_sweep;

/* How ε, μ, σ are sampled on edges and faces. ANISOTROPIC (the default, as MEEP's
 * eps_averaging): subpixel smoothing (Farjadpour et al. 2006; Kottke, Farjadpour & Johnson
 * 2008): where an interface cuts the cell-sized box around an edge, 1/ε of the edge along axis
 * a is n_a² ⟨1/ε⟩ + (1 − n_a²)/⟨ε⟩ (the diagonal of the inverse of the averaged tensor, n the
 * interface normal from the shape, or from the gradient of per-cell arrays); μ on faces the
 * same, σ its mean; second-order accurate for curved interfaces. NONE: the staircase (ε, σ the
 * mean and 1/μ the mean of 1/μ over the cells touching the edge/face, each cell the medium at
 * its centre). Both agree on boxes aligned with cell faces. */
typedef enum gm_yee_smoothing {
  GM_YEE_SMOOTHING_ANISOTROPIC = 0,
  GM_YEE_SMOOTHING_NONE = 1
} gm_yee_smoothing;

typedef struct gm_yee_options {
  double dt;                   /* time step; <= 0: courant × the Courant limit */
  double courant;              /* fraction of the limit used when dt <= 0 (default 0.99) */
  gm_yee_boundary boundary[6]; /* default PEC on every face */
  double bloch_k[3];           /* Bloch wave vector on periodic axes (default 0). Non-zero on
                                  any axis: complex fields (a real and an imaginary array per
                                  component, coupled only through the periodic faces). */
  int n_threads;               /* OpenMP threads of the updates; 0: OpenMP's default */
  gm_yee_sweep sweep;          /* how a step walks the grid (default GM_YEE_SWEEP_AUTO) */
  gm_yee_smoothing smoothing;  /* default GM_YEE_SMOOTHING_ANISOTROPIC */
} gm_yee_options;

gm_yee_options gm_yee_defaults(void);

/* The Courant limit dt_max = 1 / (c_max sqrt(Σ_axes 1/h²)) with c_max = 1/sqrt(min εμ) over
 * the cells (vacuum when materials is NULL): Yee is stable for dt <= dt_max (Taflove & Hagness
 * eq. 4.52 with the fastest medium). */
gm_status gm_yee_courant_limit(const gm_yee_grid *grid, const gm_yee_materials *materials,
                               double *dt_max, gm_error *err);

typedef struct gm_yee gm_yee;

/* A solver on grid (copied) with materials (copied into the edge and face Hodge-star
 * coefficients; NULL: vacuum) and options (copied; NULL: defaults). Fields start at zero.
 * Errors (GM_EINVAL with a message in err): zero cells, non-positive or non-finite cell sizes,
 * materials of another grid, dt above the Courant limit (the message gives the limit), a
 * periodic axis with the other face not periodic, a Bloch k on a non-periodic axis, a PML
 * thicker than the grid (both faces' thicknesses must leave at least one cell), bad CPML
 * parameters; GM_ENOMEM. */
gm_status gm_yee_create(const gm_yee_grid *grid, const gm_yee_materials *materials,
                        const gm_yee_options *options, gm_yee **out, gm_error *err);
void gm_yee_free(gm_yee *solver);
/* What failed and why, for the last error of this solver ("" when none). */
const char *gm_yee_errmsg(const gm_yee *solver);
/* 1 when a step is done as one sweep (gm_yee_sweep AUTO and the conditions there hold now:
 * adding a CPML, TF/SF wave changes it), else 0. */
int gm_yee_one_sweep(const gm_yee *solver);

/* ---- sources ------------------------------------------------------------------------------ */

typedef enum gm_waveform_kind {
  GM_WAVE_GAUSSIAN = 0,  /* exp(−τ²/2w²) cos(2πfτ + φ), τ = t − t0 (f = 0: plain Gaussian) */
  GM_WAVE_DGAUSSIAN = 1, /* derivative of the plain Gaussian, normalised: −(τ/w) exp(½ − τ²/2w²)
                            (peak value 1) */
  GM_WAVE_RICKER = 2,    /* (1 − 2π²f²τ²) exp(−π²f²τ²), f the peak frequency */
  GM_WAVE_CW = 3,        /* s(t) sin(2πf t + φ) with s the C² ramp 10x³ − 15x⁴ + 6x⁵,
                            x = t/w clipped to [0, 1] (w = 0: switched on at t = 0) */
  GM_WAVE_CUSTOM = 4     /* fn(ctx, t) */
} gm_waveform_kind;

typedef struct gm_waveform {
  gm_waveform_kind kind;
  double amplitude; /* multiplies the shape above */
  double frequency; /* f */
  double width;     /* w: Gaussian standard deviation in time / CW turn-on time */
  double delay;     /* t0 */
  double phase;     /* φ (Gaussian carrier, CW) in radians */
  double (*fn)(void *ctx, double t); /* GM_WAVE_CUSTOM; called once per step, not per cell */
  void *ctx;
} gm_waveform;

/* "gaussian", "dgaussian", "ricker", "cw", "custom"; NULL for an invalid value. */
const char *gm_waveform_kind_name(gm_waveform_kind kind);
/* By name (as above, case-insensitive). GM_ENOTFOUND when none. */
gm_status gm_waveform_kind_find(const char *name, gm_waveform_kind *out);
/* The value of the waveform at time t (GM_WAVE_CUSTOM calls fn). */
double gm_waveform_value(const gm_waveform *w, double t);
/* GM_EINVAL with a message for a waveform that cannot be evaluated (non-finite parameters,
 * w <= 0 for the Gaussians, f <= 0 for Ricker and CW, no fn for CUSTOM). */
gm_status gm_waveform_check(const gm_waveform *w, gm_error *err);

typedef enum gm_source_mode {
  GM_SOURCE_SOFT = 0, /* a current: J (E components) or M (H components) = waveform on that
                         edge/face, entering dG = 𝒥 (D' = curl H − J) or dF (B' = −curl E − M) */
  GM_SOURCE_HARD = 1  /* the field value is set to the waveform after each update */
} gm_source_mode;

/* A point dipole at x (coordinates), snapped to the nearest location of `component` inside
 * the grid. Soft E sources use J at t_n; soft H sources M at t_n + Δt/2; hard sources the
 * time of the field they set. */
typedef struct gm_point_source {
  gm_yee_component component;
  double x[3];
  gm_source_mode mode;
  gm_waveform wave;
} gm_point_source;

/* Add a source (copied). Errors: a component the dimension lacks, a position outside the grid
 * (more than half a cell beyond its last location), a bad waveform. id (may be NULL) receives
 * its index. */
gm_status gm_yee_add_point_source(gm_yee *solver, const gm_point_source *source, size_t *id);

/* A current density J = weight_e · waveform(t_n) on a set of edges of one E component (edge
 * (i,j,k) = array index (i,j,k) of that component, see gm_yee_layout). The charge it moves is
 * tracked: ρ^{n+½} = ρ^{n−½} − Δt div J^n on the vertices it touches, so that Gauss's law
 * div D − ρ is conserved exactly (gm_yee_gauss). */
typedef struct gm_current {
  gm_yee_component component; /* GM_EX, GM_EY or GM_EZ */
  size_t n_edges;
  const size_t *edges;        /* 3 indices per edge (copied) */
  const double *weights;      /* per edge (copied); NULL: all 1 */
  gm_waveform wave;
} gm_current;

/* Errors: not an E component or one the dimension lacks, an edge outside the grid or on a PEC
 * face, a bad waveform. */
gm_status gm_yee_add_current(gm_yee *solver, const gm_current *current, size_t *id);

/* Total-field/scattered-field plane wave along a grid axis (Taflove & Hagness ch. 5). The
 * incident field comes from a 1-D Yee grid with the same h and Δt along that axis in the medium
 * of the box's first cell, so the TF/SF faces cancel to round-off outside the box. The total
 * field region is the closed box of vertices [lo, hi]; on absent axes lo = hi = 0.
 * The incident E (component `polarization`, perpendicular to the axis) is
 * amplitude · g(t) at the aux grid's driven node, `margin` cells before the entry face, and
 * arrives there delayed by its (discrete) travel time. */
typedef struct gm_plane_wave {
  int axis;                       /* 0, 1, 2: direction of travel */
  int sign;                       /* +1: along +axis, −1: along −axis */
  gm_yee_component polarization;  /* GM_EX .. GM_EZ, not along axis */
  size_t lo[3], hi[3];            /* TF box (vertex indices), lo < hi on present axes, and at
                                     least one cell from the grid's faces */
  gm_waveform wave;
} gm_plane_wave;

gm_status gm_yee_add_plane_wave(gm_yee *solver, const gm_plane_wave *wave, size_t *id);

/* Total-field/scattered-field plane wave at any angle on a 2-D or 3-D grid (Taflove & Hagness
 * §5.8–5.9, the incident-field array): a 1-D Yee grid along the direction of travel, its
 * spacing chosen so that its numerical phase velocity equals the grid's along that direction
 * at match_frequency, read at each coupled location by interpolation (cubic or linear). Unlike the
 * axis-aligned wave the cancellation outside the box is not exact: the leakage measured is in
 * docs/maxwell.md. Angles in degrees:
 *   k̂ = (sin θ cos φ, sin θ sin φ, cos θ),
 *   ê = (cos ψ sin φ − sin ψ cos θ cos φ, −cos ψ cos φ − sin ψ cos θ sin φ, sin ψ sin θ),
 *   ĥ = k̂ × ê; incident E = e ê, H = (e/η) ĥ.
 * 2-D grids need θ = 90 (travel in the x-y plane); TM (E_z) is ψ = 90, TE (E in the plane)
 * ψ = 0. θ, φ, ψ at multiples of 90 give exact axis vectors. The wave is amplitude · g(t) at
 * the aux grid's driven node a few cells before the corner of the box it reaches first.
 * Errors: a 1-D grid, a component the grid lacks, non-finite angles, a bad box (as
 * gm_yee_add_plane_wave), a match frequency beyond the grid's cut-off, a matched spacing below
 * c Δt (the 1-D grid would be unstable). */
typedef enum gm_interpolation {
  GM_INTERP_CUBIC = 0,  /* 4-point Lagrange: the default (leakage in docs/maxwell.md) */
  GM_INTERP_LINEAR = 1  /* 2-point, as Taflove & Hagness */
} gm_interpolation;

typedef struct gm_oblique_wave {
  double theta, phi, psi;         /* degrees */
  size_t lo[3], hi[3];            /* TF box as in gm_plane_wave */
  double match_frequency;         /* 0: the waveform's frequency, or 1/(2π width) if that is 0 */
  gm_waveform wave;
  gm_interpolation interpolation; /* of the incident-field array (default cubic) */
} gm_oblique_wave;

gm_status gm_yee_add_oblique_wave(gm_yee *solver, const gm_oblique_wave *wave, size_t *id);
/* The unit vectors k̂, ê, ĥ of an oblique wave (above). */
void gm_oblique_wave_vectors(const gm_oblique_wave *wave, double k[3], double e[3], double h[3]);

/* ---- initial fields ----------------------------------------------------------------------- */

/* Set component c (real part: part 0; imaginary: part 1, complex fields only) from
 * values[layout.size] (copied, layout of gm_yee_layout); entries outside the component's
 * locations and tangential E on PEC faces are set to 0, ghosts refreshed. NaN/inf is
 * GM_EDOMAIN. Meant for initial data (step 0) but allowed at any step. */
gm_status gm_yee_set_field(gm_yee *solver, gm_yee_component c, int part, const double *values);
/* Same, values from f(ctx, x) at each location x of the component. */
gm_status gm_yee_set_field_fn(gm_yee *solver, gm_yee_component c, int part,
                              double (*f)(void *ctx, const double x[3]), void *ctx);

/* ---- running ------------------------------------------------------------------------------ */

/* An observer sees the solver (read-only) at a consistent state: H at gm_yee_time_h, E at
 * gm_yee_time_e. Return non-zero to stop the run with GM_ECALLBACK. */
typedef int (*gm_yee_observer_fn)(void *ctx, const gm_yee *solver);

/* Call fn whenever the step counter is a multiple of every (>= 1), step 0 included (at the
 * start of the first advance); how a run is split into advances does not change the calls. */
gm_status gm_yee_add_observer(gm_yee *solver, size_t every, gm_yee_observer_fn fn, void *ctx);

/* Advance n_steps steps. One step (seed 000 §3.4.1):
 *   E^{n+½} = E^{n−½} + Δt ⋆_ε⁻¹ (d̃ H^n − J^n)    (dG = 𝒥 on dual cells: Ampère)
 *   H^{n+1} = H^n − Δt ⋆_μ⁻¹ (d E^{n+½} + M)        (dF = 0 on primal faces: Faraday)
 * with σ loss (semi-implicit average) and CPML terms. Fails before stepping when a probe has
 * no room for n_steps samples. GM_EDOMAIN if the fields become non-finite (checked at
 * observer calls and at the end). */
gm_status gm_yee_advance(gm_yee *solver, size_t n_steps);
/* Advance to the last step with t_n <= t. */
gm_status gm_yee_advance_to(gm_yee *solver, double t);

size_t gm_yee_step(const gm_yee *solver);
double gm_yee_dt(const gm_yee *solver);
double gm_yee_time_h(const gm_yee *solver); /* n Δt */
double gm_yee_time_e(const gm_yee *solver); /* (n − ½) Δt */

/* ---- field arrays and layout (for writers) ------------------------------------------------ */

/* Every component array has the same layout: extent[a] = n[a] + 2 on present axes (one ghost
 * layer each side: index −1 and n), 1 on absent ones. Component c at index (i,j,k), i in
 * [−1, n0] on a present axis, is stored at
 *   (i + offset[0]) * stride[0] + (j + offset[1]) * stride[1] + (k + offset[2]) * stride[2]
 * (x fastest; offset 1 on present axes, 0 on absent ones) and sits at
 *   origin + h * ((i, j, k) + shift_c), shift_c from gm_yee_component_shift.
 * Its own locations are index ranges [0, count_c[a]) (gm_yee_component_count); everything
 * else (ghosts, unused entries) is not part of the field. */
typedef struct gm_yee_layout {
  gm_yee_dim dim;
  size_t n[3];      /* cells per axis (1 on absent axes) */
  double h[3];      /* cell sizes (1 on absent axes) */
  double origin[3];
  size_t extent[3];
  size_t offset[3];
  size_t stride[3];
  size_t size;      /* entries per component array */
  int complex_fields; /* 1: a second (imaginary) array per component */
} gm_yee_layout;

void gm_yee_get_layout(const gm_yee *solver, gm_yee_layout *layout);
/* Position of component c in cell units: ½ along the axis of an E component, ½ along the two
 * other axes of an H component, 0 elsewhere (0 on absent axes). */
void gm_yee_component_shift(gm_yee_dim dim, gm_yee_component c, double shift[3]);
/* Number of locations of c per axis: n on staggered axes, n + 1 on the others (1 on absent). */
void gm_yee_component_count(const gm_yee_layout *layout, gm_yee_component c, size_t count[3]);
/* Array index of (i,j,k) (each may be −1 .. n). */
size_t gm_yee_index(const gm_yee_layout *layout, long i, long j, long k);
/* The array of component c (part 0 real, 1 imaginary), borrowed, valid until the next advance
 * or set; NULL when the dimension lacks c or part 1 is asked of real fields. */
const double *gm_yee_field(const gm_yee *solver, gm_yee_component c, int part);
/* Value of component c at its location nearest to x (part 0/1). NaN when x is outside or the
 * component absent. */
double gm_yee_field_at(const gm_yee *solver, gm_yee_component c, int part, const double x[3]);

/* Bytes held by the solver and the number of grid-sized arrays among them. */
size_t gm_yee_memory(const gm_yee *solver, size_t *n_arrays);

/* ---- probes ------------------------------------------------------------------------------- */

/* A probe records component c at the location nearest to x (inside the grid) after every step,
 * with the time of that component, into room for `capacity` samples (allocated here). */
gm_status gm_yee_add_probe(gm_yee *solver, gm_yee_component c, const double x[3],
                           size_t capacity, size_t *id);
/* Recorded samples (borrowed, valid until the next advance/clear): n, times, real parts and
 * imaginary parts (NULL for real fields). */
gm_status gm_yee_probe_samples(const gm_yee *solver, size_t id, size_t *n, const double **t,
                               const double **re, const double **im);
gm_status gm_yee_probe_clear(gm_yee *solver, size_t id);
size_t gm_yee_probe_count(const gm_yee *solver);

/* ---- diagnostics -------------------------------------------------------------------------- */

typedef struct gm_yee_energy {
  double electric;  /* ½ Σ_edges V ε |E^{n−½}|² */
  double magnetic;  /* ½ Σ_faces V μ |H^n|² */
  double plain;     /* electric + magnetic (fields half a step apart; bounded, not conserved) */
  double leapfrog;  /* ½ [E^{n−½}·⋆_ε E^{n−½} + H^{n−1}·⋆_μ H^n], the quadratic form the
                       lossless leapfrog conserves exactly (H^{n−1} = H^n + Δt ⋆_μ⁻¹ d E^{n−½}
                       is reconstructed, not stored) */
  double polarization; /* energy held by the dispersive poles (yee_dispersive.c):
                          Σ_edges V Σ_poles [J² + ω0² P̄²] / (2 w s), J = (P^{n−½} − P^{n−3/2})/Δt,
                          P̄ their mean, s = Δε ω0² (Lorentz) or ω_p² (Drude), w the edge's
                          fraction of the medium; 0 without poles. leapfrog + polarization is
                          the total that a lossless medium keeps bounded */
} gm_yee_energy;

/* Energies summed over the grid (both parts for complex fields), PML cells included. V is the
 * dual volume of the edge/face (half cells at PMC faces). */
gm_status gm_yee_get_energy(const gm_yee *solver, gm_yee_energy *energy);

/* Discrete div B per primal cell (seed 000 eq. 3.10; B = ⋆_μ H as a 2-form over the cell's
 * faces divided by its volume). out (may be NULL): one value per cell at array index (i,j,k)
 * of the layout; max_abs (may be NULL): the largest |div B| (real part and imaginary part).
 * In CPML layers the stretched B is not the stored one; cells there are reported as 0. Soft H
 * sources are magnetic currents: they change div B by the magnetic charge they move. */
gm_status gm_yee_div_b(const gm_yee *solver, double *out, double *max_abs);
/* Gauss residual div D − ρ per primal vertex (seed 000 eq. 3.11, D = ⋆_ε E on dual faces, ρ
 * from the currents added; soft E point sources are currents too). Vertices on PEC and CPML
 * faces are reported as 0 (the wall holds a surface charge the scheme does not track), as are
 * vertices in CPML layers. Constant in time for σ = 0 without hard E sources (a conductor's
 * current σE moves charge that is not tracked; a hard source overrides Ampère's law). With a
 * Bloch k the charge of a current across the periodic face is booked without the phase. */
gm_status gm_yee_gauss(const gm_yee *solver, double *out, double *max_abs);
/* Total charge Σ ρ V moved by the currents so far. */
double gm_yee_charge(const gm_yee *solver);

/* Poynting flux ∫ (E × H)·n dA through the primal vertex plane `index` (1..n−1) normal to
 * axis, with E^{n−½} and H at t_{n−½} (the mean of H^n and the reconstructed H^{n−1}) averaged
 * over the two faces beside the plane; E_b and H_c (and E_c, H_b) share their positions in the
 * plane, so nothing else is interpolated. Positive along +axis. Its time sum equals the change
 * of the leapfrog energy on either side (the discrete Poynting theorem) away from sources and
 * CPML. Complex fields: the sum of the real parts' and the imaginary parts' fluxes. */
gm_status gm_yee_poynting_flux(const gm_yee *solver, int axis, size_t index, double *flux);

/* ---- DFT flux spectra (yee_dft.c) --------------------------------------------------------- */

/* Running Fourier transforms Ê(f) = Σ_n E(t) e^{2πi f t} Δt of the tangential E and H on the
 * primal vertex plane `index` (1..n−1) normal to axis, each field at its own time (E^{n−½},
 * H^n), at n_freq frequencies (copied; 0 <= f < 1/(2Δt)); the flux spectrum is
 * Re ∫ (Ê* × Ĥ)·n dA, positive along +axis (as MEEP's flux regions). Accumulated by an
 * observer added to the solver (every step, from the next advance): the object must stay alive
 * while the solver advances, and is freed by the caller after. Errors (GM_EINVAL, message in
 * gm_yee_errmsg): an axis the grid lacks, a plane at or beyond the walls or inside a CPML layer,
 * no frequencies, one outside [0, Nyquist). */
typedef struct gm_yee_dft_flux gm_yee_dft_flux;
gm_status gm_yee_dft_flux_create(gm_yee *solver, int axis, size_t index, size_t n_freq,
                                 const double *freq, gm_yee_dft_flux **out);
void gm_yee_dft_flux_free(gm_yee_dft_flux *flux);
size_t gm_yee_dft_flux_n_freq(const gm_yee_dft_flux *flux);
/* flux[n_freq]: the spectrum of the fields transformed so far. */
gm_status gm_yee_dft_flux_spectrum(const gm_yee_dft_flux *flux, double *spectrum);
/* Subtract the transforms of a normalisation run (same grid, plane, frequencies and step), so
 * that the spectrum is that of the scattered fields: for reflection, run without the object,
 * keep its flux object, run with it and subtract; −spectrum is the reflected flux. */
gm_status gm_yee_dft_flux_subtract(gm_yee_dft_flux *flux, const gm_yee_dft_flux *incident);
const char *gm_yee_dft_flux_errmsg(const gm_yee_dft_flux *flux);
/* Normalisation runs through a file (text, exact to the bit): save the transforms of n flux
 * objects; in a later run with the same planes, frequencies and step, subtract them plane by
 * plane (as gm_yee_dft_flux_subtract) and, when incident is non-NULL, write the saved run's
 * spectra there (n × n_freq, plane-major): T = spectrum/incident, R = −spectrum/incident.
 * Errors: GM_EIO (file), GM_EINVAL (another number of planes, another plane, frequencies or
 * point count; the message says which). */
gm_status gm_yee_dft_flux_save(gm_yee_dft_flux *const *fluxes, size_t n, const char *path,
                               gm_error *err);
gm_status gm_yee_dft_flux_subtract_file(gm_yee_dft_flux *const *fluxes, size_t n,
                                        const char *path, double *incident, gm_error *err);

/* ---- Maxwell on simplicial meshes: DEC leapfrog and AVI (seed 000 §3.4.2–3.4.3) ----------- */

/* The same plan/execute shape as gm_yee: gm_mesh_maxwell_create precomputes the diagonal Hodge
 * stars per cell, the PEC mask, the CFL limit and (AVI) the per-face steps and the event heap;
 * sources, probes and observers are added after create; advancing never allocates.
 *
 * Fields as cochains on a complex of dimension n = 2 (triangles in the plane: TE, B = Bz on the
 * triangles) or 3 (tetrahedra): E on primal edges (the value ∫_e E·dl), D = ⋆_ε E on the dual
 * (n−1)-cells, B on primal 2-faces (the flux ∫_σ B·dA), H = ⋆_ν B on the dual edges, with
 * ⋆_ε[e] = Σ_{T ≻ e} ε_T |⋆e ∩ T| / |e| and ⋆_ν[σ] = Σ_{T ≻ σ} |⋆σ ∩ T| / (μ_T |σ|) from the
 * circumcentric dual (the Bossavit–Kettunen diagonal stars). Units ε0 = μ0 = c = 1. PEC on the
 * whole boundary: E = 0 on boundary edges (their D and ⋆_ε are not used).
 * Leapfrog state after n steps (as gm_yee): B at t_n = t_0 + nΔt and E at t_n − Δt/2. */

typedef enum gm_mesh_maxwell_scheme {
  GM_MESH_LEAPFROG = 0, /* Bossavit–Kettunen (seed 000 §3.4.2, notes A11) */
  GM_MESH_AVI = 1       /* asynchronous variational integrator (§3.4.3, Fig. 3.6, notes A12) */
} gm_mesh_maxwell_scheme;

typedef enum gm_mesh_maxwell_star {
  GM_MESH_STAR_DIAGONAL = 0, /* circumcentric dual (Bossavit–Kettunen): diagonal, needs a
                                well-centred mesh */
  GM_MESH_STAR_WHITNEY = 1   /* Whitney (Galerkin) mass matrices (Bossavit 1988): ⋆_ε = ε M_1
                                solved by CHOLMOD (factorized once at create), ⋆_ν = M_2 / μ;
                                any mesh; ε and μ per cell (mass matrices
                                weighted cell by cell); leapfrog only */
} gm_mesh_maxwell_star;

typedef struct gm_mesh_maxwell_options {
  gm_mesh_maxwell_scheme scheme; /* default GM_MESH_LEAPFROG */
  gm_mesh_maxwell_star star;     /* default GM_MESH_STAR_DIAGONAL */
  double dt;            /* leapfrog step; <= 0: courant × the CFL limit. Above the limit: error */
  double courant;       /* default 0.9 */
  double avi_fraction;  /* AVI: each face's step is this fraction of its local limit
                           (default 0.1, as seed 000 E4) */
  const double *face_dt;/* AVI: per-face steps (count(2) values, copied; NULL: avi_fraction);
                           each must be <= the face's local limit */
  int allow_negative_stars; /* non-zero: accept a mesh that is not well-centred (⋆_ε or ⋆_ν
                               entries <= 0 on the interior); default 0: refuse */
  int avi_levels;       /* AVI: non-zero (default 1) rounds each face's step down to Δt_min 2^k
                           (Δt_min the smallest face step, k >= 0 the largest integer that
                           does), so the faces fall into few groups of equal steps; 0: the
                           steps as given (seed 000 Fig. 3.6). Either way the faces with bitwise
                           equal steps form one group, and the event heap holds groups, not
                           faces. Default by measurement (docs/maxwell-mesh.md): per face update
                           the levels cost 2.3-2.9x a leapfrog face update, distinct steps
                           40-140x (heap and scattered access). */
} gm_mesh_maxwell_options;

gm_mesh_maxwell_options gm_mesh_maxwell_defaults(void);

typedef struct gm_mesh_maxwell gm_mesh_maxwell;

/* A solver on geometry g (borrowed: it and its complex must outlive the solver; dimension 2 with
 * N = 2 or dimension 3 with N = 3), with ε and μ per top simplex (copied; NULL: vacuum).
 * Fields start at zero, t_0 = 0. Errors (GM_EINVAL, message in err): another dimension, ε or
 * μ <= 0 or non-finite (the cell is named), non-positive star entries on a mesh that is not
 * well-centred (the message gives their count) unless allow_negative_stars, dt above the CFL
 * limit (the message gives the limit), a face step above its local limit, a mesh with no
 * interior edge (under PEC every field is zero); GM_ENOMEM. */
gm_status gm_mesh_maxwell_create(const gm_geometry *g, const double *epsilon, const double *mu,
                                 const gm_mesh_maxwell_options *options, gm_mesh_maxwell **out,
                                 gm_error *err);
void gm_mesh_maxwell_free(gm_mesh_maxwell *s);
const char *gm_mesh_maxwell_errmsg(const gm_mesh_maxwell *s);

/* The leapfrog CFL limit 2/sqrt(λ_max(⋆_ε⁻¹ d₁ᵀ ⋆_ν d₁)) (interior edges), λ_max by power
 * iteration (Rayleigh quotient: a lower bound of λ_max, converged to 1e-6 relative), and the
 * per-face limits 2/sqrt(r_σ) with r_σ the Gershgorin row sum of the face's row of the
 * symmetrised operator ⋆_ν^½ d₁ ⋆_ε⁻¹ d₁ᵀ ⋆_ν^½ (a rigorous bound: min_σ of these is <= the
 * true limit). */
double gm_mesh_maxwell_cfl_limit(const gm_mesh_maxwell *s);
const double *gm_mesh_maxwell_face_limits(const gm_mesh_maxwell *s);
double gm_mesh_maxwell_dt(const gm_mesh_maxwell *s);
/* Leapfrog: step count and t_n; AVI: events processed and the time reached. */
size_t gm_mesh_maxwell_step(const gm_mesh_maxwell *s);
double gm_mesh_maxwell_time(const gm_mesh_maxwell *s);

/* Initial fields: E on edges (count(1) values: E at t_0 − Δt/2 for the leapfrog, E on the first
 * interval after t_0 for the AVI), B on faces (count(2); NULL leaves it). Copied; E on boundary
 * edges is set to 0. GM_EDOMAIN for non-finite values. Only before the first advance. */
gm_status gm_mesh_maxwell_set_fields(gm_mesh_maxwell *s, const double *E, const double *B);
/* Borrowed arrays: E (count(1)), D = ⋆_ε E, B (count(2): for the AVI each face at its own last
 * update time; gm_mesh_maxwell_sync_b gives B at the current time). */
const double *gm_mesh_maxwell_e(const gm_mesh_maxwell *s);
const double *gm_mesh_maxwell_b(const gm_mesh_maxwell *s);
/* B at the current time (AVI: B_σ = B_σ(t_0) − d₁ ∫ E dt with every edge brought to t). */
void gm_mesh_maxwell_sync_b(const gm_mesh_maxwell *s, double *B);

/* A current J_e = weights[i] · waveform(t_n) on edges[i] (interior edges, copied). Leapfrog:
 * D^{n+½} = D^{n−½} + Δt(d₁ᵀH^n − J^n); the charge it moves is booked,
 * ρ^{n+½} = ρ^{n−½} − Δt div J^n (div = −d₀ᵀ: outflow), so div D − ρ stays constant. AVI
 * (before the first advance): at an event at time t of a face holding edge e, with the face's
 * Ampère impulse, D_e −= J_e(t) (t − τ_J), τ_J the time of e's last current impulse (each
 * edge's current integrated over the intervals its faces' events cut; with equal steps the
 * leapfrog's); the charge is booked the same way. */
gm_status gm_mesh_maxwell_add_current(gm_mesh_maxwell *s, size_t n_edges, const size_t *edges,
                                      const double *weights, const gm_waveform *wave,
                                      size_t *id);
/* Probe: component c (GM_EX..GM_EZ: the Whitney interpolant of E; GM_HX..GM_HZ: of B over μ;
 * 2-D has Ex, Ey, Hz) at point x, recorded after every step (leapfrog: E at t − Δt/2) or, for
 * the AVI, every sample_dt of time from the synchronised fields; an AVI E probe records the mean
 * of E over the sampling interval (−ΔA/Δt, A = −∫E dt, exact), stamped at the interval's middle:
 * E jumps at the events of the fast cells, and point samples would alias their modes. Room for
 * capacity samples. GM_EINVAL: x in no cell, a component the dimension lacks. */
gm_status gm_mesh_maxwell_add_probe(gm_mesh_maxwell *s, gm_yee_component c, const double x[3],
                                    size_t capacity, size_t *id);
gm_status gm_mesh_maxwell_probe_samples(const gm_mesh_maxwell *s, size_t id, size_t *n,
                                        const double **t, const double **values);
/* AVI only: the probes' sampling interval (default: the smallest face step). */
gm_status gm_mesh_maxwell_set_sample_dt(gm_mesh_maxwell *s, double sample_dt);

typedef int (*gm_mesh_maxwell_observer_fn)(void *ctx, const gm_mesh_maxwell *s);
/* Leapfrog: fn at every step that is a multiple of every (step 0 included). AVI: every `every`
 * probe samples. Non-zero return stops with GM_ECALLBACK. */
gm_status gm_mesh_maxwell_add_observer(gm_mesh_maxwell *s, size_t every,
                                       gm_mesh_maxwell_observer_fn fn, void *ctx);

/* Leapfrog: n steps (seed 000 §3.4.2, notes A11):
 *   D^{n+½} = D^{n−½} + Δt (d₁ᵀ ⋆_ν B^n − J^n),  E^{n+½} = ⋆_ε⁻¹ D^{n+½}   (Ampère, dG = 𝒥)
 *   B^{n+1} = B^n − Δt d₁ E^{n+½}                                        (Faraday, dF = 0)
 * GM_EDOMAIN when the fields become non-finite (looked for every 64 steps and at the end; the
 * message names the times between which it happened). AVI: GM_EINVAL (use advance_to). */
gm_status gm_mesh_maxwell_advance(gm_mesh_maxwell *s, size_t n_steps);
/* Leapfrog: to the last step with t_n <= t. AVI: process every face event with time <= t. */
gm_status gm_mesh_maxwell_advance_to(gm_mesh_maxwell *s, double t);

/* Counts of face updates (B) and edge updates (D) done so far. */
void gm_mesh_maxwell_update_counts(const gm_mesh_maxwell *s, size_t *faces, size_t *edges);
/* Maxwell on the 2+1 prismal spacetime complex K × {t_0 .. t_N} of a 2-D triangle mesh as one
 * sparse solve (seed 000 §3.4.4): F = E∧dt + B on the primal 2-cells, the κ-signed diagonal
 * Lorentzian star (+ on spatial faces, − on extruded ones; circumcentric, so the mesh must be
 * well-centred as for gm_mesh_maxwell_create), dF = 0 on every prism and dG = 𝒥 on the interior
 * spatial edges at t_1..t_{N−1}, with the initial data B0 (nf) and E_half (ne, E at Δt/2), PEC
 * walls. J: NULL or N × ne currents (row n at t_n; row 0 unused). Out: B ((N+1) × nf, B at t_n)
 * and E (N × ne, E at t_n + Δt/2). res (may be NULL): the residuals of dF = 0 on every prism and
 * of dG = 𝒥 on the interior spatial edges (Ampère) and on the temporal edges of interior
 * vertices (Gauss, not imposed), relative to the largest term. Allocates. */
typedef struct gm_mesh_maxwell_spacetime_residuals {
  double dF, dG_ampere, dG_gauss;
  size_t unknowns;
} gm_mesh_maxwell_spacetime_residuals;
gm_status gm_mesh_maxwell_spacetime(const gm_geometry *g, const double *epsilon, const double *mu,
                                    size_t n_slabs, double dt, const double *B0,
                                    const double *E_half, const double *J, double *B, double *E,
                                    gm_mesh_maxwell_spacetime_residuals *res, gm_error *err);
/* AVI: the number of groups of faces with equal steps (one heap entry each); 0 for the leapfrog. */
size_t gm_mesh_maxwell_avi_groups(const gm_mesh_maxwell *s);

typedef struct gm_mesh_maxwell_energy {
  double electric; /* ½ Eᵀ ⋆_ε E */
  double magnetic; /* ½ Bᵀ ⋆_ν B (AVI: synchronised B) */
  double plain;    /* electric + magnetic */
  double leapfrog; /* ½ [Eᵀ⋆_ε E + B^{n−1}ᵀ ⋆_ν B^n], B^{n−1} = B^n + Δt d₁E^{n−½}: conserved
                      exactly by the leapfrog without sources (AVI: = plain) */
} gm_mesh_maxwell_energy;
void gm_mesh_maxwell_energy_get(const gm_mesh_maxwell *s, gm_mesh_maxwell_energy *energy);
/* max over top simplices of |d_{n−1} B| (3-D: div B per tetrahedron, the flux out of it; 2-D:
 * 0 by construction, B being a top form); AVI: of the synchronised B. NaN when B holds a NaN
 * (a blown-up run never reports a clean invariant); likewise gm_mesh_maxwell_gauss. */
double gm_mesh_maxwell_div_b(const gm_mesh_maxwell *s);
/* Gauss residual div D − ρ = −d₀ᵀD − ρ per vertex (out: count(0) values, may be NULL);
 * boundary vertices are reported as 0 (PEC walls carry surface charge the scheme does not
 * track). Returns the max |.| over vertices. */
double gm_mesh_maxwell_gauss(const gm_mesh_maxwell *s, double *out);
/* Σ ρ over the vertices (charge moved by the currents: 0 up to round-off). */
double gm_mesh_maxwell_charge(const gm_mesh_maxwell *s);

/* ---- harminv: resonances of a signal (Mandelshtam & Taylor filter diagonalization) --------- */

typedef struct gm_harminv_mode {
  double frequency; /* cycles per unit time */
  double decay;     /* decay rate (1/time): the signal ~ exp(−decay t) */
  double q;         /* quality factor π f / decay */
  double amplitude; /* |amplitude| */
  double phase;     /* arg amplitude (radians) */
  double error;     /* harminv's relative frequency error estimate */
} gm_harminv_mode;

/* Modes of the signal re (+ i im when im is non-NULL) sampled every dt, with frequencies in
 * [f_min, f_max] (harminv's band; 0 <= f_min < f_max <= 1/(2dt)), using n_basis basis
 * functions (0: the harminv program's default, 1.1 per Fourier bin of the band, 2..300). At most max_modes are written, in
 * ascending frequency; n_modes receives how many were written. Every mode harminv returns in
 * the band is kept (filter on error/Q yourself). Real signals give each mode once, at f > 0.
 * Errors: n < 8, non-finite samples or dt, a bad band. */
gm_status gm_harminv(size_t n, const double *re, const double *im, double dt, double f_min,
                     double f_max, size_t n_basis, size_t max_modes, gm_harminv_mode *modes,
                     size_t *n_modes, gm_error *err);

/* ---- PEC cavity resonances on a mesh (verification; docs/maxwell-mesh.md) ----------------- */

/* Analytic resonances (ε = μ = c = 1), ascending, each listed once per polarisation, up to
 * f_max. Box a×b×c: f = ½ √((l/a)² + (m/b)² + (n/c)²), two polarisations (TE and TM) when
 * l, m, n >= 1, one when exactly one is 0, none when two are. Cylinder radius R, height H:
 * TM_mnp f = √((j_mn/R)² + (pπ/H)²)/2π (p >= 0) and TE_mnp with j'_mn (p >= 1), two
 * polarisations for m >= 1; Bessel zeros by bisection on jn() from <math.h>. Errors (GM_EINVAL):
 * non-positive sizes or f_max, more than cap resonances (the message gives the count). */
gm_status gm_cavity_box_resonances(const double L[3], double f_max, size_t cap, double *f,
                                   size_t *n, gm_error *err);
gm_status gm_cavity_cylinder_resonances(double R, double H, double f_max, size_t cap, double *f,
                                        size_t *n, gm_error *err);
/* Sphere of radius a: TE_lnp j_l(x) = 0, TM_lnp [x j_l(x)]' = 0, f = x/(2πa), l >= 1, each
 * listed 2l+1 times; spherical Bessel functions by Miller's downward recurrence, zeros by
 * bisection to round-off. Errors (GM_EINVAL): as above, and 2π f_max a > 60. */
gm_status gm_cavity_sphere_resonances(double a, double f_max, size_t cap, double *f, size_t *n,
                                      gm_error *err);

/* A ring-down measurement of a PEC cavity: the leapfrog on the mesh, excited by
 * Gaussian current pulses on a carrier at (f_min + f_max)/2 (time width pulse_width; 0: the
 * spectral width (f_max − f_min)/2.5; delay 6 widths; the static field of the charge they
 * leave is removed as the signal's mean after 12 widths, where the record starts) on
 * n_sources pseudo-random interior edges with random weights ±[1, 2], E_x, E_y, E_z (2-D TE
 * on triangles in the plane: E_x, E_y, H_z) probed at n_probes pseudo-random interior points and summed with random weights (so no mode sits at
 * a node of the signal), run to t_end; harminv of the sum in bands of width `band` over
 * [f_min, f_max]; modes kept with harminv error < max_error and amplitude >= min_amplitude
 * times the largest. */
typedef struct gm_mesh_cavity_run {
  double t_end, f_min, f_max, band; /* defaults 60, 0.3, 2, 0.5 */
  size_t n_sources, n_probes;       /* defaults 6, 4 (probes <= 64) */
  uint64_t seed;                    /* default 11 */
  double pulse_width;               /* default 0 (from the band) */
  double max_error, min_amplitude;  /* defaults 1e-3, 0.01 */
  /* optional (default NULL): called every 1/200 of the run with the steps done and planned; a
   * non-zero return stops the measurement (GM_ECALLBACK) */
  int (*progress)(void *ctx, double steps_done, double steps_total);
  void *progress_ctx;               /* borrowed */
} gm_mesh_cavity_run;
gm_mesh_cavity_run gm_mesh_cavity_run_defaults(void);
/* The modes (at most cap, ascending) of the cavity g (tetrahedra, or triangles in the plane;
 * PEC walls, vacuum) under the
 * solver options (borrowed); dt_out (may be NULL) gets the step. Allocates (a solver and the
 * signal). Errors: as gm_mesh_maxwell_create, bad run fields, f_max above Nyquist, more than
 * cap modes (GM_EINVAL). */
gm_status gm_mesh_maxwell_cavity_modes(const gm_geometry *g,
                                       const gm_mesh_maxwell_options *options,
                                       const gm_mesh_cavity_run *run, size_t cap,
                                       gm_harminv_mode *modes, size_t *n_modes, double *dt_out,
                                       gm_error *err);
/* The spatial eigenfrequency behind a leapfrog frequency f at step dt (the leapfrog's dispersion
 * sin(ωΔt/2) = (Δt/2)√λ undone): sin(π f Δt)/(π Δt). */
double gm_leapfrog_space_frequency(double f, double dt);

#ifdef __cplusplus
}
#endif
#endif
