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

#endif
