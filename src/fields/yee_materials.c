/* Materials: ε, μ, σ per cell, painted from shapes (a cell takes the medium when its centre is
 * inside). The solver turns them into edge and face Hodge-star coefficients at create time. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fields/internal.h"

gm_status yee_grid_check(const gm_yee_grid *grid, gm_error *err);

gm_medium gm_medium_vacuum(void) { return (gm_medium){1.0, 1.0, 0.0}; }

gm_status yee_grid_check(const gm_yee_grid *grid, gm_error *err) {
  if (grid == NULL) return gm_error_set(err, GM_EINVAL, "grid: NULL");
  const size_t axes = gm_yee_dim_axes(grid->dim);
  if (axes == 0) return gm_error_set(err, GM_EINVAL, "grid: unknown dimension %d", (int)grid->dim);
  static const char names[3] = {'x', 'y', 'z'};
  for (size_t a = 0; a < axes; ++a) {
    if (grid->n[a] == 0)
      return gm_error_set(err, GM_EINVAL, "grid: zero cells along %c", names[a]);
    if (!(grid->h[a] > 0.0) || !isfinite(grid->h[a]))
      return gm_error_set(err, GM_EINVAL, "grid: cell size along %c must be > 0 and finite (got %g)",
                          names[a], grid->h[a]);
    if (grid->n[a] > ((size_t)1 << 24))
      return gm_error_set(err, GM_EINVAL, "grid: %zu cells along %c is too many", grid->n[a],
                          names[a]);
  }
  for (size_t a = 0; a < 3; ++a)
    if (!isfinite(grid->origin[a]))
      return gm_error_set(err, GM_EINVAL, "grid: origin is not finite");
  return GM_OK;
}

/* A medium's values must be positive and within 1e±100 (sigma up to 1e100): the solver forms
 * sums and products of neighbouring cells' values (edge averages, σΔt/2ε, ε|E|²), which
 * overflow to inf or NaN near the limits of a double (ε = 1e308 gave an energy of NaN). */
#define MEDIUM_MAX 1e100
#define MEDIUM_MIN 1e-100

static gm_status medium_check(gm_yee_materials *m, const gm_medium *md) {
  if (md == NULL) return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "medium: NULL");
  const double v[2] = {md->epsilon, md->mu};
  static const char *const name[2] = {"epsilon", "mu"};
  for (int k = 0; k < 2; ++k)
    if (!(v[k] >= MEDIUM_MIN && v[k] <= MEDIUM_MAX))
      return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                     "medium: %s must be in [%g, %g] (got %g)", name[k], MEDIUM_MIN,
                     MEDIUM_MAX, v[k]);
  if (!(md->sigma >= 0.0 && md->sigma <= MEDIUM_MAX))
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                   "medium: sigma must be in [0, %g] (got %g)", MEDIUM_MAX, md->sigma);
  return GM_OK;
}

gm_status gm_yee_materials_create(const gm_yee_grid *grid, gm_yee_materials **out,
                                  gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "materials: NULL output");
  *out = NULL;
  gm_status st = yee_grid_check(grid, err);
  if (st != GM_OK) return st;
  const size_t axes0 = gm_yee_dim_axes(grid->dim);
  double cells = 1.0;
  for (size_t a = 0; a < axes0; ++a) cells *= (double)grid->n[a];
  char what[128];
  snprintf(what, sizeof what, "materials: epsilon, mu and sigma of %.0f cells", cells);
  st = yee_memory_check(3.0 * 8.0 * cells, what, err);
  if (st != GM_OK) return st;
  gm_yee_materials *m = calloc(1, sizeof *m);
  if (m == NULL) return gm_error_set(err, GM_ENOMEM, "materials: out of memory");
  m->grid = *grid;
  const size_t axes = gm_yee_dim_axes(grid->dim);
  m->n_cells = 1;
  for (size_t a = 0; a < 3; ++a) {
    if (a >= axes) {
      m->grid.n[a] = 1;
      m->grid.h[a] = 1.0;
    }
    m->n_cells *= m->grid.n[a];
  }
  m->epsilon = malloc(m->n_cells * sizeof(double));
  m->mu = malloc(m->n_cells * sizeof(double));
  m->sigma = malloc(m->n_cells * sizeof(double));
  if (m->epsilon == NULL || m->mu == NULL || m->sigma == NULL) {
    const size_t n_cells = m->n_cells; /* read before m is freed */
    gm_yee_materials_free(m);
    return gm_error_set(err, GM_ENOMEM, "materials: out of memory for %zu cells", n_cells);
  }
  const gm_medium vac = gm_medium_vacuum();
  gm_yee_materials_fill(m, &vac);
  *out = m;
  return GM_OK;
}

void gm_yee_materials_free(gm_yee_materials *m) {
  if (m == NULL) return;
  free(m->pole_set);
  free(m->set_start);
  free(m->set_poles);
  yee_geometry_free(m);
  free(m->epsilon);
  free(m->mu);
  free(m->sigma);
  free(m);
}

gm_status gm_yee_materials_fill(gm_yee_materials *m, const gm_medium *medium) {
  if (m == NULL) return GM_EINVAL;
  gm_status st = medium_check(m, medium);
  if (st != GM_OK) return st;
  const unsigned set = m->pen;
  yee_geometry_reset(m);
  for (size_t c = 0; c < m->n_cells; ++c) {
    m->epsilon[c] = medium->epsilon;
    m->mu[c] = medium->mu;
    m->sigma[c] = medium->sigma;
    if (m->pole_set) m->pole_set[c] = (unsigned)set;
  }
  return GM_OK;
}

/* Paint every cell whose centre satisfies inside(ctx, centre). */
static gm_status paint(gm_yee_materials *m, int (*inside)(const void *ctx, const double x[3]),
                       const void *ctx, const gm_medium *medium) {
  gm_status st = medium_check(m, medium);
  if (st != GM_OK) return st;
  const unsigned set = m->pen;
  const gm_yee_grid *g = &m->grid;
  const size_t axes = gm_yee_dim_axes(g->dim);
  for (size_t k = 0; k < g->n[2]; ++k)
    for (size_t j = 0; j < g->n[1]; ++j)
      for (size_t i = 0; i < g->n[0]; ++i) {
        const size_t ijk[3] = {i, j, k};
        double x[3];
        for (size_t a = 0; a < 3; ++a)
          x[a] = a < axes ? g->origin[a] + ((double)ijk[a] + 0.5) * g->h[a] : 0.0;
        if (!inside(ctx, x)) continue;
        const size_t c = i + g->n[0] * (j + g->n[1] * k);
        m->epsilon[c] = medium->epsilon;
        m->mu[c] = medium->mu;
        m->sigma[c] = medium->sigma;
        if (m->pole_set) m->pole_set[c] = (unsigned)set;
      }
  return GM_OK;
}

typedef struct box_shape {
  double lo[3], hi[3];
  size_t axes;
} box_shape;

static int inside_box(const void *ctx, const double x[3]) {
  const box_shape *b = ctx;
  for (size_t a = 0; a < b->axes; ++a)
    if (x[a] < b->lo[a] || x[a] > b->hi[a]) return 0;
  return 1;
}

gm_status gm_yee_paint_box(gm_yee_materials *m, const double lo[3], const double hi[3],
                           const gm_medium *medium) {
  if (m == NULL) return GM_EINVAL;
  box_shape b = {.axes = gm_yee_dim_axes(m->grid.dim)};
  for (size_t a = 0; a < b.axes; ++a) {
    if (!isfinite(lo[a]) || !isfinite(hi[a]) || lo[a] > hi[a])
      return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                     "box: need finite lo <= hi on axis %zu (got %g, %g)", a, lo[a], hi[a]);
    b.lo[a] = lo[a];
    b.hi[a] = hi[a];
  }
  gm_status st = yee_geometry_record_box(m, b.lo, b.hi, medium);
  return st != GM_OK ? st : paint(m, inside_box, &b, medium);
}

typedef struct sphere_shape {
  double c[3], r2;
  size_t axes;
} sphere_shape;

static int inside_sphere(const void *ctx, const double x[3]) {
  const sphere_shape *s = ctx;
  double d2 = 0.0;
  for (size_t a = 0; a < s->axes; ++a) d2 += (x[a] - s->c[a]) * (x[a] - s->c[a]);
  return d2 <= s->r2;
}

gm_status gm_yee_paint_sphere(gm_yee_materials *m, const double center[3], double radius,
                              const gm_medium *medium) {
  if (m == NULL) return GM_EINVAL;
  if (!(radius >= 0.0) || !isfinite(radius))
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                   "sphere: radius must be >= 0 and finite (got %g)", radius);
  sphere_shape s = {.r2 = radius * radius, .axes = gm_yee_dim_axes(m->grid.dim)};
  for (size_t a = 0; a < 3; ++a) {
    if (!isfinite(center[a]))
      return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "sphere: centre is not finite");
    s.c[a] = center[a];
  }
  gm_status st = yee_geometry_record_sphere(m, s.c, radius, medium);
  return st != GM_OK ? st : paint(m, inside_sphere, &s, medium);
}

typedef struct cylinder_shape {
  double c[3], u[3], r2, half;
} cylinder_shape;

static int inside_cylinder(const void *ctx, const double x[3]) {
  const cylinder_shape *s = ctx;
  double d[3], along = 0.0;
  for (int a = 0; a < 3; ++a) {
    d[a] = x[a] - s->c[a];
    along += d[a] * s->u[a];
  }
  if (fabs(along) > s->half) return 0;
  double r2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double p = d[a] - along * s->u[a];
    r2 += p * p;
  }
  return r2 <= s->r2;
}

gm_status gm_yee_paint_cylinder(gm_yee_materials *m, const double center[3],
                                const double axis[3], double radius, double height,
                                const gm_medium *medium) {
  if (m == NULL) return GM_EINVAL;
  if (!(radius >= 0.0) || !isfinite(radius) || !(height >= 0.0) || isnan(height))
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                   "cylinder: radius and height must be >= 0 (got %g, %g)", radius, height);
  cylinder_shape s = {.r2 = radius * radius, .half = 0.5 * height};
  double norm = 0.0;
  for (int a = 0; a < 3; ++a) {
    if (!isfinite(center[a]) || !isfinite(axis[a]))
      return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                     "cylinder: centre and axis must be finite");
    norm += axis[a] * axis[a];
  }
  if (!(norm > 0.0))
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "cylinder: axis is the zero vector");
  norm = sqrt(norm);
  const size_t axes = gm_yee_dim_axes(m->grid.dim);
  for (int a = 0; a < 3; ++a) {
    s.c[a] = (size_t)a < axes ? center[a] : 0.0;
    s.u[a] = axis[a] / norm;
  }
  gm_status st = yee_geometry_record_cylinder(m, s.c, s.u, radius, height, medium);
  return st != GM_OK ? st : paint(m, inside_cylinder, &s, medium);
}

gm_status gm_yee_paint_cells(gm_yee_materials *m, const double *epsilon, const double *mu,
                             const double *sigma) {
  if (m == NULL) return GM_EINVAL;
  for (size_t c = 0; c < m->n_cells; ++c) {
    const gm_medium md = {epsilon ? epsilon[c] : 1.0, mu ? mu[c] : 1.0, sigma ? sigma[c] : 0.0};
    gm_status st = medium_check(m, &md);
    if (st != GM_OK) {
      char msg[YEE_ERRMSG];
      memcpy(msg, m->errmsg, sizeof msg);
      msg[sizeof msg - 1] = '\0';
      return gm_fail(m->errmsg, sizeof m->errmsg, st, "cell %zu: %.200s", c, msg);
    }
  }
  yee_geometry_reset(m);
  for (size_t c = 0; c < m->n_cells; ++c) {
    if (epsilon) m->epsilon[c] = epsilon[c];
    if (mu) m->mu[c] = mu[c];
    if (sigma) m->sigma[c] = sigma[c];
  }
  return GM_OK;
}

size_t gm_yee_materials_n_cells(const gm_yee_materials *m) { return m ? m->n_cells : 0; }
const double *gm_yee_materials_epsilon(const gm_yee_materials *m) { return m ? m->epsilon : NULL; }
const double *gm_yee_materials_mu(const gm_yee_materials *m) { return m ? m->mu : NULL; }
const double *gm_yee_materials_sigma(const gm_yee_materials *m) { return m ? m->sigma : NULL; }
const char *gm_yee_materials_errmsg(const gm_yee_materials *m) { return m ? m->errmsg : ""; }
size_t gm_yee_materials_n_dispersive(const gm_yee_materials *m) { return m ? m->n_sets : 0; }

/* The set id of the medium's poles (appending a new set unless an equal one exists; the cell
 * array is allocated, all 0, with the first set). 0 for a medium without poles, -1: no memory. */
static int same_poles(const gm_pole *a, const gm_pole *b, size_t n) {
  for (size_t i = 0; i < n; ++i)
    if (a[i].kind != b[i].kind || a[i].frequency != b[i].frequency ||
        a[i].gamma != b[i].gamma || (a[i].kind == GM_POLE_LORENTZ && a[i].strength != b[i].strength))
      return 0;
  return 1;
}

long yee_materials_pole_set(gm_yee_materials *m, size_t n_poles, const gm_pole *src) {
  if (n_poles == 0) return 0;
  for (size_t k = 0; k < m->n_sets; ++k) {
    const size_t n = m->set_start[k + 1] - m->set_start[k];
    if (n == n_poles && same_poles(m->set_poles + m->set_start[k], src, n)) return (long)k + 1;
  }
  if (m->pole_set == NULL) {
    m->pole_set = calloc(m->n_cells, sizeof *m->pole_set);
    m->set_start = calloc(1, sizeof *m->set_start);
    if (m->pole_set == NULL || m->set_start == NULL) return -1;
  }
  const size_t total = m->set_start[m->n_sets] + n_poles;
  size_t *start = realloc(m->set_start, (m->n_sets + 2) * sizeof *start);
  if (start == NULL) return -1;
  m->set_start = start;
  gm_pole *poles = realloc(m->set_poles, total * sizeof *poles);
  if (poles == NULL) return -1;
  m->set_poles = poles;
  memcpy(poles + m->set_start[m->n_sets], src, n_poles * sizeof *poles);
  m->set_start[m->n_sets + 1] = total;
  return (long)++m->n_sets;
}

gm_status gm_yee_materials_set_poles(gm_yee_materials *m, size_t n_poles, const gm_pole *poles) {
  if (m == NULL) return GM_EINVAL;
  gm_error e = {{0}};
  if (gm_poles_check(n_poles, poles, &e) != GM_OK)
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "poles: %.200s", e.message);
  const long set = yee_materials_pole_set(m, n_poles, poles);
  if (set < 0) return gm_fail(m->errmsg, sizeof m->errmsg, GM_ENOMEM, "poles: out of memory");
  m->pen = (unsigned)set;
  return GM_OK;
}
