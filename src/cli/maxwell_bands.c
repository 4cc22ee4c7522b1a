/* geomint maxwell bands SCENE.json --k-path G,X,M,G --points N --bands B: the band structure of
 * a periodic scene (a unit cell) along a k path, by gm_yee_bands_at at each k; writes
 * bands.csv and bands.png (gaps shaded). k in MEEP's convention: cycles per unit length. */
#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/maxwell.h"
#include "geomint/yee_bands.h"

#define COMMAND "maxwell bands"
#define MAX_K 4096
#define MAX_CORNERS 64

static const char usage[] =
    "usage: geomint maxwell bands SCENE.json (--k-path P1,P2,... [--points N] | --kx LIST\n"
    "                             [--ky LIST] [--kz LIST]) [--bands B] [--f-min F] [--f-max F]\n"
    "                             [--time T] [--probes P] [--sources S] [--seed S]\n"
    "                             [--out DIR] [--json] [--no-plot]\n\n"
    "The band structure of a periodic scene (every axis periodic: one unit cell): at each k a\n"
    "Bloch run rung by random-phase Gaussian dipoles at random points, random probes, each\n"
    "probe's signal filtered and decimated to the band, harminv; a frequency counts when two\n"
    "probes see it. k is in MEEP's convention, cycles per unit length (units of 2π/a for a\n"
    "lattice constant a = 1): the X point of a square lattice of period 1 is 0.5.\n\n"
    "  --k-path P,..  corners of the path: G (Γ), X (0.5/Lx, 0), Y (0, 0.5/Ly), M (0.5/Lx,\n"
    "                 0.5/Ly), R (0.5/Lx, 0.5/Ly, 0.5/Lz), or kx:ky[:kz]; at least two\n"
    "  --points N     k points along the path in all, corners included, spread over the\n"
    "                 segments by length (default 25)\n"
    "  --kx/--ky/--kz explicit k components, comma-separated lists of one length\n"
    "  --bands B      bands per k (default 5)\n"
    "  --f-min/--f-max  band searched (default: the scene's output.harminv band; f-min 0.05\n"
    "                 f-max without it)\n"
    "  --time T       analysed time per k after the sources (default 80/f_max)\n"
    "  --probes P, --sources S, --seed S   (defaults 8, 6, 7)\n"
    "  --out DIR      writes bands.csv and bands.png (default maxwell-bands)\n\n"
    "Exit status: 0 success, 1 a failed run, 2 bad input.\n";

typedef struct kpath {
  size_t n;
  double k[MAX_K][3];
  double s[MAX_K]; /* distance along the path */
} kpath;

static int corner(const char *name, const gm_yee_grid *g, double k[3]) {
  const double L[3] = {g->n[0] * g->h[0], g->n[1] * g->h[1], g->n[2] * g->h[2]};
  k[0] = k[1] = k[2] = 0;
  if (strcmp(name, "G") == 0 || strcmp(name, "Γ") == 0) return 0;
  if (strcmp(name, "X") == 0) { k[0] = 0.5 / L[0]; return 0; }
  if (strcmp(name, "Y") == 0) { k[1] = 0.5 / L[1]; return 0; }
  if (strcmp(name, "M") == 0) { k[0] = 0.5 / L[0]; k[1] = 0.5 / L[1]; return 0; }
  if (strcmp(name, "R") == 0) {
    for (int a = 0; a < 3; ++a) k[a] = 0.5 / L[a];
    return 0;
  }
  char *end = NULL;
  const char *p = name;
  for (int a = 0; a < 3; ++a) {
    k[a] = strtod(p, &end);
    if (end == p || !isfinite(k[a])) return -1;
    if (*end == '\0') return 0;
    if (*end != ':' || a == 2) return -1;
    p = end + 1;
  }
  return -1;
}

static int parse_path(const char *text, size_t points, const gm_yee_grid *g, kpath *out) {
  double c[MAX_CORNERS][3];
  size_t nc = 0;
  char buf[4096];
  snprintf(buf, sizeof buf, "%s", text);
  for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    if (nc == MAX_CORNERS) {
      cli_error(COMMAND, "--k-path: more than %d points", MAX_CORNERS);
      return CLI_EXIT_USAGE;
    }
    if (corner(tok, g, c[nc]) != 0) {
      cli_error(COMMAND, "--k-path: '%s' is not G, X, Y, M, R or kx:ky[:kz]", tok);
      return CLI_EXIT_USAGE;
    }
    ++nc;
  }
  if (nc < 2) {
    cli_error(COMMAND, "--k-path: a path needs at least two points (got %zu)", nc);
    return CLI_EXIT_USAGE;
  }
  if (points < nc || points > MAX_K) {
    cli_error(COMMAND, "--points: need %zu (the corners) to %d (got %zu)", nc, MAX_K, points);
    return CLI_EXIT_USAGE;
  }
  double len[MAX_CORNERS], total = 0;
  for (size_t i = 0; i + 1 < nc; ++i) {
    len[i] = hypot(hypot(c[i + 1][0] - c[i][0], c[i + 1][1] - c[i][1]), c[i + 1][2] - c[i][2]);
    total += len[i];
  }
  if (!(total > 0)) {
    cli_error(COMMAND, "--k-path: the path has zero length");
    return CLI_EXIT_USAGE;
  }
  /* intervals per segment by length (largest remainder), at least one each */
  size_t m[MAX_CORNERS], used = 0, intervals = points - 1;
  double rem[MAX_CORNERS];
  for (size_t i = 0; i + 1 < nc; ++i) {
    double want = (double)(intervals - (nc - 1)) * len[i] / total;
    m[i] = 1 + (size_t)floor(want);
    rem[i] = want - floor(want);
    used += m[i];
  }
  while (used < intervals) {
    size_t best = 0;
    for (size_t i = 1; i + 1 < nc; ++i)
      if (rem[i] > rem[best]) best = i;
    m[best]++;
    rem[best] = -1;
    used++;
  }
  out->n = 0;
  for (size_t i = 0; i + 1 < nc; ++i)
    for (size_t j = 0; j < m[i] + (i + 2 == nc ? 1 : 0); ++j) {
      double u = (double)j / (double)m[i];
      for (int a = 0; a < 3; ++a) out->k[out->n][a] = c[i][a] + u * (c[i + 1][a] - c[i][a]);
      out->n++;
    }
  double acc = 0;
  for (size_t i = 0; i < out->n; ++i) {
    if (i > 0)
      acc += hypot(hypot(out->k[i][0] - out->k[i - 1][0], out->k[i][1] - out->k[i - 1][1]),
                   out->k[i][2] - out->k[i - 1][2]);
    out->s[i] = acc;
  }
  return CLI_EXIT_OK;
}

static int parse_list(const char *opt, const char *text, double *v, size_t *n) {
  *n = 0;
  const char *p = text;
  while (*p) {
    char *end = NULL;
    double x = strtod(p, &end);
    if (end == p || !isfinite(x) || *n == MAX_K) {
      cli_error(COMMAND, "%s: expected comma-separated numbers (at most %d), got '%s'", opt, MAX_K,
                text);
      return CLI_EXIT_USAGE;
    }
    v[(*n)++] = x;
    if (*end == ',') ++end;
    else if (*end != '\0') {
      cli_error(COMMAND, "%s: expected comma-separated numbers, got '%s'", opt, text);
      return CLI_EXIT_USAGE;
    }
    p = end;
  }
  return CLI_EXIT_OK;
}

typedef struct band_plot {
  const kpath *path;
  size_t n_bands;
  const double *f; /* n × n_bands */
  const double *gap_lo, *gap_hi;
  size_t n_gaps;
} band_plot;

static void band_body(FILE *g, const void *ctx) {
  const band_plot *b = ctx;
  fputs("set grid\nset key off\nset xlabel 'distance along the k path (cycles per unit length)'"
        "\nset ylabel 'frequency (cycles per unit time)'\n",
        g);
  fprintf(g, "set xrange [0:%.12g]\n", b->path->s[b->path->n - 1]);
  for (size_t i = 0; i < b->n_gaps; ++i)
    fprintf(g, "set object %zu rect from graph 0, first %.12g to graph 1, first %.12g "
               "fc rgb '#ffd27f' fs solid 0.5 noborder behind\n",
            i + 1, b->gap_lo[i], b->gap_hi[i]);
  fputs("plot '-' using 1:2 with points pt 7 ps 0.8 lc rgb '#1f77b4'\n", g);
  size_t written = 0;
  for (size_t i = 0; i < b->path->n; ++i)
    for (size_t j = 0; j < b->n_bands; ++j)
      if (isfinite(b->f[i * b->n_bands + j])) {
        fprintf(g, "%.12g %.12g\n", b->path->s[i], b->f[i * b->n_bands + j]);
        ++written;
      }
  if (written == 0) fputs("0 NaN\n", g);
  fputs("e\n", g);
}

/* Gaps between band j and j+1: (max_k f_j, min_k f_{j+1}) when positive and no frequency of
 * any k falls inside (a degenerate pair listed once shifts the indices above it). */
static size_t find_gaps(const double *f, size_t nk, size_t nb, double *lo, double *hi) {
  size_t n = 0;
  for (size_t j = 0; j + 1 < nb; ++j) {
    double a = -INFINITY, b = INFINITY;
    for (size_t i = 0; i < nk; ++i) {
      double x = f[i * nb + j], y = f[i * nb + j + 1];
      if (!isfinite(x) || !isfinite(y)) { a = INFINITY; break; }
      a = fmax(a, x);
      b = fmin(b, y);
    }
    if (!(b > a)) continue;
    int clear = 1;
    for (size_t i = 0; i < nk * nb; ++i)
      if (f[i] > a && f[i] < b) clear = 0;
    if (clear) {
      lo[n] = a;
      hi[n] = b;
      ++n;
    }
  }
  return n;
}

int mx_bands_main(int argc, char **argv) {
  const char *out_dir = "maxwell-bands", *kpath_s = NULL, *kx_s = NULL, *ky_s = NULL,
             *kz_s = NULL;
  int json = 0, no_plot = 0;
  size_t points = 25, n_bands = 5, probes = 8, sources = 6, seed = 7;
  double f_min = NAN, f_max = NAN, time = 0;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &out_dir, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0},
                          {"--k-path", CLI_ARG_STRING, &kpath_s, 0},
                          {"--points", CLI_ARG_COUNT, &points, 0},
                          {"--kx", CLI_ARG_STRING, &kx_s, 0},
                          {"--ky", CLI_ARG_STRING, &ky_s, 0},
                          {"--kz", CLI_ARG_STRING, &kz_s, 0},
                          {"--bands", CLI_ARG_COUNT, &n_bands, 0},
                          {"--f-min", CLI_ARG_DOUBLE, &f_min, 0},
                          {"--f-max", CLI_ARG_DOUBLE, &f_max, 0},
                          {"--time", CLI_ARG_DOUBLE, &time, 0},
                          {"--probes", CLI_ARG_COUNT, &probes, 0},
                          {"--sources", CLI_ARG_COUNT, &sources, 0},
                          {"--seed", CLI_ARG_COUNT, &seed, 0}};
  const size_t n_opt = sizeof options / sizeof options[0];
  const char *positional[1];
  size_t n_pos = 0;
  int status = cli_parse(COMMAND, argc, argv, options, n_opt, positional, 1, &n_pos);
  if (status == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (status != CLI_EXIT_OK) return status;
  if (n_pos != 1) {
    cli_error(COMMAND, "expected a scene file: geomint maxwell bands SCENE.json --k-path G,X,M,G");
    return CLI_EXIT_USAGE;
  }
  if ((kpath_s != NULL) == (kx_s != NULL || ky_s != NULL || kz_s != NULL)) {
    cli_error(COMMAND, "give either --k-path or --kx/--ky/--kz lists");
    return CLI_EXIT_USAGE;
  }
  if (kpath_s == NULL && options[4].seen) {
    cli_error(COMMAND, "--points goes with --k-path (the --kx lists are used as given)");
    return CLI_EXIT_USAGE;
  }
  if (n_bands < 1 || n_bands > 100) {
    cli_error(COMMAND, "--bands: need 1..100 (got %zu)", n_bands);
    return CLI_EXIT_USAGE;
  }
  if (!isfinite(time) || time < 0) {
    cli_error(COMMAND, "--time: need a finite value >= 0 (got %g)", time);
    return CLI_EXIT_USAGE;
  }
  const char *path = positional[0];
  gm_yee_scene scene;
  gm_error err = {{0}};
  if (gm_yee_scene_load(path, &scene, &err) != GM_OK) {
    cli_error(COMMAND, "%s", err.message);
    return CLI_EXIT_USAGE;
  }
  if (isnan(f_max)) f_max = scene.harminv ? scene.harminv_fmax : NAN;
  if (isnan(f_min)) f_min = scene.harminv ? scene.harminv_fmin : 0.05 * f_max;
  kpath *kp = calloc(1, sizeof *kp);
  double *f = NULL;
  if (kp == NULL) {
    gm_yee_scene_clear(&scene);
    cli_error(COMMAND, "out of memory");
    return CLI_EXIT_FAILURE;
  }
  if (isnan(f_max)) {
    cli_error(COMMAND, "--f-max: needed (the scene has no output.harminv band)");
    status = CLI_EXIT_USAGE;
  } else if (!(f_min >= 0) || !(f_max > f_min) || !isfinite(f_max)) {
    cli_error(COMMAND, "--f-min/--f-max: need 0 <= f-min < f-max (got %g, %g)", f_min, f_max);
    status = CLI_EXIT_USAGE;
  }
  if (status == CLI_EXIT_OK && kpath_s != NULL)
    status = parse_path(kpath_s, points, &scene.grid, kp);
  if (status == CLI_EXIT_OK && kpath_s == NULL) {
    double *v = malloc(3 * MAX_K * sizeof *v);
    size_t n[3] = {0, 0, 0};
    const char *lists[3] = {kx_s, ky_s, kz_s}, *names[3] = {"--kx", "--ky", "--kz"};
    size_t nk = 0;
    for (int a = 0; a < 3 && status == CLI_EXIT_OK && v; ++a)
      if (lists[a]) {
        status = parse_list(names[a], lists[a], v + a * MAX_K, &n[a]);
        if (status == CLI_EXIT_OK && nk != 0 && n[a] != nk) {
          cli_error(COMMAND, "%s: %zu values, the other lists %zu", names[a], n[a], nk);
          status = CLI_EXIT_USAGE;
        }
        nk = n[a];
      }
    if (v == NULL) status = CLI_EXIT_FAILURE;
    kp->n = nk;
    for (size_t i = 0; status == CLI_EXIT_OK && i < nk; ++i) {
      for (int a = 0; a < 3; ++a) kp->k[i][a] = lists[a] ? v[a * MAX_K + i] : 0.0;
      kp->s[i] = i == 0 ? 0
                        : kp->s[i - 1] + hypot(hypot(kp->k[i][0] - kp->k[i - 1][0],
                                                     kp->k[i][1] - kp->k[i - 1][1]),
                                               kp->k[i][2] - kp->k[i - 1][2]);
    }
    free(v);
  }
  if (status == CLI_EXIT_OK && !no_plot) status = cli_prepare_plot_dir(COMMAND, out_dir, 0);
  else if (status == CLI_EXIT_OK) status = mx_make_dir(COMMAND, out_dir);
  gm_yee_bands_run run = gm_yee_bands_run_defaults();
  run.f_min = f_min;
  run.f_max = f_max;
  run.time = time;
  run.n_probes = probes;
  run.n_sources = sources;
  run.seed = seed;
  gm_yee_bands_info *info = NULL;
  if (status == CLI_EXIT_OK) {
    f = malloc(kp->n * n_bands * sizeof *f);
    info = calloc(kp->n, sizeof *info);
    if (f == NULL || info == NULL) status = CLI_EXIT_FAILURE;
  }
  double t0 = mx_now();
  size_t lost = 0, extra = 0;
  for (size_t i = 0; status == CLI_EXIT_OK && i < kp->n; ++i) {
    gm_status st = gm_yee_bands_at(&scene.grid, scene.materials, &scene.options, kp->k[i],
                                   n_bands, &run, f + i * n_bands, &info[i], &err);
    if (st != GM_OK) {
      cli_error(COMMAND, "k = (%g, %g, %g): %s", kp->k[i][0], kp->k[i][1], kp->k[i][2],
                err.message);
      status = i == 0 && st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
    } else {
      /* k = 0: uniform fields solve Maxwell's equations in any periodic medium, so the first
       * band is ω = 0 there (as MPB lists it); it is no resonance harminv could see. Listed
       * so that band indices (and gaps) line up along the path. */
      double *fi = f + i * n_bands;
      if (kp->k[i][0] == 0 && kp->k[i][1] == 0 && kp->k[i][2] == 0) {
        memmove(fi + 1, fi, (n_bands - 1) * sizeof *fi);
        fi[0] = 0;
        if (info[i].n_lost > 0) info[i].n_lost--;
      }
      lost += info[i].n_lost;
      extra += info[i].n_extra;
    }
  }
  const double wall = mx_now() - t0;
  double gap_lo[100], gap_hi[100];
  size_t n_gaps = 0;
  char file[4096];
  if (status == CLI_EXIT_OK) {
    n_gaps = find_gaps(f, kp->n, n_bands, gap_lo, gap_hi);
    FILE *csv = fopen(mx_path(file, sizeof file, out_dir, "bands.csv"), "w");
    if (csv == NULL) {
      cli_error(COMMAND, "cannot write %s", file);
      status = CLI_EXIT_FAILURE;
    } else {
      fputs("k_index,kx,ky,kz,path_distance", csv);
      for (size_t j = 0; j < n_bands; ++j) fprintf(csv, ",band%zu", j + 1);
      fputs(",found,lost,extra\n", csv);
      for (size_t i = 0; i < kp->n; ++i) {
        fprintf(csv, "%zu,%.10g,%.10g,%.10g,%.10g", i, kp->k[i][0], kp->k[i][1], kp->k[i][2],
                kp->s[i]);
        for (size_t j = 0; j < n_bands; ++j) fprintf(csv, ",%.10g", f[i * n_bands + j]);
        fprintf(csv, ",%zu,%zu,%zu\n", info[i].n_found, info[i].n_lost, info[i].n_extra);
      }
      if (fclose(csv) != 0) status = CLI_EXIT_FAILURE;
    }
  }
  if (status == CLI_EXIT_OK && !no_plot) {
    band_plot bp = {kp, n_bands, f, gap_lo, gap_hi, n_gaps};
    char title[512];
    snprintf(title, sizeof title, "%s: %zu bands at %zu k points", path, n_bands, kp->n);
    status = cli_plot_custom(COMMAND, mx_path(file, sizeof file, out_dir, "bands.png"), title,
                             band_body, &bp);
  }
  if (status == CLI_EXIT_OK && json) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "scene", path);
    cJSON_AddNumberToObject(root, "f_min", f_min);
    cJSON_AddNumberToObject(root, "f_max", f_max);
    cJSON_AddNumberToObject(root, "wall_seconds", wall);
    cJSON_AddNumberToObject(root, "lost", (double)lost);
    cJSON_AddNumberToObject(root, "extra", (double)extra);
    cJSON *ks = cJSON_AddArrayToObject(root, "k_points");
    for (size_t i = 0; i < kp->n; ++i) {
      cJSON *o = cJSON_CreateObject();
      cJSON_AddItemToObject(o, "k", cli_json_numbers(kp->k[i], 3));
      cJSON_AddItemToObject(o, "frequencies", cli_json_numbers(f + i * n_bands, n_bands));
      cJSON_AddNumberToObject(o, "found", (double)info[i].n_found);
      cJSON_AddNumberToObject(o, "lost", (double)info[i].n_lost);
      cJSON_AddNumberToObject(o, "extra", (double)info[i].n_extra);
      cJSON_AddNumberToObject(o, "harminv_basis", (double)info[i].n_basis);
      cJSON_AddNumberToObject(o, "decimation", (double)info[i].decimation);
      cJSON_AddItemToArray(ks, o);
    }
    cJSON *gaps = cJSON_AddArrayToObject(root, "gaps");
    for (size_t g = 0; g < n_gaps; ++g) {
      double pair[2] = {gap_lo[g], gap_hi[g]};
      cJSON_AddItemToArray(gaps, cli_json_numbers(pair, 2));
    }
    status = cli_json_print(root);
  } else if (status == CLI_EXIT_OK) {
    printf("maxwell bands %s: %zu k points, %zu bands in [%g, %g], %.3f s\n", path, kp->n,
           n_bands, f_min, f_max, wall);
    printf("  harminv basis %zu on %zu samples (decimation %zu) per probe\n", info[0].n_basis,
           info[0].n_samples, info[0].decimation);
    printf("  lost %zu band values (fewer than %zu resonances found), %zu extra (one probe "
           "only, rejected)\n",
           lost, n_bands, extra);
    for (size_t g = 0; g < n_gaps; ++g)
      printf("  gap %.6g .. %.6g (%.2f%% of its centre)\n", gap_lo[g], gap_hi[g],
             200 * (gap_hi[g] - gap_lo[g]) / (gap_hi[g] + gap_lo[g]));
    printf("  wrote %s/bands.csv%s\n", out_dir, no_plot ? "" : " and bands.png");
  }
  free(f);
  free(info);
  free(kp);
  gm_yee_scene_clear(&scene);
  return status;
}
