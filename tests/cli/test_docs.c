/* The documentation tells the truth: the tables in README.md and docs/ are what the program
 * generates from the registries, the README's C example is the compiled example, and that
 * example runs and prints a small energy error. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char *read_all(FILE *f) {
  size_t cap = 1 << 16, len = 0;
  char *buf = malloc(cap);
  cr_assert_not_null(buf);
  size_t got;
  while ((got = fread(buf + len, 1, cap - len - 1, f)) > 0) {
    len += got;
    if (len + 1 == cap) {
      cap *= 2;
      buf = realloc(buf, cap);
      cr_assert_not_null(buf);
    }
  }
  buf[len] = '\0';
  return buf;
}

static char *read_file(const char *path) {
  FILE *f = fopen(path, "r");
  cr_assert_not_null(f, "cannot open %s", path);
  char *text = read_all(f);
  fclose(f);
  return text;
}

static char *command_output(const char *command) {
  FILE *p = popen(command, "r");
  cr_assert_not_null(p, "%s", command);
  char *text = read_all(p);
  cr_assert_eq(pclose(p), 0, "%s failed", command);
  return text;
}

/* The text between <!-- generated:NAME --> and <!-- end:NAME --> equals the command's output. */
static void check_generated(const char *doc, const char *name, const char *args) {
  char path[1024], begin[64], end[64], command[1200];
  snprintf(path, sizeof path, "%s/%s", GM_SOURCE_DIR, doc);
  snprintf(begin, sizeof begin, "<!-- generated:%s -->\n", name);
  snprintf(end, sizeof end, "<!-- end:%s -->", name);
  snprintf(command, sizeof command, "%s %s", GM_CLI_PATH, args);
  char *text = read_file(path), *expected = command_output(command);
  char *i = strstr(text, begin);
  cr_assert_not_null(i, "%s has no %s", doc, begin);
  i += strlen(begin);
  char *j = strstr(i, end);
  cr_assert_not_null(j, "%s has no %s", doc, end);
  *j = '\0';
  cr_expect_str_eq(i, expected, "%s: table '%s' is stale; run scripts/update-docs", doc, name);
  free(text);
  free(expected);
}

Test(docs, generated_tables_are_current) {
  check_generated("README.md", "methods", "list methods --markdown");
  check_generated("README.md", "problems", "list problems --markdown");
  check_generated("docs/methods.md", "methods", "list methods --markdown");
  check_generated("docs/problems.md", "problems", "list problems --markdown");
  check_generated("docs/experiments.md", "experiments", "experiments list --markdown");
}

Test(docs, readme_example_is_the_compiled_example_and_runs) {
  char *readme = read_file(GM_SOURCE_DIR "/README.md");
  char *example = read_file(GM_SOURCE_DIR "/examples/kepler_verlet.c");
  cr_expect_not_null(strstr(readme, example), "README.md does not show examples/kepler_verlet.c");
  char *out = command_output(GM_BUILD_DIR "/example_kepler_verlet");
  const char *at = strstr(out, "after 100 orbits: ");
  cr_assert_not_null(at, "%s", out);
  double rel = strtod(at + strlen("after 100 orbits: "), NULL);
  cr_expect(rel != 0.0 && rel > -1e-3 && rel < 1e-3, "energy error %g", rel);
  free(readme);
  free(example);
  free(out);
}
