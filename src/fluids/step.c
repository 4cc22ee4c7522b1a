/* DEC fluid solver: the time steps (seed 004 eqs. 153–156 [R]; the inviscid implicit-midpoint
 * variant), the state and the diagnostics. No allocation here. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "core/internal.h"
#include "fluids/internal.h"

/* Net outflow of q (a vertex field: ζ or θ) from each dual cell ⋆v, written to out:
 *   − d0ᵀ ⋆1 (q ∧ U)  with the primal–primal wedge ⟨q ∧ U, [i,j]⟩ = ½ (q_i + q_j) U_ij
 * (seed 004 eq. 142 [R]) and U = Sψ the primal velocity 1-form (u♭ on primal edges); ⋆1 U is the
 * flux through the dual edges. This is the Cartan/interior-product term d i_u dω of (152a) for
 * q = ζ (i_u of the dual 2-form ζ is ⋆(ζ ∧ u♭), eq. 150 [R]) and −δ(ω ∧ θ) of (152c) for q = θ,
 * both times ⋆0. On the boundary, the flux through the two halves of each boundary edge, half of
 * (ψ_head − ψ_tail) each, leaves with the cell's own value (zero on walls; outflow only). */
void gm_fluid_convective_outflow(gm_fluid *f, const double *q, const double *psi, double *out) {
  gm_csr_matvec(f->S, 1.0, psi, 0.0, f->u_edge);
  memset(out, 0, f->nv * sizeof *out);
  for (size_t e = 0; e < f->ne; ++e) {
    size_t i = f->edge[2 * e], j = f->edge[2 * e + 1];
    double flux = f->star1[e] * 0.5 * (q[i] + q[j]) * f->u_edge[e];
    out[i] += flux;
    out[j] -= flux;
  }
  for (size_t k = 0; k < f->nb; ++k) {
    size_t a = f->b_tail[k], b = f->b_head[k];
    double half = 0.5 * (psi[b] - psi[a]);
    out[a] += q[a] * half;
    out[b] += q[b] * half;
  }
}

static void vorticity_of(const gm_fluid *f, const double *gamma, double *zeta) {
  for (size_t v = 0; v < f->nv; ++v) zeta[v] = gamma[v] / f->star0[v];
}

/* The convected vorticity is the absolute one, ζ + f, in a rotating frame (surfaces). */
static void add_coriolis(const gm_fluid *f, double *zeta) {
  if (f->closed && f->opt.rotation != 0.0)
    for (size_t v = 0; v < f->nv; ++v) zeta[v] += f->coriolis[v];
}

/* Solve the SPD system ch on the free vertices with right-hand side rhs[v] (all vertices) plus
 * c (free vertices), and write ψ (Dirichlet values elsewhere). */
static gm_status solve_psi(gm_fluid *f, gm_sparse_cholesky *ch, const double *rhs, const double *c,
                           double *psi) {
  for (size_t i = 0; i < f->n_free; ++i) f->sol[i] = rhs[f->free_list[i]] + (c ? c[i] : 0.0);
  gm_status st = gm_sparse_cholesky_solve(ch, f->sol, f->sol);
  if (st) return st;
  memcpy(psi, f->psi_bc, f->nv * sizeof *psi);
  for (size_t i = 0; i < f->n_free; ++i) psi[f->free_list[i]] = f->sol[i];
  return GM_OK;
}

/* Scalar step (155) [R]: ⋆0 (θ^{n+1} − θ^n)/dt + [convective outflow of θ^n with u^{n+½}]
 * + κ L θ^{n+1} = 0 on the non-Dirichlet vertices. The seed makes the convection implicit too;
 * here it is lagged to θ^n so that the matrix (⋆0/dt + κL) is factorized once at create. */
static gm_status scalar_step(gm_fluid *f, const double *psi_half) {
  if (!f->n_wfree) return GM_OK;
  if (f->closed && f->opt.scheme == GM_FLUID_MIDPOINT) {
    /* the P1 Jacobian, −∫ φ_v u·∇θ (conserves Σ ⋆0 θ) */
    gm_fluid_jacobian(f, psi_half, f->theta, f->out);
    for (size_t v = 0; v < f->nv; ++v) f->out[v] = -f->out[v];
  } else
    gm_fluid_convective_outflow(f, f->theta, psi_half, f->out);
  for (size_t i = 0; i < f->n_wfree; ++i) {
    size_t v = f->wfree_list[i];
    f->rhs_w[i] = f->star0[v] * f->theta[v] / f->opt.dt - f->out[v] + f->c_theta[i];
  }
  gm_status st = gm_sparse_cholesky_solve(f->m_theta, f->rhs_w, f->rhs_w);
  if (st) return st;
  for (size_t i = 0; i < f->n_wfree; ++i) f->theta[f->wfree_list[i]] = f->rhs_w[i];
  return GM_OK;
}

/* One step of the seed scheme [R]:
 * (153) Γ^{n+½} = Γ^n − (dt/2) C(ζ^n, ψ^n) − (dt/2) ν L ζ^{n+½}   (convection explicit)
 * (154) Γ^{n+1} = Γ^n − dt C(ζ^{n+½}, ψ^{n+½}) − dt ν L ζ^{n+1}
 * (156) Γ = Lψ + b (⋆ω = dψ), ζ = ⋆0⁻¹ Γ, both solved for ψ on the free vertices;
 * C = gm_fluid_convective_outflow, the d i_u dω term; ν L ζ = ν d0ᵀ⋆1 d0 ⋆0⁻¹ Γ is ν d δ d ω on
 * dual 2-forms. Only the free vertices' rows are equations: on walls and inflows Γ = Lψ + b is the
 * circulation the no-slip or inflow velocity gives (the vorticity boundary condition). */
static gm_status seed_step(gm_fluid *f) {
  const double dt = f->opt.dt;
  vorticity_of(f, f->gamma, f->zeta);
  add_coriolis(f, f->zeta);
  gm_fluid_convective_outflow(f, f->zeta, f->psi, f->out);
  for (size_t v = 0; v < f->nv; ++v) f->rhs[v] = f->gamma[v] - 0.5 * dt * f->out[v];
  gm_status st = solve_psi(f, f->m_half, f->rhs, f->c_half, f->psi_h);
  if (st) return st;
  gm_fluid_circulation_of(f, f->psi_h, f->gamma_h);
  vorticity_of(f, f->gamma_h, f->zeta_h);
  add_coriolis(f, f->zeta_h);
  gm_fluid_convective_outflow(f, f->zeta_h, f->psi_h, f->out);
  for (size_t v = 0; v < f->nv; ++v) f->rhs[v] = f->gamma[v] - dt * f->out[v];
  st = solve_psi(f, f->m_full, f->rhs, f->c_full, f->psi_k);
  if (st) return st;
  st = scalar_step(f, f->psi_h);
  if (st) return st;
  memcpy(f->psi, f->psi_k, f->nv * sizeof(double));
  gm_fluid_circulation_of(f, f->psi, f->gamma);
  return GM_OK;
}

/* ∇ of the linear interpolant of the vertex field q on triangle t (sdim values; g[2] = 0 in the
 * plane). */
static void tri_gradient(const gm_fluid *f, size_t t, const double *q, double g[3]) {
  const size_t sd = f->sdim;
  g[0] = g[1] = g[2] = 0.0;
  for (size_t k = 0; k < 3; ++k) {
    const double *gk = f->grad + (3 * t + k) * sd, v = q[f->tri[3 * t + k]];
    for (size_t c = 0; c < sd; ++c) g[c] += v * gk[c];
  }
}

/* n · (a × b): n = ẑ in the plane, the triangle's unit normal on a surface */
static double normal_cross(const gm_fluid *f, size_t t, const double *a, const double *b) {
  double z = a[0] * b[1] - a[1] * b[0];
  if (f->sdim == 2) return z;
  const double *n = f->normal + 3 * t;
  return n[0] * (a[1] * b[2] - a[2] * b[1]) + n[1] * (a[2] * b[0] - a[0] * b[2]) + n[2] * z;
}

/* Γ̇_v = ∫ φ_v n·(∇ψ × ∇ζ) = Σ_{T ∋ v} (|T|/3) n_T·(∇ψ_T × ∇ζ_T) for the P1 interpolants: the
 * trilinear form t(a, b, c) = ∫ a n·(∇b × ∇c) is integrated exactly, so it is antisymmetric in
 * (b, c) and, with ψ = 0 on the boundary or without boundary, in (a, b): Σ ψ_v Γ̇_v =
 * Σ ζ_v Γ̇_v = Σ Γ̇_v = 0 (energy ½ψᵀLψ, enstrophy, total vorticity). The vorticity equation
 * ζ_t + u·∇ζ = 0 with u = ∇ψ × n = (ψ_y, −ψ_x). */
void gm_fluid_jacobian(gm_fluid *f, const double *psi, const double *zeta, double *rate) {
  memset(rate, 0, f->nv * sizeof *rate);
  for (size_t t = 0; t < f->nt; ++t) {
    const size_t *v = f->tri + 3 * t;
    double gp[3], gz[3];
    tri_gradient(f, t, psi, gp);
    tri_gradient(f, t, zeta, gz);
    double j = f->area[t] / 3.0 * normal_cross(f, t, gp, gz);
    rate[v[0]] += j;
    rate[v[1]] += j;
    rate[v[2]] += j;
  }
}

/* Implicit midpoint on Γ (all vertices evolve: slip walls), ψ^m from the interior rows
 * L_II ψ_I = Γ^m_I with ψ = 0 on the walls; fixed-point iteration. Quadratic invariants of the
 * semi-discrete system are kept exactly by the midpoint rule (Cooper 1987). */
static gm_status midpoint_step(gm_fluid *f) {
  const double dt = f->opt.dt;
  double scale = 0.0;
  for (size_t v = 0; v < f->nv; ++v) scale = fmax(scale, fabs(f->gamma[v]));
  memcpy(f->gamma_k, f->gamma, f->nv * sizeof(double));
  if (f->m_visc) {
    vorticity_of(f, f->gamma, f->zeta);
    gm_csr_matvec(f->L, -0.5 * dt * f->opt.nu, f->zeta, 0.0, f->rhs);
    for (size_t v = 0; v < f->nv; ++v) f->rhs[v] += f->gamma[v];
  }
  double previous = INFINITY;
  for (size_t it = 1; it <= f->opt.midpoint_max_iter; ++it) {
    for (size_t v = 0; v < f->nv; ++v) f->gamma_h[v] = 0.5 * (f->gamma[v] + f->gamma_k[v]);
    gm_status st = solve_psi(f, f->poisson, f->gamma_h, NULL, f->psi_h);
    if (st) return st;
    vorticity_of(f, f->gamma_h, f->zeta_h);
    /* rotating frame: the Jacobian advects the absolute vorticity ζ + f (barotropic vorticity
     * equation); t(ψ, ψ, ζ+f) = 0 and t(1, ψ, ζ+f) = 0 keep energy and total vorticity, and
     * t(ζ+f, ψ, ζ+f) = 0 the potential enstrophy ½ Σ ⋆0 (ζ+f)². */
    add_coriolis(f, f->zeta_h);
    /* Stress-free walls: ζ̃ = 0 where ψ is fixed. Still Σ ψ_v Γ̇_v = t(ψ, ψ, ζ̃) = 0 and
     * Σ Γ̇_v = 0 (ψ constant on the wall), and Σ ζ̃_v Γ̇_v = t(ζ̃, ψ, ζ̃) = 0 with Σ ζ̃_v Γ_v = twice
     * the interior enstrophy: the quadratic invariants kept by the midpoint rule. */
    if (f->opt.stress_free_walls)
      for (size_t v = 0; v < f->nv; ++v)
        if (f->psi_fixed[v]) f->zeta_h[v] = 0.0;
    gm_fluid_jacobian(f, f->psi_h, f->zeta_h, f->out);
    if (f->m_visc) {
      /* viscosity, implicit in the midpoint rule: ⋆0 (ζ^{k+1} − ζ^n)/dt = J − ν L (ζ^n + ζ^{k+1})/2,
       * i.e. (⋆0 + ν dt/2 L) ζ^{k+1} = Γ^n − ν dt/2 L ζ^n + dt J (f->rhs holds all but dt J) */
      for (size_t v = 0; v < f->nv; ++v) f->sol[v] = f->rhs[v] + dt * f->out[v];
      st = gm_sparse_cholesky_solve(f->m_visc, f->sol, f->sol);
      if (st) return st;
      for (size_t v = 0; v < f->nv; ++v) f->out[v] = (f->star0[v] * f->sol[v] - f->gamma[v]) / dt;
    }
    double change = 0.0;
    for (size_t v = 0; v < f->nv; ++v) {
      double g = f->gamma[v] + dt * f->out[v];
      change = fmax(change, fabs(g - f->gamma_k[v]));
      f->gamma_k[v] = g;
    }
    if (!(change == change)) break;
    /* converged, or stagnating at round-off (the change no longer decreases) */
    int stagnant = it > 2 && change >= previous && change <= 1e-12 * scale;
    previous = change;
    if (change <= f->opt.midpoint_tol * scale || stagnant) {
      f->last_iterations = it;
      st = scalar_step(f, f->psi_h);
      if (st) return st;
      memcpy(f->gamma, f->gamma_k, f->nv * sizeof(double));
      for (size_t v = 0; v < f->nv; ++v) f->gamma_h[v] = f->gamma[v];
      return solve_psi(f, f->poisson, f->gamma, NULL, f->psi);
    }
  }
  snprintf(f->errmsg, sizeof f->errmsg,
           "fluid: the implicit midpoint iteration did not converge in %zu iterations at step %zu "
           "(t = %g): reduce dt",
           f->opt.midpoint_max_iter, f->step, f->t);
  return GM_ENOCONV;
}

gm_status gm_fluid_advance(gm_fluid *f, size_t n_steps) {
  if (!f) return GM_EINVAL;
  for (size_t s = 0; s < n_steps; ++s) {
    gm_status st = f->opt.scheme == GM_FLUID_MIDPOINT ? midpoint_step(f) : seed_step(f);
    if (st) {
      if (st != GM_ENOCONV)
        snprintf(f->errmsg, sizeof f->errmsg, "fluid: step %zu failed: %s", f->step,
                 gm_strerror(st));
      return st;
    }
    if (gm_first_nonfinite(f->nv, f->psi) != f->nv ||
        gm_first_nonfinite(f->nv, f->theta) != f->nv) {
      snprintf(f->errmsg, sizeof f->errmsg,
               "fluid: the solution blew up (non-finite value) at step %zu, t = %g", f->step + 1,
               f->t + f->opt.dt);
      return GM_EDOMAIN;
    }
    ++f->step;
    f->t = (double)f->step * f->opt.dt;
  }
  return GM_OK;
}

gm_status gm_fluid_set_state(gm_fluid *f, const double *psi, const double *theta) {
  if (!f) return GM_EINVAL;
  if ((psi && gm_first_nonfinite(f->nv, psi) != f->nv) ||
      (theta && gm_first_nonfinite(f->nv, theta) != f->nv)) {
    snprintf(f->errmsg, sizeof f->errmsg, "fluid: non-finite value in the initial state");
    return GM_EDOMAIN;
  }
  if (psi) {
    double umax = 0.0;
    for (size_t t = 0; t < f->nt; ++t) {
      double g[3];
      tri_gradient(f, t, psi, g);
      umax = fmax(umax, sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]));
    }
    double bound = fmin(f->dt_bound, umax > 0 ? 2.0 * f->h_min / umax : INFINITY);
    if (f->opt.scheme == GM_FLUID_SEED && f->opt.dt > bound) {
      snprintf(f->errmsg, sizeof f->errmsg,
               "fluid: dt = %g is above the bound %.6g of the explicit half step for this initial "
               "velocity (2 h_min/|u|max, |u|max = %g)",
               f->opt.dt, bound, umax);
      return GM_EINVAL;
    }
    f->dt_bound = bound;
    if (f->closed) /* no boundary: only the gauge vertex is fixed, so shift ψ to ψ = 0 there */
      for (size_t v = 0; v < f->nv; ++v) f->psi[v] = psi[v] - psi[0];
    else
      for (size_t v = 0; v < f->nv; ++v) f->psi[v] = f->psi_fixed[v] ? f->psi_bc[v] : psi[v];
    gm_fluid_circulation_of(f, f->psi, f->gamma);
  }
  if (theta)
    for (size_t v = 0; v < f->nv; ++v) f->theta[v] = f->theta_fixed[v] ? f->theta_bc[v] : theta[v];
  return GM_OK;
}

size_t gm_fluid_n_vertices(const gm_fluid *f) { return f->nv; }
size_t gm_fluid_n_triangles(const gm_fluid *f) { return f->nt; }
const gm_complex *gm_fluid_complex(const gm_fluid *f) { return f->cx; }
const gm_geometry *gm_fluid_geometry(const gm_fluid *f) { return f->geo; }
double gm_fluid_time(const gm_fluid *f) { return f->t; }
size_t gm_fluid_steps(const gm_fluid *f) { return f->step; }
double gm_fluid_dt(const gm_fluid *f) { return f->opt.dt; }
double gm_fluid_dt_bound(const gm_fluid *f) { return f->dt_bound; }
const double *gm_fluid_psi(const gm_fluid *f) { return f->psi; }
const double *gm_fluid_theta(const gm_fluid *f) { return f->theta; }
const double *gm_fluid_circulation(const gm_fluid *f) { return f->gamma; }
void gm_fluid_vorticity(const gm_fluid *f, double *zeta) { vorticity_of(f, f->gamma, zeta); }

void gm_fluid_velocity(const gm_fluid *f, double *u) {
  for (size_t t = 0; t < f->nt; ++t) {
    double g[3];
    tri_gradient(f, t, f->psi, g);
    if (f->sdim == 2) {
      u[2 * t] = g[1];
      u[2 * t + 1] = -g[0];
    } else { /* u = ∇ψ × n */
      const double *n = f->normal + 3 * t;
      u[3 * t] = g[1] * n[2] - g[2] * n[1];
      u[3 * t + 1] = g[2] * n[0] - g[0] * n[2];
      u[3 * t + 2] = g[0] * n[1] - g[1] * n[0];
    }
  }
}

const size_t *gm_fluid_vertex_map(const gm_fluid *f) { return f->rep; }
size_t gm_fluid_space_dim(const gm_fluid *f) { return f->sdim; }
const double *gm_fluid_coordinates(const gm_fluid *f) { return f->closed ? f->xq : f->x; }

void gm_fluid_flux(const gm_fluid *f, double *flux) {
  const gm_csr *d0 = gm_complex_d(f->cx, 0);
  if (!f->rep) {
    gm_csr_matvec(d0, 1.0, f->psi, 0.0, flux);
    return;
  }
  for (size_t e = 0; e < d0->n_rows; ++e) { /* ψ pulled back to the mesh's vertices */
    flux[e] = 0.0;
    for (size_t k = d0->row_start[e]; k < d0->row_start[e + 1]; ++k)
      flux[e] += d0->val[k] * f->psi[f->rep[d0->col[k]]];
  }
}

void gm_fluid_diagnose(const gm_fluid *f, gm_fluid_diagnostics *d) {
  memset(d, 0, sizeof *d);
  d->time = f->t;
  const gm_csr *d0 = gm_complex_d(f->cx, 0), *d1 = gm_complex_d(f->cx, 1);
  for (size_t t = 0; t < f->nt; ++t) {
    double g[3];
    tri_gradient(f, t, f->psi, g);
    d->kinetic_energy += 0.5 * f->area[t] * (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    /* net flux out of T: Σ over its edges of ± dψ, i.e. (d1 d0 ψ)_T (δω = 0 by d∘d = 0); the
     * mesh's d0, d1 on ψ pulled back to the mesh vertices when they were identified */
    double net = 0.0;
    for (size_t k = d1->row_start[t]; k < d1->row_start[t + 1]; ++k) {
      size_t e = d1->col[k];
      double fe = 0.0;
      for (size_t m = d0->row_start[e]; m < d0->row_start[e + 1]; ++m)
        fe += d0->val[m] * f->psi[f->rep ? f->rep[d0->col[m]] : d0->col[m]];
      net += d1->val[k] * fe;
    }
    d->div_max = fmax(d->div_max, fabs(net));
  }
  for (size_t v = 0; v < f->nv; ++v) {
    d->enstrophy += 0.5 * f->gamma[v] * f->gamma[v] / f->star0[v];
    if (!f->psi_fixed[v] || f->closed) d->interior_enstrophy += 0.5 * f->gamma[v] * f->gamma[v] / f->star0[v];
    d->total_vorticity += f->gamma[v];
    d->scalar_mass += f->star0[v] * f->theta[v];
  }
  d->midpoint_iterations = f->last_iterations;
}
