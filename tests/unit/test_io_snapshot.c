/* Field snapshot writers (.vti in three encodings, HDF5) and the probe CSV writer: what is
 * written is parsed back here by an independent reader and compared bit for bit; bad input is an
 * error with a message. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "geomint/io.h"

#if GM_TEST_HDF5
#include <hdf5.h>
#endif

static char dir[64];

static void make_dir(void) {
  snprintf(dir, sizeof dir, "/tmp/geomint-io-XXXXXX");
  cr_assert_not_null(mkdtemp(dir));
}

static void remove_dir(void) {
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  cr_assert_eq(system(cmd), 0);
}

TestSuite(io_snapshot, .init = make_dir, .fini = remove_dir);

static const char *in_dir(const char *name) {
  static char buf[4][160];
  static int next = 0;
  char *p = buf[next++ % 4];
  snprintf(p, 160, "%s/%s", dir, name);
  return p;
}

static char *slurp(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  cr_assert_not_null(f, "cannot open %s", path);
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *s = malloc((size_t)n + 1);
  cr_assert_eq(fread(s, 1, (size_t)n, f), (size_t)n);
  s[n] = '\0';
  fclose(f);
  if (len != NULL) *len = (size_t)n;
  return s;
}

/* ---- an independent .vti reader: just enough XML to find one DataArray ------------------- */

static int b64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

/* Decode one padded base64 run starting at *s into out (at most cap bytes); *s moves past it. */
static size_t b64_decode_run(const char **s, unsigned char *out, size_t cap) {
  size_t n = 0;
  const char *p = *s;
  for (;;) {
    int v[4];
    for (int k = 0; k < 4; ++k) v[k] = p[k] == '=' ? -2 : b64_value(p[k]);
    if (v[0] < 0 || v[1] < 0) break;
    unsigned bits = (unsigned)v[0] << 18 | (unsigned)v[1] << 12 |
                    (unsigned)(v[2] >= 0 ? v[2] : 0) << 6 | (unsigned)(v[3] >= 0 ? v[3] : 0);
    cr_assert_leq(n + 3, cap + 2);
    out[n++] = (unsigned char)(bits >> 16);
    if (v[2] >= 0) out[n++] = (unsigned char)(bits >> 8);
    if (v[3] >= 0) out[n++] = (unsigned char)bits;
    p += 4;
    if (v[2] < 0 || v[3] < 0) break; /* padding ends the run */
  }
  *s = p;
  return n;
}

/* The attribute value of name="..." inside the tag starting at tag (copied into buf). */
static const char *attr(const char *tag, const char *name, char *buf, size_t cap) {
  char key[64];
  snprintf(key, sizeof key, " %s=\"", name);
  const char *end = strchr(tag, '>');
  const char *p = strstr(tag, key);
  if (p == NULL || p > end) return NULL;
  p += strlen(key);
  const char *q = strchr(p, '"');
  size_t n = (size_t)(q - p) < cap - 1 ? (size_t)(q - p) : cap - 1;
  memcpy(buf, p, n);
  buf[n] = '\0';
  return buf;
}

/* Read array `name` from section ("PointData" or "CellData") into out (n_values doubles,
 * interleaved as in the file). Returns the number of components. */
static size_t read_vti_array(const char *doc, const char *section, const char *name,
                             double *out, size_t n_values) {
  char open[32], close[32], buf[128];
  snprintf(open, sizeof open, "<%s>", section);
  snprintf(close, sizeof close, "</%s>", section);
  const char *sec = strstr(doc, open), *sec_end = strstr(doc, close);
  cr_assert(sec != NULL && sec_end != NULL, "no %s", section);
  const char *tag = sec;
  for (;;) {
    tag = strstr(tag + 1, "<DataArray ");
    cr_assert(tag != NULL && tag < sec_end, "no array %s in %s", name, section);
    if (strcmp(attr(tag, "Name", buf, sizeof buf), name) == 0) break;
  }
  cr_assert_str_eq(attr(tag, "type", buf, sizeof buf), "Float64");
  size_t nc = (size_t)atoi(attr(tag, "NumberOfComponents", buf, sizeof buf));
  const char *format = attr(tag, "format", buf, sizeof buf);
  const char *body = strchr(tag, '>') + 1;
  if (strcmp(format, "ascii") == 0) {
    char *end = NULL;
    for (size_t i = 0; i < n_values; ++i) {
      out[i] = strtod(body, &end);
      cr_assert_neq(end, body, "ascii value %zu of %s", i, name);
      body = end;
    }
    while (*body == ' ' || *body == '\n') ++body;
    cr_assert(strncmp(body, "</DataArray>", 12) == 0, "extra values in %s", name);
  } else if (strcmp(format, "binary") == 0) {
    while (*body == ' ' || *body == '\n') ++body;
    uint64_t header = 0;
    unsigned char hb[16];
    cr_assert_eq(b64_decode_run(&body, hb, sizeof hb), 8, "UInt64 header run");
    memcpy(&header, hb, 8);
    cr_assert_eq(header, n_values * sizeof(double));
    unsigned char *data = malloc(n_values * sizeof(double) + 3);
    cr_assert_eq(b64_decode_run(&body, data, n_values * sizeof(double)),
                 n_values * sizeof(double));
    memcpy(out, data, n_values * sizeof(double));
    free(data);
  } else {
    cr_assert_str_eq(format, "appended");
    size_t offset = (size_t)strtoull(attr(tag, "offset", buf, sizeof buf), NULL, 10);
    const char *app = strstr(doc, "<AppendedData encoding=\"raw\">");
    cr_assert_not_null(app);
    const char *start = strchr(app, '_') + 1;
    uint64_t header;
    memcpy(&header, start + offset, 8);
    cr_assert_eq(header, n_values * sizeof(double));
    memcpy(out, start + offset + 8, n_values * sizeof(double));
  }
  return nc;
}

/* ---- a 3 x 4 x 5 box with a scalar on points and a vector on cells ------------------------ */

#define NX 3
#define NY 4
#define NZ 5
#define NPOINTS ((NX + 1) * (NY + 1) * (NZ + 1))
#define NCELLS (NX * NY * NZ)

typedef struct snapshot {
  gm_image image;
  double p[NPOINTS];
  double e[3][NCELLS];
  gm_image_array arrays[2];
} snapshot;

static void make_snapshot(snapshot *s) {
  memset(s, 0, sizeof *s);
  s->image = (gm_image){3, {NX, NY, NZ}, {-1.5, 0.25, 1e-3}, {0.5, 1.0 / 3.0, 2.0}};
  for (size_t i = 0; i < NPOINTS; ++i) s->p[i] = sin(1.0 + (double)i) * 1e-7 * (double)(i + 1);
  for (size_t c = 0; c < 3; ++c)
    for (size_t i = 0; i < NCELLS; ++i) s->e[c][i] = (double)c + 1.0 / (double)(i + 3);
  s->e[1][7] = -0.0;
  s->e[2][11] = 1e-308; /* subnormal-adjacent values survive every encoding */
  s->arrays[0] = (gm_image_array){"phi", GM_IMAGE_POINT, 1, {s->p, NULL, NULL}};
  s->arrays[1] = (gm_image_array){"E", GM_IMAGE_CELL, 3, {s->e[0], s->e[1], s->e[2]}};
}

static void check_round_trip(gm_vti_encoding enc, const char *file) {
  static snapshot s;
  make_snapshot(&s);
  gm_error err = {{0}};
  cr_assert_eq(gm_vti_write(in_dir(file), &s.image, s.arrays, 2, 0.125, enc, &err), GM_OK, "%s",
               err.message);
  char *doc = slurp(in_dir(file), NULL);
  char buf[128];
  const char *im = strstr(doc, "<ImageData ");
  cr_assert_not_null(im);
  cr_assert_str_eq(attr(im, "WholeExtent", buf, sizeof buf), "0 3 0 4 0 5");
  double o[3], h[3];
  cr_assert_eq(sscanf(attr(im, "Origin", buf, sizeof buf), "%lf %lf %lf", &o[0], &o[1], &o[2]), 3);
  cr_assert_eq(sscanf(attr(im, "Spacing", buf, sizeof buf), "%lf %lf %lf", &h[0], &h[1], &h[2]),
               3);
  for (int a = 0; a < 3; ++a) {
    cr_expect_eq(o[a], s.image.origin[a]);
    cr_expect_eq(h[a], s.image.spacing[a]);
  }
  cr_assert_not_null(strstr(doc, "Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">0.125<"));
  static double p[NPOINTS], e[3 * NCELLS];
  cr_assert_eq(read_vti_array(doc, "PointData", "phi", p, NPOINTS), 1);
  cr_assert_eq(read_vti_array(doc, "CellData", "E", e, 3 * NCELLS), 3);
  cr_expect_eq(memcmp(p, s.p, sizeof p), 0, "point scalar differs (%s)", file);
  for (size_t i = 0; i < NCELLS; ++i)
    for (size_t c = 0; c < 3; ++c)
      cr_expect_eq(memcmp(&e[3 * i + c], &s.e[c][i], sizeof(double)), 0,
                   "cell vector (%zu, %zu) differs in %s: %.17g vs %.17g", i, c, file,
                   e[3 * i + c], s.e[c][i]);
  free(doc);
}

Test(io_snapshot, vti_ascii_round_trip) { check_round_trip(GM_VTI_ASCII, "a.vti"); }
Test(io_snapshot, vti_base64_round_trip) { check_round_trip(GM_VTI_BASE64, "b.vti"); }
Test(io_snapshot, vti_appended_round_trip) { check_round_trip(GM_VTI_APPENDED, "c.vti"); }

Test(io_snapshot, vti_two_dimensional_image_is_flat) {
  double v[6] = {1, 2, 3, 4, 5, 6};
  gm_image im = {2, {3, 2, 99}, {0, 0, 0.5}, {1, 1, -7}}; /* axis 2 ignored */
  gm_image_array a = {"Hz", GM_IMAGE_CELL, 1, {v, NULL, NULL}};
  cr_assert_eq(gm_image_cell_count(&im), 6);
  cr_assert_eq(gm_image_point_count(&im), 12);
  gm_error err = {{0}};
  cr_assert_eq(gm_vti_write(in_dir("f.vti"), &im, &a, 1, 0.0, GM_VTI_BASE64, &err), GM_OK, "%s",
               err.message);
  char *doc = slurp(in_dir("f.vti"), NULL);
  cr_assert_not_null(strstr(doc, "WholeExtent=\"0 3 0 2 0 0\""));
  cr_assert_not_null(strstr(doc, "Spacing=\"1 1 1\""));
  double back[6];
  read_vti_array(doc, "CellData", "Hz", back, 6);
  cr_expect_eq(memcmp(back, v, sizeof v), 0);
  free(doc);
}

Test(io_snapshot, bad_snapshots_are_errors_with_messages) {
  double v[8] = {0};
  gm_image good = {1, {8, 0, 0}, {0, 0, 0}, {0.1, 0, 0}};
  gm_image_array a = {"u", GM_IMAGE_CELL, 1, {v, NULL, NULL}};
  gm_error err = {{0}};
  gm_image bad = good;
  bad.dim = 0;
  cr_expect_eq(gm_vti_write(in_dir("x.vti"), &bad, &a, 1, 0, GM_VTI_ASCII, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "dimension 0") != NULL, "%s", err.message);
  bad = good;
  bad.n_cells[0] = 0;
  cr_expect_eq(gm_vti_write(in_dir("x.vti"), &bad, &a, 1, 0, GM_VTI_ASCII, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "no cells along axis 0") != NULL, "%s", err.message);
  bad = good;
  bad.spacing[0] = -1;
  cr_expect_eq(gm_vti_write(in_dir("x.vti"), &bad, &a, 1, 0, GM_VTI_ASCII, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "spacing") != NULL, "%s", err.message);
  gm_image_array b = a;
  b.name = "a<b";
  cr_expect_eq(gm_vti_write(in_dir("x.vti"), &good, &b, 1, 0, GM_VTI_ASCII, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "'a<b'") != NULL, "%s", err.message);
  b = a;
  b.n_components = 2;
  cr_expect_eq(gm_vti_write(in_dir("x.vti"), &good, &b, 1, 0, GM_VTI_ASCII, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "component 1 is NULL") != NULL, "%s", err.message);
  gm_image_array two[2] = {a, a};
  cr_expect_eq(gm_vti_write(in_dir("x.vti"), &good, two, 2, 0, GM_VTI_ASCII, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "two arrays named 'u'") != NULL, "%s", err.message);
  cr_expect_eq(gm_vti_write(in_dir("x.vti"), &good, &a, 1, 0, (gm_vti_encoding)7, &err),
               GM_EINVAL);
  cr_expect_eq(gm_vti_write("/nonexistent-dir/x.vti", &good, &a, 1, 0, GM_VTI_ASCII, &err),
               GM_EIO);
  cr_expect(strstr(err.message, "/nonexistent-dir/x.vti") != NULL, "%s", err.message);
  cr_expect_eq(gm_hdf5_write("/nonexistent-dir/x.h5", &good, &a, 1, 0, &err),
               gm_hdf5_available() ? GM_EIO : GM_EUNSUPPORTED);
  cr_expect(err.message[0] != '\0');
  struct stat st;
  cr_expect_neq(stat(in_dir("x.vti"), &st), 0, "no file is left by a rejected snapshot");
}

#if GM_TEST_HDF5
static void read_attr(hid_t file, const char *name, hid_t type, void *out) {
  hid_t a = H5Aopen(file, name, H5P_DEFAULT);
  cr_assert_geq(a, 0, "attribute %s", name);
  cr_assert_geq(H5Aread(a, type, out), 0);
  H5Aclose(a);
}

Test(io_snapshot, hdf5_round_trip) {
  cr_assert(gm_hdf5_available());
  static snapshot s;
  make_snapshot(&s);
  gm_error err = {{0}};
  cr_assert_eq(gm_hdf5_write(in_dir("s.h5"), &s.image, s.arrays, 2, 2.5, &err), GM_OK, "%s",
               err.message);
  hid_t f = H5Fopen(in_dir("s.h5"), H5F_ACC_RDONLY, H5P_DEFAULT);
  cr_assert_geq(f, 0);
  double t, o[3], h[3];
  unsigned long long n[3];
  read_attr(f, "time", H5T_NATIVE_DOUBLE, &t);
  read_attr(f, "origin", H5T_NATIVE_DOUBLE, o);
  read_attr(f, "spacing", H5T_NATIVE_DOUBLE, h);
  read_attr(f, "n_cells", H5T_NATIVE_ULLONG, n);
  cr_expect_eq(t, 2.5);
  for (int a = 0; a < 3; ++a) {
    cr_expect_eq(o[a], s.image.origin[a]);
    cr_expect_eq(h[a], s.image.spacing[a]);
    cr_expect_eq(n[a], s.image.n_cells[a]);
  }
  hid_t d = H5Dopen2(f, "/cell/E", H5P_DEFAULT);
  cr_assert_geq(d, 0);
  hid_t sp = H5Dget_space(d);
  hsize_t dims[4];
  cr_assert_eq(H5Sget_simple_extent_ndims(sp), 4);
  H5Sget_simple_extent_dims(sp, dims, NULL);
  cr_expect(dims[0] == NZ && dims[1] == NY && dims[2] == NX && dims[3] == 3);
  static double e[NCELLS * 3];
  cr_assert_geq(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, e), 0);
  for (size_t i = 0; i < NCELLS; ++i)
    for (size_t c = 0; c < 3; ++c)
      cr_expect_eq(memcmp(&e[3 * i + c], &s.e[c][i], sizeof(double)), 0, "E(%zu,%zu)", i, c);
  H5Sclose(sp);
  H5Dclose(d);
  d = H5Dopen2(f, "/point/phi", H5P_DEFAULT);
  cr_assert_geq(d, 0);
  sp = H5Dget_space(d);
  cr_assert_eq(H5Sget_simple_extent_ndims(sp), 3);
  H5Sget_simple_extent_dims(sp, dims, NULL);
  cr_expect(dims[0] == NZ + 1 && dims[1] == NY + 1 && dims[2] == NX + 1);
  static double p[NPOINTS];
  cr_assert_geq(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, p), 0);
  cr_expect_eq(memcmp(p, s.p, sizeof p), 0);
  H5Sclose(sp);
  H5Dclose(d);
  H5Fclose(f);
}
#endif

/* ---- probe CSV ----------------------------------------------------------------------------- */

Test(io_snapshot, probe_csv_whole_rows_exact_values) {
  const char *names[] = {"Ez(0.5,0.5)", "flux \"x\"", "energy"};
  gm_probe_csv *w = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_probe_csv_create(in_dir("p.csv"), 3, names, &w, &err), GM_OK, "%s",
               err.message);
  gm_probe_csv_set_flush(w, 7);
  double v[3];
  for (size_t n = 0; n < 1000; ++n) {
    v[0] = sin(0.1 * (double)n);
    v[1] = -1.0 / (double)(n + 1);
    v[2] = 1e300 * (double)n;
    cr_assert_eq(gm_probe_csv_write(w, 0.01 * (double)n, v), GM_OK);
    if (n == 699) {
      /* 700 rows = 100 flushes of 7: the file holds exactly those rows, each whole */
      char *text = slurp(in_dir("p.csv"), NULL);
      size_t lines = 0;
      for (char *c = text; *c; ++c) lines += *c == '\n';
      cr_expect_eq(lines, 701);
      cr_expect_eq(text[strlen(text) - 1], '\n');
      free(text);
    }
  }
  cr_expect_eq(gm_probe_csv_rows(w), 1000);
  cr_expect_eq(gm_probe_csv_columns(w), 3);
  gm_probe_csv_free(w);
  char *text = slurp(in_dir("p.csv"), NULL);
  cr_assert(strncmp(text, "t,\"Ez(0.5,0.5)\",\"flux \"\"x\"\"\",energy\n", 35) == 0, "%.60s", text);
  char *line = strchr(text, '\n') + 1;
  for (size_t n = 0; n < 1000; ++n) {
    char *end;
    double t = strtod(line, &end);
    cr_assert_eq(t, 0.01 * (double)n);
    double x0 = strtod(end + 1, &end), x1 = strtod(end + 1, &end), x2 = strtod(end + 1, &end);
    cr_assert_eq(x0, sin(0.1 * (double)n), "row %zu", n);
    cr_assert_eq(x1, -1.0 / (double)(n + 1));
    cr_assert_eq(x2, 1e300 * (double)n);
    cr_assert_eq(*end, '\n');
    line = end + 1;
  }
  cr_expect_eq(*line, '\0');
  free(text);
}

Test(io_snapshot, probe_csv_bad_input) {
  gm_probe_csv *w = NULL;
  gm_error err = {{0}};
  const char *names[] = {"a", ""};
  cr_expect_eq(gm_probe_csv_create(in_dir("q.csv"), 2, names, &w, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "column 1 has no name") != NULL, "%s", err.message);
  cr_expect_null(w);
  cr_expect_eq(gm_probe_csv_create("/nonexistent-dir/q.csv", 1, names, &w, &err), GM_EIO);
  cr_expect(strstr(err.message, "/nonexistent-dir/q.csv") != NULL, "%s", err.message);
  cr_expect_eq(gm_probe_csv_create("", 1, names, &w, &err), GM_EINVAL);
  gm_probe_csv_free(NULL);
  /* /dev/full accepts the open and fails the write: the error says so at the flush */
  if (access("/dev/full", W_OK) == 0) {
    cr_assert_eq(gm_probe_csv_create("/dev/full", 1, names, &w, &err), GM_EIO);
  }
}

/* ---- snapshots of the Yee solver ------------------------------------------------------------ */

static double linear(void *ctx, const double x[3]) {
  const double *c = ctx;
  return c[0] + c[1] * x[0] + c[2] * x[1] + c[3] * x[2];
}

/* On interior cells (those whose edges and faces are all off the walls) the cell average of a
 * linear field is its value at the cell centre: checked for every component, 3-D and 2-D. */
Test(io_snapshot, yee_cell_average_of_linear_fields) {
  const gm_yee_dim dims[] = {GM_YEE_3D, GM_YEE_2D_TE, GM_YEE_2D_TM, GM_YEE_1D};
  for (size_t d = 0; d < 4; ++d) {
    gm_yee_grid g = {dims[d], {6, 5, 4}, {0.5, 0.25, 2.0}, {1.0, -2.0, 3.0}};
    size_t axes = gm_yee_dim_axes(dims[d]);
    gm_yee *s = NULL;
    gm_error err = {{0}};
    cr_assert_eq(gm_yee_create(&g, NULL, NULL, &s, &err), GM_OK, "%s", err.message);
    size_t n[3] = {6, axes > 1 ? 5 : 1, axes > 2 ? 4 : 1};
    double *avg = malloc(n[0] * n[1] * n[2] * sizeof *avg);
    for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
      if (!gm_yee_dim_has(dims[d], (gm_yee_component)c)) {
        cr_expect_eq(gm_yee_cell_average(s, (gm_yee_component)c, 0, avg), GM_EINVAL);
        continue;
      }
      double coef[4] = {0.3 + c, 1.5, -0.75, 0.125 * c};
      cr_assert_eq(gm_yee_set_field_fn(s, (gm_yee_component)c, 0, linear, coef), GM_OK);
      cr_assert_eq(gm_yee_cell_average(s, (gm_yee_component)c, 0, avg), GM_OK);
      for (size_t k = 0; k < n[2]; ++k)
        for (size_t j = 0; j < n[1]; ++j)
          for (size_t i = 0; i < n[0]; ++i) {
            size_t ijk[3] = {i, j, k};
            int interior = 1;
            double x[3] = {0, 0, 0};
            for (size_t a = 0; a < 3; ++a) {
              if (a < axes) {
                interior &= ijk[a] > 0 && ijk[a] + 1 < n[a];
                x[a] = g.origin[a] + ((double)ijk[a] + 0.5) * g.h[a];
              } else {
                x[a] = 0.0; /* absent axes: no variation, the location's coordinate is 0 */
              }
            }
            if (!interior) continue;
            double want = linear(coef, x);
            cr_expect(fabs(avg[i + n[0] * (j + n[1] * k)] - want) < 1e-13 * (1 + fabs(want)),
                      "dim %d, %s, cell (%zu,%zu,%zu): %.17g, want %.17g", (int)dims[d],
                      gm_yee_component_name((gm_yee_component)c), i, j, k,
                      avg[i + n[0] * (j + n[1] * k)], want);
          }
    }
    cr_expect_eq(gm_yee_cell_average(s, GM_EX, 1, avg), GM_EINVAL, "real fields have no part 1");
    free(avg);
    gm_yee_free(s);
  }
}

Test(io_snapshot, yee_writer_files_collection_and_values) {
  gm_yee_grid g = {GM_YEE_3D, {5, 4, 3}, {0.2, 0.25, 1.0 / 3.0}, {0, 0, 0}};
  gm_yee_materials *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_materials_create(&g, &m, &err), GM_OK, "%s", err.message);
  gm_medium glass = {3.0, 1.0, 0.0};
  double centre[3] = {0.5, 0.5, 0.5};
  cr_assert_eq(gm_yee_paint_sphere(m, centre, 0.35, &glass), GM_OK);
  gm_yee *s = NULL;
  cr_assert_eq(gm_yee_create(&g, m, NULL, &s, &err), GM_OK, "%s", err.message);
  double coef[4] = {1, 2, 3, 4};
  cr_assert_eq(gm_yee_set_field_fn(s, GM_EY, 0, linear, coef), GM_OK);
  cr_assert_eq(gm_yee_set_field_fn(s, GM_HZ, 0, linear, coef), GM_OK);

  unsigned formats = GM_SNAPSHOT_VTI | (gm_hdf5_available() ? GM_SNAPSHOT_HDF5 : 0);
  gm_yee_writer *w = NULL;
  cr_assert_eq(gm_yee_writer_create(s, m, in_dir("snap"), formats, GM_VTI_APPENDED, &w, &err),
               GM_OK, "%s", err.message);
  cr_assert_eq(gm_yee_writer_write(w, s), GM_OK, "%s", gm_yee_writer_errmsg(w));
  cr_assert_eq(gm_yee_add_observer(s, 2, gm_yee_writer_observe, w), GM_OK);
  cr_assert_eq(gm_yee_advance(s, 4), GM_OK, "%s", gm_yee_errmsg(s)); /* steps 0 (again), 2, 4 */
  cr_expect_eq(gm_yee_writer_count(w), 3, "step 0 is written once: the writer overwrote it");

  char *pvd = slurp(in_dir("snap.pvd"), NULL);
  cr_expect(strstr(pvd, "<DataSet timestep=\"0\" file=\"snap_000000.vti\"/>") != NULL, "%s", pvd);
  cr_expect(strstr(pvd, "file=\"snap_000004.vti\"") != NULL, "%s", pvd);
  free(pvd);
  if (gm_hdf5_available()) {
    struct stat sb;
    cr_expect_eq(stat(in_dir("snap_000004.h5"), &sb), 0);
  }
  /* the .vti holds what gm_yee_cell_average gives, and the materials */
  char *doc = slurp(in_dir("snap_000004.vti"), NULL);
  enum { NC = 5 * 4 * 3 };
  double e[3 * NC], eps[NC], want[NC];
  cr_assert_eq(read_vti_array(doc, "CellData", "E", e, 3 * NC), 3);
  for (int c = 0; c < 3; ++c) {
    cr_assert_eq(gm_yee_cell_average(s, (gm_yee_component)c, 0, want), GM_OK);
    for (size_t i = 0; i < NC; ++i)
      cr_expect_eq(memcmp(&e[3 * i + (size_t)c], &want[i], sizeof(double)), 0, "E%c of cell %zu",
                   'x' + c, i);
  }
  read_vti_array(doc, "CellData", "epsilon", eps, NC);
  cr_expect_eq(memcmp(eps, gm_yee_materials_epsilon(m), sizeof eps), 0);
  double t = NAN;
  cr_assert_not_null(strstr(doc, "Name=\"TimeValue\""));
  sscanf(strstr(strstr(doc, "Name=\"TimeValue\""), ">") + 1, "%lf", &t);
  cr_expect_float_eq(t, 4 * gm_yee_dt(s), 1e-15, "the time of H");
  free(doc);

  /* bad writers */
  gm_yee_writer *bad = NULL;
  cr_expect_eq(gm_yee_writer_create(s, NULL, in_dir("x"), 0, GM_VTI_ASCII, &bad, &err), GM_EINVAL);
  cr_expect_eq(gm_yee_writer_create(s, NULL, "", GM_SNAPSHOT_VTI, GM_VTI_ASCII, &bad, &err),
               GM_EINVAL);
  gm_yee_grid other = g;
  other.n[0] = 6;
  gm_yee_materials *m2 = NULL;
  cr_assert_eq(gm_yee_materials_create(&other, &m2, &err), GM_OK);
  cr_expect_eq(gm_yee_writer_create(s, m2, in_dir("x"), GM_SNAPSHOT_VTI, GM_VTI_ASCII, &bad, &err),
               GM_EINVAL);
  cr_expect(strstr(err.message, "materials have 72 cells, the grid 60") != NULL, "%s",
            err.message);
  cr_expect_null(bad);
  gm_yee_writer *nowhere = NULL;
  cr_assert_eq(gm_yee_writer_create(s, NULL, "/nonexistent-dir/snap", GM_SNAPSHOT_VTI,
                                    GM_VTI_ASCII, &nowhere, &err), GM_OK);
  cr_expect_eq(gm_yee_writer_write(nowhere, s), GM_EIO);
  cr_expect(strstr(gm_yee_writer_errmsg(nowhere), "/nonexistent-dir/snap_000004.vti") != NULL,
            "%s", gm_yee_writer_errmsg(nowhere));
  gm_yee_writer_free(nowhere);
  gm_yee_writer_free(NULL);
  gm_yee_materials_free(m2);
  gm_yee_writer_free(w);
  gm_yee_free(s);
  gm_yee_materials_free(m);
}
