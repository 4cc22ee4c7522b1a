/* Off-diagonal entries of the subpixel-smoothed inverse permittivity (yee_smoothing.c).
 *
 * Where an interface cuts the pixel of E_a with a normal n that has components along a and b,
 * ε̃⁻¹ has the entry (ε̃⁻¹)_ab = n_a n_b (⟨ε⁻¹⟩ − ⟨ε⟩⁻¹) (Kottke, Farjadpour & Johnson, PRE 77
 * (2008) 036611, eq. 1). Dropping it leaves a first-order error (the first-order perturbation
 * of a mode's frequency involves D_a (ε̃⁻¹)_ab D_b, non-zero for fields oblique to the
 * interface); with it the error is second order. E_a then depends on D_b, which lives at other
 * locations: as MEEP (Oskooi et al., CPC 181 (2010) 687, §4.3) we use the mean of the four D_b
 * nearest to E_a. So that the coupling is a symmetric operator (the leapfrog's energy
 * argument needs E = K D with K symmetric positive definite), the pair (E_a at q, D_b at r)
 * gets the coefficient ⅛ (ε̃⁻¹_ab(q) + ε̃⁻¹_ba(r)) both ways.
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

typedef struct cand {
  size_t q;
  long ijk[3];
  double row[3];
  int ok;
} cand;

gm_status yee_aniso_setup(gm_yee *s, const gm_yee_materials *m, gm_error *err) {
  if (s->n_axes < 2 || !s->smoothed) return GM_OK;
  const gm_yee_layout *L = &s->L;
  cand *cands[3] = {NULL, NULL, NULL};
  size_t n_cand[3] = {0, 0, 0}, cap[3] = {0, 0, 0};
  unsigned char *mark[3] = {NULL, NULL, NULL};
  struct yee_aniso *A = NULL;
  gm_status st = GM_OK;
  /* 1. cut edges with an off-diagonal entry */
  for (int c = 0; c < 3; ++c) {
    if (!s->active[c]) continue;
    size_t cnt[3];
    gm_yee_component_count(L, (gm_yee_component)c, cnt);
    for (size_t k = 0; k < cnt[2]; ++k)
      for (size_t j = 0; j < cnt[1]; ++j)
        for (size_t i = 0; i < cnt[0]; ++i) {
          double row[3], eps, sig;
          yee_smooth_inverse_row(m, L, s->periodic, c, (long)i, (long)j, (long)k, row, &eps,
                                 &sig);
          int off = 0;
          for (int b = 0; b < s->n_axes; ++b)
            if (b != c && s->active[b] && fabs(row[b]) > 1e-12 * row[c]) off = 1;
          if (!off) continue;
          if (n_cand[c] == cap[c]) {
            cap[c] = cap[c] ? 2 * cap[c] : 256;
            cand *g = realloc(cands[c], cap[c] * sizeof *g);
            if (g == NULL) {
              st = gm_error_set(err, GM_ENOMEM, "yee: out of memory (smoothing)");
              goto done;
            }
            cands[c] = g;
          }
          cand *e = &cands[c][n_cand[c]++];
          e->ijk[0] = (long)i, e->ijk[1] = (long)j, e->ijk[2] = (long)k;
          e->q = yee_idx(L, e->ijk[0], e->ijk[1], e->ijk[2]);
          memcpy(e->row, row, sizeof row);
          e->ok = 1;
        }
  }
  if (n_cand[0] + n_cand[1] + n_cand[2] == 0) goto done;
  /* 2. accept a candidate when it and its neighbours can be taken over; mark the members */
  for (int c = 0; c < 3; ++c) {
    if (!s->active[c]) continue;
    mark[c] = calloc(L->size, 1);
    if (mark[c] == NULL) {
      st = gm_error_set(err, GM_ENOMEM, "yee: out of memory (smoothing)");
      goto done;
    }
  }
  for (int c = 0; c < 3; ++c)
    for (size_t e = 0; e < n_cand[c]; ++e) {
      cand *x = &cands[c][e];
      x->ok = eligible(s, c, x->ijk);
      for (int b = 0; b < 3 && x->ok; ++b) {
        if (b == c || !s->active[b] || b >= s->n_axes) continue;
        long nb[4][3];
        neighbours(c, b, x->ijk, nb);
        for (int t = 0; t < 4; ++t) x->ok = x->ok && eligible(s, b, nb[t]);
      }
    }
  for (int c = 0; c < 3; ++c)
    for (size_t e = 0; e < n_cand[c]; ++e) {
      const cand *x = &cands[c][e];
      if (!x->ok) continue;
      mark[c][x->q] = 1;
      for (int b = 0; b < 3; ++b) {
        if (b == c || !s->active[b] || b >= s->n_axes) continue;
        long nb[4][3];
        neighbours(c, b, x->ijk, nb);
        for (int t = 0; t < 4; ++t) mark[b][yee_idx(L, nb[t][0], nb[t][1], nb[t][2])] = 1;
      }
    }
  /* 3. members, sorted by component then index */
  A = calloc(1, sizeof *A);
  if (A == NULL) {
    st = gm_error_set(err, GM_ENOMEM, "yee: out of memory (smoothing)");
    goto done;
  }
  for (int c = 0; c < 3; ++c) {
    A->start[c] = A->n;
    if (mark[c])
      for (size_t q = 0; q < L->size; ++q) A->n += mark[c][q];
  }
  A->start[3] = A->n;
  if (A->n == 0) goto done;
  A->q = malloc(A->n * sizeof *A->q);
  A->kdiag = malloc(A->n * sizeof *A->kdiag);
  A->adj_start = calloc(A->n + 1, sizeof *A->adj_start);
  int parts_ok = 1;
  for (int p = 0; p < s->n_parts; ++p) {
    A->d[p] = calloc(A->n, sizeof(double));
    A->esave[p] = calloc(A->n, sizeof(double));
    parts_ok = parts_ok && A->d[p] != NULL && A->esave[p] != NULL;
  }
  if (!parts_ok || A->q == NULL || A->kdiag == NULL || A->adj_start == NULL) {
    st = gm_error_set(err, GM_ENOMEM, "yee: out of memory (smoothing)");
    goto done;
  }
  for (int c = 0, i = 0; c < 3; ++c)
    if (mark[c])
      for (size_t q = 0; q < L->size; ++q)
        if (mark[c][q]) {
          A->q[i] = q;
          /* not a candidate: the diagonal value already in cb (lossless: cb = Δt/ε) */
          A->kdiag[i] = s->cb[c][q] / s->dt;
          ++i;
        }
  for (int c = 0; c < 3; ++c)
    for (size_t e = 0; e < n_cand[c]; ++e)
      if (cands[c][e].ok) A->kdiag[find_member(A, c, cands[c][e].q)] = cands[c][e].row[c];
  /* 4. couplings: each pair once (from its accepted end with the smaller (component, index)) */
  for (int pass = 0; pass < 2; ++pass) {
    size_t *fill = NULL;
    if (pass == 1) {
      for (size_t i = 0; i < A->n; ++i) A->adj_start[i + 1] += A->adj_start[i];
      const size_t n_adj = A->adj_start[A->n];
      A->adj = malloc((n_adj ? n_adj : 1) * sizeof *A->adj);
      A->adj_c = malloc((n_adj ? n_adj : 1) * sizeof *A->adj_c);
      fill = malloc(A->n * sizeof *fill);
      if (A->adj == NULL || A->adj_c == NULL || fill == NULL) {
        free(fill);
        st = gm_error_set(err, GM_ENOMEM, "yee: out of memory (smoothing)");
        goto done;
      }
      memcpy(fill, A->adj_start, A->n * sizeof *fill);
    }
    for (int c = 0; c < 3; ++c)
      for (size_t e = 0; e < n_cand[c]; ++e) {
        const cand *x = &cands[c][e];
        if (!x->ok) continue;
        const size_t mi = (size_t)find_member(A, c, x->q);
        for (int b = 0; b < 3; ++b) {
          if (b == c || !s->active[b] || b >= s->n_axes) continue;
          long nb[4][3];
          neighbours(c, b, x->ijk, nb);
          for (int t = 0; t < 4; ++t) {
            const size_t r = yee_idx(L, nb[t][0], nb[t][1], nb[t][2]);
            const size_t mj = (size_t)find_member(A, b, r);
            /* the other end's own entry, when it is an accepted candidate */
            double kr = 0.0;
            int r_accepted = 0;
            { /* candidates are sorted by q */
              size_t lo = 0, hi = n_cand[b];
              while (lo < hi) {
                const size_t mid = lo + (hi - lo) / 2;
                if (cands[b][mid].q < r)
                  lo = mid + 1;
                else
                  hi = mid;
              }
              if (lo < n_cand[b] && cands[b][lo].q == r && cands[b][lo].ok) {
                r_accepted = 1;
                kr = cands[b][lo].row[c];
              }
            }
            if (r_accepted && mj < mi) continue; /* done from the other end */
            const double coef = 0.125 * (x->row[b] + kr);
            if (pass == 0) {
              A->adj_start[mi + 1]++;
              A->adj_start[mj + 1]++;
            } else {
              A->adj[fill[mi]] = mj, A->adj_c[fill[mi]++] = coef;
              A->adj[fill[mj]] = mi, A->adj_c[fill[mj]++] = coef;
            }
          }
        }
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
  for (int c = 0; c < 3; ++c) free(cands[c]), free(mark[c]);
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
