/* Seed 004 experiments B14 (channel) and B15 (Couette and Poiseuille rates) as library functions,
 * so the CLI, tests and docs measure the same thing. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/fluids.h"

static double mean_edge(const gm_complex *cx) {
  const size_t ne = gm_complex_count(cx, 1);
  const size_t *e = gm_complex_simplices(cx, 1);
  const double *x = gm_complex_coordinates(cx);
  double s = 0.0;
  for (size_t k = 0; k < ne; ++k)
    s +=
        hypot(x[2 * e[2 * k]] - x[2 * e[2 * k + 1]], x[2 * e[2 * k] + 1] - x[2 * e[2 * k + 1] + 1]);
  return s / (double)ne;
}

static gm_status setup(double lx, double ly, size_t nx, gm_mesh **m, gm_fluid_groups **g,
                       gm_error *err) {
  size_t ny = (size_t)floor((double)nx * ly / lx * 2.0 / sqrt(3.0) + 0.5);
  if (ny < 2) ny = 2;
  gm_status st = gm_mesh_rectangle(0, lx, 0, ly, nx, ny, GM_DIAGONAL_ACUTE, m, err);
  if (st) return st;
  st = gm_fluid_groups_rectangle(*m, g, err);
  if (st) {
    gm_mesh_free(*m);
    *m = NULL;
  }
  return st;
}

/* The channel's four groups, as both experiments use them: walls below and above (scalar
 * Dirichlet, θ = theta_top on the top wall, 0 below), inflow on the left, outflow on the right.
 * The callers set the wall and inflow velocities and the inflow's scalar condition. */
static void channel_bcs(gm_fluid_bc bc[4], double theta_top) {
  memset(bc, 0, 4 * sizeof *bc);
  bc[0].group = "bottom";
  bc[0].kind = GM_FLUID_WALL;
  bc[0].scalar = GM_SCALAR_DIRICHLET;
  bc[1].group = "right";
  bc[1].kind = GM_FLUID_OUTFLOW;
  bc[2].group = "top";
  bc[2].kind = GM_FLUID_WALL;
  bc[2].scalar = GM_SCALAR_DIRICHLET;
  bc[2].scalar_value = theta_top;
  bc[3].group = "left";
  bc[3].kind = GM_FLUID_INFLOW;
}

gm_status gm_fluid_channel(size_t nx, double t_end, gm_fluid_channel_result *r, gm_error *err) {
  if (!r || nx < 8 || nx > 4000 || !(t_end >= 0) || t_end > 1e4)
    return gm_error_set(err, GM_EINVAL, "channel: nx = %zu must be in [8, 4000], t_end in [0, 1e4]",
                        nx);
  memset(r, 0, sizeof *r);
  const double L = 2.0 * GM_PI;
  gm_mesh *m = NULL;
  gm_fluid_groups *g = NULL;
  gm_status st = setup(L, 1.0, nx, &m, &g, err);
  if (st) return st;
  gm_fluid_bc bc[4];
  channel_bcs(bc, 20.0);
  bc[3].speed = 1.0;
  bc[3].scalar = GM_SCALAR_DIRICHLET;
  gm_fluid_options o = gm_fluid_defaults();
  o.dt = 1e-2;
  gm_fluid *f = NULL;
  st = gm_fluid_create(m, g, 4, bc, &o, &f, err);
  gm_fluid_groups_free(g);
  gm_mesh_free(m);
  if (st) return st;
  const gm_complex *cx = gm_fluid_complex(f);
  r->n_triangles = gm_fluid_n_triangles(f);
  r->mean_edge = mean_edge(cx);
  size_t n_steps = (size_t)floor(t_end / o.dt + 0.5);
  for (size_t s = 0; s < n_steps; ++s) {
    st = gm_fluid_advance(f, 1);
    if (st) {
      gm_error_set(err, st, "%s", gm_fluid_errmsg(f));
      gm_fluid_free(f);
      return st;
    }
    gm_fluid_diagnostics d;
    gm_fluid_diagnose(f, &d);
    r->div_max = fmax(r->div_max, d.div_max);
  }
  r->steps = n_steps;
  const size_t ne = gm_complex_count(cx, 1), nt = gm_fluid_n_triangles(f),
               nv = gm_fluid_n_vertices(f);
  const size_t *edge = gm_complex_simplices(cx, 1), *tri = gm_complex_simplices(cx, 2);
  const double *x = gm_complex_coordinates(cx), *psi = gm_fluid_psi(f), *th = gm_fluid_theta(f);
  size_t count = 0;
  for (size_t e = 0; e < ne; ++e) {
    const double *a = x + 2 * edge[2 * e], *b = x + 2 * edge[2 * e + 1];
    double mx = 0.5 * (a[0] + b[0]), my = 0.5 * (a[1] + b[1]);
    if (mx < 0.25 * L || mx > 0.75 * L) continue;
    double len = hypot(b[0] - a[0], b[1] - a[1]);
    /* flux dψ through e: u·n with n = (t_y, −t_x) for the edge direction t = (b − a)/|e|
     * (∂ψ/∂s = u·n_right, as on the boundary walk of create.c) */
    double ux = 4.0 * my * (1.0 - my), n_x = (b[1] - a[1]) / len;
    double exact = ux * n_x;
    r->profile_error += fabs((psi[edge[2 * e + 1]] - psi[edge[2 * e]]) / len - exact);
    ++count;
  }
  r->profile_error /= (double)(count ? count : 1);
  double *u = malloc(2 * nt * sizeof *u);
  if (!u) {
    gm_fluid_free(f);
    return gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  gm_fluid_velocity(f, u);
  count = 0;
  for (size_t t = 0; t < nt; ++t) {
    double cxm = 0, cym = 0;
    for (int k = 0; k < 3; ++k) {
      cxm += x[2 * tri[3 * t + k]] / 3.0;
      cym += x[2 * tri[3 * t + k] + 1] / 3.0;
    }
    if (cxm < 0.25 * L || cxm > 0.75 * L) continue;
    r->centroid_error += hypot(u[2 * t] - 4.0 * cym * (1.0 - cym), u[2 * t + 1]);
    ++count;
  }
  r->centroid_error /= (double)(count ? count : 1);
  free(u);
  for (size_t v = 0; v < nv; ++v)
    if (x[2 * v] >= 0.25 * L && x[2 * v] <= 0.75 * L)
      r->theta_error = fmax(r->theta_error, fabs(th[v] - 20.0 * x[2 * v + 1]));
  gm_fluid_free(f);
  return GM_OK;
}

static int couette_profile(void *c, const double *x, double *u) {
  (void)c;
  u[0] = x[1];
  u[1] = 0.0;
  return 0;
}
static int poiseuille_profile(void *c, const double *x, double *u) {
  (void)c;
  u[0] = 4.0 * x[1] * (1.0 - x[1]);
  u[1] = 0.0;
  return 0;
}

gm_status gm_fluid_shear(int poiseuille, size_t n, double dt, double t_end,
                         gm_fluid_shear_result *r, gm_error *err) {
  if (!r || n < 4 || n > 4000 || !(dt > 0) || !(t_end >= 0) || t_end / dt > 1e7)
    return gm_error_set(err, GM_EINVAL, "shear: n = %zu must be in [4, 4000], dt > 0, t_end >= 0",
                        n);
  memset(r, 0, sizeof *r);
  gm_mesh *m = NULL;
  gm_fluid_groups *g = NULL;
  gm_status st = setup(1.0, 1.0, n, &m, &g, err);
  if (st) return st;
  gm_fluid_bc bc[4];
  channel_bcs(bc, 1.0);
  bc[2].velocity[0] = poiseuille ? 0.0 : 1.0;
  bc[3].profile = poiseuille ? poiseuille_profile : couette_profile;
  gm_fluid_options o = gm_fluid_defaults();
  o.dt = dt;
  gm_fluid *f = NULL;
  st = gm_fluid_create(m, g, 4, bc, &o, &f, err);
  gm_fluid_groups_free(g);
  gm_mesh_free(m);
  if (st) return st;
  const gm_complex *cx = gm_fluid_complex(f);
  const size_t nv = gm_fluid_n_vertices(f), nt = gm_fluid_n_triangles(f),
               ne = gm_complex_count(cx, 1);
  const double *x = gm_complex_coordinates(cx);
  double *psi = malloc((2 * nv + 2 * nt) * sizeof *psi);
  if (!psi) {
    gm_fluid_free(f);
    return gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  double *theta = psi + nv, *u = theta + nv;
#define PSI_EXACT(y) (poiseuille ? 2.0 * (y) * (y)-4.0 * (y) * (y) * (y) / 3.0 : 0.5 * (y) * (y))
  const double c = gm_fluid_psi(f)[0] - PSI_EXACT(x[1]);
  for (size_t v = 0; v < nv; ++v) {
    psi[v] = c + PSI_EXACT(x[2 * v + 1]);
    theta[v] = x[2 * v + 1];
  }
#undef PSI_EXACT
  st = gm_fluid_set_state(f, psi, theta);
  size_t n_steps = (size_t)floor(t_end / dt + 0.5);
  for (size_t s = 0; !st && s < n_steps; ++s) {
    st = gm_fluid_advance(f, 1);
    gm_fluid_diagnostics d;
    gm_fluid_diagnose(f, &d);
    r->div_max = fmax(r->div_max, d.div_max);
  }
  if (st) {
    gm_error_set(err, st, "%s", gm_fluid_errmsg(f));
    free(psi);
    gm_fluid_free(f);
    return st;
  }
  const double *ps = gm_fluid_psi(f), *th = gm_fluid_theta(f);
  const double *s0 = gm_geometry_hodge_star(gm_fluid_geometry(f), 0);
  const double *s1 = gm_geometry_hodge_star(gm_fluid_geometry(f), 1);
  for (size_t v = 0; v < nv; ++v) {
    r->psi += s0[v] * (ps[v] - psi[v]) * (ps[v] - psi[v]);
    r->theta += s0[v] * (th[v] - theta[v]) * (th[v] - theta[v]);
  }
  gm_fluid_velocity(f, u);
  const size_t *tri = gm_complex_simplices(cx, 2), *edge = gm_complex_simplices(cx, 1);
  for (size_t t = 0; t < nt; ++t) {
    const double *a = x + 2 * tri[3 * t], *b = x + 2 * tri[3 * t + 1], *cc = x + 2 * tri[3 * t + 2];
    double y = (a[1] + b[1] + cc[1]) / 3.0, ue = poiseuille ? 4.0 * y * (1.0 - y) : y;
    double area = 0.5 * fabs((b[0] - a[0]) * (cc[1] - a[1]) - (b[1] - a[1]) * (cc[0] - a[0]));
    r->velocity += area * ((u[2 * t] - ue) * (u[2 * t] - ue) + u[2 * t + 1] * u[2 * t + 1]);
  }
  for (size_t e = 0; e < ne; ++e) {
    const double *a = x + 2 * edge[2 * e], *b = x + 2 * edge[2 * e + 1];
    double len = hypot(b[0] - a[0], b[1] - a[1]), my = 0.5 * (a[1] + b[1]);
    double ue = poiseuille ? 4.0 * my * (1.0 - my) : my;
    double fe = (ps[edge[2 * e + 1]] - ps[edge[2 * e]]) / len, exact = ue * (b[1] - a[1]) / len;
    /* weight |e| |⋆e| = 2 × the area of the edge's diamond */
    r->flux += s1[e] * len * len * (fe - exact) * (fe - exact);
  }
  r->psi = sqrt(r->psi);
  r->theta = sqrt(r->theta);
  r->velocity = sqrt(r->velocity);
  r->flux = sqrt(r->flux);
  r->mean_edge = mean_edge(cx);
  free(psi);
  gm_fluid_free(f);
  return GM_OK;
}
