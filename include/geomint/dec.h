/* geomint dec: discrete exterior calculus on simplicial complexes.
 *
 * A gm_complex is the topology (all faces, signed incidence matrices, boundary) of a pure
 * simplicial complex of dimension n = 1, 2 or 3 whose vertices are points of R^N (N >= n; surfaces
 * in R^3 are n = 2, N = 3). A gm_geometry adds the metric: circumcenters, primal and (signed) dual
 * volumes, diagonal Hodge stars and Whitney mass matrices. Operators act on cochains: a k-cochain
 * is an array of gm_complex_count(cx, k) doubles, its value on each k-simplex.
 *
 * Conventions (sources cited in src/dec/ next to each formula):
 * - k-simplices for k < n are stored with ascending vertex indices, which is also their
 *   orientation; k-simplices are numbered in lexicographic order of their vertex tuples. Top
 *   simplices keep the order given by the user but carry an orientation sign (+1: the ascending
 *   tuple is positively oriented) made consistent across the complex.
 * - d_k: C^k -> C^{k+1} is the coboundary, d_k = ∂_{k+1}ᵀ (seed 001 §3.4), so d_{k+1} d_k = 0
 *   exactly (integer entries ±1).
 * - ⋆_k is diagonal with entries |⋆σ|/|σ| (|σ^0| = 1, |⋆σ^n| = 1), seed 001 §3.5; the star on
 *   dual forms is (−1)^{k(n−k)} ⋆_k^{-1}, so that ⋆⋆ = (−1)^{k(n−k)}.
 * - The codifferential is the adjoint of d in the discrete inner product (α, β) = αᵀ ⋆_k β
 *   (seed 000 eq. 3.8 without boundary term): δ_{k+1} = ⋆_k^{-1} d_kᵀ ⋆_{k+1}.
 * Pointer parameters are borrowed unless a comment says otherwise. */
#ifndef GEOMINT_DEC_H
#define GEOMINT_DEC_H

#include <stddef.h>

#include "geomint/core.h"
#include "geomint/sparse.h"

#ifdef __cplusplus
extern "C" {
#endif

#define GM_DEC_MAX_DIM 3
#define GM_DEC_MAX_EMBED 8

/* ---- complexes -------------------------------------------------------------------------- */

typedef struct gm_complex gm_complex;

/* Build the complex of n_top top simplices of dimension dim (1..3), each given by dim+1 vertex
 * indices in top[], over n_vertices points of R^N (coordinates row-major in x, N values per
 * vertex; dim <= N <= GM_DEC_MAX_EMBED; N <= 3 uses the stable cross-product formulas). Coordinates
 * and simplices are copied. Orientation is made consistent (each connected component keeps the
 * orientation of its first simplex, or, when N == dim, the one of positive total volume).
 * Errors (GM_EINVAL unless noted, message names the offending simplex or vertex): an index out
 * of range, a repeated vertex in a simplex, a duplicated simplex, a vertex used by no simplex, a
 * non-manifold (n−1)-face shared by more than two top simplices, a non-orientable complex;
 * GM_EDOMAIN for non-finite coordinates. */
gm_status gm_complex_create(size_t N, size_t n_vertices, const double *x, size_t dim,
                            size_t n_top, const size_t *top, gm_complex **out, gm_error *err);
void gm_complex_free(gm_complex *cx);

size_t gm_complex_dim(const gm_complex *cx);
size_t gm_complex_embedding_dim(const gm_complex *cx);
/* Number of k-simplices (0 for k > dim). */
size_t gm_complex_count(const gm_complex *cx, size_t k);
/* The k-simplices: (k+1) vertex indices each, ascending. */
const size_t *gm_complex_simplices(const gm_complex *cx, size_t k);
/* For k >= 1: the k+1 (k−1)-faces of each k-simplex; face i is opposite vertex i. */
const size_t *gm_complex_faces(const gm_complex *cx, size_t k);
/* Orientation of each top simplex relative to its ascending vertex tuple (+1 or −1). */
const signed char *gm_complex_orientation(const gm_complex *cx);
/* Top simplices whose orientation differs from the vertex order the user gave. */
size_t gm_complex_reoriented_count(const gm_complex *cx);
/* Vertex coordinates (N per vertex). */
const double *gm_complex_coordinates(const gm_complex *cx);
/* The coboundary d_k (count(k+1) × count(k)), k = 0..dim−1; NULL otherwise. */
const gm_csr *gm_complex_d(const gm_complex *cx, size_t k);
/* The boundary matrix ∂_k = d_{k−1}ᵀ (count(k−1) × count(k)), k = 1..dim, owned by the caller. */
gm_status gm_complex_boundary_matrix(const gm_complex *cx, size_t k, gm_csr **out);
/* The two top simplices that share each (dim−1)-face (second = SIZE_MAX on the boundary). */
const size_t *gm_complex_face_cofaces(const gm_complex *cx);
/* Boundary subcomplex: mask[i] = 1 when k-simplex i lies in the boundary; and the count. */
const unsigned char *gm_complex_boundary_mask(const gm_complex *cx, size_t k);
size_t gm_complex_boundary_count(const gm_complex *cx, size_t k);
/* Index of the k-simplex with the given k+1 vertices (any order), or SIZE_MAX. */
size_t gm_complex_find(const gm_complex *cx, size_t k, const size_t *vertices);
/* χ = Σ_k (−1)^k count(k). */
long gm_complex_euler_characteristic(const gm_complex *cx);
/* Betti numbers b_0..b_dim (betti[k] = 0 above dim) from connected components, closed components,
 * boundary components and χ. For dim = 3 this uses Alexander duality and needs a complex embedded
 * in R^3 with a boundary on every component (GM_EUNSUPPORTED otherwise). Cross-checked against
 * the dimension of the harmonic spaces by the tests. */
gm_status gm_complex_betti_numbers(const gm_complex *cx, size_t betti[GM_DEC_MAX_DIM + 1]);

/* ---- geometry and Hodge stars ----------------------------------------------------------- */

typedef enum {
  GM_DUAL_CIRCUMCENTRIC = 0, /* dual vertices at circumcenters: signed dual volumes */
  GM_DUAL_BARYCENTRIC = 1    /* dual vertices at barycenters: positive, not orthogonal */
} gm_dual_kind;

typedef struct gm_geometry_options {
  gm_dual_kind dual;         /* default GM_DUAL_CIRCUMCENTRIC */
  double degenerate_tol;     /* a top simplex is degenerate when |σ| <= tol * (longest edge)^n
                                (default 1e-12) */
  int allow_inverted;        /* non-zero: inverted simplices (N == n, volume of the wrong sign
                                after orientation) are accepted and counted, not an error */
} gm_geometry_options;

gm_geometry_options gm_geometry_defaults(void);

typedef struct gm_geometry gm_geometry;

/* Compute circumcenters, volumes, dual volumes and Hodge stars of cx (borrowed: it must outlive
 * the geometry); options copied (NULL for defaults). Errors: GM_EINVAL for a degenerate or
 * inverted top simplex (the message names it and its volume). Negative dual volumes (simplices
 * that are not well-centred) are not an error: see gm_geometry_negative_duals. */
gm_status gm_geometry_create(const gm_complex *cx, const gm_geometry_options *options,
                             gm_geometry **out, gm_error *err);
void gm_geometry_free(gm_geometry *g);
const gm_complex *gm_geometry_complex(const gm_geometry *g);
/* Circumcenters (barycenters for the barycentric dual) of the k-simplices, N values each. */
const double *gm_geometry_centers(const gm_geometry *g, size_t k);
/* |σ| of each k-simplex (1 for vertices). */
const double *gm_geometry_primal_volumes(const gm_geometry *g, size_t k);
/* Signed |⋆σ| of each k-simplex, restricted to the complex (seed 000 §3.3.2); 1 for top. */
const double *gm_geometry_dual_volumes(const gm_geometry *g, size_t k);
/* Dual volume of each boundary k-simplex inside the boundary complex ∂K (dimension n−1−k),
 * 0 for interior simplices; k = 0..n−1. */
const double *gm_geometry_boundary_dual_volumes(const gm_geometry *g, size_t k);
/* Diagonal of ⋆_k: |⋆σ|/|σ|. */
const double *gm_geometry_hodge_star(const gm_geometry *g, size_t k);
/* Number of k-simplices with dual volume <= 0; number of inverted top simplices. */
size_t gm_geometry_negative_duals(const gm_geometry *g, size_t k);
size_t gm_geometry_inverted_count(const gm_geometry *g);
/* Local k-faces of top simplex `top`: the subsets of k+1 of its (ascending) vertices in
 * lexicographic order of their positions, e.g. edges of a tetrahedron (01)(02)(03)(12)(13)(23),
 * faces of a tetrahedron (012)(013)(023)(123). indices gets their C(n+1, k+1) global indices. */
gm_status gm_complex_local_faces(const gm_complex *cx, size_t top, size_t k, size_t *indices);
/* Signed volumes |⋆σ ∩ T| of the dual cells of the local k-faces of top simplex T inside T, in
 * the order of gm_complex_local_faces. */
gm_status gm_geometry_dual_pieces(const gm_geometry *g, size_t top, size_t k, double *pieces);
/* ⋆_k as a diagonal CSR matrix, or its inverse (GM_EDOMAIN when an entry is zero). */
gm_status gm_geometry_hodge_star_matrix(const gm_geometry *g, size_t k, int inverse,
                                        gm_csr **out);
/* Entry i of the star on dual (n−k)-forms: (−1)^{k(n−k)} / ⋆_k[i], so that ⋆⋆ = (−1)^{k(n−k)}. */
double gm_geometry_dual_hodge_star(const gm_geometry *g, size_t k, size_t i);
/* Galerkin Hodge star: the Whitney mass matrix M_k[σ,τ] = ∫ φ_σ · φ_τ (Bossavit 1988). */
gm_status gm_geometry_whitney_mass(const gm_geometry *g, size_t k, gm_csr **out);

/* ---- operators --------------------------------------------------------------------------- */

/* δ_k: C^k -> C^{k−1} (k = 1..n), δ_k = ⋆_{k−1}^{-1} d_{k−1}ᵀ ⋆_k: the adjoint of d_{k−1} in the
 * inner products (α, β)_k = αᵀ ⋆_k β (seed 001 §3.6 gives δ = (−1)^{n(k+1)+1} ⋆ d ⋆ on smooth
 * forms; with the dual derivative (−1)^k d_{k−1}ᵀ of Hirani 2003 §3.6 the signs cancel to this
 * matrix). GM_EDOMAIN when ⋆_{k−1} has a zero entry. */
gm_status gm_dec_codifferential(const gm_geometry *g, size_t k, gm_csr **out, gm_error *err);
/* Hodge–de Rham Laplacian Δ_k = d_{k−1} δ_k + δ_{k+1} d_k on k-cochains (Laplace–Beltrami for
 * k = 0: Δ_0 = δ_1 d_0, which is −∇² in the continuum limit, seed 001 §3.9). */
gm_status gm_dec_laplacian(const gm_geometry *g, size_t k, gm_csr **out, gm_error *err);
/* The symmetric form ⋆_k Δ_k = d_kᵀ ⋆_{k+1} d_k + ⋆_k d_{k−1} ⋆_{k−1}^{-1} d_{k−1}ᵀ ⋆_k. */
gm_status gm_dec_stiffness(const gm_geometry *g, size_t k, gm_csr **out, gm_error *err);
/* Divergence of 1-forms: div = −δ_1 (seed 001 §3.8): vertex values. */
gm_status gm_dec_divergence(const gm_geometry *g, gm_csr **out, gm_error *err);

/* ---- curvature (triangle meshes) --------------------------------------------------------- */

/* Angle deficit at every vertex (seed 000 §4.3.1): 2π − Σ angles at interior vertices, π − Σ
 * angles at boundary vertices (the turning angle of the boundary), so that Σ = 2πχ (discrete
 * Gauss–Bonnet). deficit: n_vertices values. Needs dim == 2. */
gm_status gm_dec_angle_deficit(const gm_complex *cx, double *deficit);
/* Levi-Civita holonomy around interior vertex v (seed 000 §4.3.2, seed 001 §1F): a tangent vector
 * is carried once around the triangles of v, crossing each edge by the rotation about the edge
 * that maps one triangle's normal to the next (identity on the edge), counterclockwise with
 * respect to the orientation. *angle receives the rotation angle in (−π, π]: the angle deficit
 * modulo 2π. Cost: one pass over the triangles. GM_EINVAL for a boundary vertex. */
gm_status gm_dec_holonomy(const gm_complex *cx, size_t v, double *angle);


/* ---- Hodge decomposition ------------------------------------------------------------------ */

/* α = dβ + δγ + h on k-cochains, orthogonal in (·,·) = ·ᵀ ⋆_k · (Desbrun, Hirani, Leok, Marsden,
 * "Discrete exterior calculus", 2005; seed 004 §2.5): dβ is the ⋆_k-orthogonal projection onto im d_{k−1}, found from
 * d_{k−1}ᵀ ⋆_k d_{k−1} β = d_{k−1}ᵀ ⋆_k α; δγ = ⋆_k^{-1} d_kᵀ η with d_k ⋆_k^{-1} d_kᵀ η = d_k α;
 * h is the rest. Both systems are positive semi-definite (their kernels are the closed (k−1)-
 * cochains and the dual-closed cochains); they are solved by iterated Tikhonov regularization
 * (x ← x + (A + εD)^{-1}(b − A x), D = diag A, ε = 1e-10) with one CHOLMOD factorization each,
 * which converges to a solution of the consistent singular system; the kernel part never matters
 * because d and d_kᵀ annihilate it. Needs ⋆_k > 0 (a diagonal star that is a metric). The object
 * holds the factorizations and work arrays: apply allocates nothing. */
typedef struct gm_hodge_decomposition gm_hodge_decomposition;

gm_status gm_hodge_decomposition_create(const gm_geometry *g, size_t k,
                                        gm_hodge_decomposition **out, gm_error *err);
void gm_hodge_decomposition_free(gm_hodge_decomposition *hd);
/* Split alpha (count(k) values) into exact, coexact and harmonic parts (each count(k) values,
 * any of them may be NULL). beta (count(k−1)) optionally receives a potential with dβ = exact. */
gm_status gm_hodge_decomposition_apply(gm_hodge_decomposition *hd, const double *alpha,
                                       double *exact, double *coexact, double *harmonic);
const char *gm_hodge_decomposition_errmsg(const gm_hodge_decomposition *hd);
/* A ⋆_k-orthonormal basis of the harmonic k-cochains: *count = b_k (gm_complex_betti_numbers),
 * *basis = count × count(k) values (owned by the caller, free()), computed as the harmonic parts
 * of deterministic pseudo-random cochains, orthonormalized twice by Gram–Schmidt. */
gm_status gm_dec_harmonic_basis(const gm_geometry *g, size_t k, size_t *count, double **basis,
                                gm_error *err);

#ifdef __cplusplus
}
#endif
#endif
