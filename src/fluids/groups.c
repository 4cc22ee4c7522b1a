/* Named groups of boundary edges for the fluid solver: the sides of a generated rectangle, and
 * the physical line groups of a Gmsh ASCII 2.2 file. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/fluids.h"

void gm_fluid_groups_free(gm_fluid_groups *g) {
  if (!g) return;
  free(g->names);
  free(g->vertices);
  free(g->group);
  free(g);
}

static gm_status groups_alloc(size_t n_groups, size_t n_edges, gm_fluid_groups **out) {
  gm_fluid_groups *g = calloc(1, sizeof *g);
  if (!g) return GM_ENOMEM;
  g->names = calloc(n_groups ? n_groups : 1, sizeof *g->names);
  g->vertices = calloc(2 * (n_edges ? n_edges : 1), sizeof *g->vertices);
  g->group = calloc(n_edges ? n_edges : 1, sizeof *g->group);
  if (!g->names || !g->vertices || !g->group) {
    gm_fluid_groups_free(g);
    return GM_ENOMEM;
  }
  g->n_groups = n_groups;
  g->n_edges = n_edges;
  *out = g;
  return GM_OK;
}

gm_status gm_fluid_groups_rectangle(const gm_mesh *mesh, gm_fluid_groups **out, gm_error *err) {
  if (!mesh || !out) return gm_error_set(err, GM_EINVAL, "fluid groups: NULL argument");
  *out = NULL;
  if (mesh->dim != 2 || mesh->N != 2)
    return gm_error_set(err, GM_EINVAL, "fluid groups: needs a flat triangle mesh");
  gm_complex *cx = NULL;
  gm_status st = gm_mesh_complex(mesh, &cx, err);
  if (st) return st;
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (size_t v = 0; v < mesh->n_vertices; ++v)
    for (int k = 0; k < 2; ++k) {
      lo[k] = fmin(lo[k], mesh->x[2 * v + k]);
      hi[k] = fmax(hi[k], mesh->x[2 * v + k]);
    }
  size_t nb = gm_complex_boundary_count(cx, 1), ne = gm_complex_count(cx, 1);
  const unsigned char *mask = gm_complex_boundary_mask(cx, 1);
  const size_t *edge = gm_complex_simplices(cx, 1);
  const double *x = gm_complex_coordinates(cx);
  gm_fluid_groups *g = NULL;
  st = groups_alloc(4, nb, &g);
  if (st) {
    gm_complex_free(cx);
    return gm_error_set(err, st, "fluid groups: out of memory");
  }
  static const char *names[4] = {"bottom", "right", "top", "left"};
  for (int k = 0; k < 4; ++k) snprintf(g->names[k], GM_FLUID_NAME_SIZE, "%s", names[k]);
  double tol = 1e-9 * fmax(hi[0] - lo[0], hi[1] - lo[1]);
  size_t k = 0;
  for (size_t e = 0; e < ne; ++e) {
    if (!mask[e]) continue;
    size_t i = edge[2 * e], j = edge[2 * e + 1];
    double m[2] = {0.5 * (x[2 * i] + x[2 * j]), 0.5 * (x[2 * i + 1] + x[2 * j + 1])};
    size_t side = fabs(m[1] - lo[1]) <= tol   ? 0
                  : fabs(m[0] - hi[0]) <= tol ? 1
                  : fabs(m[1] - hi[1]) <= tol ? 2
                  : fabs(m[0] - lo[0]) <= tol ? 3
                                              : 4;
    if (side == 4) {
      gm_fluid_groups_free(g);
      gm_complex_free(cx);
      return gm_error_set(err, GM_EINVAL,
                          "fluid groups: boundary edge at (%g, %g) lies on no side of the "
                          "rectangle [%g, %g]x[%g, %g]",
                          m[0], m[1], lo[0], hi[0], lo[1], hi[1]);
    }
    g->vertices[2 * k] = i;
    g->vertices[2 * k + 1] = j;
    g->group[k++] = side;
  }
  gm_complex_free(cx);
  *out = g;
  return GM_OK;
}

/* ---- Gmsh ASCII 2.2: $PhysicalNames and the line elements (type 1) ------------------------- */

typedef struct vkey {
  double x, y;
  size_t v;
} vkey;

static int cmp_vkey(const void *a, const void *b) {
  const vkey *p = a, *q = b;
  if (p->x != q->x) return p->x < q->x ? -1 : 1;
  if (p->y != q->y) return p->y < q->y ? -1 : 1;
  return 0;
}

static size_t find_vertex(const vkey *keys, size_t n, double x, double y) {
  vkey k = {x, y, 0};
  const vkey *hit = bsearch(&k, keys, n, sizeof *keys, cmp_vkey);
  return hit ? hit->v : SIZE_MAX;
}

typedef struct msh_node {
  long id;
  double x, y;
} msh_node;

static int cmp_node(const void *a, const void *b) {
  const msh_node *p = a, *q = b;
  return (p->id > q->id) - (p->id < q->id);
}

gm_status gm_fluid_groups_read_msh(const char *path, const gm_mesh *mesh, gm_fluid_groups **out,
                                   gm_error *err) {
  if (!path || !mesh || !out) return gm_error_set(err, GM_EINVAL, "fluid groups: NULL argument");
  *out = NULL;
  if (mesh->N != 2) return gm_error_set(err, GM_EINVAL, "fluid groups: needs a mesh in the plane");
  FILE *fp = fopen(path, "r");
  if (!fp) return gm_error_set(err, GM_EIO, "%s: cannot open", path);
  gm_status st = GM_OK;
  char line[512], msg[GM_ERRMSG_SIZE] = "";
  size_t n_names = 0, n_nodes = 0, n_lines = 0, cap_lines = 0, lineno = 0;
  char(*names)[GM_FLUID_NAME_SIZE] = NULL;
  long *name_tag = NULL;
  msh_node *nodes = NULL;
  long(*lines)[3] = NULL; /* node, node, physical tag */
  vkey *keys = NULL;
  gm_fluid_groups *g = NULL;
  int version_ok = 0;
#define MSH_FAIL(...)                       \
  do {                                      \
    st = GM_EINVAL;                         \
    snprintf(msg, sizeof msg, __VA_ARGS__); \
    goto done;                              \
  } while (0)
  while (fgets(line, sizeof line, fp)) {
    ++lineno;
    if (strncmp(line, "$MeshFormat", 11) == 0) {
      double ver = 0;
      int ft = 1;
      if (!fgets(line, sizeof line, fp) || sscanf(line, "%lf %d", &ver, &ft) != 2)
        MSH_FAIL("%s: line %zu: bad $MeshFormat", path, lineno + 1);
      ++lineno;
      if (ver < 2.0 || ver >= 3.0 || ft != 0)
        MSH_FAIL("%s: boundary groups are read from ASCII Gmsh 2.2 files (this is version %g%s)",
                 path, ver, ft ? ", binary" : "");
      version_ok = 1;
    } else if (strncmp(line, "$PhysicalNames", 14) == 0) {
      if (!fgets(line, sizeof line, fp) || sscanf(line, "%zu", &n_names) != 1 || n_names > 100000)
        MSH_FAIL("%s: line %zu: bad count of physical names", path, lineno + 1);
      ++lineno;
      names = calloc(n_names ? n_names : 1, sizeof *names);
      name_tag = calloc(n_names ? n_names : 1, sizeof *name_tag);
      if (!names || !name_tag) {
        st = GM_ENOMEM;
        snprintf(msg, sizeof msg, "out of memory");
        goto done;
      }
      for (size_t i = 0; i < n_names; ++i) {
        int dim;
        long tag;
        char nm[256];
        ++lineno;
        if (!fgets(line, sizeof line, fp) ||
            sscanf(line, "%d %ld \"%255[^\"]\"", &dim, &tag, nm) != 3)
          MSH_FAIL("%s: line %zu: bad physical name", path, lineno);
        name_tag[i] = dim == 1 ? tag : -1; /* only curves bound a 2-D domain */
        size_t len = strlen(nm);
        if (len >= GM_FLUID_NAME_SIZE)
          MSH_FAIL("%s: line %zu: physical name longer than %d characters", path, lineno,
                   GM_FLUID_NAME_SIZE - 1);
        memcpy(names[i], nm, len + 1);
      }
    } else if (strncmp(line, "$Nodes", 6) == 0) {
      if (!fgets(line, sizeof line, fp) || sscanf(line, "%zu", &n_nodes) != 1 ||
          n_nodes > mesh->n_vertices + 10000000)
        MSH_FAIL("%s: line %zu: bad node count", path, lineno + 1);
      ++lineno;
      nodes = calloc(n_nodes ? n_nodes : 1, sizeof *nodes);
      if (!nodes) {
        st = GM_ENOMEM;
        snprintf(msg, sizeof msg, "out of memory");
        goto done;
      }
      for (size_t i = 0; i < n_nodes; ++i) {
        ++lineno;
        if (!fgets(line, sizeof line, fp) ||
            sscanf(line, "%ld %lf %lf", &nodes[i].id, &nodes[i].x, &nodes[i].y) != 3)
          MSH_FAIL("%s: line %zu: bad node", path, lineno);
      }
      qsort(nodes, n_nodes, sizeof *nodes, cmp_node);
    } else if (strncmp(line, "$Elements", 9) == 0) {
      size_t n_el = 0;
      if (!fgets(line, sizeof line, fp) || sscanf(line, "%zu", &n_el) != 1)
        MSH_FAIL("%s: line %zu: bad element count", path, lineno + 1);
      ++lineno;
      for (size_t i = 0; i < n_el; ++i) {
        long id, type, ntags, tags[16], a, b;
        int used = 0, k = 0;
        ++lineno;
        if (!fgets(line, sizeof line, fp) ||
            sscanf(line, "%ld %ld %ld%n", &id, &type, &ntags, &used) != 3 || ntags < 0 ||
            ntags > 16)
          MSH_FAIL("%s: line %zu: bad element", path, lineno);
        if (type != 1) continue;
        const char *p = line + used;
        for (long t = 0; t < ntags; ++t, p += k)
          if (sscanf(p, "%ld%n", &tags[t], &k) != 1)
            MSH_FAIL("%s: line %zu: bad tags", path, lineno);
        if (sscanf(p, "%ld %ld", &a, &b) != 2)
          MSH_FAIL("%s: line %zu: bad line element", path, lineno);
        if (ntags < 1) continue;
        if (n_lines == cap_lines) {
          cap_lines = cap_lines ? 2 * cap_lines : 64;
          void *nl = realloc(lines, cap_lines * sizeof *lines);
          if (!nl) {
            st = GM_ENOMEM;
            snprintf(msg, sizeof msg, "out of memory");
            goto done;
          }
          lines = nl;
        }
        lines[n_lines][0] = a;
        lines[n_lines][1] = b;
        lines[n_lines++][2] = tags[0];
      }
    }
  }
  if (!version_ok) MSH_FAIL("%s: no $MeshFormat section", path);
  /* groups: the named physical curves that have line elements */
  keys = calloc(mesh->n_vertices ? mesh->n_vertices : 1, sizeof *keys);
  if (!keys) {
    st = GM_ENOMEM;
    snprintf(msg, sizeof msg, "out of memory");
    goto done;
  }
  for (size_t v = 0; v < mesh->n_vertices; ++v)
    keys[v] = (vkey){mesh->x[2 * v], mesh->x[2 * v + 1], v};
  qsort(keys, mesh->n_vertices, sizeof *keys, cmp_vkey);
  size_t n_used = 0;
  for (size_t i = 0; i < n_lines; ++i) {
    size_t nm = 0;
    while (nm < n_names && name_tag[nm] != lines[i][2]) ++nm;
    if (nm < n_names) ++n_used;
  }
  st = groups_alloc(n_names, n_used, &g);
  if (st) {
    snprintf(msg, sizeof msg, "out of memory");
    goto done;
  }
  for (size_t i = 0; i < n_names; ++i) memcpy(g->names[i], names[i], GM_FLUID_NAME_SIZE);
  size_t k = 0;
  for (size_t i = 0; i < n_lines; ++i) {
    size_t nm = 0;
    while (nm < n_names && name_tag[nm] != lines[i][2]) ++nm;
    if (nm == n_names) continue;
    for (int e = 0; e < 2; ++e) {
      msh_node key = {lines[i][e], 0, 0};
      msh_node *nd = bsearch(&key, nodes, n_nodes, sizeof *nodes, cmp_node);
      if (!nd)
        MSH_FAIL("%s: line element of \"%s\" uses undefined node %ld", path, names[nm], key.id);
      size_t v = find_vertex(keys, mesh->n_vertices, nd->x, nd->y);
      if (v == SIZE_MAX)
        MSH_FAIL("%s: node %ld of \"%s\" at (%g, %g) is no vertex of the mesh", path, key.id,
                 names[nm], nd->x, nd->y);
      g->vertices[2 * k + e] = v;
    }
    g->group[k++] = nm;
  }
#undef MSH_FAIL
done:
  fclose(fp);
  free(names);
  free(name_tag);
  free(nodes);
  free(lines);
  free(keys);
  if (st) {
    gm_fluid_groups_free(g);
    return gm_error_set(err, st, "%s", msg);
  }
  *out = g;
  return GM_OK;
}
