/* Shared by the benchmarks: a monotonic clock and a JSON results file. */
#ifndef GM_BENCH_UTIL_H
#define GM_BENCH_UTIL_H

#include <stdio.h>
#include <time.h>

static inline double bench_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* CPU time of the calling thread: for single-threaded ratios, robust to other processes
 * taking the core for a while (the machine has two). */
static inline double bench_cpu_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Open DIR/NAME.json for writing (DIR from argv[1], default bench/results). */
static inline FILE *bench_open_json(int argc, char **argv, const char *name) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s.json", argc > 1 ? argv[1] : "bench/results", name);
  FILE *f = fopen(path, "w");
  if (f == NULL) fprintf(stderr, "cannot write %s\n", path);
  return f;
}

/* The overhead benches' JSON rows end alike: the timing fields, then "," unless last. */
static inline void bench_json_timing(FILE *f, double bare_s, double library_s, double ratio,
                                     int identical, int last) {
  fprintf(f, "\"bare_s\": %.6f, \"library_s\": %.6f, \"ratio\": %.4f, \"identical\": %s}%s\n",
          bare_s, library_s, ratio, identical ? "true" : "false", last ? "" : ",");
}

/* Close the "rows" array and the object opened by the caller, and the file. */
static inline void bench_close_json(FILE *f) {
  fprintf(f, "  ]\n}\n");
  fclose(f);
}

#endif
