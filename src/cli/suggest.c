/* "Did you mean" for the CLI: the name lists and the message (the distance is gm_suggest's). */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"

const char *cli_method_name_at(const void *ctx, size_t i) {
  (void)ctx;
  const gm_method *m = gm_method_at(i);
  return m != NULL ? m->name : NULL;
}

const char *cli_problem_name_at(const void *ctx, size_t i) {
  (void)ctx;
  const gm_model_info *info = gm_model_info_at(i);
  return info != NULL ? info->name : NULL;
}

void cli_unknown(const char *command, const char *kind, const char *query, cli_name_at name_at,
                 const void *ctx, const char *hint) {
  char list[512];
  if (gm_suggest(query, name_at, ctx, list, sizeof list) > 0)
    cli_error(command, "unknown %s '%s'; did you mean: %s?", kind, query, list);
  else if (hint != NULL)
    cli_error(command, "unknown %s '%s'; %s", kind, query, hint);
  else
    cli_error(command, "unknown %s '%s'", kind, query);
}
