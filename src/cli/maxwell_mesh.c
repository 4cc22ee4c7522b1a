/* geomint maxwell mesh FILE.msh [--avi] ...: PEC cavity on a triangle or tetrahedron mesh with
 * random initial E (seed 000 E4/E5), the Bossavit–Kettunen leapfrog or the AVI; prints the run's
 * invariants, writes the energy series (CSV), a probe signal's harminv resonances and VTU
 * snapshots. */
#include <cJSON.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/maxwell.h"
#include "cli/maxwell_mesh.h"

static const char usage[] =
    "usage: geomint maxwell mesh FILE.msh [options]\n"
    "       geomint maxwell mesh --rect NX [--ly LY] [--warp W] [options]\n\n"
    "PEC cavity on a mesh of triangles (2-D TE: E on edges, Bz on triangles) or tetrahedra,\n"
    "random initial E, run with the Bossavit-Kettunen leapfrog (default) or the asynchronous\n"
    "variational integrator (--avi: every face its own step, a fraction of its local limit).\n"
    "--rect NX generates [0,1]x[0,LY] with near-equilateral triangles, NX columns (at most 1000);\n"
    "--warp W "
    "draws the x and y partitions at random (spacings in [1-W, 1+W]).\n\n"
    "options:\n"
    "  --avi              the AVI (diagonal star only)\n"
    "  --fraction F       AVI: step of each face = F x its local CFL limit, in [1e-4, 1]\n"
    "                     (default 0.1)\n"
    "  --courant C        leapfrog: dt = C x the CFL limit (default 0.9)\n"
    "  --dt DT            leapfrog: this step (refused above the CFL limit)\n"
    "  --whitney          Whitney (consistent) star, CHOLMOD; for meshes that are not\n"
    "                     well-centred (leapfrog, uniform materials)\n"
    "  --allow-negative-stars  run the diagonal star on a mesh that is not well-centred\n"
    "  --material X0,Y0[,Z0],X1,Y1[,Z1],EPS,MU\n"
    "                     epsilon and mu in a box (the cells whose centroid lies in it;\n"
    "                     repeatable, a later box wins; vacuum elsewhere; EPS, MU in [1e-6, 1e6])\n"
    "  --t-end T          final time (default 8; at most 1e9 steps of dt, or of the AVI's\n"
    "                     smallest face step)\n"
    "  --samples N        energy/probe samples over the run (default 1000, at most 1e7)\n"
    "  --seed S           random initial E (default 1)\n"
    "  --energy FILE.csv  t, electric, magnetic, plain, leapfrog energy per sample\n"
    "  --probe X,Y[,Z]    record E_x there and print its harminv resonances in (0, --fmax]\n"
    "  --fmax F           (default 2)\n"
    "  --vtu PREFIX       write PREFIX_0000.vtu .. (E on edges, B on faces) at N times\n"
    "                     spread over the run, the last at its end, and PREFIX.pvd (ParaView\n"
    "                     time series: the files with their times)\n"
    "  --snapshots N      (default 4; 1: the final state only)\n"
    "  --exact-steps      AVI: every face exactly F x its limit (default: rounded down to\n"
    "                     power-of-two levels of the smallest step, faster per update)\n"
    "  --e5               seed 000 E5 on FILE.msh, a Gmsh box cavity refined near the walls\n"
    "                     (examples/e5_cavity.msh, Delaunay: positive diagonal stars): the AVI\n"
    "                     (F default 0.25) and the Whitney leapfrog, spectra against the\n"
    "                     analytic resonances, then the cost of the AVI against uniform\n"
    "                     stepping at its smallest step; --t-end (use 60), --fmax, --seed apply\n"
    "  --sample S         (--e5) the AVI's probe interval (default 0.005)\n"
    "  --t-compare T      (--e5) the final time of the cost comparison (default 1)\n"
    "  --out DIR          (--e5) write e5-spectrum.png there\n"
    "  --json             print one JSON object instead of the text\n\n"
    "A run that blows up stops with exit status 1 and says when: the AVI when its energy\n"
    "passes 10 x its initial value (no source injects any), either scheme when the fields\n"
    "become non-finite. On a terminal a progress line is shown.\n\n"
    "Exit status: 0 success, 1 the run failed or blew up, 2 bad arguments or mesh.\n";

/* Documented bounds (usage text): they keep a run's memory and time within reach. */
#define MM_MIN_FRACTION 1e-4
#define MM_MAX_RECT 1000
#define MM_BYTES_PER_TRIANGLE 700 /* peak RSS of --rect 500 --t-end 0.01: 277 MB, 404 000 triangles */
#define MM_MAX_SAMPLES 10000000
#define MM_MAX_STEPS 1e9
#define MM_MIN_MATERIAL 1e-6
#define MM_MAX_MATERIAL 1e6

static double mm_rect_triangles(size_t rect, double ly) {
  const double ny = fmax(1.0, round(ly * 2.0 * (double)rect / sqrt(3.0)));
  return 2.0 * (double)rect * ny;
}

static double rnd(uint64_t *z) {
  uint64_t x = (*z += 0x9e3779b97f4a7c15ull);
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  x ^= x >> 31;
  return (double)(x >> 11) / 9007199254740992.0 - 0.5;
}

int mm_guard_check(mm_guard *g, double t, double plain) {
  if (!g->started) {
    g->started = 1;
    g->e0 = plain;
    g->max_ratio = isfinite(plain) ? 1.0 : NAN;
  }
  const double ratio = g->e0 != 0.0 ? fabs(plain) / fabs(g->e0) : 0.0;
  if (isnan(ratio) || ratio > g->max_ratio) g->max_ratio = ratio;
  if (isfinite(plain) && ratio <= g->limit) return 0;
  g->fired = 1;
  if (isfinite(plain))
    cli_error(g->command, "the run blew up at t = %.6g: the field energy is %.3g x its initial "
              "value (the limit is %g; nothing here injects energy)%s", t, ratio, g->limit,
              g->advice);
  else
    cli_error(g->command, "the run blew up at t = %.6g: the field energy is non-finite (%g x its "
              "initial value)%s", t, ratio, g->advice);
  return 1;
}

gm_status mm_advance_progress(gm_mesh_maxwell *s, double t) {
  enum { PIECES = 200 };
  const int avi = gm_mesh_maxwell_avi_groups(s) > 0;
  const double t0 = gm_mesh_maxwell_time(s);
  const size_t step0 = gm_mesh_maxwell_step(s);
  mx_progress p;
  mx_progress_start(&p, avi ? 0 : (size_t)floor(t / gm_mesh_maxwell_dt(s) * (1.0 + 1e-14)) - step0);
  gm_status st = GM_OK;
  for (size_t k = 1; k <= PIECES && st == GM_OK; ++k) {
    st = gm_mesh_maxwell_advance_to(s, k == PIECES ? t : t0 + (t - t0) * (double)k / PIECES);
    const size_t done = gm_mesh_maxwell_step(s) - step0;
    if (avi) p.total = done * PIECES / k; /* extrapolated: updates per unit time are ~constant */
    if (done > p.total) p.total = done;
    mx_progress_show(&p, done);
  }
  mx_progress_end(&p);
  return st;
}

/* max(m, x) that keeps a NaN once seen (fmax drops it: a blown-up run would look clean) */
static double max_nan(double m, double x) {
  if (isnan(m)) return m;
  return isnan(x) || x > m ? x : m;
}

typedef struct run_ctx {
  FILE *energy;
  const gm_complex *cx;
  const char *vtu;
  size_t snapshots, written;
  double *snap_t;       /* snapshots: the time of each file written (for the .pvd) */
  double t_end, sample; /* sample: the observer's interval */
  double max_dev;
  double *Bsync;
  mm_guard guard;
  int failed;
} run_ctx;

/* PREFIX_NNNN.vtu of the current fields, and PREFIX.pvd (ParaView's time series) rewritten
 * whole so that it lists every file written so far with its time. */
static int write_snapshot(run_ctx *c, const gm_mesh_maxwell *s) {
  char path[4096];
  snprintf(path, sizeof path, "%s_%04zu.vtu", c->vtu, c->written);
  gm_mesh_maxwell_sync_b(s, c->Bsync);
  gm_vtu_field fields[2] = {{"E", 1, 1, gm_mesh_maxwell_e(s)}, {"B", 2, 1, c->Bsync}};
  gm_error err = {{0}};
  if (gm_vtu_write(path, c->cx, 2, fields, &err) != GM_OK) {
    cli_error("maxwell mesh", "%s", err.message);
    c->failed = 1;
    return 1;
  }
  c->snap_t[c->written++] = gm_mesh_maxwell_time(s);
  snprintf(path, sizeof path, "%s.pvd", c->vtu);
  const char *slash = strrchr(c->vtu, '/'), *base = slash ? slash + 1 : c->vtu;
  FILE *f = fopen(path, "w");
  int bad = !f;
  if (f) {
    fputs("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
          "  <Collection>\n", f);
    for (size_t k = 0; k < c->written; ++k)
      fprintf(f, "    <DataSet timestep=\"%.17g\" file=\"%s_%04zu.vtu\"/>\n", c->snap_t[k],
              base, k);
    fputs("  </Collection>\n</VTKFile>\n", f);
    bad = ferror(f) != 0;
    bad |= fclose(f) != 0;
  }
  if (bad) {
    cli_error("maxwell mesh", "cannot write %s", path);
    c->failed = 1;
    return 1;
  }
  return 0;
}

static int observe(void *vctx, const gm_mesh_maxwell *s) {
  run_ctx *c = vctx;
  gm_mesh_maxwell_energy en;
  gm_mesh_maxwell_energy_get(s, &en);
  const double t = gm_mesh_maxwell_time(s);
  const int blew_up = mm_guard_check(&c->guard, t, en.plain);
  c->max_dev = max_nan(c->max_dev, fabs(en.plain - c->guard.e0) / c->guard.e0);
  if (blew_up) {
    c->failed = 1;
    return 1;
  }
  if (c->energy)
    fprintf(c->energy, "%.10g,%.17g,%.17g,%.17g,%.17g\n", t, en.electric, en.magnetic, en.plain,
            en.leapfrog);
  /* the last snapshot is left to the end of the run: the leapfrog stops at the last whole step
     (short of --t-end), where no observation may fall */
  if (c->vtu && c->written + 1 < c->snapshots &&
      t + 0.5 * c->sample >= c->t_end * (double)c->written / (double)(c->snapshots - 1) &&
      write_snapshot(c, s) != 0)
    return 1;
  return 0;
}

/* ε and μ per cell from the --material boxes X0,Y0[,Z0],X1,Y1[,Z1],EPS,MU: a cell takes the
 * values of the last box holding its centroid (vacuum elsewhere); the values are passed on as
 * given, so the library's refusal of ε, μ <= 0 reaches the user (the caller names the option).
 * hits[i]: the cells box i got. Exit status; the message printed. */
static int build_materials(const cli_settings *m, const gm_complex *cx, double *eps, double *mu,
                           size_t *owner, size_t *hits) {
  const size_t n = gm_complex_dim(cx), nt = gm_complex_count(cx, n);
  const size_t *tv = gm_complex_simplices(cx, n);
  const double *X = gm_complex_coordinates(cx);
  for (size_t T = 0; T < nt; ++T) eps[T] = mu[T] = 1.0, owner[T] = SIZE_MAX;
  for (size_t i = 0; i < m->n; ++i) {
    double v[8];
    size_t k = 0;
    const char *p = m->items[i];
    for (char *end; k < 8; p = end + 1) {
      v[k++] = strtod(p, &end);
      if (end == p || (*end != ',' && *end != '\0')) { k = 0; break; }
      if (*end == '\0') break;
    }
    int ok = k == 2 * n + 2;
    for (size_t d = 0; ok && d < n; ++d) ok = isfinite(v[d]) && isfinite(v[n + d]) && v[d] < v[n + d];
    if (!ok) {
      cli_error("maxwell mesh", "--material %s: expected %s (a box with X0 < X1 ..., then "
                "epsilon and mu)", m->items[i],
                n == 2 ? "X0,Y0,X1,Y1,EPS,MU" : "X0,Y0,Z0,X1,Y1,Z1,EPS,MU");
      return CLI_EXIT_USAGE;
    }
    hits[i] = 0;
    for (size_t T = 0; T < nt; ++T) {
      int in = 1;
      for (size_t d = 0; d < n && in; ++d) {
        double c = 0.0;
        for (size_t j = 0; j <= n; ++j) c += X[tv[(n + 1) * T + j] * n + d];
        c /= (double)(n + 1);
        in = c >= v[d] && c <= v[n + d];
      }
      if (!in) continue;
      if (owner[T] != SIZE_MAX) --hits[owner[T]];
      eps[T] = v[2 * n], mu[T] = v[2 * n + 1], owner[T] = i, ++hits[i];
    }
    if (hits[i] == 0) {
      cli_error("maxwell mesh", "--material %s: no cell's centroid lies in the box",
                m->items[i]);
      return CLI_EXIT_USAGE;
    }
  }
  return CLI_EXIT_OK;
}

int cli_maxwell_mesh(int argc, char **argv) {
  int avi = 0, whitney = 0, allow = 0, e5 = 0, exact = 0, json = 0;
  const char *out_dir = NULL;
  double fraction = 0.0 /* 0.1, E5 0.25 */, sample_dt = 0.005, t_compare = 1.0, courant = 0.9, dt = 0.0, t_end = 8.0, ly = 0.7, warp = 0.0, f_max = 2.0;
  size_t samples = 1000, seed = 1, rect = 0, snapshots = 4;
  const char *energy_path = NULL, *probe = NULL, *vtu = NULL;
  cli_settings materials = {0};
  cli_option options[] = {{"--avi", CLI_ARG_FLAG, &avi, 0},
                          {"--whitney", CLI_ARG_FLAG, &whitney, 0},
                          {"--allow-negative-stars", CLI_ARG_FLAG, &allow, 0},
                          {"--fraction", CLI_ARG_DOUBLE, &fraction, 0},
                          {"--courant", CLI_ARG_DOUBLE, &courant, 0},
                          {"--dt", CLI_ARG_DOUBLE, &dt, 0},
                          {"--t-end", CLI_ARG_DOUBLE, &t_end, 0},
                          {"--samples", CLI_ARG_COUNT, &samples, 0},
                          {"--seed", CLI_ARG_COUNT, &seed, 0},
                          {"--energy", CLI_ARG_STRING, &energy_path, 0},
                          {"--probe", CLI_ARG_STRING, &probe, 0},
                          {"--fmax", CLI_ARG_DOUBLE, &f_max, 0},
                          {"--vtu", CLI_ARG_STRING, &vtu, 0},
                          {"--snapshots", CLI_ARG_COUNT, &snapshots, 0},
                          {"--rect", CLI_ARG_COUNT, &rect, 0},
                          {"--ly", CLI_ARG_DOUBLE, &ly, 0},
                          {"--warp", CLI_ARG_DOUBLE, &warp, 0},
                          {"--e5", CLI_ARG_FLAG, &e5, 0},
                          {"--exact-steps", CLI_ARG_FLAG, &exact, 0},
                          {"--sample", CLI_ARG_DOUBLE, &sample_dt, 0},
                          {"--t-compare", CLI_ARG_DOUBLE, &t_compare, 0},
                          {"--out", CLI_ARG_STRING, &out_dir, 0},
                          {"--material", CLI_ARG_LIST, &materials, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0}};
  const char *pos[1];
  size_t n_pos = 0;
  int status = cli_parse("maxwell mesh", argc, argv, options, sizeof options / sizeof options[0],
                         pos, 1, &n_pos);
  if (status == CLI_HELP) { fputs(usage, stdout); return CLI_EXIT_OK; }
  if (status != CLI_EXIT_OK) return status;
  if ((n_pos == 1) == (rect > 0)) {
    cli_error("maxwell mesh", "give a mesh file or --rect NX (one of them)");
    return CLI_EXIT_USAGE;
  }
  if (cli_check_positive("maxwell mesh", "--t-end", t_end) != CLI_EXIT_OK) return CLI_EXIT_USAGE;
  /* a value given is checked as given (--fraction 0 is not the default) */
  if (options[3].seen && !(fraction >= MM_MIN_FRACTION && fraction <= 1.0)) {
    cli_error("maxwell mesh", "--fraction %g: must be in [%g, 1] (the AVI's work grows as 1/F)",
              fraction, MM_MIN_FRACTION);
    return CLI_EXIT_USAGE;
  }
  if (options[5].seen && cli_check_positive("maxwell mesh", "--dt", dt) != CLI_EXIT_OK)
    return CLI_EXIT_USAGE;
  if (rect > MM_MAX_RECT) {
    cli_error("maxwell mesh", "--rect %zu: at most %d (%.3g triangles, about %.3g bytes at "
              "%d bytes each)", rect, MM_MAX_RECT,
              mm_rect_triangles(rect, ly), MM_BYTES_PER_TRIANGLE * mm_rect_triangles(rect, ly),
              MM_BYTES_PER_TRIANGLE);
    return CLI_EXIT_USAGE;
  }
  if (samples > MM_MAX_SAMPLES) {
    cli_error("maxwell mesh", "--samples %zu: at most %g", samples, (double)MM_MAX_SAMPLES);
    return CLI_EXIT_USAGE;
  }
  /* options of another mode are errors, not ignored */
  {
    static const struct { size_t option; int avi, leapfrog, e5; } scope[] = {
        {3, 1, 0, 1}, {4, 0, 1, 0}, {5, 0, 1, 0}, {18, 1, 0, 0}, {19, 0, 0, 1}, {20, 0, 0, 1},
        {21, 0, 0, 1}, {15, 0, 0, 0}, {16, 0, 0, 0}};
    for (size_t i = 0; i < sizeof scope / sizeof scope[0]; ++i) {
      const cli_option *o = &options[scope[i].option];
      const int is_rect_option = scope[i].option == 15 || scope[i].option == 16;
      const int used = is_rect_option ? rect > 0
                       : e5           ? scope[i].e5
                       : avi          ? scope[i].avi
                                      : scope[i].leapfrog;
      if (o->seen && !used) {
        cli_error("maxwell mesh", "%s is not an option of %s", o->name,
                  is_rect_option ? "a mesh file (it shapes --rect)"
                  : e5           ? "--e5"
                  : avi          ? "--avi"
                                 : "the leapfrog (the default scheme)");
        return CLI_EXIT_USAGE;
      }
    }
  }
  if (fraction == 0.0) fraction = e5 ? 0.25 : 0.1;
  if (!(fraction > 0.0 && fraction <= 1.0) ||
      !(courant > 0.0 && courant <= 1.0) || !(warp >= 0.0 && warp < 1.0) || !(ly > 0.0) ||
      !isfinite(ly) || samples == 0 || !(sample_dt > 0.0 && isfinite(sample_dt)) ||
      !(t_compare > 0.0 && isfinite(t_compare)) || !(f_max > 0.0) || snapshots == 0 ||
      (dt != 0.0 && !(dt > 0.0 && isfinite(dt)))) {
    cli_error("maxwell mesh", "bad option value (--t-end, --dt, --ly, --fmax > 0; --fraction, "
                              "--courant in (0, 1]; --warp in [0, 1); --samples, --snapshots "
                              ">= 1; --sample, --t-compare > 0)");
    return CLI_EXIT_USAGE;
  }
  gm_error err = {{0}};
  gm_mesh *mesh = NULL;
  gm_status st;
  if (rect) {
    const size_t ny = (size_t)lround(ly * 2.0 * (double)rect / sqrt(3.0));
    st = gm_mesh_rectangle(0, 1, 0, ly, rect, ny ? ny : 1, GM_DIAGONAL_ACUTE, &mesh, &err);
    if (st == GM_OK && warp > 0.0) { /* random monotone piecewise-linear partitions */
      uint64_t z = 0x51ed270b27ull + seed;
      const size_t nb[2] = {2 * rect, ny ? ny : 1};
      const double len[2] = {1.0, ly};
      for (int a = 0; a < 2 && st == GM_OK; ++a) {
        double *cut = malloc((nb[a] + 1) * sizeof(double));
        if (!cut) { st = GM_ENOMEM; break; }
        cut[0] = 0.0;
        for (size_t i = 0; i < nb[a]; ++i) cut[i + 1] = cut[i] + 1.0 + 2.0 * warp * rnd(&z);
        for (size_t i = 0; i <= nb[a]; ++i) cut[i] *= len[a] / cut[nb[a]];
        for (size_t v = 0; v < mesh->n_vertices; ++v) {
          const double u = mesh->x[2 * v + a] / len[a] * (double)nb[a];
          size_t i = (size_t)floor(u);
          if (i >= nb[a]) i = nb[a] - 1;
          mesh->x[2 * v + a] = cut[i] + (u - (double)i) * (cut[i + 1] - cut[i]);
        }
        free(cut);
      }
    }
  } else {
    st = gm_mesh_read(pos[0], &mesh, &err);
  }
  if (st != GM_OK) {
    cli_error("maxwell mesh", "%s", err.message[0] ? err.message : gm_strerror(st));
    gm_mesh_free(mesh);
    return st == GM_ENOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
  }
  if (e5) {
    if (materials.n) {
      cli_error("maxwell mesh", "--material does not apply to --e5 (a vacuum cavity)");
      gm_mesh_free(mesh);
      return CLI_EXIT_USAGE;
    }
    if (rect) {
      cli_error("maxwell mesh", "--e5 takes the Gmsh cavity file (examples/e5_cavity.msh)");
      gm_mesh_free(mesh);
      return CLI_EXIT_USAGE;
    }
    status = cli_maxwell_mesh_e5(mesh, out_dir, t_end, seed, f_max, fraction, sample_dt,
                                 t_compare, json);
    gm_mesh_free(mesh);
    return status;
  }
  gm_complex *cx = NULL;
  gm_geometry *g = NULL;
  gm_mesh_maxwell *s = NULL;
  double *E = NULL, *Bsync = NULL, *snap_t = NULL, *eps = NULL, *mu = NULL;
  size_t *owner = NULL, hits[CLI_MAX_SETTINGS];
  FILE *ef = NULL;
  status = CLI_EXIT_USAGE;
  if ((st = gm_mesh_complex(mesh, &cx, &err)) != GM_OK ||
      (st = gm_geometry_create(cx, NULL, &g, &err)) != GM_OK) {
    cli_error("maxwell mesh", "%s", err.message);
    goto done;
  }
  gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
  o.scheme = avi ? GM_MESH_AVI : GM_MESH_LEAPFROG;
  o.star = whitney ? GM_MESH_STAR_WHITNEY : GM_MESH_STAR_DIAGONAL;
  o.allow_negative_stars = allow;
  o.avi_fraction = fraction;
  o.avi_levels = !exact;
  o.courant = courant;
  o.dt = dt;
  const size_t nt = gm_complex_count(cx, gm_complex_dim(cx));
  if (materials.n) {
    eps = malloc(nt * sizeof(double));
    mu = malloc(nt * sizeof(double));
    owner = malloc(nt * sizeof(size_t));
    if (!eps || !mu || !owner) { status = CLI_EXIT_FAILURE; cli_error("maxwell mesh", "out of memory"); goto done; }
    if ((status = build_materials(&materials, cx, eps, mu, owner, hits)) != CLI_EXIT_OK) goto done;
    status = CLI_EXIT_USAGE;
  }
  for (size_t T = 0; materials.n && T < nt; ++T)
    /* positive values past the bounds (the library refuses the others, naming the cell) */
    if ((eps[T] > 0.0 && (eps[T] < MM_MIN_MATERIAL || eps[T] > MM_MAX_MATERIAL)) ||
        (mu[T] > 0.0 && (mu[T] < MM_MIN_MATERIAL || mu[T] > MM_MAX_MATERIAL))) {
      cli_error("maxwell mesh", "--material %s: epsilon and mu must lie in [%g, %g] (the step "
                "falls with sqrt(epsilon mu))", materials.items[owner[T]], MM_MIN_MATERIAL,
                MM_MAX_MATERIAL);
      goto done;
    }
  if ((st = gm_mesh_maxwell_create(g, eps, mu, &o, &s, &err)) != GM_OK) {
    size_t bad = SIZE_MAX; /* the region that set a refused ε or μ */
    for (size_t T = 0; materials.n && T < nt && bad == SIZE_MAX; ++T)
      if (!(eps[T] > 0.0 && isfinite(eps[T]) && mu[T] > 0.0 && isfinite(mu[T]))) bad = owner[T];
    if (bad != SIZE_MAX)
      cli_error("maxwell mesh", "--material %s: %s", materials.items[bad], err.message);
    else if (strstr(err.message, "not well-centred"))
      cli_error("maxwell mesh", "%s; on the command line: --allow-negative-stars to insist, or "
                "--whitney (any mesh)", err.message);
    else
      cli_error("maxwell mesh", "%s", err.message);
    goto done;
  }
  const size_t ne = gm_complex_count(cx, 1), nf = gm_complex_count(cx, 2);
  E = malloc(ne * sizeof(double));
  Bsync = malloc(nf * sizeof(double));
  snap_t = malloc((snapshots ? snapshots : 1) * sizeof(double));
  if (!E || !Bsync || !snap_t) { status = CLI_EXIT_FAILURE; cli_error("maxwell mesh", "out of memory"); goto done; }
  uint64_t z = seed;
  for (size_t e = 0; e < ne; ++e) E[e] = rnd(&z);
  gm_mesh_maxwell_set_fields(s, E, NULL);
  const double step = gm_mesh_maxwell_dt(s);
  /* the step count, for the leapfrog the steps, for the AVI the ticks of its smallest step */
  if (!(t_end / step <= MM_MAX_STEPS)) {
    cli_error("maxwell mesh", "--t-end %g is %.3g steps of %s %.3g: at most %.0e%s", t_end,
              t_end / step, avi ? "the smallest face step" : "dt", step, MM_MAX_STEPS,
              materials.n ? " (--material: the step falls with sqrt(epsilon mu))"
              : options[5].seen ? " (--dt)" : "");
    goto done;
  }
  const double sample = t_end / (double)samples;
  size_t every = (size_t)floor(sample / step);
  if (every == 0) every = 1;
  if (avi) gm_mesh_maxwell_set_sample_dt(s, sample);
  const size_t n_rec = avi ? samples + 2 : (size_t)(t_end / step) + 2;
  if (probe) {
    double x[3] = {0, 0, 0};
    const int n_read = sscanf(probe, "%lf,%lf,%lf", &x[0], &x[1], &x[2]);
    if (n_read >= 2 && !(isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]))) {
      cli_error("maxwell mesh", "--probe %s: the coordinates must be finite", probe);
      goto done;
    }
    if (n_read < 2 || gm_mesh_maxwell_add_probe(s, GM_EX, x, n_rec, NULL) != GM_OK) {
      cli_error("maxwell mesh", "--probe %s: %s", probe,
                gm_mesh_maxwell_errmsg(s)[0] ? gm_mesh_maxwell_errmsg(s) : "expected X,Y[,Z]");
      goto done;
    }
  }
  if (vtu != NULL && strrchr(vtu, '/') != NULL && strrchr(vtu, '/') != vtu) {
    /* --vtu snap/s: the folder is made as `maxwell run --out` makes its own */
    char dir[4096];
    snprintf(dir, sizeof dir, "%.*s", (int)(strrchr(vtu, '/') - vtu), vtu);
    if ((status = mx_make_option_dir("maxwell mesh", "--vtu", dir)) != CLI_EXIT_OK) goto done;
  }
  if (energy_path && !(ef = fopen(energy_path, "w"))) {
    cli_error("maxwell mesh", "cannot write %s", energy_path);
    status = CLI_EXIT_FAILURE;
    goto done;
  }
  if (ef) fprintf(ef, "t,electric,magnetic,plain,leapfrog\n");
  run_ctx rc = {ef, cx, vtu, snapshots, 0, snap_t, t_end, avi ? sample : (double)every * step, 0, Bsync,
                {"maxwell mesh", avi ? MM_BLOWUP_RATIO : INFINITY, 0, 0.0, 0.0, 0, ""}, 0};
  if (avi)
    snprintf(rc.guard.advice, sizeof rc.guard.advice, "; the AVI has no stability bound for "
             "neighbouring faces with different steps: use a smaller --fraction (now %g)",
             fraction);
  else if (allow && !whitney)
    snprintf(rc.guard.advice, sizeof rc.guard.advice, "; the diagonal star has non-positive "
             "entries on this mesh (--allow-negative-stars), which no step cures: use --whitney");
  else
    snprintf(rc.guard.advice, sizeof rc.guard.advice, "; use a smaller --courant or --dt");
  gm_mesh_maxwell_add_observer(s, avi ? 1 : every, observe, &rc);
  double *g0 = malloc(gm_complex_count(cx, 0) * sizeof(double));
  double *g1 = malloc(gm_complex_count(cx, 0) * sizeof(double));
  if (!g0 || !g1) { free(g0); free(g1); status = CLI_EXIT_FAILURE; goto done; }
  gm_mesh_maxwell_gauss(s, g0);
  const double wall0 = mx_now();
  st = mm_advance_progress(s, t_end);
  const double wall_s = mx_now() - wall0;
  status = CLI_EXIT_OK;
  if (st != GM_OK || rc.failed) {
    if (!rc.failed && st == GM_EDOMAIN) /* non-finite between two observations */
      cli_error("maxwell mesh", "the run blew up: %s%s", gm_mesh_maxwell_errmsg(s),
                rc.guard.advice);
    else if (!rc.failed) /* the observer printed why */
      cli_error("maxwell mesh", "%s", gm_mesh_maxwell_errmsg(s));
    status = CLI_EXIT_FAILURE;
  }
  if (status == CLI_EXIT_OK && vtu && write_snapshot(&rc, s) != 0) status = CLI_EXIT_FAILURE;
  gm_mesh_maxwell_gauss(s, g1);
  double gd = 0.0;
  for (size_t v = 0; v < gm_complex_count(cx, 0); ++v) gd = max_nan(gd, fabs(g1[v] - g0[v]));
  free(g0); free(g1);
  size_t fu, eu;
  gm_mesh_maxwell_update_counts(s, &fu, &eu);
  const double *lim = gm_mesh_maxwell_face_limits(s);
  double smallest = INFINITY;
  size_t active = 0;
  for (size_t k = 0; k < nf; ++k)
    if (isfinite(lim[k])) { smallest = fmin(smallest, fraction * lim[k]); ++active; }
  gm_mesh_maxwell_energy en;
  gm_mesh_maxwell_energy_get(s, &en);
  /* the final state too: the library may have stopped a blow-up between two observations */
  rc.max_dev = max_nan(rc.max_dev, fabs(en.plain - rc.guard.e0) / rc.guard.e0);
  rc.guard.max_ratio = max_nan(rc.guard.max_ratio, fabs(en.plain) / fabs(rc.guard.e0));
  const double uniform_updates = (double)active * floor(t_end / smallest);
  /* the probe's resonances: a failed analysis is a failed run, never exit 0 */
  gm_harminv_mode modes[64];
  size_t nm = 0;
  int harminv_ok = 0;
  if (probe && status == CLI_EXIT_OK) {
    size_t n;
    const double *t, *v;
    gm_mesh_maxwell_probe_samples(s, 0, &n, &t, &v);
    const double sdt = n > 1 ? t[1] - t[0] : step;
    const double top = fmin(f_max, 0.5 / sdt);
    harminv_ok = n >= 8 && gm_harminv(n, v, NULL, sdt, 0.02 * top, top, 0, 64, modes, &nm,
                                      &err) == GM_OK;
    if (!harminv_ok) {
      cli_error("maxwell mesh", "--probe %s: harminv failed: %s", probe,
                n >= 8 ? err.message : "fewer than 8 samples");
      status = CLI_EXIT_FAILURE;
    }
  }
  if (json && status == CLI_EXIT_OK) {
    cJSON *j = cJSON_CreateObject();
    cJSON_AddNumberToObject(j, "dim", (double)gm_complex_dim(cx));
    cJSON_AddNumberToObject(j, "vertices", (double)gm_complex_count(cx, 0));
    cJSON_AddNumberToObject(j, "edges", (double)ne);
    cJSON_AddNumberToObject(j, "faces", (double)nf);
    cJSON_AddNumberToObject(j, "cells", (double)gm_complex_count(cx, gm_complex_dim(cx)));
    cJSON_AddStringToObject(j, "scheme", avi ? "avi" : "leapfrog");
    cJSON_AddStringToObject(j, "star", whitney ? "whitney" : "diagonal");
    cJSON_AddItemToObject(j, "cfl_limit", cli_json_number(gm_mesh_maxwell_cfl_limit(s)));
    cJSON_AddItemToObject(j, avi ? "smallest_face_step" : "dt",
                          cli_json_number(gm_mesh_maxwell_dt(s)));
    cJSON_AddItemToObject(j, "t_final", cli_json_number(gm_mesh_maxwell_time(s)));
    cJSON_AddNumberToObject(j, "steps", (double)gm_mesh_maxwell_step(s));
    cJSON_AddNumberToObject(j, "face_updates", (double)fu);
    cJSON_AddNumberToObject(j, "edge_updates", (double)eu);
    if (avi) cJSON_AddItemToObject(j, "uniform_face_updates", cli_json_number(uniform_updates));
    cJSON_AddItemToObject(j, "energy_initial", cli_json_number(rc.guard.e0));
    cJSON_AddItemToObject(j, "energy_plain_final", cli_json_number(en.plain));
    cJSON_AddItemToObject(j, "energy_leapfrog_final", cli_json_number(en.leapfrog));
    cJSON_AddItemToObject(j, "max_rel_plain_energy_deviation", cli_json_number(rc.max_dev));
    cJSON_AddItemToObject(j, "rel_leapfrog_energy_error_final",
                          cli_json_number(fabs(en.leapfrog - rc.guard.e0) / rc.guard.e0));
    cJSON_AddItemToObject(j, "max_abs_div_b", cli_json_number(gm_mesh_maxwell_div_b(s)));
    cJSON_AddItemToObject(j, "max_gauss_drift", cli_json_number(gd));
    if (probe) {
      cJSON *res = cJSON_AddArrayToObject(j, "resonances");
      for (size_t i = 0; i < nm; ++i)
        if (modes[i].error < 1e-3) cJSON_AddItemToArray(res, cli_json_number(modes[i].frequency));
    }
    cJSON_AddNumberToObject(j, "wall_s", wall_s);
    status = cli_json_print(j);
    goto done;
  }
  printf("mesh: %zu-D, %zu vertices, %zu edges, %zu faces, %zu cells\n", gm_complex_dim(cx),
         gm_complex_count(cx, 0), ne, nf, gm_complex_count(cx, gm_complex_dim(cx)));
  if (materials.n) {
    printf("materials:");
    for (size_t i = 0; i < materials.n; ++i)
      printf("%s %s on %zu cells", i ? ";" : "", materials.items[i], hits[i]);
    printf(" (vacuum elsewhere)\n");
  }
  printf("scheme: %s, star: %s, CFL limit %.6g, %s %.6g\n", avi ? "avi" : "leapfrog",
         whitney ? "whitney" : "diagonal", gm_mesh_maxwell_cfl_limit(s),
         avi ? "smallest face step" : "dt", gm_mesh_maxwell_dt(s));
  printf("run: t = %.6g, face updates %zu, edge updates %zu", gm_mesh_maxwell_time(s), fu, eu);
  if (avi)
    printf(" (uniform stepping at the smallest step: %.0f face updates, ratio %.3f)",
           uniform_updates, (double)fu / uniform_updates);
  printf("\n");
  char stops[64] = "the leapfrog stops only when non-finite";
  if (avi) snprintf(stops, sizeof stops, "the AVI stops above %g", rc.guard.limit);
  printf("energy: start %.10g, end plain %.10g, leapfrog %.10g, max |plain - E0|/E0 %.3e, max "
         "plain/E0 %.4g (%s)\n", rc.guard.e0, en.plain, en.leapfrog, rc.max_dev,
         rc.guard.max_ratio, stops);
  printf("invariants: max |div B| %.3e, max Gauss drift %.3e\n", gm_mesh_maxwell_div_b(s), gd);
  if (harminv_ok) {
    printf("resonances (harminv, error < 1e-3):");
    for (size_t i = 0; i < nm; ++i)
      if (modes[i].error < 1e-3) printf(" %.5f", modes[i].frequency);
    printf("\n");
  }
done:
  if (ef) fclose(ef);
  free(E);
  free(Bsync);
  free(snap_t);
  free(eps);
  free(mu);
  free(owner);
  gm_mesh_maxwell_free(s);
  gm_geometry_free(g);
  gm_complex_free(cx);
  gm_mesh_free(mesh);
  return status;
}
