/* geomint pde run EQUATION: one scheme on sine-Gordon (standing breather), KdV (soliton) or
 * NLS (moving soliton) from its exact solution, with the error against it at T, the final state
 * as CSV and a space-time VTK image (.vti: x along the first axis, t along the second; cell
 * data u, exact and error — ParaView opens it directly). */
#include <cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli/cli.h"

#define RUN_L 20.0

typedef struct run_params {
  double omega; /* sine-Gordon breather frequency */
  double c;     /* KdV soliton speed */
} run_params;

/* ---- exact solutions: s at (x, t), and the scalar shown (u, or |ψ| for NLS) ---------------- */
static void sg_exact(double x, double t, const run_params *q, double *s) {
  double w = q->omega, k = sqrt(1.0 - w * w), sn = sin(w * t), ch = cosh(k * x);
  double r = k / w * sn / ch, den = 1.0 + r * r;
  s[0] = 4.0 * atan(r);
  s[1] = 4.0 / den * k * cos(w * t) / ch;                /* u_t */
  s[2] = -4.0 / den * r * k * tanh(k * x);               /* u_x */
}

static void kdv_exact(double x, double t, const run_params *q, double *s) {
  double c = q->c, xi = 0.5 * sqrt(c) * (x - c * t), u = 3.0 * c / (cosh(xi) * cosh(xi));
  s[0] = 6.0 * sqrt(c) * (tanh(xi) + 1.0);
  s[1] = u;
  s[2] = -u * sqrt(c) * tanh(xi);
  s[3] = 0.5 * c * u;
}

#define NLS_C_RUN (3.14159265358979323846 / 10.0)
static void nls_exact(double x, double t, const run_params *q, double *s) {
  (void)q;
  double xi = x - NLS_C_RUN * t, amp = 1.0 / cosh(xi);
  double th = NLS_C_RUN * x / 2 - (NLS_C_RUN * NLS_C_RUN / 4 - 1.0) * t;
  double dam = -tanh(xi) / cosh(xi);
  s[0] = amp * cos(th);
  s[1] = amp * sin(th);
  s[2] = dam * cos(th) - amp * sin(th) * NLS_C_RUN / 2;
  s[3] = dam * sin(th) + amp * cos(th) * NLS_C_RUN / 2;
}

typedef struct run_equation {
  const char *name, *default_scheme, *shown;
  gm_pde_equation (*make)(void);
  void (*exact)(double x, double t, const run_params *q, double *s);
  double T;
} run_equation;

static const run_equation equations[] = {
    {"sine-gordon", "ms", "u", gm_pde_sine_gordon, sg_exact, 10.0},
    {"kdv", "preissmann", "u", gm_pde_kdv, kdv_exact, 4.0},
    {"nls", "preissmann", "|psi|", gm_pde_nls, nls_exact, 2.0},
};

static double shown(const run_equation *e, const double *s) {
  if (strcmp(e->name, "nls") == 0) return hypot(s[0], s[1]);
  return strcmp(e->name, "kdv") == 0 ? s[1] : s[0];
}

static const char run_usage[] =
    "usage: geomint pde run EQUATION [--scheme NAME] [--n N] [--dt DT] [--T T] [--dirichlet]\n"
    "                       [--omega W] [--c C] [--out FILE.csv] [--vtk FILE.vti] [--frames M]\n"
    "                       [--json] [--no-project]\n"
    "\n"
    "EQUATION, on [-20, 20) periodic from its exact solution at t = 0:\n"
    "  sine-gordon  standing breather, frequency --omega (default 0.5); default scheme ms, T 10\n"
    "  kdv          u_t + u u_x + u_xxx = 0, soliton 3c sech^2(sqrt(c)(x - ct)/2), --c (1);\n"
    "               schemes preissmann (default) or zk; T 4\n"
    "  nls          i psi_t + psi_xx + 2|psi|^2 psi = 0, soliton a = 1, c = pi/10; T 2\n"
    "--n points (default 200), --dt (default 0.1). --dirichlet (sine-gordon): the ends held,\n"
    "the points spanning [-20, 20]. Prints energy, momentum and the max error at T; --out\n"
    "writes x (for gauss-prk its Gauss points), the state and the exact value at T as CSV;\n"
    "--vtk writes a space-time VTK image (cell data u, exact, error; x along the first axis,\n"
    "t along the second, M + 1 rows; gauss-prk's points drawn as uniform cells).\n"
    "gauss-prk: the sampled initial data are projected onto the scheme's physical branch\n"
    "(gm_pde_gauss_project, periodic untwisted data only); --no-project keeps them as sampled.\n";

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int cli_pde_run(int argc, char **argv) {
  const char *scheme_name = NULL, *out = NULL, *vtk = NULL, *positional[1] = {NULL};
  size_t n = 200, frames = 100, n_pos = 0;
  double dt = 0.1, T = 0.0;
  int dirichlet = 0, json = 0, no_project = 0;
  run_params q = {0.5, 1.0};
  cli_option options[] = {{"--scheme", CLI_ARG_STRING, &scheme_name, 0},
                          {"--n", CLI_ARG_COUNT, &n, 0},
                          {"--dt", CLI_ARG_DOUBLE, &dt, 0},
                          {"--T", CLI_ARG_DOUBLE, &T, 0},
                          {"--omega", CLI_ARG_DOUBLE, &q.omega, 0},
                          {"--c", CLI_ARG_DOUBLE, &q.c, 0},
                          {"--out", CLI_ARG_STRING, &out, 0},
                          {"--vtk", CLI_ARG_STRING, &vtk, 0},
                          {"--frames", CLI_ARG_COUNT, &frames, 0},
                          {"--dirichlet", CLI_ARG_FLAG, &dirichlet, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0},
                          {"--no-project", CLI_ARG_FLAG, &no_project, 0}};
  int rc = cli_parse("pde run", argc, argv, options, sizeof options / sizeof options[0],
                     positional, 1, &n_pos);
  if (rc == CLI_HELP) {
    fputs(run_usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  const run_equation *e = NULL;
  for (size_t k = 0; n_pos == 1 && k < sizeof equations / sizeof equations[0]; k++)
    if (strcmp(positional[0], equations[k].name) == 0) e = &equations[k];
  if (e == NULL) {
    cli_error("pde run", "which equation? sine-gordon, kdv or nls");
    return CLI_EXIT_USAGE;
  }
  if (!options[3].seen) T = e->T; /* --T 0 is refused below, not taken as the default */
  /* an option the equation does not use is an error, not ignored */
  if (options[4].seen && strcmp(e->name, "sine-gordon") != 0) {
    cli_error("pde run", "--omega is an option of sine-gordon (the breather), not of %s", e->name);
    return CLI_EXIT_USAGE;
  }
  if (options[5].seen && strcmp(e->name, "kdv") != 0) {
    cli_error("pde run", "--c is an option of kdv (the soliton's speed), not of %s", e->name);
    return CLI_EXIT_USAGE;
  }
  if (options[8].seen && vtk == NULL) {
    cli_error("pde run", "--frames sets the rows of --vtk; give --vtk FILE.vti");
    return CLI_EXIT_USAGE;
  }
  if (scheme_name == NULL) scheme_name = e->default_scheme;
  if (cli_check_positive("pde run", "--dt", dt) != CLI_EXIT_OK ||
      cli_check_positive("pde run", "--T", T) != CLI_EXIT_OK ||
      cli_check_step_count("pde run", T, dt) != CLI_EXIT_OK)
    return CLI_EXIT_USAGE;
  if (!(q.omega > 0.0 && q.omega < 1.0)) {
    cli_error("pde run", "--omega must lie in (0, 1) (got %g)", q.omega);
    return CLI_EXIT_USAGE;
  }
  if (!(q.c > 0.0 && q.c <= 10.0)) {
    cli_error("pde run", "--c must lie in (0, 10] (got %g)", q.c);
    return CLI_EXIT_USAGE;
  }
  if (n > 100000000 || n < 4) {
    cli_error("pde run", "--n must lie in 4..1e8 (got %zu)", n);
    return CLI_EXIT_USAGE;
  }
  if (frames == 0 || frames > 100000) {
    cli_error("pde run", "--frames must lie in 1..100000 (got %zu)", frames);
    return CLI_EXIT_USAGE;
  }
  if (dirichlet && strcmp(e->name, "sine-gordon") != 0) {
    cli_error("pde run", "--dirichlet is offered for sine-gordon only");
    return CLI_EXIT_USAGE;
  }
  const gm_pde_scheme *scheme = NULL;
  if (gm_pde_scheme_find(scheme_name, &scheme) != GM_OK) {
    cli_error("pde run", "unknown scheme '%s' (see docs/pde.md)", scheme_name);
    return CLI_EXIT_USAGE;
  }
  gm_pde_equation eq = e->make();
  size_t d = eq.dim;
  double h = 2.0 * RUN_L / (double)(dirichlet ? n - 1 : n);
  gm_pde_grid g = {n, h, -RUN_L, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = dt;
  if (dirichlet) {
    o.dirichlet_left = scheme->kind == GM_PDE_PREISSMANN ? 3u : 1u;
    o.dirichlet_right = 1u;
  }
  double *s0 = calloc(n * d, sizeof *s0), *rows = NULL;
  if (s0 == NULL) {
    cli_error("pde run", "out of memory");
    return CLI_EXIT_FAILURE;
  }
  for (size_t i = 0; i < n; i++) e->exact(gm_pde_point_x(scheme, &g, i), 0.0, &q, s0 + i * d);
  if (eq.has_gauge) { /* φ by the trapezoidal rule, its twist the discrete mass */
    double tw = 0.0;
    for (size_t i = 0; i < n; i++) {
      double m = 0.5 * h * (s0[i * d + eq.gauge_u] + s0[((i + 1) % n) * d + eq.gauge_u]);
      if (i + 1 < n) s0[(i + 1) * d + eq.gauge_phi] = s0[i * d + eq.gauge_phi] + m;
      tw += m;
    }
    g.twist[eq.gauge_phi] = tw;
  }
  gm_error err = {{0}};
  /* gauss-prk: point-sampled data carry O(H³) on the scheme's spurious spatial branch; move
   * them onto the physical one (gm_pde_gauss_project, docs/pde.md) unless asked not to. The
   * projection is a DFT over cells, so it needs untwisted (periodic) components. */
  int twisted = 0, projected = 0;
  for (size_t a = 0; a < d; a++) twisted |= g.twist[a] != 0.0;
  if (scheme->kind == GM_PDE_GAUSS_PRK && !no_project && !twisted && !dirichlet) {
    gm_status ps = gm_pde_gauss_project(&g, d, s0, &err);
    if (ps != GM_OK) { /* bad input (odd n, non-finite data) as gm_pde_create would say it */
      cli_error("pde run", "%s", err.message);
      free(s0);
      return ps == GM_ENOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
    }
    projected = 1;
  }
  gm_pde *p = NULL;
  gm_status st = gm_pde_create(&g, &eq, scheme, &o, s0, &p, &err);
  free(s0);
  if (st != GM_OK) {
    cli_error("pde run", "%s", err.message);
    return st == GM_ENOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
  }
  size_t steps = (size_t)llround(T / dt), every = steps / frames > 0 ? steps / frames : 1;
  size_t n_rows = steps / every + 1;
  if (vtk != NULL && (rows = calloc(n_rows * n * 3, sizeof *rows)) == NULL) {
    cli_error("pde run", "out of memory (%zu frames of %zu points)", n_rows, n);
    gm_pde_free(p);
    return CLI_EXIT_FAILURE;
  }
  double e0 = gm_pde_energy(p), m0 = gm_pde_momentum(p), ex[GM_PDE_MAX_DIM];
  size_t row = 0, done = 0;
  rc = CLI_EXIT_OK;
  const double wall0 = now();
  for (;;) {
    if (rows != NULL && row < n_rows) {
      const double *s = gm_pde_state(p);
      for (size_t i = 0; i < n; i++) {
        e->exact(gm_pde_point_x(scheme, &g, i), gm_pde_time(p), &q, ex);
        double *r = rows + 3 * n * row;
        r[i] = shown(e, s + i * d);
        r[n + i] = shown(e, ex);
        r[2 * n + i] = r[i] - r[n + i];
      }
      row++;
    }
    if (done == steps) break;
    size_t m = steps - done < every ? steps - done : every;
    if (gm_pde_advance(p, m, &err) != GM_OK) {
      cli_error("pde run", "%s", err.message);
      rc = CLI_EXIT_FAILURE;
      break;
    }
    done += m;
  }
  const double wall_s = now() - wall0;
  const double *s = gm_pde_state(p);
  double t = gm_pde_time(p), emax = 0.0;
  for (size_t i = 0; rc == CLI_EXIT_OK && i < n; i++) {
    e->exact(gm_pde_point_x(scheme, &g, i), t, &q, ex);
    emax = fmax(emax, strcmp(e->name, "nls") == 0
                          ? hypot(s[i * d] - ex[0], s[i * d + 1] - ex[1])
                          : fabs(shown(e, s + i * d) - shown(e, ex)));
  }
  cJSON *j = NULL;
  if (rc == CLI_EXIT_OK && json) {
    j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "equation", e->name);
    cJSON_AddStringToObject(j, "scheme", scheme->name);
    cJSON_AddNumberToObject(j, "n", (double)n);
    cJSON_AddNumberToObject(j, "dx", h);
    cJSON_AddNumberToObject(j, "dt", dt);
    cJSON_AddNumberToObject(j, "steps", (double)steps);
    cJSON_AddNumberToObject(j, "t_final", t);
    cJSON_AddBoolToObject(j, "dirichlet", dirichlet);
    cJSON_AddBoolToObject(j, "projected", projected);
    if (isfinite(e0)) {
      cJSON_AddItemToObject(j, "energy", cli_json_number(gm_pde_energy(p)));
      cJSON_AddItemToObject(j, "rel_energy_change",
                            cli_json_number(fabs(gm_pde_energy(p) - e0) / fabs(e0)));
      cJSON_AddItemToObject(j, "momentum", cli_json_number(gm_pde_momentum(p)));
      cJSON_AddItemToObject(j, "momentum_change", cli_json_number(gm_pde_momentum(p) - m0));
    }
    if (eq.has_gauge) cJSON_AddItemToObject(j, "mass", cli_json_number(gm_pde_mass(p)));
    if (eq.has_norm) cJSON_AddItemToObject(j, "charge", cli_json_number(gm_pde_norm(p)));
    cJSON_AddItemToObject(j, "max_abs_error", cli_json_number(emax));
    cJSON_AddNumberToObject(j, "wall_s", wall_s);
  }
  if (rc == CLI_EXIT_OK && !json) {
    printf("pde run %s --scheme %s: n %zu, dx %g, dt %g, %zu steps to t = %g%s%s\n", e->name,
           scheme->name, n, h, dt, steps, t, dirichlet ? ", Dirichlet ends" : "",
           projected ? ", initial data projected (gm_pde_gauss_project)" : "");
    if (isfinite(e0)) {
      printf("  energy %.15g (relative change %.3e)\n", gm_pde_energy(p),
             fabs(gm_pde_energy(p) - e0) / fabs(e0));
      printf("  momentum %.6e (change %.3e)\n", gm_pde_momentum(p), gm_pde_momentum(p) - m0);
    } else {
      printf("  energy and momentum: no monitor for %s\n", scheme->name);
    }
    if (eq.has_gauge) printf("  mass %.15g\n", gm_pde_mass(p));
    if (eq.has_norm) printf("  charge %.15g\n", gm_pde_norm(p));
    printf("  max |%s - exact| %.3e\n", strcmp(e->name, "nls") == 0 ? "psi" : "u", emax);
  }
  if (rc == CLI_EXIT_OK && out != NULL) {
    FILE *f = fopen(out, "w");
    if (f == NULL) {
      cli_error("pde run", "cannot write '%s': %s", out, strerror(errno));
      rc = CLI_EXIT_FAILURE;
    } else {
      static const char *const cols[3][4] = {
          {"u", "v", "w", ""}, {"phi", "u", "v", "w"}, {"p", "q", "v", "w"}};
      size_t which = (size_t)(e - equations);
      fprintf(f, "x");
      for (size_t a = 0; a < d; a++) fprintf(f, ",%s", cols[which][a]);
      fprintf(f, ",exact\n");
      for (size_t i = 0; i < n; i++) {
        double x = gm_pde_point_x(scheme, &g, i);
        e->exact(x, t, &q, ex);
        fprintf(f, "%.10g", x);
        for (size_t a = 0; a < d; a++) fprintf(f, ",%.17g", s[i * d + a]);
        fprintf(f, ",%.17g\n", shown(e, ex));
      }
      if (fclose(f) != 0) {
        cli_error("pde run", "cannot write '%s': %s", out, strerror(errno));
        rc = CLI_EXIT_FAILURE;
      } else if (j != NULL) {
        cJSON_AddStringToObject(j, "csv", out);
      } else {
        printf("  state written to %s\n", out);
      }
    }
  }
  if (rc == CLI_EXIT_OK && vtk != NULL) {
    gm_image img = {2, {n, row, 1}, {-RUN_L - 0.5 * h, -0.5 * (double)every * dt, 0.0},
                    {h, (double)every * dt, 1.0}};
    gm_image_array arrays[3] = {
        {"u", GM_IMAGE_CELL, 1, {rows, NULL, NULL}},
        {"exact", GM_IMAGE_CELL, 1, {rows + n, NULL, NULL}},
        {"error", GM_IMAGE_CELL, 1, {rows + 2 * n, NULL, NULL}}};
    /* the image wants each array contiguous over (x, t): repack the rows */
    double *packed = calloc(3 * n * row, sizeof *packed);
    if (packed == NULL) {
      cli_error("pde run", "out of memory");
      rc = CLI_EXIT_FAILURE;
    } else {
      for (size_t k = 0; k < 3; k++)
        for (size_t r = 0; r < row; r++)
          memcpy(packed + k * n * row + r * n, rows + 3 * n * r + k * n, n * sizeof *packed);
      for (size_t k = 0; k < 3; k++) arrays[k].component[0] = packed + k * n * row;
      if (gm_vti_write(vtk, &img, arrays, 3, t, GM_VTI_BASE64, &err) != GM_OK) {
        cli_error("pde run", "%s", err.message);
        rc = CLI_EXIT_FAILURE;
      } else if (j != NULL) {
        cJSON_AddStringToObject(j, "vtk", vtk);
      } else {
        printf("  space-time image (%zu x %zu cells, %s) written to %s\n", n, row, e->shown, vtk);
      }
      free(packed);
    }
  }
  if (j != NULL) {
    if (rc == CLI_EXIT_OK) rc = cli_json_print(j);
    else cJSON_Delete(j);
  }
  free(rows);
  gm_pde_free(p);
  return rc;
}
