/* Creating a Yee solver: layout, Hodge-star coefficients, update ranges from the boundaries,
 * the CFL check, Bloch phases, CPML (yee_cpml.c) and the kernel choice. All allocation of the
 * time loop happens here. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "fields/internal.h"

gm_status yee_grid_check(const gm_yee_grid *grid, gm_error *err);

gm_cpml gm_cpml_defaults(void) {
  return (gm_cpml){.thickness = 10, .grading = 3.0, .sigma_max = 0.0, .sigma_factor = 1.0,
                   .kappa_max = 1.0, .alpha_max = 0.05, .alpha_grading = 1.0};
}

gm_yee_options gm_yee_defaults(void) {
  gm_yee_options o;
  memset(&o, 0, sizeof o);
  o.dt = 0.0;
  o.courant = 0.99;
  for (int f = 0; f < 6; ++f) {
    o.boundary[f].kind = GM_BOUNDARY_PEC;
    o.boundary[f].pml = gm_cpml_defaults();
  }
  return o;
}

gm_status gm_yee_courant_limit(const gm_yee_grid *grid, const gm_yee_materials *materials,
                               double *dt_max, gm_error *err) {
  gm_status st = yee_grid_check(grid, err);
  if (st != GM_OK) return st;
  double min_em = 1.0;
  if (materials != NULL) {
    min_em = INFINITY;
    for (size_t c = 0; c < materials->n_cells; ++c)
      min_em = fmin(min_em, materials->epsilon[c] * materials->mu[c]);
    min_em = fmin(min_em, yee_geometry_min_em(materials)); /* smoothing mixes in shapes' media */
  }
  double s = 0.0;
  for (size_t a = 0; a < gm_yee_dim_axes(grid->dim); ++a) s += 1.0 / (grid->h[a] * grid->h[a]);
  /* Taflove & Hagness eq. 4.52: c Δt <= 1/sqrt(Σ 1/h²), with the fastest medium's c. */
  *dt_max = sqrt(min_em) / sqrt(s);
  return GM_OK;
}

/* Cells next to a location along one axis: both neighbours (index−1, index) on a node axis,
 * the one cell on a staggered axis; out-of-range cells dropped or wrapped (periodic). */
size_t yee_cells_along(const gm_yee_layout *L, const int periodic[3], int a, long idx, int node,
                       long out[2]) {
  const long n = (long)L->n[a];
  if (L->extent[a] == 1) {
    out[0] = 0;
    return 1;
  }
  if (!node) {
    out[0] = idx;
    return 1;
  }
  size_t m = 0;
  for (long c = idx - 1; c <= idx; ++c) {
    long w = c;
    if (periodic[a]) w = ((c % n) + n) % n;
    if (w >= 0 && w < n) out[m++] = w;
  }
  if (periodic[a] && m == 2 && out[0] == out[1]) m = 1;
  return m;
}

static double cell_mean(const gm_yee_layout *L, const int periodic[3], const long ijk[3],
                        const int node[3], const double *cell, int inverse) {
  long cx[2], cy[2], cz[2];
  const size_t nx = yee_cells_along(L, periodic, 0, ijk[0], node[0], cx);
  const size_t ny = yee_cells_along(L, periodic, 1, ijk[1], node[1], cy);
  const size_t nz = yee_cells_along(L, periodic, 2, ijk[2], node[2], cz);
  double sum = 0.0;
  for (size_t c = 0; c < nz; ++c)
    for (size_t b = 0; b < ny; ++b)
      for (size_t a = 0; a < nx; ++a) {
        const double v = cell[(size_t)cx[a] + L->n[0] * ((size_t)cy[b] + L->n[1] * (size_t)cz[c])];
        sum += inverse ? 1.0 / v : v;
      }
  return sum / (double)(nx * ny * nz);
}

void yee_edge_average(const gm_yee_layout *L, const int periodic[3], int axis, long i, long j,
                      long k, const double *cell, double *mean) {
  const long ijk[3] = {i, j, k};
  int node[3] = {1, 1, 1};
  node[axis] = 0;
  *mean = cell_mean(L, periodic, ijk, node, cell, 0);
}

void yee_face_average_inverse(const gm_yee_layout *L, const int periodic[3], int axis, long i,
                              long j, long k, const double *cell, double *mean_inverse) {
  const long ijk[3] = {i, j, k};
  int node[3] = {0, 0, 0};
  node[axis] = 1;
  *mean_inverse = cell_mean(L, periodic, ijk, node, cell, 1);
}

double yee_eps_edge(const gm_yee *s, int c, long i, long j, long k) {
  if (s->eps_cell == NULL) return s->eps0;
  if (s->aniso) { /* an edge whose E is ε̃⁻¹ D with off-diagonal terms: ε̃⁻¹_aa */
    const double e = yee_aniso_eps(s, c, yee_idx(&s->L, i, j, k));
    if (e > 0) return e;
  }
  if (s->smoothed) { /* invert cb = Δt/(ε (1 + a)), ca = (1 − a)/(1 + a) */
    const size_t q = yee_idx(&s->L, i, j, k);
    const double a = s->ca[c] ? (1.0 - s->ca[c][q]) / (1.0 + s->ca[c][q]) : 0.0;
    return s->dt / (s->cb[c][q] * (1.0 + a));
  }
  double m;
  yee_edge_average(&s->L, s->periodic, c, i, j, k, s->eps_cell, &m);
  return m;
}

double yee_mu_face(const gm_yee *s, int c, long i, long j, long k) {
  if (s->mu_cell == NULL) return s->mu0;
  double m;
  yee_face_average_inverse(&s->L, s->periodic, c - 3, i, j, k, s->mu_cell, &m);
  return 1.0 / m;
}

void gm_yee_component_shift(gm_yee_dim dim, gm_yee_component c, double shift[3]) {
  const size_t axes = gm_yee_dim_axes(dim);
  for (size_t a = 0; a < 3; ++a) {
    const int staggered = yee_is_e((int)c) ? (int)a == (int)c : (int)a != (int)c - 3;
    shift[a] = (a < axes && staggered) ? 0.5 : 0.0;
  }
}

void gm_yee_component_count(const gm_yee_layout *L, gm_yee_component c, size_t count[3]) {
  double sh[3];
  gm_yee_component_shift(L->dim, c, sh);
  for (int a = 0; a < 3; ++a)
    count[a] = L->extent[a] == 1 ? 1 : (sh[a] > 0.0 ? L->n[a] : L->n[a] + 1);
}

size_t gm_yee_index(const gm_yee_layout *L, long i, long j, long k) { return yee_idx(L, i, j, k); }

static int face_is_wall(const gm_yee_options *o, int f) {
  return o->boundary[f].kind == GM_BOUNDARY_PEC || o->boundary[f].kind == GM_BOUNDARY_CPML;
}

/* Which locations each component's update loop covers: tangential E on PEC (and CPML-backing)
 * walls stays 0 and is skipped; on periodic axes the last node is a copy of the first. */
static void update_ranges(gm_yee *s) {
  for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
    size_t count[3];
    gm_yee_component_count(&s->L, (gm_yee_component)c, count);
    double sh[3];
    gm_yee_component_shift(s->L.dim, (gm_yee_component)c, sh);
    for (int a = 0; a < 3; ++a) {
      size_t lo = 0, hi = count[a]; /* [lo, hi) */
      if (s->L.extent[a] > 1 && sh[a] == 0.0) {
        if (s->periodic[a]) {
          hi = s->L.n[a];
        } else if (yee_is_e(c)) {
          if (face_is_wall(&s->opt, 2 * a)) lo = 1;
          if (face_is_wall(&s->opt, 2 * a + 1)) hi = s->L.n[a];
        }
      }
      s->upd[c].lo[a] = lo;
      s->upd[c].cnt[a] = hi > lo ? hi - lo : 0;
    }
  }
}

static gm_status fail_create(gm_yee *s, gm_error *err, gm_status st, const char *msg) {
  gm_error_set(err, st, "%s", msg);
  gm_yee_free(s);
  return st;
}

static double *alloc_array(gm_yee *s) { return calloc(s->L.size, sizeof(double)); }

gm_status gm_yee_create(const gm_yee_grid *grid, const gm_yee_materials *materials,
                        const gm_yee_options *options, gm_yee **out, gm_error *err) {
  return yee_create_with(grid, materials, options, 0, out, err);
}

gm_status yee_create_with(const gm_yee_grid *grid, const gm_yee_materials *materials,
                          const gm_yee_options *options, int cell_coefficients, gm_yee **out,
                          gm_error *err) {
  return yee_create_view(grid, materials, options, cell_coefficients, NULL, out, err);
}

gm_status yee_create_view(const gm_yee_grid *grid, const gm_yee_materials *materials,
                          const gm_yee_options *options, int cell_coefficients,
                          const yee_view *view, gm_yee **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "yee: NULL output");
  *out = NULL;
  gm_status st = yee_grid_check(grid, err);
  if (st != GM_OK) return st;
  const gm_yee_options o = options ? *options : gm_yee_defaults();
  const size_t axes = gm_yee_dim_axes(grid->dim);
  static const char an[3] = {'x', 'y', 'z'};
  if (materials != NULL) {
    for (size_t a = 0; a < axes; ++a)
      if (materials->grid.dim != grid->dim || materials->grid.n[a] != grid->n[a])
        return gm_error_set(err, GM_EINVAL, "yee: the materials were made for another grid");
  }
  /* boundaries */
  for (size_t a = 0; a < axes; ++a) {
    const gm_yee_boundary_kind lo = o.boundary[2 * a].kind, hi = o.boundary[2 * a + 1].kind;
    for (int f = 0; f < 2; ++f) {
      const gm_yee_boundary_kind kf = o.boundary[2 * a + f].kind;
      if ((unsigned)kf > GM_BOUNDARY_CPML)
        return gm_error_set(err, GM_EINVAL, "yee: unknown boundary kind %d on face %c%s",
                            (int)kf, f ? '+' : '-', (char[]){an[a], 0});
    }
    if ((lo == GM_BOUNDARY_PERIODIC) != (hi == GM_BOUNDARY_PERIODIC))
      return gm_error_set(err, GM_EINVAL,
                          "yee: periodic boundary on one %c face only: both must be periodic",
                          an[a]);
    size_t thick = 0;
    for (int f = 0; f < 2; ++f) {
      const gm_yee_boundary *b = &o.boundary[2 * a + f];
      if (b->kind != GM_BOUNDARY_CPML) continue;
      const gm_cpml *p = &b->pml;
      if (p->thickness == 0)
        return gm_error_set(err, GM_EINVAL, "yee: CPML on face %c%c has thickness 0",
                            f ? '+' : '-', an[a]);
      if (!(p->grading >= 0.0) || !isfinite(p->grading) || !(p->kappa_max >= 1.0) ||
          !isfinite(p->kappa_max) || !(p->alpha_max >= 0.0) || !isfinite(p->alpha_max) ||
          !isfinite(p->sigma_max) || !(p->alpha_grading >= 0.0) ||
          !isfinite(p->alpha_grading) || !(p->sigma_factor >= 0.0) ||
          !isfinite(p->sigma_factor))
        return gm_error_set(err, GM_EINVAL,
                            "yee: CPML on face %c%c: need grading >= 0, kappa_max >= 1, "
                            "alpha_max >= 0, alpha_grading >= 0, sigma_factor >= 0, all finite",
                            f ? '+' : '-', an[a]);
      thick += p->thickness;
    }
    if (thick >= grid->n[a])
      return gm_error_set(err, GM_EINVAL,
                          "yee: CPML layers along %c (%zu cells together) leave no interior in "
                          "a grid of %zu cells",
                          an[a], thick, grid->n[a]);
  }
  for (size_t a = 0; a < 3; ++a) {
    if (!isfinite(o.bloch_k[a]))
      return gm_error_set(err, GM_EINVAL, "yee: Bloch k along %c is not finite", an[a]);
    if (o.bloch_k[a] != 0.0 && (a >= axes || o.boundary[2 * a].kind != GM_BOUNDARY_PERIODIC))
      return gm_error_set(err, GM_EINVAL, "yee: Bloch k along %c needs periodic %c faces", an[a],
                          an[a]);
  }
  if (o.sweep != GM_YEE_SWEEP_AUTO && o.sweep != GM_YEE_SWEEP_HALF_STEPS)
    return gm_error_set(err, GM_EINVAL, "yee: sweep must be auto (0) or half-steps (1) (got %d)",
                        (int)o.sweep);
  /* CFL */
  double dt_max;
  st = gm_yee_courant_limit(grid, materials, &dt_max, err);
  if (st != GM_OK) return st;
  double dt = o.dt;
  if (isnan(dt) || isinf(dt)) return gm_error_set(err, GM_EINVAL, "yee: dt is not finite");
  if (dt <= 0.0) {
    if (!(o.courant > 0.0 && o.courant <= 1.0))
      return gm_error_set(err, GM_EINVAL, "yee: courant fraction must be in (0, 1] (got %g)",
                          o.courant);
    dt = o.courant * dt_max;
  }
  if (dt > dt_max)
    return gm_error_set(err, GM_EINVAL,
                        "yee: time step %.17g is above the Courant limit %.17g of this grid "
                        "(dt <= 1/(c_max sqrt(sum 1/h^2)))",
                        dt, dt_max);

  {
    const int complex_fields = o.bloch_k[0] != 0.0 || o.bloch_k[1] != 0.0 || o.bloch_k[2] != 0.0;
    char what[160];
    snprintf(what, sizeof what, "yee: the field and coefficient arrays of %zu x %zu x %zu cells",
             axes > 0 ? grid->n[0] : 1, axes > 1 ? grid->n[1] : 1, axes > 2 ? grid->n[2] : 1);
    st = yee_memory_check(yee_grid_bytes(grid, complex_fields), what, err);
    if (st != GM_OK) return st;
  }
  gm_yee *s = calloc(1, sizeof *s);
  if (s == NULL) return gm_error_set(err, GM_ENOMEM, "yee: out of memory");
  s->opt = o;
  s->opt.dt = dt;
  s->dt = dt;
  s->n_axes = (int)axes;
#ifdef _OPENMP
  s->n_threads = o.n_threads > 0 ? o.n_threads : omp_get_max_threads();
#else
  s->n_threads = 1;
#endif
  gm_yee_layout *L = &s->L;
  L->dim = grid->dim;
  size_t stride = 1;
  for (size_t a = 0; a < 3; ++a) {
    const int present = a < axes;
    L->n[a] = present ? grid->n[a] : 1;
    L->h[a] = present ? grid->h[a] : 1.0;
    L->origin[a] = grid->origin[a];
    L->extent[a] = present ? grid->n[a] + 2 : 1;
    L->offset[a] = present ? 1 : 0;
    L->stride[a] = stride;
    s->s[a] = present ? (long)stride : 0;
    stride *= L->extent[a];
    s->periodic[a] = present && o.boundary[2 * a].kind == GM_BOUNDARY_PERIODIC;
    s->phase_cos[a] = cos(o.bloch_k[a] * (double)L->n[a] * L->h[a]);
    s->phase_sin[a] = sin(o.bloch_k[a] * (double)L->n[a] * L->h[a]);
  }
  L->size = stride;
  s->n_parts = (o.bloch_k[0] != 0.0 || o.bloch_k[1] != 0.0 || o.bloch_k[2] != 0.0) ? 2 : 1;
  L->complex_fields = s->n_parts == 2;
  s->zeros = alloc_array(s);
  if (s->zeros == NULL) return fail_create(s, err, GM_ENOMEM, "yee: out of memory");
  for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
    s->active[c] = gm_yee_dim_has(L->dim, (gm_yee_component)c);
    for (int p = 0; p < s->n_parts; ++p) {
      s->f[p][c] = s->active[c] ? alloc_array(s) : s->zeros;
      if (s->f[p][c] == NULL) return fail_create(s, err, GM_ENOMEM, "yee: out of memory for fields");
    }
  }
  update_ranges(s);

  /* Hodge-star coefficients */
  s->uniform = !(cell_coefficients && materials != NULL);
  s->lossy = 0;
  s->eps0 = s->mu0 = 1.0;
  double sigma0 = 0.0;
  if (materials != NULL) {
    s->eps0 = materials->epsilon[0];
    s->mu0 = materials->mu[0];
    sigma0 = materials->sigma[0];
    for (size_t c = 0; c < materials->n_cells; ++c) {
      if (materials->epsilon[c] != s->eps0 || materials->mu[c] != s->mu0 ||
          materials->sigma[c] != sigma0)
        s->uniform = 0;
      if (materials->sigma[c] != 0.0) s->lossy = 1;
    }
    /* a block smooths when the whole grid does (its own cells may be uniform) */
    const gm_yee_materials *gm = view ? view->materials : materials;
    int whole_uniform = view ? 1 : s->uniform;
    if (view != NULL)
      for (size_t c = 1; c < gm->n_cells && whole_uniform; ++c)
        whole_uniform = gm->epsilon[c] == gm->epsilon[0] && gm->mu[c] == gm->mu[0] &&
                        gm->sigma[c] == gm->sigma[0];
    s->smoothed = o.smoothing == GM_YEE_SMOOTHING_ANISOTROPIC &&
                  (!whole_uniform || yee_geometry_has_shapes(gm));
    if (s->smoothed) s->uniform = 0;
    if (s->smoothed && yee_geometry_lossy(gm)) s->lossy = 1;
    s->view = view;
  }
  if (s->uniform) {
    const double a = sigma0 * dt / (2.0 * s->eps0);
    s->ca0 = (1.0 - a) / (1.0 + a);
    for (int c = 0; c < 3; ++c) s->cb0[c] = dt / s->eps0 / (1.0 + a);
    for (int c = 3; c < 6; ++c) s->cb0[c] = dt / s->mu0;
  } else {
    const size_t nc = materials->n_cells;
    s->eps_cell = malloc(nc * sizeof(double));
    s->mu_cell = malloc(nc * sizeof(double));
    if (s->eps_cell == NULL || s->mu_cell == NULL)
      return fail_create(s, err, GM_ENOMEM, "yee: out of memory");
    memcpy(s->eps_cell, materials->epsilon, nc * sizeof(double));
    memcpy(s->mu_cell, materials->mu, nc * sizeof(double));
    for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
      if (!s->active[c]) continue;
      s->cb[c] = alloc_array(s);
      if (s->cb[c] == NULL) return fail_create(s, err, GM_ENOMEM, "yee: out of memory");
      if (c < 3 && s->lossy) {
        s->ca[c] = alloc_array(s);
        if (s->ca[c] == NULL) return fail_create(s, err, GM_ENOMEM, "yee: out of memory");
      }
      size_t cnt[3];
      gm_yee_component_count(L, (gm_yee_component)c, cnt);
      for (size_t k = 0; k < cnt[2]; ++k)
        for (size_t j = 0; j < cnt[1]; ++j)
          for (size_t i = 0; i < cnt[0]; ++i) {
            const size_t q = yee_idx(L, (long)i, (long)j, (long)k);
            if (c < 3) {
              double eps, sig;
              const long ijk[3] = {(long)i, (long)j, (long)k};
              long g[3];
              yee_view_index(s, ijk, g);
              if (s->smoothed) {
                yee_smooth_edge(yee_view_materials(s, materials), yee_view_layout(s),
                                yee_view_periodic(s), c, g[0], g[1], g[2], &eps,
                                &sig);
              } else {
                yee_edge_average(L, s->periodic, c, (long)i, (long)j, (long)k,
                                 materials->epsilon, &eps);
                yee_edge_average(L, s->periodic, c, (long)i, (long)j, (long)k,
                                 materials->sigma, &sig);
              }
              const double a = sig * dt / (2.0 * eps);
              s->cb[c][q] = dt / eps / (1.0 + a);
              if (s->ca[c]) s->ca[c][q] = (1.0 - a) / (1.0 + a);
            } else {
              double inv_mu;
              const long ijk[3] = {(long)i, (long)j, (long)k};
              long g[3];
              yee_view_index(s, ijk, g);
              if (s->smoothed)
                yee_smooth_face(yee_view_materials(s, materials), yee_view_layout(s),
                                yee_view_periodic(s), c, g[0], g[1], g[2], &inv_mu);
              else
                yee_face_average_inverse(L, s->periodic, c - 3, (long)i, (long)j, (long)k,
                                         materials->mu, &inv_mu);
              s->cb[c][q] = dt * inv_mu;
            }
          }
    }
  }
  st = yee_dispersive_setup(s, materials, err); /* before the coupling: it skips these edges */
  if (st != GM_OK) {
    gm_yee_free(s);
    return st;
  }
  st = yee_aniso_setup(s, materials, err);
  s->view = NULL; /* borrowed for the set-up only */
  if (st != GM_OK) {
    gm_yee_free(s);
    return st;
  }
  /* 1/(κh) per axis and position (κ = 1 outside CPML layers; yee_cpml_setup grades it) */
  for (int a = 0; a < 3; ++a) {
    s->inv_e[a] = calloc(L->extent[a], sizeof(double));
    s->inv_h[a] = calloc(L->extent[a], sizeof(double));
    if (s->inv_e[a] == NULL || s->inv_h[a] == NULL)
      return fail_create(s, err, GM_ENOMEM, "yee: out of memory");
    if (L->extent[a] == 1) continue; /* absent axis: 0 */
    for (size_t q = 0; q < L->extent[a]; ++q) s->inv_e[a][q] = s->inv_h[a][q] = 1.0 / L->h[a];
  }
  st = yee_cpml_setup(s, err);
  if (st != GM_OK) {
    gm_yee_free(s);
    return st;
  }
  yee_select_kernels(s);
  *out = s;
  return GM_OK;
}

void gm_yee_free(gm_yee *s) {
  if (s == NULL) return;
  yee_aniso_free(s);
  yee_dispersive_free(s);
  for (int p = 0; p < 2; ++p)
    for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c)
      if (s->f[p][c] != s->zeros) free(s->f[p][c]);
  free(s->zeros);
  for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) free(s->cb[c]);
  for (int c = 0; c < 3; ++c) free(s->ca[c]);
  free(s->eps_cell);
  free(s->mu_cell);
  for (int a = 0; a < 3; ++a) {
    free(s->inv_e[a]);
    free(s->inv_h[a]);
    free(s->cpml_be[a]);
    free(s->cpml_ce[a]);
    free(s->cpml_bh[a]);
    free(s->cpml_ch[a]);
  }
  for (size_t t = 0; t < s->n_cpml; ++t) {
    free(s->cpml[t].psi);
    free(s->cpml[t].w);
  }
  free(s->cpml);
  for (size_t i = 0; i < s->n_sources; ++i) {
    free(s->sources[i].index);
    free(s->sources[i].coef);
    free(s->sources[i].vertex);
    free(s->sources[i].rho);
    free(s->sources[i].drho);
  }
  free(s->sources);
  for (size_t i = 0; i < s->n_probes; ++i) {
    free(s->probes[i].t);
    free(s->probes[i].re);
    free(s->probes[i].im);
  }
  free(s->probes);
  free(s->observers);
  for (size_t i = 0; i < s->n_tfsf; ++i) yee_tfsf_free(&s->tfsf[i]);
  free(s->tfsf);
  free(s);
}

const char *gm_yee_errmsg(const gm_yee *s) { return s ? s->errmsg : ""; }
void gm_yee_get_layout(const gm_yee *s, gm_yee_layout *layout) { *layout = s->L; }
size_t gm_yee_step(const gm_yee *s) { return s->step; }
double gm_yee_dt(const gm_yee *s) { return s->dt; }
double gm_yee_time_h(const gm_yee *s) { return (double)s->step * s->dt; }
double gm_yee_time_e(const gm_yee *s) { return ((double)s->step - 0.5) * s->dt; }

const double *gm_yee_field(const gm_yee *s, gm_yee_component c, int part) {
  if (s == NULL || (unsigned)c >= GM_YEE_N_COMPONENTS || !s->active[c]) return NULL;
  if (part < 0 || part >= s->n_parts) return NULL;
  return s->f[part][c];
}

size_t gm_yee_memory(const gm_yee *s, size_t *n_arrays) {
  size_t arrays = 1; /* zeros */
  for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
    if (s->active[c]) arrays += (size_t)s->n_parts;
    if (s->cb[c]) ++arrays;
  }
  for (int c = 0; c < 3; ++c)
    if (s->ca[c]) ++arrays;
  size_t bytes = sizeof *s + arrays * s->L.size * sizeof(double);
  if (s->eps_cell) bytes += 2 * s->L.n[0] * s->L.n[1] * s->L.n[2] * sizeof(double);
  for (int a = 0; a < 3; ++a) bytes += 2 * s->L.extent[a] * sizeof(double);
  for (size_t t = 0; t < s->n_cpml; ++t)
    bytes += 2 * s->cpml[t].box.cnt[0] * s->cpml[t].box.cnt[1] * s->cpml[t].box.cnt[2] *
             sizeof(double);
  for (size_t i = 0; i < s->n_probes; ++i)
    bytes += (2 + (size_t)(s->n_parts == 2)) * s->probes[i].capacity * sizeof(double);
  if (n_arrays) *n_arrays = arrays;
  return bytes;
}
