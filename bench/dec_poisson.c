/* Poisson −Δu = f on the unit square cut into 2 × 1000 × 1000 right triangles (1 002 001
 * vertices), Dirichlet data on the boundary, with the DEC Laplacian d_0ᵀ ⋆_1 d_0 u = ⋆_0 f on the
 * interior vertices (the path of gm_mesh_poisson): complex + geometry + assembly + CHOLMOD factor
 * + solve, against CHOLMOD's own analyse + factor + solve of the same matrix called directly in
 * the same run (the peer). As gm_mesh_poisson does, the complex, the geometry and the full
 * stiffness matrix are released before the factorization (CHOLMOD ran 15-20 % slower with them
 * resident). Target (issue 6): total / peer <= 1.2. Usage:
 * bench_dec_poisson [results-dir [cells-per-side [repeats]]]; best of the repeats, wall time and
 * CPU time of the process. */
#include <cholmod.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/dec.h"
#include "geomint/mesh.h"
#include "geomint/sparse.h"

#define BENCH_PI 3.14159265358979323846

static double process_cpu_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct {
  double wall, cpu;
} span;

static span since(double w0, double c0) {
  span s = {bench_now() - w0, process_cpu_now() - c0};
  return s;
}

static void keep_best(span *best, span s) {
  if (s.wall < best->wall) best->wall = s.wall;
  if (s.cpu < best->cpu) best->cpu = s.cpu;
}

static double exact(const double *x) { return sin(BENCH_PI * x[0] + 0.25) * sin(BENCH_PI * x[1] + 0.25); }

/* The library path; returns max |u_h − u| (a check that the two solves agree). */
static double library_path(const gm_mesh *m, span *t_cx, span *t_geo, span *t_asm, span *t_fac,
                           span *t_sol, gm_csr **aii_out, double **rhs_out, double **sol_out) {
  gm_error err = {{0}};
  double w0 = bench_now(), c0 = process_cpu_now();
  gm_complex *cx = NULL;
  if (gm_mesh_complex(m, &cx, &err) != GM_OK) {
    fprintf(stderr, "complex: %s\n", err.message);
    exit(1);
  }
  *t_cx = since(w0, c0);
  w0 = bench_now(), c0 = process_cpu_now();
  gm_geometry *g = NULL;
  if (gm_geometry_create(cx, NULL, &g, &err) != GM_OK) {
    fprintf(stderr, "geometry: %s\n", err.message);
    exit(1);
  }
  *t_geo = since(w0, c0);
  w0 = bench_now(), c0 = process_cpu_now();
  gm_csr *a = NULL;
  if (gm_dec_stiffness(g, 0, &a, &err) != GM_OK) {
    fprintf(stderr, "stiffness: %s\n", err.message);
    exit(1);
  }
  const size_t nv = m->n_vertices;
  unsigned char *bnd = malloc(nv);
  memcpy(bnd, gm_complex_boundary_mask(cx, 0), nv);
  const double *star0 = gm_geometry_hodge_star(g, 0);
  size_t *map = malloc(nv * sizeof(size_t));
  double *u = malloc(nv * sizeof(double));
  size_t ni = 0, nnz = 0;
  for (size_t v = 0; v < nv; ++v) {
    map[v] = bnd[v] ? SIZE_MAX : ni++;
    u[v] = exact(m->x + 2 * v);
  }
  for (size_t v = 0; v < nv; ++v)
    if (!bnd[v])
      for (size_t p = a->row_start[v]; p < a->row_start[v + 1]; ++p) nnz += !bnd[a->col[p]];
  gm_csr *aii = NULL;
  gm_csr_create(ni, ni, nnz, &aii);
  double *rhs = malloc(ni * sizeof(double)), *sol = malloc(ni * sizeof(double));
  const double fscale = 2.0 * BENCH_PI * BENCH_PI;
  size_t w = 0;
  for (size_t v = 0; v < nv; ++v) {
    if (bnd[v]) continue;
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
    aii->row_start[map[v] + 1] = w;
    rhs[map[v]] = b;
  }
  gm_csr_free(a);
  gm_geometry_free(g);
  gm_complex_free(cx);
  *t_asm = since(w0, c0);
  w0 = bench_now(), c0 = process_cpu_now();
  gm_sparse_cholesky *ch = NULL;
  if (gm_sparse_cholesky_create(aii, &ch, &err) != GM_OK) {
    fprintf(stderr, "cholesky: %s\n", err.message);
    exit(1);
  }
  *t_fac = since(w0, c0);
  w0 = bench_now(), c0 = process_cpu_now();
  if (gm_sparse_cholesky_solve(ch, rhs, sol) != GM_OK) {
    fprintf(stderr, "solve: %s\n", gm_sparse_cholesky_errmsg(ch));
    exit(1);
  }
  *t_sol = since(w0, c0);
  double emax = 0.0;
  for (size_t v = 0; v < nv; ++v)
    if (!bnd[v]) emax = fmax(emax, fabs(sol[map[v]] - u[v]));
  gm_sparse_cholesky_free(ch);
  free(map), free(u), free(bnd);
  *aii_out = aii, *rhs_out = rhs, *sol_out = sol;
  return emax;
}

/* CHOLMOD alone on the same matrix: analyse + factor + solve (default settings, as the library).
 * The index arrays are converted to CHOLMOD's type outside the timing. */
static span cholmod_path(const gm_csr *a, const double *rhs, double *x) {
  const size_t n = a->n_rows, nnz = gm_csr_nnz(a);
  SuiteSparse_long *p = malloc((n + 1) * sizeof *p), *i = malloc(nnz * sizeof *i);
  for (size_t r = 0; r <= n; ++r) p[r] = (SuiteSparse_long)a->row_start[r];
  for (size_t k = 0; k < nnz; ++k) i[k] = (SuiteSparse_long)a->col[k];
  cholmod_common cm;
  cholmod_l_start(&cm);
  cm.print = 0;
  cholmod_sparse s;
  memset(&s, 0, sizeof s);
  s.nrow = s.ncol = n;
  s.nzmax = nnz;
  s.p = p, s.i = i, s.x = a->val;
  s.stype = 1, s.itype = CHOLMOD_LONG, s.xtype = CHOLMOD_REAL, s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1, s.packed = 1;
  cholmod_dense *b = cholmod_l_allocate_dense(n, 1, n, CHOLMOD_REAL, &cm);
  memcpy(b->x, rhs, n * sizeof(double));
  double w0 = bench_now(), c0 = process_cpu_now();
  cholmod_factor *L = cholmod_l_analyze(&s, &cm);
  cholmod_l_factorize(&s, L, &cm);
  cholmod_dense *sol = cholmod_l_solve(CHOLMOD_A, L, b, &cm);
  span t = since(w0, c0);
  memcpy(x, sol->x, n * sizeof(double));
  cholmod_l_free_dense(&sol, &cm);
  cholmod_l_free_dense(&b, &cm);
  cholmod_l_free_factor(&L, &cm);
  cholmod_l_finish(&cm);
  free(p), free(i);
  return t;
}

int main(int argc, char **argv) {
  const size_t n = argc > 2 ? (size_t)strtoul(argv[2], NULL, 10) : 1000;
  const int repeats = argc > 3 ? atoi(argv[3]) : 3;
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  if (gm_mesh_rectangle(0, 1, 0, 1, n, n, GM_DIAGONAL_RIGHT, &m, &err) != GM_OK) {
    fprintf(stderr, "mesh: %s\n", err.message);
    return 1;
  }
  const span inf = {INFINITY, INFINITY};
  span cx = inf, geo = inf, as = inf, fac = inf, sol = inf, tot = inf, peer = inf;
  double emax = 0.0, diff = 0.0;
  size_t ni = 0;
  for (int rep = 0; rep < repeats; ++rep) {
    span s[5];
    gm_csr *aii = NULL;
    double *rhs = NULL, *x = NULL;
    emax = library_path(m, &s[0], &s[1], &s[2], &s[3], &s[4], &aii, &rhs, &x);
    span total = {0, 0};
    for (int k = 0; k < 5; ++k) total.wall += s[k].wall, total.cpu += s[k].cpu;
    keep_best(&cx, s[0]), keep_best(&geo, s[1]), keep_best(&as, s[2]), keep_best(&fac, s[3]);
    keep_best(&sol, s[4]), keep_best(&tot, total);
    ni = aii->n_rows;
    double *y = malloc(ni * sizeof(double));
    keep_best(&peer, cholmod_path(aii, rhs, y));
    diff = 0.0;
    for (size_t i = 0; i < ni; ++i) diff = fmax(diff, fabs(y[i] - x[i]));
    free(y), free(rhs), free(x);
    gm_csr_free(aii);
  }
  const double ratio_wall = tot.wall / peer.wall, ratio_cpu = tot.cpu / peer.cpu;
  printf("dec_poisson: %zu x %zu squares, 2 triangles each; %zu vertices, %zu unknowns; best of %d\n",
         n, n, m->n_vertices, ni, repeats);
  printf("  %-36s %10s %10s\n", "", "wall [s]", "CPU [s]");
  printf("  %-36s %10.3f %10.3f\n", "complex", cx.wall, cx.cpu);
  printf("  %-36s %10.3f %10.3f\n", "geometry (circumcenters, stars)", geo.wall, geo.cpu);
  printf("  %-36s %10.3f %10.3f\n", "assembly, release complex + geometry", as.wall, as.cpu);
  printf("  %-36s %10.3f %10.3f\n", "CHOLMOD analyse + factor (library)", fac.wall, fac.cpu);
  printf("  %-36s %10.3f %10.3f\n", "solve (library)", sol.wall, sol.cpu);
  printf("  %-36s %10.3f %10.3f\n", "total", tot.wall, tot.cpu);
  printf("  %-36s %10.3f %10.3f\n", "peer: CHOLMOD analyse+factor+solve", peer.wall, peer.cpu);
  printf("  %-36s %10.3f %10.3f   (target <= 1.2)\n", "ratio total / peer", ratio_wall, ratio_cpu);
  printf("  max |u_h - u| = %.3g, max |library - CHOLMOD| = %.3g\n", emax, diff);
  FILE *f = bench_open_json(argc, argv, "dec_poisson");
  if (f) {
    fprintf(f,
            "{\n  \"benchmark\": \"dec_poisson\",\n  \"cells_per_side\": %zu,\n  \"vertices\": %zu,\n"
            "  \"unknowns\": %zu,\n  \"repeats\": %d,\n"
            "  \"seconds_complex\": %.6f,\n  \"seconds_geometry\": %.6f,\n"
            "  \"seconds_assembly\": %.6f,\n  \"seconds_factor\": %.6f,\n  \"seconds_solve\": %.6f,\n"
            "  \"seconds_total\": %.6f,\n  \"cpu_seconds_total\": %.6f,\n"
            "  \"peer\": \"CHOLMOD analyse + factor + solve, same matrix\",\n"
            "  \"seconds_peer\": %.6f,\n  \"cpu_seconds_peer\": %.6f,\n"
            "  \"ratio_total_to_peer\": %.4f,\n  \"ratio_cpu_total_to_peer\": %.4f,\n"
            "  \"target_ratio\": 1.2,\n  \"error_max\": %.6g,\n  \"library_vs_peer_max_diff\": %.6g\n}\n",
            n, m->n_vertices, ni, repeats, cx.wall, geo.wall, as.wall, fac.wall, sol.wall, tot.wall,
            tot.cpu, peer.wall, peer.cpu, ratio_wall, ratio_cpu, emax, diff);
    fclose(f);
  }
  gm_mesh_free(m);
  return 0;
}
