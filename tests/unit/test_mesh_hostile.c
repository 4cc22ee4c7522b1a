/* The mesh readers on hostile input (issue 17, item 3 and 4): words are never cut, NUL bytes and
 * control bytes, duplicate nodes named on their own line, an OFF vertex or face short of numbers
 * blamed on its own line, and the size limit of gm_mesh_read_max on a regular file, a stream and
 * /dev/zero. */
#include <criterion/criterion.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "geomint/mesh.h"

static gm_status parse_off(const char *text, size_t len, gm_mesh **m, gm_error *err) {
  *m = NULL;
  memset(err, 0, sizeof *err);
  return gm_mesh_parse_off(text, len, m, err);
}

#define EXPECT_MESSAGE(err, what) \
  cr_expect(strstr((err).message, what) != NULL, "'%s' lacks '%s'", (err).message, what)

Test(mesh_hostile, long_numbers_are_read_whole_or_refused) {
  /* 0.000…001e81 (86 characters) is 1.0: cut at 63 characters it was 0 */
  char word[200] = "0.";
  for (int i = 0; i < 80; ++i) strcat(word, "0");
  strcat(word, "1e81");
  char text[512];
  snprintf(text, sizeof text, "OFF\n3 1 0\n0 0 0\n%s 0 0\n0 1 0\n3 0 1 2\n", word);
  gm_mesh *m;
  gm_error err;
  cr_assert_eq(parse_off(text, strlen(text), &m, &err), GM_OK, "%s", err.message);
  cr_expect_eq(m->x[m->N * 1 + 0], 1.0, "x = %.17g", m->x[m->N]);
  gm_mesh_free(m);
  /* a word longer than 127 characters is an error, not a different number */
  for (int i = 0; i < 60; ++i) strcat(word, "0");
  snprintf(text, sizeof text, "OFF\n3 1 0\n0 0 0\n%s 0 0\n0 1 0\n3 0 1 2\n", word);
  cr_expect_eq(parse_off(text, strlen(text), &m, &err), GM_EINVAL);
  EXPECT_MESSAGE(err, "line 4: a word longer than 127 characters");
  cr_expect_null(m);
}

Test(mesh_hostile, nul_and_control_bytes) {
  const char off[] = "OFF\n3 1 0\n0 0 0\n1\0005 0 0\n0 1 0\n3 0 1 2\n";
  gm_mesh *m;
  gm_error err;
  cr_expect_eq(parse_off(off, sizeof off - 1, &m, &err), GM_EINVAL);
  EXPECT_MESSAGE(err, "line 4: a NUL byte");
  const char msh[] = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0\000 0 0\n$EndNodes\n";
  memset(&err, 0, sizeof err);
  cr_expect_eq(gm_mesh_parse_msh(msh, sizeof msh - 1, &m, &err), GM_EINVAL);
  EXPECT_MESSAGE(err, "line 6: a NUL byte");
  /* an escape sequence (ESC [ 2 J clears a terminal) is shown as \x1b, never as the byte */
  const char esc[] = "OFF\n3 1 0\n0 0 0\n1\033[2J\a 0 0\n0 1 0\n3 0 1 2\n";
  cr_expect_eq(parse_off(esc, sizeof esc - 1, &m, &err), GM_EINVAL);
  EXPECT_MESSAGE(err, "line 4: expected a number (vertex coordinate), found '1\\x1b[2J\\x07'");
  for (const char *c = err.message; *c; ++c)
    cr_expect((unsigned char)*c >= 0x20 && (unsigned char)*c < 0x7f, "byte %#x in message",
              (unsigned char)*c);
  const char sec[] = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$\x9b" "31m\n";
  cr_expect_eq(gm_mesh_parse_msh(sec, sizeof sec - 1, &m, &err), GM_EINVAL);
  EXPECT_MESSAGE(err, "line 5: unexpected end of file: $End\\x9b31m is missing");
}

Test(mesh_hostile, duplicate_nodes_name_their_lines) {
  /* v2.2: node 2 again on line 8 (the file has 13 lines) */
  const char v22[] = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n"
                     "2 0 1 0\n4 1 1 0\n$EndNodes\n$Elements\n1\n1 2 0 1 2 4\n$EndElements\n";
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_expect_eq(gm_mesh_parse_msh(v22, strlen(v22), &m, &err), GM_EINVAL);
  EXPECT_MESSAGE(err, "line 8: node 2 is defined twice (first on line 7)");
  /* v4.1: tags one per line in a block */
  const char v41[] = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n3\n1\n"
                     "0 0 0\n1 0 0\n0 1 0\n$EndNodes\n$Elements\n1 1 1 1\n2 1 2 1\n1 1 3 1\n"
                     "$EndElements\n";
  memset(&err, 0, sizeof err);
  cr_expect_eq(gm_mesh_parse_msh(v41, strlen(v41), &m, &err), GM_EINVAL);
  EXPECT_MESSAGE(err, "line 9: node 1 is defined twice (first on line 7)");
}

Test(mesh_hostile, off_lines_short_of_numbers) {
  const char *cases[][2] = {
      {"OFF\n3 1 0\n0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "line 3: vertex 0 has 2 coordinates, expected 3"},
      {"OFF\n3 1 0\n0 0 0\n1 # one\n0 1 0\n3 0 1 2\n", "line 4: vertex 1 has 1 coordinate, expected 3"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0 7\n0 1 0\n3 0 1 2\n", "line 4: vertex 1 has more than 3 coordinates"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "line 6: face 0 has 2 vertex indexes, expected 3"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    gm_mesh *m;
    gm_error err;
    cr_expect_eq(parse_off(cases[i][0], strlen(cases[i][0]), &m, &err), GM_EINVAL, "case %zu", i);
    EXPECT_MESSAGE(err, cases[i][1]);
  }
  /* comments and blank lines between vertices still work */
  const char ok[] = "OFF\n# c\n3 1 0\n\n0 0 0 # origin\n1 0 0\n# x\n0 1 0\n3 0 1 2 255 0 0\n";
  gm_mesh *m;
  gm_error err;
  cr_assert_eq(parse_off(ok, strlen(ok), &m, &err), GM_OK, "%s", err.message);
  cr_expect_eq(m->n_cells, 1);
  gm_mesh_free(m);
}

static void write_big_off(const char *path, size_t bytes) {
  FILE *f = fopen(path, "w");
  cr_assert_not_null(f);
  fputs("OFF\n3 1 0\n", f);
  for (size_t n = 0; n < bytes; n += 16) fputs("# padding......\n", f);
  fputs("0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", f);
  fclose(f);
}

Test(mesh_hostile, size_limit) {
  char dir[] = "/tmp/geomint-mesh-hostile-XXXXXX", path[256], fifo[256], cmd[512];
  cr_assert_not_null(mkdtemp(dir));
  snprintf(path, sizeof path, "%s/big.off", dir);
  write_big_off(path, 3 << 20);
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  /* a regular file over the limit is refused before reading; under it, read */
  cr_expect_eq(gm_mesh_read_max(path, (size_t)1 << 20, &m, &err), GM_EIO);
  EXPECT_MESSAGE(err, "more than the limit of 1048576 bytes");
  cr_expect_null(m);
  cr_expect_eq(gm_mesh_read(path, &m, &err), GM_OK, "%s", err.message);
  gm_mesh_free(m);
  /* a stream that never ends stops at the limit */
  snprintf(fifo, sizeof fifo, "%s/stream.off", dir);
  cr_assert_eq(mkfifo(fifo, 0600), 0);
  snprintf(cmd, sizeof cmd, "yes '# endless' > '%s' 2>/dev/null &", fifo);
  cr_assert_eq(system(cmd), 0);
  memset(&err, 0, sizeof err);
  cr_expect_eq(gm_mesh_read_max(fifo, (size_t)1 << 20, &m, &err), GM_EIO);
  EXPECT_MESSAGE(err, "more than the limit of 1048576 bytes");
  /* /dev/zero: the first block holds a NUL byte */
  char zero[256];
  snprintf(zero, sizeof zero, "%s/zero.msh", dir);
  cr_assert_eq(symlink("/dev/zero", zero), 0);
  memset(&err, 0, sizeof err);
  cr_expect_eq(gm_mesh_read(zero, &m, &err), GM_EINVAL);
  EXPECT_MESSAGE(err, "line 1: a NUL byte");
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  cr_expect_eq(system(cmd), 0);
}

/* Quality and Hodge stars of a mesh and of the same mesh scaled by s: every length scales by s,
 * every k-volume by s^k, ⋆_k by s^(n−2k); with s = 2^±330 (2-D) or 2^265 (3-D) the squared
 * lengths of the old code overflowed (negative duals, stars 0). */
static void expect_scaled_report(gm_mesh *m, double s) {
  gm_mesh_report a, b;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_quality(m, &a, &err), GM_OK, "%s", err.message);
  for (size_t i = 0; i < m->n_vertices * m->N; ++i) m->x[i] *= s;
  cr_assert_eq(gm_mesh_quality(m, &b, &err), GM_OK, "%s", err.message);
  const size_t n = m->dim;
  cr_assert(a.geometry_ok && b.geometry_ok, "%s | %s", a.geometry_error, b.geometry_error);
  cr_expect_eq(b.degenerate, a.degenerate);
  cr_expect_eq(b.not_well_centred, a.not_well_centred);
  cr_expect_eq(b.out_of_range, 0);
  cr_expect(fabs(b.shortest_edge / (s * a.shortest_edge) - 1) < 1e-14, "%g", b.shortest_edge);
  cr_expect(fabs(b.longest_edge / (s * a.longest_edge) - 1) < 1e-14, "%g", b.longest_edge);
  cr_expect(fabs(b.max_volume / (pow(s, (double)n) * a.max_volume) - 1) < 1e-14, "%g", b.max_volume);
  for (size_t k = 0; k <= n; ++k) {
    cr_expect_eq(b.negative_duals[k], a.negative_duals[k], "k = %zu", k);
    double f = pow(s, (double)n - 2.0 * (double)k);
    cr_expect(fabs(b.star_max[k] / (f * a.star_max[k]) - 1) < 1e-12, "star %zu: %g vs %g", k,
              b.star_max[k], f * a.star_max[k]);
    if (a.star_min[k] > 0)
      cr_expect(fabs(b.star_min[k] / (f * a.star_min[k]) - 1) < 1e-12, "star %zu min", k);
  }
}

Test(mesh_hostile, quality_is_scale_invariant) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, 4, 4, GM_DIAGONAL_ACUTE, &m, &err), GM_OK);
  expect_scaled_report(m, 0x1p330); /* 2.2e99: powers of two keep right angles exact */
  gm_mesh_free(m);
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, 4, 4, GM_DIAGONAL_ACUTE, &m, &err), GM_OK);
  expect_scaled_report(m, 0x1p-330);
  gm_mesh_free(m);
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_box(lo, hi, 2, 2, 2, GM_BOX_KUHN, &m, &err), GM_OK);
  expect_scaled_report(m, 0x1p265); /* 5.9e79 */
  gm_mesh_free(m);
}

Test(mesh_hostile, volumes_outside_double_are_refused) {
  for (int sign = -1; sign <= 1; sign += 2) {
    const double s = sign > 0 ? 1e160 : 1e-160;
    gm_mesh *m = NULL;
    gm_error err = {{0}};
    cr_assert_eq(gm_mesh_rectangle(0, s, 0, s, 2, 2, GM_DIAGONAL_RIGHT, &m, &err), GM_OK);
    gm_mesh_report r;
    cr_assert_eq(gm_mesh_quality(m, &r, &err), GM_OK);
    cr_expect_eq(r.degenerate, 0, "scale %g", s);
    cr_expect_eq(r.out_of_range, 8);
    cr_expect(fabs(r.shortest_edge / (0.5 * s) - 1) < 1e-15, "%g", r.shortest_edge);
    cr_expect(fabs(r.longest_edge / (sqrt(0.5) * s) - 1) < 1e-15, "%g", r.longest_edge);
    cr_expect_eq(r.geometry_ok, 0);
    cr_expect(strstr(r.geometry_error, "8 cells have volumes outside double precision") != NULL,
              "%s", r.geometry_error);
    gm_mesh_free(m);
  }
}
