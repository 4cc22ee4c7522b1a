/* Probe time series as CSV: "t,<names>" then one row per sample. Rows are formatted into our
 * own buffer and the stream is unbuffered, so every write to the file ends at a row boundary:
 * a reader (or a run that is killed) never sees half a row. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/io.h"

#define NUMBER_WIDTH 26 /* "%.17g" is at most 24 characters, plus the separator */

struct gm_probe_csv {
  FILE *file;
  char *path;        /* owned */
  size_t n_columns;
  char *row;         /* owned, one formatted line */
  size_t row_cap;
  char *buf;         /* owned: whole rows not yet written */
  size_t buf_len, buf_cap;
  size_t rows;
  size_t flush_every;
  int failed;
  char errmsg[GM_ERRMSG_SIZE];
};

/* A CSV field: quoted when it holds a comma, quote or line break. */
static void put_field(FILE *f, const char *s) {
  if (strpbrk(s, ",\"\r\n") == NULL) {
    fputs(s, f);
    return;
  }
  fputc('"', f);
  for (; *s; ++s) {
    if (*s == '"') fputc('"', f);
    fputc(*s, f);
  }
  fputc('"', f);
}

gm_status gm_probe_csv_create(const char *path, size_t n_columns, const char *const *names,
                              gm_probe_csv **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "probe csv: out is NULL");
  *out = NULL;
  if (path == NULL || path[0] == '\0')
    return gm_error_set(err, GM_EINVAL, "probe csv: no file name");
  if (n_columns > 0 && names == NULL)
    return gm_error_set(err, GM_EINVAL, "probe csv: %zu columns but no names", n_columns);
  for (size_t k = 0; k < n_columns; ++k)
    if (names[k] == NULL || names[k][0] == '\0')
      return gm_error_set(err, GM_EINVAL, "probe csv: column %zu has no name", k);
  gm_probe_csv *w = calloc(1, sizeof *w);
  if (w == NULL) return gm_error_set(err, GM_ENOMEM, "probe csv: out of memory");
  w->n_columns = n_columns;
  w->row_cap = (n_columns + 1) * NUMBER_WIDTH + 2;
  w->row = malloc(w->row_cap);
  w->buf_cap = w->row_cap * 16 > 65536 ? w->row_cap * 16 : 65536;
  w->buf = malloc(w->buf_cap);
  w->path = malloc(strlen(path) + 1);
  if (w->row == NULL || w->buf == NULL || w->path == NULL) {
    gm_probe_csv_free(w);
    return gm_error_set(err, GM_ENOMEM, "probe csv: out of memory");
  }
  strcpy(w->path, path);
  w->file = fopen(path, "w");
  if (w->file == NULL) {
    gm_status st =
        gm_error_set(err, GM_EIO, "cannot open '%s' for writing: %s", path, strerror(errno));
    gm_probe_csv_free(w);
    return st;
  }
  setvbuf(w->file, NULL, _IONBF, 0);
  fputc('t', w->file);
  for (size_t k = 0; k < n_columns; ++k) {
    fputc(',', w->file);
    put_field(w->file, names[k]);
  }
  fputc('\n', w->file);
  if (fflush(w->file) != 0 || ferror(w->file)) {
    gm_status st = gm_error_set(err, GM_EIO, "cannot write to '%s': %s", path, strerror(errno));
    gm_probe_csv_free(w);
    return st;
  }
  *out = w;
  return GM_OK;
}

/* Write the buffered rows with one call; 0 or -1. */
static int write_buffer(gm_probe_csv *w) {
  if (w->buf_len == 0) return 0;
  size_t n = fwrite(w->buf, 1, w->buf_len, w->file);
  w->buf_len = 0;
  return n == 0 ? -1 : (ferror(w->file) ? -1 : 0);
}

gm_status gm_probe_csv_flush(gm_probe_csv *w) {
  if (w == NULL) return GM_EINVAL;
  if (w->failed) return GM_EIO;
  if (write_buffer(w) != 0) {
    w->failed = 1;
    return gm_fail(w->errmsg, sizeof w->errmsg, GM_EIO, "cannot write to '%s': %s", w->path,
                   strerror(errno));
  }
  return GM_OK;
}

void gm_probe_csv_free(gm_probe_csv *w) {
  if (w == NULL) return;
  if (w->file != NULL) {
    if (!w->failed) write_buffer(w);
    fclose(w->file);
  }
  free(w->buf);
  free(w->row);
  free(w->path);
  free(w);
}

void gm_probe_csv_set_flush(gm_probe_csv *w, size_t flush_every) {
  if (w != NULL) w->flush_every = flush_every;
}

gm_status gm_probe_csv_write(gm_probe_csv *w, double t, const double *values) {
  if (w == NULL) return GM_EINVAL;
  if (w->failed) return GM_EIO;
  if (values == NULL && w->n_columns > 0)
    return gm_fail(w->errmsg, sizeof w->errmsg, GM_EINVAL, "probe csv: values is NULL");
  size_t len = 0;
  for (size_t k = 0; k <= w->n_columns; ++k) {
    double x = k == 0 ? t : values[k - 1];
    int n = snprintf(w->row + len, w->row_cap - len, "%.17g%c", x,
                     k == w->n_columns ? '\n' : ',');
    if (n > 0) len += (size_t)n;
  }
  int bad = 0;
  if (w->buf_len + len > w->buf_cap) bad = write_buffer(w) != 0;
  if (!bad) {
    memcpy(w->buf + w->buf_len, w->row, len);
    w->buf_len += len;
    if (w->flush_every > 0 && (w->rows + 1) % w->flush_every == 0) bad = write_buffer(w) != 0;
  }
  if (bad) {
    w->failed = 1;
    return gm_fail(w->errmsg, sizeof w->errmsg, GM_EIO, "cannot write to '%s' at t = %.17g: %s",
                   w->path, t, strerror(errno));
  }
  w->rows++;
  return GM_OK;
}

size_t gm_probe_csv_rows(const gm_probe_csv *w) { return w != NULL ? w->rows : 0; }
size_t gm_probe_csv_columns(const gm_probe_csv *w) { return w != NULL ? w->n_columns : 0; }
const char *gm_probe_csv_errmsg(const gm_probe_csv *w) { return w != NULL ? w->errmsg : ""; }
