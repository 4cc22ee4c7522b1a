/* Problems and methods by name, with the messages a user sees when a name is wrong. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"

/* gauss-S and lobatto-iiia-iiib-S beyond the table (gm_method_create) live until the program
 * exits; a handful is all one command line names. */
static gm_method *made[64];
static size_t n_made;

const gm_method *cli_find_method(const char *command, const char *name) {
  const gm_method *m = gm_method_find(name);
  if (m != NULL) return m;
  gm_method *built = NULL;
  gm_error err = {{0}};
  gm_status st = gm_method_create(name, &built, &err);
  if (st == GM_OK && n_made == sizeof made / sizeof made[0]) {
    gm_method_free(built);
    cli_error(command, "%s: more than %zu methods made by stage count on one command line", name,
              sizeof made / sizeof made[0]);
    return NULL;
  }
  if (st == GM_OK) {
    made[n_made++] = built;
    return built;
  }
  if (st == GM_EINVAL)
    cli_error(command, "%s", err.message);
  else
    cli_unknown(command, "method", name, cli_method_name_at, NULL,
                "see 'geomint list methods'; gauss-S and lobatto-iiia-iiib-S take any stage "
                "count S");
  return NULL;
}

static const char *solver_name_at(const void *ctx, size_t i) {
  (void)ctx;
  const char *name = gm_solver_name((gm_solver)i);
  return strcmp(name, "unknown") == 0 ? NULL : name;
}

int cli_make_scheme(const char *command, const char *method, const char *basic,
                    const char *solver, int compensated, gm_scheme *out) {
  *out = (gm_scheme){NULL, NULL, GM_SOLVER_DEFAULT, compensated};
  if ((out->method = cli_find_method(command, method)) == NULL) return CLI_EXIT_USAGE;
  if (basic != NULL && (out->basic = cli_find_method(command, basic)) == NULL)
    return CLI_EXIT_USAGE;
  if (solver != NULL && gm_solver_find(solver, &out->solver) != GM_OK) {
    cli_unknown(command, "solver", solver, solver_name_at, NULL,
                "solvers: newton, simplified-newton, fixed-point, fixed-point-positions");
    return CLI_EXIT_USAGE;
  }
  return CLI_EXIT_OK;
}

void cli_scheme_name(const gm_scheme *scheme, char *buf, size_t cap) {
  if (scheme->basic != NULL)
    snprintf(buf, cap, "%s of %s", scheme->method->name, scheme->basic->name);
  else
    snprintf(buf, cap, "%s", scheme->method->name);
}

/* Names gm_model_set accepts: the parameters, then q1..qd, p1..pd or y1..yn. */
typedef struct setting_names {
  const gm_model_info *info;
  char buf[32];
} setting_names;

static const char *setting_name_at(const void *ctx, size_t i) {
  setting_names *s = (setting_names *)ctx;
  const gm_model_info *info = s->info;
  if (i < info->n_params) return info->params[i].name;
  i -= info->n_params;
  int hamiltonian = gm_problem_kind_has_momenta(info->kind);
  size_t d = info->default_dim, n = hamiltonian ? 2 * d : d;
  if (i >= n) return NULL;
  if (hamiltonian)
    snprintf(s->buf, sizeof s->buf, "%c%zu", i < d ? 'q' : 'p', i % d + 1);
  else
    snprintf(s->buf, sizeof s->buf, "y%zu", i + 1);
  return s->buf;
}

static int is_setting_name(const gm_model_info *info, const char *name) {
  setting_names s = {info, {0}};
  for (size_t i = 0;; ++i) {
    const char *c = setting_name_at(&s, i);
    if (c == NULL) return 0;
    if (strcmp(c, name) == 0) return 1;
  }
}

/* Is name a text parameter (a file name, say) of the problem? */
static int is_text_param(const gm_model_info *info, const char *name) {
  for (size_t i = 0; i < info->n_params; ++i)
    if (info->params[i].type == GM_PARAM_TEXT && strcmp(info->params[i].name, name) == 0)
      return 1;
  return 0;
}

/* The whole of text is one number (strtod's syntax, "nan" and "inf" included). */
static int parse_number(const char *text, double *out) {
  char *end = NULL;
  double x = strtod(text, &end);
  if (end == text || *end != '\0') return 0;
  *out = x;
  return 1;
}

/* The library's message, prefixed with the problem's name unless it already says it. */
static void model_error(const char *command, const char *name, const char *setting,
                        const char *message) {
  const char *sep = strstr(message, name) == message ? "" : ": ";
  const char *prefix = sep[0] != '\0' ? name : "";
  if (setting != NULL)
    cli_error(command, "--set %s: %s%s%s", setting, prefix, sep, message);
  else
    cli_error(command, "%s%s%s", prefix, sep, message);
}


int cli_open_model(const char *command, const char *name, const cli_settings *settings,
                   gm_model **out) {
  *out = NULL;
  gm_model *model = NULL;
  if (gm_model_create(name, &model) != GM_OK) {
    if (gm_model_info_find(name) == NULL) {
      cli_unknown(command, "problem", name, cli_problem_name_at, NULL,
                  "see 'geomint list problems'");
      return CLI_EXIT_USAGE;
    }
    cli_error(command, "%s: cannot create the model (out of memory)", name);
    return CLI_EXIT_FAILURE;
  }
  const gm_model_info *info = gm_model_info_of(model);
  for (size_t k = 0; settings != NULL && k < settings->n; ++k) {
    const char *item = settings->items[k];
    char key[64];
    const char *text = cli_setting_split(item, key, sizeof key);
    double value;
    gm_status st;
    if (is_text_param(info, key))
      st = gm_model_set_text(model, key, text);
    else if (parse_number(text, &value))
      st = gm_model_set(model, key, value);
    else if (is_setting_name(info, key)) {
      cli_error(command, "--set %s: %s expects a number, got '%s'", item, key, text);
      gm_model_free(model);
      return CLI_EXIT_USAGE;
    } else
      st = gm_model_set_text(model, key, text); /* an unknown name: the library says so */
    if (st == GM_OK) continue;
    if (!is_setting_name(info, key)) {
      setting_names s = {info, {0}};
      char list[512], what[96];
      snprintf(what, sizeof what, "parameter of %s", name);
      if (gm_suggest(key, setting_name_at, &s, list, sizeof list) > 0)
        cli_error(command, "unknown %s '%s'; did you mean: %s?", what, key, list);
      else
        model_error(command, name, item, gm_model_errmsg(model));
    } else {
      model_error(command, name, item, gm_model_errmsg(model));
    }
    gm_model_free(model);
    return CLI_EXIT_USAGE;
  }
  if (gm_model_build(model) != GM_OK) {
    model_error(command, name, NULL, gm_model_errmsg(model));
    gm_model_free(model);
    return CLI_EXIT_USAGE;
  }
  *out = model;
  return CLI_EXIT_OK;
}

size_t cli_find_invariant(const gm_problem *problem, const char *part) {
  for (size_t k = 0; k < problem->n_invariants; ++k)
    if (strstr(problem->invariants[k].name, part) != NULL) return k;
  return (size_t)-1;
}
