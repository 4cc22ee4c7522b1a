/* geomint fluid run CASE.json: the DEC Navier–Stokes solver on a case file (src/fluids/). */
#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "cli/cli.h"

static const char usage[] =
    "usage: geomint fluid run CASE.json [--out DIR] [--json]\n"
    "       geomint fluid channel [--cells N] [--time T] [--json]\n"
    "       geomint fluid rates [--flow couette|poiseuille] [--cells N,N,...] [--json]\n\n"
    "Incompressible Navier-Stokes with a passive scalar by discrete exterior calculus (seed 004,\n"
    "Mohamed, Hirani & Samtaney 2016) on the mesh and boundary groups of a case file; see\n"
    "docs/fluids.md for the format. Prints the first and last diagnostics (kinetic energy,\n"
    "enstrophy, total vorticity, max |delta omega|, scalar mass).\n\n"
    "options:\n"
    "  --out DIR   write DIR/diagnostics.csv (every step), DIR/fluid_NNNNNN.vtu every\n"
    "              output_every steps and DIR/fluid.pvd (DIR is created if missing)\n"
    "  --json      print the result as one JSON object\n\n"
    "channel: seed 004 B14, the channel [0, 2 pi]x[0, 1] with nu = kappa = 1, parabolic inflow,\n"
    "theta = 20 on the top wall, dt = 1e-2 to T (default 5) on N cells along (default 210: mean\n"
    "edge 2.99e-2, the seed's mesh size); prints the profile error against Poiseuille.\n"
    "rates: seed 004 B15, Couette or Poiseuille on the unit square at the meshes N (default\n"
    "12,20,48,72,96,120,144, mean edges close to the seed's seven), errors and rates of psi,\n"
    "theta, velocity and flux (dt = min(1e-2, 0.5/N), t = 1).\n\n"
    "       geomint fluid taylor-green [--scheme midpoint|seed] [--cells 8,16,32] [--json]\n"
    "       geomint fluid shear-layer [--scheme midpoint|seed] [--cells N] [--steps S] [--json]\n"
    "       geomint fluid rossby-haurwitz [--subdivisions 2,3,4] [--time T] [--json]\n"
    "taylor-green: psi = sin x sin y on the periodic square [0, 2 pi]^2, nu = 0.05, dt = 0.05,\n"
    "t = 1: the decay rate of the amplitude against 2 nu and its convergence rate.\n"
    "shear-layer: the inviscid double shear layer (Bell, Colella & Glaz 1989) on N cells\n"
    "(default 12), S steps of 0.05 (default 10000): drifts of energy, enstrophy, total vorticity.\n"
    "rossby-haurwitz: the wavenumber-4 wave on the unit sphere rotating at Omega = 1 (icosphere\n"
    "subdivisions; dt = 0.4 / 2^(s-2)) to T (default 10): the pattern's angular speed against\n"
    "Haurwitz's (R(3+R) omega - 2 Omega)/((1+R)(2+R)) and the convergence rate.\n";

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
  if (rc == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
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
  printf("%-16s %22.15g %22.15g\n", "kinetic_energy", rep.first.kinetic_energy,
         rep.last.kinetic_energy);
  printf("%-16s %22.15g %22.15g\n", "enstrophy", rep.first.enstrophy, rep.last.enstrophy);
  printf("%-16s %22.15g %22.15g\n", "total_vorticity", rep.first.total_vorticity,
         rep.last.total_vorticity);
  printf("%-16s %22.15g %22.15g\n", "scalar_mass", rep.first.scalar_mass, rep.last.scalar_mass);
  return CLI_EXIT_OK;
}

static int fluid_channel(int argc, char **argv) {
  size_t cells = 210;
  double t_end = 5.0;
  int json = 0;
  cli_option options[] = {{"--cells", CLI_ARG_COUNT, &cells, 0},
                          {"--time", CLI_ARG_DOUBLE, &t_end, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0}};
  size_t n_pos = 0;
  int rc = cli_parse("fluid channel", argc, argv, options, 3, NULL, 0, &n_pos);
  if (rc == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  gm_fluid_channel_result r;
  gm_error err = {{0}};
  double t0 = now();
  gm_status st = gm_fluid_channel(cells, t_end, &r, &err);
  double wall = now() - t0;
  if (st) {
    cli_error("fluid channel", "%s", err.message);
    return st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  if (json) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddItemToObject(root, "triangles", cli_json_number((double)r.n_triangles));
    cJSON_AddItemToObject(root, "mean_edge", cli_json_number(r.mean_edge));
    cJSON_AddItemToObject(root, "steps", cli_json_number((double)r.steps));
    cJSON_AddItemToObject(root, "profile_error", cli_json_number(r.profile_error));
    cJSON_AddItemToObject(root, "centroid_error", cli_json_number(r.centroid_error));
    cJSON_AddItemToObject(root, "theta_error", cli_json_number(r.theta_error));
    cJSON_AddItemToObject(root, "div_max", cli_json_number(r.div_max));
    cJSON_AddItemToObject(root, "wall_s", cli_json_number(wall));
    return cli_json_print(root);
  }
  printf("channel: %zu triangles, mean edge %.4e, %zu steps in %.2f s\n", r.n_triangles,
         r.mean_edge, r.steps, wall);
  printf("profile error (flux per length vs Poiseuille, mean) %.3e   (seed: 2.4e-4)\n",
         r.profile_error);
  printf("velocity per triangle vs Poiseuille at the centroid, mean %.3e\n", r.centroid_error);
  printf("max |theta - 20 y| in the developed region %.3e\n", r.theta_error);
  printf("max |delta omega| over all steps %.3e\n", r.div_max);
  return CLI_EXIT_OK;
}

static double fit_slope(size_t n, const double *h, const double *e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < n; ++i) {
    double a = log(h[i]), b = log(e[i]);
    sx += a;
    sy += b;
    sxx += a * a;
    sxy += a * b;
  }
  return ((double)n * sxy - sx * sy) / ((double)n * sxx - sx * sx);
}

static int fluid_rates(int argc, char **argv) {
  const char *flow = "couette", *list = "12,20,48,72,96,120,144";
  int json = 0;
  cli_option options[] = {{"--flow", CLI_ARG_STRING, &flow, 0},
                          {"--cells", CLI_ARG_STRING, &list, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0}};
  size_t n_pos = 0;
  int rc = cli_parse("fluid rates", argc, argv, options, 3, NULL, 0, &n_pos);
  if (rc == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  int pois = strcmp(flow, "poiseuille") == 0;
  if (!pois && strcmp(flow, "couette") != 0) {
    cli_error("fluid rates", "--flow must be couette or poiseuille, not '%s'", flow);
    return CLI_EXIT_USAGE;
  }
  size_t cells[16], n = 0;
  for (const char *p = list; *p && n < 16;) {
    char *end = NULL;
    long v = strtol(p, &end, 10);
    if (end == p || v < 4 || v > 4000 || (*end && *end != ',')) {
      cli_error("fluid rates", "--cells: expected integers in [4, 4000] separated by commas");
      return CLI_EXIT_USAGE;
    }
    cells[n++] = (size_t)v;
    p = *end ? end + 1 : end;
  }
  if (n < 2) {
    cli_error("fluid rates", "--cells: need at least two meshes");
    return CLI_EXIT_USAGE;
  }
  double h[16], e[4][16], div = 0.0;
  gm_error err = {{0}};
  for (size_t i = 0; i < n; ++i) {
    gm_fluid_shear_result r;
    /* dt = min(1e-2, 0.5/N): below the half step's bound 1/N (h_min = 1/(2N) on the sides) */
    double dt = fmin(1e-2, 0.5 / (double)cells[i]);
    gm_status st = gm_fluid_shear(pois, cells[i], dt, 1.0, &r, &err);
    if (st) {
      cli_error("fluid rates", "%s", err.message);
      return CLI_EXIT_FAILURE;
    }
    h[i] = r.mean_edge;
    e[0][i] = r.psi;
    e[1][i] = r.theta;
    e[2][i] = r.velocity;
    e[3][i] = r.flux;
    div = fmax(div, r.div_max);
  }
  static const char *names[4] = {"psi", "theta", "velocity", "flux"};
  if (json) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "flow", pois ? "poiseuille" : "couette");
    cJSON_AddItemToObject(root, "mean_edge", cli_json_numbers(h, n));
    for (int k = 0; k < 4; ++k) {
      char key[32];
      snprintf(key, sizeof key, "error_%s", names[k]);
      cJSON_AddItemToObject(root, key, cli_json_numbers(e[k], n));
      snprintf(key, sizeof key, "rate_%s", names[k]);
      cJSON_AddItemToObject(root, key, cli_json_number(fit_slope(n, h, e[k])));
    }
    cJSON_AddItemToObject(root, "div_max", cli_json_number(div));
    return cli_json_print(root);
  }
  printf("%s: errors at steady state (t = 1, dt = min(1e-2, 0.5/N), nu = kappa = 1)\n",
         pois ? "Poiseuille" : "Couette");
  printf("%6s %11s %11s %11s %11s %11s\n", "cells", "mean edge", "psi", "theta", "velocity",
         "flux");
  for (size_t i = 0; i < n; ++i)
    printf("%6zu %11.4e %11.4e %11.4e %11.4e %11.4e\n", cells[i], h[i], e[0][i], e[1][i], e[2][i],
           e[3][i]);
  printf("%6s %11s %11.2f %11.2f %11.2f %11.2f\n", "rate", "", fit_slope(n, h, e[0]),
         fit_slope(n, h, e[1]), fit_slope(n, h, e[2]), fit_slope(n, h, e[3]));
  printf("max |delta omega| over all steps and meshes %.3e\n", div);
  return CLI_EXIT_OK;
}

static int parse_counts(const char *cmd, const char *list, size_t lo, size_t hi, size_t *out,
                        size_t *n) {
  *n = 0;
  for (const char *p = list; *p && *n < 16;) {
    char *end = NULL;
    long v = strtol(p, &end, 10);
    if (end == p || v < (long)lo || v > (long)hi || (*end && *end != ',')) {
      cli_error(cmd, "expected integers in [%zu, %zu] separated by commas, got '%s'", lo, hi,
                list);
      return CLI_EXIT_USAGE;
    }
    out[(*n)++] = (size_t)v;
    p = *end ? end + 1 : end;
  }
  return CLI_EXIT_OK;
}

static int parse_scheme(const char *cmd, const char *name, gm_fluid_scheme *s) {
  if (strcmp(name, "midpoint") == 0)
    *s = GM_FLUID_MIDPOINT;
  else if (strcmp(name, "seed") == 0)
    *s = GM_FLUID_SEED;
  else {
    cli_error(cmd, "--scheme must be midpoint or seed, not '%s'", name);
    return CLI_EXIT_USAGE;
  }
  return CLI_EXIT_OK;
}

/* taylor-green and rossby-haurwitz: a measured rate against its closed form on a list of
 * meshes, with the convergence rate of the relative error */
static int fluid_rate_table(const char *cmd, int argc, char **argv) {
  int rh = strcmp(cmd, "fluid rossby-haurwitz") == 0, json = 0;
  const char *list = rh ? "2,3,4" : "8,16,32", *scheme_name = "midpoint";
  double t_end = 10.0;
  cli_option options[] = {{rh ? "--subdivisions" : "--cells", CLI_ARG_STRING, &list, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0},
                          {rh ? "--time" : "--scheme", rh ? CLI_ARG_DOUBLE : CLI_ARG_STRING,
                           rh ? (void *)&t_end : (void *)&scheme_name, 0}};
  size_t n_pos = 0;
  int rc = cli_parse(cmd, argc, argv, options, 3, NULL, 0, &n_pos);
  if (rc == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  gm_fluid_scheme scheme = GM_FLUID_MIDPOINT;
  size_t m[16], n = 0;
  if ((rc = parse_scheme(cmd, scheme_name, &scheme)) ||
      (rc = parse_counts(cmd, list, rh ? 1 : 4, rh ? 7 : 2000, m, &n)))
    return rc;
  if (!(t_end > 0 && t_end <= 1e4)) {
    cli_error(cmd, "--time must be in (0, 1e4]");
    return CLI_EXIT_USAGE;
  }
  double h[16], e[16];
  gm_fluid_flow_result r[16];
  gm_error err = {{0}};
  for (size_t i = 0; i < n; ++i) {
    gm_status st = rh ? gm_fluid_rossby_haurwitz(m[i], 0.4 / pow(2.0, (double)m[i] - 2.0), t_end,
                                                 &r[i], &err)
                      : gm_fluid_taylor_green(scheme, m[i], 0.05, 0.05, 20, &r[i], &err);
    if (st) {
      cli_error(cmd, "%s", err.message);
      return st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
    }
    h[i] = r[i].mean_edge;
    e[i] = fabs(r[i].measured / r[i].exact - 1.0);
  }
  double rate = n > 1 ? fit_slope(n, h, e) : NAN;
  if (json) {
    cJSON *root = cJSON_CreateObject();
    double tri[16], meas[16], drift[16];
    for (size_t i = 0; i < n; ++i) {
      tri[i] = (double)r[i].n_triangles;
      meas[i] = r[i].measured;
      drift[i] = r[i].energy_drift;
    }
    cJSON_AddItemToObject(root, "triangles", cli_json_numbers(tri, n));
    cJSON_AddItemToObject(root, "mean_edge", cli_json_numbers(h, n));
    cJSON_AddItemToObject(root, "measured", cli_json_numbers(meas, n));
    cJSON_AddItemToObject(root, "exact", cli_json_number(r[0].exact));
    cJSON_AddItemToObject(root, "relative_error", cli_json_numbers(e, n));
    cJSON_AddItemToObject(root, "energy_drift", cli_json_numbers(drift, n));
    if (n > 1) cJSON_AddItemToObject(root, "rate", cli_json_number(rate));
    return cli_json_print(root);
  }
  if (rh)
    printf("Rossby-Haurwitz wave R = 4 on the unit sphere, Omega = 1, omega = K = %.6f, t = %g\n"
           "pattern speed (Haurwitz 1940) %.6e\n",
           7.848e-6 / 7.292e-5, t_end, r[0].exact);
  else
    printf("Taylor-Green on the periodic square, %s scheme, nu = 0.05, dt = 0.05, t = 1\n"
           "decay rate of the amplitude, exact 2 nu = %.6e\n",
           scheme == GM_FLUID_SEED ? "seed" : "midpoint", r[0].exact);
  printf("%6s %9s %11s %13s %11s %11s %11s\n", rh ? "subdiv" : "cells", "triangles", "mean edge",
         rh ? "speed" : "decay rate", "rel. error", "energy", "max|div|");
  for (size_t i = 0; i < n; ++i)
    printf("%6zu %9zu %11.4e %13.6e %11.3e %11.2e %11.1e\n", m[i], r[i].n_triangles, h[i],
           r[i].measured, e[i], rh ? r[i].energy_drift : r[i].energy_change, r[i].div_max);
  if (n > 1) printf("convergence rate %.2f\n", rate);
  printf("(energy: %s)\n", rh ? "max relative drift" : "relative change over the run");
  return CLI_EXIT_OK;
}

static int fluid_shear_layer(int argc, char **argv) {
  const char *scheme_name = "midpoint";
  size_t cells = 12, steps = 10000;
  int json = 0;
  cli_option options[] = {{"--scheme", CLI_ARG_STRING, &scheme_name, 0},
                          {"--cells", CLI_ARG_COUNT, &cells, 0},
                          {"--steps", CLI_ARG_COUNT, &steps, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0}};
  size_t n_pos = 0;
  int rc = cli_parse("fluid shear-layer", argc, argv, options, 4, NULL, 0, &n_pos);
  if (rc == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  gm_fluid_scheme scheme = GM_FLUID_MIDPOINT;
  if ((rc = parse_scheme("fluid shear-layer", scheme_name, &scheme))) return rc;
  gm_fluid_flow_result r;
  gm_error err = {{0}};
  double t0 = now();
  gm_status st = gm_fluid_double_shear(scheme, cells, 0.05, steps, &r, &err);
  double wall = now() - t0;
  if (st) {
    cli_error("fluid shear-layer", "%s", err.message);
    return st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  if (json) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddItemToObject(root, "triangles", cli_json_number((double)r.n_triangles));
    cJSON_AddItemToObject(root, "steps", cli_json_number((double)r.steps));
    cJSON_AddItemToObject(root, "energy_drift", cli_json_number(r.energy_drift));
    cJSON_AddItemToObject(root, "energy_change", cli_json_number(r.energy_change));
    cJSON_AddItemToObject(root, "enstrophy_drift", cli_json_number(r.enstrophy_drift));
    cJSON_AddItemToObject(root, "vorticity_drift", cli_json_number(r.vorticity_drift));
    cJSON_AddItemToObject(root, "div_max", cli_json_number(r.div_max));
    cJSON_AddItemToObject(root, "wall_s", cli_json_number(wall));
    return cli_json_print(root);
  }
  printf("double shear layer, %s scheme, %zu triangles, %zu steps of 0.05 in %.2f s\n",
         scheme == GM_FLUID_SEED ? "seed" : "midpoint", r.n_triangles, r.steps, wall);
  printf("max relative drift: energy %.3e, enstrophy %.3e; total vorticity %.3e (of sum|Gamma|)\n",
         r.energy_drift, r.enstrophy_drift, r.vorticity_drift);
  printf("energy change at the end %.3e, max |delta omega| %.1e\n", r.energy_change, r.div_max);
  return CLI_EXIT_OK;
}

static int fluid_main(int argc, char **argv) {
  if (argc < 1 || strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0) {
    fputs(usage, argc < 1 ? stderr : stdout);
    return argc < 1 ? CLI_EXIT_USAGE : CLI_EXIT_OK;
  }
  if (strcmp(argv[0], "run") == 0) return fluid_run(argc - 1, argv + 1);
  if (strcmp(argv[0], "channel") == 0) return fluid_channel(argc - 1, argv + 1);
  if (strcmp(argv[0], "rates") == 0) return fluid_rates(argc - 1, argv + 1);
  if (strcmp(argv[0], "taylor-green") == 0)
    return fluid_rate_table("fluid taylor-green", argc - 1, argv + 1);
  if (strcmp(argv[0], "rossby-haurwitz") == 0)
    return fluid_rate_table("fluid rossby-haurwitz", argc - 1, argv + 1);
  if (strcmp(argv[0], "shear-layer") == 0) return fluid_shear_layer(argc - 1, argv + 1);
  cli_error("fluid",
            "unknown subcommand '%s' (expected run, channel, rates, taylor-green, shear-layer or "
            "rossby-haurwitz)",
            argv[0]);
  return CLI_EXIT_USAGE;
}

const cli_command cli_fluid_command = {"fluid", "incompressible flow with a passive scalar by DEC",
                                       usage, fluid_main};
