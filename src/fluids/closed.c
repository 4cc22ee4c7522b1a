/* DEC fluid solver on domains without boundary: fully periodic planar meshes (the quotient
 * complex of periodic pairs of boundary groups) and closed triangle surfaces in R³ (the DEC is
 * intrinsic: ⋆0, ⋆1 and the P1 Jacobian need only the metric of each triangle).
 *
 * Quotient: mesh vertices identified across each periodic pair form one solver vertex. Every
 * operator is assembled on the mesh and summed onto the quotient: ⋆0 of a class is the sum of
 * its boundary pieces (the halves of a dual cell cut by the seam), and L_q = Pᵀ L P with P the
 * 0/1 map from solver to mesh vertices, i.e. d0ᵀ ⋆1 d0 of the quotient with the two half dual
 * edges of an identified edge added. Triangles keep their own (unrolled) coordinates for the
 * gradients, so nothing needs coordinates of a class. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "dec/internal.h"
#include "fluids/internal.h"

static size_t uf_find(size_t *parent, size_t v) {
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

static void uf_union(size_t *parent, size_t a, size_t b) {
  a = uf_find(parent, a);
  b = uf_find(parent, b);
  if (a < b)
    parent[b] = a;
  else if (b < a)
    parent[a] = b;
}

gm_status gm_fluid_periodic_map(const gm_mesh *mesh, const gm_fluid_groups *groups, size_t n_bcs,
                                const gm_fluid_bc *bcs, size_t **rep_out, size_t *nq_out,
                                char *msg, size_t msg_size) {
  const size_t nv = mesh->n_vertices;
  const double *x = mesh->x;
  size_t *parent = malloc(nv * sizeof *parent), *rep = malloc(nv * sizeof *rep);
  size_t *in_a = NULL, *in_b = NULL;
  unsigned char *mark = calloc(nv, 1);
  gm_status st = GM_OK;
  if (!parent || !rep || !mark) {
    st = GM_ENOMEM;
    snprintf(msg, msg_size, "fluid: out of memory");
    goto done;
  }
  for (size_t v = 0; v < nv; ++v) parent[v] = v;
  double size = 0.0;
  for (size_t v = 0; v < nv; ++v) size = fmax(size, fmax(fabs(x[2 * v]), fabs(x[2 * v + 1])));
  const double tol = 1e-9 * (size > 0 ? size : 1.0);
  for (size_t i = 0; i < n_bcs; ++i) {
    if (bcs[i].kind != GM_FLUID_PERIODIC) continue;
    size_t ga = SIZE_MAX, gb = SIZE_MAX;
    for (size_t g = 0; g < groups->n_groups; ++g) {
      if (strcmp(groups->names[g], bcs[i].group) == 0) ga = g;
      if (strcmp(groups->names[g], bcs[i].partner) == 0) gb = g;
    }
    if (gb == SIZE_MAX) {
      st = GM_ENOTFOUND;
      snprintf(msg, msg_size, "fluid: periodic partner \"%s\" of group \"%s\" is not in the mesh",
               bcs[i].partner, bcs[i].group);
      goto done;
    }
    /* the vertices of each group, and the translation between their bounding boxes */
    size_t na = 0, nb = 0;
    double lo_a[2] = {INFINITY, INFINITY}, lo_b[2] = {INFINITY, INFINITY};
    free(in_a);
    free(in_b);
    in_a = malloc(2 * groups->n_edges * sizeof *in_a + 1);
    in_b = malloc(2 * groups->n_edges * sizeof *in_b + 1);
    if (!in_a || !in_b) {
      st = GM_ENOMEM;
      snprintf(msg, msg_size, "fluid: out of memory");
      goto done;
    }
    for (int side = 0; side < 2; ++side) {
      size_t g = side ? gb : ga, *list = side ? in_b : in_a, *n = side ? &nb : &na;
      double *lo = side ? lo_b : lo_a;
      memset(mark, 0, nv);
      for (size_t e = 0; e < groups->n_edges; ++e) {
        if (groups->group[e] != g) continue;
        for (int k = 0; k < 2; ++k) {
          size_t v = groups->vertices[2 * e + k];
          if (v >= nv || mark[v]) continue;
          mark[v] = 1;
          list[(*n)++] = v;
          lo[0] = fmin(lo[0], x[2 * v]);
          lo[1] = fmin(lo[1], x[2 * v + 1]);
        }
      }
    }
    double off[2] = {lo_b[0] - lo_a[0], lo_b[1] - lo_a[1]};
    if (na != nb || na == 0) {
      st = GM_EINVAL;
      snprintf(msg, msg_size,
               "fluid: periodic groups \"%s\" (%zu vertices) and \"%s\" (%zu) do not match",
               bcs[i].group, na, bcs[i].partner, nb);
      goto done;
    }
    for (size_t p = 0; p < na; ++p) {
      size_t a = in_a[p], hit = SIZE_MAX;
      for (size_t q = 0; q < nb && hit == SIZE_MAX; ++q) {
        size_t b = in_b[q];
        if (fabs(x[2 * a] + off[0] - x[2 * b]) <= tol &&
            fabs(x[2 * a + 1] + off[1] - x[2 * b + 1]) <= tol)
          hit = b;
      }
      if (hit == SIZE_MAX) {
        st = GM_EINVAL;
        snprintf(msg, msg_size,
                 "fluid: vertex (%g, %g) of periodic group \"%s\" has no partner in \"%s\" at "
                 "offset (%g, %g)",
                 x[2 * a], x[2 * a + 1], bcs[i].group, bcs[i].partner, off[0], off[1]);
        goto done;
      }
      uf_union(parent, a, hit);
    }
  }
  /* number the classes by their lowest vertex: rep is increasing along class minima */
  size_t nq = 0;
  for (size_t v = 0; v < nv; ++v) {
    size_t r = uf_find(parent, v);
    rep[v] = r == v ? nq++ : rep[r];
  }
  *rep_out = rep;
  *nq_out = nq;
  rep = NULL;
done:
  free(parent);
  free(rep);
  free(in_a);
  free(in_b);
  free(mark);
  return st;
}

gm_status gm_fluid_manifold_check(const gm_complex *cx, char *msg, size_t msg_size) {
  const size_t nv = gm_complex_count(cx, 0), ne = gm_complex_count(cx, 1),
               nt = gm_complex_count(cx, 2);
  const size_t *cof = gm_complex_face_cofaces(cx), *tri = gm_complex_simplices(cx, 2);
  size_t open = 0, first_open = SIZE_MAX;
  for (size_t e = 0; e < ne; ++e)
    if (cof[2 * e + 1] == SIZE_MAX) {
      if (first_open == SIZE_MAX) first_open = e;
      ++open;
    }
  /* each vertex: its triangles must form one closed fan (a disc), walked across edges */
  size_t *count = calloc(nv ? nv : 1, sizeof *count);
  unsigned char *walked = calloc(nv ? nv : 1, 1);
  if (!count || !walked) {
    free(count);
    free(walked);
    snprintf(msg, msg_size, "fluid: out of memory");
    return GM_ENOMEM;
  }
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) ++count[tri[3 * t + k]];
  size_t bad = 0, first_bad = SIZE_MAX;
  if (open == 0)
    for (size_t t0 = 0; t0 < nt; ++t0)
      for (int k0 = 0; k0 < 3; ++k0) {
        size_t v = tri[3 * t0 + k0];
        if (walked[v]) continue; /* one fan per vertex: it must hold all its triangles */
        walked[v] = 1;
        /* walk around v: from triangle t cross the edge (v, w) not yet used */
        size_t t = t0, len = 0, came = SIZE_MAX;
        do {
          ++len;
          size_t le[3], next = SIZE_MAX;
          gm_complex_local_faces(cx, t, 1, le);
          for (int j = 0; j < 3 && next == SIZE_MAX; ++j) {
            const size_t *ev = gm_complex_simplices(cx, 1) + 2 * le[j];
            if ((ev[0] != v && ev[1] != v) || le[j] == came) continue;
            came = le[j];
            next = cof[2 * le[j]] == t ? cof[2 * le[j] + 1] : cof[2 * le[j]];
          }
          t = next;
        } while (t != t0 && t != SIZE_MAX && len <= count[v]);
        if (len != count[v]) {
          if (first_bad == SIZE_MAX) first_bad = v;
          ++bad;
        }
      }
  free(count);
  free(walked);
  if (open || bad) {
    const double *x = gm_complex_coordinates(cx);
    size_t N = gm_complex_embedding_dim(cx), v = open ? gm_complex_simplices(cx, 1)[2 * first_open]
                                                   : first_bad;
    snprintf(msg, msg_size,
             "fluid: the surface is not a closed manifold: %zu edges on fewer than two triangles, "
             "%zu vertices whose triangles do not form one fan (first at (%g, %g, %g))",
             open, bad, x[N * v], x[N * v + 1], N > 2 ? x[N * v + 2] : 0.0);
    return GM_EINVAL;
  }
  return GM_OK;
}

#define ALLOC(ptr, n)                                 \
  do {                                                \
    (ptr) = calloc((n) > 0 ? (n) : 1, sizeof *(ptr)); \
    if (!(ptr)) goto nomem;                           \
  } while (0)

gm_status gm_fluid_create_closed(gm_fluid *f, size_t *rep, size_t nq, char *msg,
                                 size_t msg_size) {
  const gm_fluid_options *opt = &f->opt;
  const size_t nm = gm_complex_count(f->cx, 0), sd = f->sdim;
  const double *xm = gm_complex_coordinates(f->cx);
  gm_csr *S1 = NULL, *tmp = NULL, *d0t = NULL, *Lm = NULL, *M = NULL, *Mr = NULL, *D = NULL;
  size_t *ri = NULL, *ci = NULL;
  double *vv = NULL;
  gm_error sub;
  gm_status st = GM_OK;
  f->rep = rep;
  f->n_mesh_vertices = nm;
  f->nv = rep ? nq : nm;
  const size_t nv = f->nv;
  ALLOC(f->star0, nv);
  ALLOC(f->area, f->nt);
  ALLOC(f->grad, 3 * sd * f->nt);
  ALLOC(f->tri_own, 3 * f->nt);
  ALLOC(f->xq, sd * nv);
  const double *s0 = gm_geometry_hodge_star(f->geo, 0);
  for (size_t v = nm; v-- > 0;) { /* downwards: a class keeps its lowest vertex's coordinates */
    size_t q = rep ? rep[v] : v;
    f->star0[q] += s0[v];
    memcpy(f->xq + sd * q, xm + sd * v, sd * sizeof(double));
  }
  for (size_t k = 0; k < 3 * f->nt; ++k) f->tri_own[k] = rep ? rep[f->tri[k]] : f->tri[k];
  /* per triangle: area, ∇λ_k (tangent to the triangle), the unit normal of its orientation */
  if (sd == 3) ALLOC(f->normal, 3 * f->nt);
  for (size_t t = 0; t < f->nt; ++t) {
    const size_t *tv = f->tri + 3 * t;
    double e1[3] = {0}, e2[3] = {0};
    for (size_t c = 0; c < sd; ++c) {
      e1[c] = xm[sd * tv[1] + c] - xm[sd * tv[0] + c];
      e2[c] = xm[sd * tv[2] + c] - xm[sd * tv[0] + c];
    }
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    double a2 = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    f->area[t] = 0.5 * a2;
    double s = sd == 3 ? (double)gm_simplex_sign(f->cx, 2, t) : (n[2] > 0 ? 1.0 : -1.0);
    for (int c = 0; c < 3; ++c) n[c] *= s / a2; /* the orientation's unit normal (ẑ in the plane) */
    if (sd == 3) memcpy(f->normal + 3 * t, n, sizeof n);
    for (int k = 0; k < 3; ++k) { /* ∇λ_k = n × (p_{k+2} − p_{k+1}) / (2|T|) */
      const double *q1 = xm + sd * tv[(k + 1) % 3], *q2 = xm + sd * tv[(k + 2) % 3];
      double e[3] = {0};
      for (size_t c = 0; c < sd; ++c) e[c] = q2[c] - q1[c];
      double g[3] = {n[1] * e[2] - n[2] * e[1], n[2] * e[0] - n[0] * e[2],
                     n[0] * e[1] - n[1] * e[0]};
      for (size_t c = 0; c < sd; ++c) f->grad[(3 * t + (size_t)k) * sd + c] = g[c] / a2;
    }
  }
  for (size_t t = 0; t < f->nt; ++t) {
    const size_t *q = f->tri_own + 3 * t;
    if (q[0] == q[1] || q[1] == q[2] || q[0] == q[2]) {
      snprintf(msg, msg_size,
               "fluid: triangle %zu collapses in the periodic quotient (two of its vertices are "
               "identified): use more cells across the period",
               t);
      return GM_EINVAL;
    }
  }
  /* L = d0ᵀ ⋆1 d0 on the mesh, then Pᵀ L P on the quotient */
  {
    const gm_csr *d0 = gm_complex_d(f->cx, 0);
    st = gm_geometry_hodge_star_matrix(f->geo, 1, 0, &S1);
    if (!st) st = gm_csr_multiply(S1, d0, &tmp);
    if (!st) st = gm_csr_transpose(d0, &d0t);
    if (!st) st = gm_csr_multiply(d0t, tmp, &Lm);
    if (st) goto nomem;
    if (rep) {
      size_t nnz = Lm->row_start[nm];
      ALLOC(ri, nnz);
      ALLOC(ci, nnz);
      ALLOC(vv, nnz);
      for (size_t r = 0; r < nm; ++r)
        for (size_t k = Lm->row_start[r]; k < Lm->row_start[r + 1]; ++k) {
          ri[k] = rep[r];
          ci[k] = rep[Lm->col[k]];
          vv[k] = Lm->val[k];
        }
      st = gm_csr_from_triplets(nv, nv, nnz, ri, ci, vv, &f->L, &sub);
      if (st) goto nomem;
    } else {
      f->L = Lm;
      Lm = NULL;
    }
  }
  /* gauge: ψ = 0 at vertex 0 (ψ is defined up to a constant without boundary) */
  ALLOC(f->psi_fixed, nv);
  ALLOC(f->psi_bc, nv);
  ALLOC(f->b_circ, nv);
  ALLOC(f->theta_fixed, nv);
  ALLOC(f->theta_bc, nv);
  ALLOC(f->free_of, nv);
  ALLOC(f->free_list, nv);
  ALLOC(f->wfree_of, nv);
  ALLOC(f->wfree_list, nv);
  f->psi_fixed[0] = 1;
  f->free_of[0] = SIZE_MAX;
  for (size_t v = 1; v < nv; ++v) {
    f->free_of[v] = f->n_free;
    f->free_list[f->n_free++] = v;
  }
  for (size_t v = 0; v < nv; ++v) {
    f->wfree_of[v] = v;
    f->wfree_list[v] = v;
  }
  f->n_wfree = nv;
  ALLOC(f->c_theta, nv);
  ALLOC(f->psi, nv);
  ALLOC(f->theta, nv);
  ALLOC(f->gamma, nv);
  ALLOC(f->zeta, nv);
  ALLOC(f->psi_h, nv);
  ALLOC(f->gamma_h, nv);
  ALLOC(f->zeta_h, nv);
  ALLOC(f->gamma_k, nv);
  ALLOC(f->psi_k, nv);
  ALLOC(f->out, nv);
  ALLOC(f->rhs, nv);
  ALLOC(f->rhs_w, nv);
  ALLOC(f->sol, nv);
  ALLOC(f->coriolis, nv);
  if (sd == 3 && opt->rotation != 0.0)
    for (size_t v = 0; v < nv; ++v) {
      const double *p = f->xq + 3 * v;
      double r = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      f->coriolis[v] = r > 0 ? 2.0 * opt->rotation * p[2] / r : 0.0;
    }
  /* Poisson (ψ from Γ on the free vertices) */
  {
    size_t *idx = f->free_of;
    size_t nnz = 0;
    for (size_t r = 1; r < nv; ++r)
      for (size_t k = f->L->row_start[r]; k < f->L->row_start[r + 1]; ++k) nnz += f->L->col[k] != 0;
    st = gm_csr_create(nv - 1, nv - 1, nnz, &Mr);
    if (st) goto nomem;
    size_t p = 0;
    for (size_t r = 1; r < nv; ++r) {
      Mr->row_start[r - 1] = p;
      for (size_t k = f->L->row_start[r]; k < f->L->row_start[r + 1]; ++k) {
        if (f->L->col[k] == 0) continue;
        Mr->col[p] = idx[f->L->col[k]];
        Mr->val[p++] = f->L->val[k];
      }
    }
    Mr->row_start[nv - 1] = p;
    st = gm_sparse_cholesky_create(Mr, &f->poisson, &sub);
    if (st) {
      snprintf(msg, msg_size, "fluid: Poisson matrix: %s", sub.message);
      goto fail;
    }
  }
  /* viscous part of the midpoint rule: (⋆0 + ν dt/2 L) ζ^{n+1} = ... (SPD) */
  double *d = NULL;
  ALLOC(d, nv);
  if (opt->nu > 0.0) {
    st = gm_csr_diagonal(nv, f->star0, &D);
    if (!st) st = gm_csr_add(1.0, D, 0.5 * opt->dt * opt->nu, f->L, &M);
    gm_csr_free(D);
    D = NULL;
    if (st) {
      free(d);
      goto nomem;
    }
    st = gm_sparse_cholesky_create(M, &f->m_visc, &sub);
    gm_csr_free(M);
    M = NULL;
    if (st) {
      free(d);
      snprintf(msg, msg_size, "fluid: viscous matrix: %s", sub.message);
      goto fail;
    }
  }
  /* scalar: (⋆0/dt + κL) θ^{n+1} = ⋆0 θ^n/dt + J(ψ^{n+½}, θ^n) */
  for (size_t v = 0; v < nv; ++v) d[v] = f->star0[v] / opt->dt;
  st = gm_csr_diagonal(nv, d, &D);
  free(d);
  if (!st) st = gm_csr_add(1.0, D, opt->kappa, f->L, &M);
  if (st) goto nomem;
  st = gm_sparse_cholesky_create(M, &f->m_theta, &sub);
  if (st) {
    snprintf(msg, msg_size, "fluid: scalar matrix: %s", sub.message);
    goto fail;
  }
  f->dt_bound = INFINITY;
  f->h_min = INFINITY;
  f->tri = f->tri_own; /* solver vertices from here on; grad keeps the unrolled geometry */
  goto fail; /* normal exit through the cleanup below, st == GM_OK */
nomem:
  if (!st || st == GM_ENOMEM) st = GM_ENOMEM;
  snprintf(msg, msg_size, "fluid: out of memory (or assembling a matrix failed)");
fail:
  gm_csr_free(S1);
  gm_csr_free(tmp);
  gm_csr_free(d0t);
  gm_csr_free(Lm);
  gm_csr_free(M);
  gm_csr_free(Mr);
  gm_csr_free(D);
  free(ri);
  free(ci);
  free(vv);
  return st;
}
