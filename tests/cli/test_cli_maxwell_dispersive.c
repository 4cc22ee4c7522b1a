/* geomint maxwell run with dispersive scenes and the harminv parameters of the scene: the basis
 * size reaches harminv (a basis too small for the band loses the modes, the default finds
 * them), the mode filter is applied, a Drude scene runs, and the checks name the JSON path. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <cJSON.h>

#include "cli/cli_harness.h"

TestSuite(cli_maxwell_dispersive, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 300);

static void write_cavity(const char *name, const char *harminv_extra) {
  FILE *f = fopen(path_in_tmp(name), "w");
  cr_assert_not_null(f);
  fprintf(f,
          "{\"grid\": {\"dim\": \"2d-tm\", \"cells\": [20, 16], \"size\": [1.0, 0.8]},\n"
          " \"sources\": [{\"type\": \"point\", \"component\": \"Ez\", \"position\": [0.39, 0.63],\n"
          "   \"waveform\": {\"kind\": \"gaussian\", \"frequency\": 1.0, \"width\": 0.64,"
          " \"delay\": 4}}],\n"
          " \"probes\": [{\"name\": \"p\", \"component\": \"Ez\", \"position\": [0.83, 0.21]}],\n"
          " \"output\": {\"harminv\": {\"f_min\": 0.5, \"f_max\": 1.5, \"after\": 8%s}},\n"
          " \"run\": {\"time\": 100}}\n",
          harminv_extra);
  fclose(f);
}

static size_t n_resonances(const char *out) {
  cJSON *o = parse_json(out);
  const cJSON *modes =
      cJSON_GetObjectItem(cJSON_GetArrayItem(cJSON_GetObjectItem(o, "probes"), 0), "resonances");
  const size_t n = (size_t)cJSON_GetArraySize(modes);
  cJSON_Delete(o);
  return n;
}

/* The PEC cavity has 3 TM modes in [0.5, 1.5] (test_cli_maxwell.c). Measured: the default basis
 * keeps 3; a basis of 2 functions for the band cannot hold 3 modes and keeps fewer; a filter
 * max_error 1e-30 keeps none. */
Test(cli_maxwell_dispersive, harminv_parameters_reach_harminv) {
  write_cavity("a.json", "");
  run_output r = run_cli("maxwell run a.json --out out --json --threads 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  const size_t n_default = n_resonances(r.out);
  run_output_free(&r);
  cr_expect_eq(n_default, 3);

  write_cavity("b.json", ", \"basis\": 2");
  r = run_cli("maxwell run b.json --out out --json --threads 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect_lt(n_resonances(r.out), 3);
  run_output_free(&r);

  write_cavity("c.json", ", \"max_error\": 1e-30");
  r = run_cli("maxwell run c.json --out out --json --threads 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect_eq(n_resonances(r.out), 0);
  run_output_free(&r);

  /* --check refuses what cannot work before running: f_max above Nyquist, after past the end */
  write_cavity("d.json", ", \"basis\": 40, \"min_q\": 5, \"min_amplitude\": 0.01");
  r = run_cli("maxwell run d.json --check");
  cr_expect_eq(r.status, 0, "%s", r.err);
  run_output_free(&r);
  FILE *f = fopen(path_in_tmp("e.json"), "w");
  cr_assert_not_null(f);
  fputs("{\"grid\": {\"dim\": \"1d\", \"cells\": [10], \"size\": [1]},"
        " \"probes\": [{\"component\": \"Ez\", \"position\": [0.5]}],"
        " \"output\": {\"harminv\": {\"f_min\": 0.1, \"f_max\": 2, \"after\": 3}},"
        " \"run\": {\"time\": 2}}", f);
  fclose(f);
  r = run_cli("maxwell run e.json --check");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "e.json: output.harminv.after: 3 is at or beyond the end of the run") !=
                NULL, "%s", r.err);
  run_output_free(&r);
}

/* A zero probe signal (the pulse never reaches the probe) is a harminv failure: exit 1 with
 * the message (the harminv library used to end the process from inside). */
Test(cli_maxwell_dispersive, harminv_on_a_zero_signal_is_a_failed_run) {
  FILE *f = fopen(path_in_tmp("z.json"), "w");
  cr_assert_not_null(f);
  fputs("{\"grid\": {\"dim\": \"1d\", \"cells\": [200], \"size\": [10]},"
        " \"sources\": [{\"type\": \"point\", \"component\": \"Ez\", \"position\": [0.5],"
        " \"waveform\": {\"kind\": \"gaussian\", \"frequency\": 1, \"width\": 0.5, \"delay\": 2}}],"
        " \"probes\": [{\"name\": \"far\", \"component\": \"Ez\", \"position\": [9.5]}],"
        " \"output\": {\"harminv\": {\"f_min\": 0.3, \"f_max\": 2}},"
        " \"run\": {\"time\": 2}}", f);
  fclose(f);
  run_output r = run_cli("maxwell run z.json --out o");
  cr_expect_eq(r.status, 1, "exit %d: %s", r.status, r.err);
  cr_expect(strstr(r.err, "probe far: harminv failed: harminv: the signal is zero") != NULL, "%s",
            r.err);
  run_output_free(&r);
}

/* A Drude box from the library's gold in a 1-D scene runs; bad poles are exit 2 naming them. */
Test(cli_maxwell_dispersive, drude_scene_runs_and_bad_poles_are_named) {
  FILE *f = fopen(path_in_tmp("au.json"), "w");
  cr_assert_not_null(f);
  fputs("{\"unit_um\": 1, \"grid\": {\"dim\": \"1d\", \"cells\": [400], \"size\": [4]},"
        " \"materials\": [{\"shape\": \"box\", \"lo\": [2], \"hi\": [2.5], \"library\": \"Au\"}],"
        " \"sources\": [{\"type\": \"point\", \"component\": \"Ez\", \"position\": [1],"
        " \"waveform\": {\"kind\": \"gaussian\", \"frequency\": 1, \"width\": 0.5, \"delay\": 2}}],"
        " \"output\": {\"energy_every\": 10},"
        " \"run\": {\"time\": 8}}", f);
  fclose(f);
  run_output r = run_cli("maxwell run au.json --out o --json");
  cr_expect_eq(r.status, 0, "%s", r.err);
  run_output_free(&r);
  /* energy.csv carries the poles' energy as a fifth column */
  f = fopen(path_in_tmp("o/energy.csv"), "r");
  cr_assert_not_null(f);
  char line[256] = "", row[512] = "";
  cr_assert_not_null(fgets(line, sizeof line, f));
  while (fgets(row, sizeof row, f) != NULL) {
  }
  fclose(f);
  cr_expect(strstr(line, "leapfrog,polarization") != NULL, "%s", line);
  double t, v[5];
  cr_assert_eq(sscanf(row, "%lf,%lf,%lf,%lf,%lf,%lf", &t, &v[0], &v[1], &v[2], &v[3], &v[4]), 6,
               "%s", row);
  cr_expect_gt(v[4], 0.0, "the gold slab holds polarization energy at the end: %s", row);
  f = fopen(path_in_tmp("bad.json"), "w");
  cr_assert_not_null(f);
  fputs("{\"grid\": {\"dim\": \"1d\", \"cells\": [40], \"size\": [4]},"
        " \"materials\": [{\"shape\": \"box\", \"lo\": [2], \"hi\": [2.5],"
        " \"poles\": [{\"type\": \"lorentz\", \"frequency\": 1, \"gamma\": -1, \"delta_epsilon\": 1}]}],"
        " \"run\": {\"time\": 1}}", f);
  fclose(f);
  r = run_cli("maxwell run bad.json --check");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "bad.json: materials[0].poles[0].gamma: the damping rate must be >= 0") !=
                NULL, "%s", r.err);
  run_output_free(&r);
}

/* ---- "dft": flux spectra from scenes ----------------------------------------------------- */

static void write_slab(const char *name, int slab, const char *dft_file_key) {
  FILE *f = fopen(path_in_tmp(name), "w");
  cr_assert_not_null(f);
  fprintf(f,
          "{\"grid\": {\"dim\": \"1d\", \"cells\": [1200], \"size\": [6]},"
          " \"boundaries\": {\"x\": \"cpml\"}, \"pml\": {\"thickness\": 80},"
          " %s"
          " \"sources\": [{\"type\": \"point\", \"component\": \"Ez\", \"position\": [1],"
          " \"waveform\": {\"kind\": \"gaussian\", \"frequency\": 0.6, \"width\": 0.4,"
          " \"delay\": 2.4}}],"
          " \"flux\": [{\"name\": \"refl\", \"axis\": \"x\", \"position\": 2},"
          " {\"name\": \"trans\", \"axis\": \"x\", \"position\": 5}],"
          " \"dft\": {\"f_min\": 0.2, \"f_max\": 1.0, \"n\": 41, %s},"
          " \"run\": {\"time\": 60}}",
          slab ? "\"materials\": [{\"shape\": \"box\", \"lo\": [3], \"hi\": [4], \"epsilon\": 4}],"
               : "",
          dft_file_key);
  fclose(f);
}

/* A dielectric slab (n = 2, d = 1; 100 cells per wavelength in it at f = 1, 500 at f = 0.2)
 * by two scene runs, the vacuum one saving its transforms and the slab one subtracting them:
 * T and R from flux_spectra.csv against the Airy formula T = 1/(1 + F sin²(2πndf)),
 * F = 4R₀/(1 − R₀)². Measured max |T − T_Airy| 6.4e-4, max |R − R_Airy| 6.4e-4 (the C-API
 * test's numbers: the same run). */
Test(cli_maxwell_dispersive, slab_spectrum_from_scenes_against_airy) {
  write_slab("vac.json", 0, "\"save\": \"inc.dat\"");
  run_output r = run_cli("maxwell run vac.json --out v --threads 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  run_output_free(&r);
  write_slab("slab.json", 1, "\"subtract\": \"inc.dat\"");
  r = run_cli("maxwell run slab.json --out s --threads 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  run_output_free(&r);
  FILE *f = fopen(path_in_tmp("s/flux_spectra.csv"), "r");
  cr_assert_not_null(f);
  char header[256];
  cr_assert_not_null(fgets(header, sizeof header, f));
  cr_expect_str_eq(header, "frequency,refl,refl_scattered,refl_incident,trans,trans_scattered,"
                           "trans_incident\n");
  const double n = 2, d = 1, pi = 3.14159265358979323846;
  const double r0 = (n - 1) * (n - 1) / ((n + 1) * (n + 1)), F = 4 * r0 / ((1 - r0) * (1 - r0));
  double et = 0, er = 0, fr, rt, rf, ri, tf, ts, ti;
  int rows = 0;
  while (fscanf(f, "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &fr, &rt, &rf, &ri, &tf, &ts, &ti) == 7) {
    const double s = sin(2 * pi * n * d * fr), Ta = 1 / (1 + F * s * s);
    et = fmax(et, fabs(tf / ti - Ta));
    er = fmax(er, fabs(-rf / ri - (1 - Ta)));
    ++rows;
  }
  fclose(f);
  printf("scene slab vs Airy: max |T - T_Airy| %.3g, max |R - R_Airy| %.3g\n", et, er);
  cr_expect_eq(rows, 41);
  cr_expect_lt(et, 1e-3, "%g", et);
  cr_expect_lt(er, 1e-3, "%g", er);
}

/* Bad dft input: f_max above Nyquist, a plane inside the CPML, a normalisation file of another
 * run; each names the key. */
Test(cli_maxwell_dispersive, bad_dft_input_names_the_key) {
  write_slab("a.json", 0, "\"save\": \"x.dat\"");
  char *text = NULL;
  FILE *f = fopen(path_in_tmp("a.json"), "r");
  cr_assert_not_null(f);
  char buf[4096];
  size_t len = fread(buf, 1, sizeof buf - 1, f);
  buf[len] = '\0';
  fclose(f);
  (void)text;
  struct {
    const char *from, *to, *needle;
  } cases[] = {
      {"\"f_max\": 1.0", "\"f_max\": 150", "b.json: dft.f_max: 150 is at or above the Nyquist"},
      {"\"position\": 5}", "\"position\": 5.7}", "b.json: flux[1].position: 5.7 lies in the upper CPML"},
      {"\"position\": 2}", "\"position\": 6.5}", "b.json: flux[0].position: 6.5 is not inside the grid"},
      {"\"n\": 41", "\"n\": 0", "b.json: dft.n: must be in 1 .. 100000"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
    char *at = strstr(buf, cases[k].from);
    cr_assert_not_null(at, "%s", cases[k].from);
    FILE *g = fopen(path_in_tmp("b.json"), "w");
    fprintf(g, "%.*s%s%s", (int)(at - buf), buf, cases[k].to, at + strlen(cases[k].from));
    fclose(g);
    run_output r = run_cli("maxwell run b.json --check");
    cr_expect_eq(r.status, 2, "%s", r.err);
    cr_expect(strstr(r.err, cases[k].needle) != NULL, "expected '%s' in %s", cases[k].needle,
              r.err);
    run_output_free(&r);
  }
  /* a normalisation file from another run (other frequencies) is a run failure naming dft */
  write_slab("c.json", 0, "\"save\": \"c.dat\"");
  run_output r = run_cli("maxwell run c.json --out c --threads 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  run_output_free(&r);
  char *at = strstr(buf, "\"n\": 41, \"save\": \"x.dat\"");
  cr_assert_not_null(at);
  FILE *g = fopen(path_in_tmp("d.json"), "w");
  fprintf(g, "%.*s\"n\": 40, \"subtract\": \"c.dat\"%s", (int)(at - buf), buf,
          at + strlen("\"n\": 41, \"save\": \"x.dat\""));
  fclose(g);
  r = run_cli("maxwell run d.json --out d --threads 1");
  cr_expect_eq(r.status, 1, "%s", r.err);
  cr_expect(strstr(r.err, "dft.subtract: dft subtract: c.dat: flux plane 0 differs") != NULL, "%s",
            r.err);
  run_output_free(&r);
}
