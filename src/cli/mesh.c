/* geomint mesh info FILE [--json] | geomint mesh poisson FILE [--out FILE.vtu]: read a mesh (Gmsh
 * .msh or OFF), report its topology and quality, or solve a manufactured Poisson problem on it. */
#include <cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"

static const char usage[] =
    "usage: geomint mesh info FILE [--json]\n"
    "       geomint mesh poisson FILE [--out FILE.vtu]\n"
    "       geomint mesh poisson --levels L [--dim 2|3] [--n0 N] [--json]\n\n"
    "Read a mesh (Gmsh .msh ASCII 2.2 or 4.1, or .off) and\n"
    "  info     print counts, Euler characteristic, Betti numbers, boundary, and the quality\n"
    "           report: non-manifold faces, reoriented, degenerate and inverted cells, cells that\n"
    "           are not well-centred, negative dual volumes, min/max Hodge star entries\n"
    "  poisson  solve -Δu = f with the manufactured solution u = Π sin(π(x_i − lo_i)/L_i + 1/4)\n"
    "           (bounding box lo, L) and Dirichlet data, with the DEC Laplacian, and print the\n"
    "           error (a quick check that a mesh is fit for DEC); with --levels L, on L\n"
    "           generated meshes of the unit square (--dim 2, default) or cube (--dim 3) with\n"
    "           N, 2N, ..., 2^(L-1) N cells a side (--n0 N, default 4), printing the errors and\n"
    "           their observed rate of convergence\n\n"
    "options:\n"
    "  --json       (info, poisson --levels) print one JSON object\n"
    "  --out FILE   (poisson) write the mesh with u_h, u and the error to a .vtu file\n"
    "  --max-file-size SIZE  refuse files larger than SIZE bytes (suffix K, M, G: powers of\n"
    "               1024; default 1G); a NUL byte (a binary file, /dev/zero) is refused at once\n\n"
    "Exit status: 0 success (info: also for a mesh with defects, which are reported), 1 the\n"
    "file cannot be read or the problem cannot be solved, 2 bad arguments.\n";

static const char *const names[] = {"vertices", "edges", "faces", "cells"};

/* --max-file-size: bytes, with an optional K, M or G (powers of 1024); 0 when not a size. */
static size_t parse_size(const char *text) {
  char *end = NULL;
  errno = 0;
  double v = strtod(text, &end);
  if (end == text || errno == ERANGE || !(v >= 1.0)) return 0;
  double unit = 1.0;
  if (*end == 'K' || *end == 'k') unit = 1024.0, ++end;
  else if (*end == 'M' || *end == 'm') unit = 1024.0 * 1024.0, ++end;
  else if (*end == 'G' || *end == 'g') unit = 1024.0 * 1024.0 * 1024.0, ++end;
  if (*end != '\0' || !(v * unit < 0x1p62)) return 0;
  return (size_t)(v * unit);
}

static size_t max_file_bytes = GM_MESH_MAX_FILE_BYTES;

/* Read a mesh; on failure print one line (with how to raise the size limit when that was hit). */
/* A bad file is bad input (exit 2); running out of memory is a failure (exit 1). */
static int input_status(gm_status st) {
  return st == GM_ENOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
}

/* Reads the mesh; CLI_EXIT_OK, or the exit status after printing the reader's message. */
static int read_mesh(const char *path, gm_mesh **m) {
  gm_error err = {{0}};
  gm_status st = gm_mesh_read_max(path, max_file_bytes, m, &err);
  if (st == GM_OK) return CLI_EXIT_OK;
  if (strstr(err.message, "more than the limit of") != NULL)
    cli_error("mesh", "%s (raise it with --max-file-size)", err.message);
  else
    cli_error("mesh", "%s", err.message);
  return input_status(st);
}

static void print_info(const char *path, const gm_mesh_report *r) {
  printf("mesh %s: %zu-simplices in R^%zu\n", path, r->dim, r->N);
  for (size_t k = 0; k <= r->dim; ++k) {
    const char *name = k == r->dim ? "cells" : names[k];
    if (r->complex_ok)
      printf("  %-28s %zu (boundary %zu)\n", name, r->count[k], r->boundary_count[k]);
    else if (k == 0 || k == r->dim)
      printf("  %-28s %zu\n", name, r->count[k]);
  }
  if (!r->complex_ok) {
    printf("  not a valid complex: %s\n", r->complex_error);
  } else {
    printf("  %-28s %ld\n", "Euler characteristic", r->euler_characteristic);
    if (r->betti_known) {
      printf("  %-28s", "Betti numbers");
      for (size_t k = 0; k <= r->dim; ++k) printf(" %zu", r->betti[k]);
      printf("\n");
    } else {
      printf("  %-28s unknown (closed 3-D complex)\n", "Betti numbers");
    }
  }
  printf("quality:\n");
  printf("  %-28s %zu\n", "non-manifold faces", r->non_manifold);
  if (r->complex_ok) printf("  %-28s %zu\n", "reoriented cells", r->reoriented);
  printf("  %-28s %zu\n", "degenerate cells", r->degenerate);
  if (r->geometry_ok) printf("  %-28s %zu\n", "inverted cells", r->inverted);
  printf("  %-28s %zu\n", "not well-centred cells", r->not_well_centred);
  printf("  %-28s %.6g / %.6g\n", "shortest / longest edge", r->shortest_edge, r->longest_edge);
  if (r->out_of_range > 0)
    printf("  %-28s %zu cells outside double precision (rescale the mesh)\n", "cell volumes",
           r->out_of_range);
  else
    printf("  %-28s %.6g / %.6g\n", "smallest / largest cell", r->min_volume, r->max_volume);
  if (r->geometry_ok) {
    for (size_t k = 0; k <= r->dim; ++k) {
      char label[64];
      snprintf(label, sizeof label, "negative duals (k = %zu)", k);
      printf("  %-28s %zu\n", label, r->negative_duals[k]);
    }
    for (size_t k = 0; k <= r->dim; ++k) {
      char label[64];
      snprintf(label, sizeof label, "Hodge star %zu min / max", k);
      printf("  %-28s %.6g / %.6g\n", label, r->star_min[k], r->star_max[k]);
    }
  } else if (r->complex_ok) {
    printf("  no geometry: %s\n", r->geometry_error);
  }
}

static int info_json(const char *path, const gm_mesh_report *r) {
  cJSON *o = cJSON_CreateObject();
  cJSON_AddStringToObject(o, "file", path);
  cJSON_AddNumberToObject(o, "dim", (double)r->dim);
  cJSON_AddNumberToObject(o, "embedding_dim", (double)r->N);
  double counts[4], bcounts[4], betti[4], neg[4];
  for (size_t k = 0; k <= r->dim; ++k) {
    counts[k] = (double)r->count[k];
    bcounts[k] = (double)r->boundary_count[k];
    betti[k] = (double)r->betti[k];
    neg[k] = (double)r->negative_duals[k];
  }
  cJSON_AddItemToObject(o, "counts", cli_json_numbers(counts, r->dim + 1));
  cJSON_AddBoolToObject(o, "valid_complex", r->complex_ok != 0);
  if (r->complex_ok) {
    cJSON_AddItemToObject(o, "boundary_counts", cli_json_numbers(bcounts, r->dim + 1));
    cJSON_AddNumberToObject(o, "euler_characteristic", (double)r->euler_characteristic);
    if (r->betti_known)
      cJSON_AddItemToObject(o, "betti", cli_json_numbers(betti, r->dim + 1));
    else
      cJSON_AddNullToObject(o, "betti");
    cJSON_AddNumberToObject(o, "reoriented", (double)r->reoriented);
  } else {
    cJSON_AddStringToObject(o, "complex_error", r->complex_error);
  }
  cJSON_AddNumberToObject(o, "non_manifold_faces", (double)r->non_manifold);
  cJSON_AddNumberToObject(o, "degenerate", (double)r->degenerate);
  cJSON_AddNumberToObject(o, "not_well_centred", (double)r->not_well_centred);
  cJSON_AddItemToObject(o, "shortest_edge", cli_json_number(r->shortest_edge));
  cJSON_AddItemToObject(o, "longest_edge", cli_json_number(r->longest_edge));
  cJSON_AddItemToObject(o, "min_volume", cli_json_number(r->min_volume));
  cJSON_AddItemToObject(o, "max_volume", cli_json_number(r->max_volume));
  cJSON_AddNumberToObject(o, "volumes_out_of_range", (double)r->out_of_range);
  cJSON_AddBoolToObject(o, "geometry", r->geometry_ok != 0);
  if (r->geometry_ok) {
    cJSON_AddNumberToObject(o, "inverted", (double)r->inverted);
    cJSON_AddItemToObject(o, "negative_duals", cli_json_numbers(neg, r->dim + 1));
    cJSON_AddItemToObject(o, "hodge_star_min", cli_json_numbers(r->star_min, r->dim + 1));
    cJSON_AddItemToObject(o, "hodge_star_max", cli_json_numbers(r->star_max, r->dim + 1));
  } else if (r->complex_ok) {
    cJSON_AddStringToObject(o, "geometry_error", r->geometry_error);
  }
  return cli_json_print(o);
}

static int mesh_info(const char *path, int json) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  int status = read_mesh(path, &m);
  if (status != CLI_EXIT_OK) return status;
  gm_mesh_report r;
  gm_status st = gm_mesh_quality(m, &r, &err);
  gm_mesh_free(m);
  if (st != GM_OK) {
    cli_error("mesh", "%s", err.message);
    return input_status(st);
  }
  if (json) return info_json(path, &r);
  print_info(path, &r);
  return CLI_EXIT_OK;
}

static int mesh_poisson(const char *path, const char *out) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  int status = read_mesh(path, &m);
  if (status != CLI_EXIT_OK) return status;
  gm_poisson_report rep;
  double *u = malloc(m->n_vertices * sizeof(double));
  if (u == NULL) {
    gm_mesh_free(m);
    cli_error("mesh", "out of memory");
    return CLI_EXIT_FAILURE;
  }
  gm_status st = gm_mesh_poisson(m, &rep, u, &err);
  if (st != GM_OK) {
    cli_error("mesh", "poisson on %s: %s", path, err.message);
    free(u);
    gm_mesh_free(m);
    return CLI_EXIT_FAILURE;
  }
  printf("poisson on %s: -Δu = f, u = Π sin(π(x_i − lo_i)/L_i + 1/4), Dirichlet boundary\n", path);
  printf("  %-24s %zu (%zu unknowns)\n", "vertices", rep.n_vertices, rep.n_unknowns);
  printf("  %-24s %.6g\n", "h (longest edge)", rep.h);
  printf("  %-24s %.6e\n", "max error", rep.error_max);
  printf("  %-24s %.6e\n", "L2 error", rep.error_l2);
  printf("  %-24s %.6e\n", "relative max error", rep.error_max / rep.solution_max);
  status = CLI_EXIT_OK;
  if (out != NULL) {
    gm_complex *cx = NULL;
    st = gm_mesh_complex(m, &cx, &err);
    double *ex = malloc(m->n_vertices * sizeof(double)), *e = malloc(m->n_vertices * sizeof(double));
    if (st == GM_OK && ex && e) {
      /* the exact solution, as gm_mesh_poisson defines it (bounding box of the mesh) */
      double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
      for (size_t j = 0; j < m->N; ++j) lo[j] = hi[j] = m->x[j];
      for (size_t v = 0; v < m->n_vertices; ++v)
        for (size_t j = 0; j < m->N; ++j) {
          double x = m->x[v * m->N + j];
          if (x < lo[j]) lo[j] = x;
          if (x > hi[j]) hi[j] = x;
        }
      for (size_t v = 0; v < m->n_vertices; ++v) {
        double s = 1.0;
        for (size_t j = 0; j < m->N; ++j)
          s *= sin(3.14159265358979323846 * (m->x[v * m->N + j] - lo[j]) / (hi[j] - lo[j]) + 0.25);
        ex[v] = s;
        e[v] = u[v] - s;
      }
      gm_vtu_field f[3] = {{"u_h", 0, 1, u}, {"u", 0, 1, ex}, {"error", 0, 1, e}};
      st = gm_vtu_write(out, cx, 3, f, &err);
    } else if (st == GM_OK) {
      st = GM_ENOMEM;
      snprintf(err.message, sizeof err.message, "out of memory");
    }
    if (st != GM_OK) {
      cli_error("mesh", "%s", err.message);
      status = CLI_EXIT_FAILURE;
    } else {
      printf("  %-24s %s\n", "wrote", out);
    }
    free(ex), free(e);
    gm_complex_free(cx);
  }
  free(u);
  gm_mesh_free(m);
  return status;
}

/* mesh poisson --levels L: the check on generated meshes of the unit square (dim 2: n×n squares
 * cut by one diagonal) or cube (dim 3: n³ cubes in 6 Kuhn tetrahedra), n = n0, 2 n0, ...,
 * 2^(L−1) n0, with the observed rate log(e_{k−1}/e_k) / log(h_{k−1}/h_k) of each error. */
static int poisson_levels(size_t levels, size_t dim, size_t n0, int json) {
  if (levels < 2 || levels > 12) {
    cli_error("mesh", "--levels %zu: give 2 to 12 levels", levels);
    return CLI_EXIT_USAGE;
  }
  if (dim != 2 && dim != 3) {
    cli_error("mesh", "--dim %zu: the generated meshes are 2 (square) or 3 (cube)", dim);
    return CLI_EXIT_USAGE;
  }
  if (n0 < 2 || (double)n0 * pow(2.0, (double)(levels - 1)) > (dim == 2 ? 4096.0 : 128.0)) {
    cli_error("mesh", "--n0 %zu with %zu levels: need n0 >= 2 and at most %d cells a side on the "
              "finest level",
              n0, levels, dim == 2 ? 4096 : 128);
    return CLI_EXIT_USAGE;
  }
  cJSON *root = json ? cJSON_CreateObject() : NULL, *rows = NULL;
  if (json) {
    cJSON_AddStringToObject(root, "mesh", dim == 2 ? "unit square, n x n squares cut by a diagonal"
                                                   : "unit cube, n^3 cubes in 6 Kuhn tetrahedra");
    rows = cJSON_AddArrayToObject(root, "levels");
  } else {
    printf("poisson on generated meshes of the unit %s: -Δu = f, u = Π sin(π x_i + 1/4)\n",
           dim == 2 ? "square" : "cube");
    printf("  %5s %9s %10s %13s %6s %13s %6s\n", "n", "vertices", "h", "max error", "rate",
           "L2 error", "rate");
  }
  double prev_h = NAN, prev_max = NAN, prev_l2 = NAN, rate_max = NAN, rate_l2 = NAN;
  for (size_t k = 0; k < levels; ++k) {
    const size_t n = n0 << k;
    gm_mesh *m = NULL;
    gm_error err = {{0}};
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    gm_status st = dim == 2 ? gm_mesh_rectangle(0, 1, 0, 1, n, n, GM_DIAGONAL_RIGHT, &m, &err)
                            : gm_mesh_box(lo, hi, n, n, n, GM_BOX_KUHN, &m, &err);
    gm_poisson_report rep;
    if (st == GM_OK) st = gm_mesh_poisson(m, &rep, NULL, &err);
    gm_mesh_free(m);
    if (st != GM_OK) {
      cli_error("mesh", "poisson at n = %zu: %s", n, err.message);
      cJSON_Delete(root);
      return CLI_EXIT_FAILURE;
    }
    if (k > 0) {
      rate_max = log(prev_max / rep.error_max) / log(prev_h / rep.h);
      rate_l2 = log(prev_l2 / rep.error_l2) / log(prev_h / rep.h);
    }
    if (json) {
      cJSON *o = cJSON_CreateObject();
      cJSON_AddNumberToObject(o, "n", (double)n);
      cJSON_AddNumberToObject(o, "vertices", (double)rep.n_vertices);
      cJSON_AddItemToObject(o, "h", cli_json_number(rep.h));
      cJSON_AddItemToObject(o, "error_max", cli_json_number(rep.error_max));
      cJSON_AddItemToObject(o, "error_l2", cli_json_number(rep.error_l2));
      if (k > 0) {
        cJSON_AddItemToObject(o, "rate_max", cli_json_number(rate_max));
        cJSON_AddItemToObject(o, "rate_l2", cli_json_number(rate_l2));
      }
      cJSON_AddItemToArray(rows, o);
    } else if (k == 0) {
      printf("  %5zu %9zu %10.4g %13.6e %6s %13.6e %6s\n", n, rep.n_vertices, rep.h,
             rep.error_max, "", rep.error_l2, "");
    } else {
      printf("  %5zu %9zu %10.4g %13.6e %6.3f %13.6e %6.3f\n", n, rep.n_vertices, rep.h,
             rep.error_max, rate_max, rep.error_l2, rate_l2);
    }
    prev_h = rep.h, prev_max = rep.error_max, prev_l2 = rep.error_l2;
  }
  if (json) {
    cJSON_AddItemToObject(root, "rate_max", cli_json_number(rate_max));
    cJSON_AddItemToObject(root, "rate_l2", cli_json_number(rate_l2));
    return cli_json_print(root);
  }
  printf("rate of the finest level: max error %.3f, L2 error %.3f (2 is second order)\n", rate_max,
         rate_l2);
  return CLI_EXIT_OK;
}

static int mesh_main(int argc, char **argv) {
  int json = 0;
  const char *out = NULL, *max_size = NULL;
  size_t levels = 0, dim = 2, n0 = 4;
  cli_option options[] = {{"--json", CLI_ARG_FLAG, &json, 0},
                          {"--out", CLI_ARG_STRING, &out, 0},
                          {"--max-file-size", CLI_ARG_STRING, &max_size, 0},
                          {"--levels", CLI_ARG_COUNT, &levels, 0},
                          {"--dim", CLI_ARG_COUNT, &dim, 0},
                          {"--n0", CLI_ARG_COUNT, &n0, 0}};
  const char *pos[2];
  size_t n_pos = 0;
  int status = cli_parse("mesh", argc, argv, options, sizeof options / sizeof options[0], pos, 2,
                         &n_pos);
  if (status == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (status != CLI_EXIT_OK) return status;
  if (max_size != NULL && (max_file_bytes = parse_size(max_size)) == 0) {
    cli_error("mesh", "--max-file-size %s: expected a size in bytes such as 4096, 64M or 2G",
              max_size);
    return CLI_EXIT_USAGE;
  }
  if (n_pos >= 1 && strcmp(pos[0], "poisson") == 0 && options[3].seen) {
    if (n_pos > 1 || options[1].seen) {
      cli_error("mesh", "poisson --levels runs on generated meshes: no FILE, no --out");
      return CLI_EXIT_USAGE;
    }
    return poisson_levels(levels, dim, n0, json);
  }
  if (options[4].seen || options[5].seen) {
    cli_error("mesh", "--dim and --n0 belong to 'mesh poisson --levels'");
    return CLI_EXIT_USAGE;
  }
  if (n_pos < 2) {
    cli_error("mesh", "expected 'info FILE' or 'poisson FILE' (see geomint mesh --help)");
    return CLI_EXIT_USAGE;
  }
  if (strcmp(pos[0], "info") == 0) {
    if (options[1].seen) {
      cli_error("mesh", "--out belongs to 'mesh poisson'");
      return CLI_EXIT_USAGE;
    }
    return mesh_info(pos[1], json);
  }
  if (strcmp(pos[0], "poisson") == 0) {
    if (json) {
      cli_error("mesh", "--json belongs to 'mesh info'");
      return CLI_EXIT_USAGE;
    }
    return mesh_poisson(pos[1], out);
  }
  cli_error("mesh", "unknown subcommand '%s': use 'info' or 'poisson'", pos[0]);
  return CLI_EXIT_USAGE;
}

const cli_command cli_mesh_command = {"mesh", "read a mesh: topology, quality, Poisson check", usage,
                                      mesh_main};
