/* geomint mesh: simplicial meshes as plain data, generators, file readers and writers, a quality
 * report and a Poisson check.
 *
 * A gm_mesh is a vertex array (N coordinates each) and cells of one dimension (dim+1 vertex indices
 * each). gm_mesh_complex turns it into a gm_complex (geomint/dec.h). Readers report bad files with
 * the line number; nothing here prints. Pointer parameters are borrowed unless a comment says
 * otherwise. */
#ifndef GEOMINT_MESH_H
#define GEOMINT_MESH_H

#include <stddef.h>

#include "geomint/core.h"
#include "geomint/dec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gm_mesh {
  size_t N;          /* coordinates per vertex (1..3) */
  size_t n_vertices;
  double *x;         /* N * n_vertices */
  size_t dim;        /* cell dimension (1..3) */
  size_t n_cells;
  size_t *cells;     /* (dim + 1) * n_cells */
  int *cell_tags;    /* one tag per cell (Gmsh physical tag; 0 when none) */
} gm_mesh;

/* An uninitialised mesh of the given sizes (arrays allocated, tags zeroed). */
gm_status gm_mesh_create(size_t N, size_t n_vertices, size_t dim, size_t n_cells, gm_mesh **out);
void gm_mesh_free(gm_mesh *mesh);
/* The complex of the mesh's cells (see gm_complex_create for the errors). */
gm_status gm_mesh_complex(const gm_mesh *mesh, gm_complex **out, gm_error *err);
/* Keep the cells whose centroid satisfies keep(ctx, centroid) != 0 and the vertices they use
 * (vertices renumbered in their old order). */
gm_status gm_mesh_filter(gm_mesh *mesh, int (*keep)(void *ctx, const double *centroid), void *ctx);

/* ---- generators ------------------------------------------------------------------------- */

typedef enum {
  GM_DIAGONAL_RIGHT = 0,     /* every square cut by its (0,0)-(1,1) diagonal */
  GM_DIAGONAL_LEFT = 1,      /* every square cut by its (1,0)-(0,1) diagonal */
  GM_DIAGONAL_ALTERNATE = 2, /* the two diagonals alternate like a chessboard */
  GM_DIAGONAL_ACUTE = 3      /* rows shifted by half a cell: acute (equilateral when
                                ny/ly = 2 nx/(√3 lx)) triangles inside, right triangles on the
                                left and right sides; all Hodge stars positive when
                                ly/ny > lx/(2 nx). Well-centred inside. */
} gm_diagonal;

/* [x0,x1]×[y0,y1] with nx×ny cells (2 triangles each; ACUTE: nx+1/2 per row pair). */
gm_status gm_mesh_rectangle(double x0, double x1, double y0, double y1, size_t nx, size_t ny,
                            gm_diagonal pattern, gm_mesh **out, gm_error *err);

typedef enum {
  GM_BOX_KUHN = 0, /* 6 tetrahedra per cube around its (0,0,0)-(1,1,1) diagonal (Freudenthal) */
  GM_BOX_FIVE = 1  /* 5 tetrahedra per cube, mirrored in alternate cubes */
} gm_box_pattern;

gm_status gm_mesh_box(const double lo[3], const double hi[3], size_t nx, size_t ny, size_t nz,
                      gm_box_pattern pattern, gm_mesh **out, gm_error *err);
/* Annulus r_in < r < r_out: n_radial + 1 rings of n_angular vertices, consecutive rings
 * staggered by half an angular step (2 n_radial n_angular triangles, acute when the radial step
 * exceeds half the angular step). */
/* Body-centred cubic tetrahedra on the nx×ny×nz cube grid of the box (each count >= 2): the
 * octahedron around every interior face, cut in four around the segment joining the two cube
 * centres (4 tetrahedra per interior face). Well-centred (positive circumcentric stars) when the
 * cells are cubes. fill = 0: the domain is the box minus the square pyramids on its boundary
 * faces; fill != 0: those pyramids are added, four tetrahedra each around the segment from the
 * cube centre to the square's centre (a new vertex), and the mesh is the box; it is then not
 * well-centred along the box's edges and corners (Whitney star). */
gm_status gm_mesh_bcc(const double lo[3], const double hi[3], size_t nx, size_t ny, size_t nz,
                      int fill, gm_mesh **out, gm_error *err);
gm_status gm_mesh_annulus(double r_in, double r_out, size_t n_radial, size_t n_angular,
                          gm_mesh **out, gm_error *err);
/* Sphere of the given radius: an icosahedron whose triangles are split into 4, `subdivisions`
 * times, new vertices projected onto the sphere (20·4^s triangles, outward orientation). */
gm_status gm_mesh_icosphere(double radius, size_t subdivisions, gm_mesh **out, gm_error *err);
/* Torus with radii R > r in R^3: n_major (even) rings of n_minor vertices around the tube,
 * staggered by half a step (2 n_major n_minor triangles). */
gm_status gm_mesh_torus(double R, double r, size_t n_major, size_t n_minor, gm_mesh **out,
                        gm_error *err);


/* ---- red refinement (src/mesh/refine.c) ---------------------------------------------------- */

/* One level of regular (red) refinement of a triangle (dim 2, N 2 or 3) or tetrahedral (dim 3)
 * mesh: triangles into 4 by their edge midpoints, tetrahedra into 8 by Bey's rule (Computing 55
 * (1995) 355–378), see src/mesh/refine.c for the vertex orders. Fine vertex v < V is coarse vertex
 * v, fine vertex V + e the midpoint of coarse edge e (complex numbering); the 2^n children of
 * coarse cell c are fine cells 2^n c .. 2^n c + 2^n − 1, with c's tag. The fine mesh's size is
 * estimated first: above max_bytes (0: the machine's physical memory) it is GM_ENOMEM naming
 * the bytes, before anything is allocated. Errors of gm_complex_create for a bad input (e.g.
 * non-manifold); GM_EUNSUPPORTED for dim 1. *fine is owned by the caller. */
gm_status gm_mesh_refine(const gm_mesh *coarse, size_t max_bytes, gm_mesh **fine, gm_error *err);
/* Bytes of the mesh after `levels` refinements (upper bound: the coarse edge and face counts are
 * bounded by the cells' ones, the later levels follow exact recurrences). */
gm_status gm_mesh_refine_estimate(const gm_mesh *coarse, size_t levels, double *bytes,
                                  gm_error *err);

/* ---- files -------------------------------------------------------------------------------- */

/* Read a mesh by extension: .msh (Gmsh ASCII 2.2 or 4.1) or .off. The cells are the highest-
 * dimensional linear simplices in the file (Gmsh points and lower-dimensional elements are
 * skipped, cell_tags get the Gmsh physical tag); nodes no cell uses are dropped; N is the cell
 * dimension raised to cover every non-zero coordinate. Bad files are GM_EINVAL (GM_EDOMAIN for a
 * non-finite coordinate, GM_EIO when the file cannot be read) with a message "FILE: line L:
 * what": truncated sections, wrong counts, node indices out of range or undefined, unknown or
 * non-simplicial element types, binary files. Counts are checked against the file size before
 * any allocation. *out is owned by the caller. */
gm_status gm_mesh_read(const char *path, gm_mesh **out, gm_error *err);
/* The readers load the file into memory, at most GM_MESH_MAX_FILE_BYTES (1 GiB, about 10^7
 * tetrahedra) by default; a larger file, or a stream that goes on past it, is GM_EIO "FILE: ... more than the limit of N bytes". gm_mesh_read_max reads by
 * extension with another limit. A NUL byte is GM_EINVAL at once: mesh files are text. Words are
 * never cut (a word of more than 127 characters is an error) and bytes other than printable ASCII
 * are shown as \xNN in messages. */
#define GM_MESH_MAX_FILE_BYTES ((size_t)1 << 30)
gm_status gm_mesh_read_max(const char *path, size_t max_bytes, gm_mesh **out, gm_error *err);
gm_status gm_mesh_read_msh(const char *path, gm_mesh **out, gm_error *err);
gm_status gm_mesh_read_off(const char *path, gm_mesh **out, gm_error *err);
/* The same parsers on a buffer of `size` bytes (need not be NUL-terminated); messages start
 * with "line L:". */
gm_status gm_mesh_parse_msh(const char *data, size_t size, gm_mesh **out, gm_error *err);
gm_status gm_mesh_parse_off(const char *data, size_t size, gm_mesh **out, gm_error *err);
/* Write a triangle mesh (dim 2, N <= 3) as OFF (cells as given, coordinates %.17g). */
gm_status gm_mesh_write_off(const gm_mesh *mesh, const char *path, gm_error *err);
/* Write any mesh (N <= 3) as Gmsh ASCII 2.2 (physical and elementary tag = the cell tag). */
gm_status gm_mesh_write_msh(const gm_mesh *mesh, const char *path, gm_error *err);

/* A field for gm_vtu_write: n_components = 1 (a cochain: one value per `degree`-simplex) or 3
 * (a vector per simplex, e.g. gm_dec_sharp at vertices); values borrowed. */
typedef struct gm_vtu_field {
  const char *name;   /* no XML special characters */
  size_t degree;      /* 0 = vertices (PointData) .. n = top simplices */
  size_t n_components;
  const double *values;
} gm_vtu_field;

/* Write the complex as a ParaView .vtu file (XML, ASCII): points, top simplices, and the
 * k-simplices of every degree 0 < k < n that carries a field (as VTK lines / triangles); degree
 * 0 fields are PointData, the others CellData over all cells with NaN on cells of another degree,
 * plus an Int32 CellData "degree". */
gm_status gm_vtu_write(const char *path, const gm_complex *cx, size_t n_fields,
                       const gm_vtu_field *fields, gm_error *err);

/* ---- quality report ------------------------------------------------------------------------- */

typedef struct gm_mesh_report {
  size_t dim, N;
  size_t count[GM_DEC_MAX_DIM + 1];          /* k-simplices (only vertices and cells when the
                                                complex could not be built) */
  size_t boundary_count[GM_DEC_MAX_DIM + 1]; /* k-simplices on the boundary */
  long euler_characteristic;
  int betti_known;                           /* gm_complex_betti_numbers succeeded */
  size_t betti[GM_DEC_MAX_DIM + 1];
  size_t non_manifold;     /* (n−1)-faces shared by more than two cells */
  size_t reoriented;       /* cells whose vertex order was flipped to orient consistently */
  size_t degenerate;       /* |σ| <= 1e-12 (longest edge)^n */
  size_t inverted;         /* N == n: negative volume after orientation */
  size_t not_well_centred; /* circumcenter not strictly inside the cell */
  size_t negative_duals[GM_DEC_MAX_DIM + 1]; /* k-simplices with dual volume <= 0 */
  double star_min[GM_DEC_MAX_DIM + 1], star_max[GM_DEC_MAX_DIM + 1]; /* ⋆_k entries */
  double min_volume, max_volume, shortest_edge, longest_edge;
  int complex_ok, geometry_ok;          /* 0: the reason is in the message below */
  char complex_error[GM_ERRMSG_SIZE];   /* e.g. non-manifold, not orientable, index out of range */
  char geometry_error[GM_ERRMSG_SIZE];  /* e.g. a degenerate cell */
  size_t out_of_range;  /* cells whose volume (edge^n) overflows or underflows double precision
                           (coordinates of 1e160 or 1e-160): not in min/max_volume, and no
                           geometry (geometry_error says so). Edges and the degenerate and
                           well-centred tests are computed on each cell scaled to unit size. */
} gm_mesh_report;

/* Fill the report. A mesh that is not a valid complex is not an error here: complex_ok = 0 and
 * complex_error says why (and the counts that need no complex are still filled). GM_ENOMEM only. */
gm_status gm_mesh_quality(const gm_mesh *mesh, gm_mesh_report *report, gm_error *err);

/* ---- Poisson check ------------------------------------------------------------------------ */

typedef struct gm_poisson_report {
  size_t n_vertices, n_unknowns; /* all vertices; interior ones (the unknowns) */
  double h;                      /* longest edge */
  double error_max;              /* max |u_h − u| over the vertices */
  double error_l2;               /* (Σ ⋆_0 (u_h − u)²)^{1/2} */
  double solution_max;           /* max |u| */
  size_t n_cells;                /* of the mesh solved on (after refinement) */
  size_t iterations;             /* CG iterations (multigrid, hypre; 0 for CHOLMOD) */
  double relative_residual;      /* ‖b − A u‖ / ‖b‖ of the interior system */
  double contraction;            /* V-cycle contraction factor, when measured (else 0) */
  int solver;                    /* the gm_poisson_solver that ran (GM_POISSON_AUTO resolved) */
  double setup_s;                /* wall seconds: refinement, complex, geometry, assembly */
  double factor_s;               /* CHOLMOD analyse + factor, the multigrid hierarchy, or
                                    hypre's setup */
  double solve_s;                /* triangular solves, or preconditioned CG */
} gm_poisson_report;

typedef enum {
  GM_POISSON_CHOLMOD = 0,  /* sparse Cholesky of the interior system */
  GM_POISSON_MULTIGRID = 1, /* CG preconditioned by a geometric V-cycle (geomint/multigrid.h) on
                              the hierarchy input mesh → `levels` red refinements */
  GM_POISSON_HYPRE = 2,     /* CG preconditioned by hypre's BoomerAMG (gm_hypre_boomeramg_pcg) */
  GM_POISSON_AUTO = 3       /* the default: chosen by measurement (docs/dec.md, "Which solver"):
                               multigrid when levels >= 1 (a hierarchy exists); otherwise CHOLMOD
                               below GM_POISSON_HYPRE_MIN_UNKNOWNS interior unknowns, hypre (when
                               built with it) from there on */
} gm_poisson_solver;

/* The size from which GM_POISSON_AUTO prefers hypre to CHOLMOD on an unrefined mesh: measured
 * wall time of `geomint mesh poisson` (MPI start-up included) in docs/dec.md, "Which solver". */
#define GM_POISSON_HYPRE_MIN_UNKNOWNS 10000

typedef struct gm_poisson_options {
  gm_poisson_solver solver; /* default GM_POISSON_AUTO */
  size_t levels;            /* red refinements of the input before solving (default 0; the
                               multigrid needs >= 1: the input is its coarsest level) */
  double rtol;              /* multigrid, hypre: relative residual (default 1e-10) */
  size_t pre_smooth, post_smooth; /* multigrid: Gauss–Seidel sweeps (default 2, 2) */
  size_t max_iterations;    /* multigrid: CG iterations (0: 200) */
  int measure_contraction;  /* multigrid: also measure the V-cycle's contraction factor */
  size_t max_bytes;         /* refinement memory limit (0: physical memory) */
} gm_poisson_options;

gm_poisson_options gm_poisson_defaults(void);

/* Solve −Δu = f with the manufactured solution u(x) = Π_i sin(π (x_i − lo_i)/L_i + 1/4) (lo, L:
 * the bounding box), f = u Σ_i (π/L_i)², Dirichlet data u on the boundary, with the DEC
 * Laplacian d_0ᵀ ⋆_1 d_0 u = ⋆_0 f on the interior vertices (seed 001 §3.9) and CHOLMOD.
 * Needs a mesh filling its own space (dim == N) with a boundary. u_out (n_vertices values) may
 * be NULL. Errors: those of the complex and geometry; GM_EUNSUPPORTED for a surface mesh;
 * GM_ESINGULAR when the stiffness matrix is not positive definite (message says why). */
gm_status gm_mesh_poisson(const gm_mesh *mesh, gm_poisson_report *report, double *u_out,
                          gm_error *err);
/* The same check after options->levels red refinements of mesh (gm_mesh_refine), solved by the
 * chosen solver (options NULL: defaults, GM_POISSON_AUTO). *u_out (may be NULL) receives
 * the vertex values on the refined mesh (report->n_vertices, owned by the caller). Errors as
 * gm_mesh_poisson; GM_ENOMEM naming the bytes when the refined mesh would exceed
 * options->max_bytes; GM_ENOCONV when CG does not reach rtol. */
gm_status gm_mesh_poisson_solve(const gm_mesh *mesh, const gm_poisson_options *options,
                                gm_poisson_report *report, double **u_out, gm_error *err);

/* ---- curl–curl check (1-forms) ------------------------------------------------------------- */

typedef enum {
  GM_CURLCURL_CHOLMOD = 0, /* sparse Cholesky of the interior edge system */
  GM_CURLCURL_HYPRE = 1    /* CG preconditioned by hypre's AMS (gm_hypre_ams_pcg) */
} gm_curlcurl_solver;

typedef struct gm_curlcurl_report {
  size_t n_edges, n_unknowns, n_cells; /* all edges; interior ones; tetrahedra */
  double h;                            /* longest edge */
  double error_max;                    /* max over edges |e_h − ∫_e E·dl| / |e| */
  double solution_max;                 /* max over edges |∫_e E·dl| / |e| */
  size_t iterations;                   /* CG iterations (hypre; 0 for CHOLMOD) */
  double relative_residual;            /* ‖b − A e‖ / ‖b‖ of the interior system */
  double factor_s, solve_s;            /* CHOLMOD factor / solve, or hypre setup / CG (s) */
} gm_curlcurl_report;

/* The 1-form problem curl curl E + E = f on a tetrahedral mesh in R³ (bounding box lo + [0, L])
 * with the tangential trace of E given on the boundary (E × n = 0 on the box's faces):
 * manufactured E = (sin πy' sin πz', sin πz' sin πx', sin πx' sin πy'), x' = (x − lo)/L, so
 * div E = 0, curl curl E = −ΔE and f_c = (1 + π²/L_a² + π²/L_b²) E_c (a, b the other axes).
 * Discretised as (d_1ᵀ ⋆_2 d_1 + ⋆_1) e = ⋆_1 f_e on the interior edges (e, f_e: edge integrals
 * of E and f by 3-point Gauss), the boundary edges keeping the exact integrals of E. rtol: the
 * hypre solver's relative residual; e_out (n_edges values, may be NULL): the solution.
 * Errors: GM_EUNSUPPORTED unless the mesh is tetrahedral in R³; GM_ESINGULAR for a
 * non-positive ⋆_1 on an interior edge; those of the complex, geometry and solver. */
gm_status gm_mesh_curlcurl_solve(const gm_mesh *mesh, gm_curlcurl_solver solver, double rtol,
                                 gm_curlcurl_report *report, double **e_out, gm_error *err);

#ifdef __cplusplus
}
#endif
#endif
