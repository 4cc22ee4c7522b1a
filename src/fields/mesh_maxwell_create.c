/* Mesh Maxwell solver: creation (Hodge stars from the circumcentric dual, PEC mask, CFL limits,
 * AVI time steps and event heap) and the simple accessors. Seed 000 §3.4.2 (notes A11) for the
 * stars and the scheme, §3.4.3 (notes A12) for the AVI. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "fields/mesh_maxwell.h"

gm_mesh_maxwell_options gm_mesh_maxwell_defaults(void) {
  gm_mesh_maxwell_options o;
  memset(&o, 0, sizeof o);
  o.scheme = GM_MESH_LEAPFROG;
  o.dt = 0.0;
  o.courant = 0.9;
  o.avi_fraction = 0.1;
  o.face_dt = NULL;
  o.allow_negative_stars = 0;
  o.avi_levels = 1;
  return o;
}

void gm_mesh_maxwell_free(gm_mesh_maxwell *s) {
  if (!s) return;
  gm_csr_free(s->d1t);
  gm_csr_free(s->curl_h);
  free(s->eps_star); free(s->inv_eps); free(s->nu_star);
  free(s->E); free(s->D); free(s->B); free(s->rho);
  free(s->work_f); free(s->work_e); free(s->face_limit); free(s->work_v); free(s->mu_cell);
  gm_csr_free(s->M1); gm_csr_free(s->M1_full); gm_csr_free(s->M2);
  gm_sparse_cholesky_free(s->chol); free(s->interior); free(s->tmp_i); free(s->work_f2);
  for (size_t i = 0; i < s->n_cur; ++i) { free(s->cur[i].edges); free(s->cur[i].w); }
  free(s->cur);
  for (size_t i = 0; i < s->n_probe; ++i) { free(s->probe[i].t); free(s->probe[i].v); }
  free(s->probe);
  free(s->obs);
  free(s->j_start); free(s->j_src); free(s->j_w); free(s->j_tau); free(s->j_edges);
  free(s->A); free(s->tau_e); free(s->tau_f); free(s->B0); free(s->face_dt);
  free(s->group_start); free(s->group_face); free(s->group_dt); free(s->k_g); free(s->heap);
  free(s);
}

const char *gm_mesh_maxwell_errmsg(const gm_mesh_maxwell *s) { return s ? s->errmsg : ""; }
double gm_mesh_maxwell_cfl_limit(const gm_mesh_maxwell *s) { return s->cfl; }
const double *gm_mesh_maxwell_face_limits(const gm_mesh_maxwell *s) { return s->face_limit; }
double gm_mesh_maxwell_dt(const gm_mesh_maxwell *s) { return s->dt; }
size_t gm_mesh_maxwell_step(const gm_mesh_maxwell *s) { return s->step; }
double gm_mesh_maxwell_time(const gm_mesh_maxwell *s) { return s->t; }
const double *gm_mesh_maxwell_e(const gm_mesh_maxwell *s) { return s->E; }
const double *gm_mesh_maxwell_b(const gm_mesh_maxwell *s) { return s->B; }
size_t gm_mesh_maxwell_avi_groups(const gm_mesh_maxwell *s) { return s->n_groups; }
void gm_mesh_maxwell_update_counts(const gm_mesh_maxwell *s, size_t *faces, size_t *edges) {
  if (faces) *faces = s->face_updates;
  if (edges) *edges = s->edge_updates;
}

/* ⋆_ε (edges) and ⋆_ν (faces) summed cell by cell from the signed dual pieces |⋆σ ∩ T|, so that
 * materials may jump across faces (Bossavit–Kettunen; seed 000 §3.4.2). */
static gm_status build_stars(gm_mesh_maxwell *s, const double *eps, const double *mu,
                             gm_error *err) {
  const size_t n = s->n;
  const double *len = gm_geometry_primal_volumes(s->g, 1);
  const double *area = gm_geometry_primal_volumes(s->g, 2);
  size_t idx[6];
  double piece[6];
  for (size_t T = 0; T < s->nt; ++T) {
    const double e_T = eps ? eps[T] : 1.0, m_T = mu ? mu[T] : 1.0;
    gm_status st = gm_complex_local_faces(s->cx, T, 1, idx);
    if (st == GM_OK) st = gm_geometry_dual_pieces(s->g, T, 1, piece);
    if (st != GM_OK) return gm_error_set(err, st, "mesh maxwell: dual pieces of cell %zu", T);
    const size_t n_edges = n == 2 ? 3 : 6;
    for (size_t i = 0; i < n_edges; ++i) s->eps_star[idx[i]] += e_T * piece[i];
    if (n == 2) {
      s->nu_star[T] += 1.0 / (m_T * area[T]); /* ⋆σ of a top face is its circumcenter */
    } else {
      st = gm_complex_local_faces(s->cx, T, 2, idx);
      if (st == GM_OK) st = gm_geometry_dual_pieces(s->g, T, 2, piece);
      if (st != GM_OK) return gm_error_set(err, st, "mesh maxwell: dual pieces of cell %zu", T);
      for (size_t i = 0; i < 4; ++i) s->nu_star[idx[i]] += piece[i] / (m_T * area[idx[i]]);
    }
  }
  for (size_t e = 0; e < s->ne; ++e) s->eps_star[e] /= len[e];
  return GM_OK;
}

void mm_apply_nu(const gm_mesh_maxwell *s, const double *B, double *H) {
  if (s->M2) {
    gm_csr_matvec(s->M2, 1.0, B, 0.0, H);
    return;
  }
  for (size_t f = 0; f < s->nf; ++f) H[f] = s->nu_star[f] * B[f];
}

void mm_solve_eps(const gm_mesh_maxwell *s, const double *D, double *E) {
  if (!s->chol) {
    for (size_t e = 0; e < s->ne; ++e) E[e] = s->inv_eps[e] * D[e];
    return;
  }
  for (size_t i = 0; i < s->n_int; ++i) s->tmp_i[i] = D[s->interior[i]];
  gm_sparse_cholesky_solve(s->chol, s->tmp_i, s->tmp_i);
  memset(E, 0, s->ne * sizeof(double));
  for (size_t i = 0; i < s->n_int; ++i) E[s->interior[i]] = s->tmp_i[i];
}

/* Number of eigenvalues of the symmetric tridiagonal T (diagonal a, off-diagonal b[1..m−1])
 * greater than x (Sturm sequence of T − x). */
static size_t sturm_above(const double *a, const double *b, size_t m, double x) {
  size_t below = 0;
  double q = 1.0;
  for (size_t i = 0; i < m; ++i) {
    q = a[i] - x - (i ? b[i] * b[i] / q : 0.0);
    if (q == 0.0) q = 1e-300;
    if (q < 0.0) ++below;
  }
  return m - below;
}

/* λ_max(T) by bisection on [lo, hi] (Gershgorin interval). */
static double tridiag_max(const double *a, const double *b, size_t m) {
  double lo = INFINITY, hi = -INFINITY;
  for (size_t i = 0; i < m; ++i) {
    const double r = (i ? fabs(b[i]) : 0.0) + (i + 1 < m ? fabs(b[i + 1]) : 0.0);
    lo = fmin(lo, a[i] - r);
    hi = fmax(hi, a[i] + r);
  }
  for (int it = 0; it < 200 && hi - lo > 1e-15 * fmax(fabs(lo), fabs(hi)); ++it) {
    const double mid = 0.5 * (lo + hi);
    if (sturm_above(a, b, m, mid) > 0) lo = mid; else hi = mid;
  }
  return hi;
}

/* λ_max of ⋆_ε⁻¹ K, K = d₁ᵀ ⋆_ν d₁ on interior edges (⋆_ε-self-adjoint), by the Lanczos
 * process in the ⋆_ε inner product (Golub & Van Loan, Matrix Computations, 4th ed., §10.1;
 * without reorthogonalization: lost orthogonality only duplicates converged Ritz values, and the
 * largest Ritz value still increases to λ_max from below). Far fewer products than the power
 * iteration on large meshes, whose top eigenvalues cluster. Leapfrog is stable for
 * Δt² λ_max < 4. Uses E, D, work_e, work_f, work_f2 as scratch (zeroed after). */
static double lanczos_lambda(gm_mesh_maxwell *s) {
  enum { KMAX = 600 };
  double *v = s->work_e, *vp = s->E, *w = s->D, *f = s->work_f, *h = s->work_f2;
  double *mw = s->M1_full ? malloc(s->ne * sizeof(double)) : NULL;
  double *al = malloc(KMAX * sizeof(double)), *be = malloc((KMAX + 1) * sizeof(double));
  double lambda = 0.0;
  if ((s->M1_full && !mw) || !al || !be) goto done;
  uint64_t z = 0x2545f4914f6cdd1dull;
  for (size_t e = 0; e < s->ne; ++e) {
    z ^= z << 13; z ^= z >> 7; z ^= z << 17;
    v[e] = s->inv_eps[e] != 0.0 ? (double)(z >> 11) / 9007199254740992.0 - 0.5 : 0.0;
    vp[e] = 0.0;
  }
  double beta = 0.0, prev = 0.0;
  double mv = 0.0; /* normalise the first vector in ⋆_ε */
  if (s->M1_full) {
    gm_csr_matvec(s->M1_full, 1.0, v, 0.0, mw);
    for (size_t e = 0; e < s->ne; ++e) mv += v[e] * mw[e];
  } else {
    for (size_t e = 0; e < s->ne; ++e) mv += v[e] * v[e] * s->eps_star[e];
  }
  if (!(mv > 0.0)) goto done;
  for (size_t e = 0; e < s->ne; ++e) v[e] /= sqrt(mv);
  for (size_t j = 0; j < KMAX; ++j) {
    gm_csr_matvec(s->d1, 1.0, v, 0.0, f);
    mm_apply_nu(s, f, h);
    double a = 0.0; /* vᵀKv */
    for (size_t k = 0; k < s->nf; ++k) a += f[k] * h[k];
    gm_csr_matvec(s->d1t, 1.0, h, 0.0, w);
    for (size_t e = 0; e < s->ne; ++e) if (s->inv_eps[e] == 0.0) w[e] = 0.0;
    mm_solve_eps(s, w, w);                                      /* w = ⋆_ε⁻¹ K v */
    for (size_t e = 0; e < s->ne; ++e) w[e] -= a * v[e] + beta * vp[e];
    al[j] = a;
    be[j] = beta;
    lambda = tridiag_max(al, be, j + 1);
    if (j > 20 && fabs(lambda - prev) <= 1e-12 * fabs(lambda)) break;
    prev = lambda;
    double nw = 0.0;
    if (s->M1_full) {
      gm_csr_matvec(s->M1_full, 1.0, w, 0.0, mw);
      for (size_t e = 0; e < s->ne; ++e) nw += w[e] * mw[e];
    } else {
      for (size_t e = 0; e < s->ne; ++e) nw += w[e] * w[e] * s->eps_star[e];
    }
    beta = sqrt(nw);
    if (!(beta > 1e-14 * fabs(lambda))) break; /* invariant subspace: λ_max(T) is exact */
    for (size_t e = 0; e < s->ne; ++e) {
      vp[e] = v[e];
      v[e] = w[e] / beta;
    }
  }
done:
  free(mw), free(al), free(be);
  memset(s->D, 0, s->ne * sizeof(double));
  memset(s->E, 0, s->ne * sizeof(double));
  return lambda;
}

/* The Whitney stars with materials per cell: M_1^ε = Σ_T ε_T ∫_T φ_e·φ_e' on the interior edges
 * (CHOLMOD, once) and M_2^ν = Σ_T μ_T⁻¹ ∫_T φ_σ·φ_σ' (Bossavit 1988: the Galerkin Hodge stars
 * are the mass matrices of the Whitney forms weighted by the material). */
static gm_status build_whitney(gm_mesh_maxwell *s, const double *eps, const double *mu,
                               gm_error *err) {
  double *inv_mu = NULL;
  if (mu) {
    inv_mu = malloc(s->nt * sizeof(double));
    if (!inv_mu) return gm_error_set(err, GM_ENOMEM, "out of memory");
    for (size_t T = 0; T < s->nt; ++T) inv_mu[T] = 1.0 / mu[T];
  }
  gm_status st = gm_geometry_whitney_mass_weighted(s->g, 1, eps, &s->M1_full);
  if (st == GM_OK) st = gm_geometry_whitney_mass_weighted(s->g, 2, inv_mu, &s->M2);
  free(inv_mu);
  if (st != GM_OK) return gm_error_set(err, st, "mesh maxwell: Whitney mass matrices failed");
  size_t *map = malloc(s->ne * sizeof(size_t));
  s->interior = malloc((s->ne ? s->ne : 1) * sizeof(size_t));
  if (!map || !s->interior) { free(map); return gm_error_set(err, GM_ENOMEM, "out of memory"); }
  for (size_t e = 0; e < s->ne; ++e) {
    map[e] = s->bnd_e[e] ? SIZE_MAX : s->n_int;
    if (!s->bnd_e[e]) s->interior[s->n_int++] = e;
  }
  const gm_csr *M = s->M1_full;
  const size_t nnz = gm_csr_nnz(M);
  size_t *r = malloc((nnz ? nnz : 1) * sizeof(size_t)), *c = malloc((nnz ? nnz : 1) * sizeof(size_t));
  double *v = malloc((nnz ? nnz : 1) * sizeof(double));
  s->tmp_i = calloc(s->n_int ? s->n_int : 1, sizeof(double));
  if (!r || !c || !v || !s->tmp_i) {
    free(map); free(r); free(c); free(v);
    return gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  size_t w = 0;
  for (size_t i = 0; i < s->ne; ++i)
    for (size_t p = M->row_start[i]; p < M->row_start[i + 1]; ++p)
      if (map[i] != SIZE_MAX && map[M->col[p]] != SIZE_MAX) {
        r[w] = map[i]; c[w] = map[M->col[p]]; v[w] = M->val[p]; ++w;
      }
  st = gm_csr_from_triplets(s->n_int, s->n_int, w, r, c, v, &s->M1, err);
  free(map); free(r); free(c); free(v);
  if (st != GM_OK) return st;
  if (s->n_int) {
    st = gm_sparse_cholesky_create(s->M1, &s->chol, err);
    if (st != GM_OK) return st;
  }
  for (size_t e = 0; e < s->ne; ++e) s->eps_star[e] = gm_csr_get(M, e, e);
  for (size_t f = 0; f < s->nf; ++f) s->nu_star[f] = gm_csr_get(s->M2, f, f);
  return GM_OK;
}

/* Per-face Gershgorin bound of the face operator ⋆_ν^½ d₁ ⋆_ε⁻¹ d₁ᵀ ⋆_ν^½ (same non-zero
 * spectrum as S): r_σ = √ν_σ Σ_{e ∈ σ} |⋆_ε⁻¹[e]| Σ_{σ' ∋ e} √ν_σ'; local limit 2/√r_σ.
 * On a square Yee-like pattern this is exactly the Courant limit h/√2. */
static void face_limits(gm_mesh_maxwell *s) {
  const gm_csr *d1 = s->d1, *d1t = s->d1t;
  for (size_t f = 0; f < s->nf; ++f) {
    double r = 0.0;
    for (size_t p = d1->row_start[f]; p < d1->row_start[f + 1]; ++p) {
      const size_t e = d1->col[p];
      if (s->inv_eps[e] == 0.0) continue;
      double sum = 0.0;
      for (size_t q = d1t->row_start[e]; q < d1t->row_start[e + 1]; ++q)
        sum += sqrt(fabs(s->nu_star[d1t->col[q]]));
      r += fabs(s->inv_eps[e]) * sum;
    }
    r *= sqrt(fabs(s->nu_star[f]));
    s->face_limit[f] = r > 0.0 ? 2.0 / sqrt(r) : INFINITY;
  }
}

#define MM_ALLOC(p, count) \
  do { (p) = calloc((count) ? (count) : 1, sizeof *(p)); if (!(p)) goto nomem; } while (0)

gm_status gm_mesh_maxwell_create(const gm_geometry *g, const double *epsilon, const double *mu,
                                 const gm_mesh_maxwell_options *options, gm_mesh_maxwell **out,
                                 gm_error *err) {
  if (!out) return gm_error_set(err, GM_EINVAL, "mesh maxwell: out is NULL");
  *out = NULL;
  if (!g) return gm_error_set(err, GM_EINVAL, "mesh maxwell: geometry is NULL");
  const gm_complex *cx = gm_geometry_complex(g);
  const size_t n = gm_complex_dim(cx), N = gm_complex_embedding_dim(cx);
  if ((n != 2 && n != 3) || N != n)
    return gm_error_set(err, GM_EINVAL,
                        "mesh maxwell: needs triangles in the plane or tetrahedra in space "
                        "(got dimension %zu in R^%zu)", n, N);
  if (gm_geometry_inverted_count(g) > 0)
    return gm_error_set(err, GM_EINVAL, "mesh maxwell: %zu inverted cells",
                        gm_geometry_inverted_count(g));
  const size_t nt = gm_complex_count(cx, n);
  for (size_t T = 0; T < nt; ++T) {
    if (epsilon && !(isfinite(epsilon[T]) && epsilon[T] > 0.0))
      return gm_error_set(err, GM_EINVAL, "mesh maxwell: epsilon of cell %zu is %g (must be > 0)",
                          T, epsilon[T]);
    if (mu && !(isfinite(mu[T]) && mu[T] > 0.0))
      return gm_error_set(err, GM_EINVAL, "mesh maxwell: mu of cell %zu is %g (must be > 0)", T,
                          mu[T]);
  }
  /* PEC zeroes E on boundary edges; with no interior edge nothing ever moves (and the CFL
     limit would be infinite) */
  const unsigned char *bnd_edge = gm_complex_boundary_mask(cx, 1);
  size_t n_interior = 0;
  for (size_t e = 0; e < gm_complex_count(cx, 1); ++e) n_interior += !bnd_edge[e];
  if (n_interior == 0)
    return gm_error_set(err, GM_EINVAL,
                        "mesh maxwell: the mesh has no interior edges: under PEC every field is "
                        "zero");
  gm_mesh_maxwell_options o = options ? *options : gm_mesh_maxwell_defaults();
  if (!(o.courant > 0.0) || o.courant > 1.0 || !isfinite(o.dt))
    return gm_error_set(err, GM_EINVAL, "mesh maxwell: courant must be in (0, 1], dt finite");
  if (o.scheme == GM_MESH_AVI && !o.face_dt && !(o.avi_fraction > 0.0 && o.avi_fraction <= 1.0))
    return gm_error_set(err, GM_EINVAL, "mesh maxwell: avi_fraction must be in (0, 1]");
  if (o.scheme != GM_MESH_LEAPFROG && o.scheme != GM_MESH_AVI)
    return gm_error_set(err, GM_EINVAL, "mesh maxwell: unknown scheme %d", (int)o.scheme);

  gm_mesh_maxwell *s = calloc(1, sizeof *s);
  if (!s) return gm_error_set(err, GM_ENOMEM, "mesh maxwell: out of memory");
  s->g = g; s->cx = cx; s->n = n; s->nt = nt;
  s->nv = gm_complex_count(cx, 0); s->ne = gm_complex_count(cx, 1); s->nf = gm_complex_count(cx, 2);
  s->d0 = gm_complex_d(cx, 0); s->d1 = gm_complex_d(cx, 1); s->d2 = n == 3 ? gm_complex_d(cx, 2) : NULL;
  s->bnd_e = gm_complex_boundary_mask(cx, 1); s->bnd_v = gm_complex_boundary_mask(cx, 0);
  if (gm_csr_transpose(s->d1, &s->d1t) != GM_OK) goto nomem;
  MM_ALLOC(s->eps_star, s->ne); MM_ALLOC(s->inv_eps, s->ne); MM_ALLOC(s->nu_star, s->nf);
  MM_ALLOC(s->E, s->ne); MM_ALLOC(s->D, s->ne); MM_ALLOC(s->B, s->nf); MM_ALLOC(s->rho, s->nv);
  MM_ALLOC(s->work_f, s->nf); MM_ALLOC(s->work_e, s->ne); MM_ALLOC(s->face_limit, s->nf);
  MM_ALLOC(s->work_v, s->nv); MM_ALLOC(s->work_f2, s->nf); MM_ALLOC(s->mu_cell, s->nt);
  for (size_t T = 0; T < nt; ++T) s->mu_cell[T] = mu ? mu[T] : 1.0;
  gm_status st;
  if (o.star == GM_MESH_STAR_WHITNEY) {
    if (o.scheme != GM_MESH_LEAPFROG) {
      gm_mesh_maxwell_free(s);
      return gm_error_set(err, GM_EUNSUPPORTED, "mesh maxwell: the AVI needs the diagonal star");
    }
    st = build_whitney(s, epsilon, mu, err);
    if (st != GM_OK) { gm_mesh_maxwell_free(s); return st; }
    for (size_t e = 0; e < s->ne; ++e) s->inv_eps[e] = s->bnd_e[e] ? 0.0 : 1.0; /* the mask */
  } else if (o.star != GM_MESH_STAR_DIAGONAL) {
    gm_mesh_maxwell_free(s);
    return gm_error_set(err, GM_EINVAL, "mesh maxwell: unknown star %d", (int)o.star);
  } else {
  st = build_stars(s, epsilon, mu, err);
  if (st != GM_OK) { gm_mesh_maxwell_free(s); return st; }
  /* Non-positive stars on the interior (seed 000 §3.3.2): the mesh is not well-centred, and not
     Delaunay either — on a Delaunay mesh the circumcentric dual of an interior edge is its
     Voronoi face and that of an interior face a Voronoi edge, both of positive measure. */
  size_t bad_e = 0, bad_f = 0;
  const unsigned char *bnd_f = gm_complex_boundary_mask(cx, 2);
  for (size_t e = 0; e < s->ne; ++e) {
    if (s->bnd_e[e]) continue;
    if (!(s->eps_star[e] > 0.0)) ++bad_e;
  }
  for (size_t f = 0; f < s->nf; ++f)
    if (!(n == 3 && bnd_f[f]) && !(s->nu_star[f] > 0.0)) ++bad_f;
  if ((bad_e || bad_f) && !o.allow_negative_stars) {
    gm_mesh_maxwell_free(s);
    return gm_error_set(err, GM_EINVAL,
                        "mesh maxwell: the mesh is not well-centred: %zu interior edges with "
                        "star_eps <= 0 and %zu faces with star_nu <= 0 (nor Delaunay, which would "
                        "have none; set allow_negative_stars to insist)", bad_e, bad_f);
  }
  for (size_t e = 0; e < s->ne; ++e) {
    if (!s->bnd_e[e] && s->eps_star[e] == 0.0) {
      gm_mesh_maxwell_free(s);
      return gm_error_set(err, GM_EINVAL, "mesh maxwell: edge %zu has a zero star_eps", e);
    }
    s->inv_eps[e] = s->bnd_e[e] ? 0.0 : 1.0 / s->eps_star[e];
  }
  }
  if (o.star == GM_MESH_STAR_DIAGONAL) {
    /* the fused Ampère operator d1ᵀ⋆_ν, PEC rows zeroed (d1 entries are ±1, so the products
       round exactly as ⋆_ν B followed by d1ᵀ) */
    if (gm_csr_copy(s->d1t, &s->curl_h) != GM_OK) goto nomem;
    for (size_t e = 0; e < s->ne; ++e)
      for (size_t p = s->curl_h->row_start[e]; p < s->curl_h->row_start[e + 1]; ++p)
        s->curl_h->val[p] = s->bnd_e[e] ? 0.0 : s->curl_h->val[p] * s->nu_star[s->curl_h->col[p]];
  }
  const double lambda = lanczos_lambda(s);
  s->cfl = lambda > 0.0 ? 2.0 / sqrt(lambda) : INFINITY;
  face_limits(s);
  s->opt = o;
  s->opt.face_dt = NULL;
  if (o.scheme == GM_MESH_LEAPFROG) {
    s->dt = o.dt > 0.0 ? o.dt : o.courant * s->cfl;
    if (!(s->dt <= s->cfl) || !isfinite(s->dt)) {
      const double dt = s->dt, lim = s->cfl;
      gm_mesh_maxwell_free(s);
      return gm_error_set(err, GM_EINVAL,
                          "mesh maxwell: dt = %.6g is above the CFL limit %.6g", dt, lim);
    }
    *out = s;
    return GM_OK;
  }
  /* AVI: per-face steps, the event heap, the A/τ arrays (seed 000 Fig. 3.6, notes A12). */
  MM_ALLOC(s->A, s->ne); MM_ALLOC(s->tau_e, s->ne); MM_ALLOC(s->tau_f, s->nf);
  MM_ALLOC(s->B0, s->nf); MM_ALLOC(s->face_dt, s->nf);
  double smallest = INFINITY;
  for (size_t f = 0; f < s->nf; ++f) {
    if (!isfinite(s->face_limit[f])) { s->face_dt[f] = INFINITY; continue; } /* no interior edge */
    const double dtf = o.face_dt ? o.face_dt[f] : o.avi_fraction * s->face_limit[f];
    if (!(dtf > 0.0) || !isfinite(dtf) || dtf > s->face_limit[f] * (1.0 + 1e-12)) {
      const double lim = s->face_limit[f];
      gm_mesh_maxwell_free(s);
      return gm_error_set(err, GM_EINVAL,
                          "mesh maxwell: the step %.6g of face %zu is above its local CFL "
                          "limit %.6g (or not positive)", dtf, f, lim);
    }
    s->face_dt[f] = dtf;
    smallest = dtf < smallest ? dtf : smallest;
  }
  if (o.avi_levels && isfinite(smallest)) { /* round down to Δt_min 2^k */
    for (size_t f = 0; f < s->nf; ++f) {
      if (!isfinite(s->face_dt[f])) continue;
      double d = smallest;
      while (2.0 * d <= s->face_dt[f]) d *= 2.0; /* exact doublings: levels share their ticks */
      s->face_dt[f] = d;
    }
  }
  s->dt = isfinite(smallest) ? smallest : 0.0;
  s->sample_dt = s->dt;
  s->next_sample = s->dt;
  if (mm_groups_build(s) != GM_OK) goto nomem;
  *out = s;
  return GM_OK;
nomem:
  gm_mesh_maxwell_free(s);
  return gm_error_set(err, GM_ENOMEM, "mesh maxwell: out of memory");
}

gm_status gm_mesh_maxwell_set_fields(gm_mesh_maxwell *s, const double *E, const double *B) {
  if (s->started)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "set_fields: only before the first advance");
  if (E && gm_first_nonfinite(s->ne, E) != s->ne)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EDOMAIN, "set_fields: non-finite E");
  if (B && gm_first_nonfinite(s->nf, B) != s->nf)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EDOMAIN, "set_fields: non-finite B");
  if (E) {
    for (size_t e = 0; e < s->ne; ++e) s->E[e] = s->bnd_e[e] ? 0.0 : E[e];
    if (s->M1_full) gm_csr_matvec(s->M1_full, 1.0, s->E, 0.0, s->D); /* D = ε M_1 E */
    for (size_t e = 0; e < s->ne; ++e)
      s->D[e] = s->bnd_e[e] ? 0.0 : s->M1_full ? s->D[e] : s->eps_star[e] * s->E[e];
  }
  if (B) {
    memcpy(s->B, B, s->nf * sizeof(double));
    if (s->B0) memcpy(s->B0, B, s->nf * sizeof(double));
  }
  return GM_OK;
}
