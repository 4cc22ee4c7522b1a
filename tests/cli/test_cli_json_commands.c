/* --json of every other command that prints results (issue 26, "JSON everywhere"): each runs on
 * a small input and prints one JSON object (an array for list) that cJSON parses, with the shared
 * vocabulary (wall_s, steps, max_rel_*), every required key present and every number finite.
 * The experiments' commands: test_cli_json_experiments.c. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli_harness.h"
#include "cli/json_vocabulary.h"
#include "geomint/mesh.h"

TestSuite(cli_json_commands, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

#define EX GM_SOURCE_DIR "/examples/"

Test(cli_json_commands, mechanics) {
  static const json_case cases[] = {
      {"run kepler --steps 100 --json", "steps,max_rel_energy_error,wall_s"},
      {"order --method verlet --levels 3 --json", "order,declared_order"},
      {"wp kepler --methods verlet,yoshida-4 --levels 3 --json", "steps,wall_s"},
      {"mimetic circular --no-plot --out m --json", "steps,wall_s"},
      {"reduction j2-satellite --t-end 10 --no-plot --out r --json", "steps,wall_s"},
      {"reduction double-spherical-pendulum --t-end 1 --no-plot --out r --json",
       "steps,max_rel_energy_error_rsprk,wall_s"},
      {"oscillatory work-precision --no-plot --out o --json",
       "rows,largest_h,i_error,best_composition,wall_s"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) check_json_case(&cases[i]);
}

Test(cli_json_commands, fields_and_pde) {
  static const json_case cases[] = {
      {"maxwell e4 --n 8 --out e4 --json", "steps,leapfrog_max_rel_drift,wall_s"},
      {"maxwell run " EX "maxwell_scene.json --out mr --json", "steps,wall_s"},
      {"maxwell mesh --rect 8 --t-end 0.2 --json", "steps,max_rel_plain_energy_deviation,wall_s"},
      {"pde run sine-gordon --T 1 --json", "steps,wall_s"},
      {"pde invariant galilean --no-plot --out pi --json", "steps"},
      {"fluid channel --cells 8 --time 0.05 --json", "steps,wall_s"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) check_json_case(&cases[i]);
}

Test(cli_json_commands, meshes) {
  char *a = path_in_tmp("a.msh"), *b = path_in_tmp("b.msh");
  gm_error err = {{0}};
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, 7, 5, GM_DIAGONAL_ALTERNATE, &m, &err), GM_OK);
  cr_assert_eq(gm_mesh_write_msh(m, a, &err), GM_OK, "%s", err.message);
  gm_mesh_free(m);
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, 11, 13, GM_DIAGONAL_ACUTE, &m, &err), GM_OK);
  cr_assert_eq(gm_mesh_write_msh(m, b, &err), GM_OK, "%s", err.message);
  gm_mesh_free(m);
  const json_case cases[] = {
      {"mesh info " EX "cavity_sphere_1.msh --json", "counts,shortest_edge"},
      {"mesh poisson " EX "cavity_sphere_1.msh --json", "error_max,error_l2,max_rel_error,wall_s"},
      {"mesh poisson --levels 2 --json", "error_max,rate_max"},
      {"mesh refine " EX "cavity_sphere_1.msh --levels 1 --json", "levels,wall_s"},
      {"mesh transfer a.msh b.msh --json", "forward,backward"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) check_json_case(&cases[i]);
}

/* the demo's Kepler table (the field commands' text is not printed with --json) */
Test(cli_json_commands, demo) {
  static const json_case c = {"demo --out d --json",
                              "kepler,steps,max_rel_energy_error,force_evals,wall_s,plots"};
  check_json_case(&c);
}

/* list prints an array: each row an object with its name */
Test(cli_json_commands, list_and_experiments_list) {
  static const char *const commands[] = {"list methods --json", "list problems --json",
                                         "experiments list --json"};
  for (size_t i = 0; i < 3; ++i) {
    run_output r = run_cli("%s", commands[i]);
    cr_expect_eq(r.status, 0, "%s: %s", commands[i], r.err);
    cJSON *a = cJSON_Parse(r.out);
    cr_expect(cJSON_IsArray(a) && cJSON_GetArraySize(a) > 0, "%s", commands[i]);
    const cJSON *row;
    if (cJSON_IsArray(a)) cJSON_ArrayForEach(row, a) json_walk(row, commands[i]);
    cJSON_Delete(a);
    run_output_free(&r);
  }
}
