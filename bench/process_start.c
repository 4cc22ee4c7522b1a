/* Process start of the geomint program (issue 25, goal ≤ 10× a program that links only libc):
 * `geomint run kepler --steps 1 --quiet` against /bin/true (libc only), REPEATS interleaved
 * runs each, reporting the minimum wall time and the minimum CPU time (user + system of the
 * child, from getrusage of the children) and their ratios. CPU time is the robust figure on a loaded machine:
 * wall time there includes waiting for a core. `bench_process_start DIR PROGRAM` times another
 * build's program instead. Writes DIR/process_start.json. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>
#include <fcntl.h>

#include "bench_util.h"

#define REPEATS 40

typedef struct {
  double wall, cpu;
} start_cost;

/* Run argv once with stdout and stderr on /dev/null; the best times so far in *c. */
static double children_cpu(void) {
  struct rusage ru;
  getrusage(RUSAGE_CHILDREN, &ru);
  return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
         (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

static int run_once(char *const argv[], start_cost *c) {
  const double cpu0 = children_cpu();
  double t0 = bench_now();
  pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    int fd = open("/dev/null", O_WRONLY);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
    }
    execv(argv[0], argv);
    _exit(127);
  }
  int status;
  if (waitpid(pid, &status, 0) != pid) return -1;
  double wall = bench_now() - t0;
  double cpu = children_cpu() - cpu0;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1;
  c->wall = fmin(c->wall, wall);
  c->cpu = fmin(c->cpu, cpu);
  return 0;
}

int main(int argc, char **argv) {
  char *program = argc > 2 ? argv[2] : GM_CLI_PATH; /* another build's program, to compare */
  char *geomint[] = {program, "run", "kepler", "--steps", "1", "--quiet", NULL};
  char *libc_only[] = {"/bin/true", NULL};
  start_cost g = {INFINITY, INFINITY}, t = {INFINITY, INFINITY};
  for (int r = 0; r < REPEATS; ++r)
    if (run_once(geomint, &g) != 0 || run_once(libc_only, &t) != 0) {
      fprintf(stderr, "process_start: a run failed (%s)\n", program);
      return 1;
    }
  printf("min of %d interleaved runs    wall [ms]   CPU [ms]\n", REPEATS);
  printf("geomint run kepler --steps 1 %10.3f %10.3f\n", 1e3 * g.wall, 1e3 * g.cpu);
  printf("/bin/true (libc only)        %10.3f %10.3f\n", 1e3 * t.wall, 1e3 * t.cpu);
  printf("ratio                        %10.2f %10.2f   (goal <= 10)\n", g.wall / t.wall,
         g.cpu / fmax(t.cpu, 1e-6));
  FILE *f = bench_open_json(argc, argv, "process_start");
  if (f == NULL) return 1;
  fprintf(f, "{\n \"benchmark\": \"process_start\",\n \"repeats\": %d,\n"
          " \"geomint_wall_s\": %.6f, \"geomint_cpu_s\": %.6f,\n"
          " \"libc_only_wall_s\": %.6f, \"libc_only_cpu_s\": %.6f,\n"
          " \"wall_ratio\": %.3f, \"cpu_ratio\": %.3f\n}\n", REPEATS, g.wall, g.cpu, t.wall,
          t.cpu, g.wall / t.wall, g.cpu / fmax(t.cpu, 1e-6));
  fclose(f);
  return 0;
}
