/* The mesh readers on hostile input (issue 17, item 3 and 4): words are never cut, NUL bytes and
 * control bytes, duplicate nodes named on their own line, an OFF vertex or face short of numbers
 * blamed on its own line, and the size limit of gm_mesh_read_max on a regular file, a stream and
 * /dev/zero. */
#include <criterion/criterion.h>
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
