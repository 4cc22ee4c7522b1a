/* The Yee solver over MPI against the single-process solver (run by mpirun at 1, 2, 3, 4 and 8
 * ranks, tests/CMakeLists.txt): fields and probes bitwise equal, energy to round-off, on 1-D,
 * 2-D and 3-D scenes with CPML, periodic, PEC and PMC faces, materials and sources across rank
 * boundaries, for the automatic process grid and for grids split along one axis; and a bad
 * input on one rank stops every rank with that rank's message. Not Criterion: Criterion forks
 * each test, which an MPI process must not do. Exit status 0 when everything holds. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/fields.h"
#include "geomint/fields_mpi.h"

static int g_rank, g_size, g_failures;

#define CHECK(cond, ...)                                                                        \
  do {                                                                                         \
    if (!(cond)) {                                                                             \
      fprintf(stderr, "rank %d: %s:%d: ", g_rank, __FILE__, __LINE__);                        \
      fprintf(stderr, __VA_ARGS__);                                                            \
      fprintf(stderr, "\n");                                                                   \
      ++g_failures;                                                                            \
    }                                                                                          \
  } while (0)

typedef struct scene {
  const char *name;
  gm_yee_grid grid;
  gm_yee_options opt;
  int materials;  /* paint a dielectric sphere, a lossy magnetic box */
  size_t steps;
} scene;

static double initial_ey(void *ctx, const double x[3]) {
  (void)ctx;
  return exp(-((x[0] - 2.0) * (x[0] - 2.0) + (x[1] - 1.5) * (x[1] - 1.5)));
}

static gm_yee_materials *paint(const scene *sc) {
  gm_yee_materials *m = NULL;
  gm_error err;
  if (gm_yee_materials_create(&sc->grid, &m, &err) != GM_OK) return NULL;
  const gm_medium glass = {2.5, 1.0, 0.0}, lossy = {1.5, 1.7, 0.3};
  /* the sphere straddles the middle planes, where 2, 4 and 8 ranks cut */
  const double c[3] = {sc->grid.origin[0] + 0.5 * (double)sc->grid.n[0] * sc->grid.h[0],
                       sc->grid.origin[1] + 0.5 * (double)sc->grid.n[1] * sc->grid.h[1],
                       sc->grid.origin[2] + 0.5 * (double)sc->grid.n[2] * sc->grid.h[2]};
  gm_yee_paint_sphere(m, c, 2.2 * sc->grid.h[0], &glass);
  const double lo[3] = {c[0] - 1.0, c[1], c[2] - 1.5}, hi[3] = {c[0] + 0.6, c[1] + 2.0, c[2]};
  gm_yee_paint_box(m, lo, hi, &lossy);
  return m;
}

/* Sources and probes of a scene, added identically to both solvers. */
static void add_all(const scene *sc, gm_yee *serial, gm_yee_mpi *dist) {
  const int three = sc->grid.dim == GM_YEE_3D;
  const double mid[3] = {sc->grid.origin[0] + 0.5 * (double)sc->grid.n[0] * sc->grid.h[0],
                         sc->grid.origin[1] + 0.5 * (double)sc->grid.n[1] * sc->grid.h[1],
                         sc->grid.origin[2] + 0.5 * (double)sc->grid.n[2] * sc->grid.h[2]};
  gm_point_source src[2];
  memset(src, 0, sizeof src);
  const int te = sc->grid.dim == GM_YEE_2D_TE;
  src[0].component = te ? GM_EX : GM_EZ;
  for (int a = 0; a < 3; ++a) src[0].x[a] = mid[a]; /* on the cut planes */
  src[0].mode = GM_SOURCE_SOFT;
  src[0].wave = (gm_waveform){.kind = GM_WAVE_GAUSSIAN, .amplitude = 1.0, .frequency = 0.4,
                              .width = 1.5, .delay = 4.0};
  src[1].component = te ? GM_HZ : GM_HY;
  src[1].x[0] = mid[0] - 1.3;
  src[1].x[1] = mid[1] + 0.7;
  src[1].x[2] = mid[2];
  src[1].mode = three ? GM_SOURCE_HARD : GM_SOURCE_SOFT;
  src[1].wave = (gm_waveform){.kind = GM_WAVE_RICKER, .amplitude = 0.5, .frequency = 0.3,
                              .delay = 3.0};
  for (int i = 0; i < 2; ++i) {
    if (serial) CHECK(gm_yee_add_point_source(serial, &src[i], NULL) == GM_OK, "%s: serial src %d: %s",
                      sc->name, i, gm_yee_errmsg(serial));
    CHECK(gm_yee_mpi_add_point_source(dist, &src[i], NULL) == GM_OK, "%s: mpi src %d: %s",
          sc->name, i, gm_yee_mpi_errmsg(dist));
  }
  const gm_yee_component pc[3] = {te ? GM_EY : GM_EZ, te ? GM_HZ : GM_HY, te ? GM_EX : GM_EZ};
  const double px[3][3] = {{mid[0] + 0.9, mid[1] - 0.4, mid[2] + 0.3},
                           {sc->grid.origin[0] + 0.2, mid[1], mid[2]},
                           {mid[0] + 0.1, mid[1] + 0.1, mid[2] - 0.6}};
  for (int i = 0; i < 3; ++i) {
    if (serial) CHECK(gm_yee_add_probe(serial, pc[i], px[i], sc->steps, NULL) == GM_OK,
                      "%s: serial probe", sc->name);
    CHECK(gm_yee_mpi_add_probe(dist, pc[i], px[i], sc->steps, NULL) == GM_OK, "%s: mpi probe: %s",
          sc->name, gm_yee_mpi_errmsg(dist));
  }
}

static void compare(const scene *sc, const int *dims) {
  gm_yee_materials *mat = sc->materials ? paint(sc) : NULL;
  gm_error err;
  gm_yee *serial = NULL;
  if (g_rank == 0)
    CHECK(gm_yee_create(&sc->grid, mat, &sc->opt, &serial, &err) == GM_OK, "%s: serial: %s",
          sc->name, err.message);
  gm_yee_mpi *dist = NULL;
  const gm_status st = gm_yee_mpi_create(&sc->grid, mat, &sc->opt, MPI_COMM_WORLD, dims, &dist, &err);
  CHECK(st == GM_OK, "%s: mpi create: %s", sc->name, err.message);
  if (st != GM_OK) {
    gm_yee_free(serial);
    gm_yee_materials_free(mat);
    return;
  }
  add_all(sc, serial, dist);
  const gm_yee_component init = sc->grid.dim == GM_YEE_2D_TM || sc->grid.dim == GM_YEE_1D ? GM_EZ : GM_EY;
  if (serial) CHECK(gm_yee_set_field_fn(serial, init, 0, initial_ey, NULL) == GM_OK, "set");
  CHECK(gm_yee_mpi_set_field_fn(dist, init, 0, initial_ey, NULL) == GM_OK, "mpi set: %s",
        gm_yee_mpi_errmsg(dist));
  /* in two runs, so that a run split into advances is checked too */
  if (serial) CHECK(gm_yee_advance(serial, sc->steps) == GM_OK, "serial advance");
  CHECK(gm_yee_mpi_advance(dist, sc->steps / 3) == GM_OK, "mpi advance: %s", gm_yee_mpi_errmsg(dist));
  CHECK(gm_yee_mpi_advance(dist, sc->steps - sc->steps / 3) == GM_OK, "mpi advance");
  gm_yee_layout G;
  gm_yee_mpi_global_layout(dist, &G);
  double *out = g_rank == 0 ? malloc(G.size * sizeof(double)) : NULL;
  size_t differ = 0, compared = 0;
  for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
    if (!gm_yee_dim_has(sc->grid.dim, (gm_yee_component)c)) continue;
    CHECK(gm_yee_mpi_gather_field(dist, (gm_yee_component)c, 0, out) == GM_OK, "gather");
    if (g_rank != 0) continue;
    const double *ref = gm_yee_field(serial, (gm_yee_component)c, 0);
    size_t cnt[3];
    gm_yee_component_count(&G, (gm_yee_component)c, cnt);
    for (size_t k = 0; k < cnt[2]; ++k)
      for (size_t j = 0; j < cnt[1]; ++j)
        for (size_t i = 0; i < cnt[0]; ++i) {
          const size_t q = gm_yee_index(&G, (long)i, (long)j, (long)k);
          ++compared;
          if (memcmp(&ref[q], &out[q], sizeof(double)) != 0) {
            if (differ < 5)
              fprintf(stderr, "%s: %s (%zu,%zu,%zu): %.17g vs %.17g\n", sc->name,
                      gm_yee_component_name((gm_yee_component)c), i, j, k, ref[q], out[q]);
            ++differ;
          }
        }
  }
  if (g_rank == 0)
    CHECK(differ == 0, "%s (dims %s): %zu of %zu field values differ from one process", sc->name,
          dims ? "given" : "auto", differ, compared);
  double norm = 0.0;
  for (size_t p = 0; p < 3; ++p) { /* add_all's three probes */
    size_t n = 0, ns = 0;
    const double *t = NULL, *re = NULL, *ts = NULL, *res = NULL;
    CHECK(gm_yee_mpi_probe_samples(dist, p, &n, &t, &re, NULL) == GM_OK, "probe samples");
    if (g_rank != 0) continue;
    gm_yee_probe_samples(serial, p, &ns, &ts, &res, NULL);
    CHECK(n == ns && n == sc->steps, "%s: probe %zu: %zu samples vs %zu", sc->name, p, n, ns);
    CHECK(n == ns && memcmp(t, ts, n * sizeof *t) == 0 && memcmp(re, res, n * sizeof *re) == 0,
          "%s: probe %zu differs from one process", sc->name, p);
    for (size_t i = 0; i < ns; ++i) norm = fmax(norm, fabs(res[i]));
  }
  if (g_rank == 0) CHECK(norm > 1e-6, "%s: the probes saw nothing (max %g)", sc->name, norm);
  gm_yee_energy es = {0}, ed;
  if (serial) gm_yee_get_energy(serial, &es);
  CHECK(gm_yee_mpi_get_energy(dist, &ed) == GM_OK, "energy");
  if (g_rank == 0) {
    /* measured: relative differences <= 2.6e-15 at 2-8 ranks (summation order only) */
    CHECK(fabs(ed.leapfrog - es.leapfrog) <= 1e-14 * fabs(es.leapfrog) &&
              fabs(ed.plain - es.plain) <= 1e-14 * fabs(es.plain) && es.plain > 0.0,
          "%s: energy %.17g vs %.17g (leapfrog %.17g vs %.17g)", sc->name, ed.plain, es.plain,
          ed.leapfrog, es.leapfrog);
  }
  free(out);
  gm_yee_mpi_free(dist);
  gm_yee_free(serial);
  gm_yee_materials_free(mat);
}

/* A run cut by a checkpoint and continued in a new solver equals the uninterrupted one. */
static void restart(const scene *sc) {
  gm_yee_materials *mat = sc->materials ? paint(sc) : NULL;
  gm_error err;
  gm_yee_mpi *a = NULL, *b = NULL;
  CHECK(gm_yee_mpi_create(&sc->grid, mat, &sc->opt, MPI_COMM_WORLD, NULL, &a, &err) == GM_OK &&
            gm_yee_mpi_create(&sc->grid, mat, &sc->opt, MPI_COMM_WORLD, NULL, &b, &err) == GM_OK,
        "restart: create: %s", err.message);
  if (a == NULL || b == NULL) return;
  add_all(sc, NULL, a);
  add_all(sc, NULL, b);
  const size_t cut = sc->steps / 2;
  char prefix[256];
  snprintf(prefix, sizeof prefix, "test_yee_mpi_ck_%d", g_size);
  CHECK(gm_yee_mpi_advance(a, cut) == GM_OK, "restart: advance");
  CHECK(gm_yee_mpi_checkpoint_write(a, prefix) == GM_OK, "checkpoint: %s", gm_yee_mpi_errmsg(a));
  CHECK(gm_yee_mpi_advance(a, sc->steps - cut) == GM_OK, "restart: advance");
  CHECK(gm_yee_mpi_checkpoint_read(b, prefix) == GM_OK, "read: %s", gm_yee_mpi_errmsg(b));
  CHECK(gm_yee_mpi_step(b) == cut, "restart: step %zu, expected %zu", gm_yee_mpi_step(b), cut);
  CHECK(gm_yee_mpi_advance(b, sc->steps - cut) == GM_OK, "restart: advance: %s",
        gm_yee_mpi_errmsg(b));
  gm_yee_layout G;
  gm_yee_mpi_global_layout(a, &G);
  double *fa = g_rank == 0 ? calloc(G.size, sizeof(double)) : NULL;
  double *fb = g_rank == 0 ? calloc(G.size, sizeof(double)) : NULL;
  for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
    if (!gm_yee_dim_has(sc->grid.dim, (gm_yee_component)c)) continue;
    gm_yee_mpi_gather_field(a, (gm_yee_component)c, 0, fa);
    gm_yee_mpi_gather_field(b, (gm_yee_component)c, 0, fb);
    if (g_rank == 0)
      CHECK(memcmp(fa, fb, G.size * sizeof(double)) == 0, "restart: %s differs",
            gm_yee_component_name((gm_yee_component)c));
  }
  for (size_t p = 0; p < 3; ++p) {
    size_t na = 0, nb = 0;
    const double *ra = NULL, *rb = NULL;
    gm_yee_mpi_probe_samples(a, p, &na, NULL, &ra, NULL);
    double *copy = g_rank == 0 ? malloc((na + 1) * sizeof(double)) : NULL;
    if (copy) memcpy(copy, ra, na * sizeof(double));
    gm_yee_mpi_probe_samples(b, p, &nb, NULL, &rb, NULL);
    if (g_rank == 0)
      CHECK(na == sc->steps && na == nb && memcmp(copy, rb, na * sizeof(double)) == 0,
            "restart: probe %zu differs (%zu vs %zu samples)", p, na, nb);
    free(copy);
  }
  /* a checkpoint of another problem is refused on every rank */
  gm_yee_grid other = sc->grid;
  other.n[1] += 2;
  gm_yee_mpi *c = NULL;
  CHECK(gm_yee_mpi_create(&other, NULL, &sc->opt, MPI_COMM_WORLD, NULL, &c, &err) == GM_OK,
        "create other");
  if (c) {
    const gm_status st = gm_yee_mpi_checkpoint_read(c, prefix);
    CHECK(st == GM_EINVAL && strstr(gm_yee_mpi_errmsg(c), "another solver"),
          "foreign checkpoint: status %d '%s'", (int)st, gm_yee_mpi_errmsg(c));
  }
  gm_yee_mpi_free(c);
  char path[300];
  snprintf(path, sizeof path, "%s.rank%dof%d", prefix, g_rank, g_size);
  remove(path);
  free(fa);
  free(fb);
  gm_yee_mpi_free(a);
  gm_yee_mpi_free(b);
  gm_yee_materials_free(mat);
}

/* A bad input on the last rank only: every rank fails, with that rank's message. */
static void bad_input(void) {
  gm_yee_grid grid = {.dim = GM_YEE_3D, .n = {8, 8, 8}, .h = {0.5, 0.5, 0.5}};
  gm_error err;
  gm_yee_mpi *dist = NULL;
  gm_yee_grid mine = grid;
  if (g_rank == g_size - 1 && g_size > 1) mine.n[2] = 9;
  gm_status st = gm_yee_mpi_create(&mine, NULL, NULL, MPI_COMM_WORLD, NULL, &dist, &err);
  if (g_size > 1) {
    char want[64];
    snprintf(want, sizeof want, "rank %d: ", g_size - 1);
    CHECK(st == GM_EINVAL && dist == NULL && strstr(err.message, want) == err.message &&
              strstr(err.message, "differ from rank 0"),
          "disagreeing grids: status %d, message '%s'", (int)st, err.message);
  }
  if (st == GM_OK) gm_yee_mpi_free(dist);
  st = gm_yee_mpi_create(&grid, NULL, NULL, MPI_COMM_WORLD, NULL, &dist, &err);
  CHECK(st == GM_OK, "create: %s", err.message);
  if (st != GM_OK) return;
  gm_point_source ps = {.component = GM_EZ, .x = {1.0, 1.0, 1.0}, .mode = GM_SOURCE_SOFT,
                        .wave = {.kind = GM_WAVE_GAUSSIAN, .amplitude = 1, .width = 1, .delay = 3}};
  if (g_rank == g_size - 1) ps.x[1] = 40.0; /* outside, on one rank only */
  st = gm_yee_mpi_add_point_source(dist, &ps, NULL);
  CHECK(st == GM_EINVAL && strstr(gm_yee_mpi_errmsg(dist), "outside the grid"),
        "source outside on one rank: status %d, '%s'", (int)st, gm_yee_mpi_errmsg(dist));
  /* the solver still runs afterwards, on every rank */
  CHECK(gm_yee_mpi_advance(dist, 3) == GM_OK, "advance after a refused source");
  /* a probe without room for the run: refused on every rank before any step */
  const double x[3] = {2.0, 2.0, 2.0};
  CHECK(gm_yee_mpi_add_probe(dist, GM_HX, x, 2, NULL) == GM_OK, "probe");
  st = gm_yee_mpi_advance(dist, 5);
  CHECK(st == GM_EINVAL && gm_yee_mpi_step(dist) == 3, "probe capacity: status %d", (int)st);
  /* a CPML thicker than a rank's block */
  gm_yee_options o = gm_yee_defaults();
  o.boundary[GM_FACE_XLO].kind = GM_BOUNDARY_CPML;
  o.boundary[GM_FACE_XLO].pml.thickness = 5;
  const int dims[3] = {g_size, 1, 1};
  gm_yee_mpi *bad = NULL;
  st = gm_yee_mpi_create(&grid, NULL, &o, MPI_COMM_WORLD, dims, &bad, &err);
  if (g_size >= 2)
    CHECK(st == GM_EINVAL && strstr(err.message, "CPML on face -x"), "thick CPML: '%s'",
          err.message);
  gm_yee_mpi_free(bad);
  /* a process grid that does not fit the ranks */
  const int too_many[3] = {g_size + 1, 1, 1};
  bad = NULL;
  st = gm_yee_mpi_create(&grid, NULL, NULL, MPI_COMM_WORLD, too_many, &bad, &err);
  CHECK(st == GM_EINVAL && bad == NULL && strstr(err.message, "do not fit"), "bad dims: '%s'",
        err.message);
  const int free_y[3] = {1, 0, 1};
  st = gm_yee_mpi_create(&grid, NULL, NULL, MPI_COMM_WORLD, free_y, &bad, &err);
  int got[3] = {0, 0, 0};
  if (st == GM_OK) gm_yee_mpi_block(bad, got, NULL, NULL, NULL, NULL);
  CHECK(st == GM_OK && got[0] == 1 && got[1] == g_size && got[2] == 1, "dims 1x0x1: %d x %d x %d",
        got[0], got[1], got[2]);
  gm_yee_mpi_free(bad);
  gm_yee_mpi_free(dist);
}

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
  gm_yee_options cube = gm_yee_defaults();
  cube.smoothing = GM_YEE_SMOOTHING_NONE; /* refused with materials over MPI (not decomposed) */
  /* x: CPML, y: periodic, z: PEC below, PMC above */
  for (int f = 0; f < 2; ++f) {
    cube.boundary[f].kind = GM_BOUNDARY_CPML;
    cube.boundary[f].pml.thickness = 3;
    cube.boundary[2 + f].kind = GM_BOUNDARY_PERIODIC;
  }
  cube.boundary[GM_FACE_ZHI].kind = GM_BOUNDARY_PMC;
  const scene s3 = {"3-D", {GM_YEE_3D, {16, 10, 9}, {0.5, 0.5, 0.5}, {-1.0, 0.0, 0.25}}, cube, 1,
                    36};
  compare(&s3, NULL);
  restart(&s3);
  const int along_y[3] = {1, g_size, 1}, along_z[3] = {1, 1, g_size};
  if (g_size <= 4) {
    compare(&s3, along_y);
    compare(&s3, along_z);
  }
  gm_yee_options sq = cube;
  sq.boundary[GM_FACE_YLO].kind = GM_BOUNDARY_PEC;
  sq.boundary[GM_FACE_YHI].kind = GM_BOUNDARY_PMC;
  const scene tm = {"2-D TM", {GM_YEE_2D_TM, {24, 20, 1}, {0.25, 0.25, 1.0}, {0, 0, 0}}, sq, 1, 40};
  const scene te = {"2-D TE", {GM_YEE_2D_TE, {24, 20, 1}, {0.25, 0.25, 1.0}, {0, 0, 0}}, cube, 1, 40};
  compare(&tm, NULL);
  compare(&te, NULL);
  /* subpixel smoothing (the default) with the sphere and box across the cuts: each block
     smooths from the whole grid's shapes, the overlap cells' coupled E from the neighbours */
  scene s3s = s3, tms = tm, tes = te;
  s3s.name = "3-D smoothed";
  tms.name = "2-D TM smoothed";
  tes.name = "2-D TE smoothed";
  s3s.opt.smoothing = tms.opt.smoothing = tes.opt.smoothing = GM_YEE_SMOOTHING_ANISOTROPIC;
  compare(&s3s, NULL);
  restart(&s3s); /* the checkpoint carries the coupling's D and E_saved */
  if (g_size <= 4) {
    compare(&s3s, along_y);
    compare(&s3s, along_z);
  }
  compare(&tms, NULL);
  compare(&tes, NULL);
  gm_yee_options line = gm_yee_defaults();
  line.smoothing = GM_YEE_SMOOTHING_NONE;
  line.boundary[0].kind = line.boundary[1].kind = GM_BOUNDARY_PERIODIC;
  const scene s1 = {"1-D", {GM_YEE_1D, {48, 1, 1}, {0.25, 1, 1}, {0, 0, 0}}, line, 1, 60};
  compare(&s1, NULL);
  bad_input();
  int total = 0;
  MPI_Allreduce(&g_failures, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (g_rank == 0) printf("test_yee_mpi: %d ranks, %d failure(s)\n", g_size, total);
  MPI_Finalize();
  return total == 0 ? 0 : 1;
}
