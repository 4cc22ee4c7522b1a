/* Private declarations of the dec module; never installed. */
#ifndef GM_DEC_INTERNAL_H
#define GM_DEC_INTERNAL_H

#include "core/internal.h"
#include "geomint/dec.h"

/* OpenMP pragmas that vanish (without an unknown-pragma warning) when OpenMP is not enabled. Every
 * parallel loop in dec writes disjoint slots or reduces integers, so results do not depend on the
 * number of threads. */
#ifdef _OPENMP
#define GM_OMP(x) _Pragma(#x)
#else
#define GM_OMP(x)
#endif
/* Loops over fewer items than this stay serial (thread start-up would dominate). */
#define GM_OMP_MIN 20000

struct gm_complex {
  size_t n, N, n_vertices;
  double *x;
  size_t count[GM_DEC_MAX_DIM + 1];
  size_t *simplices[GM_DEC_MAX_DIM + 1]; /* sorted tuples; simplices[0] = 0..n_vertices-1 */
  size_t *faces[GM_DEC_MAX_DIM + 1];     /* faces[k], k >= 1: (k+1) per k-simplex */
  signed char *orient;                   /* per top simplex */
  size_t n_reoriented;
  gm_csr *d[GM_DEC_MAX_DIM];
  size_t *cofaces; /* 2 per (n−1)-face */
  unsigned char *coface_local; /* 2 per (n−1)-face: its local index in each coface */
  int faces_problem;           /* an (n−1)-face with more than two cofaces or a duplicate */
  unsigned char *boundary[GM_DEC_MAX_DIM + 1];
  size_t n_boundary[GM_DEC_MAX_DIM + 1];
};

struct gm_geometry {
  const gm_complex *cx;
  gm_geometry_options opt;
  double *centers[GM_DEC_MAX_DIM + 1];
  double *primal[GM_DEC_MAX_DIM + 1];
  double *dual[GM_DEC_MAX_DIM + 1];
  double *bdual[GM_DEC_MAX_DIM + 1];
  double *star[GM_DEC_MAX_DIM + 1];
  unsigned char *bsign[GM_DEC_MAX_DIM + 1]; /* signs of the barycentric coordinates of each
                                               circumcenter: 2 bits per vertex (1 +, 2 −, 0 zero) */
  size_t negative[GM_DEC_MAX_DIM + 1];
  size_t inverted;
};

/* Local geometry of one simplex with m+1 <= 4 vertices p (N coordinates each, N <= 3 uses the
 * stable cross-product formulas). */
#define GM_LOCAL_MAX 4
/* Signed dual pieces |⋆s ∩ S| for every vertex subset s of the simplex S = [p_0..p_m]
 * (bitmask index; entry 0 unused): circumcentric (heights) or barycentric (Gram volumes). */
void gm_local_dual_pieces(size_t N, size_t m, const double *p, gm_dual_kind kind, double *pieces);
/* Circumcenter c and barycentric coordinates (m+1 values) of [p_0..p_m]; returns the m-volume. */
double gm_local_circumcenter(size_t N, size_t m, const double *p, double *c, double *bary);
/* m-volume of [p_0..p_m] (unsigned). */
double gm_local_volume(size_t N, size_t m, const double *p);
/* Gradients of the barycentric coordinates (m+1 vectors of N values) of [p_0..p_m]. */
int gm_local_barycentric_gradients(size_t N, size_t m, const double *p, double *grad);
/* Gather the coordinates of k+1 vertices of cx into p. */
void gm_gather_points(const gm_complex *cx, size_t k, const size_t *vertices, double *p);
/* Index of the local face (bitmask over the top's vertices) within gm_geometry_dual_pieces'
 * ordering, and the number of faces of each size. */
size_t gm_binomial(size_t n, size_t k);
/* Global index of the face of simplex s (dimension d >= 1, or any d when mask has one bit) spanned
 * by the vertex positions in mask (bitmask over the d+1 ascending vertices of s). */
size_t gm_local_face(const gm_complex *cx, size_t d, size_t s, unsigned mask);
/* Orientation sign of simplex i of dimension k: +1 for k < n, orient[i] for k == n. */
int gm_simplex_sign(const gm_complex *cx, size_t k, size_t i);

/* The clipping transfer of top forms between tetrahedral meshes in R³ (transfer_clip3.c), for
 * gm_dec_transfer with n = N = 3, k = 3. */
struct gm_transfer_report;
gm_status dec_transfer_tets(const gm_complex *from, const gm_complex *to, gm_csr **out,
                            struct gm_transfer_report *report, gm_error *err);

#endif
