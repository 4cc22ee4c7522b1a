/* Private declarations of the methods module: the tables and the steppers of each family. */
#ifndef GM_METHODS_INTERNAL_H
#define GM_METHODS_INTERNAL_H

#include "ode/internal.h"

/* Method tables, one per family (src/methods/..._table.c). */
extern const gm_method gm_explicit_rk_methods[];
extern const size_t gm_n_explicit_rk_methods;
extern const gm_method gm_splitting_methods[];
extern const size_t gm_n_splitting_methods;
extern const gm_method gm_implicit_rk_methods[];
extern const size_t gm_n_implicit_rk_methods;
extern const gm_method gm_composition_methods[];
extern const size_t gm_n_composition_methods;

/* Computed coefficients (collocation.c). */
gm_status gm_gauss_tableau(const gm_method *m, gm_tableau *t);
gm_status gm_lobatto_iiia_iiib_tableau(const gm_method *m, gm_tableau *t);
extern const gm_method gm_partitioned_rk_methods[];
extern const size_t gm_n_partitioned_rk_methods;
/* Mimetic and discrete-gradient rows and steppers (mimetic*.c, discrete_gradient*.c; their
 * private declarations are in methods/energy.h). */
extern const gm_method gm_mimetic_methods[];
extern const size_t gm_n_mimetic_methods;
extern const gm_method gm_discrete_gradient_methods[];
extern const size_t gm_n_discrete_gradient_methods;
extern const gm_stepper gm_mimetic_stepper;
extern const gm_stepper gm_discrete_gradient_stepper;
/* Variational rows and steppers (variational*.c; engine in methods/variational_internal.h). */
extern const gm_method gm_variational_methods[];
extern const size_t gm_n_variational_methods;
extern const gm_stepper gm_variational_stepper;
extern const gm_stepper gm_sem_stepper;
gm_status gm_vi_gauss_tableau(const gm_method *m, gm_tableau *t);
gm_status gm_vi_lobatto_tableau(const gm_method *m, gm_tableau *t);
gm_status gm_vi_alpha_tableau(const gm_method *m, gm_tableau *t);
/* Oscillatory rows and their stepper (oscillatory*.c; private parts in methods/oscillatory.h). */
extern const gm_method gm_oscillatory_methods[];
extern const size_t gm_n_oscillatory_methods;
extern const gm_stepper gm_oscillatory_stepper;

/* Lie group rows and their stepper for rigid bodies (lie_group*.c). */
extern const gm_method gm_lie_group_methods[];
extern const size_t gm_n_lie_group_methods;
extern const gm_stepper gm_lie_group_stepper;

/* Near-integrable rows and their stepper (src/celestial/near_integrable*.c); the SABA_n and
 * SBAB_n coefficients of splitting_table.c, which they share. */
extern const gm_method gm_near_integrable_methods[];
extern const size_t gm_n_near_integrable_methods;
extern const gm_stepper gm_near_integrable_stepper;
gm_status gm_saba_tableau(const gm_method *m, gm_tableau *t);
gm_status gm_sbab_tableau(const gm_method *m, gm_tableau *t);

/* Shared by the implicit steppers (solve_support.c). */
/* A failed solve of the stage equations: count it (convergence failures only) and prefix the
 * reason already in it->errmsg with the method, t and h. Returns status. */
gm_status gm_stage_solve_failed(gm_integrator *it, gm_status status, double t, double h);
/* Starting values z_i = Σ_j e_ij z_prev_j (s blocks of m values): the previous step's
 * polynomial extrapolated to the new stages. */
void gm_stage_extrapolate(size_t s, size_t m, const double *e, const double *z_prev, double *z);

/* Is ∇T the identity (the built-in T = ½|p|², src/problems/kinetic.c)? Then a stepper may use p
 * itself where it would call kinetic_gradient (the same numbers, no call and no copy). */
int gm_kinetic_is_identity(const gm_problem *problem);

/* The eigen-decomposition A⁻¹ = V Λ V⁻¹ of a Runge–Kutta matrix, one block per real eigenvalue
 * and per conjugate pair (stage_transform.c): simplified Newton on s/2 complex systems of size n
 * instead of one of size sn. lambda[b]: eigenvalue of A⁻¹ of block b (Im > 0 for a pair);
 * v: s × n_blocks, column b the eigenvector (doubled for a pair, so that ΔZ_i = Re Σ_b v_ib ΔW_b);
 * vinv: n_blocks × s, the matching rows of V⁻¹; ainv: A⁻¹ (s×s). All owned. */
typedef struct gm_stage_transform {
  size_t s, n_blocks, n_real, n_pairs;
  _Complex double *lambda, *v, *vinv;
  double *ainv;
} gm_stage_transform;
/* GM_ESINGULAR when A is singular (Lobatto IIIA), GM_ENOCONV when dgeev fails. */
gm_status gm_stage_transform_create(size_t s, const double *a, gm_stage_transform **out);
void gm_stage_transform_free(gm_stage_transform *t);
/* Complex LU with partial pivoting of the row-major n×n a, in place, U's diagonal inverted
 * (GM_ESINGULAR on a zero pivot), and the solve of a x = b with it (b overwritten). Neither allocates. */
gm_status gm_complex_lu_factor(size_t n, _Complex double *a, int *piv);
void gm_complex_lu_solve(size_t n, const _Complex double *lu, const int *piv, _Complex double *b);

/* Steppers, one per family. */
extern const gm_stepper gm_explicit_rk_stepper;
extern const gm_stepper gm_splitting_stepper;
extern const gm_stepper gm_implicit_rk_stepper;
extern const gm_stepper gm_composition_stepper;

#endif
