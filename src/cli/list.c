/* geomint list methods|problems [--json]: the registries as a table or JSON. */
#include <stdio.h>
#include <string.h>

#include <cJSON.h>

#include "cli/cli.h"

static const char usage[] =
    "usage: geomint list methods [--json | --markdown]\n"
    "       geomint list problems [--json | --markdown]\n\n"
    "List the integration methods or the built-in problems.\n\n"
    "options:\n"
    "  --json       print a JSON array (one object per row) instead of a table\n"
    "  --markdown   print a Markdown table with the sources (the README and docs use it)\n";

static const gm_problem_kind kinds[] = {GM_PROBLEM_FIRST_ORDER, GM_PROBLEM_POISSON,
                                        GM_PROBLEM_HAMILTONIAN, GM_PROBLEM_SEPARABLE,
                                        GM_PROBLEM_LAGRANGIAN, GM_PROBLEM_RIGID_BODY};
#define N_KINDS (sizeof kinds / sizeof kinds[0])

static int has_energy_kind(gm_problem_kind kind) { return kind != GM_PROBLEM_FIRST_ORDER; }

/* Append s to buf (capacity cap) after a separator when buf is not empty. */
static void join(char *buf, size_t cap, const char *sep, const char *s) {
  size_t len = strlen(buf);
  snprintf(buf + len, cap - len, "%s%s", len > 0 ? sep : "", s);
}

static void method_flags(const gm_method *m, char *buf, size_t cap) {
  buf[0] = '\0';
  for (size_t bit = 0; bit < GM_N_METHOD_FLAGS; ++bit)
    if (m->flags & (1u << bit)) join(buf, cap, ",", gm_method_flag_name(bit));
}

static void method_accepts(const gm_method *m, char *buf, size_t cap) {
  buf[0] = '\0';
  for (size_t k = 0; k < N_KINDS; ++k)
    if (m->accepts & (unsigned)kinds[k]) join(buf, cap, ",", gm_problem_kind_name(kinds[k]));
}

static int methods_json(void) {
  cJSON *rows = cJSON_CreateArray();
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    cJSON *row = cJSON_CreateObject();
    cJSON_AddStringToObject(row, "name", m->name);
    cJSON_AddStringToObject(row, "family", gm_method_family_name(m->family));
    cJSON_AddNumberToObject(row, "order", m->order);
    cJSON_AddNumberToObject(row, "stages", (double)m->n_stages);
    cJSON *flags = cJSON_AddArrayToObject(row, "flags");
    for (size_t bit = 0; bit < GM_N_METHOD_FLAGS; ++bit)
      if (m->flags & (1u << bit))
        cJSON_AddItemToArray(flags, cJSON_CreateString(gm_method_flag_name(bit)));
    cJSON *accepts = cJSON_AddArrayToObject(row, "accepts");
    for (size_t k = 0; k < N_KINDS; ++k)
      if (m->accepts & (unsigned)kinds[k])
        cJSON_AddItemToArray(accepts, cJSON_CreateString(gm_problem_kind_name(kinds[k])));
    cJSON_AddStringToObject(row, "reference", m->reference != NULL ? m->reference : "");
    cJSON_AddItemToArray(rows, row);
  }
  return cli_json_print(rows);
}

static int methods_table(void) {
  char flags[256], accepts[128];
  int w_name = 4, w_family = 6, w_flags = 5;
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    method_flags(m, flags, sizeof flags);
    int a = (int)strlen(m->name), b = (int)strlen(gm_method_family_name(m->family)),
        c = (int)strlen(flags);
    if (a > w_name) w_name = a;
    if (b > w_family) w_family = b;
    if (c > w_flags) w_flags = c;
  }
  printf("%-*s  %-*s  %5s  %6s  %-*s  %s\n", w_name, "NAME", w_family, "FAMILY", "ORDER",
         "STAGES", w_flags, "FLAGS", "ACCEPTS");
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    method_flags(m, flags, sizeof flags);
    method_accepts(m, accepts, sizeof accepts);
    printf("%-*s  %-*s  %5d  %6zu  %-*s  %s\n", w_name, m->name, w_family,
           gm_method_family_name(m->family), m->order, m->n_stages, w_flags, flags, accepts);
  }
  return CLI_EXIT_OK;
}

static int problems_json(void) {
  cJSON *rows = cJSON_CreateArray();
  for (size_t i = 0; i < gm_model_count(); ++i) {
    const gm_model_info *p = gm_model_info_at(i);
    cJSON *row = cJSON_CreateObject();
    cJSON_AddStringToObject(row, "name", p->name);
    cJSON_AddStringToObject(row, "kind", gm_problem_kind_name(p->kind));
    cJSON_AddNumberToObject(row, "dim", (double)p->default_dim);
    cJSON *params = cJSON_AddObjectToObject(row, "parameters");
    for (size_t k = 0; k < p->n_params; ++k)
      cJSON_AddItemToObject(params, p->params[k].name,
                            p->params[k].type == GM_PARAM_TEXT
                                ? cJSON_CreateString("")
                                : cli_json_number(p->params[k].default_value));
    cJSON *inv = cJSON_AddArrayToObject(row, "invariants");
    if (has_energy_kind(p->kind)) cJSON_AddItemToArray(inv, cJSON_CreateString("energy"));
    for (size_t k = 0; k < p->n_invariants; ++k)
      cJSON_AddItemToArray(inv, cJSON_CreateString(p->invariant_names[k]));
    cJSON_AddBoolToObject(row, "exact_solution", p->has_exact != 0);
    cJSON_AddStringToObject(row, "description", p->description != NULL ? p->description : "");
    cJSON_AddItemToArray(rows, row);
  }
  return cli_json_print(rows);
}

static void problem_params(const gm_model_info *p, char *buf, size_t cap) {
  buf[0] = '\0';
  char item[96];
  for (size_t k = 0; k < p->n_params; ++k) {
    if (p->params[k].type == GM_PARAM_TEXT) /* a text, unset by default */
      snprintf(item, sizeof item, "%s=\"\"", p->params[k].name);
    else
      snprintf(item, sizeof item, "%s=%g", p->params[k].name, p->params[k].default_value);
    join(buf, cap, " ", item);
  }
}

static void problem_invariants(const gm_model_info *p, char *buf, size_t cap) {
  buf[0] = '\0';
  if (has_energy_kind(p->kind)) join(buf, cap, ",", "energy");
  for (size_t k = 0; k < p->n_invariants; ++k) join(buf, cap, ",", p->invariant_names[k]);
}

static int problems_table(void) {
  char params[512], inv[512];
  int w_name = 4, w_kind = 4, w_params = 10, w_inv = 10;
  for (size_t i = 0; i < gm_model_count(); ++i) {
    const gm_model_info *p = gm_model_info_at(i);
    problem_params(p, params, sizeof params);
    problem_invariants(p, inv, sizeof inv);
    int a = (int)strlen(p->name), b = (int)strlen(gm_problem_kind_name(p->kind)),
        c = (int)strlen(params), d = (int)strlen(inv);
    if (a > w_name) w_name = a;
    if (b > w_kind) w_kind = b;
    if (c > w_params) w_params = c;
    if (d > w_inv) w_inv = d;
  }
  printf("%-*s  %-*s  %3s  %-*s  %-*s  %s\n", w_name, "NAME", w_kind, "KIND", "DIM", w_params,
         "PARAMETERS", w_inv, "INVARIANTS", "DESCRIPTION");
  for (size_t i = 0; i < gm_model_count(); ++i) {
    const gm_model_info *p = gm_model_info_at(i);
    problem_params(p, params, sizeof params);
    problem_invariants(p, inv, sizeof inv);
    printf("%-*s  %-*s  %3zu  %-*s  %-*s  %s\n", w_name, p->name, w_kind,
           gm_problem_kind_name(p->kind), p->default_dim, w_params, params, w_inv, inv,
           p->description != NULL ? p->description : "");
  }
  return CLI_EXIT_OK;
}

/* Markdown tables: flag lists separated by ", " so that they wrap. */
static int methods_markdown(void) {
  char flags[256], accepts[128];
  puts("| method | family | order | stages | properties | accepts | source |");
  puts("|---|---|---:|---:|---|---|---|");
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    flags[0] = accepts[0] = '\0';
    for (size_t bit = 0; bit < GM_N_METHOD_FLAGS; ++bit)
      if (m->flags & (1u << bit)) join(flags, sizeof flags, ", ", gm_method_flag_name(bit));
    for (size_t k = 0; k < N_KINDS; ++k)
      if (m->accepts & (unsigned)kinds[k])
        join(accepts, sizeof accepts, ", ", gm_problem_kind_name(kinds[k]));
    printf("| `%s` | %s | %d | %zu | %s | %s | %s |\n", m->name, gm_method_family_name(m->family),
           m->order, m->n_stages, flags, accepts, m->reference != NULL ? m->reference : "");
  }
  return CLI_EXIT_OK;
}

static int problems_markdown(void) {
  char params[512], inv[512];
  puts("| problem | kind | dim | parameters | invariants | description |");
  puts("|---|---|---:|---|---|---|");
  for (size_t i = 0; i < gm_model_count(); ++i) {
    const gm_model_info *p = gm_model_info_at(i);
    problem_params(p, params, sizeof params);
    problem_invariants(p, inv, sizeof inv);
    printf("| `%s` | %s | %zu | %s | %s | %s |\n", p->name, gm_problem_kind_name(p->kind),
           p->default_dim, params, inv, p->description != NULL ? p->description : "");
  }
  return CLI_EXIT_OK;
}

static const char *what_name_at(const void *ctx, size_t i) {
  (void)ctx;
  static const char *const names[] = {"methods", "problems"};
  return i < 2 ? names[i] : NULL;
}

static int list_main(int argc, char **argv) {
  int json = 0, markdown = 0;
  cli_option options[] = {{"--json", CLI_ARG_FLAG, &json, 0},
                          {"--markdown", CLI_ARG_FLAG, &markdown, 0}};
  const char *what[1];
  size_t n_what = 0;
  int status = cli_parse("list", argc, argv, options, 2, what, 1, &n_what);
  if (status == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (status != CLI_EXIT_OK) return status;
  if (n_what == 0) {
    cli_error("list", "what to list? 'methods' or 'problems'");
    return CLI_EXIT_USAGE;
  }
  if (json && markdown) {
    cli_error("list", "--json and --markdown exclude each other");
    return CLI_EXIT_USAGE;
  }
  if (strcmp(what[0], "methods") == 0)
    return json ? methods_json() : markdown ? methods_markdown() : methods_table();
  if (strcmp(what[0], "problems") == 0)
    return json ? problems_json() : markdown ? problems_markdown() : problems_table();
  cli_unknown("list", "list", what[0], what_name_at, NULL, "use 'methods' or 'problems'");
  return CLI_EXIT_USAGE;
}

const cli_command cli_list_command = {"list", "list the methods or the problems", usage,
                                      list_main};
