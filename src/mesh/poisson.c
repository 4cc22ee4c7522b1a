/* The manufactured-solution Poisson check behind `geomint mesh poisson`, solved by CHOLMOD, by
 * CG preconditioned with a geometric multigrid V-cycle on the red-refinement hierarchy, or by CG
 * with hypre's BoomerAMG. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/internal.h"
#include "geomint/mesh.h"
#include "geomint/multigrid.h"

static double exact(size_t n, const double *x, const double *lo, const double *len) {
  double u = 1.0;
  for (size_t i = 0; i < n; ++i) u *= sin(GM_PI * (x[i] - lo[i]) / len[i] + 0.25);
  return u;
}

static double wall_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

gm_poisson_options gm_poisson_defaults(void) {
  gm_poisson_options o;
  memset(&o, 0, sizeof o);
  o.solver = GM_POISSON_AUTO;
  o.rtol = 1e-10;
  o.pre_smooth = o.post_smooth = 2;
  return o;
}

/* The interior system of one mesh: A_II u_I = ⋆_0 f − A_IB u_B. */
typedef struct poisson_system {
  size_t nv, ni, n;
  unsigned char *bnd;
  size_t *map; /* vertex -> unknown, SIZE_MAX on the boundary */
  double *star0, *u, *rhs;
  gm_csr *aii;
  double h;
} poisson_system;

static void system_free(poisson_system *s) {
  free(s->bnd), free(s->map), free(s->star0), free(s->u), free(s->rhs);
  gm_csr_free(s->aii);
  memset(s, 0, sizeof *s);
}

static gm_status assemble(const gm_mesh *mesh, poisson_system *s, gm_error *err) {
  memset(s, 0, sizeof *s);
  gm_complex *cx = NULL;
  gm_geometry *g = NULL;
  gm_csr *a = NULL;
  gm_status st = gm_mesh_complex(mesh, &cx, err);
  if (st != GM_OK) return st;
  st = gm_geometry_create(cx, NULL, &g, err);
  if (st != GM_OK) goto done;
  const size_t n = mesh->dim, nv = mesh->n_vertices;
  s->nv = nv, s->n = n;
  /* What the error report needs after the solve is copied out, so that the complex and the
   * geometry can be released before the factorization: it is the memory peak, and CHOLMOD runs
   * measurably slower (bench/dec_poisson: 13-15 s instead of 11 s) with them still resident. */
  s->bnd = malloc(nv);
  s->star0 = malloc(nv * sizeof(double));
  s->map = malloc(nv * sizeof(size_t));
  s->u = malloc(nv * sizeof(double));
  if (!s->bnd || !s->star0 || !s->map || !s->u) {
    st = gm_error_set(err, GM_ENOMEM, "out of memory");
    goto done;
  }
  memcpy(s->bnd, gm_complex_boundary_mask(cx, 0), nv);
  memcpy(s->star0, gm_geometry_hodge_star(g, 0), nv * sizeof(double));
  const double *elen = gm_geometry_primal_volumes(g, 1);
  for (size_t e = 0; e < gm_complex_count(cx, 1); ++e)
    if (elen[e] > s->h) s->h = elen[e];
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
    if (!s->bnd[v] && !(s->star0[v] > 0.0)) {
      st = gm_error_set(err, GM_ESINGULAR,
                        "dual volume of interior vertex %zu is %.3g <= 0: the mesh is too far from "
                        "well-centred for a diagonal Hodge star",
                        v, s->star0[v]);
      goto done;
    }
  st = gm_dec_stiffness(g, 0, &a, err);
  if (st != GM_OK) goto done;
  size_t ni = 0;
  for (size_t v = 0; v < nv; ++v) s->map[v] = s->bnd[v] ? SIZE_MAX : ni++;
  if (ni == 0) {
    st = gm_error_set(err, GM_EINVAL, "the mesh has no interior vertex");
    goto done;
  }
  s->ni = ni;
  double fscale = 0.0;
  for (size_t i = 0; i < n; ++i) fscale += (GM_PI / len[i]) * (GM_PI / len[i]);
  for (size_t v = 0; v < nv; ++v) s->u[v] = exact(n, mesh->x + v * n, lo, len);
  size_t nnz = 0;
  for (size_t v = 0; v < nv; ++v)
    if (!s->bnd[v])
      for (size_t p = a->row_start[v]; p < a->row_start[v + 1]; ++p) nnz += !s->bnd[a->col[p]];
  st = gm_csr_create(ni, ni, nnz, &s->aii);
  s->rhs = malloc(ni * sizeof(double));
  if (st != GM_OK || !s->rhs) {
    st = gm_error_set(err, GM_ENOMEM, "out of memory");
    goto done;
  }
  size_t w = 0;
  for (size_t v = 0; v < nv; ++v) {
    if (s->bnd[v]) continue;
    size_t r = s->map[v];
    double b = s->star0[v] * fscale * s->u[v];
    for (size_t p = a->row_start[v]; p < a->row_start[v + 1]; ++p) {
      size_t c = a->col[p];
      if (s->bnd[c]) {
        b -= a->val[p] * s->u[c];
      } else {
        s->aii->col[w] = s->map[c];
        s->aii->val[w++] = a->val[p];
      }
    }
    s->aii->row_start[r + 1] = w;
    s->rhs[r] = b;
  }
done:
  gm_csr_free(a);
  gm_geometry_free(g);
  gm_complex_free(cx);
  if (st != GM_OK) system_free(s);
  return st;
}

gm_status gm_mesh_poisson_solve(const gm_mesh *mesh, const gm_poisson_options *options,
                                gm_poisson_report *report, double **u_out, gm_error *err) {
  if (mesh == NULL || report == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  memset(report, 0, sizeof *report);
  if (u_out) *u_out = NULL;
  gm_poisson_options opt = options ? *options : gm_poisson_defaults();
  if (mesh->dim != mesh->N)
    return gm_error_set(err, GM_EUNSUPPORTED,
                        "the Poisson check needs a mesh that fills its space (cells of dimension "
                        "%zu in R^%zu): a surface has no Dirichlet boundary to pin",
                        mesh->dim, mesh->N);
  if (opt.solver != GM_POISSON_CHOLMOD && opt.solver != GM_POISSON_MULTIGRID &&
      opt.solver != GM_POISSON_HYPRE && opt.solver != GM_POISSON_AUTO)
    return gm_error_set(err, GM_EINVAL, "unknown Poisson solver %d", (int)opt.solver);
  if (opt.levels > 20) return gm_error_set(err, GM_EINVAL, "%zu refinements: at most 20", opt.levels);
  if (opt.solver == GM_POISSON_MULTIGRID && opt.levels == 0)
    return gm_error_set(err, GM_EINVAL, "multigrid needs at least one refinement level "
                                        "(--levels >= 1): the input mesh is the coarsest level");
  if (opt.levels > 0) {
    double need = 0.0;
    gm_status st = gm_mesh_refine_estimate(mesh, opt.levels, &need, err);
    if (st != GM_OK) return st;
    size_t limit = opt.max_bytes;
    if (limit != 0 && need > (double)limit)
      return gm_error_set(err, GM_ENOMEM,
                          "%zu refinements of %zu cells need about %.3g bytes for the finest mesh "
                          "alone, more than the limit of %zu bytes",
                          opt.levels, mesh->n_cells, need, limit);
  }
  const double t0 = wall_now();
  gm_mesh **lv = calloc(opt.levels + 1, sizeof(gm_mesh *));
  gm_csr **P = calloc(opt.levels + 1, sizeof(gm_csr *));
  gm_multigrid *mg = NULL;
  gm_sparse_cholesky *ch = NULL;
  double *sol = NULL;
  poisson_system s;
  memset(&s, 0, sizeof s);
  gm_status st = GM_OK;
  if (!lv || !P) {
    st = gm_error_set(err, GM_ENOMEM, "out of memory");
    goto done;
  }
  lv[0] = (gm_mesh *)mesh; /* borrowed, never freed below */
  for (size_t l = 0; l < opt.levels && st == GM_OK; ++l)
    st = gm_mesh_refine(lv[l], opt.max_bytes, &lv[l + 1], err);
  if (st != GM_OK) goto done;
  const gm_mesh *fine = lv[opt.levels];
  st = assemble(fine, &s, err);
  if (st != GM_OK) goto done;
  sol = calloc(s.ni, sizeof(double));
  if (sol == NULL) {
    st = gm_error_set(err, GM_ENOMEM, "out of memory");
    goto done;
  }
  report->setup_s = wall_now() - t0; /* refinement + complex + geometry + assembly */
  if (opt.solver == GM_POISSON_AUTO)
    opt.solver = opt.levels >= 1 ? GM_POISSON_MULTIGRID
                 : s.ni >= GM_POISSON_HYPRE_MIN_UNKNOWNS && gm_hypre_available() ? GM_POISSON_HYPRE
                                                                                   : GM_POISSON_CHOLMOD;
  report->solver = opt.solver;
  double t1 = wall_now();
  if (opt.solver == GM_POISSON_CHOLMOD) {
    st = gm_sparse_cholesky_create(s.aii, &ch, err);
    if (st != GM_OK) {
      if (st == GM_ESINGULAR)
        gm_error_set(err, st, "the DEC stiffness matrix is not positive definite (negative Hodge "
                              "star entries: check `mesh info`)");
      goto done;
    }
    report->factor_s = wall_now() - t1;
    t1 = wall_now();
    st = gm_sparse_cholesky_solve(ch, s.rhs, sol);
    if (st != GM_OK) {
      gm_error_set(err, st, "%s", gm_sparse_cholesky_errmsg(ch));
      goto done;
    }
    report->solve_s = wall_now() - t1;
  } else if (opt.solver == GM_POISSON_HYPRE) {
    gm_hypre_report hr;
    st = gm_hypre_boomeramg_pcg(s.aii, s.rhs, sol, opt.rtol, opt.max_iterations, &hr, err);
    report->iterations = hr.iterations, report->relative_residual = hr.relative_residual;
    /* wall seconds as for the other solvers: the setup's share of the call by hypre's CPU split
     * (hypre runs on this thread; MPI start-up falls into the setup) */
    const double wall = wall_now() - t1, cpu = hr.setup_s + hr.solve_s;
    report->factor_s = cpu > 0.0 ? wall * hr.setup_s / cpu : wall;
    report->solve_s = wall - report->factor_s;
    if (st != GM_OK) goto done;
  } else {
    /* P[l]: level (levels − l − 1) → level (levels − l), finest first, on interior vertices
     * (the correction vanishes on the Dirichlet boundary); the fine level's boundary mask is the
     * previous coarse one (s.bnd on the finest level). */
    const unsigned char *fb = s.bnd;
    unsigned char *mask = NULL;
    for (size_t l = 0; l < opt.levels && st == GM_OK; ++l) {
      const gm_mesh *c = lv[opt.levels - l - 1], *f = lv[opt.levels - l];
      gm_complex *cx = NULL;
      st = gm_mesh_complex(c, &cx, err);
      if (st != GM_OK) break;
      const unsigned char *cb = gm_complex_boundary_mask(cx, 0);
      st = gm_refinement_vertex_prolongation(cx, f->n_vertices, cb, fb, &P[l], err);
      unsigned char *next = st == GM_OK ? malloc(c->n_vertices) : NULL;
      if (next) memcpy(next, cb, c->n_vertices);
      gm_complex_free(cx);
      if (st == GM_OK && next == NULL) st = gm_error_set(err, GM_ENOMEM, "out of memory");
      free(mask);
      mask = next;
      fb = mask;
    }
    if (st == GM_OK) {
      gm_multigrid_options mo = gm_multigrid_defaults();
      mo.rtol = opt.rtol;
      mo.pre_smooth = opt.pre_smooth, mo.post_smooth = opt.post_smooth;
      if (opt.max_iterations) mo.max_iterations = opt.max_iterations;
      st = gm_multigrid_create(s.aii, opt.levels, (const gm_csr *const *)P, &mo, &mg, err);
    }
    free(mask);
    if (st != GM_OK) goto done;
    report->factor_s = wall_now() - t1; /* hierarchy: prolongations, Galerkin products */
    if (opt.measure_contraction) report->contraction = gm_multigrid_contraction(mg, 12);
    t1 = wall_now();
    st = gm_multigrid_pcg(mg, s.rhs, sol, &report->iterations, &report->relative_residual);
    report->solve_s = wall_now() - t1;
    if (st != GM_OK) {
      gm_error_set(err, st, "%s", gm_multigrid_errmsg(mg));
      goto done;
    }
  }
  if (opt.solver == GM_POISSON_CHOLMOD) {
    double *r = malloc(s.ni * sizeof(double));
    if (r) {
      memcpy(r, s.rhs, s.ni * sizeof(double));
      gm_csr_matvec(s.aii, -1.0, sol, 1.0, r);
      double rn = 0.0, bn = 0.0;
      for (size_t i = 0; i < s.ni; ++i) rn += r[i] * r[i], bn += s.rhs[i] * s.rhs[i];
      report->relative_residual = bn > 0.0 ? sqrt(rn / bn) : 0.0;
      free(r);
    }
  }
  double emax = 0.0, e2 = 0.0, umax = 0.0;
  double *uo = u_out ? malloc(s.nv * sizeof(double)) : NULL;
  if (u_out && uo == NULL) {
    st = gm_error_set(err, GM_ENOMEM, "out of memory");
    goto done;
  }
  for (size_t v = 0; v < s.nv; ++v) {
    double uh = s.bnd[v] ? s.u[v] : sol[s.map[v]];
    double e = uh - s.u[v];
    if (fabs(e) > emax) emax = fabs(e);
    if (fabs(s.u[v]) > umax) umax = fabs(s.u[v]);
    e2 += s.star0[v] * e * e;
    if (uo) uo[v] = uh;
  }
  if (u_out) *u_out = uo;
  report->n_vertices = s.nv;
  report->n_unknowns = s.ni;
  report->n_cells = fine->n_cells;
  report->h = s.h;
  report->error_max = emax;
  report->error_l2 = sqrt(e2);
  report->solution_max = umax;
done:
  gm_sparse_cholesky_free(ch);
  gm_multigrid_free(mg);
  if (lv)
    for (size_t l = 1; l <= opt.levels; ++l) gm_mesh_free(lv[l]);
  if (P)
    for (size_t l = 0; l <= opt.levels; ++l) gm_csr_free(P[l]);
  free(lv), free(P), free(sol);
  system_free(&s);
  return st;
}

gm_status gm_mesh_poisson(const gm_mesh *mesh, gm_poisson_report *report, double *u_out,
                          gm_error *err) {
  double *u = NULL;
  gm_poisson_options o = gm_poisson_defaults();
  o.solver = GM_POISSON_CHOLMOD; /* as documented: the direct solve */
  gm_status st = gm_mesh_poisson_solve(mesh, &o, report, u_out ? &u : NULL, err);
  if (st == GM_OK && u_out) memcpy(u_out, u, report->n_vertices * sizeof(double));
  free(u);
  return st;
}
