/* Fluid case files (JSON, read with cJSON): the mesh (a Gmsh file with physical line groups, or
 * a generated rectangle), one condition per boundary group, ν, κ, ρ, dt, t_end, the initial
 * state by preset name and the outputs. Errors name the file and the JSON path. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "fluids/internal.h"

void gm_fluid_case_free(gm_fluid_case *c) {
  if (!c) return;
  gm_mesh_free(c->mesh);
  gm_fluid_groups_free(c->groups);
  free(c->bcs);
  free(c->bc_names);
  free(c->partner_names);
  free(c);
}

typedef struct parser {
  const char *file;
  char msg[GM_ERRMSG_SIZE];
} parser;

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static gm_status
bad(parser *p, const char *json_path, const char *fmt, ...) {
  char what[GM_ERRMSG_SIZE];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  snprintf(p->msg, sizeof p->msg, "%.80s: %.60s: %.100s", p->file, json_path, what);
  return GM_EINVAL;
}

/* An optional number: absent -> *v unchanged. */
static gm_status get_number(parser *p, const cJSON *obj, const char *key, const char *json_path,
                            double *v) {
  const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!it) return GM_OK;
  if (!cJSON_IsNumber(it)) return bad(p, json_path, "expected a number");
  if (!isfinite(it->valuedouble)) return bad(p, json_path, "not a finite number");
  *v = it->valuedouble;
  return GM_OK;
}

static gm_status get_pair(parser *p, const cJSON *obj, const char *key, const char *json_path,
                          double v[2]) {
  const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!it) return GM_OK;
  if (!cJSON_IsArray(it) || cJSON_GetArraySize(it) != 2)
    return bad(p, json_path, "expected [a, b]");
  for (int k = 0; k < 2; ++k) {
    const cJSON *e = cJSON_GetArrayItem(it, k);
    if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble))
      return bad(p, json_path, "entry %d is not a finite number", k);
    v[k] = e->valuedouble;
  }
  return GM_OK;
}

static const char *known_keys[] = {
    "mesh",    "boundaries", "nu",           "kappa",          "rho",     "dt", "t_end", "scheme",
    "initial", "amplitude",  "output_every", "velocity_scale", "comment", "stress_free_walls",
    "rotation", NULL};

static gm_status parse_mesh(parser *p, const cJSON *m, const char *base_dir, gm_fluid_case *c,
                            gm_error *err) {
  gm_status st;
  if (cJSON_IsString(m)) {
    char path[4096];
    const char *name = m->valuestring;
    if (name[0] == '/' || !base_dir)
      snprintf(path, sizeof path, "%s", name);
    else
      snprintf(path, sizeof path, "%s/%s", base_dir, name);
    st = gm_mesh_read(path, &c->mesh, err);
    if (st) return st;
    st = gm_fluid_groups_read_msh(path, c->mesh, &c->groups, err);
    return st;
  }
  const cJSON *ps = cJSON_GetObjectItemCaseSensitive(m, "periodic_square");
  const cJSON *ico = cJSON_GetObjectItemCaseSensitive(m, "icosphere");
  const cJSON *tor = cJSON_GetObjectItemCaseSensitive(m, "torus");
  if (cJSON_IsObject(ps)) { /* gm_fluid_periodic_square_mesh */
    double L = 2.0 * GM_PI, n = 32;
    if ((st = get_number(p, ps, "length", "$.mesh.periodic_square.length", &L)) ||
        (st = get_number(p, ps, "cells", "$.mesh.periodic_square.cells", &n)))
      return st;
    if (!(L > 0) || !(n >= 3 && n <= 1e4 && n == floor(n)))
      return bad(p, "$.mesh.periodic_square", "length > 0 and cells an integer in [3, 10000]");
    return gm_fluid_periodic_square_mesh(L, (size_t)n, &c->mesh, &c->groups, err);
  }
  if (cJSON_IsObject(ico) || cJSON_IsObject(tor)) { /* closed surfaces: no boundary groups */
    c->groups = calloc(1, sizeof *c->groups);
    if (!c->groups) return GM_ENOMEM;
    if (cJSON_IsObject(ico)) {
      double r = 1, s = 4;
      if ((st = get_number(p, ico, "radius", "$.mesh.icosphere.radius", &r)) ||
          (st = get_number(p, ico, "subdivisions", "$.mesh.icosphere.subdivisions", &s)))
        return st;
      if (!(r > 0) || !(s >= 0 && s <= 8 && s == floor(s)))
        return bad(p, "$.mesh.icosphere", "radius > 0 and subdivisions an integer in [0, 8]");
      return gm_mesh_icosphere(r, (size_t)s, &c->mesh, err);
    }
    double R = 2, r = 0.8, n[2] = {40, 16};
    if ((st = get_number(p, tor, "R", "$.mesh.torus.R", &R)) ||
        (st = get_number(p, tor, "r", "$.mesh.torus.r", &r)) ||
        (st = get_pair(p, tor, "cells", "$.mesh.torus.cells", n)))
      return st;
    if (!(R > r && r > 0) || !(n[0] >= 4 && n[0] <= 1e4 && n[1] >= 3 && n[1] <= 1e4) ||
        n[0] != floor(n[0]) || n[1] != floor(n[1]))
      return bad(p, "$.mesh.torus", "R > r > 0 and cells two integers (major even >= 4)");
    return gm_mesh_torus(R, r, (size_t)n[0], (size_t)n[1], &c->mesh, err);
  }
  const cJSON *r = cJSON_GetObjectItemCaseSensitive(m, "rectangle");
  if (!cJSON_IsObject(m) || !r || !cJSON_IsObject(r))
    return bad(p, "$.mesh",
               "expected a mesh file name or {\"rectangle\" | \"periodic_square\" | "
               "\"icosphere\" | \"torus\": {...}}");
  double x[2] = {0, 1}, y[2] = {0, 1}, n[2] = {16, 0};
  if ((st = get_pair(p, r, "x", "$.mesh.rectangle.x", x)) ||
      (st = get_pair(p, r, "y", "$.mesh.rectangle.y", y)) ||
      (st = get_pair(p, r, "cells", "$.mesh.rectangle.cells", n)))
    return st;
  if (!(x[1] > x[0]) || !(y[1] > y[0])) return bad(p, "$.mesh.rectangle", "empty rectangle");
  if (n[1] == 0) n[1] = floor(n[0] * (y[1] - y[0]) / (x[1] - x[0]) * 2.0 / sqrt(3.0) + 0.5);
  if (!(n[0] >= 2 && n[0] <= 1e4 && n[1] >= 2 && n[1] <= 1e4) || n[0] != floor(n[0]) ||
      n[1] != floor(n[1]))
    return bad(p, "$.mesh.rectangle.cells", "expected two integers in [2, 10000], got %g %g", n[0],
               n[1]);
  st = gm_mesh_rectangle(x[0], x[1], y[0], y[1], (size_t)n[0], (size_t)n[1], GM_DIAGONAL_ACUTE,
                         &c->mesh, err);
  if (st) return st;
  return gm_fluid_groups_rectangle(c->mesh, &c->groups, err);
}

static gm_status parse_boundaries(parser *p, const cJSON *b, gm_fluid_case *c) {
  if (!cJSON_IsObject(b)) return bad(p, "$.boundaries", "expected an object: group -> condition");
  size_t n = (size_t)cJSON_GetArraySize(b);
  c->bcs = calloc(n ? n : 1, sizeof *c->bcs);
  c->bc_names = calloc(n ? n : 1, sizeof *c->bc_names);
  c->partner_names = calloc(n ? n : 1, sizeof *c->partner_names);
  if (!c->bcs || !c->bc_names || !c->partner_names) return GM_ENOMEM;
  const cJSON *g;
  size_t i = 0;
  cJSON_ArrayForEach(g, b) {
    char jp[128];
    snprintf(jp, sizeof jp, "$.boundaries.%.40s", g->string);
    if (strlen(g->string) >= GM_FLUID_NAME_SIZE) return bad(p, jp, "group name too long");
    memcpy(c->bc_names[i], g->string, strlen(g->string) + 1);
    gm_fluid_bc *bc = &c->bcs[i];
    bc->group = c->bc_names[i];
    if (!cJSON_IsObject(g)) return bad(p, jp, "expected an object");
    const cJSON *type = cJSON_GetObjectItemCaseSensitive(g, "type");
    const char *t = cJSON_IsString(type) ? type->valuestring : "";
    if (strcmp(t, "wall") == 0)
      bc->kind = GM_FLUID_WALL;
    else if (strcmp(t, "inflow") == 0)
      bc->kind = GM_FLUID_INFLOW;
    else if (strcmp(t, "outflow") == 0)
      bc->kind = GM_FLUID_OUTFLOW;
    else if (strcmp(t, "periodic") == 0) {
      bc->kind = GM_FLUID_PERIODIC;
      const cJSON *pn = cJSON_GetObjectItemCaseSensitive(g, "partner");
      char jt[160];
      snprintf(jt, sizeof jt, "%s.partner", jp);
      if (!cJSON_IsString(pn) || strlen(pn->valuestring) >= GM_FLUID_NAME_SIZE)
        return bad(p, jt, "expected the name of the group identified with this one");
      memcpy(c->partner_names[i], pn->valuestring, strlen(pn->valuestring) + 1);
      bc->partner = c->partner_names[i];
    } else {
      char jt[160];
      snprintf(jt, sizeof jt, "%s.type", jp);
      return bad(p, jt, "expected \"wall\", \"inflow\", \"outflow\" or \"periodic\"");
    }
    char jk[160];
    gm_status st;
    snprintf(jk, sizeof jk, "%s.velocity", jp);
    if ((st = get_pair(p, g, "velocity", jk, bc->velocity))) return st;
    snprintf(jk, sizeof jk, "%s.speed", jp);
    if ((st = get_number(p, g, "speed", jk, &bc->speed))) return st;
    const cJSON *s = cJSON_GetObjectItemCaseSensitive(g, "scalar");
    snprintf(jk, sizeof jk, "%s.scalar", jp);
    if (s && cJSON_IsString(s) && strcmp(s->valuestring, "zero_flux") == 0) {
      bc->scalar = GM_SCALAR_ZERO_FLUX;
    } else if (s) {
      if (!cJSON_IsNumber(s) || !isfinite(s->valuedouble))
        return bad(p, jk, "expected a number (Dirichlet value) or \"zero_flux\"");
      bc->scalar = GM_SCALAR_DIRICHLET;
      bc->scalar_value = s->valuedouble;
    }
    ++i;
  }
  c->n_bcs = i;
  return GM_OK;
}

static gm_status case_parse(const char *text, const char *base_dir, const char *file,
                            gm_fluid_case **out, gm_error *err) {
  if (!text || !out) return gm_error_set(err, GM_EINVAL, "fluid case: NULL argument");
  *out = NULL;
  parser p = {file, ""};
  const char *end = NULL;
  cJSON *root = cJSON_ParseWithOpts(text, &end, 0);
  if (!root) {
    size_t line = 1;
    for (const char *q = text; end && q < end && *q; ++q) line += *q == '\n';
    return gm_error_set(err, GM_EINVAL, "%.200s: not valid JSON (line %zu)", file, line);
  }
  gm_fluid_case *c = calloc(1, sizeof *c);
  gm_status st = GM_OK;
  if (!c) {
    cJSON_Delete(root);
    return gm_error_set(err, GM_ENOMEM, "fluid case: out of memory");
  }
  c->options = gm_fluid_defaults();
  c->rho = 1.0;
  c->t_end = 1.0;
  c->initial_amplitude = 0.1;
  if (!cJSON_IsObject(root)) {
    st = bad(&p, "$", "expected an object");
    goto done;
  }
  for (const cJSON *it = root->child; it; it = it->next) {
    size_t k = 0;
    while (known_keys[k] && strcmp(known_keys[k], it->string) != 0) ++k;
    if (!known_keys[k]) {
      char jp[96];
      snprintf(jp, sizeof jp, "$.%.60s", it->string);
      st = bad(&p, jp, "unknown key");
      goto done;
    }
  }
  const cJSON *m = cJSON_GetObjectItemCaseSensitive(root, "mesh");
  if (!m) {
    st = bad(&p, "$.mesh", "missing");
    goto done;
  }
  gm_error sub = {{0}};
  st = parse_mesh(&p, m, base_dir, c, &sub);
  if (st) {
    if (!p.msg[0]) snprintf(p.msg, sizeof p.msg, "%.60s: $.mesh: %.180s", file, sub.message);
    goto done;
  }
  const cJSON *b = cJSON_GetObjectItemCaseSensitive(root, "boundaries");
  if (!b && c->mesh->N == 2) {
    st = bad(&p, "$.boundaries", "missing");
    goto done;
  }
  if (b && (st = parse_boundaries(&p, b, c))) goto done;
  double every = 0;
  if ((st = get_number(&p, root, "nu", "$.nu", &c->options.nu)) ||
      (st = get_number(&p, root, "kappa", "$.kappa", &c->options.kappa)) ||
      (st = get_number(&p, root, "rho", "$.rho", &c->rho)) ||
      (st = get_number(&p, root, "dt", "$.dt", &c->options.dt)) ||
      (st = get_number(&p, root, "t_end", "$.t_end", &c->t_end)) ||
      (st = get_number(&p, root, "velocity_scale", "$.velocity_scale",
                       &c->options.velocity_scale)) ||
      (st = get_number(&p, root, "amplitude", "$.amplitude", &c->initial_amplitude)) ||
      (st = get_number(&p, root, "rotation", "$.rotation", &c->options.rotation)) ||
      (st = get_number(&p, root, "output_every", "$.output_every", &every)))
    goto done;
  if (c->options.nu < 0) {
    st = bad(&p, "$.nu", "viscosity %g < 0", c->options.nu);
    goto done;
  }
  if (c->options.kappa < 0) {
    st = bad(&p, "$.kappa", "diffusivity %g < 0", c->options.kappa);
    goto done;
  }
  if (!(c->rho > 0)) {
    st = bad(&p, "$.rho", "density %g <= 0", c->rho);
    goto done;
  }
  if (!(c->options.dt > 0)) {
    st = bad(&p, "$.dt", "time step %g <= 0", c->options.dt);
    goto done;
  }
  if (!(c->t_end >= 0) || c->t_end / c->options.dt > 1e12) {
    st = bad(&p, "$.t_end", "t_end = %g must be >= 0 and at most 1e12 steps", c->t_end);
    goto done;
  }
  if (!(every >= 0 && every <= 1e12 && every == floor(every))) {
    st = bad(&p, "$.output_every", "expected a count >= 0");
    goto done;
  }
  c->output_every = (size_t)every;
  const cJSON *s = cJSON_GetObjectItemCaseSensitive(root, "scheme");
  if (s) {
    if (cJSON_IsString(s) && strcmp(s->valuestring, "seed") == 0)
      c->options.scheme = GM_FLUID_SEED;
    else if (cJSON_IsString(s) && strcmp(s->valuestring, "midpoint") == 0)
      c->options.scheme = GM_FLUID_MIDPOINT;
    else {
      st = bad(&p, "$.scheme", "expected \"seed\" or \"midpoint\"");
      goto done;
    }
  }
  const cJSON *sf = cJSON_GetObjectItemCaseSensitive(root, "stress_free_walls");
  if (sf) {
    if (!cJSON_IsBool(sf)) {
      st = bad(&p, "$.stress_free_walls", "expected true or false");
      goto done;
    }
    c->options.stress_free_walls = cJSON_IsTrue(sf) ? 1 : 0;
  }
  const cJSON *in = cJSON_GetObjectItemCaseSensitive(root, "initial");
  if (in) {
    if (cJSON_IsString(in) && strcmp(in->valuestring, "rest") == 0)
      c->initial = GM_FLUID_INIT_REST;
    else if (cJSON_IsString(in) && strcmp(in->valuestring, "shear_modes") == 0)
      c->initial = GM_FLUID_INIT_SHEAR_MODES;
    else if (cJSON_IsString(in) && strcmp(in->valuestring, "taylor_green") == 0)
      c->initial = GM_FLUID_INIT_TAYLOR_GREEN;
    else if (cJSON_IsString(in) && strcmp(in->valuestring, "double_shear_layer") == 0)
      c->initial = GM_FLUID_INIT_DOUBLE_SHEAR;
    else if (cJSON_IsString(in) && strcmp(in->valuestring, "rossby_haurwitz") == 0)
      c->initial = GM_FLUID_INIT_ROSSBY_HAURWITZ;
    else {
      st = bad(&p, "$.initial",
               "expected \"rest\", \"shear_modes\", \"taylor_green\", \"double_shear_layer\" "
               "or \"rossby_haurwitz\"");
      goto done;
    }
    int surface = c->mesh->N == 3, needs_surface = c->initial == GM_FLUID_INIT_ROSSBY_HAURWITZ;
    if (c->initial != GM_FLUID_INIT_REST && surface != needs_surface) {
      st = bad(&p, "$.initial", "\"%s\" is for %s", in->valuestring,
               needs_surface ? "surfaces in R^3" : "flat meshes");
      goto done;
    }
  }
done:
  cJSON_Delete(root);
  if (st) {
    gm_error_set(err, st, "%s", p.msg[0] ? p.msg : "fluid case: out of memory");
    gm_fluid_case_free(c);
    return st;
  }
  *out = c;
  return GM_OK;
}

gm_status gm_fluid_case_parse(const char *text, const char *base_dir, gm_fluid_case **out,
                              gm_error *err) {
  return case_parse(text, base_dir, "case", out, err);
}

gm_status gm_fluid_case_read(const char *path, gm_fluid_case **out, gm_error *err) {
  if (!path || !out) return gm_error_set(err, GM_EINVAL, "fluid case: NULL argument");
  *out = NULL;
  char why[GM_ERRMSG_SIZE];
  FILE *f = gm_input_open(path, why, sizeof why); /* a directory or a FIFO says what it is */
  if (!f) return gm_error_set(err, GM_EIO, "%s", why);
  const size_t cap = (size_t)1 << 24; /* 16 MiB: a case file is a few lines */
  char *text = malloc(cap + 1);
  if (!text) {
    fclose(f);
    return gm_error_set(err, GM_ENOMEM, "fluid case: out of memory");
  }
  size_t n = fread(text, 1, cap + 1, f);
  fclose(f);
  if (n > cap) {
    free(text);
    return gm_error_set(err, GM_EIO, "%s: larger than 16 MiB", path);
  }
  text[n] = 0;
  char dir[4096];
  snprintf(dir, sizeof dir, "%s", path);
  char *slash = strrchr(dir, '/');
  if (slash)
    *slash = 0;
  else
    snprintf(dir, sizeof dir, ".");
  gm_status st = case_parse(text, dir, path, out, err);
  free(text);
  return st;
}

gm_status gm_fluid_case_solver(const gm_fluid_case *c, gm_fluid **out, gm_error *err) {
  if (!c || !out) return gm_error_set(err, GM_EINVAL, "fluid case: NULL argument");
  gm_status st = gm_fluid_create(c->mesh, c->groups, c->n_bcs, c->bcs, &c->options, out, err);
  if (st || c->initial == GM_FLUID_INIT_REST) return st;
  gm_fluid *f = *out;
  const size_t nv = gm_fluid_n_vertices(f), sd = gm_fluid_space_dim(f);
  const double *x = gm_fluid_coordinates(f);
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  const double *xm = gm_complex_coordinates(gm_fluid_complex(f)); /* the box of the whole mesh */
  for (size_t v = 0; v < gm_complex_count(gm_fluid_complex(f), 0); ++v)
    for (int k = 0; k < 2; ++k) {
      lo[k] = fmin(lo[k], xm[sd * v + (size_t)k]);
      hi[k] = fmax(hi[k], xm[sd * v + (size_t)k]);
    }
  for (int k = 0; k < 2; ++k) /* a periodic box is one period long (its seams may zigzag) */
    if (f->period[k] > 0) hi[k] = lo[k] + f->period[k];
  double *psi = malloc(2 * nv * sizeof *psi);
  if (!psi) {
    gm_fluid_free(f);
    *out = NULL;
    return gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  double *theta = psi + nv, A = c->initial_amplitude;
  for (size_t v = 0; v < nv; ++v) {
    const double *p = x + sd * v;
    if (sd == 3) { /* directions on the unit sphere; θ: a blob at latitude 30°, longitude 0 */
      double r = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), u[3] = {p[0] / r, p[1] / r, p[2] / r};
      psi[v] = r * r * gm_fluid_rossby_haurwitz_psi(u);
      double d2 = (u[0] - sqrt(0.75)) * (u[0] - sqrt(0.75)) + u[1] * u[1] + (u[2] - 0.5) * (u[2] - 0.5);
      theta[v] = exp(-20.0 * d2);
      continue;
    }
    double X = (p[0] - lo[0]) / (hi[0] - lo[0]), Y = (p[1] - lo[1]) / (hi[1] - lo[1]);
    theta[v] = exp(-20.0 * ((X - 0.3) * (X - 0.3) + (Y - 0.6) * (Y - 0.6)));
    if (c->initial == GM_FLUID_INIT_TAYLOR_GREEN) {
      psi[v] = A * sin(2 * GM_PI * X) * sin(2 * GM_PI * Y);
    } else if (c->initial == GM_FLUID_INIT_DOUBLE_SHEAR) { /* scaled from [0, 2π]² */
      double q[2] = {2 * GM_PI * X, 2 * GM_PI * Y};
      psi[v] = gm_fluid_double_shear_psi(q) * (hi[1] - lo[1]) / (2 * GM_PI);
    } else {
      psi[v] = A * (sin(GM_PI * X) * sin(GM_PI * Y) + 0.5 * sin(2 * GM_PI * X) * sin(GM_PI * Y));
    }
  }
  st = gm_fluid_set_state(f, psi, theta);
  free(psi);
  if (st) {
    gm_error_set(err, st, "%s", gm_fluid_errmsg(f));
    gm_fluid_free(f);
    *out = NULL;
  }
  return st;
}
