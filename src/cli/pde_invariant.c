/* geomint pde invariant galilean|shock|orders: seed 004's experiments on invariant schemes
 * (B12, B13; the library runs them, gm_inv_b12_run / gm_inv_b13_run) and the measured orders
 * of consistency. Writes CSV and draws PNG figures with gnuplot. */
#include <cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"

const char cli_pde_invariant_usage[] =
    "       geomint pde invariant galilean|shock|orders [--out DIR] [--json] [--no-plot]\n"
    "\n"
    "invariant: Burgers u_t + u u_x = nu u_xx, FTCS / Lax-Wendroff / Crank-Nicolson in standard\n"
    "     form and invariantized under G0 (translations, projection, Galilean boost) by a moving\n"
    "     frame (docs/pde.md).\n"
    "     galilean (B12): front u in [-1/2, 1/2] on [-2, 2] x [0, 1], nu = 5e-3, h = 2e-2,\n"
    "       k = h/2; mesh and data boosted by lambda = 0, 0.25, 0.5, 1, mapped back at t = 1.\n"
    "       Writes DIR/b12.csv and DIR/b12.png.\n"
    "     shock (B13): projection-invariant viscous shock, nu = 1e-2, k = h = 5e-2, t = 2:\n"
    "       standard against invariant FTCS. Writes DIR/b13.csv and DIR/b13.png.\n"
    "     orders: measured order of consistency of each scheme, both forms.\n";

static FILE *open_out(const char *cmd, const char *dir, const char *name, char *path, size_t cap) {
  snprintf(path, cap, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  if (f == NULL) cli_error(cmd, "cannot write '%s': %s", path, strerror(errno));
  return f;
}

/* A larger canvas than the preamble's: the same terminal, resized (the output stays open). */
static const char resize_1500[] =
    "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
    "  set terminal pngcairo size 1500,900 enhanced font 'sans,10'\n"
    "} else {\n  set terminal png size 1500,900\n}\n";

/* ---- B12 ------------------------------------------------------------------------------------ */
typedef struct b12_plot {
  const char *csv;
} b12_plot;

static void b12_body(FILE *g, const void *ctx) {
  const b12_plot *p = ctx;
  const char *names[3] = {"FTCS", "Lax-Wendroff", "Crank-Nicolson"};
  fputs(resize_1500, g);
  fputs("set datafile separator ','\nset xrange [-0.5:1.5]\nset yrange [-1.5:1.5]\n"
        "set xlabel 'x'\nset ylabel 'u (mapped back)'\nset key bottom left\n", g);
  fputs("set multiplot layout 2,3 title 'B12: Galilean consistency, t = 1 (nu = 5e-3, "
        "h = 2e-2, k = 1e-2), mesh and data boosted by lambda'\n", g);
  for (int form = 0; form < 2; form++)
    for (int s = 0; s < 3; s++) {
      fprintf(g, "set title '%s, %s'\nplot '%s' u 1:2 w l lw 3 lc rgb 'gray' t 'exact'", names[s],
              form ? "invariant" : "standard", p->csv);
      for (int l = 0; l < GM_INV_B12_N_LAMBDA; l++)
        fprintf(g, ", '' u 1:%d w lp pt 7 ps 0.4 t 'lambda = %g'",
                3 + (2 * s + form) * GM_INV_B12_N_LAMBDA + l, gm_inv_b12_lambdas[l]);
      fputs("\n", g);
    }
  fputs("unset multiplot\n", g);
}

static const char *status_text(const gm_inv_b12_row *r) {
  if (r->status == GM_OK) return "ok";
  return r->status == GM_EDOMAIN ? "blew up" : gm_strerror(r->status);
}

static int invariant_galilean(const char *dir, int json, int no_plot) {
  const char *cmd = "pde invariant galilean";
  int rc = cli_prepare_plot_dir(cmd, dir, no_plot);
  if (rc != CLI_EXIT_OK) return rc;
  gm_inv_b12 *b = malloc(sizeof *b);
  if (b == NULL) {
    cli_error(cmd, "out of memory");
    return CLI_EXIT_FAILURE;
  }
  gm_error err = {{0}};
  if (gm_inv_b12_run(b, &err) != GM_OK) {
    cli_error(cmd, "%s", err.message);
    free(b);
    return CLI_EXIT_FAILURE;
  }
  char csv[4200];
  FILE *f = open_out(cmd, dir, "b12.csv", csv, sizeof csv);
  if (f == NULL) {
    free(b);
    return CLI_EXIT_FAILURE;
  }
  fputs("x,exact", f);
  for (size_t r = 0; r < GM_INV_B12_N_SCHEMES * GM_INV_B12_N_LAMBDA; r++)
    fprintf(f, ",%s_%s_%g", b->rows[r].scheme, b->rows[r].invariant ? "inv" : "std",
            b->rows[r].lambda);
  fputs("\n", f);
  for (size_t j = 0; j < b->n; j++) {
    fprintf(f, "%.6f,%.10e", b->x[j], b->exact[j]);
    for (size_t r = 0; r < GM_INV_B12_N_SCHEMES * GM_INV_B12_N_LAMBDA; r++)
      fprintf(f, ",%.10e", b->u[r][j]);
    fputs("\n", f);
  }
  fclose(f);
  if (!no_plot) {
    char png[4200];
    snprintf(png, sizeof png, "%s/b12.png", dir);
    b12_plot p = {csv};
    if ((rc = cli_plot_custom(cmd, png, "B12", b12_body, &p)) != CLI_EXIT_OK) {
      free(b);
      return rc;
    }
  }
  if (json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "experiment", "B12");
    cJSON *arr = cJSON_AddArrayToObject(o, "rows");
    for (size_t r = 0; r < GM_INV_B12_N_SCHEMES * GM_INV_B12_N_LAMBDA; r++) {
      const gm_inv_b12_row *w = &b->rows[r];
      cJSON *m = cJSON_CreateObject();
      cJSON_AddStringToObject(m, "scheme", w->scheme);
      cJSON_AddStringToObject(m, "form", w->invariant ? "invariant" : "standard");
      cJSON_AddNumberToObject(m, "lambda", w->lambda);
      cJSON_AddStringToObject(m, "status", status_text(w));
      cJSON_AddNumberToObject(m, "steps", (double)w->steps_done);
      cJSON_AddItemToObject(m, "max_abs_error", cli_json_number(w->max_error));
      cJSON_AddItemToObject(m, "max_abs_diff_lambda0", cli_json_number(w->max_diff_lambda0));
      cJSON_AddItemToObject(m, "overshoot", cli_json_number(w->overshoot));
      cJSON_AddItemToObject(m, "step_bound", cli_json_number(w->step_bound));
      cJSON_AddItemToArray(arr, m);
    }
    free(b);
    return cli_json_print(o);
  }
  printf("B12 (seed 004 Test 1): Galilean consistency, t = 1, k = 1e-2 (errors max over x)\n");
  printf("%-15s %-9s %6s %-8s %10s %12s %10s %10s\n", "scheme", "form", "lambda", "status",
         "max error", "|u - u(l=0)|", "overshoot", "k bound");
  for (size_t r = 0; r < GM_INV_B12_N_SCHEMES * GM_INV_B12_N_LAMBDA; r++) {
    const gm_inv_b12_row *w = &b->rows[r];
    printf("%-15s %-9s %6.2f %-8s %10.3e %12.3e %10.3e %10.3e\n", w->scheme,
           w->invariant ? "invariant" : "standard", w->lambda, status_text(w), w->max_error,
           w->max_diff_lambda0, w->overshoot, w->step_bound);
  }
  printf("  data: %s%s%s/b12.png\n", csv, no_plot ? "" : ", figure: ", no_plot ? "" : dir);
  free(b);
  return CLI_EXIT_OK;
}

/* ---- B13 ------------------------------------------------------------------------------------ */
static void b13_body(FILE *g, const void *ctx) {
  fprintf(g, "set datafile separator ','\nset xlabel 'x'\nset ylabel 'u(2, x)'\n"
             "set key top right\n"
             "plot '%s' u 1:2 w l lw 3 lc rgb 'gray' t 'exact', '' u 1:3 w lp pt 7 t 'FTCS', "
             "'' u 1:4 w lp pt 5 t 'invariant FTCS'\n",
          (const char *)ctx);
}

static int invariant_shock(const char *dir, int json, int no_plot) {
  const char *cmd = "pde invariant shock";
  int rc = cli_prepare_plot_dir(cmd, dir, no_plot);
  if (rc != CLI_EXIT_OK) return rc;
  gm_inv_b13 b;
  gm_error err = {{0}};
  if (gm_inv_b13_run(&b, &err) != GM_OK) {
    cli_error(cmd, "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  char csv[4200];
  FILE *f = open_out(cmd, dir, "b13.csv", csv, sizeof csv);
  if (f == NULL) return CLI_EXIT_FAILURE;
  fputs("x,exact,ftcs,ftcs_invariant\n", f);
  for (size_t j = 0; j < b.n; j++)
    fprintf(f, "%.6f,%.10e,%.10e,%.10e\n", b.x[j], b.exact[j], b.standard[j], b.invariant[j]);
  fclose(f);
  if (!no_plot) {
    char png[4200];
    snprintf(png, sizeof png, "%s/b13.png", dir);
    rc = cli_plot_custom(cmd, png, "B13: projection-invariant viscous shock, nu = 1e-2, "
                         "k = h = 5e-2, t = 2", b13_body, csv);
    if (rc != CLI_EXIT_OK) return rc;
  }
  if (json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "experiment", "B13");
    cJSON_AddItemToObject(o, "max_abs_error_standard", cli_json_number(b.err_standard));
    cJSON_AddItemToObject(o, "max_abs_error_invariant", cli_json_number(b.err_invariant));
    cJSON_AddItemToObject(o, "max_abs_error_shock_standard",
                          cli_json_number(b.err_shock_standard));
    cJSON_AddItemToObject(o, "max_abs_error_shock_invariant",
                          cli_json_number(b.err_shock_invariant));
    return cli_json_print(o);
  }
  printf("B13 (seed 004 Test 2): u = (x - A tanh(A x/(2 nu tau)))/tau, tau = t + 1, A = 0.5, "
         "on [-1, 1]\n");
  printf("  max |u - u_exact| at t = 2: FTCS %.3e, invariant FTCS %.3e\n", b.err_standard,
         b.err_invariant);
  printf("  the same over |x| <= 0.2:  FTCS %.3e, invariant FTCS %.3e\n", b.err_shock_standard,
         b.err_shock_invariant);
  printf("  data: %s%s%s/b13.png\n", csv, no_plot ? "" : ", figure: ", no_plot ? "" : dir);
  return CLI_EXIT_OK;
}

/* ---- orders --------------------------------------------------------------------------------- */
static int invariant_orders(int json) {
  const char *names[3] = {"ftcs", "lax-wendroff", "crank-nicolson"};
  cJSON *o = json ? cJSON_CreateObject() : NULL, *arr = NULL;
  if (json) arr = cJSON_AddArrayToObject(o, "rows");
  else
    printf("order of consistency (one step from exact data / k; front nu = 0.1, k = h/2, "
           "h = 0.02 .. 0.0025)\n%-15s %-9s %7s  %s\n", "scheme", "form", "order",
           "tau at h = 0.02, 0.01, 0.005, 0.0025");
  for (int s = 0; s < 3; s++)
    for (int inv = 0; inv < 2; inv++) {
      const gm_inv_scheme *sc;
      gm_inv_scheme_find(names[s], &sc);
      double p, tau[4];
      gm_error err = {{0}};
      if (gm_inv_consistency_order(sc, inv ? &gm_inv_burgers_g0 : NULL, &p, tau, &err) != GM_OK) {
        cli_error("pde invariant orders", "%s", err.message);
        cJSON_Delete(o);
        return CLI_EXIT_FAILURE;
      }
      if (json) {
        cJSON *m = cJSON_CreateObject();
        cJSON_AddStringToObject(m, "scheme", names[s]);
        cJSON_AddStringToObject(m, "form", inv ? "invariant" : "standard");
        cJSON_AddItemToObject(m, "order", cli_json_number(p));
        cJSON_AddItemToObject(m, "tau", cli_json_numbers(tau, 4));
        cJSON_AddItemToArray(arr, m);
      } else {
        printf("%-15s %-9s %7.2f  %.3e %.3e %.3e %.3e\n", names[s],
               inv ? "invariant" : "standard", p, tau[0], tau[1], tau[2], tau[3]);
      }
    }
  return json ? cli_json_print(o) : CLI_EXIT_OK;
}

int cli_pde_invariant(int argc, char **argv) {
  const char *dir = "pde-output";
  int json = 0, no_plot = 0;
  const char *pos[1] = {NULL};
  size_t n_pos = 0;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &dir, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0}};
  int rc = cli_parse("pde invariant", argc, argv, options, 3, pos, 1, &n_pos);
  if (rc == CLI_HELP) {
    fputs(cli_pde_invariant_usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  if (n_pos == 1 && strcmp(pos[0], "galilean") == 0) return invariant_galilean(dir, json, no_plot);
  if (n_pos == 1 && strcmp(pos[0], "shock") == 0) return invariant_shock(dir, json, no_plot);
  if (n_pos == 1 && strcmp(pos[0], "orders") == 0) return invariant_orders(json);
  cli_error("pde invariant", "which experiment? galilean, shock or orders");
  return CLI_EXIT_USAGE;
}
