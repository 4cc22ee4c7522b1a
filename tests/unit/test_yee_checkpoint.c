/* Checkpoint/restart of the Yee solver (geomint/yee_checkpoint.h): a run cut by a checkpoint and
 * continued in a freshly built solver is bitwise the uninterrupted run, with every kind of state
 * the file carries (CPML ψ, a TF/SF incident grid, a soft E source's charge, lossy media, probes);
 * a foreign, truncated or missing file is an error with a message. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include <math.h>

#include "geomint/fields.h"
#include "geomint/yee_checkpoint.h"

#define STEPS 80
#define CUT 33

static gm_yee *build(size_t ny) {
  const gm_yee_grid g = {GM_YEE_2D_TM, {40, ny, 1}, {0.1, 0.1, 1.0}, {0, 0, 0}};
  gm_yee_materials *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_yee_materials_create(&g, &m, &err), GM_OK);
  const gm_medium lossy = {2.0, 1.0, 0.4};
  const double c[3] = {2.6, 1.5, 0.0};
  cr_assert_eq(gm_yee_paint_sphere(m, c, 0.5, &lossy), GM_OK);
  gm_yee_options o = gm_yee_defaults();
  for (int f = 0; f < 4; ++f) {
    o.boundary[f].kind = GM_BOUNDARY_CPML;
    o.boundary[f].pml.thickness = 6;
  }
  gm_yee *s = NULL;
  cr_assert_eq(gm_yee_create(&g, m, &o, &s, &err), GM_OK, "%s", err.message);
  gm_yee_materials_free(m);
  const gm_waveform w = {.kind = GM_WAVE_GAUSSIAN, .amplitude = 1.0, .frequency = 1.5,
                         .width = 0.3, .delay = 1.2};
  const gm_plane_wave pw = {0, 1, GM_EZ, {9, 9, 0}, {30, ny - 9, 0}, w};
  cr_assert_eq(gm_yee_add_plane_wave(s, &pw, NULL), GM_OK, "%s", gm_yee_errmsg(s));
  const gm_point_source ps = {GM_EZ, {1.5, 1.2, 0}, GM_SOURCE_SOFT, w};
  cr_assert_eq(gm_yee_add_point_source(s, &ps, NULL), GM_OK);
  const double x[3] = {2.2, 1.4, 0};
  cr_assert_eq(gm_yee_add_probe(s, GM_EZ, x, STEPS, NULL), GM_OK);
  return s;
}

Test(yee_checkpoint, restart_is_bitwise_the_uninterrupted_run) {
  const char *path = "test_yee_checkpoint.bin";
  gm_yee *a = build(30), *b = build(30);
  cr_assert_eq(gm_yee_advance(a, CUT), GM_OK);
  cr_assert_eq(gm_yee_checkpoint_write(a, path), GM_OK, "%s", gm_yee_errmsg(a));
  cr_assert_eq(gm_yee_advance(a, STEPS - CUT), GM_OK);
  cr_assert_eq(gm_yee_checkpoint_read(b, path), GM_OK, "%s", gm_yee_errmsg(b));
  cr_assert_eq(gm_yee_step(b), CUT);
  cr_assert_eq(gm_yee_advance(b, STEPS - CUT), GM_OK);
  gm_yee_layout L;
  gm_yee_get_layout(a, &L);
  for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
    const double *fa = gm_yee_field(a, (gm_yee_component)c, 0);
    if (fa == NULL) continue;
    cr_assert(memcmp(fa, gm_yee_field(b, (gm_yee_component)c, 0), L.size * sizeof(double)) == 0,
              "%s differs after the restart", gm_yee_component_name((gm_yee_component)c));
  }
  size_t na, nb;
  const double *ra, *rb;
  gm_yee_probe_samples(a, 0, &na, NULL, &ra, NULL);
  gm_yee_probe_samples(b, 0, &nb, NULL, &rb, NULL);
  cr_assert_eq(na, STEPS);
  cr_assert_eq(nb, STEPS);
  cr_assert(memcmp(ra, rb, na * sizeof(double)) == 0, "probe differs after the restart");
  double peak = 0.0;
  for (size_t i = 0; i < na; ++i) peak = fmax(peak, fabs(ra[i]));
  cr_assert_gt(peak, 1e-3, "the probe saw nothing (peak %g)", peak);
  /* another grid */
  gm_yee *c = build(32);
  cr_assert_eq(gm_yee_checkpoint_read(c, path), GM_EINVAL);
  cr_assert(strstr(gm_yee_errmsg(c), "another solver") != NULL, "%s", gm_yee_errmsg(c));
  /* truncated */
  FILE *f = fopen(path, "r+b");
  cr_assert_not_null(f);
  fseek(f, 0, SEEK_END);
  const long size = ftell(f);
  fclose(f);
  cr_assert_eq(truncate(path, size / 2), 0);
  gm_yee *d = build(30);
  cr_assert_eq(gm_yee_checkpoint_read(d, path), GM_EIO);
  cr_assert(strstr(gm_yee_errmsg(d), "truncated") != NULL, "%s", gm_yee_errmsg(d));
  remove(path);
  cr_assert_eq(gm_yee_checkpoint_read(d, path), GM_EIO);
  cr_assert(strstr(gm_yee_errmsg(d), "cannot read") != NULL, "%s", gm_yee_errmsg(d));
  gm_yee_free(a);
  gm_yee_free(b);
  gm_yee_free(c);
  gm_yee_free(d);
}
