/* geomint order PROBLEM --method NAME: the empirical order of convergence. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <cJSON.h>

#include "cli/cli.h"

static const char usage[] =
    "usage: geomint order PROBLEM --method NAME [--basic NAME] [--solver NAME] [--dt H0]\n"
    "                     [--t-end T] [--levels L] [--ratio R] [--reference NAME]\n"
    "                     [--set name=value ...] [--json]\n\n"
    "Measure the order of a method: integrate to T with steps H0, H0/R, ..., H0/R^(L-1) and fit\n"
    "log(error) against log(dt). The error is the max-norm distance of the state at T from the\n"
    "exact solution when the problem has one, else from a reference run.\n\n"
    "options:\n"
    "  --method NAME      method to measure (required)\n"
    "  --dt H0            largest step (default 0.1)\n"
    "  --t-end T          final time (default 1)\n"
    "  --basic NAME       the basic method of a composition (see 'geomint run --help')\n"
    "  --solver NAME      solver of implicit stage equations (see 'geomint run --help')\n"
    "  --levels L         number of step sizes, 2..16 (default 5)\n"
    "  --ratio R          refinement between levels, > 1 (default 2; less for orders > 10)\n"
    "  --reference NAME   reference method when there is no exact solution (default: the\n"
    "                     highest-order explicit method that accepts the problem)\n"
    "  --set name=value   change a parameter or an initial value; repeatable\n"
    "  --json             print {\"order\", \"dts\", \"errors\", ...} as JSON\n";

static int print_result(const char *problem, const gm_scheme *sc, const gm_order_result *r,
                        int json) {
  const gm_method *m = sc->method;
  char name[128];
  cli_scheme_name(sc, name, sizeof name);
  const char *ref_name = r->reference_is_exact ? "exact" : r->reference->name;
  if (json) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "problem", problem);
    cJSON_AddStringToObject(root, "method", m->name);
    if (sc->basic != NULL) cJSON_AddStringToObject(root, "basic", sc->basic->name);
    cJSON_AddNumberToObject(root, "declared_order", m->order);
    cJSON_AddItemToObject(root, "order", cli_json_number(r->order));
    cJSON_AddNumberToObject(root, "n_fitted", (double)r->n_fitted);
    cJSON_AddItemToObject(root, "dts", cli_json_numbers(r->dts, r->n_levels));
    cJSON_AddItemToObject(root, "errors", cli_json_numbers(r->errors, r->n_levels));
    cJSON_AddStringToObject(root, "reference", ref_name);
    return cli_json_print(root);
  }
  printf("%s with %s (declared order %d), reference: %s\n", problem, name, m->order,
         ref_name);
  printf("%14s  %14s  %8s\n", "dt", "error", "ratio");
  for (size_t i = 0; i < r->n_levels; ++i) {
    if (i > 0 && r->errors[i] > 0)
      printf("%14.6e  %14.6e  %8.3f\n", r->dts[i], r->errors[i], r->errors[i - 1] / r->errors[i]);
    else
      printf("%14.6e  %14.6e  %8s\n", r->dts[i], r->errors[i], "");
  }
  printf("fitted order %.3f (over %zu levels)\n", r->order, r->n_fitted);
  return CLI_EXIT_OK;
}

static int measure(const char *problem, const gm_model *model, const gm_scheme *sc,
                   const gm_method *ref, double dt, double t_end, size_t levels, double ratio,
                   int json) {
  const gm_problem *pb = gm_model_problem(model);
  size_t n = gm_model_state_size(model);
  double t0 = 0.0, *y0 = calloc(n, sizeof *y0);
  if (y0 == NULL) {
    cli_error("order", "out of memory");
    return CLI_EXIT_FAILURE;
  }
  gm_model_initial_state(model, &t0, y0);
  if (!(t_end > t0)) {
    free(y0);
    cli_error("order", "--t-end %g is not after the initial time %g", t_end, t0);
    return CLI_EXIT_USAGE;
  }
  gm_order_result r;
  gm_error err = {{0}};
  gm_status st = gm_order_measure(sc, pb, t0, y0, t_end, dt, levels, ratio, ref, &r, &err);
  free(y0);
  if (st != GM_OK) {
    cli_error("order", "%s with %s: %s", problem, sc->method->name,
              err.message[0] ? err.message : gm_strerror(st));
    return st == GM_EINVAL || st == GM_EUNSUPPORTED ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  return print_result(problem, sc, &r, json);
}

static int order_main(int argc, char **argv) {
  const char *method = NULL, *reference = NULL, *basic = NULL, *solver = NULL;
  double dt = 0.1, t_end = 1.0, ratio = 2.0;
  size_t levels = 5;
  int json = 0;
  cli_settings settings = {0, {0}};
  cli_option options[] = {{"--method", CLI_ARG_STRING, &method, 0},
                          {"--dt", CLI_ARG_DOUBLE, &dt, 0},
                          {"--t-end", CLI_ARG_DOUBLE, &t_end, 0},
                          {"--levels", CLI_ARG_COUNT, &levels, 0},
                          {"--ratio", CLI_ARG_DOUBLE, &ratio, 0},
                          {"--basic", CLI_ARG_STRING, &basic, 0},
                          {"--solver", CLI_ARG_STRING, &solver, 0},
                          {"--reference", CLI_ARG_STRING, &reference, 0},
                          {"--set", CLI_ARG_SETTING, &settings, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0}};
  const char *problem[1];
  size_t n_problem = 0;
  int status = cli_parse("order", argc, argv, options, sizeof options / sizeof options[0],
                         problem, 1, &n_problem);
  if (status == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (status != CLI_EXIT_OK) return status;
  if (n_problem == 0 || method == NULL) {
    cli_error("order", "usage: geomint order PROBLEM --method NAME (see 'geomint order --help')");
    return CLI_EXIT_USAGE;
  }
  if (cli_check_positive("order", "--dt", dt) != CLI_EXIT_OK ||
      cli_check_positive("order", "--t-end", t_end) != CLI_EXIT_OK)
    return CLI_EXIT_USAGE;
  if (levels < 2 || levels > GM_ORDER_MAX_LEVELS) {
    cli_error("order", "--levels must be between 2 and %d, got %zu", GM_ORDER_MAX_LEVELS,
              levels);
    return CLI_EXIT_USAGE;
  }
  if (!(ratio > 1.0) || !isfinite(ratio)) {
    cli_error("order", "--ratio must be a finite number > 1, got %g", ratio);
    return CLI_EXIT_USAGE;
  }
  gm_scheme scheme;
  if ((status = cli_make_scheme("order", method, basic, solver, 0, &scheme)) != CLI_EXIT_OK)
    return status;
  const gm_method *ref = NULL;
  if (reference != NULL && (ref = cli_find_method("order", reference)) == NULL)
    return CLI_EXIT_USAGE;
  gm_model *model = NULL;
  if ((status = cli_open_model("order", problem[0], &settings, &model)) != CLI_EXIT_OK)
    return status;
  status = measure(problem[0], model, &scheme, ref, dt, t_end, levels, ratio, json);
  gm_model_free(model);
  return status;
}

const cli_command cli_order_command = {"order", "measure the order of convergence of a method",
                                       usage, order_main};
