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
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/maxwell.h"
#include "cli/maxwell_mesh.h"
#include "geomint/geomint.h"

#define MC "maxwell mesh-cavity"
#define MC_MAX_LEVELS 6
#define MC_MAX_MODES 128
#define MC_MAX_UNIQ 16

/* the longest record --t-end accepts */
#define MC_MAX_T_END 1e4

static const char usage[] =
    "usage: geomint maxwell mesh-cavity [--shape box|cylinder|sphere] [--levels K] [--n0 N]\n"
    "                                   [--modes N] [--diagonal] [--t-end T] [--seed S]\n"
    "                                   [--mesh-dir DIR]\n"
    "                                   [--plot FILE.png]\n\n"
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
    "                    the nearest peak, or the farthest where a multiplet has > 2 members)\n\n"
    "Exit status: 0 success (the table is printed; spurious peaks are reported, not fatal),\n"
    "1 a failed run, 2 bad input.\n";

static int show_progress(void *ctx, double done, double total) {
  mx_progress *p = ctx;
  p->total = (size_t)total; /* known once the library has the step */
  mx_progress_show(p, (size_t)done);
  return 0;
}

static int make_level(const char *shape, const char *dir, size_t n0, size_t k, gm_mesh **mesh,
                      double *h) {
  gm_error err = {{0}};
  if (strcmp(shape, "box") == 0) {
    const double lo[3] = {0, 0, 0}, hi[3] = {1.0, 0.8, 0.6};
    const size_t n = n0 * k;
    *h = 1.0 / (double)n;
    if (gm_mesh_bcc(lo, hi, n, (size_t)lround(0.8 * (double)n), (size_t)lround(0.6 * (double)n),
                    1, mesh, &err) != GM_OK) {
      cli_error(MC, "%s", err.message);
      return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
  }
  char path[1024];
  snprintf(path, sizeof path, "%s/cavity_%s_%zu.msh", dir, shape, k);
  if (gm_mesh_read(path, mesh, &err) != GM_OK) {
    cli_error(MC, "%s", err.message);
    return CLI_EXIT_USAGE;
  }
  /* h: the mean edge length */
  gm_complex *cx = NULL;
  if (gm_mesh_complex(*mesh, &cx, &err) != GM_OK) {
    cli_error(MC, "%s", err.message);
    return CLI_EXIT_USAGE;
  }
  const size_t ne = gm_complex_count(cx, 1);
  const size_t *ev = gm_complex_simplices(cx, 1);
  const double *X = gm_complex_coordinates(cx);
  double s = 0.0;
  for (size_t e = 0; e < ne; ++e) {
    double r2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double d = X[3 * ev[2 * e] + (size_t)i] - X[3 * ev[2 * e + 1] + (size_t)i];
      r2 += d * d;
    }
    s += sqrt(r2);
  }
  *h = s / (double)ne;
  gm_complex_free(cx);
  return CLI_EXIT_OK;
}

/* The error table: one row per distinct resonance, the rate a least-squares slope of
 * log |error| against log h over the levels where it was found. */
static void print_table(const char *what, size_t levels, const double *hs, size_t nu,
                        const double *uniq, const int *mult, double errs[][MC_MAX_LEVELS]) {
  printf("\nrelative error of the %s:\n| f analytic | mult. |", what);
  for (size_t l = 0; l < levels; ++l) printf(" rel. error h = %.4f |", hs[l]);
  printf(" rate |\n|---|---|");
  for (size_t l = 0; l <= levels; ++l) printf("---|");
  printf("\n");
  for (size_t j = 0; j < nu; ++j) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    size_t m = 0;
    printf("| %.5f | %d |", uniq[j], mult[j]);
    for (size_t l = 0; l < levels; ++l) {
      if (isnan(errs[j][l])) { printf(" — |"); continue; }
      printf(" %+.2e |", errs[j][l]);
      const double x = log(hs[l]), y = log(fabs(errs[j][l]) + 1e-300);
      sx += x, sy += y, sxx += x * x, sxy += x * y, ++m;
    }
    if (m >= 2) printf(" %.2f |\n", (m * sxy - sx * sy) / (m * sxx - sx * sx));
    else printf(" — |\n");
  }
}

int cli_maxwell_mesh_cavity(int argc, char **argv) {
  const char *shape = "box", *dir = "examples", *plot = NULL;
  size_t levels = 3, n0 = 5, seed = 11, n_first = 10;
  int diagonal = 0;
  double t_end = 150.0;
  cli_option options[] = {{"--shape", CLI_ARG_STRING, &shape, 0},
                          {"--levels", CLI_ARG_COUNT, &levels, 0},
                          {"--n0", CLI_ARG_COUNT, &n0, 0},
                          {"--modes", CLI_ARG_COUNT, &n_first, 0},
                          {"--diagonal", CLI_ARG_FLAG, &diagonal, 0},
                          {"--t-end", CLI_ARG_DOUBLE, &t_end, 0},
                          {"--seed", CLI_ARG_COUNT, &seed, 0},
                          {"--mesh-dir", CLI_ARG_STRING, &dir, 0},
                          {"--plot", CLI_ARG_STRING, &plot, 0}};
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
  gm_error err = {{0}};
  double ana[MC_MAX_MODES];
  size_t na = 0;
  gm_status st = strcmp(shape, "box") == 0
                     ? gm_cavity_box_resonances((const double[3]){1.0, 0.8, 0.6}, 2.0,
                                                MC_MAX_MODES, ana, &na, &err)
                 : strcmp(shape, "cylinder") == 0
                     ? gm_cavity_cylinder_resonances(0.5, 0.6, 2.0, MC_MAX_MODES, ana, &na, &err)
                     : gm_cavity_sphere_resonances(0.5, 2.7, MC_MAX_MODES, ana, &na, &err);
  if (st != GM_OK || na < 11) {
    cli_error(MC, "analytic resonances: %s", st != GM_OK ? err.message : "fewer than 11");
    return CLI_EXIT_FAILURE;
  }
  /* the band: up to halfway between the n_first-th resonance (with multiplicity) and the next
   * distinct one; the multiplet of the n_first-th is taken whole */
  size_t next = n_first;
  while (next < na && ana[next] <= ana[n_first - 1] * (1 + 1e-12)) ++next;
  if (next >= na) {
    cli_error(MC, "--modes %zu: the analytic list ends there", n_first);
    return CLI_EXIT_USAGE;
  }
  const double f_hi = 0.5 * (ana[n_first - 1] + ana[next]);
  double uniq[MC_MAX_UNIQ];
  int mult[MC_MAX_UNIQ];
  size_t nu = 0;
  for (size_t j = 0; j < next; ++j) {
    if (nu > 0 && ana[j] <= uniq[nu - 1] * (1 + 1e-12)) { ++mult[nu - 1]; continue; }
    if (nu == MC_MAX_UNIQ) {
      cli_error(MC, "--modes %zu: more than %d distinct resonances", n_first, MC_MAX_UNIQ);
      return CLI_EXIT_USAGE;
    }
    uniq[nu] = ana[j];
    mult[nu++] = 1;
  }
  gm_mesh_cavity_run run = gm_mesh_cavity_run_defaults();
  run.t_end = t_end;
  run.seed = seed;
  run.f_min = 0.5 * ana[0];
  run.f_max = f_hi;
  run.band = 0.2;
  run.n_sources = 12;
  run.n_probes = 8;
  printf("PEC %s cavity, %s-star leapfrog (0.9 of the CFL limit), %zu sources, %zu probe "
         "points x 3 components, t = %g,\nharminv in bands of %.2g over [%.3f, %.3f] (error < "
         "%.0e, amplitude >= %.0e of the largest), leapfrog dispersion undone\n",
         shape, diagonal ? "diagonal" : "Whitney", run.n_sources, run.n_probes, t_end, run.band,
         run.f_min, run.f_max, run.max_error, run.min_amplitude);
  /* per distinct resonance and level: the error of the nearest peak, and of the farthest of the
   * peaks nearest to it (a multiplet split by the mesh: its spread) */
  double errs[MC_MAX_UNIQ][MC_MAX_LEVELS], worst[MC_MAX_UNIQ][MC_MAX_LEVELS], hs[MC_MAX_LEVELS];
  size_t total_spurious = 0;
  for (size_t l = 0; l < levels; ++l) {
    gm_mesh *mesh = NULL;
    gm_complex *cx = NULL;
    gm_geometry *g = NULL;
    if ((status = make_level(shape, dir, n0, l + 1, &mesh, &hs[l])) != CLI_EXIT_OK) return status;
    if (gm_mesh_complex(mesh, &cx, &err) != GM_OK ||
        gm_geometry_create(cx, NULL, &g, &err) != GM_OK) {
      cli_error(MC, "%s", err.message);
      gm_complex_free(cx), gm_mesh_free(mesh);
      return CLI_EXIT_USAGE;
    }
    gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
    if (diagonal) o.allow_negative_stars = 1; /* the diagonal star, as --diagonal asks */
    else o.star = GM_MESH_STAR_WHITNEY;
    gm_harminv_mode modes[MC_MAX_MODES];
    size_t nm = 0;
    double dt = 0.0;
    mx_progress progress; /* a line on a terminal only; steps known once dt is */
    mx_progress_start(&progress, 0);
    run.progress = show_progress;
    run.progress_ctx = &progress;
    st = gm_mesh_maxwell_cavity_modes(g, &o, &run, MC_MAX_MODES, modes, &nm, &dt, &err);
    mx_progress_end(&progress);
    const size_t ntet = gm_complex_count(cx, 3), nedge = gm_complex_count(cx, 1);
    gm_geometry_free(g), gm_complex_free(cx), gm_mesh_free(mesh);
    if (st != GM_OK) {
      cli_error(MC, "level %zu: %s%s", l + 1, err.message,
                st != GM_EDOMAIN ? ""
                : diagonal ? "; the run blew up: the diagonal star has non-positive entries on "
                             "this mesh (--diagonal accepts them), which no step cures: drop "
                             "--diagonal for the Whitney star"
                           : "; the run blew up");
      return CLI_EXIT_FAILURE;
    }
    for (size_t j = 0; j < nu; ++j) errs[j][l] = worst[j][l] = NAN;
    size_t spurious = 0, in_band = 0;
    for (size_t j = 0; j < na; ++j) in_band += ana[j] >= run.f_min && ana[j] <= run.f_max;
    printf("level %zu: h = %.4f, %zu tetrahedra, %zu edges, dt = %.4g; %zu peaks (analytic "
           "modes in the band, with multiplicity: %zu):", l + 1, hs[l], ntet, nedge, dt, nm,
           in_band);
    for (size_t i = 0; i < nm; ++i) {
      const double fs = gm_leapfrog_space_frequency(modes[i].frequency, dt);
      size_t best = 0;
      for (size_t j = 1; j < na; ++j)
        if (fabs(ana[j] - fs) < fabs(ana[best] - fs)) best = j;
      const double rel = (fs - ana[best]) / ana[best];
      printf(" %.5f", fs);
      if (fabs(rel) > 0.05) { ++spurious; printf("(SPURIOUS)"); }
      for (size_t j = 0; j < nu; ++j)
        if (ana[best] == uniq[j]) {
          if (!(fabs(errs[j][l]) <= fabs(rel))) errs[j][l] = rel;
          if (!(fabs(worst[j][l]) >= fabs(rel))) worst[j][l] = rel;
        }
    }
    printf("; spurious: %zu\n", spurious);
    total_spurious += spurious;
  }
  int split = 0, wide = 0; /* wide: a multiplet of more than two (the sphere's) */
  for (size_t j = 0; j < nu; ++j) split |= mult[j] > 1, wide |= mult[j] > 2;
  print_table("nearest peak", levels, hs, nu, uniq, mult, errs);
  if (split) print_table("farthest of the peaks nearest to the resonance (a split multiplet's "
                         "spread)", levels, hs, nu, uniq, mult, worst);
  /* the largest error over the band (farthest peaks, resonances found at every level): one
   * number per level that does not depend on which members of a multiplet harminv resolves */
  double bmax[MC_MAX_LEVELS], sx = 0, sy = 0, sxx = 0, sxy = 0;
  printf("\nlargest relative error in the band:");
  for (size_t l = 0; l < levels; ++l) {
    bmax[l] = 0.0;
    for (size_t j = 0; j < nu; ++j)
      if (!isnan(worst[j][l])) bmax[l] = fmax(bmax[l], fabs(worst[j][l]));
    printf(" %.2e", bmax[l]);
    const double x = log(hs[l]), y = log(bmax[l] + 1e-300);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  if (levels >= 2) printf(", rate %.2f", (levels * sxy - sx * sy) / (levels * sxx - sx * sx));
  printf("\n");
  printf("\nspurious peaks below the 10th resonance (all levels): %zu\n", total_spurious);
  if (plot) {
    double ys[MC_MAX_UNIQ][MC_MAX_LEVELS];
    char titles[MC_MAX_UNIQ][48];
    cli_xy_series series[MC_MAX_UNIQ];
    for (size_t j = 0; j < nu; ++j) {
      for (size_t l = 0; l < levels; ++l) /* NaN: left out */
        ys[j][l] = fabs(wide ? worst[j][l] : errs[j][l]);
      snprintf(titles[j], sizeof titles[j], "f = %.4f", uniq[j]);
      if (mult[j] > 1)
        snprintf(titles[j] + strlen(titles[j]), sizeof titles[j] - strlen(titles[j]), " (x%d)",
                 mult[j]);
      series[j] = (cli_xy_series){titles[j], levels, hs, ys[j]};
    }
    char title[96];
    snprintf(title, sizeof title, "PEC %s cavity: %s errors (%s leapfrog, harminv)", shape,
             wide ? "farthest-peak" : "resonance", diagonal ? "diagonal-star" : "Whitney");
    const int ps = cli_plot_loglog(MC, plot, title, "h", "|relative error|", series, nu);
    if (ps != CLI_EXIT_OK) return ps;
    printf("wrote %s\n", plot);
  }
  return CLI_EXIT_OK;
}
