/* DEC Poisson (0-form Laplacian d_0ᵀ ⋆_1 d_0, Dirichlet) on red-refined BCC tetrahedral meshes of
 * the unit cube: CHOLMOD against CG preconditioned by the geometric multigrid V(2,2)-cycle
 * (geomint/multigrid.h) and CG with hypre's BoomerAMG (when built with hypre), to a relative
 * residual of 1e-10, each as a multiple of one sparse product y = A x with the same interior
 * matrix timed in the same run (the floor of any solver that touches the matrix). Each solver
 * runs in its own child process, so the peak resident memory (getrusage) is that solver's run
 * alone (mesh, DEC build, solver). Goal of issue 24:
 * the iterative solver within 40 products' worth.
 * Usage: bench_dec_multigrid [results-dir [finest-level [cholmod-finest-level]]]: levels 3..L
 * of the BCC cube 2×2×2 (48 tets; level l has 48·8^l tets), default L = 5 for both. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench_util.h"
#include "geomint/dec.h"
#include "geomint/mesh.h"
#include "geomint/multigrid.h"
#include "geomint/sparse.h"

typedef struct result {
  int ok;
  double factor_s, solve_s, relres, peak_mb;
  double refine_s, build_s; /* job 0: the last refinement; complex + geometry of the result */
  size_t iterations, unknowns, cells;
  double matvec_s;
  size_t nnz;
} result;

static gm_mesh *coarse_mesh(void) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  if (gm_mesh_bcc(lo, hi, 2, 2, 2, 0, &m, &err) != GM_OK) {
    fprintf(stderr, "bcc: %s\n", err.message);
    exit(1);
  }
  return m;
}

static double peak_mb(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return (double)ru.ru_maxrss / 1024.0;
}

static double cpu_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Interior rows and columns of a (mask: 1 = boundary, drop). */
static gm_csr *interior(const gm_csr *a, const unsigned char *rb, const unsigned char *cb) {
  size_t *cmap = malloc(a->n_cols * sizeof(size_t)), nc = 0, nr = 0, nnz = 0;
  for (size_t j = 0; j < a->n_cols; ++j) cmap[j] = cb[j] ? SIZE_MAX : nc++;
  for (size_t i = 0; i < a->n_rows; ++i)
    if (!rb[i]) {
      ++nr;
      for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p) nnz += !cb[a->col[p]];
    }
  gm_csr *b = NULL;
  gm_csr_create(nr, nc, nnz, &b);
  size_t w = 0, r = 0;
  for (size_t i = 0; i < a->n_rows; ++i) {
    if (rb[i]) continue;
    for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p)
      if (!cb[a->col[p]]) b->col[w] = cmap[a->col[p]], b->val[w++] = a->val[p];
    b->row_start[++r] = w;
  }
  free(cmap);
  return b;
}

/* job 0: one sparse product (best of 5, CPU time of the thread); 1: CHOLMOD analyse + factor +
 * solve; 2: multigrid hierarchy (prolongations gm_refinement_vertex_prolongation on interior
 * vertices, Galerkin products, coarsest factor) + PCG; 3: hypre BoomerAMG setup + PCG. Times
 * are CPU seconds of the process for CHOLMOD (its BLAS threads) and of the thread for the
 * single-threaded MG and hypre (the machine is shared: wall time measures the other jobs too). */
static void run_job(size_t L, int job, result *r) {
  gm_error err = {{0}};
  gm_mesh **m = calloc(L + 1, sizeof(gm_mesh *));
  gm_complex **cx = calloc(L + 1, sizeof(gm_complex *));
  m[0] = coarse_mesh();
  double t_ref = 0.0;
  for (size_t l = 0; l < L; ++l) {
    t_ref = cpu_now();
    if (gm_mesh_refine(m[l], 0, &m[l + 1], &err) != GM_OK) return;
    t_ref = cpu_now() - t_ref;
  }
  for (size_t l = 0; l < L; ++l)
    if (gm_mesh_complex(m[l], &cx[l], &err) != GM_OK) return;
  double t_build = cpu_now();
  gm_geometry *g = NULL;
  gm_csr *a = NULL;
  if (gm_mesh_complex(m[L], &cx[L], &err) || gm_geometry_create(cx[L], NULL, &g, &err)) return;
  r->refine_s = t_ref, r->build_s = cpu_now() - t_build;
  if (gm_dec_stiffness(g, 0, &a, &err)) return;
  const unsigned char *bnd = gm_complex_boundary_mask(cx[L], 0);
  gm_csr *A = interior(a, bnd, bnd);
  gm_csr_free(a);
  gm_geometry_free(g);
  const size_t n = A->n_rows;
  double *b = malloc(n * sizeof(double)), *x = calloc(n, sizeof(double));
  for (size_t i = 0; i < n; ++i) b[i] = 1.0;
  r->unknowns = n, r->nnz = gm_csr_nnz(A), r->cells = m[L]->n_cells;
  if (job == 0) {
    double best = INFINITY;
    for (int rep = 0; rep < 5; ++rep) {
      double t0 = bench_cpu_now();
      gm_csr_matvec(A, 1.0, b, 0.0, x);
      best = fmin(best, bench_cpu_now() - t0);
    }
    r->matvec_s = best;
    r->ok = 1;
  } else if (job == 1) {
    gm_sparse_cholesky *ch = NULL;
    double t0 = cpu_now();
    if (gm_sparse_cholesky_create(A, &ch, &err) == GM_OK) {
      r->factor_s = cpu_now() - t0;
      t0 = cpu_now();
      gm_sparse_cholesky_solve(ch, b, x);
      r->solve_s = cpu_now() - t0;
      r->ok = 1;
    }
    gm_sparse_cholesky_free(ch);
  } else if (job == 2) { /* single-threaded: the thread's CPU time (the process's would count the OpenMP
            * workers of the DEC build still spinning) */
    double t0 = bench_cpu_now();
    gm_csr **P = calloc(L, sizeof(gm_csr *));
    for (size_t l = 0; l < L; ++l) /* P[l]: level L-l-1 -> level L-l, interior vertices */
      if (gm_refinement_vertex_prolongation(cx[L - l - 1], m[L - l]->n_vertices,
                                            gm_complex_boundary_mask(cx[L - l - 1], 0),
                                            gm_complex_boundary_mask(cx[L - l], 0), &P[l], &err))
        return;
    gm_multigrid *mg = NULL;
    if (gm_multigrid_create(A, L, (const gm_csr *const *)P, NULL, &mg, &err) == GM_OK) {
      r->factor_s = bench_cpu_now() - t0;
      t0 = bench_cpu_now();
      r->ok = gm_multigrid_pcg(mg, b, x, &r->iterations, &r->relres) == GM_OK;
      r->solve_s = bench_cpu_now() - t0;
    }
    gm_multigrid_free(mg);
    for (size_t l = 0; l < L; ++l) gm_csr_free(P[l]);
    free(P);
  } else { /* job 3: hypre BoomerAMG-CG (one thread: its thread CPU time, setup and solve) */
    gm_hypre_report hr;
    r->ok = gm_hypre_boomeramg_pcg(A, b, x, 1e-10, 200, &hr, &err) == GM_OK;
    r->factor_s = hr.setup_s, r->solve_s = hr.solve_s, r->iterations = hr.iterations;
  }
  if (job != 0) { /* relative residual of the solution */
    double *res = malloc(n * sizeof(double)), rn = 0.0;
    memcpy(res, b, n * sizeof(double));
    gm_csr_matvec(A, -1.0, x, 1.0, res);
    for (size_t i = 0; i < n; ++i) rn += res[i] * res[i];
    r->relres = sqrt(rn / (double)n);
    free(res);
  }
  free(b), free(x);
  gm_csr_free(A);
  for (size_t l = 0; l <= L; ++l) gm_complex_free(cx[l]), gm_mesh_free(m[l]);
  free(cx), free(m);
}

/* Run job in a child process and bring its result (with its peak memory) back. */
static result in_child(size_t L, int job) {
  result r;
  memset(&r, 0, sizeof r);
  int fd[2];
  if (pipe(fd) != 0) return r;
  fflush(stdout);
  pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    run_job(L, job, &r);
    r.peak_mb = peak_mb();
    ssize_t wr = write(fd[1], &r, sizeof r);
    _exit(wr == (ssize_t)sizeof r ? 0 : 1);
  }
  close(fd[1]);
  ssize_t got = read(fd[0], &r, sizeof r);
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (got != (ssize_t)sizeof r) memset(&r, 0, sizeof r);
  return r;
}

int main(int argc, char **argv) {
  const size_t finest = argc > 2 ? (size_t)atoi(argv[2]) : 5;
  const size_t chol_finest = argc > 3 ? (size_t)atoi(argv[3]) : finest;
  FILE *f = bench_open_json(argc, argv, "dec_multigrid");
  if (f) fprintf(f, "{\n  \"bench\": \"dec_multigrid\",\n  \"rows\": [\n");
  printf("DEC Poisson on the BCC cube refined l times (48·8^l tets), rtol 1e-10; CPU seconds, "
         "'x mv' = multiples of one sparse product, MB = peak resident memory of the run\n");
  printf("%5s %9s %9s %10s | %9s %9s %8s %7s | %9s %9s %8s %4s %7s | %9s %9s %8s %4s %7s\n",
         "level", "tets", "unknowns", "matvec", "chol fac", "chol sol", "x mv", "MB", "mg hier",
         "mg cg", "x mv", "its", "MB", "hy setup", "hy cg", "x mv", "its", "MB");
  double last_refine = NAN, last_build = NAN;
  for (size_t L = 3; L <= finest; ++L) {
    result mv = in_child(L, 0);
    result ch = L <= chol_finest ? in_child(L, 1) : (result){0};
    result mg = in_child(L, 2);
    result hy = gm_hypre_available() ? in_child(L, 3) : (result){0};
    last_refine = mv.refine_s, last_build = mv.build_s;
    if (!mv.ok || !mg.ok) {
      fprintf(stderr, "level %zu failed\n", L);
      return 1;
    }
    const double chol_x = ch.ok ? (ch.factor_s + ch.solve_s) / mv.matvec_s : NAN;
    const double mg_x = (mg.factor_s + mg.solve_s) / mv.matvec_s;
    const double hy_x = hy.ok ? (hy.factor_s + hy.solve_s) / mv.matvec_s : NAN;
    printf("%5zu %9zu %9zu %10.3e | %9.3f %9.3f %8.0f %7.0f | %9.3f %9.3f %8.1f %4zu %7.0f | %9.3f "
           "%9.3f %8.1f %4zu %7.0f\n",
           L, mg.cells, mg.unknowns, mv.matvec_s, ch.factor_s, ch.solve_s, chol_x, ch.peak_mb,
           mg.factor_s, mg.solve_s, mg_x, mg.iterations, mg.peak_mb, hy.factor_s, hy.solve_s,
           hy_x, hy.iterations, hy.peak_mb);
    if (f)
      fprintf(f,
              "    {\"level\": %zu, \"tets\": %zu, \"unknowns\": %zu, \"nnz\": %zu, "
              "\"matvec_s\": %.6e, \"cholmod_ok\": %s, "
              "\"cholmod_factor_s\": %.4f, \"cholmod_solve_s\": %.4f, \"cholmod_matvecs\": %.1f, "
              "\"cholmod_peak_mb\": %.0f, \"mg_hierarchy_s\": %.4f, "
              "\"mg_cg_s\": %.4f, \"mg_matvecs\": %.1f, \"mg_iterations\": %zu, "
              "\"mg_peak_mb\": %.0f, \"hypre_ok\": %s, \"hypre_setup_s\": %.4f, "
              "\"hypre_cg_s\": %.4f, \"hypre_matvecs\": %.1f, \"hypre_iterations\": %zu, "
              "\"hypre_peak_mb\": %.0f}%s\n",
              L, mg.cells, mg.unknowns, mv.nnz, mv.matvec_s, ch.ok ? "true" : "false",
              ch.factor_s, ch.solve_s, ch.ok ? chol_x : -1.0, ch.peak_mb,
              mg.factor_s, mg.solve_s, mg_x, mg.iterations, mg.peak_mb, hy.ok ? "true" : "false",
              hy.factor_s, hy.solve_s, hy.ok ? hy_x : -1.0, hy.iterations, hy.peak_mb,
              L == finest ? "" : ",");
  }
  if (f) bench_close_json(f);
  printf("refinement of the finest level: %.3f s CPU, %.2f x the DEC build (complex + geometry, "
         "%.3f s) of the refined mesh\n",
         last_refine, last_refine / last_build, last_build);
  return 0;
}
