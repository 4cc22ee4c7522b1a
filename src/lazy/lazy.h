/* Heavy shared libraries opened on first use instead of at process start (issue 25, "process
 * start"): the geomint program links these stubs, which define the few functions geomint calls
 * from LAPACKE, SuiteSparse (CHOLMOD, UMFPACK), FFTW and harminv with their own prototypes
 * (checked against the libraries' headers), and links with --as-needed, so the libraries (and
 * OpenBLAS, METIS, ... behind them) are not loaded by a command that does not use them. The
 * library libgeomint itself links them as before; only the program uses the stubs.
 * A library that cannot be loaded is reported once on stderr, naming it and why, and its
 * functions then return their failure value (the callers report the failure as usual). */
#ifndef GM_LAZY_H
#define GM_LAZY_H

#include <pthread.h>
#include <stddef.h>

typedef struct gm_lazy_lib {
  const char *soname;
  pthread_once_t once;
  int ok;        /* 1: every function found */
  void *handle;
} gm_lazy_lib;

#define GM_LAZY_LIB(soname) {soname, PTHREAD_ONCE_INIT, 0, NULL}

/* Open lib (once); 0 on failure (reported on stderr). */
int gm_lazy_open(gm_lazy_lib *lib);
/* Find name in lib into the function pointer at fn (size bytes); 0 on failure (reported). */
int gm_lazy_find(gm_lazy_lib *lib, const char *name, void *fn, size_t size);

#endif
