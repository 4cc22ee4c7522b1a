/* Running a fluid case: CSV diagnostics every step, VTU snapshots with a .pvd collection. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/fluids.h"

typedef struct writer {
  const char *dir;
  FILE *csv;
  size_t n_vtu, cap;
  double *times;
  double *zeta, *u3;
  double *pull; /* 3 fields pulled back to the mesh's vertices (periodic meshes) */
} writer;

static gm_status write_pvd(writer *w, gm_error *err) {
  char path[4096];
  snprintf(path, sizeof path, "%s/fluid.pvd", w->dir);
  FILE *f = fopen(path, "w");
  if (!f) return gm_error_set(err, GM_EIO, "cannot write %s: %s", path, strerror(errno));
  fputs("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n",
        f);
  for (size_t i = 0; i < w->n_vtu; ++i)
    fprintf(f, "<DataSet timestep=\"%.17g\" file=\"fluid_%06zu.vtu\"/>\n", w->times[i], i);
  fputs("</Collection>\n</VTKFile>\n", f);
  int bad = ferror(f);
  if (fclose(f) != 0 || bad) return gm_error_set(err, GM_EIO, "error writing %s", path);
  return GM_OK;
}

static gm_status write_vtu(writer *w, const gm_fluid *f, gm_error *err) {
  if (w->n_vtu == w->cap) {
    size_t cap = w->cap ? 2 * w->cap : 16;
    double *t = realloc(w->times, cap * sizeof *t);
    if (!t) return gm_error_set(err, GM_ENOMEM, "out of memory");
    w->times = t;
    w->cap = cap;
  }
  const size_t nt = gm_fluid_n_triangles(f);
  gm_fluid_vorticity(f, w->zeta);
  gm_fluid_velocity(f, w->u3); /* 2 per triangle in the plane, spread to 3 (from the end) */
  if (gm_fluid_space_dim(f) == 2)
    for (size_t t = nt; t-- > 0;) {
      double ux = w->u3[2 * t], uy = w->u3[2 * t + 1];
      w->u3[3 * t] = ux;
      w->u3[3 * t + 1] = uy;
      w->u3[3 * t + 2] = 0.0;
    }
  const double *vf[3] = {gm_fluid_psi(f), gm_fluid_theta(f), w->zeta};
  const size_t *map = gm_fluid_vertex_map(f);
  if (map) {
    const size_t nm = gm_complex_count(gm_fluid_complex(f), 0);
    for (int k = 0; k < 3; ++k) {
      for (size_t v = 0; v < nm; ++v) w->pull[k * nm + v] = vf[k][map[v]];
      vf[k] = w->pull + k * nm;
    }
  }
  gm_vtu_field fields[4] = {{"psi", 0, 1, vf[0]},
                            {"theta", 0, 1, vf[1]},
                            {"vorticity", 0, 1, vf[2]},
                            {"velocity", 2, 3, w->u3}};
  char path[4096];
  snprintf(path, sizeof path, "%s/fluid_%06zu.vtu", w->dir, w->n_vtu);
  gm_status st = gm_vtu_write(path, gm_fluid_complex(f), 4, fields, err);
  if (st) return st;
  w->times[w->n_vtu++] = gm_fluid_time(f);
  return write_pvd(w, err);
}

static void write_row(writer *w, size_t step, const gm_fluid_diagnostics *d) {
  fprintf(w->csv, "%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", step, d->time, d->kinetic_energy,
          d->enstrophy, d->total_vorticity, d->div_max, d->scalar_mass);
}

gm_status gm_fluid_case_run(const gm_fluid_case *c, const char *out_dir, gm_fluid_run_report *rep,
                            gm_error *err) {
  if (!c || !rep) return gm_error_set(err, GM_EINVAL, "fluid run: NULL argument");
  memset(rep, 0, sizeof *rep);
  gm_fluid *f = NULL;
  gm_status st = gm_fluid_case_solver(c, &f, err);
  if (st) return st;
  writer w = {out_dir, NULL, 0, 0, NULL, NULL, NULL, NULL};
  const size_t nv = gm_fluid_n_vertices(f), nt = gm_fluid_n_triangles(f);
  size_t n_steps = (size_t)floor(c->t_end / c->options.dt + 0.5);
  if (out_dir) {
    char path[4096];
    snprintf(path, sizeof path, "%s/diagnostics.csv", out_dir);
    w.csv = fopen(path, "w");
    w.zeta = malloc(nv * sizeof *w.zeta);
    w.u3 = malloc(3 * nt * sizeof *w.u3);
    w.pull = malloc(3 * gm_complex_count(gm_fluid_complex(f), 0) * sizeof *w.pull);
    if (!w.csv) {
      st = gm_error_set(err, GM_EIO, "cannot write %s: %s", path, strerror(errno));
      goto done;
    }
    if (!w.zeta || !w.u3 || !w.pull) {
      st = gm_error_set(err, GM_ENOMEM, "out of memory");
      goto done;
    }
    fputs("step,time,kinetic_energy,enstrophy,total_vorticity,div_max,scalar_mass\n", w.csv);
  }
  gm_fluid_diagnose(f, &rep->first);
  rep->last = rep->first;
  rep->div_max = rep->first.div_max;
  if (w.csv) write_row(&w, 0, &rep->first);
  if (out_dir && c->output_every && (st = write_vtu(&w, f, err))) goto done;
  for (size_t s = 1; s <= n_steps; ++s) {
    st = gm_fluid_advance(f, 1);
    if (st) {
      gm_error_set(err, st, "%s", gm_fluid_errmsg(f));
      goto done;
    }
    gm_fluid_diagnose(f, &rep->last);
    rep->steps = s;
    rep->div_max = fmax(rep->div_max, rep->last.div_max);
    if (w.csv) write_row(&w, s, &rep->last);
    if (out_dir && c->output_every && s % c->output_every == 0 && (st = write_vtu(&w, f, err)))
      goto done;
  }
done:
  rep->vtu_files = w.n_vtu;
  if (w.csv && fclose(w.csv) != 0 && !st) st = gm_error_set(err, GM_EIO, "error writing the CSV");
  free(w.times);
  free(w.zeta);
  free(w.u3);
  free(w.pull);
  gm_fluid_free(f);
  return st;
}
