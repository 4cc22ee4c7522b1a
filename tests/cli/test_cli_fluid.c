/* geomint fluid run CASE.json: help and usage errors (exit 2), malformed cases naming the JSON
 * path, a missing group named, a step above the half step's bound printed, a closed-box run
 * whose JSON and CSV show δω = 0, constant total vorticity and scalar mass, a Gmsh 2.2 file with
 * physical line groups end to end (a case no experiment covers: a moving wall on the left side,
 * inflow at the bottom, outflow at the top), and a run that blows up: exit 1, output kept. */
#include <math.h>

#include "cli_harness.h"
#include "geomint/geomint.h"

TestSuite(cli_fluid, .init = make_tmpdir, .fini = remove_tmpdir);

static void write_text(const char *name, const char *text) {
  FILE *f = fopen(path_in_tmp(name), "w");
  cr_assert_not_null(f);
  fputs(text, f);
  fclose(f);
}

#define BOX_WALLS                                                                      \
  "\"boundaries\": {\"bottom\": {\"type\": \"wall\"}, \"top\": {\"type\": \"wall\"}, " \
  "\"left\": {\"type\": \"wall\"}, \"right\": {\"type\": \"wall\"}}"

Test(cli_fluid, help_and_usage) {
  run_output r = run_cli("fluid --help");
  cr_expect_eq(r.status, 0);
  cr_expect(strstr(r.out, "geomint fluid run CASE.json") != NULL, "%s", r.out);
  run_output_free(&r);
  r = run_cli("--help");
  cr_expect(strstr(r.out, "fluid") != NULL);
  run_output_free(&r);
  const char *bad[] = {"fluid", "fluid bogus", "fluid run", "fluid run a.json b.json",
                       "fluid run a.json --bogus"};
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
    r = run_cli("%s", bad[k]);
    cr_expect_eq(r.status, 2, "'%s' exited %d", bad[k], r.status);
    run_output_free(&r);
  }
  r = run_cli("fluid run missing.json");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "cannot open missing.json: No such file") != NULL, "%s", r.err);
  run_output_free(&r);
  /* the shared input opener (src/core/input_file.c) says what a non-file is */
  r = run_cli("fluid run /tmp");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "/tmp is a directory, not a file") != NULL, "%s", r.err);
  run_output_free(&r);
}

Test(cli_fluid, bad_cases_name_the_culprit) {
  struct {
    const char *text, *needle;
  } cases[] = {
      {"{\"mesh\": {\"rectangle\": {}}, " BOX_WALLS ", \"nu\": -1}", "$.nu: viscosity -1 < 0"},
      {"{\"mesh\": {\"rectangle\": {}}, " BOX_WALLS ", \"kappa\": -2}",
       "$.kappa: diffusivity -2 < 0"},
      {"{\"mesh\": {\"rectangle\": {}}, " BOX_WALLS ", \"dt\": NaN}", "not valid JSON"},
      {"{\"mesh\": {\"rectangle\": {}}, " BOX_WALLS ", \"dt\": 1e999}",
       "$.dt: not a finite number"},
      {"{\"mesh\": {\"rectangle\": {}}, " BOX_WALLS ", \"nuu\": 1}", "$.nuu: unknown key"},
      {"{\"mesh\": {\"rectangle\": {}}, \"boundaries\": {\"bottom\": {\"type\": \"slip\"}}}",
       "$.boundaries.bottom.type: expected"},
      {"{\"mesh\": {\"rectangle\": {}}, \"boundaries\": {\"bottom\": {\"type\": \"wall\"}, "
       "\"inlet\": {\"type\": \"inflow\"}}}",
       "boundary group \"inlet\" (bcs[1]) is not in the mesh"},
      {"{\"mesh\": {\"rectangle\": {}}, \"boundaries\": {\"bottom\": {\"type\": \"wall\"}, "
       "\"top\": {\"type\": \"wall\", \"velocity\": [1, 0]}, \"left\": {\"type\": \"wall\"}, "
       "\"right\": {\"type\": \"wall\"}}, \"dt\": 0.5}",
       "above the bound 0.0625 of the explicit half step (2 h_min/|u|max, h_min = 0.03125)"},
      {"{\"mesh\": \"none.msh\", " BOX_WALLS "}", "none.msh"},
      {"{\"mesh\": {\"rectangle\": {}}, " BOX_WALLS ", \"stress_free_walls\": 1}",
       "$.stress_free_walls: expected true or false"},
      {"{\"mesh\": {\"rectangle\": {}}, " BOX_WALLS ", \"stress_free_walls\": true}",
       "stress_free_walls applies to the midpoint scheme only"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
    write_text("bad.json", cases[k].text);
    run_output r = run_cli("fluid run bad.json");
    cr_expect_eq(r.status, 2, "case %zu exited %d: %s", k, r.status, r.err);
    cr_expect(strstr(r.err, cases[k].needle) != NULL, "case %zu: '%s' lacks '%s'", k, r.err,
              cases[k].needle);
    run_output_free(&r);
  }
}

Test(cli_fluid, closed_box_json_and_files) {
  write_text("box.json", "{\"mesh\": {\"rectangle\": {\"cells\": [12, 0]}}, " BOX_WALLS
                         ", \"nu\": 0.01, \"kappa\": 0.01, \"dt\": 0.02, \"t_end\": 1, "
                         "\"initial\": \"shear_modes\", \"output_every\": 10}");
  run_output r = run_cli("fluid run box.json --out out --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *root = parse_json(r.out);
  cr_expect_eq(json_number(root, "steps"), 50);
  cr_expect_eq(json_number(root, "vtu_files"), 6);
  cr_expect_leq(json_number(root, "div_max"), 1e-14);
  const cJSON *first = cJSON_GetObjectItem(root, "first"),
              *last = cJSON_GetObjectItem(root, "last");
  double m0 = json_number(first, "scalar_mass"), m1 = json_number(last, "scalar_mass");
  /* measured: relative change 1.1e-16; total vorticity 4e-17 */
  cr_expect_leq(fabs(m1 / m0 - 1.0), 1e-14, "scalar mass %.17g -> %.17g", m0, m1);
  cr_expect_leq(fabs(json_number(last, "total_vorticity")), 1e-14);
  cr_expect_lt(json_number(last, "kinetic_energy"), json_number(first, "kinetic_energy"));
  cJSON_Delete(root);
  run_output_free(&r);
  char *csv = read_file(path_in_tmp("out/diagnostics.csv"));
  cr_expect_eq(count_lines(csv), 52, "header + 51 rows");
  cr_expect(strncmp(csv, "step,time,kinetic_energy,enstrophy,total_vorticity,div_max,scalar_mass",
                    70) == 0);
  free(csv);
  char *pvd = read_file(path_in_tmp("out/fluid.pvd"));
  cr_expect(strstr(pvd, "file=\"fluid_000005.vtu\"") != NULL, "%s", pvd);
  free(pvd);
  char *vtu = read_file(path_in_tmp("out/fluid_000005.vtu"));
  cr_expect(strstr(vtu, "Name=\"psi\"") && strstr(vtu, "Name=\"velocity\""));
  free(vtu);
}

/* A Gmsh 2.2 file written from a generated mesh, with physical curves "wall_left" (moving up),
 * "in" (bottom, parabolic), "out" (top), "wall_right". */
static void write_msh(const char *name) {
  gm_mesh *m = NULL;
  gm_fluid_groups *g = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 2, 8, 18, GM_DIAGONAL_ACUTE, &m, &err), GM_OK);
  cr_assert_eq(gm_fluid_groups_rectangle(m, &g, &err), GM_OK, "%s", err.message);
  FILE *f = fopen(path_in_tmp(name), "w");
  cr_assert_not_null(f);
  fprintf(f, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n5\n");
  fprintf(f, "1 1 \"in\"\n1 2 \"wall_right\"\n1 3 \"out\"\n1 4 \"wall_left\"\n2 5 \"fluid\"\n");
  fprintf(f, "$EndPhysicalNames\n$Nodes\n%zu\n", m->n_vertices);
  for (size_t v = 0; v < m->n_vertices; ++v)
    fprintf(f, "%zu %.17g %.17g 0\n", v + 1, m->x[2 * v], m->x[2 * v + 1]);
  fprintf(f, "$EndNodes\n$Elements\n%zu\n", g->n_edges + m->n_cells);
  size_t id = 1;
  for (size_t e = 0; e < g->n_edges; ++e)
    fprintf(f, "%zu 1 2 %zu %zu %zu %zu\n", id++, g->group[e] + 1, g->group[e] + 1,
            g->vertices[2 * e] + 1, g->vertices[2 * e + 1] + 1);
  for (size_t t = 0; t < m->n_cells; ++t)
    fprintf(f, "%zu 2 2 5 1 %zu %zu %zu\n", id++, m->cells[3 * t] + 1, m->cells[3 * t + 1] + 1,
            m->cells[3 * t + 2] + 1);
  fprintf(f, "$EndElements\n");
  fclose(f);
  gm_fluid_groups_free(g);
  gm_mesh_free(m);
}

Test(cli_fluid, gmsh_groups_end_to_end) {
  write_msh("tall.msh");
  write_text("tall.json",
             "{\"mesh\": \"tall.msh\", \"boundaries\": {"
             "\"in\": {\"type\": \"inflow\", \"speed\": 1, \"scalar\": 1},"
             "\"out\": {\"type\": \"outflow\"},"
             "\"wall_left\": {\"type\": \"wall\", \"velocity\": [0, 0.5], \"scalar\": 0},"
             "\"wall_right\": {\"type\": \"wall\", \"scalar\": 0}},"
             "\"nu\": 0.1, \"kappa\": 0.1, \"dt\": 0.02, \"t_end\": 2}");
  run_output r = run_cli("fluid run tall.json --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *root = parse_json(r.out);
  cr_expect_eq(json_number(root, "steps"), 100);
  cr_expect_leq(json_number(root, "div_max"), 1e-14);
  const cJSON *last = cJSON_GetObjectItem(root, "last");
  /* measured at t = 2: kinetic energy 0.498447 (from 6.456 at the impulsive start) */
  double ke = json_number(last, "kinetic_energy");
  cr_expect(ke > 0.49 && ke < 0.51, "kinetic energy %.6g", ke);
  /* Stokes on the dual cells: Σ Γ = ∮ u_t ds = −0.5 · 2 (the left wall moves up, against the
   * counter-clockwise tangent), exact at every step */
  cr_expect_leq(fabs(json_number(last, "total_vorticity") + 1.0), 1e-13);
  /* the scalar enters with the inflow: its mass grows */
  cr_expect_gt(json_number(last, "scalar_mass"), 0.2);
  cJSON_Delete(root);
  run_output_free(&r);
  /* a group of the case that the file lacks is named */
  write_text("tall2.json",
             "{\"mesh\": \"tall.msh\", \"boundaries\": {"
             "\"inlet\": {\"type\": \"inflow\", \"speed\": 1}}}");
  r = run_cli("fluid run tall2.json");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "\"inlet\"") != NULL, "%s", r.err);
  run_output_free(&r);
}

Test(cli_fluid, blow_up_exits_1_and_keeps_output) {
  /* the seed scheme without viscosity at the explicit bound: energy grows until overflow */
  write_text("blow.json",
             "{\"mesh\": {\"rectangle\": {\"cells\": [12, 0]}}, " BOX_WALLS
             ", \"nu\": 0, \"kappa\": 0, \"dt\": 0.044, \"t_end\": 200, "
             "\"initial\": \"shear_modes\", \"amplitude\": 0.3, \"output_every\": 100}");
  run_output r = run_cli("fluid run blow.json --out blow");
  cr_expect_eq(r.status, 1, "%s", r.err);
  cr_expect(strstr(r.err, "output written so far is kept") != NULL, "%s", r.err);
  run_output_free(&r);
  char *csv = read_file(path_in_tmp("blow/diagnostics.csv"));
  cr_expect_gt(count_lines(csv), 1000);
  free(csv);
  char *pvd = read_file(path_in_tmp("blow/fluid.pvd"));
  cr_expect(strstr(pvd, "fluid_000018.vtu") != NULL);
  free(pvd);
}

/* The example case runs as documented: the B14 channel at 96 cells along reaches the Poiseuille
 * kinetic energy ½ · 2π · 8/15 = 1.6755 (measured 1.66799: the entrance region is slower). */
Test(cli_fluid, example_channel_case) {
  run_output r = run_cli("fluid run '%s/examples/fluid_channel.json' --json", GM_SOURCE_DIR);
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *root = parse_json(r.out);
  cr_expect_eq(json_number(root, "steps"), 500);
  cr_expect_leq(json_number(root, "div_max"), 1e-14);
  double ke = json_number(cJSON_GetObjectItem(root, "last"), "kinetic_energy");
  cr_expect(fabs(ke - 1.66799) < 1e-4, "kinetic energy %.6f", ke);
  cJSON_Delete(root);
  run_output_free(&r);
}

/* The inviscid midpoint scheme with stress-free walls from a case file: energy and total
 * vorticity kept (the interior enstrophy is asserted in tests/invariants). */
Test(cli_fluid, midpoint_stress_free_case) {
  write_text("sf.json", "{\"mesh\": {\"rectangle\": {\"cells\": [10, 0]}}, " BOX_WALLS
                        ", \"nu\": 0, \"kappa\": 0.01, \"dt\": 0.02, \"t_end\": 2, "
                        "\"scheme\": \"midpoint\", \"stress_free_walls\": true, "
                        "\"velocity_scale\": 1, \"initial\": \"shear_modes\"}");
  run_output r = run_cli("fluid run sf.json --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *root = parse_json(r.out);
  const cJSON *first = cJSON_GetObjectItem(root, "first"),
              *last = cJSON_GetObjectItem(root, "last");
  double e0 = json_number(first, "kinetic_energy"), e1 = json_number(last, "kinetic_energy");
  double v0 = json_number(first, "total_vorticity"), v1 = json_number(last, "total_vorticity");
  /* measured: energy 5.6e-16 relative, total vorticity 6.6e-17 (the full enstrophy, which counts
   * the wall sheet, moves by 4.1e-6) */
  cr_expect_eq(json_number(root, "steps"), 100);
  cr_expect_leq(fabs(e1 / e0 - 1.0), 1e-14, "energy %.17g -> %.17g", e0, e1);
  cr_expect_leq(fabs(v1 - v0), 1e-14, "total vorticity %.17g -> %.17g", v0, v1);
  cJSON_Delete(root);
  run_output_free(&r);
}
