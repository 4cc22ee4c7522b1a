/* Command-line options: a table per command, "--name value" or "--name=value". */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"

typedef struct option_table {
  const cli_option *options;
  size_t n;
} option_table;

static const char *option_name_at(const void *ctx, size_t i) {
  const option_table *table = ctx;
  if (i < table->n) return table->options[i].name;
  return i == table->n ? "--help" : NULL;
}

static int parse_double(const char *text, double *out) {
  char *end = NULL;
  errno = 0;
  double x = strtod(text, &end);
  if (end == text || *end != '\0') return -1;
  *out = x;
  return 0;
}

static int parse_count(const char *text, size_t *out) {
  if (!isdigit((unsigned char)text[0])) return -1;
  char *end = NULL;
  errno = 0;
  unsigned long long x = strtoull(text, &end, 10);
  if (*end != '\0' || errno == ERANGE || x > (unsigned long long)SIZE_MAX) return -1;
  *out = (size_t)x;
  return 0;
}

/* Store value into option o; returns an exit status. */
/* One more value of a repeatable option (--set, lists), within CLI_MAX_SETTINGS. */
static int append_item(const char *command, const cli_option *o, cli_settings *s,
                       const char *value) {
  if (s->n == CLI_MAX_SETTINGS) {
    cli_error(command, "too many %s options (at most %d)", o->name, CLI_MAX_SETTINGS);
    return CLI_EXIT_USAGE;
  }
  s->items[s->n++] = value;
  return CLI_EXIT_OK;
}

static int store(const char *command, cli_option *o, const char *value) {
  switch (o->type) {
    case CLI_ARG_FLAG:
      *(int *)o->target = 1;
      return CLI_EXIT_OK;
    case CLI_ARG_STRING:
      if (value[0] == '\0') {
        cli_error(command, "%s needs a non-empty value", o->name);
        return CLI_EXIT_USAGE;
      }
      *(const char **)o->target = value;
      return CLI_EXIT_OK;
    case CLI_ARG_DOUBLE:
      if (parse_double(value, o->target) != 0) {
        cli_error(command, "%s expects a number, got '%s'", o->name, value);
        return CLI_EXIT_USAGE;
      }
      return CLI_EXIT_OK;
    case CLI_ARG_COUNT:
      if (parse_count(value, o->target) != 0) {
        cli_error(command, "%s expects a non-negative integer, got '%s'", o->name, value);
        return CLI_EXIT_USAGE;
      }
      return CLI_EXIT_OK;
    case CLI_ARG_SETTING: {
      cli_settings *s = o->target;
      const char *eq = strchr(value, '=');
      if (eq == NULL || eq == value || (size_t)(eq - value) >= 64 || eq[1] == '\0') {
        cli_error(command, "%s expects name=value (e.g. --set e=0.6), got '%s'", o->name, value);
        return CLI_EXIT_USAGE;
      }
      return append_item(command, o, s, value);
    }
    case CLI_ARG_LIST: {
      if (value[0] == '\0') {
        cli_error(command, "%s needs a non-empty value", o->name);
        return CLI_EXIT_USAGE;
      }
      return append_item(command, o, o->target, value);
    }
  }
  return CLI_EXIT_USAGE;
}

int cli_parse(const char *command, int argc, char **argv, cli_option *options,
              size_t n_options, const char **positional, size_t max_positional,
              size_t *n_positional) {
  *n_positional = 0;
  int only_positional = 0;
  for (int i = 0; i < argc; ++i) {
    const char *arg = argv[i];
    if (only_positional || arg[0] != '-' || arg[1] == '\0') {
      if (*n_positional == max_positional) {
        cli_error(command, "unexpected argument '%s'", arg);
        return CLI_EXIT_USAGE;
      }
      positional[(*n_positional)++] = arg;
      continue;
    }
    if (strcmp(arg, "--") == 0) {
      only_positional = 1;
      continue;
    }
    if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) return CLI_HELP;
    const char *eq = strchr(arg, '=');
    size_t len = eq != NULL ? (size_t)(eq - arg) : strlen(arg);
    cli_option *o = NULL;
    for (size_t k = 0; k < n_options; ++k)
      if (strlen(options[k].name) == len && strncmp(options[k].name, arg, len) == 0)
        o = &options[k];
    if (o == NULL) {
      char name[64];
      snprintf(name, sizeof name, "%.*s", (int)(len < 63 ? len : 63), arg);
      option_table table = {options, n_options};
      cli_unknown(command, "option", name, option_name_at, &table, NULL);
      return CLI_EXIT_USAGE;
    }
    if (o->seen && o->type != CLI_ARG_SETTING && o->type != CLI_ARG_LIST) {
      cli_error(command, "%s given twice", o->name);
      return CLI_EXIT_USAGE;
    }
    o->seen = 1;
    const char *value = "";
    if (o->type == CLI_ARG_FLAG) {
      if (eq != NULL) {
        cli_error(command, "%s takes no value", o->name);
        return CLI_EXIT_USAGE;
      }
    } else if (eq != NULL) {
      value = eq + 1;
    } else if (i + 1 < argc) {
      value = argv[++i];
    } else {
      cli_error(command, "%s needs a value", o->name);
      return CLI_EXIT_USAGE;
    }
    int status = store(command, o, value);
    if (status != CLI_EXIT_OK) return status;
  }
  return CLI_EXIT_OK;
}

const char *cli_setting_split(const char *item, char *name, size_t cap) {
  const char *eq = strchr(item, '=');
  size_t len = (size_t)(eq - item);
  if (len >= cap) len = cap - 1;
  memcpy(name, item, len);
  name[len] = '\0';
  return eq + 1;
}

int cli_check_positive(const char *command, const char *option, double value) {
  if (isfinite(value) && value > 0.0) return CLI_EXIT_OK;
  cli_error(command, "%s must be a positive finite number, got %g", option, value);
  return CLI_EXIT_USAGE;
}

int cli_check_step_count(const char *command, double span, double dt) {
  const double steps = span / dt;
  if (steps > 1e15) {
    cli_error(command, "--dt %g is too small: %.3g steps over an interval of %g (at most 1e15)",
              dt, steps, span);
    return CLI_EXIT_USAGE;
  }
  return CLI_EXIT_OK;
}
