/* DEC fluid solver: creation. Checks the input, classifies the boundary, sets the boundary
 * stream function, assembles and factorizes every matrix of the step (seed 004 eqs. 153–156 as
 * reconstructed in seeds/notes/003-004 §2.5 and docs/fluids.md). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "fluids/internal.h"

gm_fluid_options gm_fluid_defaults(void) {
  gm_fluid_options o;
  memset(&o, 0, sizeof o);
  o.scheme = GM_FLUID_SEED;
  o.nu = 1.0;
  o.kappa = 1.0;
  o.dt = 1e-2;
  o.velocity_scale = 0.0;
  o.midpoint_tol = 1e-15;
  o.midpoint_max_iter = 200;
  return o;
}

void gm_fluid_free(gm_fluid *f) {
  if (!f) return;
  gm_geometry_free(f->geo);
  gm_complex_free(f->cx);
  free(f->star0);
  free(f->star1);
  free(f->area);
  free(f->grad);
  gm_csr_free(f->L);
  gm_csr_free(f->S);
  free(f->rep);
  free(f->tri_own);
  free(f->edge_own);
  free(f->xq);
  free(f->normal);
  free(f->coriolis);
  gm_sparse_cholesky_free(f->m_visc);
  free(f->b_tail);
  free(f->b_head);
  free(f->b_circ);
  free(f->free_of);
  free(f->free_list);
  free(f->psi_fixed);
  free(f->psi_bc);
  gm_sparse_cholesky_free(f->m_half);
  gm_sparse_cholesky_free(f->m_full);
  gm_sparse_cholesky_free(f->poisson);
  gm_sparse_cholesky_free(f->m_theta);
  free(f->c_half);
  free(f->c_full);
  free(f->wfree_of);
  free(f->wfree_list);
  free(f->theta_fixed);
  free(f->theta_bc);
  free(f->c_theta);
  free(f->psi);
  free(f->theta);
  free(f->gamma);
  free(f->zeta);
  free(f->psi_h);
  free(f->gamma_h);
  free(f->zeta_h);
  free(f->gamma_k);
  free(f->psi_k);
  free(f->u_edge);
  free(f->out);
  free(f->rhs);
  free(f->rhs_w);
  free(f->sol);
  free(f);
}

const char *gm_fluid_errmsg(const gm_fluid *f) { return f ? f->errmsg : ""; }

/* The rows and columns of a listed in `list` (n of them; index_of maps a vertex to its
 * position in list or SIZE_MAX). */
static gm_status csr_restrict(const gm_csr *a, size_t n, const size_t *list, const size_t *index_of,
                              gm_csr **out) {
  size_t nnz = 0;
  for (size_t r = 0; r < n; ++r)
    for (size_t k = a->row_start[list[r]]; k < a->row_start[list[r] + 1]; ++k)
      if (index_of[a->col[k]] != SIZE_MAX) ++nnz;
  gm_status st = gm_csr_create(n, n, nnz, out);
  if (st) return st;
  gm_csr *m = *out;
  size_t p = 0;
  for (size_t r = 0; r < n; ++r) {
    m->row_start[r] = p;
    for (size_t k = a->row_start[list[r]]; k < a->row_start[list[r] + 1]; ++k) {
      size_t c = index_of[a->col[k]];
      if (c == SIZE_MAX) continue;
      m->col[p] = c; /* index_of is increasing along the vertex order, so columns stay sorted */
      m->val[p++] = a->val[k];
    }
  }
  m->row_start[n] = p;
  return GM_OK;
}

static double dist2(const double *a, const double *b) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]));
}

/* Outward normal velocity of a condition at point p of a boundary edge with ccw unit tangent t:
 * u·n_out with n_out = (t_y, −t_x); s = arc length from the start of the group's run. */
static int bc_velocity(const gm_fluid_bc *bc, const double *p, double s, double run_length,
                       const double *t, double *u_n, double *u_t) {
  double u[2] = {0.0, 0.0};
  if (bc->kind == GM_FLUID_WALL) {
    u[0] = bc->velocity[0];
    u[1] = bc->velocity[1];
    *u_n = 0.0; /* walls are impermeable whatever the vector given */
    *u_t = u[0] * t[0] + u[1] * t[1];
    return 0;
  }
  if (bc->kind == GM_FLUID_INFLOW && bc->profile) {
    if (bc->profile(bc->profile_ctx, p, u)) return 1;
    *u_n = u[0] * t[1] - u[1] * t[0];
    *u_t = u[0] * t[0] + u[1] * t[1];
    return 0;
  }
  if (bc->kind == GM_FLUID_INFLOW) { /* parabola 4 U s (l − s)/l² into the domain */
    double q = s / run_length;
    *u_n = -4.0 * bc->speed * q * (1.0 - q);
    *u_t = 0.0;
    return 0;
  }
  *u_n = 0.0;
  *u_t = 0.0;
  return 0;
}

static gm_status fail(gm_error *err, gm_fluid *f, gm_status st, const char *msg) {
  gm_error_set(err, st, "%s", msg);
  gm_fluid_free(f);
  return st;
}

#define TRY(expr)                                                          \
  do {                                                                     \
    st = (expr);                                                           \
    if (st) {                                                              \
      snprintf(msg, sizeof msg, "%s failed (%s)", #expr, gm_strerror(st)); \
      goto done;                                                           \
    }                                                                      \
  } while (0)
#define ALLOC(ptr, n)                                 \
  do {                                                \
    (ptr) = calloc((n) > 0 ? (n) : 1, sizeof *(ptr)); \
    if (!(ptr)) {                                     \
      st = GM_ENOMEM;                                 \
      snprintf(msg, sizeof msg, "out of memory");     \
      goto done;                                      \
    }                                                 \
  } while (0)

gm_status gm_fluid_create(const gm_mesh *mesh, const gm_fluid_groups *groups, size_t n_bcs,
                          const gm_fluid_bc *bcs, const gm_fluid_options *options, gm_fluid **out,
                          gm_error *err) {
  char msg[2 * GM_ERRMSG_SIZE] = "";
  gm_status st = GM_OK;
  if (!out) return gm_error_set(err, GM_EINVAL, "fluid: out is NULL");
  *out = NULL;
  if (!mesh || !groups || (n_bcs && !bcs))
    return gm_error_set(err, GM_EINVAL, "fluid: mesh, groups or bcs is NULL");
  gm_fluid_options opt = options ? *options : gm_fluid_defaults();
  if (!(opt.nu >= 0.0) || !isfinite(opt.nu))
    return gm_error_set(err, GM_EINVAL, "fluid: viscosity nu = %g must be finite and >= 0", opt.nu);
  if (!(opt.kappa >= 0.0) || !isfinite(opt.kappa))
    return gm_error_set(err, GM_EINVAL, "fluid: diffusivity kappa = %g must be finite and >= 0",
                        opt.kappa);
  if (!(opt.dt > 0.0) || !isfinite(opt.dt))
    return gm_error_set(err, GM_EINVAL, "fluid: time step dt = %g must be finite and > 0", opt.dt);
  if (!(opt.velocity_scale >= 0.0) || !isfinite(opt.velocity_scale))
    return gm_error_set(err, GM_EINVAL, "fluid: velocity_scale = %g must be finite and >= 0",
                        opt.velocity_scale);
  if (opt.scheme != GM_FLUID_SEED && opt.scheme != GM_FLUID_MIDPOINT)
    return gm_error_set(err, GM_EINVAL, "fluid: unknown scheme %d", (int)opt.scheme);
  if (opt.stress_free_walls && opt.scheme != GM_FLUID_MIDPOINT)
    return gm_error_set(err, GM_EINVAL,
                        "fluid: stress_free_walls applies to the midpoint scheme only");
  if (!(opt.midpoint_tol > 0.0) || opt.midpoint_max_iter == 0)
    return gm_error_set(err, GM_EINVAL,
                        "fluid: midpoint_tol must be > 0 and midpoint_max_iter >= 1");
  if (!(isfinite(opt.rotation)))
    return gm_error_set(err, GM_EINVAL, "fluid: rotation = %g must be finite", opt.rotation);
  if (mesh->dim != 2 || (mesh->N != 2 && mesh->N != 3))
    return gm_error_set(
        err, GM_EUNSUPPORTED,
        "fluid: needs a triangle mesh in the plane or a surface in R^3, got dim %zu in R^%zu",
        mesh->dim, mesh->N);
  int closed = mesh->N == 3;
  for (size_t i = 0; i < n_bcs; ++i) closed |= bcs[i].kind == GM_FLUID_PERIODIC;
  if (!closed && opt.scheme == GM_FLUID_MIDPOINT && opt.nu != 0.0)
    return gm_error_set(err, GM_EINVAL,
                        "fluid: the midpoint scheme with walls is inviscid: nu must be 0 (got %g); "
                        "viscosity needs a domain without boundary (periodic or closed surface)",
                        opt.nu);
  if (opt.rotation != 0.0 && mesh->N != 3)
    return gm_error_set(err, GM_EINVAL, "fluid: rotation applies to surfaces in R^3 only");
  if (closed && opt.stress_free_walls)
    return gm_error_set(err, GM_EINVAL, "fluid: stress_free_walls: the domain has no walls");
  for (size_t i = 0; i < n_bcs; ++i) {
    const gm_fluid_bc *b = &bcs[i];
    if (!b->group) return gm_error_set(err, GM_EINVAL, "fluid: bcs[%zu].group is NULL", i);
    if (b->kind > GM_FLUID_PERIODIC || b->scalar > GM_SCALAR_DIRICHLET)
      return gm_error_set(err, GM_EINVAL, "fluid: bcs[%zu] (\"%s\"): unknown kind", i, b->group);
    if (!isfinite(b->velocity[0]) || !isfinite(b->velocity[1]) || !isfinite(b->speed) ||
        !isfinite(b->scalar_value))
      return gm_error_set(err, GM_EDOMAIN, "fluid: bcs[%zu] (\"%s\"): non-finite value", i,
                          b->group);
    if (b->kind == GM_FLUID_PERIODIC && !b->partner)
      return gm_error_set(err, GM_EINVAL, "fluid: bcs[%zu] (\"%s\"): periodic without a partner",
                          i, b->group);
    if (b->kind == GM_FLUID_PERIODIC) continue;
    if (closed)
      return gm_error_set(err, GM_EUNSUPPORTED,
                          "fluid: group \"%s\" is not periodic: every boundary group of a periodic "
                          "domain must be (periodic channels with walls are not implemented)",
                          b->group);
    if (opt.scheme == GM_FLUID_MIDPOINT &&
        (b->kind != GM_FLUID_WALL || b->velocity[0] != 0.0 || b->velocity[1] != 0.0))
      return gm_error_set(err, GM_EUNSUPPORTED,
                          "fluid: the midpoint scheme needs a closed box of walls at rest; group "
                          "\"%s\" is not one",
                          b->group);
  }
  /* every condition names a group of the mesh */
  size_t *bc_of_group = calloc(groups->n_groups ? groups->n_groups : 1, sizeof *bc_of_group);
  if (!bc_of_group) return gm_error_set(err, GM_ENOMEM, "fluid: out of memory");
  for (size_t g = 0; g < groups->n_groups; ++g) bc_of_group[g] = SIZE_MAX;
  for (size_t i = 0; i < n_bcs; ++i) {
    size_t g = 0;
    if (bcs[i].kind == GM_FLUID_PERIODIC) {
      while (g < groups->n_groups && strcmp(groups->names[g], bcs[i].partner) != 0) ++g;
      if (g == groups->n_groups) {
        free(bc_of_group);
        return gm_error_set(err, GM_ENOTFOUND,
                            "fluid: periodic partner \"%s\" of bcs[%zu] (\"%s\") is not in the mesh",
                            bcs[i].partner, i, bcs[i].group);
      }
      g = 0;
    }
    while (g < groups->n_groups && strcmp(groups->names[g], bcs[i].group) != 0) ++g;
    if (g == groups->n_groups) {
      free(bc_of_group);
      return gm_error_set(err, GM_ENOTFOUND,
                          "fluid: boundary group \"%s\" (bcs[%zu]) is not in the mesh (%zu groups)",
                          bcs[i].group, i, groups->n_groups);
    }
    bc_of_group[g] = i;
  }

  gm_fluid *f = calloc(1, sizeof *f);
  if (!f) {
    free(bc_of_group);
    return gm_error_set(err, GM_ENOMEM, "fluid: out of memory");
  }
  f->opt = opt;
  gm_csr *LD = NULL, *LDL = NULL, *M = NULL, *Mr = NULL, *T = NULL;
  size_t *edge_bc = NULL, *next = NULL, *next_edge = NULL;
  double *lookup = NULL;
  gm_error sub;
  st = gm_mesh_complex(mesh, &f->cx, &sub);
  if (st) {
    snprintf(msg, sizeof msg, "fluid: %s", sub.message);
    goto done;
  }
  gm_geometry_options gopt = gm_geometry_defaults();
  st = gm_geometry_create(f->cx, &gopt, &f->geo, &sub);
  if (st) {
    snprintf(msg, sizeof msg, "fluid: %s", sub.message);
    goto done;
  }
  f->nv = gm_complex_count(f->cx, 0);
  f->ne = gm_complex_count(f->cx, 1);
  f->nt = gm_complex_count(f->cx, 2);
  f->edge = gm_complex_simplices(f->cx, 1);
  f->tri = gm_complex_simplices(f->cx, 2);
  f->x = gm_complex_coordinates(f->cx);

  /* The diagonal star (seed 004 eq. 146) needs positive ⋆0, ⋆1: refuse with counts. */
  {
    size_t neg0 = gm_geometry_negative_duals(f->geo, 0),
           neg1 = gm_geometry_negative_duals(f->geo, 1);
    if (neg0 || neg1) {
      size_t bad_tri = 0;
      for (size_t t = 0; t < f->nt; ++t) {
        double pc[3];
        if (gm_geometry_dual_pieces(f->geo, t, 1, pc) == GM_OK &&
            (pc[0] <= 0.0 || pc[1] <= 0.0 || pc[2] <= 0.0))
          ++bad_tri;
      }
      st = GM_EINVAL;
      snprintf(
          msg, sizeof msg,
          "fluid: mesh not well-centred for the diagonal Hodge star: %zu of %zu edges have "
          "star1 <= 0, %zu of %zu vertices star0 <= 0, %zu of %zu triangles do not contain "
          "their circumcentre (remesh acute, or use the Whitney star gm_geometry_whitney_mass)",
          neg1, f->ne, neg0, f->nv, bad_tri, f->nt);
      goto done;
    }
  }
  f->sdim = mesh->N;
  if (closed) {
    size_t *rep = NULL, nq = f->nv;
    if (mesh->N == 3) {
      if (n_bcs || groups->n_edges) {
        st = GM_EUNSUPPORTED;
        snprintf(msg, sizeof msg, "fluid: surfaces in R^3 must be closed (no boundary groups)");
        goto done;
      }
      if ((st = gm_fluid_manifold_check(f->cx, msg, sizeof msg))) goto done;
    } else {
      /* every boundary edge in a periodic group or a partner */
      const unsigned char *bm = gm_complex_boundary_mask(f->cx, 1);
      size_t covered = 0;
      for (size_t i = 0; i < groups->n_edges; ++i) {
        const char *name = groups->names[groups->group[i] < groups->n_groups ? groups->group[i] : 0];
        int per = 0;
        for (size_t b = 0; b < n_bcs; ++b)
          per |= strcmp(bcs[b].group, name) == 0 || strcmp(bcs[b].partner, name) == 0;
        size_t ev[2] = {groups->vertices[2 * i], groups->vertices[2 * i + 1]};
        size_t e = ev[0] < mesh->n_vertices && ev[1] < mesh->n_vertices
                       ? gm_complex_find(f->cx, 1, ev)
                       : SIZE_MAX;
        if (per && e != SIZE_MAX && bm[e]) ++covered;
      }
      if (covered != gm_complex_boundary_count(f->cx, 1)) {
        st = GM_EUNSUPPORTED;
        snprintf(msg, sizeof msg,
                 "fluid: %zu of %zu boundary edges are in periodic groups: every boundary edge of "
                 "a periodic domain must be (periodic channels with walls are not implemented)",
                 covered, gm_complex_boundary_count(f->cx, 1));
        goto done;
      }
      if ((st = gm_fluid_periodic_map(mesh, groups, n_bcs, bcs, &rep, &nq, f->period, msg,
                                      sizeof msg)))
        goto done;
    }
    f->closed = 1;
    st = gm_fluid_create_closed(f, rep, nq, msg, sizeof msg);
    if (!st) {
      memset(f->psi, 0, f->nv * sizeof(double));
      gm_fluid_circulation_of(f, f->psi, f->gamma);
    }
    goto done;
  }
  ALLOC(f->star0, f->nv);
  ALLOC(f->star1, f->ne);
  ALLOC(f->area, f->nt);
  ALLOC(f->grad, 6 * f->nt);
  memcpy(f->star0, gm_geometry_hodge_star(f->geo, 0), f->nv * sizeof(double));
  memcpy(f->star1, gm_geometry_hodge_star(f->geo, 1), f->ne * sizeof(double));
  f->h_min = INFINITY;
  for (size_t e = 0; e < f->ne; ++e) {
    double h = dist2(f->x + 2 * f->edge[2 * e], f->x + 2 * f->edge[2 * e + 1]);
    if (h < f->h_min) f->h_min = h;
  }
  /* ∇λ_k = rot90(p_{k+2} − p_{k+1}) / (2 signed area) on each triangle */
  for (size_t t = 0; t < f->nt; ++t) {
    const double *p[3] = {f->x + 2 * f->tri[3 * t], f->x + 2 * f->tri[3 * t + 1],
                          f->x + 2 * f->tri[3 * t + 2]};
    double a2 =
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    f->area[t] = 0.5 * fabs(a2);
    for (int k = 0; k < 3; ++k) {
      const double *q1 = p[(k + 1) % 3], *q2 = p[(k + 2) % 3];
      f->grad[6 * t + 2 * k] = -(q2[1] - q1[1]) / a2;
      f->grad[6 * t + 2 * k + 1] = (q2[0] - q1[0]) / a2;
    }
  }
  /* L = d0ᵀ ⋆1 d0 (seed 001 §3.9): the cotangent stiffness; Γ = Lψ + b is the circulation. */
  {
    gm_csr *S1 = NULL, *tmp = NULL, *d0t = NULL;
    const gm_csr *d0 = gm_complex_d(f->cx, 0);
    TRY(gm_geometry_hodge_star_matrix(f->geo, 1, 0, &S1));
    st = gm_csr_multiply(S1, d0, &tmp);
    if (!st) st = gm_csr_transpose(d0, &d0t);
    if (!st) st = gm_csr_multiply(d0t, tmp, &f->L);
    gm_csr_free(S1);
    gm_csr_free(tmp);
    gm_csr_free(d0t);
    if (st) {
      snprintf(msg, sizeof msg, "fluid: assembling the Laplacian failed");
      goto done;
    }
  }
  /* U = Sψ: tangential velocity ∫_e u·t along each edge, u_T = rot∇ψ_T averaged over the
   * cofaces with the weights |⋆e ∩ T|/|⋆e| of the DPP flat (Hirani 2003 §5.5; gm_dec_flat). */
  {
    size_t n3 = 9 * f->nt;
    size_t *ri = NULL, *ci = NULL;
    double *vv = NULL;
    ALLOC(ri, n3);
    ci = calloc(n3, sizeof *ci);
    vv = calloc(n3, sizeof *vv);
    if (!ci || !vv) {
      free(ri);
      free(ci);
      free(vv);
      st = GM_ENOMEM;
      snprintf(msg, sizeof msg, "out of memory");
      goto done;
    }
    size_t p = 0;
    const double *dual1 = gm_geometry_dual_volumes(f->geo, 1);
    for (size_t t = 0; t < f->nt; ++t) {
      size_t le[3];
      double pieces[3];
      gm_complex_local_faces(f->cx, t, 1, le);
      gm_geometry_dual_pieces(f->geo, t, 1, pieces);
      for (int j = 0; j < 3; ++j) {
        size_t e = le[j];
        const double *xi = f->x + 2 * f->edge[2 * e], *xj = f->x + 2 * f->edge[2 * e + 1];
        double ex = xj[0] - xi[0], ey = xj[1] - xi[1];
        double w = pieces[j] / dual1[e];
        for (int k = 0; k < 3; ++k) {
          double gx = f->grad[6 * t + 2 * k], gy = f->grad[6 * t + 2 * k + 1];
          ri[p] = e;
          ci[p] = f->tri[3 * t + k];
          vv[p++] = w * (gy * ex - gx * ey); /* (∂yλ, −∂xλ)·e⃗ */
        }
      }
    }
    st = gm_csr_from_triplets(f->ne, f->nv, p, ri, ci, vv, &f->S, &sub);
    free(ri);
    free(ci);
    free(vv);
    if (st) {
      snprintf(msg, sizeof msg, "fluid: %s", sub.message);
      goto done;
    }
  }

  /* ---- boundary: each boundary edge in a group with a condition, oriented ccw ---- */
  const unsigned char *bmask = gm_complex_boundary_mask(f->cx, 1);
  const size_t *cof = gm_complex_face_cofaces(f->cx);
  ALLOC(edge_bc, f->ne);
  for (size_t e = 0; e < f->ne; ++e) edge_bc[e] = SIZE_MAX;
  for (size_t i = 0; i < groups->n_edges; ++i) {
    size_t v[2] = {groups->vertices[2 * i], groups->vertices[2 * i + 1]};
    if (v[0] >= mesh->n_vertices || v[1] >= mesh->n_vertices ||
        groups->group[i] >= groups->n_groups) {
      st = GM_EINVAL;
      snprintf(msg, sizeof msg, "fluid: group edge %zu has an index out of range", i);
      goto done;
    }
    size_t e = gm_complex_find(f->cx, 1, v);
    if (e == SIZE_MAX || !bmask[e]) {
      st = GM_EINVAL;
      snprintf(msg, sizeof msg, "fluid: edge %zu-%zu of group \"%s\" is not a boundary edge", v[0],
               v[1], groups->names[groups->group[i]]);
      goto done;
    }
    edge_bc[e] = bc_of_group[groups->group[i]];
    if (edge_bc[e] == SIZE_MAX) {
      st = GM_EINVAL;
      snprintf(msg, sizeof msg, "fluid: boundary group \"%s\" has no condition",
               groups->names[groups->group[i]]);
      goto done;
    }
  }
  f->nb = gm_complex_boundary_count(f->cx, 1);
  ALLOC(f->b_tail, f->nb);
  ALLOC(f->b_head, f->nb);
  ALLOC(next, f->nv);
  ALLOC(next_edge, f->nv);
  for (size_t v = 0; v < f->nv; ++v) next[v] = next_edge[v] = SIZE_MAX;
  {
    size_t k = 0;
    for (size_t e = 0; e < f->ne; ++e) {
      if (!bmask[e]) continue;
      if (edge_bc[e] == SIZE_MAX) {
        st = GM_EINVAL;
        snprintf(msg, sizeof msg,
                 "fluid: boundary edge %zu-%zu at (%g, %g) belongs to no group with a condition",
                 f->edge[2 * e], f->edge[2 * e + 1], f->x[2 * f->edge[2 * e]],
                 f->x[2 * f->edge[2 * e] + 1]);
        goto done;
      }
      size_t t = cof[2 * e], i = f->edge[2 * e], j = f->edge[2 * e + 1], c = 0;
      for (int q = 0; q < 3; ++q)
        if (f->tri[3 * t + q] != i && f->tri[3 * t + q] != j) c = f->tri[3 * t + q];
      const double *xi = f->x + 2 * i, *xj = f->x + 2 * j, *xc = f->x + 2 * c;
      double cr = (xj[0] - xi[0]) * (xc[1] - xi[1]) - (xj[1] - xi[1]) * (xc[0] - xi[0]);
      size_t a = cr > 0 ? i : j, b = cr > 0 ? j : i;
      f->b_tail[k] = a;
      f->b_head[k] = b;
      next[a] = b;
      next_edge[a] = e;
      ++k;
    }
  }
  /* one boundary loop, at most one outflow run on it */
  size_t start = SIZE_MAX, n_out_runs = 0, loop_len = 0;
  for (size_t k = 0; k < f->nb; ++k) {
    size_t a = f->b_tail[k];
    int here_out = bcs[edge_bc[next_edge[a]]].kind == GM_FLUID_OUTFLOW;
    size_t b = f->b_head[k];
    int next_out = bcs[edge_bc[next_edge[b]]].kind == GM_FLUID_OUTFLOW;
    if (here_out && !next_out) {
      ++n_out_runs;
      start = b;
    }
  }
  if (start == SIZE_MAX) {
    if (bcs[edge_bc[next_edge[f->b_tail[0]]]].kind == GM_FLUID_OUTFLOW) {
      st = GM_EINVAL;
      snprintf(msg, sizeof msg, "fluid: the whole boundary is outflow: nothing fixes psi");
      goto done;
    }
    start = f->b_tail[0];
  }
  for (size_t v = start;;) {
    ++loop_len;
    v = next[v];
    if (v == start || v == SIZE_MAX || loop_len > f->nb) break;
  }
  if (loop_len != f->nb) {
    st = GM_EUNSUPPORTED;
    snprintf(msg, sizeof msg,
             "fluid: the boundary has more than one loop (%zu of %zu boundary edges on the first): "
             "multiply connected domains (island stream-function constants) are not implemented",
             loop_len, f->nb);
    goto done;
  }
  if (n_out_runs > 1) {
    st = GM_EUNSUPPORTED;
    snprintf(msg, sizeof msg,
             "fluid: %zu separate outflow runs on the boundary: at most one is supported",
             n_out_runs);
    goto done;
  }
  /* run lengths of inflow groups (for the parabola) */
  double *run_len = NULL;
  ALLOC(run_len, n_bcs);
  for (size_t k = 0; k < f->nb; ++k) {
    size_t e = next_edge[f->b_tail[k]];
    run_len[edge_bc[e]] += dist2(f->x + 2 * f->b_tail[k], f->x + 2 * f->b_head[k]);
  }
  /* Walk the loop ccw from `start`: ψ increases by ∫ u·n_out ds along the boundary (u = rot∇ψ,
   * so ∂ψ/∂s = u·n_out, exact by Simpson for the parabola); b_v collects ∫ u_t ds over the two
   * boundary halves of ∂⋆v, the part of the circulation Γ_v that L ψ does not see. */
  ALLOC(f->psi_fixed, f->nv);
  ALLOC(f->psi_bc, f->nv);
  ALLOC(f->b_circ, f->nv);
  ALLOC(f->theta_fixed, f->nv);
  ALLOC(f->theta_bc, f->nv);
  {
    double psi = 0.0, *s_run = calloc(n_bcs ? n_bcs : 1, sizeof *s_run);
    if (!s_run) {
      free(run_len);
      st = GM_ENOMEM;
      snprintf(msg, sizeof msg, "out of memory");
      goto done;
    }
    double u_max = 0.0;
    size_t v = start;
    for (size_t k = 0; k < f->nb; ++k) {
      size_t e = next_edge[v], w = next[v], ib = edge_bc[e];
      const gm_fluid_bc *bc = &bcs[ib];
      const double *xa = f->x + 2 * v, *xb = f->x + 2 * w;
      double len = dist2(xa, xb), tt[2] = {(xb[0] - xa[0]) / len, (xb[1] - xa[1]) / len};
      if (bc->kind != GM_FLUID_OUTFLOW) {
        double s0 = s_run[ib], un[3], ut[3];
        for (int q = 0; q < 3; ++q) { /* endpoints and midpoint (Simpson); quarter points for u_t */
          double a = 0.5 * q, p[2] = {xa[0] + a * (xb[0] - xa[0]), xa[1] + a * (xb[1] - xa[1])};
          if (bc_velocity(bc, p, s0 + a * len, run_len[ib], tt, &un[q], &ut[q])) {
            free(s_run);
            free(run_len);
            st = GM_ECALLBACK;
            snprintf(msg, sizeof msg, "fluid: the inflow profile of \"%s\" failed", bc->group);
            goto done;
          }
          if (fabs(un[q]) > u_max) u_max = fabs(un[q]);
          if (fabs(ut[q]) > u_max) u_max = fabs(ut[q]);
        }
        double ut_a, ut_b, dummy;
        double pa[2] = {xa[0] + 0.25 * (xb[0] - xa[0]), xa[1] + 0.25 * (xb[1] - xa[1])};
        double pb[2] = {xa[0] + 0.75 * (xb[0] - xa[0]), xa[1] + 0.75 * (xb[1] - xa[1])};
        bc_velocity(bc, pa, s0 + 0.25 * len, run_len[ib], tt, &dummy, &ut_a);
        bc_velocity(bc, pb, s0 + 0.75 * len, run_len[ib], tt, &dummy, &ut_b);
        f->b_circ[v] += 0.5 * len * ut_a;
        f->b_circ[w] += 0.5 * len * ut_b;
        f->psi_fixed[v] = f->psi_fixed[w] = 1;
        f->psi_bc[v] = psi;
        psi += len * (un[0] + 4.0 * un[1] + un[2]) / 6.0;
        f->psi_bc[w] = psi;
      }
      s_run[ib] += len;
      if (bc->scalar == GM_SCALAR_DIRICHLET) {
        if (!f->theta_fixed[v]) f->theta_bc[v] = bc->scalar_value;
        if (!f->theta_fixed[w]) f->theta_bc[w] = bc->scalar_value;
        f->theta_fixed[v] = f->theta_fixed[w] = 1;
      }
      v = w;
    }
    free(s_run);
    if (n_out_runs == 0 && fabs(psi) > 1e-12 * (1.0 + u_max)) {
      free(run_len);
      st = GM_EINVAL;
      snprintf(msg, sizeof msg,
               "fluid: net inflow %g through a boundary without outflow (mass cannot be conserved)",
               -psi);
      goto done;
    }
    if (opt.velocity_scale > u_max) u_max = opt.velocity_scale;
    f->dt_bound = u_max > 0.0 ? 2.0 * f->h_min / u_max : INFINITY;
  }
  free(run_len);
  /* Explicit half step (153) [R]: forward Euler over dt/2 of the convection, Courant number
   * (dt/2)|u|/h_min <= 1. */
  if (opt.scheme == GM_FLUID_SEED && opt.dt > f->dt_bound) {
    st = GM_EINVAL;
    snprintf(msg, sizeof msg,
             "fluid: dt = %g is above the bound %.6g of the explicit half step (2 h_min/|u|max, "
             "h_min = %.6g)",
             opt.dt, f->dt_bound, f->h_min);
    goto done;
  }
  /* free vertices for ψ and θ */
  ALLOC(f->free_of, f->nv);
  ALLOC(f->free_list, f->nv);
  ALLOC(f->wfree_of, f->nv);
  ALLOC(f->wfree_list, f->nv);
  for (size_t v = 0; v < f->nv; ++v) {
    f->free_of[v] = f->wfree_of[v] = SIZE_MAX;
    if (!f->psi_fixed[v]) {
      f->free_of[v] = f->n_free;
      f->free_list[f->n_free++] = v;
    }
    if (!f->theta_fixed[v]) {
      f->wfree_of[v] = f->n_wfree;
      f->wfree_list[f->n_wfree++] = v;
    }
  }
  if (f->n_free == 0) {
    st = GM_EINVAL;
    snprintf(msg, sizeof msg, "fluid: the mesh has no interior vertex");
    goto done;
  }
  ALLOC(f->c_half, f->n_free);
  ALLOC(f->c_full, f->n_free);
  ALLOC(f->c_theta, f->n_wfree);
  ALLOC(f->psi, f->nv);
  ALLOC(f->theta, f->nv);
  ALLOC(f->gamma, f->nv);
  ALLOC(f->zeta, f->nv);
  ALLOC(f->psi_h, f->nv);
  ALLOC(f->gamma_h, f->nv);
  ALLOC(f->zeta_h, f->nv);
  ALLOC(f->gamma_k, f->nv);
  ALLOC(f->psi_k, f->nv);
  ALLOC(f->u_edge, f->ne);
  ALLOC(f->out, f->nv);
  ALLOC(f->rhs, f->nv);
  ALLOC(f->rhs_w, f->nv);
  ALLOC(f->sol, f->nv);

  /* Poisson matrix L on the free vertices: ψ from Γ (156: ⋆ω = dψ, Γ = d̃ ⋆1 dψ) [R]. */
  TRY(csr_restrict(f->L, f->n_free, f->free_list, f->free_of, &Mr));
  st = gm_sparse_cholesky_create(Mr, &f->poisson, &sub);
  gm_csr_free(Mr);
  Mr = NULL;
  if (st) {
    snprintf(msg, sizeof msg, "fluid: Poisson matrix: %s", sub.message);
    goto done;
  }
  /* Semi-implicit steps (153, 154) [R] solved for ψ: Γ + α ν L ⋆0⁻¹ Γ = r with Γ = Lψ + b, i.e.
   * (L + α ν L ⋆0⁻¹ L) ψ = r − b − α ν L ⋆0⁻¹ b, α = dt/2 (half step) and dt (full step);
   * symmetric positive definite on the free vertices. */
  if (opt.scheme == GM_FLUID_SEED) {
    double *inv0 = NULL, *g = NULL, *h = NULL;
    ALLOC(inv0, f->nv);
    for (size_t v = 0; v < f->nv; ++v) inv0[v] = 1.0 / f->star0[v];
    TRY(gm_csr_copy(f->L, &LD));
    gm_csr_scale_cols(LD, inv0);
    TRY(gm_csr_multiply(LD, f->L, &LDL));
    g = calloc(f->nv, sizeof *g);
    h = calloc(f->nv, sizeof *h);
    if (!g || !h) {
      free(inv0);
      free(g);
      free(h);
      st = GM_ENOMEM;
      snprintf(msg, sizeof msg, "out of memory");
      goto done;
    }
    gm_fluid_circulation_of(f, f->psi_bc, g); /* zero ψ on free vertices: g = Lψ_B + b */
    for (int pass = 0; pass < 2; ++pass) {
      double alpha = (pass == 0 ? 0.5 : 1.0) * opt.dt * opt.nu;
      TRY(gm_csr_add(1.0, f->L, alpha, LDL, &M));
      TRY(csr_restrict(M, f->n_free, f->free_list, f->free_of, &Mr));
      gm_csr_free(M);
      M = NULL;
      st = gm_sparse_cholesky_create(Mr, pass == 0 ? &f->m_half : &f->m_full, &sub);
      gm_csr_free(Mr);
      Mr = NULL;
      if (st) {
        free(inv0);
        free(g);
        free(h);
        snprintf(msg, sizeof msg, "fluid: vorticity matrix: %s", sub.message);
        goto done;
      }
      for (size_t v = 0; v < f->nv; ++v) h[v] = g[v] * inv0[v];
      gm_csr_matvec(f->L, alpha, h, 0.0, f->sol);
      double *c = pass == 0 ? f->c_half : f->c_full;
      for (size_t i = 0; i < f->n_free; ++i) {
        size_t v = f->free_list[i];
        c[i] = -(g[v] + f->sol[v]);
      }
    }
    free(inv0);
    free(g);
    free(h);
  }
  /* Scalar (155) [R], diffusion implicit: (⋆0/dt + κL) θ on the non-Dirichlet vertices. */
  if (f->n_wfree) {
    double *d = NULL;
    ALLOC(d, f->nv);
    for (size_t v = 0; v < f->nv; ++v) d[v] = f->star0[v] / opt.dt;
    gm_csr *D = NULL;
    st = gm_csr_diagonal(f->nv, d, &D);
    free(d);
    if (st) {
      snprintf(msg, sizeof msg, "out of memory");
      goto done;
    }
    st = gm_csr_add(1.0, D, opt.kappa, f->L, &T);
    gm_csr_free(D);
    if (st) {
      snprintf(msg, sizeof msg, "out of memory");
      goto done;
    }
    TRY(csr_restrict(T, f->n_wfree, f->wfree_list, f->wfree_of, &Mr));
    st = gm_sparse_cholesky_create(Mr, &f->m_theta, &sub);
    gm_csr_free(Mr);
    Mr = NULL;
    if (st) {
      snprintf(msg, sizeof msg, "fluid: scalar matrix: %s", sub.message);
      goto done;
    }
    gm_csr_matvec(f->L, -opt.kappa, f->theta_bc, 0.0, f->sol);
    for (size_t i = 0; i < f->n_wfree; ++i) f->c_theta[i] = f->sol[f->wfree_list[i]];
  }
  /* initial state */
  memcpy(f->psi, f->psi_bc, f->nv * sizeof(double));
  memcpy(f->theta, f->theta_bc, f->nv * sizeof(double));
  gm_fluid_circulation_of(f, f->psi, f->gamma);

done:
  free(bc_of_group);
  free(edge_bc);
  free(next);
  free(next_edge);
  free(lookup);
  gm_csr_free(LD);
  gm_csr_free(LDL);
  gm_csr_free(M);
  gm_csr_free(Mr);
  gm_csr_free(T);
  if (st) return fail(err, f, st, msg);
  *out = f;
  return GM_OK;
}

void gm_fluid_circulation_of(const gm_fluid *f, const double *psi, double *gamma) {
  gm_csr_matvec(f->L, 1.0, psi, 0.0, gamma);
  for (size_t v = 0; v < f->nv; ++v) gamma[v] += f->b_circ[v];
}
