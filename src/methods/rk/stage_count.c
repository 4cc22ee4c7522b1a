/* Gauss and Lobatto IIIA–IIIB methods of any stage count. Their coefficients are computed from
 * the nodes when an integrator is created (collocation.c), so a row differs from another only in
 * its stage count, order and name; the table lists s ≤ 8 and s ≤ 4, and these constructors make
 * the same row for any s up to the collocation code's limit, owned by the caller (no global state,
 * no cache). The family, flags, accepted kinds, coefficient function and reference are copied
 * from the table's first row of the family, so the two cannot drift apart. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "methods/internal.h"

#define MAX_STAGES 64 /* collocation.c */

/* One allocation: the row, then its name and description. */
typedef struct {
  gm_method method;
  char name[48];
  char description[96];
} owned_method;

static gm_status make(const char *template_name, const char *family, size_t s, size_t min_s,
                      int order, gm_method **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  *out = NULL;
  if (s < min_s || s > MAX_STAGES)
    return gm_error_set(err, GM_EINVAL, "%s-%zu: %zu stages; %s-s is made for %zu <= s <= %d",
                        family, s, s, family, min_s, MAX_STAGES);
  const gm_method *row = gm_method_find(template_name);
  if (row == NULL) return gm_error_set(err, GM_ENOTFOUND, "no row %s to copy", template_name);
  owned_method *m = malloc(sizeof *m);
  if (m == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  m->method = *row;
  m->method.n_stages = s;
  m->method.order = order;
  snprintf(m->name, sizeof m->name, "%s-%zu", family, s);
  snprintf(m->description, sizeof m->description, "%s, %zu stages, order %d (made for any s)",
           strcmp(family, "gauss") == 0 ? "Gauss-Legendre collocation" : "Lobatto IIIA-IIIB pair",
           s, order);
  m->method.name = m->name;
  m->method.description = m->description;
  *out = &m->method;
  return GM_OK;
}

gm_status gm_method_gauss(size_t s, gm_method **out, gm_error *err) {
  return make("gauss-1", "gauss", s, 1, (int)(2 * s), out, err);
}

gm_status gm_method_lobatto_iiia_iiib(size_t s, gm_method **out, gm_error *err) {
  return make("lobatto-iiia-iiib-2", "lobatto-iiia-iiib", s, 2, (int)(2 * s) - 2, out, err);
}

/* "PREFIX-S" with S a plain decimal count: 1 and S, else 0. */
static int stage_suffix(const char *name, const char *prefix, size_t *s) {
  size_t n = strlen(prefix);
  if (strncmp(name, prefix, n) != 0 || name[n] != '-' || name[n + 1] < '0' || name[n + 1] > '9')
    return 0;
  size_t v = 0;
  for (const char *c = name + n + 1; *c; ++c) {
    if (*c < '0' || *c > '9' || v > 100000) return 0;
    v = 10 * v + (size_t)(*c - '0');
  }
  *s = v;
  return 1;
}

gm_status gm_method_create(const char *name, gm_method **out, gm_error *err) {
  if (name == NULL || out == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  *out = NULL;
  size_t s = 0;
  if (stage_suffix(name, "gauss", &s)) return gm_method_gauss(s, out, err);
  if (stage_suffix(name, "lobatto-iiia-iiib", &s)) return gm_method_lobatto_iiia_iiib(s, out, err);
  return gm_error_set(err, GM_ENOTFOUND,
                      "'%s' is not gauss-S or lobatto-iiia-iiib-S (the families made for any "
                      "stage count S)",
                      name);
}

void gm_method_free(gm_method *method) {
  /* method is the first member of its owned_method */
  free(method);
}
