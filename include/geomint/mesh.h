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
gm_status gm_mesh_annulus(double r_in, double r_out, size_t n_radial, size_t n_angular,
                          gm_mesh **out, gm_error *err);
/* Sphere of the given radius: an icosahedron whose triangles are split into 4, `subdivisions`
 * times, new vertices projected onto the sphere (20·4^s triangles, outward orientation). */
gm_status gm_mesh_icosphere(double radius, size_t subdivisions, gm_mesh **out, gm_error *err);
/* Torus with radii R > r in R^3: n_major (even) rings of n_minor vertices around the tube,
 * staggered by half a step (2 n_major n_minor triangles). */
gm_status gm_mesh_torus(double R, double r, size_t n_major, size_t n_minor, gm_mesh **out,
                        gm_error *err);


/* ---- Poisson check ------------------------------------------------------------------------ */

typedef struct gm_poisson_report {
  size_t n_vertices, n_unknowns; /* all vertices; interior ones (the unknowns) */
  double h;                      /* longest edge */
  double error_max;              /* max |u_h − u| over the vertices */
  double error_l2;               /* (Σ ⋆_0 (u_h − u)²)^{1/2} */
  double solution_max;           /* max |u| */
} gm_poisson_report;

/* Solve −Δu = f with the manufactured solution u(x) = Π_i sin(π (x_i − lo_i)/L_i + 1/4) (lo, L:
 * the bounding box), f = u Σ_i (π/L_i)², Dirichlet data u on the boundary, with the DEC
 * Laplacian d_0ᵀ ⋆_1 d_0 u = ⋆_0 f on the interior vertices (seed 001 §3.9) and CHOLMOD.
 * Needs a mesh filling its own space (dim == N) with a boundary. u_out (n_vertices values) may
 * be NULL. Errors: those of the complex and geometry; GM_EUNSUPPORTED for a surface mesh;
 * GM_ESINGULAR when the stiffness matrix is not positive definite (message says why). */
gm_status gm_mesh_poisson(const gm_mesh *mesh, gm_poisson_report *report, double *u_out,
                          gm_error *err);

#ifdef __cplusplus
}
#endif
#endif
