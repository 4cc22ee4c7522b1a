/* Off-diagonal entries of the subpixel-smoothed inverse permittivity (yee_smoothing.c).
 *
 * Where an interface cuts the pixel of E_a with a normal n that has components along a and b,
 * ε̃⁻¹ has the entry (ε̃⁻¹)_ab = n_a n_b (⟨ε⁻¹⟩ − ⟨ε⟩⁻¹) (Kottke, Farjadpour & Johnson, PRE 77
 * (2008) 036611, eq. 1). Dropping it leaves a first-order error (the first-order perturbation
 * of a mode's frequency involves D_a (ε̃⁻¹)_ab D_b, non-zero for fields oblique to the
 * interface); with it the error is second order. E_a then depends on D_b, which lives at other
 * locations: as MEEP (Oskooi et al., CPC 181 (2010) 687, §4.3) we use the mean of the four D_b
 * nearest to E_a. The pair (E_a at q, D_b at r) gets ¼ ε̃⁻¹_ab of the pixel centred at their
 * midpoint, both ways, so that E = K D with K symmetric (the leapfrog's energy argument needs
 * it; with ¼ ε̃⁻¹_ab(q) in row q only, as MEEP, a 2-D run with ε = 12 blew up after 2.7·10⁵
 * steps at Courant 0.99; with ⅛ (ε̃⁻¹_ab(q) + ε̃⁻¹_ba(r)) the entry is halved where one end's
 * pixel is not cut, and the order measured 1.80 instead of 2).
 *
 * Implementation: on the coupled edges ("members": cut edges with an off-diagonal entry and the
 * neighbours they couple to) the E update runs with cb = Δt, ca = 1, so after the kernel,
 * CPML, TF/SF and soft-source terms E − E_saved is the increment of D; then
 *   D += E − E_saved,   E = ε̃⁻¹_aa D + Σ_pairs c D_other,   E_saved = E.
 * Lossy (σ > 0) edges, edges in CPML layers and stencils leaving the update range keep the
 * diagonal form (docs/maxwell.md). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fields/internal.h"

struct yee_aniso {
  size_t n;                  /* members */
  size_t start[4];           /* members of component a: [start[a], start[a+1]), q ascending */
  size_t *q;                 /* array index */
  double *kdiag;             /* ε̃⁻¹_aa */
  double *d[2], *esave[2];   /* per part */
  size_t *adj_start;         /* n + 1: CSR of the couplings */
  size_t *adj;               /* member index of the other end */
  double *adj_c;             /* coefficient */
};

static long find_member(const struct yee_aniso *A, int c, size_t q) {
  size_t lo = A->start[c], hi = A->start[c + 1];
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    if (A->q[mid] < q)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < A->start[c + 1] && A->q[lo] == q ? (long)lo : -1;
}

double yee_aniso_eps(const gm_yee *s, int c, size_t q) {
  if (s->aniso == NULL) return 0.0;
  const long m = find_member(s->aniso, c, q);
  return m < 0 ? 0.0 : 1.0 / s->aniso->kdiag[m];
}

void yee_aniso_free(gm_yee *s) {
  struct yee_aniso *A = s->aniso;
  if (A == NULL) return;
  free(A->q);
  free(A->kdiag);
  for (int p = 0; p < 2; ++p) free(A->d[p]), free(A->esave[p]);
  free(A->adj_start);
  free(A->adj);
  free(A->adj_c);
  free(A);
  s->aniso = NULL;
}

/* Is location ijk of E component c one whose update the coupling can take over? */
static int eligible(const gm_yee *s, int c, const long ijk[3]) {
  const yee_box *b = &s->upd[c];
  for (int a = 0; a < 3; ++a)
    if (ijk[a] < (long)b->lo[a] || ijk[a] >= (long)(b->lo[a] + b->cnt[a])) return 0;
  const size_t q = yee_idx(&s->L, ijk[0], ijk[1], ijk[2]);
  if (s->ca[c] && s->ca[c][q] != 1.0) return 0; /* lossy */
  if (yee_dispersive_has(s, c, q)) return 0;      /* its E update is the ADE's (yee_dispersive.c) */
  for (int a = 0; a < s->n_axes; ++a)
    for (int f = 0; f < 2; ++f) {
      const gm_yee_boundary *bd = &s->opt.boundary[2 * a + f];
      if (bd->kind != GM_BOUNDARY_CPML) continue;
      const long t = (long)bd->pml.thickness;
      if (f == 0 ? ijk[a] <= t : ijk[a] >= (long)s->L.n[a] - t) return 0;
    }
  return 1;
}

/* The four locations of D_b nearest to E_a at ijk: along a at i and i + 1, along b at j − 1 and
 * j (E_a sits at i + ½ along a and on the node j along b; D_b the other way round). */
static void neighbours(int a, int b, const long ijk[3], long out[4][3]) {
  for (int t = 0; t < 4; ++t) {
    for (int x = 0; x < 3; ++x) out[t][x] = ijk[x];
    out[t][a] += t & 1;
    out[t][b] -= 1 - ((t >> 1) & 1);
  }
}

typedef struct pair {
  int a, b;      /* components */
  size_t q, r;   /* array indices of E_a and D_b */
  double coef;   /* ¼ ε̃⁻¹_ab at their midpoint */
} pair;

static gm_status oom(gm_error *err) {
  return gm_error_set(err, GM_ENOMEM, "yee: out of memory (subpixel smoothing)");
}

gm_status yee_aniso_setup(gm_yee *s, const gm_yee_materials *m, gm_error *err) {
  if (s->n_axes < 2 || !s->smoothed) return GM_OK;
  const gm_yee_layout *L = &s->L;
  unsigned char *cut[3] = {NULL, NULL, NULL}, *mark[3] = {NULL, NULL, NULL};
  double *kd[3] = {NULL, NULL, NULL}; /* ε̃⁻¹_aa per location (cut ones) */
  pair *pairs = NULL;
  size_t n_pairs = 0, cap = 0;
  struct yee_aniso *A = NULL;
  gm_status st = GM_OK;
  /* 1. edges whose own pixel is cut with an off-diagonal entry */
  int any = 0;
  for (int c = 0; c < 3; ++c) {
    if (!s->active[c]) continue;
    cut[c] = calloc(L->size, 1);
    mark[c] = calloc(L->size, 1);
    kd[c] = calloc(L->size, sizeof(double));
    if (cut[c] == NULL || mark[c] == NULL || kd[c] == NULL) {
      st = oom(err);
      goto done;
    }
    size_t cnt[3];
    gm_yee_component_count(L, (gm_yee_component)c, cnt);
    for (size_t k = 0; k < cnt[2]; ++k)
      for (size_t j = 0; j < cnt[1]; ++j)
        for (size_t i = 0; i < cnt[0]; ++i) {
          double row[3], eps, sig;
          const long ijk[3] = {(long)i, (long)j, (long)k};
          long g[3];
          yee_view_index(s, ijk, g); /* an MPI block: the whole grid's pixel (yee_view.c) */
          yee_smooth_inverse_row(yee_view_materials(s, m), yee_view_layout(s),
                                 yee_view_periodic(s), c, g[0], g[1], g[2], row, &eps, &sig);
          const size_t q = yee_idx(L, (long)i, (long)j, (long)k);
          kd[c][q] = row[c];
          for (int b = 0; b < s->n_axes; ++b)
            if (b != c && s->active[b] && fabs(row[b]) > 1e-12 * row[c]) cut[c][q] = 1, any = 1;
        }
  }
  if (!any) goto done;
  /* 2. pairs (E_a at q, D_b at r), a < b, r one of the four D_b nearest q, where q or r is cut:
        the entry of the pixel centred at their midpoint, when both can be taken over */
  for (int c = 0; c < 3; ++c) {
    if (!s->active[c]) continue;
    double sh_c[3];
    gm_yee_component_shift(L->dim, (gm_yee_component)c, sh_c);
    size_t cnt[3];
    gm_yee_component_count(L, (gm_yee_component)c, cnt);
    for (size_t k = 0; k < cnt[2]; ++k)
      for (size_t j = 0; j < cnt[1]; ++j)
        for (size_t i = 0; i < cnt[0]; ++i) {
          const long ijk[3] = {(long)i, (long)j, (long)k};
          const size_t q = yee_idx(L, ijk[0], ijk[1], ijk[2]);
          for (int b = c + 1; b < s->n_axes; ++b) {
            if (!s->active[b]) continue;
            double sh_b[3];
            gm_yee_component_shift(L->dim, (gm_yee_component)b, sh_b);
            long nb[4][3];
            neighbours(c, b, ijk, nb);
            for (int t = 0; t < 4; ++t) {
              int inside = 1;
              for (int x = 0; x < 3; ++x)
                inside &= nb[t][x] >= -1 && nb[t][x] <= (long)L->n[x];
              if (!inside) continue;
              const size_t r = yee_idx(L, nb[t][0], nb[t][1], nb[t][2]);
              if (!cut[c][q] && !cut[b][r]) continue;
              if (!eligible(s, c, ijk) || !eligible(s, b, nb[t])) continue;
              /* an MPI block: the pair as the whole grid sees it, from E_a's wrapped index */
              long gq[3], gr[3];
              yee_view_index(s, ijk, gq);
              for (int x = 0; x < 3; ++x) gr[x] = gq[x] + nb[t][x] - ijk[x];
              if (!yee_view_eligible(s, c, gq) || !yee_view_eligible(s, b, gr)) continue;
              double mid[3];
              for (int x = 0; x < 3; ++x)
                mid[x] = 0.5 * ((double)gq[x] + sh_c[x] + (double)gr[x] + sh_b[x]);
              const double kab = yee_smooth_offdiag_at(yee_view_materials(s, m), yee_view_layout(s),
                                                       yee_view_periodic(s), mid, c, b);
              if (!(fabs(kab) > 1e-12 * kd[c][q])) continue;
              if (n_pairs == cap) {
                cap = cap ? 2 * cap : 1024;
                pair *g = realloc(pairs, cap * sizeof *g);
                if (g == NULL) {
                  st = oom(err);
                  goto done;
                }
                pairs = g;
              }
              pairs[n_pairs++] = (pair){c, b, q, r, 0.25 * kab};
              mark[c][q] = mark[b][r] = 1;
            }
          }
        }
  }
  if (n_pairs == 0) goto done;
  /* 3. members (the ends of the pairs), sorted by component then index */
  A = calloc(1, sizeof *A);
  if (A == NULL) {
    st = oom(err);
    goto done;
  }
  for (int c = 0; c < 3; ++c) {
    A->start[c] = A->n;
    if (mark[c])
      for (size_t q = 0; q < L->size; ++q) A->n += mark[c][q];
  }
  A->start[3] = A->n;
  A->q = malloc(A->n * sizeof *A->q);
  A->kdiag = malloc(A->n * sizeof *A->kdiag);
  A->adj_start = calloc(A->n + 1, sizeof *A->adj_start);
  A->adj = malloc(2 * n_pairs * sizeof *A->adj);
  A->adj_c = malloc(2 * n_pairs * sizeof *A->adj_c);
  int ok = A->q && A->kdiag && A->adj_start && A->adj && A->adj_c;
  for (int p = 0; p < s->n_parts; ++p) {
    A->d[p] = calloc(A->n, sizeof(double));
    A->esave[p] = calloc(A->n, sizeof(double));
    ok = ok && A->d[p] && A->esave[p];
  }
  if (!ok) {
    st = oom(err);
    goto done;
  }
  for (int c = 0, i = 0; c < 3; ++c)
    if (mark[c])
      for (size_t q = 0; q < L->size; ++q)
        if (mark[c][q]) {
          A->q[i] = q;
          A->kdiag[i] = kd[c][q];
          ++i;
        }
  /* 4. the couplings, both ways: E = K D with K symmetric */
  for (size_t t = 0; t < n_pairs; ++t) {
    A->adj_start[find_member(A, pairs[t].a, pairs[t].q) + 1]++;
    A->adj_start[find_member(A, pairs[t].b, pairs[t].r) + 1]++;
  }
  for (size_t i = 0; i < A->n; ++i) A->adj_start[i + 1] += A->adj_start[i];
  {
    size_t *fill = malloc((A->n ? A->n : 1) * sizeof *fill);
    if (fill == NULL) {
      st = oom(err);
      goto done;
    }
    memcpy(fill, A->adj_start, A->n * sizeof *fill);
    for (size_t t = 0; t < n_pairs; ++t) {
      const size_t mi = (size_t)find_member(A, pairs[t].a, pairs[t].q);
      const size_t mj = (size_t)find_member(A, pairs[t].b, pairs[t].r);
      A->adj[fill[mi]] = mj, A->adj_c[fill[mi]++] = pairs[t].coef;
      A->adj[fill[mj]] = mi, A->adj_c[fill[mj]++] = pairs[t].coef;
    }
    free(fill);
  }
  /* 5. the kernels now add Δt curl H on the members: E − E_saved is the increment of D */
  for (int c = 0; c < 3; ++c)
    for (size_t i = A->start[c]; i < A->start[c + 1]; ++i) s->cb[c][A->q[i]] = s->dt;
  s->aniso = A;
  A = NULL;
done:
  if (A != NULL) {
    s->aniso = A;
    yee_aniso_free(s);
  }
  for (int c = 0; c < 3; ++c) free(cut[c]), free(mark[c]), free(kd[c]);
  free(pairs);
  return st;
}

void yee_aniso_apply(gm_yee *s) {
  struct yee_aniso *A = s->aniso;
  if (A == NULL) return;
  for (int p = 0; p < s->n_parts; ++p) {
    double *d = A->d[p], *es = A->esave[p];
    for (int c = 0; c < 3; ++c) {
      double *E = s->f[p][c];
      for (size_t i = A->start[c]; i < A->start[c + 1]; ++i) d[i] += E[A->q[i]] - es[i];
    }
    for (int c = 0; c < 3; ++c) {
      double *E = s->f[p][c];
      for (size_t i = A->start[c]; i < A->start[c + 1]; ++i) {
        double v = A->kdiag[i] * d[i];
        for (size_t t = A->adj_start[i]; t < A->adj_start[i + 1]; ++t)
          v += A->adj_c[t] * d[A->adj[t]];
        E[A->q[i]] = es[i] = v;
      }
    }
  }
}

size_t yee_aniso_state(const gm_yee *s, int part, double **d, double **esave) {
  struct yee_aniso *A = s->aniso;
  if (A == NULL) return 0;
  if (d) *d = A->d[part];
  if (esave) *esave = A->esave[part];
  return A->n;
}

void yee_aniso_resave(gm_yee *s) {
  struct yee_aniso *A = s->aniso;
  if (A == NULL) return;
  for (int p = 0; p < s->n_parts; ++p)
    for (int c = 0; c < 3; ++c)
      for (size_t i = A->start[c]; i < A->start[c + 1]; ++i) A->esave[p][i] = s->f[p][c][A->q[i]];
}

void yee_aniso_sync(gm_yee *s) {
  struct yee_aniso *A = s->aniso;
  if (A == NULL) return;
  /* E set from outside: D = E / ε̃⁻¹_aa (the off-diagonal part of E = ε̃⁻¹ D is not inverted) */
  for (int p = 0; p < s->n_parts; ++p)
    for (int c = 0; c < 3; ++c)
      for (size_t i = A->start[c]; i < A->start[c + 1]; ++i) {
        const double e = s->f[p][c][A->q[i]];
        A->esave[p][i] = e;
        A->d[p][i] = e / A->kdiag[i];
      }
}
