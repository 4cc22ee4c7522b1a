/* Private declarations of the oscillatory family (issue 12): the scheme behind each row, and
 * the fast quadratic part in the eigenbasis of the mass-weighted Ω (built once at create). */
#ifndef GM_METHODS_OSCILLATORY_H
#define GM_METHODS_OSCILLATORY_H

#include "geomint/oscillatory.h"
#include "methods/internal.h"

typedef enum {
  GM_OSC_IMEX = 1,     /* kick U – implicit midpoint on T + W – kick U (seed 000 §2.2.1) */
  GM_OSC_IMPULSE,      /* kick U – n Verlet substeps on T + W – kick U (GNI VIII.4) */
  GM_OSC_MOLLIFIED,    /* impulse with U(A q), A = φ(hΩ) the averaging (GNI VIII.4) */
  GM_OSC_TRIG,         /* GNI XIII (2.7)–(2.8) with the filters (ψ, φ) */
  GM_OSC_VTI,          /* variational trigonometric, vector case, exact filters (§2.3.2) */
  GM_OSC_VTI_SCALAR    /* variational trigonometric, scalar case, free Φ (§2.3.1) */
} gm_osc_kind;

/* The scheme of a row: kept beside the rows (oscillatory_table.c), same index. */
typedef struct {
  gm_osc_kind kind;
  gm_filter_fn phi, psi; /* TRIG: the filter pair; MOLLIFIED: phi is the averaging; VTI_SCALAR:
                            phi is the default Φ */
  size_t substeps;       /* IMPULSE, MOLLIFIED: default number of substeps */
  int needs_quadratic;   /* the scheme needs W = ½ qᵀΩ²q */
} gm_osc_scheme;

extern const gm_osc_scheme gm_oscillatory_schemes[];

/* W = ½ qᵀΩ²q with kinetic energy ½ pᵀM⁻¹p, seen in the coordinates that diagonalize it:
 * x = M^{1/2} q, K = M^{−1/2} Ω² M^{−1/2} = Q diag(ν²) Qᵀ, modal z = Qᵀx, w = Qᵀ M^{−1/2} p. */
typedef struct {
  size_t d;
  int quadratic;          /* a fast quadratic part exists */
  double *msqrt;          /* √m_i (all 1 without a mass) */
  double *nu;             /* eigenfrequencies ν_k ≥ 0 */
  double *basis;          /* Q, d×d row-major (column k = eigenvector k); NULL: identity */
  double *omega2;         /* Ω²: d×d, or d entries when diagonal (omega2_diagonal) */
  int omega2_diagonal;
  double *tmp;            /* d values */
} gm_osc_fast;

/* Build from the problem's split (validated first); errors name the problem. */
gm_status gm_osc_fast_create(const gm_problem *pb, gm_osc_fast *fast, char *errmsg, size_t cap);
void gm_osc_fast_release(gm_osc_fast *fast);
/* z = Qᵀ M^{1/2} q;  w = Qᵀ M^{−1/2} p (also the modal image of a force −∇U) */
void gm_osc_to_modal_position(const gm_osc_fast *f, const double *q, double *z);
void gm_osc_to_modal_momentum(const gm_osc_fast *f, const double *p, double *w);
/* q = M^{−1/2} Q z;  p = M^{1/2} Q w */
void gm_osc_from_modal_position(const gm_osc_fast *f, const double *z, double *q);
void gm_osc_from_modal_momentum(const gm_osc_fast *f, const double *w, double *p);
/* out = Ω² q */
void gm_osc_omega2_apply(const gm_osc_fast *f, const double *q, double *out);

#endif
