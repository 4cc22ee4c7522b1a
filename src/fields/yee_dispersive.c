/* Dispersive media: Drude and Lorentz poles by the auxiliary-differential-equation (ADE) method
 * (Taflove & Hagness, Computational Electrodynamics 3rd ed., §9.4: the polarization of each
 * pole obeys an ODE driven by E, stepped beside Ampère's law; the Lorentz ODE is their
 * eq. 9.41's time-domain form, the Drude one its ω0 → 0 limit).
 *
 * Model (per pole, ω = 2πf, time dependence e^{−iωt}): the polarization P obeys
 *   P'' + γ P' + ω0² P = s E,   s = Δε ω0² (Lorentz), s = ω_p², ω0 = 0 (Drude),
 * so P = s E / (ω0² − ω² − iγω), and Ampère reads ε∞ E' + Σ P' + σE = curl H.
 *
 * Discretisation. P lives with E (on the edges, at E's half steps t_m). The ODE is centred at
 * t_m with the three-level second difference and centred first difference, and the restoring
 * and driving terms averaged over t_{m−1}, t_m, t_{m+1} with weights ¼, ½, ¼:
 *   (P⁺ − 2P + P⁻)/Δt² + γ (P⁺ − P⁻)/(2Δt) + ω0² (P⁺ + 2P + P⁻)/4 = s (E⁺ + 2E + E⁻)/4,
 * and Ampère over [t_m, t_{m+1}] as the existing σ update (Taflove & Hagness eq. 3.28):
 *   (ε∞ + σΔt/2) E⁺ + Σ P⁺ = (ε∞ − σΔt/2) E + Δt curl H + Σ P.
 * P⁺ = A + B E⁺ with A from old values only, so E⁺ is explicit:
 *   E⁺ = f₂ E' − (Σ A − Σ P) / D,  D = K + Σ B,  K = ε∞ + σΔt/2 = Δt / cb,  f₂ = K / D,
 * E' the value the ordinary Yee kernel (with its sources, CPML and TF/SF terms) wrote.
 * The same weights as Taflove & Hagness's Drude ADE (eqs. 9.54-9.56 there: the current driven by
 * (E⁺ + E)/2), extended to the Lorentz restoring term. In the frequency domain the scheme is the
 * continuous ε(ω) at ω̃ = (2/Δt) tan(ωΔt/2) (the bilinear map: (z − 2 + 1/z)/Δt² over
 * (z + 2 + 1/z)/4 is −ω̃², (z − 1/z)/2Δt over the same is −iω̃), so the discrete medium is
 * ε_d(ω) = ε(ω̃) (gm_medium_epsilon with dt > 0). Stability: with γ = 0 the Yee dispersion
 * sin²(ωΔt/2)(4/Δt²) ε(ω̃) = k̃² has, for every k̃² up to 4ε∞/Δt² (the Courant limit of ε∞),
 * two real roots ωΔt/2 in (0, π/2) (one on each side of the pole ω̃ = ω0, since ε(ω̃) → ε∞ as
 * ω̃ → ∞): all four roots of the fourth-order recurrence on the unit circle, for any s and ω0.
 * So the dispersive solver is stable up to the same Courant limit (that of ε∞), unlike the
 * explicit scheme with E at t_m only (Oskooi et al., CPC 181 (2010) 687, §4.2), which needs
 * (1 − C²) ε∞ (4/Δt² − ω0²) ≥ s at Courant fraction C.
 *
 * Layout: the dispersive edges (any cell around the edge has poles; weight w of a pole = the
 * fraction of those cells that have it, as the staircase σ) sorted by array index, and one
 * entry per (pole, edge) grouped by pole. The state per entry is P^{m−1} and A^m with
 * P^m = A^m + w c₃ E^m: P^m is completed at the start of the next step, so that after the E
 * kernel only one pass over the edges is needed (E⁺ = f₂ E' − g). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fields/internal.h"

static const double two_pi = 6.283185307179586476925286766559;

typedef struct disp_pole {
  double c1, c2, c3;     /* P⁺ = c1 P + c2 P⁻ + c3 w (E⁺ + 2E + E⁻) */
  double s, omega0_sq;   /* for the energy */
  size_t first, end;     /* its entries */
} disp_pole;

struct yee_dispersive {
  size_t n_edges;
  size_t *q;             /* array index, ascending (ties: by component) */
  int *comp;
  double *f2, *invd, *vol;
  double *eo[2];         /* E^{m−1} per part (E^m once begin has run) */
  double *g[2];          /* Σ (A − P) while accumulating, then that over D */
  size_t n_poles;
  disp_pole *poles;
  size_t n_entries;
  size_t *edge;          /* entry → edge */
  double *w;             /* entry → weight */
  double *pp[2], *a[2];  /* P^{m−1}, A^m per part */
};

/* ---- media -------------------------------------------------------------------------------- */

gm_status gm_poles_check(size_t n_poles, const gm_pole *poles, gm_error *err) {
  if (n_poles > 0 && poles == NULL)
    return gm_error_set(err, GM_EINVAL, "poles: %zu poles and a NULL array", n_poles);
  if (n_poles > 64) return gm_error_set(err, GM_EINVAL, "poles: %zu poles (at most 64)", n_poles);
  for (size_t k = 0; k < n_poles; ++k) {
    const gm_pole *p = &poles[k];
    const int drude = p->kind == GM_POLE_DRUDE;
    if (p->kind != GM_POLE_DRUDE && p->kind != GM_POLE_LORENTZ)
      return gm_error_set(err, GM_EINVAL, "poles[%zu].type: unknown pole kind %d", k,
                          (int)p->kind);
    if (!(p->frequency > 0.0 && p->frequency <= 1e100))
      return gm_error_set(err, GM_EINVAL, "poles[%zu].frequency: the %s frequency must be > 0 "
                          "and finite (got %g)", k, drude ? "plasma" : "resonance", p->frequency);
    if (!(p->gamma >= 0.0 && p->gamma <= 1e100))
      return gm_error_set(err, GM_EINVAL,
                          "poles[%zu].gamma: the damping rate must be >= 0 and finite (got %g)",
                          k, p->gamma);
    if (!drude && !(p->strength > 0.0 && p->strength <= 1e100))
      return gm_error_set(err, GM_EINVAL,
                          "poles[%zu].delta_epsilon: a Lorentz strength must be > 0 and finite "
                          "(got %g)", k, p->strength);
  }
  return GM_OK;
}

/* s and ω0² of a pole in angular units. */
static void pole_omega(const gm_pole *p, double *s, double *w0sq) {
  const double w = two_pi * p->frequency;
  *w0sq = p->kind == GM_POLE_LORENTZ ? w * w : 0.0;
  *s = p->kind == GM_POLE_LORENTZ ? p->strength * w * w : w * w;
}

gm_status gm_medium_epsilon(const gm_medium *md, size_t n_poles, const gm_pole *poles, double f,
                            double dt, double eps[2], gm_error *err) {
  if (md == NULL || eps == NULL) return gm_error_set(err, GM_EINVAL, "medium epsilon: NULL");
  gm_status st = gm_poles_check(n_poles, poles, err);
  if (st != GM_OK) return st;
  if (!(f > 0.0) || !isfinite(f) || !(dt >= 0.0) || !isfinite(dt) || (dt > 0 && f * dt >= 0.5))
    return gm_error_set(err, GM_EINVAL,
                        "medium epsilon: need f > 0, dt >= 0 and f < 1/(2 dt) (f = %g, dt = %g)",
                        f, dt);
  /* the scheme's frequency map (file comment): ω̃ = (2/Δt) tan(ωΔt/2) */
  const double w = dt > 0 ? 2.0 / dt * tan(0.5 * two_pi * f * dt) : two_pi * f;
  double re = md->epsilon, im = md->sigma / w;
  for (size_t k = 0; k < n_poles; ++k) {
    const gm_pole *p = &poles[k];
    double s, w0sq;
    pole_omega(p, &s, &w0sq);
    const double g = two_pi * p->gamma;
    /* s / (ω0² − ω² − iγω) */
    const double dr = w0sq - w * w, di = -g * w, den = dr * dr + di * di;
    re += s * dr / den;
    im -= s * di / den;
  }
  eps[0] = re;
  eps[1] = im;
  return GM_OK;
}

/* ---- solver ------------------------------------------------------------------------------- */

void yee_dispersive_free(gm_yee *s) {
  struct yee_dispersive *d = s->disp;
  if (d == NULL) return;
  free(d->q), free(d->comp), free(d->f2), free(d->invd), free(d->vol);
  free(d->poles), free(d->edge), free(d->w);
  for (int p = 0; p < 2; ++p) free(d->eo[p]), free(d->g[p]), free(d->pp[p]), free(d->a[p]);
  free(d);
  s->disp = NULL;
}

/* Fraction of the cells around edge (c, ijk) in each pole set: count[1..n_sets] over total. */
static size_t edge_sets(const gm_yee *s, const gm_yee_materials *m, int c, const long ijk[3],
                        size_t *count) {
  long cx[3][2];
  size_t nx[3];
  for (int b = 0; b < 3; ++b) nx[b] = yee_cells_along(&s->L, s->periodic, b, ijk[b], b != c, cx[b]);
  memset(count, 0, (m->n_sets + 1) * sizeof *count);
  for (size_t z = 0; z < nx[2]; ++z)
    for (size_t y = 0; y < nx[1]; ++y)
      for (size_t x = 0; x < nx[0]; ++x)
        ++count[m->pole_set[(size_t)cx[0][x] +
                            m->grid.n[0] * ((size_t)cx[1][y] + m->grid.n[1] * (size_t)cx[2][z])]];
  return nx[0] * nx[1] * nx[2];
}

typedef struct edge_rec {
  size_t q;
  int c;
  long ijk[3];
} edge_rec;

static int by_index(const void *x, const void *y) {
  const edge_rec *a = x, *b = y;
  if (a->q != b->q) return a->q < b->q ? -1 : 1;
  return (a->c > b->c) - (a->c < b->c);
}

static gm_status oom(gm_error *err) {
  return gm_error_set(err, GM_ENOMEM, "yee: out of memory (dispersive media)");
}

gm_status yee_dispersive_setup(gm_yee *s, const gm_yee_materials *m, gm_error *err) {
  if (m == NULL || m->n_sets == 0) return GM_OK;
  const size_t n_poles = m->set_start[m->n_sets];
  size_t *count = malloc((m->n_sets + 1) * sizeof *count);
  size_t *per_pole = calloc(n_poles + 1, sizeof *per_pole);
  edge_rec *rec = NULL;
  gm_status st = GM_OK;
  if (count == NULL || per_pole == NULL) {
    st = oom(err);
    goto done;
  }
  /* 1. the dispersive edges in the update ranges, and the entries each pole gets */
  size_t n_edges = 0;
  for (int pass = 0; pass < 2; ++pass) {
    size_t e = 0;
    for (int c = 0; c < 3; ++c) {
      if (!s->active[c]) continue;
      const yee_box *b = &s->upd[c];
      for (size_t k = b->lo[2]; k < b->lo[2] + b->cnt[2]; ++k)
        for (size_t j = b->lo[1]; j < b->lo[1] + b->cnt[1]; ++j)
          for (size_t i = b->lo[0]; i < b->lo[0] + b->cnt[0]; ++i) {
            const long ijk[3] = {(long)i, (long)j, (long)k};
            edge_sets(s, m, c, ijk, count);
            int any = 0;
            for (size_t t = 1; t <= m->n_sets; ++t) {
              if (count[t] == 0) continue;
              any = 1;
              if (pass == 0)
                for (size_t p = m->set_start[t - 1]; p < m->set_start[t]; ++p) ++per_pole[p];
            }
            if (!any) continue;
            if (pass == 1) rec[e] = (edge_rec){yee_idx(&s->L, ijk[0], ijk[1], ijk[2]), c,
                                               {ijk[0], ijk[1], ijk[2]}};
            ++e;
          }
    }
    if (pass == 0) {
      n_edges = e;
      if (n_edges == 0) goto done;
      size_t n_entries = 0;
      for (size_t p = 0; p < n_poles; ++p) n_entries += per_pole[p];
      char what[160];
      snprintf(what, sizeof what, "yee: the state of %zu dispersive edges (%zu pole entries)",
               n_edges, n_entries);
      const double bytes = (double)n_edges * (8.0 * 5 + 4 + 16.0 * s->n_parts) +
                           (double)n_entries * (16.0 + 16.0 * s->n_parts) +
                           (double)n_edges * sizeof(edge_rec);
      st = yee_memory_check(bytes, what, err);
      if (st != GM_OK) goto done;
      rec = malloc(n_edges * sizeof *rec);
      if (rec == NULL) {
        st = oom(err);
        goto done;
      }
    }
  }
  qsort(rec, n_edges, sizeof *rec, by_index);
  struct yee_dispersive *d = calloc(1, sizeof *d);
  if (d == NULL) {
    st = oom(err);
    goto done;
  }
  s->disp = d;
  d->n_edges = n_edges;
  d->n_poles = n_poles;
  d->poles = calloc(n_poles, sizeof *d->poles);
  size_t n_entries = 0;
  for (size_t p = 0; p < n_poles; ++p) {
    d->poles[p].first = n_entries;
    n_entries += per_pole[p];
    d->poles[p].end = d->poles[p].first; /* filled below */
  }
  d->n_entries = n_entries;
  d->q = malloc(n_edges * sizeof *d->q);
  d->comp = malloc(n_edges * sizeof *d->comp);
  d->f2 = malloc(n_edges * sizeof *d->f2);
  d->invd = malloc(n_edges * sizeof *d->invd);
  d->vol = malloc(n_edges * sizeof *d->vol);
  d->edge = malloc(n_entries * sizeof *d->edge);
  d->w = malloc(n_entries * sizeof *d->w);
  int ok = d->poles && d->q && d->comp && d->f2 && d->invd && d->vol && d->edge && d->w;
  for (int p = 0; p < s->n_parts && ok; ++p) {
    d->eo[p] = calloc(n_edges, sizeof(double));
    d->g[p] = calloc(n_edges, sizeof(double));
    d->pp[p] = calloc(n_entries, sizeof(double));
    d->a[p] = calloc(n_entries, sizeof(double));
    ok = d->eo[p] && d->g[p] && d->pp[p] && d->a[p];
  }
  if (!ok) {
    st = oom(err);
    goto done;
  }
  /* 2. pole coefficients (file comment; multiplied through by Δt²) */
  const double dt = s->dt;
  for (size_t p = 0; p < n_poles; ++p) {
    disp_pole *P = &d->poles[p];
    const gm_pole *src = &m->set_poles[p];
    pole_omega(src, &P->s, &P->omega0_sq);
    const double g = two_pi * src->gamma * dt, w2 = P->omega0_sq * dt * dt;
    const double den = 1.0 + 0.5 * g + 0.25 * w2;
    P->c1 = (2.0 - 0.5 * w2) / den;
    P->c2 = -(1.0 - 0.5 * g + 0.25 * w2) / den;
    P->c3 = 0.25 * P->s * dt * dt / den;
  }
  /* 3. edges and entries */
  for (size_t e = 0; e < n_edges; ++e) {
    const edge_rec *r = &rec[e];
    const size_t total = edge_sets(s, m, r->c, r->ijk, count);
    double sum_b = 0.0;
    for (size_t t = 1; t <= m->n_sets; ++t) {
      if (count[t] == 0) continue;
      const double w = (double)count[t] / (double)total;
      for (size_t p = m->set_start[t - 1]; p < m->set_start[t]; ++p) {
        disp_pole *P = &d->poles[p];
        d->edge[P->end] = e;
        d->w[P->end] = w;
        ++P->end;
        sum_b += w * P->c3;
      }
    }
    const double cb = s->uniform ? s->cb0[r->c] : s->cb[r->c][r->q];
    const double K = dt / cb, D = K + sum_b;
    d->q[e] = r->q;
    d->comp[e] = r->c;
    d->f2[e] = K / D;
    d->invd[e] = 1.0 / D;
    d->vol[e] = yee_dual_weight(s, r->c, r->ijk);
  }
done:
  free(count);
  free(per_pole);
  free(rec);
  if (st != GM_OK) yee_dispersive_free(s);
  return st;
}

int yee_dispersive_has(const gm_yee *s, int c, size_t q) {
  const struct yee_dispersive *d = s->disp;
  if (d == NULL) return 0;
  size_t lo = 0, hi = d->n_edges;
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    if (d->q[mid] < q || (d->q[mid] == q && d->comp[mid] < c))
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < d->n_edges && d->q[lo] == q && d->comp[lo] == c;
}

/* Before the E kernels: complete P^m, form A^{m+1} and g = Σ (A − P)/D, keep E^m. */
void yee_dispersive_begin(gm_yee *s) {
  struct yee_dispersive *d = s->disp;
  if (d == NULL) return;
  for (int part = 0; part < s->n_parts; ++part) {
    double *const *F = s->f[part];
    double *restrict eo = d->eo[part], *restrict g = d->g[part];
    double *restrict pp = d->pp[part], *restrict a = d->a[part];
    for (size_t p = 0; p < d->n_poles; ++p) {
      const disp_pole *P = &d->poles[p];
      const double c1 = P->c1, c2 = P->c2, c3 = P->c3;
      /* one entry per edge within a pole: the iterations write disjoint slots */
      YEE_OMP(omp parallel for num_threads(s->n_threads) if (P->end - P->first > YEE_OMP_MIN))
      for (size_t i = P->first; i < P->end; ++i) {
        const size_t e = d->edge[i];
        const double E = F[d->comp[e]][d->q[e]], wc3 = d->w[i] * c3;
        const double pm = a[i] + wc3 * E;                           /* P^m */
        const double an = c1 * pm + c2 * pp[i] + wc3 * (2.0 * E + eo[e]); /* A^{m+1} */
        g[e] += an - pm;
        pp[i] = pm;
        a[i] = an;
      }
    }
    YEE_OMP(omp parallel for num_threads(s->n_threads) if (d->n_edges > YEE_OMP_MIN))
    for (size_t e = 0; e < d->n_edges; ++e) {
      g[e] *= d->invd[e];
      eo[e] = F[d->comp[e]][d->q[e]];
    }
  }
}

static void apply_edges(gm_yee *s, size_t e0, size_t e1) {
  struct yee_dispersive *d = s->disp;
  for (int part = 0; part < s->n_parts; ++part) {
    double *const *F = s->f[part];
    double *restrict g = d->g[part];
    for (size_t e = e0; e < e1; ++e) {
      double *E = &F[d->comp[e]][d->q[e]];
      *E = d->f2[e] * *E - g[e];
      g[e] = 0.0;
    }
  }
}

void yee_dispersive_apply(gm_yee *s) {
  if (s->disp == NULL) return;
  apply_edges(s, 0, s->disp->n_edges);
}

void yee_dispersive_apply_range(gm_yee *s, size_t lo, size_t n) {
  const struct yee_dispersive *d = s->disp;
  if (d == NULL) return;
  size_t a = 0, b = d->n_edges;
  while (a < b) {
    const size_t mid = a + (b - a) / 2;
    if (d->q[mid] < lo)
      a = mid + 1;
    else
      b = mid;
  }
  size_t e1 = a;
  while (e1 < d->n_edges && d->q[e1] < lo + n) ++e1;
  apply_edges(s, a, e1);
}

/* E was set: the medium starts unpolarised (P = 0) with E constant before. */
void yee_dispersive_sync(gm_yee *s) {
  struct yee_dispersive *d = s->disp;
  if (d == NULL) return;
  for (int part = 0; part < s->n_parts; ++part) {
    for (size_t e = 0; e < d->n_edges; ++e) {
      d->eo[part][e] = s->f[part][d->comp[e]][d->q[e]];
      d->g[part][e] = 0.0;
    }
    for (size_t p = 0; p < d->n_poles; ++p)
      for (size_t i = d->poles[p].first; i < d->poles[p].end; ++i) {
        const size_t e = d->edge[i];
        d->pp[part][i] = 0.0;
        d->a[part][i] = -d->w[i] * d->poles[p].c3 * s->f[part][d->comp[e]][d->q[e]];
      }
  }
}

double yee_dispersive_energy(const gm_yee *s) {
  const struct yee_dispersive *d = s->disp;
  if (d == NULL) return 0.0;
  double sum = 0.0;
  for (int part = 0; part < s->n_parts; ++part)
    for (size_t p = 0; p < d->n_poles; ++p) {
      const disp_pole *P = &d->poles[p];
      for (size_t i = P->first; i < P->end; ++i) {
        const size_t e = d->edge[i];
        const double E = s->f[part][d->comp[e]][d->q[e]];
        const double pm = d->a[part][i] + d->w[i] * P->c3 * E, pv = d->pp[part][i];
        const double J = (pm - pv) / s->dt, Pbar = 0.5 * (pm + pv);
        sum += d->vol[e] * (J * J + P->omega0_sq * Pbar * Pbar) / (2.0 * d->w[i] * P->s);
      }
    }
  return sum;
}

int yee_dispersive_visit(gm_yee *s, int (*fn)(void *ctx, double *data, size_t n), void *ctx) {
  struct yee_dispersive *d = s->disp;
  if (d == NULL) return 0;
  for (int p = 0; p < s->n_parts; ++p)
    if (fn(ctx, d->eo[p], d->n_edges) != 0 || fn(ctx, d->pp[p], d->n_entries) != 0 ||
        fn(ctx, d->a[p], d->n_entries) != 0)
      return -1;
  return 0;
}

size_t yee_dispersive_state_size(const gm_yee *s) {
  const struct yee_dispersive *d = s->disp;
  return d ? (size_t)s->n_parts * (d->n_edges + 2 * d->n_entries) : 0;
}
