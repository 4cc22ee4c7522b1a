/* Building a DEC complex and its geometry on the 64³ box cut into 6 tetrahedra per cube
 * (1 572 864 tetrahedra): faces, boundary matrices, circumcenters, dual volumes, Hodge stars.
 * Targets (issue 6): at most 3 s and 1 KB of peak memory per tetrahedron. Floor: the LSD radix
 * sort of the packed face keys alone (4 per tetrahedron), measured in the same run. Usage:
 * bench_dec_build [results-dir [cells-per-side [repeats]]]; the best of the repeats is reported,
 * wall time and CPU time of the process (OMP_NUM_THREADS sets the threads of the library). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/dec.h"
#include "geomint/mesh.h"
#ifdef _OPENMP
#include <omp.h>
#endif

static long peak_rss_kb(void) {
  FILE *f = fopen("/proc/self/status", "r");
  if (f == NULL) return -1;
  char line[256];
  long kb = -1;
  while (fgets(line, sizeof line, f))
    if (strncmp(line, "VmHWM:", 6) == 0) kb = strtol(line + 6, NULL, 10);
  fclose(f);
  return kb;
}

/* Pack the 4 sorted face triples of every tetrahedron into 63-bit keys and radix sort them
 * (16-bit digits, 4 passes); single-threaded. Wall time returned, thread CPU time in *cpu. */
static double face_key_sort_time(const gm_mesh *m, double *cpu) {
  const size_t nk = 4 * m->n_cells;
  uint64_t *a = malloc(nk * sizeof(uint64_t)), *b = malloc(nk * sizeof(uint64_t));
  size_t *cnt = malloc(65536 * sizeof(size_t));
  if (!a || !b || !cnt) return -1.0;
  double t0 = bench_now(), c0 = bench_cpu_now();
  for (size_t t = 0; t < m->n_cells; ++t) {
    size_t v[4];
    memcpy(v, m->cells + 4 * t, sizeof v);
    for (int i = 1; i < 4; ++i)
      for (int j = i; j > 0 && v[j - 1] > v[j]; --j) {
        size_t s = v[j];
        v[j] = v[j - 1];
        v[j - 1] = s;
      }
    for (int i = 0; i < 4; ++i) {
      uint64_t k = 0;
      for (int j = 0; j < 4; ++j)
        if (j != i) k = (k << 21) | (uint64_t)v[j];
      a[4 * t + (size_t)i] = k;
    }
  }
  for (int pass = 0; pass < 4; ++pass) {
    int shift = 16 * pass;
    memset(cnt, 0, 65536 * sizeof(size_t));
    for (size_t i = 0; i < nk; ++i) cnt[(a[i] >> shift) & 0xffff]++;
    size_t sum = 0;
    for (size_t d = 0; d < 65536; ++d) {
      size_t c = cnt[d];
      cnt[d] = sum;
      sum += c;
    }
    for (size_t i = 0; i < nk; ++i) b[cnt[(a[i] >> shift) & 0xffff]++] = a[i];
    uint64_t *s = a;
    a = b;
    b = s;
  }
  double t1 = bench_now();
  *cpu = bench_cpu_now() - c0;
  size_t unique = nk ? 1 : 0;
  for (size_t i = 1; i < nk; ++i) unique += a[i] != a[i - 1];
  free(a), free(b), free(cnt);
  return unique ? t1 - t0 : -1.0;
}

static double process_cpu_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(int argc, char **argv) {
  const size_t n = argc > 2 ? (size_t)strtoul(argv[2], NULL, 10) : 64;
  const int repeats = argc > 3 ? atoi(argv[3]) : 3;
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  if (gm_mesh_box(lo, hi, n, n, n, GM_BOX_KUHN, &m, &err) != GM_OK) {
    fprintf(stderr, "mesh: %s\n", err.message);
    return 1;
  }
  const double nt = (double)m->n_cells;
  long rss_mesh = peak_rss_kb();
  /* best of the repeats, separately for each quantity; wall and CPU time of the process (all
   * threads: CPU > wall means the threads overlapped) */
  double w_cx = INFINITY, w_g = INFINITY, w_tot = INFINITY, c_cx = INFINITY, c_g = INFINITY,
         c_tot = INFINITY, t_sort = INFINITY, c_sort = INFINITY;
  size_t counts[4] = {0};
  long rss_before = 0, rss_peak = 0;
  for (int rep = 0; rep < repeats; ++rep) {
    double cs = 0.0, ts = face_key_sort_time(m, &cs);
    if (ts < 0) return 1;
    t_sort = fmin(t_sort, ts);
    c_sort = fmin(c_sort, cs);
    if (rep == 0) rss_before = peak_rss_kb();
    double t0 = bench_now(), p0 = process_cpu_now();
    gm_complex *cx = NULL;
    if (gm_mesh_complex(m, &cx, &err) != GM_OK) {
      fprintf(stderr, "complex: %s\n", err.message);
      return 1;
    }
    double t1 = bench_now(), p1 = process_cpu_now();
    gm_geometry *g = NULL;
    if (gm_geometry_create(cx, NULL, &g, &err) != GM_OK) {
      fprintf(stderr, "geometry: %s\n", err.message);
      return 1;
    }
    double t2 = bench_now(), p2 = process_cpu_now();
    if (rep == 0) rss_peak = peak_rss_kb();
    w_cx = fmin(w_cx, t1 - t0), w_g = fmin(w_g, t2 - t1), w_tot = fmin(w_tot, t2 - t0);
    c_cx = fmin(c_cx, p1 - p0), c_g = fmin(c_g, p2 - p1), c_tot = fmin(c_tot, p2 - p0);
    for (size_t k = 0; k < 4; ++k) counts[k] = gm_complex_count(cx, k);
    gm_geometry_free(g);
    gm_complex_free(cx);
  }
  /* the sort floor ran before the complex: its buffers do not overlap the peak below */
  const double bytes_per_tet = (double)(rss_peak > rss_before ? rss_peak : rss_before) * 1024.0 / nt;
  const double bytes_per_tet_no_mesh = (double)(rss_peak - rss_mesh) * 1024.0 / nt;
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  printf("dec_build: %zu^3 box, 6 tetrahedra per cube; best of %d, %d thread(s)\n", n, repeats,
         threads);
  printf("  %-34s %12.0f\n", "tetrahedra", nt);
  printf("  %-34s %12zu / %zu / %zu\n", "vertices / edges / faces", counts[0], counts[1],
         counts[2]);
  printf("  %-34s %12s %12s\n", "", "wall [s]", "CPU [s]");
  printf("  %-34s %12.3f %12.3f\n", "faces + boundary matrices", w_cx, c_cx);
  printf("  %-34s %12.3f %12.3f\n", "circumcenters, duals, Hodge stars", w_g, c_g);
  printf("  %-34s %12.3f %12.3f   (targets <= 3 s, <= 1.5 s)\n", "total", w_tot, c_tot);
  printf("  %-34s %12.3f %12.3f\n", "floor: radix sort of face keys", t_sort, c_sort);
  printf("  %-34s %12.2f %12.2f\n", "ratio total / floor", w_tot / t_sort, c_tot / c_sort);
  printf("  %-34s %12.0f B   (target <= 1024 B)\n", "peak memory per tetrahedron", bytes_per_tet);
  printf("  %-34s %12.0f B\n", "  of which after the input mesh", bytes_per_tet_no_mesh);
  FILE *f = bench_open_json(argc, argv, "dec_build");
  if (f) {
    fprintf(f,
            "{\n  \"benchmark\": \"dec_build\",\n  \"cells_per_side\": %zu,\n  \"tetrahedra\": %.0f,\n"
            "  \"threads\": %d,\n  \"repeats\": %d,\n"
            "  \"seconds_complex\": %.6f,\n  \"seconds_geometry\": %.6f,\n  \"seconds_total\": %.6f,\n"
            "  \"cpu_seconds_complex\": %.6f,\n  \"cpu_seconds_geometry\": %.6f,\n"
            "  \"cpu_seconds_total\": %.6f,\n"
            "  \"seconds_face_key_sort\": %.6f,\n  \"cpu_seconds_face_key_sort\": %.6f,\n"
            "  \"ratio_total_to_sort\": %.4f,\n  \"ratio_cpu_total_to_sort\": %.4f,\n"
            "  \"target_seconds\": 3.0,\n  \"ratio_total_to_target\": %.4f,\n"
            "  \"peak_bytes_per_tetrahedron\": %.1f,\n  \"target_bytes_per_tetrahedron\": 1024,\n"
            "  \"ratio_memory_to_target\": %.4f\n}\n",
            n, nt, threads, repeats, w_cx, w_g, w_tot, c_cx, c_g, c_tot, t_sort, c_sort,
            w_tot / t_sort, c_tot / c_sort, w_tot / 3.0, bytes_per_tet, bytes_per_tet / 1024.0);
    fclose(f);
  }
  gm_mesh_free(m);
  return 0;
}
