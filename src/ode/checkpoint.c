/* Checkpoints of an integrator: everything the next step depends on, so that a run restarted
 * from one continues bitwise identically to an uninterrupted run.
 *
 * Layout (this machine's byte order; version 1):
 *   "GMCHKPT\0", u32 version, u32 byte-order mark 0x01020304,
 *   char method[64], char basic[64] (NUL-padded; "" without a basic method),
 *   u32 solver, u32 compensated, u64 state size n, u64 dim,
 *   f64 t, u64 step index, u64 statistics[7],
 *   u32 run kind, u32 0, f64 run t0, f64 run h, f64 run t_last, u64 run steps, u64 run start,
 *   f64 y[n], f64 carry[n],
 *   u64 method-state size, bytes, u64 extra size, bytes,
 *   u64 FNV-1a checksum of everything before it. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ode/internal.h"

#define CHECKPOINT_VERSION 1u
#define BYTE_ORDER_MARK 0x01020304u
#define NAME_SIZE 64
static const char magic[8] = {'G', 'M', 'C', 'H', 'K', 'P', 'T', '\0'};

typedef struct stream {
  FILE *f;
  uint64_t hash;
  int short_io; /* a read or write came up short */
} stream;

static void hash_bytes(stream *s, const void *p, size_t n) {
  const unsigned char *b = p;
  for (size_t i = 0; i < n; ++i) {
    s->hash ^= b[i];
    s->hash *= 1099511628211ull;
  }
}

static void put(stream *s, const void *p, size_t n) {
  if (s->short_io || n == 0) return;
  if (fwrite(p, 1, n, s->f) != n) s->short_io = 1;
  hash_bytes(s, p, n);
}

static int get(stream *s, void *p, size_t n) {
  if (s->short_io) return -1;
  if (n > 0 && fread(p, 1, n, s->f) != n) {
    s->short_io = 1;
    return -1;
  }
  hash_bytes(s, p, n);
  return 0;
}

static void put_u32(stream *s, uint32_t x) { put(s, &x, sizeof x); }
static void put_u64(stream *s, uint64_t x) { put(s, &x, sizeof x); }
static void put_f64(stream *s, double x) { put(s, &x, sizeof x); }

static void stats_to(const gm_stats *st, uint64_t out[7]) {
  out[0] = st->steps;
  out[1] = st->force_evals;
  out[2] = st->jacobian_evals;
  out[3] = st->fd_jacobians;
  out[4] = st->newton_iterations;
  out[5] = st->fixed_point_iterations;
  out[6] = st->newton_failures;
}

static void stats_from(const uint64_t in[7], gm_stats *st) {
  st->steps = (size_t)in[0];
  st->force_evals = (size_t)in[1];
  st->jacobian_evals = (size_t)in[2];
  st->fd_jacobians = (size_t)in[3];
  st->newton_iterations = (size_t)in[4];
  st->fixed_point_iterations = (size_t)in[5];
  st->newton_failures = (size_t)in[6];
}

static void name_field(const char *name, char out[NAME_SIZE]) {
  memset(out, 0, NAME_SIZE);
  if (name != NULL) strncpy(out, name, NAME_SIZE - 1);
}

gm_status gm_integrator_save(gm_integrator *it, FILE *f, const void *extra, size_t extra_size) {
  if (it == NULL) return GM_EINVAL;
  if (f == NULL)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "checkpoint: no file");
  if (extra_size > GM_CHECKPOINT_MAX_EXTRA || (extra_size > 0 && extra == NULL))
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "checkpoint: %zu extra bytes (at most %d)", extra_size,
                   GM_CHECKPOINT_MAX_EXTRA);
  const gm_stepper_state *ms = gm_stepper_state_of(it->stepper);
  size_t ms_size = ms != NULL && ms->size != NULL ? ms->size(it) : 0;
  unsigned char *ms_bytes = malloc(ms_size ? ms_size : 1);
  if (ms_bytes == NULL) return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOMEM, "out of memory");
  if (ms_size > 0) ms->save(it, ms_bytes);
  stream s = {f, 1469598103934665603ull, 0};
  char name[NAME_SIZE];
  put(&s, magic, sizeof magic);
  put_u32(&s, CHECKPOINT_VERSION);
  put_u32(&s, BYTE_ORDER_MARK);
  name_field(it->method->name, name);
  put(&s, name, NAME_SIZE);
  name_field(it->basic != NULL ? it->basic->name : "", name);
  put(&s, name, NAME_SIZE);
  put_u32(&s, (uint32_t)it->solver);
  put_u32(&s, (uint32_t)it->compensated);
  put_u64(&s, it->n);
  put_u64(&s, it->dim);
  put_f64(&s, it->t);
  put_u64(&s, it->step_index);
  uint64_t st[7];
  stats_to(&it->stats, st);
  put(&s, st, sizeof st);
  put_u32(&s, (uint32_t)it->run_kind);
  put_u32(&s, 0);
  put_f64(&s, it->run.t0);
  put_f64(&s, it->run.h);
  put_f64(&s, it->run.t_last);
  put_u64(&s, it->run.n_steps);
  put_u64(&s, it->run_start);
  put(&s, it->y, it->n * sizeof *it->y);
  put(&s, it->carry, it->n * sizeof *it->carry);
  put_u64(&s, ms_size);
  put(&s, ms_bytes, ms_size);
  put_u64(&s, extra_size);
  put(&s, extra, extra_size);
  const uint64_t checksum = s.hash;
  put_u64(&s, checksum);
  free(ms_bytes);
  if (s.short_io || fflush(f) != 0 || ferror(f))
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EIO, "checkpoint: write failed: %s",
                   strerror(errno));
  return GM_OK;
}

gm_status gm_integrator_save_file(gm_integrator *it, const char *path, const void *extra,
                                  size_t extra_size) {
  if (it == NULL) return GM_EINVAL;
  if (path == NULL || path[0] == '\0')
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "checkpoint: no file name");
  size_t len = strlen(path);
  char *tmp = malloc(len + 5);
  if (tmp == NULL) return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOMEM, "out of memory");
  memcpy(tmp, path, len);
  memcpy(tmp + len, ".tmp", 5);
  FILE *f = fopen(tmp, "wb");
  if (f == NULL) {
    gm_status st = gm_fail(it->errmsg, sizeof it->errmsg, GM_EIO,
                           "checkpoint: cannot open '%s' for writing: %s", tmp, strerror(errno));
    free(tmp);
    return st;
  }
  gm_status st = gm_integrator_save(it, f, extra, extra_size);
  if (fclose(f) != 0 && st == GM_OK)
    st = gm_fail(it->errmsg, sizeof it->errmsg, GM_EIO, "checkpoint: cannot write '%s': %s",
                 tmp, strerror(errno));
  if (st == GM_OK && rename(tmp, path) != 0)
    st = gm_fail(it->errmsg, sizeof it->errmsg, GM_EIO, "checkpoint: cannot rename '%s' to "
                 "'%s': %s", tmp, path, strerror(errno));
  if (st != GM_OK) remove(tmp);
  free(tmp);
  return st;
}

/* What a checkpoint holds, read before anything is applied. */
typedef struct saved {
  uint32_t solver, compensated, run_kind;
  uint64_t n, dim, step_index, stats[7], run_steps, run_start, ms_size, extra_size;
  double t, run_t0, run_h, run_t_last;
  double *y, *carry;
  unsigned char *ms;
} saved;

static gm_status truncated(gm_integrator *it, const char *what) {
  return gm_fail(it->errmsg, sizeof it->errmsg, GM_EIO,
                 "checkpoint: the file ends early (in %s): truncated", what);
}

/* Every field of a checkpoint, checked as input before anything is applied. */
static gm_status check_saved(gm_integrator *it, const saved *v) {
  char *m = it->errmsg;
  const size_t cap = sizeof it->errmsg;
  if (!isfinite(v->t)) return gm_fail(m, cap, GM_EINVAL, "checkpoint: time t = %g", v->t);
  size_t bad = gm_first_nonfinite(it->n, v->y);
  if (bad < it->n)
    return gm_fail(m, cap, GM_EINVAL, "checkpoint: state component %zu is %g", bad + 1,
                   v->y[bad]);
  bad = gm_first_nonfinite(it->n, v->carry);
  if (bad < it->n)
    return gm_fail(m, cap, GM_EINVAL, "checkpoint: compensation carry %zu is %g", bad + 1,
                   v->carry[bad]);
  /* far off the state space (a run may drift past GM_STATE_DEFECT_TOLERANCE legitimately:
   * a method that does not keep the manifold; 1e-3 is no such drift) */
  const double defect = gm_problem_state_defect(it->problem, v->y);
  if (!(defect <= 1e-3))
    return gm_fail(m, cap, GM_EINVAL, "checkpoint: the state is off the state space: %s = %.3g",
                   gm_problem_state_defect_name(it->problem), defect);
  if (gm_problem_has_energy(it->problem)) { /* a singular state (two bodies at one point) */
    const double e = gm_problem_energy(it->problem, v->y);
    if (!isfinite(e))
      return gm_fail(m, cap, GM_EINVAL,
                     "checkpoint: the state is singular for this problem (energy %g)", e);
  }
  if (v->run_kind > 2)
    return gm_fail(m, cap, GM_EINVAL, "checkpoint: run kind %u (0, 1 or 2)", v->run_kind);
  if (v->run_kind == 0) return GM_OK;
  if (!isfinite(v->run_t0) || !isfinite(v->run_t_last) || !isfinite(v->run_h) ||
      v->run_h == 0.0 || (v->run_kind == 2 && !(v->run_h > 0.0)))
    return gm_fail(m, cap, GM_EINVAL,
                   "checkpoint: the run's step h = %g (must be finite and non-zero), start %g, "
                   "end %g (finite)", v->run_h, v->run_t0, v->run_t_last);
  /* a run goes from t0 towards t_last in the direction of h (gm_integrator_run takes h < 0) */
  const double lo = fmin(v->run_t0, v->run_t_last), hi = fmax(v->run_t0, v->run_t_last);
  if ((v->run_h > 0.0) != (v->run_t_last >= v->run_t0) ||
      (v->run_kind == 1 && !(v->t >= lo && v->t <= hi)))
    return gm_fail(m, cap, GM_EINVAL,
                   "checkpoint: a run from %g to %g with step h = %g at t = %g is inconsistent",
                   v->run_t0, v->run_t_last, v->run_h, v->t);
  if (v->run_kind == 1) {
    if ((double)v->run_steps > 1e15 || v->step_index < v->run_start ||
        v->step_index - v->run_start > v->run_steps)
      return gm_fail(m, cap, GM_EINVAL,
                     "checkpoint: step %llu is not in the run of %llu steps from step %llu",
                     (unsigned long long)v->step_index, (unsigned long long)v->run_steps,
                     (unsigned long long)v->run_start);
    /* the time on the run's grid (as the driver sets it: t0 + k h, the last t_last) */
    const gm_run run = {v->run_t0, v->run_h, v->run_t_last, (size_t)v->run_steps};
    const double expected = gm_run_time(&run, (size_t)(v->step_index - v->run_start));
    if (fabs(v->t - expected) > 1e-9 * fmax(1.0, fabs(expected)))
      return gm_fail(m, cap, GM_EINVAL,
                     "checkpoint: t = %.17g is not the time %.17g of step %llu of its run", v->t,
                     expected, (unsigned long long)(v->step_index - v->run_start));
  }
  return GM_OK;
}

gm_status gm_integrator_load(gm_integrator *it, FILE *f, void *extra, size_t extra_cap,
                             size_t *extra_size) {
  if (it == NULL) return GM_EINVAL;
  if (f == NULL)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "checkpoint: no file");
  stream s = {f, 1469598103934665603ull, 0};
  char head[sizeof magic], name[NAME_SIZE], basic[NAME_SIZE];
  uint32_t version = 0, bom = 0, pad = 0;
  saved v;
  memset(&v, 0, sizeof v);
  if (get(&s, head, sizeof head) != 0) return truncated(it, "the magic");
  if (memcmp(head, magic, sizeof magic) != 0)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "checkpoint: not a geomint checkpoint (wrong magic)");
  if (get(&s, &version, sizeof version) || get(&s, &bom, sizeof bom))
    return truncated(it, "the header");
  if (version != CHECKPOINT_VERSION)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "checkpoint: version %u, this geomint reads version %u", version,
                   CHECKPOINT_VERSION);
  if (bom != BYTE_ORDER_MARK)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "checkpoint: written on a machine of another byte order");
  if (get(&s, name, NAME_SIZE) || get(&s, basic, NAME_SIZE)) return truncated(it, "the header");
  name[NAME_SIZE - 1] = basic[NAME_SIZE - 1] = '\0';
  if (strcmp(name, it->method->name) != 0)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "checkpoint: written by method '%s', not '%s'", name, it->method->name);
  const char *my_basic = it->basic != NULL ? it->basic->name : "";
  if (strcmp(basic, my_basic) != 0)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "checkpoint: basic method '%s', not '%s'", basic, my_basic);
  if (get(&s, &v.solver, 4) || get(&s, &v.compensated, 4) || get(&s, &v.n, 8) ||
      get(&s, &v.dim, 8) || get(&s, &v.t, 8) || get(&s, &v.step_index, 8) ||
      get(&s, v.stats, sizeof v.stats) || get(&s, &v.run_kind, 4) || get(&s, &pad, 4) ||
      get(&s, &v.run_t0, 8) || get(&s, &v.run_h, 8) || get(&s, &v.run_t_last, 8) ||
      get(&s, &v.run_steps, 8) || get(&s, &v.run_start, 8))
    return truncated(it, "the header");
  if (v.solver != (uint32_t)it->solver)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "checkpoint: solver '%s', not '%s'", gm_solver_name((gm_solver)v.solver),
                   gm_solver_name(it->solver));
  if (v.compensated != (uint32_t)it->compensated)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "checkpoint: written %s compensated summation, the integrator is %s",
                   v.compensated ? "with" : "without", it->compensated ? "with it" : "without");
  if (v.n != it->n || v.dim != it->dim)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "checkpoint: a problem of dimension %llu with state size %llu, this one has "
                   "dimension %zu and state size %zu",
                   (unsigned long long)v.dim, (unsigned long long)v.n, it->dim, it->n);
  const gm_stepper_state *ms = gm_stepper_state_of(it->stepper);
  const size_t ms_size = ms != NULL && ms->size != NULL ? ms->size(it) : 0;
  v.y = malloc(it->n * sizeof(double) + 1);
  v.carry = malloc(it->n * sizeof(double) + 1);
  v.ms = malloc(ms_size + 1);
  gm_status st = GM_OK;
  unsigned char *extra_buf = NULL;
  if (v.y == NULL || v.carry == NULL || v.ms == NULL) {
    st = gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOMEM, "out of memory");
    goto done;
  }
  if (get(&s, v.y, it->n * sizeof(double)) || get(&s, v.carry, it->n * sizeof(double))) {
    st = truncated(it, "the state");
    goto done;
  }
  if (get(&s, &v.ms_size, 8)) {
    st = truncated(it, "the method's state");
    goto done;
  }
  if (v.ms_size != ms_size) {
    st = gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                 "checkpoint: %llu bytes of method state, '%s' here has %zu",
                 (unsigned long long)v.ms_size, it->method->name, ms_size);
    goto done;
  }
  if (get(&s, v.ms, ms_size) || get(&s, &v.extra_size, 8)) {
    st = truncated(it, "the method's state");
    goto done;
  }
  if (v.extra_size > GM_CHECKPOINT_MAX_EXTRA) {
    st = gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                 "checkpoint: %llu extra bytes: not a valid checkpoint",
                 (unsigned long long)v.extra_size);
    goto done;
  }
  extra_buf = malloc((size_t)v.extra_size + 1);
  if (extra_buf == NULL) {
    st = gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOMEM, "out of memory");
    goto done;
  }
  if (get(&s, extra_buf, (size_t)v.extra_size)) {
    st = truncated(it, "the caller's data");
    goto done;
  }
  const uint64_t expected = s.hash;
  uint64_t checksum = 0;
  if (get(&s, &checksum, 8)) {
    st = truncated(it, "the checksum");
    goto done;
  }
  if (checksum != expected) {
    st = gm_fail(it->errmsg, sizeof it->errmsg, GM_EIO,
                 "checkpoint: checksum mismatch: the file is damaged");
    goto done;
  }
  if (extra_cap < v.extra_size && v.extra_size > 0) {
    st = gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                 "checkpoint: %llu bytes of caller's data, room for %zu",
                 (unsigned long long)v.extra_size, extra_cap);
    goto done;
  }
  /* a valid checksum says the file is as written, not that it was written by geomint: every
   * field is input (a forged h = 0 or t = inf ran, a singular state gave NaN) */
  if ((st = check_saved(it, &v)) != GM_OK) goto done;
  /* everything read and checked: apply */
  memcpy(it->y, v.y, it->n * sizeof(double));
  memcpy(it->carry, v.carry, it->n * sizeof(double));
  it->t = v.t;
  it->step_index = (size_t)v.step_index;
  stats_from(v.stats, &it->stats);
  it->run_kind = (int)v.run_kind;
  it->run = (gm_run){v.run_t0, v.run_h, v.run_t_last, (size_t)v.run_steps};
  it->run_start = (size_t)v.run_start;
  if (it->stepper->invalidate != NULL) it->stepper->invalidate(it);
  if (ms_size > 0 && (st = ms->load(it, v.ms)) != GM_OK) goto done;
  /* the observers have seen the saved step (it was observed before the checkpoint) */
  for (size_t k = 0; k < it->n_observers; ++k) it->observers[k].last_step = it->step_index;
  if (v.extra_size > 0 && extra != NULL) memcpy(extra, extra_buf, (size_t)v.extra_size);
  if (extra_size != NULL) *extra_size = (size_t)v.extra_size;
  it->errmsg[0] = '\0';
done:
  free(v.y);
  free(v.carry);
  free(v.ms);
  free(extra_buf);
  return st;
}

gm_status gm_integrator_load_file(gm_integrator *it, const char *path, void *extra,
                                  size_t extra_cap, size_t *extra_size) {
  if (it == NULL) return GM_EINVAL;
  if (path == NULL)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "checkpoint: no file name");
  char what[GM_ERRMSG_SIZE];
  FILE *f = gm_input_open(path, what, sizeof what); /* a directory or a FIFO says what it is */
  if (f == NULL) return gm_fail(it->errmsg, sizeof it->errmsg, GM_EIO, "%s", what);
  gm_status st = gm_integrator_load(it, f, extra, extra_cap, extra_size);
  /* anything after the checksum is not ours */
  if (st == GM_OK && fgetc(f) != EOF)
    st = gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                 "checkpoint: '%s' has bytes after the checksum", path);
  fclose(f);
  if (st != GM_OK) {
    char why[GM_ERRMSG_SIZE];
    memcpy(why, it->errmsg, sizeof why);
    gm_fail(it->errmsg, sizeof it->errmsg, st, "%s: %s", path, why);
  }
  return st;
}
