/* Point dipoles (soft = a current on one edge/face, hard = a set value), currents J on sets of
 * edges with the charge they move, and the per-step application (once per step per source,
 * outside the update loops). */
#include <math.h>
#include <stdlib.h>

#include "fields/internal.h"

int yee_locate(const gm_yee *s, int c, const double x[3], long ijk[3]) {
  double sh[3];
  size_t cnt[3];
  gm_yee_component_shift(s->L.dim, (gm_yee_component)c, sh);
  gm_yee_component_count(&s->L, (gm_yee_component)c, cnt);
  for (int a = 0; a < 3; ++a) {
    if (a >= s->n_axes) {
      ijk[a] = 0;
      continue;
    }
    if (!isfinite(x[a])) return -1;
    const double r = (x[a] - s->L.origin[a]) / s->L.h[a] - sh[a];
    const double idx = floor(r + 0.5);
    if (idx < 0.0 || idx > (double)cnt[a] - 1.0) return -1;
    ijk[a] = (long)idx;
  }
  return 0;
}

/* Non-zero when the location is one the update loop of c covers. */
static int updated(const gm_yee *s, int c, const long ijk[3]) {
  for (int a = 0; a < 3; ++a) {
    const long lo = (long)s->upd[c].lo[a];
    if (ijk[a] < lo || ijk[a] >= lo + (long)s->upd[c].cnt[a]) return 0;
  }
  return 1;
}

double yee_medium_cb_e(const gm_yee *s, int c, size_t q) { return s->cb[c] ? s->cb[c][q] : s->cb0[c]; }
double yee_medium_cb_h(const gm_yee *s, int c, size_t q) { return s->cb[c] ? s->cb[c][q] : s->cb0[c]; }

static gm_status push_source(gm_yee *s, yee_source *src, size_t *id) {
  yee_source *grown = realloc(s->sources, (s->n_sources + 1) * sizeof *grown);
  if (grown == NULL) {
    free(src->index);
    free(src->coef);
    free(src->vertex);
    free(src->rho);
    free(src->drho);
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "source: out of memory");
  }
  s->sources = grown;
  s->sources[s->n_sources] = *src;
  if (id) *id = s->n_sources;
  ++s->n_sources;
  return GM_OK;
}

/* Build a soft or hard source on n locations of component c; weights may be NULL. */
static gm_status build_source(gm_yee *s, int c, int hard, size_t n, const long (*ijk)[3],
                              const double *weights, const gm_waveform *wave, size_t *id) {
  yee_source src = {0};
  src.n = n;
  src.component = c;
  src.hard = hard;
  src.wave = *wave;
  const int e = yee_is_e(c);
  src.time_shift = e ? (hard ? 0.5 : 0.0) : (hard ? 1.0 : 0.5); /* in units of Δt */
  src.index = malloc((n + 1) * sizeof(size_t));
  src.coef = malloc((n + 1) * sizeof(double));
  const int track = e && !hard;
  if (track) {
    src.n_vertices = 2 * n;
    src.vertex = malloc((2 * n + 1) * sizeof(size_t));
    src.rho = calloc(2 * n + 1, sizeof(double));
    src.drho = malloc((2 * n + 1) * sizeof(double));
  }
  if (!src.index || !src.coef || (track && (!src.vertex || !src.rho || !src.drho))) {
    free(src.index);
    free(src.coef);
    free(src.vertex);
    free(src.rho);
    free(src.drho);
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "source: out of memory");
  }
  for (size_t l = 0; l < n; ++l) {
    const double w = weights ? weights[l] : 1.0;
    const size_t q = yee_idx(&s->L, ijk[l][0], ijk[l][1], ijk[l][2]);
    src.index[l] = q;
    if (l == 0 || q < src.index_min) src.index_min = q;
    if (l == 0 || q > src.index_max) src.index_max = q;
    if (hard) {
      src.coef[l] = w;
    } else {
      /* E: D' = d̃H − J → E −= (Δt/ε) J; H: B' = −dE − M → H −= (Δt/μ) M */
      src.coef[l] = -(e ? yee_medium_cb_e(s, c, q) : yee_medium_cb_h(s, c, q)) * w;
    }
    if (track) {
      /* ρ' = −div J: the edge from its lower to its upper vertex carries w·g(t) */
      long lo[3] = {ijk[l][0], ijk[l][1], ijk[l][2]}, hi[3] = {lo[0], lo[1], lo[2]};
      hi[c] += 1;
      if (s->periodic[c] && hi[c] == (long)s->L.n[c]) hi[c] = 0;
      src.vertex[2 * l] = yee_idx(&s->L, lo[0], lo[1], lo[2]);
      src.vertex[2 * l + 1] = yee_idx(&s->L, hi[0], hi[1], hi[2]);
      src.drho[2 * l] = -s->dt * w / s->L.h[c];
      src.drho[2 * l + 1] = s->dt * w / s->L.h[c];
    }
  }
  return push_source(s, &src, id);
}

gm_status gm_yee_add_point_source(gm_yee *s, const gm_point_source *ps, size_t *id) {
  if (s == NULL || ps == NULL) return GM_EINVAL;
  const int c = (int)ps->component;
  if ((unsigned)c >= GM_YEE_N_COMPONENTS || !s->active[c])
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "point source: this grid has no component %d (%s)", c,
                   gm_yee_component_name(ps->component) ? gm_yee_component_name(ps->component)
                                                        : "?");
  gm_error e;
  if (gm_waveform_check(&ps->wave, &e) != GM_OK)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "point source: %s", e.message);
  long ijk[1][3];
  if (yee_locate(s, c, ps->x, ijk[0]) != 0)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "point source: (%g, %g, %g) is outside the grid", ps->x[0], ps->x[1],
                   ps->x[2]);
  if (!updated(s, c, ijk[0]))
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "point source: (%g, %g, %g) is on a PEC face (or the copy of a periodic "
                   "one), where %s is never updated",
                   ps->x[0], ps->x[1], ps->x[2], gm_yee_component_name(ps->component));
  return build_source(s, c, ps->mode == GM_SOURCE_HARD, 1, (const long(*)[3])ijk, NULL,
                      &ps->wave, id);
}

gm_status gm_yee_add_current(gm_yee *s, const gm_current *cur, size_t *id) {
  if (s == NULL || cur == NULL) return GM_EINVAL;
  const int c = (int)cur->component;
  if ((unsigned)c >= 3 || !s->active[c])
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "current: component must be an E component this grid has (got %d)", c);
  gm_error e;
  if (gm_waveform_check(&cur->wave, &e) != GM_OK)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "current: %s", e.message);
  if (cur->n_edges == 0 || cur->edges == NULL)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "current: no edges");
  long (*ijk)[3] = malloc(cur->n_edges * sizeof *ijk);
  if (ijk == NULL) return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "current: out of memory");
  for (size_t l = 0; l < cur->n_edges; ++l) {
    for (int a = 0; a < 3; ++a) ijk[l][a] = (long)cur->edges[3 * l + a];
    if (!updated(s, c, ijk[l])) {
      free(ijk);
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                     "current: edge %zu (%zu, %zu, %zu) is outside the grid or on a PEC face",
                     l, cur->edges[3 * l], cur->edges[3 * l + 1], cur->edges[3 * l + 2]);
    }
    if (cur->weights && !isfinite(cur->weights[l])) {
      free(ijk);
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "current: weight %zu is not finite",
                     l);
    }
  }
  gm_status st = build_source(s, c, 0, cur->n_edges, (const long(*)[3])ijk, cur->weights,
                              &cur->wave, id);
  free(ijk);
  return st;
}

void yee_sources_apply(gm_yee *s, int e_field) {
  double *restrict const *f = s->f[0];
  for (size_t i = 0; i < s->n_sources; ++i) {
    yee_source *src = &s->sources[i];
    if (yee_is_e(src->component) != e_field) continue;
    const double g = gm_waveform_value(&src->wave, ((double)s->step + src->time_shift) * s->dt);
    double *field = f[src->component];
    if (src->hard) {
      for (size_t l = 0; l < src->n; ++l) field[src->index[l]] = src->coef[l] * g;
    } else {
      for (size_t l = 0; l < src->n; ++l) field[src->index[l]] += src->coef[l] * g;
      for (size_t v = 0; v < src->n_vertices; ++v) src->rho[v] += src->drho[v] * g;
    }
  }
}

/* The one-sweep step (yee_update.c): the E sources' waveform values and charges once per step,
 * then each plane's locations right after that plane's E update, with the same arithmetic as
 * yee_sources_apply. */
void yee_sources_begin_e(gm_yee *s) {
  for (size_t i = 0; i < s->n_sources; ++i) {
    yee_source *src = &s->sources[i];
    if (!yee_is_e(src->component)) continue;
    src->g = gm_waveform_value(&src->wave, ((double)s->step + src->time_shift) * s->dt);
    if (!src->hard)
      for (size_t v = 0; v < src->n_vertices; ++v) src->rho[v] += src->drho[v] * src->g;
  }
}

void yee_sources_apply_plane(gm_yee *s, size_t lo, size_t n) {
  double *restrict const *f = s->f[0];
  for (size_t i = 0; i < s->n_sources; ++i) {
    const yee_source *src = &s->sources[i];
    if (!yee_is_e(src->component) || src->index_max < lo || src->index_min >= lo + n) continue;
    double *field = f[src->component];
    const double g = src->g;
    for (size_t l = 0; l < src->n; ++l) {
      const size_t q = src->index[l];
      if (q < lo || q >= lo + n) continue;
      if (src->hard)
        field[q] = src->coef[l] * g;
      else
        field[q] += src->coef[l] * g;
    }
  }
}
