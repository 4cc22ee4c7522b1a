/* geomint fluids: incompressible Navier–Stokes with a passive scalar by discrete exterior calculus
 * on flat triangle meshes (seed 004 §"Discrete exterior calculus", eqs. 151–157, reconstructed in
 * seeds/notes/003-004 §2.5; the scheme of Mohamed, Hirani & Samtaney, J. Comput. Phys. 312 (2016)
 * 175–191). docs/fluids.md lists every reconstruction and what was measured.
 *
 * Unknowns where the seed puts them: the stream function ψ and the scalar θ on primal vertices;
 * the velocity 1-form ω = u♭ lives on dual edges and is never stored: its flux through each
 * primal edge is dψ, so the net flux out of every triangle is d(dψ) = 0 (δω = 0 by d∘d = 0). The
 * vorticity is the circulation Γ_v of ω around each dual cell ⋆v (a dual 2-form); ζ_v = Γ_v/|⋆v|.
 *
 * Boundary conditions are given per named group of boundary edges (Gmsh physical groups, or the
 * sides of a generated rectangle). Plan/execute (DESIGN §5a): gm_fluid_create does every
 * precomputation (stars, boundary stream function, matrices, CHOLMOD factorizations, work
 * arrays); gm_fluid_advance is back-substitutions and sparse products, with no allocation.
 * Pointer parameters are borrowed unless a comment says otherwise. */
#ifndef GEOMINT_FLUIDS_H
#define GEOMINT_FLUIDS_H

#include <stddef.h>

#include "geomint/core.h"
#include "geomint/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- boundary groups ----------------------------------------------------------------------- */

#define GM_FLUID_NAME_SIZE 64

/* Named groups of boundary edges: edge i joins mesh vertices vertices[2i], vertices[2i+1] and
 * belongs to group group[i] (index into names). Owned by the caller of the functions below. */
typedef struct gm_fluid_groups {
  size_t n_groups;
  char (*names)[GM_FLUID_NAME_SIZE];
  size_t n_edges;
  size_t *vertices; /* 2 per edge */
  size_t *group;    /* 1 per edge */
} gm_fluid_groups;

void gm_fluid_groups_free(gm_fluid_groups *g);
/* The boundary edges of a mesh of the rectangle [x0,x1]×[y0,y1] (gm_mesh_rectangle) in four
 * groups named "bottom", "right", "top", "left" by the side they lie on (corners: the side of the
 * edge's midpoint). GM_EINVAL when a boundary edge lies on no side. */
gm_status gm_fluid_groups_rectangle(const gm_mesh *mesh, gm_fluid_groups **out, gm_error *err);
/* The line elements of a Gmsh ASCII 2.2 file with a physical tag named in $PhysicalNames,
 * matched to the vertices of `mesh` (read from the same file) by their coordinates. */
gm_status gm_fluid_groups_read_msh(const char *path, const gm_mesh *mesh, gm_fluid_groups **out,
                                   gm_error *err);

/* ---- boundary conditions ------------------------------------------------------------------- */

typedef enum {
  GM_FLUID_WALL = 0,   /* no normal flow; tangential velocity = `velocity` (0: no-slip) */
  GM_FLUID_INFLOW = 1, /* prescribed velocity: the parabola of centreline speed `speed` across
                          the group (a straight run of edges), or `profile` when set */
  GM_FLUID_OUTFLOW = 2, /* ψ free, zero tangential velocity, zero diffusive flux of vorticity */
  /* Identified with the group named `partner` by the translation that maps the group's bounding
   * box onto the partner's: vertices and edges of the pair become one (the DEC operators live on
   * the quotient complex). Every boundary group must then be periodic (a fully periodic domain;
   * periodic channels with walls are not implemented), and the scheme GM_FLUID_MIDPOINT. */
  GM_FLUID_PERIODIC = 3
} gm_fluid_bc_kind;

typedef enum {
  GM_SCALAR_ZERO_FLUX = 0, /* no diffusive flux (convective flux through outflows only) */
  GM_SCALAR_DIRICHLET = 1  /* θ = scalar_value */
} gm_fluid_scalar_bc;

/* A velocity field u(x) (2 values) for inflow profiles; return non-zero to fail. */
typedef int (*gm_fluid_velocity_fn)(void *ctx, const double *x, double *u);

typedef struct gm_fluid_bc {
  const char *group; /* group name (copied) */
  gm_fluid_bc_kind kind;
  double velocity[2];           /* WALL: wall velocity (its tangential part is used) */
  double speed;                 /* INFLOW: centreline speed of the parabolic profile */
  gm_fluid_velocity_fn profile; /* INFLOW: optional profile instead of the parabola */
  void *profile_ctx;
  gm_fluid_scalar_bc scalar;
  double scalar_value;
  const char *partner; /* PERIODIC: the group identified with this one (copied) */
} gm_fluid_bc;

/* ---- the solver ---------------------------------------------------------------------------- */

typedef enum {
  /* Seed 004 eqs. 153–156 [R]: an explicit half step of the convection, a semi-implicit step of
   * the vorticity/stream function, an implicit diffusion step of the scalar. */
  GM_FLUID_SEED = 0,
  /* Implicit midpoint on the vorticity with the P1 Jacobian (antisymmetric trilinear form).
   * ν = 0 in a closed box of walls at rest (slip), or ν >= 0 on a domain without boundary (fully
   * periodic planar mesh, closed surface in R³; the viscous term implicit in the midpoint rule).
   * At ν = 0 kinetic energy, enstrophy (of the absolute vorticity with rotation) and total
   * vorticity are conserved to the tolerance of the fixed-point iteration. */
  GM_FLUID_MIDPOINT = 1
} gm_fluid_scheme;

typedef struct gm_fluid_options {
  gm_fluid_scheme scheme;   /* default GM_FLUID_SEED */
  double nu;                /* kinematic viscosity >= 0 (default 1) */
  double kappa;             /* scalar diffusivity >= 0 (default 1) */
  double dt;                /* time step > 0 (default 1e-2) */
  double velocity_scale;    /* speed used in the half step's Courant bound, in addition to the
                               boundary speeds and the initial velocity (default 0) */
  double midpoint_tol;      /* fixed-point tolerance of GM_FLUID_MIDPOINT, relative (1e-15) */
  size_t midpoint_max_iter; /* default 200 */
  /* GM_FLUID_MIDPOINT: the Jacobian sees ζ = 0 on the walls (flat stress-free walls, where
   * ∂u_t/∂n = 0 gives ζ = 0) instead of the wall vortex sheet Γ_v/|⋆v| = O(1/h) of the boundary
   * dual cells. Energy and total vorticity stay exact; the conserved enstrophy is then the
   * interior one (gm_fluid_diagnostics.interior_enstrophy). Default 0. docs/fluids.md. */
  int stress_free_walls;
  /* Closed surfaces in R³: angular speed Ω of the frame about the z axis; the Jacobian advects
   * the absolute vorticity ζ + f with f = 2Ω z/|x| (2Ω sin(latitude) on a sphere about the
   * origin): the non-divergent barotropic vorticity equation. Default 0. */
  double rotation;
} gm_fluid_options;

gm_fluid_options gm_fluid_defaults(void);

typedef struct gm_fluid gm_fluid;

/* Build the solver on a flat triangle mesh (dim 2, coordinates in the plane) or a closed
 * triangle surface in R³ (dim 2, N = 3; GM_FLUID_MIDPOINT only), its boundary
 * groups (an empty set for closed surfaces) and one condition per group (bcs[i].group names a group; every boundary edge must be in
 * a group that has a condition). Copies what it needs. The initial state is ψ = the boundary
 * values on the walls and inflows and 0 elsewhere, θ = the Dirichlet values on the boundary and
 * 0 elsewhere (gm_fluid_set_state changes it).
 * Errors (GM_EINVAL unless noted; the message names the culprit): ν < 0, κ < 0, dt <= 0 or
 * non-finite values; a condition naming a group absent from the mesh; a boundary edge without a
 * condition; a mesh that is not well-centred enough for the diagonal star (counts of edges with
 * ⋆1 <= 0, vertices with ⋆0 <= 0, triangles not well-centred); dt above the Courant bound of the
 * explicit half step (the bound is in the message and in gm_fluid_dt_bound); more than one
 * boundary loop or outflow run per loop (GM_EUNSUPPORTED); a net inflow with no outflow; a
 * surface mesh that is not a closed manifold (edges not shared by exactly two triangles,
 * vertices whose triangles do not form one fan: counts and the first culprit); a periodic group
 * whose vertices have no partner vertex (named, with the offset). On domains without boundary
 * ψ is fixed to 0 at one vertex (its gauge). */
gm_status gm_fluid_create(const gm_mesh *mesh, const gm_fluid_groups *groups, size_t n_bcs,
                          const gm_fluid_bc *bcs, const gm_fluid_options *options, gm_fluid **out,
                          gm_error *err);
void gm_fluid_free(gm_fluid *f);
const char *gm_fluid_errmsg(const gm_fluid *f);

/* Replace the state: psi (n_vertices values; boundary values of walls and inflows are kept from
 * the conditions) and theta (n_vertices; Dirichlet values kept); either may be NULL (unchanged).
 * GM_EDOMAIN for non-finite values; GM_EINVAL when the new velocity violates the Courant bound. */
gm_status gm_fluid_set_state(gm_fluid *f, const double *psi, const double *theta);
/* Advance n steps. GM_EDOMAIN (state kept at the last finite step) when the solution blows up;
 * GM_ENOCONV when the midpoint iteration does not converge. */
gm_status gm_fluid_advance(gm_fluid *f, size_t n_steps);

/* Solver vertices: the mesh's, or on a periodic mesh the classes of identified vertices. The
 * per-vertex arrays below have this length. */
size_t gm_fluid_n_vertices(const gm_fluid *f);
/* Mesh vertex -> solver vertex (n_mesh_vertices entries), NULL when they are the same. */
const size_t *gm_fluid_vertex_map(const gm_fluid *f);
/* Coordinates of each solver vertex (gm_fluid_space_dim values each; a periodic class takes its
 * lowest-numbered mesh vertex's). */
const double *gm_fluid_coordinates(const gm_fluid *f);
/* 2 for flat meshes, 3 for surfaces in R³. */
size_t gm_fluid_space_dim(const gm_fluid *f);
size_t gm_fluid_n_triangles(const gm_fluid *f);
const gm_complex *gm_fluid_complex(const gm_fluid *f);
const gm_geometry *gm_fluid_geometry(const gm_fluid *f);
double gm_fluid_time(const gm_fluid *f);
size_t gm_fluid_steps(const gm_fluid *f);
double gm_fluid_dt(const gm_fluid *f);
/* Largest dt the explicit half step allows (+inf when every speed is zero). */
double gm_fluid_dt_bound(const gm_fluid *f);
const double *gm_fluid_psi(const gm_fluid *f);         /* per vertex */
const double *gm_fluid_theta(const gm_fluid *f);       /* per vertex */
const double *gm_fluid_circulation(const gm_fluid *f); /* Γ per vertex (dual cell) */
/* ζ = Γ/|⋆v| per vertex (n_vertices values written). */
void gm_fluid_vorticity(const gm_fluid *f, double *zeta);
/* Velocity per triangle (gm_fluid_space_dim values each): u = ∇ψ × n = (∂ψ/∂y, −∂ψ/∂x) in the
 * plane, of the linear interpolant of ψ, the Whitney (Raviart–Thomas) reconstruction whose
 * normal flux through each edge is dψ. */
void gm_fluid_velocity(const gm_fluid *f, double *u);
/* Flux through each primal edge of the mesh, oriented by the complex: dψ (the complex's n_edges
 * values; on a periodic mesh both copies of a seam edge carry the flux). */
void gm_fluid_flux(const gm_fluid *f, double *flux);

typedef struct gm_fluid_diagnostics {
  double time;
  double kinetic_energy;      /* ½ Σ_T |T| |u_T|² = ½ ψᵀ d0ᵀ⋆1 d0 ψ */
  double enstrophy;           /* ½ Σ_v Γ_v² / |⋆v| */
  double interior_enstrophy;  /* the same over the vertices where ψ is free */
  double total_vorticity;     /* Σ_v Γ_v */
  double div_max;             /* ‖δω‖∞: max over triangles of the net flux out, |d1 dψ| */
  double scalar_mass;         /* Σ_v |⋆v| θ_v */
  size_t midpoint_iterations; /* of the last step (GM_FLUID_MIDPOINT) */
} gm_fluid_diagnostics;

void gm_fluid_diagnose(const gm_fluid *f, gm_fluid_diagnostics *d);

/* ---- case files (JSON) --------------------------------------------------------------------- */

typedef enum {
  GM_FLUID_INIT_REST = 0, /* ψ = boundary values, 0 inside; θ = Dirichlet values, 0 inside */
  GM_FLUID_INIT_SHEAR_MODES = 1, /* ψ = A (sin πx̂ sin πŷ + ½ sin 2πx̂ sin πŷ) on the bounding box
                                   (x̂, ŷ in [0,1]); θ = a Gaussian blob at (0.3, 0.6) */
  /* periodic boxes (x̂, ŷ in [0, 1] on the bounding box; θ the same blob): */
  GM_FLUID_INIT_TAYLOR_GREEN = 2, /* ψ = A sin 2πx̂ sin 2πŷ */
  GM_FLUID_INIT_DOUBLE_SHEAR = 3, /* gm_fluid_double_shear's layer on [0, 2π]² scaled to the box */
  /* the unit-sphere directions x/|x| of a surface (θ = the blob at latitude 30°, longitude 0): */
  GM_FLUID_INIT_ROSSBY_HAURWITZ = 4 /* gm_fluid_rossby_haurwitz's wave (Ω-scaled units) */
} gm_fluid_initial;

/* A case file read into memory: mesh, groups, conditions, options, run length and outputs.
 * docs/fluids.md gives the format; every error names the JSON path of the bad value. */
typedef struct gm_fluid_case {
  gm_mesh *mesh;
  gm_fluid_groups *groups;
  size_t n_bcs;
  gm_fluid_bc *bcs; /* group names point into bc_names */
  char (*bc_names)[GM_FLUID_NAME_SIZE];
  char (*partner_names)[GM_FLUID_NAME_SIZE]; /* periodic partners (bcs[i].partner) */
  gm_fluid_options options;
  double rho; /* density (only scales the pressure; default 1) */
  double t_end;
  gm_fluid_initial initial;
  double initial_amplitude; /* default 0.1 */
  size_t output_every;      /* VTU every k steps (0: none); CSV every step */
} gm_fluid_case;

/* Read a case file (mesh paths relative to its directory). GM_EIO when it cannot be read,
 * GM_EINVAL with "FILE: $.path: what" for bad values, and the errors of the mesh readers. */
gm_status gm_fluid_case_read(const char *path, gm_fluid_case **out, gm_error *err);
/* The same from a NUL-terminated text; base_dir (may be NULL: ".") resolves mesh paths. */
gm_status gm_fluid_case_parse(const char *text, const char *base_dir, gm_fluid_case **out,
                              gm_error *err);
void gm_fluid_case_free(gm_fluid_case *c);
/* Create the solver of a case with its initial state. */
gm_status gm_fluid_case_solver(const gm_fluid_case *c, gm_fluid **out, gm_error *err);

typedef struct gm_fluid_run_report {
  size_t steps;
  size_t vtu_files;
  double div_max; /* max over all steps of ‖δω‖∞ */
  gm_fluid_diagnostics first, last;
} gm_fluid_run_report;

/* Run a case to t_end. With out_dir (an existing directory; NULL: no files): diagnostics.csv
 * (one row per step: step, time, kinetic_energy, enstrophy, total_vorticity, div_max,
 * scalar_mass), fluid_NNNNNN.vtu every output_every steps (ψ, θ, ζ on vertices, velocity on
 * triangles) and fluid.pvd listing them. A run that blows up stops with GM_EDOMAIN, keeping the
 * files written so far (the .pvd included). */
gm_status gm_fluid_case_run(const gm_fluid_case *c, const char *out_dir, gm_fluid_run_report *rep,
                            gm_error *err);

/* ---- seed 004 experiments ------------------------------------------------------------------- */

typedef struct gm_fluid_channel_result {
  size_t n_triangles, steps;
  double mean_edge;
  double profile_error;  /* mean |dψ/|e| − u_exact(midpoint)·n_e| over the edges with midpoint
                            x in [L/4, 3L/4] (the flux per unit length against Poiseuille) */
  double centroid_error; /* mean |u_T − u_exact(centroid)| over the triangles there */
  double theta_error;    /* max |θ − 20 y| over the vertices there (θ linear across) */
  double div_max;        /* max over all steps of ‖δω‖∞ */
} gm_fluid_channel_result;

/* B14: the channel [0, 2π]×[0, 1], ν = κ = 1, parabolic inflow of centreline speed 1, outflow
 * on the right, θ = 20 on the top wall, 0 on the bottom and the inlet; zero initial flow, dt =
 * 1e-2 to t_end, acute rectangle mesh of nx cells along the channel (nx = 210: mean edge 2.99e-2,
 * the seed's 2.989e-2). */
gm_status gm_fluid_channel(size_t nx, double t_end, gm_fluid_channel_result *r, gm_error *err);

typedef struct gm_fluid_shear_result {
  double mean_edge, psi, theta, velocity, flux; /* errors (see docs/fluids.md for the norms) */
  double div_max;
} gm_fluid_shear_result;

/* B15: Couette (poiseuille = 0) or Poiseuille flow on the unit square on an acute mesh of n
 * cells across, started from the exact ψ and θ = y and run with dt to t_end (the steady state):
 * errors of ψ and θ (⋆0-weighted), velocity per triangle (area-weighted), flux per unit length
 * on the edges (|e||⋆e|-weighted). */
gm_status gm_fluid_shear(int poiseuille, size_t n, double dt, double t_end,
                         gm_fluid_shear_result *r, gm_error *err);

/* ---- flows on domains without boundary (docs/fluids.md) -------------------------------------- */

typedef struct gm_fluid_flow_result {
  size_t n_triangles, n_vertices, steps, max_iterations;
  double mean_edge;
  double measured, exact; /* Taylor–Green: amplitude decay rate and 2ν; Rossby–Haurwitz: angular
                             speed of the pattern and Haurwitz's; double shear layer: 0 */
  /* max over the steps of |X − X0| / |X0| (total vorticity: |ΣΓ − ΣΓ0| / Σ|Γ0|) */
  double energy_drift, enstrophy_drift, vorticity_drift;
  double energy_change; /* (E(T) − E0)/E0 */
  double div_max;
} gm_fluid_flow_result;

/* The square [0, L]² as a triangular lattice for periodic pairs: n cells along x, an even number
 * of rows ≈ 2n/√3 (near-equilateral triangles), every other row shifted by half a cell, so the
 * sides "left" and "right" are zigzags that match by translation, as do "bottom" and "top";
 * identified, every vertex has six triangles (no right triangles at the seams). */
gm_status gm_fluid_periodic_square_mesh(double L, size_t n, gm_mesh **mesh,
                                        gm_fluid_groups **groups, gm_error *err);
/* Taylor–Green vortex ψ = sin x sin y on the periodic square [0, 2π]²
 * (gm_fluid_periodic_square_mesh, n cells along x), with viscosity nu (scheme GM_FLUID_MIDPOINT or GM_FLUID_SEED): `measured` = −ln(E(T)/E0)/(2T), against exact
 * 2ν (the amplitude decays as exp(−2νt)). */
gm_status gm_fluid_taylor_green(gm_fluid_scheme scheme, size_t n, double nu, double dt, size_t steps,
                                gm_fluid_flow_result *r, gm_error *err);
/* Inviscid double shear layer on [0, 2π]² (Bell, Colella & Glaz, J. Comput. Phys. 85 (1989)
 * 257–283: u = tanh((y − π/2)/δ) below y = π, tanh((3π/2 − y)/δ) above, v = ε sin x, δ = π/15,
 * ε = 0.05), ν = 0 (either scheme; the seed scheme does not conserve energy). */
gm_status gm_fluid_double_shear(gm_fluid_scheme scheme, size_t n, double dt, size_t steps, gm_fluid_flow_result *r,
                                gm_error *err);
/* Rossby–Haurwitz wave of wavenumber 4 on the unit sphere rotating at Ω = 1 (icosphere of the
 * given subdivisions), ω = K = 7.848e-6/7.292e-5 (Williamson et al. 1992, test 6, in units of
 * 1/Ω), midpoint scheme, ν = 0, to t_end: `measured` = angular speed of the pattern (phase of
 * its zonal wavenumber-4 part), `exact` = (R(3+R)ω − 2Ω)/((1+R)(2+R)) (Haurwitz 1940). */
gm_status gm_fluid_rossby_haurwitz(size_t subdivisions, double dt, double t_end,
                                   gm_fluid_flow_result *r, gm_error *err);

#ifdef __cplusplus
}
#endif
#endif
