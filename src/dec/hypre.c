/* Algebraic multigrid through hypre (Lawrence Livermore, https://github.com/hypre-space/hypre;
 * Debian libhypre-dev): PCG preconditioned by BoomerAMG for 0-form Laplacians and by AMS for
 * the 1-form curl–curl problem. Parameters and their meaning: hypre Reference Manual, sections
 * "ParCSR Solvers" (HYPRE_BoomerAMGSet*, HYPRE_AMSSet*, HYPRE_ParCSRPCG*). Everything runs on
 * MPI_COMM_SELF. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/internal.h"
#include "geomint/multigrid.h"

#ifndef GM_HAVE_HYPRE

int gm_hypre_available(void) { return 0; }

static gm_status no_hypre(gm_error *err) {
  return gm_error_set(err, GM_EUNSUPPORTED,
                      "geomint was built without hypre: install Debian libhypre-dev "
                      "(scripts/install-deps) and rebuild");
}

gm_status gm_hypre_boomeramg_pcg(const gm_csr *A, const double *b, double *x, double rtol,
                                 size_t max_iterations, gm_hypre_report *report, gm_error *err) {
  (void)A, (void)b, (void)x, (void)rtol, (void)max_iterations, (void)report;
  return no_hypre(err);
}

gm_status gm_hypre_ams_pcg(const gm_csr *A, const gm_csr *G, const double *xyz, const double *b,
                           double *x, double rtol, size_t max_iterations, gm_hypre_report *report,
                           gm_error *err) {
  (void)A, (void)G, (void)xyz, (void)b, (void)x, (void)rtol, (void)max_iterations, (void)report;
  return no_hypre(err);
}

#else

#include <HYPRE.h>
#include <HYPRE_IJ_mv.h>
#include <HYPRE_krylov.h>
#include <HYPRE_parcsr_ls.h>
#include <mpi.h>

int gm_hypre_available(void) { return 1; }

static double thread_cpu(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static gm_status start(gm_error *err) {
  int up = 0;
  MPI_Initialized(&up);
  if (!up && MPI_Init(NULL, NULL) != MPI_SUCCESS)
    return gm_error_set(err, GM_EUNSUPPORTED, "hypre needs MPI, and MPI_Init failed");
  static int hypre_up = 0;
  if (!hypre_up) {
    if (HYPRE_Init() != 0)
      return gm_error_set(err, GM_EUNSUPPORTED, "hypre could not be initialised (HYPRE_Init failed)");
    hypre_up = 1;
  }
  return GM_OK;
}

/* An IJ matrix holding a (rows 0..n_rows−1, columns 0..n_cols−1 on this one process). */
static gm_status ij_matrix(const gm_csr *a, HYPRE_IJMatrix *out, gm_error *err) {
  const size_t n = a->n_rows, nnz = gm_csr_nnz(a);
  if (n > INT32_MAX || a->n_cols > INT32_MAX || nnz > INT32_MAX)
    return gm_error_set(err, GM_EUNSUPPORTED, "%zu × %zu matrix with %zu entries: hypre's 32-bit "
                        "indices (this Debian build) allow at most 2^31 − 1", n, a->n_cols, nnz);
  HYPRE_Int *ncols = malloc((n ? n : 1) * sizeof(HYPRE_Int));
  HYPRE_BigInt *rows = malloc((n ? n : 1) * sizeof(HYPRE_BigInt));
  HYPRE_BigInt *cols = malloc((nnz ? nnz : 1) * sizeof(HYPRE_BigInt));
  if (!ncols || !rows || !cols) {
    free(ncols), free(rows), free(cols);
    return gm_error_set(err, GM_ENOMEM, "out of memory copying the matrix into hypre");
  }
  for (size_t i = 0; i < n; ++i)
    ncols[i] = (HYPRE_Int)(a->row_start[i + 1] - a->row_start[i]), rows[i] = (HYPRE_BigInt)i;
  for (size_t p = 0; p < nnz; ++p) cols[p] = (HYPRE_BigInt)a->col[p];
  HYPRE_IJMatrix m;
  HYPRE_IJMatrixCreate(MPI_COMM_SELF, 0, (HYPRE_BigInt)n - 1, 0, (HYPRE_BigInt)a->n_cols - 1, &m);
  HYPRE_IJMatrixSetObjectType(m, HYPRE_PARCSR);
  HYPRE_IJMatrixSetRowSizes(m, ncols);
  HYPRE_IJMatrixInitialize(m);
  HYPRE_IJMatrixSetValues(m, (HYPRE_Int)n, ncols, rows, cols, a->val);
  HYPRE_IJMatrixAssemble(m);
  free(ncols), free(rows), free(cols);
  *out = m;
  return GM_OK;
}

static HYPRE_IJVector ij_vector(size_t n, const double *v) {
  HYPRE_IJVector x;
  HYPRE_IJVectorCreate(MPI_COMM_SELF, 0, (HYPRE_BigInt)n - 1, &x);
  HYPRE_IJVectorSetObjectType(x, HYPRE_PARCSR);
  HYPRE_IJVectorInitialize(x);
  HYPRE_IJVectorSetValues(x, (HYPRE_Int)n, NULL, v); /* NULL indices: 0..n−1 */
  HYPRE_IJVectorAssemble(x);
  return x;
}

static double relative_residual(const gm_csr *A, const double *b, const double *x) {
  const size_t n = A->n_rows;
  double *r = malloc(n * sizeof(double)), rr = 0.0, bb = 0.0;
  if (r == NULL) return NAN;
  memcpy(r, b, n * sizeof(double));
  gm_csr_matvec(A, -1.0, x, 1.0, r);
  for (size_t i = 0; i < n; ++i) rr += r[i] * r[i], bb += b[i] * b[i];
  free(r);
  return bb > 0.0 ? sqrt(rr / bb) : sqrt(rr);
}

static gm_status check_system(const gm_csr *A, const double *b, double *x, double rtol,
                              gm_error *err) {
  if (A == NULL || b == NULL || x == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  if (A->n_rows != A->n_cols || A->n_rows == 0)
    return gm_error_set(err, GM_EINVAL, "the matrix is %zu × %zu: needs a non-empty square one",
                        A->n_rows, A->n_cols);
  if (!(rtol > 0.0) || !(rtol < 1.0))
    return gm_error_set(err, GM_EINVAL, "rtol = %g: needs 0 < rtol < 1", rtol);
  for (size_t i = 0; i < A->n_rows; ++i)
    if (!isfinite(b[i]) || !isfinite(x[i]))
      return gm_error_set(err, GM_EDOMAIN, "non-finite %s at entry %zu",
                          isfinite(b[i]) ? "x" : "b", i);
  return GM_OK;
}

/* PCG with the given preconditioner (already configured), then the report. */
static gm_status run_pcg(const gm_csr *A, HYPRE_IJMatrix ij, HYPRE_Solver pre,
                         HYPRE_PtrToSolverFcn solve, HYPRE_PtrToSolverFcn setup, const double *b,
                         double *x, double rtol, size_t max_iterations, double t_start,
                         const char *name, gm_hypre_report *report, gm_error *err) {
  const size_t n = A->n_rows;
  HYPRE_ParCSRMatrix pA;
  HYPRE_IJMatrixGetObject(ij, (void **)&pA);
  HYPRE_IJVector vb = ij_vector(n, b), vx = ij_vector(n, x);
  HYPRE_ParVector pb, px;
  HYPRE_IJVectorGetObject(vb, (void **)&pb);
  HYPRE_IJVectorGetObject(vx, (void **)&px);
  HYPRE_Solver pcg;
  HYPRE_ParCSRPCGCreate(MPI_COMM_SELF, &pcg);
  HYPRE_PCGSetTol(pcg, rtol);
  HYPRE_PCGSetTwoNorm(pcg, 1); /* stop on ‖r‖₂ ≤ rtol ‖b‖₂, as gm_multigrid_pcg */
  HYPRE_PCGSetMaxIter(pcg, (HYPRE_Int)(max_iterations ? max_iterations : 200));
  HYPRE_PCGSetPrecond(pcg, solve, setup, pre);
  HYPRE_ParCSRPCGSetup(pcg, pA, pb, px);
  const double t_setup = thread_cpu();
  HYPRE_ParCSRPCGSolve(pcg, pA, pb, px);
  const double t_solve = thread_cpu();
  HYPRE_Int its = 0;
  HYPRE_PCGGetNumIterations(pcg, &its);
  HYPRE_IJVectorGetValues(vx, (HYPRE_Int)n, NULL, x);
  HYPRE_ParCSRPCGDestroy(pcg);
  HYPRE_IJVectorDestroy(vb);
  HYPRE_IJVectorDestroy(vx);
  HYPRE_ClearAllErrors(); /* a PCG that stops at max_iterations sets hypre's error flag */
  gm_hypre_report rep = {(size_t)its, relative_residual(A, b, x), t_setup - t_start,
                         t_solve - t_setup};
  if (report) *report = rep;
  if (!(rep.relative_residual <= rtol))
    return gm_error_set(err, GM_ENOCONV,
                        "hypre PCG with %s: relative residual %.3g after %zu iterations, above "
                        "rtol = %.3g",
                        name, rep.relative_residual, rep.iterations, rtol);
  return GM_OK;
}

gm_status gm_hypre_boomeramg_pcg(const gm_csr *A, const double *b, double *x, double rtol,
                                 size_t max_iterations, gm_hypre_report *report, gm_error *err) {
  gm_status st = check_system(A, b, x, rtol, err);
  if (st == GM_OK) st = start(err);
  if (st != GM_OK) return st;
  const double t0 = thread_cpu();
  HYPRE_IJMatrix ij;
  st = ij_matrix(A, &ij, err);
  if (st != GM_OK) return st;
  HYPRE_Solver amg;
  HYPRE_BoomerAMGCreate(&amg);
  HYPRE_BoomerAMGSetPrintLevel(amg, 0);
  HYPRE_BoomerAMGSetMaxIter(amg, 1); /* one cycle per application: a preconditioner */
  HYPRE_BoomerAMGSetTol(amg, 0.0);
  HYPRE_BoomerAMGSetCoarsenType(amg, 10);      /* HMIS */
  HYPRE_BoomerAMGSetInterpType(amg, 6);        /* extended+i */
  HYPRE_BoomerAMGSetPMaxElmts(amg, 4);         /* interpolation truncated to 4 entries a row */
  HYPRE_BoomerAMGSetStrongThreshold(amg, 0.5); /* the manual's value for 3-D Laplacians */
  HYPRE_BoomerAMGSetRelaxType(amg, 8);         /* l1-scaled symmetric Gauss–Seidel: SPD cycle */
  HYPRE_BoomerAMGSetNumSweeps(amg, 1);
  st = run_pcg(A, ij, amg, (HYPRE_PtrToSolverFcn)HYPRE_BoomerAMGSolve,
               (HYPRE_PtrToSolverFcn)HYPRE_BoomerAMGSetup, b, x, rtol, max_iterations, t0,
               "BoomerAMG", report, err);
  HYPRE_BoomerAMGDestroy(amg);
  HYPRE_IJMatrixDestroy(ij);
  return st;
}

gm_status gm_hypre_ams_pcg(const gm_csr *A, const gm_csr *G, const double *xyz, const double *b,
                           double *x, double rtol, size_t max_iterations, gm_hypre_report *report,
                           gm_error *err) {
  gm_status st = check_system(A, b, x, rtol, err);
  if (st != GM_OK) return st;
  if (G == NULL || xyz == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  if (G->n_rows != A->n_rows || G->n_cols == 0)
    return gm_error_set(err, GM_EINVAL,
                        "the discrete gradient is %zu × %zu: it needs %zu rows (the edge "
                        "unknowns) and at least one vertex column",
                        G->n_rows, G->n_cols, A->n_rows);
  st = start(err);
  if (st != GM_OK) return st;
  const double t0 = thread_cpu();
  HYPRE_IJMatrix ij, ijg;
  st = ij_matrix(A, &ij, err);
  if (st != GM_OK) return st;
  st = ij_matrix(G, &ijg, err);
  if (st != GM_OK) {
    HYPRE_IJMatrixDestroy(ij);
    return st;
  }
  const size_t nv = G->n_cols;
  double *c = malloc(nv * sizeof(double));
  if (c == NULL) {
    HYPRE_IJMatrixDestroy(ij), HYPRE_IJMatrixDestroy(ijg);
    return gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  HYPRE_IJVector coord[3];
  HYPRE_ParVector pc[3];
  for (int d = 0; d < 3; ++d) {
    for (size_t v = 0; v < nv; ++v) c[v] = xyz[3 * v + (size_t)d];
    coord[d] = ij_vector(nv, c);
    HYPRE_IJVectorGetObject(coord[d], (void **)&pc[d]);
  }
  free(c);
  HYPRE_ParCSRMatrix pG;
  HYPRE_IJMatrixGetObject(ijg, (void **)&pG);
  HYPRE_Solver ams;
  HYPRE_AMSCreate(&ams);
  HYPRE_AMSSetDimension(ams, 3);
  HYPRE_AMSSetMaxIter(ams, 1);
  HYPRE_AMSSetTol(ams, 0.0);
  HYPRE_AMSSetCycleType(ams, 1); /* the multiplicative "01210" cycle: symmetric */
  HYPRE_AMSSetPrintLevel(ams, 0);
  HYPRE_AMSSetDiscreteGradient(ams, pG);
  HYPRE_AMSSetCoordinateVectors(ams, pc[0], pc[1], pc[2]);
  st = run_pcg(A, ij, ams, (HYPRE_PtrToSolverFcn)HYPRE_AMSSolve,
               (HYPRE_PtrToSolverFcn)HYPRE_AMSSetup, b, x, rtol, max_iterations, t0, "AMS", report,
               err);
  HYPRE_AMSDestroy(ams);
  for (int d = 0; d < 3; ++d) HYPRE_IJVectorDestroy(coord[d]);
  HYPRE_IJMatrixDestroy(ijg);
  HYPRE_IJMatrixDestroy(ij);
  return st;
}

#endif
