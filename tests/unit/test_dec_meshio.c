/* Mesh files: the Gmsh 2.2 and 4.1 files in tests/data (made by gmsh 4.8.4 from the .geo files
 * next to them) read to the same mesh; OFF and VTU writers; bad files give GM_EINVAL or
 * GM_EDOMAIN with the line number; the quality report counts defects. */
#include <stdio.h>
#include <string.h>

#include "dec_util.h"

static gm_mesh *read_data(const char *name) {
  char path[512];
  snprintf(path, sizeof path, "%s/tests/data/%s", GM_SOURCE_DIR, name);
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_read(path, &m, &err), GM_OK, "%s", err.message);
  return m;
}

static void expect_same(const gm_mesh *a, const gm_mesh *b) {
  cr_assert_eq(a->N, b->N);
  cr_assert_eq(a->dim, b->dim);
  cr_assert_eq(a->n_vertices, b->n_vertices);
  cr_assert_eq(a->n_cells, b->n_cells);
  for (size_t i = 0; i < a->N * a->n_vertices; ++i) cr_expect_eq(a->x[i], b->x[i]);
  for (size_t i = 0; i < (a->dim + 1) * a->n_cells; ++i) cr_expect_eq(a->cells[i], b->cells[i]);
  for (size_t i = 0; i < a->n_cells; ++i) cr_expect_eq(a->cell_tags[i], b->cell_tags[i]);
}

Test(mesh_io, gmsh_versions_agree) {
  gm_mesh *a = read_data("square_v22.msh"), *b = read_data("square_v41.msh");
  cr_expect_eq(a->N, 2);
  cr_expect_eq(a->dim, 2);
  cr_expect_eq(a->n_vertices, 30);
  cr_expect_eq(a->n_cells, 42);
  cr_expect_eq(a->cell_tags[0], 7); /* Physical Surface("domain", 7) */
  expect_same(a, b);
  gm_complex *cx = test_complex(a);
  cr_expect_eq(gm_complex_euler_characteristic(cx), 1);
  gm_complex_free(cx);
  gm_mesh_free(a), gm_mesh_free(b);
  a = read_data("cube_v22.msh"), b = read_data("cube_v41.msh");
  cr_expect_eq(a->N, 3);
  cr_expect_eq(a->dim, 3);
  cr_expect_eq(a->n_cells, 1125);
  cr_expect_eq(a->cell_tags[0], 3);
  expect_same(a, b);
  gm_mesh_free(a), gm_mesh_free(b);
}

Test(mesh_io, off_round_trip) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_icosphere(2.0, 1, &m, &err), GM_OK);
  char path[] = "/tmp/gm-meshio-XXXXXX";
  int fd = mkstemp(path);
  cr_assert_geq(fd, 0);
  cr_assert_eq(gm_mesh_write_off(m, path, &err), GM_OK, "%s", err.message);
  gm_mesh *r = NULL;
  cr_assert_eq(gm_mesh_read_off(path, &r, &err), GM_OK, "%s", err.message);
  expect_same(m, r);
  gm_mesh_free(r);
  gm_mesh_free(m);
  remove(path);
}

Test(mesh_io, vtu_fields_on_every_degree) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_box(lo, hi, 1, 1, 1, GM_BOX_KUHN, &m, &err), GM_OK);
  gm_complex *cx = test_complex(m);
  double v0[8], v1[19], v3[6], vec[24];
  for (int i = 0; i < 8; ++i) v0[i] = i;
  for (int i = 0; i < 19; ++i) v1[i] = 0.5 * i;
  for (int i = 0; i < 6; ++i) v3[i] = -i;
  for (int i = 0; i < 24; ++i) vec[i] = i;
  cr_assert_eq(gm_complex_count(cx, 1), 19);
  gm_vtu_field f[4] = {{"f", 0, 1, v0}, {"a", 1, 1, v1}, {"rho", 3, 1, v3}, {"X", 0, 3, vec}};
  char path[] = "/tmp/gm-vtu-XXXXXX";
  int fd = mkstemp(path);
  cr_assert_geq(fd, 0);
  cr_assert_eq(gm_vtu_write(path, cx, 4, f, &err), GM_OK, "%s", err.message);
  FILE *fp = fopen(path, "r");
  char buf[65536];
  size_t n = fread(buf, 1, sizeof buf - 1, fp);
  buf[n] = 0;
  fclose(fp);
  cr_expect(strstr(buf, "NumberOfPoints=\"8\" NumberOfCells=\"25\"") != NULL); /* 6 tets + 19 edges */
  cr_expect(strstr(buf, "Name=\"a\"") && strstr(buf, "Name=\"rho\"") && strstr(buf, "NaN"));
  cr_expect(strstr(buf, "NumberOfComponents=\"3\"") != NULL);
  gm_vtu_field bad = {"a<b", 1, 1, v1};
  cr_expect_eq(gm_vtu_write(path, cx, 1, &bad, &err), GM_EINVAL);
  remove(path);
  gm_complex_free(cx);
  gm_mesh_free(m);
}

typedef struct {
  const char *text;
  gm_status status;
  const char *message; /* must occur in the error message */
} bad_file;

static const char *msh_head = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";

Test(mesh_io, bad_files_name_their_line) {
  char buf[1024];
  const bad_file cases[] = {
      /* truncated in $Nodes */
      {"$Nodes\n3\n1 0 0 0\n2 1 0", GM_EINVAL, "line 7: unexpected end of file"},
      /* wrong count: fewer nodes than announced */
      {"$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n", GM_EINVAL, "line 9: expected an integer (node tag), found '$EndNodes'"},
      /* a count larger than the file */
      {"$Nodes\n99999999\n1 0 0 0\n", GM_EINVAL, "line 5: number of nodes 99999999 is larger"},
      /* index out of range */
      {"$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n$Elements\n1\n1 2 0 1 2 4\n$EndElements\n",
       GM_EINVAL, "line 12: element refers to node 4"},
      /* NaN coordinate */
      {"$Nodes\n3\n1 0 0 0\n2 nan 0 0\n3 0 1 0\n$EndNodes\n", GM_EDOMAIN, "line 7: node coordinate is not finite"},
      /* unknown element type */
      {"$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n$Elements\n1\n1 99 0 1 2 3\n$EndElements\n",
       GM_EINVAL, "line 12: unknown element type 99"},
      /* quadrangles are known but not simplices */
      {"$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n$Elements\n1\n1 3 0 1 2 3 4\n$EndElements\n",
       GM_EINVAL, "not a linear simplex"},
      /* missing $EndNodes */
      {"$Nodes\n1\n1 0 0 0\n$Elements\n", GM_EINVAL, "line 7: expected $EndNodes, found '$Elements'"},
      /* garbage integer */
      {"$Nodes\nthree\n", GM_EINVAL, "line 5: expected an integer"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    snprintf(buf, sizeof buf, "%s%s", msh_head, cases[i].text);
    gm_mesh *m = NULL;
    gm_error err = {{0}};
    gm_status st = gm_mesh_parse_msh(buf, strlen(buf), &m, &err);
    cr_expect_eq(st, cases[i].status, "case %zu: status %d (%s)", i, st, err.message);
    cr_expect(strstr(err.message, cases[i].message) != NULL, "case %zu: '%s' lacks '%s'", i,
              err.message, cases[i].message);
    cr_expect_null(m);
    gm_mesh_free(m);
  }
  /* 4.1: block counts disagree with the header */
  const char *v41 =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n"
      "0 1 0\n1 1 0\n$EndNodes\n";
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_expect_eq(gm_mesh_parse_msh(v41, strlen(v41), &m, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "line 6: node blocks hold more nodes") != NULL, "%s", err.message);
  const char *off_cases[][2] = {
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", "line 6: face 0: vertex index 5 out of range"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2 0\n", "line 6: face 0 has 4 vertices"},
      {"OFF\n# comment\n3 1 0\n0 0 0\n1 0 0\n", "line 6: unexpected end of file"},
      {"NOFF\n", "line 1: expected OFF"},
  };
  for (size_t i = 0; i < 4; ++i) {
    cr_expect_eq(gm_mesh_parse_off(off_cases[i][0], strlen(off_cases[i][0]), &m, &err), GM_EINVAL);
    cr_expect(strstr(err.message, off_cases[i][1]) != NULL, "OFF %zu: '%s'", i, err.message);
  }
  /* empty input */
  cr_expect_eq(gm_mesh_parse_msh("", 0, &m, &err), GM_EINVAL);
  cr_expect_eq(gm_mesh_parse_off("", 0, &m, &err), GM_EINVAL);
}

/* Every prefix of a good file is rejected cleanly or read (never a crash). */
Test(mesh_io, every_truncation_is_handled) {
  char path[512];
  snprintf(path, sizeof path, "%s/tests/data/square_v41.msh", GM_SOURCE_DIR);
  FILE *f = fopen(path, "rb");
  cr_assert_not_null(f);
  char buf[8192];
  size_t n = fread(buf, 1, sizeof buf, f);
  fclose(f);
  size_t ok = 0;
  for (size_t len = 0; len < n; len += 7) {
    gm_mesh *m = NULL;
    gm_error err = {{0}};
    gm_status st = gm_mesh_parse_msh(buf, len, &m, &err);
    if (st == GM_OK) ++ok, gm_mesh_free(m);
    else cr_expect(strncmp(err.message, "line ", 5) == 0, "len %zu: %s", len, err.message);
  }
  cr_expect_leq(ok, 2, "only (nearly) complete files read: %zu", ok);
}

Test(mesh_quality, counts_defects) {
  /* three triangles on one edge: non-manifold */
  const double x[] = {0, 0, 1, 0, 0, 1, 0, -1, 1, 1};
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_create(2, 5, 2, 3, &m), GM_OK);
  memcpy(m->x, x, sizeof x);
  const size_t c[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  memcpy(m->cells, c, sizeof c);
  gm_mesh_report r;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_quality(m, &r, &err), GM_OK);
  cr_expect_eq(r.non_manifold, 1);
  cr_expect_eq(r.complex_ok, 0);
  cr_expect(strstr(r.complex_error, "non-manifold") != NULL, "%s", r.complex_error);
  gm_mesh_free(m);
  /* a square with one flat (degenerate) triangle and obtuse ones */
  const double y[] = {0, 0, 1, 0, 2, 0, 1, 0.2};
  cr_assert_eq(gm_mesh_create(2, 4, 2, 3, &m), GM_OK);
  memcpy(m->x, y, sizeof y);
  const size_t d[] = {0, 1, 3, 1, 2, 3, 0, 1, 2};
  memcpy(m->cells, d, sizeof d);
  cr_assert_eq(gm_mesh_quality(m, &r, &err), GM_OK);
  cr_expect_eq(r.degenerate, 1);
  cr_expect_eq(r.not_well_centred, 2);
  cr_expect_eq(r.geometry_ok, 0);
  gm_mesh_free(m);
  /* well-centred mesh: everything clean, stars positive */
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, 4, 4, GM_DIAGONAL_ACUTE, &m, &err), GM_OK);
  cr_assert_eq(gm_mesh_quality(m, &r, &err), GM_OK);
  cr_expect_eq(r.complex_ok, 1);
  cr_expect_eq(r.geometry_ok, 1);
  cr_expect_eq(r.euler_characteristic, 1);
  cr_expect_eq(r.betti[0], 1);
  cr_expect_eq(r.non_manifold + r.degenerate + r.inverted, 0);
  cr_expect_gt(r.star_min[1], 0.0);
  gm_mesh_free(m);
}
