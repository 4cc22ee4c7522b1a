/* Plots of the maxwell command, drawn by gnuplot (cli_plot_custom): lines on linear or log
 * axes, a probe spectrum with the expected frequencies marked, and a colour map of a field
 * slice. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli/maxwell.h"

static const char *const colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                     "#9467bd", "#8c564b", "#e377c2", "#000000"};

/* A gnuplot single-quoted string. */
static void quoted(FILE *g, const char *s) {
  fputc('\'', g);
  for (; *s; ++s) {
    if (*s == '\'') fputc('\'', g);
    fputc(*s, g);
  }
  fputc('\'', g);
}

typedef struct lines_plot {
  const char *xlabel, *ylabel;
  int logy;
  const mx_line *lines;
  size_t n;
} lines_plot;

static int drawable(double x, double y, int logy) {
  return isfinite(x) && isfinite(y) && (!logy || y > 0);
}

static void lines_body(FILE *g, const void *ctx) {
  const lines_plot *l = ctx;
  fputs("set grid\nset key outside right top noenhanced\nset autoscale xfix\n", g);
  if (l->logy) fputs("set logscale y\nset format y '10^{%L}'\n", g);
  fputs("set xlabel ", g);
  quoted(g, l->xlabel);
  fputs(" noenhanced\nset ylabel ", g);
  quoted(g, l->ylabel);
  fputs(" noenhanced\nplot ", g);
  size_t drawn = 0;
  for (size_t k = 0; k < l->n; ++k) {
    if (drawn++ > 0) fputs(", \\\n     ", g);
    fprintf(g, "'-' using 1:2 with %s lw 1.5 lc rgb '%s' title ",
            l->lines[k].points ? "points pt 7 ps 0.8" : "lines", colors[k % 8]);
    quoted(g, l->lines[k].title);
  }
  if (drawn == 0) fputs("1/0 notitle", g);
  fputc('\n', g);
  for (size_t k = 0; k < l->n; ++k) {
    const mx_line *s = &l->lines[k];
    size_t written = 0;
    for (size_t i = 0; i < s->n; ++i)
      if (drawable(s->x[i], s->y[i], l->logy)) {
        fprintf(g, "%.12g %.12g\n", s->x[i], s->y[i]);
        ++written;
      }
    if (written == 0) fputs("0 NaN\n", g); /* an empty block would end the data early */
    fputs("e\n", g);
  }
}

int mx_plot_lines(const char *command, const char *png, const char *title, const char *xlabel,
                  const char *ylabel, int logy, const mx_line *lines, size_t n_lines) {
  lines_plot l = {xlabel, ylabel, logy, lines, n_lines};
  return cli_plot_custom(command, png, title, lines_body, &l);
}

typedef struct spectrum_plot {
  size_t n_freq;
  const double *f, *amp;
  const double *marks;
  size_t n_marks;
  double f_max;
} spectrum_plot;

static void spectrum_body(FILE *g, const void *ctx) {
  const spectrum_plot *s = ctx;
  fputs("set grid\nset logscale y\nset format y '10^{%L}'\nset key inside right top\n"
        "set xlabel 'frequency'\nset ylabel 'sum of |DFT| over the probes (Hann window)'\n", g);
  fprintf(g, "set xrange [0:%.12g]\n", s->f_max);
  for (size_t k = 0; k < s->n_marks; ++k)
    fprintf(g, "set arrow from %.12g, graph 0 to %.12g, graph 1 nohead lc rgb '#d62728' "
            "dt 2 lw 1\n", s->marks[k], s->marks[k]);
  fputs("plot '-' using 1:2 with lines lw 1.2 lc rgb '#1f77b4' title 'probe spectrum', "
        "NaN with lines dt 2 lc rgb '#d62728' title 'analytic resonances'\n", g);
  for (size_t i = 0; i < s->n_freq; ++i)
    if (s->amp[i] > 0) fprintf(g, "%.12g %.12g\n", s->f[i], s->amp[i]);
  fputs("e\n", g);
}

int mx_plot_spectrum(const char *command, const char *png, const char *title, size_t n_signals,
                     size_t n, const double *signals, double dt, double f_max,
                     const double *marks, size_t n_marks) {
  /* A direct DFT on a fine frequency grid: the plot needs a few thousand frequencies, and
   * this keeps FFTW out of the CLI. */
  size_t n_freq = 2000;
  double *f = malloc(n_freq * sizeof *f), *amp = calloc(n_freq, sizeof *amp);
  double *w = malloc((n + 1) * sizeof *w);
  if (f == NULL || amp == NULL || w == NULL) {
    free(f), free(amp), free(w);
    cli_error(command, "out of memory");
    return CLI_EXIT_FAILURE;
  }
  const double pi = 3.14159265358979323846;
  for (size_t k = 0; k < n_freq; ++k) f[k] = f_max * (double)k / (double)(n_freq - 1);
  for (size_t p = 0; p < n_signals; ++p) {
    const double *signal = signals + p * n;
    for (size_t i = 0; i < n; ++i)
      w[i] = signal[i] * (n > 1 ? 0.5 - 0.5 * cos(2 * pi * (double)i / (double)(n - 1)) : 1.0);
    for (size_t k = 0; k < n_freq; ++k) {
      /* rotation recurrence: e^{-i 2π f t_i} without a sin/cos per sample */
      double c = cos(2 * pi * f[k] * dt), s = -sin(2 * pi * f[k] * dt);
      double re = 0, im = 0, zr = 1, zi = 0;
      for (size_t i = 0; i < n; ++i) {
        re += w[i] * zr;
        im += w[i] * zi;
        double t = zr * c - zi * s;
        zi = zr * s + zi * c;
        zr = t;
      }
      amp[k] += sqrt(re * re + im * im) * dt;
    }
  }
  spectrum_plot s = {n_freq, f, amp, marks, n_marks, f_max};
  int rc = cli_plot_custom(command, png, title, spectrum_body, &s);
  free(f), free(amp), free(w);
  return rc;
}

typedef struct map_plot {
  const char *label;
  size_t nx, ny;
  double x0, y0, hx, hy;
  const double *v;
} map_plot;

static void map_body(FILE *g, const void *ctx) {
  const map_plot *m = ctx;
  double vmax = 0;
  for (size_t i = 0; i < m->nx * m->ny; ++i)
    if (isfinite(m->v[i])) vmax = fmax(vmax, fabs(m->v[i]));
  if (vmax == 0) vmax = 1;
  fputs("set view map\nset size ratio -1\nset xlabel 'x'\nset ylabel 'y'\n"
        "set palette defined (0 '#3b4cc0', 1 '#ffffff', 2 '#b40426')\n", g);
  fprintf(g, "set cbrange [%.12g:%.12g]\nset cblabel ", -vmax, vmax);
  quoted(g, m->label);
  fprintf(g, " noenhanced\nset xrange [%.12g:%.12g]\nset yrange [%.12g:%.12g]\n", m->x0,
          m->x0 + (double)m->nx * m->hx, m->y0, m->y0 + (double)m->ny * m->hy);
  fputs("plot '-' using 1:2:3 with image notitle\n", g);
  for (size_t j = 0; j < m->ny; ++j) {
    for (size_t i = 0; i < m->nx; ++i)
      fprintf(g, "%.9g %.9g %.9g\n", m->x0 + ((double)i + 0.5) * m->hx,
              m->y0 + ((double)j + 0.5) * m->hy, m->v[i + m->nx * j]);
    fputc('\n', g);
  }
  fputs("e\n", g);
}

int mx_plot_map(const char *command, const char *png, const char *title, const char *label,
                size_t nx, size_t ny, double x0, double y0, double hx, double hy,
                const double *values) {
  map_plot m = {label, nx, ny, x0, y0, hx, hy, values};
  return cli_plot_custom(command, png, title, map_body, &m);
}
