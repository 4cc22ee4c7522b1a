/* The 3-D PEC cavity verification (issue 11; E5's claim of seed 000 §3.4.2: no spurious modes)
 * on tetrahedral meshes. For each level the cavity is meshed (box: body-centred cubic
 * tetrahedra of the whole box, gm_mesh_bcc with fill, n0 k cubes along x; cylinder, sphere:
 * the Gmsh files mesh_dir/cavity_<shape>_<k>.msh), the leapfrog rings down after current
 * pulses (gm_mesh_maxwell_cavity_modes), harminv's peaks are mapped back to spatial
 * eigenfrequencies (the leapfrog's dispersion undone, gm_leapfrog_space_frequency) and compared
 * with the analytic resonances: per level the error of each of the first n_first resonances
 * (with multiplicity), the rate (least-squares slope of log error against log h), and every
 * peak of the band checked against the analytic list (farther than 5 % from all: spurious).
 * A degenerate resonance split by the mesh has two errors: its nearest peak, and the farthest
 * of the peaks nearest to it (the split's spread; the sphere's (2l+1)-fold multiplets). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/dec.h"
#include "geomint/fields.h"
#include "geomint/mesh.h"

gm_mesh_cavity_config gm_mesh_cavity_defaults(void) {
  gm_mesh_cavity_config c = {"box", "examples", 3, 5, 10, 0, 150.0, 11, NULL, NULL};
  return c;
}

static gm_status make_level(const gm_mesh_cavity_config *c, size_t k, gm_mesh **mesh, double *h,
                            gm_error *err) {
  if (strcmp(c->shape, "box") == 0) {
    const double lo[3] = {0, 0, 0}, hi[3] = {1.0, 0.8, 0.6};
    const size_t n = c->n0 * k;
    *h = 1.0 / (double)n;
    return gm_mesh_bcc(lo, hi, n, (size_t)lround(0.8 * (double)n), (size_t)lround(0.6 * (double)n),
                       1, mesh, err);
  }
  char path[GM_EXPERIMENT_PATH_SIZE];
  snprintf(path, sizeof path, "%s/cavity_%s_%zu.msh", c->mesh_dir, c->shape, k);
  gm_status st = gm_mesh_read(path, mesh, err);
  if (st != GM_OK) return st == GM_ENOMEM ? st : GM_EINVAL;
  /* h: the mean edge length */
  gm_complex *cx = NULL;
  if ((st = gm_mesh_complex(*mesh, &cx, err)) != GM_OK) return GM_EINVAL;
  const size_t ne = gm_complex_count(cx, 1);
  const size_t *ev = gm_complex_simplices(cx, 1);
  const double *X = gm_complex_coordinates(cx);
  double s = 0.0;
  for (size_t e = 0; e < ne; ++e) {
    double r2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double d = X[3 * ev[2 * e] + (size_t)i] - X[3 * ev[2 * e + 1] + (size_t)i];
      r2 += d * d;
    }
    s += sqrt(r2);
  }
  *h = s / (double)ne;
  gm_complex_free(cx);
  return GM_OK;
}

/* least-squares slope of log |e| against log h over the finite entries; NAN with fewer than 2 */
static double slope(size_t levels, const double *hs, const double *e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  size_t m = 0;
  for (size_t l = 0; l < levels; ++l) {
    if (isnan(e[l])) continue;
    const double x = log(hs[l]), y = log(fabs(e[l]) + 1e-300);
    sx += x, sy += y, sxx += x * x, sxy += x * y, ++m;
  }
  return m >= 2 ? ((double)m * sxy - sx * sy) / ((double)m * sxx - sx * sx) : NAN;
}

gm_status gm_experiment_mesh_cavity(const gm_mesh_cavity_config *c, gm_mesh_cavity_result *r,
                                    gm_error *err) {
  memset(r, 0, sizeof *r);
  const int box = c->shape != NULL && strcmp(c->shape, "box") == 0;
  if (c->shape == NULL ||
      (!box && strcmp(c->shape, "cylinder") != 0 && strcmp(c->shape, "sphere") != 0) ||
      c->levels < 1 || c->levels > GM_MESH_CAVITY_MAX_LEVELS || c->n_first < 1 ||
      !(c->t_end > 0.0) || !isfinite(c->t_end))
    return gm_error_set(err, GM_EINVAL, "mesh-cavity: bad setting (shape box|cylinder|sphere, "
                        "levels 1..%d, n_first >= 1, t_end > 0)", GM_MESH_CAVITY_MAX_LEVELS);
  if (c->n0 < 3 || c->n0 > 40)
    return gm_error_set(err, GM_EINVAL, "mesh-cavity: n0 = %zu must be in [3, 40] (the box's "
                        "0.6 side needs 2 cubes at n0 = 3)", c->n0);
  if (c->t_end > GM_MESH_CAVITY_MAX_T_END)
    return gm_error_set(err, GM_EINVAL, "mesh-cavity: t_end %g: at most %g (24 probe signals are "
                        "kept in memory, 8 bytes each a step: %g is about %.2g bytes at the "
                        "finest level)", c->t_end, GM_MESH_CAVITY_MAX_T_END, c->t_end,
                        24.0 * 8.0 * c->t_end / (0.3 / (double)(c->n0 * c->levels)));
  const double t0 = gm_experiment_clock();
  double ana[GM_MESH_CAVITY_MAX_MODES];
  size_t na = 0;
  gm_error aerr = {{0}};
  gm_status st = box ? gm_cavity_box_resonances((const double[3]){1.0, 0.8, 0.6}, 2.0,
                                                 GM_MESH_CAVITY_MAX_MODES, ana, &na, &aerr)
                 : strcmp(c->shape, "cylinder") == 0
                     ? gm_cavity_cylinder_resonances(0.5, 0.6, 2.0, GM_MESH_CAVITY_MAX_MODES, ana,
                                                     &na, &aerr)
                     : gm_cavity_sphere_resonances(0.5, 2.7, GM_MESH_CAVITY_MAX_MODES, ana, &na,
                                                   &aerr);
  if (st != GM_OK || na < 11)
    return gm_error_set(err, st != GM_OK ? st : GM_EINVAL, "analytic resonances: %s",
                        st != GM_OK ? aerr.message : "fewer than 11");
  /* the band: up to halfway between the n_first-th resonance (with multiplicity) and the next
   * distinct one; the multiplet of the n_first-th is taken whole */
  const size_t n_first = c->n_first;
  size_t next = n_first;
  while (next < na && ana[next] <= ana[n_first - 1] * (1 + 1e-12)) ++next;
  if (next >= na)
    return gm_error_set(err, GM_EINVAL, "mesh-cavity: n_first = %zu: the analytic list ends "
                        "there", n_first);
  const double f_hi = 0.5 * (ana[n_first - 1] + ana[next]);
  for (size_t j = 0; j < next; ++j) {
    if (r->n_uniq > 0 && ana[j] <= r->uniq[r->n_uniq - 1] * (1 + 1e-12)) {
      ++r->mult[r->n_uniq - 1];
      continue;
    }
    if (r->n_uniq == GM_MESH_CAVITY_MAX_UNIQ)
      return gm_error_set(err, GM_EINVAL, "mesh-cavity: n_first = %zu: more than %d distinct "
                          "resonances", n_first, GM_MESH_CAVITY_MAX_UNIQ);
    r->uniq[r->n_uniq] = ana[j];
    r->mult[r->n_uniq++] = 1;
  }
  gm_mesh_cavity_run run = gm_mesh_cavity_run_defaults();
  run.t_end = c->t_end;
  run.seed = c->seed;
  run.f_min = 0.5 * ana[0];
  run.f_max = f_hi;
  run.band = 0.2;
  run.n_sources = 12;
  run.n_probes = 8;
  r->run = run;
  run.progress = c->progress;
  run.progress_ctx = c->progress_ctx;
  r->levels = c->levels;
  double hs[GM_MESH_CAVITY_MAX_LEVELS];
  for (size_t l = 0; l < c->levels; ++l) {
    gm_mesh_cavity_level *L = &r->level[l];
    gm_mesh *mesh = NULL;
    gm_complex *cx = NULL;
    gm_geometry *g = NULL;
    if ((st = make_level(c, l + 1, &mesh, &L->h, err)) != GM_OK) {
      gm_mesh_free(mesh);
      return st;
    }
    hs[l] = L->h;
    if ((st = gm_mesh_complex(mesh, &cx, err)) != GM_OK ||
        (st = gm_geometry_create(cx, NULL, &g, err)) != GM_OK) {
      gm_complex_free(cx), gm_mesh_free(mesh);
      return st == GM_ENOMEM ? st : GM_EINVAL;
    }
    gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
    if (c->diagonal) o.allow_negative_stars = 1; /* the diagonal star, as asked */
    else o.star = GM_MESH_STAR_WHITNEY;
    gm_harminv_mode modes[GM_MESH_CAVITY_MAX_MODES];
    size_t nm = 0;
    st = gm_mesh_maxwell_cavity_modes(g, &o, &run, GM_MESH_CAVITY_MAX_MODES, modes, &nm, &L->dt,
                                      err);
    L->n_tetrahedra = gm_complex_count(cx, 3);
    L->n_edges = gm_complex_count(cx, 1);
    gm_geometry_free(g), gm_complex_free(cx), gm_mesh_free(mesh);
    if (st != GM_OK) {
      char why[GM_ERRMSG_SIZE];
      snprintf(why, sizeof why, "%s", err->message);
      return gm_error_set(err, st, "level %zu: %s%s", l + 1, why,
                          st != GM_EDOMAIN ? ""
                          : c->diagonal ? "; the run blew up: the diagonal star has non-positive "
                                          "entries on this mesh (--diagonal accepts them), which "
                                          "no step cures: drop --diagonal for the Whitney star"
                                        : "; the run blew up");
    }
    for (size_t j = 0; j < r->n_uniq; ++j) r->nearest[j][l] = r->farthest[j][l] = NAN;
    for (size_t j = 0; j < na; ++j) L->in_band += ana[j] >= run.f_min && ana[j] <= run.f_max;
    L->n_peaks = nm;
    for (size_t i = 0; i < nm; ++i) {
      const double fs = gm_leapfrog_space_frequency(modes[i].frequency, L->dt);
      size_t best = 0;
      for (size_t j = 1; j < na; ++j)
        if (fabs(ana[j] - fs) < fabs(ana[best] - fs)) best = j;
      const double rel = (fs - ana[best]) / ana[best];
      L->peaks[i] = fs;
      L->spurious_peak[i] = fabs(rel) > 0.05;
      L->spurious += (size_t)L->spurious_peak[i];
      for (size_t j = 0; j < r->n_uniq; ++j)
        if (ana[best] == r->uniq[j]) {
          if (!(fabs(r->nearest[j][l]) <= fabs(rel))) r->nearest[j][l] = rel;
          if (!(fabs(r->farthest[j][l]) >= fabs(rel))) r->farthest[j][l] = rel;
        }
    }
    r->spurious += L->spurious;
  }
  for (size_t j = 0; j < r->n_uniq; ++j) {
    r->rate_nearest[j] = slope(c->levels, hs, r->nearest[j]);
    r->rate_farthest[j] = slope(c->levels, hs, r->farthest[j]);
  }
  /* the largest error over the band (farthest peaks): one number per level that does not depend
   * on which members of a multiplet harminv resolves */
  for (size_t l = 0; l < c->levels; ++l) {
    r->band_max[l] = 0.0;
    for (size_t j = 0; j < r->n_uniq; ++j)
      if (!isnan(r->farthest[j][l])) r->band_max[l] = fmax(r->band_max[l], fabs(r->farthest[j][l]));
  }
  r->band_rate = c->levels >= 2 ? slope(c->levels, hs, r->band_max) : NAN;
  r->wall_s = gm_experiment_clock() - t0;
  return GM_OK;
}

gm_status gm_experiment_run_mesh_cavity(const char *dir, gm_experiment_result *result,
                                        gm_error *err) {
  (void)dir; /* numbers only; the error figure is the command's */
  gm_mesh_cavity_config c = gm_mesh_cavity_defaults();
  gm_mesh_cavity_result r;
  gm_status st = gm_experiment_mesh_cavity(&c, &r, err);
  if (st != GM_OK) return st;
  gm_experiment_add(result, "levels", (double)r.levels);
  gm_experiment_add(result, "spurious", (double)r.spurious);
  gm_experiment_add(result, "max_rel_error_finest", r.band_max[r.levels - 1]);
  gm_experiment_add(result, "rate", r.band_rate);
  gm_experiment_add(result, "wall_s", r.wall_s);
  return GM_OK;
}
