/* The problem library: definitions by name, parameters, initial values and building. */
#include <ctype.h>
#include <fenv.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/variational.h"
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
    &gm_model_free_rigid_body,
    &gm_model_heavy_top,
    &gm_model_pendulum_3d,
    &gm_model_satellite,
    &gm_model_central_body,
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

/* A constrained Lagrangian problem starts on its constraint manifold: g(q0) = 0 and v0 tangent,
 * (∂g/∂q) v0 = 0 (v0 from the Legendre transform of p0). Each row i is held to a relative
 * tolerance, |g_i| <= tol |∂g_i/∂q| |q| and |(∂g_i/∂q) v| <= tol |∂g_i/∂q| |v|, so positions typed
 * to 10 digits pass and a state the integrator would have to project (q1=5 on a unit sphere) is
 * an error rather than a silent jump in energy. */
#define CONSTRAINT_START_TOL 1e-9

static double norm2(const double *x, size_t n) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += x[i] * x[i];
  return sqrt(s);
}

static gm_status check_on_manifold(gm_model *m) {
  const gm_problem *pb = &m->problem;
  if (pb->kind != GM_PROBLEM_LAGRANGIAN || pb->n_constraints == 0) return GM_OK;
  const size_t d = pb->dim, nc = pb->n_constraints;
  const char *name = m->def->info.name;
  const double *q = m->y0, *p = m->y0 + d;
  double *buf = malloc((nc + nc * d + d) * sizeof *buf);
  if (buf == NULL) return gm_fail(m->errmsg, sizeof m->errmsg, GM_ENOMEM, "out of memory");
  double *g = buf, *jac = g + nc, *v = jac + nc * d;
  gm_status st = GM_OK;
  if (pb->constraint(pb->ctx, q, g) != 0 || pb->constraint_jacobian(pb->ctx, q, jac) != 0) {
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                 "%s: the constraint cannot be evaluated at the initial positions", name);
  } else if (gm_lagrangian_velocity(pb, q, p, v) != GM_OK) {
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                 "%s: no velocity has the initial momenta (the Legendre transform failed)", name);
  }
  const double nq = norm2(q, d), nv = st == GM_OK ? norm2(v, d) : 0.0;
  for (size_t i = 0; i < nc && st == GM_OK; ++i) {
    const double *row = jac + i * d, nrow = norm2(row, d);
    double gv = 0.0;
    for (size_t j = 0; j < d; ++j) gv += row[j] * v[j];
    if (!(fabs(g[i]) <= CONSTRAINT_START_TOL * nrow * nq))
      st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                   "%s: the initial positions are off the constraint manifold: constraint %zu is "
                   "g = %.3g, not 0 (relative tolerance %g); set positions on it or leave q at its "
                   "default",
                   name, i + 1, g[i], CONSTRAINT_START_TOL);
    else if (!(fabs(gv) <= CONSTRAINT_START_TOL * nrow * nv))
      st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                   "%s: the initial velocity is not tangent to the constraint manifold: "
                   "(dg%zu/dq)·v = %.3g, not 0 (relative tolerance %g); set momenta tangent to it "
                   "or leave p at its default",
                   name, i + 1, gv, CONSTRAINT_START_TOL);
  }
  free(buf);
  return st;
}

/* The parameter or initial value farthest from 1 in magnitude (|log10 |x||, zero excluded), as
 * "name = value" in buf; 0 when every value is 0. */
static int most_extreme(const gm_model *m, char *buf, size_t cap) {
  const gm_model_info *info = &m->def->info;
  double worst = -1.0;
  for (size_t i = 0; i < info->n_params; ++i) {
    double x = m->params[i];
    if (info->params[i].type != GM_PARAM_NUMBER || x == 0.0) continue;
    double e = fabs(log10(fabs(x)));
    if (e > worst) worst = e, snprintf(buf, cap, "%s = %g", info->params[i].name, x);
  }
  const size_t n = gm_problem_state_size(&m->problem), d = m->problem.dim;
  const int qp = gm_problem_has_momenta(&m->problem);
  for (size_t i = 0; i < n; ++i) {
    double x = m->y0[i];
    if (x == 0.0) continue;
    double e = fabs(log10(fabs(x)));
    if (e > worst) {
      worst = e;
      if (qp) snprintf(buf, cap, "%c%zu = %g", i < d ? 'q' : 'p', (i < d ? i : i - d) + 1, x);
      else snprintf(buf, cap, "y%zu = %g", i + 1, x);
    }
  }
  return worst >= 0.0;
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
  /* A state off its manifold (a non-orthogonal R typed by hand) is no state to start from. */
  double defect = gm_problem_state_defect(&m->problem, m->y0);
  if (!(defect <= GM_STATE_DEFECT_TOLERANCE))
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                   "%s: the initial state is not on its manifold: %s = %.3g (tolerance %g)",
                   def->info.name, gm_problem_state_defect_name(&m->problem), defect,
                   GM_STATE_DEFECT_TOLERANCE);
  st = check_on_manifold(m);
  if (st != GM_OK) return st;
  /* An initial state where the energy or an invariant is not finite (a collision, a log of a
   * non-positive population) is no state the problem can start from; when the floating-point
   * flags say the arithmetic overflowed or underflowed, the message says so and names the most
   * extreme value instead of blaming a singular point. */
  fexcept_t saved;
  fegetexceptflag(&saved, FE_ALL_EXCEPT);
  feclearexcept(FE_OVERFLOW | FE_UNDERFLOW);
  const char *what = NULL;
  double bad = 0.0;
  if (gm_problem_has_energy(&m->problem)) {
    bad = gm_problem_energy(&m->problem, m->y0);
    if (!isfinite(bad)) what = "energy";
  }
  for (size_t k = 0; what == NULL && k < m->problem.n_invariants; ++k) {
    bad = m->problem.invariants[k].value(m->ctx, m->y0);
    if (!isfinite(bad)) what = m->problem.invariants[k].name;
  }
  const int range = fetestexcept(FE_OVERFLOW | FE_UNDERFLOW) != 0;
  fesetexceptflag(&saved, FE_ALL_EXCEPT);
  if (what != NULL) {
    char extreme[96];
    if (range && most_extreme(m, extreme, sizeof extreme))
      return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                     "%s: the %s of the initial state is not finite (%g): double precision "
                     "overflows with these values (the most extreme: %s); use values nearer the "
                     "problem's scale",
                     def->info.name, what, bad, extreme);
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                   "%s: the %s of the initial state is %g (a singular point)", def->info.name,
                   what, bad);
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
