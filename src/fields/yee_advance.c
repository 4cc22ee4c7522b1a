/* The time loop: one step is the E half (Ampère) then the H half (Faraday), each followed by
 * its CPML, TF/SF and source terms and its boundary ghosts; then probes record and observers
 * that are due see the state. Nothing here allocates. Also initial fields and probes. */
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fields/internal.h"

static void record_probes(gm_yee *s) {
  for (size_t i = 0; i < s->n_probes; ++i) {
    yee_probe *p = &s->probes[i];
    if (p->n >= p->capacity) continue; /* checked before the run; never reached */
    p->t[p->n] = yee_is_e(p->component) ? gm_yee_time_e(s) : gm_yee_time_h(s);
    p->re[p->n] = s->f[0][p->component][p->index];
    if (p->im) p->im[p->n] = s->f[1][p->component][p->index];
    ++p->n;
  }
}

static gm_status check_finite(gm_yee *s) {
  for (int p = 0; p < s->n_parts; ++p)
    for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
      if (!s->active[c]) continue;
      const size_t bad = gm_first_nonfinite(s->L.size, s->f[p][c]);
      if (bad < s->L.size)
        return gm_fail(s->errmsg, sizeof s->errmsg, GM_EDOMAIN,
                       "yee: %s became non-finite at step %zu (array index %zu)",
                       gm_yee_component_name((gm_yee_component)c), s->step, bad);
    }
  return GM_OK;
}

static gm_status observe(gm_yee *s) {
  for (size_t i = 0; i < s->n_observers; ++i) {
    yee_observer *o = &s->observers[i];
    if (s->step % o->every != 0 || o->last_step == s->step) continue;
    o->last_step = s->step;
    const int rc = o->fn(o->ctx, s);
    if (rc != 0)
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_ECALLBACK,
                     "yee: observer %zu returned %d at step %zu", i, rc, s->step);
  }
  return GM_OK;
}

gm_status gm_yee_advance(gm_yee *s, size_t n_steps) {
  if (s == NULL) return GM_EINVAL;
  for (size_t i = 0; i < s->n_probes; ++i)
    if (s->probes[i].n + n_steps > s->probes[i].capacity)
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                     "yee: probe %zu holds %zu samples and has %zu; %zu more steps asked", i,
                     s->probes[i].capacity, s->probes[i].n, n_steps);
  gm_status st = observe(s);
  if (st != GM_OK) return st;
  const int one_sweep = yee_wavefront_eligible(s);
  for (size_t n = 0; n < n_steps; ++n) {
    yee_dispersive_begin(s); /* pole updates from old values (yee_dispersive.c) */
    if (one_sweep) {
      /* the same two half steps as below, interleaved plane by plane (yee_update.c) */
      yee_sources_begin_e(s);
      yee_step_wavefront(s);
    } else {
      /* Ampère: E^{n−½} → E^{n+½} with H^n and J^n */
      yee_update_e(s);
      yee_cpml_apply(s, 1);
      yee_tfsf_apply(s, 1);
      yee_sources_apply(s, 1);
      yee_dispersive_apply(s); /* E on dispersive edges from the kernel's value */
      yee_aniso_apply(s); /* off-diagonal ε̃⁻¹ of smoothed interfaces (yee_aniso.c) */
      yee_apply_ghosts_e(s);
      if (s->exchange_e) s->exchange_e(s->exchange_ctx, s);
      /* Faraday: H^n → H^{n+1} with E^{n+½} */
      yee_update_h(s);
    }
    yee_cpml_apply(s, 0);
    yee_tfsf_apply(s, 0);
    yee_sources_apply(s, 0);
    yee_apply_ghosts_h(s);
    ++s->step;
    record_probes(s);
    if (s->n_observers > 0) {
      int due = 0;
      for (size_t i = 0; i < s->n_observers; ++i) due |= s->step % s->observers[i].every == 0;
      if (due) {
        st = check_finite(s);
        if (st != GM_OK) return st;
        st = observe(s);
        if (st != GM_OK) return st;
      }
    }
  }
  return check_finite(s);
}

gm_status gm_yee_advance_to(gm_yee *s, double t) {
  if (s == NULL) return GM_EINVAL;
  if (!isfinite(t))
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "yee: target time is not finite");
  const double steps = floor(t / s->dt * (1.0 + 1e-14) + 1e-12);
  if (steps <= (double)s->step) return GM_OK;
  return gm_yee_advance(s, (size_t)steps - s->step);
}

gm_status gm_yee_add_observer(gm_yee *s, size_t every, gm_yee_observer_fn fn, void *ctx) {
  if (s == NULL) return GM_EINVAL;
  if (every == 0 || fn == NULL)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "observer: need every >= 1 and a function");
  yee_observer *grown = realloc(s->observers, (s->n_observers + 1) * sizeof *grown);
  if (grown == NULL) return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "observer: out of memory");
  s->observers = grown;
  s->observers[s->n_observers++] = (yee_observer){every, fn, ctx, SIZE_MAX};
  return GM_OK;
}

/* ---- initial fields ---- */

static gm_status set_common(gm_yee *s, int c, int part) {
  if (s == NULL) return GM_EINVAL;
  if ((unsigned)c >= GM_YEE_N_COMPONENTS || !s->active[c])
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "set field: this grid has no component %d", c);
  if (part < 0 || part >= s->n_parts)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "set field: part %d (the fields have %d part(s))", part, s->n_parts);
  return GM_OK;
}

/* Zero what is not a location the update covers (ghosts, unused entries, walls), then refresh
 * periodic copies and ghosts. */
static void finish_set(gm_yee *s, int c, int part) {
  double *f = s->f[part][c];
  const yee_box *b = &s->upd[c];
  for (size_t k = 0; k < s->L.extent[2]; ++k)
    for (size_t j = 0; j < s->L.extent[1]; ++j)
      for (size_t i = 0; i < s->L.extent[0]; ++i) {
        const long ijk[3] = {(long)i - (long)s->L.offset[0], (long)j - (long)s->L.offset[1],
                             (long)k - (long)s->L.offset[2]};
        int in = 1;
        for (int a = 0; a < 3; ++a)
          in &= ijk[a] >= (long)b->lo[a] && ijk[a] < (long)(b->lo[a] + b->cnt[a]);
        if (!in) f[yee_idx(&s->L, ijk[0], ijk[1], ijk[2])] = 0.0;
      }
  if (yee_is_e(c)) yee_aniso_sync(s);
  if (yee_is_e(c)) yee_dispersive_sync(s);
  if (yee_is_e(c))
    yee_apply_ghosts_e(s);
  else
    yee_apply_ghosts_h(s);
}

gm_status gm_yee_set_field(gm_yee *s, gm_yee_component c, int part, const double *values) {
  gm_status st = set_common(s, (int)c, part);
  if (st != GM_OK) return st;
  if (values == NULL) return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "set field: NULL values");
  const size_t bad = gm_first_nonfinite(s->L.size, values);
  if (bad < s->L.size)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EDOMAIN, "set field: value %zu is not finite",
                   bad);
  memcpy(s->f[part][c], values, s->L.size * sizeof(double));
  finish_set(s, (int)c, part);
  return GM_OK;
}

gm_status gm_yee_set_field_fn(gm_yee *s, gm_yee_component c, int part,
                              double (*fn)(void *ctx, const double x[3]), void *ctx) {
  gm_status st = set_common(s, (int)c, part);
  if (st != GM_OK) return st;
  if (fn == NULL) return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "set field: NULL function");
  double sh[3];
  size_t cnt[3];
  gm_yee_component_shift(s->L.dim, c, sh);
  gm_yee_component_count(&s->L, c, cnt);
  double *f = s->f[part][c];
  for (size_t k = 0; k < cnt[2]; ++k)
    for (size_t j = 0; j < cnt[1]; ++j)
      for (size_t i = 0; i < cnt[0]; ++i) {
        const size_t ijk[3] = {i, j, k};
        double x[3];
        for (int a = 0; a < 3; ++a)
          x[a] = a < s->n_axes ? s->L.origin[a] + ((double)ijk[a] + sh[a]) * s->L.h[a] : 0.0;
        const double v = fn(ctx, x);
        if (!isfinite(v))
          return gm_fail(s->errmsg, sizeof s->errmsg, GM_EDOMAIN,
                         "set field: f(%g, %g, %g) is not finite", x[0], x[1], x[2]);
        f[yee_idx(&s->L, (long)i, (long)j, (long)k)] = v;
      }
  finish_set(s, (int)c, part);
  return GM_OK;
}

double gm_yee_field_at(const gm_yee *s, gm_yee_component c, int part, const double x[3]) {
  if (s == NULL || (unsigned)c >= GM_YEE_N_COMPONENTS || !s->active[c] || part < 0 ||
      part >= s->n_parts)
    return NAN;
  long ijk[3];
  if (yee_locate(s, (int)c, x, ijk) != 0) return NAN;
  return s->f[part][c][yee_idx(&s->L, ijk[0], ijk[1], ijk[2])];
}

/* ---- probes ---- */

gm_status gm_yee_add_probe(gm_yee *s, gm_yee_component c, const double x[3], size_t capacity,
                           size_t *id) {
  if (s == NULL) return GM_EINVAL;
  if ((unsigned)c >= GM_YEE_N_COMPONENTS || !s->active[c])
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "probe: this grid has no component %d",
                   (int)c);
  long ijk[3];
  if (yee_locate(s, (int)c, x, ijk) != 0)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "probe: (%g, %g, %g) is outside the grid", x[0], x[1], x[2]);
  {
    /* this buffer and those already held */
    double bytes = (2.0 + (s->n_parts == 2)) * 8.0 * ((double)capacity + 1.0);
    for (size_t i = 0; i < s->n_probes; ++i)
      bytes += (2.0 + (s->n_parts == 2)) * 8.0 * ((double)s->probes[i].capacity + 1.0);
    char what[128];
    gm_error e = {{0}};
    snprintf(what, sizeof what, "probe: buffers of %zu samples", capacity);
    if (yee_memory_check(bytes, what, &e) != GM_OK)
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "%s", e.message);
  }
  yee_probe p = {.component = (int)c, .index = yee_idx(&s->L, ijk[0], ijk[1], ijk[2]),
                 .capacity = capacity};
  p.t = malloc((capacity + 1) * sizeof(double));
  p.re = malloc((capacity + 1) * sizeof(double));
  p.im = s->n_parts == 2 ? malloc((capacity + 1) * sizeof(double)) : NULL;
  yee_probe *grown = (p.t && p.re && (p.im || s->n_parts == 1))
                         ? realloc(s->probes, (s->n_probes + 1) * sizeof *grown)
                         : NULL;
  if (grown == NULL) {
    free(p.t);
    free(p.re);
    free(p.im);
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "probe: out of memory");
  }
  s->probes = grown;
  s->probes[s->n_probes] = p;
  if (id) *id = s->n_probes;
  ++s->n_probes;
  return GM_OK;
}

gm_status gm_yee_probe_samples(const gm_yee *s, size_t id, size_t *n, const double **t,
                               const double **re, const double **im) {
  if (s == NULL || id >= s->n_probes) return GM_EINVAL;
  const yee_probe *p = &s->probes[id];
  if (n) *n = p->n;
  if (t) *t = p->t;
  if (re) *re = p->re;
  if (im) *im = p->im;
  return GM_OK;
}

gm_status gm_yee_probe_clear(gm_yee *s, size_t id) {
  if (s == NULL || id >= s->n_probes) return GM_EINVAL;
  s->probes[id].n = 0;
  return GM_OK;
}

size_t gm_yee_probe_count(const gm_yee *s) { return s ? s->n_probes : 0; }
