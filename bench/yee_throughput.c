/* Yee FDTD throughput: a 128³ vacuum cavity with PEC walls, 200 steps, at 1 and 2 threads,
 * against two references measured in the same run:
 *   - the floor: an in-place stream a += s·b over the bytes one vacuum Yee step must move at
 *     least (the six field arrays, each read twice and written once: E += c curl H reads E and
 *     H and writes E, then H −= c curl E reads H and E and writes H; a and b are 6 arrays of
 *     the solver's size each, so one sweep moves the same 18 arrays' worth of bytes);
 *   - MEEP on the same cavity (bench/meep_cavity.py: 1 process and `mpirun -np 2`).
 * Mcells·steps/s = cells × steps / seconds / 10⁶. Both codes are excited the same way: three
 * soft point dipoles (Ex, Ey, Ez, Gaussian pulse) at the same relative positions, Δt = 0.5 h
 * (MEEP's default Courant factor).
 *
 *   bench_yee_throughput [DIR] [N] [STEPS]      (defaults bench/results, 128, 200)
 *
 * Environment: GM_MEEP_SCRIPT overrides the script path, GM_SKIP_MEEP=1 skips MEEP,
 * GM_YEE_SWEEP=half makes geomint do two sweeps a step (the comparison in docs/maxwell.md).
 * Writes DIR/yee_throughput.json with the rates and the ratios to the goals of issue 10
 * (≥ 1.8 × MEEP np 1 with one thread, ≥ 1.6 × MEEP np 2 with two threads, ≥ 0.75 of the
 * stream floor). Timings are wall clock. Each of REPEATS rounds times geomint and the floor
 * at 1 and 2 threads and then MEEP (one timed loop per process count), so that all of them see
 * the same load in a round; the best round of each counts. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include <cJSON.h>

#include "bench_util.h"
#include "geomint/fields.h"

#define REPEATS 3
#define MAX_THREADS 2

static double load_average(void) {
  double l = NAN;
  FILE *f = fopen("/proc/loadavg", "r");
  if (f != NULL) {
    if (fscanf(f, "%lf", &l) != 1) l = NAN;
    fclose(f);
  }
  return l;
}

/* ---- the floor -------------------------------------------------------------------------- */

/* Seconds per sweep of a += s b over n doubles with `threads` threads (mean of `sweeps`). */
static double stream_sweep(double *a, const double *b, size_t n, int threads, size_t sweeps) {
  const double s = 1e-9;
  double t0 = bench_now();
  for (size_t k = 0; k < sweeps; ++k) {
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(threads)
#endif
    for (size_t i = 0; i < n; ++i) a[i] += s * b[i];
  }
  (void)threads;
  return (bench_now() - t0) / (double)sweeps;
}

/* ---- geomint ---------------------------------------------------------------------------- */

static const double dipole_at[3][3] = {{0.17, 0.31, 0.23}, {0.61, 0.19, 0.43}, {0.37, 0.71, 0.59}};

static gm_yee *make_cavity(size_t n, int threads, gm_error *err) {
  gm_yee_grid grid = {GM_YEE_3D, {n, n, n}, {1, 1, 1}, {0, 0, 0}};
  gm_yee_options opt = gm_yee_defaults();
  opt.dt = 0.5;
  opt.n_threads = threads;
  /* GM_YEE_SWEEP=half: two sweeps a step (E, then H) even where one sweep applies */
  const char *sweep = getenv("GM_YEE_SWEEP");
  if (sweep != NULL && strcmp(sweep, "half") == 0) opt.sweep = GM_YEE_SWEEP_HALF_STEPS;
  gm_yee *s = NULL;
  if (gm_yee_create(&grid, NULL, &opt, &s, err) != GM_OK) return NULL;
  for (int c = 0; c < 3; ++c) {
    gm_point_source src = {(gm_yee_component)(GM_EX + c),
                           {dipole_at[c][0] * (double)n, dipole_at[c][1] * (double)n,
                            dipole_at[c][2] * (double)n},
                           GM_SOURCE_SOFT,
                           {GM_WAVE_GAUSSIAN, 1.0, 0.15, 10.0, 40.0, 0.0, NULL, NULL}};
    if (gm_yee_add_point_source(s, &src, NULL) != GM_OK) {
      snprintf(err->message, sizeof err->message, "%s", gm_yee_errmsg(s));
      gm_yee_free(s);
      return NULL;
    }
  }
  return s;
}

/* One solver per thread count, one warm-up step (first touch, lazy set-up) untimed. */
static gm_yee *open_cavity(size_t n, int threads, size_t *bytes, size_t *arrays,
                           size_t *layout_size) {
  gm_error err = {{0}};
  gm_yee *s = make_cavity(n, threads, &err);
  if (s == NULL) {
    fprintf(stderr, "bench_yee_throughput: %s\n", err.message);
    exit(1);
  }
  *bytes = gm_yee_memory(s, arrays);
  gm_yee_layout layout;
  gm_yee_get_layout(s, &layout);
  *layout_size = layout.size;
  if (gm_yee_advance(s, 1) != GM_OK) {
    fprintf(stderr, "bench_yee_throughput: %s\n", gm_yee_errmsg(s));
    exit(1);
  }
  return s;
}

/* Seconds for `steps` more steps. */
static double time_steps(gm_yee *s, size_t steps) {
  double t0 = bench_now();
  gm_status st = gm_yee_advance(s, steps);
  double t = bench_now() - t0;
  if (st != GM_OK) {
    fprintf(stderr, "bench_yee_throughput: %s\n", gm_yee_errmsg(s));
    exit(1);
  }
  return t;
}

/* ---- MEEP ------------------------------------------------------------------------------- */

typedef struct meep_result {
  double rate[MAX_THREADS + 1]; /* by number of processes; NaN when not measured */
  char skipped[512];
} meep_result;

static void run_meep(size_t n, size_t steps, meep_result *m) {
  for (int p = 0; p <= MAX_THREADS; ++p) m->rate[p] = NAN;
  m->skipped[0] = '\0';
  const char *skip = getenv("GM_SKIP_MEEP");
  if (skip != NULL && strcmp(skip, "1") == 0) {
    snprintf(m->skipped, sizeof m->skipped, "GM_SKIP_MEEP=1");
    return;
  }
  char script[1024];
  const char *env = getenv("GM_MEEP_SCRIPT");
  if (env != NULL) {
    snprintf(script, sizeof script, "%s", env);
  } else { /* next to this source file */
    snprintf(script, sizeof script, "%s", __FILE__);
    char *slash = strrchr(script, '/');
    snprintf(slash != NULL ? slash + 1 : script,
             sizeof script - (size_t)(slash != NULL ? slash + 1 - script : 0), "meep_cavity.py");
  }
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "python3 '%s' --n %zu --steps %zu --repeats 1", script, n, steps);
  FILE *p = popen(cmd, "r");
  if (p == NULL) {
    snprintf(m->skipped, sizeof m->skipped, "cannot run %.400s", cmd);
    return;
  }
  char line[8192];
  cJSON *result = NULL;
  while (fgets(line, sizeof line, p) != NULL) {
    if (strncmp(line, "MEEP_RESULT ", 12) == 0) {
      cJSON_Delete(result);
      result = cJSON_Parse(line + 12);
    } else {
      fputs(line, stdout);
    }
  }
  int status = pclose(p);
  if (result == NULL) {
    snprintf(m->skipped, sizeof m->skipped, "%.400s printed no result (exit status %d)", cmd,
             status);
    return;
  }
  const cJSON *run;
  cJSON_ArrayForEach(run, cJSON_GetObjectItem(result, "runs")) {
    int np = cJSON_GetObjectItem(run, "np")->valueint;
    if (np >= 1 && np <= MAX_THREADS)
      m->rate[np] = cJSON_GetObjectItem(run, "mcells_steps_per_s")->valuedouble;
  }
  const cJSON *why;
  size_t len = 0;
  cJSON_ArrayForEach(why, cJSON_GetObjectItem(result, "skipped")) {
    int k = snprintf(m->skipped + len, sizeof m->skipped - len, "%s%s", len > 0 ? "; " : "",
                     why->valuestring);
    if (k > 0) len += (size_t)k < sizeof m->skipped - len ? (size_t)k : 0;
  }
  cJSON_Delete(result);
}

static cJSON *number_or_null(double x) {
  return isfinite(x) ? cJSON_CreateNumber(x) : cJSON_CreateNull();
}

int main(int argc, char **argv) {
  size_t n = argc > 2 ? (size_t)strtoul(argv[2], NULL, 10) : 128;
  size_t steps = argc > 3 ? (size_t)strtoul(argv[3], NULL, 10) : 200;
  if (n < 8 || steps < 1) {
    fprintf(stderr, "usage: bench_yee_throughput [DIR] [N >= 8] [STEPS >= 1]\n");
    return 2;
  }
  double cells = (double)n * (double)n * (double)n;
  double load0 = load_average();
  int max_threads = 1;
#ifdef _OPENMP
  max_threads = omp_get_num_procs() < MAX_THREADS ? omp_get_num_procs() : MAX_THREADS;
#endif

  /* The solvers first (they fix the floor's array size), then REPEATS rounds that time each
   * solver and the floor at each thread count back to back, so that both see the same load;
   * the best round of each counts. */
  double yee_rate[MAX_THREADS + 1] = {0}, stream_rate[MAX_THREADS + 1] = {0};
  size_t bytes = 0, n_arrays = 0, layout_size = 0;
  gm_yee *solver[MAX_THREADS + 1] = {NULL};
  for (int t = 1; t <= max_threads; ++t)
    solver[t] = open_cavity(n, t, &bytes, &n_arrays, &layout_size);
  /* The floor over 6 arrays of the solver's size each for a and b (first touch in parallel
   * with the same static schedule as the sweep). */
  size_t len = 6 * layout_size;
  double *a = malloc(len * sizeof *a), *b = malloc(len * sizeof *b);
  if (a == NULL || b == NULL) {
    fprintf(stderr, "bench_yee_throughput: out of memory\n");
    return 1;
  }
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(max_threads)
#endif
  for (size_t i = 0; i < len; ++i) {
    a[i] = 1.0;
    b[i] = (double)(i % 7);
  }
  size_t sweeps = steps / 4 > 10 ? steps / 4 : 10;
  meep_result meep;
  double meep_best[MAX_THREADS + 1];
  int meep_off = 0;
  for (int p = 0; p <= MAX_THREADS; ++p) meep_best[p] = NAN;
  for (int r = 0; r < REPEATS; ++r) {
    for (int t = 1; t <= max_threads; ++t) {
      double ys = cells * (double)steps / time_steps(solver[t], steps) / 1e6;
      double ss = cells / stream_sweep(a, b, len, t, sweeps) / 1e6;
      if (ys > yee_rate[t]) yee_rate[t] = ys;
      if (ss > stream_rate[t]) stream_rate[t] = ss;
    }
    if (meep_off) continue;
    run_meep(n, steps, &meep);
    for (int p = 1; p <= MAX_THREADS; ++p)
      if (isfinite(meep.rate[p]) && !(meep.rate[p] <= meep_best[p])) meep_best[p] = meep.rate[p];
    /* skipped altogether (not installed, GM_SKIP_MEEP): do not ask again */
    meep_off = meep.skipped[0] != '\0' && !isfinite(meep.rate[1]) && !isfinite(meep.rate[2]);
  }
  for (int p = 1; p <= MAX_THREADS; ++p) meep.rate[p] = meep_best[p];
  double energy = 0.0;
  gm_yee_energy e;
  if (gm_yee_get_energy(solver[1], &e) == GM_OK) energy = e.plain;
  for (int t = 1; t <= max_threads; ++t) gm_yee_free(solver[t]);
  double checksum = a[len / 3];
  free(a);
  free(b);

  double load1 = load_average();

  printf("Yee %zu^3 vacuum cavity, PEC, %zu steps (dt = 0.5 h); load average %.2f -> %.2f\n", n,
         steps, load0, load1);
  printf("%-28s %8s %18s\n", "", "threads", "Mcells*steps/s");
  for (int t = 1; t <= max_threads; ++t) {
    printf("%-28s %8d %18.1f\n", "geomint gm_yee_advance", t, yee_rate[t]);
    printf("%-28s %8d %18.1f\n", "floor: stream a += s*b", t, stream_rate[t]);
    printf("%-28s %8d %18.1f\n", t == 1 ? "MEEP (1 process)" : "MEEP (mpirun -np 2)", t,
           meep.rate[t]);
  }
  if (meep.skipped[0] != '\0') printf("MEEP skipped: %s\n", meep.skipped);
  double r_meep1 = yee_rate[1] / meep.rate[1];
  double r_meep2 = max_threads >= 2 ? yee_rate[2] / meep.rate[2] : NAN;
  double f1 = yee_rate[1] / stream_rate[1];
  double f2 = max_threads >= 2 ? yee_rate[2] / stream_rate[2] : NAN;
  printf("ratio geomint 1 thread / MEEP np 1:   %.3f (goal >= 1.8)\n", r_meep1);
  printf("ratio geomint 2 threads / MEEP np 2:  %.3f (goal >= 1.6)\n", r_meep2);
  printf("fraction of the stream floor:        %.3f (1 thread), %.3f (2 threads) (goal >= 0.75)\n",
         f1, f2);
  printf("memory: %.1f bytes per cell in %zu grid-sized arrays (%zu bytes in all)\n",
         (double)bytes / cells, n_arrays, bytes);

  cJSON *o = cJSON_CreateObject();
  cJSON_AddStringToObject(o, "benchmark", "yee_throughput");
  cJSON_AddNumberToObject(o, "n", (double)n);
  cJSON_AddNumberToObject(o, "steps", (double)steps);
  cJSON_AddItemToObject(o, "load_average_start", number_or_null(load0));
  cJSON_AddItemToObject(o, "load_average_end", number_or_null(load1));
  cJSON *rows = cJSON_AddArrayToObject(o, "rows");
  for (int t = 1; t <= max_threads; ++t) {
    const char *what[3] = {"geomint", "stream_floor", "meep"};
    double rate[3] = {yee_rate[t], stream_rate[t], meep.rate[t]};
    for (int k = 0; k < 3; ++k) {
      cJSON *row = cJSON_CreateObject();
      cJSON_AddStringToObject(row, "what", what[k]);
      cJSON_AddNumberToObject(row, k == 2 ? "processes" : "threads", t);
      cJSON_AddItemToObject(row, "mcells_steps_per_s", number_or_null(rate[k]));
      cJSON_AddItemToArray(rows, row);
    }
  }
  cJSON *ratios = cJSON_AddObjectToObject(o, "ratios");
  cJSON_AddItemToObject(ratios, "geomint_1t_over_meep_np1", number_or_null(r_meep1));
  cJSON_AddItemToObject(ratios, "geomint_2t_over_meep_np2", number_or_null(r_meep2));
  cJSON_AddItemToObject(ratios, "geomint_1t_over_floor_1t", number_or_null(f1));
  cJSON_AddItemToObject(ratios, "geomint_2t_over_floor_2t", number_or_null(f2));
  cJSON *goals = cJSON_AddObjectToObject(o, "goals");
  cJSON_AddNumberToObject(goals, "geomint_1t_over_meep_np1", 1.8);
  cJSON_AddNumberToObject(goals, "geomint_2t_over_meep_np2", 1.6);
  cJSON_AddNumberToObject(goals, "fraction_of_floor", 0.75);
  if (meep.skipped[0] != '\0') cJSON_AddStringToObject(o, "meep_skipped", meep.skipped);
  cJSON_AddNumberToObject(o, "memory_bytes_per_cell", (double)bytes / cells);
  cJSON_AddNumberToObject(o, "memory_arrays", (double)n_arrays);
  cJSON_AddNumberToObject(o, "final_energy", energy);
  cJSON_AddNumberToObject(o, "stream_checksum", checksum);
  FILE *f = bench_open_json(argc, argv, "yee_throughput");
  if (f == NULL) {
    cJSON_Delete(o);
    return 1;
  }
  char *text = cJSON_Print(o);
  fprintf(f, "%s\n", text);
  fclose(f);
  free(text);
  cJSON_Delete(o);
  return 0;
}
