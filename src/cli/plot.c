/* Plots of the relative energy error against time, drawn by gnuplot through a pipe. */
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

static void write_script(FILE *g, const char *png_path, const char *title,
                         const cli_plot_series *series, size_t n_series) {
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
  fputs(" noenhanced\n"
        "set datafile separator ','\n"
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

int cli_plot_energy_error(const char *command, const char *png_path, const char *title,
                          const cli_plot_series *series, size_t n_series) {
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
    write_script(g, png_path, title, series, n_series);
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
