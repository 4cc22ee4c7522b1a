/* The documentation tells the truth: the tables in README.md and docs/ are what the program
 * generates from the registries, the README's C example is the compiled example, and that
 * example runs and prints a small energy error; every code block of a page in docs/ marked
 * <!-- quick-check --> is re-run: each of its `$ geomint ...` commands runs (in the source
 * directory), and every other line of the block (but "...") is a line of their output, token by
 * token, where a `~` in the doc stands for a token that is not compared (a timing, given with its
 * date and load in the text next to the block) and a last token `...` for the rest of the line;
 * and every <!-- output quick-check: CMD --> region of README.md and docs/ is CMD's output, line
 * for line. scripts/update-docs regenerates all of these, and the <!-- output: CMD --> regions
 * whose commands take longer than the test's budget (scripts/docs_regen.py). */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>

/* how many <!-- output quick-check: --> regions the pages hold at least (a lost marker fails) */
#define REGIONS_AT_LEAST 12

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

/* ---- quick examples re-run ------------------------------------------------------------- */

/* Does the doc line equal the output line token by token (`~` matches any token; a last token
 * `...` the rest of the line)? */
static int tokens_match(const char *doc, const char *out) {
  for (;;) {
    while (*doc == ' ' || *doc == '\t') ++doc;
    while (*out == ' ' || *out == '\t') ++out;
    if (strcmp(doc, "...") == 0) return 1;
    if (*doc == '\0' || *out == '\0') return *doc == '\0' && *out == '\0';
    size_t nd = strcspn(doc, " \t"), no = strcspn(out, " \t");
    if (!(nd == 1 && doc[0] == '~') && (nd != no || strncmp(doc, out, nd) != 0)) return 0;
    doc += nd, out += no;
  }
}

static int output_has_line(char *out, const char *doc_line) {
  for (char *line = out; line != NULL && *line != '\0';) {
    char *nl = strchr(line, '\n');
    if (nl != NULL) *nl = '\0';
    const int ok = tokens_match(doc_line, line);
    if (nl != NULL) *nl = '\n';
    if (ok) return 1;
    line = nl != NULL ? nl + 1 : NULL;
  }
  return 0;
}

/* Check every marked block of one page; returns how many blocks were checked. */
static size_t check_quick_blocks(const char *page) {
  char path[1024];
  snprintf(path, sizeof path, "%s/docs/%s", GM_SOURCE_DIR, page);
  char *text = read_file(path);
  size_t checked = 0;
  static const char mark[] = "<!-- quick-check -->\n```";
  for (char *at = strstr(text, mark); at != NULL; at = strstr(at + 1, mark)) {
    char *body = strchr(at + strlen(mark), '\n');
    cr_assert_not_null(body, "%s: unterminated block", page);
    ++body;
    char *end = strstr(body, "\n```");
    cr_assert_not_null(end, "%s: unterminated block", page);
    *end = '\0';
    /* run the commands first, in the source directory: their outputs together */
    size_t cap = 1 << 20, len = 0;
    char *out = calloc(cap, 1);
    cr_assert_not_null(out);
    for (char *line = body; line != NULL && *line != '\0';) {
      char *nl = strchr(line, '\n');
      if (nl != NULL) *nl = '\0';
      if (strncmp(line, "$ geomint ", 10) == 0) {
        char command[2048];
        /* an example may show an error: its message is compared, not the exit status */
        snprintf(command, sizeof command, "cd %s && %s %s 2>&1 || true", GM_SOURCE_DIR, GM_CLI_PATH,
                 line + 10);
        char *got = command_output(command);
        size_t n = strlen(got);
        cr_assert_lt(len + n + 1, cap, "%s: output too long", page);
        memcpy(out + len, got, n + 1);
        len += n;
        free(got);
      }
      if (nl != NULL) *nl = '\n';
      line = nl != NULL ? nl + 1 : NULL;
    }
    cr_assert_gt(len, 0, "%s: a quick-check block without a `$ geomint` command", page);
    for (char *line = body; line != NULL && *line != '\0';) {
      char *nl = strchr(line, '\n');
      if (nl != NULL) *nl = '\0';
      const char *t = line + strspn(line, " \t");
      if (strncmp(line, "$ ", 2) != 0 && strcmp(t, "...") != 0 && *t != '\0')
        cr_expect(output_has_line(out, line), "%s: the line\n%s\nis not in the program's "
                  "output:\n%s", page, line, out);
      if (nl != NULL) *nl = '\n';
      line = nl != NULL ? nl + 1 : NULL;
    }
    free(out);
    *end = '\n';
    ++checked;
  }
  free(text);
  return checked;
}

/* Check every <!-- output quick-check: CMD --> ... <!-- end:output --> region of one page (see
 * scripts/docs_regen.py): CMD, run by the shell in the source directory with the program's
 * directory first on PATH, prints the region's lines, token by token (`~`: any token), no more
 * and no fewer. Returns how many regions were checked. */
static size_t check_output_regions(const char *page) {
  char path[1024], bindir[1024];
  snprintf(path, sizeof path, "%s/%s", GM_SOURCE_DIR, page);
  snprintf(bindir, sizeof bindir, "%s", GM_CLI_PATH);
  *strrchr(bindir, '/') = '\0';
  char *text = read_file(path);
  size_t checked = 0;
  static const char mark[] = "<!-- output quick-check: ", close_mark[] = "<!-- end:output -->";
  for (char *at = strstr(text, mark); at != NULL; at = strstr(at + 1, mark)) {
    char *cmd = at + strlen(mark), *cmd_end = strstr(cmd, " -->\n");
    cr_assert_not_null(cmd_end, "%s: unterminated output marker", page);
    char *body = cmd_end + 5, *end = strstr(body, close_mark);
    cr_assert_not_null(end, "%s: no %s after %.60s", page, close_mark, cmd);
    char command[4096];
    snprintf(command, sizeof command,
             "cd '%s' && export PATH='%s':\"$PATH\" OPENBLAS_NUM_THREADS=1 && { %.*s; }",
             GM_SOURCE_DIR, bindir, (int)(cmd_end - cmd), cmd);
    char *out = command_output(command);
    const char saved = *end;
    *end = '\0';
    char *d = body, *o = out;
    for (size_t line = 1; *d != '\0' || *o != '\0'; ++line) {
      char *dn = strchr(d, '\n'), *on = strchr(o, '\n');
      cr_assert(dn != NULL && on != NULL, "%s: `%.*s`: the page shows %s lines than it prints "
                "(line %zu); run scripts/update-docs", page, (int)(cmd_end - cmd), cmd,
                dn == NULL ? "fewer" : "more", line);
      *dn = *on = '\0';
      cr_expect(tokens_match(d, o), "%s: `%.*s` line %zu: the page says\n%s\nthe program prints\n%s\n"
                "(run scripts/update-docs)", page, (int)(cmd_end - cmd), cmd, line, d, o);
      *dn = *on = '\n';
      d = dn + 1, o = on + 1;
    }
    *end = saved;
    free(out);
    ++checked;
  }
  free(text);
  return checked;
}

Test(docs, output_regions_are_what_the_program_prints, .timeout = 300) {
  size_t regions = check_output_regions("README.md");
  DIR *d = opendir(GM_SOURCE_DIR "/docs");
  cr_assert_not_null(d);
  struct dirent *e;
  while ((e = readdir(d)) != NULL) {
    const size_t n = strlen(e->d_name);
    if (n > 3 && strcmp(e->d_name + n - 3, ".md") == 0) {
      char page[300];
      snprintf(page, sizeof page, "docs/%s", e->d_name);
      regions += check_output_regions(page);
    }
  }
  closedir(d);
  cr_expect_geq(regions, REGIONS_AT_LEAST, "only %zu quick-check output regions", regions);
}

Test(docs, quick_examples_are_what_the_program_prints, .timeout = 300) {
  DIR *d = opendir(GM_SOURCE_DIR "/docs");
  cr_assert_not_null(d);
  size_t blocks = 0;
  struct dirent *e;
  while ((e = readdir(d)) != NULL) {
    const size_t n = strlen(e->d_name);
    if (n > 3 && strcmp(e->d_name + n - 3, ".md") == 0) blocks += check_quick_blocks(e->d_name);
  }
  closedir(d);
  cr_expect_geq(blocks, 14, "only %zu quick-check blocks in docs/", blocks); /* a lost marker fails */
}
