/* Mesh Maxwell costs (issue 11), on the 2-D acute triangle mesh of [0,1]×[0,0.7] with N columns
 * and on the 3-D body-centred cubic box (gm_mesh_bcc, well-centred) with N3 cubes per side
 * (N3 = 44: 998 976 tetrahedra):
 * - leapfrog update rate, (edges + faces) per second, against the floor of two CSR matrix–vector
 *   products with d₁ and d₁ᵀ measured in the same run (goal >= 0.8 of the floor's rate), the
 *   two timed alternately (best of 3 each) so that load from other processes hits both;
 * - AVI cost per face update against the leapfrog's cost per face (goal <= 3×), both to the
 *   same final time with every face at the same fraction (0.5) of ... its own local limit (AVI)
 *   and the leapfrog at its global step;
 * - create time (stars + power-iteration CFL estimate).
 * CPU time of the thread (bench_cpu_now). Usage: bench_mesh_maxwell [results-dir [N [steps [N3 [steps3]]]]]. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "geomint/geomint.h"

typedef struct lf_rate {
  size_t ne, nf;
  double t_create, rate, floor_rate, t_step, dt;
} lf_rate;

/* Leapfrog (edges + faces)/s against the CSR floor d₁ᵀ then d₁ on the same vectors sizes; the
 * best of 3 alternating repeats of each. */
static int leapfrog_rate(const gm_geometry *g, size_t steps, lf_rate *r) {
  gm_error err = {{0}};
  const gm_complex *cx = gm_geometry_complex(g);
  const size_t ne = gm_complex_count(cx, 1), nf = gm_complex_count(cx, 2);
  double t0 = bench_cpu_now();
  gm_mesh_maxwell *lf = NULL;
  if (gm_mesh_maxwell_create(g, NULL, NULL, NULL, &lf, &err) != GM_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  r->t_create = bench_cpu_now() - t0;
  double *E = malloc(ne * sizeof(double)), *B = calloc(nf, sizeof(double));
  double *y = malloc(ne * sizeof(double)), *z = malloc(nf * sizeof(double));
  for (size_t e = 0; e < ne; ++e) E[e] = y[e] = sin(0.37 * (double)e);
  for (size_t f = 0; f < nf; ++f) z[f] = 0.0;
  gm_mesh_maxwell_set_fields(lf, E, B);
  const gm_csr *d1 = gm_complex_d(cx, 1);
  double t_lf = INFINITY, t_floor = INFINITY;
  for (int rep = 0; rep < 3; ++rep) {
    t0 = bench_cpu_now();
    gm_mesh_maxwell_advance(lf, steps);
    t_lf = fmin(t_lf, bench_cpu_now() - t0);
    t0 = bench_cpu_now();
    for (size_t k = 0; k < steps; ++k) {
      gm_csr_matvec_transpose(d1, 1e-3, z, 1.0, y);
      gm_csr_matvec(d1, -1e-3, y, 1.0, z);
    }
    t_floor = fmin(t_floor, bench_cpu_now() - t0);
  }
  r->ne = ne, r->nf = nf;
  r->rate = (double)(ne + nf) * (double)steps / t_lf;
  r->floor_rate = (double)(ne + nf) * (double)steps / t_floor;
  r->t_step = t_lf / (double)steps;
  r->dt = gm_mesh_maxwell_dt(lf);
  free(E), free(B), free(y), free(z);
  gm_mesh_maxwell_free(lf);
  return 0;
}

/* AVI to the time of `steps` leapfrog steps, every face at `fraction` of its local limit: face
 * updates and cost per face update against the leapfrog's (r). */
typedef enum { AVI_AS_IS, AVI_DISTINCT, AVI_DISTINCT_LEVELS } avi_mode;

static int avi_cost(const gm_geometry *g, size_t steps, double fraction, const lf_rate *r,
                    avi_mode mode, size_t *fu, double *per_face_ratio, double *total_ratio,
                    size_t *groups) {
  gm_error err = {{0}};
  gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
  o.scheme = GM_MESH_AVI;
  o.avi_fraction = fraction;
  o.avi_levels = mode == AVI_DISTINCT_LEVELS;
  double *face_dt = NULL;
  gm_mesh_maxwell *avi = NULL;
  if (mode != AVI_AS_IS) { /* every face its own step: fraction × limit × (1 − 0.01 u), u in [0,1) */
    if (gm_mesh_maxwell_create(g, NULL, NULL, &o, &avi, &err) != GM_OK) {
      fprintf(stderr, "%s\n", err.message);
      return 1;
    }
    face_dt = malloc(r->nf * sizeof(double));
    const double *lim = gm_mesh_maxwell_face_limits(avi);
    for (size_t f = 0; f < r->nf; ++f)
      face_dt[f] = isfinite(lim[f]) ? fraction * lim[f] * (1.0 - 0.01 * fmod(0.6180339887 * (double)f, 1.0))
                                    : INFINITY;
    gm_mesh_maxwell_free(avi);
    avi = NULL;
    o.face_dt = face_dt;
  }
  if (gm_mesh_maxwell_create(g, NULL, NULL, &o, &avi, &err) != GM_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  double *E = malloc(r->ne * sizeof(double));
  for (size_t e = 0; e < r->ne; ++e) E[e] = sin(0.37 * (double)e);
  gm_mesh_maxwell_set_fields(avi, E, NULL);
  const double T = (double)steps * r->dt;
  const double t0 = bench_cpu_now();
  gm_mesh_maxwell_advance_to(avi, T);
  const double t_avi = bench_cpu_now() - t0;
  gm_mesh_maxwell_update_counts(avi, fu, NULL);
  *groups = gm_mesh_maxwell_avi_groups(avi);
  free(face_dt);
  *per_face_ratio = (t_avi / (double)*fu) / (r->t_step / (double)r->nf);
  *total_ratio = t_avi / (r->t_step * (double)steps);
  free(E);
  gm_mesh_maxwell_free(avi);
  return 0;
}

int main(int argc, char **argv) {
  const size_t N = argc > 2 ? (size_t)atol(argv[2]) : 200;
  const size_t steps = argc > 3 ? (size_t)atol(argv[3]) : 200;
  const size_t N3 = argc > 4 ? (size_t)atol(argv[4]) : 44;
  const size_t steps3 = argc > 5 ? (size_t)atol(argv[5]) : 10;
  gm_error err = {{0}};
  gm_mesh *m = NULL, *m3 = NULL;
  gm_complex *cx = NULL, *cx3 = NULL;
  gm_geometry *g = NULL, *g3 = NULL;
  const size_t ny = (size_t)lround(0.7 * 2.0 * (double)N / sqrt(3.0));
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  if (gm_mesh_rectangle(0, 1, 0, 0.7, N, ny, GM_DIAGONAL_ACUTE, &m, &err) != GM_OK ||
      gm_mesh_complex(m, &cx, &err) != GM_OK || gm_geometry_create(cx, NULL, &g, &err) != GM_OK ||
      gm_mesh_bcc(lo, hi, N3, N3, N3, 0, &m3, &err) != GM_OK ||
      gm_mesh_complex(m3, &cx3, &err) != GM_OK ||
      gm_geometry_create(cx3, NULL, &g3, &err) != GM_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  lf_rate r2, r3;
  size_t fu[2][3] = {{0}}, ng[2][3] = {{0}};
  double pf[2][3], tot[2][3];
  if (leapfrog_rate(g, steps, &r2) || leapfrog_rate(g3, steps3, &r3)) return 1;
  for (int mode = 0; mode < 3; ++mode)
    if (avi_cost(g, steps, 0.5, &r2, (avi_mode)mode, &fu[0][mode], &pf[0][mode], &tot[0][mode],
                 &ng[0][mode]) ||
        avi_cost(g3, steps3, 0.5, &r3, (avi_mode)mode, &fu[1][mode], &pf[1][mode], &tot[1][mode],
                 &ng[1][mode]))
      return 1;
  const size_t nt3 = gm_complex_count(cx3, 3);
  static const char *mode_name[3] = {"steps 0.5 x local limit (equal limits grouped)",
                                     "every face a distinct step (heap of faces)",
                                     "distinct steps rounded to power-of-two levels"};
  for (int d = 0; d < 2; ++d) {
    const lf_rate *r = d ? &r3 : &r2;
    if (d == 0)
      printf("2-D acute triangles: %zu triangles, %zu edges; create (stars + Lanczos CFL) %.3f s "
             "CPU\n", r->nf, r->ne, r->t_create);
    else
      printf("3-D bcc box: %zu tetrahedra, %zu faces, %zu edges; create %.3f s CPU\n", nt3, r->nf,
             r->ne, r->t_create);
    printf("  leapfrog: %.3g (edges+faces)/s; floor d1ᵀ + d1 CSR products: %.3g/s; ratio %.3f "
           "(goal >= 0.8)\n", r->rate, r->floor_rate, r->rate / r->floor_rate);
    for (int mode = 0; mode < 3; ++mode)
      printf("  AVI, %-48s: %6zu groups, %zu face updates (leapfrog %zu), cost per face update "
             "%.2fx leapfrog's (goal <= 3), total time %.2fx\n", mode_name[mode], ng[d][mode],
             fu[d][mode], r->nf * (d ? steps3 : steps), pf[d][mode], tot[d][mode]);
  }
  FILE *f = bench_open_json(argc, argv, "mesh_maxwell");
  if (f) {
    fprintf(f, "{\n  \"triangles\": %zu, \"edges\": %zu, \"create_s\": %.6f,\n", r2.nf, r2.ne,
            r2.t_create);
    fprintf(f, "  \"leapfrog_rate\": %.6g, \"floor_rate\": %.6g, \"ratio_to_floor\": %.4f,\n",
            r2.rate, r2.floor_rate, r2.rate / r2.floor_rate);
    fprintf(f, "  \"avi_cost_per_face_ratio\": [%.4f, %.4f, %.4f],\n", pf[0][0], pf[0][1], pf[0][2]);
    fprintf(f, "  \"tetrahedra_3d\": %zu, \"create_3d_s\": %.6f,\n", nt3, r3.t_create);
    fprintf(f, "  \"leapfrog_rate_3d\": %.6g, \"floor_rate_3d\": %.6g, \"ratio_to_floor_3d\": %.4f,\n",
            r3.rate, r3.floor_rate, r3.rate / r3.floor_rate);
    fprintf(f, "  \"avi_cost_per_face_ratio_3d\": [%.4f, %.4f, %.4f]\n}\n", pf[1][0], pf[1][1],
            pf[1][2]);
    fclose(f);
  }
  gm_geometry_free(g), gm_complex_free(cx), gm_mesh_free(m);
  gm_geometry_free(g3), gm_complex_free(cx3), gm_mesh_free(m3);
  return 0;
}
