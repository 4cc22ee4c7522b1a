/* geomint pde schrodinger | spectral-star | tent-vi: the pseudospectral Schrödinger VI against
 * Strang split-step Fourier (eigenvalues; a coherent state at equal cost), the spectral Hodge
 * star's dispersion against the diagonal star's (each writes .dat files and one gnuplot
 * figure), and the tent-function VI of seed 001 §5.1 on sine-Gordon. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "cli/pde_spectral.h"

#define PI_ 3.14159265358979323846
#define HO_BOX 20.0 /* harmonic: [−10, 10) */
#define PT_BOX 40.0 /* Pöschl–Teller λ = 2: [−20, 20) */

const char cli_pde_spectral_usage[] =
    "       geomint pde schrodinger eigen [--out DIR] [--no-plot]\n"
    "       geomint pde schrodinger compare [--n N] [--dt DT] [--T T] [--out DIR] [--no-plot]\n"
    "       geomint pde spectral-star [--n N] [--courant C] [--out DIR] [--no-plot]\n"
    "       geomint pde tent-vi [--initial breather|kink] [--param P] [--n N] [--dt DT] [--T T]\n"
    "                           [--out FILE.csv]\n"
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

/* ---- potentials and states ---------------------------------------------------------------- */

static double potential(int pt, double x) { return pt ? -3.0 / (cosh(x) * cosh(x)) : 0.5 * x * x; }

/* harmonic φ_k (Hermite functions) or Pöschl–Teller φ0 = √(3/4) sech²x, φ1 = √(3/2) tanh sech */
static double eigenstate(int pt, int k, double x) {
  if (pt) return k == 0 ? sqrt(0.75) / (cosh(x) * cosh(x)) : sqrt(1.5) * tanh(x) / cosh(x);
  double h0 = 1.0, h1 = 2.0 * x, hk = k == 0 ? h0 : h1, f = 1.0;
  for (int j = 2; j <= k; j++) {
    hk = 2.0 * x * h1 - 2.0 * (j - 1) * h0;
    h0 = h1;
    h1 = hk;
  }
  for (int j = 1; j <= k; j++) f *= 2.0 * j;
  return hk / sqrt(f) * pow(PI_, -0.25) * exp(-0.5 * x * x);
}

static int eigenvalue(const char *cmd, int pt, int k, size_t n, double box,
                      gm_schrodinger_scheme sc, double dt, double T, double *E, double *omega) {
  double *V = malloc(n * sizeof *V), *phi = calloc(2 * n, sizeof *phi);
  if (V == NULL || phi == NULL) {
    free(V);
    free(phi);
    cli_error(cmd, "out of memory");
    return CLI_EXIT_FAILURE;
  }
  for (size_t j = 0; j < n; j++) {
    double x = -0.5 * box + (double)j * box / (double)n;
    V[j] = potential(pt, x);
    phi[2 * j] = eigenstate(pt, k, x);
  }
  gm_schrodinger_options o = gm_schrodinger_options_defaults();
  o.scheme = sc;
  o.dt = dt;
  gm_error err = {{0}};
  gm_status st = gm_schrodinger_eigenvalue(n, -0.5 * box, box, V, phi, &o, T, E, omega, &err);
  free(V);
  free(phi);
  if (st != GM_OK) {
    cli_error(cmd, "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  return CLI_EXIT_OK;
}

static int sch_eigen(const char *dir, int no_plot) {
  const char *cmd = "pde schrodinger eigen";
  int rc = cli_prepare_plot_dir(cmd, dir, no_plot);
  if (rc != CLI_EXIT_OK) return rc;
  FILE *f = open_out(cmd, dir, "schrodinger-eigen-n.dat");
  if (f == NULL) return CLI_EXIT_FAILURE;
  printf("Eigenvalues by evolution (VI; the phase of <phi, psi(t)> fitted, the scheme's\n"
         "dispersion relation inverted), against N:\n");
  printf("  %-6s %-12s %-12s %-6s %-12s %-12s\n", "N", "harm. E1", "harm. E3", "N", "P-T E0",
         "P-T E1 (box 60)");
  fprintf(f, "# N_harmonic err_E1 err_E3 N_pt err_E0 err_E1(box 60, 1.5 N)\n");
  static const size_t nh[] = {16, 24, 32, 40, 48, 56, 64};
  static const size_t np[] = {32, 64, 96, 128, 160, 192, 224};
  for (int i = 0; i < 7; i++) {
    double e[4], E, om;
    if ((rc = eigenvalue(cmd, 0, 1, nh[i], HO_BOX, GM_SCHRODINGER_VI, 0.01, 10.0, &E, &om)))
      goto fail;
    e[0] = fabs(E - 1.5);
    if ((rc = eigenvalue(cmd, 0, 3, nh[i], HO_BOX, GM_SCHRODINGER_VI, 0.01, 10.0, &E, &om)))
      goto fail;
    e[1] = fabs(E - 3.5);
    if ((rc = eigenvalue(cmd, 1, 0, np[i], PT_BOX, GM_SCHRODINGER_VI, 0.005, 10.0, &E, &om)))
      goto fail;
    e[2] = fabs(E + 2.0);
    if ((rc = eigenvalue(cmd, 1, 1, np[i] * 3 / 2, 1.5 * PT_BOX, GM_SCHRODINGER_VI, 0.005, 10.0,
                         &E, &om)))
      goto fail;
    e[3] = fabs(E + 0.5);
    printf("  %-6zu %-12.3e %-12.3e %-6zu %-12.3e %-12.3e\n", nh[i], e[0], e[1], np[i], e[2],
           e[3]);
    fprintf(f, "%zu %.6e %.6e %zu %.6e %.6e\n", nh[i], e[0], e[1], np[i], e[2], e[3]);
  }
  fclose(f);
  f = open_out(cmd, dir, "schrodinger-eigen-dt.dat");
  if (f == NULL) return CLI_EXIT_FAILURE;
  printf("Frequency error |Omega - E| of harmonic phi_3 (E = 3.5), N = 64, T = 8, against dt\n"
         "(no inversion: the time error itself):\n  %-8s %-12s %-12s\n", "dt", "VI",
         "split-step");
  fprintf(f, "# dt err_vi err_split_step\n");
  double prev_vi = 0.0, prev_ss = 0.0;
  for (double dt = 0.016; dt > 0.0019; dt /= 2.0) {
    double E, om_vi, om_ss;
    if ((rc = eigenvalue(cmd, 0, 3, 64, HO_BOX, GM_SCHRODINGER_VI, dt, 8.0, &E, &om_vi))) goto fail;
    if ((rc = eigenvalue(cmd, 0, 3, 64, HO_BOX, GM_SCHRODINGER_SPLIT_STEP, dt, 8.0, &E, &om_ss)))
      goto fail;
    double a = fabs(om_vi - 3.5), b = fabs(om_ss - 3.5);
    printf("  %-8g %-12.3e %-12.3e", dt, a, b);
    if (prev_vi > 0.0) printf("  orders %.2f, %.2f", log2(prev_vi / a), log2(prev_ss / b));
    printf("\n");
    prev_vi = a;
    prev_ss = b;
    fprintf(f, "%g %.6e %.6e\n", dt, a, b);
  }
  fclose(f);
  if (no_plot) return CLI_EXIT_OK;
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
  if (rc == CLI_EXIT_OK) printf("  figure: %s/schrodinger-eigen.png\n", dir);
  return rc;
fail:
  fclose(f);
  return rc;
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

static int sch_compare(size_t n, double dt, double T, const char *dir, int no_plot) {
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
  printf("Coherent state a = 2 of V = x^2/2 on [-10, 10), N = %zu, dt = %g, T = %g\n", n, dt, T);
  printf("  the VI takes %.2f FFTs a step (%.2f inner iterations); split-step 2: equal cost is\n"
         "  split-step at dt/%zu\n",
         per_step, (per_step - 2.0) / 2.0, ratio);
  printf("  %-10s %-12s %-14s %-18s %-12s\n", "t", "VI", "split (dt)", "split (dt/r, equal)",
         "VI charge");
  fprintf(f, "# t err_vi err_split_dt err_split_equal_cost vi_charge_drift vi_norm_drift\n");
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
      if (print) printf("  %-10.4g %-12.3e %-14.3e %-18.3e %-12.2e\n", t, a, b, c, dq);
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
    if (rc == CLI_EXIT_OK) printf("  figure: %s/schrodinger-compare.png\n", dir);
  }
done:
  gm_schrodinger_free(vi);
  gm_schrodinger_free(ss);
  gm_schrodinger_free(se);
  return rc;
}

int cli_pde_schrodinger(int argc, char **argv) {
  const char *dir = "pde-output", *positional[1] = {NULL};
  int no_plot = 0;
  size_t n = 64, n_pos = 0;
  double dt = 0.01, T = 100.0;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &dir, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0},
                          {"--n", CLI_ARG_COUNT, &n, 0},
                          {"--dt", CLI_ARG_DOUBLE, &dt, 0},
                          {"--T", CLI_ARG_DOUBLE, &T, 0}};
  int rc = cli_parse("pde schrodinger", argc, argv, options, 5, positional, 1, &n_pos);
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
    return sch_eigen(dir, no_plot);
  }
  if (n_pos == 1 && strcmp(positional[0], "compare") == 0)
    return sch_compare(n, dt, T, dir, no_plot);
  cli_error("pde schrodinger", "which experiment? eigen or compare");
  return CLI_EXIT_USAGE;
}

/* ---- spectral Hodge star ------------------------------------------------------------------- */

/* leapfrog run of mode m from its discrete forward mode; the frequency from the phase, followed
 * by an observer every step */
typedef struct mode_phase {
  size_t n;
  long m;
  double phase, pc, ps;
} mode_phase;

static int follow_mode(gm_wave1d *w, void *ctx) {
  mode_phase *p = ctx;
  const double *u = gm_wave1d_u(w);
  double c = 0.0, s = 0.0;
  for (size_t j = 0; j < p->n; j++) {
    double x = 2.0 * PI_ * (double)j / (double)p->n;
    c += u[j] * cos((double)p->m * x);
    s += u[j] * sin((double)p->m * x);
  }
  p->phase += atan2(s * p->pc - c * p->ps, c * p->pc + s * p->ps);
  p->pc = c;
  p->ps = s;
  return 0;
}

static double run_mode(gm_wave1d *w, size_t n, long m, size_t steps, double dt) {
  mode_phase p = {n, m, 0.0, 1.0, 0.0};
  gm_error err = {{0}};
  if (gm_wave1d_add_observer(w, 1, follow_mode, &p, &err) != GM_OK ||
      gm_wave1d_advance(w, steps, &err) != GM_OK)
    return NAN;
  return p.phase / ((double)steps * dt);
}

int cli_pde_spectral_star(int argc, char **argv) {
  const char *cmd = "pde spectral-star", *dir = "pde-output";
  int no_plot = 0;
  size_t n = 64, n_pos = 0;
  double courant = 0.1;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &dir, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0},
                          {"--n", CLI_ARG_COUNT, &n, 0},
                          {"--courant", CLI_ARG_DOUBLE, &courant, 0}};
  int rc = cli_parse(cmd, argc, argv, options, 4, NULL, 0, &n_pos);
  if (rc == CLI_HELP) {
    print_help();
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  if (n < 4 || n % 2 != 0 || n > 4096) {
    cli_error(cmd, "--n %zu must be even, >= 4 and <= 4096", n);
    return CLI_EXIT_USAGE;
  }
  if (!(courant > 0.0 && courant <= 2.0 / PI_)) {
    cli_error(cmd, "--courant %g must lie in (0, 2/pi] (leapfrog with the spectral star)",
              courant);
    return CLI_EXIT_USAGE;
  }
  if ((rc = cli_prepare_plot_dir(cmd, dir, no_plot)) != CLI_EXIT_OK) return rc;
  FILE *f = open_out(cmd, dir, "spectral-star.dat");
  if (f == NULL) return CLI_EXIT_FAILURE;
  double L = 2.0 * PI_, h = L / (double)n, dt = courant * h;
  size_t steps = (size_t)ceil(10.0 / dt);
  fprintf(f, "# m/N rel_err_semi_diag rel_err_semi_spectral rel_err_leapfrog_diag "
             "rel_err_leapfrog_spectral spatial_part_spectral (omega_measured - leapfrog(exact "
             "k))/k\n");
  printf("u_tt = *d*d u on [0, 2 pi), N = %zu, leapfrog dt = %g h, T = %g: relative frequency "
         "error\n  %-5s %-12s %-12s %-14s %-14s %-12s\n",
         n, courant, (double)steps * dt, "m", "diag (semi)", "spec (semi)", "diag+leapfrog",
         "spec+leapfrog", "spec spatial");
  double *u = malloc(n * sizeof *u), *v = malloc(n * sizeof *v);
  if (u == NULL || v == NULL) {
    free(u);
    free(v);
    fclose(f);
    cli_error(cmd, "out of memory");
    return CLI_EXIT_FAILURE;
  }
  for (long m = 1; m < (long)n / 2; m++) {
    double k = (double)m, res[2], sem[2];
    for (int kind = 0; kind < 2; kind++) {
      double sym = gm_wave1d_symbol((gm_hodge_kind)kind, n, L, m);
      double om_pred = 2.0 / dt * asin(0.5 * dt * sqrt(-sym));
      for (size_t j = 0; j < n; j++) {
        u[j] = cos(k * (double)j * h);
        v[j] = sin(om_pred * dt) / dt * sin(k * (double)j * h);
      }
      gm_wave1d *w = NULL;
      gm_error err = {{0}};
      if (gm_wave1d_create(n, L, (gm_hodge_kind)kind, dt, u, v, &w, &err) != GM_OK) {
        cli_error(cmd, "%s", err.message);
        free(u);
        free(v);
        fclose(f);
        return CLI_EXIT_FAILURE;
      }
      /* semi-discrete: the Rayleigh quotient of ⋆d⋆d on the sampled mode */
      gm_wave1d_laplacian(w, u, v);
      double num = 0.0, den = 0.0;
      for (size_t j = 0; j < n; j++) {
        num += u[j] * v[j];
        den += u[j] * u[j];
      }
      sem[kind] = fabs(sqrt(-num / den) - k) / k;
      res[kind] = run_mode(w, n, m, steps, dt);
      gm_wave1d_free(w);
    }
    double om_leap = 2.0 / dt * asin(0.5 * dt * k);
    double ld = fabs(res[0] - k) / k, ls = fabs(res[1] - k) / k;
    double sp = fabs(res[1] - om_leap) / k;
    fprintf(f, "%.6f %.6e %.6e %.6e %.6e %.6e\n", k / (double)n, sem[0], sem[1], ld, ls, sp);
    if (m % (long)(n / 16 > 0 ? n / 16 : 1) == 0 || m == 1)
      printf("  %-5ld %-12.3e %-12.3e %-14.3e %-14.3e %-12.3e\n", m, sem[0], sem[1], ld, ls, sp);
  }
  free(u);
  free(v);
  fclose(f);
  if (no_plot) return CLI_EXIT_OK;
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
           n, courant);
  rc = run_gnuplot(cmd, dir, "spectral-star.gp", body);
  if (rc == CLI_EXIT_OK) printf("  figure: %s/spectral-star.png\n", dir);
  return rc;
}

/* ---- the tent-function VI on sine-Gordon ---------------------------------------------------- */

static double sg_V(double u, const void *c) {
  (void)c;
  return -cos(u);
}
static double sg_dV(double u, const void *c) {
  (void)c;
  return sin(u);
}
static double sg_d2V(double u, const void *c) {
  (void)c;
  return cos(u);
}

/* breather u = 4 atan((k/ω) sin ωt / cosh kx) or kink u = 4 atan(exp(γ(x − ct))) */
static double sg_exact(int kink, double p, double x, double t) {
  if (kink) return 4.0 * atan(exp((x - p * t) / sqrt(1.0 - p * p)));
  double k = sqrt(1.0 - p * p);
  return 4.0 * atan(k / p * sin(p * t) / cosh(k * x));
}

int cli_pde_tent_vi(int argc, char **argv) {
  const char *cmd = "pde tent-vi", *initial = "breather", *out = NULL;
  size_t n = 200, n_pos = 0;
  double dt = 0.1, T = 10.0, param = 0.5;
  cli_option options[] = {{"--initial", CLI_ARG_STRING, &initial, 0},
                          {"--n", CLI_ARG_COUNT, &n, 0},
                          {"--dt", CLI_ARG_DOUBLE, &dt, 0},
                          {"--T", CLI_ARG_DOUBLE, &T, 0},
                          {"--param", CLI_ARG_DOUBLE, &param, 0},
                          {"--out", CLI_ARG_STRING, &out, 0}};
  int rc = cli_parse(cmd, argc, argv, options, 6, NULL, 0, &n_pos);
  if (rc == CLI_HELP) {
    print_help();
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  int kink = strcmp(initial, "kink") == 0;
  if (!kink && strcmp(initial, "breather") != 0) {
    cli_error(cmd, "--initial must be breather or kink (got '%s')", initial);
    return CLI_EXIT_USAGE;
  }
  if (cli_check_positive(cmd, "--dt", dt) != CLI_EXIT_OK ||
      cli_check_positive(cmd, "--T", T) != CLI_EXIT_OK ||
      cli_check_step_count(cmd, T, dt) != CLI_EXIT_OK)
    return CLI_EXIT_USAGE;
  if (!(param > 0.0 && param < 1.0)) {
    cli_error(cmd, "--param (breather frequency or kink speed) must lie in (0, 1)");
    return CLI_EXIT_USAGE;
  }
  if (n < 4 || n > 100000000) {
    cli_error(cmd, "--n %zu must lie in [4, 1e8]", n);
    return CLI_EXIT_USAGE;
  }
  double L = 20.0, h = 2.0 * L / (double)n;
  double *u0 = malloc(n * sizeof *u0), *u1 = malloc(n * sizeof *u1);
  if (u0 == NULL || u1 == NULL) {
    free(u0);
    free(u1);
    cli_error(cmd, "out of memory");
    return CLI_EXIT_FAILURE;
  }
  for (size_t i = 0; i < n; i++) {
    u0[i] = sg_exact(kink, param, -L + (double)i * h, 0.0);
    u1[i] = sg_exact(kink, param, -L + (double)i * h, dt);
  }
  gm_tentvi *m = NULL;
  gm_error err = {{0}};
  gm_status st = gm_tentvi_create(n, -L, h, kink ? 2.0 * PI_ : 0.0, dt, sg_V, sg_dV, sg_d2V,
                                  NULL, u0, u1, &m, &err);
  free(u0);
  free(u1);
  if (st != GM_OK) {
    cli_error(cmd, "%s", err.message);
    return st == GM_ENOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
  }
  double e0 = gm_tentvi_energy(m);
  size_t steps = (size_t)llround(T / dt);
  if (steps > 1 && gm_tentvi_advance(m, steps - 1, &err) != GM_OK) {
    cli_error(cmd, "%s", err.message);
    gm_tentvi_free(m);
    return CLI_EXIT_FAILURE;
  }
  const double *u = gm_tentvi_u(m);
  double t = gm_tentvi_time(m), e = 0.0;
  for (size_t i = 0; i < n; i++)
    e = fmax(e, fabs(u[i] - sg_exact(kink, param, -L + (double)i * h, t)));
  printf("pde tent-vi (seed 001 5.1, sine-Gordon %s %g on [-20, 20)): n %zu, dx %g, dt %g, "
         "t = %g\n", initial, param, n, h, dt, t);
  printf("  strip energy %.15g (relative change %.3e)\n", gm_tentvi_energy(m),
         fabs(gm_tentvi_energy(m) - e0) / fabs(e0));
  printf("  max |u - exact| %.3e\n", e);
  if (out != NULL) {
    FILE *f = fopen(out, "w");
    if (f == NULL) {
      cli_error(cmd, "cannot write '%s': %s", out, strerror(errno));
      gm_tentvi_free(m);
      return CLI_EXIT_FAILURE;
    }
    fprintf(f, "x,u,exact\n");
    for (size_t i = 0; i < n; i++) {
      double x = -L + (double)i * h;
      fprintf(f, "%.10g,%.17g,%.17g\n", x, u[i], sg_exact(kink, param, x, t));
    }
    fclose(f);
    printf("  state written to %s\n", out);
  }
  gm_tentvi_free(m);
  return CLI_EXIT_OK;
}
