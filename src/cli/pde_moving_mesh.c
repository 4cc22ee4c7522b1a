/* geomint pde moving-mesh: the space–time adaptive variational integrator of the wave equation
 * (seed 004 (62), (66), (67a)–(67c); geomint/pde_moving_mesh.h) on a travelling pulse: the
 * conditioning of each kind's Newton matrix, runs of each kind, the order against d'Alembert,
 * the cost against the fixed-grid tent VI, and the space–time mesh figure. */
#include <cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli/cli.h"

const char cli_pde_moving_mesh_usage[] =
    "       geomint pde moving-mesh [--n N] [--cfl C] [--steps S] [--alpha A] [--out DIR]\n"
    "                               [--json] [--no-plot]\n"
    "\n"
    "moving-mesh: the space-time adaptive VI of u_tt = u_xx (seed 004 (62), (66), (67a)-(67c))\n"
    "     on the pulse u = exp(-(x - 10 - t)^2), [0, 20) periodic, N nodes (default 100), first\n"
    "     step dt = C min dx (default 0.5; C <= 1, the start's stability bound), S steps\n"
    "     (default 2000). Kinds: seed (the seed's equations), equidistribute (Tyranowski-\n"
    "     Desbrun's equal-arc-length constraint with multipliers, alpha = 0 and A, default 1),\n"
    "     time-adaptive (grid held, t from the energy equation). Prints the Newton matrix's\n"
    "     condition number against N, each kind's run (a failed step ends it and is counted),\n"
    "     the order against d'Alembert, the cost per step against the fixed-grid tent VI.\n"
    "     Writes DIR/moving-mesh-layers.dat, DIR/moving-mesh-dt.dat, DIR/moving-mesh.png.\n";

static const char *kind_name(gm_moving_mesh_kind k) {
  return k == GM_MOVING_MESH_SEED ? "seed"
         : k == GM_MOVING_MESH_EQUIDISTRIBUTE ? "equidistribute"
                                              : "time-adaptive";
}

/* ---- the layers of the figure run ------------------------------------------------------------ */
typedef struct layer_log {
  FILE *layers, *dt;
  size_t max_layers, seen;
  double t_prev;
} layer_log;

static void write_layer(layer_log *g, const gm_moving_mesh *m) {
  const double *x = gm_moving_mesh_x(m), *u = gm_moving_mesh_u(m);
  double t = gm_moving_mesh_time(m);
  if (g->seen < g->max_layers) {
    for (size_t j = 0; j < gm_moving_mesh_n(m); j++)
      fprintf(g->layers, "%.9g %.9g %.9g\n", x[j], t, u[j]);
    fputs("\n", g->layers);
  }
  if (g->seen > 0) fprintf(g->dt, "%.9g %.9g\n", t, t - g->t_prev);
  g->t_prev = t;
  g->seen++;
}

static int log_layer(const gm_moving_mesh *m, void *ctx) {
  write_layer(ctx, m);
  return 0;
}

static void figure_body(FILE *g, const void *ctx) {
  const char *dir = ctx;
  fprintf(g,
          "set multiplot layout 1,2\n"
          "set title 'space-time mesh (x_j, t^n), time-adaptive, first layers; colour u'\n"
          "set xlabel 'x'\nset ylabel 't'\nset palette rgbformulae 33,13,10\n"
          "plot '%s/moving-mesh-layers.dat' u 1:2:3 w p pt 7 ps 0.35 lc palette notitle\n"
          "set title 'adapted step t^{n+1} - t^n'\nset xlabel 't'\nset ylabel 'dt'\n"
          "plot '%s/moving-mesh-dt.dat' u 1:2 w l lw 2 t 'pulse'\n"
          "unset multiplot\n",
          dir, dir);
}

/* ---- wall time per step (min of 3) ----------------------------------------------------------- */
static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
static double zero_potential(double u, const void *c) {
  (void)u;
  (void)c;
  return 0.0;
}

/* tent VI (V = 0) on the same uniform grid and Δt as the time-adaptive run's first step */
static int cost(const gm_moving_mesh_pulse *p, size_t steps, double *mm_s, double *tent_s,
                gm_error *err) {
  *mm_s = *tent_s = INFINITY;
  for (int rep = 0; rep < 3; rep++) {
    gm_moving_mesh *m = NULL;
    if (gm_moving_mesh_pulse_create(p, &m, err) != GM_OK) return 1;
    double t0 = now();
    gm_status st = gm_moving_mesh_advance(m, steps, err);
    *mm_s = fmin(*mm_s, (now() - t0) / (double)steps);
    size_t n = gm_moving_mesh_n(m);
    double h = 20.0 / (double)n, dt = p->cfl * h;
    double *u0 = malloc(n * sizeof *u0), *u1 = malloc(n * sizeof *u1);
    gm_moving_mesh_free(m);
    if (st != GM_OK || u0 == NULL || u1 == NULL) {
      free(u0);
      free(u1);
      return 1;
    }
    for (size_t j = 0; j < n; j++) {
      u0[j] = gm_moving_mesh_pulse_exact(p, (double)j * h, 0.0);
      u1[j] = gm_moving_mesh_pulse_exact(p, (double)j * h, dt);
    }
    gm_tentvi *tv = NULL;
    st = gm_tentvi_create(n, 0.0, h, 0.0, dt, zero_potential, zero_potential, zero_potential,
                          NULL, u0, u1, &tv, err);
    free(u0);
    free(u1);
    if (st != GM_OK) return 1;
    t0 = now();
    st = gm_tentvi_advance(tv, steps, err);
    *tent_s = fmin(*tent_s, (now() - t0) / (double)steps);
    gm_tentvi_free(tv);
    if (st != GM_OK) return 1;
  }
  return 0;
}

static cJSON *run_json(const char *kind, double alpha, int dirichlet,
                       const gm_moving_mesh_pulse_result *r, const char *msg) {
  cJSON *o = cJSON_CreateObject();
  cJSON_AddStringToObject(o, "kind", kind);
  cJSON_AddNumberToObject(o, "alpha", alpha);
  cJSON_AddStringToObject(o, "ends", dirichlet ? "dirichlet" : "periodic");
  cJSON_AddStringToObject(o, "status", r->status == GM_OK ? "ok" : gm_strerror(r->status));
  cJSON_AddStringToObject(o, "message", r->status == GM_OK ? "" : msg);
  cJSON_AddNumberToObject(o, "steps", (double)r->steps);
  cJSON_AddNumberToObject(o, "failed_steps", r->status == GM_OK ? 0.0 : 1.0);
  cJSON_AddItemToObject(o, "t", cli_json_number(r->t));
  cJSON_AddItemToObject(o, "max_rel_energy", cli_json_number(r->max_rel_energy));
  cJSON_AddItemToObject(o, "max_rel_momentum", cli_json_number(r->max_rel_momentum));
  cJSON_AddItemToObject(o, "max_abs_error", cli_json_number(r->max_error));
  cJSON_AddItemToObject(o, "newton_per_step", cli_json_number(r->newton_per_step));
  return o;
}

int cli_pde_moving_mesh(int argc, char **argv) {
  const char *cmd = "pde moving-mesh", *dir = "pde-output";
  size_t n = 100, steps = 2000;
  double cfl = 0.5, alpha = 1.0;
  int json = 0, no_plot = 0;
  cli_option options[] = {{"--n", CLI_ARG_COUNT, &n, 0},
                          {"--cfl", CLI_ARG_DOUBLE, &cfl, 0},
                          {"--steps", CLI_ARG_COUNT, &steps, 0},
                          {"--alpha", CLI_ARG_DOUBLE, &alpha, 0},
                          {"--out", CLI_ARG_STRING, &dir, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0},
                          {"--no-plot", CLI_ARG_FLAG, &no_plot, 0}};
  const char *pos[1] = {NULL};
  size_t n_pos = 0;
  int rc = cli_parse(cmd, argc, argv, options, 7, pos, 0, &n_pos);
  if (rc == CLI_HELP) {
    fputs(cli_pde_moving_mesh_usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  if (n < 20 || n > 100000) {
    cli_error(cmd, "--n %zu: need 20 .. 100000 nodes", n);
    return CLI_EXIT_USAGE;
  }
  if (!(isfinite(cfl) && cfl > 0.0)) {
    cli_error(cmd, "--cfl %g: must be a finite number > 0", cfl);
    return CLI_EXIT_USAGE;
  }
  if (cfl > 1.0) {
    cli_error(cmd, "--cfl %g is above the stability bound of the start, dt <= min dx (cfl <= 1)",
              cfl);
    return CLI_EXIT_USAGE;
  }
  if (!(isfinite(alpha) && alpha >= 0.0)) {
    cli_error(cmd, "--alpha %g: must be finite and >= 0", alpha);
    return CLI_EXIT_USAGE;
  }
  if (steps == 0 || steps > 10000000) {
    cli_error(cmd, "--steps %zu: need 1 .. 1e7", steps);
    return CLI_EXIT_USAGE;
  }
  if ((rc = cli_prepare_plot_dir(cmd, dir, no_plot)) != CLI_EXIT_OK) return rc;
  cJSON *root = json ? cJSON_CreateObject() : NULL;
  gm_error err = {{0}};

  /* 1. conditioning against n, both data sets */
  static const size_t sizes[4] = {20, 40, 80, 160};
  static const gm_moving_mesh_kind kinds[3] = {GM_MOVING_MESH_SEED, GM_MOVING_MESH_EQUIDISTRIBUTE,
                                               GM_MOVING_MESH_TIME_ADAPTIVE};
  cJSON *jc = json ? cJSON_AddArrayToObject(root, "conditioning") : NULL;
  if (!json)
    printf("Newton matrix at the first step (rows scaled to max 1): condition number\n"
           "%-6s %5s %14s %14s %14s\n", "data", "n", "seed", "equidistr. 0", "time-adaptive");
  for (int ramp = 0; ramp < 2; ramp++)
    for (int k = 0; k < 4; k++) {
      double c[3];
      for (int q = 0; q < 3; q++) {
        gm_moving_mesh_pulse p = {sizes[k], cfl, kinds[q], 0.0, 0, ramp};
        gm_moving_mesh *m = NULL;
        double smin;
        if (gm_moving_mesh_pulse_create(&p, &m, &err) != GM_OK ||
            gm_moving_mesh_conditioning(m, &smin, &c[q], &err) != GM_OK) {
          cli_error(cmd, "%s", err.message);
          gm_moving_mesh_free(m);
          cJSON_Delete(root);
          return CLI_EXIT_FAILURE;
        }
        gm_moving_mesh_free(m);
      }
      if (json) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "data", ramp ? "ramp" : "pulse");
        cJSON_AddNumberToObject(o, "n", (double)sizes[k]);
        cJSON_AddItemToObject(o, "cond", cli_json_numbers(c, 3));
        cJSON_AddItemToArray(jc, o);
      } else {
        printf("%-6s %5zu %14.3e %14.3e %14.3e\n", ramp ? "ramp" : "pulse", sizes[k], c[0], c[1],
               c[2]);
      }
    }

  /* 2. each kind on the pulse */
  struct {
    gm_moving_mesh_kind kind;
    double alpha;
    int dirichlet;
  } runs[5] = {{GM_MOVING_MESH_SEED, 0.0, 0},
               {GM_MOVING_MESH_EQUIDISTRIBUTE, 0.0, 0},
               {GM_MOVING_MESH_EQUIDISTRIBUTE, alpha, 0},
               {GM_MOVING_MESH_TIME_ADAPTIVE, 0.0, 0},
               {GM_MOVING_MESH_TIME_ADAPTIVE, 0.0, 1}};
  cJSON *jr = json ? cJSON_AddArrayToObject(root, "runs") : NULL;
  if (!json)
    printf("\npulse, n = %zu, first dt = %g min dx, %zu steps\n%-15s %5s %-9s %7s %9s %10s %10s "
           "%10s %6s  %s\n", n, cfl, steps, "kind", "alpha", "ends", "steps", "t", "max dE/E",
           "max dP/P", "max err", "it/st", "status");
  char layers_path[4096], dt_path[4096];
  snprintf(layers_path, sizeof layers_path, "%s/moving-mesh-layers.dat", dir);
  snprintf(dt_path, sizeof dt_path, "%s/moving-mesh-dt.dat", dir);
  for (int q = 0; q < 5; q++) {
    gm_moving_mesh_pulse p = {n, cfl, runs[q].kind, runs[q].alpha, runs[q].dirichlet, 0};
    gm_moving_mesh_pulse_result r;
    layer_log log = {NULL, NULL, 120, 0, 0.0};
    int logged = q == 3 && !no_plot;
    if (logged) {
      log.layers = fopen(layers_path, "w");
      log.dt = fopen(dt_path, "w");
      if (log.layers == NULL || log.dt == NULL) {
        cli_error(cmd, "cannot write in '%s': %s", dir, strerror(errno));
        if (log.layers) fclose(log.layers);
        if (log.dt) fclose(log.dt);
        cJSON_Delete(root);
        return CLI_EXIT_FAILURE;
      }
    }
    gm_status st = gm_moving_mesh_pulse_run(&p, steps, logged ? log_layer : NULL, &log, &r, &err);
    if (logged) {
      fclose(log.layers);
      fclose(log.dt);
    }
    if (st != GM_OK) {
      cli_error(cmd, "%s", err.message);
      cJSON_Delete(root);
      return CLI_EXIT_FAILURE;
    }
    if (json) {
      cJSON_AddItemToArray(jr, run_json(kind_name(runs[q].kind), runs[q].alpha,
                                        runs[q].dirichlet, &r, err.message));
    } else {
      printf("%-15s %5g %-9s %7zu %9.4f %10.2e %10.2e %10.2e %6.2f  %s\n",
             kind_name(runs[q].kind), runs[q].alpha, runs[q].dirichlet ? "dirichlet" : "periodic",
             r.steps, r.t, r.max_rel_energy, r.max_rel_momentum, r.max_error, r.newton_per_step,
             r.status == GM_OK ? "ok" : err.message);
    }
  }

  /* 3. order against d'Alembert, t ≈ 4 */
  double e[3], t_end[3];
  for (int k = 0; k < 3; k++) {
    size_t nk = (size_t)100 << k;
    gm_moving_mesh_pulse p = {nk, 0.5, GM_MOVING_MESH_TIME_ADAPTIVE, 0.0, 0, 0};
    gm_moving_mesh_pulse_result r;
    if (gm_moving_mesh_pulse_run(&p, 2 * nk / 5, NULL, NULL, &r, &err) != GM_OK ||
        r.status != GM_OK) {
      cli_error(cmd, "order run n = %zu: %s", nk, err.message);
      cJSON_Delete(root);
      return CLI_EXIT_FAILURE;
    }
    e[k] = r.max_error;
    t_end[k] = r.t;
  }
  double orders[2] = {log2(e[0] / e[1]), log2(e[1] / e[2])};

  /* 4. cost per step against the tent VI */
  gm_moving_mesh_pulse pc = {n, cfl, GM_MOVING_MESH_TIME_ADAPTIVE, 0.0, 0, 0};
  size_t cost_steps = steps < 500 ? steps : 500;
  double mm_s, tent_s;
  if (cost(&pc, cost_steps, &mm_s, &tent_s, &err) != 0) {
    cli_error(cmd, "cost run: %s", err.message);
    cJSON_Delete(root);
    return CLI_EXIT_FAILURE;
  }
  if (json) {
    cJSON *o = cJSON_AddObjectToObject(root, "order");
    cJSON_AddItemToObject(o, "n", cli_json_numbers((double[]){100, 200, 400}, 3));
    cJSON_AddItemToObject(o, "t", cli_json_numbers(t_end, 3));
    cJSON_AddItemToObject(o, "max_abs_error", cli_json_numbers(e, 3));
    cJSON_AddItemToObject(o, "orders", cli_json_numbers(orders, 2));
    cJSON *c = cJSON_AddObjectToObject(root, "cost");
    cJSON_AddNumberToObject(c, "n", (double)n);
    cJSON_AddNumberToObject(c, "steps", (double)cost_steps);
    cJSON_AddItemToObject(c, "time_adaptive_s_per_step", cli_json_number(mm_s));
    cJSON_AddItemToObject(c, "tent_vi_s_per_step", cli_json_number(tent_s));
    cJSON_AddItemToObject(c, "ratio", cli_json_number(mm_s / tent_s));
  } else {
    printf("\norder against d'Alembert (time-adaptive, first dt = h/2, t ~ 4): n = 100, 200, 400:"
           " max err %.3e, %.3e, %.3e; orders %.2f, %.2f\n", e[0], e[1], e[2], orders[0],
           orders[1]);
    printf("cost per step, n = %zu, %zu steps, wall time min of 3: time-adaptive %.3e s, tent VI "
           "(fixed grid, same dt) %.3e s, ratio %.1f\n", n, cost_steps, mm_s, tent_s,
           mm_s / tent_s);
  }
  if (!no_plot) {
    char png[4096];
    snprintf(png, sizeof png, "%s/moving-mesh.png", dir);
    rc = cli_plot_custom(cmd, png, "space-time adaptive VI of the wave equation", figure_body, dir);
    if (rc != CLI_EXIT_OK) {
      cJSON_Delete(root);
      return rc;
    }
    if (!json) printf("  data: %s, %s, figure: %s\n", layers_path, dt_path, png);
  }
  return json ? cli_json_print(root) : CLI_EXIT_OK;
}
