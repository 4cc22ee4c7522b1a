/* geomint maxwell mesh CAVITY.msh --e5: seed 000 experiment E5 (notes §2) as one command; the
 * computation is gm_experiment_e5 (src/experiments/e5.c), here its report, the spectrum
 * figure and --json. */
#include <cJSON.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/maxwell.h"
#include "cli/maxwell_mesh.h"
#include "geomint/experiments.h"

#define E5 "maxwell mesh --e5"

static int show_progress(void *ctx, double done, double total) {
  mx_progress *p = ctx;
  p->total = (size_t)total;
  mx_progress_show(p, (size_t)done);
  return 0;
}

static void print_spectrum(const gm_e5_result *r, const gm_e5_spectrum *x) {
  printf("   %-12s %-12s %s\n", "harminv", "analytic", "rel. error");
  for (size_t i = 0; i < x->n_peaks; ++i)
    printf("   %-12.5f %-12.5f %.2e%s\n", x->peaks[i], x->nearest[i], x->rel_error[i],
           x->rel_error[i] > 0.05 ? "  SPURIOUS" : "");
  printf("   first %zu analytic resonances: %zu seen at the probe; %zu peaks, %zu spurious, worst "
         "error of the others %.2e\n", r->n_check, x->matched, x->n_peaks, x->spurious, x->worst);
}

static void print_invariants(const gm_e5_run *x) {
  printf("   energy: start %.10g, end %.10g, max |E(t) - E0|/E0 %.3e over 1000 samples (max "
         "E/E0 %.4g); max |div B| %.2e, Gauss drift %.2e\n", x->energy0, x->energy,
         x->max_rel_energy_error, x->max_energy_ratio, x->max_div_b, x->gauss_drift);
}

/* The spectrum figure of one run's three probe signals; the file name or NULL */
static const char *plot(const gm_e5_result *r, const gm_e5_run *x, const char *out_dir,
                        const char *title, char *png, size_t cap) {
  snprintf(png, cap, "%s/e5-spectrum.png", out_dir);
  if (x->signals == NULL || !cli_gnuplot_available() ||
      mx_plot_spectrum(E5, png, title, 3, x->n_samples, x->signals, x->sample_dt, r->f_top * 1.1,
                       r->analytic, r->n_check) != CLI_EXIT_OK)
    return NULL;
  return png;
}

static cJSON *json_run(const gm_e5_run *x) {
  cJSON *o = cJSON_CreateObject();
  cJSON_AddNumberToObject(o, "dt", x->dt);
  cJSON_AddNumberToObject(o, "steps", (double)x->steps);
  cJSON_AddNumberToObject(o, "face_updates", (double)x->face_updates);
  cJSON_AddNumberToObject(o, "cpu_s", x->cpu_s);
  cJSON_AddItemToObject(o, "peaks", cli_json_numbers(x->spectrum.peaks, x->spectrum.n_peaks));
  cJSON_AddItemToObject(o, "rel_errors", cli_json_numbers(x->spectrum.rel_error, x->spectrum.n_peaks));
  cJSON_AddNumberToObject(o, "matched", (double)x->spectrum.matched);
  cJSON_AddNumberToObject(o, "spurious", (double)x->spectrum.spurious);
  cJSON_AddItemToObject(o, "max_rel_frequency_error", cli_json_number(x->spectrum.worst));
  cJSON_AddItemToObject(o, "energy0", cli_json_number(x->energy0));
  cJSON_AddItemToObject(o, "energy", cli_json_number(x->energy));
  cJSON_AddItemToObject(o, "max_rel_energy_error", cli_json_number(x->max_rel_energy_error));
  cJSON_AddItemToObject(o, "max_div_b", cli_json_number(x->max_div_b));
  cJSON_AddItemToObject(o, "gauss_drift", cli_json_number(x->gauss_drift));
  return o;
}

static int print_json(const gm_e5_result *r, const char *png) {
  cJSON *o = cJSON_CreateObject();
  cJSON_AddItemToObject(o, "box", cli_json_numbers(r->L, 3));
  cJSON_AddItemToObject(o, "probe", cli_json_numbers(r->probe, 3));
  cJSON_AddNumberToObject(o, "tetrahedra", (double)r->n_tetrahedra);
  cJSON_AddNumberToObject(o, "edges", (double)r->n_edges);
  cJSON_AddNumberToObject(o, "faces", (double)r->n_faces);
  cJSON_AddItemToObject(o, "analytic", cli_json_numbers(r->analytic, r->n_check));
  cJSON_AddBoolToObject(o, "positive_stars", r->positive);
  if (r->positive) cJSON_AddItemToObject(o, "avi", json_run(&r->avi));
  cJSON_AddItemToObject(o, "whitney", json_run(&r->whitney));
  if (r->positive) {
    cJSON *c = cJSON_AddObjectToObject(o, "cost");
    cJSON_AddNumberToObject(c, "uniform_dt", r->uniform_dt);
    cJSON_AddNumberToObject(c, "uniform_steps", (double)r->uniform_steps);
    cJSON_AddNumberToObject(c, "uniform_face_updates", r->uniform_face_updates);
    cJSON_AddNumberToObject(c, "uniform_cpu_s", r->uniform_cpu_s);
    cJSON_AddNumberToObject(c, "avi_face_updates", (double)r->avi_face_updates);
    cJSON_AddNumberToObject(c, "avi_cpu_s", r->avi_cpu_s);
    cJSON_AddNumberToObject(c, "whitney_steps", (double)r->whitney_steps);
    cJSON_AddNumberToObject(c, "whitney_cpu_s", r->whitney_cpu_s);
  }
  cJSON_AddNumberToObject(o, "wall_s", r->wall_s);
  if (png != NULL) cJSON_AddStringToObject(o, "plot", png);
  return cli_json_print(o);
}

int cli_maxwell_mesh_e5(const gm_mesh *mesh, const char *out_dir, double t_end, uint64_t seed,
                        double f_max, double fraction, double sample_dt, double t_compare,
                        int json) {
  if (out_dir && mx_make_dir(E5, out_dir) != CLI_EXIT_OK) return CLI_EXIT_FAILURE;
  gm_e5_config c = gm_e5_defaults();
  c.t_end = t_end;
  c.seed = seed;
  c.f_max = f_max;
  c.fraction = fraction;
  c.sample_dt = sample_dt;
  c.t_compare = t_compare;
  mx_progress progress;
  mx_progress_start(&progress, 0);
  c.progress = show_progress;
  c.progress_ctx = &progress;
  gm_e5_result r;
  gm_error err = {{0}};
  gm_status st = gm_experiment_e5(mesh, &c, &r, &err);
  mx_progress_end(&progress);
  if (st != GM_OK) {
    cli_error(E5, "%s", err.message);
    return st == GM_EINVAL ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  char png_buf[4096];
  const char *png = NULL;
  if (out_dir)
    png = r.positive ? plot(&r, &r.avi, out_dir, "E5: Gmsh cavity refined near the walls, AVI "
                            "(diagonal star); dashed: analytic resonances", png_buf,
                            sizeof png_buf)
                     : plot(&r, &r.whitney, out_dir, "E5: Gmsh cavity refined near the walls, "
                            "leapfrog (Whitney star); dashed: analytic resonances", png_buf,
                            sizeof png_buf);
  if (json) {
    const int rc = print_json(&r, png);
    gm_e5_result_clear(&r);
    return rc;
  }
  const double *L = r.L, *x = r.probe;
  printf("E5: PEC box %.4g x %.4g x %.4g, random initial E (seed %llu), t = %g, E at (%.3g, "
         "%.3g, %.3g)\n", L[0], L[1], L[2], (unsigned long long)seed, t_end, x[0], x[1], x[2]);
  printf("1. Gmsh mesh: %zu tetrahedra, %zu edges, %zu faces; cell volumes %.3g .. %.3g (ratio "
         "%.0f)\n", r.n_tetrahedra, r.n_edges, r.n_faces, r.volume_min, r.volume_max,
         r.volume_max / r.volume_min);
  if (r.positive && r.have_limits)
    printf("   circumcentric stars: positive on every interior edge and face (the mesh is "
           "Delaunay)\n   CFL limit of the whole mesh %.3g; local face limits %.3g .. %.3g, "
           "median %.3g; %zu faces below 1/4 of the median (near-cospherical vertices)\n",
           r.cfl_limit, r.face_limit_min, r.face_limit_max, r.face_limit_median, r.small_faces);
  else if (!r.positive)
    printf("   circumcentric stars: %s\n   -> the AVI cannot run here (it needs a positive "
           "diagonal star): make the mesh with examples/e5_cavity.geo (Delaunay, no "
           "optimisation); the Whitney leapfrog runs alone\n", r.star_message);
  if (r.positive) {
    printf("2. AVI: every face at %.2g of its local limit in %zu power-of-two groups, smallest "
           "step %.3g; E sampled every %.3g; %zu face updates, %.2f s CPU\n", fraction,
           r.avi.avi_groups, r.avi.dt, sample_dt, r.avi.face_updates, r.avi.cpu_s);
    print_spectrum(&r, &r.avi.spectrum);
    print_invariants(&r.avi);
    if (png) printf("   wrote %s\n", png);
  }
  printf("3. leapfrog, Whitney star (CHOLMOD): dt %.4g (0.9 of its CFL limit), %zu steps, %.2f s "
         "CPU\n", r.whitney.dt, r.whitney.steps, r.whitney.cpu_s);
  print_spectrum(&r, &r.whitney.spectrum);
  print_invariants(&r.whitney);
  if (png && !r.positive) printf("   wrote %s\n", png);
  if (r.positive) {
    printf("4. cost to t = %g:\n   uniform leapfrog (diagonal star) at the AVI's smallest step "
           "%.4g: %zu steps, %.0f face updates, %.3f s CPU\n", t_compare, r.uniform_dt,
           r.uniform_steps, r.uniform_face_updates, r.uniform_cpu_s);
    printf("   AVI: %zu face updates, ratio to uniform %.4f; %.3f s CPU: time ratio AVI/uniform "
           "%.4f (%s)\n", r.avi_face_updates, (double)r.avi_face_updates / r.uniform_face_updates,
           r.avi_cpu_s, r.avi_cpu_s / r.uniform_cpu_s,
           r.avi_cpu_s < r.uniform_cpu_s ? "faster" : "NOT faster");
    printf("   leapfrog, Whitney star at its own step: %zu steps, %.3f s CPU: time ratio "
           "AVI/Whitney %.3f (%s)\n", r.whitney_steps, r.whitney_cpu_s,
           r.avi_cpu_s / r.whitney_cpu_s,
           r.avi_cpu_s < r.whitney_cpu_s ? "the AVI is faster" : "the Whitney leapfrog is faster");
  }
  gm_e5_result_clear(&r);
  return CLI_EXIT_OK;
}
