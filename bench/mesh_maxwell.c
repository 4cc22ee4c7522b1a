/* Mesh Maxwell costs (issue 11), on the 2-D acute triangle mesh of [0,1]×[0,0.7] with N columns:
 * - leapfrog update rate, (edges + faces) per second, against the floor of two CSR matrix–vector
 *   products with d₁ and d₁ᵀ measured in the same run (goal >= 0.8 of the floor's rate);
 * - AVI cost per face update against the leapfrog's cost per face (goal <= 3×), both to the
 *   same final time with every face at the same fraction (0.5) of ... its own local limit (AVI)
 *   and the leapfrog at its global step;
 * - create time (stars + power-iteration CFL estimate).
 * CPU time of the thread (bench_cpu_now). Usage: bench_mesh_maxwell [results-dir [N [steps]]]. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "geomint/geomint.h"

int main(int argc, char **argv) {
  const size_t N = argc > 2 ? (size_t)atol(argv[2]) : 200;
  const size_t steps = argc > 3 ? (size_t)atol(argv[3]) : 200;
  gm_error err = {{0}};
  gm_mesh *m = NULL;
  gm_complex *cx = NULL;
  gm_geometry *g = NULL;
  const size_t ny = (size_t)lround(0.7 * 2.0 * (double)N / sqrt(3.0));
  if (gm_mesh_rectangle(0, 1, 0, 0.7, N, ny, GM_DIAGONAL_ACUTE, &m, &err) != GM_OK ||
      gm_mesh_complex(m, &cx, &err) != GM_OK || gm_geometry_create(cx, NULL, &g, &err) != GM_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  const size_t ne = gm_complex_count(cx, 1), nf = gm_complex_count(cx, 2);
  double t0 = bench_cpu_now();
  gm_mesh_maxwell *lf = NULL;
  if (gm_mesh_maxwell_create(g, NULL, NULL, NULL, &lf, &err) != GM_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  const double t_create = bench_cpu_now() - t0;
  double *E = malloc(ne * sizeof(double)), *B = calloc(nf, sizeof(double));
  double *y = malloc(ne * sizeof(double)), *z = malloc(nf * sizeof(double));
  for (size_t e = 0; e < ne; ++e) E[e] = sin(0.37 * (double)e);
  gm_mesh_maxwell_set_fields(lf, E, B);
  t0 = bench_cpu_now();
  gm_mesh_maxwell_advance(lf, steps);
  const double t_lf = bench_cpu_now() - t0;
  const gm_csr *d1 = gm_complex_d(cx, 1);
  t0 = bench_cpu_now();
  for (size_t k = 0; k < steps; ++k) {
    gm_csr_matvec_transpose(d1, 1.0, z, 1.0, y);
    gm_csr_matvec(d1, 1.0, y, 1.0, z);
  }
  const double t_floor = bench_cpu_now() - t0;
  const double rate = (double)(ne + nf) * (double)steps / t_lf;
  const double floor_rate = (double)(ne + nf) * (double)steps / t_floor;
  /* AVI to the same final time, every face at 0.5 of its local limit */
  gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
  o.scheme = GM_MESH_AVI;
  o.avi_fraction = 0.5;
  gm_mesh_maxwell *avi = NULL;
  if (gm_mesh_maxwell_create(g, NULL, NULL, &o, &avi, &err) != GM_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  gm_mesh_maxwell_set_fields(avi, E, B);
  const double T = (double)steps * gm_mesh_maxwell_dt(lf);
  t0 = bench_cpu_now();
  gm_mesh_maxwell_advance_to(avi, T);
  const double t_avi = bench_cpu_now() - t0;
  size_t fu, eu;
  gm_mesh_maxwell_update_counts(avi, &fu, &eu);
  const double per_face_lf = t_lf / ((double)nf * (double)steps);
  const double per_face_avi = t_avi / (double)fu;
  printf("mesh: %zu triangles, %zu edges; create (stars + CFL power iteration) %.3f s CPU\n", nf,
         ne, t_create);
  printf("leapfrog: %.3g (edges+faces)/s; floor d1ᵀ + d1 CSR products: %.3g/s; ratio %.3f "
         "(goal >= 0.8)\n", rate, floor_rate, rate / floor_rate);
  printf("AVI (0.5 of local limits) to t = %.4g: %zu face updates (leapfrog %zu); cost per face "
         "update %.3g s vs leapfrog %.3g s: %.2fx (goal <= 3); total time ratio AVI/leapfrog %.2f\n",
         T, fu, nf * steps, per_face_avi, per_face_lf, per_face_avi / per_face_lf, t_avi / t_lf);
  FILE *f = bench_open_json(argc, argv, "mesh_maxwell");
  if (f) {
    fprintf(f, "{\n  \"triangles\": %zu, \"edges\": %zu, \"create_s\": %.6f,\n", nf, ne, t_create);
    fprintf(f, "  \"leapfrog_rate\": %.6g, \"floor_rate\": %.6g, \"ratio_to_floor\": %.4f,\n", rate,
            floor_rate, rate / floor_rate);
    fprintf(f, "  \"avi_face_updates\": %zu, \"avi_cost_per_face_ratio\": %.4f\n}\n", fu,
            per_face_avi / per_face_lf);
    fclose(f);
  }
  free(E); free(B); free(y); free(z);
  gm_mesh_maxwell_free(lf);
  gm_mesh_maxwell_free(avi);
  gm_geometry_free(g);
  gm_complex_free(cx);
  gm_mesh_free(m);
  return 0;
}
