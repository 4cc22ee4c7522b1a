/* geomint maxwell run SCENE.json [--out DIR] [--json] [--check]: run a scene file and write
 * probes.csv, energy.csv, flux.csv, snapshots (.vti/.h5 + snapshots.pvd), then summarize the
 * probe resonances (harminv) and the time-integrated Poynting flux through each plane. */
#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/maxwell.h"

#define COMMAND "maxwell run"
#define MAX_MODES 32

/* Energy and flux series, filled by observers (arrays allocated before the run). */
typedef struct series {
  size_t n, cap, width;
  double *t;      /* owned */
  double *values; /* owned, width per row */
} series;

static int series_init(series *s, size_t cap, size_t width) {
  s->n = 0;
  s->cap = cap;
  s->width = width;
  s->t = malloc((cap + 1) * sizeof *s->t);
  s->values = malloc((cap + 1) * (width + 1) * sizeof *s->values);
  return s->t != NULL && s->values != NULL ? 0 : -1;
}

static void series_free(series *s) {
  free(s->t);
  free(s->values);
}

typedef struct run_state {
  gm_yee_scene *scene;
  series energy, flux;
  gm_status flux_status;
} run_state;

static int observe_energy(void *ctx, const gm_yee *solver) {
  run_state *r = ctx;
  series *s = &r->energy;
  if (s->n >= s->cap) return 0;
  gm_yee_energy e;
  if (gm_yee_get_energy(solver, &e) != GM_OK) return 1;
  s->t[s->n] = gm_yee_time_h(solver);
  double *row = s->values + s->n * s->width;
  row[0] = e.electric;
  row[1] = e.magnetic;
  row[2] = e.plain;
  row[3] = e.leapfrog;
  if (s->width > 4) row[4] = e.polarization; /* dispersive scenes: the poles' energy */
  s->n++;
  return 0;
}

/* The flux is of E^{n−½} and H averaged to t_{n−½}: one sample per step at E's time. */
static int observe_flux(void *ctx, const gm_yee *solver) {
  run_state *r = ctx;
  series *s = &r->flux;
  if (s->n >= s->cap || gm_yee_step(solver) == 0) return 0;
  s->t[s->n] = gm_yee_time_e(solver);
  for (size_t k = 0; k < r->scene->n_fluxes; ++k) {
    const gm_yee_scene_flux *f = &r->scene->fluxes[k];
    gm_status st = gm_yee_poynting_flux(solver, f->axis, f->index, &s->values[s->n * s->width + k]);
    if (st != GM_OK) {
      r->flux_status = st;
      return 1;
    }
  }
  s->n++;
  return 0;
}

/* ---- output files ---------------------------------------------------------------------- */

static int write_series_csv(const char *path, const char *const *names, const series *s) {
  gm_probe_csv *w = NULL;
  gm_error err = {{0}};
  if (gm_probe_csv_create(path, s->width, names, &w, &err) != GM_OK) {
    cli_error(COMMAND, "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  for (size_t i = 0; i < s->n; ++i)
    if (gm_probe_csv_write(w, s->t[i], s->values + i * s->width) != GM_OK) {
      cli_error(COMMAND, "%s", gm_probe_csv_errmsg(w));
      gm_probe_csv_free(w);
      return CLI_EXIT_FAILURE;
    }
  gm_status st = gm_probe_csv_flush(w);
  if (st != GM_OK) cli_error(COMMAND, "%s", gm_probe_csv_errmsg(w));
  gm_probe_csv_free(w);
  return st == GM_OK ? CLI_EXIT_OK : CLI_EXIT_FAILURE;
}

/* probes.csv: t (the time of H, t_n), t_e (the time of E, t_n − Δt/2), one column per probe
 * (each sampled at its own component's time). */
static int write_probes_csv(const char *path, const gm_yee_scene *sc, const gm_yee *solver) {
  size_t np = sc->n_probes;
  const char **names = malloc((np + 1) * sizeof *names);
  double *row = malloc((np + 1) * sizeof *row);
  const double **re = malloc((np + 1) * sizeof *re);
  if (names == NULL || row == NULL || re == NULL) {
    free(names), free(row), free(re);
    cli_error(COMMAND, "out of memory");
    return CLI_EXIT_FAILURE;
  }
  names[0] = "t_e";
  size_t n = (size_t)-1;
  const double *t0 = NULL;
  for (size_t k = 0; k < np; ++k) {
    names[k + 1] = sc->probes[k].name;
    size_t nk;
    const double *t, *im;
    gm_yee_probe_samples(solver, k, &nk, &t, &re[k], &im);
    if (nk < n) n = nk;
    if (k == 0) t0 = t;
  }
  gm_probe_csv *w = NULL;
  gm_error err = {{0}};
  int rc = CLI_EXIT_OK;
  if (gm_probe_csv_create(path, np + 1, names, &w, &err) != GM_OK) {
    cli_error(COMMAND, "%s", err.message);
    rc = CLI_EXIT_FAILURE;
  }
  double dt = gm_yee_dt(solver);
  /* probe 0's times are those of its component: E at t_n − Δt/2, H at t_n */
  double to_h = sc->probes[0].component <= GM_EZ ? 0.5 * dt : 0.0;
  for (size_t i = 0; rc == CLI_EXIT_OK && i < n; ++i) {
    double t_h = t0[i] + to_h;
    row[0] = t_h - 0.5 * dt;
    for (size_t k = 0; k < np; ++k) row[k + 1] = re[k][i];
    if (gm_probe_csv_write(w, t_h, row) != GM_OK) rc = CLI_EXIT_FAILURE;
  }
  if (rc == CLI_EXIT_OK && w != NULL && gm_probe_csv_flush(w) != GM_OK) rc = CLI_EXIT_FAILURE;
  if (rc != CLI_EXIT_OK && w != NULL) cli_error(COMMAND, "%s", gm_probe_csv_errmsg(w));
  gm_probe_csv_free(w);
  free(names), free(row), free(re);
  return rc;
}

/* ---- the summary ------------------------------------------------------------------------ */

static const char *dim_name(gm_yee_dim d) {
  switch (d) {
    case GM_YEE_1D: return "1d";
    case GM_YEE_2D_TE: return "2d-te";
    case GM_YEE_2D_TM: return "2d-tm";
    default: return "3d";
  }
}

typedef struct probe_result {
  size_t n_modes;
  gm_harminv_mode modes[MAX_MODES];
  char error[256];
} probe_result;

static void print_text(const char *path, const gm_yee_scene *sc, const gm_yee *solver, double wall,
                       size_t steps, const probe_result *pr, const double *flux_integral,
                       const run_state *r, const char *out_dir, size_t n_snapshots) {
  size_t n_arrays = 0, bytes = gm_yee_memory(solver, &n_arrays);
  double cells = (double)(sc->grid.n[0] * sc->grid.n[1] * sc->grid.n[2]);
  printf("maxwell run %s: %s grid %zu x %zu x %zu cells, h = %g x %g x %g\n", path,
         dim_name(sc->grid.dim), sc->grid.n[0], sc->grid.n[1], sc->grid.n[2], sc->grid.h[0],
         sc->grid.h[1], sc->grid.h[2]);
  printf("  dt %.6g, %zu steps to t = %.6g in %.3f s (%.1f Mcells*steps/s), %.1f MB in %zu "
         "grid arrays\n", gm_yee_dt(solver), steps, gm_yee_time_h(solver), wall,
         wall > 0 ? cells * (double)steps / wall / 1e6 : 0.0, (double)bytes / 1e6, n_arrays);
  if (r->energy.n > 0) {
    const double *first = r->energy.values,
                 *last = r->energy.values + (r->energy.n - 1) * r->energy.width;
    printf("  energy (electric + magnetic): %.9g at t = %.6g, %.9g at t = %.6g\n", first[2],
           r->energy.t[0], last[2], r->energy.t[r->energy.n - 1]);
  }
  for (size_t k = 0; k < sc->n_fluxes; ++k)
    printf("  flux %-12s %s = %-10.6g (plane %zu): integral over time %.9g\n",
           sc->fluxes[k].name, (const char *[]){"x", "y", "z"}[sc->fluxes[k].axis],
           sc->fluxes[k].position, sc->fluxes[k].index, flux_integral[k]);
  if (sc->harminv)
    for (size_t k = 0; k < sc->n_probes; ++k) {
      printf("  probe %s (%s): ", sc->probes[k].name,
             gm_yee_component_name(sc->probes[k].component));
      if (pr[k].error[0] != '\0') {
        printf("harminv failed: %s\n", pr[k].error);
        continue;
      }
      printf("%zu resonances in [%g, %g]\n", pr[k].n_modes, sc->harminv_fmin, sc->harminv_fmax);
      if (pr[k].n_modes > 0)
        printf("    %14s %12s %12s %12s %10s\n", "frequency", "decay", "Q", "amplitude", "error");
      for (size_t m = 0; m < pr[k].n_modes; ++m) {
        const gm_harminv_mode *md = &pr[k].modes[m];
        printf("    %14.9f %12.4g %12.4g %12.4g %10.2g\n", md->frequency, md->decay, md->q,
               md->amplitude, md->error);
      }
    }
  char files[256] = "";
  size_t len = 0;
  const char *names[3] = {sc->n_probes > 0 ? "probes.csv" : NULL,
                          r->energy.n > 0 ? "energy.csv" : NULL,
                          sc->n_fluxes > 0 ? "flux.csv" : NULL};
  for (int k = 0; k < 3; ++k)
    if (names[k] != NULL && len < sizeof files)
      len += (size_t)snprintf(files + len, sizeof files - len, "%s%s", len > 0 ? ", " : "",
                              names[k]);
  if (n_snapshots > 0 && len < sizeof files)
    snprintf(files + len, sizeof files - len, "%s%zu snapshots (snapshot.pvd)",
             len > 0 ? ", " : "", n_snapshots);
  printf("  wrote %s/: %s\n", out_dir, files[0] != '\0' ? files : "nothing (no probes, "
         "energy, flux or snapshots asked for)");
}

static int print_json(const char *path, const gm_yee_scene *sc, const gm_yee *solver, double wall,
                      size_t steps, const probe_result *pr, const double *flux_integral,
                      const run_state *r, const char *out_dir, size_t n_snapshots) {
  size_t n_arrays = 0, bytes = gm_yee_memory(solver, &n_arrays);
  cJSON *o = cJSON_CreateObject();
  cJSON_AddStringToObject(o, "scene", path);
  cJSON_AddStringToObject(o, "dim", dim_name(sc->grid.dim));
  double n[3] = {(double)sc->grid.n[0], (double)sc->grid.n[1], (double)sc->grid.n[2]};
  cJSON_AddItemToObject(o, "cells", cli_json_numbers(n, 3));
  cJSON_AddItemToObject(o, "h", cli_json_numbers(sc->grid.h, 3));
  cJSON_AddNumberToObject(o, "dt", gm_yee_dt(solver));
  cJSON_AddNumberToObject(o, "steps", (double)steps);
  cJSON_AddNumberToObject(o, "t_final", gm_yee_time_h(solver));
  cJSON_AddNumberToObject(o, "wall_s", wall);
  cJSON_AddNumberToObject(o, "memory_bytes", (double)bytes);
  cJSON_AddNumberToObject(o, "memory_arrays", (double)n_arrays);
  cJSON_AddStringToObject(o, "out", out_dir);
  cJSON_AddNumberToObject(o, "snapshots", (double)n_snapshots);
  if (r->energy.n > 0) {
    const double *last = r->energy.values + (r->energy.n - 1) * r->energy.width;
    cJSON *e = cJSON_AddObjectToObject(o, "energy");
    cJSON_AddItemToObject(e, "initial", cli_json_number(r->energy.values[2]));
    cJSON_AddItemToObject(e, "final", cli_json_number(last[2]));
    cJSON_AddItemToObject(e, "final_leapfrog", cli_json_number(last[3]));
    cJSON_AddNumberToObject(e, "samples", (double)r->energy.n);
  }
  cJSON *fl = cJSON_AddArrayToObject(o, "flux");
  for (size_t k = 0; k < sc->n_fluxes; ++k) {
    cJSON *f = cJSON_CreateObject();
    cJSON_AddStringToObject(f, "name", sc->fluxes[k].name);
    cJSON_AddNumberToObject(f, "axis", sc->fluxes[k].axis);
    cJSON_AddNumberToObject(f, "plane", (double)sc->fluxes[k].index);
    cJSON_AddItemToObject(f, "integral", cli_json_number(flux_integral[k]));
    cJSON_AddItemToArray(fl, f);
  }
  cJSON *probes = cJSON_AddArrayToObject(o, "probes");
  for (size_t k = 0; k < sc->n_probes; ++k) {
    cJSON *p = cJSON_CreateObject();
    cJSON_AddStringToObject(p, "name", sc->probes[k].name);
    cJSON_AddStringToObject(p, "component", gm_yee_component_name(sc->probes[k].component));
    if (sc->harminv) {
      if (pr[k].error[0] != '\0') cJSON_AddStringToObject(p, "harminv_error", pr[k].error);
      cJSON *modes = cJSON_AddArrayToObject(p, "resonances");
      for (size_t m = 0; m < pr[k].n_modes; ++m) {
        cJSON *md = cJSON_CreateObject();
        cJSON_AddItemToObject(md, "frequency", cli_json_number(pr[k].modes[m].frequency));
        cJSON_AddItemToObject(md, "decay", cli_json_number(pr[k].modes[m].decay));
        cJSON_AddItemToObject(md, "q", cli_json_number(pr[k].modes[m].q));
        cJSON_AddItemToObject(md, "amplitude", cli_json_number(pr[k].modes[m].amplitude));
        cJSON_AddItemToObject(md, "error", cli_json_number(pr[k].modes[m].error));
        cJSON_AddItemToArray(modes, md);
      }
    }
    cJSON_AddItemToArray(probes, p);
  }
  return cli_json_print(o);
}

static int print_check(const char *path, const gm_yee_scene *sc, const gm_yee *solver, int json) {
  size_t steps = gm_yee_scene_total_steps(sc, gm_yee_dt(solver));
  size_t n_arrays = 0, bytes = gm_yee_memory(solver, &n_arrays);
  if (json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "scene", path);
    cJSON_AddStringToObject(o, "dim", dim_name(sc->grid.dim));
    double n[3] = {(double)sc->grid.n[0], (double)sc->grid.n[1], (double)sc->grid.n[2]};
    cJSON_AddItemToObject(o, "cells", cli_json_numbers(n, 3));
    cJSON_AddItemToObject(o, "h", cli_json_numbers(sc->grid.h, 3));
    cJSON_AddNumberToObject(o, "dt", gm_yee_dt(solver));
    cJSON_AddNumberToObject(o, "steps", (double)steps);
    cJSON_AddNumberToObject(o, "sources", (double)(sc->n_points + sc->n_planes + sc->n_obliques));
    cJSON_AddNumberToObject(o, "probes", (double)sc->n_probes);
    cJSON_AddNumberToObject(o, "flux_planes", (double)sc->n_fluxes);
    cJSON_AddNumberToObject(o, "memory_bytes", (double)bytes);
    cJSON_AddNumberToObject(o, "memory_arrays", (double)n_arrays);
    return cli_json_print(o);
  }
  printf("maxwell run %s: scene is valid\n", path);
  printf("  %s grid %zu x %zu x %zu cells, dt %.6g, %zu steps, %zu sources, %zu probes, "
         "%zu flux planes, %.1f MB in %zu grid arrays\n", dim_name(sc->grid.dim), sc->grid.n[0],
         sc->grid.n[1], sc->grid.n[2], gm_yee_dt(solver), steps, sc->n_points + sc->n_planes + sc->n_obliques,
         sc->n_probes, sc->n_fluxes, (double)bytes / 1e6, n_arrays);
  return CLI_EXIT_OK;
}

/* A colour map of component `field` at the final state: the grid in 2-D, the middle z slice
 * in 3-D, the x axis stretched to a strip in 1-D. */
static int plot_final(const char *png, const char *field, const char *scene_path,
                      const gm_yee_scene *sc, const gm_yee *solver) {
  gm_yee_component c;
  if (gm_yee_component_find(field, &c) != GM_OK || !gm_yee_dim_has(sc->grid.dim, c)) {
    cli_error(COMMAND, "--plot-field %s: not a component of this grid", field);
    return CLI_EXIT_USAGE;
  }
  size_t nx = sc->grid.n[0], ny = sc->grid.n[1], nz = sc->grid.n[2];
  double *cells = malloc(nx * ny * nz * sizeof *cells);
  if (cells == NULL || gm_yee_cell_average(solver, c, 0, cells) != GM_OK) {
    free(cells);
    cli_error(COMMAND, "cannot read %s for the plot", field);
    return CLI_EXIT_FAILURE;
  }
  size_t k = nz / 2;
  char title[512], label[64];
  snprintf(title, sizeof title, "%s: %s at t = %.6g%s (cell averages)", scene_path, field,
           gm_yee_component_name(c)[0] == 'E' ? gm_yee_time_e(solver) : gm_yee_time_h(solver),
           nz > 1 ? ", middle z slice" : "");
  snprintf(label, sizeof label, "%s", gm_yee_component_name(c));
  double hy = ny > 1 ? sc->grid.h[1] : sc->grid.h[0] * (double)nx / 8;
  int rc = mx_plot_map(COMMAND, png, title, label, nx, ny, sc->grid.origin[0],
                       ny > 1 ? sc->grid.origin[1] : 0, sc->grid.h[0], hy, cells + nx * ny * k);
  free(cells);
  return rc;
}

int mx_run_main(int argc, char **argv) {
#ifdef GM_HAVE_MPI
  if (mx_mpi_launched()) return mx_run_mpi_main(argc, argv);
#endif
  const char *out_dir = "maxwell-output";
  const char *plot = NULL, *plot_field = NULL;
  int json = 0, check = 0;
  size_t threads = (size_t)-1; /* not given: the solver's default */
  cli_option options[] = {{"--out", CLI_ARG_STRING, &out_dir, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0},
                          {"--check", CLI_ARG_FLAG, &check, 0},
                          {"--threads", CLI_ARG_COUNT, &threads, 0},
                          {"--plot", CLI_ARG_STRING, &plot, 0},
                          {"--plot-field", CLI_ARG_STRING, &plot_field, 0}};
  const char *positional[1];
  size_t n_pos = 0;
  int status = cli_parse(COMMAND, argc, argv, options, 6, positional, 1, &n_pos);
  if (status == CLI_HELP) {
    fputs(mx_usage(), stdout);
    return CLI_EXIT_OK;
  }
  if (status != CLI_EXIT_OK) return status;
  if (n_pos != 1) {
    cli_error(COMMAND, "expected a scene file: geomint maxwell run SCENE.json [--out DIR]");
    return CLI_EXIT_USAGE;
  }
  const char *path = positional[0];
  if (threads == 0 || (threads != (size_t)-1 && threads > 4096)) {
    cli_error(COMMAND, "--threads must be in [1, 4096], got %zu", threads);
    return CLI_EXIT_USAGE;
  }
  if (plot_field != NULL && plot == NULL) {
    cli_error(COMMAND, "--plot-field needs --plot FILE.png");
    return CLI_EXIT_USAGE;
  }
  if (plot != NULL && cli_plot_check_output(COMMAND, plot) != CLI_EXIT_OK) return CLI_EXIT_USAGE;
  gm_yee_scene scene;
  gm_error scene_err = {{0}};
  if (gm_yee_scene_load(path, &scene, &scene_err) != GM_OK) {
    cli_error(COMMAND, "%s", scene_err.message);
    return CLI_EXIT_USAGE;
  }
  if (threads != (size_t)-1) scene.options.n_threads = (int)threads;
  gm_yee *solver = NULL;
  if (gm_yee_scene_build(&scene, path, &solver, &scene_err) != GM_OK) {
    cli_error(COMMAND, "%s", scene_err.message);
    gm_yee_scene_clear(&scene);
    return CLI_EXIT_USAGE;
  }
  if (check) {
    status = print_check(path, &scene, solver, json);
    gm_yee_free(solver);
    gm_yee_scene_clear(&scene);
    return status;
  }
  status = mx_make_dir(COMMAND, out_dir);
  size_t steps = gm_yee_scene_total_steps(&scene, gm_yee_dt(solver));
  run_state r;
  memset(&r, 0, sizeof r);
  r.scene = &scene;
  gm_yee_writer *writer = NULL;
  char file[4096];
  if (status == CLI_EXIT_OK &&
      /* samples at step 0, every energy_every steps, and the final step when off that grid;
       * a fifth column (polarization) with dispersive media */
      (series_init(&r.energy,
                   scene.energy_every > 0
                       ? steps / scene.energy_every + 1 + (steps % scene.energy_every != 0)
                       : 0,
                   gm_yee_materials_n_dispersive(scene.materials) > 0 ? 5 : 4) != 0 ||
       series_init(&r.flux, scene.n_fluxes > 0 ? steps : 0, scene.n_fluxes) != 0)) {
    cli_error(COMMAND, "out of memory");
    status = CLI_EXIT_FAILURE;
  }
  if (status == CLI_EXIT_OK && scene.energy_every > 0)
    gm_yee_add_observer(solver, scene.energy_every, observe_energy, &r);
  if (status == CLI_EXIT_OK && scene.n_fluxes > 0) gm_yee_add_observer(solver, 1, observe_flux, &r);
  if (status == CLI_EXIT_OK && scene.snapshot_every > 0) {
    gm_error err = {{0}};
    if (gm_yee_writer_create(solver, scene.snapshot_materials ? scene.materials : NULL,
                             mx_path(file, sizeof file, out_dir, "snapshot"),
                             scene.snapshot_formats, scene.encoding, &writer, &err) != GM_OK) {
      cli_error(COMMAND, "%s", err.message);
      status = err.message[0] != '\0' && strstr(err.message, "HDF5") != NULL ? CLI_EXIT_USAGE
                                                                               : CLI_EXIT_FAILURE;
    } else {
      gm_yee_add_observer(solver, scene.snapshot_every, gm_yee_writer_observe, writer);
    }
  }
  double wall = 0;
  if (status == CLI_EXIT_OK) {
    mx_progress progress;
    mx_progress_start(&progress, steps);
    size_t chunk = steps / 200 > 0 ? steps / 200 : 1;
    double t0 = mx_now();
    for (size_t done = 0; done < steps && status == CLI_EXIT_OK;) {
      size_t k = steps - done < chunk ? steps - done : chunk;
      gm_status st = gm_yee_advance(solver, k);
      if (st != GM_OK) {
        mx_progress_end(&progress);
        if (writer != NULL && gm_yee_writer_errmsg(writer)[0] != '\0')
          cli_error(COMMAND, "%s", gm_yee_writer_errmsg(writer));
        else
          cli_error(COMMAND, "step %zu: %s", gm_yee_step(solver), gm_yee_errmsg(solver));
        status = CLI_EXIT_FAILURE;
      }
      done += k;
      mx_progress_show(&progress, done);
    }
    wall = mx_now() - t0;
    mx_progress_end(&progress);
  }
  /* the final state is observed too when it is not on the observers' grid of steps */
  if (status == CLI_EXIT_OK && writer != NULL && steps % scene.snapshot_every != 0 &&
      gm_yee_writer_write(writer, solver) != GM_OK) {
    cli_error(COMMAND, "%s", gm_yee_writer_errmsg(writer));
    status = CLI_EXIT_FAILURE;
  }
  if (status == CLI_EXIT_OK && scene.energy_every > 0 && steps % scene.energy_every != 0)
    observe_energy(&r, solver);
  /* finite fields can still give an energy that overflows (ε|E|² near the top of a double) */
  for (size_t i = 0; status == CLI_EXIT_OK && i < r.energy.n * r.energy.width; ++i)
    if (!isfinite(r.energy.values[i])) {
      cli_error(COMMAND, "the energy is not finite at t = %g: the run overflowed",
                r.energy.t[i / r.energy.width]);
      status = CLI_EXIT_FAILURE;
    }
  if (status == CLI_EXIT_OK && scene.n_probes > 0)
    status = write_probes_csv(mx_path(file, sizeof file, out_dir, "probes.csv"), &scene, solver);
  static const char *const energy_names[] = {"electric", "magnetic", "plain", "leapfrog",
                                             "polarization"};
  if (status == CLI_EXIT_OK && scene.energy_every > 0)
    status = write_series_csv(mx_path(file, sizeof file, out_dir, "energy.csv"), energy_names,
                              &r.energy);
  double *flux_integral = calloc(scene.n_fluxes + 1, sizeof *flux_integral);
  if (status == CLI_EXIT_OK && scene.n_fluxes > 0) {
    const char **names = malloc(scene.n_fluxes * sizeof *names);
    for (size_t k = 0; names != NULL && k < scene.n_fluxes; ++k) names[k] = scene.fluxes[k].name;
    status = names != NULL && flux_integral != NULL
                 ? write_series_csv(mx_path(file, sizeof file, out_dir, "flux.csv"), names, &r.flux)
                 : CLI_EXIT_FAILURE;
    free(names);
    /* ∫ flux dt by the midpoint rule: each sample is the flux at t_{n−½} */
    for (size_t i = 0; status == CLI_EXIT_OK && i < r.flux.n; ++i)
      for (size_t k = 0; k < scene.n_fluxes; ++k)
        flux_integral[k] += gm_yee_dt(solver) * r.flux.values[i * r.flux.width + k];
  }
  if (status == CLI_EXIT_OK && plot != NULL) {
    const char *field = plot_field;
    if (field == NULL) field = gm_yee_dim_has(scene.grid.dim, GM_EZ) ? "Ez" : "Hz";
    status = plot_final(plot, field, path, &scene, solver);
  }
  if (status == CLI_EXIT_OK) status = mx_write_spectra(out_dir, &scene);
  probe_result *pr = calloc(scene.n_probes + 1, sizeof *pr);
  if (status == CLI_EXIT_OK && scene.harminv && pr != NULL)
    for (size_t k = 0; k < scene.n_probes; ++k) {
      size_t n;
      const double *t, *re, *im;
      gm_yee_probe_samples(solver, k, &n, &t, &re, &im);
      size_t first = 0;
      while (first < n && t[first] < scene.harminv_after) ++first;
      const mx_harminv_params hp = {scene.harminv_basis, scene.harminv_max_error,
                                    scene.harminv_min_q, scene.harminv_min_amplitude};
      pr[k].n_modes = mx_resonances_with(re + first, n - first, gm_yee_dt(solver),
                                         scene.harminv_fmin, scene.harminv_fmax, &hp,
                                         pr[k].modes, MAX_MODES, pr[k].error,
                                         sizeof pr[k].error);
    }
  if (status == CLI_EXIT_OK && pr != NULL && flux_integral != NULL) {
    size_t n_snap = gm_yee_writer_count(writer);
    if (json)
      status = print_json(path, &scene, solver, wall, steps, pr, flux_integral, &r, out_dir, n_snap);
    else
      print_text(path, &scene, solver, wall, steps, pr, flux_integral, &r, out_dir, n_snap);
    /* the results are printed (and say which probe failed), but a failed harminv is a failed
     * run: never exit 0 */
    for (size_t k = 0; status == CLI_EXIT_OK && scene.harminv && k < scene.n_probes; ++k)
      if (pr[k].error[0] != '\0') {
        cli_error(COMMAND, "probe %s: harminv failed: %s", scene.probes[k].name, pr[k].error);
        status = CLI_EXIT_FAILURE;
      }
  }
  free(pr);
  free(flux_integral);
  series_free(&r.energy);
  series_free(&r.flux);
  gm_yee_writer_free(writer);
  gm_yee_free(solver);
  gm_yee_scene_clear(&scene);
  return status;
}
