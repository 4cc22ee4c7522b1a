/* The manufactured-solution Poisson check behind `geomint mesh poisson`. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/mesh.h"

static double exact(size_t n, const double *x, const double *lo, const double *len) {
  double u = 1.0;
  for (size_t i = 0; i < n; ++i) u *= sin(GM_PI * (x[i] - lo[i]) / len[i] + 0.25);
  return u;
}

gm_status gm_mesh_poisson(const gm_mesh *mesh, gm_poisson_report *report, double *u_out,
                          gm_error *err) {
  if (mesh == NULL || report == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  memset(report, 0, sizeof *report);
  if (mesh->dim != mesh->N)
    return gm_error_set(err, GM_EUNSUPPORTED,
                        "the Poisson check needs a mesh that fills its space (cells of dimension "
                        "%zu in R^%zu): a surface has no Dirichlet boundary to pin",
                        mesh->dim, mesh->N);
  gm_complex *cx = NULL;
  gm_geometry *g = NULL;
  gm_csr *a = NULL, *aii = NULL;
  gm_sparse_cholesky *ch = NULL;
  size_t *map = NULL;
  unsigned char *bnd = NULL;
  double *u = NULL, *rhs = NULL, *sol = NULL, *star0 = NULL;
  gm_status st = gm_mesh_complex(mesh, &cx, err);
  if (st != GM_OK) return st;
  st = gm_geometry_create(cx, NULL, &g, err);
  if (st != GM_OK) goto done;
  const size_t n = mesh->dim, nv = mesh->n_vertices;
  /* What the error report needs after the solve is copied out, so that the complex and the
   * geometry can be released before the factorization: it is the memory peak, and CHOLMOD runs
   * measurably slower (bench/dec_poisson: 13-15 s instead of 11 s) with them still resident. */
  bnd = malloc(nv);
  star0 = malloc(nv * sizeof(double));
  if (!bnd || !star0) {
    st = gm_error_set(err, GM_ENOMEM, "out of memory");
    goto done;
  }
  memcpy(bnd, gm_complex_boundary_mask(cx, 0), nv);
  memcpy(star0, gm_geometry_hodge_star(g, 0), nv * sizeof(double));
  double h = 0.0;
  const double *elen = gm_geometry_primal_volumes(g, 1);
  for (size_t e = 0; e < gm_complex_count(cx, 1); ++e)
    if (elen[e] > h) h = elen[e];
  double lo[3], hi[3], len[3];
  for (size_t i = 0; i < n; ++i) lo[i] = INFINITY, hi[i] = -INFINITY;
  for (size_t v = 0; v < nv; ++v)
    for (size_t i = 0; i < n; ++i) {
      double xi = mesh->x[v * n + i];
      if (xi < lo[i]) lo[i] = xi;
      if (xi > hi[i]) hi[i] = xi;
    }
  for (size_t i = 0; i < n; ++i) len[i] = hi[i] - lo[i];
  for (size_t v = 0; v < nv; ++v)
    if (!bnd[v] && !(star0[v] > 0.0)) {
      st = gm_error_set(err, GM_ESINGULAR,
                        "dual volume of interior vertex %zu is %.3g <= 0: the mesh is too far from "
                        "well-centred for a diagonal Hodge star",
                        v, star0[v]);
      goto done;
    }
  st = gm_dec_stiffness(g, 0, &a, err);
  if (st != GM_OK) goto done;
  map = malloc(nv * sizeof(size_t));
  u = malloc(nv * sizeof(double));
  if (!map || !u) {
    st = gm_error_set(err, GM_ENOMEM, "out of memory");
    goto done;
  }
  size_t ni = 0;
  for (size_t v = 0; v < nv; ++v) map[v] = bnd[v] ? SIZE_MAX : ni++;
  if (ni == 0) {
    st = gm_error_set(err, GM_EINVAL, "the mesh has no interior vertex");
    goto done;
  }
  double fscale = 0.0;
  for (size_t i = 0; i < n; ++i) fscale += (GM_PI / len[i]) * (GM_PI / len[i]);
  for (size_t v = 0; v < nv; ++v) u[v] = exact(n, mesh->x + v * n, lo, len);
  /* interior block and right-hand side ⋆_0 f − A_IB u_B */
  size_t nnz = 0;
  for (size_t v = 0; v < nv; ++v)
    if (!bnd[v])
      for (size_t p = a->row_start[v]; p < a->row_start[v + 1]; ++p) nnz += !bnd[a->col[p]];
  st = gm_csr_create(ni, ni, nnz, &aii);
  rhs = malloc(ni * sizeof(double));
  sol = malloc(ni * sizeof(double));
  if (st != GM_OK || !rhs || !sol) {
    st = gm_error_set(err, GM_ENOMEM, "out of memory");
    goto done;
  }
  size_t w = 0;
  for (size_t v = 0; v < nv; ++v) {
    if (bnd[v]) continue;
    size_t r = map[v];
    double b = star0[v] * fscale * u[v];
    for (size_t p = a->row_start[v]; p < a->row_start[v + 1]; ++p) {
      size_t c = a->col[p];
      if (bnd[c]) {
        b -= a->val[p] * u[c];
      } else {
        aii->col[w] = map[c];
        aii->val[w++] = a->val[p];
      }
    }
    aii->row_start[r + 1] = w;
    rhs[r] = b;
  }
  gm_csr_free(a), a = NULL;
  gm_geometry_free(g), g = NULL;
  gm_complex_free(cx), cx = NULL;
  st = gm_sparse_cholesky_create(aii, &ch, err);
  if (st != GM_OK) {
    if (st == GM_ESINGULAR)
      gm_error_set(err, st, "the DEC stiffness matrix is not positive definite (negative Hodge "
                            "star entries: check `mesh info`)");
    goto done;
  }
  st = gm_sparse_cholesky_solve(ch, rhs, sol);
  if (st != GM_OK) {
    gm_error_set(err, st, "%s", gm_sparse_cholesky_errmsg(ch));
    goto done;
  }
  double emax = 0.0, e2 = 0.0, umax = 0.0;
  for (size_t v = 0; v < nv; ++v) {
    double uh = bnd[v] ? u[v] : sol[map[v]];
    double e = uh - u[v];
    if (fabs(e) > emax) emax = fabs(e);
    if (fabs(u[v]) > umax) umax = fabs(u[v]);
    e2 += star0[v] * e * e;
    if (u_out) u_out[v] = uh;
  }
  report->n_vertices = nv;
  report->n_unknowns = ni;
  report->h = h;
  report->error_max = emax;
  report->error_l2 = sqrt(e2);
  report->solution_max = umax;
done:
  gm_sparse_cholesky_free(ch);
  gm_csr_free(aii);
  gm_csr_free(a);
  free(map), free(u), free(rhs), free(sol), free(bnd), free(star0);
  gm_geometry_free(g);
  gm_complex_free(cx);
  return st;
}
