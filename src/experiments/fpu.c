/* Seed 000 experiments E2 and E3 (Stern 2009, §2.4, Figs 2.2–2.3; notes §2 E2–E3): the
 * Fermi–Pasta–Ulam problem with ℓ = 3 stiff springs, ω = 50 (HLW I.5.1 initial data), the
 * oscillatory energies I1, I2, I3 and I = I1 + I2 + I3 against a Verlet h = 0.001 reference.
 * E2: T = 200 sampled every 0.6; E3: T = 4000 sampled every 1.0 with the trigonometric rows and
 * vti beside IMEX. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/experiments.h"

typedef struct {
  const char *method;
  double h;
  const char *title;
} fpu_spec;

static const fpu_spec short_runs[] = {
    {"verlet", 0.001, "Verlet h = 0.001 (reference)"}, {"verlet", 0.03, "Verlet h = 0.03"},
    {"imex", 0.03, "IMEX h = 0.03"},                   {"imex", 0.1, "IMEX h = 0.1"},
    {"imex", 0.15, "IMEX h = 0.15"},                   {"imex", 0.2, "IMEX h = 0.2"}};
static const fpu_spec long_runs[] = {
    {"verlet", 0.001, "Verlet h = 0.001 (reference)"},
    {"imex", 0.1, "IMEX h = 0.1"},
    {"trig-gautschi", 0.1, "trig-gautschi h = 0.1"},
    {"trig-deuflhard", 0.1, "trig-deuflhard h = 0.1"},
    {"trig-garcia-archilla", 0.1, "trig-garcia-archilla h = 0.1"},
    {"trig-hochbruck-lubich", 0.1, "trig-hochbruck-lubich h = 0.1"},
    {"trig-hairer-lubich", 0.1, "trig-hairer-lubich h = 0.1"},
    {"vti", 0.05, "vti h = 0.05"}};

typedef struct {
  const gm_problem *pb;
  FILE *csv;
  double h0, i0;
  double *samples;         /* I1, I2, I3, I per sample (reference run: stored) */
  size_t n_samples, cap;
  const double *reference; /* NULL for the reference run */
  gm_fpu_run_result *out;
} fpu_trace;

static int fpu_observe(void *ctx, size_t step, double t, const double *y) {
  (void)step;
  fpu_trace *tr = ctx;
  const gm_problem *pb = tr->pb;
  gm_fpu_run_result *o = tr->out;
  double v[4];
  for (size_t j = 0; j < 4; ++j) v[j] = pb->invariants[j].value(pb->ctx, y);
  const double dh = fabs(gm_problem_energy(pb, y) - tr->h0);
  o->max_abs_dh = fmax(o->max_abs_dh, dh);
  o->max_abs_di = fmax(o->max_abs_di, fabs(v[3] - tr->i0));
  if (fabs(t - 150.0) < 1e-6) memcpy(o->at150, v, 3 * sizeof *v);
  if (v[2] > 0.5 && !(o->t_exchange >= 0.0)) o->t_exchange = t;
  if (tr->n_samples < tr->cap) {
    double *s = tr->samples + 4 * tr->n_samples;
    if (tr->reference != NULL) {
      for (size_t j = 0; j < 4; ++j)
        o->max_abs_dev = fmax(o->max_abs_dev, fabs(v[j] - tr->reference[4 * tr->n_samples + j]));
    } else {
      memcpy(s, v, sizeof v);
    }
    tr->n_samples++;
  }
  if (tr->csv != NULL)
    fprintf(tr->csv, "%.10g,%.10g,%.10g,%.10g,%.10g,%.6e\n", t, v[0], v[1], v[2], v[3], dh);
  return 0;
}

/* One run sampled every `sample` time units (a multiple of h), into tr->out. */
static gm_status fpu_simulate(const gm_model *model, const fpu_spec *spec, double t_end,
                              double sample, fpu_trace *tr, gm_error *err) {
  gm_fpu_run_result *o = tr->out;
  gm_integrator *it = NULL;
  gm_status st = gm_experiment_start(model, spec->method, 0, &it, err);
  if (st != GM_OK) return st;
  const gm_problem *pb = gm_model_problem(model);
  double t0, y0[64];
  gm_model_initial_state(model, &t0, y0);
  tr->pb = pb;
  tr->h0 = gm_problem_energy(pb, y0);
  tr->i0 = pb->invariants[3].value(pb->ctx, y0);
  const size_t every = (size_t)llround(sample / spec->h), n = (size_t)llround(t_end / spec->h);
  if (fabs((double)every * spec->h - sample) > 1e-9 * sample) {
    gm_integrator_free(it);
    return gm_error_set(err, GM_EINVAL, "fpu: %s: h = %g does not divide the sampling interval %g",
                        spec->method, spec->h, sample);
  }
  if (o->csv[0] != '\0' && (tr->csv = fopen(o->csv, "w")) == NULL) {
    gm_integrator_free(it);
    return gm_error_set(err, GM_EIO, "fpu: cannot write %s", o->csv);
  }
  if (tr->csv) fprintf(tr->csv, "t,I1,I2,I3,I,abs_energy_error\n");
  st = gm_integrator_add_observer(it, fpu_observe, tr, every);
  if (st == GM_OK) st = gm_integrator_run(it, n, spec->h);
  if (st != GM_OK)
    gm_error_set(err, st, "fpu: %s h = %g: %s", spec->method, spec->h, gm_integrator_errmsg(it));
  o->steps = n;
  if (tr->csv != NULL && (ferror(tr->csv) | fclose(tr->csv)) != 0 && st == GM_OK)
    st = gm_error_set(err, GM_EIO, "fpu: writing %s failed", o->csv);
  gm_integrator_free(it);
  return st;
}

gm_status gm_experiment_fpu(int long_run, const char *dir, gm_fpu_result *r, gm_error *err) {
  memset(r, 0, sizeof *r);
  const fpu_spec *specs = long_run ? long_runs : short_runs;
  const size_t n_runs = long_run ? sizeof long_runs / sizeof long_runs[0]
                                 : sizeof short_runs / sizeof short_runs[0];
  r->long_run = long_run != 0;
  r->t_end = long_run ? 4000.0 : 200.0;
  r->sample = long_run ? 1.0 : 0.6;
  const char *name = long_run ? "fpu-long" : "fpu";
  gm_model *model = NULL;
  gm_status st = gm_experiment_model("fpu", &model, err);
  if (st != GM_OK) return st;
  const size_t cap = (size_t)(r->t_end / r->sample) + 2;
  double *ref = calloc(4 * cap, sizeof *ref), *scratch = calloc(4 * cap, sizeof *scratch);
  if (ref == NULL || scratch == NULL)
    st = gm_error_set(err, GM_ENOMEM, "fpu: cannot allocate 2 x %zu samples", cap);
  const double t0 = gm_experiment_clock();
  for (size_t k = 0; k < n_runs && st == GM_OK; ++k) {
    gm_fpu_run_result *o = &r->runs[k];
    o->method = specs[k].method;
    o->h = specs[k].h;
    o->title = specs[k].title;
    o->t_exchange = NAN;
    if (dir != NULL) {
      char file[128];
      snprintf(file, sizeof file, "%s-%s-%g.csv", name, o->method, o->h);
      if (gm_experiment_path(o->csv, sizeof o->csv, dir, file) != GM_OK) {
        st = gm_error_set(err, GM_EINVAL, "fpu: the directory name is too long");
        break;
      }
    }
    fpu_trace tr = {0};
    tr.samples = k == 0 ? ref : scratch;
    tr.cap = cap;
    tr.reference = k == 0 ? NULL : ref;
    tr.out = o;
    st = fpu_simulate(model, &specs[k], r->t_end, r->sample, &tr, err);
    if (k == 0) o->max_abs_dev = NAN; /* the reference itself */
    if (st == GM_OK) r->n_runs = k + 1;
  }
  r->wall_s = gm_experiment_clock() - t0;
  free(ref);
  free(scratch);
  gm_model_free(model);
  return st;
}

/* The runs of the table's rows: the notes' numbers (seed000 notes E2/E3) are those of
 * IMEX h = 0.1 and of Verlet h = 0.03 / the reference. */
static gm_status run_fpu_row(int long_run, const char *dir, gm_experiment_result *out,
                             gm_error *err) {
  gm_fpu_result *r = malloc(sizeof *r);
  if (r == NULL) return gm_error_set(err, GM_ENOMEM, "fpu: cannot allocate the result");
  gm_status st = gm_experiment_fpu(long_run, dir, r, err);
  if (st == GM_OK) {
    const gm_fpu_run_result *ref = &r->runs[0], *imex = &r->runs[long_run ? 1 : 3];
    gm_experiment_add(out, "t_end", r->t_end);
    gm_experiment_add(out, "reference_t_exchange", ref->t_exchange);
    gm_experiment_add(out, "imex_0.1_max_abs_dH", imex->max_abs_dh);
    gm_experiment_add(out, "imex_0.1_max_abs_dI", imex->max_abs_di);
    gm_experiment_add(out, "imex_0.1_t_exchange", imex->t_exchange);
    if (!long_run) {
      gm_experiment_add(out, "reference_I3_at_150", ref->at150[2]);
      gm_experiment_add(out, "imex_0.1_I1_at_150", imex->at150[0]);
      gm_experiment_add(out, "imex_0.1_I3_at_150", imex->at150[2]);
      gm_experiment_add(out, "verlet_0.03_max_abs_dH", r->runs[1].max_abs_dh);
    }
    gm_experiment_add(out, "wall_s", r->wall_s);
    for (size_t k = 0; k < r->n_runs && k < GM_EXPERIMENT_MAX_FILES; ++k)
      if (r->runs[k].csv[0] != '\0')
        snprintf(out->files[out->n_files++], GM_EXPERIMENT_PATH_SIZE, "%s", r->runs[k].csv);
  }
  free(r);
  return st;
}

gm_status gm_experiment_run_fpu(const char *dir, gm_experiment_result *out, gm_error *err) {
  return run_fpu_row(0, dir, out, err);
}

gm_status gm_experiment_run_fpu_long(const char *dir, gm_experiment_result *out, gm_error *err) {
  return run_fpu_row(1, dir, out, err);
}
