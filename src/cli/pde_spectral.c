/* geomint pde schrodinger | spectral-star | tent-vi: the pseudospectral Schrödinger VI against
 * Strang split-step Fourier (eigenvalues; a coherent state at equal cost), the spectral Hodge
 * star's dispersion against the diagonal star's (each writes .dat files and one gnuplot
 * figure), and the tent-function VI of seed 001 §5.1 on sine-Gordon. */
#include <cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "cli/cli.h"
#include "cli/pde_spectral.h"
#include "geomint/experiments.h"

#define PI_ 3.14159265358979323846
#define HO_BOX 20.0 /* harmonic: [−10, 10) */
#define PT_BOX 40.0 /* Pöschl–Teller λ = 2: [−20, 20) */

const char cli_pde_spectral_usage[] =
    "       geomint pde schrodinger eigen [--out DIR] [--no-plot] [--json]\n"
    "       geomint pde schrodinger compare [--n N] [--dt DT] [--T T] [--out DIR] [--no-plot]\n"
    "                                       [--json]\n"
    "       geomint pde spectral-star [--n N] [--courant C] [--out DIR] [--no-plot] [--json]\n"
    "       geomint pde tent-vi [--initial breather|kink] [--param P] [--n N] [--dt DT] [--T T]\n"
    "                           [--out FILE.csv] [--json]\n"
    "\n"
    "schrodinger: i psi_t = -psi_xx/2 + V psi, periodic; the pseudospectral VI (seed 001 5.8)\n"
    "     and Strang split-step Fourier. eigen: eigenvalues of V = x^2/2 on [-10, 10) and\n"
    "     V = -3 sech^2 x on [-20, 20) from the phase of an evolved eigenstate, against N and dt.\n"
    "     compare: the coherent state a = 2 of V = x^2/2 (default N 64, dt 0.01, T 100), VI\n"
    "     against split-step at the same dt and at equal FFT count; error against t.\n"
    "spectral-star: u_tt = *d*d u on [0, 2 pi), N points (default 64), d topological, diagonal\n"
    "     or spectral star (h sinc(k/N)); frequency error of every mode, semi-discrete and with\n"
    "     leapfrog at dt = C h (default C = 0.1).\n"
    "tent-vi: the multisymplectic VI with bilinear tents (seed 001 5.1) on sine-Gordon, from the\n"
    "     exact breather (frequency P, default 0.5) or kink (speed P) at t = 0 and dt on\n"
    "     [-20, 20) (default N 200, dt 0.1 <= dx, T 10); prints the error and the strip energy;\n"
    "     --out writes x,u,exact at T.\n";

/* --help of schrodinger, spectral-star, tent-vi: the usage lines (the text's first line, which
 * pde --help prints after its own, is indented for that) */
static void print_help(void) {
  fputs("usage:", stdout);
  fputs(cli_pde_spectral_usage + strlen("      "), stdout);
}

static double wall_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static FILE *open_out(const char *cmd, const char *dir, const char *name) {
  char path[4200];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  if (f == NULL) cli_error(cmd, "cannot write '%s': %s", path, strerror(errno));
  return f;
}

static int run_gnuplot(const char *cmd, const char *dir, const char *name, const char *body) {
  FILE *g = open_out(cmd, dir, name);
  if (g == NULL) return CLI_EXIT_FAILURE;
  fputs(body, g);
  fclose(g);
  char line[8600];
  snprintf(line, sizeof line, "cd '%s' && gnuplot '%s' 2>/dev/null", dir, name);
  if (system(line) != 0) {
    cli_error(cmd, "gnuplot failed on %s/%s", dir, name);
    return CLI_EXIT_FAILURE;
  }
  return CLI_EXIT_OK;
}

/* ---- eigenvalues by evolution (gm_experiment_schrodinger_eigen) ----------------------------- */

static double potential(int pt, double x) { return pt ? -3.0 / (cosh(x) * cosh(x)) : 0.5 * x * x; }

static int sch_eigen(const char *dir, int no_plot, int json) {
  const char *cmd = "pde schrodinger eigen";
  int rc = cli_prepare_plot_dir(cmd, dir, no_plot);
  if (rc != CLI_EXIT_OK) return rc;
  gm_schrodinger_eigen_result r;
  gm_error err = {{0}};
  if (gm_experiment_schrodinger_eigen(dir, &r, &err) != GM_OK) {
    cli_error(cmd, "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  if (!json) {
    printf("Eigenvalues by evolution (VI; the phase of <phi, psi(t)> fitted, the scheme's\n"
           "dispersion relation inverted), against N:\n");
    printf("  %-6s %-12s %-12s %-6s %-12s %-12s\n", "N", "harm. E1", "harm. E3", "N", "P-T E0",
           "P-T E1 (box 60)");
    for (int i = 0; i < GM_SCHRODINGER_EIGEN_N; i++)
      printf("  %-6zu %-12.3e %-12.3e %-6zu %-12.3e %-12.3e\n", r.n_harmonic[i], r.err_n[i][0],
             r.err_n[i][1], r.n_pt[i], r.err_n[i][2], r.err_n[i][3]);
    printf("Frequency error |Omega - E| of harmonic phi_3 (E = 3.5), N = 64, T = 8, against dt\n"
           "(no inversion: the time error itself):\n  %-8s %-12s %-12s\n", "dt", "VI",
           "split-step");
    for (int i = 0; i < GM_SCHRODINGER_EIGEN_DT; i++) {
      printf("  %-8g %-12.3e %-12.3e", r.dt[i], r.err_vi[i], r.err_split_step[i]);
      if (i > 0)
        printf("  orders %.2f, %.2f", log2(r.err_vi[i - 1] / r.err_vi[i]),
               log2(r.err_split_step[i - 1] / r.err_split_step[i]));
      printf("\n");
    }
  }
  if (!no_plot) {
    rc = run_gnuplot(
        cmd, dir, "schrodinger-eigen.gp",
        "set terminal pngcairo size 1200,500 font ',10'\n"
        "set output 'schrodinger-eigen.png'\n"
        "set multiplot layout 1,2\n"
        "set logscale y\nset format y '10^{%L}'\nset key top right\nset grid\n"
        "set title 'eigenvalue error against N (pseudospectral VI)'\n"
        "set xlabel 'N'\nset ylabel '|E_N - E|'\nset yrange [1e-16:1]\n"
        "plot 'schrodinger-eigen-n.dat' u 1:($2>0?$2:1e-16) w lp lw 2 t 'harmonic E_1 (box 20)', "
        "'' u 1:($3>0?$3:1e-16) w lp lw 2 t 'harmonic E_3', "
        "'' u 4:($5>0?$5:1e-16) w lp lw 2 t 'Poschl-Teller E_0 (box 40)', "
        "'' u ($4*1.5):($6>0?$6:1e-16) w lp lw 2 t 'Poschl-Teller E_1 (box 60)'\n"
        "set title 'frequency error of harmonic E_3 against dt (N = 64)'\n"
        "set logscale x\nset xlabel 'dt'\nset ylabel '|Omega - E|'\nset yrange [*:*]\n"
        "plot 'schrodinger-eigen-dt.dat' u 1:2 w lp lw 2 t 'VI (Milne-Simpson): order 4', "
        "'' u 1:3 w lp lw 2 t 'Strang split-step: order 2'\n"
        "unset multiplot\n");
    if (rc != CLI_EXIT_OK) return rc;
    if (!json) printf("  figure: %s/schrodinger-eigen.png\n", dir);
  }
  if (!json) return CLI_EXIT_OK;
  cJSON *o = cJSON_CreateObject();
  cJSON *a = cJSON_AddArrayToObject(o, "against_n");
  for (int i = 0; i < GM_SCHRODINGER_EIGEN_N; i++) {
    cJSON *j = cJSON_CreateObject();
    cJSON_AddNumberToObject(j, "n_harmonic", (double)r.n_harmonic[i]);
    cJSON_AddItemToObject(j, "harmonic_e1_error", cli_json_number(r.err_n[i][0]));
    cJSON_AddItemToObject(j, "harmonic_e3_error", cli_json_number(r.err_n[i][1]));
    cJSON_AddNumberToObject(j, "n_poschl_teller", (double)r.n_pt[i]);
    cJSON_AddItemToObject(j, "poschl_teller_e0_error", cli_json_number(r.err_n[i][2]));
    cJSON_AddItemToObject(j, "poschl_teller_e1_error", cli_json_number(r.err_n[i][3]));
    cJSON_AddItemToArray(a, j);
  }
  a = cJSON_AddArrayToObject(o, "against_dt");
  for (int i = 0; i < GM_SCHRODINGER_EIGEN_DT; i++) {
    cJSON *j = cJSON_CreateObject();
    cJSON_AddNumberToObject(j, "dt", r.dt[i]);
    cJSON_AddItemToObject(j, "vi_frequency_error", cli_json_number(r.err_vi[i]));
    cJSON_AddItemToObject(j, "split_step_frequency_error", cli_json_number(r.err_split_step[i]));
    cJSON_AddItemToArray(a, j);
  }
  cJSON_AddItemToObject(o, "order_vi", cli_json_number(r.order_vi));
  cJSON_AddItemToObject(o, "order_split_step", cli_json_number(r.order_split_step));
  cJSON_AddNumberToObject(o, "wall_s", r.wall_s);
  return cli_json_print(o);
}

/* ---- coherent state at equal cost ------------------------------------------------------------ */

static void coherent(double x, double t, double *re, double *im) {
  const double a = 2.0;
  double q = a * cos(t), p = -a * sin(t);
  double mod = pow(PI_, -0.25) * exp(-0.5 * (x - q) * (x - q));
  double ph = p * x - 0.5 * t + 0.25 * a * a * sin(2.0 * t);
  *re = mod * cos(ph);
  *im = mod * sin(ph);
}

static gm_schrodinger *coherent_solver(const char *cmd, gm_schrodinger_scheme sc, size_t n,
                                       double dt) {
  double *V = malloc(n * sizeof *V), *psi = malloc(2 * n * sizeof *psi);
  gm_schrodinger *s = NULL;
  if (V == NULL || psi == NULL) {
    cli_error(cmd, "out of memory");
  } else {
    for (size_t j = 0; j < n; j++) {
      double x = -0.5 * HO_BOX + (double)j * HO_BOX / (double)n;
      V[j] = potential(0, x);
      coherent(x, 0.0, psi + 2 * j, psi + 2 * j + 1);
    }
    gm_schrodinger_options o = gm_schrodinger_options_defaults();
    o.scheme = sc;
    o.dt = dt;
    gm_error err = {{0}};
    if (gm_schrodinger_create(n, -0.5 * HO_BOX, HO_BOX, V, psi, &o, &s, &err) != GM_OK)
      cli_error(cmd, "%s", err.message);
  }
  free(V);
  free(psi);
  return s;
}

static double coherent_error(const gm_schrodinger *s, size_t n) {
  const double *p = gm_schrodinger_psi(s);
  double t = gm_schrodinger_time(s), e = 0.0;
  for (size_t j = 0; j < n; j++) {
    double re, im;
    coherent(-0.5 * HO_BOX + (double)j * HO_BOX / (double)n, t, &re, &im);
    e = fmax(e, hypot(p[2 * j] - re, p[2 * j + 1] - im));
  }
  return e;
}

static int sch_compare(size_t n, double dt, double T, const char *dir, int no_plot, int json) {
  const char *cmd = "pde schrodinger compare";
  if (cli_check_positive(cmd, "--dt", dt) != CLI_EXIT_OK ||
      cli_check_positive(cmd, "--T", T) != CLI_EXIT_OK ||
      cli_check_step_count(cmd, T, dt) != CLI_EXIT_OK)
    return CLI_EXIT_USAGE;
  if (n < 4 || n % 2 != 0 || n > (1u << 24)) {
    cli_error(cmd, "--n %zu must be even, >= 4 and <= 2^24", n);
    return CLI_EXIT_USAGE;
  }
  int rc = cli_prepare_plot_dir(cmd, dir, no_plot);
  if (rc != CLI_EXIT_OK) return rc;
  /* the VI's FFTs a step, measured on its first 20 steps, set the split-step's equal-cost step */
  gm_schrodinger *vi = coherent_solver(cmd, GM_SCHRODINGER_VI, n, dt);
  if (vi == NULL) return CLI_EXIT_USAGE;
  gm_error err = {{0}};
  size_t f0 = gm_schrodinger_ffts(vi);
  if (gm_schrodinger_advance(vi, 21, &err) != GM_OK) {
    cli_error(cmd, "%s", err.message);
    gm_schrodinger_free(vi);
    return CLI_EXIT_FAILURE;
  }
  double per_step = (double)(gm_schrodinger_ffts(vi) - f0) / 20.0; /* step 1 is the start */
  gm_schrodinger_free(vi);
  size_t ratio = (size_t)floor(per_step / 2.0 + 0.5);
  if (ratio < 1) ratio = 1;
  vi = coherent_solver(cmd, GM_SCHRODINGER_VI, n, dt);
  gm_schrodinger *ss = coherent_solver(cmd, GM_SCHRODINGER_SPLIT_STEP, n, dt);
  gm_schrodinger *se = coherent_solver(cmd, GM_SCHRODINGER_SPLIT_STEP, n, dt / (double)ratio);
  if (vi == NULL || ss == NULL || se == NULL) {
    gm_schrodinger_free(vi);
    gm_schrodinger_free(ss);
    gm_schrodinger_free(se);
    return CLI_EXIT_FAILURE;
  }
  FILE *f = open_out(cmd, dir, "schrodinger-compare.dat");
  if (f == NULL) {
    rc = CLI_EXIT_FAILURE;
    goto done;
  }
  cJSON *rows = json ? cJSON_CreateArray() : NULL;
  if (!json) {
  printf("Coherent state a = 2 of V = x^2/2 on [-10, 10), N = %zu, dt = %g, T = %g\n", n, dt, T);
  printf("  the VI takes %.2f FFTs a step (%.2f inner iterations); split-step 2: equal cost is\n"
         "  split-step at dt/%zu\n",
         per_step, (per_step - 2.0) / 2.0, ratio);
  printf("  %-10s %-12s %-14s %-18s %-12s\n", "t", "VI", "split (dt)", "split (dt/r, equal)",
         "VI charge");
  }
  fprintf(f, "# t err_vi err_split_dt err_split_equal_cost vi_charge_drift vi_norm_drift\n");
  const double t_wall = wall_now();
  double q0 = gm_schrodinger_charge(vi), n0 = gm_schrodinger_norm(vi), next = dt;
  size_t steps = (size_t)llround(T / dt), report = steps / 10 > 0 ? steps / 10 : 1;
  for (size_t k = 1; k <= steps; k++) {
    if (gm_schrodinger_advance(vi, 1, &err) != GM_OK ||
        gm_schrodinger_advance(ss, 1, &err) != GM_OK ||
        gm_schrodinger_advance(se, ratio, &err) != GM_OK) {
      cli_error(cmd, "%s", err.message);
      rc = CLI_EXIT_FAILURE;
      break;
    }
    double t = (double)k * dt;
    int print = k % report == 0;
    if (t + 1e-12 >= next || k == steps || print) { /* logarithmic in t, and every T/10 */
      double a = coherent_error(vi, n), b = coherent_error(ss, n), c = coherent_error(se, n);
      double dq = fabs(gm_schrodinger_charge(vi) - q0) / q0;
      double dn = fabs(gm_schrodinger_norm(vi) - n0) / n0;
      fprintf(f, "%.6g %.6e %.6e %.6e %.3e %.3e\n", t, a, b, c, dq, dn);
      if (t + 1e-12 >= next) next = t * 1.035;
      if (print && !json) printf("  %-10.4g %-12.3e %-14.3e %-18.3e %-12.2e\n", t, a, b, c, dq);
      if (print && json) {
        cJSON *j = cJSON_CreateObject();
        cJSON_AddNumberToObject(j, "t", t);
        cJSON_AddItemToObject(j, "vi_max_abs_error", cli_json_number(a));
        cJSON_AddItemToObject(j, "split_step_max_abs_error", cli_json_number(b));
        cJSON_AddItemToObject(j, "split_step_equal_cost_max_abs_error", cli_json_number(c));
        cJSON_AddItemToObject(j, "vi_max_rel_charge_error", cli_json_number(dq));
        cJSON_AddItemToArray(rows, j);
      }
    }
  }
  fclose(f);
  if (rc == CLI_EXIT_OK && !no_plot) {
    char body[2400];
    snprintf(body, sizeof body,
             "set terminal pngcairo size 900,550 font ',10'\n"
             "set output 'schrodinger-compare.png'\n"
             "set logscale xy\nset format y '10^{%%L}'\nset grid\nset key bottom right\n"
             "set title 'coherent state a = 2, V = x^2/2, N = %zu: max error against t'\n"
             "set xlabel 't'\nset ylabel 'max_j |psi_j - psi(x_j, t)|'\n"
             "plot 'schrodinger-compare.dat' u 1:2 w l lw 2 t 'VI, dt = %g', "
             "'' u 1:3 w l lw 2 t 'split-step, dt = %g', "
             "'' u 1:4 w l lw 2 dt 2 t 'split-step, dt/%zu (equal FFT count)'\n",
             n, dt, dt, ratio);
    rc = run_gnuplot(cmd, dir, "schrodinger-compare.gp", body);
    if (rc == CLI_EXIT_OK && !json) printf("  figure: %s/schrodinger-compare.png\n", dir);
  }
  if (rc == CLI_EXIT_OK && json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "n", (double)n);
    cJSON_AddNumberToObject(o, "dt", dt);
    cJSON_AddNumberToObject(o, "t_end", T);
    cJSON_AddNumberToObject(o, "steps", (double)steps);
    cJSON_AddNumberToObject(o, "vi_ffts_per_step", per_step);
    cJSON_AddNumberToObject(o, "equal_cost_ratio", (double)ratio);
    cJSON_AddItemToObject(o, "rows", rows);
    rows = NULL;
    cJSON_AddNumberToObject(o, "wall_s", wall_now() - t_wall);
    rc = cli_json_print(o);
  }
  cJSON_Delete(rows);
done:
  gm_schrodinger_free(vi);
  gm_schrodinger_free(ss);
  gm_schrodinger_free(se);
  return rc;
}

int cli_pde_schrodinger(int argc, char **argv) {
  const char *dir = "pde-output", *positional[1] = {NULL};
  int no_plot = 0, json = 0;
  size_t n = 64, n_pos = 0;
  double dt = 0.01, T = 100.0;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &dir, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0},
                          {"--n", CLI_ARG_COUNT, &n, 0},
                          {"--dt", CLI_ARG_DOUBLE, &dt, 0},
                          {"--T", CLI_ARG_DOUBLE, &T, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0}};
  int rc = cli_parse("pde schrodinger", argc, argv, options, 6, positional, 1, &n_pos);
  if (rc == CLI_HELP) {
    print_help();
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  if (n_pos == 1 && strcmp(positional[0], "eigen") == 0) {
    /* eigen scans its own N and dt (an option it would ignore is an error) */
    for (size_t i = 2; i < 5; ++i)
      if (options[i].seen) {
        cli_error("pde schrodinger", "%s is an option of 'compare'; 'eigen' scans N and dt itself",
                  options[i].name);
        return CLI_EXIT_USAGE;
      }
    return sch_eigen(dir, no_plot, json);
  }
  if (n_pos == 1 && strcmp(positional[0], "compare") == 0)
    return sch_compare(n, dt, T, dir, no_plot, json);
  cli_error("pde schrodinger", "which experiment? eigen or compare");
  return CLI_EXIT_USAGE;
}

/* ---- spectral Hodge star (gm_experiment_spectral_star) ------------------------------------ */

int cli_pde_spectral_star(int argc, char **argv) {
  const char *cmd = "pde spectral-star", *dir = "pde-output";
  int no_plot = 0, json = 0;
  size_t n_pos = 0;
  gm_spectral_star_config c = gm_spectral_star_defaults();
  cli_option options[] = {{"--out", CLI_ARG_STRING, &dir, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0},
                          {"--n", CLI_ARG_COUNT, &c.n, 0},
                          {"--courant", CLI_ARG_DOUBLE, &c.courant, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0}};
  int rc = cli_parse(cmd, argc, argv, options, 5, NULL, 0, &n_pos);
  if (rc == CLI_HELP) {
    print_help();
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  const size_t n = c.n;
  if (n < 4 || n % 2 != 0 || n > 4096) {
    cli_error(cmd, "--n %zu must be even, >= 4 and <= 4096", n);
    return CLI_EXIT_USAGE;
  }
  if (!(c.courant > 0.0 && c.courant <= 2.0 / PI_)) {
    cli_error(cmd, "--courant %g must lie in (0, 2/pi] (leapfrog with the spectral star)",
              c.courant);
    return CLI_EXIT_USAGE;
  }
  if ((rc = cli_prepare_plot_dir(cmd, dir, no_plot)) != CLI_EXIT_OK) return rc;
  gm_spectral_star_result r;
  gm_error err = {{0}};
  if (gm_experiment_spectral_star(&c, dir, &r, &err) != GM_OK) {
    cli_error(cmd, "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  if (!json) {
    printf("u_tt = *d*d u on [0, 2 pi), N = %zu, leapfrog dt = %g h, T = %g: relative frequency "
           "error\n  %-5s %-12s %-12s %-14s %-14s %-12s\n",
           n, c.courant, r.t_end, "m", "diag (semi)", "spec (semi)", "diag+leapfrog",
           "spec+leapfrog", "spec spatial");
    for (size_t i = 0; i < r.n_modes; ++i) {
      const gm_spectral_star_mode *x = &r.modes[i];
      if (x->m % (long)(n / 16 > 0 ? n / 16 : 1) == 0 || x->m == 1)
        printf("  %-5ld %-12.3e %-12.3e %-14.3e %-14.3e %-12.3e\n", x->m, x->semi_diagonal,
               x->semi_spectral, x->leapfrog_diagonal, x->leapfrog_spectral, x->spectral_spatial);
    }
  }
  if (!no_plot) {
    char body[2400];
    snprintf(body, sizeof body,
             "set terminal pngcairo size 900,550 font ',10'\n"
             "set output 'spectral-star.png'\n"
             "set logscale y\nset format y '10^{%%L}'\nset grid\nset key center right\n"
             "set yrange [1e-17:10]\n"
             "set title 'u_{tt} = *d*d u, N = %zu: relative frequency error |omega - k|/k'\n"
             "set xlabel 'k / N'\nset ylabel 'relative error'\n"
             "f(x) = x > 1e-17 ? x : 1e-17\n"
             "plot 'spectral-star.dat' u 1:(f($2)) w lp lw 2 t 'diagonal star, semi-discrete', "
             "'' u 1:(f($3)) w lp lw 2 t 'spectral star, semi-discrete', "
             "'' u 1:(f($4)) w l lw 2 dt 2 t 'diagonal star + leapfrog (dt = %g h)', "
             "'' u 1:(f($5)) w l lw 2 dt 2 t 'spectral star + leapfrog', "
             "'' u 1:(f($6)) w p pt 6 t 'spectral + leapfrog minus leapfrog(exact k)'\n",
             n, c.courant);
    rc = run_gnuplot(cmd, dir, "spectral-star.gp", body);
    if (rc == CLI_EXIT_OK && !json) printf("  figure: %s/spectral-star.png\n", dir);
  }
  if (rc == CLI_EXIT_OK && json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "n", (double)n);
    cJSON_AddNumberToObject(o, "courant", c.courant);
    cJSON_AddNumberToObject(o, "dt", r.dt);
    cJSON_AddNumberToObject(o, "steps", (double)r.steps);
    cJSON_AddNumberToObject(o, "t_end", r.t_end);
    cJSON *a = cJSON_AddArrayToObject(o, "modes");
    for (size_t i = 0; i < r.n_modes; ++i) {
      const gm_spectral_star_mode *x = &r.modes[i];
      cJSON *j = cJSON_CreateObject();
      cJSON_AddNumberToObject(j, "m", (double)x->m);
      cJSON_AddItemToObject(j, "rel_error_semi_diagonal", cli_json_number(x->semi_diagonal));
      cJSON_AddItemToObject(j, "rel_error_semi_spectral", cli_json_number(x->semi_spectral));
      cJSON_AddItemToObject(j, "rel_error_leapfrog_diagonal", cli_json_number(x->leapfrog_diagonal));
      cJSON_AddItemToObject(j, "rel_error_leapfrog_spectral", cli_json_number(x->leapfrog_spectral));
      cJSON_AddItemToObject(j, "rel_error_spectral_spatial", cli_json_number(x->spectral_spatial));
      cJSON_AddItemToArray(a, j);
    }
    cJSON_AddItemToObject(o, "max_rel_error_semi_diagonal", cli_json_number(r.max_rel_semi_diagonal));
    cJSON_AddItemToObject(o, "max_rel_error_semi_spectral", cli_json_number(r.max_rel_semi_spectral));
    cJSON_AddNumberToObject(o, "wall_s", r.wall_s);
    rc = cli_json_print(o);
  }
  gm_spectral_star_result_clear(&r);
  return rc;
}

/* ---- the tent-function VI on sine-Gordon (gm_experiment_tent_vi) -------------------------- */

int cli_pde_tent_vi(int argc, char **argv) {
  const char *cmd = "pde tent-vi", *initial = "breather", *out = NULL;
  gm_tent_vi_config c = gm_tent_vi_defaults();
  size_t n_pos = 0;
  int json = 0;
  cli_option options[] = {{"--initial", CLI_ARG_STRING, &initial, 0},
                          {"--n", CLI_ARG_COUNT, &c.n, 0},
                          {"--dt", CLI_ARG_DOUBLE, &c.dt, 0},
                          {"--T", CLI_ARG_DOUBLE, &c.t_end, 0},
                          {"--param", CLI_ARG_DOUBLE, &c.param, 0},
                          {"--out", CLI_ARG_STRING, &out, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0}};
  int rc = cli_parse(cmd, argc, argv, options, 7, NULL, 0, &n_pos);
  if (rc == CLI_HELP) {
    print_help();
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  c.kink = strcmp(initial, "kink") == 0;
  if (!c.kink && strcmp(initial, "breather") != 0) {
    cli_error(cmd, "--initial must be breather or kink (got '%s')", initial);
    return CLI_EXIT_USAGE;
  }
  if (cli_check_positive(cmd, "--dt", c.dt) != CLI_EXIT_OK ||
      cli_check_positive(cmd, "--T", c.t_end) != CLI_EXIT_OK ||
      cli_check_step_count(cmd, c.t_end, c.dt) != CLI_EXIT_OK)
    return CLI_EXIT_USAGE;
  if (!(c.param > 0.0 && c.param < 1.0)) {
    cli_error(cmd, "--param (breather frequency or kink speed) must lie in (0, 1)");
    return CLI_EXIT_USAGE;
  }
  if (c.n < 4 || c.n > 100000000) {
    cli_error(cmd, "--n %zu must lie in [4, 1e8]", c.n);
    return CLI_EXIT_USAGE;
  }
  gm_tent_vi_result r;
  gm_error err = {{0}};
  gm_status st = gm_experiment_tent_vi(&c, out, &r, &err);
  if (st != GM_OK) {
    cli_error(cmd, "%s", err.message);
    return st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  if (json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "initial", initial);
    cJSON_AddNumberToObject(o, "param", c.param);
    cJSON_AddNumberToObject(o, "n", (double)r.n);
    cJSON_AddNumberToObject(o, "dx", r.h);
    cJSON_AddNumberToObject(o, "dt", r.dt);
    cJSON_AddNumberToObject(o, "steps", (double)r.steps);
    cJSON_AddNumberToObject(o, "t", r.t);
    cJSON_AddItemToObject(o, "energy", cli_json_number(r.energy));
    cJSON_AddItemToObject(o, "max_rel_energy_error", cli_json_number(r.max_rel_energy_error));
    cJSON_AddItemToObject(o, "max_abs_error", cli_json_number(r.max_abs_error));
    cJSON_AddNumberToObject(o, "wall_s", r.wall_s);
    if (out != NULL) cJSON_AddStringToObject(o, "csv", out);
    return cli_json_print(o);
  }
  printf("pde tent-vi (seed 001 5.1, sine-Gordon %s %g on [-20, 20)): n %zu, dx %g, dt %g, "
         "t = %g\n", initial, c.param, r.n, r.h, r.dt, r.t);
  printf("  strip energy %.15g (relative change %.3e)\n", r.energy, r.max_rel_energy_error);
  printf("  max |u - exact| %.3e\n", r.max_abs_error);
  if (out != NULL) printf("  state written to %s\n", out);
  return CLI_EXIT_OK;
}
