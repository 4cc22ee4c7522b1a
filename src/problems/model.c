/* The problem library: definitions by name, parameters, initial values and building. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "problems/internal.h"

static const gm_model_def *const defs[] = {
    &gm_model_harmonic,
    &gm_model_pendulum,
    &gm_model_kepler,
    &gm_model_henon_heiles,
    &gm_model_lotka_volterra,
    &gm_model_outer_solar_system,
    &gm_model_n_body,
    &gm_model_point_vortices,
    &gm_model_fpu,
    &gm_model_spherical_pendulum,
    &gm_model_double_spherical_pendulum,
    &gm_model_spring_pendulum,
    &gm_model_j2_satellite,
    &gm_model_damped_oscillator,
    &gm_model_toy_resonance,
    &gm_model_stiff_spring_pendulum,
    &gm_model_diatomic_chain,
};
static const size_t n_defs = sizeof defs / sizeof defs[0];

size_t gm_model_count(void) { return n_defs; }

const gm_model_info *gm_model_info_at(size_t index) {
  return index < n_defs ? &defs[index]->info : NULL;
}

static const gm_model_def *find_def(const char *name) {
  if (name == NULL) return NULL;
  for (size_t i = 0; i < n_defs; ++i)
    if (strcmp(defs[i]->info.name, name) == 0) return defs[i];
  return NULL;
}

const gm_model_info *gm_model_info_find(const char *name) {
  const gm_model_def *def = find_def(name);
  return def ? &def->info : NULL;
}

typedef struct {
  char prefix;  /* 'q', 'p' or 'y' */
  size_t index; /* 1-based */
  double value;
} initial_override;

struct gm_model {
  const gm_model_def *def;
  double *params;
  char **texts;  /* owned copies, n_params entries; NULL where unset or a number parameter */
  initial_override *overrides;
  size_t n_overrides;
  int built;
  gm_problem problem;
  void *ctx;
  double t0;
  double *y0;
  char errmsg[GM_ERRMSG_SIZE];
};

gm_status gm_model_create(const char *name, gm_model **out) {
  if (out == NULL) return GM_EINVAL;
  *out = NULL;
  const gm_model_def *def = find_def(name);
  if (def == NULL) return GM_ENOTFOUND;
  gm_model *m = calloc(1, sizeof *m);
  if (m == NULL) return GM_ENOMEM;
  m->def = def;
  m->params = calloc(def->info.n_params ? def->info.n_params : 1, sizeof(double));
  m->texts = calloc(def->info.n_params ? def->info.n_params : 1, sizeof(char *));
  if (m->params == NULL || m->texts == NULL) {
    free(m->params);
    free(m->texts);
    free(m);
    return GM_ENOMEM;
  }
  for (size_t i = 0; i < def->info.n_params; ++i) m->params[i] = def->info.params[i].default_value;
  *out = m;
  return GM_OK;
}

/* Free the problem context and what the definition allocated inside it. */
static void release_ctx(gm_model *m) {
  if (m->ctx != NULL && m->def->release != NULL) m->def->release(m->ctx);
  free(m->ctx);
  m->ctx = NULL;
}

void gm_model_free(gm_model *m) {
  if (m == NULL) return;
  for (size_t i = 0; i < m->def->info.n_params; ++i) free(m->texts[i]);
  free(m->texts);
  free(m->params);
  free(m->overrides);
  release_ctx(m);
  free(m->y0);
  free(m);
}

/* "q12" → ('q', 12); 0 when the name is not an initial value. */
static int parse_initial_name(const char *name, char *prefix, size_t *index) {
  if (name[0] != 'q' && name[0] != 'p' && name[0] != 'y') return 0;
  if (!isdigit((unsigned char)name[1]) || name[1] == '0') return 0;
  char *end = NULL;
  unsigned long v = strtoul(name + 1, &end, 10);
  if (*end != '\0' || v == 0 || v > 1000000000ul) return 0;
  *prefix = name[0];
  *index = (size_t)v;
  return 1;
}

/* "kepler has no parameter 'mass' (parameters: e, q1.., p1..)" */
static gm_status unknown_parameter(gm_model *m, const char *name) {
  const gm_model_info *info = &m->def->info;
  int hamiltonian = gm_problem_kind_has_momenta(info->kind);
  char known[160] = "";
  size_t len = 0;
  for (size_t i = 0; i < info->n_params && len < sizeof known; ++i) {
    int w = snprintf(known + len, sizeof known - len, "%s, ", info->params[i].name);
    if (w > 0) len += (size_t)w;
  }
  return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                 "%s has no parameter '%s' (parameters: %s%s)", info->name, name, known,
                 hamiltonian ? "q1.., p1.." : "y1..");
}

gm_status gm_model_set(gm_model *m, const char *name, double value) {
  if (m == NULL || name == NULL) return GM_EINVAL;
  const gm_model_info *info = &m->def->info;
  if (!isfinite(value))
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "%s: %s = %g is not finite",
                   info->name, name, value);
  for (size_t i = 0; i < info->n_params; ++i)
    if (strcmp(info->params[i].name, name) == 0) {
      if (info->params[i].type == GM_PARAM_TEXT)
        return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                       "%s: %s is a text parameter (%s), not a number", info->name, name,
                       info->params[i].description);
      m->params[i] = value;
      m->built = 0;
      return GM_OK;
    }
  char prefix;
  size_t index;
  int hamiltonian = gm_problem_kind_has_momenta(info->kind);
  if (parse_initial_name(name, &prefix, &index) && (prefix == 'y') != hamiltonian) {
    initial_override *grown = realloc(m->overrides, (m->n_overrides + 1) * sizeof *grown);
    if (grown == NULL) return GM_ENOMEM;
    m->overrides = grown;
    m->overrides[m->n_overrides++] = (initial_override){prefix, index, value};
    m->built = 0;
    return GM_OK;
  }
  return unknown_parameter(m, name);
}

gm_status gm_model_set_text(gm_model *m, const char *name, const char *value) {
  if (m == NULL || name == NULL || value == NULL) return GM_EINVAL;
  const gm_model_info *info = &m->def->info;
  for (size_t i = 0; i < info->n_params; ++i) {
    if (strcmp(info->params[i].name, name) != 0) continue;
    if (info->params[i].type != GM_PARAM_TEXT)
      return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                     "%s: %s is a number (%s), got the text '%s'", info->name, name,
                     info->params[i].description, value);
    char *copy = NULL;
    if (value[0] != '\0') {
      size_t len = strlen(value);
      copy = malloc(len + 1);
      if (copy == NULL) return GM_ENOMEM;
      memcpy(copy, value, len + 1);
    }
    free(m->texts[i]);
    m->texts[i] = copy;
    m->built = 0;
    return GM_OK;
  }
  return unknown_parameter(m, name);
}

gm_status gm_model_build(gm_model *m) {
  if (m == NULL) return GM_EINVAL;
  const gm_model_def *def = m->def;
  m->built = 0;
  release_ctx(m);
  free(m->y0);
  m->y0 = NULL;
  m->ctx = calloc(1, def->ctx_size ? def->ctx_size : 1);
  if (m->ctx == NULL) return gm_fail(m->errmsg, sizeof m->errmsg, GM_ENOMEM, "out of memory");
  size_t dim = def->info.default_dim;
  gm_status st = GM_OK;
  if (def->prepare != NULL)
    st = def->prepare(m->ctx, m->params, (const char *const *)m->texts, &dim, m->errmsg,
                      sizeof m->errmsg);
  if (st != GM_OK) return st;
  memset(&m->problem, 0, sizeof m->problem);
  m->problem.kind = def->info.kind;
  m->problem.dim = dim;
  m->problem.ctx = m->ctx;
  const size_t n = gm_problem_state_size(&m->problem);
  m->y0 = calloc(n, sizeof(double));
  if (m->y0 == NULL)
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_ENOMEM, "out of memory");
  m->t0 = 0.0;
  st = def->setup(m->ctx, m->params, &m->problem, &m->t0, m->y0, m->errmsg, sizeof m->errmsg);
  if (st != GM_OK) return st;
  for (size_t k = 0; k < m->n_overrides; ++k) {
    const initial_override *o = &m->overrides[k];
    size_t limit = o->prefix == 'y' ? n : dim;
    if (o->index > limit)
      return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                     "%s has %zu %s, so %c%zu does not exist", def->info.name, limit,
                     o->prefix == 'y' ? "state components" : "degrees of freedom", o->prefix,
                     o->index);
    size_t offset = o->prefix == 'p' ? dim : 0;
    m->y0[offset + o->index - 1] = o->value;
  }
  if (m->n_overrides > 0) {
    if (def->initial_changed == NULL || !def->initial_changed(m->ctx, m->y0))
      m->problem.exact = NULL;
  }
  /* An initial state where the energy or an invariant is not finite (a collision, a log of a
   * non-positive population) is no state the problem can start from. */
  if (gm_problem_has_energy(&m->problem) && !isfinite(gm_problem_energy(&m->problem, m->y0)))
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                   "%s: the energy of the initial state is %g (a singular point)", def->info.name,
                   gm_problem_energy(&m->problem, m->y0));
  for (size_t k = 0; k < m->problem.n_invariants; ++k) {
    double v = m->problem.invariants[k].value(m->ctx, m->y0);
    if (!isfinite(v))
      return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                     "%s: the invariant %s of the initial state is %g (a singular point)",
                     def->info.name, m->problem.invariants[k].name, v);
  }
  m->built = 1;
  return GM_OK;
}

const gm_problem *gm_model_problem(const gm_model *m) {
  return (m != NULL && m->built) ? &m->problem : NULL;
}

size_t gm_model_state_size(const gm_model *m) {
  return (m != NULL && m->built) ? gm_problem_state_size(&m->problem) : 0;
}

void gm_model_initial_state(const gm_model *m, double *t0, double *y0) {
  if (m == NULL || !m->built) return;
  if (t0 != NULL) *t0 = m->t0;
  if (y0 != NULL) memcpy(y0, m->y0, gm_problem_state_size(&m->problem) * sizeof *y0);
}

const gm_model_info *gm_model_info_of(const gm_model *m) { return m ? &m->def->info : NULL; }

double gm_model_param(const gm_model *m, const char *name) {
  if (m == NULL || name == NULL) return NAN;
  for (size_t i = 0; i < m->def->info.n_params; ++i)
    if (strcmp(m->def->info.params[i].name, name) == 0)
      return m->def->info.params[i].type == GM_PARAM_TEXT ? NAN : m->params[i];
  return NAN;
}

const char *gm_model_errmsg(const gm_model *m) { return m ? m->errmsg : ""; }
