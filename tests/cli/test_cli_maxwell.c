/* geomint maxwell run / cavity / e4: the documented output, the files a run writes, the
 * numbers the checks print (cavity resonances against Yee's dispersion relation, E4's energy),
 * and exit statuses for malformed scenes (the message names the JSON path) and bad
 * arguments. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <cJSON.h>

#include "geomint/io.h"

#include "cli/cli_harness.h"

TestSuite(cli_maxwell, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 300);

static void write_text(const char *name, const char *text) {
  FILE *f = fopen(path_in_tmp(name), "w");
  cr_assert_not_null(f);
  fputs(text, f);
  fclose(f);
}

/* gnuplot on PATH (as the program looks for it) */
static int cli_gnuplot_available_here(void) { return system("command -v gnuplot >/dev/null 2>&1") == 0; }

static int file_exists(const char *name) {
  struct stat sb;
  return stat(path_in_tmp(name), &sb) == 0 && sb.st_size > 0;
}

/* A small valid scene; `extra` is spliced in before "run" (it must end with a comma). */
static void write_scene(const char *name, const char *extra, const char *run) {
  char text[4096];
  snprintf(text, sizeof text,
           "{\"grid\": {\"dim\": \"2d-tm\", \"cells\": [24, 20], \"size\": [1.2, 1.0]},\n"
           " \"sources\": [{\"type\": \"point\", \"component\": \"Ez\", \"position\": [0.31, 0.43],\n"
           "   \"waveform\": {\"kind\": \"dgaussian\", \"width\": 0.08, \"delay\": 0.5}},\n"
           "   {\"type\": \"point\", \"component\": \"Hx\", \"position\": [0.7, 0.6, 0],\n"
           "   \"waveform\": {\"kind\": \"ricker\", \"frequency\": 1.5, \"delay\": 1}}],\n"
           " \"probes\": [{\"name\": \"a\", \"component\": \"Ez\", \"position\": [0.83, 0.27]},\n"
           "   {\"component\": \"Hy\", \"position\": [0.5, 0.5]}],\n"
           " %s\n"
           " \"run\": %s}\n",
           extra, run);
  write_text(name, text);
}

static run_output expect_usage_error(const char *scene_name, const char *needle) {
  run_output r = run_cli("maxwell run %s --out out", scene_name);
  cr_expect_eq(r.status, 2, "exit %d for %s: %s", r.status, scene_name, r.err);
  cr_expect(strstr(r.err, needle) != NULL, "expected '%s' in: %s", needle, r.err);
  cr_expect_eq(count_lines(r.err), 1, "one line: %s", r.err);
  cr_expect_eq(r.out[0], '\0', "nothing on stdout: %s", r.out);
  return r;
}

/* ---- help and bad arguments -------------------------------------------------------------- */

Test(cli_maxwell, help_and_bad_subcommands) {
  run_output r = run_cli("maxwell --help");
  cr_expect_eq(r.status, 0);
  cr_expect(strstr(r.out, "geomint maxwell run SCENE.json") != NULL);
  cr_expect(strstr(r.out, "geomint maxwell cavity") != NULL);
  cr_expect(strstr(r.out, "geomint maxwell e4") != NULL);
  run_output_free(&r);
  r = run_cli("help maxwell");
  cr_expect_eq(r.status, 0);
  cr_expect(strstr(r.out, "Exit status") != NULL);
  run_output_free(&r);
  r = run_cli("--help");
  cr_expect(strstr(r.out, "maxwell") != NULL, "listed in the commands: %s", r.out);
  run_output_free(&r);
  r = run_cli("maxwell");
  cr_expect_eq(r.status, 2);
  run_output_free(&r);
  r = run_cli("maxwell bogus");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "unknown subcommand 'bogus'") != NULL, "%s", r.err);
  run_output_free(&r);
  const char *bad[] = {"maxwell run", "maxwell run a.json b.json", "maxwell run x.json --bogus",
                       "maxwell cavity --dim 4", "maxwell cavity --n 2", "maxwell cavity --n x",
                       "maxwell cavity --periods 1", "maxwell e4 --time -1", "maxwell e4 --n 1",
                       "maxwell e4 extra"};
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
    r = run_cli("%s", bad[k]);
    cr_expect_eq(r.status, 2, "'%s' exited %d: %s", bad[k], r.status, r.err);
    cr_expect_eq(count_lines(r.err), 1, "'%s': %s", bad[k], r.err);
    run_output_free(&r);
  }
}

/* ---- malformed scenes: exit 2, one line naming the JSON path ----------------------------- */

Test(cli_maxwell, malformed_scenes_name_the_json_path) {
  run_output r = run_cli("maxwell run missing.json");
  cr_expect_eq(r.status, 2);
  cr_expect(strstr(r.err, "cannot open missing.json") != NULL, "%s", r.err);
  run_output_free(&r);

  write_text("syntax.json", "{\"grid\": {\"dim\": \"3d\",\n \"cells\": [4, 4 4]}}\n");
  r = expect_usage_error("syntax.json", "syntax.json: line 2, column");
  run_output_free(&r);

  /* the example of the issue: a string where a coordinate belongs */
  char text[4096];
  write_scene("p.json", "", "{\"steps\": 10}");
  char *scene = read_file(path_in_tmp("p.json"));
  char *at = strstr(scene, "[0.7, 0.6, 0]");
  cr_assert_not_null(at);
  snprintf(text, sizeof text, "%.*s[0.7, 0.6, \"zero\"]%s", (int)(at - scene), scene, at + 13);
  write_text("p.json", text);
  free(scene);
  r = expect_usage_error("p.json", "p.json: sources[1].position[2]: expected a number, got a string");
  run_output_free(&r);

  struct {
    const char *extra, *run, *needle;
  } cases[] = {
      {"", "{}", "run: missing \"steps\" (or \"time\")"},
      {"", "{\"steps\": 10, \"time\": 1}", "run: give \"steps\" or \"time\", not both"},
      {"", "{\"steps\": -3}", "run.steps: expected a non-negative integer"},
      {"", "{\"steps\": 10, \"courant\": 1.5}", "run.courant: must be in (0, 1]"},
      {"\"materials\": [{\"shape\": \"box\", \"lo\": [0, 0], \"hi\": [1, 1], \"epsilon\": -2}],",
       "{\"steps\": 10}", "materials[0].epsilon: must be > 0, got -2"},
      {"\"materials\": [{\"shape\": \"sphere\", \"center\": [0, 0], \"radius\": 1, \"mu\": 0}],",
       "{\"steps\": 10}", "materials[0].mu: must be > 0"},
      {"\"materials\": [{\"shape\": \"cone\"}],", "{\"steps\": 10}",
       "materials[0].shape: unknown shape \"cone\""},
      {"\"materials\": [{\"shape\": \"box\", \"lo\": [0, 0], \"hi\": [1, 1], \"epsilom\": 2}],",
       "{\"steps\": 10}", "materials[0].epsilom: unknown key (did you mean 'epsilon'?)"},
      {"\"boundaries\": {\"x\": \"cpml\", \"z\": \"pec\"},", "{\"steps\": 10}",
       "boundaries.z: this grid has no z axis"},
      {"\"boundaries\": {\"y\": [\"pec\", \"absorbing\"]},", "{\"steps\": 10}",
       "boundaries.y[1]: unknown boundary \"absorbing\""},
      {"\"pml\": {\"thickness\": 2.5},", "{\"steps\": 10}",
       "pml.thickness: expected a non-negative integer"},
      {"\"output\": {\"formats\": [\"vtk\"]},", "{\"steps\": 10}",
       "output.formats[0]: expected \"vti\" or \"h5\""},
      {"\"output\": {\"harminv\": {\"f_min\": 2, \"f_max\": 1}},", "{\"steps\": 10}",
       "output.harminv: expected 0 <= f_min < f_max"},
      {"\"output\": {\"harminv\": {\"f_min\": 0.5, \"f_max\": 20}},", "{\"steps\": 10}",
       "output.harminv.f_max: 20 is above the Nyquist frequency 1/(2 dt) = 14.28"},
      {"\"output\": {\"harminv\": {\"f_min\": 0.5, \"f_max\": 2, \"after\": 5}},",
       "{\"steps\": 10}", "output.harminv.after: 5 is at or beyond the end of the run (t = 0.35"},
      {"\"output\": {\"harminv\": {\"f_min\": 0.5, \"f_max\": 2, \"basis\": 1}},",
       "{\"steps\": 10}", "output.harminv.basis: must be 0 (harminv's default) or 2 .. 1000"},
      {"\"output\": {\"harminv\": {\"f_min\": 0.5, \"f_max\": 2, \"basis\": 50}},",
       "{\"steps\": 10}", "output.harminv.basis: 50 basis functions for about 11 samples"},
      {"\"output\": {\"harminv\": {\"f_min\": 0.5, \"f_max\": 2, \"max_error\": 0}},",
       "{\"steps\": 10}", "output.harminv.max_error: must be in (0, 1]"},
      {"\"flux\": [{\"axis\": \"x\", \"position\": 7}],", "{\"steps\": 10}",
       "flux[0].position: 7 is not inside the grid: a flux plane lies in [0.05, 1.15]"},
      {"\"flux\": [{\"axis\": \"y\", \"position\": 0.01}],", "{\"steps\": 10}",
       "flux[0].position: 0.01 is not inside the grid"},
      {"\"bloch_k\": [0, \"1\", 0],", "{\"steps\": 10}", "bloch_k[1]: expected a number"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
    write_scene("c.json", cases[k].extra, cases[k].run);
    r = expect_usage_error("c.json", cases[k].needle);
    run_output_free(&r);
  }

  write_text("g.json", "{\"grid\": {\"dim\": \"3d\", \"cells\": [8, 0, 8], \"h\": [1, 1, 1]},"
                       " \"run\": {\"steps\": 1}}");
  r = expect_usage_error("g.json", "grid.cells[1]: expected a positive whole number of cells");
  run_output_free(&r);
  write_text("g.json", "{\"grid\": {\"dim\": \"4d\", \"cells\": [8]}, \"run\": {\"steps\": 1}}");
  r = expect_usage_error("g.json", "grid.dim: expected \"1d\", \"2d-te\", \"2d-tm\" or \"3d\"");
  run_output_free(&r);
  write_text("g.json", "[1, 2]");
  r = expect_usage_error("g.json", "g.json: (top level): expected an object, got an array");
  run_output_free(&r);
  write_text("g.json", "{\"grid\": {\"dim\": \"2d-te\", \"cells\": [8, 8], \"size\": [1, 1]},"
                       " \"probes\": [{\"component\": \"Ez\", \"position\": [0.5, 0.5]}],"
                       " \"run\": {\"steps\": 1}}");
  r = expect_usage_error("g.json", "probes[0].component: this grid has no Ez component");
  run_output_free(&r);
}

/* Errors the solver finds (the scene is well-formed JSON) are bad input too. */
Test(cli_maxwell, solver_rejections_are_bad_input) {
  write_scene("s.json", "", "{\"steps\": 10, \"dt\": 1.0}");
  run_output r = expect_usage_error("s.json", "Courant");
  run_output_free(&r);
  write_scene("s.json", "\"boundaries\": {\"x\": \"cpml\"}, \"pml\": {\"thickness\": 12},",
              "{\"steps\": 10}");
  r = run_cli("maxwell run s.json");
  cr_expect_eq(r.status, 2, "a PML thicker than the grid: %s", r.err);
  cr_expect(strstr(r.err, "s.json") != NULL, "%s", r.err);
  run_output_free(&r);
  char text[4096];
  write_scene("s.json", "", "{\"steps\": 10}");
  char *scene = read_file(path_in_tmp("s.json"));
  char *at = strstr(scene, "[0.7, 0.6, 0]");
  snprintf(text, sizeof text, "%.*s[7.0, 0.6, 0]%s", (int)(at - scene), scene, at + 13);
  write_text("s.json", text);
  free(scene);
  r = expect_usage_error("s.json", "s.json: sources[1]:");
  run_output_free(&r);
}

/* ---- a run: files and summary ------------------------------------------------------------ */

Test(cli_maxwell, run_writes_probes_energy_flux_and_snapshots) {
  write_scene("scene.json",
              "\"flux\": [{\"name\": \"mid\", \"axis\": \"x\", \"position\": 0.6}],"
              " \"output\": {\"snapshot_every\": 50, \"formats\": [\"vti\", \"h5\"],"
              " \"encoding\": \"base64\", \"materials\": true, \"energy_every\": 5,"
              " \"harminv\": {\"f_min\": 0.3, \"f_max\": 3.0, \"after\": 2.0}},",
              "{\"steps\": 120, \"courant\": 0.9}");
  run_output r = run_cli("maxwell run scene.json --out out --json --threads 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_eq(json_number(o, "steps"), 120);
  double dt = json_number(o, "dt");
  /* the Courant limit of a 0.05 x 0.05 grid is 0.05 / sqrt(2) */
  cr_expect_float_eq(dt, 0.9 * 0.05 / sqrt(2.0), 1e-12);
  cr_expect_float_eq(json_number(o, "t_final"), 120 * dt, 1e-12);
  cr_expect_eq(json_number(o, "snapshots"), 4, "steps 0, 50, 100 and the last");
  const cJSON *probes = cJSON_GetObjectItem(o, "probes");
  cr_assert_eq(cJSON_GetArraySize(probes), 2);
  cr_expect_str_eq(json_string(cJSON_GetArrayItem(probes, 0), "name"), "a");
  cr_expect_str_eq(json_string(cJSON_GetArrayItem(probes, 1), "name"), "Hy_1");
  const cJSON *flux = cJSON_GetArrayItem(cJSON_GetObjectItem(o, "flux"), 0);
  cr_expect_eq(json_number(flux, "plane"), 12);
  cr_expect(isfinite(json_number(flux, "integral")));
  const cJSON *energy = cJSON_GetObjectItem(o, "energy");
  cr_expect_gt(json_number(energy, "final"), 0);
  cJSON_Delete(o);
  run_output_free(&r);

  /* probes.csv: header, one whole row per step, t and t_e half a step apart */
  char *csv = read_file(path_in_tmp("out/probes.csv"));
  cr_expect(strncmp(csv, "t,t_e,a,Hy_1\n", 13) == 0, "%.40s", csv);
  cr_expect_eq(count_lines(csv), 121);
  char *line = strchr(csv, '\n') + 1;
  double t = strtod(line, &line), te = strtod(line + 1, NULL);
  cr_expect_float_eq(t, dt, 1e-15);
  cr_expect_float_eq(te, 0.5 * dt, 1e-15);
  free(csv);
  char *ecsv = read_file(path_in_tmp("out/energy.csv"));
  cr_expect(strncmp(ecsv, "t,electric,magnetic,plain,leapfrog\n", 35) == 0);
  cr_expect_eq(count_lines(ecsv), 1 + 120 / 5 + 1, "steps 0, 5, ..., 120");
  free(ecsv);
  char *fcsv = read_file(path_in_tmp("out/flux.csv"));
  cr_expect(strncmp(fcsv, "t,mid\n", 6) == 0);
  cr_expect_eq(count_lines(fcsv), 121);
  free(fcsv);
  const char *snaps[] = {"out/snapshot_000000.vti", "out/snapshot_000050.vti",
                         "out/snapshot_000100.vti", "out/snapshot_000120.vti"};
  for (int k = 0; k < 4; ++k) cr_expect(file_exists(snaps[k]), "%s", snaps[k]);
  if (gm_hdf5_available()) cr_expect(file_exists("out/snapshot_000120.h5"));
  char *vti = read_file(path_in_tmp("out/snapshot_000100.vti"));
  cr_expect(strstr(vti, "WholeExtent=\"0 24 0 20 0 0\"") != NULL);
  cr_expect(strstr(vti, "Name=\"E\" NumberOfComponents=\"3\" format=\"binary\"") != NULL);
  cr_expect(strstr(vti, "Name=\"epsilon\"") != NULL);
  free(vti);
  char *pvd = read_file(path_in_tmp("out/snapshot.pvd"));
  cr_expect(strstr(pvd, "file=\"snapshot_000120.vti\"") != NULL, "%s", pvd);
  free(pvd);

  /* the text summary names what it wrote; --check runs nothing */
  r = run_cli("maxwell run scene.json --out out2 --threads 1");
  cr_expect_eq(r.status, 0, "%s", r.err);
  cr_expect(strstr(r.out, "2d-tm grid 24 x 20 x 1 cells") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "probe a (Ez):") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "wrote out2/: probes.csv, energy.csv, flux.csv, 4 snapshots") != NULL,
            "%s", r.out);
  run_output_free(&r);
  r = run_cli("maxwell run scene.json --out out4 --threads 1 --plot ez.png --plot-field Hy");
  cr_expect_eq(r.status, cli_gnuplot_available_here() ? 0 : 1, "%s", r.err);
  if (r.status == 0) cr_expect(file_exists("ez.png"));
  run_output_free(&r);
  r = run_cli("maxwell run scene.json --out out4 --plot ez.png --plot-field Hz");
  cr_expect_eq(r.status, 2, "a TM grid has no Hz: %s", r.err);
  cr_expect(strstr(r.err, "--plot-field Hz: not a component of this grid") != NULL, "%s", r.err);
  run_output_free(&r);
  r = run_cli("maxwell run scene.json --plot-field Ez");
  cr_expect_eq(r.status, 2);
  run_output_free(&r);
  r = run_cli("maxwell run scene.json --out out3 --check");
  cr_expect_eq(r.status, 0, "%s", r.err);
  cr_expect(strstr(r.out, "scene is valid") != NULL, "%s", r.out);
  cr_expect(!file_exists("out3/probes.csv"));
  run_output_free(&r);
}

/* 23 steps sampled every 5: steps 0, 5, ..., 20 and the final step 23 (which the energy series
 * dropped when steps was not a multiple of energy_every: its buffer held steps / every + 1). */
Test(cli_maxwell, run_energy_keeps_the_final_sample_off_the_grid) {
  write_scene("e.json", "\"output\": {\"energy_every\": 5},", "{\"steps\": 23, \"courant\": 0.9}");
  run_output r = run_cli("maxwell run e.json --out eo --json --threads 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  const double dt = json_number(o, "dt");
  cJSON_Delete(o);
  run_output_free(&r);
  char *ecsv = read_file(path_in_tmp("eo/energy.csv"));
  cr_expect_eq(count_lines(ecsv), 1 + 5 + 1, "header, steps 0, 5, 10, 15, 20 and 23:\n%s", ecsv);
  const char *last = ecsv + strlen(ecsv) - 1; /* the newline that ends the file */
  while (last > ecsv && last[-1] != '\n') --last;
  cr_expect_float_eq(strtod(last, NULL), 23 * dt, 1e-12, "last row: %s", last);
  free(ecsv);
}

/* A PEC cavity scene: the resonances harminv reports are the Yee frequencies of the modes. */
Test(cli_maxwell, run_harminv_finds_the_cavity_modes) {
  write_text("cav.json",
             "{\"grid\": {\"dim\": \"2d-tm\", \"cells\": [20, 16], \"size\": [1.0, 0.8]},\n"
             " \"sources\": [{\"type\": \"point\", \"component\": \"Ez\", \"position\": [0.39, 0.63],\n"
             "   \"waveform\": {\"kind\": \"gaussian\", \"frequency\": 1.0, \"width\": 0.64,"
             " \"delay\": 4}}],\n"
             " \"probes\": [{\"name\": \"p\", \"component\": \"Ez\", \"position\": [0.83, 0.21]}],\n"
             " \"output\": {\"harminv\": {\"f_min\": 0.5, \"f_max\": 1.5, \"after\": 8}},\n"
             " \"run\": {\"time\": 300}}\n");
  run_output r = run_cli("maxwell run cav.json --out out --json --threads 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  double dt = json_number(o, "dt");
  const cJSON *modes =
      cJSON_GetObjectItem(cJSON_GetArrayItem(cJSON_GetObjectItem(o, "probes"), 0), "resonances");
  /* TM modes (1,1), (2,1), (1,2) of [0,1]x[0,0.8] with h = 0.05 by Yee's dispersion relation:
   * sin(pi f dt) / dt = sqrt(sum sin^2(pi m_a h / 2 L_a) / h^2) */
  const int m[3][2] = {{1, 1}, {2, 1}, {1, 2}};
  const double pi = 3.14159265358979323846, h = 0.05, L[2] = {1.0, 0.8};
  for (int k = 0; k < 3; ++k) {
    double s = 0;
    for (int a = 0; a < 2; ++a) s += pow(sin(pi * m[k][a] * h / (2 * L[a])) / h, 2);
    double f = asin(dt * sqrt(s)) / (pi * dt);
    double best = INFINITY;
    const cJSON *md;
    cJSON_ArrayForEach(md, modes) best = fmin(best, fabs(json_number(md, "frequency") / f - 1));
    cr_expect_lt(best, 1e-5, "mode (%d,%d): Yee %.9f, nearest computed off by %.2e", m[k][0],
                 m[k][1], f, best);
  }
  cJSON_Delete(o);
  run_output_free(&r);
}

/* ---- cavity ------------------------------------------------------------------------------ */

Test(cli_maxwell, cavity_2d_finds_ten_resonances_at_the_yee_frequencies) {
  run_output r = run_cli("maxwell cavity --dim 2 --n 12 --json --out out --threads 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_eq(json_number(o, "found"), 10);
  cr_expect_eq(json_number(o, "spurious"), 0);
  const cJSON *modes = cJSON_GetObjectItem(o, "modes");
  cr_assert_eq(cJSON_GetArraySize(modes), 10);
  const cJSON *md;
  double prev = 0;
  cJSON_ArrayForEach(md, modes) {
    double fa = json_number(md, "analytic");
    cr_expect_gt(fa, prev, "distinct and ascending");
    prev = fa;
    cr_expect_lt(fabs(json_number(md, "rel_error_yee")), 1e-5, "computed = Yee at %.6f", fa);
    /* second-order dispersion at h = 1/12: below (pi m h)^2 / 24 < 3e-2 for m <= 4 */
    cr_expect_lt(fabs(json_number(md, "rel_error_analytic")), 3e-2);
  }
  /* (1,1) of [0,1]x[0,0.8]: f = sqrt(1 + 1/0.64) / 2 */
  cr_expect_float_eq(json_number(cJSON_GetArrayItem(modes, 0), "analytic"),
                     0.5 * sqrt(1 + 1 / 0.64), 1e-14);
  cr_expect(file_exists("out/cavity-spectrum.png") || !cJSON_GetObjectItem(o, "plot"));
  cJSON_Delete(o);
  run_output_free(&r);
  r = run_cli("maxwell cavity --dim 2 --n 12 --out out --threads 1");
  cr_expect_eq(r.status, 0, "%s", r.err);
  cr_expect(strstr(r.out, "10 of 10 resonances found") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "(1,1)") != NULL);
  run_output_free(&r);
}

/* The error against the analytic frequencies falls as h^2 (rate 2 between n = 8 and 16). */
Test(cli_maxwell, cavity_3d_converges_at_second_order) {
  double err[2];
  size_t ns[2] = {8, 16};
  for (int k = 0; k < 2; ++k) {
    run_output r = run_cli("maxwell cavity --dim 3 --n %zu --json --out out --threads 1", ns[k]);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cJSON *o = parse_json(r.out);
    cr_expect_eq(json_number(o, "found"), 10);
    const cJSON *md = cJSON_GetArrayItem(cJSON_GetObjectItem(o, "modes"), 0);
    err[k] = fabs(json_number(md, "rel_error_analytic"));
    cJSON_Delete(o);
    run_output_free(&r);
  }
  double rate = log(err[0] / err[1]) / log(2.0);
  cr_expect(rate > 1.8 && rate < 2.2, "rate %.3f (errors %.3e, %.3e)", rate, err[0], err[1]);
}

/* ---- E4 ---------------------------------------------------------------------------------- */

Test(cli_maxwell, e4_energy_bounded_leapfrog_conserved) {
  run_output r = run_cli("maxwell e4 --n 16 --time 4 --json --out out --threads 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  double dt = json_number(o, "dt");
  cr_expect_float_eq(dt, 0.1 / (16 * sqrt(2.0)), 1e-14, "0.1 of the Courant limit h/sqrt(2)");
  cr_expect_lt(json_number(o, "leapfrog_max_rel_drift"), 1e-12);
  double r1 = json_number(o, "plain_range_first_half"), r2 = json_number(o, "plain_range_second_half");
  cr_expect_gt(r2, 1e-4, "the plain energy oscillates");
  cr_expect_lt(r2, 0.1, "boundedly");
  cr_expect_leq(r2, r1 * 1.0001, "no growth: %.3e then %.3e", r1, r2);
  char *csv = read_file(path_in_tmp("out/e4-energy.csv"));
  cr_expect_eq(count_lines(csv), (size_t)json_number(o, "steps") + 2, "steps 0 .. N and a header");
  free(csv);
  cJSON_Delete(o);
  run_output_free(&r);
  r = run_cli("maxwell e4 --n 16 --time 1 --out out --threads 1");
  cr_expect_eq(r.status, 0);
  cr_expect(strstr(r.out, "E4 (seed 000): PEC unit square, 16 x 16 cells") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "conserved to round-off") != NULL);
  run_output_free(&r);
}

/* ---- the documentation shows the example scene that is in the tree, and it is valid ----- */

Test(cli_maxwell, docs_show_the_example_scene) {
  char *doc = read_file(GM_SOURCE_DIR "/docs/maxwell.md");
  char *scene = read_file(GM_SOURCE_DIR "/examples/maxwell_scene.json");
  cr_expect_not_null(strstr(doc, scene), "docs/maxwell.md does not show examples/maxwell_scene.json");
  free(doc);
  free(scene);
  run_output r = run_cli("maxwell run '%s/examples/maxwell_scene.json' --check --json", GM_SOURCE_DIR);
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_expect_eq(json_number(o, "steps"), 914);
  cr_expect_eq(json_number(o, "sources"), 1);
  cr_expect_eq(json_number(o, "probes"), 3);
  cr_expect_eq(json_number(o, "flux_planes"), 2);
  cJSON_Delete(o);
  run_output_free(&r);
}

/* Progress goes to stderr only when it is a terminal (util-linux `script` provides one). */
Test(cli_maxwell, progress_only_on_a_terminal) {
  write_scene("scene.json", "", "{\"steps\": 200}");
  run_output r = run_cli("maxwell run scene.json --out out --threads 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect_eq(r.err[0], '\0', "no progress into a pipe: %s", r.err);
  run_output_free(&r);
  if (system("command -v script >/dev/null 2>&1") != 0) {
    SKIP_TEST("no `script` program to provide a terminal");
  }
  char cmd[2048];
  snprintf(cmd, sizeof cmd,
           "cd '%s' && script -qec \"'%s' maxwell run scene.json --out out2 --threads 1\" "
           "/dev/null > tty.txt 2>&1", tmpdir, GM_CLI_PATH);
  cr_assert_eq(system(cmd), 0);
  char *tty = read_file(path_in_tmp("tty.txt"));
  cr_expect(strstr(tty, "\r  step 200 / 200 (100%)") != NULL, "%s", tty);
  cr_expect(strstr(tty, "\r\033[K") != NULL, "the progress line is cleared");
  cr_expect(strstr(tty, "wrote out2/: probes.csv") != NULL, "%s", tty);
  free(tty);
}

/* `maxwell mesh`: the DEC leapfrog on a generated triangle mesh keeps its modified energy and
 * Gauss's law to round-off; the AVI on a warped mesh keeps Gauss's law; bad input exits 2. */
static double number_after(const char *text, const char *key) {
  const char *at = strstr(text, key);
  cr_assert_not_null(at, "no '%s' in: %s", key, text);
  return strtod(at + strlen(key), NULL);
}

Test(cli_maxwell, mesh_leapfrog_and_avi) {
  run_output r = run_cli("maxwell mesh --rect 10 --t-end 1 --samples 10");
  cr_assert_eq(r.status, 0, "%s", r.err);
  const double start = number_after(r.out, "energy: start "),
               leapfrog = number_after(r.out, "leapfrog ");
  cr_expect(fabs(leapfrog - start) <= 1e-12 * start, "%s", r.out);
  cr_expect_leq(number_after(r.out, "max Gauss drift "), 1e-12, "%s", r.out);
  run_output_free(&r);
  r = run_cli("maxwell mesh --rect 8 --warp 0.3 --avi --t-end 1 --samples 10");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect_leq(number_after(r.out, "max Gauss drift "), 1e-12, "%s", r.out);
  run_output_free(&r);
  r = run_cli("maxwell mesh /nonexistent.msh");
  cr_expect_eq(r.status, 2);
  run_output_free(&r);
  r = run_cli("maxwell mesh --rect 10 --dt 1");
  cr_expect_eq(r.status, 2, "%s", r.err);
  run_output_free(&r);
}

/* E5 as one command (short run: the structure, not the spectrum, which needs --t-end 60). The
 * checked-in Gmsh mesh is Delaunay: positive diagonal stars, the AVI runs on it, makes about
 * 0.005 of the face updates of uniform stepping at its smallest step (the near-cospherical cells
 * set that step) and keeps Gauss's law. A mesh that is not Delaunay (the Gmsh cube) gets the
 * Whitney leapfrog alone, with the count of non-positive stars. */
Test(cli_maxwell, mesh_e5, .timeout = 300) {
  run_output r = run_cli("maxwell mesh " GM_SOURCE_DIR
                         "/examples/e5_cavity.msh --e5 --t-end 4 --t-compare 0.2");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect(strstr(r.out, "positive on every interior edge and face") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "time ratio AVI/uniform") != NULL, "%s", r.out);
  cr_expect_lt(number_after(r.out, "ratio to uniform "), 0.02, "%s", r.out);
  cr_expect_gt(number_after(r.out, "ratio to uniform "), 1e-3, "%s", r.out);
  cr_expect_lt(number_after(r.out, "Gauss drift "), 1e-12, "%s", r.out);
  cr_expect_lt(number_after(r.out, "max |div B| "), 1e-12, "%s", r.out);
  run_output_free(&r);
  r = run_cli("maxwell mesh " GM_SOURCE_DIR "/tests/data/cube_v22.msh --e5 --t-end 2");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect(strstr(r.out, "the mesh is not well-centred") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "the AVI cannot run here") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "2. AVI") == NULL, "%s", r.out);
  cr_expect(strstr(r.out, "3. leapfrog, Whitney star") != NULL, "%s", r.out);
  run_output_free(&r);
  r = run_cli("maxwell mesh --rect 6 --e5");
  cr_expect_eq(r.status, 2, "%s", r.err);
  run_output_free(&r);
  r = run_cli("maxwell mesh " GM_SOURCE_DIR "/examples/e5_cavity.msh --e5 --sample 0");
  cr_expect_eq(r.status, 2, "%s", r.err);
  run_output_free(&r);
}

/* A plane wave given by angles (oblique TF/SF): inside the box a probe sees the pulse, outside
 * only the leakage (below −50 dB with cubic interpolation, tests/invariants/
 * test_yee_tfsf_oblique.c); bad angle fields are errors with their JSON path. */
static double csv_column_max(const char *csv, int column) {
  double mx = 0.0;
  const char *line = strchr(csv, '\n');
  while (line != NULL && line[1] != '\0') {
    const char *at = line + 1;
    for (int c = 0; c < column; ++c) at = strchr(at, ',') + 1;
    mx = fmax(mx, fabs(strtod(at, NULL)));
    line = strchr(at, '\n');
  }
  return mx;
}

Test(cli_maxwell, run_oblique_plane_wave) {
  write_text("ob.json",
             "{\"grid\": {\"dim\": \"2d-tm\", \"cells\": [80, 80], \"size\": [8, 8]},\n"
             " \"boundaries\": {\"x\": \"cpml\", \"y\": \"cpml\"}, \"pml\": {\"thickness\": 10},\n"
             " \"sources\": [{\"type\": \"plane-wave\", \"theta\": 90, \"phi\": 25, \"psi\": 90,\n"
             "   \"lo\": [20, 20], \"hi\": [60, 60],\n"
             "   \"waveform\": {\"kind\": \"gaussian\", \"frequency\": 0.5, \"width\": 2, \"delay\": 10}}],\n"
             " \"probes\": [{\"name\": \"in\", \"component\": \"Ez\", \"position\": [4, 4]},\n"
             "   {\"name\": \"out\", \"component\": \"Ez\", \"position\": [1.6, 5.1]}],\n"
             " \"run\": {\"time\": 30}}\n");
  run_output r = run_cli("maxwell run ob.json --out out --threads 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  run_output_free(&r);
  char *csv = read_file(path_in_tmp("out/probes.csv"));
  const double in = csv_column_max(csv, 2), out = csv_column_max(csv, 3);
  free(csv);
  cr_log_info("oblique scene: max |Ez| inside %.4f, outside %.3g (%.1f dB)", in, out,
              20 * log10(out / in));
  cr_expect_gt(in, 0.95);
  cr_expect_lt(in, 1.05);
  cr_expect_lt(out, pow(10.0, -50.0 / 20.0) * in);

  const char *bad[][2] = {
      {"\"interpolation\": \"spline\",", "sources[0].interpolation: expected \"cubic\" or \"linear\""},
      {"\"theta\": 80,", "sources[0]: oblique wave: on a 2-D grid the wave travels in the x-y plane"},
      {"\"psi\": \"up\",", "sources[0].psi: expected a number"},
      {"\"axis\": \"x\",", "sources[0].axis: unknown key"}};
  for (size_t k = 0; k < sizeof bad / sizeof *bad; ++k) {
    char text[2048];
    snprintf(text, sizeof text,
             "{\"grid\": {\"dim\": \"2d-tm\", \"cells\": [40, 40], \"size\": [4, 4]},\n"
             " \"sources\": [{\"type\": \"plane-wave\", \"phi\": 25, %s\n"
             "   \"lo\": [10, 10], \"hi\": [30, 30],\n"
             "   \"waveform\": {\"kind\": \"gaussian\", \"frequency\": 0.5, \"width\": 2, \"delay\": 10}}],\n"
             " \"run\": {\"steps\": 5}}\n",
             bad[k][0]);
    write_text("bad.json", text);
    r = expect_usage_error("bad.json", bad[k][1]);
    run_output_free(&r);
  }
}
