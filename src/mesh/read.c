/* Mesh readers: Gmsh .msh ASCII 2.2 and 4.1, OFF.
 *
 * Formats: Gmsh reference manual, "MSH file format" (version 4.1, and the legacy 2.2 section);
 * OFF as written by Geomview ("OFF" header, counts, vertices, faces "3 i j k"). Files are read
 * into memory and parsed by a tokenizer that counts lines, so every error names its line. The
 * highest-dimensional linear simplices (line 1, triangle 2, tetrahedron 4) become the cells;
 * points and lower-dimensional elements (boundary lines, surface triangles of a volume mesh)
 * are skipped; any other element type is an error. Nodes used by no cell are dropped. The
 * embedding dimension is the cell dimension raised to cover every non-zero coordinate (a flat
 * triangle mesh with z = 0 is 2-D, a surface is 3-D). Counts are checked against the size of the
 * file before anything is allocated, so a corrupt count cannot request a huge allocation; the file
 * itself is read up to a size limit. Words are never cut (a word longer than TOKEN_MAX − 1 is an
 * error) and words from the file are escaped in messages. */
#include <errno.h>
#include <inttypes.h>
#include <sys/stat.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/mesh.h"

#define TOKEN_MAX 128 /* longest word, NUL included: a longer one is an error, never cut */

typedef struct {
  const char *p, *end;
  size_t line;
  gm_error *err;
  char tok[TOKEN_MAX];
  char shown[4 * 40 + 8]; /* tok as messages show it (see show_token) */
} lexer;

static int is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

static void skip_space(lexer *lx) {
  while (lx->p < lx->end && is_space(*lx->p)) {
    if (*lx->p == '\n') ++lx->line;
    ++lx->p;
  }
}

/* Text from the file as messages show it: at most 40 bytes, printable ASCII as is, every other
 * byte (control characters, escape sequences, non-ASCII) as \xNN, so a file cannot write to the
 * user's terminal through an error message; "..." when cut. out holds 4 * 40 + 8 bytes. */
static const char *escape_text(const char *in, char *out) {
  size_t w = 0, i = 0;
  for (; in[i] != '\0' && i < 40; ++i) {
    unsigned char c = (unsigned char)in[i];
    if (c >= 0x20 && c < 0x7f && c != '\\') out[w++] = (char)c;
    else w += (size_t)snprintf(out + w, 5, "\\x%02x", c);
  }
  if (in[i] != '\0') memcpy(out + w, "...", 3), w += 3;
  out[w] = '\0';
  return out;
}

static const char *show_token(lexer *lx) { return escape_text(lx->tok, lx->shown); }

static gm_status too_long(lexer *lx) {
  return gm_error_set(lx->err, GM_EINVAL, "line %zu: a word longer than %d characters ('%s')",
                      lx->line, TOKEN_MAX - 1, show_token(lx));
}

/* Next whitespace-separated token into lx->tok; 0 at end of input, -1 (with the error set) for
 * a word longer than TOKEN_MAX - 1 characters. */
static int next_token(lexer *lx) {
  skip_space(lx);
  if (lx->p >= lx->end) return 0;
  size_t n = 0;
  while (lx->p < lx->end && !is_space(*lx->p)) {
    if (n == sizeof lx->tok - 1) {
      lx->tok[n] = '\0';
      too_long(lx);
      return -1;
    }
    lx->tok[n++] = *lx->p++;
  }
  lx->tok[n] = '\0';
  return 1;
}

static void skip_line(lexer *lx) {
  while (lx->p < lx->end && *lx->p != '\n') ++lx->p;
}

/* Spaces and tabs only: 1 when another word follows on the same line. */
static int more_on_line(lexer *lx) {
  while (lx->p < lx->end && (*lx->p == ' ' || *lx->p == '\t' || *lx->p == '\r' ||
                             *lx->p == '\f' || *lx->p == '\v'))
    ++lx->p;
  return lx->p < lx->end && *lx->p != '\n' && *lx->p != '#';
}

static gm_status fail(lexer *lx, const char *what) {
  return gm_error_set(lx->err, GM_EINVAL, "line %zu: %s", lx->line, what);
}

/* Mesh files are text: a NUL byte anywhere (binary data, /dev/zero) is an error naming its line,
 * found before parsing so no NUL can end a number early. */
static gm_status check_text(lexer *lx) {
  const char *nul = memchr(lx->p, '\0', (size_t)(lx->end - lx->p));
  if (nul == NULL) return GM_OK;
  size_t line = 1;
  for (const char *q = lx->p; q < nul; ++q) line += *q == '\n';
  return gm_error_set(lx->err, GM_EINVAL, "line %zu: a NUL byte (binary data): not a text mesh file",
                      line);
}

static gm_status expect_token(lexer *lx, const char *what) {
  int got = next_token(lx);
  if (got < 0) return GM_EINVAL;
  if (got == 0)
    return gm_error_set(lx->err, GM_EINVAL, "line %zu: unexpected end of file (expected %s)",
                        lx->line, what);
  return GM_OK;
}

static gm_status read_long(lexer *lx, const char *what, long long *v) {
  gm_status st = expect_token(lx, what);
  if (st != GM_OK) return st;
  char *e = NULL;
  errno = 0;
  long long x = strtoll(lx->tok, &e, 10);
  if (e == lx->tok || *e != '\0' || errno == ERANGE)
    return gm_error_set(lx->err, GM_EINVAL, "line %zu: expected an integer (%s), found '%s'",
                        lx->line, what, show_token(lx));
  *v = x;
  return GM_OK;
}

/* A non-negative count no larger than the bytes left (each item takes at least 2 bytes). */
static gm_status read_count(lexer *lx, const char *what, size_t *v) {
  long long x = 0;
  gm_status st = read_long(lx, what, &x);
  if (st != GM_OK) return st;
  if (x < 0) return gm_error_set(lx->err, GM_EINVAL, "line %zu: negative %s %lld", lx->line, what, x);
  if ((unsigned long long)x > (unsigned long long)(lx->end - lx->p) / 2 + 1)
    return gm_error_set(lx->err, GM_EINVAL,
                        "line %zu: %s %lld is larger than the rest of the file can hold "
                        "(truncated file or wrong count)",
                        lx->line, what, x);
  *v = (size_t)x;
  return GM_OK;
}

static gm_status read_double(lexer *lx, const char *what, double *v) {
  gm_status st = expect_token(lx, what);
  if (st != GM_OK) return st;
  char *e = NULL;
  double x = strtod(lx->tok, &e);
  if (e == lx->tok || *e != '\0')
    return gm_error_set(lx->err, GM_EINVAL, "line %zu: expected a number (%s), found '%s'",
                        lx->line, what, show_token(lx));
  if (!isfinite(x))
    return gm_error_set(lx->err, GM_EDOMAIN, "line %zu: %s is not finite ('%s')", lx->line, what,
                        show_token(lx));
  *v = x;
  return GM_OK;
}

static gm_status expect_word(lexer *lx, const char *word) {
  gm_status st = expect_token(lx, word);
  if (st != GM_OK) return st;
  if (strcmp(lx->tok, word) != 0)
    return gm_error_set(lx->err, GM_EINVAL, "line %zu: expected %s, found '%s'", lx->line, word,
                        show_token(lx));
  return GM_OK;
}

/* ---- assembling the mesh ----------------------------------------------------------------- */

typedef struct {
  size_t n_nodes;
  long long *node_tag; /* sorted after reading */
  size_t *node_order;  /* node index of each sorted tag */
  double *xyz;         /* 3 per node */
  size_t *node_line;   /* line of each node's tag, for errors */
  size_t dim;          /* highest cell dimension seen */
  size_t n_cells, cap_cells;
  long long *cell_nodes; /* 4 per cell (tags) */
  size_t *cell_line;     /* line of each cell, for errors */
  int *cell_tag;
  unsigned char *cell_dim;
} raw_mesh;

static void raw_free(raw_mesh *r) {
  free(r->node_tag), free(r->node_order), free(r->xyz), free(r->node_line);
  free(r->cell_nodes), free(r->cell_line), free(r->cell_tag), free(r->cell_dim);
}

static gm_status raw_nodes(raw_mesh *r, size_t n, gm_error *err) {
  r->node_tag = malloc((n ? n : 1) * sizeof(long long));
  r->node_order = malloc((n ? n : 1) * sizeof(size_t));
  r->xyz = malloc((n ? n : 1) * 3 * sizeof(double));
  r->node_line = malloc((n ? n : 1) * sizeof(size_t));
  if (!r->node_tag || !r->node_order || !r->xyz || !r->node_line)
    return gm_error_set(err, GM_ENOMEM, "out of memory for %zu nodes", n);
  r->n_nodes = n;
  return GM_OK;
}

static gm_status raw_add_cell(raw_mesh *r, size_t dim, const long long *nodes, int tag, size_t line,
                              gm_error *err) {
  if (r->n_cells == r->cap_cells) {
    size_t cap = r->cap_cells ? 2 * r->cap_cells : 256;
    long long *cn = realloc(r->cell_nodes, cap * 4 * sizeof(long long));
    if (cn) r->cell_nodes = cn;
    size_t *cl = realloc(r->cell_line, cap * sizeof(size_t));
    if (cl) r->cell_line = cl;
    int *ct = realloc(r->cell_tag, cap * sizeof(int));
    if (ct) r->cell_tag = ct;
    unsigned char *cd = realloc(r->cell_dim, cap);
    if (cd) r->cell_dim = cd;
    if (!cn || !cl || !ct || !cd) return gm_error_set(err, GM_ENOMEM, "out of memory for cells");
    r->cap_cells = cap;
  }
  memcpy(r->cell_nodes + 4 * r->n_cells, nodes, (dim + 1) * sizeof(long long));
  r->cell_line[r->n_cells] = line;
  r->cell_tag[r->n_cells] = tag;
  r->cell_dim[r->n_cells] = (unsigned char)dim;
  if (dim > r->dim) r->dim = dim;
  r->n_cells++;
  return GM_OK;
}

typedef struct {
  long long tag;
  size_t node;
} tag_node;

static int cmp_tag(const void *a, const void *b) {
  long long x = ((const tag_node *)a)->tag, y = ((const tag_node *)b)->tag;
  return x < y ? -1 : x > y;
}

/* Build the gm_mesh: sort node tags, resolve cell nodes, drop unused nodes. */
static gm_status raw_finish(raw_mesh *r, size_t line, gm_mesh **out, gm_error *err) {
  if (r->dim == 0 || r->n_cells == 0)
    return gm_error_set(err, GM_EINVAL, "line %zu: the file has no line, triangle or tetrahedron elements", line);
  const size_t nn = r->n_nodes;
  /* sorted tags and the node each belongs to (node_order) */
  tag_node *tn = malloc((nn ? nn : 1) * sizeof(tag_node));
  long long *sorted = malloc((nn ? nn : 1) * sizeof(long long));
  if (tn == NULL || sorted == NULL) {
    free(tn), free(sorted);
    return gm_error_set(err, GM_ENOMEM, "line %zu: out of memory", line);
  }
  int already = 1;
  for (size_t i = 0; i < nn; ++i) {
    tn[i].tag = r->node_tag[i];
    tn[i].node = i;
    if (i > 0 && r->node_tag[i] <= r->node_tag[i - 1]) already = 0;
  }
  if (!already) qsort(tn, nn, sizeof(tag_node), cmp_tag);
  for (size_t i = 0; i < nn; ++i) {
    sorted[i] = tn[i].tag;
    r->node_order[i] = tn[i].node;
  }
  free(tn);
  for (size_t i = 1; i < nn; ++i)
    if (sorted[i] == sorted[i - 1]) {
      long long t = sorted[i];
      size_t a = r->node_line[r->node_order[i - 1]], b = r->node_line[r->node_order[i]];
      free(sorted);
      return gm_error_set(err, GM_EINVAL, "line %zu: node %lld is defined twice (first on line %zu)",
                          a > b ? a : b, t, a < b ? a : b);
    }
  size_t *map = malloc((nn ? nn : 1) * sizeof(size_t)); /* node index -> vertex or SIZE_MAX */
  if (map == NULL) {
    free(sorted);
    return gm_error_set(err, GM_ENOMEM, "line %zu: out of memory", line);
  }
  for (size_t i = 0; i < nn; ++i) map[i] = SIZE_MAX;
  const size_t dim = r->dim, kp = dim + 1;
  size_t n_cells = 0;
  gm_status st = GM_OK;
  for (size_t c = 0; c < r->n_cells && st == GM_OK; ++c) {
    if (r->cell_dim[c] != dim) continue;
    ++n_cells;
    for (size_t i = 0; i < kp; ++i) {
      long long tag = r->cell_nodes[4 * c + i];
      size_t lo = 0, hi = nn;
      while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (sorted[mid] < tag) lo = mid + 1;
        else hi = mid;
      }
      if (lo == nn || sorted[lo] != tag) {
        st = gm_error_set(err, GM_EINVAL,
                          "line %zu: element refers to node %lld, which is not defined in the "
                          "nodes section",
                          r->cell_line[c], tag);
        break;
      }
      size_t node = r->node_order[lo];
      map[node] = 0;
      r->cell_nodes[4 * c + i] = (long long)node;
    }
  }
  free(sorted);
  if (st != GM_OK) {
    free(map);
    return st;
  }
  size_t nv = 0, N = dim;
  for (size_t i = 0; i < nn; ++i)
    if (map[i] == 0) {
      map[i] = nv++;
      for (size_t j = 0; j < 3; ++j)
        if (r->xyz[3 * i + j] != 0.0 && j + 1 > N) N = j + 1;
    }
  gm_mesh *m = NULL;
  st = gm_mesh_create(N, nv, dim, n_cells, &m);
  if (st != GM_OK) {
    free(map);
    return gm_error_set(err, st, "line %zu: cannot make a mesh of %zu vertices and %zu cells", line, nv, n_cells);
  }
  for (size_t i = 0; i < nn; ++i)
    if (map[i] != SIZE_MAX)
      for (size_t j = 0; j < N; ++j) m->x[map[i] * N + j] = r->xyz[3 * i + j];
  size_t w = 0;
  for (size_t c = 0; c < r->n_cells; ++c) {
    if (r->cell_dim[c] != dim) continue;
    for (size_t i = 0; i < kp; ++i) m->cells[w * kp + i] = map[r->cell_nodes[4 * c + i]];
    m->cell_tags[w] = r->cell_tag[c];
    ++w;
  }
  free(map);
  *out = m;
  return GM_OK;
}

/* Gmsh element types: node counts of the ones we know; linear simplices are kept. */
static int gmsh_type(long long type, size_t *n_nodes, size_t *dim) {
  static const struct { int type, nodes, dim; } table[] = {
      {1, 2, 1},   {2, 3, 2},   {3, 4, 2},   {4, 4, 3},   {5, 8, 3},  {6, 6, 3},   {7, 5, 3},
      {8, 3, 1},   {9, 6, 2},   {10, 9, 2},  {11, 10, 3}, {12, 27, 3}, {13, 18, 3}, {14, 14, 3},
      {15, 1, 0},  {16, 8, 2},  {17, 20, 3}, {18, 15, 3}, {19, 13, 3}, {20, 9, 2},  {21, 10, 2},
      {22, 12, 2}, {23, 15, 2}, {24, 15, 2}, {25, 21, 2}, {26, 4, 1},  {27, 5, 1},  {28, 6, 1},
      {29, 20, 3}, {30, 35, 3}, {31, 56, 3}};
  for (size_t i = 0; i < sizeof table / sizeof table[0]; ++i)
    if (table[i].type == type) {
      *n_nodes = (size_t)table[i].nodes;
      *dim = (size_t)table[i].dim;
      return type == 1 || type == 2 || type == 4 || type == 15 ? 1 : 2;
    }
  return 0;
}

static gm_status element_type(lexer *lx, long long type, size_t *nn, size_t *dim) {
  int kind = gmsh_type(type, nn, dim);
  if (kind == 0) {
    char msg[96];
    snprintf(msg, sizeof msg, "unknown element type %lld", type);
    return fail(lx, msg);
  }
  if (kind == 2 && *dim > 0) {
    char msg[128];
    snprintf(msg, sizeof msg,
             "element type %lld is not a linear simplex (geomint reads lines, triangles and "
             "tetrahedra)",
             type);
    return fail(lx, msg);
  }
  return GM_OK;
}

/* Skip to the line after "$End<name>". */
static gm_status skip_section(lexer *lx, const char *name) {
  char end[TOKEN_MAX + 8];
  snprintf(end, sizeof end, "$End%s", name);
  int got;
  while ((got = next_token(lx)) > 0)
    if (strcmp(lx->tok, end) == 0) return GM_OK;
  if (got < 0) return GM_EINVAL;
  return gm_error_set(lx->err, GM_EINVAL, "line %zu: unexpected end of file: %s is missing",
                      lx->line, escape_text(end, lx->shown));
}

static gm_status msh22_nodes(lexer *lx, raw_mesh *r) {
  size_t n = 0;
  gm_status st = read_count(lx, "number of nodes", &n);
  if (st == GM_OK) st = raw_nodes(r, n, lx->err);
  for (size_t i = 0; i < n && st == GM_OK; ++i) {
    st = read_long(lx, "node tag", &r->node_tag[i]);
    r->node_line[i] = lx->line;
    for (size_t j = 0; j < 3 && st == GM_OK; ++j) st = read_double(lx, "node coordinate", &r->xyz[3 * i + j]);
  }
  if (st == GM_OK) st = expect_word(lx, "$EndNodes");
  return st;
}

static gm_status msh22_elements(lexer *lx, raw_mesh *r) {
  size_t n = 0;
  gm_status st = read_count(lx, "number of elements", &n);
  for (size_t i = 0; i < n && st == GM_OK; ++i) {
    long long id, type = 0, ntags = 0;
    size_t line;
    st = read_long(lx, "element tag", &id);
    line = lx->line;
    if (st == GM_OK) st = read_long(lx, "element type", &type);
    size_t nn = 0, dim = 0;
    if (st == GM_OK) st = element_type(lx, type, &nn, &dim);
    if (st == GM_OK) st = read_long(lx, "number of tags", &ntags);
    if (st == GM_OK && (ntags < 0 || ntags > 64)) st = fail(lx, "number of element tags out of range");
    long long tag0 = 0, t;
    for (long long j = 0; j < ntags && st == GM_OK; ++j) {
      st = read_long(lx, "element tag", &t);
      if (j == 0) tag0 = t;
    }
    long long nodes[4] = {0, 0, 0, 0};
    for (size_t j = 0; j < nn && st == GM_OK; ++j) {
      st = read_long(lx, "element node", &t);
      if (j < 4) nodes[j] = t;
    }
    if (st == GM_OK && dim >= 1)
      st = raw_add_cell(r, dim, nodes, (int)(tag0 > INT32_MAX || tag0 < INT32_MIN ? 0 : tag0), line, lx->err);
  }
  if (st == GM_OK) st = expect_word(lx, "$EndElements");
  return st;
}

/* 4.1 $Entities: physical tag (first one, 0 if none) of each entity of dimension 1..3. */
typedef struct {
  size_t n[4];
  long long *tag[4];
  int *phys[4];
} entities;

static void entities_free(entities *e) {
  for (int d = 0; d < 4; ++d) free(e->tag[d]), free(e->phys[d]);
}

static gm_status msh41_entities(lexer *lx, entities *e) {
  gm_status st = GM_OK;
  for (int d = 0; d < 4 && st == GM_OK; ++d) st = read_count(lx, "number of entities", &e->n[d]);
  for (int d = 0; d < 4 && st == GM_OK; ++d) {
    e->tag[d] = malloc((e->n[d] ? e->n[d] : 1) * sizeof(long long));
    e->phys[d] = calloc(e->n[d] ? e->n[d] : 1, sizeof(int));
    if (!e->tag[d] || !e->phys[d]) return gm_error_set(lx->err, GM_ENOMEM, "out of memory");
    for (size_t i = 0; i < e->n[d] && st == GM_OK; ++i) {
      double x;
      st = read_long(lx, "entity tag", &e->tag[d][i]);
      for (int j = 0; j < (d == 0 ? 3 : 6) && st == GM_OK; ++j) st = read_double(lx, "bounding box", &x);
      size_t np = 0;
      if (st == GM_OK) st = read_count(lx, "number of physical tags", &np);
      for (size_t j = 0; j < np && st == GM_OK; ++j) {
        long long t;
        st = read_long(lx, "physical tag", &t);
        if (j == 0 && st == GM_OK) e->phys[d][i] = (int)(t > INT32_MAX || t < INT32_MIN ? 0 : t);
      }
      if (d > 0 && st == GM_OK) {
        size_t nb = 0;
        st = read_count(lx, "number of bounding entities", &nb);
        for (size_t j = 0; j < nb && st == GM_OK; ++j) {
          long long t;
          st = read_long(lx, "bounding entity", &t);
        }
      }
    }
  }
  if (st == GM_OK) st = expect_word(lx, "$EndEntities");
  return st;
}

static gm_status msh41_nodes(lexer *lx, raw_mesh *r) {
  size_t nblocks = 0, n = 0;
  long long lo, hi;
  gm_status st = read_count(lx, "number of node blocks", &nblocks);
  if (st == GM_OK) st = read_count(lx, "number of nodes", &n);
  if (st == GM_OK) st = read_long(lx, "minimum node tag", &lo);
  if (st == GM_OK) st = read_long(lx, "maximum node tag", &hi);
  if (st == GM_OK) st = raw_nodes(r, n, lx->err);
  size_t w = 0;
  for (size_t b = 0; b < nblocks && st == GM_OK; ++b) {
    long long edim, etag, param;
    size_t nb = 0;
    st = read_long(lx, "entity dimension", &edim);
    if (st == GM_OK) st = read_long(lx, "entity tag", &etag);
    if (st == GM_OK) st = read_long(lx, "parametric flag", &param);
    if (st == GM_OK) st = read_count(lx, "nodes in block", &nb);
    if (st == GM_OK && param != 0) st = fail(lx, "parametric node coordinates are not supported");
    if (st == GM_OK && nb > n - w) st = fail(lx, "node blocks hold more nodes than the header says");
    for (size_t i = 0; i < nb && st == GM_OK; ++i) {
      st = read_long(lx, "node tag", &r->node_tag[w + i]);
      r->node_line[w + i] = lx->line;
    }
    for (size_t i = 0; i < nb && st == GM_OK; ++i)
      for (size_t j = 0; j < 3 && st == GM_OK; ++j)
        st = read_double(lx, "node coordinate", &r->xyz[3 * (w + i) + j]);
    w += nb;
  }
  if (st == GM_OK && w != n) {
    char msg[128];
    snprintf(msg, sizeof msg, "the node blocks hold %zu nodes, the header says %zu", w, n);
    st = fail(lx, msg);
  }
  if (st == GM_OK) st = expect_word(lx, "$EndNodes");
  return st;
}

static int entity_phys(const entities *e, long long dim, long long tag) {
  if (dim < 0 || dim > 3) return 0;
  for (size_t i = 0; i < e->n[dim]; ++i)
    if (e->tag[dim][i] == tag) return e->phys[dim][i];
  return 0;
}

static gm_status msh41_elements(lexer *lx, raw_mesh *r, const entities *e) {
  size_t nblocks = 0, n = 0, seen = 0;
  long long lo, hi;
  gm_status st = read_count(lx, "number of element blocks", &nblocks);
  if (st == GM_OK) st = read_count(lx, "number of elements", &n);
  if (st == GM_OK) st = read_long(lx, "minimum element tag", &lo);
  if (st == GM_OK) st = read_long(lx, "maximum element tag", &hi);
  for (size_t b = 0; b < nblocks && st == GM_OK; ++b) {
    long long edim = 0, etag = 0, type = 0;
    size_t nb = 0, nn = 0, dim = 0;
    st = read_long(lx, "entity dimension", &edim);
    if (st == GM_OK) st = read_long(lx, "entity tag", &etag);
    if (st == GM_OK) st = read_long(lx, "element type", &type);
    if (st == GM_OK) st = element_type(lx, type, &nn, &dim);
    if (st == GM_OK) st = read_count(lx, "elements in block", &nb);
    if (st == GM_OK && nb > n - seen) st = fail(lx, "element blocks hold more elements than the header says");
    int phys = entity_phys(e, edim, etag);
    for (size_t i = 0; i < nb && st == GM_OK; ++i) {
      long long id, nodes[4] = {0, 0, 0, 0}, t;
      st = read_long(lx, "element tag", &id);
      size_t line = lx->line;
      for (size_t j = 0; j < nn && st == GM_OK; ++j) {
        st = read_long(lx, "element node", &t);
        if (j < 4) nodes[j] = t;
      }
      if (st == GM_OK && dim >= 1) st = raw_add_cell(r, dim, nodes, phys, line, lx->err);
    }
    seen += nb;
  }
  if (st == GM_OK && seen != n) {
    char msg[128];
    snprintf(msg, sizeof msg, "the element blocks hold %zu elements, the header says %zu", seen, n);
    st = fail(lx, msg);
  }
  if (st == GM_OK) st = expect_word(lx, "$EndElements");
  return st;
}

gm_status gm_mesh_parse_msh(const char *data, size_t size, gm_mesh **out, gm_error *err) {
  if (out == NULL || (data == NULL && size > 0)) return gm_error_set(err, GM_EINVAL, "NULL argument");
  *out = NULL;
  lexer lx = {data, data + size, 1, err, {0}, {0}};
  raw_mesh r;
  memset(&r, 0, sizeof r);
  entities ent;
  memset(&ent, 0, sizeof ent);
  int version = 0, have_nodes = 0, have_elements = 0;
  gm_status st = check_text(&lx);
  int got = 0;
  while (st == GM_OK && (got = next_token(&lx)) != 0) {
    if (got < 0) {
      st = GM_EINVAL;
      break;
    }
    if (lx.tok[0] != '$') {
      char msg[256];
      snprintf(msg, sizeof msg, "expected a section header ($Name), found '%s'", show_token(&lx));
      st = fail(&lx, msg);
      break;
    }
    char name[TOKEN_MAX];
    memcpy(name, lx.tok + 1, sizeof name - 1); /* tok holds at most TOKEN_MAX - 1 characters */
    name[sizeof name - 1] = '\0';
    if (strcmp(name, "MeshFormat") == 0) {
      double v;
      long long ft, ds;
      st = read_double(&lx, "format version", &v);
      if (st == GM_OK) st = read_long(&lx, "file type", &ft);
      if (st == GM_OK) st = read_long(&lx, "data size", &ds);
      if (st != GM_OK) break;
      if (ft != 0) {
        st = fail(&lx, "binary .msh files are not supported (save as ASCII)");
        break;
      }
      if (v == 2.2 || v == 2.0 || v == 2.1) version = 2;
      else if (v == 4.1) version = 4;
      else {
        char msg[96];
        snprintf(msg, sizeof msg, "unsupported .msh version %g (2.2 and 4.1 are read)", v);
        st = fail(&lx, msg);
        break;
      }
      st = expect_word(&lx, "$EndMeshFormat");
    } else if (version == 0) {
      st = fail(&lx, "the file does not start with $MeshFormat");
    } else if (strcmp(name, "Nodes") == 0) {
      if (have_nodes) st = fail(&lx, "a second $Nodes section");
      else st = version == 2 ? msh22_nodes(&lx, &r) : msh41_nodes(&lx, &r);
      have_nodes = 1;
    } else if (strcmp(name, "Elements") == 0) {
      if (have_elements) st = fail(&lx, "a second $Elements section");
      else st = version == 2 ? msh22_elements(&lx, &r) : msh41_elements(&lx, &r, &ent);
      have_elements = 1;
    } else if (strcmp(name, "Entities") == 0 && version == 4) {
      if (ent.tag[0] != NULL) st = fail(&lx, "a second $Entities section");
      else st = msh41_entities(&lx, &ent);
    } else if (strncmp(name, "End", 3) == 0) {
      char msg[256];
      snprintf(msg, sizeof msg, "unexpected %s", show_token(&lx));
      st = fail(&lx, msg);
    } else {
      st = skip_section(&lx, name);
    }
  }
  if (st == GM_OK && version == 0) st = gm_error_set(err, GM_EINVAL, "line %zu: empty file or no $MeshFormat", lx.line);
  if (st == GM_OK && (!have_nodes || !have_elements))
    st = gm_error_set(err, GM_EINVAL, "line %zu: the file has no %s section", lx.line,
                      have_nodes ? "$Elements" : "$Nodes");
  if (st == GM_OK) st = raw_finish(&r, lx.line, out, err);
  raw_free(&r);
  entities_free(&ent);
  return st;
}

gm_status gm_mesh_parse_off(const char *data, size_t size, gm_mesh **out, gm_error *err) {
  if (out == NULL || (data == NULL && size > 0)) return gm_error_set(err, GM_EINVAL, "NULL argument");
  *out = NULL;
  lexer lx = {data, data + size, 1, err, {0}, {0}};
  raw_mesh r;
  memset(&r, 0, sizeof r);
  /* comments: '#' to the end of the line, anywhere a token may start; a vertex (x y z) and a
   * face (3 i j k) are one line each, so a missing number is blamed on its own line */
  gm_status st = check_text(&lx);
  if (st != GM_OK) return st;
#define OFF_NEXT()                                          \
  do {                                                      \
    skip_space(&lx);                                        \
    while (lx.p < lx.end && *lx.p == '#') {                 \
      skip_line(&lx);                                       \
      skip_space(&lx);                                      \
    }                                                       \
  } while (0)
  OFF_NEXT();
  st = expect_word(&lx, "OFF");
  size_t nv = 0, nf = 0, ne = 0;
  if (st == GM_OK) { OFF_NEXT(); st = read_count(&lx, "number of vertices", &nv); }
  if (st == GM_OK) { OFF_NEXT(); st = read_count(&lx, "number of faces", &nf); }
  if (st == GM_OK) { OFF_NEXT(); st = read_count(&lx, "number of edges", &ne); }
  if (st == GM_OK) st = raw_nodes(&r, nv, err);
  for (size_t i = 0; i < nv && st == GM_OK; ++i) {
    r.node_tag[i] = (long long)i;
    OFF_NEXT();
    r.node_line[i] = lx.line;
    for (size_t j = 0; j < 3 && st == GM_OK; ++j) {
      if (j > 0 && !more_on_line(&lx)) {
        char msg[128];
        snprintf(msg, sizeof msg, "vertex %zu has %zu coordinate%s, expected 3 (x y z)", i, j,
                 j == 1 ? "" : "s");
        st = fail(&lx, msg);
        break;
      }
      st = read_double(&lx, "vertex coordinate", &r.xyz[3 * i + j]);
    }
    if (st == GM_OK && more_on_line(&lx)) {
      char msg[128];
      snprintf(msg, sizeof msg, "vertex %zu has more than 3 coordinates, expected 3 (x y z)", i);
      st = fail(&lx, msg);
    }
  }
  for (size_t i = 0; i < nf && st == GM_OK; ++i) {
    long long k, v[4] = {0, 0, 0, 0};
    OFF_NEXT();
    st = read_long(&lx, "number of face vertices", &k);
    size_t line = lx.line;
    if (st == GM_OK && k != 3) {
      char msg[96];
      snprintf(msg, sizeof msg, "face %zu has %lld vertices: only triangles are read", i, k);
      st = fail(&lx, msg);
    }
    for (int j = 0; j < 3 && st == GM_OK; ++j) {
      if (!more_on_line(&lx)) {
        char msg[128];
        snprintf(msg, sizeof msg, "face %zu has %d vertex index%s, expected 3", i, j,
                 j == 1 ? "" : "es");
        st = fail(&lx, msg);
        break;
      }
      st = read_long(&lx, "face vertex", &v[j]);
      if (st == GM_OK && (v[j] < 0 || (size_t)v[j] >= nv)) {
        char msg[128];
        snprintf(msg, sizeof msg, "face %zu: vertex index %lld out of range (%zu vertices)", i, v[j], nv);
        st = fail(&lx, msg);
      }
    }
    skip_line(&lx); /* optional colour values */
    if (st == GM_OK) st = raw_add_cell(&r, 2, v, 0, line, err);
  }
#undef OFF_NEXT
  if (st == GM_OK) st = raw_finish(&r, lx.line, out, err);
  raw_free(&r);
  return st;
}

/* Read the whole file, at most max_bytes: a regular file larger than that is refused before
 * reading, a stream (pipe, device) when it passes the limit; a NUL byte stops reading at once
 * (mesh files are text: /dev/zero fails on its first block). */
static gm_status slurp(const char *path, size_t max_bytes, char **data, size_t *size, gm_error *err) {
  FILE *f = fopen(path, "rb");
  if (f == NULL) return gm_error_set(err, GM_EIO, "cannot open %s: %s", path, strerror(errno));
  struct stat sb;
  if (fstat(fileno(f), &sb) == 0 && S_ISREG(sb.st_mode) && (uintmax_t)sb.st_size > max_bytes) {
    fclose(f);
    return gm_error_set(err, GM_EIO,
                        "%s: the file has %ju bytes, more than the limit of %zu bytes for a mesh "
                        "file",
                        path, (uintmax_t)sb.st_size, max_bytes);
  }
  size_t cap = 1 << 16, n = 0;
  char *buf = malloc(cap);
  gm_status st = GM_OK;
  while (buf != NULL) {
    size_t got = fread(buf + n, 1, cap - n, f);
    const char *nul = memchr(buf + n, '\0', got);
    n += got;
    if (nul != NULL) {
      size_t line = 1;
      for (const char *q = buf; q < nul; ++q) line += *q == '\n';
      st = gm_error_set(err, GM_EINVAL, "%s: line %zu: a NUL byte (binary data): not a text mesh file",
                        path, line);
      break;
    }
    if (n > max_bytes) {
      st = gm_error_set(err, GM_EIO, "%s: more than the limit of %zu bytes for a mesh file", path,
                        max_bytes);
      break;
    }
    if (n < cap) break;
    size_t grow = cap * 2 > max_bytes + 1 ? max_bytes + 1 : cap * 2;
    char *nb = realloc(buf, grow);
    if (nb == NULL) {
      free(buf);
      buf = NULL;
      break;
    }
    buf = nb;
    cap = grow;
  }
  int bad = ferror(f);
  fclose(f);
  if (buf == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory reading %s", path);
  if (st == GM_OK && bad) st = gm_error_set(err, GM_EIO, "error reading %s", path);
  if (st != GM_OK) {
    free(buf);
    return st;
  }
  *data = buf;
  *size = n;
  return GM_OK;
}

static gm_status read_with(const char *path, size_t max_bytes,
                           gm_status (*parse)(const char *, size_t, gm_mesh **, gm_error *),
                           gm_mesh **out, gm_error *err) {
  if (out == NULL || path == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  *out = NULL;
  char *data = NULL;
  size_t size = 0;
  gm_status st = slurp(path, max_bytes, &data, &size, err);
  if (st != GM_OK) return st;
  gm_error local = {{0}};
  st = parse(data, size, out, &local);
  free(data);
  if (st != GM_OK) gm_error_set(err, st, "%s: %s", path, local.message);
  return st;
}

gm_status gm_mesh_read_msh(const char *path, gm_mesh **out, gm_error *err) {
  return read_with(path, GM_MESH_MAX_FILE_BYTES, gm_mesh_parse_msh, out, err);
}

gm_status gm_mesh_read_off(const char *path, gm_mesh **out, gm_error *err) {
  return read_with(path, GM_MESH_MAX_FILE_BYTES, gm_mesh_parse_off, out, err);
}

gm_status gm_mesh_read_max(const char *path, size_t max_bytes, gm_mesh **out, gm_error *err) {
  if (path == NULL) return gm_error_set(err, GM_EINVAL, "NULL path");
  size_t n = strlen(path);
  if (n >= 4 && strcmp(path + n - 4, ".msh") == 0)
    return read_with(path, max_bytes, gm_mesh_parse_msh, out, err);
  if (n >= 4 && strcmp(path + n - 4, ".off") == 0)
    return read_with(path, max_bytes, gm_mesh_parse_off, out, err);
  return gm_error_set(err, GM_EINVAL, "%s: unknown mesh file extension (.msh and .off are read)", path);
}

gm_status gm_mesh_read(const char *path, gm_mesh **out, gm_error *err) {
  return gm_mesh_read_max(path, GM_MESH_MAX_FILE_BYTES, out, err);
}
