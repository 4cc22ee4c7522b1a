/* geomint multigrid: cochains across meshes (seed 001 ch. 3, the remeshing / multigrid transfer;
 * notes 001 "Remeshing / multigrid transfer", item P4) and a geometric multigrid for the DEC
 * Laplacians.
 *
 * - Nested complexes: the parent maps of a red refinement (gm_mesh_refine, geomint/mesh.h), the
 *   restriction R (fine → coarse: the seed's coarsening, sums of the fine values with orientation
 *   signs) and the prolongation P (coarse → fine: the Whitney interpolant integrated over the fine
 *   simplices). Both are cochain maps: d R = R d and d P = P d exactly (integer or dyadic entries;
 *   derivation in src/dec/refinement.c), and R P = I.
 * - Unrelated 2-D triangle meshes of one domain: the seed's support-volume transfer
 *   ⟨Tω, τ⟩ = Σ_σ (|V_τ ∩ V_σ| / |V_σ|) ⟨ω, σ⟩ for top forms (V = the triangle) and its dual for
 *   0-forms (V = the vertex's dual cell), by polygon clipping (src/dec/transfer_clip.c).
 * - A V-cycle multigrid on a hierarchy given by prolongation matrices, with Galerkin coarse
 *   operators Pᵀ A P, as a solver or as the preconditioner of CG (src/dec/multigrid.c).
 * Pointer parameters are borrowed unless a comment says otherwise. */
#ifndef GEOMINT_MULTIGRID_H
#define GEOMINT_MULTIGRID_H

#include <stddef.h>

#include "geomint/core.h"
#include "geomint/dec.h"
#include "geomint/sparse.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- nested complexes ------------------------------------------------------------------------ */

typedef struct gm_refinement gm_refinement;

/* Parent maps between coarse and fine = the complexes of a mesh and of gm_mesh_refine of it
 * (both borrowed: they must outlive the object). For every fine k-simplex: its carrier, the
 * smallest coarse simplex containing it (dimension k..n), and when the carrier has dimension k
 * the orientation sign of the fine simplex in it (0 otherwise). The children of a coarse simplex
 * are the fine simplices it carries. Errors: GM_EINVAL when fine is not the red refinement of
 * coarse (the message names the first fine vertex or simplex that does not fit). */
gm_status gm_refinement_create(const gm_complex *coarse, const gm_complex *fine,
                               gm_refinement **out, gm_error *err);
void gm_refinement_free(gm_refinement *r);
const gm_complex *gm_refinement_coarse(const gm_refinement *r);
const gm_complex *gm_refinement_fine(const gm_refinement *r);
/* Per fine k-simplex: dimension of its carrier, its carrier's index, and the sign. */
const unsigned char *gm_refinement_parent_dim(const gm_refinement *r, size_t k);
const size_t *gm_refinement_parent(const gm_refinement *r, size_t k);
const signed char *gm_refinement_parent_sign(const gm_refinement *r, size_t k);

/* Restriction R_k (count_coarse(k) × count_fine(k), entries ±1): ⟨Rω, τ⟩ = Σ_{σ ⊂ τ} ±⟨ω, σ⟩.
 * Totals of top forms are kept exactly; constants and linear 0-forms are kept (injection). */
gm_status gm_refinement_restriction(const gm_refinement *r, size_t k, gm_csr **out,
                                    gm_error *err);
/* Prolongation P_k (count_fine(k) × count_coarse(k)): ⟨Pω, σ⟩ = ∫_σ (Whitney interpolant of ω).
 * k = 0: linear interpolation; k = n: ω_T / 2^n on each child. */
gm_status gm_refinement_prolongation(const gm_refinement *r, size_t k, gm_csr **out,
                                     gm_error *err);

/* The 0-form prolongation (linear interpolation, = gm_refinement_prolongation(r, 0)) of a red
 * refinement (n_fine_vertices = vertices + edges of coarse) straight from the vertex numbering
 * of gm_mesh_refine, without the fine complex or the parent maps of the higher simplices: what multigrid for 0-forms needs. Rows of fine vertices with
 * fine_drop[v] != 0 and columns of coarse vertices with coarse_drop[v] != 0 are left out and
 * the rest renumbered in order (e.g. the boundary masks, for Dirichlet problems; NULL keeps
 * all). GM_EINVAL when the vertex counts do not match a red refinement. */
gm_status gm_refinement_vertex_prolongation(const gm_complex *coarse, size_t n_fine_vertices,
                                            const unsigned char *coarse_drop,
                                            const unsigned char *fine_drop, gm_csr **out,
                                            gm_error *err);

/* How well-centred the cells are: a cell is well-centred when its circumcenter is strictly
 * inside it; the margin is the least barycentric coordinate of a circumcenter (> 0: all
 * well-centred). "children": the fine cells whose parent is well-centred. */
typedef struct gm_well_centredness {
  size_t coarse_cells, coarse_well_centred;
  size_t fine_cells, fine_well_centred;
  size_t children_of_well_centred, children_well_centred;
  double coarse_margin, fine_margin, children_margin;
} gm_well_centredness;

gm_status gm_refinement_well_centredness(const gm_refinement *r, gm_well_centredness *wc);

/* ---- unrelated meshes of one domain: triangles (2-D), tetrahedra (3-D, top forms) ---------- */

typedef struct gm_transfer_report {
  double volume_from, volume_to; /* areas of the two domains (Σ |T|) */
  double volume_overlap;         /* Σ over all pairs of |σ ∩ τ| */
  size_t pairs;                  /* pairs of triangles (k = n) or dual pieces (k = 0) that meet */
} gm_transfer_report;

/* The support-volume transfer of k-cochains from the complex of `from` to that of `to` (both
 * dim = N = 2), k = 2 (top forms) or k = 0, as a count_to(k) × count_from(k) matrix.
 *   k = 2: T[τ, σ] = |τ ∩ σ| / Σ_τ' |τ' ∩ σ|: the fraction of σ's integral that lands in τ (the
 *          seed's formula, with |σ| replaced by the measured sum of its overlaps, equal to it to
 *          round-off when the domains coincide, so the total is kept to round-off).
 *   k = 0: the same on the dual cells V_v (v's Voronoi region within each triangle, which is its
 *          circumcentric dual cell on well-centred meshes), applied to the densities: (Tf)(w) =
 *          Σ_v |V_w ∩ V_v| f(v) / Σ_v |V_w ∩ V_v|: constants are kept exactly, the integral
 *          Σ |V_v| f(v) to round-off.
 * Tetrahedral meshes in R³ (n = N = 3): k = 3 only, T[τ, σ] = |τ ∩ σ| / Σ_τ' |τ' ∩ σ| as for
 * k = 2, the intersections by clipping σ with τ's four half-spaces (src/dec/transfer_clip3.c).
 * Errors: GM_EINVAL when the domains differ: |from|, |to| and their overlap are compared and
 * a difference above 1e-10 relative is refused with the three areas (volumes) in the message;
 * GM_EUNSUPPORTED for other dimensions or degrees. */
gm_status gm_dec_transfer(const gm_complex *from, const gm_complex *to, size_t k, gm_csr **out,
                          gm_transfer_report *report, gm_error *err);

/* ---- pull-back under a simplicial map -------------------------------------------------------- */

/* f* on k-cochains for the simplicial map given by vertex_map (K's vertex v ↦ M's vertex
 * vertex_map[v]): the count_K(k) × count_M(k) matrix with ⟨f*α, σ⟩ = ±⟨α, f(σ)⟩ (the sign of the
 * permutation sorting the image, times top-simplex orientations) and 0 where σ collapses. A
 * cochain map: d f* = f* d exactly. GM_EINVAL when the image of a k-simplex is not a simplex of
 * M (the message names it) or an image vertex is out of range. */
gm_status gm_dec_pullback(const gm_complex *K, const gm_complex *M, const size_t *vertex_map,
                          size_t k, gm_csr **out, gm_error *err);

/* ---- geometric multigrid -------------------------------------------------------------------- */

typedef struct gm_multigrid_options {
  size_t pre_smooth, post_smooth; /* symmetric Gauss–Seidel sweeps: forward before the coarse
                                     correction, backward after (defaults 2, 2) */
  size_t max_iterations;          /* of gm_multigrid_pcg (default 200) */
  double rtol;                    /* ‖b − A x‖ <= rtol ‖b‖ (default 1e-10) */
} gm_multigrid_options;

gm_multigrid_options gm_multigrid_defaults(void);

typedef struct gm_multigrid gm_multigrid;

/* A hierarchy of n_levels = n_prolongations + 1 levels, level 0 the finest with the symmetric
 * positive definite matrix A (borrowed: it must outlive the object; CG's products use it);
 * P[l] (n_l × n_{l+1}, copied) prolongs level l+1 to level l. The coarse operators are Galerkin
 * products A_{l+1} = P[l]ᵀ A_l P[l]; the coarsest level is factored by CHOLMOD. The smoothing
 * levels keep their operators and prolongations with 32-bit columns and float values (the
 * arithmetic is double; src/dec/multigrid.c says why). All work arrays are allocated here.
 * Errors: GM_EINVAL for shapes that do not chain, GM_ESINGULAR when a diagonal entry is not
 * positive or the coarsest matrix is not positive definite, GM_EUNSUPPORTED above 2^32 − 1
 * unknowns. */
gm_status gm_multigrid_create(const gm_csr *A, size_t n_prolongations, const gm_csr *const *P,
                              const gm_multigrid_options *options, gm_multigrid **out,
                              gm_error *err);
void gm_multigrid_free(gm_multigrid *mg);
size_t gm_multigrid_levels(const gm_multigrid *mg);
/* Unknowns and stored entries of level l's operator. */
size_t gm_multigrid_level_size(const gm_multigrid *mg, size_t level, size_t *nnz);
/* One V-cycle for A x = b on the finest level, improving x in place (no allocation). */
void gm_multigrid_vcycle(gm_multigrid *mg, const double *b, double *x);
/* Conjugate gradients preconditioned by one V-cycle from zero (symmetric: Gauss–Seidel forward
 * before, backward after), from the initial guess in x. *iterations and *relres (final
 * ‖b − Ax‖/‖b‖) may be NULL. GM_ENOCONV (message in gm_multigrid_errmsg) when rtol is not
 * reached in max_iterations. */
gm_status gm_multigrid_pcg(gm_multigrid *mg, const double *b, double *x, size_t *iterations,
                           double *relres);
/* Measured contraction factor of the V-cycle as a stationary iteration on A e = 0: the ratio of
 * A-norms ‖e_{c}‖_A / ‖e_{c−1}‖_A averaged geometrically over cycles 3..`cycles` from a
 * deterministic pseudo-random e_0 (the asymptotic rate). */
double gm_multigrid_contraction(gm_multigrid *mg, size_t cycles);
const char *gm_multigrid_errmsg(const gm_multigrid *mg);

/* ---- algebraic multigrid through hypre (optional: Debian libhypre-dev) -------------------- */

/* Conjugate gradients preconditioned by one cycle of hypre's BoomerAMG (classical AMG, HMIS
 * coarsening, extended+i interpolation, l1-Gauss–Seidel smoothing: the settings hypre's manual
 * recommends for 3-D problems) or AMS (the auxiliary-space Maxwell solver of Hiptmair and Xu,
 * SIAM J. Numer. Anal. 45 (2007) 2483–2509; Kolev and Vassilevski, J. Comput. Math. 27 (2009)
 * 604–623), both run on one process (MPI_COMM_SELF; MPI is initialised here when the caller has
 * not). The report gives the setup and solve seconds (thread CPU time: hypre runs on this
 * thread), the CG iterations and the final relative residual ‖b − Ax‖/‖b‖ (recomputed here with
 * gm_csr_matvec, not hypre's own). Built without hypre, every call returns GM_EUNSUPPORTED
 * saying so. */
typedef struct gm_hypre_report {
  size_t iterations;
  double relative_residual;
  double setup_s, solve_s;
} gm_hypre_report;

/* 1 when geomint was built with hypre. */
int gm_hypre_available(void);
/* A x = b for a symmetric positive definite A (a 0-form Laplacian), from the guess in x. */
gm_status gm_hypre_boomeramg_pcg(const gm_csr *A, const double *b, double *x, double rtol,
                                 size_t max_iterations, gm_hypre_report *report, gm_error *err);
/* A x = b for an edge (1-form) system A = d_1ᵀ ⋆_2 d_1 + ⋆_1 (curl–curl plus a positive mass
 * term) in 3-D: G is the discrete gradient d_0 on the same edges (rows = A's unknowns, columns =
 * the vertices whose gradients lie in the space, e.g. interior edges × interior vertices for a
 * Dirichlet problem) and xyz the coordinates of those vertices (3 per column of G). */
gm_status gm_hypre_ams_pcg(const gm_csr *A, const gm_csr *G, const double *xyz, const double *b,
                           double *x, double rtol, size_t max_iterations, gm_hypre_report *report,
                           gm_error *err);

#ifdef __cplusplus
}
#endif
#endif
