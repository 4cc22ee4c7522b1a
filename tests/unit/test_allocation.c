/* How much memory an integrator takes when it is created: explicit methods O(n), implicit
 * Runge–Kutta methods with their default (fixed-point) solvers O(s·n); the n×n and (sn)²
 * matrices only with a solver that uses them.
 *
 * The counting allocator: this test is linked with --wrap=malloc,calloc,realloc
 * (tests/CMakeLists.txt), so every allocation of the library (linked statically) passes
 * through the wrappers below, which add the bytes requested while `counting` is set. */
#include <criterion/criterion.h>
#include <stdlib.h>

#include "geomint/geomint.h"

void *__real_malloc(size_t size);
void *__real_calloc(size_t count, size_t size);
void *__real_realloc(void *p, size_t size);

static int counting;
static size_t bytes_requested;

void *__wrap_malloc(size_t size) {
  if (counting) bytes_requested += size;
  return __real_malloc(size);
}
void *__wrap_calloc(size_t count, size_t size) {
  if (counting) bytes_requested += count * size;
  return __real_calloc(count, size);
}
void *__wrap_realloc(void *p, size_t size) {
  if (counting) bytes_requested += size;
  return __real_realloc(p, size);
}

/* 2000 bodies in 3-D: n = 12 000 state components; a dense n×n matrix would be 1.15 GB. */
#define BODIES 2000.0

typedef struct {
  gm_model *model;
  const gm_problem *problem;
  size_t n;
} big_problem;

static big_problem n_body(void) {
  big_problem b = {0};
  cr_assert_eq(gm_model_create("n-body", &b.model), GM_OK);
  cr_assert_eq(gm_model_set(b.model, "n", BODIES), GM_OK);
  cr_assert_eq(gm_model_build(b.model), GM_OK, "%s", gm_model_errmsg(b.model));
  b.problem = gm_model_problem(b.model);
  b.n = gm_model_state_size(b.model);
  cr_assert_eq(b.n, 6 * (size_t)BODIES);
  return b;
}

/* Bytes requested by creating (and, with a solver, configuring) an integrator of `scheme`. */
static size_t bytes_to_create(const gm_scheme *scheme, const gm_problem *pb) {
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  bytes_requested = 0;
  counting = 1;
  gm_status st = gm_integrator_create_scheme(scheme, pb, &it, &err);
  counting = 0;
  cr_assert_eq(st, GM_OK, "%s: %s", scheme->method->name, err.message);
  gm_integrator_free(it);
  return bytes_requested;
}

/* Every explicit row (explicit Runge–Kutta, splitting, compositions of Verlet): at most 64
 * state vectors plus 64 KB, where a single n×n matrix would be 12 000 vectors. */
Test(allocation, explicit_rows_take_linear_memory) {
  big_problem b = n_body();
  const size_t bound = 64 * b.n * sizeof(double) + 65536;
  size_t checked = 0;
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (!(m->flags & GM_EXPLICIT) || !(m->accepts & GM_PROBLEM_SEPARABLE)) continue;
    /* rows that need structure a generated n-body problem does not have: a split potential
     * U + W (oscillatory) or a dominant central body (near-integrable) */
    if (m->family == GM_FAMILY_OSCILLATORY || m->family == GM_FAMILY_NEAR_INTEGRABLE) continue;
    const gm_scheme scheme = {m, NULL, GM_SOLVER_DEFAULT, 0};
    size_t bytes = bytes_to_create(&scheme, b.problem);
    cr_expect_leq(bytes, bound, "%s takes %zu bytes for n = %zu (bound %zu)", m->name, bytes,
                  b.n, bound);
    /* the counter sees the library: the driver's own state vectors at least */
    cr_expect_geq(bytes, 5 * b.n * sizeof(double), "%s: only %zu bytes counted", m->name, bytes);
    checked++;
  }
  cr_expect_geq(checked, 20, "only %zu explicit rows", checked);
  gm_model_free(b.model);
}

/* gauss-s with its default solver (fixed-point on positions for this q'' = f(q)): O(s·n);
 * Newton's matrices only when asked for (checked on a smaller system: 20 bodies, sn = 480). */
Test(allocation, implicit_rows_allocate_newton_only_when_asked) {
  big_problem b = n_body();
  const gm_method *gauss4 = gm_method_find("gauss-4");
  const gm_scheme fixed = {gauss4, NULL, GM_SOLVER_DEFAULT, 0};
  size_t bytes = bytes_to_create(&fixed, b.problem);
  cr_expect_leq(bytes, 16 * 4 * b.n * sizeof(double) + 65536, "gauss-4: %zu bytes", bytes);
  gm_model_free(b.model);

  gm_model *small = NULL;
  cr_assert_eq(gm_model_create("n-body", &small), GM_OK);
  cr_assert_eq(gm_model_set(small, "n", 20.0), GM_OK);
  cr_assert_eq(gm_model_build(small), GM_OK);
  const size_t n = gm_model_state_size(small), sn = 4 * n;
  const gm_scheme newton = {gauss4, NULL, GM_SOLVER_NEWTON, 0};
  const gm_scheme simplified = {gauss4, NULL, GM_SOLVER_SIMPLIFIED_NEWTON, 0};
  size_t with_newton = bytes_to_create(&newton, gm_model_problem(small));
  size_t with_simplified = bytes_to_create(&simplified, gm_model_problem(small));
  size_t without = bytes_to_create(&fixed, gm_model_problem(small));
  /* full Newton: the (sn)² matrix; simplified Newton through the eigenvalues of A: two
   * complex n×n factors (s/2 = 2 pairs) and the n×n Jacobian with the Hessian work */
  cr_expect_geq(with_newton, sn * sn * sizeof(double), "newton: %zu bytes", with_newton);
  cr_expect_leq(with_simplified, (2 * 16 + 3 * 8) * n * n + 65536, "simplified: %zu bytes",
                with_simplified);
  cr_expect_lt(with_simplified, sn * sn * sizeof(double) / 2, "simplified: %zu bytes",
               with_simplified);
  cr_expect_lt(without, sn * sn * sizeof(double) / 8, "default: %zu bytes", without);
  gm_model_free(small);
}

/* The DEC fluid solver (DESIGN §5a): a step is back-substitutions and sparse products; after the
 * first step (CHOLMOD sizes its solve workspace on first use) no step allocates. */
Test(allocation, fluid_steps_allocate_nothing) {
  gm_mesh *mesh = NULL;
  gm_fluid_groups *groups = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, 8, 9, GM_DIAGONAL_ACUTE, &mesh, &err), GM_OK);
  cr_assert_eq(gm_fluid_groups_rectangle(mesh, &groups, &err), GM_OK, "%s", err.message);
  const char *names[4] = {"bottom", "right", "top", "left"};
  for (int scheme = 0; scheme < 2; ++scheme) {
    gm_fluid_bc bc[4] = {{0}};
    for (int k = 0; k < 4; ++k) {
      bc[k].group = names[k];
      bc[k].kind = GM_FLUID_WALL;
    }
    if (scheme == GM_FLUID_SEED) bc[2].velocity[0] = 1.0;
    gm_fluid_options o = gm_fluid_defaults();
    o.scheme = (gm_fluid_scheme)scheme;
    o.nu = scheme == GM_FLUID_SEED ? 1.0 : 0.0;
    gm_fluid *f = NULL;
    cr_assert_eq(gm_fluid_create(mesh, groups, 4, bc, &o, &f, &err), GM_OK, "%s", err.message);
    cr_assert_eq(gm_fluid_advance(f, 1), GM_OK, "%s", gm_fluid_errmsg(f));
    bytes_requested = 0;
    counting = 1;
    gm_status st = gm_fluid_advance(f, 5);
    counting = 0;
    cr_assert_eq(st, GM_OK, "%s", gm_fluid_errmsg(f));
    cr_assert_eq(bytes_requested, 0, "scheme %d: a step requested %zu bytes", scheme, bytes_requested);
    gm_fluid_free(f);
  }
  gm_fluid_groups_free(groups);
  gm_mesh_free(mesh);
}
