/* VTK XML ImageData (.vti) writer: Float64 point and cell data, ASCII, inline base64 or raw
 * appended binary.
 *
 * Format facts (VTK file-format documentation, "VTK XML Formats"): with header_type="UInt64"
 * (file version 1.0) every binary block is preceded by its size in bytes as a UInt64; inline
 * base64 encodes that header and the data as two separate base64 runs (each padded); the
 * appended section starts after a '_' and each DataArray's offset counts bytes from there;
 * vector tuples are interleaved (x0 y0 z0 x1 ...). Binary data are in the byte order the
 * VTKFile element declares, which is this machine's. */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/io.h"
#include "io/image_internal.h"

static int little_endian(void) {
  const uint16_t one = 1;
  unsigned char b;
  memcpy(&b, &one, 1);
  return b == 1;
}

/* ---- base64 (RFC 4648 alphabet, '=' padding), streamed through a FILE ---------------- */

typedef struct b64 {
  FILE *f;
  unsigned char carry[3];
  size_t n_carry;
} b64;

static const char b64_alphabet[] =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

static void b64_emit(b64 *e, const unsigned char *in, size_t n) {
  char out[4];
  out[0] = b64_alphabet[in[0] >> 2];
  out[1] = b64_alphabet[((in[0] & 3u) << 4) | (n > 1 ? in[1] >> 4 : 0)];
  out[2] = n > 1 ? b64_alphabet[((in[1] & 15u) << 2) | (n > 2 ? in[2] >> 6 : 0)] : '=';
  out[3] = n > 2 ? b64_alphabet[in[2] & 63u] : '=';
  fwrite(out, 1, 4, e->f);
}

static void b64_put(b64 *e, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t i = 0; i < n; ++i) {
    e->carry[e->n_carry++] = p[i];
    if (e->n_carry == 3) {
      b64_emit(e, e->carry, 3);
      e->n_carry = 0;
    }
  }
}

/* End one base64 run: pad the last group. */
static void b64_finish(b64 *e) {
  if (e->n_carry > 0) b64_emit(e, e->carry, e->n_carry);
  e->n_carry = 0;
}

/* ---- the document ---------------------------------------------------------------------- */

typedef struct vti_writer {
  FILE *f;
  const gm_image *image;
  gm_vti_encoding encoding;
  uint64_t appended_offset; /* bytes of the appended section so far */
} vti_writer;

static uint64_t array_bytes(const gm_image *im, const gm_image_array *a) {
  return (uint64_t)gm_image_array_count(im, a) * a->n_components * sizeof(double);
}

/* Values of tuple i, component c: arrays hold one pointer per component. */
static double value_at(const gm_image_array *a, size_t i, size_t c) { return a->component[c][i]; }

static void write_ascii_values(FILE *f, const gm_image *im, const gm_image_array *a) {
  size_t n = gm_image_array_count(im, a);
  size_t per_line = a->n_components == 1 ? 6 : a->n_components;
  size_t k = 0;
  for (size_t i = 0; i < n; ++i)
    for (size_t c = 0; c < a->n_components; ++c) {
      fprintf(f, "%.17g", value_at(a, i, c));
      fputc(++k % per_line == 0 ? '\n' : ' ', f);
    }
  if (k % per_line != 0) fputc('\n', f);
}

/* The tuples interleaved, written through put (raw fwrite or base64) a block at a time. */
typedef void (*put_fn)(void *ctx, const void *data, size_t n);

static void put_values(const gm_image *im, const gm_image_array *a, put_fn put, void *ctx) {
  enum { BLOCK = 512 };
  double buf[BLOCK * GM_IMAGE_MAX_COMPONENTS];
  size_t n = gm_image_array_count(im, a);
  for (size_t start = 0; start < n; start += BLOCK) {
    size_t m = n - start < BLOCK ? n - start : BLOCK;
    for (size_t i = 0; i < m; ++i)
      for (size_t c = 0; c < a->n_components; ++c)
        buf[i * a->n_components + c] = value_at(a, start + i, c);
    put(ctx, buf, m * a->n_components * sizeof(double));
  }
}

static void put_raw(void *ctx, const void *data, size_t n) { fwrite(data, 1, n, ctx); }
static void put_b64(void *ctx, const void *data, size_t n) { b64_put(ctx, data, n); }

static void write_data_array(vti_writer *w, const gm_image_array *a) {
  static const char *const formats[] = {"ascii", "binary", "appended"};
  fprintf(w->f, "        <DataArray type=\"Float64\" Name=\"%s\" NumberOfComponents=\"%zu\" "
          "format=\"%s\"", a->name, a->n_components, formats[w->encoding]);
  if (w->encoding == GM_VTI_APPENDED) {
    fprintf(w->f, " offset=\"%llu\"/>\n", (unsigned long long)w->appended_offset);
    w->appended_offset += sizeof(uint64_t) + array_bytes(w->image, a);
    return;
  }
  fputs(">\n", w->f);
  if (w->encoding == GM_VTI_ASCII) {
    write_ascii_values(w->f, w->image, a);
  } else {
    b64 e = {w->f, {0}, 0};
    uint64_t header = array_bytes(w->image, a);
    b64_put(&e, &header, sizeof header);
    b64_finish(&e);
    put_values(w->image, a, put_b64, &e);
    b64_finish(&e);
    fputc('\n', w->f);
  }
  fputs("        </DataArray>\n", w->f);
}

static void write_section(vti_writer *w, const char *tag, gm_image_centering centering,
                          const gm_image_array *arrays, size_t n_arrays) {
  fprintf(w->f, "      <%s>\n", tag);
  for (size_t k = 0; k < n_arrays; ++k)
    if (arrays[k].centering == centering) write_data_array(w, &arrays[k]);
  fprintf(w->f, "      </%s>\n", tag);
}

static void write_document(vti_writer *w, const gm_image_array *arrays, size_t n_arrays,
                           double time) {
  const gm_image *im = w->image;
  FILE *f = w->f;
  char extent[128];
  snprintf(extent, sizeof extent, "0 %zu 0 %zu 0 %zu", gm_image_extent(im, 0),
           gm_image_extent(im, 1), gm_image_extent(im, 2));
  double spacing[3];
  for (size_t a = 0; a < 3; ++a) spacing[a] = a < im->dim ? im->spacing[a] : 1.0;
  fprintf(f, "<?xml version=\"1.0\"?>\n"
          "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"%s\" header_type=\"UInt64\">\n",
          little_endian() ? "LittleEndian" : "BigEndian");
  fprintf(f, "  <ImageData WholeExtent=\"%s\" Origin=\"%.17g %.17g %.17g\" "
          "Spacing=\"%.17g %.17g %.17g\">\n", extent, im->origin[0], im->origin[1],
          im->origin[2], spacing[0], spacing[1], spacing[2]);
  fprintf(f, "    <FieldData>\n"
          "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
          "format=\"ascii\">%.17g</DataArray>\n"
          "    </FieldData>\n", time);
  fprintf(f, "    <Piece Extent=\"%s\">\n", extent);
  write_section(w, "PointData", GM_IMAGE_POINT, arrays, n_arrays);
  write_section(w, "CellData", GM_IMAGE_CELL, arrays, n_arrays);
  fputs("    </Piece>\n  </ImageData>\n", f);
  if (w->encoding == GM_VTI_APPENDED) {
    fputs("  <AppendedData encoding=\"raw\">\n   _", f);
    /* The same order as the offsets above: point arrays, then cell arrays. */
    for (int pass = 0; pass < 2; ++pass) {
      gm_image_centering c = pass == 0 ? GM_IMAGE_POINT : GM_IMAGE_CELL;
      for (size_t k = 0; k < n_arrays; ++k) {
        if (arrays[k].centering != c) continue;
        uint64_t header = array_bytes(im, &arrays[k]);
        fwrite(&header, sizeof header, 1, f);
        put_values(im, &arrays[k], put_raw, f);
      }
    }
    fputs("\n  </AppendedData>\n", f);
  }
  fputs("</VTKFile>\n", f);
}

gm_status gm_vti_write(const char *path, const gm_image *image, const gm_image_array *arrays,
                       size_t n_arrays, double time, gm_vti_encoding encoding, gm_error *err) {
  if (path == NULL || path[0] == '\0') return gm_error_set(err, GM_EINVAL, "vti: no file name");
  if (encoding != GM_VTI_ASCII && encoding != GM_VTI_BASE64 && encoding != GM_VTI_APPENDED)
    return gm_error_set(err, GM_EINVAL, "vti: unknown encoding %d", (int)encoding);
  gm_status st = gm_image_validate(image, arrays, n_arrays, err);
  if (st != GM_OK) return st;
  FILE *f = fopen(path, encoding == GM_VTI_APPENDED ? "wb" : "w");
  if (f == NULL)
    return gm_error_set(err, GM_EIO, "cannot open '%s' for writing: %s", path, strerror(errno));
  vti_writer w = {f, image, encoding, 0};
  write_document(&w, arrays, n_arrays, time);
  int failed = ferror(f);
  int saved = errno;
  if (fclose(f) != 0 && !failed) {
    failed = 1;
    saved = errno;
  }
  if (failed)
    return gm_error_set(err, GM_EIO, "cannot write '%s': %s", path, strerror(saved));
  return GM_OK;
}
