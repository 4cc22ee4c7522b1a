/* The harness of the CLI tests: a temporary directory per test, running the built program in
 * it with stdout and stderr captured, and JSON helpers. Each test file declares its suite with
 *   TestSuite(NAME, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120); */
#ifndef GM_TESTS_CLI_HARNESS_H
#define GM_TESTS_CLI_HARNESS_H

#include <criterion/criterion.h>
#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cJSON.h>

static char tmpdir[256];

static inline void make_tmpdir(void) {
  snprintf(tmpdir, sizeof tmpdir, "/tmp/geomint-cli-XXXXXX");
  cr_assert_not_null(mkdtemp(tmpdir));
}

static inline void remove_tmpdir(void) {
  char cmd[320];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
  cr_assert_eq(system(cmd), 0);
}

/* A skipped test does not reach .fini: clean up first. */
#define SKIP_TEST(why)   \
  do {                   \
    remove_tmpdir();     \
    cr_skip_test(why);   \
  } while (0)

/* ---- running the program ------------------------------------------------------------------ */

typedef struct run_output {
  int status; /* exit status, or -1 when it did not exit normally */
  char *out;  /* stdout */
  char *err;  /* stderr */
} run_output;

static inline char *read_stream(FILE *f) {
  size_t cap = 4096, len = 0;
  char *buf = malloc(cap);
  cr_assert_not_null(buf);
  size_t n;
  while ((n = fread(buf + len, 1, cap - len - 1, f)) > 0) {
    len += n;
    if (cap - len < 2) {
      cap *= 2;
      buf = realloc(buf, cap);
      cr_assert_not_null(buf);
    }
  }
  buf[len] = '\0';
  return buf;
}

static inline char *read_file(const char *path) {
  FILE *f = fopen(path, "r");
  cr_assert_not_null(f, "cannot open %s", path);
  char *s = read_stream(f);
  fclose(f);
  return s;
}

static inline char *path_in_tmp(const char *name) {
  static char buf[4][512];
  static int next = 0;
  char *p = buf[next++ % 4];
  snprintf(p, 512, "%s/%s", tmpdir, name);
  return p;
}

/* Run `env geomint ARGS` in the temporary directory (env may be "" or "PATH=/x"). */
static inline run_output run_env(const char *env, const char *fmt, ...) {
  char args[1024], cmd[2048];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(args, sizeof args, fmt, ap);
  va_end(ap);
  snprintf(cmd, sizeof cmd, "cd '%s' && exec env %s '%s' %s 2>'%s/stderr.txt'", tmpdir, env,
           GM_CLI_PATH, args, tmpdir);
  FILE *p = popen(cmd, "r");
  cr_assert_not_null(p);
  run_output r;
  r.out = read_stream(p);
  int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.err = read_file(path_in_tmp("stderr.txt"));
  return r;
}

#define run_cli(...) run_env("", __VA_ARGS__)

static inline void run_output_free(run_output *r) {
  free(r->out);
  free(r->err);
}

static inline size_t count_lines(const char *s) {
  size_t n = 0;
  for (; *s; ++s) n += *s == '\n';
  return n;
}

/* stdout must be exactly one JSON value (and white space). */
static inline cJSON *parse_json(const char *text) {
  const char *end = NULL;
  cJSON *root = cJSON_ParseWithOpts(text, &end, 0);
  cr_assert_not_null(root, "not JSON: %s", text);
  for (; *end; ++end) cr_assert(isspace((unsigned char)*end), "text after the JSON: %s", end);
  return root;
}

static inline double json_number(const cJSON *obj, const char *key) {
  const cJSON *item = cJSON_GetObjectItemCaseSensitive(obj, key);
  cr_assert(cJSON_IsNumber(item), "key '%s' missing or not a number", key);
  return item->valuedouble;
}

static inline const char *json_string(const cJSON *obj, const char *key) {
  const cJSON *item = cJSON_GetObjectItemCaseSensitive(obj, key);
  cr_assert(cJSON_IsString(item), "key '%s' missing or not a string", key);
  return item->valuestring;
}

static inline int json_array_has(const cJSON *array, const char *s) {
  const cJSON *item;
  cJSON_ArrayForEach(item, array) {
    if (cJSON_IsString(item) && strcmp(item->valuestring, s) == 0) return 1;
  }
  return 0;
}

#endif
