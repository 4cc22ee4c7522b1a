/* The manufactured-solution curl–curl check behind gm_mesh_curlcurl_solve: the DEC 1-form
 * system (d_1ᵀ ⋆_2 d_1 + ⋆_1) e = ⋆_1 f_e (seed 001 §3.9: δ_2 d_1 + I on 1-forms, multiplied by
 * ⋆_1 to make it symmetric) on the interior edges, solved by CHOLMOD or by CG with hypre's AMS,
 * which needs the discrete gradient d_0 and the vertex coordinates (geomint/multigrid.h). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/internal.h"
#include "geomint/mesh.h"
#include "geomint/multigrid.h"

typedef struct box {
  double lo[3], len[3];
} box;

/* E at x (component c), and the factor k_c with curl curl E + E = k_c E_c (div E = 0, so
 * curl curl E = −ΔE, and −ΔE_c = π² (1/L_a² + 1/L_b²) E_c for the two other axes a, b). */
static double field(const box *bx, const double *x, int c) {
  const int a = (c + 1) % 3, b = (c + 2) % 3;
  return sin(GM_PI * (x[a] - bx->lo[a]) / bx->len[a]) * sin(GM_PI * (x[b] - bx->lo[b]) / bx->len[b]);
}

static double factor(const box *bx, int c) {
  const int a = (c + 1) % 3, b = (c + 2) % 3;
  return 1.0 + GM_PI * GM_PI * (1.0 / (bx->len[a] * bx->len[a]) + 1.0 / (bx->len[b] * bx->len[b]));
}

/* ∫_e E·dl and ∫_e f·dl from tail to head, 3-point Gauss–Legendre (Abramowitz & Stegun 25.4.29). */
static void edge_integrals(const box *bx, const double *x0, const double *x1, double *e,
                           double *f) {
  static const double t[3] = {0.5 - 0.3872983346207417, 0.5, 0.5 + 0.3872983346207417};
  static const double w[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  double se = 0.0, sf = 0.0;
  for (int q = 0; q < 3; ++q) {
    double x[3];
    for (int i = 0; i < 3; ++i) x[i] = x0[i] + t[q] * (x1[i] - x0[i]);
    for (int c = 0; c < 3; ++c) {
      const double v = field(bx, x, c) * (x1[c] - x0[c]);
      se += w[q] * v;
      sf += w[q] * factor(bx, c) * v;
    }
  }
  *e = se, *f = sf;
}

static double cpu_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Rows rmask == 0 and columns cmask == 0 of a, renumbered in order. */
static gm_status interior(const gm_csr *a, const unsigned char *rmask, const unsigned char *cmask,
                          gm_csr **out) {
  size_t *cmap = malloc((a->n_cols ? a->n_cols : 1) * sizeof(size_t)), nc = 0, nr = 0, nnz = 0;
  if (cmap == NULL) return GM_ENOMEM;
  for (size_t j = 0; j < a->n_cols; ++j) cmap[j] = cmask[j] ? SIZE_MAX : nc++;
  for (size_t i = 0; i < a->n_rows; ++i)
    if (!rmask[i]) {
      ++nr;
      for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p) nnz += !cmask[a->col[p]];
    }
  gm_csr *b = NULL;
  gm_status st = gm_csr_create(nr, nc, nnz, &b);
  if (st != GM_OK) {
    free(cmap);
    return st;
  }
  size_t w = 0, r = 0;
  for (size_t i = 0; i < a->n_rows; ++i) {
    if (rmask[i]) continue;
    for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p)
      if (!cmask[a->col[p]]) b->col[w] = cmap[a->col[p]], b->val[w++] = a->val[p];
    b->row_start[++r] = w;
  }
  free(cmap);
  *out = b;
  return GM_OK;
}

gm_status gm_mesh_curlcurl_solve(const gm_mesh *mesh, gm_curlcurl_solver solver, double rtol,
                                 gm_curlcurl_report *report, double **e_out, gm_error *err) {
  if (mesh == NULL || report == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  memset(report, 0, sizeof *report);
  if (e_out) *e_out = NULL;
  if (mesh->dim != 3 || mesh->N != 3)
    return gm_error_set(err, GM_EUNSUPPORTED,
                        "the curl–curl check needs a tetrahedral mesh in R^3 (got cells of "
                        "dimension %zu in R^%zu)",
                        mesh->dim, mesh->N);
  if (solver != GM_CURLCURL_CHOLMOD && solver != GM_CURLCURL_HYPRE)
    return gm_error_set(err, GM_EINVAL, "unknown curl–curl solver %d", (int)solver);
  if (!(rtol > 0.0 && rtol < 1.0))
    return gm_error_set(err, GM_EINVAL, "rtol = %g: needs 0 < rtol < 1", rtol);
  gm_complex *cx = NULL;
  gm_geometry *g = NULL;
  gm_csr *d1t = NULL, *s2d1 = NULL, *cc = NULL, *m1 = NULL, *full = NULL, *A = NULL, *G = NULL;
  gm_sparse_cholesky *ch = NULL;
  double *eex = NULL, *b = NULL, *x = NULL, *xyz = NULL;
  size_t *emap = NULL;
  gm_status st = gm_mesh_complex(mesh, &cx, err);
  if (st == GM_OK) st = gm_geometry_create(cx, NULL, &g, err);
  if (st != GM_OK) goto done;
  const size_t nv = mesh->n_vertices, ne = gm_complex_count(cx, 1);
  const unsigned char *ebnd = gm_complex_boundary_mask(cx, 1), *vbnd = gm_complex_boundary_mask(cx, 0);
  const double *star1 = gm_geometry_hodge_star(g, 1), *star2 = gm_geometry_hodge_star(g, 2);
  const gm_csr *d0 = gm_complex_d(cx, 0), *d1 = gm_complex_d(cx, 1);
  box bx;
  for (int i = 0; i < 3; ++i) {
    double lo = INFINITY, hi = -INFINITY;
    for (size_t v = 0; v < nv; ++v) lo = fmin(lo, mesh->x[3 * v + i]), hi = fmax(hi, mesh->x[3 * v + i]);
    bx.lo[i] = lo, bx.len[i] = hi - lo;
  }
  for (size_t e = 0; e < ne; ++e)
    if (!ebnd[e] && !(star1[e] > 0.0)) {
      st = gm_error_set(err, GM_ESINGULAR,
                        "⋆_1 of interior edge %zu is %.3g <= 0: the mesh is too far from "
                        "well-centred for a diagonal Hodge star",
                        e, star1[e]);
      goto done;
    }
  /* A = d_1ᵀ ⋆_2 d_1 + ⋆_1 on all edges, then the interior block */
  st = gm_csr_transpose(d1, &d1t);
  if (st == GM_OK) st = gm_csr_copy(d1, &s2d1);
  if (st == GM_OK) gm_csr_scale_rows(s2d1, star2), st = gm_csr_multiply(d1t, s2d1, &cc);
  if (st == GM_OK) st = gm_csr_diagonal(ne, star1, &m1);
  if (st == GM_OK) st = gm_csr_add(1.0, cc, 1.0, m1, &full);
  if (st == GM_OK) st = interior(full, ebnd, ebnd, &A);
  if (st == GM_OK) st = interior(d0, ebnd, vbnd, &G);
  eex = malloc(ne * sizeof(double));
  emap = malloc(ne * sizeof(size_t));
  if (st != GM_OK || !eex || !emap) {
    st = gm_error_set(err, GM_ENOMEM, "out of memory assembling the curl–curl system");
    goto done;
  }
  const size_t ni = A->n_rows;
  if (ni == 0) {
    st = gm_error_set(err, GM_EINVAL, "the mesh has no interior edge");
    goto done;
  }
  b = malloc(ni * sizeof(double));
  x = calloc(ni, sizeof(double));
  if (!b || !x) {
    st = gm_error_set(err, GM_ENOMEM, "out of memory");
    goto done;
  }
  /* edge orientation from d_0: the tail has −1, the head +1 */
  double h = 0.0;
  for (size_t e = 0, k = 0; e < ne; ++e) {
    size_t tail = SIZE_MAX, head = SIZE_MAX;
    for (size_t p = d0->row_start[e]; p < d0->row_start[e + 1]; ++p)
      *(d0->val[p] > 0.0 ? &head : &tail) = d0->col[p];
    const double *x0 = mesh->x + 3 * tail, *x1 = mesh->x + 3 * head;
    double fe, len = sqrt((x1[0] - x0[0]) * (x1[0] - x0[0]) + (x1[1] - x0[1]) * (x1[1] - x0[1]) +
                          (x1[2] - x0[2]) * (x1[2] - x0[2]));
    if (len > h) h = len;
    edge_integrals(&bx, x0, x1, &eex[e], &fe);
    emap[e] = ebnd[e] ? SIZE_MAX : k;
    if (!ebnd[e]) b[k++] = star1[e] * fe;
  }
  /* Dirichlet data: the boundary edges keep the exact integrals, b_I −= A_IB e_B */
  for (size_t e = 0; e < ne; ++e) {
    if (ebnd[e]) continue;
    for (size_t p = full->row_start[e]; p < full->row_start[e + 1]; ++p)
      if (ebnd[full->col[p]]) b[emap[e]] -= full->val[p] * eex[full->col[p]];
  }
  report->h = h;
  double t0 = cpu_now();
  if (solver == GM_CURLCURL_CHOLMOD) {
    st = gm_sparse_cholesky_create(A, &ch, err);
    if (st != GM_OK) goto done;
    report->factor_s = cpu_now() - t0;
    t0 = cpu_now();
    st = gm_sparse_cholesky_solve(ch, b, x);
    report->solve_s = cpu_now() - t0;
    if (st != GM_OK) {
      gm_error_set(err, st, "%s", gm_sparse_cholesky_errmsg(ch));
      goto done;
    }
    double *r = malloc(ni * sizeof(double)), rr = 0.0, bb = 0.0;
    if (r) {
      memcpy(r, b, ni * sizeof(double));
      gm_csr_matvec(A, -1.0, x, 1.0, r);
      for (size_t i = 0; i < ni; ++i) rr += r[i] * r[i], bb += b[i] * b[i];
      report->relative_residual = sqrt(rr / bb);
      free(r);
    }
  } else {
    xyz = malloc(3 * G->n_cols * sizeof(double));
    if (xyz == NULL) {
      st = gm_error_set(err, GM_ENOMEM, "out of memory");
      goto done;
    }
    for (size_t v = 0, k = 0; v < nv; ++v)
      if (!vbnd[v]) memcpy(xyz + 3 * k++, mesh->x + 3 * v, 3 * sizeof(double));
    gm_hypre_report hr;
    st = gm_hypre_ams_pcg(A, G, xyz, b, x, rtol, 0, &hr, err);
    report->iterations = hr.iterations, report->relative_residual = hr.relative_residual;
    report->factor_s = hr.setup_s, report->solve_s = hr.solve_s;
    if (st != GM_OK) goto done;
  }
  double emax = 0.0, smax = 0.0;
  for (size_t e = 0; e < ne; ++e) {
    size_t tail = SIZE_MAX, head = SIZE_MAX;
    for (size_t p = d0->row_start[e]; p < d0->row_start[e + 1]; ++p)
      *(d0->val[p] > 0.0 ? &head : &tail) = d0->col[p];
    const double *x0 = mesh->x + 3 * tail, *x1 = mesh->x + 3 * head;
    const double len = sqrt((x1[0] - x0[0]) * (x1[0] - x0[0]) + (x1[1] - x0[1]) * (x1[1] - x0[1]) +
                            (x1[2] - x0[2]) * (x1[2] - x0[2]));
    const double eh = emap[e] == SIZE_MAX ? eex[e] : x[emap[e]];
    emax = fmax(emax, fabs(eh - eex[e]) / len);
    smax = fmax(smax, fabs(eex[e]) / len);
    eex[e] = eh; /* eex now holds the solution on all edges */
  }
  report->error_max = emax, report->solution_max = smax;
  report->n_edges = ne, report->n_unknowns = ni, report->n_cells = mesh->n_cells;
  if (e_out) *e_out = eex, eex = NULL;
done:
  gm_sparse_cholesky_free(ch);
  gm_csr_free(d1t), gm_csr_free(s2d1), gm_csr_free(cc), gm_csr_free(m1), gm_csr_free(full);
  gm_csr_free(A), gm_csr_free(G);
  free(eex), free(b), free(x), free(xyz), free(emap);
  gm_geometry_free(g);
  gm_complex_free(cx);
  return st;
}
