/* The JSON scene file of `geomint maxwell run`: grid, materials, boundaries, PML, sources,
 * probes, flux planes, output and run length (docs/maxwell.md lists every key). Every error
 * names the JSON path of the bad value, e.g. "sources[1].position[2]: expected a number";
 * unknown keys are errors too (with the nearest known key), so that a typo never silently
 * falls back to a default. */
#include <cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fields/internal.h"
#include "geomint/yee_scene.h"

/* ---- the JSON path of the value being read ----------------------------------------------- */

typedef struct parser {
  char path[256];
  size_t len;
  char *msg;
  size_t cap;
  const char *name; /* the file, for messages */
} parser;

static size_t push_key(parser *p, const char *key) {
  size_t old = p->len;
  int n = snprintf(p->path + p->len, sizeof p->path - p->len, "%s%s", p->len > 0 ? "." : "", key);
  if (n > 0) p->len = p->len + (size_t)n < sizeof p->path ? p->len + (size_t)n : sizeof p->path - 1;
  return old;
}

static size_t push_index(parser *p, size_t i) {
  size_t old = p->len;
  int n = snprintf(p->path + p->len, sizeof p->path - p->len, "[%zu]", i);
  if (n > 0) p->len = p->len + (size_t)n < sizeof p->path ? p->len + (size_t)n : sizeof p->path - 1;
  return old;
}

static void pop(parser *p, size_t old) {
  p->len = old;
  p->path[old] = '\0';
}

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static int fail(parser *p, const char *fmt, ...) {
  char what[384];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  char raw[2 * GM_ERRMSG_SIZE];
  snprintf(raw, sizeof raw, "%s: %s: %s", p->name, p->len > 0 ? p->path : "(top level)", what);
  gm_escape_controls(raw, p->msg, p->cap); /* a key like "\u001b[31m" must not reach a terminal */
  return -1;
}

static const char *type_name(const cJSON *v) {
  if (cJSON_IsNumber(v)) return "a number";
  if (cJSON_IsString(v)) return "a string";
  if (cJSON_IsBool(v)) return "a boolean";
  if (cJSON_IsNull(v)) return "null";
  if (cJSON_IsArray(v)) return "an array";
  return "an object";
}

/* ---- typed getters: 0 found, 1 absent (optional), -1 error (message written) ----------- */

static const cJSON *member(const cJSON *obj, const char *key) {
  return cJSON_GetObjectItemCaseSensitive(obj, key);
}

/* Unknown keys of obj (not in the NULL-terminated list) are errors with a suggestion. */
static int check_keys(parser *p, const cJSON *obj, const char *const *known) {
  const cJSON *item;
  cJSON_ArrayForEach(item, obj) {
    int ok = 0;
    for (size_t k = 0; known[k] != NULL && !ok; ++k) ok = strcmp(known[k], item->string) == 0;
    if (ok) continue;
    const char *best = NULL;
    size_t best_d = 3;
    for (size_t k = 0; known[k] != NULL; ++k) {
      size_t d = gm_edit_distance(item->string, known[k]);
      if (d < best_d) best_d = d, best = known[k];
    }
    size_t old = push_key(p, item->string);
    if (best != NULL) return fail(p, "unknown key (did you mean '%s'?)", best);
    char list[256];
    size_t len = 0;
    for (size_t k = 0; known[k] != NULL && len < sizeof list; ++k) {
      int n = snprintf(list + len, sizeof list - len, "%s%s", k > 0 ? ", " : "", known[k]);
      if (n > 0) len += (size_t)n;
    }
    int rc = fail(p, "unknown key (known: %s)", list);
    pop(p, old);
    return rc;
  }
  return 0;
}

static int get_object(parser *p, const cJSON *obj, const char *key, int required,
                      const cJSON **out) {
  const cJSON *v = member(obj, key);
  *out = v;
  if (v == NULL) {
    if (!required) return 1;
    size_t old = push_key(p, key);
    int rc = fail(p, "missing (expected an object)");
    pop(p, old);
    return rc;
  }
  if (!cJSON_IsObject(v)) {
    size_t old = push_key(p, key);
    int rc = fail(p, "expected an object, got %s", type_name(v));
    pop(p, old);
    return rc;
  }
  return 0;
}

static int get_array(parser *p, const cJSON *obj, const char *key, const cJSON **out) {
  const cJSON *v = member(obj, key);
  *out = v;
  if (v == NULL) return 1;
  if (!cJSON_IsArray(v)) {
    size_t old = push_key(p, key);
    int rc = fail(p, "expected an array, got %s", type_name(v));
    pop(p, old);
    return rc;
  }
  return 0;
}

/* A number at the current path (already pushed). */
static int number_here(parser *p, const cJSON *v, double *out) {
  if (!cJSON_IsNumber(v)) return fail(p, "expected a number, got %s", type_name(v));
  if (!isfinite(v->valuedouble)) return fail(p, "expected a finite number");
  *out = v->valuedouble;
  return 0;
}

static int get_number(parser *p, const cJSON *obj, const char *key, int required,
                      double *out) {
  const cJSON *v = member(obj, key);
  size_t old = push_key(p, key);
  int rc = 1;
  if (v != NULL)
    rc = number_here(p, v, out);
  else if (required)
    rc = fail(p, "missing (expected a number)");
  pop(p, old);
  return rc;
}

/* A non-negative integer (a count or an index). */
static int get_count(parser *p, const cJSON *obj, const char *key, int required, size_t *out) {
  const cJSON *v = member(obj, key);
  size_t old = push_key(p, key);
  int rc = 1;
  if (v == NULL) {
    if (required) rc = fail(p, "missing (expected a non-negative integer)");
  } else if (!cJSON_IsNumber(v) || !(v->valuedouble >= 0) || v->valuedouble > 1e15 ||
             floor(v->valuedouble) != v->valuedouble) {
    rc = fail(p, "expected a non-negative integer, got %s",
              cJSON_IsNumber(v) ? "a number that is not one" : type_name(v));
  } else {
    *out = (size_t)v->valuedouble;
    rc = 0;
  }
  pop(p, old);
  return rc;
}

static int get_string(parser *p, const cJSON *obj, const char *key, int required,
                      const char **out) {
  const cJSON *v = member(obj, key);
  size_t old = push_key(p, key);
  int rc = 1;
  if (v == NULL) {
    if (required) rc = fail(p, "missing (expected a string)");
  } else if (!cJSON_IsString(v) || v->valuestring[0] == '\0') {
    rc = fail(p, "expected a non-empty string, got %s", type_name(v));
  } else {
    *out = v->valuestring;
    rc = 0;
  }
  pop(p, old);
  return rc;
}

static int get_bool(parser *p, const cJSON *obj, const char *key, int *out) {
  const cJSON *v = member(obj, key);
  if (v == NULL) return 1;
  size_t old = push_key(p, key);
  int rc = 0;
  if (!cJSON_IsBool(v))
    rc = fail(p, "expected true or false, got %s", type_name(v));
  else
    *out = cJSON_IsTrue(v);
  pop(p, old);
  return rc;
}

/* An array of min..max numbers into out (the rest set to fill). */
static int get_vector(parser *p, const cJSON *obj, const char *key, int required, size_t min,
                      size_t max, double fill, double *out) {
  const cJSON *v = member(obj, key);
  size_t old = push_key(p, key);
  int rc = 0;
  if (v == NULL) {
    rc = required ? fail(p, "missing (expected %zu numbers)", min) : 1;
  } else if (!cJSON_IsArray(v)) {
    rc = fail(p, "expected an array of %zu numbers, got %s", min, type_name(v));
  } else {
    size_t n = (size_t)cJSON_GetArraySize(v);
    if (n < min || n > max) {
      if (min == max)
        rc = fail(p, "expected %zu numbers, got %zu", min, n);
      else
        rc = fail(p, "expected %zu to %zu numbers, got %zu", min, max, n);
    }
    for (size_t i = 0; rc == 0 && i < max; ++i) {
      if (i >= n) {
        out[i] = fill;
        continue;
      }
      size_t o = push_index(p, i);
      rc = number_here(p, cJSON_GetArrayItem(v, (int)i), &out[i]);
      pop(p, o);
    }
  }
  pop(p, old);
  return rc;
}

static int get_component(parser *p, const cJSON *obj, const char *key, const gm_yee_grid *grid,
                         gm_yee_component *out) {
  const char *s = NULL;
  int rc = get_string(p, obj, key, 1, &s);
  if (rc != 0) return rc;
  size_t old = push_key(p, key);
  if (gm_yee_component_find(s, out) != GM_OK)
    rc = fail(p, "unknown field component '%s' (Ex, Ey, Ez, Hx, Hy, Hz)", s);
  else if (!gm_yee_dim_has(grid->dim, *out))
    rc = fail(p, "this grid has no %s component", gm_yee_component_name(*out));
  pop(p, old);
  return rc;
}

static int get_axis(parser *p, const cJSON *obj, const char *key, size_t axes, int *out) {
  const char *s = NULL;
  int rc = get_string(p, obj, key, 1, &s);
  if (rc != 0) return rc;
  size_t old = push_key(p, key);
  int a = strcmp(s, "x") == 0 ? 0 : strcmp(s, "y") == 0 ? 1 : strcmp(s, "z") == 0 ? 2 : -1;
  if (a < 0)
    rc = fail(p, "expected \"x\", \"y\" or \"z\", got \"%s\"", s);
  else if ((size_t)a >= axes)
    rc = fail(p, "this grid has no %s axis", s);
  else
    *out = a;
  pop(p, old);
  return rc;
}

/* ---- sections ---------------------------------------------------------------------------- */

static int parse_grid(parser *p, const cJSON *root, gm_yee_scene *s) {
  const cJSON *g;
  if (get_object(p, root, "grid", 1, &g) != 0) return -1;
  size_t old = push_key(p, "grid");
  static const char *const keys[] = {"dim", "cells", "size", "h", "origin", NULL};
  int rc = check_keys(p, g, keys);
  const char *dim = "3d";
  if (rc == 0 && get_string(p, g, "dim", 0, &dim) < 0) rc = -1;
  if (rc == 0) {
    static const struct { const char *name; gm_yee_dim dim; } dims[] = {
        {"1d", GM_YEE_1D}, {"2d-te", GM_YEE_2D_TE}, {"2d-tm", GM_YEE_2D_TM}, {"3d", GM_YEE_3D}};
    int found = 0;
    for (size_t k = 0; k < 4; ++k)
      if (strcmp(dims[k].name, dim) == 0) s->grid.dim = dims[k].dim, found = 1;
    if (!found) {
      size_t o = push_key(p, "dim");
      rc = fail(p, "expected \"1d\", \"2d-te\", \"2d-tm\" or \"3d\", got \"%s\"", dim);
      pop(p, o);
    }
  }
  size_t axes = rc == 0 ? gm_yee_dim_axes(s->grid.dim) : 0;
  double cells[3] = {1, 1, 1}, size[3] = {1, 1, 1}, h[3] = {1, 1, 1};
  if (rc == 0 && get_vector(p, g, "cells", 1, axes, axes, 1, cells) != 0) rc = -1;
  for (size_t a = 0; rc == 0 && a < axes; ++a)
    if (cells[a] < 1 || floor(cells[a]) != cells[a] || cells[a] > 1e9) {
      size_t o = push_key(p, "cells");
      size_t o2 = push_index(p, a);
      rc = fail(p, "expected a positive whole number of cells, got %g", cells[a]);
      pop(p, o2);
      pop(p, o);
    }
  int has_size = rc == 0 ? get_vector(p, g, "size", 0, axes, axes, 1, size) : -1;
  int has_h = has_size >= 0 ? get_vector(p, g, "h", 0, axes, axes, 1, h) : -1;
  if (rc == 0 && (has_size < 0 || has_h < 0)) rc = -1;
  if (rc == 0 && has_size == 0 && has_h == 0) rc = fail(p, "give either \"size\" or \"h\", not both");
  if (rc == 0 && has_size != 0 && has_h != 0) rc = fail(p, "missing \"size\" (or \"h\")");
  for (size_t a = 0; rc == 0 && a < axes; ++a) {
    double x = has_size == 0 ? size[a] : h[a];
    if (!(x > 0)) {
      size_t o = push_key(p, has_size == 0 ? "size" : "h");
      size_t o2 = push_index(p, a);
      rc = fail(p, "must be > 0, got %g", x);
      pop(p, o2);
      pop(p, o);
    }
  }
  if (rc == 0) {
    /* the solver's arrays, estimated before anything is allocated */
    gm_yee_grid est = s->grid;
    for (size_t a = 0; a < 3; ++a) est.n[a] = a < axes ? (size_t)cells[a] : 1;
    gm_error e = {{0}};
    if (yee_memory_check(yee_grid_bytes(&est, 0), "the fields, coefficients and materials",
                         &e) != GM_OK) {
      size_t o = push_key(p, "cells");
      rc = fail(p, "%.0f x %.0f x %.0f cells: %s", cells[0], cells[1], cells[2], e.message);
      pop(p, o);
    }
  }
  double origin[3] = {0, 0, 0};
  if (rc == 0 && get_vector(p, g, "origin", 0, axes, 3, 0, origin) < 0) rc = -1;
  if (rc == 0)
    for (size_t a = 0; a < 3; ++a) {
      s->grid.n[a] = a < axes ? (size_t)cells[a] : 1;
      s->grid.h[a] = a < axes ? (has_size == 0 ? size[a] / cells[a] : h[a]) : 1.0;
      s->grid.origin[a] = origin[a];
    }
  pop(p, old);
  return rc;
}

static const char *const medium_keys[] = {"epsilon", "mu", "sigma"};

/* One element of "poles": {"type": "drude"|"lorentz", "frequency", "gamma", "delta_epsilon"}. */
static int parse_pole(parser *p, const cJSON *item, gm_pole *pole) {
  static const char *const keys[] = {"type", "frequency", "gamma", "delta_epsilon", NULL};
  const char *type = NULL;
  *pole = (gm_pole){GM_POLE_DRUDE, 0.0, 0.0, 0.0};
  if (check_keys(p, item, keys) != 0 || get_string(p, item, "type", 1, &type) != 0) return -1;
  if (strcmp(type, "drude") == 0 || strcmp(type, "lorentz") == 0) {
    pole->kind = type[0] == 'd' ? GM_POLE_DRUDE : GM_POLE_LORENTZ;
  } else {
    size_t o = push_key(p, "type");
    int rc = fail(p, "expected \"drude\" or \"lorentz\", got \"%s\"", type);
    pop(p, o);
    return rc;
  }
  const int lorentz = pole->kind == GM_POLE_LORENTZ;
  if (get_number(p, item, "frequency", 1, &pole->frequency) != 0 ||
      get_number(p, item, "gamma", 0, &pole->gamma) < 0 ||
      get_number(p, item, "delta_epsilon", lorentz, &pole->strength) < 0)
    return -1;
  if (!lorentz && member(item, "delta_epsilon") != NULL) {
    size_t o = push_key(p, "delta_epsilon");
    int rc = fail(p, "a Drude pole has no delta_epsilon (its strength is the plasma frequency)");
    pop(p, o);
    return rc;
  }
  return 0;
}

/* "library" (a metal of the material library, lengths in the scene's unit_um) and "poles" of
 * obj: the poles the materials' pen gets for this medium (none when neither is given). */
static int parse_poles(parser *p, const cJSON *obj, gm_yee_scene *s, gm_medium *m) {
  gm_pole poles[GM_MATERIAL_MAX_POLES + 16];
  size_t n = 0;
  const char *lib = NULL;
  int rc = get_string(p, obj, "library", 0, &lib);
  if (rc < 0) return -1;
  if (rc == 0) {
    gm_error err = {{0}};
    size_t o = push_key(p, "library");
    const double eps = m->epsilon;
    if (gm_material_find(lib, s->unit_um, m, poles, GM_MATERIAL_MAX_POLES, &n, &err) != GM_OK) {
      rc = fail(p, "%s", err.message);
      pop(p, o);
      return rc;
    }
    pop(p, o);
    if (member(obj, "epsilon") != NULL) m->epsilon = eps; /* an explicit ε∞ wins */
  }
  const cJSON *list;
  rc = get_array(p, obj, "poles", &list);
  if (rc < 0) return -1;
  if (rc == 0) {
    size_t old = push_key(p, "poles");
    size_t k = 0;
    const cJSON *item;
    cJSON_ArrayForEach(item, list) {
      size_t o = push_index(p, k);
      if (n >= sizeof poles / sizeof poles[0])
        rc = fail(p, "too many poles (at most %zu with the library's)", sizeof poles / sizeof poles[0]);
      else if (!cJSON_IsObject(item))
        rc = fail(p, "expected an object, got %s", type_name(item));
      else
        rc = parse_pole(p, item, &poles[n++]);
      pop(p, o);
      ++k;
      if (rc != 0) break;
    }
    pop(p, old);
    if (rc != 0) return -1;
  }
  gm_error err = {{0}};
  if (gm_poles_check(n, poles, &err) != GM_OK) {
    /* "poles[k].field: why": the library's poles come first, so k is the array index only when
     * there is no library; name it as the path either way */
    char key[64] = {0};
    const char *colon = strstr(err.message, ": ");
    const size_t len = colon ? (size_t)(colon - err.message) : 0;
    if (len > 0 && len < sizeof key) memcpy(key, err.message, len);
    size_t o = push_key(p, key[0] ? key : "poles");
    rc = fail(p, "%s", colon ? colon + 2 : err.message);
    pop(p, o);
    return rc;
  }
  if (gm_yee_materials_set_poles(s->materials, n, poles) != GM_OK)
    return fail(p, "%s", gm_yee_materials_errmsg(s->materials));
  return 0;
}

/* epsilon, mu, sigma of obj over the defaults in m. */
static int parse_medium(parser *p, const cJSON *obj, gm_medium *m) {
  double *v[3] = {&m->epsilon, &m->mu, &m->sigma};
  for (size_t k = 0; k < 3; ++k) {
    if (get_number(p, obj, medium_keys[k], 0, v[k]) < 0) return -1;
    size_t o = push_key(p, medium_keys[k]);
    int bad = k < 2 ? !(*v[k] > 0) : !(*v[k] >= 0);
    int rc = bad ? fail(p, "must be %s 0, got %g", k < 2 ? ">" : ">=", *v[k]) : 0;
    pop(p, o);
    if (rc != 0) return -1;
  }
  return 0;
}

/* Calls one(p, item, i, s) for each element i of the array list, with the JSON path
   "key[i]" pushed so that errors name it; an element that is not an object is an error. Stops
   at the first failure. */
typedef int (*element_fn)(parser *p, const cJSON *item, size_t i, gm_yee_scene *s);
static int for_each_object(parser *p, const cJSON *list, const char *key, element_fn one,
                           gm_yee_scene *s) {
  size_t old = push_key(p, key);
  size_t i = 0;
  const cJSON *item;
  int rc = 0;
  cJSON_ArrayForEach(item, list) {
    size_t o = push_index(p, i);
    rc = cJSON_IsObject(item) ? one(p, item, i, s)
                              : fail(p, "expected an object, got %s", type_name(item));
    pop(p, o);
    ++i;
    if (rc != 0) break;
  }
  pop(p, old);
  return rc;
}

static int lib_fail(parser *p, const char *what) { return fail(p, "%s", what); }

/* One element of "materials": a shape painted with a medium. */
static int parse_material(parser *p, const cJSON *item, size_t i, gm_yee_scene *s) {
  (void)i;
  const size_t axes = gm_yee_dim_axes(s->grid.dim);
  const char *shape = NULL;
  gm_medium m = gm_medium_vacuum();
  int rc = get_string(p, item, "shape", 1, &shape) != 0 ? -1 : 0;
  if (rc == 0 && parse_medium(p, item, &m) != 0) rc = -1;
  if (rc == 0 && parse_poles(p, item, s, &m) != 0) rc = -1;
  gm_status st = GM_OK;
  if (rc == 0 && strcmp(shape, "box") == 0) {
    static const char *const keys[] = {"shape", "epsilon", "mu", "sigma", "poles", "library",
                                       "lo", "hi", NULL};
    double lo[3], hi[3];
    if (check_keys(p, item, keys) != 0 || get_vector(p, item, "lo", 1, axes, 3, 0, lo) != 0 ||
        get_vector(p, item, "hi", 1, axes, 3, 0, hi) != 0)
      rc = -1;
    else
      st = gm_yee_paint_box(s->materials, lo, hi, &m);
  } else if (rc == 0 && strcmp(shape, "sphere") == 0) {
    static const char *const keys[] = {"shape", "epsilon", "mu", "sigma", "poles", "library",
                                       "center", "radius", NULL};
    double c[3], r = 0;
    if (check_keys(p, item, keys) != 0 ||
        get_vector(p, item, "center", 1, axes, 3, 0, c) != 0 ||
        get_number(p, item, "radius", 1, &r) != 0)
      rc = -1;
    else
      st = gm_yee_paint_sphere(s->materials, c, r, &m);
  } else if (rc == 0 && strcmp(shape, "cylinder") == 0) {
    static const char *const keys[] = {"shape", "epsilon", "mu", "sigma", "poles", "library",
                                       "center", "axis", "radius", "height", NULL};
    double c[3], ax[3] = {0, 0, 1}, r = 0, height = INFINITY;
    if (check_keys(p, item, keys) != 0 ||
        get_vector(p, item, "center", 1, axes, 3, 0, c) != 0 ||
        get_vector(p, item, "axis", 0, 3, 3, 0, ax) < 0 ||
        get_number(p, item, "radius", 1, &r) != 0 ||
        get_number(p, item, "height", 0, &height) < 0)
      rc = -1;
    else
      st = gm_yee_paint_cylinder(s->materials, c, ax, r, height, &m);
  } else if (rc == 0) {
    size_t o2 = push_key(p, "shape");
    rc = fail(p, "unknown shape \"%s\" (box, sphere, cylinder)", shape);
    pop(p, o2);
  }
  if (rc == 0 && st != GM_OK) rc = lib_fail(p, gm_yee_materials_errmsg(s->materials));
  return rc;
}

static int parse_materials(parser *p, const cJSON *root, gm_yee_scene *s) {
  gm_error err = {{0}};
  s->unit_um = 1.0;
  if (get_number(p, root, "unit_um", 0, &s->unit_um) < 0) return -1;
  if (!(s->unit_um > 0) || !isfinite(s->unit_um)) {
    size_t o = push_key(p, "unit_um");
    int rc = fail(p, "must be > 0 (micrometres per length unit), got %g", s->unit_um);
    pop(p, o);
    return rc;
  }
  if (gm_yee_materials_create(&s->grid, &s->materials, &err) != GM_OK) return lib_fail(p, err.message);
  const cJSON *bg;
  int rc = get_object(p, root, "background", 0, &bg);
  if (rc < 0) return -1;
  if (rc == 0) {
    size_t old = push_key(p, "background");
    gm_medium m = gm_medium_vacuum();
    static const char *const keys[] = {"epsilon", "mu", "sigma", "poles", "library", NULL};
    rc = check_keys(p, bg, keys) != 0 || parse_medium(p, bg, &m) != 0 ||
                 parse_poles(p, bg, s, &m) != 0
             ? -1
             : 0;
    if (rc == 0 && gm_yee_materials_fill(s->materials, &m) != GM_OK)
      rc = lib_fail(p, gm_yee_materials_errmsg(s->materials));
    pop(p, old);
    if (rc != 0) return -1;
  }
  const cJSON *list;
  rc = get_array(p, root, "materials", &list);
  if (rc < 0) return -1;
  if (rc == 1) return 0;
  return for_each_object(p, list, "materials", parse_material, s);
}

static int parse_pml(parser *p, const cJSON *root, gm_cpml *pml) {
  *pml = gm_cpml_defaults();
  const cJSON *obj;
  int rc = get_object(p, root, "pml", 0, &obj);
  if (rc != 0) return rc < 0 ? -1 : 0;
  size_t old = push_key(p, "pml");
  static const char *const keys[] = {"thickness", "grading", "sigma_max", "sigma_factor",
                                     "kappa_max", "alpha_max", "alpha_grading", NULL};
  rc = check_keys(p, obj, keys);
  if (rc == 0 && get_count(p, obj, "thickness", 0, &pml->thickness) < 0) rc = -1;
  double *v[] = {&pml->grading, &pml->sigma_max, &pml->sigma_factor, &pml->kappa_max,
                 &pml->alpha_max, &pml->alpha_grading};
  for (size_t k = 0; rc == 0 && k < 6; ++k)
    if (get_number(p, obj, keys[k + 1], 0, v[k]) < 0) rc = -1;
  pop(p, old);
  return rc;
}

static int boundary_kind(parser *p, const cJSON *v, gm_yee_boundary_kind *out) {
  if (!cJSON_IsString(v)) return fail(p, "expected a boundary name, got %s", type_name(v));
  if (gm_yee_boundary_kind_find(v->valuestring, out) != GM_OK)
    return fail(p, "unknown boundary \"%s\" (pec, pmc, periodic, cpml)", v->valuestring);
  return 0;
}

static int parse_boundaries(parser *p, const cJSON *root, gm_yee_scene *s) {
  gm_cpml pml;
  if (parse_pml(p, root, &pml) != 0) return -1;
  const cJSON *obj;
  int rc = get_object(p, root, "boundaries", 0, &obj);
  if (rc != 0) return rc < 0 ? -1 : 0;
  size_t old = push_key(p, "boundaries");
  static const char *const keys[] = {"x", "y", "z", NULL};
  rc = check_keys(p, obj, keys);
  size_t axes = gm_yee_dim_axes(s->grid.dim);
  for (size_t a = 0; rc == 0 && a < 3; ++a) {
    const cJSON *v = member(obj, keys[a]);
    if (v == NULL) continue;
    size_t o = push_key(p, keys[a]);
    gm_yee_boundary_kind kind[2];
    if (a >= axes) {
      rc = fail(p, "this grid has no %s axis", keys[a]);
    } else if (cJSON_IsArray(v)) {
      if (cJSON_GetArraySize(v) != 2) rc = fail(p, "expected [low face, high face]");
      for (int f = 0; rc == 0 && f < 2; ++f) {
        size_t o2 = push_index(p, (size_t)f);
        rc = boundary_kind(p, cJSON_GetArrayItem(v, f), &kind[f]);
        pop(p, o2);
      }
    } else {
      rc = boundary_kind(p, v, &kind[0]);
      kind[1] = kind[0];
    }
    for (int f = 0; rc == 0 && f < 2; ++f) {
      s->options.boundary[2 * a + (size_t)f].kind = kind[f];
      s->options.boundary[2 * a + (size_t)f].pml = pml;
    }
    pop(p, o);
  }
  pop(p, old);
  return rc;
}

static int parse_waveform(parser *p, const cJSON *obj, gm_waveform *w) {
  const cJSON *wv;
  if (get_object(p, obj, "waveform", 1, &wv) != 0) return -1;
  size_t old = push_key(p, "waveform");
  static const char *const keys[] = {"kind", "amplitude", "frequency", "width", "delay",
                                     "phase", NULL};
  memset(w, 0, sizeof *w);
  w->amplitude = 1.0;
  const char *kind = NULL;
  int rc = check_keys(p, wv, keys);
  if (rc == 0 && get_string(p, wv, "kind", 1, &kind) != 0) rc = -1;
  if (rc == 0) {
    size_t o = push_key(p, "kind");
    if (gm_waveform_kind_find(kind, &w->kind) != GM_OK || w->kind == GM_WAVE_CUSTOM)
      rc = fail(p, "unknown waveform \"%s\" (gaussian, dgaussian, ricker, cw)", kind);
    pop(p, o);
  }
  double *v[] = {&w->amplitude, &w->frequency, &w->width, &w->delay, &w->phase};
  for (size_t k = 0; rc == 0 && k < 5; ++k)
    if (get_number(p, wv, keys[k + 1], 0, v[k]) < 0) rc = -1;
  gm_error err = {{0}};
  if (rc == 0 && gm_waveform_check(w, &err) != GM_OK) rc = lib_fail(p, err.message);
  pop(p, old);
  return rc;
}

/* A plane wave with angle fields: theta, phi, psi in degrees (gm_oblique_wave), optional
 * match_frequency and interpolation ("cubic", "linear"). */
static int parse_oblique(parser *p, const cJSON *item, size_t axes, gm_oblique_wave *ow) {
  static const char *const keys[] = {"type", "theta", "phi", "psi", "lo", "hi", "waveform",
                                     "match_frequency", "interpolation", NULL};
  double lo[3], hi[3];
  const char *interp = "cubic";
  memset(ow, 0, sizeof *ow);
  ow->theta = 90.0;
  ow->psi = axes == 2 ? 90.0 : 0.0;
  if (check_keys(p, item, keys) != 0 || get_number(p, item, "theta", 0, &ow->theta) < 0 ||
      get_number(p, item, "phi", 1, &ow->phi) != 0 ||
      get_number(p, item, "psi", 0, &ow->psi) < 0 ||
      get_vector(p, item, "lo", 1, axes, 3, 0, lo) != 0 ||
      get_vector(p, item, "hi", 1, axes, 3, 0, hi) != 0 ||
      get_number(p, item, "match_frequency", 0, &ow->match_frequency) < 0 ||
      get_string(p, item, "interpolation", 0, &interp) < 0 ||
      parse_waveform(p, item, &ow->wave) != 0)
    return -1;
  if (strcmp(interp, "cubic") == 0 || strcmp(interp, "linear") == 0) {
    ow->interpolation = interp[0] == 'c' ? GM_INTERP_CUBIC : GM_INTERP_LINEAR;
  } else {
    size_t o = push_key(p, "interpolation");
    int rc = fail(p, "expected \"cubic\" or \"linear\", got \"%s\"", interp);
    pop(p, o);
    return rc;
  }
  for (size_t a = 0; a < 3; ++a) {
    /* lo and hi are vertex indices of the total-field box */
    const char *key = NULL;
    if (lo[a] < 0 || floor(lo[a]) != lo[a]) key = "lo";
    if (hi[a] < 0 || floor(hi[a]) != hi[a]) key = "hi";
    if (key != NULL) {
      size_t o2 = push_key(p, key), o3 = push_index(p, a);
      int rc = fail(p, "expected a vertex index (a non-negative integer)");
      pop(p, o3);
      pop(p, o2);
      return rc;
    }
    ow->lo[a] = (size_t)lo[a];
    ow->hi[a] = (size_t)hi[a];
  }
  return 0;
}

/* One element of "sources": a point source or a plane wave (axis-aligned or oblique). */
static int parse_source(parser *p, const cJSON *item, size_t i, gm_yee_scene *s) {
  const size_t axes = gm_yee_dim_axes(s->grid.dim);
  const char *type = NULL;
  int rc = get_string(p, item, "type", 1, &type) != 0 ? -1 : 0;
  if (rc == 0 && strcmp(type, "point") == 0) {
    static const char *const keys[] = {"type", "component", "position", "mode", "waveform",
                                       NULL};
    gm_point_source *src = &s->points[s->n_points];
    const char *mode = "soft";
    if (check_keys(p, item, keys) != 0 ||
        get_component(p, item, "component", &s->grid, &src->component) != 0 ||
        get_vector(p, item, "position", 1, axes, 3, 0, src->x) != 0 ||
        get_string(p, item, "mode", 0, &mode) < 0 || parse_waveform(p, item, &src->wave) != 0)
      rc = -1;
    if (rc == 0) {
      size_t o2 = push_key(p, "mode");
      if (strcmp(mode, "soft") == 0)
        src->mode = GM_SOURCE_SOFT;
      else if (strcmp(mode, "hard") == 0)
        src->mode = GM_SOURCE_HARD;
      else
        rc = fail(p, "expected \"soft\" or \"hard\", got \"%s\"", mode);
      pop(p, o2);
    }
    if (rc == 0) s->point_json[s->n_points++] = i;
  } else if (rc == 0 && strcmp(type, "plane-wave") == 0 &&
             (member(item, "theta") || member(item, "phi") || member(item, "psi"))) {
    rc = parse_oblique(p, item, axes, &s->obliques[s->n_obliques]);
    if (rc == 0) s->oblique_json[s->n_obliques++] = i;
  } else if (rc == 0 && strcmp(type, "plane-wave") == 0) {
    static const char *const keys[] = {"type", "axis", "direction", "polarization", "lo",
                                       "hi", "waveform", NULL};
    gm_plane_wave *pw = &s->planes[s->n_planes];
    double lo[3], hi[3], dir = 1;
    if (check_keys(p, item, keys) != 0 || get_axis(p, item, "axis", axes, &pw->axis) != 0 ||
        get_number(p, item, "direction", 0, &dir) < 0 ||
        get_component(p, item, "polarization", &s->grid, &pw->polarization) != 0 ||
        get_vector(p, item, "lo", 1, axes, 3, 0, lo) != 0 ||
        get_vector(p, item, "hi", 1, axes, 3, 0, hi) != 0 ||
        parse_waveform(p, item, &pw->wave) != 0)
      rc = -1;
    if (rc == 0 && dir != 1 && dir != -1) {
      size_t o2 = push_key(p, "direction");
      rc = fail(p, "expected 1 or -1, got %g", dir);
      pop(p, o2);
    }
    for (size_t a = 0; rc == 0 && a < 3; ++a) {
      /* lo and hi are vertex indices of the total-field box */
      const char *key = NULL;
      if (lo[a] < 0 || floor(lo[a]) != lo[a]) key = "lo";
      if (hi[a] < 0 || floor(hi[a]) != hi[a]) key = "hi";
      if (key != NULL) {
        size_t o2 = push_key(p, key), o3 = push_index(p, a);
        rc = fail(p, "expected a vertex index (a non-negative integer)");
        pop(p, o3);
        pop(p, o2);
      }
      pw->lo[a] = (size_t)lo[a];
      pw->hi[a] = (size_t)hi[a];
    }
    pw->sign = dir > 0 ? 1 : -1;
    if (rc == 0) s->plane_json[s->n_planes++] = i;
  } else if (rc == 0) {
    size_t o2 = push_key(p, "type");
    rc = fail(p, "unknown source type \"%s\" (point, plane-wave)", type);
    pop(p, o2);
  }
  return rc;
}

static int parse_sources(parser *p, const cJSON *root, gm_yee_scene *s) {
  const cJSON *list;
  int rc = get_array(p, root, "sources", &list);
  if (rc != 0) return rc < 0 ? -1 : 0;
  size_t n = (size_t)cJSON_GetArraySize(list);
  s->points = calloc(n + 1, sizeof *s->points);
  s->planes = calloc(n + 1, sizeof *s->planes);
  s->point_json = calloc(n + 1, sizeof *s->point_json);
  s->plane_json = calloc(n + 1, sizeof *s->plane_json);
  s->obliques = calloc(n + 1, sizeof *s->obliques);
  s->oblique_json = calloc(n + 1, sizeof *s->oblique_json);
  if (s->points == NULL || s->planes == NULL || s->point_json == NULL || s->plane_json == NULL ||
      s->obliques == NULL || s->oblique_json == NULL)
    return fail(p, "out of memory");
  return for_each_object(p, list, "sources", parse_source, s);
}

/* A name that would break the CSV header it becomes: separators, quotes, control bytes. */
static int bad_name(const char *name) {
  for (const unsigned char *c = (const unsigned char *)name; *c != '\0'; ++c)
    if (*c == ',' || *c == '"' || *c < 0x20 || *c == 0x7F) return 1;
  return 0;
}

/* One element of "probes". */
static int parse_probe(parser *p, const cJSON *item, size_t i, gm_yee_scene *s) {
  const size_t axes = gm_yee_dim_axes(s->grid.dim);
  int rc = 0;
  gm_yee_scene_probe *pr = &s->probes[s->n_probes];
  const char *name = NULL;
  static const char *const keys[] = {"name", "component", "position", NULL};
  if (check_keys(p, item, keys) != 0 ||
      get_component(p, item, "component", &s->grid, &pr->component) != 0 ||
      get_vector(p, item, "position", 1, axes, 3, 0, pr->x) != 0 ||
      get_string(p, item, "name", 0, &name) < 0)
    rc = -1;
  if (rc == 0 && name != NULL && bad_name(name)) {
    size_t o2 = push_key(p, "name");
    rc = fail(p, "a probe name (a CSV column) may not hold commas, quotes or control characters");
    pop(p, o2);
  }
  if (rc == 0) {
    if (name != NULL)
      snprintf(pr->name, sizeof pr->name, "%s", name);
    else
      snprintf(pr->name, sizeof pr->name, "%s_%zu", gm_yee_component_name(pr->component), i);
    s->n_probes++;
  }
  return rc;
}

static int parse_probes(parser *p, const cJSON *root, gm_yee_scene *s) {
  const cJSON *list;
  int rc = get_array(p, root, "probes", &list);
  if (rc != 0) return rc < 0 ? -1 : 0;
  s->probes = calloc((size_t)cJSON_GetArraySize(list) + 1, sizeof *s->probes);
  if (s->probes == NULL) return fail(p, "out of memory");
  return for_each_object(p, list, "probes", parse_probe, s);
}

/* One element of "flux": a plane whose Poynting flux is recorded. */
static int parse_flux(parser *p, const cJSON *item, size_t i, gm_yee_scene *s) {
  const size_t axes = gm_yee_dim_axes(s->grid.dim);
  int rc = 0;
  gm_yee_scene_flux *fl = &s->fluxes[s->n_fluxes];
  const char *name = NULL;
  static const char *const keys[] = {"name", "axis", "position", NULL};
  if (check_keys(p, item, keys) != 0 || get_axis(p, item, "axis", axes, &fl->axis) != 0 ||
      get_number(p, item, "position", 1, &fl->position) != 0 ||
      get_string(p, item, "name", 0, &name) < 0)
    rc = -1;
  if (rc == 0 && name != NULL && bad_name(name)) {
    size_t o2 = push_key(p, "name");
    rc = fail(p, "a flux name (a CSV column) may not hold commas, quotes or control characters");
    pop(p, o2);
  }
  if (rc == 0) {
    const gm_yee_grid *g = &s->grid;
    /* the solver's flux planes are the interior vertex planes 1 .. n−1 (fields.h) */
    size_t na = g->n[fl->axis];
    double u = (fl->position - g->origin[fl->axis]) / g->h[fl->axis];
    if (!(u >= 0.5 && u < (double)na - 0.5)) {
      size_t o2 = push_key(p, "position");
      rc = fail(p, "%g is not inside the grid: a flux plane lies in [%g, %g]", fl->position,
                g->origin[fl->axis] + g->h[fl->axis],
                g->origin[fl->axis] + (double)(na - 1) * g->h[fl->axis]);
      pop(p, o2);
    } else {
      fl->index = (size_t)floor(u + 0.5);
      if (name != NULL)
        snprintf(fl->name, sizeof fl->name, "%s", name);
      else
        snprintf(fl->name, sizeof fl->name, "flux_%zu", i);
      s->n_fluxes++;
    }
  }
  return rc;
}

/* "dft": {"f_min", "f_max", "n", "save", "subtract"}: the flux planes' spectra. */
static int parse_dft(parser *p, const cJSON *root, gm_yee_scene *s) {
  const cJSON *obj;
  int rc = get_object(p, root, "dft", 0, &obj);
  if (rc != 0) return rc < 0 ? -1 : 0;
  size_t old = push_key(p, "dft");
  static const char *const keys[] = {"f_min", "f_max", "n", "save", "subtract", NULL};
  const char *save = NULL, *sub = NULL;
  rc = check_keys(p, obj, keys) != 0 || get_number(p, obj, "f_min", 1, &s->dft_fmin) != 0 ||
               get_number(p, obj, "f_max", 1, &s->dft_fmax) != 0 ||
               get_count(p, obj, "n", 1, &s->dft_n) != 0 ||
               get_string(p, obj, "save", 0, &save) < 0 ||
               get_string(p, obj, "subtract", 0, &sub) < 0
           ? -1
           : 0;
  const char *bad = NULL;
  char why[128] = "";
  if (rc == 0 && !(s->dft_fmin >= 0))
    bad = "f_min", snprintf(why, sizeof why, "must be >= 0, got %g", s->dft_fmin);
  else if (rc == 0 && !(s->dft_fmax >= s->dft_fmin && isfinite(s->dft_fmax)))
    bad = "f_max", snprintf(why, sizeof why, "must be >= f_min and finite, got %g", s->dft_fmax);
  else if (rc == 0 && (s->dft_n == 0 || s->dft_n > 100000))
    bad = "n", snprintf(why, sizeof why, "must be in 1 .. 100000 frequencies");
  else if (rc == 0 && s->dft_n > 1 && s->dft_fmax == s->dft_fmin)
    bad = "f_max", snprintf(why, sizeof why, "equals f_min with n > 1 frequencies");
  else if (rc == 0 && s->n_fluxes == 0)
    bad = "n", snprintf(why, sizeof why, "flux spectra need flux planes (\"flux\")");
  if (bad != NULL) {
    size_t o = push_key(p, bad);
    rc = fail(p, "%s", why);
    pop(p, o);
  }
  if (rc == 0 && save != NULL && (s->dft_save = strdup(save)) == NULL) rc = fail(p, "out of memory");
  if (rc == 0 && sub != NULL && (s->dft_subtract = strdup(sub)) == NULL)
    rc = fail(p, "out of memory");
  pop(p, old);
  return rc;
}

static int parse_fluxes(parser *p, const cJSON *root, gm_yee_scene *s) {
  const cJSON *list;
  int rc = get_array(p, root, "flux", &list);
  if (rc != 0) return rc < 0 ? -1 : 0;
  s->fluxes = calloc((size_t)cJSON_GetArraySize(list) + 1, sizeof *s->fluxes);
  if (s->fluxes == NULL) return fail(p, "out of memory");
  return for_each_object(p, list, "flux", parse_flux, s);
}

static int parse_output(parser *p, const cJSON *root, gm_yee_scene *s) {
  s->encoding = GM_VTI_APPENDED;
  s->snapshot_formats = GM_SNAPSHOT_VTI;
  const cJSON *obj;
  int rc = get_object(p, root, "output", 0, &obj);
  if (rc != 0) return rc < 0 ? -1 : 0;
  size_t old = push_key(p, "output");
  static const char *const keys[] = {"snapshot_every", "formats", "encoding", "materials",
                                     "energy_every", "harminv", NULL};
  rc = check_keys(p, obj, keys);
  if (rc == 0 && (get_count(p, obj, "snapshot_every", 0, &s->snapshot_every) < 0 ||
                  get_count(p, obj, "energy_every", 0, &s->energy_every) < 0 ||
                  get_bool(p, obj, "materials", &s->snapshot_materials) < 0))
    rc = -1;
  const cJSON *formats;
  if (rc == 0 && (rc = get_array(p, obj, "formats", &formats)) == 0) {
    s->snapshot_formats = 0;
    size_t o = push_key(p, "formats");
    for (int k = 0; rc == 0 && k < cJSON_GetArraySize(formats); ++k) {
      const cJSON *f = cJSON_GetArrayItem(formats, k);
      size_t o2 = push_index(p, (size_t)k);
      if (cJSON_IsString(f) && strcmp(f->valuestring, "vti") == 0)
        s->snapshot_formats |= GM_SNAPSHOT_VTI;
      else if (cJSON_IsString(f) && strcmp(f->valuestring, "h5") == 0)
        s->snapshot_formats |= GM_SNAPSHOT_HDF5;
      else
        rc = fail(p, "expected \"vti\" or \"h5\"");
      pop(p, o2);
    }
    if (rc == 0 && s->snapshot_formats == 0) rc = fail(p, "expected \"vti\" and/or \"h5\"");
    pop(p, o);
  } else if (rc == 1) {
    rc = 0;
  }
  const char *enc = NULL;
  if (rc == 0 && (rc = get_string(p, obj, "encoding", 0, &enc)) == 0) {
    size_t o = push_key(p, "encoding");
    if (strcmp(enc, "ascii") == 0)
      s->encoding = GM_VTI_ASCII;
    else if (strcmp(enc, "base64") == 0)
      s->encoding = GM_VTI_BASE64;
    else if (strcmp(enc, "appended") == 0)
      s->encoding = GM_VTI_APPENDED;
    else
      rc = fail(p, "expected \"ascii\", \"base64\" or \"appended\", got \"%s\"", enc);
    pop(p, o);
  } else if (rc == 1) {
    rc = 0;
  }
  const cJSON *hv;
  if (rc == 0 && (rc = get_object(p, obj, "harminv", 0, &hv)) == 0) {
    size_t o = push_key(p, "harminv");
    static const char *const hkeys[] = {"f_min", "f_max", "after", "basis", "max_error",
                                        "min_q", "min_amplitude", NULL};
    s->harminv = 1;
    s->harminv_max_error = 1e-4, s->harminv_min_q = 1.0, s->harminv_min_amplitude = 1e-6;
    if (check_keys(p, hv, hkeys) != 0 || get_number(p, hv, "f_min", 1, &s->harminv_fmin) != 0 ||
        get_number(p, hv, "f_max", 1, &s->harminv_fmax) != 0 ||
        get_number(p, hv, "after", 0, &s->harminv_after) < 0 ||
        get_count(p, hv, "basis", 0, &s->harminv_basis) < 0 ||
        get_number(p, hv, "max_error", 0, &s->harminv_max_error) < 0 ||
        get_number(p, hv, "min_q", 0, &s->harminv_min_q) < 0 ||
        get_number(p, hv, "min_amplitude", 0, &s->harminv_min_amplitude) < 0)
      rc = -1;
    if (rc == 0 && !(s->harminv_fmin >= 0 && s->harminv_fmax > s->harminv_fmin))
      rc = fail(p, "expected 0 <= f_min < f_max");
    /* the basis is a dense complex eigenproblem of its size (harminv allocates a few basis²
     * matrices): 1000 is 16 MB each */
    const char *bad = NULL;
    char why[96] = "";
    if (rc == 0 && s->harminv_basis != 0 && (s->harminv_basis < 2 || s->harminv_basis > 1000))
      bad = "basis", snprintf(why, sizeof why, "must be 0 (harminv's default) or 2 .. 1000");
    else if (rc == 0 && !(s->harminv_max_error > 0 && s->harminv_max_error <= 1))
      bad = "max_error", snprintf(why, sizeof why, "must be in (0, 1]");
    else if (rc == 0 && !(s->harminv_min_q >= 0 && isfinite(s->harminv_min_q)))
      bad = "min_q", snprintf(why, sizeof why, "must be >= 0 and finite");
    else if (rc == 0 && !(s->harminv_min_amplitude >= 0 && s->harminv_min_amplitude < 1))
      bad = "min_amplitude", snprintf(why, sizeof why, "must be in [0, 1) (relative to the strongest mode)");
    if (bad != NULL) {
      size_t o2 = push_key(p, bad);
      rc = fail(p, "%s", why);
      pop(p, o2);
    }
    pop(p, o);
  } else if (rc == 1) {
    rc = 0;
  }
  pop(p, old);
  return rc;
}

static int parse_run(parser *p, const cJSON *root, gm_yee_scene *s) {
  const cJSON *obj;
  if (get_object(p, root, "run", 1, &obj) != 0) return -1;
  size_t old = push_key(p, "run");
  static const char *const keys[] = {"steps", "time", "dt", "courant", NULL};
  int rc = check_keys(p, obj, keys);
  int has_steps = rc == 0 ? get_count(p, obj, "steps", 0, &s->steps) : -1;
  int has_time = has_steps >= 0 ? get_number(p, obj, "time", 0, &s->time) : -1;
  if (rc == 0 && (has_steps < 0 || has_time < 0)) rc = -1;
  if (rc == 0 && has_steps == 0 && has_time == 0) rc = fail(p, "give \"steps\" or \"time\", not both");
  if (rc == 0 && has_steps != 0 && has_time != 0) rc = fail(p, "missing \"steps\" (or \"time\")");
  if (rc == 0 && has_steps == 0 && s->steps == 0) {
    size_t o = push_key(p, "steps");
    rc = fail(p, "must be at least 1");
    pop(p, o);
  }
  if (rc == 0 && has_time == 0 && !(s->time > 0)) {
    size_t o = push_key(p, "time");
    rc = fail(p, "must be > 0, got %g", s->time);
    pop(p, o);
  }
  int has_dt = rc == 0 ? get_number(p, obj, "dt", 0, &s->options.dt) : -1;
  int has_c = has_dt >= 0 ? get_number(p, obj, "courant", 0, &s->options.courant) : -1;
  if (rc == 0 && (has_dt < 0 || has_c < 0)) rc = -1;
  if (rc == 0 && has_dt == 0 && has_c == 0) rc = fail(p, "give \"dt\" or \"courant\", not both");
  if (rc == 0 && has_dt == 0 && !(s->options.dt > 0)) {
    size_t o = push_key(p, "dt");
    rc = fail(p, "must be > 0, got %g", s->options.dt);
    pop(p, o);
  }
  if (rc == 0 && has_c == 0 && !(s->options.courant > 0 && s->options.courant <= 1)) {
    size_t o = push_key(p, "courant");
    rc = fail(p, "must be in (0, 1], got %g", s->options.courant);
    pop(p, o);
  }
  pop(p, old);
  return rc;
}

/* Line and column (from 1) of offset `at` in text, for messages about the text itself. */
static void text_position(const char *text, const char *at, size_t *line, size_t *col) {
  *line = 1, *col = 1;
  for (const char *c = text; at != NULL && c < at && *c; ++c) {
    if (*c == '\n')
      ++*line, *col = 1;
    else
      ++*col;
  }
}

static int by_string(const void *a, const void *b) {
  return strcmp((*(const cJSON *const *)a)->string, (*(const cJSON *const *)b)->string);
}

/* A key given twice in one object is an error (cJSON keeps both and the lookup finds the first,
 * so the second was silently ignored). Sorted so that a large object costs n log n. */
static int check_duplicates(parser *p, const cJSON *v) {
  if (!cJSON_IsObject(v) && !cJSON_IsArray(v)) return 0;
  size_t n = (size_t)cJSON_GetArraySize(v), k = 0;
  if (cJSON_IsObject(v) && n > 1) {
    const cJSON **item = malloc(n * sizeof *item);
    if (item == NULL) return fail(p, "out of memory");
    const cJSON *c;
    cJSON_ArrayForEach(c, v) item[k++] = c;
    qsort(item, n, sizeof *item, by_string);
    const char *twice = NULL;
    for (k = 1; k < n && twice == NULL; ++k)
      if (strcmp(item[k - 1]->string, item[k]->string) == 0) twice = item[k]->string;
    free(item);
    if (twice != NULL) {
      size_t o = push_key(p, twice);
      int rc = fail(p, "given twice (a key may appear once in an object)");
      pop(p, o);
      return rc;
    }
  }
  const cJSON *c;
  k = 0;
  cJSON_ArrayForEach(c, v) {
    size_t o = cJSON_IsObject(v) ? push_key(p, c->string) : push_index(p, k);
    int rc = check_duplicates(p, c);
    pop(p, o);
    if (rc != 0) return rc;
    ++k;
  }
  return 0;
}

gm_status gm_yee_scene_parse(const char *text, const char *name, gm_yee_scene *s,
                             gm_error *err) {
  char *msg = err->message;
  size_t cap = sizeof err->message;
  memset(s, 0, sizeof *s);
  s->options = gm_yee_defaults();
  parser p = {{0}, 0, msg, cap, name};
  size_t line, col;
  const char *why = NULL;
  const size_t bad = gm_json_check_text(text, &why);
  if (why != NULL) {
    text_position(text, text + bad, &line, &col);
    snprintf(msg, cap, "%s: line %zu, column %zu: not valid JSON: %s", name, line, col, why);
    return GM_EINVAL;
  }
  const char *end = NULL;
  cJSON *root = cJSON_ParseWithOpts(text, &end, 1);
  if (root == NULL) {
    /* cJSON reports where it stopped: turn that into a line and column */
    text_position(text, end, &line, &col);
    cJSON *first = cJSON_ParseWithOpts(text, NULL, 0);
    snprintf(msg, cap, "%s: line %zu, column %zu: not valid JSON%s", name, line, col,
             first != NULL ? ": text after the end of the scene object (one object per file)"
                           : "");
    cJSON_Delete(first);
    return GM_EINVAL;
  }
  int rc = 0;
  if (!cJSON_IsObject(root)) rc = fail(&p, "expected an object, got %s", type_name(root));
  if (rc == 0) rc = check_duplicates(&p, root);
  static const char *const keys[] = {"grid", "background", "materials", "boundaries", "pml",
                                     "bloch_k", "sources", "probes", "flux", "output", "run",
                                     "description", "eps_averaging", "unit_um", "dft", NULL};
  if (rc == 0) rc = check_keys(&p, root, keys);
  if (rc == 0) rc = parse_grid(&p, root, s);
  if (rc == 0) rc = parse_materials(&p, root, s);
  int averaging = 1; /* subpixel smoothing, on by default (MEEP's eps_averaging) */
  if (rc == 0 && get_bool(&p, root, "eps_averaging", &averaging) < 0) rc = -1;
  s->options.smoothing = averaging ? GM_YEE_SMOOTHING_ANISOTROPIC : GM_YEE_SMOOTHING_NONE;
  if (rc == 0) rc = parse_boundaries(&p, root, s);
  if (rc == 0 && get_vector(&p, root, "bloch_k", 0, 3, 3, 0, s->options.bloch_k) < 0) rc = -1;
  if (rc == 0) rc = parse_sources(&p, root, s);
  if (rc == 0) rc = parse_probes(&p, root, s);
  if (rc == 0) rc = parse_fluxes(&p, root, s);
  if (rc == 0) rc = parse_dft(&p, root, s);
  if (rc == 0) rc = parse_output(&p, root, s);
  if (rc == 0) rc = parse_run(&p, root, s);
  if (rc == 0 && s->harminv && s->n_probes == 0) {
    push_key(&p, "output.harminv");
    rc = fail(&p, "resonances need at least one probe (\"probes\")");
  }
  cJSON_Delete(root);
  if (rc != 0) {
    gm_yee_scene_clear(s);
    return GM_EINVAL;
  }
  return GM_OK;
}

gm_status gm_yee_scene_load(const char *path, gm_yee_scene *s, gm_error *err) {
  char *msg = err->message;
  size_t cap = sizeof err->message;
  memset(s, 0, sizeof *s);
  char why[GM_ERRMSG_SIZE];
  FILE *f = gm_input_open(path, why, sizeof why);
  if (f == NULL) {
    gm_escape_controls(why, msg, cap);
    return GM_EIO;
  }
  size_t len = 0, size = 4096;
  char *text = malloc(size);
  size_t n;
  while (text != NULL && (n = fread(text + len, 1, size - len - 1, f)) > 0) {
    len += n;
    if (size - len < 2) {
      char *bigger = size < ((size_t)64 << 20) ? realloc(text, 2 * size) : NULL;
      if (bigger == NULL) {
        free(text);
        text = NULL;
      } else {
        text = bigger;
        size *= 2;
      }
    }
  }
  fclose(f);
  if (text == NULL) {
    snprintf(msg, cap, "%s: too large or out of memory", path);
    return GM_ENOMEM;
  }
  text[len] = '\0';
  if (len == 0) {
    free(text);
    char raw[GM_ERRMSG_SIZE];
    snprintf(raw, sizeof raw, "%s: the file is empty", path);
    gm_escape_controls(raw, msg, cap);
    return GM_EINVAL;
  }
  gm_status rc = gm_yee_scene_parse(text, path, s, err);
  free(text);
  return rc;
}

void gm_yee_scene_clear(gm_yee_scene *s) {
  gm_yee_materials_free(s->materials);
  free(s->points);
  free(s->planes);
  free(s->point_json);
  free(s->plane_json);
  free(s->obliques);
  free(s->oblique_json);
  free(s->probes);
  free(s->fluxes);
  for (size_t k = 0; s->dft != NULL && k < s->n_fluxes; ++k) gm_yee_dft_flux_free(s->dft[k]);
  free(s->dft);
  free(s->dft_save);
  free(s->dft_subtract);
  memset(s, 0, sizeof *s);
}

/* The longest run a scene may ask for, as `geomint run` (GM_MAX_STEPS elsewhere): past it a
 * step count is not a run but an overflow (time 1e300 or dt 1e-300 gave 0 steps and exit 0). */
#define SCENE_MAX_STEPS 1e15

static double steps_wanted(const gm_yee_scene *s, double dt) {
  if (s->steps > 0) return (double)s->steps;
  return floor(s->time / dt * (1.0 + 1e-12));
}

size_t gm_yee_scene_total_steps(const gm_yee_scene *s, double dt) {
  const double n = steps_wanted(s, dt);
  return n >= 0 && n <= SCENE_MAX_STEPS ? (size_t)n : 0; /* 0: refused by gm_yee_scene_build */
}

/* What a run of the scene records besides the grid: the probe buffers of the solver and the
 * energy and flux series of `maxwell run` (one row of 5 and of n_fluxes + 1 doubles). */
static double recorded_bytes(const gm_yee_scene *s, double steps) {
  const int complex_fields = s->options.bloch_k[0] != 0.0 || s->options.bloch_k[1] != 0.0 ||
                             s->options.bloch_k[2] != 0.0;
  double bytes = (double)s->n_probes * (2.0 + complex_fields) * 8.0 * (steps + 2.0);
  if (s->energy_every > 0) bytes += 5.0 * 8.0 * (steps / (double)s->energy_every + 2.0);
  if (s->n_fluxes > 0) bytes += ((double)s->n_fluxes + 2.0) * 8.0 * (steps + 1.0);
  return bytes;
}

gm_status gm_yee_scene_build(gm_yee_scene *s, const char *name, gm_yee **out,
                             gm_error *error) {
  char *msg = error->message;
  size_t cap = sizeof error->message;
  *out = NULL;
  gm_error err = {{0}};
  gm_yee *solver = NULL;
  if (gm_yee_create(&s->grid, s->materials, &s->options, &solver, &err) != GM_OK) {
    snprintf(msg, cap, "%s: %.400s", name, err.message);
    return GM_EINVAL;
  }
  const double dt = gm_yee_dt(solver), wanted = steps_wanted(s, dt);
  const char *run_key = s->steps > 0 ? "run.steps" : s->options.dt > 0 ? "run.dt" : "run.time";
  if (!(wanted <= SCENE_MAX_STEPS)) {
    snprintf(msg, cap, "%s: %s: time %g at dt = %g is %.3g steps, more than %.0e", name, run_key,
             s->time, dt, wanted, SCENE_MAX_STEPS);
    gm_yee_free(solver);
    return GM_EINVAL;
  }
  const size_t steps = (size_t)wanted;
  /* harminv's band and window against the run: its band must lie below the Nyquist frequency
   * of the probe samples (one per step) and its window must hold samples */
  if (s->harminv) {
    const double nyquist = 0.5 / dt, t_end = (double)steps * dt;
    if (s->harminv_fmax > nyquist) {
      snprintf(msg, cap, "%s: output.harminv.f_max: %g is above the Nyquist frequency "
               "1/(2 dt) = %g of the probe samples", name, s->harminv_fmax, nyquist);
      gm_yee_free(solver);
      return GM_EINVAL;
    }
    if (s->harminv_after >= t_end) {
      snprintf(msg, cap, "%s: output.harminv.after: %g is at or beyond the end of the run "
               "(t = %g, %s)", name, s->harminv_after, t_end, run_key);
      gm_yee_free(solver);
      return GM_EINVAL;
    }
    const double window = floor((t_end - s->harminv_after) / dt) + 1;
    if (s->harminv_basis > 0 && (double)s->harminv_basis > window) {
      snprintf(msg, cap, "%s: output.harminv.basis: %zu basis functions for about %.0f samples "
               "after t = %g; at most one per sample", name, s->harminv_basis, window,
               s->harminv_after);
      gm_yee_free(solver);
      return GM_EINVAL;
    }
  }
  {
    char what[160];
    snprintf(what, sizeof what, "the records of %zu steps (%zu probe%s%s%s)", steps,
             s->n_probes, s->n_probes == 1 ? "" : "s", s->energy_every > 0 ? ", energy" : "",
             s->n_fluxes > 0 ? ", flux" : "");
    if (yee_memory_check(recorded_bytes(s, wanted), what, &err) != GM_OK) {
      snprintf(msg, cap, "%s: %s: %.400s", name, run_key, err.message);
      gm_yee_free(solver);
      return GM_EINVAL;
    }
  }
  for (size_t k = 0; k < s->n_points; ++k)
    if (gm_yee_add_point_source(solver, &s->points[k], NULL) != GM_OK) {
      snprintf(msg, cap, "%s: sources[%zu]: %s", name, s->point_json[k], gm_yee_errmsg(solver));
      gm_yee_free(solver);
      return GM_EINVAL;
    }
  for (size_t k = 0; k < s->n_planes; ++k)
    if (gm_yee_add_plane_wave(solver, &s->planes[k], NULL) != GM_OK) {
      snprintf(msg, cap, "%s: sources[%zu]: %s", name, s->plane_json[k], gm_yee_errmsg(solver));
      gm_yee_free(solver);
      return GM_EINVAL;
    }
  for (size_t k = 0; k < s->n_obliques; ++k)
    if (gm_yee_add_oblique_wave(solver, &s->obliques[k], NULL) != GM_OK) {
      snprintf(msg, cap, "%s: sources[%zu]: %s", name, s->oblique_json[k], gm_yee_errmsg(solver));
      gm_yee_free(solver);
      return GM_EINVAL;
    }
  for (size_t k = 0; k < s->n_probes; ++k)
    if (gm_yee_add_probe(solver, s->probes[k].component, s->probes[k].x, steps + 1, NULL) !=
        GM_OK) {
      snprintf(msg, cap, "%s: probes[%zu]: %s", name, k, gm_yee_errmsg(solver));
      gm_yee_free(solver);
      return GM_EINVAL;
    }
  /* a flux plane inside a CPML layer measures the stretched fields, not the physical flux:
   * refused for spectra ("dft"); the time-domain series of older scenes keep working */
  for (size_t k = 0; s->dft_n > 0 && k < s->n_fluxes; ++k) {
    const int a = s->fluxes[k].axis;
    const long m = (long)s->fluxes[k].index, n = (long)s->grid.n[a];
    for (int f = 0; f < 2; ++f) {
      const gm_yee_boundary *b = &s->options.boundary[2 * a + f];
      if (b->kind == GM_BOUNDARY_CPML &&
          (f == 0 ? m <= (long)b->pml.thickness : m >= n - (long)b->pml.thickness)) {
        snprintf(msg, cap, "%s: flux[%zu].position: %g lies in the %s CPML layer (%zu cells); "
                 "move the plane out of it", name, k, s->fluxes[k].position,
                 f == 0 ? "lower" : "upper", b->pml.thickness);
        gm_yee_free(solver);
        return GM_EINVAL;
      }
    }
  }
  if (s->dft_n > 0) {
    const double nyquist = 0.5 / dt;
    if (!(s->dft_fmax < nyquist)) {
      snprintf(msg, cap, "%s: dft.f_max: %g is at or above the Nyquist frequency 1/(2 dt) = %g",
               name, s->dft_fmax, nyquist);
      gm_yee_free(solver);
      return GM_EINVAL;
    }
    double *freq = malloc(s->dft_n * sizeof *freq);
    s->dft = calloc(s->n_fluxes, sizeof *s->dft);
    if (freq == NULL || s->dft == NULL) {
      free(freq);
      snprintf(msg, cap, "%s: dft: out of memory", name);
      gm_yee_free(solver);
      return GM_ENOMEM;
    }
    for (size_t i = 0; i < s->dft_n; ++i)
      freq[i] = s->dft_n == 1 ? s->dft_fmin
                              : s->dft_fmin + (s->dft_fmax - s->dft_fmin) * (double)i /
                                                  (double)(s->dft_n - 1);
    for (size_t k = 0; k < s->n_fluxes; ++k)
      if (gm_yee_dft_flux_create(solver, s->fluxes[k].axis, s->fluxes[k].index, s->dft_n, freq,
                                 &s->dft[k]) != GM_OK) {
        snprintf(msg, cap, "%s: flux[%zu]: %s", name, k, gm_yee_errmsg(solver));
        free(freq);
        gm_yee_free(solver);
        return GM_EINVAL;
      }
    free(freq);
  }
  *out = solver;
  return GM_OK;
}
