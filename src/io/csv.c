/* CSV writer of trajectories, energy error and invariants; an observer of the integrator. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/io.h"

#define NUMBER_WIDTH 32 /* "%.17g" needs at most 24 characters, plus the comma */

struct gm_csv_writer {
  FILE *file;
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

/* Write s as a CSV field, quoted when it holds a comma, quote or line break. */
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

static gm_status write_header(gm_csv_writer *w) {
  for (size_t k = 0; k < w->n_columns; ++k) {
    if (k > 0) fputc(',', w->file);
    put_field(w->file, w->column_names[k]);
  }
  fputc('\n', w->file);
  if (fflush(w->file) != 0 || ferror(w->file)) return GM_EIO;
  return GM_OK;
}

static double relative_error(double h, double h0) {
  double d = fabs(h - h0);
  return h0 != 0.0 ? d / fabs(h0) : d;
}

gm_status gm_csv_writer_create(const char *path, const gm_problem *problem, const double *y0,
                               gm_csv_writer **out, gm_error *err) {
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
  if (w->row == NULL) {
    gm_csv_writer_free(w);
    return gm_error_set(err, GM_ENOMEM, "csv writer: out of memory");
  }
  w->file = fopen(path, "w");
  if (w->file == NULL) {
    st = gm_error_set(err, GM_EIO, "cannot open '%s' for writing: %s", path, strerror(errno));
    gm_csv_writer_free(w);
    return st;
  }
  if (write_header(w) != GM_OK) {
    st = gm_error_set(err, GM_EIO, "cannot write to '%s': %s", path, strerror(errno));
    gm_csv_writer_free(w);
    return st;
  }
  *out = w;
  return GM_OK;
}

void gm_csv_writer_free(gm_csv_writer *w) {
  if (w == NULL) return;
  if (w->file != NULL) fclose(w->file);
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
  if (w == NULL || w->file == NULL) return 1;
  if (w->failed) return 1;
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
  /* One write per row: a row is either complete in the file or the run stops here. */
  if (fwrite(w->row, 1, len, w->file) != len) {
    w->failed = 1;
    gm_fail(w->errmsg, sizeof w->errmsg, GM_EIO, "cannot write to '%s' at t = %.17g: %s",
            w->path, t, strerror(errno));
    return 1;
  }
  w->rows++;
  return 0;
}

size_t gm_csv_writer_rows(const gm_csv_writer *w) { return w != NULL ? w->rows : 0; }

size_t gm_csv_writer_column(const gm_csv_writer *w, const char *name) {
  if (w == NULL || name == NULL) return (size_t)-1;
  for (size_t k = 0; k < w->n_columns; ++k)
    if (strcmp(w->column_names[k], name) == 0) return k;
  return (size_t)-1;
}

const char *gm_csv_writer_errmsg(const gm_csv_writer *w) { return w != NULL ? w->errmsg : ""; }
