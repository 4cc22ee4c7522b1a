/* geomint order PROBLEM --method NAME: the empirical order of convergence. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cJSON.h>

#include "cli/cli.h"

static const char usage[] =
    "usage: geomint order [PROBLEM] --method NAME [--basic NAME] [--solver NAME] [--dt H0]\n"
    "                     [--t-end T] [--levels L] [--ratio R] [--reference NAME]\n"
    "                     [--set name=value ...] [--json] [--quiet]\n\n"
    "Measure the order of a method: integrate PROBLEM (default: kepler with e = 0.1, or for\n"
    "methods of other kinds the first of heavy-top, rigid-body, toy-resonance and\n"
    "outer-solar-system (T = 20000 and H0 = 400 days) they integrate) to T with steps H0,\n"
    "H0/R, ..., H0/R^(L-1) and fit log(error) against log(dt) over the levels whose error lies\n"
    "in the asymptotic window of the method's declared order p (relative to max(1, |y0|):\n"
    "from 10^-(p+2), clamped to [1e-7, 1e-3], down at most 2p decades and not below 1e-12).\n"
    "The error is the max-norm distance of the state at T from the exact solution when the\n"
    "problem has one, else from a reference run. When the order cannot be measured (every\n"
    "error above the window, round-off reached before three levels are in it, too few levels,\n"
    "a slope more than 0.3 off p with round-off right below the window), the table is printed\n"
    "and the reason, with exit status 1.\n\n"
    "options:\n"
    "  --method NAME      method to measure (required)\n"
    "  --dt H0            largest step (default: the largest power of two whose error is in\n"
    "                     the window)\n"
    "  --t-end T          final time (default 3.7, away from the orbit's symmetric points)\n"
    "  --basic NAME       the basic method of a composition (see 'geomint run --help')\n"
    "  --solver NAME      solver of implicit stage equations (see 'geomint run --help')\n"
    "  --levels L         number of step sizes, 2..16 (default: enough to span the window)\n"
    "  --ratio R          refinement between levels, > 1 (default min(2, 10^(1/(2p))))\n"
    "  --reference NAME   reference method when there is no exact solution (default: the\n"
    "                     highest-order explicit method that accepts the problem)\n"
    "  --set name=value   change a parameter or an initial value; repeatable\n"
    "  --json             print {\"order\", \"dts\", \"errors\", ...} as JSON\n"
    "  --quiet            no progress line on a terminal\n";

/* Without a PROBLEM: Kepler with e = 0.1. On the default e = 0.6 the pre-asymptotic range of
 * orders ≥ 10 reaches into the window (sofroniou-spaletta-10 measures 10.9 there, the Gauss
 * rows of order 12 measure 12.9); near-circular orbits have smaller high derivatives. */
#define CLI_ORDER_DEFAULT_SETTING "e=0.1"

/* Without a PROBLEM, the first of these the method can integrate: rows for other kinds
 * (rigid bodies, split potentials, near-integrable splittings) measure on their own kind's
 * classic problem. The lie-group rows of free bodies only (dep-s) take rigid-body. */
static const struct {
  const char *name, *setting;
  double t_end, dt; /* defaults for the problem's time scale (0: the command's) */
} default_problems[] = {{"kepler", CLI_ORDER_DEFAULT_SETTING, 0, 0},
                        {"heavy-top", NULL, 0, 0},
                        {"rigid-body", NULL, 0, 0},
                        {"toy-resonance", NULL, 0, 0},
                        /* days: Jupiter's period is 4333; steps from 400 down */
                        {"outer-solar-system", NULL, 20000, 400}};

static int integrates(const gm_scheme *scheme, const char *name, const char *setting) {
  gm_model *model = NULL;
  int ok = gm_model_create(name, &model) == GM_OK;
  if (ok && setting != NULL) {
    char key[32];
    const char *eq = strchr(setting, '=');
    snprintf(key, sizeof key, "%.*s", (int)(eq - setting), setting);
    ok = gm_model_set(model, key, strtod(eq + 1, NULL)) == GM_OK;
  }
  ok = ok && gm_model_build(model) == GM_OK;
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  ok = ok && gm_integrator_create_scheme(scheme, gm_model_problem(model), &it, &err) == GM_OK;
  gm_integrator_free(it);
  gm_model_free(model);
  return ok;
}

static const char *outcome_text(int outcome) {
  switch (outcome) {
    case GM_ORDER_PRE_ASYMPTOTIC:
      return "every error is above the asymptotic window: the steps are too large (smaller --dt)";
    case GM_ORDER_ROUNDOFF:
      return "round-off reached: the errors fall below the window before three levels are "
             "inside it (the asymptotic range of this order lies at round-off on this problem)";
    case GM_ORDER_TOO_FEW_LEVELS:
      return "too few levels inside the window (more --levels or a smaller --ratio)";
    case GM_ORDER_IRREGULAR:
      return "the errors inside the window do not follow a power law (more than 0.05 decade "
             "from the fitted line: round-off or the solver's tolerance)";
    case GM_ORDER_NOT_SETTLED:
      return "the slope over the window is not the declared order (more than 0.3 off) and the "
             "next levels are already at round-off, so no finer level shows whether it settles: "
             "the asymptotic range of this order is not visible above round-off on this problem "
             "(pre-asymptotic errors, or round-off inside the window; a less eccentric orbit, "
             "e.g. kepler's e = 0.1 of `geomint order --method M`, lifts it)";
    default:
      return "measured";
  }
}

static const char *outcome_key(int outcome) {
  switch (outcome) {
    case GM_ORDER_PRE_ASYMPTOTIC:
      return "pre-asymptotic";
    case GM_ORDER_ROUNDOFF:
      return "round-off";
    case GM_ORDER_TOO_FEW_LEVELS:
      return "too-few-levels";
    case GM_ORDER_IRREGULAR:
      return "irregular";
    case GM_ORDER_NOT_SETTLED:
      return "not-settled";
    default:
      return "measured";
  }
}

static int in_fit(const gm_order_result *r, size_t l) {
  return r->errors[l] >= r->window_bottom && r->errors[l] <= r->window_top;
}

static int print_result(const char *problem, const gm_scheme *sc, const gm_order_result *r,
                        double t_end, int json) {
  const gm_method *m = sc->method;
  char name[128];
  cli_scheme_name(sc, name, sizeof name);
  const char *ref_name = r->reference_is_exact ? "exact" : r->reference->name;
  const int measured = r->outcome == GM_ORDER_MEASURED;
  if (json) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "problem", problem);
    cJSON_AddStringToObject(root, "method", m->name);
    if (sc->basic != NULL) cJSON_AddStringToObject(root, "basic", sc->basic->name);
    cJSON_AddNumberToObject(root, "declared_order", m->order);
    cJSON_AddItemToObject(root, "order", cli_json_number(measured ? r->order : NAN));
    if (r->outcome == GM_ORDER_NOT_SETTLED)
      cJSON_AddItemToObject(root, "slope", cli_json_number(r->order));
    cJSON_AddStringToObject(root, "outcome", outcome_key(r->outcome));
    if (!measured) cJSON_AddStringToObject(root, "error", outcome_text(r->outcome));
    cJSON_AddNumberToObject(root, "n_fitted", (double)r->n_fitted);
    cJSON_AddNumberToObject(root, "fit_deviation", r->fit_deviation);
    cJSON *fitted = cJSON_AddArrayToObject(root, "fitted_levels");
    for (size_t l = 0; l < r->n_levels; ++l)
      if (in_fit(r, l)) cJSON_AddItemToArray(fitted, cJSON_CreateNumber((double)l));
    cJSON_AddItemToObject(root, "window", cli_json_numbers((double[]){r->window_bottom,
                                                                      r->window_top}, 2));
    cJSON_AddNumberToObject(root, "t_end", t_end);
    cJSON_AddNumberToObject(root, "ratio", r->refinement);
    cJSON_AddItemToObject(root, "dts", cli_json_numbers(r->dts, r->n_levels));
    cJSON_AddItemToObject(root, "errors", cli_json_numbers(r->errors, r->n_levels));
    cJSON_AddStringToObject(root, "reference", ref_name);
    int status = cli_json_print(root);
    if (!measured)
      cli_error("order", "%s with %s: order not measured: %s", problem, m->name,
                outcome_text(r->outcome));
    return status != CLI_EXIT_OK ? status : measured ? CLI_EXIT_OK : CLI_EXIT_FAILURE;
  }
  printf("%s with %s (declared order %d) to t = %g, reference: %s\n", problem, name, m->order,
         t_end, ref_name);
  printf("window: errors in [%.1e, %.1e] are fitted (asymptotic range of order %d)\n",
         r->window_bottom, r->window_top, m->order);
  printf("%5s  %14s  %14s  %8s  %s\n", "level", "dt", "error", "ratio", "fit");
  for (size_t i = 0; i < r->n_levels; ++i) {
    const char *mark = in_fit(r, i) ? "*" : r->errors[i] > r->window_top ? "above" : "below";
    if (i > 0 && r->errors[i] > 0)
      printf("%5zu  %14.6e  %14.6e  %8.3f  %s\n", i, r->dts[i], r->errors[i],
             r->errors[i - 1] / r->errors[i], mark);
    else
      printf("%5zu  %14.6e  %14.6e  %8s  %s\n", i, r->dts[i], r->errors[i], "", mark);
  }
  if (r->outcome == GM_ORDER_NOT_SETTLED)
    printf("slope %.3f over levels %zu..%zu (%zu levels, largest deviation %.3f decades), "
           "declared %d\n", r->order, r->first_fitted, r->first_fitted + r->n_fitted - 1,
           r->n_fitted, r->fit_deviation, m->order);
  if (!measured) {
    printf("order not measured: %s\n", outcome_text(r->outcome));
    cli_error("order", "%s with %s: order not measured: %s", problem, m->name,
              outcome_text(r->outcome));
    return CLI_EXIT_FAILURE;
  }
  printf("fitted order %.3f over levels %zu..%zu (%zu levels, largest deviation %.3f "
         "decades)\n", r->order, r->first_fitted, r->first_fitted + r->n_fitted - 1, r->n_fitted,
         r->fit_deviation);
  return CLI_EXIT_OK;
}

static int progress_callback(void *ctx, double done, double total) {
  return cli_progress_update(ctx, done, total);
}

static int measure(const char *problem, const gm_model *model, const gm_scheme *sc,
                   const gm_order_plan *plan_in, double t_end, int json, int quiet) {
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
  gm_order_plan plan = *plan_in;
  if (plan.dt0 > 0.0) {
    const double levels = plan.n_levels > 0 ? (double)plan.n_levels : 2.0;
    const double ratio = plan.refinement > 0.0 ? plan.refinement : 2.0;
    const double dt_min = plan.dt0 / pow(ratio, levels - 1.0);
    if (dt_min >= t_end - t0) {
      free(y0);
      cli_error("order", "--dt %g: every level would take the same single step over the "
                "interval %g .. %g, so there is nothing to fit; use --dt below %g", plan.dt0,
                t0, t_end, (t_end - t0) / 2.0);
      return CLI_EXIT_USAGE;
    }
    if (cli_check_step_count("order", t_end - t0, dt_min) != CLI_EXIT_OK) {
      free(y0);
      return CLI_EXIT_USAGE;
    }
  }
  cli_progress progress;
  cli_progress_start(&progress, "order", quiet);
  plan.progress = progress_callback;
  plan.progress_ctx = &progress;
  gm_order_result r;
  gm_error err = {{0}};
  cli_interrupt_install();
  gm_status st = gm_order_measure_window(sc, pb, t0, y0, t_end, &plan, &r, &err);
  cli_interrupt_restore();
  cli_progress_end(&progress);
  free(y0);
  if (cli_interrupted) {
    cli_error("order", "interrupted (SIGINT) after %zu levels", r.n_levels);
    return CLI_EXIT_INTERRUPTED;
  }
  if (st != GM_OK) {
    cli_error("order", "%s with %s: %s", problem, sc->method->name,
              err.message[0] ? err.message : gm_strerror(st));
    if (json) {
      cJSON *root = cJSON_CreateObject();
      cJSON_AddStringToObject(root, "problem", problem);
      cJSON_AddStringToObject(root, "method", sc->method->name);
      cJSON_AddStringToObject(root, "error", err.message[0] ? err.message : gm_strerror(st));
      cli_json_print(root);
    }
    return st == GM_EINVAL || st == GM_EUNSUPPORTED ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
  }
  return print_result(problem, sc, &r, t_end, json);
}

static int order_main(int argc, char **argv) {
  const char *method = NULL, *reference = NULL, *basic = NULL, *solver = NULL;
  double dt = 0.0, t_end = 3.7, ratio = 0.0;
  size_t levels = 0;
  int json = 0, quiet = 0;
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
                          {"--json", CLI_ARG_FLAG, &json, 0},
                          {"--quiet", CLI_ARG_FLAG, &quiet, 0}};
  const char *problem[1] = {"kepler"};
  size_t n_problem = 0;
  int status = cli_parse("order", argc, argv, options, sizeof options / sizeof options[0],
                         problem, 1, &n_problem);
  if (status == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (status != CLI_EXIT_OK) return status;
  if (method == NULL) {
    cli_error("order", "usage: geomint order [PROBLEM] --method NAME (see 'geomint order --help')");
    return CLI_EXIT_USAGE;
  }
  if ((options[1].seen && cli_check_positive("order", "--dt", dt) != CLI_EXIT_OK) ||
      cli_check_positive("order", "--t-end", t_end) != CLI_EXIT_OK)
    return CLI_EXIT_USAGE;
  if (options[3].seen && (levels < 2 || levels > GM_ORDER_MAX_LEVELS)) {
    cli_error("order", "--levels must be between 2 and %d, got %zu", GM_ORDER_MAX_LEVELS,
              levels);
    return CLI_EXIT_USAGE;
  }
  if (options[4].seen && (!(ratio > 1.0) || !isfinite(ratio))) {
    cli_error("order", "--ratio must be a finite number > 1, got %g", ratio);
    return CLI_EXIT_USAGE;
  }
  gm_scheme scheme;
  if ((status = cli_make_scheme("order", method, basic, solver, 0, &scheme)) != CLI_EXIT_OK)
    return status;
  if (n_problem == 0) { /* the default problem of the method's kind (see default_problems) */
    const size_t n_defaults = sizeof default_problems / sizeof default_problems[0];
    size_t k = 0;
    while (k + 1 < n_defaults &&
           !integrates(&scheme, default_problems[k].name, default_problems[k].setting))
      ++k;
    problem[0] = default_problems[k].name;
    if (default_problems[k].t_end > 0 && !options[2].seen) t_end = default_problems[k].t_end;
    if (default_problems[k].dt > 0 && !options[1].seen) dt = default_problems[k].dt;
    if (default_problems[k].setting != NULL) {
      if (settings.n == CLI_MAX_SETTINGS) {
        cli_error("order", "too many --set options");
        return CLI_EXIT_USAGE;
      }
      memmove(settings.items + 1, settings.items, settings.n * sizeof settings.items[0]);
      settings.items[0] = default_problems[k].setting; /* a later --set overrides it */
      settings.n++;
    }
  }
  const gm_method *ref = NULL;
  if (reference != NULL && (ref = cli_find_method("order", reference)) == NULL)
    return CLI_EXIT_USAGE;
  gm_model *model = NULL;
  if ((status = cli_open_model("order", problem[0], &settings, &model)) != CLI_EXIT_OK)
    return status;
  const gm_order_plan plan = {dt, levels, ratio, ref, NULL, NULL};
  status = measure(problem[0], model, &scheme, &plan, t_end, json, quiet);
  gm_model_free(model);
  return status;
}

const cli_command cli_order_command = {"order", "measure the order of convergence of a method",
                                       usage, order_main};
