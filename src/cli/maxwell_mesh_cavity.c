/* geomint maxwell mesh-cavity: the 3-D PEC cavity verification of issue 11 as one command.
 * For each level the cavity is meshed (box: body-centred cubic tetrahedra of the whole box,
 * gm_mesh_bcc with fill, n0·k cubes along x; cylinder, sphere: the Gmsh files
 * examples/cavity_<shape>_<k>.msh), the Whitney-star leapfrog rings down after current
 * pulses (gm_mesh_maxwell_cavity_modes), harminv's peaks are mapped back to spatial
 * eigenfrequencies (the leapfrog's dispersion undone, gm_leapfrog_space_frequency) and compared
 * with the analytic resonances (gm_cavity_box_resonances / _cylinder_ / _sphere_): per level
 * the error of each of the first 10 resonances (with multiplicity; --modes), the rate
 * (least-squares slope of log error against log h), and every peak below the 10th resonance
 * checked against the analytic list (a peak farther than 5 % from all of them is spurious).
 * A degenerate resonance split by the mesh has two errors: its nearest peak, and the farthest
 * of the peaks nearest to it (the split's spread and shift; the sphere's (2l+1)-fold
 * multiplets need it, see docs/maxwell-mesh.md). */
#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/maxwell.h"
#include "cli/maxwell_mesh.h"
#include "geomint/experiments.h"
#include "geomint/geomint.h"

#define MC "maxwell mesh-cavity"
#define MC_MAX_LEVELS GM_MESH_CAVITY_MAX_LEVELS
#define MC_MAX_T_END GM_MESH_CAVITY_MAX_T_END /* the longest record --t-end accepts */

static const char usage[] =
    "usage: geomint maxwell mesh-cavity [--shape box|cylinder|sphere] [--levels K] [--n0 N]\n"
    "                                   [--modes N] [--diagonal] [--t-end T] [--seed S]\n"
    "                                   [--mesh-dir DIR]\n"
    "                                   [--plot FILE.png] [--json]\n\n"
    "PEC cavity resonances on tetrahedral meshes at K resolutions (issue 11): Whitney-star\n"
    "leapfrog, current pulses on random edges, E probed at random points, harminv; the\n"
    "first 10 analytic resonances against the peaks, the rate of convergence with the mesh\n"
    "size, and a check that every peak below the 10th resonance is an analytic one.\n"
    "Resonances split by the mesh get a second table: the farthest of their peaks.\n\n"
    "  --shape box       [0,1]x[0,0.8]x[0,0.6], body-centred cubic tetrahedra (boundary\n"
    "                    pyramids filled), N*k cubes along x at level k = 1..K (default)\n"
    "  --shape cylinder  radius 0.5, height 0.6: DIR/cavity_cylinder_<k>.msh (Gmsh, made by\n"
    "                    scripts/cavity_cylinder_mesh.sh; DIR default examples)\n"
    "  --shape sphere    radius 0.5: DIR/cavity_sphere_<k>.msh (scripts/cavity_sphere_mesh.sh)\n"
    "  --levels K        resolutions (default 3, at most 6)\n"
    "  --modes N         the band covers the first N analytic resonances counted with\n"
    "                    multiplicity, the last multiplet whole (default 10)\n"
    "  --diagonal        the circumcentric diagonal star (accepted where it is not positive)\n"
    "                    instead of the Whitney star\n"
    "  --n0 N            (box) cubes along x at level 1, 3..40 (default 5)\n"
    "  --t-end T         record length, at most 1e4 (default 150)\n"
    "  --seed S          sources and probes (default 11)\n"
    "  --plot FILE.png   |relative error| against h, log-log, one line per resonance (gnuplot;\n"
    "                    the nearest peak, or the farthest where a multiplet has > 2 members)\n"
    "  --json            print one JSON object instead of the tables\n\n"
    "Exit status: 0 success (the table is printed; spurious peaks are reported, not fatal),\n"
    "1 a failed run, 2 bad input.\n";

static int show_progress(void *ctx, double done, double total) {
  mx_progress *p = ctx;
  p->total = (size_t)total; /* known once the library has the step */
  mx_progress_show(p, (size_t)done);
  return 0;
}

/* The error table: one row per distinct resonance, the rate a least-squares slope of
 * log |error| against log h over the levels where it was found. */
static void print_table(const char *what, const gm_mesh_cavity_result *r, int farthest) {
  const double(*errs)[GM_MESH_CAVITY_MAX_LEVELS] = farthest ? r->farthest : r->nearest;
  const double *rates = farthest ? r->rate_farthest : r->rate_nearest;
  const size_t levels = r->levels;
  printf("\nrelative error of the %s:\n| f analytic | mult. |", what);
  for (size_t l = 0; l < levels; ++l) printf(" rel. error h = %.4f |", r->level[l].h);
  printf(" rate |\n|---|---|");
  for (size_t l = 0; l <= levels; ++l) printf("---|");
  printf("\n");
  for (size_t j = 0; j < r->n_uniq; ++j) {
    printf("| %.5f | %d |", r->uniq[j], r->mult[j]);
    for (size_t l = 0; l < levels; ++l) {
      if (isnan(errs[j][l])) { printf(" — |"); continue; }
      printf(" %+.2e |", errs[j][l]);
    }
    if (!isnan(rates[j])) printf(" %.2f |\n", rates[j]);
    else printf(" — |\n");
  }
}

static cJSON *json_errors(const gm_mesh_cavity_result *r, int farthest) {
  const double(*errs)[GM_MESH_CAVITY_MAX_LEVELS] = farthest ? r->farthest : r->nearest;
  const double *rates = farthest ? r->rate_farthest : r->rate_nearest;
  cJSON *a = cJSON_CreateArray();
  for (size_t j = 0; j < r->n_uniq; ++j) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "analytic", r->uniq[j]);
    cJSON_AddNumberToObject(o, "multiplicity", r->mult[j]);
    cJSON_AddItemToObject(o, "rel_errors", cli_json_numbers(errs[j], r->levels));
    cJSON_AddItemToObject(o, "rate", cli_json_number(rates[j]));
    cJSON_AddItemToArray(a, o);
  }
  return a;
}

static int print_json(const char *shape, const gm_mesh_cavity_result *r, const char *plot) {
  cJSON *o = cJSON_CreateObject();
  cJSON_AddStringToObject(o, "shape", shape);
  cJSON_AddNumberToObject(o, "t_end", r->run.t_end);
  cJSON_AddNumberToObject(o, "f_min", r->run.f_min);
  cJSON_AddNumberToObject(o, "f_max", r->run.f_max);
  cJSON *levels = cJSON_AddArrayToObject(o, "levels");
  for (size_t l = 0; l < r->levels; ++l) {
    const gm_mesh_cavity_level *L = &r->level[l];
    cJSON *j = cJSON_CreateObject();
    cJSON_AddNumberToObject(j, "h", L->h);
    cJSON_AddNumberToObject(j, "tetrahedra", (double)L->n_tetrahedra);
    cJSON_AddNumberToObject(j, "edges", (double)L->n_edges);
    cJSON_AddNumberToObject(j, "dt", L->dt);
    cJSON_AddItemToObject(j, "peaks", cli_json_numbers(L->peaks, L->n_peaks));
    cJSON_AddNumberToObject(j, "analytic_in_band", (double)L->in_band);
    cJSON_AddNumberToObject(j, "spurious", (double)L->spurious);
    cJSON_AddItemToArray(levels, j);
  }
  cJSON_AddItemToObject(o, "nearest", json_errors(r, 0));
  cJSON_AddItemToObject(o, "farthest", json_errors(r, 1));
  cJSON_AddItemToObject(o, "max_rel_error", cli_json_numbers(r->band_max, r->levels));
  cJSON_AddItemToObject(o, "rate", cli_json_number(r->band_rate));
  cJSON_AddNumberToObject(o, "spurious", (double)r->spurious);
  cJSON_AddNumberToObject(o, "wall_s", r->wall_s);
  if (plot) cJSON_AddStringToObject(o, "plot", plot);
  return cli_json_print(o);
}

int cli_maxwell_mesh_cavity(int argc, char **argv) {
  const char *shape = "box", *dir = "examples", *plot = NULL;
  size_t levels = 3, n0 = 5, seed = 11, n_first = 10;
  int diagonal = 0, json = 0;
  double t_end = 150.0;
  cli_option options[] = {{"--shape", CLI_ARG_STRING, &shape, 0},
                          {"--levels", CLI_ARG_COUNT, &levels, 0},
                          {"--n0", CLI_ARG_COUNT, &n0, 0},
                          {"--modes", CLI_ARG_COUNT, &n_first, 0},
                          {"--diagonal", CLI_ARG_FLAG, &diagonal, 0},
                          {"--t-end", CLI_ARG_DOUBLE, &t_end, 0},
                          {"--seed", CLI_ARG_COUNT, &seed, 0},
                          {"--mesh-dir", CLI_ARG_STRING, &dir, 0},
                          {"--plot", CLI_ARG_STRING, &plot, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0}};
  const char *pos[1];
  size_t n_pos = 0;
  int status = cli_parse(MC, argc, argv, options, sizeof options / sizeof options[0], pos, 0,
                         &n_pos);
  if (status == CLI_HELP) { fputs(usage, stdout); return CLI_EXIT_OK; }
  if (status != CLI_EXIT_OK) return status;
  if ((strcmp(shape, "box") != 0 && strcmp(shape, "cylinder") != 0 &&
       strcmp(shape, "sphere") != 0) || levels < 1 ||
      levels > MC_MAX_LEVELS || n_first < 1 || !(t_end > 0.0) || !isfinite(t_end)) {
    cli_error(MC, "bad option value (--shape box|cylinder|sphere, --levels 1..%d, --modes >= 1, "
                  "--t-end > 0)", MC_MAX_LEVELS);
    return CLI_EXIT_USAGE;
  }
  /* the box needs two cubes along its shortest side (0.6 n0, rounded); n0 = 40 at 6 levels is
   * 240 x 192 x 144 cubes, about 4e7 tetrahedra */
  if (options[2].seen && strcmp(shape, "box") != 0) {
    cli_error(MC, "--n0 is an option of --shape box (the %s's meshes are files)", shape);
    return CLI_EXIT_USAGE;
  }
  if (n0 < 3 || n0 > 40) {
    cli_error(MC, "--n0 %zu: must be in [3, 40] (the box's 0.6 side needs 2 cubes at n0 = 3)", n0);
    return CLI_EXIT_USAGE;
  }
  /* the probe signals live in memory: 24 doubles a step, about 1e6 steps at t = 1e4 on the
   * finest default level */
  if (t_end > MC_MAX_T_END) {
    cli_error(MC, "--t-end %g: at most %g (24 probe signals are kept in memory, 8 bytes each a "
              "step: %g is about %.2g bytes at the finest level)", t_end, MC_MAX_T_END, t_end,
              24.0 * 8.0 * t_end / (0.3 / (double)(n0 * levels)));
    return CLI_EXIT_USAGE;
  }
  if (plot && cli_plot_check_output(MC, plot) != CLI_EXIT_OK) return CLI_EXIT_USAGE;
  gm_mesh_cavity_config c = gm_mesh_cavity_defaults();
  c.shape = shape;
  c.mesh_dir = dir;
  c.levels = levels;
  c.n0 = n0;
  c.n_first = n_first;
  c.diagonal = diagonal;
  c.t_end = t_end;
  c.seed = seed;
  mx_progress progress; /* a line on a terminal only; steps known once dt is */
  mx_progress_start(&progress, 0);
  c.progress = show_progress;
  c.progress_ctx = &progress;
  gm_mesh_cavity_result r;
  gm_error err = {{0}};
  gm_status st = gm_experiment_mesh_cavity(&c, &r, &err);
  mx_progress_end(&progress);
  if (st != GM_OK) {
    cli_error(MC, "%s", err.message);
    return st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  const gm_mesh_cavity_run run = r.run;
  const size_t nu = r.n_uniq;
  if (!json) {
  printf("PEC %s cavity, %s-star leapfrog (0.9 of the CFL limit), %zu sources, %zu probe "
         "points x 3 components, t = %g,\nharminv in bands of %.2g over [%.3f, %.3f] (error < "
         "%.0e, amplitude >= %.0e of the largest), leapfrog dispersion undone\n",
         shape, diagonal ? "diagonal" : "Whitney", run.n_sources, run.n_probes, t_end, run.band,
         run.f_min, run.f_max, run.max_error, run.min_amplitude);
  for (size_t l = 0; l < levels; ++l) {
    const gm_mesh_cavity_level *L = &r.level[l];
    printf("level %zu: h = %.4f, %zu tetrahedra, %zu edges, dt = %.4g; %zu peaks (analytic "
           "modes in the band, with multiplicity: %zu):", l + 1, L->h, L->n_tetrahedra,
           L->n_edges, L->dt, L->n_peaks, L->in_band);
    for (size_t i = 0; i < L->n_peaks; ++i) {
      printf(" %.5f", L->peaks[i]);
      if (L->spurious_peak[i]) printf("(SPURIOUS)");
    }
    printf("; spurious: %zu\n", L->spurious);
  }
  }
  int split = 0, wide = 0; /* wide: a multiplet of more than two (the sphere's) */
  for (size_t j = 0; j < nu; ++j) split |= r.mult[j] > 1, wide |= r.mult[j] > 2;
  if (!json) {
    print_table("nearest peak", &r, 0);
    if (split) print_table("farthest of the peaks nearest to the resonance (a split multiplet's "
                           "spread)", &r, 1);
    printf("\nlargest relative error in the band:");
    for (size_t l = 0; l < levels; ++l) printf(" %.2e", r.band_max[l]);
    if (levels >= 2) printf(", rate %.2f", r.band_rate);
    printf("\n");
    printf("\nspurious peaks below the 10th resonance (all levels): %zu\n", r.spurious);
  }
  if (plot) {
    double ys[GM_MESH_CAVITY_MAX_UNIQ][GM_MESH_CAVITY_MAX_LEVELS], hs[GM_MESH_CAVITY_MAX_LEVELS];
    char titles[GM_MESH_CAVITY_MAX_UNIQ][48];
    cli_xy_series series[GM_MESH_CAVITY_MAX_UNIQ];
    for (size_t l = 0; l < levels; ++l) hs[l] = r.level[l].h;
    for (size_t j = 0; j < nu; ++j) {
      for (size_t l = 0; l < levels; ++l) /* NaN: left out */
        ys[j][l] = fabs(wide ? r.farthest[j][l] : r.nearest[j][l]);
      snprintf(titles[j], sizeof titles[j], "f = %.4f", r.uniq[j]);
      if (r.mult[j] > 1)
        snprintf(titles[j] + strlen(titles[j]), sizeof titles[j] - strlen(titles[j]), " (x%d)",
                 r.mult[j]);
      series[j] = (cli_xy_series){titles[j], levels, hs, ys[j]};
    }
    char title[96];
    snprintf(title, sizeof title, "PEC %s cavity: %s errors (%s leapfrog, harminv)", shape,
             wide ? "farthest-peak" : "resonance", diagonal ? "diagonal-star" : "Whitney");
    const int ps = cli_plot_loglog(MC, plot, title, "h", "|relative error|", series, nu);
    if (ps != CLI_EXIT_OK) return ps;
    if (!json) printf("wrote %s\n", plot);
  }
  return json ? print_json(shape, &r, plot) : CLI_EXIT_OK;
}
