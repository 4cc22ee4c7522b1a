/* harminv, opened on first use (lazy.h): the resonance extraction of the Maxwell cavity
 * commands and experiment tables. */
#include <complex.h>
#include <harminv.h>

#include "lazy/lazy.h"

static gm_lazy_lib lib = GM_LAZY_LIB(GM_HARMINV_SONAME);
static struct {
  harminv_data (*data_create)(int, const harminv_complex *, double, double, int);
  void (*data_destroy)(harminv_data);
  void (*get_amplitude)(harminv_complex *, harminv_data, int);
  double (*get_decay)(harminv_data, int);
  double (*get_freq)(harminv_data, int);
  double (*get_freq_error)(harminv_data, int);
  double (*get_q)(harminv_data, int);
  int (*get_num_freqs)(harminv_data);
  void (*solve)(harminv_data);
} api;

/* the pointers have the headers' types (a mismatch is a compile error with -Werror) */
static void check_types(void) {
  (void)sizeof(api.data_create == &harminv_data_create);
  (void)sizeof(api.data_destroy == &harminv_data_destroy);
  (void)sizeof(api.get_amplitude == &harminv_get_amplitude);
  (void)sizeof(api.get_decay == &harminv_get_decay);
  (void)sizeof(api.get_freq == &harminv_get_freq);
  (void)sizeof(api.get_freq_error == &harminv_get_freq_error);
  (void)sizeof(api.get_q == &harminv_get_Q);
  (void)sizeof(api.get_num_freqs == &harminv_get_num_freqs);
  (void)sizeof(api.solve == &harminv_solve);
}

#define FIND(field, name) gm_lazy_find(&lib, name, &api.field, sizeof api.field)

static void load(void) {
  (void)check_types;
  lib.ok = gm_lazy_open(&lib) && FIND(data_create, "harminv_data_create") &&
           FIND(data_destroy, "harminv_data_destroy") &&
           FIND(get_amplitude, "harminv_get_amplitude") && FIND(get_decay, "harminv_get_decay") &&
           FIND(get_freq, "harminv_get_freq") && FIND(get_freq_error, "harminv_get_freq_error") && FIND(get_q, "harminv_get_Q") &&
           FIND(get_num_freqs, "harminv_get_num_freqs") && FIND(solve, "harminv_solve");
}

static int ready(void) {
  pthread_once(&lib.once, load);
  return lib.ok;
}

/* Without the library: no data and no frequencies. */
harminv_data harminv_data_create(int n, const harminv_complex *signal, double fmin, double fmax,
                                 int nf) {
  return ready() ? api.data_create(n, signal, fmin, fmax, nf) : NULL;
}

void harminv_data_destroy(harminv_data d) {
  if (ready()) api.data_destroy(d);
}

void harminv_solve(harminv_data d) {
  if (ready() && d != NULL) api.solve(d);
}

int harminv_get_num_freqs(harminv_data d) {
  return ready() && d != NULL ? api.get_num_freqs(d) : 0;
}

double harminv_get_freq(harminv_data d, int k) { return ready() ? api.get_freq(d, k) : 0.0; }
double harminv_get_decay(harminv_data d, int k) { return ready() ? api.get_decay(d, k) : 0.0; }

double harminv_get_Q(harminv_data d, int k) { return ready() ? api.get_q(d, k) : 0.0; }

double harminv_get_freq_error(harminv_data d, int k) {
  return ready() ? api.get_freq_error(d, k) : 0.0;
}

void harminv_get_amplitude(harminv_complex *amplitude, harminv_data d, int k) {
  if (ready()) api.get_amplitude(amplitude, d, k);
}
