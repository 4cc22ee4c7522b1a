/* DEC fluid invariants in a closed box (walls at rest on all four sides of the unit square):
 * - seed scheme, viscous: total vorticity Σ Γ_v = ∮ u_t ds = 0 (Stokes, exact on the dual
 *   cells) and the scalar mass Σ |⋆v| θ_v (zero-flux walls) constant to round-off, ‖δω‖∞ <= 1e-14
 *   at every step;
 * - inviscid implicit-midpoint scheme: kinetic energy, enstrophy and total vorticity conserved
 *   over 10⁴ steps; the seed scheme with ν = 0 from the same data beside it (its energy drifts). */
#include "../fluids_util.h"

#define PI 3.14159265358979323846

static const char *sides[4] = {"bottom", "right", "top", "left"};

static gm_fluid *closed_box(size_t n, gm_fluid_scheme scheme, double nu, double dt) {
  fl_fixture fx = fl_rect(1.0, 1.0, n);
  gm_fluid_bc bc[4];
  memset(bc, 0, sizeof bc);
  for (int k = 0; k < 4; ++k) {
    bc[k].group = sides[k];
    bc[k].kind = GM_FLUID_WALL;
  }
  gm_fluid_options o = gm_fluid_defaults();
  o.scheme = scheme;
  o.nu = nu;
  o.kappa = 0.01;
  o.dt = dt;
  o.velocity_scale = 1.0;
  gm_fluid *f = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_fluid_create(fx.mesh, fx.groups, 4, bc, &o, &f, &err), GM_OK, "%s", err.message);
  const size_t nv = gm_fluid_n_vertices(f);
  const double *x = gm_complex_coordinates(gm_fluid_complex(f));
  double *psi = malloc(nv * sizeof *psi), *theta = malloc(nv * sizeof *theta);
  for (size_t v = 0; v < nv; ++v) {
    double X = x[2 * v], Y = x[2 * v + 1];
    psi[v] = 0.1 * sin(PI * X) * sin(PI * Y) + 0.05 * sin(2 * PI * X) * sin(PI * Y);
    theta[v] = exp(-20.0 * ((X - 0.3) * (X - 0.3) + (Y - 0.6) * (Y - 0.6)));
  }
  cr_assert_eq(gm_fluid_set_state(f, psi, theta), GM_OK, "%s", gm_fluid_errmsg(f));
  free(psi);
  free(theta);
  fl_free(&fx);
  return f;
}

Test(fluids_invariants, closed_box_vorticity_and_mass) {
  gm_fluid *f = closed_box(16, GM_FLUID_SEED, 0.01, 0.01);
  gm_fluid_diagnostics d0, d;
  gm_fluid_diagnose(f, &d0);
  double dv = 0.0, dm = 0.0, div = 0.0;
  for (int s = 0; s < 500; ++s) {
    cr_assert_eq(gm_fluid_advance(f, 1), GM_OK, "%s", gm_fluid_errmsg(f));
    gm_fluid_diagnose(f, &d);
    dv = fmax(dv, fabs(d.total_vorticity - d0.total_vorticity));
    dm = fmax(dm, fabs(d.scalar_mass - d0.scalar_mass) / d0.scalar_mass);
    div = fmax(div, d.div_max);
  }
  /* measured: total vorticity 0 -> max |Σ Γ| 4.9e-16, scalar mass 2.2e-16 relative,
   * max |d1 dψ| 0 (the flow decays: kinetic energy falls by the factor below) */
  cr_assert_leq(dv, 1e-14, "total vorticity changed by %.3e", dv);
  cr_assert_leq(dm, 1e-14, "scalar mass changed by %.3e (relative)", dm);
  cr_assert_leq(div, 1e-14, "max |d1 d psi| = %.3e", div);
  cr_assert_lt(d.kinetic_energy, 0.9 * d0.kinetic_energy, "no viscous decay: %.6e -> %.6e",
               d0.kinetic_energy, d.kinetic_energy);
  gm_fluid_free(f);
}

Test(fluids_invariants, inviscid_midpoint_conserves_energy) {
  gm_fluid *f = closed_box(10, GM_FLUID_MIDPOINT, 0.0, 0.02);
  gm_fluid *g = closed_box(10, GM_FLUID_SEED, 0.0, 0.02);
  gm_fluid_diagnostics a0, b0, a, b;
  gm_fluid_diagnose(f, &a0);
  gm_fluid_diagnose(g, &b0);
  double de = 0.0, dz = 0.0, dv = 0.0, de_seed = 0.0;
  size_t iters = 0;
  for (int s = 0; s < 100; ++s) {
    cr_assert_eq(gm_fluid_advance(f, 100), GM_OK, "%s", gm_fluid_errmsg(f));
    cr_assert_eq(gm_fluid_advance(g, 100), GM_OK, "%s", gm_fluid_errmsg(g));
    gm_fluid_diagnose(f, &a);
    gm_fluid_diagnose(g, &b);
    de = fmax(de, fabs(a.kinetic_energy / a0.kinetic_energy - 1.0));
    dz = fmax(dz, fabs(a.enstrophy / a0.enstrophy - 1.0));
    dv = fmax(dv, fabs(a.total_vorticity - a0.total_vorticity));
    de_seed = fmax(de_seed, fabs(b.kinetic_energy / b0.kinetic_energy - 1.0));
    iters = a.midpoint_iterations > iters ? a.midpoint_iterations : iters;
  }
  /* measured over 10⁴ steps: energy 4.1e-15 relative, enstrophy 6.4e-15 relative, total
   * vorticity 2.9e-15 absolute, at most 12 fixed-point iterations per step; the seed scheme with
   * ν = 0 (no-slip walls, explicit convective half step): energy grows by 2.985 relative */
  cr_assert_leq(de, 2e-14, "midpoint: energy drift %.3e over 1e4 steps", de);
  cr_assert_leq(dz, 3e-14, "midpoint: enstrophy drift %.3e", dz);
  cr_assert_leq(dv, 2e-14, "midpoint: total vorticity drift %.3e", dv);
  cr_assert_leq(iters, 20, "midpoint: %zu iterations", iters);
  cr_assert(de_seed > 1.0 && de_seed < 10.0, "seed scheme, nu = 0: energy drift %.3e", de_seed);
  gm_fluid_free(f);
  gm_fluid_free(g);
}

/* The inviscid Taylor–Green cell: ψ = A sin πx sin πy in the unit square with slip walls is a
 * steady solution of Euler's equations (ζ = 2π²ψ, so u·∇ζ = 0), the one Taylor–Green cell a
 * closed box holds (the periodic square is not done: docs/fluids.md). The midpoint scheme keeps
 * energy, enstrophy and total vorticity over 10⁴ steps; the discrete flow departs from the steady
 * state only by the O(h²) mismatch of ζ and 2π²ψ, measured at two resolutions for its rate. */
static double taylor_green_cell(size_t n, size_t steps, int stress_free, double *de, double *dz,
                                double *dv) {
  fl_fixture fx = fl_rect(1.0, 1.0, n);
  gm_fluid_bc bc[4];
  memset(bc, 0, sizeof bc);
  for (int k = 0; k < 4; ++k) {
    bc[k].group = sides[k];
    bc[k].kind = GM_FLUID_WALL;
  }
  gm_fluid_options o = gm_fluid_defaults();
  o.scheme = GM_FLUID_MIDPOINT;
  o.nu = 0.0;
  o.dt = 0.02;
  o.velocity_scale = 1.0;
  o.stress_free_walls = stress_free;
  gm_fluid *f = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_fluid_create(fx.mesh, fx.groups, 4, bc, &o, &f, &err), GM_OK, "%s", err.message);
  const size_t nv = gm_fluid_n_vertices(f);
  const double *x = gm_complex_coordinates(gm_fluid_complex(f));
  double *psi0 = malloc(nv * sizeof *psi0);
  double pmax = 0.0;
  for (size_t v = 0; v < nv; ++v) {
    psi0[v] = 0.1 * sin(PI * x[2 * v]) * sin(PI * x[2 * v + 1]);
    pmax = fmax(pmax, fabs(psi0[v]));
  }
  cr_assert_eq(gm_fluid_set_state(f, psi0, NULL), GM_OK, "%s", gm_fluid_errmsg(f));
  gm_fluid_diagnostics d0, d;
  gm_fluid_diagnose(f, &d0);
  *de = *dz = *dv = 0.0;
  for (size_t s = 0; s < steps; s += 100) {
    cr_assert_eq(gm_fluid_advance(f, 100), GM_OK, "%s", gm_fluid_errmsg(f));
    gm_fluid_diagnose(f, &d);
    *de = fmax(*de, fabs(d.kinetic_energy / d0.kinetic_energy - 1.0));
    double z = stress_free ? d.interior_enstrophy : d.enstrophy;
    double z0 = stress_free ? d0.interior_enstrophy : d0.enstrophy;
    *dz = fmax(*dz, fabs(z / z0 - 1.0));
    *dv = fmax(*dv, fabs(d.total_vorticity - d0.total_vorticity));
  }
  double dev = 0.0;
  const double *psi = gm_fluid_psi(f);
  for (size_t v = 0; v < nv; ++v) dev = fmax(dev, fabs(psi[v] - psi0[v]));
  free(psi0);
  gm_fluid_free(f);
  fl_free(&fx);
  return dev / pmax;
}

Test(fluids_invariants, inviscid_taylor_green_cell) {
  double de, dz, dv, de2, dz2, dv2;
  /* departure from the steady state at t = 2 (100 steps) at n = 8, 16, 32 */
  double dev8 = taylor_green_cell(8, 100, 0, &de2, &dz2, &dv2);
  double dev16 = taylor_green_cell(16, 100, 0, &de2, &dz2, &dv2);
  double dev32 = taylor_green_cell(32, 100, 0, &de2, &dz2, &dv2);
  double dev_long = taylor_green_cell(10, 10000, 0, &de, &dz, &dv);
  cr_log_info("Taylor-Green cell, t = 2: max|psi - psi0|/max|psi0| = %.3e (n=8) %.3e (n=16) "
              "%.3e (n=32); 1e4 steps (n=10): departure %.3e, energy %.3e, enstrophy %.3e, "
              "total vorticity %.3e",
              dev8, dev16, dev32, dev_long, de, dz, dv);
  /* measured: invariants over 1e4 steps 6.9e-15, 2.6e-14 (relative), 1.4e-15 (absolute) */
  cr_assert_leq(de, 2e-14, "energy drift %.3e", de);
  cr_assert_leq(dz, 8e-14, "enstrophy drift %.3e", dz);
  cr_assert_leq(dv, 1e-14, "total vorticity drift %.3e", dv);
  /* measured: departure at t = 2 of 1.93e-1, 1.90e-1, 1.59e-1 (n = 8, 16, 32): NOT converging.
   * The slip wall's vortex sheet sits in the boundary dual cells as ζ_v = Γ_v/|⋆v| = O(1/h) and
   * the P1 Jacobian carries it into the interior (docs/fluids.md, "Taylor–Green cell"). These
   * bounds only guard against a worse scheme; a fix of the wall treatment must tighten them. */
  cr_assert_leq(dev8, 0.25, "n = 8: departure %.3e", dev8);
  cr_assert_leq(dev32, 0.2, "n = 32: departure %.3e", dev32);
  cr_assert_leq(dev_long, 0.3, "1e4 steps: departure %.3e", dev_long);
}

/* The same with stress_free_walls: the Jacobian sees ζ = 0 on the walls (exact for this cell),
 * the departure converges at second order and the invariants (energy, interior enstrophy, total
 * vorticity) stay exact. */
Test(fluids_invariants, inviscid_taylor_green_cell_stress_free) {
  double de, dz, dv, de2, dz2, dv2;
  double dev8 = taylor_green_cell(8, 100, 1, &de2, &dz2, &dv2);
  double dev16 = taylor_green_cell(16, 100, 1, &de2, &dz2, &dv2);
  double dev32 = taylor_green_cell(32, 100, 1, &de2, &dz2, &dv2);
  double dev_long = taylor_green_cell(10, 10000, 1, &de, &dz, &dv);
  double rate = log(dev8 / dev32) / log(4.0);
  cr_log_info("Taylor-Green cell, stress-free walls, t = 2: departure %.3e (n=8) %.3e (n=16) "
              "%.3e (n=32), rate %.2f; 1e4 steps (n=10): departure %.3e, energy %.3e, interior "
              "enstrophy %.3e, total vorticity %.3e",
              dev8, dev16, dev32, rate, dev_long, de, dz, dv);
  /* measured: 3.437e-3, 9.093e-4, 2.032e-4 (rate 2.04); 1e4 steps: departure 1.549e-3, energy
   * 2.9e-15, total vorticity 5.7e-16 */
  cr_assert(fabs(rate - 2.04) <= 0.15, "departure rate %.3f", rate);
  cr_assert_leq(dev32, 4e-4, "n = 32: departure %.3e", dev32);
  cr_assert_leq(dev_long, 3e-3, "1e4 steps: departure %.3e", dev_long);
  cr_assert_leq(de, 2e-14, "energy drift %.3e", de);
  cr_assert_leq(dz, 8e-14, "interior enstrophy drift %.3e", dz);
  cr_assert_leq(dv, 1e-14, "total vorticity drift %.3e", dv);
}

