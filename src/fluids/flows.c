/* Flows on domains without boundary as library functions (the tests, the CLI and the docs
 * measure the same thing): the Taylor–Green vortex and the double shear layer on the periodic
 * square, the Rossby–Haurwitz wave on the rotating sphere. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "fluids/internal.h"

static double mean_edge(const gm_complex *cx) {
  const size_t ne = gm_complex_count(cx, 1), N = gm_complex_embedding_dim(cx);
  const size_t *e = gm_complex_simplices(cx, 1);
  const double *x = gm_complex_coordinates(cx);
  double s = 0.0;
  for (size_t k = 0; k < ne; ++k) {
    double d2 = 0.0;
    for (size_t c = 0; c < N; ++c) {
      double d = x[N * e[2 * k] + c] - x[N * e[2 * k + 1] + c];
      d2 += d * d;
    }
    s += sqrt(d2);
  }
  return s / (double)ne;
}

gm_status gm_fluid_periodic_square_mesh(double L, size_t n, gm_mesh **mesh,
                                        gm_fluid_groups **groups, gm_error *err) {
  if (!mesh || !groups) return gm_error_set(err, GM_EINVAL, "periodic square: NULL argument");
  *mesh = NULL;
  *groups = NULL;
  if (!(L > 0) || !isfinite(L) || n < 3 || n > 10000)
    return gm_error_set(err, GM_EINVAL, "periodic square: L = %g > 0 and n = %zu in [3, 10000]", L,
                        n);
  size_t ny = 2 * (size_t)floor((double)n / sqrt(3.0) + 0.5); /* even: the top row matches row 0 */
  if (ny < 4) ny = 4;
  const size_t nx1 = n + 1, nv = nx1 * (ny + 1), nt = 2 * n * ny;
  const double hx = L / (double)n, hy = L / (double)ny;
  gm_status st = gm_mesh_create(2, nv, 2, nt, mesh);
  if (st) return gm_error_set(err, st, "periodic square: out of memory");
  gm_mesh *m = *mesh;
  for (size_t j = 0; j <= ny; ++j)
    for (size_t i = 0; i <= n; ++i) {
      m->x[2 * (j * nx1 + i)] = ((double)i + 0.5 * (double)(j % 2)) * hx;
      m->x[2 * (j * nx1 + i) + 1] = (double)j * hy;
    }
  size_t *c = m->cells;
#define V(i, j) ((j) * nx1 + (i))
  for (size_t j = 0; j < ny; ++j)
    for (size_t i = 0; i < n; ++i) {
      if (j % 2 == 0) { /* row j+1 shifted right by half a cell */
        size_t t[6] = {V(i, j), V(i + 1, j), V(i, j + 1), V(i + 1, j), V(i + 1, j + 1), V(i, j + 1)};
        memcpy(c, t, sizeof t);
      } else { /* row j shifted */
        size_t t[6] = {V(i, j), V(i + 1, j + 1), V(i, j + 1), V(i, j), V(i + 1, j), V(i + 1, j + 1)};
        memcpy(c, t, sizeof t);
      }
      c += 6;
    }
  /* groups: bottom (row 0), right (column n, a zigzag), top (row ny), left (column 0) */
  gm_fluid_groups *g = calloc(1, sizeof *g);
  const size_t ne = 2 * n + 2 * ny;
  if (g) {
    g->names = calloc(4, sizeof *g->names);
    g->vertices = calloc(2 * ne, sizeof *g->vertices);
    g->group = calloc(ne, sizeof *g->group);
  }
  if (!g || !g->names || !g->vertices || !g->group) {
    gm_fluid_groups_free(g);
    gm_mesh_free(m);
    *mesh = NULL;
    return gm_error_set(err, GM_ENOMEM, "periodic square: out of memory");
  }
  static const char *names[4] = {"bottom", "right", "top", "left"};
  for (int k = 0; k < 4; ++k) snprintf(g->names[k], GM_FLUID_NAME_SIZE, "%s", names[k]);
  g->n_groups = 4;
  g->n_edges = ne;
  size_t k = 0;
  for (size_t i = 0; i < n; ++i, ++k) {
    g->vertices[2 * k] = V(i, 0), g->vertices[2 * k + 1] = V(i + 1, 0), g->group[k] = 0;
  }
  for (size_t i = 0; i < n; ++i, ++k) {
    g->vertices[2 * k] = V(i, ny), g->vertices[2 * k + 1] = V(i + 1, ny), g->group[k] = 2;
  }
  for (size_t j = 0; j < ny; ++j, ++k) {
    g->vertices[2 * k] = V(n, j), g->vertices[2 * k + 1] = V(n, j + 1), g->group[k] = 1;
  }
  for (size_t j = 0; j < ny; ++j, ++k) {
    g->vertices[2 * k] = V(0, j), g->vertices[2 * k + 1] = V(0, j + 1), g->group[k] = 3;
  }
#undef V
  *groups = g;
  return GM_OK;
}

/* The periodic square [0, 2π]² of gm_fluid_periodic_square_mesh, both pairs identified. */
static gm_status periodic_square(size_t n, const gm_fluid_options *o, gm_fluid **f,
                                 gm_error *err) {
  gm_mesh *m = NULL;
  gm_fluid_groups *g = NULL;
  gm_status st = gm_fluid_periodic_square_mesh(2.0 * GM_PI, n, &m, &g, err);
  if (!st) {
    gm_fluid_bc bc[2];
    memset(bc, 0, sizeof bc);
    bc[0].group = "left";
    bc[0].kind = GM_FLUID_PERIODIC;
    bc[0].partner = "right";
    bc[1].group = "bottom";
    bc[1].kind = GM_FLUID_PERIODIC;
    bc[1].partner = "top";
    st = gm_fluid_create(m, g, 2, bc, o, f, err);
  }
  gm_fluid_groups_free(g);
  gm_mesh_free(m);
  return st;
}

typedef struct tracker {
  gm_fluid_diagnostics d0;
  double abs_vorticity0;
} tracker;

static void track_start(const gm_fluid *f, tracker *tr, gm_fluid_flow_result *r) {
  gm_fluid_diagnose(f, &tr->d0);
  const double *g = gm_fluid_circulation(f);
  tr->abs_vorticity0 = 0.0;
  for (size_t v = 0; v < gm_fluid_n_vertices(f); ++v) tr->abs_vorticity0 += fabs(g[v]);
  r->n_triangles = gm_fluid_n_triangles(f);
  r->n_vertices = gm_fluid_n_vertices(f);
  r->mean_edge = mean_edge(gm_fluid_complex(f));
  r->div_max = tr->d0.div_max;
}

static void track(const gm_fluid *f, const tracker *tr, gm_fluid_flow_result *r) {
  gm_fluid_diagnostics d;
  gm_fluid_diagnose(f, &d);
  r->energy_drift = fmax(r->energy_drift, fabs(d.kinetic_energy - tr->d0.kinetic_energy) /
                                              tr->d0.kinetic_energy);
  r->enstrophy_drift =
      fmax(r->enstrophy_drift, fabs(d.enstrophy - tr->d0.enstrophy) / tr->d0.enstrophy);
  r->vorticity_drift =
      fmax(r->vorticity_drift,
           fabs(d.total_vorticity - tr->d0.total_vorticity) / tr->abs_vorticity0);
  r->energy_change = (d.kinetic_energy - tr->d0.kinetic_energy) / tr->d0.kinetic_energy;
  r->div_max = fmax(r->div_max, d.div_max);
  if (d.midpoint_iterations > r->max_iterations) r->max_iterations = d.midpoint_iterations;
}

static gm_status set_psi(gm_fluid *f, double (*fn)(const double *x), gm_error *err) {
  const size_t nv = gm_fluid_n_vertices(f), sd = gm_fluid_space_dim(f);
  const double *x = gm_fluid_coordinates(f);
  double *psi = malloc(nv * sizeof *psi);
  if (!psi) return gm_error_set(err, GM_ENOMEM, "out of memory");
  for (size_t v = 0; v < nv; ++v) psi[v] = fn(x + sd * v);
  gm_status st = gm_fluid_set_state(f, psi, NULL);
  free(psi);
  if (st) return gm_error_set(err, st, "%s", gm_fluid_errmsg(f));
  return GM_OK;
}

static gm_status run(gm_fluid *f, size_t steps, gm_fluid_flow_result *r, gm_error *err) {
  tracker tr;
  track_start(f, &tr, r);
  for (size_t s = 0; s < steps; ++s) {
    gm_status st = gm_fluid_advance(f, 1);
    if (st) return gm_error_set(err, st, "%s", gm_fluid_errmsg(f));
    track(f, &tr, r);
  }
  r->steps = steps;
  return GM_OK;
}

static double taylor_green_psi(const double *x) {
  return sin(x[0]) * sin(x[1]);
}

gm_status gm_fluid_taylor_green(gm_fluid_scheme scheme, size_t n, double nu, double dt, size_t steps,
                                gm_fluid_flow_result *r, gm_error *err) {
  if (!r || n < 4 || n > 4000 || !(nu >= 0) || !(dt > 0) || steps > 100000000)
    return gm_error_set(err, GM_EINVAL,
                        "taylor-green: n = %zu in [4, 4000], nu >= 0, dt > 0 required", n);
  memset(r, 0, sizeof *r);
  gm_fluid_options o = gm_fluid_defaults();
  o.scheme = scheme;
  o.nu = nu;
  o.dt = dt;
  gm_fluid *f = NULL;
  gm_status st = periodic_square(n, &o, &f, err);
  if (!st) st = set_psi(f, taylor_green_psi, err);
  gm_fluid_diagnostics d0, d1;
  if (!st) gm_fluid_diagnose(f, &d0);
  if (!st) st = run(f, steps, r, err);
  if (!st) {
    gm_fluid_diagnose(f, &d1);
    double T = gm_fluid_time(f);
    r->measured = T > 0 ? -log(d1.kinetic_energy / d0.kinetic_energy) / (2.0 * T) : 0.0;
    r->exact = 2.0 * nu;
  }
  gm_fluid_free(f);
  return st;
}

/* ψ with u = ∂ψ/∂y = tanh((y − π/2)/δ) (y <= π), tanh((3π/2 − y)/δ) (y > π) and
 * v = −∂ψ/∂x = ε sin x; continuous at y = π and periodic in y (ψ(0) = ψ(2π)). log cosh is
 * written as |z| + log((1 + e^{−2|z|})/2), which does not overflow. */
static double log_cosh(double z) {
  z = fabs(z);
  return z + log1p(exp(-2.0 * z)) - log(2.0);
}

double gm_fluid_double_shear_psi(const double *x) {
  const double delta = GM_PI / 15.0, eps = 0.05, y = x[1];
  double c = 2.0 * delta * log_cosh(GM_PI / (2.0 * delta));
  double p = y <= GM_PI ? delta * log_cosh((y - 0.5 * GM_PI) / delta)
                        : c - delta * log_cosh((1.5 * GM_PI - y) / delta);
  return p + eps * cos(x[0]);
}

gm_status gm_fluid_double_shear(gm_fluid_scheme scheme, size_t n, double dt, size_t steps, gm_fluid_flow_result *r,
                                gm_error *err) {
  if (!r || n < 4 || n > 4000 || !(dt > 0) || steps > 100000000)
    return gm_error_set(err, GM_EINVAL, "double shear: n = %zu in [4, 4000], dt > 0 required", n);
  memset(r, 0, sizeof *r);
  gm_fluid_options o = gm_fluid_defaults();
  o.scheme = scheme;
  o.nu = 0.0;
  o.dt = dt;
  gm_fluid *f = NULL;
  gm_status st = periodic_square(n, &o, &f, err);
  if (!st) st = set_psi(f, gm_fluid_double_shear_psi, err);
  if (!st) st = run(f, steps, r, err);
  gm_fluid_free(f);
  return st;
}

/* Rossby–Haurwitz wave, Williamson et al. (J. Comput. Phys. 102 (1992) 211–224, test case 6)
 * with a = 1 and time in units of 1/Ω: ω = K = 7.848e-6 / 7.292e-5, R = 4. Their stream
 * function ψ_m = −a²ω sin φ + a²K cos^R φ sin φ cos Rλ has u = −∂ψ_m/∂y; ours has u = ∇ψ × n,
 * so ψ = −ψ_m = ω z − K z Re((x + iy)^4) on the unit sphere (cos^4 φ cos 4λ = Re((x+iy)^4)). */
#define RH_OMEGA (7.848e-6 / 7.292e-5)
#define RH_R 4.0

double gm_fluid_rossby_haurwitz_psi(const double *x) {
  double re4 = x[0] * x[0] * x[0] * x[0] - 6.0 * x[0] * x[0] * x[1] * x[1] +
               x[1] * x[1] * x[1] * x[1];
  return RH_OMEGA * x[2] - RH_OMEGA * x[2] * re4;
}

/* Phase of the zonal wavenumber-4 part of the vorticity: arg Σ_v Γ_v z_v (x_v + i y_v)^4, the
 * projection on the pattern z cos^4 φ e^{4iλ} (the wave is odd in z). */
static double rh_phase(const gm_fluid *f) {
  const double *x = gm_fluid_coordinates(f), *g = gm_fluid_circulation(f);
  double c = 0.0, s = 0.0;
  for (size_t v = 0; v < gm_fluid_n_vertices(f); ++v) {
    const double *p = x + 3 * v;
    double re4 = p[0] * p[0] * p[0] * p[0] - 6.0 * p[0] * p[0] * p[1] * p[1] +
                 p[1] * p[1] * p[1] * p[1];
    double im4 = 4.0 * p[0] * p[0] * p[0] * p[1] - 4.0 * p[0] * p[1] * p[1] * p[1];
    c += g[v] * p[2] * re4;
    s += g[v] * p[2] * im4;
  }
  return atan2(s, c);
}

gm_status gm_fluid_rossby_haurwitz(size_t subdivisions, double dt, double t_end,
                                   gm_fluid_flow_result *r, gm_error *err) {
  if (!r || subdivisions < 1 || subdivisions > 8 || !(dt > 0) || !(t_end >= 0) || t_end > 1e6)
    return gm_error_set(err, GM_EINVAL,
                        "rossby-haurwitz: subdivisions = %zu in [1, 8], dt > 0, t_end >= 0",
                        subdivisions);
  memset(r, 0, sizeof *r);
  gm_mesh *m = NULL;
  gm_fluid_groups g = {0, NULL, 0, NULL, NULL};
  gm_status st = gm_mesh_icosphere(1.0, subdivisions, &m, err);
  if (st) return st;
  gm_fluid_options o = gm_fluid_defaults();
  o.scheme = GM_FLUID_MIDPOINT;
  o.nu = 0.0;
  o.kappa = 0.0;
  o.dt = dt;
  o.rotation = 1.0;
  gm_fluid *f = NULL;
  st = gm_fluid_create(m, &g, 0, NULL, &o, &f, err);
  gm_mesh_free(m);
  if (!st) st = set_psi(f, gm_fluid_rossby_haurwitz_psi, err);
  if (st) {
    gm_fluid_free(f);
    return st;
  }
  tracker tr;
  track_start(f, &tr, r);
  size_t steps = (size_t)floor(t_end / dt + 0.5);
  double phase0 = rh_phase(f), last = phase0, unwrapped = 0.0;
  for (size_t s = 0; s < steps && !st; ++s) {
    st = gm_fluid_advance(f, 1);
    if (st) {
      gm_error_set(err, st, "%s", gm_fluid_errmsg(f));
      break;
    }
    track(f, &tr, r);
    double ph = rh_phase(f), d = ph - last;
    d -= 2.0 * GM_PI * floor((d + GM_PI) / (2.0 * GM_PI)); /* unwrap */
    unwrapped += d;
    last = ph;
  }
  if (!st) {
    r->steps = steps;
    double T = gm_fluid_time(f);
    /* pattern cos(4(λ − νt)): its phase arg Σ Γ z (x+iy)^4 advances by 4νt */
    r->measured = T > 0 ? unwrapped / (RH_R * T) : 0.0;
    r->exact = (RH_R * (3.0 + RH_R) * RH_OMEGA - 2.0) / ((1.0 + RH_R) * (2.0 + RH_R));
  }
  gm_fluid_free(f);
  return st;
}
