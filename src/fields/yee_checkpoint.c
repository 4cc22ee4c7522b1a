/* Checkpoint/restart of the Yee solver (geomint/yee_checkpoint.h): a header of sizes that fix the
 * layout, then the arrays in a fixed order. Nothing here runs inside the time loop. */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fields/internal.h"
#include "geomint/yee_checkpoint.h"

#define MAGIC "GMYEECK2" /* 2: with the subpixel coupling's D and E_saved, and the poles' state */
#define N_HEAD 15

/* The sizes that must agree between the writer and the reader. */
static void header(const gm_yee *s, uint64_t h[N_HEAD]) {
  memset(h, 0, N_HEAD * sizeof *h);
  h[0] = (uint64_t)s->L.dim;
  for (int a = 0; a < 3; ++a) h[1 + a] = s->L.n[a];
  h[4] = (uint64_t)s->n_parts;
  h[5] = s->L.size;
  h[6] = s->n_cpml;
  h[7] = s->n_sources;
  h[8] = s->n_probes;
  h[9] = s->n_tfsf;
  for (size_t t = 0; t < s->n_cpml; ++t) h[10] += s->cpml[t].n;
  h[10] += yee_dispersive_state_size(s); /* 0 without poles: older files read unchanged */
  for (size_t i = 0; i < s->n_sources; ++i) h[11] += s->sources[i].rho ? s->sources[i].n_vertices : 0;
  for (size_t i = 0; i < s->n_tfsf; ++i) h[12] += s->tfsf[i].n_aux;
  for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) h[13] |= (uint64_t)s->active[c] << c;
  h[14] = yee_aniso_state(s, 0, NULL, NULL);
}

/* Every array of the state, in file order, through one function: fn(ctx, data, count). */
typedef int (*visit_fn)(void *ctx, double *data, size_t n);

static int visit_state(gm_yee *s, visit_fn fn, void *ctx) {
  for (int p = 0; p < s->n_parts; ++p)
    for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c)
      if (s->active[c] && fn(ctx, s->f[p][c], s->L.size) != 0) return -1;
  for (size_t t = 0; t < s->n_cpml; ++t)
    if (fn(ctx, s->cpml[t].psi, s->cpml[t].n * (size_t)s->n_parts) != 0) return -1;
  for (size_t i = 0; i < s->n_sources; ++i)
    if (s->sources[i].rho && fn(ctx, s->sources[i].rho, s->sources[i].n_vertices) != 0) return -1;
  for (size_t i = 0; i < s->n_tfsf; ++i) {
    const size_t n = s->tfsf[i].n_aux;
    if (fn(ctx, s->tfsf[i].e, n) != 0 || fn(ctx, s->tfsf[i].h, n - 1) != 0) return -1;
  }
  if (yee_dispersive_visit(s, fn, ctx) != 0) return -1;
  for (int p = 0; p < s->n_parts; ++p) { /* D and E_saved of the smoothed couplings (yee_aniso.c) */
    double *d = NULL, *es = NULL;
    const size_t n = yee_aniso_state(s, p, &d, &es);
    if (n > 0 && (fn(ctx, d, n) != 0 || fn(ctx, es, n) != 0)) return -1;
  }
  for (size_t i = 0; i < s->n_probes; ++i) {
    yee_probe *q = &s->probes[i];
    if (fn(ctx, q->t, q->n) != 0 || fn(ctx, q->re, q->n) != 0) return -1;
    if (q->im && fn(ctx, q->im, q->n) != 0) return -1;
  }
  return 0;
}

static int write_block(void *ctx, double *data, size_t n) {
  return fwrite(data, sizeof(double), n, (FILE *)ctx) == n ? 0 : -1;
}

static int read_block(void *ctx, double *data, size_t n) {
  return fread(data, sizeof(double), n, (FILE *)ctx) == n ? 0 : -1;
}

gm_status gm_yee_checkpoint_write(gm_yee *s, const char *path) {
  if (s == NULL) return GM_EINVAL;
  if (path == NULL) return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "checkpoint: NULL path");
  char tmp[4096];
  if (snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "checkpoint: path too long");
  FILE *f = fopen(tmp, "wb");
  if (f == NULL)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EIO, "checkpoint: cannot write %s: %s", tmp,
                   strerror(errno));
  uint64_t h[N_HEAD];
  header(s, h);
  const uint64_t step = s->step;
  int ok = fwrite(MAGIC, 1, 8, f) == 8 && fwrite(h, sizeof *h, N_HEAD, f) == N_HEAD &&
           fwrite(&step, sizeof step, 1, f) == 1;
  for (size_t i = 0; ok && i < s->n_probes; ++i) {
    const uint64_t n = s->probes[i].n;
    ok = fwrite(&n, sizeof n, 1, f) == 1;
  }
  ok = ok && visit_state(s, write_block, f) == 0;
  ok = fclose(f) == 0 && ok;
  if (!ok || rename(tmp, path) != 0) {
    const int e = errno;
    remove(tmp);
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EIO, "checkpoint: writing %s failed: %s",
                   path, strerror(e));
  }
  return GM_OK;
}

gm_status gm_yee_checkpoint_read(gm_yee *s, const char *path) {
  if (s == NULL) return GM_EINVAL;
  if (path == NULL) return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "checkpoint: NULL path");
  FILE *f = fopen(path, "rb");
  if (f == NULL)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EIO, "checkpoint: cannot read %s: %s", path,
                   strerror(errno));
  char magic[8];
  uint64_t h[N_HEAD], want[N_HEAD], step;
  header(s, want);
  gm_status st = GM_OK;
  if (fread(magic, 1, 8, f) != 8 || memcmp(magic, MAGIC, 8) != 0)
    st = gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "checkpoint: %s is not a Yee checkpoint",
                 path);
  else if (fread(h, sizeof *h, N_HEAD, f) != N_HEAD || fread(&step, sizeof step, 1, f) != 1)
    st = gm_fail(s->errmsg, sizeof s->errmsg, GM_EIO, "checkpoint: %s is truncated", path);
  for (int i = 0; st == GM_OK && i < N_HEAD; ++i)
    if (h[i] != want[i])
      st = gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "checkpoint: %s was written by another solver (layout item %d: %llu, this "
                   "solver %llu: grid, boundaries, sources, probes or plane waves differ)",
                   path, i, (unsigned long long)h[i], (unsigned long long)want[i]);
  uint64_t *counts = calloc(s->n_probes + 1, sizeof *counts);
  if (st == GM_OK && counts == NULL)
    st = gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "checkpoint: out of memory");
  if (st == GM_OK && fread(counts, sizeof *counts, s->n_probes, f) != s->n_probes)
    st = gm_fail(s->errmsg, sizeof s->errmsg, GM_EIO, "checkpoint: %s is truncated", path);
  for (size_t i = 0; st == GM_OK && i < s->n_probes; ++i)
    if (counts[i] > s->probes[i].capacity)
      st = gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "checkpoint: probe %zu has %llu samples in %s but room for %zu", i,
                   (unsigned long long)counts[i], path, s->probes[i].capacity);
  if (st == GM_OK) {
    for (size_t i = 0; i < s->n_probes; ++i) s->probes[i].n = (size_t)counts[i];
    s->step = (size_t)step;
    if (visit_state(s, read_block, f) != 0)
      st = gm_fail(s->errmsg, sizeof s->errmsg, GM_EIO,
                   "checkpoint: %s is truncated (the solver's state is now undefined)", path);
  }
  free(counts);
  fclose(f);
  return st;
}
