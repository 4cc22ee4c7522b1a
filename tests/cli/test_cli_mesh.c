/* geomint mesh info / mesh poisson: documented output and JSON on the Gmsh and OFF files in
 * tests/data, the Poisson error and its decrease under refinement, and exit statuses for bad
 * files (1, with the line number) and bad arguments (2). */
#include <criterion/criterion.h>
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cJSON.h>

#include "geomint/mesh.h"

#include "cli/cli_harness.h"

TestSuite(cli_mesh, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

static double json_at(const cJSON *o, const char *key, int i) {
  const cJSON *a = cJSON_GetObjectItemCaseSensitive(o, key);
  cr_assert_not_null(a, "no key %s", key);
  if (i < 0) return a->valuedouble;
  const cJSON *e = cJSON_GetArrayItem(a, i);
  cr_assert_not_null(e, "%s[%d]", key, i);
  return e->valuedouble;
}

Test(cli_mesh, info_json_on_gmsh_files) {
  const char *files[] = {"square_v22.msh", "square_v41.msh"};
  for (int f = 0; f < 2; ++f) {
    run_output r = run_cli("mesh info '%s/tests/data/%s' --json", GM_SOURCE_DIR, files[f]);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cJSON *o = parse_json(r.out);
    cr_expect_eq(json_at(o, "dim", -1), 2);
    cr_expect_eq(json_at(o, "embedding_dim", -1), 2);
    cr_expect_eq(json_at(o, "counts", 0), 30);
    cr_expect_eq(json_at(o, "counts", 1), 71);
    cr_expect_eq(json_at(o, "counts", 2), 42);
    cr_expect_eq(json_at(o, "euler_characteristic", -1), 1);
    cr_expect_eq(json_at(o, "betti", 0), 1);
    cr_expect_eq(json_at(o, "betti", 1), 0);
    cr_expect_eq(json_at(o, "boundary_counts", 1), 16);
    cr_expect_eq(json_at(o, "negative_duals", 1), 0);
    cr_expect_gt(json_at(o, "hodge_star_min", 1), 0.1);
    cr_expect_lt(json_at(o, "hodge_star_max", 1), 1.1);
    cJSON_Delete(o);
    run_output_free(&r);
  }
  run_output r = run_cli("mesh info '%s/tests/data/cube_v41.msh' --json", GM_SOURCE_DIR);
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_eq(json_at(o, "counts", 0), 339);
  cr_expect_eq(json_at(o, "counts", 3), 1125);
  cr_expect_eq(json_at(o, "euler_characteristic", -1), 1);
  cr_expect_eq(json_at(o, "betti", 2), 0);
  cr_expect_eq(json_at(o, "inverted", -1), 0);
  /* a Delaunay-ish Gmsh tetrahedral mesh is not well-centred: reported, not hidden */
  cr_expect_gt(json_at(o, "not_well_centred", -1), 100);
  cr_expect_gt(json_at(o, "negative_duals", 2), 0);
  cJSON_Delete(o);
  run_output_free(&r);
}

Test(cli_mesh, info_table) {
  run_output r = run_cli("mesh info '%s/tests/data/square_v41.msh'", GM_SOURCE_DIR);
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect(strstr(r.out, "Euler characteristic         1\n") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "Betti numbers                1 0 0\n") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "not well-centred cells       0\n") != NULL, "%s", r.out);
  run_output_free(&r);
}

static int write_rect(const char *path, size_t n);

static double poisson_error(const char *file) {
  run_output r = run_cli("mesh poisson '%s'", file);
  cr_assert_eq(r.status, 0, "%s", r.err);
  const char *p = strstr(r.out, "max error");
  cr_assert_not_null(p, "%s", r.out);
  double e = strtod(p + strlen("max error"), NULL);
  run_output_free(&r);
  return e;
}

/* Structured meshes written as OFF by the library: the error falls at second order. */
Test(cli_mesh, poisson_error_falls_at_second_order) {
  char a[512], b[512];
  snprintf(a, sizeof a, "%s/coarse.off", tmpdir);
  snprintf(b, sizeof b, "%s/fine.off", tmpdir);
  cr_assert_eq(write_rect(a, 8), 0);
  cr_assert_eq(write_rect(b, 16), 0);
  double e1 = poisson_error(a), e2 = poisson_error(b);
  double rate = log2(e1 / e2);
  cr_expect(rate > 1.8 && rate < 2.3, "errors %.3g, %.3g: rate %.2f", e1, e2, rate);
  run_output r = run_cli("mesh poisson '%s' --out fine.vtu", b);
  cr_assert_eq(r.status, 0, "%s", r.err);
  char vtu[512];
  snprintf(vtu, sizeof vtu, "%s/fine.vtu", tmpdir);
  FILE *f = fopen(vtu, "r");
  cr_assert_not_null(f);
  char *text = read_stream(f);
  fclose(f);
  cr_expect(strstr(text, "Name=\"u_h\"") && strstr(text, "Name=\"error\""));
  cr_expect(strstr(text, "NumberOfPoints=\"289\" NumberOfCells=\"512\"") != NULL);
  free(text);
  run_output_free(&r);
}

Test(cli_mesh, bad_files_and_arguments) {
  char path[512];
  snprintf(path, sizeof path, "%s/bad.msh", tmpdir);
  FILE *f = fopen(path, "w");
  fputs("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n"
        "$Elements\n1\n1 2 2 0 0 1 2 9\n$EndElements\n", f);
  fclose(f);
  run_output r = run_cli("mesh info bad.msh");
  cr_expect_eq(r.status, 2); /* a bad file is bad input */
  cr_expect(strstr(r.err, "line 12") && strstr(r.err, "node 9"), "%s", r.err);
  run_output_free(&r);
  r = run_cli("mesh info missing.off");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "cannot open") != NULL, "%s", r.err);
  run_output_free(&r);
  r = run_cli("mesh info");
  cr_expect_eq(r.status, 2);
  run_output_free(&r);
  r = run_cli("mesh frobnicate x.msh");
  cr_expect_eq(r.status, 2);
  run_output_free(&r);
  r = run_cli("mesh info x.msh --out y.vtu");
  cr_expect_eq(r.status, 2);
  run_output_free(&r);
}

static int write_rect(const char *path, size_t n) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  if (gm_mesh_rectangle(0, 1, 0, 1, n, n, GM_DIAGONAL_RIGHT, &m, &err) != GM_OK) return 1;
  gm_status st = gm_mesh_write_off(m, path, &err);
  gm_mesh_free(m);
  return st != GM_OK;
}

/* mesh poisson --levels: generated meshes, errors and their rate (issue 17: no rate before).
 * Measured: square n = 4..64, rates 1.998 (max) and 2.001 (L2); cube n = 4..16, 1.944, 2.008. */
Test(cli_mesh, poisson_levels_prints_the_rate) {
  run_output r = run_cli("mesh poisson --levels 5 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_eq(cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(o, "levels")), 5);
  cr_expect(fabs(json_at(o, "rate_max", -1) - 2.0) < 0.05, "%g", json_at(o, "rate_max", -1));
  cr_expect(fabs(json_at(o, "rate_l2", -1) - 2.0) < 0.05, "%g", json_at(o, "rate_l2", -1));
  cJSON_Delete(o);
  run_output_free(&r);
  r = run_cli("mesh poisson --levels 3 --dim 3 --n0 4 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  o = parse_json(r.out);
  cr_expect(fabs(json_at(o, "rate_l2", -1) - 2.0) < 0.1, "%g", json_at(o, "rate_l2", -1));
  cr_expect(fabs(json_at(o, "rate_max", -1) - 2.0) < 0.15, "%g", json_at(o, "rate_max", -1));
  cJSON_Delete(o);
  run_output_free(&r);
  r = run_cli("mesh poisson --levels 3");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect(strstr(r.out, "rate of the finest level: max error 1.98") != NULL, "%s", r.out);
  run_output_free(&r);
  const char *bad[] = {"mesh poisson --levels 1", "mesh poisson --levels 3 --dim 4",
                       "mesh poisson x.off --levels 3", "mesh poisson --levels 3 --out a.vtu",
                       "mesh poisson x.off --dim 3", "mesh poisson --levels 12 --n0 4"};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    r = run_cli("%s", bad[i]);
    cr_expect_eq(r.status, 2, "%s: %d %s", bad[i], r.status, r.err);
    run_output_free(&r);
  }
}
