/* The PDE solver's plan (create: every check and allocation), execute (advance) and monitors. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pde/internal.h"

gm_pde_options gm_pde_options_defaults(void) {
  gm_pde_options o = {0};
  o.newton_tol = 1e-13;
  o.newton_max_iter = 30;
  o.tangent_seed = 1.0;
  return o;
}

static double *vec(size_t n) { return calloc(n > 0 ? n : 1, sizeof(double)); }

void gm_pde_free(gm_pde *p) {
  if (p == NULL) return;
  free(p->s);
  free(p->s_prev);
  free(p->s_new);
  free(p->F);
  free(p->dx);
  free(p->hess);
  free(p->work);
  free(p->pos);
  gm_band_release(&p->band);
  for (int k = 0; k < 2; k++)
    for (int j = 0; j < 3; j++) free(p->tan[k][j]);
  free(p->msres);
  free(p->aux[0]);
  free(p->gp_x);
  free(p->gp_F);
  free(p->gp_b);
  free(p->gp_cell);
  gm_bband_release(&p->gp_band);
  free(p->gp_t[0]);
  free(p->gp_t[1]);
  free(p->aux[1]);
  free(p->u_prev);
  free(p->u);
  free(p->u_new);
  free(p);
}

/* Deterministic pseudo-random numbers in (−1, 1) for the tangent variations (no global state). */
static double lcg(unsigned long long *x) {
  *x = *x * 6364136223846793005ULL + 1442695040888963407ULL;
  return ((double)(*x >> 11) / 9007199254740992.0) * 2.0 - 1.0;
}

gm_status gm_pde_create(const gm_pde_grid *grid, const gm_pde_equation *eq,
                        const gm_pde_scheme *scheme, const gm_pde_options *options,
                        const double *s0, gm_pde **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "pde: NULL output pointer");
  *out = NULL;
  if (grid == NULL || scheme == NULL || options == NULL || s0 == NULL)
    return gm_error_set(err, GM_EINVAL, "pde: NULL argument");
  gm_status st = gm_pde_equation_check(eq, err);
  if (st != GM_OK) return st;
  size_t n = grid->n, d = eq->dim;
  if (n < 4) return gm_error_set(err, GM_EINVAL, "pde: need n >= 4 grid points (got %zu)", n);
  if (n > ((size_t)1 << 40) / (d * d * 16))
    return gm_error_set(err, GM_EINVAL, "pde: n = %zu is too large", n);
  if (!(isfinite(grid->h) && grid->h > 0.0) || !isfinite(grid->x0))
    return gm_error_set(err, GM_EINVAL, "pde: grid spacing h must be finite and > 0 (got %g)",
                        grid->h);
  double dt = options->dt;
  if (!(isfinite(dt) && dt > 0.0))
    return gm_error_set(err, GM_EINVAL, "pde: time step dt must be finite and > 0 (got %g)", dt);
  if (!(options->newton_tol > 0.0) || options->newton_max_iter == 0)
    return gm_error_set(err, GM_EINVAL, "pde: Newton tolerance and iteration limit must be > 0");
  double kcopy[GM_PDE_MAX_DIM * GM_PDE_MAX_DIM];
  int kpiv[GM_PDE_MAX_DIM];
  memcpy(kcopy, eq->K, d * d * sizeof *kcopy);
  int k_singular = gm_lu_factor(d, kcopy, kpiv) != GM_OK;
  if ((scheme->kind == GM_PDE_PREISSMANN || scheme->kind == GM_PDE_BOX_SDIRK2) && n % 2 == 0 &&
      k_singular && options->dirichlet_left == 0 && options->dirichlet_right == 0)
    return gm_error_set(err, GM_EINVAL,
                        "pde: the Preissmann box needs an odd number of grid points on a "
                        "periodic grid when K is singular (got n = %zu: the checkerboard mode "
                        "makes its Newton matrix singular)", n);
  if (scheme->scalar && (eq->V == NULL || d != 3))
    return gm_error_set(err, GM_EINVAL,
                        "pde: scheme '%s' needs a wave equation (s = (u, v, w) with V, dV)",
                        scheme->name);
  if (scheme->kind == GM_PDE_GAUSS_PRK) {
    if (n % 2 != 0)
      return gm_error_set(err, GM_EINVAL, "pde: gauss-prk needs an even number of points "
                          "(two Gauss points per cell; got n = %zu)", n);
    for (size_t a = 0; a < d; a++)
      if (grid->twist[a] != 0.0)
        return gm_error_set(err, GM_EINVAL, "pde: gauss-prk does not take a twist");
    if (!gm_pde_gauss_kernel_ok(eq))
      return gm_error_set(err, GM_EINVAL, "pde: gauss-prk needs the kernel of K along "
                          "coordinates (components whose row and column of K vanish)");
    if (options->dirichlet_left != 0 || options->dirichlet_right != 0 || eq->has_gauge)
      return gm_error_set(err, GM_EINVAL,
                          "pde: gauss-prk is implemented for periodic grids without a gauge");
  }
  if (scheme->kind == GM_PDE_KDV_ZK && !eq->is_kdv)
    return gm_error_set(err, GM_EINVAL, "pde: scheme 'zk' needs the KdV equation");
  if (eq->has_gauge && (eq->gauge_phi >= d || eq->gauge_u >= d || eq->gauge_phi == eq->gauge_u))
    return gm_error_set(err, GM_EINVAL, "pde: gauge components out of range");
  if (eq->has_gauge && (scheme->kind == GM_PDE_EULER_BOX || scheme->kind == GM_PDE_BOX_SDIRK2))
    return gm_error_set(err, GM_EINVAL, "pde: the Euler box does not pin the gauge of an "
                        "equation with a potential (use preissmann)");
  if (scheme->kind == GM_PDE_WAVE_LF && dt > grid->h)
    return gm_error_set(err, GM_EINVAL,
                        "pde: LF step violates the CFL bound dt <= dx (dt = %g, dx = %g)", dt,
                        grid->h);
  for (size_t a = 0; a < d; a++)
    if (!isfinite(grid->twist[a]))
      return gm_error_set(err, GM_EINVAL, "pde: grid twist must be finite");
  if (options->dirichlet_left != 0 || options->dirichlet_right != 0) {
    unsigned all = (1u << d) - 1u;
    int bits = __builtin_popcount(options->dirichlet_left & all) +
               __builtin_popcount(options->dirichlet_right & all);
    if ((options->dirichlet_left | options->dirichlet_right) & ~all)
      return gm_error_set(err, GM_EINVAL, "pde: Dirichlet masks name components past d = %zu", d);
    for (size_t a = 0; a < d; a++)
      if (grid->twist[a] != 0.0)
        return gm_error_set(err, GM_EINVAL, "pde: a twist makes no sense with Dirichlet ends");
    if (scheme->scalar && !((options->dirichlet_left & 1u) && (options->dirichlet_right & 1u)))
      return gm_error_set(err, GM_EINVAL,
                          "pde: Dirichlet ends for '%s' hold u (bit 0) at both ends", scheme->name);
    if (!scheme->scalar && scheme->kind != GM_PDE_PREISSMANN)
      return gm_error_set(err, GM_EINVAL, "pde: Dirichlet ends are not implemented for '%s'",
                          scheme->name);
    if (scheme->kind == GM_PDE_PREISSMANN && (size_t)bits != d)
      return gm_error_set(err, GM_EINVAL,
                          "pde: the Preissmann box with Dirichlet ends needs d = %zu held "
                          "components in all (got %d): they replace the missing cell's equations",
                          d, bits);
    if (eq->has_gauge)
      return gm_error_set(err, GM_EINVAL, "pde: Dirichlet ends with a gauge are not implemented");
  }
  for (size_t k = 0; k < n * d; k++)
    if (!isfinite(s0[k]))
      return gm_error_set(err, GM_EDOMAIN, "pde: initial data not finite at point %zu "
                          "component %zu", k / d, k % d);
  if (scheme->kind == GM_PDE_KDV_ZK) {
    double umax = 0.0;
    for (size_t i = 0; i < n; i++) umax = fmax(umax, fabs(s0[i * d + eq->gauge_u]));
    double bound = gm_pde_zk_bound(grid, umax);
    if (dt > bound)
      return gm_error_set(err, GM_EINVAL,
                          "pde: Zabusky-Kruskal step violates its stability bound "
                          "dt (3 sqrt(3)/(2 dx^3) + max|u|/dx) <= 1 (dt = %g > %g)", dt, bound);
  }
  if (eq->has_gauge && scheme->kind == GM_PDE_PREISSMANN) {
    /* the sum of the w rows at level 0: h Σ ū_{i+½} must close the ring of φ */
    double m = 0.0, mabs = 0.0;
    for (size_t i = 0; i < n; i++) {
      double ub = 0.5 * (s0[i * d + eq->gauge_u] + s0[((i + 1) % n) * d + eq->gauge_u]);
      m += grid->h * ub;
      mabs += grid->h * fabs(ub);
    }
    double tw = grid->twist[eq->gauge_phi];
    if (!(fabs(m - tw) <= 1e-10 * (1.0 + fabs(tw) + mabs)))
      return gm_error_set(err, GM_EINVAL,
                          "pde: the potential's twist (%.17g) must equal the mass h sum of "
                          "(u_i + u_{i+1})/2 (%.17g): the box's Newton system is otherwise "
                          "inconsistent", tw, m);
  }

  gm_pde *p = calloc(1, sizeof *p);
  if (p == NULL) return gm_error_set(err, GM_ENOMEM, "pde: out of memory");
  p->grid = *grid;
  p->eq = *eq;
  p->scheme = scheme;
  p->opt = *options;
  p->d = d;
  p->n = n;
  p->nu = n * d;
  size_t nu = p->nu;
  int ok = 1;
  ok &= (p->s = vec(nu)) != NULL;
  ok &= (p->s_prev = vec(nu)) != NULL;
  ok &= (p->s_new = vec(nu)) != NULL;
  ok &= (p->F = vec(nu)) != NULL;
  ok &= (p->dx = vec(nu)) != NULL;
  ok &= (p->hess = vec(n * d * d)) != NULL;
  ok &= (p->work = vec(8 * d + 8)) != NULL;
  ok &= (p->pos = calloc(n, sizeof *p->pos)) != NULL;
  ok &= (p->msres = vec(n)) != NULL;
  if (scheme->kind == GM_PDE_KDV_ZK) {
    ok &= (p->u_prev = vec(n)) != NULL;
    ok &= (p->u = vec(n)) != NULL;
    ok &= (p->u_new = vec(n)) != NULL;
  } else if (scheme->kind == GM_PDE_GAUSS_PRK) {
    /* 6d unknowns per cell, n/2 cells; the Newton matrix condensed to the node values of the
     * 𝕂-coupled components (2d_f per cell, gauss_prk.c): band 2·2d_f − 1 below, border 2d_f */
    size_t nx = 3 * d * n, df = 0;
    for (size_t a = 0; a < d; a++) {
      int coupled = 0;
      for (size_t b = 0; b < d; b++) coupled |= eq->K[a * d + b] != 0.0 || eq->K[b * d + a] != 0.0;
      df += (size_t)coupled;
    }
    size_t nb = 2 * df, ny = nb * (n / 2);
    ok &= df > 0 && gm_bband_init(&p->gp_band, ny, 2 * nb - 1, 0, nb, nb) == GM_OK;
    ok &= (p->gp_x = vec(nx)) != NULL;
    ok &= (p->gp_F = vec(nx)) != NULL;
    ok &= (p->gp_b = vec(ny > 0 ? ny : 1)) != NULL;
    ok &= (p->gp_cell = vec(16 * d * d + 8 * d * d + 4 * d)) != NULL;
    free(p->F); /* unused: the Newton vectors are gp_x, gp_F */
    free(p->dx);
    p->F = p->dx = NULL;
    free(p->hess); /* one stage's Hessian at a time */
    ok &= (p->hess = vec(d * d)) != NULL;
    if (options->track_variations)
      for (int k = 0; k < 2; k++) {
        ok &= (p->gp_t[k] = vec(nx)) != NULL;
        for (int j = 0; j < 3; j++) ok &= (p->tan[k][j] = vec(nu)) != NULL;
      }
  } else if (!scheme->scalar) {
    ok &= gm_band_init(&p->band, nu, 3 * d - 1, 3 * d - 1) == GM_OK;
    if (scheme->kind == GM_PDE_BOX_SDIRK2)
      for (int k = 0; k < 2; k++) ok &= (p->aux[k] = vec(nu)) != NULL;
    if (options->track_variations && scheme->multisymplectic)
      for (int k = 0; k < 2; k++)
        for (int j = 0; j < 3; j++) ok &= (p->tan[k][j] = vec(nu)) != NULL;
  } else {
    ok &= (p->u_prev = vec(n)) != NULL;
    ok &= (p->u = vec(n)) != NULL;
    ok &= (p->u_new = vec(n)) != NULL;
    if (scheme->kind == GM_PDE_WAVE_MS) ok &= gm_band_init(&p->band, n, 2, 2) == GM_OK;
  }
  if (!ok) {
    gm_pde_free(p);
    return gm_error_set(err, GM_ENOMEM, "pde: out of memory (n = %zu)", n);
  }
  gm_ring_positions(n, p->pos);
  memcpy(p->s, s0, nu * sizeof *s0);
  memcpy(p->s_prev, s0, nu * sizeof *s0); /* Euler box start: sⁿ⁻¹ = s⁰ (docs/pde.md) */
  /* 𝕎₊, 𝕂₊: strictly upper triangles; 𝕎₋ = −𝕎₊ᵀ (the splitting of notes/003-004 §2.2) */
  for (size_t i = 0; i < d; i++)
    for (size_t j = 0; j < d; j++) {
      p->Wp[i * d + j] = j > i ? eq->W[i * d + j] : 0.0;
      p->Wm[i * d + j] = j < i ? eq->W[i * d + j] : 0.0;
      p->Kp[i * d + j] = j > i ? eq->K[i * d + j] : 0.0;
      p->Km[i * d + j] = j < i ? eq->K[i * d + j] : 0.0;
    }
  if (p->tan[0][0] != NULL) {
    unsigned long long x = (unsigned long long)(options->tangent_seed * 1e6) + 12345u;
    for (int k = 0; k < 2; k++)
      for (size_t q = 0; q < nu; q++) {
        double r = lcg(&x);
        p->tan[k][0][q] = p->tan[k][1][q] = r;
      }
    for (int k = 0; k < 2; k++) /* held components: their variations vanish */
      for (size_t a = 0; a < d; a++) {
        if (options->dirichlet_left & (1u << a)) p->tan[k][0][a] = p->tan[k][1][a] = 0.0;
        if (options->dirichlet_right & (1u << a))
          p->tan[k][0][(n - 1) * d + a] = p->tan[k][1][(n - 1) * d + a] = 0.0;
      }
    if (eq->has_gauge) /* the variations of the mass vanish (consistent linearised system) */
      for (int k = 0; k < 2; k++) {
        double mean = 0.0;
        for (size_t i = 0; i < n; i++) mean += p->tan[k][0][i * d + eq->gauge_u] / (double)n;
        for (size_t i = 0; i < n; i++)
          p->tan[k][0][i * d + eq->gauge_u] = p->tan[k][1][i * d + eq->gauge_u] -= mean;
      }
  }
  if (scheme->kind == GM_PDE_GAUSS_PRK) gm_pde_gauss_init(p);
  if (scheme->scalar || scheme->kind == GM_PDE_KDV_ZK) {
    st = scheme->scalar ? gm_pde_wave_start(p, err) : gm_pde_zk_start(p, err);
    if (st != GM_OK) {
      gm_pde_free(p);
      return st;
    }
  }
  *out = p;
  return GM_OK;
}

gm_status gm_pde_add_observer(gm_pde *p, size_t every, gm_pde_observer_fn fn, void *ctx,
                              gm_error *err) {
  if (p == NULL || fn == NULL) return gm_error_set(err, GM_EINVAL, "pde: NULL observer");
  if (every == 0) return gm_error_set(err, GM_EINVAL, "pde: observer interval must be >= 1");
  if (p->n_observers == GM_PDE_MAX_OBSERVERS)
    return gm_error_set(err, GM_EINVAL, "pde: at most %d observers", GM_PDE_MAX_OBSERVERS);
  p->observers[p->n_observers++] = (struct gm_pde_observer){every, fn, ctx};
  return GM_OK;
}

gm_status gm_pde_advance(gm_pde *p, size_t n_steps, gm_error *err) {
  if (p == NULL) return gm_error_set(err, GM_EINVAL, "pde: NULL solver");
  for (size_t k = 0; k < n_steps; k++) {
    gm_status st = p->scheme->scalar                    ? gm_pde_wave_step(p, err)
                   : p->scheme->kind == GM_PDE_KDV_ZK ? gm_pde_zk_step(p, err)
                                                      : gm_pde_box_step(p, err);
    if (st != GM_OK) return st;
    p->steps++;
    p->stats.steps++;
    for (size_t o = 0; o < p->n_observers; o++)
      if (p->steps % p->observers[o].every == 0 &&
          p->observers[o].fn(p, p->observers[o].ctx) != 0)
        return gm_error_set(err, GM_ECALLBACK, "pde: observer %zu stopped the run at step %zu",
                            o, p->steps);
  }
  return GM_OK;
}

size_t gm_pde_steps(const gm_pde *p) { return p->steps; }
double gm_pde_time(const gm_pde *p) { return (double)p->steps * p->opt.dt; }
size_t gm_pde_dim(const gm_pde *p) { return p->d; }
size_t gm_pde_n(const gm_pde *p) { return p->n; }
const double *gm_pde_state(const gm_pde *p) { return p->s; }
gm_pde_stats gm_pde_get_stats(const gm_pde *p) { return p->stats; }

/* (δ_x⁺s_i)ᵀ M s_i summed: the densities of (35) and (36) */
static double quad_sum(const gm_pde *p, const double *M) {
  size_t n = p->n, d = p->d;
  double sum = 0.0;
  for (size_t i = 0; i < n; i++) {
    const double *si = p->s + i * d;
    if (i == n - 1 && gm_pde_dirichlet(p)) break; /* no cell past the right end */
    for (size_t a = 0; a < d; a++)
      for (size_t b = 0; b < d; b++)
        sum += (gm_pde_at(p, p->s, i, 1, a) - si[a]) / p->grid.h * M[a * d + b] * si[b];
  }
  return sum;
}

double gm_pde_point_x(const gm_pde_scheme *scheme, const gm_pde_grid *grid, size_t i) {
  if (scheme != NULL && scheme->kind == GM_PDE_GAUSS_PRK) return gm_pde_gauss_point_x(grid, i);
  return grid->x0 + (double)i * grid->h;
}

double gm_pde_energy(const gm_pde *p) {
  if (p->scheme->kind == GM_PDE_GAUSS_PRK && !p->eq.is_kdv) return NAN; /* not implemented */
  if (p->eq.is_kdv) return gm_pde_kdv_energy(p);
  if (p->scheme->scalar) return gm_pde_wave_energy(p);
  double e = 0.0;
  for (size_t i = 0; i < p->n; i++) e += p->eq.S(p->s + i * p->d, p->eq.params);
  return p->grid.h * (e + 0.5 * quad_sum(p, p->eq.K));
}

double gm_pde_momentum(const gm_pde *p) {
  if (p->scheme->kind == GM_PDE_GAUSS_PRK && !p->eq.is_kdv) return NAN; /* not implemented */
  if (p->eq.is_kdv) return gm_pde_kdv_momentum(p);
  if (p->scheme->scalar) return gm_pde_wave_momentum(p);
  return p->grid.h * 0.5 * quad_sum(p, p->eq.W);
}

double gm_pde_norm(const gm_pde *p) {
  if (!p->eq.has_norm) return NAN;
  size_t n = p->n, d = p->d, a = p->eq.norm_a, b = p->eq.norm_b;
  double sum = 0.0;
  for (size_t i = 0; i < n; i++) {
    const double *si = p->s + i * d, *sj = p->s + ((i + 1) % n) * d;
    if (p->scheme->scalar || p->scheme->kind == GM_PDE_GAUSS_PRK) {
      sum += si[a] * si[a] + si[b] * si[b]; /* gauss-prk: Gauss quadrature, b_j H = h */
    } else {
      if (i == n - 1 && gm_pde_dirichlet(p)) break;
      double re = 0.5 * (si[a] + sj[a]), im = 0.5 * (si[b] + sj[b]);
      sum += re * re + im * im;
    }
  }
  return p->grid.h * sum;
}

double gm_pde_ms_residual(const gm_pde *p, double *rel) {
  if (!p->ms_valid) return -1.0;
  double m = 0.0;
  for (size_t i = 0; i < p->n; i++) {
    if (rel != NULL) rel[i] = p->msres[i];
    if (p->msres[i] > m) m = p->msres[i];
  }
  return m;
}

/* (δ_x⁺ s)ᵀ M s̄ over cell i+½ of level x, and (δ_t⁺ s_i)ᵀ M s^{n+½}_i at node i */
static double cell_quad(const gm_pde *p, const double *x, size_t i, const double *M) {
  size_t d = p->d;
  double r = 0.0;
  for (size_t a = 0; a < d; a++)
    for (size_t b = 0; b < d; b++)
      r += (gm_pde_at(p, x, i, 1, a) - x[i * d + a]) / p->grid.h * M[a * d + b] * 0.5 *
           (x[i * d + b] + gm_pde_at(p, x, i, 1, b));
  return r;
}
/* at node i + shift (shift 0 or 1), on the twisted ring */
static double node_quad(const gm_pde *p, const double *x0, const double *x1, size_t i,
                        int shift, const double *M) {
  size_t d = p->d;
  double r = 0.0;
  for (size_t a = 0; a < d; a++)
    for (size_t b = 0; b < d; b++)
      r += (gm_pde_at(p, x1, i, shift, a) - gm_pde_at(p, x0, i, shift, a)) / p->opt.dt *
           M[a * d + b] * 0.5 * (gm_pde_at(p, x0, i, shift, b) + gm_pde_at(p, x1, i, shift, b));
  return r;
}

double gm_pde_cell_energy(const gm_pde *p) {
  if (p == NULL || p->scheme->scalar || p->scheme->kind == GM_PDE_GAUSS_PRK) return NAN;
  size_t n = p->n, d = p->d;
  double e = 0.0, bar[GM_PDE_MAX_DIM];
  for (size_t i = 0; i + (gm_pde_dirichlet(p) ? 1 : 0) < n; i++) {
    for (size_t a = 0; a < d; a++) bar[a] = 0.5 * (p->s[i * d + a] + gm_pde_at(p, p->s, i, 1, a));
    e += p->eq.S(bar, p->eq.params) + 0.5 * cell_quad(p, p->s, i, p->eq.K);
  }
  return p->grid.h * e;
}

double gm_pde_cell_momentum(const gm_pde *p) {
  if (p == NULL || p->scheme->scalar || p->scheme->kind == GM_PDE_GAUSS_PRK) return NAN;
  double m = 0.0;
  for (size_t i = 0; i + (gm_pde_dirichlet(p) ? 1 : 0) < p->n; i++)
    m += 0.5 * cell_quad(p, p->s, i, p->eq.W);
  return p->grid.h * m;
}

gm_status gm_pde_local_residuals(const gm_pde *p, double *energy, double *momentum) {
  if (p == NULL || p->scheme->scalar || p->scheme->kind == GM_PDE_KDV_ZK ||
      p->scheme->kind == GM_PDE_GAUSS_PRK || p->steps == 0)
    return GM_EUNSUPPORTED;
  size_t n = p->n, d = p->d;
  const double *x0 = p->s_prev, *x1 = p->s; /* sⁿ and sⁿ⁺¹ of the last step */
  double bar[GM_PDE_MAX_DIM];
  const void *c = p->eq.params;
  for (size_t i = 0; i < n; i++) {
    if (i == n - 1 && gm_pde_dirichlet(p)) { /* no cell past the right end */
      if (energy != NULL) energy[i] = 0.0;
      if (momentum != NULL) momentum[i] = 0.0;
      break;
    }
    double Sbar[2], Smid[2];
    const double *lv[2] = {x0, x1};
    for (int l = 0; l < 2; l++) {
      for (size_t a = 0; a < d; a++)
        bar[a] = 0.5 * (lv[l][i * d + a] + gm_pde_at(p, lv[l], i, 1, a));
      Sbar[l] = p->eq.S(bar, c);
    }
    for (int l = 0; l < 2; l++) {
      for (size_t a = 0; a < d; a++)
        bar[a] = 0.5 * (gm_pde_at(p, x0, i, l, a) + gm_pde_at(p, x1, i, l, a));
      Smid[l] = p->eq.S(bar, c);
    }
    if (energy != NULL) {
      double e1 = Sbar[1] + 0.5 * cell_quad(p, x1, i, p->eq.K);
      double e0 = Sbar[0] + 0.5 * cell_quad(p, x0, i, p->eq.K);
      double fj = -0.5 * node_quad(p, x0, x1, i, 1, p->eq.K);
      double fi = -0.5 * node_quad(p, x0, x1, i, 0, p->eq.K);
      energy[i] = (e1 - e0) / p->opt.dt + (fj - fi) / p->grid.h;
    }
    if (momentum != NULL) {
      double m1 = 0.5 * cell_quad(p, x1, i, p->eq.W), m0 = 0.5 * cell_quad(p, x0, i, p->eq.W);
      double gj = -0.5 * node_quad(p, x0, x1, i, 1, p->eq.W) - Smid[1];
      double gi = -0.5 * node_quad(p, x0, x1, i, 0, p->eq.W) - Smid[0];
      momentum[i] = (m1 - m0) / p->opt.dt + (gj - gi) / p->grid.h;
    }
  }
  return GM_OK;
}
