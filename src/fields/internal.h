/* Private declarations of the fields module (the Yee solver); never installed. */
#ifndef GM_FIELDS_INTERNAL_H
#define GM_FIELDS_INTERNAL_H

#include <stddef.h>

#include "core/internal.h"
#include "geomint/fields.h"

#define YEE_ERRMSG 256

/* OpenMP pragmas that vanish without OpenMP. Update loops write disjoint slots and reduce
 * nothing, so results are bitwise identical for any thread count. */
#ifdef _OPENMP
#define YEE_OMP(x) _Pragma(#x)
#else
#define YEE_OMP(x)
#endif
/* Loops over fewer locations than this stay serial. */
#define YEE_OMP_MIN 32768

struct gm_yee_materials {
  gm_yee_grid grid;
  size_t n_cells;
  double *epsilon, *mu, *sigma; /* per cell, x fastest */
  char errmsg[YEE_ERRMSG];
  struct yee_geometry *geometry; /* shapes painted, for subpixel smoothing (yee_smoothing.c) */
  /* dispersive media (yee_dispersive.c): per cell the pole set painted there (0: none; NULL
   * until a medium with poles is painted), and the sets: set k (1-based) holds the poles
   * set_poles[set_start[k − 1] .. set_start[k]) */
  unsigned *pole_set;
  size_t n_sets;
  size_t *set_start;  /* n_sets + 1 */
  gm_pole *set_poles;
  unsigned pen;       /* the set later paints give their cells (gm_yee_materials_set_poles) */
};

/* A box of locations of one component: [lo, lo + cnt) per axis, in component index space. */
typedef struct yee_box {
  size_t lo[3], cnt[3];
} yee_box;

/* One CPML auxiliary term (Roden & Gedney 2000; Taflove & Hagness eqs. 7.105–7.106):
 *   ψ ← b ψ + c (src[idx + o1] − src[idx + o0]) / h_d;   target[idx] += w ψ
 * over a slab of target locations. w holds sign × (Δt/ε or Δt/μ of the location). */
typedef struct yee_cpml_term {
  yee_box box;
  int target, src;       /* components */
  long o1, o0;           /* offsets of the difference along the derivative axis */
  double inv_h;          /* 1 / h_d */
  const double *b, *c;   /* per position along d (index + offset of that axis) */
  size_t m[3];           /* 1 on the derivative axis, 0 elsewhere: picks the position */
  size_t n;              /* locations in the slab */
  double *psi;           /* n per field part */
  double *w;             /* n */
  int e_field;           /* 1: an E target (applied after the E update) */
} yee_cpml_term;

typedef struct yee_source {
  size_t n;              /* locations */
  size_t *index;         /* array indices */
  size_t index_min, index_max; /* their range */
  double g;              /* waveform value of the current E half step (one-sweep step) */
  double *coef;          /* per location: soft: −Δt/ε·weight (or −Δt/μ·weight); hard: weight */
  int component;
  int hard;
  gm_waveform wave;
  double time_shift;     /* waveform time = t_n + time_shift */
  /* charge bookkeeping (soft E sources): vertex indices, ρ values, per-edge ±Δt/h factors */
  size_t n_vertices;
  size_t *vertex;        /* 2 per location: array index of the lower and upper vertex */
  double *rho;           /* per vertex slot (2 per location) */
  double *drho;          /* per vertex slot: Δt·weight/h (lower: +, upper: −) times g */
} yee_source;

typedef struct yee_probe {
  int component;
  size_t index;
  size_t n, capacity;
  double *t, *re, *im;
} yee_probe;

typedef struct yee_observer {
  size_t every;
  gm_yee_observer_fn fn;
  void *ctx;
  size_t last_step;      /* step of the last call (SIZE_MAX: never) */
} yee_observer;

/* TF/SF: a 1-D Yee grid along the axis carries the incident wave; the corrections on the box
 * faces add target[index] += coef · aux[aux_index] after each half step. */
typedef struct yee_tfsf_corr {
  size_t n;
  int *comp;
  size_t *target, *aux;
  double *coef;
  double *frac;          /* oblique waves: incident = (1 − frac) aux[j] + frac aux[j + 1];
                            NULL: aux[j] (axis-aligned) */
  int cubic;             /* with frac: the cubic through aux[j − 1 … j + 2] instead */
} yee_tfsf_corr;

typedef struct yee_tfsf {
  gm_waveform wave;
  size_t n_aux;          /* aux E nodes 0..n_aux−1; aux H at the n_aux−1 half nodes between */
  double *e, *h;
  double *ca_e, *cb_e;   /* aux E update: e ← ca e − cb (h_j − h_{j−1}) / h */
  double *ca_h, *cb_h;   /* aux H update: h ← ca h − cb (e_{j+1} − e_j) / h */
  double inv_h;
  size_t drive;          /* node set to amplitude·g(t) */
  yee_tfsf_corr ecorr, hcorr;
} yee_tfsf;

struct gm_yee {
  gm_yee_layout L;
  gm_yee_options opt;
  int n_axes;
  long s[3];             /* strides for differences (0 on absent axes) */
  double dt;
  int n_parts;           /* 1 real, 2 complex (Bloch) */
  int n_threads;
  double *zeros;         /* stands in for components the dimension lacks (read, never written) */
  /* update kernels over a box of one component, and (3-D) one fused kernel per field that
   * updates all three components in one sweep over the box they share; the rest of each
   * component's range is a few face slabs */
  void (*update_e[3])(gm_yee *s, int part, const yee_box *box);
  void (*update_h[3])(gm_yee *s, int part, const yee_box *box);
  void (*fused_e)(gm_yee *s, int part, const yee_box *box);
  void (*fused_h)(gm_yee *s, int part, const yee_box *box);
  /* the same kernels without worksharing: all rows on the calling thread (one-sweep step) */
  void (*update_e1[3])(gm_yee *s, int part, const yee_box *box);
  void (*update_h1[3])(gm_yee *s, int part, const yee_box *box);
  void (*fused_e1)(gm_yee *s, int part, const yee_box *box);
  void (*fused_h1)(gm_yee *s, int part, const yee_box *box);
  yee_box fused_box[2];  /* E, H (cnt 0 when not fused) */
  yee_box rest[GM_YEE_N_COMPONENTS][6];
  size_t n_rest[GM_YEE_N_COMPONENTS];
  int active[GM_YEE_N_COMPONENTS];
  double *f[2][GM_YEE_N_COMPONENTS];
  /* Hodge-star update coefficients: E: cb = Δt/ε_e /(1 + σΔt/2ε), ca = loss factor;
   * H: cb = Δt/μ_f. Arrays when the medium varies, else the scalars. */
  int uniform, lossy;
  double *cb[GM_YEE_N_COMPONENTS], *ca[3];
  double cb0[GM_YEE_N_COMPONENTS], ca0;
  /* per-cell material copies (NULL when uniform) for diagnostics */
  double *eps_cell, *mu_cell;
  double eps0, mu0;
  int smoothed;          /* edge ε from subpixel smoothing: yee_eps_edge reads it from cb, ca */
  struct yee_aniso *aniso; /* off-diagonal ε̃⁻¹ coupling on cut edges (NULL: none) */
  struct yee_dispersive *disp; /* Drude/Lorentz poles on dispersive edges (NULL: none) */
  /* per axis, per position index (extent entries, index + offset): 1/(κ h) at integer (e)
   * and half-integer (h) positions; 0 on absent axes */
  double *inv_e[3], *inv_h[3];
  double *cpml_be[3], *cpml_ce[3], *cpml_bh[3], *cpml_ch[3];
  yee_box upd[GM_YEE_N_COMPONENTS]; /* update range of each component */
  size_t n_cpml;
  yee_cpml_term *cpml;
  double phase_cos[3], phase_sin[3];
  int periodic[3];
  size_t n_sources;
  yee_source *sources;
  size_t n_probes;
  yee_probe *probes;
  size_t n_observers;
  yee_observer *observers;
  size_t n_tfsf;
  yee_tfsf *tfsf;
  size_t step;
  /* MPI subdomains (src/fields/mpi/yee_mpi.c): called after each E half step to copy the
   * ghost planes' tangential E from the neighbouring ranks; NULL for a whole-domain solver */
  void (*exchange_e)(void *ctx, gm_yee *s);
  void *exchange_ctx;
  const struct yee_view *view; /* during yee_create_view only (yee_view.c); NULL after */
  char errmsg[YEE_ERRMSG];
};

/* An MPI subdomain seen from the whole grid (yee_view.c): subpixel smoothing of a block takes
 * its ε̃, 1/μ̃ and off-diagonal couplings from the whole grid's shapes at the global indices, so
 * that every coefficient rounds as in one process. */
typedef struct yee_view {
  const gm_yee_materials *materials; /* the whole grid's, with the shapes painted */
  gm_yee_layout L;                   /* the whole grid's layout */
  gm_yee_options opt;                /* the whole grid's boundaries */
  int periodic[3];
  long offset[3];                    /* global index of local index 0 */
} yee_view;
gm_status yee_create_view(const gm_yee_grid *grid, const gm_yee_materials *materials,
                          const gm_yee_options *options, int cell_coefficients,
                          const yee_view *view, gm_yee **out, gm_error *err);
/* Global index of local location ijk, wrapped into [0, n) on the whole grid's periodic axes
 * (identity without a view). */
void yee_view_index(const gm_yee *s, const long ijk[3], long g[3]);
/* The materials, layout and periodic flags the smoothing reads (the whole grid's with a view). */
const gm_yee_materials *yee_view_materials(const gm_yee *s, const gm_yee_materials *local);
const gm_yee_layout *yee_view_layout(const gm_yee *s);
const int *yee_view_periodic(const gm_yee *s);
/* Would the whole-grid solver let the anisotropic coupling take over E component c at global
 * index g (in its update range, outside CPML layers)? Always 1 without a view. */
int yee_view_eligible(const gm_yee *s, int c, const long g[3]);
/* Cells next to a location along axis a: both neighbours (index-1, index) on a node axis, the
 * one cell on a staggered axis; out-of-range cells dropped or wrapped (periodic). Count in
 * out[0..1] (yee_create.c; the dispersive edges use it too). */
size_t yee_cells_along(const gm_yee_layout *L, const int periodic[3], int a, long idx, int node,
                       long out[2]);

/* gm_yee_create, with per-location Hodge-star coefficients even when the materials are uniform
 * (cell_coefficients != 0; materials must then be non-NULL): an MPI subdomain whose cells
 * happen to be uniform must round as the whole non-uniform domain does. */
gm_status yee_create_with(const gm_yee_grid *grid, const gm_yee_materials *materials,
                          const gm_yee_options *options, int cell_coefficients, gm_yee **out,
                          gm_error *err);

/* Helpers shared by the solver files. */
static inline int yee_is_e(int c) { return c < 3; }
static inline size_t yee_idx(const gm_yee_layout *L, long i, long j, long k) {
  return (size_t)((i + (long)L->offset[0]) * (long)L->stride[0] +
                  (j + (long)L->offset[1]) * (long)L->stride[1] +
                  (k + (long)L->offset[2]) * (long)L->stride[2]);
}
/* Edge ε / σ averaged over the cells around the edge, face 1/μ averaged over the cells on
 * both sides: the diagonal DEC Hodge stars for piecewise-constant media (seed 000 §3.3). */
void yee_edge_average(const gm_yee_layout *L, const int periodic[3], int axis, long i, long j,
                      long k, const double *cell, double *mean);
void yee_face_average_inverse(const gm_yee_layout *L, const int periodic[3], int axis, long i,
                              long j, long k, const double *cell, double *mean_inverse);
void yee_apply_ghosts_e(gm_yee *s);
void yee_apply_ghosts_h(gm_yee *s);
void yee_select_kernels(gm_yee *s);
void yee_update_e(gm_yee *s);
void yee_update_h(gm_yee *s);
gm_status yee_cpml_setup(gm_yee *s, gm_error *err);
/* yee_memory.c: sizes estimated before allocating (bytes in double: no overflow) */
double yee_memory_budget(void);
const char *yee_bytes_text(double bytes, char *out, size_t cap);
double yee_grid_bytes(const gm_yee_grid *grid, int complex_fields);
gm_status yee_memory_check(double bytes, const char *what, gm_error *err);
void yee_cpml_apply(gm_yee *s, int e_field);
void yee_sources_apply(gm_yee *s, int e_field);
void yee_sources_begin_e(gm_yee *s);
void yee_sources_apply_plane(gm_yee *s, size_t lo, size_t n);
int yee_wavefront_eligible(const gm_yee *s);
void yee_step_wavefront(gm_yee *s);
void yee_tfsf_apply(gm_yee *s, int e_field);
void yee_tfsf_free(yee_tfsf *t);
int yee_tfsf_push_corr(yee_tfsf_corr *c, size_t *cap, int comp, size_t target, size_t aux,
                       double coef);
int yee_tfsf_in_box(const gm_yee *s, const size_t lo[3], const size_t hi[3], int c,
                    const long ijk[3]);
#define YEE_TFSF_AUX_PML 60 /* nodes of graded matched loss at the far end of an aux grid */
void yee_tfsf_background(const gm_yee *s, const size_t lo[3], double *eps, double *mu);
int yee_tfsf_aux_grid(yee_tfsf *t, double d, double dt, double eps, double mu);
/* One term of the Yee curl update of component c at ijk: coef × (component comp at the index
   shifted by shift along axis). */
typedef struct yee_curl_term {
  int comp, axis;
  long shift;
  double coef;
} yee_curl_term;
void yee_curl_terms(const gm_yee *s, int c, const long ijk[3], yee_curl_term terms[4]);
int yee_locate(const gm_yee *s, int c, const double x[3], long ijk[3]);
double yee_medium_cb_e(const gm_yee *s, int c, size_t index);
double yee_medium_cb_h(const gm_yee *s, int c, size_t index);
double yee_eps_edge(const gm_yee *s, int c, long i, long j, long k);
double yee_mu_face(const gm_yee *s, int c, long i, long j, long k);
/* Subpixel smoothing (yee_smoothing.c): the materials record the shapes painted into them;
 * the solver asks for the smoothed ε and ⟨σ⟩ of an edge and 1/μ of a face. */
gm_status yee_geometry_record_box(gm_yee_materials *m, const double lo[3], const double hi[3],
                                  const gm_medium *medium);
gm_status yee_geometry_record_sphere(gm_yee_materials *m, const double center[3], double radius,
                                     const gm_medium *medium);
gm_status yee_geometry_record_cylinder(gm_yee_materials *m, const double center[3],
                                       const double unit_axis[3], double radius, double height,
                                       const gm_medium *medium);
void yee_geometry_reset(gm_yee_materials *m);
void yee_geometry_free(gm_yee_materials *m);
int yee_geometry_has_shapes(const gm_yee_materials *m);
int yee_geometry_lossy(const gm_yee_materials *m); /* a shape has σ > 0 */
double yee_geometry_min_em(const gm_yee_materials *m);
void yee_smooth_edge(const gm_yee_materials *m, const gm_yee_layout *L, const int periodic[3],
                     int c, long i, long j, long k, double *epsilon, double *sigma);
/* Row c (an E component) of the smoothed inverse tensor ε̃⁻¹ at edge ijk, its diagonal's
 * inverse ε_aa and ⟨σ⟩. */
void yee_smooth_inverse_row(const gm_yee_materials *m, const gm_yee_layout *L,
                            const int periodic[3], int c, long i, long j, long k, double row[3],
                            double *eps_aa, double *sigma);
/* Entry (a, b) of ε̃⁻¹ for the pixel centred at pos (index units: location = origin + h pos). */
double yee_smooth_offdiag_at(const gm_yee_materials *m, const gm_yee_layout *L,
                             const int periodic[3], const double pos[3], int a, int b);
/* Off-diagonal coupling of the smoothed tensor (yee_aniso.c): set up at create, applied after
 * each E half step (D tracked on the coupled edges), synced when E is set. */
gm_status yee_aniso_setup(gm_yee *s, const gm_yee_materials *m, gm_error *err);
void yee_aniso_apply(gm_yee *s);
void yee_aniso_sync(gm_yee *s);
/* E_saved = E on the coupled edges, after an MPI exchange overwrote some of them (D, the sum of
 * the increments, stays). */
void yee_aniso_resave(gm_yee *s);
/* The coupling's state of part (its D and E_saved, for checkpoints): the member count (0: none). */
size_t yee_aniso_state(const gm_yee *s, int part, double **d, double **esave);
void yee_aniso_free(gm_yee *s);
/* 1/ε̃⁻¹_aa of a coupled edge, or 0 when the edge is not coupled. */
double yee_aniso_eps(const gm_yee *s, int c, size_t q);
void yee_smooth_face(const gm_yee_materials *m, const gm_yee_layout *L, const int periodic[3],
                     int c, long i, long j, long k, double *inv_mu);

/* Dispersive media (yee_dispersive.c). Materials: record a medium's poles before painting
 * (returns the set id to paint, 0 for none; GM_ENOMEM as -1), paint the cell ids. Solver: set
 * up at create from the materials' cell ids; begin (before the E kernels: the pole updates that
 * need only old values), apply (after the E kernels, sources and CPML: E corrected on the
 * dispersive edges), apply_range (the same for edges with array index in [lo, lo + n), for the
 * one-sweep step), sync (after E is set), energy, free. */
long yee_materials_pole_set(gm_yee_materials *m, size_t n_poles, const gm_pole *poles);
gm_status yee_dispersive_setup(gm_yee *s, const gm_yee_materials *m, gm_error *err);
void yee_dispersive_begin(gm_yee *s);
void yee_dispersive_apply(gm_yee *s);
void yee_dispersive_apply_range(gm_yee *s, size_t lo, size_t n);
void yee_dispersive_sync(gm_yee *s);
double yee_dispersive_energy(const gm_yee *s);
int yee_dispersive_has(const gm_yee *s, int c, size_t q);
void yee_dispersive_free(gm_yee *s);
/* Checkpoints: the dispersive state's arrays through fn (E^{m−1}, P^{m−1}, A^m per part) and
 * their total length. */
int yee_dispersive_visit(gm_yee *s, int (*fn)(void *ctx, double *data, size_t n), void *ctx);
size_t yee_dispersive_state_size(const gm_yee *s);
double yee_dual_weight(const gm_yee *s, int c, const long ijk[3]);

#endif
