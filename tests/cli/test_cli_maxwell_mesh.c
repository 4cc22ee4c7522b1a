/* geomint maxwell mesh: a run that blows up stops with exit 1 and says when and why (the AVI
 * above 10 times its initial energy, the leapfrog when non-finite), its summary never reports
 * clean invariants after a NaN, the last VTU snapshot is the final state and a ParaView .pvd
 * lists the files with their times. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli_harness.h"

TestSuite(cli_maxwell_mesh, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 300);

#define CUBE GM_SOURCE_DIR "/tests/data/cube_v22.msh"

static double number_after(const char *text, const char *key) {
  const char *at = strstr(text, key);
  cr_assert_not_null(at, "no '%s' in: %s", key, text);
  return strtod(at + strlen(key), NULL);
}

static size_t count_substr(const char *text, const char *needle) {
  size_t n = 0;
  for (const char *p = strstr(text, needle); p; p = strstr(p + 1, needle)) ++n;
  return n;
}

/* The AVI at its full local limits with distinct steps (coupling resonances between neighbouring
 * faces): it grew the energy 4.2e4 times and exited 0; now it stops where the energy passes 10
 * times its initial value. The same mesh at 1/10 (E4) runs to the end below 2. */
Test(cli_maxwell_mesh, avi_blow_up_stops) {
  run_output r = run_cli("maxwell mesh --rect 20 --warp 0.3 --avi --exact-steps --fraction 1 "
                         "--t-end 8");
  cr_expect_eq(r.status, 1, "%s%s", r.out, r.err);
  cr_expect(strstr(r.err, "blew up at t = ") != NULL, "%s", r.err);
  cr_expect(strstr(r.err, "x its initial value") != NULL, "%s", r.err);
  cr_expect(strstr(r.err, "smaller --fraction (now 1)") != NULL, "%s", r.err);
  cr_expect_eq(count_lines(r.err), 1, "%s", r.err);
  const double t = number_after(r.err, "blew up at t = ");
  cr_expect(t > 0.0 && t < 8.0, "stopped early: %s", r.err);
  const double ratio = number_after(r.err, "the field energy is ");
  cr_expect(ratio > 10.0 && ratio < 20.0, "stopped where it passed 10: %s", r.err);
  run_output_free(&r);
  r = run_cli("maxwell mesh " GM_SOURCE_DIR "/examples/e5_cavity.msh --e5 --t-end 4 "
              "--fraction 1");
  cr_expect_eq(r.status, 1, "%s%s", r.out, r.err);
  cr_expect(strstr(r.err, "maxwell mesh --e5: the run blew up at t = ") != NULL, "%s", r.err);
  cr_expect(strstr(r.err, "smaller --fraction (now 1)") != NULL, "%s", r.err);
  run_output_free(&r);
  r = run_cli("maxwell mesh --rect 20 --warp 0.3 --avi --exact-steps --t-end 8");
  cr_expect_eq(r.status, 0, "%s", r.err);
  cr_expect_lt(number_after(r.out, "max plain/E0 "), 2.0, "%s", r.out);
  run_output_free(&r);
}

/* The diagonal star insisted on where it is not positive (the Gmsh cube) grows at any step: the
 * leapfrog stops when the energy is non-finite, advises --whitney, and the summary's invariants
 * are NaN, not the 0.000e+00 that fmax made of them. */
Test(cli_maxwell_mesh, leapfrog_non_finite_stops) {
  run_output r = run_cli("maxwell mesh " CUBE " --allow-negative-stars --t-end 3 --samples 1");
  cr_expect_eq(r.status, 1, "%s%s", r.out, r.err);
  cr_expect(strstr(r.err, "blew up") != NULL, "%s", r.err);
  cr_expect(strstr(r.err, "non-finite") != NULL, "%s", r.err);
  cr_expect(strstr(r.err, "use --whitney") != NULL, "%s", r.err);
  cr_expect(isnan(number_after(r.out, "max |div B| ")), "%s", r.out);
  cr_expect(!(number_after(r.out, "max Gauss drift ") <= 1e-6), "%s", r.out); /* NaN or huge */
  cr_expect(isnan(number_after(r.out, "max |plain - E0|/E0 ")), "%s", r.out);
  run_output_free(&r);
  /* observed every step: stopped at the first non-finite energy, long before t = 3 */
  r = run_cli("maxwell mesh " CUBE " --allow-negative-stars --t-end 3 --samples 1000");
  cr_expect_eq(r.status, 1, "%s%s", r.out, r.err);
  cr_expect_lt(number_after(r.err, "blew up at t = "), 1.5, "%s", r.err);
  run_output_free(&r);
}

static size_t count_vtu(const char *dir) {
  DIR *d = opendir(path_in_tmp(dir));
  cr_assert_not_null(d);
  size_t n = 0;
  for (struct dirent *e; (e = readdir(d)) != NULL;) {
    const size_t len = strlen(e->d_name);
    n += len > 4 && strcmp(e->d_name + len - 4, ".vtu") == 0;
  }
  closedir(d);
  return n;
}

/* The leapfrog stops at t = 0.9756 for --t-end 1 (the last whole step), where no observation
 * fell: the third snapshot was lost. Now the last one is the final state, and snap/s.pvd lists
 * the three files with their times, the last the run's final time. */
Test(cli_maxwell_mesh, snapshots_and_pvd) {
  cr_assert_eq(mkdir(path_in_tmp("snap"), 0755), 0);
  run_output r = run_cli("maxwell mesh " CUBE " --whitney --t-end 1 --vtu snap/s --snapshots 3");
  cr_assert_eq(r.status, 0, "%s", r.err);
  const double t_final = number_after(r.out, "run: t = ");
  cr_expect_lt(t_final, 1.0, "%s", r.out);
  run_output_free(&r);
  cr_expect_eq(count_vtu("snap"), 3);
  char *pvd = read_file(path_in_tmp("snap/s.pvd"));
  cr_expect(strstr(pvd, "<VTKFile type=\"Collection\"") != NULL, "%s", pvd);
  cr_expect_eq(count_substr(pvd, "<DataSet "), 3, "%s", pvd);
  cr_expect(strstr(pvd, "timestep=\"0\" file=\"s_0000.vtu\"") != NULL, "%s", pvd);
  const char *last = strstr(pvd, "file=\"s_0002.vtu\"");
  cr_assert_not_null(last, "%s", pvd);
  const char *ts = last;
  while (ts > pvd && strncmp(ts, "timestep=\"", 10) != 0) --ts;
  cr_expect_lt(fabs(strtod(ts + 10, NULL) - t_final), 1e-5, "%s", pvd);
  free(pvd);
  /* the AVI, and a single snapshot: the final state */
  cr_assert_eq(mkdir(path_in_tmp("one"), 0755), 0);
  r = run_cli("maxwell mesh --rect 6 --avi --t-end 0.5 --vtu one/a --snapshots 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  run_output_free(&r);
  cr_expect_eq(count_vtu("one"), 1);
  pvd = read_file(path_in_tmp("one/a.pvd"));
  cr_expect(strstr(pvd, "timestep=\"0.5\" file=\"a_0000.vtu\"") != NULL, "%s", pvd);
  free(pvd);
  r = run_cli("maxwell mesh --rect 6 --vtu x --snapshots 0");
  cr_expect_eq(r.status, 2, "%s", r.err);
  run_output_free(&r);
  /* a --vtu folder that is a file: the message names --vtu (it said --out) */
  FILE *f = fopen(path_in_tmp("plain"), "w");
  cr_assert_not_null(f);
  fclose(f);
  r = run_cli("maxwell mesh --rect 6 --t-end 0.1 --vtu plain/s");
  cr_expect_eq(r.status, 1, "%s", r.err);
  cr_expect(strstr(r.err, "--vtu plain: not a writable directory") != NULL, "%s", r.err);
  run_output_free(&r);
}

/* Progress: the maxwell commands' line (step k / N, percentage, time left) on a terminal only,
 * cleared at the end; nothing on stderr otherwise. `script` gives the program a terminal. */
static char *run_on_tty(const char *args) {
  char cmd[2048];
  snprintf(cmd, sizeof cmd, "cd '%s' && script -qec \"'%s' %s\" /dev/null > tty.txt 2>&1",
           tmpdir, GM_CLI_PATH, args);
  cr_assert_eq(system(cmd), 0, "%s", cmd);
  return read_file(path_in_tmp("tty.txt"));
}

Test(cli_maxwell_mesh, progress_on_a_terminal_only) {
  if (system("command -v script >/dev/null 2>&1") != 0) SKIP_TEST("no script(1)");
  const char *runs[] = {"maxwell mesh --rect 10 --t-end 1 --samples 10",
                        "maxwell mesh --rect 10 --avi --t-end 1 --samples 10",
                        "maxwell mesh-cavity --shape box --levels 1 --t-end 30"};
  for (size_t i = 0; i < sizeof runs / sizeof runs[0]; ++i) {
    char *tty = run_on_tty(runs[i]);
    cr_expect(strstr(tty, "\r  step ") != NULL, "%s: %s", runs[i], tty);
    cr_expect(strstr(tty, "(100%)") != NULL, "%s: %s", runs[i], tty);
    cr_expect(strstr(tty, "\r\033[K") != NULL, "%s: the line is cleared", runs[i]);
    free(tty);
    run_output r = run_cli("%s", runs[i]);
    cr_expect_eq(r.status, 0, "%s: %s", runs[i], r.err);
    cr_expect_eq(r.err[0], '\0', "%s: nothing on stderr off a terminal: %s", runs[i], r.err);
    run_output_free(&r);
  }
}

/* --material: ε and μ per box (cells by centroid); ε = 4 everywhere doubles the CFL limit (the
 * wave speed halves); the library's refusal of ε or μ <= 0 reaches the user naming the option;
 * malformed boxes and boxes holding no cell are bad input. */
Test(cli_maxwell_mesh, materials) {
  run_output r = run_cli("maxwell mesh --rect 10 --t-end 0.5");
  cr_assert_eq(r.status, 0, "%s", r.err);
  const double vacuum = number_after(r.out, "CFL limit ");
  run_output_free(&r);
  r = run_cli("maxwell mesh --rect 10 --t-end 0.5 --material -1,-1,2,2,4,1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect_lt(fabs(number_after(r.out, "CFL limit ") / vacuum - 2.0), 1e-6, "%s", r.out);
  cr_expect(strstr(r.out, "on 168 cells") != NULL, "%s", r.out);
  run_output_free(&r);
  /* two regions, the AVI: runs and keeps Gauss's law */
  r = run_cli("maxwell mesh --rect 10 --avi --t-end 1 --material 0,0,0.5,0.7,2.5,1 "
              "--material 0.5,0,1,0.3,1,1.5");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect_leq(number_after(r.out, "max Gauss drift "), 1e-12, "%s", r.out);
  run_output_free(&r);
  const char *bad_values[] = {"0,0,0.5,0.7,-1,1", "0,0,0.5,0.7,1,0", "0,0,0,1,1,1,0,1"};
  for (size_t i = 0; i < 3; ++i) {
    const char *mesh = i < 2 ? "--rect 10" : CUBE " --whitney";
    r = run_cli("maxwell mesh %s --material %s", mesh, bad_values[i]);
    cr_expect_eq(r.status, 2, "%s: %s", bad_values[i], r.err);
    char want[128];
    snprintf(want, sizeof want, "--material %s: mesh maxwell: %s of cell", bad_values[i],
             i == 1 ? "mu" : "epsilon");
    cr_expect(strstr(r.err, want) != NULL, "want '%s' in: %s", want, r.err);
    cr_expect(strstr(r.err, "must be > 0") != NULL, "%s", r.err);
    run_output_free(&r);
  }
  const char *malformed[] = {"0,0,0.5,0.7,1", "0.5,0,0.2,0.7,1,1", "a,0,1,1,1,1",
                             "0,0,0.5,0.7,1,1,1,1", "2,2,3,3,1,1"};
  for (size_t i = 0; i < 5; ++i) {
    r = run_cli("maxwell mesh --rect 10 --material %s", malformed[i]);
    cr_expect_eq(r.status, 2, "%s: %s", malformed[i], r.err);
    cr_expect(strstr(r.err, malformed[i]) != NULL, "%s", r.err);
    run_output_free(&r);
  }
}

/* Help texts name the sphere and the new options. Refusals at create: a mesh with no interior
 * edge (one triangle) says why instead of "dt = inf is above the CFL limit inf"; the
 * not-well-centred refusal names the command-line flag. */
Test(cli_maxwell_mesh, refusals_at_create) {
  FILE *f = fopen(path_in_tmp("tri.msh"), "w");
  cr_assert_not_null(f);
  fputs("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
        "$EndNodes\n$Elements\n1\n1 2 2 0 0 1 2 3\n$EndElements\n", f);
  fclose(f);
  run_output r = run_cli("maxwell --help");
  cr_expect(strstr(r.out, "mesh-cavity [--shape box|cylinder|sphere]") != NULL, "%s", r.out);
  run_output_free(&r);
  r = run_cli("maxwell mesh --help");
  cr_expect(strstr(r.out, "--material X0,Y0[,Z0],X1,Y1[,Z1],EPS,MU") != NULL, "%s", r.out);
  cr_expect(strstr(r.out, "PREFIX.pvd") != NULL, "%s", r.out);
  run_output_free(&r);
  r = run_cli("maxwell mesh tri.msh");
  cr_expect_eq(r.status, 2, "%s", r.err);
  cr_expect(strstr(r.err, "the mesh has no interior edges: under PEC every field is zero") != NULL,
            "%s", r.err);
  cr_expect(strstr(r.err, "inf") == NULL, "%s", r.err);
  run_output_free(&r);
  r = run_cli("maxwell mesh " CUBE);
  cr_expect_eq(r.status, 2, "%s", r.err);
  cr_expect(strstr(r.err, "not well-centred") != NULL, "%s", r.err);
  cr_expect(strstr(r.err, "--allow-negative-stars") != NULL, "%s", r.err);
  run_output_free(&r);
}
