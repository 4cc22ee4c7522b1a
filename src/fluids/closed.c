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
                                double period[2], char *msg, size_t msg_size) {
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
    for (int k = 0; k < 2; ++k) period[k] = fmax(period[k], fabs(off[k]));
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


/* a without row and column 0 (the gauge vertex); idx maps the other vertices to 0..n−2 */
static gm_status restrict_gauge(const gm_csr *a, const size_t *idx, gm_csr **out) {
  const size_t nv = a->n_rows;
  size_t nnz = 0;
  for (size_t r = 1; r < nv; ++r)
    for (size_t k = a->row_start[r]; k < a->row_start[r + 1]; ++k) nnz += a->col[k] != 0;
  gm_status st = gm_csr_create(nv - 1, nv - 1, nnz, out);
  if (st) return st;
  gm_csr *m = *out;
  size_t p = 0;
  for (size_t r = 1; r < nv; ++r) {
    m->row_start[r - 1] = p;
    for (size_t k = a->row_start[r]; k < a->row_start[r + 1]; ++k) {
      if (a->col[k] == 0) continue;
      m->col[p] = idx[a->col[k]];
      m->val[p++] = a->val[k];
    }
  }
  m->row_start[nv - 1] = p;
  return GM_OK;
}

typedef struct qedge {
  size_t a, b, e; /* solver vertices a < b, mesh edge e */
} qedge;

static int cmp_qedge(const void *p, const void *q) {
  const qedge *x = p, *y = q;
  if (x->a != y->a) return x->a < y->a ? -1 : 1;
  if (x->b != y->b) return x->b < y->b ? -1 : 1;
  return (x->e > y->e) - (x->e < y->e);
}

/* What the seed scheme needs besides L: the edges of the quotient (a mesh edge and its periodic
 * image are one; ⋆1 and the dual length summed over the copies), U = Sψ the tangential velocity
 * u_T·e⃗ averaged over the cofaces with the DPP-flat weights |⋆e ∩ T|/|⋆e| (Hirani 2003 §5.5)
 * and u = ∇ψ × n, the two matrices of the semi-implicit steps (153, 154) on the free vertices,
 * and h_min for the Courant bound of the explicit half step. Called before f->tri is remapped. */
static gm_status seed_parts(gm_fluid *f, char *msg, size_t msg_size) {
  const size_t nm_e = gm_complex_count(f->cx, 1), sd = f->sdim, nv = f->nv;
  const size_t *me = gm_complex_simplices(f->cx, 1);
  const double *xm = gm_complex_coordinates(f->cx), *s1 = gm_geometry_hodge_star(f->geo, 1),
               *dual1 = gm_geometry_dual_volumes(f->geo, 1);
  gm_status st = GM_OK;
  gm_error sub;
  qedge *q = malloc((nm_e ? nm_e : 1) * sizeof *q);
  size_t *qof = malloc((nm_e ? nm_e : 1) * sizeof *qof);
  double *sgn = malloc((nm_e ? nm_e : 1) * sizeof *sgn), *qdual = NULL, *inv0 = NULL;
  size_t *ri = NULL, *ci = NULL;
  double *vv = NULL;
  gm_csr *LD = NULL, *LDL = NULL, *M = NULL, *Mr = NULL;
  if (!q || !qof || !sgn) goto nomem;
  for (size_t e = 0; e < nm_e; ++e) {
    size_t a = f->rep ? f->rep[me[2 * e]] : me[2 * e], b = f->rep ? f->rep[me[2 * e + 1]] : me[2 * e + 1];
    sgn[e] = a < b ? 1.0 : -1.0;
    q[e].a = a < b ? a : b;
    q[e].b = a < b ? b : a;
    q[e].e = e;
    double h2 = 0.0;
    for (size_t c = 0; c < sd; ++c) {
      double d = xm[sd * me[2 * e] + c] - xm[sd * me[2 * e + 1] + c];
      h2 += d * d;
    }
    f->h_min = fmin(f->h_min, sqrt(h2));
  }
  qsort(q, nm_e, sizeof *q, cmp_qedge);
  size_t ne = 0;
  for (size_t k = 0; k < nm_e; ++k) {
    if (k == 0 || q[k].a != q[k - 1].a || q[k].b != q[k - 1].b) ++ne;
    qof[q[k].e] = ne - 1;
  }
  f->ne = ne;
  f->edge_own = malloc(2 * ne * sizeof *f->edge_own);
  f->star1 = calloc(ne, sizeof *f->star1);
  qdual = calloc(ne, sizeof *qdual);
  f->u_edge = calloc(ne, sizeof *f->u_edge);
  if (!f->edge_own || !f->star1 || !qdual || !f->u_edge) goto nomem;
  for (size_t k = 0; k < nm_e; ++k) {
    size_t e = q[k].e, qe = qof[e];
    f->edge_own[2 * qe] = q[k].a;
    f->edge_own[2 * qe + 1] = q[k].b;
    f->star1[qe] += s1[e];
    qdual[qe] += dual1[e];
  }
  f->edge = f->edge_own;
  /* S: row = quotient edge, columns = solver vertices */
  const size_t n3 = 9 * f->nt;
  ri = malloc(n3 * sizeof *ri);
  ci = malloc(n3 * sizeof *ci);
  vv = malloc(n3 * sizeof *vv);
  if (!ri || !ci || !vv) goto nomem;
  size_t p = 0;
  for (size_t t = 0; t < f->nt; ++t) {
    size_t le[3];
    double pieces[3];
    gm_complex_local_faces(f->cx, t, 1, le);
    gm_geometry_dual_pieces(f->geo, t, 1, pieces);
    double n[3] = {0.0, 0.0, 1.0};
    if (sd == 3) memcpy(n, f->normal + 3 * t, sizeof n);
    for (int j = 0; j < 3; ++j) {
      size_t e = le[j], qe = qof[e];
      double ev[3] = {0};
      for (size_t c = 0; c < sd; ++c) ev[c] = xm[sd * me[2 * e + 1] + c] - xm[sd * me[2 * e] + c];
      double w = sgn[e] * pieces[j] / qdual[qe];
      for (int k = 0; k < 3; ++k) {
        const double *g = f->grad + (3 * t + (size_t)k) * sd;
        double gz = sd == 3 ? g[2] : 0.0;
        double u[3] = {g[1] * n[2] - gz * n[1], gz * n[0] - g[0] * n[2],
                       g[0] * n[1] - g[1] * n[0]}; /* ∇λ_k × n */
        ri[p] = qe;
        ci[p] = f->rep ? f->rep[f->tri[3 * t + (size_t)k]] : f->tri[3 * t + (size_t)k];
        vv[p++] = w * (u[0] * ev[0] + u[1] * ev[1] + u[2] * ev[2]);
      }
    }
  }
  st = gm_csr_from_triplets(ne, nv, p, ri, ci, vv, &f->S, &sub);
  if (st) goto nomem;
  /* (L + α ν L ⋆0⁻¹ L) on the free vertices, α = dt/2 and dt; b = 0 and ψ_bc = 0 (no walls) */
  inv0 = malloc(nv * sizeof *inv0);
  f->c_half = calloc(nv, sizeof *f->c_half);
  f->c_full = calloc(nv, sizeof *f->c_full);
  if (!inv0 || !f->c_half || !f->c_full) goto nomem;
  for (size_t v = 0; v < nv; ++v) inv0[v] = 1.0 / f->star0[v];
  if ((st = gm_csr_copy(f->L, &LD))) goto nomem;
  gm_csr_scale_cols(LD, inv0);
  if ((st = gm_csr_multiply(LD, f->L, &LDL))) goto nomem;
  for (int pass = 0; pass < 2; ++pass) {
    double alpha = (pass == 0 ? 0.5 : 1.0) * f->opt.dt * f->opt.nu;
    if ((st = gm_csr_add(1.0, f->L, alpha, LDL, &M))) goto nomem;
    if ((st = restrict_gauge(M, f->free_of, &Mr))) goto nomem;
    gm_csr_free(M);
    M = NULL;
    st = gm_sparse_cholesky_create(Mr, pass == 0 ? &f->m_half : &f->m_full, &sub);
    gm_csr_free(Mr);
    Mr = NULL;
    if (st) {
      snprintf(msg, msg_size, "fluid: vorticity matrix: %s", sub.message);
      goto out;
    }
  }
  goto out;
nomem:
  if (!st) st = GM_ENOMEM;
  snprintf(msg, msg_size, "fluid: out of memory (or assembling a matrix failed)");
out:
  free(q);
  free(qof);
  free(sgn);
  free(qdual);
  free(inv0);
  free(ri);
  free(ci);
  free(vv);
  gm_csr_free(LD);
  gm_csr_free(LDL);
  gm_csr_free(M);
  gm_csr_free(Mr);
  return st;
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
    for (int c = 0; c < 3; ++c) n[c] /= a2; /* the normal for which p0, p1, p2 turn ccw */
    /* the orientation's unit normal (the complex's sign; ẑ in the plane) for n·(∇a × ∇b) */
    double s = sd == 3 ? (double)gm_simplex_sign(f->cx, 2, t) : 1.0;
    if (sd == 3)
      for (int c = 0; c < 3; ++c) f->normal[3 * t + (size_t)c] = s * n[c];
    for (int k = 0; k < 3; ++k) { /* ∇λ_k = n × (p_{k+2} − p_{k+1}) / (2|T|), n of the order */
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
  if ((st = restrict_gauge(f->L, f->free_of, &Mr))) goto nomem;
  st = gm_sparse_cholesky_create(Mr, &f->poisson, &sub);
  if (st) {
    snprintf(msg, msg_size, "fluid: Poisson matrix: %s", sub.message);
    goto fail;
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
  if (opt->scheme == GM_FLUID_SEED && (st = seed_parts(f, msg, msg_size))) goto fail;
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
