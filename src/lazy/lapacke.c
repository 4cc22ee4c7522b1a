/* LAPACKE, opened on first use (lazy.h): LU factors and solves above the built-in small LU,
 * symmetric eigenproblems (src/core/linalg.c) and the eigenvectors of a Runge–Kutta matrix
 * (src/methods/rk/stage_transform.c), singular values for the moving-mesh VI's conditioning
 * (src/pde/moving_mesh.c). */
#include <lapacke.h>

#include "lazy/lazy.h"

static gm_lazy_lib lib = GM_LAZY_LIB(GM_LAPACKE_SONAME);
static struct {
  lapack_int (*dgeev)(int, char, char, lapack_int, double *, lapack_int, double *, double *,
                      double *, lapack_int, double *, lapack_int);
  lapack_int (*dgetrf_work)(int, lapack_int, lapack_int, double *, lapack_int, lapack_int *);
  lapack_int (*dgetrs_work)(int, char, lapack_int, lapack_int, const double *, lapack_int,
                            const lapack_int *, double *, lapack_int);
  lapack_int (*dsyev)(int, char, char, lapack_int, double *, lapack_int, double *);
  lapack_int (*dgesvd)(int, char, char, lapack_int, lapack_int, double *, lapack_int, double *,
                       double *, lapack_int, double *, lapack_int, double *);
} api;

/* the pointers have the headers' types (a mismatch is a compile error with -Werror) */
static void check_types(void) {
  (void)sizeof(api.dgeev == &LAPACKE_dgeev);
  (void)sizeof(api.dgetrf_work == &LAPACKE_dgetrf_work);
  (void)sizeof(api.dgetrs_work == &LAPACKE_dgetrs_work);
  (void)sizeof(api.dsyev == &LAPACKE_dsyev);
  (void)sizeof(api.dgesvd == &LAPACKE_dgesvd);
}

static void load(void) {
  (void)check_types;
  lib.ok = gm_lazy_open(&lib) && gm_lazy_find(&lib, "LAPACKE_dgeev", &api.dgeev, sizeof api.dgeev) &&
           gm_lazy_find(&lib, "LAPACKE_dgetrf_work", &api.dgetrf_work, sizeof api.dgetrf_work) &&
           gm_lazy_find(&lib, "LAPACKE_dgetrs_work", &api.dgetrs_work, sizeof api.dgetrs_work) &&
           gm_lazy_find(&lib, "LAPACKE_dsyev", &api.dsyev, sizeof api.dsyev) &&
           gm_lazy_find(&lib, "LAPACKE_dgesvd", &api.dgesvd, sizeof api.dgesvd);
}

static int ready(void) {
  pthread_once(&lib.once, load);
  return lib.ok;
}

/* -1: LAPACKE's "argument 1 is illegal", a failure the callers report */
lapack_int LAPACKE_dgeev(int matrix_layout, char jobvl, char jobvr, lapack_int n, double *a,
                         lapack_int lda, double *wr, double *wi, double *vl, lapack_int ldvl,
                         double *vr, lapack_int ldvr) {
  return ready() ? api.dgeev(matrix_layout, jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr)
                 : -1;
}

lapack_int LAPACKE_dgetrf_work(int matrix_layout, lapack_int m, lapack_int n, double *a,
                               lapack_int lda, lapack_int *ipiv) {
  return ready() ? api.dgetrf_work(matrix_layout, m, n, a, lda, ipiv) : -1;
}

lapack_int LAPACKE_dgetrs_work(int matrix_layout, char trans, lapack_int n, lapack_int nrhs,
                               const double *a, lapack_int lda, const lapack_int *ipiv, double *b,
                               lapack_int ldb) {
  return ready() ? api.dgetrs_work(matrix_layout, trans, n, nrhs, a, lda, ipiv, b, ldb) : -1;
}

lapack_int LAPACKE_dsyev(int matrix_layout, char jobz, char uplo, lapack_int n, double *a,
                         lapack_int lda, double *w) {
  return ready() ? api.dsyev(matrix_layout, jobz, uplo, n, a, lda, w) : -1;
}

lapack_int LAPACKE_dgesvd(int matrix_layout, char jobu, char jobvt, lapack_int m, lapack_int n,
                          double *a, lapack_int lda, double *s, double *u, lapack_int ldu,
                          double *vt, lapack_int ldvt, double *superb) {
  return ready() ? api.dgesvd(matrix_layout, jobu, jobvt, m, n, a, lda, s, u, ldu, vt, ldvt, superb)
                 : -1;
}
