/* Private state of the mesh Maxwell solvers (leapfrog and AVI); never installed. */
#ifndef GM_FIELDS_MESH_MAXWELL_H
#define GM_FIELDS_MESH_MAXWELL_H

#include <stddef.h>

#include "geomint/fields.h"

typedef struct mm_event mm_event;

typedef struct mm_current {
  size_t n;
  size_t *edges;  /* owned */
  double *w;      /* owned */
  gm_waveform wave;
} mm_current;

typedef struct mm_probe {
  gm_yee_component c;
  size_t top;      /* cell holding the point */
  double bary[4];  /* barycentric coordinates in the cell's ascending vertex order */
  size_t cap, n;
  double *t, *v;   /* owned */
  double a_prev[3], t_prev; /* AVI, E probes: the interpolated A = −∫E dt at the last sample */
} mm_probe;

typedef struct mm_observer {
  size_t every;
  gm_mesh_maxwell_observer_fn fn;
  void *ctx;
} mm_observer;

struct gm_mesh_maxwell {
  const gm_geometry *g; /* borrowed */
  const gm_complex *cx; /* borrowed */
  size_t n, nv, ne, nf, nt;
  gm_mesh_maxwell_options opt;
  const gm_csr *d0, *d1, *d2; /* borrowed from cx; d2 NULL in 2-D */
  gm_csr *d1t;                /* owned: d1ᵀ (edges × faces) */
  gm_csr *curl_h;             /* owned, diagonal star only: d1ᵀ ⋆_ν with the rows of PEC edges
                                 zeroed, so Ampère is one gather pass over B (no H pass, no
                                 mask branch) */
  double *eps_star;  /* ⋆_ε per edge */
  double *inv_eps;   /* 1/⋆_ε on interior edges, 0 on boundary edges (the PEC mask) */
  double *nu_star;   /* ⋆_ν per face */
  const unsigned char *bnd_e, *bnd_v;
  double *E, *D, *B, *rho;
  double *work_f;    /* nf scratch (H, synchronised B) */
  double *work_e;    /* ne scratch */
  double *work_v;    /* nv scratch (Gauss) */
  double *mu_cell;   /* μ per top simplex (probes of H) */
  /* Whitney star (GM_MESH_STAR_WHITNEY): M_1 restricted to the interior edges, factorized */
  gm_csr *M1;                 /* owned: ε M_1 on interior edges (n_int × n_int) */
  gm_csr *M1_full;            /* owned: ε M_1 on all edges (energy of E, D = M_1 E) */
  gm_csr *M2;                 /* owned: M_2 / μ (nf × nf) */
  gm_sparse_cholesky *chol;   /* owned */
  size_t *interior;           /* owned: interior edge list */
  size_t n_int;
  double *tmp_i;              /* n_int scratch */
  double *work_f2;            /* nf scratch */
  double dt, cfl;
  double *face_limit;
  size_t step;
  double t;
  int started;
  mm_current *cur; size_t n_cur;
  mm_probe *probe; size_t n_probe;
  mm_observer *obs; size_t n_obs;
  size_t face_updates, edge_updates;
  /* AVI (seed 000 Fig. 3.6 with the fixes of notes A12) */
  double *A;        /* −∫E dt since t_0 per edge, brought up to tau_e */
  double *tau_e;    /* time each edge's A was last brought up to date */
  double *tau_f;    /* last update time of each face */
  double *B0;       /* B at t_0: B_σ(t) = B0_σ + (d₁ A(t))_σ */
  /* currents under the AVI, per edge (CSR over the edges, rebuilt by add_current): the sources
     j_src[j_start[e] .. j_start[e+1]) with weights j_w; j_tau: when e's current impulse was
     last applied */
  size_t *j_start, *j_src;
  double *j_w, *j_tau;
  size_t *j_edges, n_j_edges; /* the edges with a current, ascending */
  double *face_dt;  /* per-face step */
  /* groups: faces with bitwise equal steps; the faces of group g are
     group_face[group_start[g] .. group_start[g+1]) in ascending order */
  size_t n_groups;
  size_t *group_start, *group_face;
  double *group_dt;
  size_t *k_g;      /* events done per group */
  struct mm_event { double t; size_t g; } *heap; /* binary min-heap of (next time, group),
                                                     keys inline for locality; next time of
                                                     a group = (k_g + 1) group_dt */
  size_t heap_n;
  double sample_dt, next_sample;
  size_t n_samples;
  char errmsg[GM_ERRMSG_SIZE];
};

/* Helpers shared by the files of the solver. */
/* B: the fields' B at t (AVI: synchronised); AVI: s->work_e holds the synchronised A at t. */
gm_status mm_probe_record(gm_mesh_maxwell *s, double t, const double *B);
/* AVI: the per-edge CSR of the first n_cur currents (j_start, j_src, j_w; j_tau = 0);
 * GM_ENOMEM leaves the previous one. */
gm_status mm_avi_currents_build(gm_mesh_maxwell *s, size_t n_cur);
/* AVI: A synchronised to time t on every edge (A_e − E_e (t − τ_e)) into out (ne values). */
void mm_avi_sync_a(const gm_mesh_maxwell *s, double t, double *out);
gm_status mm_observe(gm_mesh_maxwell *s, size_t counter);
void mm_heap_build(gm_mesh_maxwell *s);
gm_status mm_groups_build(gm_mesh_maxwell *s); /* allocates the groups and the heap */
/* H = ⋆_ν B (nf values); E = ⋆_ε⁻¹ D on interior edges, 0 on PEC edges (ne values). */
void mm_apply_nu(const gm_mesh_maxwell *s, const double *B, double *H);
void mm_solve_eps(const gm_mesh_maxwell *s, const double *D, double *E);

#endif
