/* hypre, opened on first use (lazy.h): BoomerAMG- and AMS-preconditioned CG of the DEC
 * Laplacians (src/dec/hypre.c, `geomint mesh poisson --solver hypre`). The stubs were generated
 * from the prototypes in Debian's hypre headers, which are included here, so a stub that does
 * not match its prototype is a compile error. Without the library every call returns
 * HYPRE_ERROR_GENERIC (1); src/dec/hypre.c reports that at HYPRE_Init. */
#include <HYPRE.h>
#include <HYPRE_IJ_mv.h>
#include <HYPRE_krylov.h>
#include <HYPRE_parcsr_ls.h>

#include "lazy/lazy.h"

static gm_lazy_lib lib = GM_LAZY_LIB(GM_HYPRE_SONAME);
static struct {
  __typeof__(&HYPRE_AMSCreate) AMSCreate;
  __typeof__(&HYPRE_AMSDestroy) AMSDestroy;
  __typeof__(&HYPRE_AMSSetCoordinateVectors) AMSSetCoordinateVectors;
  __typeof__(&HYPRE_AMSSetCycleType) AMSSetCycleType;
  __typeof__(&HYPRE_AMSSetDimension) AMSSetDimension;
  __typeof__(&HYPRE_AMSSetDiscreteGradient) AMSSetDiscreteGradient;
  __typeof__(&HYPRE_AMSSetMaxIter) AMSSetMaxIter;
  __typeof__(&HYPRE_AMSSetPrintLevel) AMSSetPrintLevel;
  __typeof__(&HYPRE_AMSSetTol) AMSSetTol;
  __typeof__(&HYPRE_AMSSetup) AMSSetup;
  __typeof__(&HYPRE_AMSSolve) AMSSolve;
  __typeof__(&HYPRE_BoomerAMGCreate) BoomerAMGCreate;
  __typeof__(&HYPRE_BoomerAMGDestroy) BoomerAMGDestroy;
  __typeof__(&HYPRE_BoomerAMGSetCoarsenType) BoomerAMGSetCoarsenType;
  __typeof__(&HYPRE_BoomerAMGSetInterpType) BoomerAMGSetInterpType;
  __typeof__(&HYPRE_BoomerAMGSetMaxIter) BoomerAMGSetMaxIter;
  __typeof__(&HYPRE_BoomerAMGSetNumSweeps) BoomerAMGSetNumSweeps;
  __typeof__(&HYPRE_BoomerAMGSetPMaxElmts) BoomerAMGSetPMaxElmts;
  __typeof__(&HYPRE_BoomerAMGSetPrintLevel) BoomerAMGSetPrintLevel;
  __typeof__(&HYPRE_BoomerAMGSetRelaxType) BoomerAMGSetRelaxType;
  __typeof__(&HYPRE_BoomerAMGSetStrongThreshold) BoomerAMGSetStrongThreshold;
  __typeof__(&HYPRE_BoomerAMGSetTol) BoomerAMGSetTol;
  __typeof__(&HYPRE_BoomerAMGSetup) BoomerAMGSetup;
  __typeof__(&HYPRE_BoomerAMGSolve) BoomerAMGSolve;
  __typeof__(&HYPRE_ClearAllErrors) ClearAllErrors;
  __typeof__(&HYPRE_IJMatrixAssemble) IJMatrixAssemble;
  __typeof__(&HYPRE_IJMatrixCreate) IJMatrixCreate;
  __typeof__(&HYPRE_IJMatrixDestroy) IJMatrixDestroy;
  __typeof__(&HYPRE_IJMatrixGetObject) IJMatrixGetObject;
  __typeof__(&HYPRE_IJMatrixInitialize) IJMatrixInitialize;
  __typeof__(&HYPRE_IJMatrixSetObjectType) IJMatrixSetObjectType;
  __typeof__(&HYPRE_IJMatrixSetRowSizes) IJMatrixSetRowSizes;
  __typeof__(&HYPRE_IJMatrixSetValues) IJMatrixSetValues;
  __typeof__(&HYPRE_IJVectorAssemble) IJVectorAssemble;
  __typeof__(&HYPRE_IJVectorCreate) IJVectorCreate;
  __typeof__(&HYPRE_IJVectorDestroy) IJVectorDestroy;
  __typeof__(&HYPRE_IJVectorGetObject) IJVectorGetObject;
  __typeof__(&HYPRE_IJVectorGetValues) IJVectorGetValues;
  __typeof__(&HYPRE_IJVectorInitialize) IJVectorInitialize;
  __typeof__(&HYPRE_IJVectorSetObjectType) IJVectorSetObjectType;
  __typeof__(&HYPRE_IJVectorSetValues) IJVectorSetValues;
  __typeof__(&HYPRE_Init) Init;
  __typeof__(&HYPRE_PCGGetNumIterations) PCGGetNumIterations;
  __typeof__(&HYPRE_PCGSetMaxIter) PCGSetMaxIter;
  __typeof__(&HYPRE_PCGSetPrecond) PCGSetPrecond;
  __typeof__(&HYPRE_PCGSetTol) PCGSetTol;
  __typeof__(&HYPRE_PCGSetTwoNorm) PCGSetTwoNorm;
  __typeof__(&HYPRE_ParCSRPCGCreate) ParCSRPCGCreate;
  __typeof__(&HYPRE_ParCSRPCGDestroy) ParCSRPCGDestroy;
  __typeof__(&HYPRE_ParCSRPCGSetup) ParCSRPCGSetup;
  __typeof__(&HYPRE_ParCSRPCGSolve) ParCSRPCGSolve;
} api;

#define FIND(name) gm_lazy_find(&lib, "HYPRE_" #name, &api.name, sizeof api.name)

static void load(void) {
  lib.ok = gm_lazy_open(&lib) &&
           FIND(AMSCreate) &&
           FIND(AMSDestroy) &&
           FIND(AMSSetCoordinateVectors) &&
           FIND(AMSSetCycleType) &&
           FIND(AMSSetDimension) &&
           FIND(AMSSetDiscreteGradient) &&
           FIND(AMSSetMaxIter) &&
           FIND(AMSSetPrintLevel) &&
           FIND(AMSSetTol) &&
           FIND(AMSSetup) &&
           FIND(AMSSolve) &&
           FIND(BoomerAMGCreate) &&
           FIND(BoomerAMGDestroy) &&
           FIND(BoomerAMGSetCoarsenType) &&
           FIND(BoomerAMGSetInterpType) &&
           FIND(BoomerAMGSetMaxIter) &&
           FIND(BoomerAMGSetNumSweeps) &&
           FIND(BoomerAMGSetPMaxElmts) &&
           FIND(BoomerAMGSetPrintLevel) &&
           FIND(BoomerAMGSetRelaxType) &&
           FIND(BoomerAMGSetStrongThreshold) &&
           FIND(BoomerAMGSetTol) &&
           FIND(BoomerAMGSetup) &&
           FIND(BoomerAMGSolve) &&
           FIND(ClearAllErrors) &&
           FIND(IJMatrixAssemble) &&
           FIND(IJMatrixCreate) &&
           FIND(IJMatrixDestroy) &&
           FIND(IJMatrixGetObject) &&
           FIND(IJMatrixInitialize) &&
           FIND(IJMatrixSetObjectType) &&
           FIND(IJMatrixSetRowSizes) &&
           FIND(IJMatrixSetValues) &&
           FIND(IJVectorAssemble) &&
           FIND(IJVectorCreate) &&
           FIND(IJVectorDestroy) &&
           FIND(IJVectorGetObject) &&
           FIND(IJVectorGetValues) &&
           FIND(IJVectorInitialize) &&
           FIND(IJVectorSetObjectType) &&
           FIND(IJVectorSetValues) &&
           FIND(Init) &&
           FIND(PCGGetNumIterations) &&
           FIND(PCGSetMaxIter) &&
           FIND(PCGSetPrecond) &&
           FIND(PCGSetTol) &&
           FIND(PCGSetTwoNorm) &&
           FIND(ParCSRPCGCreate) &&
           FIND(ParCSRPCGDestroy) &&
           FIND(ParCSRPCGSetup) &&
           FIND(ParCSRPCGSolve);
}

static int ready(void) {
  pthread_once(&lib.once, load);
  return lib.ok;
}

HYPRE_Int HYPRE_AMSCreate(HYPRE_Solver *solver) {
  return ready() ? api.AMSCreate(solver) : 1;
}
HYPRE_Int HYPRE_AMSDestroy(HYPRE_Solver solver) {
  return ready() ? api.AMSDestroy(solver) : 1;
}
HYPRE_Int HYPRE_AMSSetCoordinateVectors(HYPRE_Solver solver, HYPRE_ParVector x, HYPRE_ParVector y, HYPRE_ParVector z) {
  return ready() ? api.AMSSetCoordinateVectors(solver, x, y, z) : 1;
}
HYPRE_Int HYPRE_AMSSetCycleType(HYPRE_Solver solver, HYPRE_Int cycle_type) {
  return ready() ? api.AMSSetCycleType(solver, cycle_type) : 1;
}
HYPRE_Int HYPRE_AMSSetDimension(HYPRE_Solver solver, HYPRE_Int dim) {
  return ready() ? api.AMSSetDimension(solver, dim) : 1;
}
HYPRE_Int HYPRE_AMSSetDiscreteGradient(HYPRE_Solver solver, HYPRE_ParCSRMatrix G) {
  return ready() ? api.AMSSetDiscreteGradient(solver, G) : 1;
}
HYPRE_Int HYPRE_AMSSetMaxIter(HYPRE_Solver solver, HYPRE_Int maxit) {
  return ready() ? api.AMSSetMaxIter(solver, maxit) : 1;
}
HYPRE_Int HYPRE_AMSSetPrintLevel(HYPRE_Solver solver, HYPRE_Int print_level) {
  return ready() ? api.AMSSetPrintLevel(solver, print_level) : 1;
}
HYPRE_Int HYPRE_AMSSetTol(HYPRE_Solver solver, HYPRE_Real tol) {
  return ready() ? api.AMSSetTol(solver, tol) : 1;
}
HYPRE_Int HYPRE_AMSSetup(HYPRE_Solver solver, HYPRE_ParCSRMatrix A, HYPRE_ParVector b, HYPRE_ParVector x) {
  return ready() ? api.AMSSetup(solver, A, b, x) : 1;
}
HYPRE_Int HYPRE_AMSSolve(HYPRE_Solver solver, HYPRE_ParCSRMatrix A, HYPRE_ParVector b, HYPRE_ParVector x) {
  return ready() ? api.AMSSolve(solver, A, b, x) : 1;
}
HYPRE_Int HYPRE_BoomerAMGCreate(HYPRE_Solver *solver) {
  return ready() ? api.BoomerAMGCreate(solver) : 1;
}
HYPRE_Int HYPRE_BoomerAMGDestroy(HYPRE_Solver solver) {
  return ready() ? api.BoomerAMGDestroy(solver) : 1;
}
HYPRE_Int HYPRE_BoomerAMGSetCoarsenType(HYPRE_Solver solver, HYPRE_Int coarsen_type) {
  return ready() ? api.BoomerAMGSetCoarsenType(solver, coarsen_type) : 1;
}
HYPRE_Int HYPRE_BoomerAMGSetInterpType(HYPRE_Solver solver, HYPRE_Int interp_type) {
  return ready() ? api.BoomerAMGSetInterpType(solver, interp_type) : 1;
}
HYPRE_Int HYPRE_BoomerAMGSetMaxIter(HYPRE_Solver solver, HYPRE_Int max_iter) {
  return ready() ? api.BoomerAMGSetMaxIter(solver, max_iter) : 1;
}
HYPRE_Int HYPRE_BoomerAMGSetNumSweeps(HYPRE_Solver solver, HYPRE_Int num_sweeps) {
  return ready() ? api.BoomerAMGSetNumSweeps(solver, num_sweeps) : 1;
}
HYPRE_Int HYPRE_BoomerAMGSetPMaxElmts(HYPRE_Solver solver, HYPRE_Int P_max_elmts) {
  return ready() ? api.BoomerAMGSetPMaxElmts(solver, P_max_elmts) : 1;
}
HYPRE_Int HYPRE_BoomerAMGSetPrintLevel(HYPRE_Solver solver, HYPRE_Int print_level) {
  return ready() ? api.BoomerAMGSetPrintLevel(solver, print_level) : 1;
}
HYPRE_Int HYPRE_BoomerAMGSetRelaxType(HYPRE_Solver solver, HYPRE_Int relax_type) {
  return ready() ? api.BoomerAMGSetRelaxType(solver, relax_type) : 1;
}
HYPRE_Int HYPRE_BoomerAMGSetStrongThreshold(HYPRE_Solver solver, HYPRE_Real strong_threshold) {
  return ready() ? api.BoomerAMGSetStrongThreshold(solver, strong_threshold) : 1;
}
HYPRE_Int HYPRE_BoomerAMGSetTol(HYPRE_Solver solver, HYPRE_Real tol) {
  return ready() ? api.BoomerAMGSetTol(solver, tol) : 1;
}
HYPRE_Int HYPRE_BoomerAMGSetup(HYPRE_Solver solver, HYPRE_ParCSRMatrix A, HYPRE_ParVector b, HYPRE_ParVector x) {
  return ready() ? api.BoomerAMGSetup(solver, A, b, x) : 1;
}
HYPRE_Int HYPRE_BoomerAMGSolve(HYPRE_Solver solver, HYPRE_ParCSRMatrix A, HYPRE_ParVector b, HYPRE_ParVector x) {
  return ready() ? api.BoomerAMGSolve(solver, A, b, x) : 1;
}
HYPRE_Int HYPRE_ClearAllErrors() {
  return ready() ? api.ClearAllErrors() : 1;
}
HYPRE_Int HYPRE_IJMatrixAssemble(HYPRE_IJMatrix matrix) {
  return ready() ? api.IJMatrixAssemble(matrix) : 1;
}
HYPRE_Int HYPRE_IJMatrixCreate(MPI_Comm comm, HYPRE_BigInt ilower, HYPRE_BigInt iupper, HYPRE_BigInt jlower, HYPRE_BigInt jupper, HYPRE_IJMatrix *matrix) {
  return ready() ? api.IJMatrixCreate(comm, ilower, iupper, jlower, jupper, matrix) : 1;
}
HYPRE_Int HYPRE_IJMatrixDestroy(HYPRE_IJMatrix matrix) {
  return ready() ? api.IJMatrixDestroy(matrix) : 1;
}
HYPRE_Int HYPRE_IJMatrixGetObject(HYPRE_IJMatrix matrix, void **object) {
  return ready() ? api.IJMatrixGetObject(matrix, object) : 1;
}
HYPRE_Int HYPRE_IJMatrixInitialize(HYPRE_IJMatrix matrix) {
  return ready() ? api.IJMatrixInitialize(matrix) : 1;
}
HYPRE_Int HYPRE_IJMatrixSetObjectType(HYPRE_IJMatrix matrix, HYPRE_Int type) {
  return ready() ? api.IJMatrixSetObjectType(matrix, type) : 1;
}
HYPRE_Int HYPRE_IJMatrixSetRowSizes(HYPRE_IJMatrix matrix, const HYPRE_Int *sizes) {
  return ready() ? api.IJMatrixSetRowSizes(matrix, sizes) : 1;
}
HYPRE_Int HYPRE_IJMatrixSetValues(HYPRE_IJMatrix matrix, HYPRE_Int nrows, HYPRE_Int *ncols, const HYPRE_BigInt *rows, const HYPRE_BigInt *cols, const HYPRE_Complex *values) {
  return ready() ? api.IJMatrixSetValues(matrix, nrows, ncols, rows, cols, values) : 1;
}
HYPRE_Int HYPRE_IJVectorAssemble(HYPRE_IJVector vector) {
  return ready() ? api.IJVectorAssemble(vector) : 1;
}
HYPRE_Int HYPRE_IJVectorCreate(MPI_Comm comm, HYPRE_BigInt jlower, HYPRE_BigInt jupper, HYPRE_IJVector *vector) {
  return ready() ? api.IJVectorCreate(comm, jlower, jupper, vector) : 1;
}
HYPRE_Int HYPRE_IJVectorDestroy(HYPRE_IJVector vector) {
  return ready() ? api.IJVectorDestroy(vector) : 1;
}
HYPRE_Int HYPRE_IJVectorGetObject(HYPRE_IJVector vector, void **object) {
  return ready() ? api.IJVectorGetObject(vector, object) : 1;
}
HYPRE_Int HYPRE_IJVectorGetValues(HYPRE_IJVector vector, HYPRE_Int nvalues, const HYPRE_BigInt *indices, HYPRE_Complex *values) {
  return ready() ? api.IJVectorGetValues(vector, nvalues, indices, values) : 1;
}
HYPRE_Int HYPRE_IJVectorInitialize(HYPRE_IJVector vector) {
  return ready() ? api.IJVectorInitialize(vector) : 1;
}
HYPRE_Int HYPRE_IJVectorSetObjectType(HYPRE_IJVector vector, HYPRE_Int type) {
  return ready() ? api.IJVectorSetObjectType(vector, type) : 1;
}
HYPRE_Int HYPRE_IJVectorSetValues(HYPRE_IJVector vector, HYPRE_Int nvalues, const HYPRE_BigInt *indices, const HYPRE_Complex *values) {
  return ready() ? api.IJVectorSetValues(vector, nvalues, indices, values) : 1;
}
HYPRE_Int HYPRE_Init() {
  return ready() ? api.Init() : 1;
}
HYPRE_Int HYPRE_PCGGetNumIterations(HYPRE_Solver solver, HYPRE_Int *num_iterations) {
  return ready() ? api.PCGGetNumIterations(solver, num_iterations) : 1;
}
HYPRE_Int HYPRE_PCGSetMaxIter(HYPRE_Solver solver, HYPRE_Int max_iter) {
  return ready() ? api.PCGSetMaxIter(solver, max_iter) : 1;
}
HYPRE_Int HYPRE_PCGSetPrecond(HYPRE_Solver solver, HYPRE_PtrToSolverFcn precond, HYPRE_PtrToSolverFcn precond_setup, HYPRE_Solver precond_solver) {
  return ready() ? api.PCGSetPrecond(solver, precond, precond_setup, precond_solver) : 1;
}
HYPRE_Int HYPRE_PCGSetTol(HYPRE_Solver solver, HYPRE_Real tol) {
  return ready() ? api.PCGSetTol(solver, tol) : 1;
}
HYPRE_Int HYPRE_PCGSetTwoNorm(HYPRE_Solver solver, HYPRE_Int two_norm) {
  return ready() ? api.PCGSetTwoNorm(solver, two_norm) : 1;
}
HYPRE_Int HYPRE_ParCSRPCGCreate(MPI_Comm comm, HYPRE_Solver *solver) {
  return ready() ? api.ParCSRPCGCreate(comm, solver) : 1;
}
HYPRE_Int HYPRE_ParCSRPCGDestroy(HYPRE_Solver solver) {
  return ready() ? api.ParCSRPCGDestroy(solver) : 1;
}
HYPRE_Int HYPRE_ParCSRPCGSetup(HYPRE_Solver solver, HYPRE_ParCSRMatrix A, HYPRE_ParVector b, HYPRE_ParVector x) {
  return ready() ? api.ParCSRPCGSetup(solver, A, b, x) : 1;
}
HYPRE_Int HYPRE_ParCSRPCGSolve(HYPRE_Solver solver, HYPRE_ParCSRMatrix A, HYPRE_ParVector b, HYPRE_ParVector x) {
  return ready() ? api.ParCSRPCGSolve(solver, A, b, x) : 1;
}
