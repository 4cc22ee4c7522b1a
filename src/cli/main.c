/* geomint: the command-line program. Dispatches to one command per file. */
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"

static const cli_command *const commands[] = {&cli_list_command, &cli_run_command,
                                              &cli_order_command, &cli_demo_command,
                                              &cli_wp_command, &cli_mesh_command,
                                              &cli_mimetic_command,
                                              &cli_oscillatory_command,
                                              &cli_maxwell_command,
                                              &cli_reduction_command,
                                              &cli_routh_command,
                                              &cli_pde_command,
                                              &cli_experiments_command,
                                              &cli_fluid_command};
#define N_COMMANDS (sizeof commands / sizeof commands[0])

void cli_error(const char *command, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  if (command != NULL)
    fprintf(stderr, "geomint %s: ", command);
  else
    fputs("geomint: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
}

static void print_usage(FILE *f) {
  fputs("usage: geomint COMMAND [ARGS...]\n\n"
        "geometric numerical integration: symplectic, symmetric and energy-preserving methods\n\n"
        "commands:\n",
        f);
  for (size_t i = 0; i < N_COMMANDS; ++i)
    fprintf(f, "  %-11s %s\n", commands[i]->name, commands[i]->summary);
  fputs("  help        show this message, or a command's: geomint help COMMAND\n\n"
        "options:\n"
        "  --help     show this message\n"
        "  --version  print the version\n\n"
        "Run 'geomint COMMAND --help' for the options of a command.\n"
        "Exit status: 0 success, 1 failure during a run, 2 bad input.\n",
        f);
}

static const char *command_name_at(const void *ctx, size_t i) {
  (void)ctx;
  if (i < N_COMMANDS) return commands[i]->name;
  return i == N_COMMANDS ? "help" : NULL;
}

const cli_command *cli_find_command(const char *name) {
  for (size_t i = 0; i < N_COMMANDS; ++i)
    if (strcmp(commands[i]->name, name) == 0) return commands[i];
  return NULL;
}

static int help(int argc, char **argv) {
  if (argc < 1) {
    print_usage(stdout);
    return CLI_EXIT_OK;
  }
  const cli_command *c = cli_find_command(argv[0]);
  if (c == NULL) {
    cli_unknown(NULL, "command", argv[0], command_name_at, NULL, "see 'geomint --help'");
    return CLI_EXIT_USAGE;
  }
  fputs(c->usage, stdout);
  return CLI_EXIT_OK;
}

int main(int argc, char **argv) {
  /* a file size limit makes write(2) fail with EFBIG (reported) instead of killing us */
  signal(SIGXFSZ, SIG_IGN);
  if (argc < 2) {
    print_usage(stderr);
    return CLI_EXIT_USAGE;
  }
  const char *name = argv[1];
  if (strcmp(name, "--help") == 0 || strcmp(name, "-h") == 0) return help(0, NULL);
  if (strcmp(name, "help") == 0) return help(argc - 2, argv + 2);
  if (strcmp(name, "--version") == 0 || strcmp(name, "version") == 0) {
    printf("geomint %s\n", GM_VERSION_STRING);
    return CLI_EXIT_OK;
  }
  const cli_command *c = cli_find_command(name);
  if (c == NULL) {
    cli_unknown(NULL, "command", name, command_name_at, NULL, "see 'geomint --help'");
    return CLI_EXIT_USAGE;
  }
  return c->main(argc - 2, argv + 2);
}
