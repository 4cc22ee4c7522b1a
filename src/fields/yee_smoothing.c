/* Subpixel smoothing of ε, μ and σ (on by default, as in MEEP; gm_yee_options.smoothing).
 *
 * Method: Farjadpour et al., Opt. Lett. 31 (2006) 2972 and Kottke, Farjadpour & Johnson,
 * Phys. Rev. E 77 (2008) 036611, eq. (1): over the "pixel" of a field location (a box one cell
 * wide centred on it) cut by an interface with unit normal n, the effective tensor is
 *   ε̃ = P ⟨ε⁻¹⟩⁻¹ + (1 − P) ⟨ε⟩,   P = n nᵀ,
 * so, P and 1 − P being complementary projectors, ε̃⁻¹ = P ⟨ε⁻¹⟩ + (1 − P) ⟨ε⟩⁻¹.
 * Yee stores one ε per edge: the update of E_a reads E_a = (ε̃⁻¹ D)_a, and we keep the diagonal
 * entry of the inverse tensor (the projection of ε̃⁻¹ onto the edge direction e_a),
 *   1/ε_a = n_a² ⟨ε⁻¹⟩ + (1 − n_a²) ⟨ε⟩⁻¹,
 * dropping the off-diagonal entries (they would couple E_a to the other components at other
 * locations). The same for μ on faces (H_a) and the plain mean ⟨σ⟩ for the conductivity.
 *
 * Geometry: the shapes painted into the materials are recorded (box, sphere, cylinder) with the
 * arrays as they were before the first shape (the "base"). For a pixel, the last-painted shape
 * whose surface comes within the pixel's half-diagonal cuts it: n and the signed distance d
 * come from the shape's signed-distance function (n its gradient, by central differences), the
 * fill fraction f is the exact volume of the pixel on the inner side of the tangent plane (a
 * planar interface, as MEEP), ε inside is the shape's, ε outside the material just outside the
 * surface. A pixel touched by no shape averages the base cell arrays exactly (the overlap of
 * the pixel with each cell), with n along the gradient of those box averages — the per-cell
 * arrays case. Pixels of one medium keep it: smoothing changes only cut pixels. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fields/internal.h"

typedef enum { SHAPE_BOX, SHAPE_SPHERE, SHAPE_CYLINDER } shape_kind;

typedef struct yee_shape {
  shape_kind kind;
  double a[3], b[3]; /* box: lo, hi; sphere: centre; cylinder: centre, unit axis */
  double r, half;    /* sphere/cylinder radius; cylinder half height */
  gm_medium medium;
} yee_shape;

struct yee_geometry {
  size_t n, cap;
  yee_shape *shapes;
  double *eps, *mu, *sigma; /* base arrays (NULL: the uniform base medium) */
  gm_medium base;
};

static int medium_ok(const gm_medium *md) {
  return md != NULL && md->epsilon > 0.0 && isfinite(md->epsilon) && md->mu > 0.0 &&
         isfinite(md->mu) && md->sigma >= 0.0 && isfinite(md->sigma);
}

void yee_geometry_free(gm_yee_materials *m) {
  if (m == NULL || m->geometry == NULL) return;
  free(m->geometry->shapes);
  free(m->geometry->eps);
  free(m->geometry->mu);
  free(m->geometry->sigma);
  free(m->geometry);
  m->geometry = NULL;
}

/* The arrays now hold every shape as a staircase: forget the shapes, the arrays are the base. */
void yee_geometry_reset(gm_yee_materials *m) { yee_geometry_free(m); }

static gm_status record(gm_yee_materials *m, const yee_shape *shape) {
  if (!medium_ok(&shape->medium)) return GM_OK; /* paint() reports the bad medium */
  struct yee_geometry *g = m->geometry;
  if (g == NULL) {
    g = calloc(1, sizeof *g);
    if (g == NULL) return gm_fail(m->errmsg, sizeof m->errmsg, GM_ENOMEM, "out of memory");
    m->geometry = g;
    int uniform = 1;
    for (size_t c = 1; c < m->n_cells && uniform; ++c)
      uniform = m->epsilon[c] == m->epsilon[0] && m->mu[c] == m->mu[0] &&
                m->sigma[c] == m->sigma[0];
    g->base = (gm_medium){m->epsilon[0], m->mu[0], m->sigma[0]};
    if (!uniform) {
      const size_t bytes = m->n_cells * sizeof(double);
      g->eps = malloc(bytes);
      g->mu = malloc(bytes);
      g->sigma = malloc(bytes);
      if (g->eps == NULL || g->mu == NULL || g->sigma == NULL) {
        yee_geometry_free(m);
        return gm_fail(m->errmsg, sizeof m->errmsg, GM_ENOMEM, "out of memory");
      }
      memcpy(g->eps, m->epsilon, bytes);
      memcpy(g->mu, m->mu, bytes);
      memcpy(g->sigma, m->sigma, bytes);
    }
  }
  if (g->n == g->cap) {
    const size_t cap = g->cap ? 2 * g->cap : 8;
    yee_shape *s = realloc(g->shapes, cap * sizeof *s);
    if (s == NULL) return gm_fail(m->errmsg, sizeof m->errmsg, GM_ENOMEM, "out of memory");
    g->shapes = s;
    g->cap = cap;
  }
  g->shapes[g->n++] = *shape;
  return GM_OK;
}

gm_status yee_geometry_record_box(gm_yee_materials *m, const double lo[3], const double hi[3],
                                  const gm_medium *medium) {
  yee_shape s = {.kind = SHAPE_BOX, .medium = medium ? *medium : (gm_medium){0, 0, 0}};
  for (int a = 0; a < 3; ++a) s.a[a] = lo[a], s.b[a] = hi[a];
  return record(m, &s);
}

gm_status yee_geometry_record_sphere(gm_yee_materials *m, const double center[3], double radius,
                                     const gm_medium *medium) {
  yee_shape s = {.kind = SHAPE_SPHERE, .r = radius,
                 .medium = medium ? *medium : (gm_medium){0, 0, 0}};
  for (int a = 0; a < 3; ++a) s.a[a] = center[a];
  return record(m, &s);
}

gm_status yee_geometry_record_cylinder(gm_yee_materials *m, const double center[3],
                                       const double unit_axis[3], double radius, double height,
                                       const gm_medium *medium) {
  yee_shape s = {.kind = SHAPE_CYLINDER, .r = radius, .half = 0.5 * height,
                 .medium = medium ? *medium : (gm_medium){0, 0, 0}};
  for (int a = 0; a < 3; ++a) s.a[a] = center[a], s.b[a] = unit_axis[a];
  return record(m, &s);
}

double yee_geometry_min_em(const gm_yee_materials *m) {
  double v = INFINITY;
  if (m == NULL || m->geometry == NULL) return v;
  for (size_t i = 0; i < m->geometry->n; ++i)
    v = fmin(v, m->geometry->shapes[i].medium.epsilon * m->geometry->shapes[i].medium.mu);
  return v;
}

int yee_geometry_lossy(const gm_yee_materials *m) {
  if (m == NULL || m->geometry == NULL) return 0;
  for (size_t i = 0; i < m->geometry->n; ++i)
    if (m->geometry->shapes[i].medium.sigma != 0.0) return 1;
  return 0;
}

int yee_geometry_has_shapes(const gm_yee_materials *m) {
  return m != NULL && m->geometry != NULL && m->geometry->n > 0;
}

/* Signed distance to the shape's surface (negative inside) at x, over the grid's axes. */
static double shape_sdf(const yee_shape *s, size_t axes, const double x[3]) {
  double p[3] = {0, 0, 0};
  switch (s->kind) {
  case SHAPE_BOX: {
    double out2 = 0.0, qmax = -INFINITY;
    for (size_t a = 0; a < axes; ++a) {
      const double q = fabs(x[a] - 0.5 * (s->a[a] + s->b[a])) - 0.5 * (s->b[a] - s->a[a]);
      qmax = fmax(qmax, q);
      if (q > 0) out2 += q * q;
    }
    return sqrt(out2) + fmin(qmax, 0.0);
  }
  case SHAPE_SPHERE: {
    double d2 = 0.0;
    for (size_t a = 0; a < axes; ++a) d2 += (x[a] - s->a[a]) * (x[a] - s->a[a]);
    return sqrt(d2) - s->r;
  }
  case SHAPE_CYLINDER: {
    double along = 0.0;
    for (size_t a = 0; a < 3; ++a) {
      p[a] = (a < axes ? x[a] - s->a[a] : 0.0);
      along += p[a] * s->b[a];
    }
    double perp2 = 0.0;
    for (int a = 0; a < 3; ++a) perp2 += (p[a] - along * s->b[a]) * (p[a] - along * s->b[a]);
    const double qr = sqrt(perp2) - s->r;
    /* in 2-D a cylinder along z is a disk whatever its height (as gm_yee_paint_cylinder) */
    if (axes == 2 && s->b[0] == 0.0 && s->b[1] == 0.0) return qr;
    const double qh = fabs(along) - s->half;
    return fmin(fmax(qr, qh), 0.0) + hypot(fmax(qr, 0.0), fmax(qh, 0.0));
  }
  }
  return INFINITY;
}

/* As gm_yee_paint_* decide (closed shapes). */
static int shape_inside(const yee_shape *s, size_t axes, const double x[3]) {
  return shape_sdf(s, axes, x) <= 0.0;
}

/* Cell of the base arrays holding x (clamped, or wrapped on periodic axes). */
static size_t base_cell(const gm_yee_layout *L, const int periodic[3], const double x[3]) {
  size_t c = 0, stride = 1;
  for (int a = 0; a < 3; ++a) {
    const long n = (long)L->n[a];
    long i = L->extent[a] == 1 ? 0 : (long)floor((x[a] - L->origin[a]) / L->h[a]);
    if (periodic[a]) i = ((i % n) + n) % n;
    i = i < 0 ? 0 : i >= n ? n - 1 : i;
    c += (size_t)i * stride;
    stride *= (size_t)n;
  }
  return c;
}

static gm_medium base_at(const gm_yee_materials *m, const gm_yee_layout *L,
                         const int periodic[3], const double x[3]) {
  const struct yee_geometry *g = m->geometry;
  const double *eps = g ? g->eps : m->epsilon, *mu = g ? g->mu : m->mu;
  const double *sig = g ? g->sigma : m->sigma;
  if (eps == NULL) return g->base;
  const size_t c = base_cell(L, periodic, x);
  return (gm_medium){eps[c], mu[c], sig[c]};
}

/* The medium at x from the shapes below index `below` (painted earlier) and the base. */
static gm_medium medium_below(const gm_yee_materials *m, const gm_yee_layout *L,
                              const int periodic[3], size_t below, const double x[3]) {
  const size_t axes = gm_yee_dim_axes(L->dim);
  for (size_t i = below; i-- > 0;)
    if (shape_inside(&m->geometry->shapes[i], axes, x)) return m->geometry->shapes[i].medium;
  return base_at(m, L, periodic, x);
}

/* Fraction of the box Π[−half_b, half_b] with n·y <= t (the exact volume of a box cut by a
 * plane: inclusion–exclusion over the corners, e.g. Lasserre's formula for a simplex sum). */
static double box_fraction_below(size_t axes, const double n[3], const double half[3], double t) {
  double a[3];
  size_t k = 0;
  double amax = 0.0;
  for (size_t b = 0; b < axes; ++b) amax = fmax(amax, 2.0 * fabs(n[b]) * half[b]);
  /* u_b in [0, 1], y_b = half_b (2u_b − 1): Σ c_b u_b <= T with c_b = 2 n_b half_b,
     T = t + Σ n_b half_b; where c_b < 0, u_b → 1 − u_b makes it |c_b| u_b and T += |c_b| */
  for (size_t b = 0; b < axes; ++b) t += n[b] * half[b];
  for (size_t b = 0; b < axes; ++b) {
    const double c = 2.0 * n[b] * half[b];
    if (c < 0) t -= c;
    /* a coefficient below 1e-7 of the largest moves the fraction by < 1e-7: replace its term
       by its mean (the formula divides by it) */
    if (fabs(c) > 1e-7 * amax) a[k++] = fabs(c);
    else t -= 0.5 * fabs(c);
  }
  if (k == 0) return t >= 0 ? 1.0 : 0.0;
  double sum = 0.0, prod = 1.0, fact = 1.0;
  for (size_t b = 0; b < k; ++b) prod *= a[b], fact *= (double)(b + 1);
  for (unsigned v = 0; v < (1u << k); ++v) {
    double s = t;
    int sign = 1;
    for (size_t b = 0; b < k; ++b)
      if (v & (1u << b)) s -= a[b], sign = -sign;
    if (s > 0) sum += sign * pow(s, (double)k);
  }
  const double f = sum / (fact * prod);
  return f < 0 ? 0.0 : f > 1 ? 1.0 : f;
}

/* Exact averages of the base cell arrays over the box [lo, lo + 1) (index units per axis). */
static int base_box_mean(const gm_yee_materials *m, const gm_yee_layout *L,
                         const int periodic[3], const double lo[3], double mean[3],
                         double mean_inv[3]) {
  const struct yee_geometry *g = m->geometry;
  const double *arr[3] = {g ? g->eps : m->epsilon, g ? g->mu : m->mu,
                          g ? g->sigma : m->sigma};
  for (int p = 0; p < 3; ++p) mean[p] = mean_inv[p] = 0.0;
  if (arr[0] == NULL) {
    const double v[3] = {g->base.epsilon, g->base.mu, g->base.sigma};
    for (int p = 0; p < 3; ++p) mean[p] = v[p], mean_inv[p] = 1.0 / v[p];
    return 1;
  }
  long idx[3][2];
  double w[3][2];
  int cnt[3];
  for (int a = 0; a < 3; ++a) {
    if (L->extent[a] == 1) {
      idx[a][0] = 0, w[a][0] = 1.0, cnt[a] = 1;
      continue;
    }
    const long n = (long)L->n[a];
    const double fl = floor(lo[a]);
    const double fr = lo[a] - fl;
    cnt[a] = fr > 0 ? 2 : 1;
    for (int q = 0; q < cnt[a]; ++q) {
      long i = (long)fl + q;
      if (periodic[a]) i = ((i % n) + n) % n;
      idx[a][q] = i < 0 ? 0 : i >= n ? n - 1 : i;
      w[a][q] = cnt[a] == 1 ? 1.0 : q == 0 ? 1.0 - fr : fr;
    }
  }
  const size_t c0 = (size_t)idx[0][0] + L->n[0] * ((size_t)idx[1][0] + L->n[1] * (size_t)idx[2][0]);
  int uniform = 1;
  for (int z = 0; z < cnt[2]; ++z)
    for (int y = 0; y < cnt[1]; ++y)
      for (int x = 0; x < cnt[0]; ++x) {
        const double wt = w[0][x] * w[1][y] * w[2][z];
        const size_t c =
            (size_t)idx[0][x] + L->n[0] * ((size_t)idx[1][y] + L->n[1] * (size_t)idx[2][z]);
        for (int p = 0; p < 3; ++p) {
          mean[p] += wt * arr[p][c];
          mean_inv[p] += wt / arr[p][c];
        }
        uniform = uniform && arr[0][c] == arr[0][c0] && arr[1][c] == arr[1][c0];
      }
  if (uniform) /* one ε and μ: their values, not a rounded mean (σ keeps its mean) */
    for (int p = 0; p < 2; ++p) mean[p] = arr[p][c0], mean_inv[p] = 1.0 / arr[p][c0];
  return uniform;
}

/* Averages over the pixel of component c at index ijk: ⟨ε⟩, ⟨1/ε⟩, ⟨μ⟩, ⟨1/μ⟩, ⟨σ⟩ (as
 * mean[3], mean_inv[3]) and the interface normal n (zero when the pixel holds one medium). */
static void pixel_average_at(const gm_yee_materials *m, const gm_yee_layout *L,
                             const int periodic[3], const double pos[3], double mean[3],
                             double mean_inv[3], double n[3]) {
  const size_t axes = gm_yee_dim_axes(L->dim);
  double x[3], half[3], lo[3];
  double r2 = 0.0, hmin = INFINITY;
  for (int a = 0; a < 3; ++a) {
    const int present = (size_t)a < axes;
    x[a] = present ? L->origin[a] + L->h[a] * pos[a] : 0.0;
    lo[a] = present ? pos[a] - 0.5 : 0.0;
    half[a] = present ? 0.5 * L->h[a] : 0.0;
    r2 += half[a] * half[a];
    if (present) hmin = fmin(hmin, L->h[a]);
  }
  const double r = sqrt(r2);
  n[0] = n[1] = n[2] = 0.0;
  const struct yee_geometry *g = m->geometry;
  for (size_t s = g ? g->n : 0; s-- > 0;) {
    const yee_shape *sh = &g->shapes[s];
    const double d = shape_sdf(sh, axes, x);
    if (d > r) continue; /* the pixel is outside: look below */
    const gm_medium in = sh->medium;
    if (d < -r) {        /* inside */
      mean[0] = in.epsilon, mean[1] = in.mu, mean[2] = in.sigma;
      mean_inv[0] = 1.0 / in.epsilon, mean_inv[1] = 1.0 / in.mu, mean_inv[2] = 0.0;
      return;
    }
    /* cut: the normal from the signed distance's gradient (central differences) */
    const double delta = 1e-5 * hmin;
    double g2 = 0.0;
    for (size_t a = 0; a < axes; ++a) {
      double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
      xp[a] += delta, xm[a] -= delta;
      n[a] = (shape_sdf(sh, axes, xp) - shape_sdf(sh, axes, xm)) / (2.0 * delta);
      g2 += n[a] * n[a];
    }
    double dist = d;
    if (g2 > 0) {
      const double gn = sqrt(g2);
      for (size_t a = 0; a < axes; ++a) n[a] /= gn;
      dist = d / gn;
    }
    /* the outer medium just outside the surface, below this shape */
    double xo[3];
    const double step = fmax(0.0, -dist) + 1e-6 * hmin;
    for (int a = 0; a < 3; ++a) xo[a] = x[a] + n[a] * step;
    const gm_medium out = medium_below(m, L, periodic, s, xo);
    const double f = g2 > 0 ? box_fraction_below(axes, n, half, -dist) : (d <= 0 ? 1.0 : 0.0);
    const double vi[3] = {in.epsilon, in.mu, in.sigma}, vo[3] = {out.epsilon, out.mu, out.sigma};
    for (int p = 0; p < 3; ++p) {
      mean[p] = f * vi[p] + (1.0 - f) * vo[p];
      mean_inv[p] = p < 2 ? f / vi[p] + (1.0 - f) / vo[p] : 0.0;
    }
    return;
  }
  /* no shape touches the pixel: exact averages of the base cells, n along their gradient */
  if (base_box_mean(m, L, periodic, lo, mean, mean_inv)) return; /* one medium */
  double g2 = 0.0, gm2 = 0.0, nm[3] = {0, 0, 0};
  for (size_t a = 0; a < axes; ++a) {
    double lp[3] = {lo[0], lo[1], lo[2]}, lm[3] = {lo[0], lo[1], lo[2]}, mp[3], mm[3], ip[3],
           im[3];
    lp[a] += 0.5, lm[a] -= 0.5;
    base_box_mean(m, L, periodic, lp, mp, ip);
    base_box_mean(m, L, periodic, lm, mm, im);
    n[a] = (mp[0] - mm[0]) / L->h[a];
    nm[a] = (mp[1] - mm[1]) / L->h[a];
    g2 += n[a] * n[a];
    gm2 += nm[a] * nm[a];
  }
  /* along the gradient of ε, or of μ for a purely magnetic contrast */
  if (!(g2 > 0)) {
    for (int a = 0; a < 3; ++a) n[a] = nm[a];
    g2 = gm2;
  }
  if (g2 > 0)
    for (size_t a = 0; a < axes; ++a) n[a] /= sqrt(g2);
}

/* The same for the pixel of component c at index ijk. */
static void pixel_average(const gm_yee_materials *m, const gm_yee_layout *L,
                          const int periodic[3], int c, const long ijk[3], double mean[3],
                          double mean_inv[3], double n[3]) {
  double shift[3], pos[3];
  gm_yee_component_shift(L->dim, (gm_yee_component)c, shift);
  for (int a = 0; a < 3; ++a) pos[a] = (double)ijk[a] + shift[a];
  pixel_average_at(m, L, periodic, pos, mean, mean_inv, n);
}

double yee_smooth_offdiag_at(const gm_yee_materials *m, const gm_yee_layout *L,
                             const int periodic[3], const double pos[3], int a, int b) {
  double mean[3], mean_inv[3], n[3];
  pixel_average_at(m, L, periodic, pos, mean, mean_inv, n);
  return n[a] * n[b] * (mean_inv[0] - 1.0 / mean[0]);
}

void yee_smooth_inverse_row(const gm_yee_materials *m, const gm_yee_layout *L,
                            const int periodic[3], int c, long i, long j, long k, double row[3],
                            double *eps_aa, double *sigma) {
  const long ijk[3] = {i, j, k};
  double mean[3], mean_inv[3], n[3];
  pixel_average(m, L, periodic, c, ijk, mean, mean_inv, n);
  /* row a of ε̃⁻¹ = P ⟨ε⁻¹⟩ + (1 − P) ⟨ε⟩⁻¹ (Kottke et al. 2008 eq. 1):
     δ_ab ⟨ε⟩⁻¹ + n_a n_b (⟨ε⁻¹⟩ − ⟨ε⟩⁻¹) */
  for (int b = 0; b < 3; ++b)
    row[b] = (b == c ? 1.0 / mean[0] : 0.0) + n[c] * n[b] * (mean_inv[0] - 1.0 / mean[0]);
  *eps_aa = n[c] == 0.0 ? mean[0] : 1.0 / row[c]; /* ⟨ε⟩ itself, not 1/(1/⟨ε⟩) */
  *sigma = mean[2];
}

void yee_smooth_edge(const gm_yee_materials *m, const gm_yee_layout *L, const int periodic[3],
                     int c, long i, long j, long k, double *epsilon, double *sigma) {
  double row[3];
  /* 1/ε_a = n_a² ⟨ε⁻¹⟩ + (1 − n_a²) ⟨ε⟩⁻¹, the diagonal of ε̃⁻¹ */
  yee_smooth_inverse_row(m, L, periodic, c, i, j, k, row, epsilon, sigma);
}

void yee_smooth_face(const gm_yee_materials *m, const gm_yee_layout *L, const int periodic[3],
                     int c, long i, long j, long k, double *inv_mu) {
  const long ijk[3] = {i, j, k};
  double mean[3], mean_inv[3], n[3];
  pixel_average(m, L, periodic, c, ijk, mean, mean_inv, n);
  const double na2 = n[c - 3] * n[c - 3];
  *inv_mu = na2 * mean_inv[1] + (1.0 - na2) / mean[1];
}
