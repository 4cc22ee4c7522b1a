/* CSV writer of trajectories, energy error and invariants; an observer of the integrator. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/internal.h"
#include "geomint/io.h"

#define NUMBER_WIDTH 32 /* "%.17g" needs at most 24 characters, plus the comma */
#define BUFFER_SIZE 65536 /* whole rows are collected here and written together */

/* Rows are written whole: they are collected in a buffer of whole rows and written with
 * write(2); when a write fails or is short (disk full, file size limit), the file is cut back
 * to the end of the last whole row it holds, and the writer fails from then on. */
struct gm_csv_writer {
  int fd;             /* -1 when closed */
  char *buffer;       /* whole rows not yet written */
  size_t buffer_len, buffer_cap;
  size_t buffer_rows; /* rows in the buffer */
  long long committed; /* bytes of whole rows in the file */
  char *path;
  const gm_problem *problem;
  size_t n_state;   /* entries of y */
  int has_energy;
  double energy0;
  size_t n_columns;
  char **column_names; /* owned, n_columns entries */
  char *row;           /* one formatted line */
  size_t row_cap;
  size_t rows;
  int failed;
  int header_pending;  /* the header is written with the first row (columns may be added) */
  size_t n_extra;      /* columns added by gm_csv_writer_add_column, after the invariants */
  gm_csv_column_fn *extra_fn;
  void **extra_ctx;
  char *resume_header; /* gm_csv_writer_resume: the file's header, checked at the first row */
  char errmsg[GM_ERRMSG_SIZE];
};

static char *copy_string(const char *s) {
  size_t n = strlen(s) + 1;
  char *c = malloc(n);
  if (c != NULL) memcpy(c, s, n);
  return c;
}

/* Column names in order; returns 0 or -1 when out of memory. */
static int name_columns(gm_csv_writer *w) {
  const gm_problem *pb = w->problem;
  size_t n_fixed = 1 + w->n_state + (w->has_energy ? 2 : 0);
  w->n_columns = n_fixed + pb->n_invariants;
  w->column_names = calloc(w->n_columns, sizeof *w->column_names);
  if (w->column_names == NULL) return -1;
  char name[32];
  size_t c = 0;
  w->column_names[c++] = copy_string("t");
  const gm_state_space *space = gm_problem_space(pb);
  for (size_t i = 0; i < w->n_state; ++i) {
    if (space != NULL && space->component_names != NULL) /* R11..R33, Pi1..: R as 9 columns */
      snprintf(name, sizeof name, "%s", space->component_names[i]);
    else if (gm_problem_has_momenta(pb))
      snprintf(name, sizeof name, "%c%zu", i < pb->dim ? 'q' : 'p', i % pb->dim + 1);
    else
      snprintf(name, sizeof name, "y%zu", i + 1);
    w->column_names[c++] = copy_string(name);
  }
  if (w->has_energy) {
    w->column_names[c++] = copy_string("H");
    w->column_names[c++] = copy_string("rel_energy_error");
  }
  for (size_t k = 0; k < pb->n_invariants; ++k)
    w->column_names[c++] = copy_string(pb->invariants[k].name);
  for (size_t k = 0; k < w->n_columns; ++k)
    if (w->column_names[k] == NULL) return -1;
  return 0;
}

/* Append s as a CSV field to the buffer, quoted when it holds a comma, quote or line break;
 * returns -1 when the buffer is full. */
static int put_field(gm_csv_writer *w, const char *s) {
  const int quote = strpbrk(s, ",\"\r\n") != NULL;
  if (w->buffer_len + 2 * strlen(s) + 3 >= w->buffer_cap) return -1;
  char *b = w->buffer + w->buffer_len;
  if (quote) *b++ = '"';
  for (; *s; ++s) {
    if (quote && *s == '"') *b++ = '"';
    *b++ = *s;
  }
  if (quote) *b++ = '"';
  w->buffer_len = (size_t)(b - w->buffer);
  return 0;
}

/* Write the buffer; on failure keep the whole rows that reached the file and cut the rest. */
static gm_status flush_rows(gm_csv_writer *w) {
  size_t done = 0;
  while (done < w->buffer_len) {
    ssize_t n = write(w->fd, w->buffer + done, w->buffer_len - done);
    if (n > 0) {
      done += (size_t)n;
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    int why = n < 0 ? errno : ENOSPC;
    size_t whole = done, rows = 0;
    while (whole > 0 && w->buffer[whole - 1] != '\n') --whole;
    for (size_t i = 0; i < whole; ++i) rows += w->buffer[i] == '\n';
    w->committed += (long long)whole;
    (void)!ftruncate(w->fd, (off_t)w->committed); /* a failure here keeps the first reason */
    w->rows += rows;
    w->failed = 1;
    w->buffer_len = 0;
    w->buffer_rows = 0;
    gm_fail(w->errmsg, sizeof w->errmsg, GM_EIO,
            "cannot write to '%s': %s (the file ends with the last whole row, %zu rows)",
            w->path, strerror(why), w->rows);
    return GM_EIO;
  }
  w->committed += (long long)w->buffer_len;
  w->rows += w->buffer_rows;
  w->buffer_len = 0;
  w->buffer_rows = 0;
  return GM_OK;
}

static gm_status write_header(gm_csv_writer *w) {
  w->header_pending = 0;
  for (size_t k = 0; k < w->n_columns; ++k) {
    if (k > 0) w->buffer[w->buffer_len++] = ',';
    if (put_field(w, w->column_names[k]) != 0 || w->buffer_len + 2 >= w->buffer_cap) {
      w->failed = 1;
      return gm_fail(w->errmsg, sizeof w->errmsg, GM_EIO, "'%s': header too long", w->path);
    }
  }
  w->buffer[w->buffer_len++] = '\n';
  if (w->resume_header != NULL) { /* continuing a file: its header must be this run's */
    const size_t len = w->buffer_len;
    w->buffer_len = 0;
    if (strlen(w->resume_header) != len || memcmp(w->resume_header, w->buffer, len) != 0) {
      w->failed = 1;
      return gm_fail(w->errmsg, sizeof w->errmsg, GM_EINVAL,
                     "'%s' has other columns than this run writes: cannot continue it", w->path);
    }
    return GM_OK;
  }
  return flush_rows(w);
}

static double relative_error(double h, double h0) {
  double d = fabs(h - h0);
  return h0 != 0.0 ? d / fabs(h0) : d;
}

/* Resume: read the file, keep its header (checked at the first row) and its whole rows up to
 * the last with t <= t_last, cut the rest, and open it for appending. */
static gm_status keep_rows_until(gm_csv_writer *w, const char *path, double t_last,
                                 double max_gap, gm_error *err) {
  FILE *f = fopen(path, "rb");
  if (f == NULL)
    return gm_error_set(err, GM_EIO, "cannot continue '%s': %s", path, strerror(errno));
  char *line = NULL;
  size_t cap = 0, header_len = 0;
  long long keep = 0;
  double t_kept = NAN; /* the time of the last row kept */
  ssize_t len;
  gm_status st = GM_OK;
  if ((len = getline(&line, &cap, f)) <= 0 || line[len - 1] != '\n') {
    st = gm_error_set(err, GM_EINVAL, "cannot continue '%s': no header line", path);
  } else {
    header_len = (size_t)len;
    w->resume_header = malloc(header_len + 1);
    if (w->resume_header == NULL) st = gm_error_set(err, GM_ENOMEM, "out of memory");
    else memcpy(w->resume_header, line, header_len + 1);
    keep = (long long)header_len;
  }
  while (st == GM_OK && (len = getline(&line, &cap, f)) > 0) {
    if (line[len - 1] != '\n') break; /* an incomplete last row: cut */
    char *end;
    double t = strtod(line, &end);
    if (end == line || *end != ',' || !(t <= t_last)) break;
    keep += len;
    w->rows++;
    t_kept = t;
  }
  free(line);
  fclose(f);
  if (st != GM_OK) return st;
  /* checked before anything is cut: a file that ends long before t_last is another run's */
  if (!(t_last - t_kept <= max_gap)) {
    if (isnan(t_kept))
      return gm_error_set(err, GM_EINVAL, "cannot continue '%s': it has no row at or before "
                          "t = %.17g", path, t_last);
    return gm_error_set(err, GM_EINVAL, "cannot continue '%s': its rows end at t = %.17g, "
                        "before t = %.17g (more than %.3g earlier): it is not the output of "
                        "the run being continued", path, t_kept, t_last, max_gap);
  }
  w->fd = open(path, O_WRONLY | O_CLOEXEC);
  if (w->fd < 0) return GM_OK; /* reported by the caller */
  if (ftruncate(w->fd, (off_t)keep) != 0 || lseek(w->fd, 0, SEEK_END) < 0)
    return gm_error_set(err, GM_EIO, "cannot continue '%s': %s", path, strerror(errno));
  w->committed = keep;
  return GM_OK;
}

/* Open path: truncated (t_last NaN), or kept up to its last row with t <= t_last (resume). */
static gm_status open_writer(const char *path, const gm_problem *problem, const double *y0,
                             double t_last, double max_gap, gm_csv_writer **out,
                             gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "csv writer: out is NULL");
  *out = NULL;
  if (path == NULL || path[0] == '\0')
    return gm_error_set(err, GM_EINVAL, "csv writer: no file name");
  if (y0 == NULL) return gm_error_set(err, GM_EINVAL, "csv writer: initial state is NULL");
  gm_status st = gm_problem_validate(problem, err);
  if (st != GM_OK) return st;

  gm_csv_writer *w = calloc(1, sizeof *w);
  if (w == NULL) return gm_error_set(err, GM_ENOMEM, "csv writer: out of memory");
  w->problem = problem;
  w->n_state = gm_problem_state_size(problem);
  w->has_energy = gm_problem_has_energy(problem);
  w->energy0 = w->has_energy ? gm_problem_energy(problem, y0) : NAN;
  w->path = copy_string(path);
  if (w->path == NULL || name_columns(w) != 0) {
    gm_csv_writer_free(w);
    return gm_error_set(err, GM_ENOMEM, "csv writer: out of memory");
  }
  w->row_cap = w->n_columns * NUMBER_WIDTH + 2;
  w->row = malloc(w->row_cap);
  w->buffer_cap = BUFFER_SIZE + w->row_cap;
  for (size_t k = 0; k < w->n_columns; ++k) w->buffer_cap += 2 * strlen(w->column_names[k]) + 3;
  w->buffer = malloc(w->buffer_cap);
  w->fd = -1;
  if (w->row == NULL || w->buffer == NULL) {
    gm_csv_writer_free(w);
    return gm_error_set(err, GM_ENOMEM, "csv writer: out of memory");
  }
  if (isnan(t_last)) {
    w->fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  } else if ((st = keep_rows_until(w, path, t_last, max_gap, err)) != GM_OK) {
    gm_csv_writer_free(w);
    return st;
  }
  if (w->fd < 0) {
    st = gm_error_set(err, GM_EIO, "cannot open '%s' for writing: %s", path, strerror(errno));
    gm_csv_writer_free(w);
    return st;
  }
  w->header_pending = 1;
  *out = w;
  return GM_OK;
}

gm_status gm_csv_writer_create(const char *path, const gm_problem *problem, const double *y0,
                               gm_csv_writer **out, gm_error *err) {
  return open_writer(path, problem, y0, NAN, INFINITY, out, err);
}

void gm_csv_writer_free(gm_csv_writer *w) {
  if (w == NULL) return;
  if (w->fd >= 0) {
    if (!w->failed && w->header_pending) write_header(w);
    if (!w->failed) flush_rows(w);
    close(w->fd);
  }
  free(w->buffer);
  free(w->extra_fn);
  free(w->extra_ctx);
  free(w->resume_header);
  if (w->column_names != NULL)
    for (size_t k = 0; k < w->n_columns; ++k) free(w->column_names[k]);
  free(w->column_names);
  free(w->row);
  free(w->path);
  free(w);
}

/* Append "%.17g" of x and a separator to the row at *len. */
static void put_number(gm_csv_writer *w, size_t *len, double x, char sep) {
  int n = snprintf(w->row + *len, w->row_cap - *len, "%.17g%c", x, sep);
  if (n > 0) *len += (size_t)n;
}

int gm_csv_writer_observe(void *writer, size_t step, double t, const double *y) {
  gm_csv_writer *w = writer;
  (void)step;
  if (w == NULL || w->fd < 0) return 1;
  if (w->failed) return 1;
  if (w->header_pending && write_header(w) != GM_OK) return 1;
  const gm_problem *pb = w->problem;
  size_t len = 0;
  size_t last = w->n_columns - 1;
  size_t c = 0;
  put_number(w, &len, t, c++ == last ? '\n' : ',');
  for (size_t i = 0; i < w->n_state; ++i) put_number(w, &len, y[i], c++ == last ? '\n' : ',');
  if (w->has_energy) {
    double h = gm_problem_energy(pb, y);
    put_number(w, &len, h, c++ == last ? '\n' : ',');
    put_number(w, &len, relative_error(h, w->energy0), c++ == last ? '\n' : ',');
  }
  for (size_t k = 0; k < pb->n_invariants; ++k)
    put_number(w, &len, pb->invariants[k].value(pb->ctx, y), c++ == last ? '\n' : ',');
  for (size_t k = 0; k < w->n_extra; ++k)
    put_number(w, &len, w->extra_fn[k](w->extra_ctx[k], step, t, y), c++ == last ? '\n' : ',');
  /* The row joins the buffer of whole rows; a full buffer is written first. */
  if (w->buffer_len + len > w->buffer_cap && flush_rows(w) != GM_OK) return 1;
  memcpy(w->buffer + w->buffer_len, w->row, len);
  w->buffer_len += len;
  w->buffer_rows++;
  if (w->buffer_len >= BUFFER_SIZE && flush_rows(w) != GM_OK) return 1;
  return 0;
}

gm_status gm_csv_writer_flush(gm_csv_writer *w) {
  if (w == NULL || w->fd < 0) return GM_EINVAL;
  if (w->failed) return GM_EIO;
  if (w->header_pending && write_header(w) != GM_OK) return GM_EIO;
  return flush_rows(w);
}

gm_status gm_csv_writer_add_column(gm_csv_writer *w, const char *name, gm_csv_column_fn fn,
                                   void *ctx) {
  if (w == NULL || name == NULL || name[0] == '\0' || fn == NULL) return GM_EINVAL;
  if (!w->header_pending)
    return gm_fail(w->errmsg, sizeof w->errmsg, GM_EINVAL,
                   "csv writer: column '%s' added after the first row", name);
  char *copy = copy_string(name);
  char **names = realloc(w->column_names, (w->n_columns + 1) * sizeof *names);
  if (names != NULL) w->column_names = names;
  gm_csv_column_fn *fns = realloc(w->extra_fn, (w->n_extra + 1) * sizeof *fns);
  if (fns != NULL) w->extra_fn = fns;
  void **ctxs = realloc(w->extra_ctx, (w->n_extra + 1) * sizeof *ctxs);
  if (ctxs != NULL) w->extra_ctx = ctxs;
  const size_t row_cap = w->row_cap + NUMBER_WIDTH,
               buffer_cap = w->buffer_cap + NUMBER_WIDTH + 2 * strlen(name) + 3;
  char *row = realloc(w->row, row_cap);
  if (row != NULL) w->row = row;
  char *buffer = realloc(w->buffer, buffer_cap);
  if (buffer != NULL) w->buffer = buffer;
  if (copy == NULL || names == NULL || fns == NULL || ctxs == NULL || row == NULL ||
      buffer == NULL) {
    free(copy);
    return gm_fail(w->errmsg, sizeof w->errmsg, GM_ENOMEM, "csv writer: out of memory");
  }
  w->row_cap = row_cap;
  w->buffer_cap = buffer_cap;
  w->column_names[w->n_columns++] = copy;
  w->extra_fn[w->n_extra] = fn;
  w->extra_ctx[w->n_extra++] = ctx;
  return GM_OK;
}

gm_status gm_csv_writer_resume(const char *path, const gm_problem *problem, const double *y0,
                               double t_last, gm_csv_writer **out, gm_error *err) {
  if (isnan(t_last)) return gm_error_set(err, GM_EINVAL, "csv writer: t_last is NaN");
  return open_writer(path, problem, y0, t_last, INFINITY, out, err);
}

gm_status gm_csv_writer_resume_within(const char *path, const gm_problem *problem,
                                      const double *y0, double t_last, double max_gap,
                                      gm_csv_writer **out, gm_error *err) {
  if (isnan(t_last)) return gm_error_set(err, GM_EINVAL, "csv writer: t_last is NaN");
  if (!(max_gap >= 0.0)) return gm_error_set(err, GM_EINVAL, "csv writer: max_gap < 0");
  return open_writer(path, problem, y0, t_last, max_gap, out, err);
}

size_t gm_csv_writer_rows(const gm_csv_writer *w) {
  return w != NULL ? w->rows + w->buffer_rows : 0;
}

size_t gm_csv_writer_column(const gm_csv_writer *w, const char *name) {
  if (w == NULL || name == NULL) return (size_t)-1;
  for (size_t k = 0; k < w->n_columns; ++k)
    if (strcmp(w->column_names[k], name) == 0) return k;
  return (size_t)-1;
}

const char *gm_csv_writer_errmsg(const gm_csv_writer *w) { return w != NULL ? w->errmsg : ""; }
