/* Private declarations of the pde module (DESIGN §2: one concern per file). */
#ifndef GM_PDE_INTERNAL_H
#define GM_PDE_INTERNAL_H

#include "core/internal.h"
#include "geomint/pde.h"

#define GM_PDE_MAX_OBSERVERS 8

/* ---- banded LU with partial pivoting (band.c) ----------------------------------------------- */
/* A periodic ring of blocks is made banded by the interleaved ordering 0, n−1, 1, n−2, 2, ...
 * (neighbours i, i±1 end up at most two positions apart), so the Newton matrix of a box scheme
 * needs no dense N×N solve: bandwidth kl = ku = 3d − 1. Row-major band storage: A(r, c) at
 * ab[r·w + c − r + kl], w = 2kl + ku + 1 (ku + kl above the diagonal after pivoting). */
typedef struct gm_band {
  size_t n, kl, ku, w;
  double *ab; /* owned, n·w */
  int *piv;   /* owned, n */
} gm_band;
gm_status gm_band_init(gm_band *b, size_t n, size_t kl, size_t ku);
void gm_band_release(gm_band *b);
void gm_band_zero(gm_band *b);
void gm_band_add(gm_band *b, size_t r, size_t c, double v); /* |c − r| within the band */
gm_status gm_band_factor(gm_band *b);
void gm_band_solve(const gm_band *b, double *x);
/* pos[i] = position of ring block i in the interleaved order (n entries written). */
void gm_ring_positions(size_t n, size_t *pos);

/* ---- banded LU with a dense border of the last nb columns (band_border.c) ------------------ */
/* For a periodic chain of blocks (block size bs) in natural order: band kl below / ku above the
 * diagonal, plus the wrap-around block in the last nb columns. Factored and forward-eliminated
 * with one right-hand side as the rows arrive (no L kept): reset, add the rows of the next
 * blocks (within the window of nwin rows from column k), eliminate up to a column, ..., back.
 * Storage: a window of nwin LINPACK-width rows, U packed (kl + ku + 1 − (k mod bs) per row),
 * border n·nb row-major. */
typedef struct gm_bband {
  size_t n, kl, ku, nb, bs, w, ublock, nwin;
  size_t k;                 /* next column to eliminate */
  double *win, *u, *border; /* owned */
} gm_bband;
gm_status gm_bband_init(gm_bband *b, size_t n, size_t kl, size_t ku, size_t nb, size_t bs);
void gm_bband_release(gm_bband *b);
size_t gm_bband_bytes(const gm_bband *b); /* storage allocated by init */
void gm_bband_reset(gm_bband *b);
void gm_bband_add(gm_bband *b, size_t r, size_t c, double v); /* row r in the window */
/* eliminate columns k..kend−1 (pivoting rows ≤ their profile, all added), applying to rhs */
gm_status gm_bband_eliminate(gm_bband *b, size_t kend, double *rhs);
void gm_bband_back(const gm_bband *b, double *x); /* after eliminating all n columns */

struct gm_pde_observer {
  size_t every;
  gm_pde_observer_fn fn;
  void *ctx;
};

struct gm_pde {
  gm_pde_grid grid;
  gm_pde_equation eq;
  const gm_pde_scheme *scheme;
  gm_pde_options opt;
  size_t d, n, nu; /* components, points, unknowns n·d */
  size_t steps;
  double Wp[GM_PDE_MAX_DIM * GM_PDE_MAX_DIM], Wm[GM_PDE_MAX_DIM * GM_PDE_MAX_DIM];
  double Kp[GM_PDE_MAX_DIM * GM_PDE_MAX_DIM], Km[GM_PDE_MAX_DIM * GM_PDE_MAX_DIM];
  /* state: s (current), s_prev (one step back), s_new (Newton iterate); all owned, nu each */
  double *s, *s_prev, *s_new, *F, *dx, *hess, *work;
  size_t *pos; /* ring positions (owned) */
  gm_band band;
  /* tangent variations U (k = 0) and V (k = 1): prev, cur, new (owned, nu each) */
  double *tan[2][3];
  double *aux[2]; /* box-sdirk2: stage 1 and the stage-2 base point (owned, nu each) */
  /* gauss-prk (gauss_prk.c): Newton unknowns (Z, Y) per cell, residual, band scratch, and the
   * tangents' (δZ, δY); 6d·n/2 each, owned */
  double *gp_x, *gp_F, *gp_b, *gp_t[2];
  gm_bband gp_band; /* the Newton matrix condensed to the node values Y (gauss_prk.c) */
  double *gp_cell;  /* one cell's A, A⁻¹C, A⁻¹R (owned) */
  double *msres; /* per-cell relative multisymplectic residual of the last step (owned) */
  int ms_valid;
  /* scalar wave schemes: u^{n−1}, u^n, u^{n+1} (owned, n each) */
  double *u_prev, *u, *u_new;
  struct gm_pde_observer observers[GM_PDE_MAX_OBSERVERS];
  size_t n_observers;
  gm_pde_stats stats;
};

static inline int gm_pde_dirichlet(const gm_pde *p) {
  return p->opt.dirichlet_left != 0 || p->opt.dirichlet_right != 0;
}

/* Component a of point i + shift (shift in {−1, 0, 1}) of a state x on the twisted ring:
 * x_{i+n} = x_i + twist. */
static inline double gm_pde_at(const gm_pde *p, const double *x, size_t i, int shift, size_t a) {
  size_t n = p->n, d = p->d;
  if (shift > 0 && i == n - 1) return x[a] + p->grid.twist[a];
  if (shift < 0 && i == 0) return x[(n - 1) * d + a] - p->grid.twist[a];
  size_t j = shift > 0 ? i + 1 : shift < 0 ? i - 1 : i;
  return x[j * d + a];
}
/* The same for the scalar schemes' u arrays (twist of component 0). */
static inline double gm_pde_u_at(const gm_pde *p, const double *u, size_t i, int shift) {
  size_t n = p->n;
  if (shift > 0 && i == n - 1) return u[0] + p->grid.twist[0];
  if (shift < 0 && i == 0) return u[n - 1] - p->grid.twist[0];
  return u[shift > 0 ? i + 1 : shift < 0 ? i - 1 : i];
}

/* Hessian of S at s (d×d), analytic or by central differences of the gradient (symmetrised;
 * counted). work: 2d doubles. */
void gm_pde_hessian(gm_pde *p, const double *s, double *H, double *work);

/* One step of each family (box.c, wave.c). */
gm_status gm_pde_box_step(gm_pde *p, gm_error *err);
gm_status gm_pde_wave_step(gm_pde *p, gm_error *err);
gm_status gm_pde_wave_start(gm_pde *p, gm_error *err); /* u¹ from u⁰, u_t */
void gm_pde_wave_fill_state(gm_pde *p);
double gm_pde_wave_energy(const gm_pde *p);
double gm_pde_wave_momentum(const gm_pde *p);

/* gauss-prk (gauss_prk.c) */
double gm_pde_gauss_point_x(const gm_pde_grid *g, size_t i);
void gm_pde_gauss_init(gm_pde *p);
int gm_pde_gauss_kernel_ok(const gm_pde_equation *eq);
gm_status gm_pde_gauss_step(gm_pde *p, gm_error *err);

/* KdV (kdv.c): Zabusky–Kruskal on the scalar arrays u_prev, u, u_new, its stability bound
 * (the largest stable Δt), and the gauge-free invariants */
gm_status gm_pde_zk_start(gm_pde *p, gm_error *err);
gm_status gm_pde_zk_step(gm_pde *p, gm_error *err);
void gm_pde_zk_fill_state(gm_pde *p);
double gm_pde_zk_bound(const gm_pde_grid *g, double umax);
double gm_pde_kdv_energy(const gm_pde *p);
double gm_pde_kdv_momentum(const gm_pde *p);

#endif
