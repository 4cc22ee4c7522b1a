/* geomint experiments list|run: the table of the seeds' experiments (src/experiments/table.c)
 * and a run of one of them: the row's library function, the same computation as its command. */
#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/maxwell.h"
#include "geomint/experiments.h"

#define CMD "experiments"

static const char usage[] =
    "usage: geomint experiments list [--json | --markdown]\n"
    "       geomint experiments run NAME [--out DIR] [--json]\n\n"
    "The experiments of the seeds that geomint reproduces, one row each: the seed and section,\n"
    "what it shows, the seed's own number or figure and the command that runs it\n"
    "(docs/experiments.md is made from this table).\n"
    "  list  print the table (--markdown: the docs' table)\n"
    "  run   run one at its defaults, writing into DIR (default experiments-output), and print\n"
    "        its numbers (--json: one JSON object; wall_s is the run's measured time); the\n"
    "        same computation as its command\n";

static const char *name_at(const void *ctx, size_t i) {
  (void)ctx;
  const gm_experiment_info *e = gm_experiment_at(i);
  return e ? e->name : NULL;
}

static int list_json(void) {
  cJSON *a = cJSON_CreateArray();
  for (size_t i = 0; i < gm_experiment_count(); ++i) {
    const gm_experiment_info *e = gm_experiment_at(i);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "name", e->name);
    cJSON_AddStringToObject(o, "seed", e->seed);
    cJSON_AddStringToObject(o, "shows", e->shows);
    cJSON_AddStringToObject(o, "seed_result", e->seed_result);
    char command[256];
    snprintf(command, sizeof command, "geomint %s", e->command);
    cJSON_AddStringToObject(o, "command", command);
    cJSON_AddStringToObject(o, "doc", e->doc);
    cJSON_AddItemToArray(a, o);
  }
  return cli_json_print(a);
}

static int list_markdown(void) {
  puts("| experiment | seed | what it shows | the seed's result | command | our numbers |\n"
       "|---|---|---|---|---|---|");
  for (size_t i = 0; i < gm_experiment_count(); ++i) {
    const gm_experiment_info *e = gm_experiment_at(i);
    const char *page = e->doc + 5; /* past "docs/": the links are relative to docs/ */
    const int page_len = (int)strcspn(page, "#");
    printf("| `%s` | %s | %s | %s | `geomint %s` | [%.*s](%s) |\n", e->name, e->seed,
           e->shows, e->seed_result, e->command, page_len, page, page);
  }
  return fflush(stdout) == 0 ? CLI_EXIT_OK : CLI_EXIT_FAILURE;
}

static int list_text(void) {
  for (size_t i = 0; i < gm_experiment_count(); ++i) {
    const gm_experiment_info *e = gm_experiment_at(i);
    printf("%-26s seed %s\n  %s\n  seed: %s\n  run:  geomint %s\n", e->name, e->seed,
           e->shows, e->seed_result, e->command);
  }
  return CLI_EXIT_OK;
}

static int print_result(const gm_experiment_info *e, const gm_experiment_result *r, int json) {
  if (json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "experiment", e->name);
    for (size_t i = 0; i < r->n_values; ++i)
      cJSON_AddItemToObject(o, r->names[i], cli_json_number(r->values[i]));
    cJSON *files = cJSON_AddArrayToObject(o, "files");
    for (size_t i = 0; i < r->n_files; ++i)
      cJSON_AddItemToArray(files, cJSON_CreateString(r->files[i]));
    return cli_json_print(o);
  }
  printf("%s (seed %s): %s\n", e->name, e->seed, e->shows);
  for (size_t i = 0; i < r->n_values; ++i) printf("  %-26s %.6g\n", r->names[i], r->values[i]);
  printf("  seed: %s\n", e->seed_result);
  for (size_t i = 0; i < r->n_files; ++i) printf("  wrote %s\n", r->files[i]);
  return CLI_EXIT_OK;
}

static int run_main(int argc, char **argv) {
  const char *dir = "experiments-output";
  int json = 0;
  cli_option options[] = {{"--out", CLI_ARG_STRING, &dir, 0}, {"--json", CLI_ARG_FLAG, &json, 0}};
  const char *positional[1];
  size_t n_pos = 0;
  int rc = cli_parse(CMD " run", argc, argv, options, 2, positional, 1, &n_pos);
  if (rc == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  if (n_pos != 1) {
    cli_error(CMD " run", "which experiment? see 'geomint experiments list'");
    return CLI_EXIT_USAGE;
  }
  const gm_experiment_info *e = gm_experiment_find(positional[0]);
  if (e == NULL) {
    cli_unknown(CMD " run", "experiment", positional[0], name_at, NULL,
                "see 'geomint experiments list'");
    return CLI_EXIT_USAGE;
  }
  if ((rc = mx_make_dir(CMD " run", dir)) != CLI_EXIT_OK) return rc;
  gm_experiment_result r = {0};
  gm_error err = {{0}};
  gm_status st = e->run(dir, &r, &err);
  if (st != GM_OK) {
    cli_error(CMD " run", "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  return print_result(e, &r, json);
}

static int list_main(int argc, char **argv) {
  int json = 0, markdown = 0;
  cli_option options[] = {{"--json", CLI_ARG_FLAG, &json, 0},
                          {"--markdown", CLI_ARG_FLAG, &markdown, 0}};
  const char *positional[1];
  size_t n_pos = 0;
  int rc = cli_parse(CMD " list", argc, argv, options, 2, positional, 0, &n_pos);
  if (rc == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (rc != CLI_EXIT_OK) return rc;
  if (json && markdown) {
    cli_error(CMD " list", "--json and --markdown: choose one");
    return CLI_EXIT_USAGE;
  }
  return json ? list_json() : markdown ? list_markdown() : list_text();
}

static int experiments_main(int argc, char **argv) {
  if (argc < 1) {
    fputs(usage, stderr);
    return CLI_EXIT_USAGE;
  }
  if (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (strcmp(argv[0], "list") == 0) return list_main(argc - 1, argv + 1);
  if (strcmp(argv[0], "run") == 0) return run_main(argc - 1, argv + 1);
  cli_error(CMD, "unknown subcommand '%s' (list, run); see 'geomint experiments --help'",
            argv[0]);
  return CLI_EXIT_USAGE;
}

const cli_command cli_experiments_command = {
    CMD, "the seeds' experiments: list them, run one (docs/experiments.md)", usage,
    experiments_main};
