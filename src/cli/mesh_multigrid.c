/* geomint mesh refine: red refinement (Bey's rule for tetrahedra) with the counts, the time and
 * the well-centredness of every level; geomint mesh transfer: the support-volume transfer
 * between two triangle meshes of one planar domain and its conservation figures. */
#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli/cli.h"
#include "cli/mesh_multigrid.h"
#include "geomint/multigrid.h"

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int cli_mesh_solver(const char *name) {
  if (strcmp(name, "cholmod") == 0) return GM_POISSON_CHOLMOD;
  if (strcmp(name, "mg") == 0) return GM_POISSON_MULTIGRID;
  if (strcmp(name, "hypre") == 0) return GM_POISSON_HYPRE;
  return -1;
}

int cli_mesh_refine(const gm_mesh *m, const char *path, size_t levels, const char *out,
                    size_t max_bytes, int json) {
  gm_error err = {{0}};
  double need = 0.0;
  if (gm_mesh_refine_estimate(m, levels, &need, &err) != GM_OK) {
    cli_error("mesh", "refine %s: %s", path, err.message);
    return CLI_EXIT_USAGE;
  }
  if (max_bytes != 0 && need > (double)max_bytes) {
    cli_error("mesh", "refine %s: %zu levels need about %.3g bytes for the finest mesh, more than "
              "--max-memory %zu bytes", path, levels, need, max_bytes);
    return CLI_EXIT_FAILURE;
  }
  cJSON *root = json ? cJSON_CreateObject() : NULL, *rows = NULL;
  if (json) {
    cJSON_AddStringToObject(root, "file", path);
    rows = cJSON_AddArrayToObject(root, "levels");
  } else {
    printf("refine %s: %zu-cells, %zu red refinement%s (%s)\n", path, m->dim, levels,
           levels == 1 ? "" : "s", m->dim == 3 ? "Bey's rule" : "4 triangles per triangle");
    printf("  %5s %11s %11s %9s %22s %10s\n", "level", "vertices", "cells", "time (s)",
           "well-centred children", "margin");
  }
  gm_mesh *cur = (gm_mesh *)m;
  int status = CLI_EXIT_OK;
  for (size_t l = 1; l <= levels; ++l) {
    gm_mesh *f = NULL;
    double t0 = now();
    gm_status st = gm_mesh_refine(cur, max_bytes, &f, &err);
    double dt = now() - t0;
    if (st != GM_OK) {
      cli_error("mesh", "refine level %zu: %s", l, err.message);
      status = st == GM_ENOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
      break;
    }
    /* how well-centred the children of well-centred cells are */
    gm_complex *cc = NULL, *fc = NULL;
    gm_refinement *r = NULL;
    gm_well_centredness wc;
    memset(&wc, 0, sizeof wc);
    st = gm_mesh_complex(cur, &cc, &err);
    if (st == GM_OK) st = gm_mesh_complex(f, &fc, &err);
    if (st == GM_OK) st = gm_refinement_create(cc, fc, &r, &err);
    if (st == GM_OK) st = gm_refinement_well_centredness(r, &wc);
    gm_refinement_free(r);
    gm_complex_free(cc), gm_complex_free(fc);
    if (cur != m) gm_mesh_free(cur);
    cur = f;
    if (st != GM_OK) {
      cli_error("mesh", "refine level %zu: %s", l, err.message);
      status = CLI_EXIT_FAILURE;
      break;
    }
    if (json) {
      cJSON *o = cJSON_CreateObject();
      cJSON_AddNumberToObject(o, "level", (double)l);
      cJSON_AddNumberToObject(o, "vertices", (double)f->n_vertices);
      cJSON_AddNumberToObject(o, "cells", (double)f->n_cells);
      cJSON_AddItemToObject(o, "wall_s", cli_json_number(dt));
      cJSON_AddNumberToObject(o, "well_centred_parents", (double)wc.coarse_well_centred);
      cJSON_AddNumberToObject(o, "children_of_well_centred", (double)wc.children_of_well_centred);
      cJSON_AddNumberToObject(o, "children_well_centred", (double)wc.children_well_centred);
      cJSON_AddItemToObject(o, "children_margin", wc.children_of_well_centred
                                                      ? cli_json_number(wc.children_margin)
                                                      : cJSON_CreateNull());
      cJSON_AddItemToArray(rows, o);
    } else {
      char wcs[64], margin[32];
      snprintf(wcs, sizeof wcs, "%zu / %zu", wc.children_well_centred,
               wc.children_of_well_centred);
      if (wc.children_of_well_centred)
        snprintf(margin, sizeof margin, "%.4g", wc.children_margin);
      else
        snprintf(margin, sizeof margin, "-");
      printf("  %5zu %11zu %11zu %9.3f %22s %10s\n", l, f->n_vertices, f->n_cells, dt, wcs,
             margin);
    }
  }
  if (status == CLI_EXIT_OK && out != NULL) {
    gm_status st = gm_mesh_write_msh(cur, out, &err);
    if (st != GM_OK) {
      cli_error("mesh", "%s", err.message);
      status = CLI_EXIT_FAILURE;
    } else if (json) {
      cJSON_AddStringToObject(root, "wrote", out);
    } else {
      printf("wrote %s\n", out);
    }
  }
  if (cur != m) gm_mesh_free(cur);
  if (status != CLI_EXIT_OK) {
    cJSON_Delete(root);
    return status;
  }
  if (json) return cli_json_print(root);
  if (levels == 0) printf("  (no refinement)\n");
  return CLI_EXIT_OK;
}

/* Conservation figures of one direction: the total of the top form |T| f(centroid) (f = 1 + x +
 * y²), constants of 0-forms, and the linear 0-form x + 2y. */
static int transfer_figures(const gm_complex *a, const gm_complex *b, cJSON *o, const char *label) {
  gm_error err = {{0}};
  gm_csr *T2 = NULL, *T0 = NULL;
  gm_transfer_report rep;
  gm_status st = gm_dec_transfer(a, b, 2, &T2, &rep, &err);
  if (st == GM_OK) st = gm_dec_transfer(a, b, 0, &T0, NULL, &err);
  if (st != GM_OK) {
    gm_csr_free(T2);
    cli_error("mesh", "%s: %s", label, err.message);
    return st == GM_ENOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
  }
  const size_t na = gm_complex_count(a, 2), nb = gm_complex_count(b, 2);
  const size_t va = gm_complex_count(a, 0), vb = gm_complex_count(b, 0);
  double *w = malloc(na * sizeof(double)), *tw = malloc(nb * sizeof(double));
  double *f = malloc(va * sizeof(double)), *tf = malloc(vb * sizeof(double));
  if (!w || !tw || !f || !tf) {
    free(w), free(tw), free(f), free(tf);
    gm_csr_free(T2), gm_csr_free(T0);
    cli_error("mesh", "out of memory");
    return CLI_EXIT_FAILURE;
  }
  const double *xa = gm_complex_coordinates(a), *xb = gm_complex_coordinates(b);
  const size_t *tri = gm_complex_simplices(a, 2);
  double s0 = 0.0, s1 = 0.0;
  for (size_t t = 0; t < na; ++t) {
    const double *p = xa + 2 * tri[3 * t], *q = xa + 2 * tri[3 * t + 1], *r = xa + 2 * tri[3 * t + 2];
    double area = 0.5 * fabs((q[0] - p[0]) * (r[1] - p[1]) - (r[0] - p[0]) * (q[1] - p[1]));
    double cx = (p[0] + q[0] + r[0]) / 3.0, cy = (p[1] + q[1] + r[1]) / 3.0;
    w[t] = area * (1.0 + cx + cy * cy);
    s0 += w[t];
  }
  gm_csr_matvec(T2, 1.0, w, 0.0, tw);
  for (size_t t = 0; t < nb; ++t) s1 += tw[t];
  for (size_t v = 0; v < va; ++v) f[v] = 1.0;
  gm_csr_matvec(T0, 1.0, f, 0.0, tf);
  double cerr = 0.0, lerr = 0.0;
  for (size_t v = 0; v < vb; ++v) cerr = fmax(cerr, fabs(tf[v] - 1.0));
  for (size_t v = 0; v < va; ++v) f[v] = xa[2 * v] + 2.0 * xa[2 * v + 1];
  gm_csr_matvec(T0, 1.0, f, 0.0, tf);
  for (size_t v = 0; v < vb; ++v) lerr = fmax(lerr, fabs(tf[v] - (xb[2 * v] + 2.0 * xb[2 * v + 1])));
  const double rel = fabs(s1 - s0) / fabs(s0);
  if (o) {
    cJSON_AddItemToObject(o, "area_from", cli_json_number(rep.volume_from));
    cJSON_AddItemToObject(o, "area_to", cli_json_number(rep.volume_to));
    cJSON_AddItemToObject(o, "area_overlap", cli_json_number(rep.volume_overlap));
    cJSON_AddNumberToObject(o, "pairs", (double)rep.pairs);
    cJSON_AddItemToObject(o, "total_rel_change", cli_json_number(rel));
    cJSON_AddItemToObject(o, "constant_max_err", cli_json_number(cerr));
    cJSON_AddItemToObject(o, "linear_max_err", cli_json_number(lerr));
  } else {
    printf("%s\n", label);
    printf("  %-36s %.17g / %.17g / %.17g\n", "areas: from / to / overlap", rep.volume_from,
           rep.volume_to, rep.volume_overlap);
    printf("  %-36s %zu\n", "overlapping triangle pairs", rep.pairs);
    printf("  %-36s %.3e\n", "top form: relative change of total", rel);
    printf("  %-36s %.3e\n", "0-form: constant, max error", cerr);
    printf("  %-36s %.3e\n", "0-form: x + 2y, max error", lerr);
  }
  free(w), free(tw), free(f), free(tf);
  gm_csr_free(T2), gm_csr_free(T0);
  return CLI_EXIT_OK;
}

int cli_mesh_transfer(const gm_mesh *a, const char *path_a, const gm_mesh *b, const char *path_b,
                      int json) {
  gm_error err = {{0}};
  gm_complex *ca = NULL, *cb = NULL;
  gm_status st = gm_mesh_complex(a, &ca, &err);
  if (st == GM_OK) st = gm_mesh_complex(b, &cb, &err);
  if (st != GM_OK) {
    cli_error("mesh", "transfer: %s", err.message);
    gm_complex_free(ca);
    return st == GM_ENOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
  }
  cJSON *root = json ? cJSON_CreateObject() : NULL;
  cJSON *ab = json ? cJSON_AddObjectToObject(root, "forward") : NULL;
  cJSON *ba = json ? cJSON_AddObjectToObject(root, "backward") : NULL;
  char la[1024], lb[1024];
  snprintf(la, sizeof la, "transfer %s -> %s", path_a, path_b);
  snprintf(lb, sizeof lb, "transfer %s -> %s", path_b, path_a);
  int status = transfer_figures(ca, cb, ab, la);
  if (status == CLI_EXIT_OK) status = transfer_figures(cb, ca, ba, lb);
  gm_complex_free(ca), gm_complex_free(cb);
  if (status != CLI_EXIT_OK) {
    cJSON_Delete(root);
    return status;
  }
  return json ? cli_json_print(root) : CLI_EXIT_OK;
}
