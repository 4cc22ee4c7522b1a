/* geomint mesh info FILE [--json] | geomint mesh poisson FILE [--out FILE.vtu]: read a mesh (Gmsh
 * .msh or OFF), report its topology and quality, or solve a manufactured Poisson problem on it. */
#include <cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/mesh_multigrid.h"

static const char usage[] =
    "usage: geomint mesh info FILE [--json]\n"
    "       geomint mesh poisson FILE [--out FILE.vtu] [--solver cholmod|mg|hypre] [--refine L]\n"
    "                            [--json]\n"
    "       geomint mesh poisson --levels L [--dim 2|3] [--n0 N] [--json]\n"
    "       geomint mesh refine FILE --levels L [--out FILE.msh] [--max-memory SIZE] [--json]\n"
    "       geomint mesh transfer A B [--json]\n\n"
    "Read a mesh (Gmsh .msh ASCII 2.2 or 4.1, or .off) and\n"
    "  info     print counts, Euler characteristic, Betti numbers, boundary, and the quality\n"
    "           report: non-manifold faces, reoriented, degenerate and inverted cells, cells that\n"
    "           are not well-centred, negative dual volumes, min/max Hodge star entries\n"
    "  poisson  solve -Δu = f with the manufactured solution u = Π sin(π(x_i − lo_i)/L_i + 1/4)\n"
    "           (bounding box lo, L) and Dirichlet data, with the DEC Laplacian, and print the\n"
    "           error (a quick check that a mesh is fit for DEC); with --levels L, on L\n"
    "           generated meshes of the unit square (--dim 2, default) or cube (--dim 3) with\n"
    "           N, 2N, ..., 2^(L-1) N cells a side (--n0 N, default 4), printing the errors and\n"
    "           their observed rate of convergence\n"
    "  refine   L levels of red refinement (triangles into 4, tetrahedra into 8 by Bey's rule),\n"
    "           printing counts, time and how many children of well-centred cells are\n"
    "           well-centred; --out writes the finest mesh (Gmsh 2.2)\n"
    "  transfer the support-volume transfer of top forms and 0-forms between two triangle\n"
    "           meshes of one planar domain (polygon clipping), both ways: areas, the change of\n"
    "           the total of a top form, the error on a constant and on a linear 0-form;\n"
    "           meshes of different domains are refused (exit 2) with their areas\n\n"
    "options:\n"
    "  --json       print one JSON object\n"
    "  --out FILE   (poisson) write the mesh with u_h, u and the error to a .vtu file;\n"
    "               (refine) write the finest mesh as .msh\n"
    "  --solver S   (poisson FILE) cholmod, mg: CG preconditioned by a geometric\n"
    "               multigrid V-cycle on the hierarchy FILE -> --refine L refinements (L >= 1),\n"
    "               or hypre: CG preconditioned by BoomerAMG (needs a build with libhypre-dev);\n"
    "               default: mg with --refine, else cholmod below 10000 unknowns, else hypre\n"
    "               (the measurement behind it: docs/dec.md, 'Which solver')\n"
    "  --refine L   (poisson FILE) solve on the mesh refined L times (default 0)\n"
    "  --max-memory SIZE  (refine, poisson) refuse a refinement whose mesh needs more (suffix\n"
    "               K, M, G; default: the physical memory)\n"
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

static int mesh_poisson(const char *path, const char *out, const gm_poisson_options *opt,
                        int json) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  int status = read_mesh(path, &m);
  if (status != CLI_EXIT_OK) return status;
  gm_poisson_report rep;
  double *u = NULL;
  gm_status st = gm_mesh_poisson_solve(m, opt, &rep, &u, &err);
  if (st != GM_OK) {
    cli_error("mesh", "poisson on %s: %s", path, err.message);
    free(u);
    gm_mesh_free(m);
    return st == GM_EINVAL && opt->solver == GM_POISSON_MULTIGRID && opt->levels == 0
               ? CLI_EXIT_USAGE
               : CLI_EXIT_FAILURE;
  }
  if (!json) {
  printf("poisson on %s: -Δu = f, u = Π sin(π(x_i − lo_i)/L_i + 1/4), Dirichlet boundary\n", path);
  if (opt->levels > 0) printf("  %-24s %zu (%zu cells)\n", "refinements", opt->levels, rep.n_cells);
  printf("  %-24s %zu (%zu unknowns)\n", "vertices", rep.n_vertices, rep.n_unknowns);
  if (rep.solver == GM_POISSON_MULTIGRID) {
    printf("  %-24s mg: CG + V(%zu,%zu) Gauss-Seidel, %zu levels\n", "solver", opt->pre_smooth,
           opt->post_smooth, opt->levels + 1);
    printf("  %-24s %zu (relative residual %.3e)\n", "CG iterations", rep.iterations,
           rep.relative_residual);
    printf("  %-24s %.4f\n", "V-cycle contraction", rep.contraction);
  } else if (rep.solver == GM_POISSON_HYPRE) {
    printf("  %-24s hypre: CG + BoomerAMG\n", "solver");
    printf("  %-24s %zu (relative residual %.3e)\n", "CG iterations", rep.iterations,
           rep.relative_residual);
  } else {
    printf("  %-24s cholmod (relative residual %.3e)\n", "solver", rep.relative_residual);
  }
  printf("  %-24s %.3f / %.3f / %.3f\n", "setup / factor / solve s", rep.setup_s, rep.factor_s,
         rep.solve_s);
  printf("  %-24s %.6g\n", "h (longest edge)", rep.h);
  printf("  %-24s %.6e\n", "max error", rep.error_max);
  printf("  %-24s %.6e\n", "L2 error", rep.error_l2);
  printf("  %-24s %.6e\n", "relative max error", rep.error_max / rep.solution_max);
  }
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
    } else if (!json) {
      printf("  %-24s %s\n", "wrote", out);
    }
    free(ex), free(e);
    gm_complex_free(cx);
  }
  free(u);
  gm_mesh_free(m);
  if (json && status == CLI_EXIT_OK) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "mesh", path);
    cJSON_AddNumberToObject(o, "refinements", (double)opt->levels);
    cJSON_AddNumberToObject(o, "cells", (double)rep.n_cells);
    cJSON_AddNumberToObject(o, "vertices", (double)rep.n_vertices);
    cJSON_AddNumberToObject(o, "unknowns", (double)rep.n_unknowns);
    /* the solver that ran (the default picks one by size: rep.solver) */
    cJSON_AddStringToObject(o, "solver", rep.solver == GM_POISSON_MULTIGRID ? "mg"
                                         : rep.solver == GM_POISSON_HYPRE   ? "hypre"
                                                                            : "cholmod");
    if (rep.solver != GM_POISSON_CHOLMOD)
      cJSON_AddNumberToObject(o, "cg_iterations", (double)rep.iterations);
    if (rep.solver == GM_POISSON_MULTIGRID)
      cJSON_AddItemToObject(o, "contraction", cli_json_number(rep.contraction));
    cJSON_AddItemToObject(o, "relative_residual", cli_json_number(rep.relative_residual));
    cJSON_AddNumberToObject(o, "setup_s", rep.setup_s);
    cJSON_AddNumberToObject(o, "factor_s", rep.factor_s);
    cJSON_AddNumberToObject(o, "solve_s", rep.solve_s);
    cJSON_AddNumberToObject(o, "wall_s", rep.setup_s + rep.factor_s + rep.solve_s);
    cJSON_AddItemToObject(o, "h", cli_json_number(rep.h));
    cJSON_AddItemToObject(o, "error_max", cli_json_number(rep.error_max));
    cJSON_AddItemToObject(o, "error_l2", cli_json_number(rep.error_l2));
    cJSON_AddItemToObject(o, "max_rel_error", cli_json_number(rep.error_max / rep.solution_max));
    if (out != NULL) cJSON_AddStringToObject(o, "vtu", out);
    status = cli_json_print(o);
  }
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
  const char *out = NULL, *max_size = NULL, *solver = NULL, *max_memory = NULL;
  size_t levels = 0, dim = 2, n0 = 4, refine = 0;
  cli_option options[] = {{"--json", CLI_ARG_FLAG, &json, 0},
                          {"--out", CLI_ARG_STRING, &out, 0},
                          {"--max-file-size", CLI_ARG_STRING, &max_size, 0},
                          {"--levels", CLI_ARG_COUNT, &levels, 0},
                          {"--dim", CLI_ARG_COUNT, &dim, 0},
                          {"--n0", CLI_ARG_COUNT, &n0, 0},
                          {"--solver", CLI_ARG_STRING, &solver, 0},
                          {"--refine", CLI_ARG_COUNT, &refine, 0},
                          {"--max-memory", CLI_ARG_STRING, &max_memory, 0}};
  const char *pos[3];
  size_t n_pos = 0;
  int status = cli_parse("mesh", argc, argv, options, sizeof options / sizeof options[0], pos, 3,
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
  size_t max_memory_bytes = 0;
  if (max_memory != NULL && (max_memory_bytes = parse_size(max_memory)) == 0) {
    cli_error("mesh", "--max-memory %s: expected a size in bytes such as 4096, 64M or 2G",
              max_memory);
    return CLI_EXIT_USAGE;
  }
  const int is_poisson_file = n_pos == 2 && strcmp(pos[0], "poisson") == 0;
  if ((options[6].seen || options[7].seen) && !is_poisson_file) {
    cli_error("mesh", "--solver and --refine belong to 'mesh poisson FILE'");
    return CLI_EXIT_USAGE;
  }
  if (n_pos >= 1 && strcmp(pos[0], "refine") == 0) {
    if (n_pos != 2 || !options[3].seen || options[4].seen || options[5].seen) {
      cli_error("mesh", "usage: mesh refine FILE --levels L [--out FILE.msh] [--json]");
      return CLI_EXIT_USAGE;
    }
    if (levels > 12) {
      cli_error("mesh", "--levels %zu: at most 12 refinements (each multiplies the cells by 4 "
                        "or 8)", levels);
      return CLI_EXIT_USAGE;
    }
    gm_mesh *m = NULL;
    status = read_mesh(pos[1], &m);
    if (status != CLI_EXIT_OK) return status;
    status = cli_mesh_refine(m, pos[1], levels, out, max_memory_bytes, json);
    gm_mesh_free(m);
    return status;
  }
  if (n_pos >= 1 && strcmp(pos[0], "transfer") == 0) {
    if (n_pos != 3 || options[1].seen || options[3].seen || options[4].seen || options[5].seen) {
      cli_error("mesh", "usage: mesh transfer A B [--json]");
      return CLI_EXIT_USAGE;
    }
    gm_mesh *a = NULL, *b = NULL;
    status = read_mesh(pos[1], &a);
    if (status == CLI_EXIT_OK) status = read_mesh(pos[2], &b);
    if (status == CLI_EXIT_OK) status = cli_mesh_transfer(a, pos[1], b, pos[2], json);
    gm_mesh_free(a), gm_mesh_free(b);
    return status;
  }
  if (n_pos > 2) {
    cli_error("mesh", "too many arguments (see geomint mesh --help)");
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
    gm_poisson_options opt = gm_poisson_defaults();
    if (solver != NULL) {
      int sv = cli_mesh_solver(solver);
      if (sv < 0) {
        cli_error("mesh", "--solver %s: use cholmod, mg or hypre", solver);
        return CLI_EXIT_USAGE;
      }
      opt.solver = (gm_poisson_solver)sv;
    }
    if (refine > 12) {
      cli_error("mesh", "--refine %zu: at most 12 refinements", refine);
      return CLI_EXIT_USAGE;
    }
    if (opt.solver == GM_POISSON_MULTIGRID && refine == 0) {
      cli_error("mesh", "--solver mg needs --refine L >= 1: FILE is the coarsest level");
      return CLI_EXIT_USAGE;
    }
    if (out != NULL && refine > 0) {
      cli_error("mesh", "--out with --refine: write the refined mesh with 'mesh refine' and "
                        "solve on it");
      return CLI_EXIT_USAGE;
    }
    opt.levels = refine;
    opt.max_bytes = max_memory_bytes;
    opt.measure_contraction = opt.solver == GM_POISSON_MULTIGRID || opt.solver == GM_POISSON_AUTO;
    return mesh_poisson(pos[1], out, &opt, json);
  }
  cli_error("mesh", "unknown subcommand '%s': use info, poisson, refine or transfer", pos[0]);
  return CLI_EXIT_USAGE;
}

const cli_command cli_mesh_command = {"mesh", "read a mesh: topology, quality, Poisson check, refine, transfer", usage,
                                      mesh_main};
