/* `mpirun -np N geomint maxwell run SCENE.json [--out DIR] [--json] [--check] [--dims AxBxC]`:
 * the scene on the distributed Yee solver (geomint/fields_mpi.h). Every rank reads the scene and
 * runs its block; rank 0 gathers the probes and the energy series and writes probes.csv,
 * energy.csv and the summary (the same files and JSON names as the single-process run, plus the
 * process grid). Every rank exits with the same status; only rank 0 prints. Built with GM_MPI. */
#include "cli/maxwell.h"

#ifdef GM_HAVE_MPI
#include <cJSON.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/fields_mpi.h"

#define COMMAND "maxwell run"
#define MAX_MODES 32

int mx_mpi_launched(void) {
  /* set by Open MPI's mpirun (and by PMI/PMIx launchers) in every rank's environment */
  return getenv("OMPI_COMM_WORLD_SIZE") != NULL || getenv("PMI_SIZE") != NULL ||
         getenv("PMIX_RANK") != NULL;
}

/* SIGINT/SIGTERM (a wall-time limit, Ctrl-C): the run stops at the next poll, every rank at the
 * same step, and writes a checkpoint. */
static volatile sig_atomic_t stop_requested;
static void on_stop(int sig) { stop_requested = sig; }
#define POLL_STEPS 16

static int parse_dims(const char *text, int dims[3]) {
  dims[0] = dims[1] = dims[2] = 0;
  if (text == NULL) return 0;
  char *end = NULL;
  const char *p = text;
  for (int a = 0; a < 3; ++a) {
    const long v = strtol(p, &end, 10);
    if (end == p || v < 1 || v > 1 << 20) return -1;
    dims[a] = (int)v;
    if (*end == '\0') return 0;
    if (*end != 'x') return -1;
    p = end + 1;
  }
  return -1;
}

/* rank 0: probes.csv as the single-process run writes it (t, t_e, one column per probe) */
static int write_probes(const char *path, const gm_yee_scene *sc, gm_yee_mpi *m, double dt,
                        double **signals, size_t *n_out) {
  const size_t np = sc->n_probes;
  size_t n = (size_t)-1;
  double *t0 = NULL;
  int failed = 0;
  for (size_t k = 0; k < np; ++k) {
    size_t nk = 0;
    const double *t = NULL, *re = NULL;
    /* collective: every rank makes every call, whatever failed before on rank 0 */
    if (gm_yee_mpi_probe_samples(m, k, &nk, &t, &re, NULL) != GM_OK) failed = 1;
    if (gm_yee_mpi_rank(m) != 0 || failed) continue;
    signals[k] = malloc((nk + 1) * sizeof(double));
    if (k == 0) t0 = malloc((nk + 1) * sizeof(double));
    if (signals[k] == NULL || t0 == NULL) {
      failed = 1;
      continue;
    }
    memcpy(signals[k], re, nk * sizeof(double));
    if (k == 0) memcpy(t0, t, nk * sizeof(double));
    if (nk < n) n = nk;
  }
  if (gm_yee_mpi_rank(m) != 0) return CLI_EXIT_OK;
  if (failed) {
    free(t0);
    cli_error(COMMAND, "gathering the probes failed (out of memory on rank 0)");
    return CLI_EXIT_FAILURE;
  }
  *n_out = n;
  const char **names = malloc((np + 1) * sizeof *names);
  double *row = malloc((np + 1) * sizeof *row);
  gm_probe_csv *w = NULL;
  gm_error err = {{0}};
  int rc = names && row ? CLI_EXIT_OK : CLI_EXIT_FAILURE;
  if (rc == CLI_EXIT_OK) {
    names[0] = "t_e";
    for (size_t k = 0; k < np; ++k) names[k + 1] = sc->probes[k].name;
    if (gm_probe_csv_create(path, np + 1, names, &w, &err) != GM_OK) {
      cli_error(COMMAND, "%s", err.message);
      rc = CLI_EXIT_FAILURE;
    }
  }
  const double to_h = sc->probes[0].component <= GM_EZ ? 0.5 * dt : 0.0;
  for (size_t i = 0; rc == CLI_EXIT_OK && i < n; ++i) {
    const double t_h = t0[i] + to_h;
    row[0] = t_h - 0.5 * dt;
    for (size_t k = 0; k < np; ++k) row[k + 1] = signals[k][i];
    if (gm_probe_csv_write(w, t_h, row) != GM_OK) rc = CLI_EXIT_FAILURE;
  }
  if (rc == CLI_EXIT_OK && gm_probe_csv_flush(w) != GM_OK) rc = CLI_EXIT_FAILURE;
  if (rc != CLI_EXIT_OK && w != NULL) cli_error(COMMAND, "%s", gm_probe_csv_errmsg(w));
  gm_probe_csv_free(w);
  free(names);
  free(row);
  free(t0);
  return rc;
}

static int write_energy(const char *path, size_t n, const double *t, const double *rows) {
  static const char *const names[] = {"electric", "magnetic", "plain", "leapfrog"};
  gm_probe_csv *w = NULL;
  gm_error err = {{0}};
  if (gm_probe_csv_create(path, 4, names, &w, &err) != GM_OK) {
    cli_error(COMMAND, "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  int rc = CLI_EXIT_OK;
  for (size_t i = 0; rc == CLI_EXIT_OK && i < n; ++i)
    if (gm_probe_csv_write(w, t[i], rows + 4 * i) != GM_OK) rc = CLI_EXIT_FAILURE;
  if (rc == CLI_EXIT_OK && gm_probe_csv_flush(w) != GM_OK) rc = CLI_EXIT_FAILURE;
  if (rc != CLI_EXIT_OK) cli_error(COMMAND, "%s", gm_probe_csv_errmsg(w));
  gm_probe_csv_free(w);
  return rc;
}

static int run(int argc, char **argv, int rank, int size) {
  const char *out_dir = "maxwell-output", *dims_text = NULL, *plot = NULL;
  const char *ck_prefix = NULL, *restart_prefix = NULL;
  int json = 0, check = 0;
  size_t threads = 0, ck_every = 0;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &out_dir, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0},
                          {"--check", CLI_ARG_FLAG, &check, 0},
                          {"--threads", CLI_ARG_COUNT, &threads, 0},
                          {"--dims", CLI_ARG_STRING, &dims_text, 0},
                          {"--plot", CLI_ARG_STRING, &plot, 0},
                          {"--checkpoint", CLI_ARG_STRING, &ck_prefix, 0},
                          {"--checkpoint-every", CLI_ARG_COUNT, &ck_every, 0},
                          {"--restart", CLI_ARG_STRING, &restart_prefix, 0}};
  const char *positional[1];
  size_t n_pos = 0;
  int status = cli_parse(COMMAND, argc, argv, options, 9, positional, 1, &n_pos);
  if (status == CLI_HELP) {
    if (rank == 0) fputs(mx_usage(), stdout);
    return CLI_EXIT_OK;
  }
  if (status != CLI_EXIT_OK) return status;
  int dims[3];
  /* the same checks on every rank; only rank 0 says why */
  if (n_pos != 1) {
    if (rank == 0)
      cli_error(COMMAND, "expected a scene file: mpirun -np N geomint maxwell run SCENE.json");
    return CLI_EXIT_USAGE;
  }
  if (parse_dims(dims_text, dims) != 0) {
    if (rank == 0)
      cli_error(COMMAND, "--dims %s: expected ranks per axis as A, AxB or AxBxC", dims_text);
    return CLI_EXIT_USAGE;
  }
  if (plot != NULL) {
    if (rank == 0) cli_error(COMMAND, "--plot is not available over MPI yet: run on one process");
    return CLI_EXIT_USAGE;
  }
  if (ck_every > 0 && ck_prefix == NULL) {
    if (rank == 0) cli_error(COMMAND, "--checkpoint-every needs --checkpoint PREFIX");
    return CLI_EXIT_USAGE;
  }
  const char *path = positional[0];
  gm_yee_scene scene;
  gm_error err = {{0}};
  /* a file one rank cannot read (another node's view of the path) stops every rank */
  const int loaded = gm_yee_scene_load(path, &scene, &err) == GM_OK;
  const int mine = loaded ? size : rank;
  int failing = size;
  MPI_Allreduce(&mine, &failing, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (failing < size) {
    if (rank == failing && size > 1) cli_error(COMMAND, "rank %d: %s", rank, err.message);
    if (rank == failing && size == 1) cli_error(COMMAND, "%s", err.message);
    if (loaded) gm_yee_scene_clear(&scene);
    return CLI_EXIT_USAGE;
  }
  if (threads > 0) scene.options.n_threads = (int)threads;
  gm_yee_mpi *m = NULL;
  if (gm_yee_scene_build_mpi(&scene, path, MPI_COMM_WORLD, dims_text ? dims : NULL, &m, &err) !=
      GM_OK) {
    if (rank == 0) cli_error(COMMAND, "%s", err.message);
    gm_yee_scene_clear(&scene);
    return CLI_EXIT_USAGE;
  }
  int pd[3];
  gm_yee_mpi_block(m, pd, NULL, NULL, NULL, NULL);
  const double dt = gm_yee_mpi_dt(m);
  const size_t steps = gm_yee_scene_total_steps(&scene, dt);
  if (check) {
    if (rank == 0) {
      if (json) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "scene", path);
        cJSON_AddNumberToObject(o, "dt", dt);
        cJSON_AddNumberToObject(o, "steps", (double)steps);
        cJSON_AddNumberToObject(o, "ranks", size);
        const double d[3] = {pd[0], pd[1], pd[2]};
        cJSON_AddItemToObject(o, "dims", cli_json_numbers(d, 3));
        status = cli_json_print(o);
      } else {
        printf("maxwell run %s: scene is valid\n  %d ranks as %d x %d x %d, dt %.6g, %zu steps\n",
               path, size, pd[0], pd[1], pd[2], dt, steps);
      }
    }
    gm_yee_mpi_free(m);
    gm_yee_scene_clear(&scene);
    return status;
  }
  if (rank == 0) status = mx_make_dir(COMMAND, out_dir);
  MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
  char ck_default[4096];
  if (ck_prefix == NULL) ck_prefix = mx_path(ck_default, sizeof ck_default, out_dir, "checkpoint");
  if (status == CLI_EXIT_OK && restart_prefix != NULL &&
      gm_yee_mpi_checkpoint_read(m, restart_prefix) != GM_OK) {
    if (rank == 0) cli_error(COMMAND, "--restart %s: %s", restart_prefix, gm_yee_mpi_errmsg(m));
    status = CLI_EXIT_USAGE;
  }
  const size_t start = gm_yee_mpi_step(m);
  if (status == CLI_EXIT_OK && start > steps) {
    if (rank == 0)
      cli_error(COMMAND, "--restart %s: the checkpoint is at step %zu, past the run's %zu",
                restart_prefix, start, steps);
    status = CLI_EXIT_USAGE;
  }

  /* the energy series: advance to each sampling step, then the collective sum */
  const size_t every = scene.energy_every;
  const size_t n_energy = every > 0 ? steps / every + 1 + (steps % every != 0) : 0;
  double *et = calloc(n_energy + 1, sizeof *et), *ev = calloc(4 * n_energy + 1, sizeof *ev);
  size_t ne = 0;
  double wall = 0.0;
  if (status == CLI_EXIT_OK && (et == NULL || ev == NULL)) status = CLI_EXIT_FAILURE;
  if (status == CLI_EXIT_OK) {
    MPI_Barrier(MPI_COMM_WORLD);
    const double t0 = MPI_Wtime();
    for (size_t done = start; status == CLI_EXIT_OK;) {
      if (every > 0 && (done % every == 0 || done == steps)) {
        gm_yee_energy e;
        gm_yee_mpi_get_energy(m, &e);
        et[ne] = (double)done * dt;
        ev[4 * ne + 0] = e.electric;
        ev[4 * ne + 1] = e.magnetic;
        ev[4 * ne + 2] = e.plain;
        ev[4 * ne + 3] = e.leapfrog;
        ++ne;
      }
      if (done == steps) break;
      size_t k = steps - done;
      if (every > 0 && k > every - done % every) k = every - done % every;
      if (ck_every > 0 && k > ck_every - done % ck_every) k = ck_every - done % ck_every;
      if (k > POLL_STEPS) k = POLL_STEPS;
      if (gm_yee_mpi_advance(m, k) != GM_OK) {
        if (rank == 0) cli_error(COMMAND, "step %zu: %s", gm_yee_mpi_step(m), gm_yee_mpi_errmsg(m));
        status = CLI_EXIT_FAILURE;
      }
      done += k;
      /* a signal on any rank stops all of them here, at the same step */
      int sig = (int)stop_requested, any = 0;
      MPI_Allreduce(&sig, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
      const int due = ck_every > 0 && done % ck_every == 0 && done < steps;
      if (status == CLI_EXIT_OK && (any || due)) {
        if (gm_yee_mpi_checkpoint_write(m, ck_prefix) != GM_OK) {
          if (rank == 0) cli_error(COMMAND, "%s", gm_yee_mpi_errmsg(m));
          status = CLI_EXIT_FAILURE;
        } else if (any) {
          if (rank == 0)
            cli_error(COMMAND, "interrupted at step %zu of %zu: checkpoint %s written (continue "
                      "with --restart %s)", done, steps, ck_prefix, ck_prefix);
          status = CLI_EXIT_INTERRUPTED;
        }
      }
    }
    wall = MPI_Wtime() - t0;
  }

  char file[4096];
  const size_t np = scene.n_probes;
  double **signals = calloc(np + 1, sizeof *signals);
  size_t n_samples = 0;
  if (status == CLI_EXIT_OK && np > 0)
    status = signals ? write_probes(mx_path(file, sizeof file, out_dir, "probes.csv"), &scene, m,
                                    dt, signals, &n_samples)
                     : CLI_EXIT_FAILURE;
  if (status == CLI_EXIT_OK && rank == 0 && every > 0)
    status = write_energy(mx_path(file, sizeof file, out_dir, "energy.csv"), ne, et, ev);
  MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (status == CLI_EXIT_OK && rank == 0) {
    const double cells = (double)scene.grid.n[0] * (double)scene.grid.n[1] * (double)scene.grid.n[2];
    cJSON *o = json ? cJSON_CreateObject() : NULL;
    if (o) {
      cJSON_AddStringToObject(o, "scene", path);
      cJSON_AddNumberToObject(o, "ranks", size);
      const double d[3] = {pd[0], pd[1], pd[2]};
      cJSON_AddItemToObject(o, "dims", cli_json_numbers(d, 3));
      cJSON_AddNumberToObject(o, "dt", dt);
      cJSON_AddNumberToObject(o, "steps", (double)steps);
      cJSON_AddNumberToObject(o, "t_final", (double)steps * dt);
      cJSON_AddNumberToObject(o, "wall_s", wall);
      cJSON_AddNumberToObject(o, "exchange_bytes_per_step_rank0",
                              (double)gm_yee_mpi_bytes_per_step(m));
      cJSON_AddStringToObject(o, "out", out_dir);
      if (ne > 0) {
        cJSON *e = cJSON_AddObjectToObject(o, "energy");
        cJSON_AddItemToObject(e, "initial", cli_json_number(ev[2]));
        cJSON_AddItemToObject(e, "final", cli_json_number(ev[4 * (ne - 1) + 2]));
        cJSON_AddItemToObject(e, "final_leapfrog", cli_json_number(ev[4 * (ne - 1) + 3]));
        cJSON_AddNumberToObject(e, "samples", (double)ne);
      }
    } else {
      printf("maxwell run %s: %zu x %zu x %zu cells on %d ranks (%d x %d x %d)\n", path,
             scene.grid.n[0], scene.grid.n[1], scene.grid.n[2], size, pd[0], pd[1], pd[2]);
      printf("  dt %.6g, %zu steps to t = %.6g in %.3f s (%.1f Mcells*steps/s)\n", dt, steps,
             (double)steps * dt, wall, wall > 0 ? cells * (double)steps / wall / 1e6 : 0.0);
      if (ne > 0)
        printf("  energy (electric + magnetic): %.9g at t = %.6g, %.9g at t = %.6g\n", ev[2],
               et[0], ev[4 * (ne - 1) + 2], et[ne - 1]);
    }
    cJSON *probes = o ? cJSON_AddArrayToObject(o, "probes") : NULL;
    for (size_t k = 0; k < np; ++k) {
      gm_harminv_mode modes[MAX_MODES];
      char msg[256] = "";
      size_t n_modes = 0;
      if (scene.harminv) {
        size_t first = 0;
        const double to_t = scene.probes[k].component <= GM_EZ ? -0.5 * dt : 0.0;
        while (first < n_samples && (double)(first + 1) * dt + to_t < scene.harminv_after) ++first;
        const mx_harminv_params hp = {scene.harminv_basis, scene.harminv_max_error,
                                      scene.harminv_min_q, scene.harminv_min_amplitude};
        n_modes = mx_resonances_with(signals[k] + first, n_samples - first, dt,
                                     scene.harminv_fmin, scene.harminv_fmax, &hp, modes,
                                     MAX_MODES, msg, sizeof msg);
      }
      if (probes) {
        cJSON *p = cJSON_CreateObject();
        cJSON_AddStringToObject(p, "name", scene.probes[k].name);
        cJSON_AddStringToObject(p, "component", gm_yee_component_name(scene.probes[k].component));
        if (scene.harminv) {
          if (msg[0] != '\0') cJSON_AddStringToObject(p, "harminv_error", msg);
          cJSON *ms = cJSON_AddArrayToObject(p, "resonances");
          for (size_t i = 0; i < n_modes; ++i) {
            cJSON *md = cJSON_CreateObject();
            cJSON_AddItemToObject(md, "frequency", cli_json_number(modes[i].frequency));
            cJSON_AddItemToObject(md, "decay", cli_json_number(modes[i].decay));
            cJSON_AddItemToObject(md, "q", cli_json_number(modes[i].q));
            cJSON_AddItemToObject(md, "amplitude", cli_json_number(modes[i].amplitude));
            cJSON_AddItemToObject(md, "error", cli_json_number(modes[i].error));
            cJSON_AddItemToArray(ms, md);
          }
        }
        cJSON_AddItemToArray(probes, p);
      } else if (scene.harminv) {
        printf("  probe %s (%s): ", scene.probes[k].name,
               gm_yee_component_name(scene.probes[k].component));
        if (msg[0] != '\0') {
          printf("harminv failed: %s\n", msg);
          continue;
        }
        printf("%zu resonances in [%g, %g]\n", n_modes, scene.harminv_fmin, scene.harminv_fmax);
        for (size_t i = 0; i < n_modes; ++i)
          printf("    %14.9f %12.4g %12.4g %12.4g %10.2g\n", modes[i].frequency, modes[i].decay,
                 modes[i].q, modes[i].amplitude, modes[i].error);
      }
    }
    if (o)
      status = cli_json_print(o);
    else
      printf("  wrote %s/:%s%s\n", out_dir, np > 0 ? " probes.csv" : "",
             ne > 0 ? " energy.csv" : "");
  }
  for (size_t k = 0; signals && k < np; ++k) free(signals[k]);
  free(signals);
  free(et);
  free(ev);
  gm_yee_mpi_free(m);
  gm_yee_scene_clear(&scene);
  return status;
}

int mx_run_mpi_main(int argc, char **argv) {
  MPI_Init(NULL, NULL);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  /* from here on a SIGINT/SIGTERM only sets the flag the run polls (a signal during the setup
   * stops the run at its first poll, with a checkpoint) */
  stop_requested = 0;
  void (*old_int)(int) = signal(SIGINT, on_stop);
  void (*old_term)(int) = signal(SIGTERM, on_stop);
  int status = run(argc, argv, rank, size);
  signal(SIGINT, old_int);
  signal(SIGTERM, old_term);
  /* the same exit status on every rank (the worst one) */
  int worst = status;
  MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  fflush(stdout);
  MPI_Finalize();
  return worst;
}
#else
typedef int mx_run_mpi_unused; /* an MPI-less build compiles nothing here */
#endif
