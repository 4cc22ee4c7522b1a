/* The Yee solver over MPI (geomint/fields_mpi.h): blocks of cells on a Cartesian process grid,
 * each an ordinary gm_yee with one overlap cell towards every neighbouring rank.
 *
 * Why one overlap cell and one exchange per step suffice (for bitwise equality with the whole
 * domain): in a block whose cells run from global cell c0 − 1 (overlap) to c1 (overlap), every
 * update reads only locations inside the block except tangential E on the outermost vertex
 * planes (c0 − 1 and c1 + 1), whose curl needs H half a cell further out. Those planes are the
 * block's artificial PEC faces (held at 0 by the local solver) and are overwritten after each E
 * half step by the neighbour's values, which it computed in its own interior. If all of E and H
 * in the block equal the whole-domain values before a step, the E update gives the right E
 * everywhere but on those planes, the exchange fixes them (axis after axis: a plane sent along
 * y already holds the x neighbours' values at its x ends, so corners are right), and the H update
 * then reads only right values. Hodge-star coefficients come from the same cells (the overlap
 * cells carry their materials), in the same order, so every value rounds as it would in one
 * process. Locations on the vertex plane shared by two blocks are computed by both. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fields/internal.h"
#include "geomint/fields_mpi.h"
#include "geomint/yee_checkpoint.h"

typedef struct mpi_probe {
  int owner;        /* rank holding the location */
  size_t local_id;  /* its probe id there */
  size_t capacity;
  size_t recorded;  /* samples so far (tracked on every rank, for the capacity check) */
} mpi_probe;

struct gm_yee_mpi {
  MPI_Comm comm;   /* the Cartesian communicator (owned) */
  int rank, size;
  int dims[3], coords[3];
  int nb[3][2];    /* neighbour ranks (MPI_PROC_NULL: none) */
  int n_axes;
  gm_yee_grid grid;       /* the whole grid */
  gm_yee_options opt;     /* the whole grid's options, dt resolved */
  int periodic[3];
  size_t c0[3], c1[3];    /* owned cells [c0, c1) */
  size_t ov[3][2];        /* overlap cells below / above (0 or 1) */
  gm_yee *local;
  /* exchange: per axis and side, send and receive buffers of the tangential E planes */
  size_t plane[3];        /* entries of one plane normal to the axis (local extents) */
  double *sbuf[3][2], *rbuf[3][2];
  int coupled;            /* subpixel smoothing with materials: E_a of the overlap cells too */
  yee_view view;          /* the whole grid, for the blocks' smoothing (yee_view.c) */
  size_t bytes_per_step;
  size_t n_sources;
  size_t n_probes;
  mpi_probe *probes;
  double *gather[3];      /* rank 0: t, re, im of the last gathered probe */
  char errmsg[GM_ERRMSG_SIZE];
};

/* ---- agreement: one failure stops every rank with one message ---------------------------- */

/* Every rank passes its status and message; the lowest failing rank's status and message
 * (prefixed by its rank when the communicator has several) are returned on all ranks. */
static gm_status agree(MPI_Comm comm, gm_status st, char *msg, size_t cap) {
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int mine = st != GM_OK ? rank : size;
  int first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size) return GM_OK;
  int code = (int)st;
  if (rank == first && size > 1) {
    char tmp[GM_ERRMSG_SIZE];
    snprintf(tmp, sizeof tmp, "rank %d: %s", rank, msg);
    snprintf(msg, cap, "%s", tmp);
  }
  MPI_Bcast(&code, 1, MPI_INT, first, comm);
  MPI_Bcast(msg, (int)cap, MPI_CHAR, first, comm);
  msg[cap - 1] = '\0';
  return (gm_status)code;
}

static gm_status agree_m(gm_yee_mpi *m, gm_status st) {
  return agree(m->comm, st, m->errmsg, sizeof m->errmsg);
}

/* ---- the exchange ------------------------------------------------------------------------ */

/* Copy the plane of component c normal to axis a at local vertex index v to/from buf. */
static void plane_copy(gm_yee *s, int part, int c, int a, long v, double *buf, int pack) {
  const gm_yee_layout *L = &s->L;
  const int b = (a + 1) % 3, d = (a + 2) % 3;
  const long ob = (long)L->offset[b], od = (long)L->offset[d];
  double *f = s->f[part][c];
  size_t l = 0;
  for (long w = -od; w < (long)L->extent[d] - od; ++w)
    for (long u = -ob; u < (long)L->extent[b] - ob; ++u, ++l) {
      long p[3];
      p[a] = v;
      p[b] = u;
      p[d] = w;
      const size_t q = yee_idx(L, p[0], p[1], p[2]);
      if (pack)
        buf[l] = f[q];
      else
        f[q] = buf[l];
    }
}

/* The planes of axis a in a buffer: for each part, each active E component tangential to a on
 * vertex plane v, and with subpixel smoothing also E_a on cell plane v_cell (its off-diagonal
 * coupling reaches D on the overlap plane, which a block does not update: see exchange_e). */
static size_t pack_planes(gm_yee_mpi *m, int a, long v, long v_cell, double *buf, int pack) {
  gm_yee *s = m->local;
  size_t off = 0;
  for (int p = 0; p < s->n_parts; ++p)
    for (int c = 0; c < 3; ++c) {
      if (!s->active[c] || (c == a && !m->coupled)) continue;
      plane_copy(s, p, c, a, c == a ? v_cell : v, buf + off, pack);
      off += m->plane[a];
    }
  return off;
}

/* After the E half step: tangential E on the outer vertex planes from the neighbours, one axis
 * after the other (non-blocking sends and receives within an axis). With n local cells (vertex
 * planes 0..n), plane 0 is the low overlap plane (global c0 − 1) and plane n the high one
 * (global c1 + 1); the neighbours need global c0 + 1 (local 2) and c1 − 1 (local n − 2).
 * With subpixel smoothing the off-diagonal coupling (yee_aniso.c) of E_a in the overlap cells
 * (local cells 0 and n − 1) misses D on the overlap planes: those E_a come from the neighbours
 * too (their cells c0 and c1 − 1: local 1 and n − 2), and E_saved is reset to the received E so
 * that D keeps summing the right increments. Every other value is computed as in one process. */
static void exchange_e(void *ctx, gm_yee *s) {
  gm_yee_mpi *m = ctx;
  for (int a = 0; a < m->n_axes; ++a) {
    if (m->dims[a] == 1) continue;
    const long n = (long)s->L.n[a];
    MPI_Request req[4];
    size_t cnt = 0;
    for (int side = 0; side < 2; ++side) {
      const long v = side == 0 ? 2 : n - 2;
      cnt = pack_planes(m, a, v, side == 0 ? 1 : n - 2, m->sbuf[a][side], 1);
    }
    for (int side = 0; side < 2; ++side)
      MPI_Irecv(m->rbuf[a][side], (int)cnt, MPI_DOUBLE, m->nb[a][side], 1 - side, m->comm,
                &req[side]);
    /* tag: 0 travels down (to the low neighbour), 1 travels up */
    for (int side = 0; side < 2; ++side)
      MPI_Isend(m->sbuf[a][side], (int)cnt, MPI_DOUBLE, m->nb[a][side], side, m->comm,
                &req[2 + side]);
    MPI_Waitall(4, req, MPI_STATUSES_IGNORE);
    for (int side = 0; side < 2; ++side)
      if (m->nb[a][side] != MPI_PROC_NULL)
        pack_planes(m, a, side == 0 ? 0 : n, side == 0 ? 0 : n - 1, m->rbuf[a][side], 0);
  }
  yee_aniso_resave(s);
}

/* ---- creation ---------------------------------------------------------------------------- */

static int bad_dims(const int *dims) { return dims == NULL || (!dims[0] && !dims[1] && !dims[2]); }

/* The whole grid's grid and options as doubles, to check that every rank passed the same. */
static size_t fingerprint(const gm_yee_grid *g, const gm_yee_options *o, double *v) {
  size_t k = 0;
  v[k++] = (double)g->dim;
  for (int a = 0; a < 3; ++a) {
    v[k++] = (double)g->n[a];
    v[k++] = g->h[a];
    v[k++] = g->origin[a];
    v[k++] = o->bloch_k[a];
  }
  v[k++] = o->dt;
  v[k++] = o->courant;
  for (int f = 0; f < 6; ++f) {
    const gm_cpml *p = &o->boundary[f].pml;
    v[k++] = (double)o->boundary[f].kind;
    v[k++] = (double)p->thickness;
    v[k++] = p->grading;
    v[k++] = p->sigma_max;
    v[k++] = p->sigma_factor;
    v[k++] = p->kappa_max;
    v[k++] = p->alpha_max;
    v[k++] = p->alpha_grading;
  }
  return k;
}

/* σ_max of a CPML face as the whole-domain solver computes it (yee_cpml.c: σ_opt of the cell at
 * the face's centre just inside the layer), so that every rank's layer has the same profile. */
static double whole_sigma_max(const gm_yee_mpi *m, const gm_yee_materials *mat, int f) {
  const gm_cpml *p = &m->opt.boundary[f].pml;
  if (p->sigma_max > 0.0) return p->sigma_max;
  const int a = f / 2;
  double eps = 1.0, mu = 1.0;
  if (mat != NULL) {
    const double *E = gm_yee_materials_epsilon(mat), *M = gm_yee_materials_mu(mat);
    const double *S = gm_yee_materials_sigma(mat);
    const size_t nc = gm_yee_materials_n_cells(mat);
    int uniform = 1;
    for (size_t c = 0; c < nc && uniform; ++c)
      uniform = E[c] == E[0] && M[c] == M[0] && S[c] == S[0];
    size_t n[3], ijk[3];
    for (int b = 0; b < 3; ++b) n[b] = b < m->n_axes ? m->grid.n[b] : 1;
    for (int b = 0; b < 3; ++b) ijk[b] = n[b] / 2;
    ijk[a] = (f % 2 == 0) ? p->thickness : n[a] - 1 - p->thickness;
    const size_t c = uniform ? 0 : ijk[0] + n[0] * (ijk[1] + n[1] * ijk[2]);
    eps = E[c];
    mu = M[c];
  }
  return p->sigma_factor * 0.8 * (p->grading + 1.0) / (m->grid.h[a] * sqrt(eps * mu));
}

/* Split the cells of each axis in blocks and find the neighbours. */
static gm_status decompose(gm_yee_mpi *m, MPI_Comm comm, const int *dims_in) {
  int dims[3] = {1, 1, 1}, periods[3] = {0, 0, 0};
  for (int a = 0; a < m->n_axes; ++a) {
    dims[a] = bad_dims(dims_in) ? 0 : dims_in[a];
    if (dims[a] < 0)
      return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "yee mpi: dims[%d] = %d < 0", a,
                     dims[a]);
    if (m->opt.bloch_k[a] != 0.0) {
      if (dims[a] > 1)
        return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                       "yee mpi: a Bloch k along axis %d needs 1 rank along it (dims[%d] = %d)",
                       a, a, dims[a]);
      dims[a] = 1;
    }
    periods[a] = m->periodic[a];
  }
  int prod = 1, any_free = 0;
  for (int a = 0; a < m->n_axes; ++a) {
    prod *= dims[a] > 0 ? dims[a] : 1;
    any_free |= dims[a] == 0;
  }
  if (any_free ? m->size % prod != 0 : prod != m->size)
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                   "yee mpi: dims %d x %d x %d do not fit the %d ranks", dims[0], dims[1],
                   dims[2], m->size);
  /* the axes left at 0 get MPI's balanced factors */
  if (any_free && MPI_Dims_create(m->size, m->n_axes, dims) != MPI_SUCCESS)
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "yee mpi: MPI_Dims_create failed");
  for (int a = 0; a < m->n_axes; ++a)
    if ((size_t)dims[a] > m->grid.n[a])
      return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                     "yee mpi: %d ranks along axis %d but only %zu cells", dims[a], a,
                     m->grid.n[a]);
  if (MPI_Cart_create(comm, m->n_axes, dims, periods, 0, &m->comm) != MPI_SUCCESS)
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "yee mpi: MPI_Cart_create failed");
  MPI_Comm_rank(m->comm, &m->rank);
  int coords[3] = {0, 0, 0};
  MPI_Cart_coords(m->comm, m->rank, m->n_axes, coords);
  for (int a = 0; a < 3; ++a) {
    m->dims[a] = dims[a];
    m->coords[a] = coords[a];
    m->nb[a][0] = m->nb[a][1] = MPI_PROC_NULL;
    const size_t n = a < m->n_axes ? m->grid.n[a] : 1;
    m->c0[a] = n * (size_t)coords[a] / (size_t)dims[a];
    m->c1[a] = n * (size_t)(coords[a] + 1) / (size_t)dims[a];
    if (a < m->n_axes && dims[a] > 1) MPI_Cart_shift(m->comm, a, 1, &m->nb[a][0], &m->nb[a][1]);
    m->ov[a][0] = m->nb[a][0] != MPI_PROC_NULL;
    m->ov[a][1] = m->nb[a][1] != MPI_PROC_NULL;
  }
  return GM_OK;
}

/* The local grid, options and materials of this rank's block. */
static gm_status make_local(gm_yee_mpi *m, const gm_yee_materials *mat, gm_error *err) {
  gm_yee_grid lg = m->grid;
  gm_yee_options lo = m->opt;
  lo.sweep = GM_YEE_SWEEP_HALF_STEPS; /* the exchange sits between the two half steps */
  size_t ln[3] = {1, 1, 1};
  for (int a = 0; a < m->n_axes; ++a) {
    ln[a] = m->c1[a] - m->c0[a] + m->ov[a][0] + m->ov[a][1];
    lg.n[a] = ln[a];
    lg.origin[a] = m->grid.origin[a] + m->grid.h[a] * ((double)m->c0[a] - (double)m->ov[a][0]);
    for (int side = 0; side < 2; ++side) {
      const int f = 2 * a + side;
      if (m->ov[a][side]) {
        lo.boundary[f].kind = GM_BOUNDARY_PEC; /* overwritten by the exchange */
      } else if (lo.boundary[f].kind == GM_BOUNDARY_CPML) {
        const size_t owned = m->c1[a] - m->c0[a];
        if (m->dims[a] > 1 && owned < lo.boundary[f].pml.thickness + 1)
          return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                         "yee mpi: the CPML on face %c%c is %zu cells thick but this rank owns "
                         "%zu cells along it (it must own the layer and one cell more: use "
                         "fewer ranks along %c)",
                         side ? '+' : '-', "xyz"[a], lo.boundary[f].pml.thickness, owned,
                         "xyz"[a]);
        lo.boundary[f].pml.sigma_max = whole_sigma_max(m, mat, f);
      }
    }
  }
  gm_yee_materials *lm = NULL;
  int cells = 0;
  gm_status st = GM_OK;
  if (mat != NULL) {
    const double *E = gm_yee_materials_epsilon(mat), *M = gm_yee_materials_mu(mat);
    const double *S = gm_yee_materials_sigma(mat);
    const size_t nc = gm_yee_materials_n_cells(mat);
    for (size_t c = 0; c < nc && !cells; ++c)
      cells = E[c] != E[0] || M[c] != M[0] || S[c] != S[0];
    const size_t n_loc = ln[0] * ln[1] * ln[2];
    double *buf = malloc(3 * n_loc * sizeof(double) + 1);
    if (buf == NULL) return gm_fail(m->errmsg, sizeof m->errmsg, GM_ENOMEM, "yee mpi: out of memory");
    size_t gn[3];
    for (int a = 0; a < 3; ++a) gn[a] = a < m->n_axes ? m->grid.n[a] : 1;
    size_t l = 0;
    for (size_t k = 0; k < ln[2]; ++k)
      for (size_t j = 0; j < ln[1]; ++j)
        for (size_t i = 0; i < ln[0]; ++i, ++l) {
          const size_t loc[3] = {i, j, k};
          size_t g[3];
          for (int a = 0; a < 3; ++a) {
            const long x = (long)m->c0[a] - (long)m->ov[a][0] + (long)loc[a];
            g[a] = (size_t)((x % (long)gn[a] + (long)gn[a]) % (long)gn[a]); /* periodic wrap */
          }
          const size_t q = g[0] + gn[0] * (g[1] + gn[1] * g[2]);
          buf[l] = E[q];
          buf[n_loc + l] = M[q];
          buf[2 * n_loc + l] = S[q];
        }
    st = gm_yee_materials_create(&lg, &lm, err);
    if (st == GM_OK) {
      st = gm_yee_paint_cells(lm, buf, buf + n_loc, buf + 2 * n_loc);
      if (st != GM_OK) gm_error_set(err, st, "%s", gm_yee_materials_errmsg(lm));
    }
    free(buf);
  }
  const yee_view *view = NULL;
  if (mat != NULL && m->opt.smoothing == GM_YEE_SMOOTHING_ANISOTROPIC) {
    /* smoothing reads the whole grid's shapes at global indices (yee_view.c) */
    gm_yee_mpi_global_layout(m, &m->view.L);
    m->view.materials = mat;
    m->view.opt = m->opt;
    for (int a = 0; a < 3; ++a) {
      m->view.periodic[a] = m->periodic[a];
      m->view.offset[a] = (long)m->c0[a] - (long)m->ov[a][0];
    }
    view = &m->view;
  }
  if (st == GM_OK) st = yee_create_view(&lg, lm, &lo, cells, view, &m->local, err);
  gm_yee_materials_free(lm);
  if (st != GM_OK) snprintf(m->errmsg, sizeof m->errmsg, "%s", err->message);
  return st;
}

static gm_status alloc_buffers(gm_yee_mpi *m) {
  gm_yee *s = m->local;
  m->bytes_per_step = 0;
  for (int a = 0; a < m->n_axes; ++a) {
    const int b = (a + 1) % 3, d = (a + 2) % 3;
    m->plane[a] = s->L.extent[b] * s->L.extent[d];
    size_t n_comp = 0;
    for (int c = 0; c < 3; ++c) n_comp += (c != a || m->coupled) && s->active[c];
    const size_t len = m->plane[a] * n_comp * (size_t)s->n_parts;
    for (int side = 0; side < 2; ++side) {
      m->sbuf[a][side] = malloc(len * sizeof(double) + 1);
      m->rbuf[a][side] = malloc(len * sizeof(double) + 1);
      if (m->sbuf[a][side] == NULL || m->rbuf[a][side] == NULL)
        return gm_fail(m->errmsg, sizeof m->errmsg, GM_ENOMEM, "yee mpi: out of memory");
      if (m->nb[a][side] != MPI_PROC_NULL) m->bytes_per_step += len * sizeof(double);
    }
  }
  return GM_OK;
}

gm_status gm_yee_mpi_create(const gm_yee_grid *grid, const gm_yee_materials *materials,
                            const gm_yee_options *options, MPI_Comm comm, const int dims[3],
                            gm_yee_mpi **out, gm_error *err) {
  gm_error local_err = {{0}};
  if (err == NULL) err = &local_err;
  if (out == NULL || grid == NULL) return gm_error_set(err, GM_EINVAL, "yee mpi: NULL argument");
  *out = NULL;
  gm_yee_mpi *m = calloc(1, sizeof *m);
  int ok = m != NULL;
  int all_ok = 0;
  MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, comm);
  if (!all_ok) {
    free(m);
    return gm_error_set(err, GM_ENOMEM, "yee mpi: out of memory on a rank");
  }
  m->comm = MPI_COMM_NULL;
  MPI_Comm_size(comm, &m->size);
  MPI_Comm_rank(comm, &m->rank);
  m->grid = *grid;
  m->opt = options ? *options : gm_yee_defaults();
  /* the whole grid's checks and step (the Courant limit of all cells, not of a block) */
  double dt_max = 0.0;
  gm_status st = gm_yee_courant_limit(grid, materials, &dt_max, err);
  if (st == GM_OK) {
    snprintf(m->errmsg, sizeof m->errmsg, "%s", "");
    m->n_axes = (int)gm_yee_dim_axes(grid->dim);
    if (m->opt.dt <= 0.0 && m->opt.courant > 0.0 && m->opt.courant <= 1.0)
      m->opt.dt = m->opt.courant * dt_max;
    if (m->opt.dt > dt_max)
      st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                   "yee: time step %.17g is above the Courant limit %.17g of this grid "
                   "(dt <= 1/(c_max sqrt(sum 1/h^2)))",
                   m->opt.dt, dt_max);
    /* subpixel smoothing: each block reads the whole grid's shapes (make_local) */
    m->coupled = materials != NULL && m->opt.smoothing == GM_YEE_SMOOTHING_ANISOTROPIC &&
                 m->n_axes >= 2;
    /* Dispersive poles (yee_dispersive.c) keep per-edge state the blocks do not split yet. */
    if (materials != NULL && gm_yee_materials_n_dispersive(materials) > 0)
      st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EUNSUPPORTED,
                   "yee mpi: dispersive media (Drude/Lorentz poles) are serial only; run "
                   "without mpirun");
    if (materials != NULL) {
      const gm_yee_grid *mg = &materials->grid;
      for (int a = 0; a < m->n_axes; ++a)
        if (mg->dim != grid->dim || mg->n[a] != grid->n[a])
          st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                       "yee: the materials were made for another grid");
    }
    for (int a = 0; a < m->n_axes; ++a) {
      const int lo = m->opt.boundary[2 * a].kind == GM_BOUNDARY_PERIODIC;
      const int hi = m->opt.boundary[2 * a + 1].kind == GM_BOUNDARY_PERIODIC;
      if (lo != hi)
        st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                     "yee: periodic boundary on one %c face only: both must be periodic",
                     "xyz"[a]);
      m->periodic[a] = lo && hi;
    }
  } else {
    snprintf(m->errmsg, sizeof m->errmsg, "%s", err->message);
  }
  /* every rank must describe the same problem */
  if (st == GM_OK) {
    double mine[64], root[64];
    const size_t k = fingerprint(grid, &m->opt, mine);
    memcpy(root, mine, sizeof mine);
    MPI_Bcast(root, (int)k, MPI_DOUBLE, 0, comm);
    for (size_t i = 0; i < k && st == GM_OK; ++i)
      if (!(mine[i] == root[i] || (isnan(mine[i]) && isnan(root[i]))))
        st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                     "yee mpi: the grid or options differ from rank 0's (item %zu: %g vs %g)", i,
                     mine[i], root[i]);
  }
  st = agree(comm, st, m->errmsg, sizeof m->errmsg);
  if (st == GM_OK) st = agree(comm, decompose(m, comm, dims), m->errmsg, sizeof m->errmsg);
  if (st == GM_OK) st = agree_m(m, make_local(m, materials, err));
  if (st == GM_OK) st = agree_m(m, alloc_buffers(m));
  if (st != GM_OK) {
    gm_error_set(err, st, "%s", m->errmsg);
    gm_yee_mpi_free(m);
    return st;
  }
  m->local->exchange_e = exchange_e;
  m->local->exchange_ctx = m;
  *out = m;
  return GM_OK;
}

void gm_yee_mpi_free(gm_yee_mpi *m) {
  if (m == NULL) return;
  gm_yee_free(m->local);
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      free(m->sbuf[a][side]);
      free(m->rbuf[a][side]);
    }
  for (int i = 0; i < 3; ++i) free(m->gather[i]);
  free(m->probes);
  if (m->comm != MPI_COMM_NULL) MPI_Comm_free(&m->comm);
  free(m);
}

const char *gm_yee_mpi_errmsg(const gm_yee_mpi *m) { return m ? m->errmsg : ""; }
const gm_yee *gm_yee_mpi_local(const gm_yee_mpi *m) { return m->local; }
int gm_yee_mpi_rank(const gm_yee_mpi *m) { return m->rank; }
double gm_yee_mpi_dt(const gm_yee_mpi *m) { return m->local->dt; }
size_t gm_yee_mpi_step(const gm_yee_mpi *m) { return m->local->step; }
size_t gm_yee_mpi_bytes_per_step(const gm_yee_mpi *m) { return m->bytes_per_step; }

void gm_yee_mpi_block(const gm_yee_mpi *m, int dims[3], int coords[3], size_t first[3],
                      size_t owned[3], long local_origin[3]) {
  for (int a = 0; a < 3; ++a) {
    if (dims) dims[a] = m->dims[a];
    if (coords) coords[a] = m->coords[a];
    if (first) first[a] = m->c0[a];
    if (owned) owned[a] = m->c1[a] - m->c0[a];
    if (local_origin) local_origin[a] = (long)m->c0[a] - (long)m->ov[a][0];
  }
}

/* ---- locations: the whole grid's index space ---------------------------------------------- */

void gm_yee_mpi_global_layout(const gm_yee_mpi *m, gm_yee_layout *L) {
  memset(L, 0, sizeof *L);
  L->dim = m->grid.dim;
  size_t stride = 1;
  for (int a = 0; a < 3; ++a) {
    const int present = a < m->n_axes;
    L->n[a] = present ? m->grid.n[a] : 1;
    L->h[a] = present ? m->grid.h[a] : 1.0;
    L->origin[a] = m->grid.origin[a];
    L->extent[a] = present ? m->grid.n[a] + 2 : 1;
    L->offset[a] = present ? 1 : 0;
    L->stride[a] = stride;
    stride *= L->extent[a];
  }
  L->size = stride;
  L->complex_fields = m->opt.bloch_k[0] != 0.0 || m->opt.bloch_k[1] != 0.0 ||
                      m->opt.bloch_k[2] != 0.0; /* as gm_yee_create (also before m->local) */
}

/* The whole grid's location of c nearest to x (yee_locate's rule); -1 when outside. */
static int global_locate(const gm_yee_mpi *m, int c, const double x[3], long ijk[3]) {
  gm_yee_layout L;
  gm_yee_mpi_global_layout(m, &L);
  double sh[3];
  size_t cnt[3];
  gm_yee_component_shift(L.dim, (gm_yee_component)c, sh);
  gm_yee_component_count(&L, (gm_yee_component)c, cnt);
  for (int a = 0; a < 3; ++a) {
    if (a >= m->n_axes) {
      ijk[a] = 0;
      continue;
    }
    if (!isfinite(x[a])) return -1;
    const double r = (x[a] - L.origin[a]) / L.h[a] - sh[a];
    const double idx = floor(r + 0.5);
    if (idx < 0.0 || idx > (double)cnt[a] - 1.0) return -1;
    ijk[a] = (long)idx;
  }
  return 0;
}

/* Coordinates of the local location ijk of c. */
static void local_position(const gm_yee *s, int c, const long ijk[3], double x[3]) {
  double sh[3];
  gm_yee_component_shift(s->L.dim, (gm_yee_component)c, sh);
  for (int a = 0; a < 3; ++a)
    x[a] = a < s->n_axes ? s->L.origin[a] + ((double)ijk[a] + sh[a]) * s->L.h[a] : 0.0;
}

static int local_updated(const gm_yee *s, int c, const long ijk[3]) {
  for (int a = 0; a < 3; ++a) {
    const long lo = (long)s->upd[c].lo[a];
    if (ijk[a] < lo || ijk[a] >= lo + (long)s->upd[c].cnt[a]) return 0;
  }
  return 1;
}

/* Is the whole-grid location g updated by the whole-domain solver (update_ranges' rule)? */
static int global_updated(const gm_yee_mpi *m, int c, const long g[3]) {
  double sh[3];
  gm_yee_component_shift(m->grid.dim, (gm_yee_component)c, sh);
  for (int a = 0; a < m->n_axes; ++a) {
    if (sh[a] > 0.0) continue;
    const long n = (long)m->grid.n[a];
    const gm_yee_boundary_kind lo = m->opt.boundary[2 * a].kind;
    const gm_yee_boundary_kind hi = m->opt.boundary[2 * a + 1].kind;
    if (m->periodic[a]) {
      if (g[a] >= n) return 0;
    } else if (yee_is_e(c)) {
      if (g[a] == 0 && (lo == GM_BOUNDARY_PEC || lo == GM_BOUNDARY_CPML)) return 0;
      if (g[a] == n && (hi == GM_BOUNDARY_PEC || hi == GM_BOUNDARY_CPML)) return 0;
    }
  }
  return 1;
}

/* Does this rank own location g of c (exactly one rank does)? Shared vertex planes go to the
 * upper block; the last vertex plane to the last. */
static int owns(const gm_yee_mpi *m, const long g[3], long loc[3]) {
  for (int a = 0; a < 3; ++a) {
    loc[a] = a < m->n_axes ? g[a] - ((long)m->c0[a] - (long)m->ov[a][0]) : 0;
    if (a >= m->n_axes) continue;
    const int in = (g[a] >= (long)m->c0[a] && g[a] < (long)m->c1[a]) ||
                   (g[a] == (long)m->c1[a] && m->c1[a] == m->grid.n[a]);
    if (!in) return 0;
  }
  return 1;
}

/* ---- sources, probes, fields ------------------------------------------------------------- */

gm_status gm_yee_mpi_add_point_source(gm_yee_mpi *m, const gm_point_source *ps, size_t *id) {
  if (m == NULL) return GM_EINVAL;
  gm_status st = GM_OK;
  const int c = ps ? (int)ps->component : -1;
  long g[3];
  gm_error e;
  if (ps == NULL || (unsigned)c >= GM_YEE_N_COMPONENTS || !m->local->active[c])
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                 "point source: this grid has no component %d", c);
  else if (gm_waveform_check(&ps->wave, &e) != GM_OK)
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "point source: %s", e.message);
  else if (global_locate(m, c, ps->x, g) != 0)
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                 "point source: (%g, %g, %g) is outside the grid", ps->x[0], ps->x[1], ps->x[2]);
  else if (!global_updated(m, c, g))
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                 "point source: (%g, %g, %g) is on a PEC face (or the copy of a periodic one), "
                 "where %s is never updated",
                 ps->x[0], ps->x[1], ps->x[2], gm_yee_component_name(ps->component));
  /* every image of the location in this block (a periodic split axis also holds it at g ± n) */
  for (int img = 0; st == GM_OK && img < 27; ++img) {
    const long shift[3] = {img % 3 - 1, (img / 3) % 3 - 1, img / 9 - 1};
    long loc[3];
    int inside = 1;
    for (int a = 0; a < 3; ++a) {
      if (shift[a] != 0 && (a >= m->n_axes || !m->periodic[a] || m->dims[a] == 1)) inside = 0;
      const long base = a < m->n_axes ? (long)m->c0[a] - (long)m->ov[a][0] : 0;
      loc[a] = g[a] + shift[a] * (a < m->n_axes ? (long)m->grid.n[a] : 0) - base;
    }
    if (!inside || !local_updated(m->local, c, loc)) continue;
    gm_point_source p = *ps;
    local_position(m->local, c, loc, p.x);
    if (gm_yee_add_point_source(m->local, &p, NULL) != GM_OK)
      st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "%s", gm_yee_errmsg(m->local));
  }
  st = agree_m(m, st);
  if (st == GM_OK && id) *id = m->n_sources;
  if (st == GM_OK) ++m->n_sources;
  return st;
}

gm_status gm_yee_mpi_add_probe(gm_yee_mpi *m, gm_yee_component c, const double x[3],
                               size_t capacity, size_t *id) {
  if (m == NULL) return GM_EINVAL;
  gm_status st = GM_OK;
  long g[3], loc[3];
  int mine = 0;
  size_t lid = 0;
  if ((unsigned)c >= GM_YEE_N_COMPONENTS || !m->local->active[c])
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "probe: this grid has no component %d",
                 (int)c);
  else if (x == NULL || global_locate(m, (int)c, x, g) != 0)
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "probe: (%g, %g, %g) is outside the grid",
                 x ? x[0] : NAN, x ? x[1] : NAN, x ? x[2] : NAN);
  else if (owns(m, g, loc)) {
    double p[3];
    local_position(m->local, (int)c, loc, p);
    mine = 1;
    if (gm_yee_add_probe(m->local, c, p, capacity, &lid) != GM_OK)
      st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "%s", gm_yee_errmsg(m->local));
  }
  mpi_probe *grown = realloc(m->probes, (m->n_probes + 1) * sizeof *grown);
  if (st == GM_OK && grown == NULL)
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_ENOMEM, "probe: out of memory");
  if (grown) m->probes = grown;
  st = agree_m(m, st);
  if (st != GM_OK) return st;
  int owner = mine ? m->rank : m->size;
  int who = 0;
  MPI_Allreduce(&owner, &who, 1, MPI_INT, MPI_MIN, m->comm);
  unsigned long lid_all = (unsigned long)lid;
  MPI_Bcast(&lid_all, 1, MPI_UNSIGNED_LONG, who, m->comm);
  m->probes[m->n_probes] = (mpi_probe){who, (size_t)lid_all, capacity, 0};
  if (id) *id = m->n_probes;
  ++m->n_probes;
  return GM_OK;
}

gm_status gm_yee_mpi_probe_samples(gm_yee_mpi *m, size_t id, size_t *n, const double **t,
                                   const double **re, const double **im) {
  if (m == NULL || id >= m->n_probes) return GM_EINVAL;
  const mpi_probe *p = &m->probes[id];
  const int parts = m->local->n_parts;
  size_t cnt = 0;
  const double *arr[3] = {NULL, NULL, NULL};
  if (m->rank == p->owner) gm_yee_probe_samples(m->local, p->local_id, &cnt, &arr[0], &arr[1], &arr[2]);
  unsigned long cl = (unsigned long)cnt;
  MPI_Bcast(&cl, 1, MPI_UNSIGNED_LONG, p->owner, m->comm);
  cnt = (size_t)cl;
  gm_status st = GM_OK;
  if (m->rank == 0 && p->owner != 0) {
    for (int i = 0; i < 1 + parts; ++i) {
      free(m->gather[i]);
      m->gather[i] = malloc(cnt * sizeof(double) + 1);
      if (m->gather[i] == NULL) st = GM_ENOMEM;
    }
  }
  /* a failed allocation on rank 0 still receives (into nothing) to keep the ranks in step */
  for (int i = 0; i < 1 + parts; ++i) {
    if (p->owner == 0) break;
    if (m->rank == p->owner)
      MPI_Send(arr[i], (int)cnt, MPI_DOUBLE, 0, 7, m->comm);
    else if (m->rank == 0)
      MPI_Recv(m->gather[i] ? m->gather[i] : MPI_BOTTOM, m->gather[i] ? (int)cnt : 0,
               MPI_DOUBLE, p->owner, 7, m->comm, MPI_STATUS_IGNORE);
  }
  if (st != GM_OK) snprintf(m->errmsg, sizeof m->errmsg, "probe: out of memory on rank 0");
  st = agree_m(m, st);
  if (st != GM_OK) return st;
  if (m->rank != 0) {
    if (n) *n = 0;
    if (t) *t = NULL;
    if (re) *re = NULL;
    if (im) *im = NULL;
    return GM_OK;
  }
  const double *const *src = p->owner == 0 ? arr : (const double *const *)m->gather;
  if (n) *n = cnt;
  if (t) *t = src[0];
  if (re) *re = src[1];
  if (im) *im = parts == 2 ? src[2] : NULL;
  return GM_OK;
}

gm_status gm_yee_mpi_set_field_fn(gm_yee_mpi *m, gm_yee_component c, int part,
                                  double (*f)(void *ctx, const double x[3]), void *ctx) {
  if (m == NULL) return GM_EINVAL;
  gm_yee *s = m->local;
  gm_status st = GM_OK;
  if ((unsigned)c >= GM_YEE_N_COMPONENTS || !s->active[c] || part < 0 || part >= s->n_parts ||
      f == NULL)
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                 "set field: no component %d part %d (or no function)", (int)c, part);
  double *v = st == GM_OK ? calloc(s->L.size, sizeof(double)) : NULL;
  if (st == GM_OK && v == NULL)
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_ENOMEM, "set field: out of memory");
  if (st == GM_OK) {
    /* f at the whole grid's coordinates of each location (a block's own origin would round
     * differently); periodic axes wrap, as the whole grid's copy of node 0 at node n */
    double sh[3];
    size_t cnt[3];
    gm_yee_component_shift(s->L.dim, c, sh);
    gm_yee_component_count(&s->L, c, cnt);
    for (size_t k = 0; k < cnt[2] && st == GM_OK; ++k)
      for (size_t j = 0; j < cnt[1] && st == GM_OK; ++j)
        for (size_t i = 0; i < cnt[0]; ++i) {
          const size_t l[3] = {i, j, k};
          double x[3] = {0.0, 0.0, 0.0};
          for (int a = 0; a < m->n_axes; ++a) {
            long gi = (long)l[a] + (long)m->c0[a] - (long)m->ov[a][0];
            const long n = (long)m->grid.n[a];
            if (m->periodic[a] && m->dims[a] > 1) gi = ((gi % n) + n) % n;
            x[a] = m->grid.origin[a] + ((double)gi + sh[a]) * m->grid.h[a];
          }
          const double y = f(ctx, x);
          if (!isfinite(y)) {
            st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EDOMAIN,
                         "set field: f(%g, %g, %g) is not finite", x[0], x[1], x[2]);
            break;
          }
          v[yee_idx(&s->L, (long)i, (long)j, (long)k)] = y;
        }
  }
  /* walls and ghosts as gm_yee_set_field leaves them (E on the artificial walls is zeroed
   * there, but it is never read before the first exchange overwrites it) */
  if (st == GM_OK && gm_yee_set_field(s, c, part, v) != GM_OK)
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "%s", gm_yee_errmsg(s));
  free(v);
  return agree_m(m, st);
}

gm_status gm_yee_mpi_advance(gm_yee_mpi *m, size_t n_steps) {
  if (m == NULL) return GM_EINVAL;
  /* the probes' room is checked here on every rank alike (a rank must not refuse alone) */
  for (size_t i = 0; i < m->n_probes; ++i)
    if (m->probes[i].recorded + n_steps > m->probes[i].capacity) {
      gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
              "yee: probe %zu holds %zu samples and has %zu; %zu more steps asked", i,
              m->probes[i].capacity, m->probes[i].recorded, n_steps);
      return GM_EINVAL;
    }
  gm_status st = gm_yee_advance(m->local, n_steps);
  if (st != GM_OK) snprintf(m->errmsg, sizeof m->errmsg, "%s", gm_yee_errmsg(m->local));
  st = agree_m(m, st);
  if (st == GM_OK)
    for (size_t i = 0; i < m->n_probes; ++i) m->probes[i].recorded += n_steps;
  return st;
}

/* The box of whole-grid locations of c this rank owns (owns()'s rule). */
static void owned_box(const gm_yee_mpi *m, int c, long lo[3], long cnt[3]) {
  double sh[3];
  gm_yee_component_shift(m->grid.dim, (gm_yee_component)c, sh);
  for (int a = 0; a < 3; ++a) {
    if (a >= m->n_axes) {
      lo[a] = 0;
      cnt[a] = 1;
      continue;
    }
    lo[a] = (long)m->c0[a];
    long hi = (long)m->c1[a];
    if (sh[a] == 0.0 && m->c1[a] == m->grid.n[a]) hi += 1; /* the last vertex plane */
    cnt[a] = hi - lo[a];
  }
}

gm_status gm_yee_mpi_gather_field(gm_yee_mpi *m, gm_yee_component c, int part, double *out) {
  if (m == NULL) return GM_EINVAL;
  gm_yee *s = m->local;
  gm_status st = GM_OK;
  if ((unsigned)c >= GM_YEE_N_COMPONENTS || !s->active[c] || part < 0 || part >= s->n_parts)
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "gather: no component %d part %d",
                 (int)c, part);
  else if (m->rank == 0 && out == NULL)
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "gather: NULL output on rank 0");
  st = agree_m(m, st);
  if (st != GM_OK) return st;
  gm_yee_layout G;
  gm_yee_mpi_global_layout(m, &G);
  long lo[3], cnt[3];
  owned_box(m, (int)c, lo, cnt);
  const size_t n = (size_t)(cnt[0] * cnt[1] * cnt[2]);
  double *buf = malloc(n * sizeof(double) + 1);
  int ok = buf != NULL, all = 0;
  MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, m->comm);
  if (!all) {
    free(buf);
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_ENOMEM, "gather: out of memory");
  }
  size_t l = 0;
  for (long k = 0; k < cnt[2]; ++k)
    for (long j = 0; j < cnt[1]; ++j)
      for (long i = 0; i < cnt[0]; ++i, ++l) {
        const long g[3] = {lo[0] + i, lo[1] + j, lo[2] + k};
        long loc[3];
        for (int a = 0; a < 3; ++a)
          loc[a] = a < m->n_axes ? g[a] - ((long)m->c0[a] - (long)m->ov[a][0]) : 0;
        buf[l] = s->f[part][c][yee_idx(&s->L, loc[0], loc[1], loc[2])];
      }
  if (m->rank != 0) {
    long hdr[6] = {lo[0], lo[1], lo[2], cnt[0], cnt[1], cnt[2]};
    MPI_Send(hdr, 6, MPI_LONG, 0, 11, m->comm);
    MPI_Send(buf, (int)n, MPI_DOUBLE, 0, 12, m->comm);
    free(buf);
    return GM_OK;
  }
  memset(out, 0, G.size * sizeof(double));
  for (int r = 0; r < m->size; ++r) {
    long hdr[6] = {lo[0], lo[1], lo[2], cnt[0], cnt[1], cnt[2]};
    double *rb = buf;
    if (r != 0) {
      MPI_Recv(hdr, 6, MPI_LONG, r, 11, m->comm, MPI_STATUS_IGNORE);
      const size_t rn = (size_t)(hdr[3] * hdr[4] * hdr[5]);
      rb = malloc(rn * sizeof(double) + 1);
      MPI_Recv(rb ? rb : MPI_BOTTOM, rb ? (int)rn : 0, MPI_DOUBLE, r, 12, m->comm,
               MPI_STATUS_IGNORE);
      if (rb == NULL) continue;
    }
    size_t q = 0;
    for (long k = 0; k < hdr[5]; ++k)
      for (long j = 0; j < hdr[4]; ++j)
        for (long i = 0; i < hdr[3]; ++i, ++q)
          out[yee_idx(&G, hdr[0] + i, hdr[1] + j, hdr[2] + k)] = rb[q];
    if (rb != buf) free(rb);
  }
  free(buf);
  return GM_OK;
}

/* ---- energy ------------------------------------------------------------------------------ */

/* Dual volume weight of whole-grid location g (yee_diagnostics.c's rule on the whole grid). */
static double global_dual_weight(const gm_yee_mpi *m, int c, const long g[3]) {
  double sh[3];
  gm_yee_component_shift(m->grid.dim, (gm_yee_component)c, sh);
  const gm_yee *s = m->local;
  double w = s->L.h[0] * s->L.h[1] * s->L.h[2];
  for (int a = 0; a < m->n_axes; ++a) {
    if (sh[a] > 0.0) continue;
    if (m->periodic[a]) {
      if (g[a] == (long)m->grid.n[a]) return 0.0;
    } else if (g[a] == 0 || g[a] == (long)m->grid.n[a]) {
      w *= 0.5;
    }
  }
  return w;
}

gm_status gm_yee_mpi_get_energy(gm_yee_mpi *m, gm_yee_energy *en) {
  if (m == NULL || en == NULL) return GM_EINVAL;
  const gm_yee *s = m->local;
  double sum[3] = {0.0, 0.0, 0.0}; /* we, wh, wl */
  for (int p = 0; p < s->n_parts; ++p)
    for (int c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
      if (!s->active[c]) continue;
      long lo[3], cnt[3];
      owned_box(m, c, lo, cnt);
      const double *f = s->f[p][c];
      for (long k = 0; k < cnt[2]; ++k)
        for (long j = 0; j < cnt[1]; ++j)
          for (long i = 0; i < cnt[0]; ++i) {
            const long g[3] = {lo[0] + i, lo[1] + j, lo[2] + k};
            const double w = global_dual_weight(m, c, g);
            if (w == 0.0) continue;
            long l[3];
            for (int a = 0; a < 3; ++a)
              l[a] = a < m->n_axes ? g[a] - ((long)m->c0[a] - (long)m->ov[a][0]) : 0;
            const size_t q = yee_idx(&s->L, l[0], l[1], l[2]);
            const double v = f[q];
            if (c < 3) {
              sum[0] += w * yee_eps_edge(s, c, l[0], l[1], l[2]) * v * v;
            } else {
              const double mu = yee_mu_face(s, c, l[0], l[1], l[2]);
              sum[1] += w * mu * v * v;
              /* H^{n−1} = H^n + Δt ⋆_μ⁻¹ d E^{n−½}, as gm_yee_get_energy */
              const int A = c - 3, B = (A + 1) % 3, C = (A + 2) % 3;
              const double *Ec = s->f[p][C], *Eb = s->f[p][B];
              const double ib = s->inv_h[B][l[B] + (long)s->L.offset[B]];
              const double ic = s->inv_h[C][l[C] + (long)s->L.offset[C]];
              const double curl = (Ec[q + s->s[B]] - Ec[q]) * ib - (Eb[q + s->s[C]] - Eb[q]) * ic;
              const double cbh = s->cb[c] ? s->cb[c][q] : s->cb0[c];
              sum[2] += w * mu * v * (v + cbh * curl);
            }
          }
    }
  double tot[3];
  MPI_Allreduce(sum, tot, 3, MPI_DOUBLE, MPI_SUM, m->comm);
  en->electric = 0.5 * tot[0];
  en->magnetic = 0.5 * tot[1];
  en->plain = en->electric + en->magnetic;
  en->leapfrog = 0.5 * (tot[0] + tot[2]);
  en->polarization = 0.0; /* dispersive media are refused at create */
  return GM_OK;
}

/* ---- checkpoint/restart ------------------------------------------------------------------- */

static gm_status block_path(gm_yee_mpi *m, const char *prefix, char *path, size_t cap) {
  if (prefix == NULL || snprintf(path, cap, "%s.rank%dof%d", prefix, m->rank, m->size) >= (int)cap)
    return gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL, "checkpoint: bad or too long prefix");
  return GM_OK;
}

gm_status gm_yee_mpi_checkpoint_write(gm_yee_mpi *m, const char *prefix) {
  if (m == NULL) return GM_EINVAL;
  char path[4096];
  gm_status st = block_path(m, prefix, path, sizeof path);
  if (st == GM_OK && (st = gm_yee_checkpoint_write(m->local, path)) != GM_OK)
    snprintf(m->errmsg, sizeof m->errmsg, "%s", gm_yee_errmsg(m->local));
  return agree_m(m, st);
}

gm_status gm_yee_mpi_checkpoint_read(gm_yee_mpi *m, const char *prefix) {
  if (m == NULL) return GM_EINVAL;
  char path[4096];
  gm_status st = block_path(m, prefix, path, sizeof path);
  if (st == GM_OK && (st = gm_yee_checkpoint_read(m->local, path)) != GM_OK)
    snprintf(m->errmsg, sizeof m->errmsg, "%s", gm_yee_errmsg(m->local));
  /* every block must be at the same step */
  unsigned long step = (unsigned long)m->local->step, lo = 0, hi = 0;
  MPI_Allreduce(&step, &lo, 1, MPI_UNSIGNED_LONG, MPI_MIN, m->comm);
  MPI_Allreduce(&step, &hi, 1, MPI_UNSIGNED_LONG, MPI_MAX, m->comm);
  if (st == GM_OK && lo != hi)
    st = gm_fail(m->errmsg, sizeof m->errmsg, GM_EINVAL,
                 "checkpoint: the blocks of %s are at steps %lu to %lu (mixed checkpoints)",
                 prefix, lo, hi);
  st = agree_m(m, st);
  if (st != GM_OK) return st;
  /* the probes' sample counts, known on their owners, for the capacity check */
  for (size_t i = 0; i < m->n_probes; ++i) {
    unsigned long n = 0;
    if (m->rank == m->probes[i].owner) {
      size_t k = 0;
      gm_yee_probe_samples(m->local, m->probes[i].local_id, &k, NULL, NULL, NULL);
      n = (unsigned long)k;
    }
    MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG, m->probes[i].owner, m->comm);
    m->probes[i].recorded = (size_t)n;
  }
  return GM_OK;
}
