/* geomint methods: the registry of integration methods. A method is a static const row of a
 * table (DESIGN §4): its name, family, order, stages, coefficients, flags and reference. */
#ifndef GEOMINT_METHODS_H
#define GEOMINT_METHODS_H

#include <stddef.h>

#include "geomint/core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum gm_method_family {
  GM_FAMILY_EXPLICIT_RK = 1, /* explicit Runge–Kutta (Butcher tableau), first-order problems */
  GM_FAMILY_SPLITTING,       /* drift–kick compositions for separable H = T(p) + V(q) */
  GM_FAMILY_IMPLICIT_RK,     /* implicit Runge–Kutta solved by Newton or fixed-point iteration */
  GM_FAMILY_COMPOSITION,     /* Φ_{γ_s h} ∘ … ∘ Φ_{γ_1 h} of a symmetric basic method Φ */
  GM_FAMILY_PARTITIONED_RK,  /* partitioned Runge–Kutta: one tableau for q, one for p */
  GM_FAMILY_MIMETIC,         /* mimetic spectral elements in time (seed 003; geomint/mimetic.h) */
  GM_FAMILY_DISCRETE_GRADIENT, /* y1 = y0 + h S ∇̄H(y0, y1): energy-preserving, Poisson systems */
  GM_FAMILY_VARIATIONAL,     /* discrete Euler–Lagrange equations of a discrete Lagrangian
                                (geomint/variational.h) */
  GM_FAMILY_LIE_GROUP,       /* rigid bodies on SO(3) (× R³): Lie group variational integrators,
                                RKMK, Crouch–Grossman, body-axis splitting (geomint/lie.h) */
  GM_FAMILY_OSCILLATORY,     /* split potentials U + W: IMEX, impulse, trigonometric
                                (geomint/oscillatory.h) */
  GM_FAMILY_NEAR_INTEGRABLE  /* Kepler drifts and interaction kicks of a planetary system
                                H = H_Kepler + ε H_interaction (geomint/celestial.h) */
} gm_method_family;

/* "explicit-rk", "splitting", "implicit-rk", "composition", "partitioned-rk", "mimetic",
 * "discrete-gradient", "variational", "lie-group", "oscillatory", "near-integrable" */
const char *gm_method_family_name(gm_method_family family);

enum {
  GM_SYMPLECTIC = 1u << 0,
  GM_SYMMETRIC = 1u << 1,
  GM_EXPLICIT = 1u << 2,
  GM_IMPLICIT = 1u << 3,
  GM_ENERGY_PRESERVING = 1u << 4,
  GM_FSAL = 1u << 5 /* last force of a step is the first of the next: evaluated once */
};
#define GM_N_METHOD_FLAGS 6
/* Name of the flag with index bit (0 ≤ bit < GM_N_METHOD_FLAGS): "symplectic", ... */
const char *gm_method_flag_name(size_t bit);

/* The coefficients of a method, literal or computed (gm_method_tableau). */
typedef struct gm_tableau {
  size_t n_stages;
  /* Runge–Kutta: a is n_stages×n_stages row-major, b and c have n_stages entries.
   * Splitting: one step is, for i = 0..n_stages-1,
   *   drift  q += a[i]·h·∇T(p),  then  kick  p -= b[i]·h·∇V(q)
   * (c unused; zero coefficients are skipped).
   * Partitioned RK: (a, b, c) for q, (a_bar, b_bar) for p (same c). */
  double *a, *b, *c;
  double *a_bar, *b_bar;
  /* Composition: the fractions γ_1..γ_s of the step given to the basic method. */
  double *gamma;
} gm_tableau;

struct gm_method;
/* Fill a tableau whose arrays are allocated for the method's family and stage count. */
typedef gm_status (*gm_tableau_fn)(const struct gm_method *method, gm_tableau *tableau);

typedef struct gm_method {
  const char *name;           /* lowercase-with-hyphens, unique */
  gm_method_family family;
  int order;                  /* classical order (of the composition: with an order-2 basic) */
  size_t n_stages;            /* stages; splitting: drift–kick pairs; composition: basic steps */
  unsigned flags;             /* GM_SYMPLECTIC | ... */
  unsigned accepts;           /* bitwise or of gm_problem_kind */
  /* Literal coefficients, laid out as in gm_tableau (NULL where unused) ... */
  const double *a, *b, *c;
  const double *gamma;
  /* ... or computed from closed forms when the integrator is created (Gauss nodes). */
  gm_tableau_fn compute;
  const char *basic;          /* composition: the default basic method ("verlet") */
  const char *description;
  const char *reference;      /* paper and equation the coefficients come from */
} gm_method;

/* The method's coefficients (literal ones copied, computed ones computed); free with
 * gm_tableau_free. */
gm_status gm_method_tableau(const gm_method *method, gm_tableau **out);
void gm_tableau_free(gm_tableau *tableau);

size_t gm_method_count(void);
const gm_method *gm_method_at(size_t index);   /* NULL past the end */
/* Row by exact name; NULL when there is none. */
const gm_method *gm_method_find(const char *name);

/* Methods of any stage count s. Gauss–Legendre collocation ("gauss-s": order 2s, symplectic,
 * symmetric; 1 <= s <= 64) and the Lobatto IIIA–IIIB pair ("lobatto-iiia-iiib-s": order 2s − 2,
 * for Hamiltonian problems; 2 <= s <= 64) compute their coefficients from the nodes when an
 * integrator is created, so any s works; the table lists s <= 8 and s <= 4. These make the row
 * for any s (the same as the table's where both exist), *out owned by the caller: free it with
 * gm_method_free after every integrator that uses it. Measured orders beyond the table (Kepler,
 * e = 0.1, one period): see docs/methods.md. gm_method_create parses "gauss-S" and
 * "lobatto-iiia-iiib-S" (GM_ENOTFOUND for other names, GM_EINVAL for S out of range). */
gm_status gm_method_gauss(size_t s, gm_method **out, gm_error *err);
gm_status gm_method_lobatto_iiia_iiib(size_t s, gm_method **out, gm_error *err);
gm_status gm_method_create(const char *name, gm_method **out, gm_error *err);
/* Free a method made by the constructors above (never a table row); NULL is a no-op. */
void gm_method_free(gm_method *method);

#ifdef __cplusplus
}
#endif
#endif
