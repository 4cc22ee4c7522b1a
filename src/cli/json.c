/* JSON output with cJSON: non-finite numbers become null. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <cJSON.h>

#include "cli/cli.h"

cJSON *cli_json_number(double x) {
  return isfinite(x) ? cJSON_CreateNumber(x) : cJSON_CreateNull();
}

cJSON *cli_json_numbers(const double *x, size_t n) {
  cJSON *a = cJSON_CreateArray();
  for (size_t i = 0; a != NULL && i < n; ++i) cJSON_AddItemToArray(a, cli_json_number(x[i]));
  return a;
}

int cli_json_print(cJSON *root) {
  char *text = root != NULL ? cJSON_Print(root) : NULL;
  cJSON_Delete(root);
  if (text == NULL) {
    cli_error(NULL, "out of memory while writing JSON");
    return CLI_EXIT_FAILURE;
  }
  puts(text);
  free(text);
  return fflush(stdout) == 0 ? CLI_EXIT_OK : CLI_EXIT_FAILURE;
}
