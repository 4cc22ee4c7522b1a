/* Strong and weak scaling of the MPI Yee solver (geomint/fields_mpi.h) on a vacuum PEC cavity
 * with one soft dipole, and the check of the performance model of docs/maxwell.md:
 *   t_step = t_compute(block) + t_exchange,  t_exchange = Σ_axes (α + β · bytes_axis)
 * Each rank also times an ordinary gm_yee on a grid of its block's size (overlap cells included)
 * in the same run, so t_exchange is measured as the difference (both under the same load).
 *
 *   OMP_NUM_THREADS=1 mpirun -np P bench_yee_mpi_scaling [DIR] [N] [STEPS]
 *   (defaults bench/results, 64, 60; without mpirun it runs as one rank)
 *
 * strong: the N³ cavity split over the P ranks (MPI_Dims_create); weak: N³ cells per rank, the
 * grid N·P × N × N split along x. Writes DIR/yee_mpi_scaling_np<P>.json. Wall-clock times, the
 * best of REPEATS rounds. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/fields.h"

#ifdef GM_HAVE_MPI
#include "geomint/fields_mpi.h"

#define REPEATS 3

typedef struct result {
  double cells, wall_s, compute_s, rate;
  size_t bytes_per_step, block_cells;
  int dims[3];
} result;

static double load_average(void) {
  double l = NAN;
  FILE *f = fopen("/proc/loadavg", "r");
  if (f != NULL) {
    if (fscanf(f, "%lf", &l) != 1) l = NAN;
    fclose(f);
  }
  return l;
}

static gm_point_source dipole(const gm_yee_grid *g) {
  gm_point_source ps = {GM_EZ, {0, 0, 0}, GM_SOURCE_SOFT,
                        {.kind = GM_WAVE_GAUSSIAN, .amplitude = 1.0, .frequency = 0.5,
                         .width = 2.0, .delay = 8.0}};
  for (int a = 0; a < 3; ++a) ps.x[a] = g->origin[a] + 0.37 * (double)g->n[a] * g->h[a];
  return ps;
}

/* Time STEPS steps of the distributed solver on grid g and of a serial solver of one block. */
static int run(const gm_yee_grid *g, const int *dims, size_t steps, result *r) {
  gm_error err;
  gm_yee_mpi *m = NULL;
  if (gm_yee_mpi_create(g, NULL, NULL, MPI_COMM_WORLD, dims, &m, &err) != GM_OK) {
    fprintf(stderr, "bench_yee_mpi_scaling: %s\n", err.message);
    return -1;
  }
  const gm_point_source ps = dipole(g);
  gm_yee_mpi_add_point_source(m, &ps, NULL);
  gm_yee_layout L;
  gm_yee_get_layout(gm_yee_mpi_local(m), &L);
  gm_yee_grid bg = {GM_YEE_3D, {L.n[0], L.n[1], L.n[2]}, {g->h[0], g->h[1], g->h[2]}, {0, 0, 0}};
  gm_yee_options o = gm_yee_defaults();
  o.dt = gm_yee_mpi_dt(m);
  o.sweep = GM_YEE_SWEEP_HALF_STEPS; /* as the blocks step */
  gm_yee *block = NULL;
  if (gm_yee_create(&bg, NULL, &o, &block, &err) != GM_OK) return -1;
  gm_point_source bps = dipole(&bg);
  gm_yee_add_point_source(block, &bps, NULL);
  double best = INFINITY, best_c = INFINITY;
  for (int rep = 0; rep < REPEATS; ++rep) {
    MPI_Barrier(MPI_COMM_WORLD);
    double t0 = MPI_Wtime();
    gm_yee_mpi_advance(m, steps);
    double t = MPI_Wtime() - t0, tmax = 0.0;
    MPI_Allreduce(&t, &tmax, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    best = fmin(best, tmax);
    MPI_Barrier(MPI_COMM_WORLD);
    t0 = MPI_Wtime();
    gm_yee_advance(block, steps);
    t = MPI_Wtime() - t0;
    MPI_Allreduce(&t, &tmax, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    best_c = fmin(best_c, tmax);
  }
  r->cells = (double)g->n[0] * (double)g->n[1] * (double)g->n[2];
  r->wall_s = best;
  r->compute_s = best_c;
  r->rate = r->cells * (double)steps / best / 1e6;
  r->bytes_per_step = gm_yee_mpi_bytes_per_step(m);
  r->block_cells = L.n[0] * L.n[1] * L.n[2];
  gm_yee_mpi_block(m, r->dims, NULL, NULL, NULL, NULL);
  gm_yee_free(block);
  gm_yee_mpi_free(m);
  return 0;
}

/* The model of docs/maxwell.md for a block of m[0] x m[1] x m[2] owned cells with neighbours on
 * every face (the worst, interior block): per axis one round of two messages of the two
 * tangential E planes, 16 (m_b + 4)(m_d + 4) bytes each (local extents with overlap and ghost
 * cells), axes one after the other and not overlapped with the update:
 *   t_step = c · Π m + Σ_axes (α + 2 · bytes_axis / W). */
static double model_step(const double m[3], double c, double alpha, double w, double *bytes) {
  double t = c * m[0] * m[1] * m[2], b = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double msg = 16.0 * (m[(a + 1) % 3] + 4.0) * (m[(a + 2) % 3] + 4.0);
    t += alpha + 2.0 * msg / w;
    b += 2.0 * msg;
  }
  if (bytes) *bytes = b;
  return t;
}

static void print_model(double c, double alpha, double w, const char *what) {
  /* weak: 128³ per rank; strong: the 1024³ grid on 4x4x4 and 16x8x8 ranks */
  const double weak[3] = {128, 128, 128}, s64[3] = {256, 256, 256}, s1024[3] = {64, 128, 128};
  double b;
  printf("  model (%s: c = %.3g ns per cell update, alpha = %.3g us, W = %.3g GB/s per rank):\n",
         what, c * 1e9, alpha * 1e6, w / 1e9);
  const double tw = model_step(weak, c, alpha, w, &b);
  printf("    weak, 128^3 per rank (any rank count >= 27): %.3g ms/step, %.3g MB sent per rank "
         "per step, efficiency %.1f %%\n", tw * 1e3, b / 1e6, 100.0 * c * 128 * 128 * 128 / tw);
  const double cells = 1024.0 * 1024.0 * 1024.0;
  const double t64 = model_step(s64, c, alpha, w, &b);
  printf("    strong, 1024^3 on 64 ranks (4x4x4): %.3g ms/step, %.3g MB/rank/step, efficiency "
         "%.1f %%, %.3g Gcells*steps/s\n", t64 * 1e3, b / 1e6, 100.0 * c * cells / 64 / t64,
         cells / t64 / 1e9);
  const double t1k = model_step(s1024, c, alpha, w, &b);
  printf("    strong, 1024^3 on 1024 ranks (16x8x8): %.3g ms/step, %.3g MB/rank/step, "
         "efficiency %.1f %%, %.3g Gcells*steps/s\n", t1k * 1e3, b / 1e6,
         100.0 * c * cells / 1024 / t1k, cells / t1k / 1e9);
}

static void print_row(FILE *f, const char *name, const result *r, size_t steps, int last) {
  fprintf(f,
          "    {\"case\": \"%s\", \"cells\": %.0f, \"dims\": [%d, %d, %d], \"steps\": %zu, "
          "\"wall_s\": %.6f, \"mcells_steps_per_s\": %.3f, \"block_cells\": %zu, "
          "\"block_compute_s\": %.6f, \"exchange_s_per_step\": %.3e, "
          "\"exchange_bytes_per_step_rank0\": %zu}%s\n",
          name, r->cells, r->dims[0], r->dims[1], r->dims[2], steps, r->wall_s, r->rate,
          r->block_cells, r->compute_s, (r->wall_s - r->compute_s) / (double)steps,
          r->bytes_per_step, last ? "" : ",");
}

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  int rank, size;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const size_t n = argc > 2 ? (size_t)atol(argv[2]) : 64;
  const size_t steps = argc > 3 ? (size_t)atol(argv[3]) : 60;
  const double load = load_average();
  const gm_yee_grid strong = {GM_YEE_3D, {n, n, n}, {1.0, 1.0, 1.0}, {0, 0, 0}};
  const gm_yee_grid weak = {GM_YEE_3D, {n * (size_t)size, n, n}, {1.0, 1.0, 1.0}, {0, 0, 0}};
  const int along_x[3] = {size, 1, 1};
  result rs, rw;
  int rc = run(&strong, NULL, steps, &rs) != 0 || run(&weak, along_x, steps, &rw) != 0;
  if (rank == 0 && rc == 0) {
    printf("Yee over MPI, %d rank(s), vacuum PEC cavity, %zu steps, load average %.1f\n", size,
           steps, load);
    printf("  %-7s %-16s %-9s %10s %14s %14s %16s\n", "case", "cells", "dims", "wall s",
           "Mcells*st/s", "block s", "bytes/step r0");
    const result *rr[2] = {&rs, &rw};
    const char *names[2] = {"strong", "weak"};
    for (int k = 0; k < 2; ++k)
      printf("  %-7s %-16.0f %dx%dx%-5d %10.4f %14.2f %14.4f %16zu\n", names[k], rr[k]->cells,
             rr[k]->dims[0], rr[k]->dims[1], rr[k]->dims[2], rr[k]->wall_s, rr[k]->rate,
             rr[k]->compute_s, rr[k]->bytes_per_step);
    /* the model with this run's single-block rate, and with the idle two-sweep one-thread rate
     * of docs/maxwell.md (195 Mcells*steps/s); network: GM_NET_LATENCY (s, default 2e-6) and
     * GM_NET_BANDWIDTH (bytes/s per rank, default 1e9: 100 Gb/s InfiniBand shared by 12 ranks) */
    const double alpha = getenv("GM_NET_LATENCY") ? atof(getenv("GM_NET_LATENCY")) : 2e-6;
    const double w = getenv("GM_NET_BANDWIDTH") ? atof(getenv("GM_NET_BANDWIDTH")) : 1e9;
    print_model(rs.compute_s / (double)steps / (double)rs.block_cells, alpha, w, "this run");
    print_model(1.0 / 195e6, alpha, w, "idle rate");
    char name[64];
    snprintf(name, sizeof name, "yee_mpi_scaling_np%d", size);
    FILE *f = bench_open_json(argc, argv, name);
    if (f != NULL) {
      fprintf(f, "{\n  \"bench\": \"yee_mpi_scaling\", \"ranks\": %d, \"n\": %zu, "
              "\"load_average\": %.2f,\n  \"rows\": [\n", size, n, load);
      print_row(f, "strong", &rs, steps, 0);
      print_row(f, "weak", &rw, steps, 1);
      bench_close_json(f);
    }
  }
  MPI_Finalize();
  return rc;
}
#else
int main(void) {
  printf("bench_yee_mpi_scaling: skipped (geomint built without MPI, GM_MPI=OFF)\n");
  return 0;
}
#endif
