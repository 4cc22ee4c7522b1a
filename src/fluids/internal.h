/* Private state of the DEC fluid solver (src/fluids/). */
#ifndef GEOMINT_FLUIDS_INTERNAL_H
#define GEOMINT_FLUIDS_INTERNAL_H

#include "geomint/dec.h"
#include "geomint/fluids.h"
#include "geomint/sparse.h"

struct gm_fluid {
  gm_fluid_options opt;
  gm_complex *cx;
  gm_geometry *geo;
  size_t nv, ne, nt;
  const size_t *edge; /* 2 vertices per edge (borrowed from cx) */
  const size_t *tri;  /* 3 vertices per triangle (borrowed from cx) */
  const double *x;    /* coordinates, 2 per vertex (copied into cx, N = 2) */
  double *star0, *star1, *area;
  double *grad; /* ∇λ_k of each triangle: 6 per triangle */
  gm_csr *L;    /* d0ᵀ ⋆1 d0 */
  gm_csr *S;    /* tangential velocity along edges from ψ: U = S ψ (n_e × n_v) */
  /* boundary: ccw boundary edges a→b and their outward flux halves */
  size_t nb;
  size_t *b_tail, *b_head;
  double *b_circ; /* per vertex: ∫ u_t ds over the boundary part of ∂⋆v (walls, inflows) */
  /* stream function: free (unknown) vertices and Dirichlet values */
  size_t n_free;
  size_t *free_of; /* vertex -> index among free vertices, SIZE_MAX for Dirichlet */
  size_t *free_list;
  unsigned char *psi_fixed;
  double *psi_bc; /* Dirichlet ψ (0 on free vertices) */
  gm_sparse_cholesky *m_half, *m_full, *poisson;
  double *c_half, *c_full; /* constant parts of the right-hand sides (free vertices) */
  /* scalar */
  size_t n_wfree;
  size_t *wfree_of, *wfree_list;
  unsigned char *theta_fixed;
  double *theta_bc;
  gm_sparse_cholesky *m_theta;
  double *c_theta;
  /* state and work */
  double *psi, *theta, *gamma, *zeta;
  double *psi_h, *gamma_h, *zeta_h, *gamma_k, *psi_k;
  double *u_edge, *out, *rhs, *rhs_w, *sol;
  double dt_bound, t, h_min;
  size_t step, last_iterations;
  /* domains without boundary (src/fluids/closed.c) */
  int closed;
  size_t sdim;            /* 2: plane, 3: surface in R³; grad has 3·sdim values per triangle */
  size_t n_mesh_vertices; /* the mesh's vertices (nv: the solver's, after periodic identification) */
  size_t *rep;            /* mesh vertex -> solver vertex (NULL: identity) */
  size_t *tri_own;
  size_t *edge_own;       /* quotient edges (f->edge points here when closed, seed scheme) */        /* triangles in solver vertices (f->tri points here when closed) */
  double *xq;             /* coordinates per solver vertex */
  double *normal;         /* unit normal per triangle (surfaces) */
  double *coriolis;       /* f = 2Ω z/|x| per solver vertex (closed domains) */
  double period[2];       /* the periodic translations along x and y (0: none) */
  gm_sparse_cholesky *m_visc;
  char errmsg[GM_ERRMSG_SIZE];
};

/* Γ = L ψ + b on every vertex (the circulation around each dual cell, with the boundary part
 * given by the wall velocity). */
void gm_fluid_circulation_of(const gm_fluid *f, const double *psi, double *gamma);

/* Net convective outflow of the vertex field q from each dual cell with the velocity of psi:
 * − d0ᵀ ⋆1 (q ∧ Sψ) plus the boundary half-edge fluxes (the d i_u dω and −δ(ω∧θ) terms, ×⋆0). */
void gm_fluid_convective_outflow(gm_fluid *f, const double *q, const double *psi, double *out);
/* ∫ φ_v ∇ψ × ∇ζ per vertex (the P1 Jacobian of the midpoint scheme). */
void gm_fluid_jacobian(gm_fluid *f, const double *psi, const double *zeta, double *rate);

/* src/fluids/closed.c: the vertex classes of the periodic pairs among bcs (rep: mesh vertex ->
 * class, increasing along the classes' lowest vertices; *nq classes). */
gm_status gm_fluid_periodic_map(const gm_mesh *mesh, const gm_fluid_groups *groups, size_t n_bcs,
                                const gm_fluid_bc *bcs, size_t **rep, size_t *nq,
                                double period[2], char *msg, size_t msg_size);
/* Every edge on two triangles and every vertex's triangles one fan; else GM_EINVAL with counts. */
gm_status gm_fluid_manifold_check(const gm_complex *cx, char *msg, size_t msg_size);
/* Initial stream functions of src/fluids/flows.c: the double shear layer at a point of
 * [0, 2π]², the Rossby–Haurwitz wave at a point of the unit sphere. */
double gm_fluid_double_shear_psi(const double *x);
double gm_fluid_rossby_haurwitz_psi(const double *x);
/* Everything of the solver on a domain without boundary (takes ownership of rep). */
gm_status gm_fluid_create_closed(gm_fluid *f, size_t *rep, size_t nq, char *msg, size_t msg_size);

#endif
