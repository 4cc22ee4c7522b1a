/* The checks of the --json tests (test_cli_json_*.c): the output is one JSON object, every
 * required key occurs in it (at any depth) with a finite number, a string, an array or an
 * object as value (never null: a non-finite number prints as null), and no key uses another
 * name for the shared vocabulary (wall_s, steps, max_rel_*). */
#ifndef GM_TESTS_CLI_JSON_VOCABULARY_H
#define GM_TESTS_CLI_JSON_VOCABULARY_H

#include <math.h>
#include <string.h>

#include "cli/cli_harness.h"

typedef struct json_case {
  const char *command; /* run in the test's directory */
  const char *keys;    /* required, comma-separated */
} json_case;

/* names the vocabulary replaces (a run's time is wall_s, its step count steps) */
static const char *const json_forbidden[] = {"wall",    "wall_time", "elapsed", "elapsed_s",
                                             "seconds", "time_s",    "n_steps", "nsteps",
                                             "num_steps", "runtime"};

static inline const cJSON *json_find(const cJSON *x, const char *key) {
  const cJSON *c;
  if (cJSON_IsObject(x)) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(x, key);
    if (v != NULL) return v;
  }
  if (cJSON_IsObject(x) || cJSON_IsArray(x))
    cJSON_ArrayForEach(c, x) {
      const cJSON *v = json_find(c, key);
      if (v != NULL) return v;
    }
  return NULL;
}

/* every key against the forbidden names; every number finite */
static inline void json_walk(const cJSON *x, const char *command) {
  const cJSON *c;
  if (x->string != NULL)
    for (size_t i = 0; i < sizeof json_forbidden / sizeof json_forbidden[0]; ++i)
      cr_expect(strcmp(x->string, json_forbidden[i]) != 0, "%s: key '%s' (use the shared name)",
                command, x->string);
  if (cJSON_IsNumber(x)) cr_expect(isfinite(x->valuedouble), "%s: %s", command, x->string);
  if (cJSON_IsObject(x) || cJSON_IsArray(x)) cJSON_ArrayForEach(c, x) json_walk(c, command);
}

static inline void check_json_case(const json_case *c) {
  run_output r = run_cli("%s", c->command);
  cr_expect_eq(r.status, 0, "%s: exit %d: %s", c->command, r.status, r.err);
  cJSON *o = cJSON_Parse(r.out);
  cr_expect(cJSON_IsObject(o), "%s: not one JSON object:\n%.400s", c->command, r.out);
  if (cJSON_IsObject(o)) {
    json_walk(o, c->command);
    char keys[512];
    snprintf(keys, sizeof keys, "%s", c->keys);
    for (char *k = strtok(keys, ","); k != NULL; k = strtok(NULL, ",")) {
      const cJSON *v = json_find(o, k);
      cr_expect(v != NULL, "%s: no key '%s'", c->command, k);
      if (v != NULL)
        cr_expect(cJSON_IsNumber(v) || cJSON_IsString(v) || cJSON_IsArray(v) ||
                      cJSON_IsObject(v) || cJSON_IsBool(v),
                  "%s: '%s' is null (a non-finite number)", c->command, k);
    }
    const cJSON *w = cJSON_GetObjectItemCaseSensitive(o, "wall_s");
    if (w != NULL) cr_expect(cJSON_IsNumber(w) && w->valuedouble >= 0.0, "%s: wall_s", c->command);
  }
  cJSON_Delete(o);
  run_output_free(&r);
}

#endif
