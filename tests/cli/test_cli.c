/* The geomint program: each command's documented output, JSON keys and values, CSV files,
 * plots, and the exit statuses of bad input (2) and of failed runs (1). */
#include <criterion/criterion.h>
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cJSON.h>

#include "geomint/geomint.h"

#include "cli/cli_harness.h"

TestSuite(cli, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

/* ---- CSV -------------------------------------------------------------------------------- */

typedef struct csv_table {
  char *header;
  size_t n_rows, n_cols;
  double *values; /* n_rows × n_cols */
} csv_table;

/* Parse a numeric CSV; every row must be a complete line with as many fields as the header. */
static csv_table read_csv(const char *path) {
  char *text = read_file(path);
  csv_table t = {0};
  cr_assert(strlen(text) > 0 && text[strlen(text) - 1] == '\n', "%s: last line incomplete", path);
  char *line_end = strchr(text, '\n');
  *line_end = '\0';
  t.header = strdup(text);
  t.n_cols = 1;
  for (const char *c = t.header; *c; ++c) t.n_cols += *c == ',';
  size_t n_lines = count_lines(line_end + 1);
  t.values = malloc((n_lines + 1) * t.n_cols * sizeof *t.values);
  char *p = line_end + 1;
  while (*p) {
    for (size_t c = 0; c < t.n_cols; ++c) {
      char *end;
      t.values[t.n_rows * t.n_cols + c] = strtod(p, &end);
      cr_assert(end != p, "%s row %zu: field %zu is not a number", path, t.n_rows + 1, c + 1);
      char want = c + 1 < t.n_cols ? ',' : '\n';
      cr_assert_eq(*end, want, "%s row %zu: %zu fields expected", path, t.n_rows + 1, t.n_cols);
      p = end + 1;
    }
    t.n_rows++;
  }
  free(text);
  return t;
}

static double csv_at(const csv_table *t, size_t row, size_t col) {
  return t->values[row * t->n_cols + col];
}

static void csv_free(csv_table *t) {
  free(t->header);
  free(t->values);
}

static int file_is_png(const char *path) {
  FILE *f = fopen(path, "rb");
  if (f == NULL) return 0;
  unsigned char sig[8] = {0};
  size_t n = fread(sig, 1, 8, f);
  fclose(f);
  static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  return n == 8 && memcmp(sig, png, 8) == 0;
}

static long file_size(const char *path) {
  struct stat sb;
  return stat(path, &sb) == 0 ? (long)sb.st_size : -1;
}

static int have_gnuplot(void) { return system("command -v gnuplot >/dev/null 2>&1") == 0; }

/* ---- usage and version ------------------------------------------------------------------ */

Test(cli, help_and_version) {
  run_output r = run_cli("--help");
  cr_assert_eq(r.status, 0);
  cr_assert(strstr(r.out, "usage: geomint") != NULL);
  for (const char *const *c = (const char *const[]){"list", "run", "order", "demo", NULL}; *c;
       ++c)
    cr_assert(strstr(r.out, *c) != NULL, "--help does not mention %s", *c);
  run_output_free(&r);

  r = run_cli("help");
  cr_assert_eq(r.status, 0);
  cr_assert(strstr(r.out, "usage: geomint") != NULL);
  run_output_free(&r);

  r = run_cli("--version");
  cr_assert_eq(r.status, 0);
  cr_assert(strstr(r.out, GM_VERSION_STRING) != NULL, "version: %s", r.out);
  run_output_free(&r);

  r = run_cli("");
  cr_assert_eq(r.status, 2);
  cr_assert_str_empty(r.out);
  cr_assert(strstr(r.err, "usage: geomint") != NULL);
  run_output_free(&r);
}

Test(cli, command_help) {
  static const char *const commands[][2] = {
      {"list", "--json"}, {"run", "--t-end"}, {"order", "--levels"}, {"demo", "--out"}};
  for (size_t i = 0; i < 4; ++i) {
    run_output r = run_cli("%s --help", commands[i][0]);
    cr_assert_eq(r.status, 0, "%s --help", commands[i][0]);
    cr_assert(strstr(r.out, "usage: geomint") != NULL && strstr(r.out, commands[i][1]) != NULL,
              "%s --help: %s", commands[i][0], r.out);
    run_output_free(&r);
    r = run_cli("help %s", commands[i][0]);
    cr_assert_eq(r.status, 0);
    cr_assert(strstr(r.out, commands[i][1]) != NULL);
    run_output_free(&r);
  }
}

/* ---- list ------------------------------------------------------------------------------- */

Test(cli, list_methods_json) {
  run_output r = run_cli("list methods --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *rows = parse_json(r.out);
  cr_assert(cJSON_IsArray(rows));
  cr_assert_eq((size_t)cJSON_GetArraySize(rows), gm_method_count());
  int saw_verlet = 0;
  const cJSON *row;
  cJSON_ArrayForEach(row, rows) {
    const gm_method *m = gm_method_find(json_string(row, "name"));
    cr_assert_not_null(m);
    cr_assert_str_eq(json_string(row, "family"), gm_method_family_name(m->family));
    cr_assert_eq(json_number(row, "order"), m->order);
    cr_assert_eq(json_number(row, "stages"), (double)m->n_stages);
    cr_assert(strlen(json_string(row, "reference")) > 0, "%s has no reference", m->name);
    const cJSON *flags = cJSON_GetObjectItem(row, "flags");
    const cJSON *accepts = cJSON_GetObjectItem(row, "accepts");
    cr_assert(cJSON_IsArray(flags) && cJSON_IsArray(accepts) && cJSON_GetArraySize(accepts) > 0);
    cr_assert_eq(json_array_has(flags, "symplectic"), (m->flags & GM_SYMPLECTIC) != 0);
    cr_assert_eq(json_array_has(flags, "explicit"), (m->flags & GM_EXPLICIT) != 0);
    if (strcmp(m->name, "verlet") == 0) {
      saw_verlet = 1;
      cr_assert_eq(m->order, 2);
      cr_assert(json_array_has(flags, "symplectic") && json_array_has(flags, "symmetric"));
      cr_assert(json_array_has(accepts, "separable"));
    }
  }
  cr_assert(saw_verlet);
  cJSON_Delete(rows);
  run_output_free(&r);
}

Test(cli, list_methods_table) {
  run_output r = run_cli("list methods");
  cr_assert_eq(r.status, 0);
  cr_assert_eq(count_lines(r.out), gm_method_count() + 1, "%s", r.out);
  cr_assert(strncmp(r.out, "NAME", 4) == 0);
  for (size_t i = 0; i < gm_method_count(); ++i) {
    char needle[80];
    snprintf(needle, sizeof needle, "\n%s ", gm_method_at(i)->name);
    cr_assert(strstr(r.out, needle) != NULL, "no row for %s", gm_method_at(i)->name);
  }
  run_output_free(&r);
}

Test(cli, list_problems) {
  run_output r = run_cli("list problems --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *rows = parse_json(r.out);
  cr_assert_eq((size_t)cJSON_GetArraySize(rows), gm_model_count());
  const cJSON *row, *kepler = NULL;
  cJSON_ArrayForEach(row, rows) {
    cr_assert(strlen(json_string(row, "description")) > 0);
    cr_assert(json_number(row, "dim") >= 1);
    cr_assert(cJSON_IsObject(cJSON_GetObjectItem(row, "parameters")));
    const cJSON *inv = cJSON_GetObjectItem(row, "invariants");
    cr_assert(cJSON_IsArray(inv));
    if (strcmp(json_string(row, "kind"), "first-order") != 0)
      cr_assert_str_eq(cJSON_GetArrayItem(inv, 0)->valuestring, "energy");
    if (strcmp(json_string(row, "name"), "kepler") == 0) kepler = row;
  }
  cr_assert_not_null(kepler);
  cr_assert_str_eq(json_string(kepler, "kind"), "separable");
  cr_assert_eq(json_number(kepler, "dim"), 2);
  cr_assert_eq(json_number(cJSON_GetObjectItem(kepler, "parameters"), "e"), 0.6);
  cr_assert(json_array_has(cJSON_GetObjectItem(kepler, "invariants"), "angular-momentum"));
  cJSON_Delete(rows);
  run_output_free(&r);

  r = run_cli("list problems");
  cr_assert_eq(r.status, 0);
  cr_assert_eq(count_lines(r.out), gm_model_count() + 1);
  cr_assert(strstr(r.out, "\nkepler ") != NULL);
  run_output_free(&r);
}

/* ---- run -------------------------------------------------------------------------------- */

/* The exact Kepler state at time t from the library's model (default e = 0.6). */
static void kepler_exact(double t, double *y) {
  gm_model *m = NULL;
  cr_assert_eq(gm_model_create("kepler", &m), GM_OK);
  cr_assert_eq(gm_model_build(m), GM_OK);
  const gm_problem *pb = gm_model_problem(m);
  cr_assert_not_null(pb->exact);
  cr_assert_eq(pb->exact(pb->ctx, t, y), 0);
  gm_model_free(m);
}

Test(cli, run_json) {
  run_output r = run_cli("run kepler --method verlet --dt 0.01 --steps 1000 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_assert_str_eq(json_string(o, "problem"), "kepler");
  cr_assert_str_eq(json_string(o, "method"), "verlet");
  cr_assert_eq(json_number(o, "dt"), 0.01);
  cr_assert_eq(json_number(o, "steps"), 1000);
  double t_end = json_number(o, "t_end");
  cr_assert(fabs(t_end - 10.0) < 1e-9, "t_end = %.17g", t_end);
  /* verlet with FSAL: one force per step plus the first */
  double evals = json_number(o, "force_evals");
  cr_assert(evals >= 1000 && evals <= 1001, "force_evals = %g", evals);
  cr_assert_eq(json_number(o, "newton_iterations"), 0);
  cr_assert(json_number(o, "wall_s") >= 0);
  double emax = json_number(o, "max_rel_energy_error");
  double efinal = json_number(o, "final_rel_energy_error");
  cr_assert(emax > 0 && emax < 1e-2, "max_rel_energy_error = %g", emax);
  cr_assert(efinal >= 0 && efinal <= emax, "final_rel_energy_error = %g", efinal);
  const cJSON *inv = cJSON_GetObjectItem(o, "invariants");
  /* a symplectic splitting conserves the angular momentum of a central force to round-off */
  cr_assert(json_number(inv, "angular-momentum") < 1e-12);
  cr_assert(json_number(inv, "runge-lenz") > 0);

  const cJSON *final = cJSON_GetObjectItem(o, "final");
  cr_assert_eq(json_number(final, "t"), t_end);
  const cJSON *q = cJSON_GetObjectItem(final, "q"), *p = cJSON_GetObjectItem(final, "p");
  cr_assert(cJSON_GetArraySize(q) == 2 && cJSON_GetArraySize(p) == 2);
  double exact[4];
  kepler_exact(t_end, exact);
  double y[4] = {cJSON_GetArrayItem(q, 0)->valuedouble, cJSON_GetArrayItem(q, 1)->valuedouble,
                 cJSON_GetArrayItem(p, 0)->valuedouble, cJSON_GetArrayItem(p, 1)->valuedouble};
  for (int i = 0; i < 4; ++i)
    cr_assert(fabs(y[i] - exact[i]) < 0.05, "y[%d] = %g, exact %g", i, y[i], exact[i]);
  cJSON_Delete(o);
  run_output_free(&r);
}

Test(cli, run_t_end_exact) {
  /* 1 / 0.3 is not an integer: four equal steps of 0.25 end exactly at t = 1 */
  run_output r = run_cli("run harmonic --method rk4 --dt 0.3 --t-end 1 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_assert_eq(json_number(o, "steps"), 4);
  cr_assert_eq(json_number(o, "t_end"), 1.0);
  const cJSON *final = cJSON_GetObjectItem(o, "final");
  cr_assert_eq(json_number(final, "t"), 1.0);
  /* harmonic oscillator q = cos t, p = -sin t; rk4 at h = 0.25 is accurate to ~1e-4 */
  double q = cJSON_GetArrayItem(cJSON_GetObjectItem(final, "q"), 0)->valuedouble;
  double p = cJSON_GetArrayItem(cJSON_GetObjectItem(final, "p"), 0)->valuedouble;
  cr_assert(fabs(q - cos(1.0)) < 1e-4 && fabs(p + sin(1.0)) < 1e-4, "q = %g, p = %g", q, p);
  cJSON_Delete(o);
  run_output_free(&r);
}

Test(cli, run_summary) {
  run_output r = run_cli("run pendulum --method midpoint --set k=2 --t-end 5");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_assert(strstr(r.out, "pendulum with midpoint") != NULL, "%s", r.out);
  cr_assert(strstr(r.out, "rel. energy error") != NULL);
  cr_assert(strstr(r.out, "500 of dt = 0.01") != NULL, "%s", r.out);
  cr_assert_str_empty(r.err);
  run_output_free(&r);
}

Test(cli, run_csv) {
  run_output r = run_cli("run kepler --steps 1000 --every 10 --out k.csv --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  csv_table t = read_csv(path_in_tmp("k.csv"));
  cr_assert_str_eq(t.header, "t,q1,q2,p1,p2,H,rel_energy_error,angular-momentum,runge-lenz");
  cr_assert_eq(t.n_rows, 101, "rows: %zu", t.n_rows); /* steps 0, 10, ..., 1000 */
  cr_assert_eq(json_number(o, "csv_rows"), 101);
  cr_assert_eq(csv_at(&t, 0, 0), 0.0);
  cr_assert(fabs(csv_at(&t, 100, 0) - 10.0) < 1e-9);
  cr_assert(fabs(csv_at(&t, 10, 0) - 1.0) < 1e-12, "row 10 at t = %g", csv_at(&t, 10, 0));
  cr_assert_eq(csv_at(&t, 0, 5), -0.5); /* H0 of the orbit with semi-major axis 1 */
  cr_assert_eq(csv_at(&t, 0, 6), 0.0);
  /* the monitor saw the same states: the largest error in the file is the reported one */
  double emax = 0;
  for (size_t i = 0; i < t.n_rows; ++i) {
    double h = csv_at(&t, i, 5), rel = csv_at(&t, i, 6);
    cr_assert(fabs(rel - fabs(h + 0.5) / 0.5) <= 1e-15, "row %zu: rel %g, H %g", i, rel, h);
    emax = fmax(emax, rel);
  }
  double reported = json_number(o, "max_rel_energy_error");
  cr_assert(fabs(emax - reported) <= 1e-14 * reported, "%g vs %g", emax, reported);
  /* the last row is the final state */
  const cJSON *q = cJSON_GetObjectItem(cJSON_GetObjectItem(o, "final"), "q");
  cr_assert_eq(csv_at(&t, 100, 1), cJSON_GetArrayItem(q, 0)->valuedouble);
  csv_free(&t);
  cJSON_Delete(o);
  run_output_free(&r);
}

/* Without an output file the monitor observes every ceil(1024 / stages) steps (at most 1/100 of
 * the planned steps) and the last (issue 25: under 1 % of the run, bench/monitor_cost.c), says so, and its maxima are those of
 * the steps it saw: at most the every-step maxima of --every 1, and equal to them where the
 * largest error falls on an observed step. */
Test(cli, run_monitor_stride) {
  run_output r = run_cli("run kepler --method kahan-li-8 --dt 0.05 --steps 10000 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_assert_eq(json_number(o, "every"), 1);
  cr_assert_eq(json_number(o, "monitor_every"), 61); /* ceil(1024 / 17) */
  /* the initial state, steps 61, 122, ..., 9943 and step 10000 */
  cr_assert_eq(json_number(o, "monitor_observations"), 165);
  const double sampled = json_number(o, "max_rel_energy_error");
  cJSON_Delete(o);
  run_output_free(&r);
  r = run_cli("run kepler --method kahan-li-8 --dt 0.05 --steps 10000 --every 1 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  o = parse_json(r.out);
  cr_assert_eq(json_number(o, "monitor_every"), 1);
  cr_assert_eq(json_number(o, "monitor_observations"), 10001);
  const double all = json_number(o, "max_rel_energy_error");
  /* measured: 1.5664e-11 of 1.5698e-11 */
  cr_assert(sampled > 0.0 && sampled <= all && sampled > 0.9 * all, "%g vs %g", sampled, all);
  cJSON_Delete(o);
  run_output_free(&r);
  r = run_cli("run kepler --method kahan-li-8 --dt 0.05 --steps 10000");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_assert(strstr(r.out, "the maxima are over every 61 steps and the last (165 observed") != NULL,
            "%s", r.out);
  run_output_free(&r);
  r = run_cli("run kepler --method kahan-li-8 --dt 0.05 --steps 10000 --every 1");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_assert(strstr(r.out, "the maxima are over") == NULL, "%s", r.out);
  run_output_free(&r);
}

/* A short run is observed at least about 100 times: 1000 steps of kahan-li-8, every 10. */
Test(cli, run_monitor_short_run) {
  run_output r = run_cli("run kepler --method kahan-li-8 --dt 0.05 --steps 1000 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  cr_assert_eq(json_number(o, "monitor_every"), 10);
  cr_assert_eq(json_number(o, "monitor_observations"), 101);
  cJSON_Delete(o);
  run_output_free(&r);
  r = run_cli("run kepler --method verlet --dt 0.01 --steps 50 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  o = parse_json(r.out);
  cr_assert_eq(json_number(o, "monitor_every"), 1);
  cJSON_Delete(o);
  run_output_free(&r);
}

/* Process start (issue 25): a run that needs no linear algebra, sparse solver, FFT or harminv
 * loads none of them (src/lazy/ opens them on first use); one that does opens LAPACKE then and
 * computes as before. LD_DEBUG=libs lists each library the loader initialises. */
static int loaded(const char *err, const char *lib) {
  const char *key = "calling init: ";
  for (const char *at = strstr(err, key); at != NULL; at = strstr(at + 1, key)) {
    const char *end = strchr(at, '\n');
    const char *hit = strstr(at, lib);
    if (hit != NULL && (end == NULL || hit < end)) return 1;
  }
  return 0;
}

Test(cli, run_loads_heavy_libraries_on_use) {
  static const char *const heavy[] = {"liblapacke", "libopenblas", "libcholmod", "libumfpack",
                                      "libfftw3", "libharminv", "libhdf5", "libHYPRE"};
  run_output r = run_env("LD_DEBUG=libs", "run kepler --steps 1 --quiet");
  cr_assert_eq(r.status, 0, "%s", r.err);
  for (size_t k = 0; k < sizeof heavy / sizeof heavy[0]; ++k)
    cr_expect(!loaded(r.err, heavy[k]), "%s loaded at start", heavy[k]);
  run_output_free(&r);
  r = run_env("LD_DEBUG=libs", "run kepler --method gauss-4 --solver simplified-newton --steps 10 "
              "--quiet --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_expect(loaded(r.err, "liblapacke"), "simplified Newton on Gauss needs LAPACKE (dgeev)");
  cJSON *o = parse_json(r.out);
  cr_expect_eq(json_number(o, "steps"), 10);
  cr_expect_lt(json_number(o, "max_rel_energy_error"), 1e-13); /* measured 8.9e-16 */
  cJSON_Delete(o);
  run_output_free(&r);
}

Test(cli, run_plot) {
  if (!have_gnuplot()) SKIP_TEST("gnuplot is not installed");
  run_output r = run_cli("run kepler --t-end 20 --plot energy.png --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out); /* gnuplot's chatter must not reach stdout */
  cr_assert_str_eq(json_string(o, "plot"), "energy.png");
  cr_assert(file_is_png(path_in_tmp("energy.png")));
  cr_assert(file_size(path_in_tmp("energy.png")) > 1000);
  cJSON_Delete(o);
  run_output_free(&r);
}

Test(cli, run_plot_without_gnuplot) {
  run_output r = run_env("PATH=/nonexistent", "run kepler --plot energy.png");
  cr_assert_eq(r.status, 1);
  cr_assert(strstr(r.err, "gnuplot") != NULL, "%s", r.err);
  cr_assert_eq(count_lines(r.err), 1);
  cr_assert_eq(file_size(path_in_tmp("energy.png")), -1);
  run_output_free(&r);
}

Test(cli, run_plot_unwritable) {
  if (!have_gnuplot()) SKIP_TEST("gnuplot is not installed");
  run_output r = run_cli("run kepler --plot no/such/dir/energy.png --json");
  cr_assert_eq(r.status, 1);
  cr_assert_str_empty(r.out);
  cr_assert_eq(count_lines(r.err), 1, "%s", r.err);
  cr_assert(strstr(r.err, "no/such/dir") != NULL, "%s", r.err);
  run_output_free(&r);
}

/* ---- bad input: one line on stderr, exit status 2 -------------------------------------- */

static void expect_usage_error(const char *args, const char *message) {
  run_output r = run_cli("%s", args);
  cr_assert_eq(r.status, 2, "'%s' exited with %d", args, r.status);
  cr_assert_str_empty(r.out, "'%s' printed on stdout: %s", args, r.out);
  cr_assert_eq(count_lines(r.err), 1, "'%s': stderr is not one line: %s", args, r.err);
  cr_assert(strstr(r.err, message) != NULL, "'%s': '%s' not in: %s", args, message, r.err);
  run_output_free(&r);
}

Test(cli, unknown_names) {
  expect_usage_error("run kepler --method verlt",
                     "unknown method 'verlt'; did you mean: verlet, verlet-position?");
  expect_usage_error("run keplr", "unknown problem 'keplr'; did you mean: kepler?");
  expect_usage_error("run kepler --method nosuchthing", "geomint list methods");
  expect_usage_error("order kepler --method rk5", "did you mean: rk4");
  expect_usage_error("run kepler --metod rk4", "unknown option '--metod'; did you mean: --method?");
  expect_usage_error("list metods", "did you mean: methods?");
  expect_usage_error("rnu kepler", "unknown command 'rnu'; did you mean: run");
  expect_usage_error("run kepler --set bogus=1", "bogus");
  expect_usage_error("run kepler --set omega=2", "omega");
}

Test(cli, bad_numbers) {
  expect_usage_error("run kepler --dt 0", "--dt");
  expect_usage_error("run kepler --dt -0.1", "--dt");
  expect_usage_error("run kepler --dt nan", "--dt");
  expect_usage_error("run kepler --dt inf", "--dt");
  expect_usage_error("run kepler --dt fast", "--dt");
  expect_usage_error("run kepler --t-end 0", "--t-end");
  expect_usage_error("run kepler --t-end 5 --steps 10", "--steps");
  expect_usage_error("run kepler --steps 0", "--steps");
  expect_usage_error("run kepler --steps -3", "--steps");
  expect_usage_error("run kepler --every 0", "--every");
  expect_usage_error("run kepler --set q1", "name=");
  expect_usage_error("order kepler --method rk4 --levels 1", "--levels");
  expect_usage_error("order kepler --method rk4 --levels 17", "--levels");
  expect_usage_error("run", "problem");
  expect_usage_error("order kepler", "--method");
  expect_usage_error("run kepler extra", "extra");
}

Test(cli, bad_initial_state) {
  expect_usage_error("run kepler --set q1=nan", "q1");
  expect_usage_error("run kepler --set p2=inf", "p2");
  expect_usage_error("run kepler --set e=1.5", "kepler");
  /* at the origin the Kepler energy is infinite: no state to start from */
  expect_usage_error("run kepler --method midpoint --set q1=0 --set q2=0", "kepler");
}

/* --set name=TEXT sets a text parameter: n-body reads its bodies from a file; a bad file is
 * a usage error that names the file and the line; a text where a number belongs is one too. */
static void write_text(const char *name, const char *text) {
  FILE *f = fopen(path_in_tmp(name), "w");
  cr_assert_not_null(f);
  fputs(text, f);
  fclose(f);
}

Test(cli, set_file_of_bodies) {
  /* a binary star and a distant light body: m x y z vx vy vz */
  write_text("bodies.txt",
             "# binary\n"
             "1 -0.5 0 0  0 -0.5 0\n"
             "1  0.5 0 0  0  0.5 0\n"
             "\n"
             "1e-3 10 0 0 0 0.4 0  # far away\n");
  run_output r = run_cli("run n-body --set file=bodies.txt --method verlet --dt 0.001 "
                         "--t-end 1 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  const cJSON *final = cJSON_GetObjectItem(o, "final");
  cr_assert_eq(cJSON_GetArraySize(cJSON_GetObjectItem(final, "q")), 9);
  double e = json_number(o, "max_rel_energy_error");
  cr_assert(e > 0 && e < 1e-5, "energy error %g", e);
  cJSON_Delete(o);
  run_output_free(&r);
  /* the same with --set file=PATH before a number setting, and a text given to a number */
  r = run_cli("run n-body --set file=bodies.txt --set eps=0.1 --method verlet --steps 3");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cr_assert(strstr(r.out, "n-body with verlet") != NULL, "%s", r.out);
  run_output_free(&r);

  write_text("bad.txt", "1 0 0 0 0 0 0\n# ok\n1 1 0 0 0 0\n");
  expect_usage_error("run n-body --set file=bad.txt", "bad.txt:3: expected 7 numbers");
  expect_usage_error("run n-body --set file=missing.txt", "cannot open 'missing.txt'");
  expect_usage_error("run n-body --set n=many", "--set n=many: n expects a number, got 'many'");
  expect_usage_error("run kepler --set e=abc", "e expects a number");
  expect_usage_error("run n-body --set file=", "name=value");
  expect_usage_error("run n-body --set fil=bodies.txt", "did you mean: file");
}

/* A method/problem pair the library refuses: exit 2 with the library's message. */
Test(cli, method_does_not_accept_problem) {
  const gm_method *method = NULL;
  const gm_model_info *problem = NULL;
  for (size_t i = 0; i < gm_method_count() && problem == NULL; ++i)
    for (size_t j = 0; j < gm_model_count() && problem == NULL; ++j) {
      gm_model *m = NULL;
      gm_integrator *it = NULL;
      cr_assert_eq(gm_model_create(gm_model_info_at(j)->name, &m), GM_OK);
      cr_assert_eq(gm_model_build(m), GM_OK);
      gm_error err;
      if (gm_integrator_create(gm_method_at(i), gm_model_problem(m), &it, &err) != GM_OK) {
        method = gm_method_at(i);
        problem = gm_model_info_at(j);
      }
      gm_integrator_free(it);
      gm_model_free(m);
    }
  cr_assert_not_null(problem, "every method accepts every built-in problem");
  char args[256];
  snprintf(args, sizeof args, "run %s --method %s", problem->name, method->name);
  expect_usage_error(args, method->name);
}

/* ---- a failure during the run: exit status 1, the CSV kept up to the last good step ---- */

Test(cli, run_failure_keeps_csv) {
  /* p = 0: a radial fall into the centre, reached at t = (π/2)·sqrt(0.4³/2) ≈ 0.281; near it
   * the implicit midpoint rule's iteration (fixed-point on positions, the default for
   * q'' = f(q)) cannot converge */
  run_output r = run_cli("run kepler --method midpoint --set p2=0 --out fall.csv --json");
  cr_assert_eq(r.status, 1, "exit %d, stderr %s", r.status, r.err);
  cJSON *o = parse_json(r.out); /* one JSON object with the error and the partial statistics */
  cr_assert(strstr(json_string(o, "error"), "did not converge") != NULL, "%s", r.out);
  cr_assert_gt(json_number(o, "steps"), 10);
  cJSON_Delete(o);
  cr_assert_eq(count_lines(r.err), 1, "%s", r.err);
  cr_assert(strstr(r.err, "did not converge") != NULL, "%s", r.err);
  const char *at = strstr(r.err, "failed at t = ");
  cr_assert_not_null(at, "%s", r.err);
  double t_fail = strtod(at + strlen("failed at t = "), NULL);
  const char *after = strstr(r.err, " after ");
  cr_assert_not_null(after);
  size_t steps = strtoul(after + strlen(" after "), NULL, 10);
  cr_assert(t_fail > 0.1 && t_fail < 0.2813, "t_fail = %g", t_fail);

  csv_table t = read_csv(path_in_tmp("fall.csv")); /* complete rows only */
  cr_assert_eq(t.n_rows, steps + 1, "rows %zu, steps %zu", t.n_rows, steps);
  cr_assert_eq(csv_at(&t, t.n_rows - 1, 0), t_fail);
  for (size_t i = 0; i < t.n_rows; ++i) {
    cr_assert(isfinite(csv_at(&t, i, 5)), "row %zu: H is not finite", i);
    cr_assert_eq(csv_at(&t, i, 2), 0.0); /* the fall stays on the axis */
  }
  csv_free(&t);
  run_output_free(&r);
}

/* ---- order ------------------------------------------------------------------------------ */

Test(cli, order_rk4_kepler) {
  run_output r = run_cli("order kepler --method rk4 --dt 0.025 --levels 5 --ratio 2 --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  double order = json_number(o, "order");
  cr_assert(fabs(order - 4.0) < 0.3, "order = %g", order);
  cr_assert_str_eq(json_string(o, "reference"), "exact");
  cr_assert_str_eq(json_string(o, "method"), "rk4");
  cr_assert_str_eq(json_string(o, "problem"), "kepler");
  cr_assert_str_eq(json_string(o, "outcome"), "measured");
  const cJSON *dts = cJSON_GetObjectItem(o, "dts"), *errors = cJSON_GetObjectItem(o, "errors");
  cr_assert_eq(cJSON_GetArraySize(dts), 5);
  cr_assert_eq(cJSON_GetArraySize(errors), 5);
  /* the steps actually taken: 3.7 / ceil(3.7 / (0.025 / 2^i)) */
  for (int i = 0; i < 5; ++i) {
    double dt = cJSON_GetArrayItem(dts, i)->valuedouble, nominal = 0.025 / (1 << i);
    cr_assert_eq(dt, 3.7 / ceil(3.7 / nominal - 1e-9), "level %d: dt %.17g", i, dt);
  }
  for (int i = 1; i < 5; ++i) {
    double ratio = cJSON_GetArrayItem(errors, i - 1)->valuedouble /
                   cJSON_GetArrayItem(errors, i)->valuedouble;
    cr_assert(ratio > 12 && ratio < 24, "error ratio %g at level %d", ratio, i);
  }
  cr_assert_geq(json_number(o, "n_fitted"), 3);
  cJSON_Delete(o);
  run_output_free(&r);
}

Test(cli, order_reference_run) {
  /* Hénon–Heiles has no exact solution: a reference run of an explicit method is used */
  run_output r = run_cli("order henon-heiles --method verlet --json");
  cr_assert_eq(r.status, 0, "%s", r.err);
  cJSON *o = parse_json(r.out);
  const gm_method *ref = gm_method_find(json_string(o, "reference"));
  cr_assert_not_null(ref, "reference %s", json_string(o, "reference"));
  cr_assert(ref->flags & GM_EXPLICIT);
  cr_assert(fabs(json_number(o, "order") - 2.0) < 0.2);
  cJSON_Delete(o);
  run_output_free(&r);

  r = run_cli("order kepler --method verlet");
  cr_assert_eq(r.status, 0);
  cr_assert(strstr(r.out, "fitted order 2.0") != NULL, "%s", r.out);
  cr_assert(strstr(r.out, "over levels 0..") != NULL, "%s", r.out);
  run_output_free(&r);
}

/* ---- demo ------------------------------------------------------------------------------- */

/* The row of method in the demo table (after its step): max and final relative energy error,
 * drift of L. */
static void demo_row(const char *table, const char *method, double *emax, double *efinal,
                     double *drift) {
  char needle[32];
  snprintf(needle, sizeof needle, "\n%s ", method);
  const char *row = strstr(table, needle);
  cr_assert_not_null(row, "no row for %s in:\n%s", method, table);
  double dt;
  cr_assert_eq(sscanf(row + strlen(needle), "%lf %lf %lf %lf", &dt, emax, efinal, drift), 4);
}

Test(cli, demo) {
  if (!have_gnuplot()) SKIP_TEST("gnuplot is not installed");
  run_output r = run_cli("demo --out out");
  cr_assert_eq(r.status, 0, "%s", r.err);
  double emax, efinal, drift, verlet_max, yoshida_max, rk4_final;
  demo_row(r.out, "euler", &emax, &efinal, &drift);
  cr_assert(emax > 0.1, "euler: %g", emax); /* explicit Euler gains energy every orbit */
  demo_row(r.out, "verlet", &verlet_max, &efinal, &drift);
  cr_assert(verlet_max > 1e-5 && verlet_max < 1e-3, "verlet: %g", verlet_max);
  cr_assert(efinal <= verlet_max && drift < 1e-10, "verlet: final %g, drift %g", efinal, drift);
  demo_row(r.out, "yoshida-4", &yoshida_max, &efinal, &drift);
  cr_assert(yoshida_max < verlet_max / 10 && drift < 1e-10, "yoshida-4: %g", yoshida_max);
  demo_row(r.out, "rk4", &emax, &rk4_final, &drift);
  /* at equal cost rk4's drift ends above the bounded errors of both symplectic methods */
  cr_assert(rk4_final > verlet_max && rk4_final == emax, "rk4 final %g, verlet max %g",
            rk4_final, verlet_max);
  cr_assert(strstr(r.out, "rk4's energy error passes the largest of verlet") != NULL, "%s",
            r.out);
  /* equal cost: the same number of force evaluations, to one */
  static const char *const methods[] = {"euler", "verlet", "rk4", "yoshida-4"};
  double evals[4];
  for (size_t i = 0; i < 4; ++i) {
    char needle[32];
    snprintf(needle, sizeof needle, "\n%s ", methods[i]);
    const char *row = strstr(r.out, needle);
    cr_assert_not_null(row);
    double dt, a, b, c;
    cr_assert_eq(sscanf(row + strlen(needle), "%lf %lf %lf %lf %lf", &dt, &a, &b, &c,
                        &evals[i]), 5);
    cr_assert(fabs(evals[i] - evals[0]) <= 3, "%s: %g force evaluations, euler %g", methods[i],
              evals[i], evals[0]);
    char name[64];
    snprintf(name, sizeof name, "out/kepler-%s.csv", methods[i]);
    csv_table t = read_csv(path_in_tmp(name));
    cr_assert_eq(t.n_cols, 9);
    cr_assert(t.n_rows > 20000 && t.n_rows < 21000, "%s: %zu rows", name, t.n_rows);
    cr_assert(fabs(csv_at(&t, t.n_rows - 1, 0) - 2000 * 3.14159265358979323846) < 1e-8);
    csv_free(&t);
  }
  cr_assert(file_is_png(path_in_tmp("out/kepler-energy-error.png")));
  /* the fields half: a Yee scene's picture and the mesh leapfrog's invariants (measured: Gauss
   * drift 1.554e-15, div B 0, leapfrog energy 8.498074691 at the start and the end) */
  cr_assert(file_is_png(path_in_tmp("out/yee-field.png")));
  cr_assert(file_is_png(path_in_tmp("out/mesh-energy.png")));
  const char *gauss = strstr(r.out, "max Gauss drift ");
  cr_assert_not_null(gauss, "%s", r.out);
  cr_expect_lt(strtod(gauss + strlen("max Gauss drift "), NULL), 1e-14, "%s", gauss);
  cr_expect(strstr(r.out, "energy: start 8.498074691, end plain") != NULL &&
                strstr(r.out, "leapfrog 8.498074691,") != NULL, "%s", r.out);
  char *readme = read_file(path_in_tmp("out/README.md"));
  static const char *const pictures[] = {"`kepler-energy-error.png`", "`yee-field.png`",
                                         "`mesh-energy.png`"};
  for (size_t i = 0; i < 3; ++i)
    cr_expect(strstr(readme, pictures[i]) != NULL, "README.md lacks %s: %s", pictures[i], readme);
  cr_expect_eq(count_lines(readme), 5, "%s", readme); /* title, blank, one line a picture */
  free(readme);
  run_output_free(&r);
}
