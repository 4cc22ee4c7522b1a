/* Shared fixtures of the fluid tests: the unit square (or a rectangle) meshed by acute rows, its
 * four sides as boundary groups, and the Couette / Poiseuille conditions of seed 004 (B15). */
#ifndef GM_TESTS_FLUIDS_UTIL_H
#define GM_TESTS_FLUIDS_UTIL_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/geomint.h"

typedef struct fl_fixture {
  gm_mesh *mesh;
  gm_fluid_groups *groups;
} fl_fixture;

/* [0,lx]×[0,ly] with about n cells along x and equilateral-ish acute rows. */
static inline fl_fixture fl_rect(double lx, double ly, size_t n) {
  fl_fixture f = {0};
  gm_error err = {{0}};
  size_t ny = (size_t)(n * ly / lx * 2.0 / sqrt(3.0) + 0.5);
  cr_assert_eq(gm_mesh_rectangle(0, lx, 0, ly, n, ny, GM_DIAGONAL_ACUTE, &f.mesh, &err), GM_OK,
               "%s", err.message);
  cr_assert_eq(gm_fluid_groups_rectangle(f.mesh, &f.groups, &err), GM_OK, "%s", err.message);
  return f;
}

static inline void fl_free(fl_fixture *f) {
  gm_fluid_groups_free(f->groups);
  gm_mesh_free(f->mesh);
}

static inline int fl_couette_inflow(void *c, const double *x, double *u) {
  (void)c;
  u[0] = x[1];
  u[1] = 0.0;
  return 0;
}
static inline int fl_poiseuille_inflow(void *c, const double *x, double *u) {
  (void)c;
  u[0] = 4.0 * x[1] * (1.0 - x[1]);
  u[1] = 0.0;
  return 0;
}
/* exact stream functions (u = ∂ψ/∂y) and the scalar θ = y of both flows on the unit square */
static inline double fl_couette_psi(double y) { return 0.5 * y * y; }
static inline double fl_poiseuille_psi(double y) { return 2.0 * y * y - 4.0 * y * y * y / 3.0; }

/* Couette (poiseuille = 0: top wall moving at speed 1) or Poiseuille (centreline speed 1) on
 * the unit square: inflow on the left with the exact profile, outflow on the right; θ = 0 on
 * the bottom, 1 on the top, zero flux on the inflow and outflow. */
static inline void fl_shear_bcs(int poiseuille, gm_fluid_bc bc[4]) {
  memset(bc, 0, 4 * sizeof *bc);
  bc[0].group = "bottom";
  bc[0].kind = GM_FLUID_WALL;
  bc[0].scalar = GM_SCALAR_DIRICHLET;
  bc[0].scalar_value = 0.0;
  bc[1].group = "right";
  bc[1].kind = GM_FLUID_OUTFLOW;
  bc[2].group = "top";
  bc[2].kind = GM_FLUID_WALL;
  bc[2].velocity[0] = poiseuille ? 0.0 : 1.0;
  bc[2].scalar = GM_SCALAR_DIRICHLET;
  bc[2].scalar_value = 1.0;
  bc[3].group = "left";
  bc[3].kind = GM_FLUID_INFLOW;
  bc[3].profile = poiseuille ? fl_poiseuille_inflow : fl_couette_inflow;
}

static inline double fl_tri_area(const double *x, const size_t *t) {
  const double *a = x + 2 * t[0], *b = x + 2 * t[1], *c = x + 2 * t[2];
  return 0.5 * fabs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

/* least-squares slope of log e against log h (a convergence rate) */
static inline double fl_slope(size_t n, const double *h, const double *e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < n; ++i) {
    double x = log(h[i]), y = log(e[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return ((double)n * sxy - sx * sy) / ((double)n * sxx - sx * sx);
}

#endif
