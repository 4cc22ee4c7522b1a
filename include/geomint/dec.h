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
/* The same with a weight per top simplex (cell_weight[T], borrowed; NULL: 1), e.g. ε_T for
 * M_1^ε[σ,τ] = Σ_T ε_T ∫_T φ_σ · φ_τ (materials constant per cell). */
gm_status gm_geometry_whitney_mass_weighted(const gm_geometry *g, size_t k,
                                            const double *cell_weight, gm_csr **out);

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

/* ---- flat, sharp, wedge, interior product, Lie derivative (seed 001 §3.7–3.8) ----------- */

/* Flat of a dual vector field (one vector of N values per top simplex, at its circumcenter) to a
 * primal 1-cochain (seed 001 §3.7, Hirani 2003 "DPP-flat"):
 *   ⟨X♭, e⟩ = Σ_{T ≻ e} (|⋆e ∩ T| / |⋆e|) X(T)·e⃗,
 * e⃗ the edge vector (head − tail). The weights sum to 1, so constant fields are exact. Where
 * |⋆e| vanishes (a zero or tiny dual edge: |⋆e| <= 1e-12 Σ|⋆e ∩ T|) the weights fall back to
 * 1/(number of cofaces). alpha: count(1) values. */
gm_status gm_dec_flat(const gm_geometry *g, const double *X, double *alpha);
/* Sharp of a primal 1-cochain to a vector at every primal vertex (seed 001 §3.7 corrected as
 * in Hirani 2003 "PP-sharp"): α♯(v) = Σ_{T ∋ v} w_T Σ_{u ∈ T, u ≠ v} ⟨α, [v,u]⟩ ∇λ_u^T, where
 * ∇λ_u^T is the gradient of the barycentric coordinate of u in T (tangent to T) and
 * w_T = |⋆v ∩ T| / |⋆v| (the seed's "|σ^n|" denominator and "normal n̂" are garbled: with these
 * weights, which sum to 1, the de Rham map of a constant 1-form is sharpened to its vector
 * exactly). Zero |⋆v| falls back to volume weights |T| / Σ|T|. X: N values per vertex. */
gm_status gm_dec_sharp(const gm_geometry *g, const double *alpha, double *X);

/* Primal–primal wedge of a k-cochain and an l-cochain (k + l <= n), the natural (barycentric)
 * variant (ii) of seed 001 §3.8 (Castrillón-López; the antisymmetrized cup product):
 *   ⟨α∧β, [v_0..v_{k+l}]⟩ = 1/(k+l+1)! Σ_{τ ∈ S_{k+l+1}} sign(τ) ⟨α,[v_τ0..v_τk]⟩⟨β,[v_τk..v_τ(k+l)]⟩.
 * It is anticommutative (α∧β = (−1)^{kl} β∧α) and satisfies the Leibniz rule
 * d(α∧β) = dα∧β + (−1)^k α∧dβ exactly, because the antisymmetrization commutes with d and the
 * cup product satisfies Leibniz. out: count(k+l) values (must not alias the inputs). */
gm_status gm_dec_wedge(const gm_complex *cx, size_t k, const double *alpha, size_t l,
                       const double *beta, double *out);
/* The metric-weighted variant (i) of seed 001 §3.8 (Hirani 2003 Def. 7.1.1): the factor
 * 1/(k+l+1) is replaced by |σ ∩ ⋆v_τ(k)| / |σ|, the circumcentric Voronoi fraction of σ at
 * the shared vertex, with prefactor 1/(k+l)!. Anticommutative; Leibniz holds only when all
 * those fractions equal 1/(k+l+1) (tests show it fails on generic triangles). */
gm_status gm_dec_wedge_circumcentric(const gm_geometry *g, size_t k, const double *alpha,
                                     size_t l, const double *beta, double *out);

/* Interior product i_X: C^k -> C^{k−1} (k = 1..n) of a vector field X given at the vertices (N
 * values per vertex, interpolated linearly): the contraction of the Whitney interpolant of α
 * (gm_dec_whitney_interpolate) with X, integrated over each (k−1)-simplex σ (exactly: the
 * integrand is quadratic), averaged over the top simplices T ≻ σ with weights |T| / Σ|T|
 * (the Whitney interpolant's normal components jump across faces). This is the first-order
 * term of the extrusion definition of seed 001 §3.8: ⟨α, E_X^t(σ)⟩ = t ⟨i_X α, σ⟩ + O(t²).
 * Exact (to round-off) for constant forms and linear X. out: count(k−1) values. */
gm_status gm_dec_interior_product(const gm_geometry *g, size_t k, const double *X,
                                  const double *alpha, double *out, gm_error *err);

typedef enum {
  GM_LIE_ALGEBRAIC = 0, /* the flow definition: ⟨L_X α, σ⟩ = d/dt ⟨α̃, φ_t(σ)⟩ at t = 0, with α̃ the
                           Whitney interpolant and φ_t(σ) the simplex whose vertices moved to
                           v + t X(v); averaged over T ≻ σ with weights |T| (seed 001 §3.8) */
  GM_LIE_CARTAN = 1     /* Cartan's formula L_X = i_X d + d i_X with gm_dec_interior_product */
} gm_lie_method;

/* Lie derivative L_X: C^k -> C^k (k = 0..n). The two methods agree exactly on 0-forms and on
 * top forms of uniform density. On 1-forms only Cartan's formula is consistent: on a structured
 * triangle mesh its error per unit edge length falls 8.7e-4 -> 2.2e-4 from h = 1/10 to 1/20,
 * while the flow derivative stays at 0.39 (it takes the endpoint values of i_X α̃ from the two
 * cofaces of the edge only; see tests/unit/test_dec_whitney.c). Use GM_LIE_CARTAN. */
gm_status gm_dec_lie_derivative(const gm_geometry *g, size_t k, const double *X,
                                const double *alpha, gm_lie_method method, double *out,
                                gm_error *err);

/* ---- de Rham map and Whitney interpolation -------------------------------------------------- */

/* A k-form field on R^N: *value = ω(x)(u_1, .., u_k), u = k vectors of N values (unused for
 * k = 0: then *value = f(x)). Return 0 on success, non-zero to stop with GM_ECALLBACK. */
typedef int (*gm_form_fn)(void *ctx, const double *x, const double *u, double *value);

/* Quadrature on the reference k-simplex (k = 0..3) exact for polynomials of degree <= degree
 * (any degree), by collapsed coordinates (Duffy / Stroud conical product) with Gauss–Legendre
 * points: m = ⌊(degree + k)/2⌋ + 1 points per direction, m^k in all. bary receives k+1
 * barycentric coordinates per point, weights sum to 1 (∫_σ f ≈ |σ| Σ w_q f(x_q)). With bary ==
 * NULL only *n_points is set (to size the arrays). */
gm_status gm_simplex_quadrature(size_t k, size_t degree, size_t *n_points, double *bary,
                                double *weights);

/* de Rham map: ⟨R ω, σ⟩ = ∫_σ ω over every k-simplex σ (with its orientation), by
 * gm_simplex_quadrature of the given degree. out: count(k) values. */
gm_status gm_dec_de_rham(const gm_complex *cx, size_t k, gm_form_fn form, void *ctx,
                         size_t degree, double *out, gm_error *err);

/* Whitney interpolation (Whitney 1957): the k-form Σ_σ ⟨α,σ⟩ φ_σ at the point of top simplex
 * `top` with barycentric coordinates bary (n+1 values, in the order of the ascending vertices
 * gm_complex_simplices(cx, n) + top·(n+1)), where in T
 * φ_[i_0..i_k] = k! Σ_j (−1)^j λ_{i_j} dλ_{i_0}∧..(omit j)..∧dλ_{i_k}. components receives the
 * C(N, k) values ω(e_{i_1}, .., e_{i_k}), i_1 < .. < i_k in lexicographic order (k = 0: the
 * value; k = 1: the vector). R∘W = identity and d∘W = W∘d (tested). */
gm_status gm_dec_whitney_interpolate(const gm_complex *cx, size_t k, const double *alpha,
                                     size_t top, const double *bary, double *components);

/* ---- Poincaré lemma: cone operator (seed 001 §3.11) ------------------------------------------ */

/* Homotopy operators H_k: C^k -> C^{k−1} (k = 1..n; count(k−1) × count(k) CSR matrices with
 * integer entries, owned by the caller; H[0] = NULL) with H_{k+1} d_k + d_{k−1} H_k = I on
 * k-cochains for k >= 1 and H_1 d_0 f = f − f(apex). Built from the chain homotopy p = Hᵀ,
 * p∂ + ∂p = I, of a sequence of elementary collapses of the complex down to the vertex *apex:
 * for each collapsed pair (σ, τ), σ a free face of τ with incidence ε, p(τ) = 0 and
 * p(σ) = ε(τ − p(∂τ − εσ)) (seed 001 §3.11, generalized star-shaped complexes; on a cone over
 * w this reduces to p(σ) = [w, σ]). If dα = 0 (k >= 1), β = H_k α solves dβ = α.
 * Errors: GM_EUNSUPPORTED when the greedy collapse gets stuck (the complex is not contractible,
 * e.g. an annulus, seed 001 Ex. 3.18; the message gives the number of simplices left).
 * Cost: the chains p(σ) can be long (nnz grows faster than linearly): meant for moderate
 * meshes. */
gm_status gm_dec_cone_operators(const gm_complex *cx, gm_csr *H[GM_DEC_MAX_DIM + 1],
                                size_t *apex, gm_error *err);

/* ---- integration by parts with a boundary term (seed 000 §3.3.3, eq. 3.8) --------------------- */

/* The codifferential on the dual complex restricted to K (seed 000 §3.3.2): the dual boundary of
 * the cell ⋆σ of a boundary k-simplex σ includes the boundary dual cell ⋆_∂σ ⊂ ∂K, on which the
 * dual form ⋆β takes the given value flux[σ] = ∫_{⋆_∂σ} ⋆β (boundary data; ⋆_∂σ oriented as
 * part of ∂(⋆σ), i.e. outward: for k = 0 and β = df, the outward flux ∫ ∂f/∂n over the part of
 * ∂K nearest to σ). Then δ̃_{k+1} β = ⋆_k^{-1} (d_kᵀ ⋆_{k+1} β − flux) on k-cochains (flux
 * entries of interior simplices are ignored) and
 *   (d α, β)_{k+1} = (α, δ̃ β)_k + ⟨α ∧ ⋆β, ∂K⟩,  ⟨α ∧ ⋆β, ∂K⟩ = Σ_{σ ⊂ ∂K} ⟨α,σ⟩ flux[σ]
 * (seed 000 eq. 3.8), where (a, b)_k = aᵀ ⋆_k b. Unlike gm_dec_codifferential (flux = 0),
 * δ̃ stays consistent at boundary simplices. out: count(k) values; k = 0..n−1. */
gm_status gm_dec_codifferential_boundary(const gm_geometry *g, size_t k, const double *beta,
                                         const double *flux, double *out, gm_error *err);
/* ⟨α ∧ ⋆β, ∂K⟩ = Σ_{k-simplices σ ⊂ ∂K} α[σ] flux[σ] (the primal–dual pairing on ∂K). */
double gm_dec_boundary_pairing(const gm_complex *cx, size_t k, const double *alpha,
                               const double *flux);

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

/* ---- discrete Levi-Civita connection of tetrahedral meshes (seed 001 §4, notes §1F; seed 000
 * §4.2.2) --------------------------------------------------------------------------------------
 * For dim == 3 and any N >= 3 (N == 4: a piecewise-flat mesh of a curved 3-manifold, e.g. on S³).
 * Each tet T gets an orthonormal frame: Gram–Schmidt of v1 − v0, v2 − v0, v3 − v0 (ascending
 * vertices) in R^N, the third axis multiplied by the orientation sign of T, so every frame has
 * the complex's orientation. The connection is an SO(3)-valued dual 1-form: on each interior
 * triangle f with cofaces (T0, T1) (gm_complex_face_cofaces), the rotation R_f = F₁ F₀ᵀ that maps
 * T0's frame coordinates to T1's by gluing f isometrically (F_i: the frame of f's ascending
 * vertices (e1 along the first edge, e2 in f, e3 = e1 × e2) in T_i's coordinates); R_f maps the
 * normal of f to itself, i.e. n0 ↦ n1 with the identity on f's plane, the seed's definition
 * (notes §1F). transport: 9 values (row-major) per triangle, the identity on boundary triangles.
 * GM_EINVAL unless dim == 3; GM_EDOMAIN for a degenerate tet. */
gm_status gm_dec_levi_civita_3d(const gm_complex *cx, double *transport);
/* Curvature on the dual faces: for every edge e, the holonomy of the transport around the dual
 * cycle of e (the ring of tets about e, starting at the lowest-numbered tet containing e and
 * turning counterclockwise about e's direction v_a → v_b, a < b, in that tet's frame): a
 * rotation about e by *angle in (−π, π] (9 values per edge in holonomy, the angle per edge in
 * angle; either may be NULL). deficit (may be NULL) gets 2π − Σ dihedral angles about interior
 * edges and π − Σ about boundary edges; angle and holonomy are 0 and I on boundary edges. The
 * discrete Gauss–Bonnet statement tested is angle = deficit (mod 2π): 0 to round-off on a flat
 * mesh of R³, the deficit on a cone singularity or a mesh of S³. Allocates the edge-to-tet map. */
gm_status gm_dec_curvature_3d(const gm_complex *cx, const double *transport, double *holonomy,
                              double *angle, double *deficit, gm_error *err);


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
 * any of them may be NULL). The potentials of the exact and coexact parts are not returned. */
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
