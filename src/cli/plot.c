/* Plots drawn by gnuplot through a pipe: the relative energy error against time (run, demo),
 * and log-log lines of y against x (wp: error against force evaluations). */
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli/cli.h"

int cli_gnuplot_available(void) {
  const char *path = getenv("PATH");
  if (path == NULL) return 0;
  char file[4096];
  while (*path != '\0') {
    size_t len = strcspn(path, ":");
    const char *dir = len > 0 ? path : ".";
    int dir_len = len > 0 ? (int)len : 1;
    if (snprintf(file, sizeof file, "%.*s/gnuplot", dir_len, dir) < (int)sizeof file &&
        access(file, X_OK) == 0)
      return 1;
    path += len;
    if (*path == ':') ++path;
  }
  return 0;
}

/* A gnuplot single-quoted string: ' is doubled. */
static void put_quoted(FILE *f, const char *s) {
  fputc('\'', f);
  for (; *s; ++s) {
    if (*s == '\'') fputc('\'', f);
    fputc(*s, f);
  }
  fputc('\'', f);
}

/* The PNG terminal, the output file and the title. */
static void write_preamble(FILE *g, const char *png_path, const char *title) {
  fputs("if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
        "  set terminal pngcairo size 960,600 enhanced font 'sans,10'\n"
        "} else {\n"
        "  set terminal png size 960,600\n"
        "}\n",
        g);
  fputs("set output ", g);
  put_quoted(g, png_path);
  fputs("\nset title ", g);
  put_quoted(g, title);
  fputs(" noenhanced\n", g);
}

typedef struct energy_plot {
  const char *title;
  const cli_plot_series *series;
  size_t n_series;
} energy_plot;

static void write_energy_script(FILE *g, const char *png_path, const void *ctx) {
  const energy_plot *e = ctx;
  const cli_plot_series *series = e->series;
  size_t n_series = e->n_series;
  write_preamble(g, png_path, e->title);
  fputs("set datafile separator ','\n"
        "set logscale y\n"
        "set autoscale xfix\n"
        "set format y '10^{%L}'\n"
        "set xlabel 't'\n"
        "set ylabel '|H - H_0| / |H_0|'\n"
        "set grid\n"
        "set key outside right top noenhanced\n"
        "plot ",
        g);
  for (size_t k = 0; k < n_series; ++k) {
    size_t col = series[k].column + 1;
    if (k > 0) fputs(", \\\n     ", g);
    put_quoted(g, series[k].csv_path);
    /* zeros have no logarithm: they are left out of the curve */
    fprintf(g, " skip 1 using 1:(column(%zu) > 0 ? column(%zu) : 1/0) with lines lw 1.5 title ",
            col, col);
    put_quoted(g, series[k].title);
  }
  fputs("\nset output\n", g);
}

/* The most telling line of gnuplot's complaint: the text after its last "line N:" marker. */
static void gnuplot_reason(FILE *log, char *reason, size_t cap) {
  char line[512];
  reason[0] = '\0';
  rewind(log);
  while (fgets(line, sizeof line, log) != NULL) {
    line[strcspn(line, "\r\n")] = '\0';
    const char *text = strstr(line, "line ");
    if (text != NULL && (text = strchr(text, ':')) != NULL) {
      text += strspn(text + 1, " ") + 1;
      snprintf(reason, cap, "%s", text);
    }
  }
}

int cli_plot_check_output(const char *command, const char *png_path) {
  char dir[4096];
  const char *slash = strrchr(png_path, '/');
  if (slash == NULL)
    snprintf(dir, sizeof dir, ".");
  else if (slash == png_path)
    snprintf(dir, sizeof dir, "/");
  else
    snprintf(dir, sizeof dir, "%.*s", (int)(slash - png_path), png_path);
  struct stat sb;
  if (stat(dir, &sb) == 0 && S_ISDIR(sb.st_mode) && access(dir, W_OK) == 0)
    return CLI_EXIT_OK;
  cli_error(command, "cannot write %s: '%s' is not a writable directory", png_path, dir);
  return CLI_EXIT_FAILURE;
}

typedef void (*script_writer)(FILE *g, const char *png_path, const void *ctx);

/* Pipe the script into gnuplot and check that it wrote png_path; returns an exit status. */
static int run_gnuplot(const char *command, const char *png_path, script_writer write_script,
                       const void *ctx) {
  if (!cli_gnuplot_available()) {
    cli_error(command, "cannot draw %s: gnuplot is not installed (or not on PATH)", png_path);
    return CLI_EXIT_FAILURE;
  }
  /* gnuplot's complaints go to a log we summarize; its stdout never reaches ours */
  char log_path[] = "/tmp/geomint-gnuplot-XXXXXX", cmd[128];
  int fd = mkstemp(log_path);
  FILE *log = fd >= 0 ? fdopen(fd, "r") : NULL;
  if (log == NULL) {
    if (fd >= 0) close(fd);
    cli_error(command, "cannot create a temporary file in /tmp for gnuplot");
    return CLI_EXIT_FAILURE;
  }
  snprintf(cmd, sizeof cmd, "exec gnuplot >/dev/null 2>'%s'", log_path);
  fflush(stdout);
  signal(SIGPIPE, SIG_IGN); /* a gnuplot that exits early must not kill us */
  FILE *g = popen(cmd, "w");
  int status = -1;
  if (g != NULL) {
    write_script(g, png_path, ctx);
    status = pclose(g);
  }
  char reason[256];
  gnuplot_reason(log, reason, sizeof reason);
  fclose(log);
  remove(log_path);
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    cli_error(command, "gnuplot failed to draw %s: %s", png_path,
              reason[0] ? reason : "no reason given");
    return CLI_EXIT_FAILURE;
  }
  struct stat sb;
  if (stat(png_path, &sb) != 0 || sb.st_size == 0) {
    cli_error(command, "gnuplot did not write %s%s%s", png_path, reason[0] ? ": " : "", reason);
    return CLI_EXIT_FAILURE;
  }
  return CLI_EXIT_OK;
}

int cli_plot_energy_error(const char *command, const char *png_path, const char *title,
                          const cli_plot_series *series, size_t n_series) {
  energy_plot e = {title, series, n_series};
  return run_gnuplot(command, png_path, write_energy_script, &e);
}

/* Twelve colours that stay distinct next to each other on white. */
static const char *const line_colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                          "#9467bd", "#8c564b", "#e377c2", "#000000",
                                          "#17becf", "#bcbd22", "#7f7f7f", "#00008b"};
#define N_LINE_COLORS (sizeof line_colors / sizeof line_colors[0])

typedef struct loglog_plot {
  const char *title, *xlabel, *ylabel;
  const cli_xy_series *series;
  size_t n_series;
} loglog_plot;

/* Points with a positive finite x and y: the others have no place on log axes. */
static int loggable(double x, double y) {
  return isfinite(x) && isfinite(y) && x > 0.0 && y > 0.0;
}

static void write_loglog_script(FILE *g, const char *png_path, const void *ctx) {
  const loglog_plot *l = ctx;
  write_preamble(g, png_path, l->title);
  fputs("set logscale xy\n"
        "set format x '10^{%L}'\n"
        "set format y '10^{%L}'\n"
        "set grid xtics ytics mxtics mytics lw 0.5, lw 0.25\n"
        "set key inside right top noenhanced box opaque\n"
        "set xlabel ",
        g);
  put_quoted(g, l->xlabel);
  fputs(" noenhanced\nset ylabel ", g);
  put_quoted(g, l->ylabel);
  fputs(" noenhanced\nplot ", g);
  /* inline data ('-'), one block per series that has a point to draw */
  size_t drawn = 0;
  for (size_t k = 0; k < l->n_series; ++k) {
    size_t n_points = 0;
    for (size_t i = 0; i < l->series[k].n; ++i)
      n_points += loggable(l->series[k].x[i], l->series[k].y[i]);
    if (n_points == 0) continue;
    if (drawn++ > 0) fputs(", \\\n     ", g);
    fprintf(g, "'-' using 1:2 with linespoints lw 1.5 lc rgb '%s' pt %zu ps 1.1 title ",
            line_colors[k % N_LINE_COLORS], k % 13 + 1);
    put_quoted(g, l->series[k].title);
  }
  if (drawn == 0) fputs("1/0 notitle", g);
  fputc('\n', g);
  for (size_t k = 0; k < l->n_series; ++k) {
    size_t n_points = 0;
    for (size_t i = 0; i < l->series[k].n; ++i)
      if (loggable(l->series[k].x[i], l->series[k].y[i])) {
        fprintf(g, "%.17g %.17g\n", l->series[k].x[i], l->series[k].y[i]);
        ++n_points;
      }
    if (n_points > 0) fputs("e\n", g);
  }
  fputs("set output\n", g);
}

int cli_plot_loglog(const char *command, const char *png_path, const char *title,
                    const char *xlabel, const char *ylabel, const cli_xy_series *series,
                    size_t n_series) {
  loglog_plot l = {title, xlabel, ylabel, series, n_series};
  return run_gnuplot(command, png_path, write_loglog_script, &l);
}

typedef struct custom_plot {
  const char *title;
  cli_plot_body body;
  const void *ctx;
} custom_plot;

static void write_custom_script(FILE *g, const char *png_path, const void *ctx) {
  const custom_plot *c = ctx;
  write_preamble(g, png_path, c->title);
  c->body(g, c->ctx);
  fputs("\nset output\n", g);
}

int cli_plot_custom(const char *command, const char *png_path, const char *title,
                    cli_plot_body body, const void *ctx) {
  custom_plot c = {title, body, ctx};
  return run_gnuplot(command, png_path, write_custom_script, &c);
}

int cli_prepare_plot_dir(const char *cmd, const char *dir, int no_plot) {
  if (strchr(dir, '\'') != NULL) {
    cli_error(cmd, "--out: the directory name may not contain a quote");
    return CLI_EXIT_USAGE;
  }
  if (!no_plot && !cli_gnuplot_available()) {
    cli_error(cmd, "gnuplot is not installed (or not on PATH): use --no-plot");
    return CLI_EXIT_FAILURE;
  }
  if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
    cli_error(cmd, "cannot create the directory '%s': %s", dir, strerror(errno));
    return CLI_EXIT_FAILURE;
  }
  return CLI_EXIT_OK;
}
