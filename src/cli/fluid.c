/* geomint fluid run CASE.json: the DEC Navier–Stokes solver on a case file (src/fluids/). */
#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "cli/cli.h"

static const char usage[] =
    "usage: geomint fluid run CASE.json [--out DIR] [--json]\n\n"
    "Incompressible Navier-Stokes with a passive scalar by discrete exterior calculus (seed 004,\n"
    "Mohamed, Hirani & Samtaney 2016) on the mesh and boundary groups of a case file; see\n"
    "docs/fluids.md for the format. Prints the first and last diagnostics (kinetic energy,\n"
    "enstrophy, total vorticity, max |delta omega|, scalar mass).\n\n"
    "options:\n"
    "  --out DIR   write DIR/diagnostics.csv (every step), DIR/fluid_NNNNNN.vtu every\n"
    "              output_every steps and DIR/fluid.pvd (DIR is created if missing)\n"
    "  --json      print the result as one JSON object\n";

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static cJSON *diag_json(const gm_fluid_diagnostics *d) {
  cJSON *o = cJSON_CreateObject();
  cJSON_AddItemToObject(o, "time", cli_json_number(d->time));
  cJSON_AddItemToObject(o, "kinetic_energy", cli_json_number(d->kinetic_energy));
  cJSON_AddItemToObject(o, "enstrophy", cli_json_number(d->enstrophy));
  cJSON_AddItemToObject(o, "total_vorticity", cli_json_number(d->total_vorticity));
  cJSON_AddItemToObject(o, "div_max", cli_json_number(d->div_max));
  cJSON_AddItemToObject(o, "scalar_mass", cli_json_number(d->scalar_mass));
  return o;
}

static int fluid_run(int argc, char **argv) {
  const char *out = NULL;
  int json = 0;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &out, 0}, {"--json", CLI_ARG_FLAG, &json, 0}};
  const char *pos[1];
  size_t n_pos = 0;
  int rc = cli_parse("fluid run", argc, argv, options, 2, pos, 1, &n_pos);
  if (rc == CLI_HELP) { fputs(usage, stdout); return CLI_EXIT_OK; }
  if (rc != CLI_EXIT_OK) return rc;
  if (n_pos != 1) {
    cli_error("fluid run", "expected one case file\n%s", usage);
    return CLI_EXIT_USAGE;
  }
  gm_error err = {{0}};
  gm_fluid_case *c = NULL;
  gm_status st = gm_fluid_case_read(pos[0], &c, &err);
  if (st) {
    cli_error("fluid run", "%s", err.message);
    return st == GM_ENOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
  }
  if (out && mkdir(out, 0777) != 0 && errno != EEXIST) {
    cli_error("fluid run", "cannot create the directory '%s': %s", out, strerror(errno));
    gm_fluid_case_free(c);
    return CLI_EXIT_FAILURE;
  }
  gm_fluid_run_report rep;
  double t0 = now();
  st = gm_fluid_case_run(c, out, &rep, &err);
  double wall = now() - t0;
  gm_fluid_case_free(c);
  if (st) {
    /* bad input found at create (bound, groups, mesh) is a usage error; a run failure is 1 */
    int input = rep.steps == 0 && (st == GM_EINVAL || st == GM_ENOTFOUND || st == GM_EUNSUPPORTED);
    cli_error("fluid run", "%s%s", err.message,
              input ? "" : " (the output written so far is kept)");
    return input ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  if (!isfinite(rep.last.kinetic_energy)) {
    cli_error("fluid run", "non-finite kinetic energy at the end");
    return CLI_EXIT_FAILURE;
  }
  if (json) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddItemToObject(root, "steps", cli_json_number((double)rep.steps));
    cJSON_AddItemToObject(root, "wall_s", cli_json_number(wall));
    cJSON_AddItemToObject(root, "div_max", cli_json_number(rep.div_max));
    cJSON_AddItemToObject(root, "vtu_files", cli_json_number((double)rep.vtu_files));
    cJSON_AddItemToObject(root, "first", diag_json(&rep.first));
    cJSON_AddItemToObject(root, "last", diag_json(&rep.last));
    return cli_json_print(root);
  }
  printf("%zu steps in %.3f s, max |delta omega| = %.3e, %zu VTU files\n", rep.steps, wall,
         rep.div_max, rep.vtu_files);
  printf("%-16s %22s %22s\n", "", "first", "last");
  printf("%-16s %22.15g %22.15g\n", "time", rep.first.time, rep.last.time);
  printf("%-16s %22.15g %22.15g\n", "kinetic_energy", rep.first.kinetic_energy, rep.last.kinetic_energy);
  printf("%-16s %22.15g %22.15g\n", "enstrophy", rep.first.enstrophy, rep.last.enstrophy);
  printf("%-16s %22.15g %22.15g\n", "total_vorticity", rep.first.total_vorticity, rep.last.total_vorticity);
  printf("%-16s %22.15g %22.15g\n", "scalar_mass", rep.first.scalar_mass, rep.last.scalar_mass);
  return CLI_EXIT_OK;
}

static int fluid_main(int argc, char **argv) {
  if (argc < 1 || strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0) {
    fputs(usage, argc < 1 ? stderr : stdout);
    return argc < 1 ? CLI_EXIT_USAGE : CLI_EXIT_OK;
  }
  if (strcmp(argv[0], "run") == 0) return fluid_run(argc - 1, argv + 1);
  cli_error("fluid", "unknown subcommand '%s' (expected run)", argv[0]);
  return CLI_EXIT_USAGE;
}

const cli_command cli_fluid_command = {"fluid", "incompressible flow with a passive scalar by DEC",
                                       usage, fluid_main};
