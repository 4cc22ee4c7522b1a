/* DEC fluid solver contracts: bad input is an error naming the culprit (ν < 0, κ < 0, NaN, a
 * missing group, a group without a condition, a step above the half step's bound, a mesh that
 * is not well-centred); and each reconstructed equation of seed 004 checked against an exact
 * solution: the circulation Γ = Lψ + b (156) gives the exact vorticity of Couette and
 * Poiseuille flow, the convective term (the d i_u dω of 153–154, with the wedge 142) and the
 * midpoint scheme's Jacobian converge to u·∇ζ. */
#include "../fluids_util.h"

#include "fluids/internal.h"

static void expect_fail(const fl_fixture *fx, size_t n_bcs, const gm_fluid_bc *bc,
                        const gm_fluid_options *o, gm_status want, const char *needle) {
  gm_fluid *f = (gm_fluid *)0x1;
  gm_error err = {{0}};
  gm_status st = gm_fluid_create(fx->mesh, fx->groups, n_bcs, bc, o, &f, &err);
  cr_assert_eq(st, want, "expected %d for '%s', got %d (%s)", want, needle, st, err.message);
  cr_assert_null(f);
  cr_assert(strstr(err.message, needle) != NULL, "message '%s' lacks '%s'", err.message, needle);
}

Test(fluids, bad_input) {
  fl_fixture fx = fl_rect(1.0, 1.0, 8);
  gm_fluid_bc bc[4];
  fl_shear_bcs(0, bc);
  gm_fluid_options o = gm_fluid_defaults();
  o.nu = -1.0;
  expect_fail(&fx, 4, bc, &o, GM_EINVAL, "nu = -1");
  o.nu = 1.0;
  o.kappa = -0.5;
  expect_fail(&fx, 4, bc, &o, GM_EINVAL, "kappa = -0.5");
  o.kappa = 1.0;
  o.dt = NAN;
  expect_fail(&fx, 4, bc, &o, GM_EINVAL, "dt = nan");
  o.dt = 1e-2;
  o.stress_free_walls = 1;
  expect_fail(&fx, 4, bc, &o, GM_EINVAL, "stress_free_walls applies to the midpoint scheme only");
  o.stress_free_walls = 0;
  bc[2].scalar_value = NAN;
  expect_fail(&fx, 4, bc, &o, GM_EDOMAIN, "(\"top\"): non-finite");
  bc[2].scalar_value = 1.0;
  bc[3].group = "inlet";
  expect_fail(&fx, 4, bc, &o, GM_ENOTFOUND, "group \"inlet\" (bcs[3]) is not in the mesh");
  bc[3].group = "left";
  expect_fail(&fx, 3, bc, &o, GM_EINVAL, "group \"left\" has no condition");
  /* the explicit half step: Courant bound 2 h_min/|u|max with the moving wall's speed 1 */
  o.dt = 1.0;
  expect_fail(&fx, 4, bc, &o, GM_EINVAL, "above the bound");
  gm_fluid *f = NULL;
  gm_error err = {{0}};
  o.dt = 1e-2;
  cr_assert_eq(gm_fluid_create(fx.mesh, fx.groups, 4, bc, &o, &f, &err), GM_OK, "%s", err.message);
  const double bound = gm_fluid_dt_bound(f);
  gm_fluid_free(f);
  o.dt = bound * 1.0001;
  char want[64];
  snprintf(want, sizeof want, "bound %.6g", bound);
  expect_fail(&fx, 4, bc, &o, GM_EINVAL, want);
  o.dt = bound * 0.9999;
  cr_assert_eq(gm_fluid_create(fx.mesh, fx.groups, 4, bc, &o, &f, &err), GM_OK, "%s", err.message);
  /* a NaN initial state */
  double *psi = calloc(gm_fluid_n_vertices(f), sizeof *psi);
  psi[5] = NAN;
  cr_assert_eq(gm_fluid_set_state(f, psi, NULL), GM_EDOMAIN);
  cr_assert(strstr(gm_fluid_errmsg(f), "non-finite") != NULL);
  free(psi);
  gm_fluid_free(f);
  /* the midpoint scheme is inviscid and needs walls at rest */
  o = gm_fluid_defaults();
  o.scheme = GM_FLUID_MIDPOINT;
  expect_fail(&fx, 4, bc, &o, GM_EINVAL, "nu must be 0");
  o.nu = 0.0;
  expect_fail(&fx, 4, bc, &o, GM_EUNSUPPORTED, "closed box of walls at rest");
  fl_free(&fx);

  /* right triangles: the hypotenuses have ⋆1 = 0 */
  fl_fixture rt = {0};
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, 4, 4, GM_DIAGONAL_RIGHT, &rt.mesh, &err), GM_OK);
  cr_assert_eq(gm_fluid_groups_rectangle(rt.mesh, &rt.groups, &err), GM_OK);
  fl_shear_bcs(0, bc);
  expect_fail(&rt, 4, bc, NULL, GM_EINVAL,
              "not well-centred for the diagonal Hodge star: 16 of 56 edges");
  fl_free(&rt);
}

/* (156) [R]: Γ_v = (Lψ)_v + ∫ u_t ds over the boundary part of ∂⋆v. For the exact Couette and
 * Poiseuille stream functions, ζ = Γ/|⋆v| is the exact vorticity −ψ'' at every vertex, walls
 * included (this is the vorticity boundary condition the no-slip and moving walls impose). */
Test(fluids, circulation_is_exact_vorticity) {
  for (int pois = 0; pois < 2; ++pois) {
    fl_fixture fx = fl_rect(1.0, 1.0, 16);
    gm_fluid_bc bc[4];
    fl_shear_bcs(pois, bc);
    gm_fluid *f = NULL;
    gm_error err = {{0}};
    cr_assert_eq(gm_fluid_create(fx.mesh, fx.groups, 4, bc, NULL, &f, &err), GM_OK, "%s",
                 err.message);
    const size_t nv = gm_fluid_n_vertices(f);
    const double *x = gm_complex_coordinates(gm_fluid_complex(f));
    double *psi = malloc(nv * sizeof *psi), *zeta = malloc(nv * sizeof *zeta);
    /* the boundary values fix the constant: match it at vertex 0 */
    const double *psi_bc = gm_fluid_psi(f);
    double c = psi_bc[0] - (pois ? fl_poiseuille_psi(x[1]) : fl_couette_psi(x[1]));
    for (size_t v = 0; v < nv; ++v)
      psi[v] = c + (pois ? fl_poiseuille_psi(x[2 * v + 1]) : fl_couette_psi(x[2 * v + 1]));
    double bmax = 0.0;
    for (size_t v = 0; v < nv; ++v)
      bmax = fmax(bmax, fabs(psi_bc[v] - psi[v]) * (psi_bc[v] != 0.0));
    cr_assert_eq(gm_fluid_set_state(f, psi, NULL), GM_OK, "%s", gm_fluid_errmsg(f));
    gm_fluid_vorticity(f, zeta);
    double emax = 0.0;
    for (size_t v = 0; v < nv; ++v) {
      /* away from the side rows, where the acute pattern has right triangles and the dual cells
       * are not centred on their vertices (an O(1) local error there, as in any finite volume
       * scheme on irregular cells; the solution still converges, see test_fluids_rates) */
      if (x[2 * v] < 0.2 || x[2 * v] > 0.8) continue;
      /* Poiseuille: Γ/|⋆v| on a wall is the mean of the linear ζ over a half cell, not ζ(v) */
      if (pois && (x[2 * v + 1] < 1e-12 || x[2 * v + 1] > 1.0 - 1e-12)) continue;
      double y = x[2 * v + 1], exact = pois ? -(4.0 - 8.0 * y) : -1.0;
      emax = fmax(emax, fabs(zeta[v] - exact));
    }
    /* measured: Couette 9.1e-14 (walls included), Poiseuille 9.6e-14 */
    cr_assert_lt(emax, 1e-12, "%s: max vorticity error %.3e", pois ? "Poiseuille" : "Couette",
                 emax);
    /* the boundary stream function from the inflow profile is the exact one */
    cr_assert_lt(bmax, 1e-14, "boundary psi error %.3e", bmax);
    free(psi);
    free(zeta);
    gm_fluid_free(f);
    fl_free(&fx);
  }
}

/* The convective term (153–154) [R] and the midpoint Jacobian against ⋆0 u·∇ζ on the interior
 * vertices, for ψ = sin(x) sin(2y)/3, ζ = cos(x + y): max error at n = 16 and 32. */
static void convective_errors(size_t n, double *e_conv, double *e_jac) {
  fl_fixture fx = fl_rect(1.0, 1.0, n);
  gm_fluid_bc bc[4];
  memset(bc, 0, sizeof bc);
  const char *names[4] = {"bottom", "right", "top", "left"};
  for (int k = 0; k < 4; ++k) {
    bc[k].group = names[k];
    bc[k].kind = GM_FLUID_WALL;
  }
  gm_fluid_options o = gm_fluid_defaults();
  o.dt = 1e-4;
  gm_fluid *f = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_fluid_create(fx.mesh, fx.groups, 4, bc, &o, &f, &err), GM_OK, "%s", err.message);
  const size_t nv = gm_fluid_n_vertices(f);
  const double *x = gm_complex_coordinates(gm_fluid_complex(f));
  const double *s0 = gm_geometry_hodge_star(gm_fluid_geometry(f), 0);
  const unsigned char *bnd = gm_complex_boundary_mask(gm_fluid_complex(f), 0);
  double *psi = malloc(nv * sizeof *psi), *zeta = malloc(nv * sizeof *zeta);
  double *c = malloc(nv * sizeof *c), *j = malloc(nv * sizeof *j);
  for (size_t v = 0; v < nv; ++v) {
    psi[v] = sin(x[2 * v]) * sin(2.0 * x[2 * v + 1]) / 3.0;
    zeta[v] = cos(x[2 * v] + x[2 * v + 1]);
  }
  gm_fluid_convective_outflow(f, zeta, psi, c);
  gm_fluid_jacobian(f, psi, zeta, j);
  *e_conv = *e_jac = 0.0;
  for (size_t v = 0; v < nv; ++v) {
    if (bnd[v] || x[2 * v] < 0.2 || x[2 * v] > 0.8) continue; /* as above */
    double X = x[2 * v], Y = x[2 * v + 1];
    double ux = 2.0 * sin(X) * cos(2.0 * Y) / 3.0, uy = -cos(X) * sin(2.0 * Y) / 3.0;
    double adv = -(ux + uy) * sin(X + Y); /* u·∇ζ */
    *e_conv = fmax(*e_conv, fabs(c[v] / s0[v] - adv));
    *e_jac = fmax(*e_jac, fabs(-j[v] / s0[v] - adv)); /* ζ_t = −u·∇ζ = ∇ψ × ∇ζ */
  }
  free(psi);
  free(zeta);
  free(c);
  free(j);
  gm_fluid_free(f);
  fl_free(&fx);
}

Test(fluids, convective_terms_are_consistent) {
  double c1, j1, c2, j2;
  convective_errors(16, &c1, &j1);
  convective_errors(32, &c2, &j2);
  /* measured: convective 1.362e-3 -> 3.433e-4, Jacobian 1.355e-3 -> 3.433e-4: second order */
  cr_assert_lt(c2, 4e-4, "convective error %.3e", c2);
  cr_assert_lt(j2, 4e-4, "jacobian error %.3e", j2);
  cr_assert_gt(c1 / c2, 3.6, "convective errors %.3e %.3e", c1, c2);
  cr_assert_gt(j1 / j2, 3.6, "jacobian errors %.3e %.3e", j1, j2);
}
