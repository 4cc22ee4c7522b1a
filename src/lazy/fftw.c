/* FFTW, opened on first use (lazy.h): the spectral PDE solvers of src/pde/. */
#include <fftw3.h>

#include "lazy/lazy.h"

static gm_lazy_lib lib = GM_LAZY_LIB(GM_FFTW3_SONAME);
static struct {
  fftw_complex *(*alloc_complex)(size_t);
  double *(*alloc_real)(size_t);
  void (*destroy_plan)(fftw_plan);
  void (*execute)(const fftw_plan);
  void (*free_)(void *);
  fftw_plan (*plan_dft_1d)(int, fftw_complex *, fftw_complex *, int, unsigned);
  fftw_plan (*plan_dft_c2r_1d)(int, fftw_complex *, double *, unsigned);
  fftw_plan (*plan_dft_r2c_1d)(int, double *, fftw_complex *, unsigned);
} api;

/* the pointers have the headers' types (a mismatch is a compile error with -Werror) */
static void check_types(void) {
  (void)sizeof(api.alloc_complex == &fftw_alloc_complex);
  (void)sizeof(api.alloc_real == &fftw_alloc_real);
  (void)sizeof(api.destroy_plan == &fftw_destroy_plan);
  (void)sizeof(api.execute == &fftw_execute);
  (void)sizeof(api.free_ == &fftw_free);
  (void)sizeof(api.plan_dft_1d == &fftw_plan_dft_1d);
  (void)sizeof(api.plan_dft_c2r_1d == &fftw_plan_dft_c2r_1d);
  (void)sizeof(api.plan_dft_r2c_1d == &fftw_plan_dft_r2c_1d);
}

#define FIND(field, name) gm_lazy_find(&lib, name, &api.field, sizeof api.field)

static void load(void) {
  (void)check_types;
  lib.ok = gm_lazy_open(&lib) && FIND(alloc_complex, "fftw_alloc_complex") &&
           FIND(alloc_real, "fftw_alloc_real") && FIND(destroy_plan, "fftw_destroy_plan") &&
           FIND(execute, "fftw_execute") && FIND(free_, "fftw_free") &&
           FIND(plan_dft_1d, "fftw_plan_dft_1d") &&
           FIND(plan_dft_c2r_1d, "fftw_plan_dft_c2r_1d") &&
           FIND(plan_dft_r2c_1d, "fftw_plan_dft_r2c_1d");
}

static int ready(void) {
  pthread_once(&lib.once, load);
  return lib.ok;
}

/* Without the library: NULL buffers and plans (the callers' out-of-memory and plan failures). */
fftw_complex *fftw_alloc_complex(size_t n) { return ready() ? api.alloc_complex(n) : NULL; }
double *fftw_alloc_real(size_t n) { return ready() ? api.alloc_real(n) : NULL; }

void fftw_destroy_plan(fftw_plan p) {
  if (ready()) api.destroy_plan(p);
}

void fftw_execute(const fftw_plan p) {
  if (ready()) api.execute(p);
}

void fftw_free(void *p) {
  if (ready()) api.free_(p);
}

fftw_plan fftw_plan_dft_1d(int n, fftw_complex *in, fftw_complex *out, int sign, unsigned flags) {
  return ready() ? api.plan_dft_1d(n, in, out, sign, flags) : NULL;
}

fftw_plan fftw_plan_dft_c2r_1d(int n, fftw_complex *in, double *out, unsigned flags) {
  return ready() ? api.plan_dft_c2r_1d(n, in, out, flags) : NULL;
}

fftw_plan fftw_plan_dft_r2c_1d(int n, double *in, fftw_complex *out, unsigned flags) {
  return ready() ? api.plan_dft_r2c_1d(n, in, out, flags) : NULL;
}
