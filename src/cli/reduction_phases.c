/* geomint reduction phases: the table of gm_experiment_phases (src/experiments/phases.c):
 * geometric phases against their closed forms (docs/reduction.md, "Phases"). */
#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/reduction_phases.h"
#include "geomint/experiments.h"

static void print_table(const gm_phases_result *r) {
  printf("Geometric phases: computed vs closed form (errors at the two levels; order = log2 ratio)\n");
  printf("%-40s %-20s %15s %15s %9s %9s %6s  %s\n", "phase", "method", "closed form", "computed",
         "error 1", "error 2", "order", "levels");
  for (size_t i = 0; i < r->n_rows; ++i) {
    const gm_phases_row *x = &r->rows[i];
    if (x->mesh)
      printf("%-40s %-20s %15.10f %15.10f %9.2e %9s %6s  %s\n", x->what, x->how, x->closed,
             x->computed, x->error[0], "", "", x->levels);
    else
      printf("%-40s %-20s %15.10f %15.10f %9.2e %9.2e %6.2f  %s\n", x->what, x->how, x->closed,
             x->computed, x->error[0], x->error[1], log2(x->error[0] / x->error[1]), x->levels);
    /* Montgomery's terms after the rigid-body rows */
    if (strcmp(x->how, "lgvi-galerkin-2") == 0)
      printf("%-40s T = %.10f, 2ET/|m| = %.10f, solid angle %.10f\n", "", r->rigid_period,
             r->rigid_dynamic, r->rigid_solid_angle);
  }
}

static int print_json(const gm_phases_result *r, const char *csv) {
  cJSON *o = cJSON_CreateObject();
  cJSON *rows = cJSON_AddArrayToObject(o, "rows");
  for (size_t i = 0; i < r->n_rows; ++i) {
    const gm_phases_row *x = &r->rows[i];
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "phase", x->what);
    cJSON_AddStringToObject(j, "method", x->how);
    cJSON_AddItemToObject(j, "closed_form", cli_json_number(x->closed));
    cJSON_AddItemToObject(j, "computed", cli_json_number(x->computed));
    cJSON_AddItemToObject(j, "errors", cli_json_numbers(x->error, x->mesh ? 1 : 2));
    if (!x->mesh) cJSON_AddItemToObject(j, "order", cli_json_number(log2(x->error[0] / x->error[1])));
    cJSON_AddStringToObject(j, "levels", x->levels);
    cJSON_AddItemToArray(rows, j);
  }
  cJSON_AddItemToObject(o, "rigid_period", cli_json_number(r->rigid_period));
  cJSON_AddItemToObject(o, "rigid_dynamic_phase", cli_json_number(r->rigid_dynamic));
  cJSON_AddItemToObject(o, "rigid_solid_angle", cli_json_number(r->rigid_solid_angle));
  cJSON_AddItemToObject(o, "max_abs_phase_error", cli_json_number(r->max_error));
  cJSON_AddNumberToObject(o, "wall_s", r->wall_s);
  if (csv != NULL) cJSON_AddStringToObject(o, "csv", csv);
  return cli_json_print(o);
}

int cli_reduction_phases(const char *dir, int json) {
  gm_phases_result r;
  gm_error err = {{0}};
  if (gm_experiment_phases(dir, &r, &err) != GM_OK) {
    cli_error("reduction", "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  if (!json) {
    print_table(&r);
    return CLI_EXIT_OK;
  }
  char csv[4200];
  if (dir != NULL) snprintf(csv, sizeof csv, "%s/phases-convergence.csv", dir);
  return print_json(&r, dir != NULL ? csv : NULL);
}
