/* Convolutional PML (Roden & Gedney 2000) with CFS parameters, graded polynomially
 * (Taflove & Hagness 3rd ed. §7.9–7.11, eqs. 7.60, 7.79, 7.102, 7.105–7.106). In the layer a
 * derivative ∂_d becomes (1/κ_d) ∂_d + ψ_d with the recursive convolution
 *   ψ_d ← b_d ψ_d + c_d ∂_d (field),  b = exp(−(σ/κ + α) Δt),  c = σ (b − 1) / (σκ + κ²α).
 * The 1/κ_d factor lives in the kernels' per-axis 1/(κh) arrays; the ψ terms are added by one
 * slab loop per (face, target component) after the main update (linearity makes the order
 * immaterial up to rounding, and the order is fixed). σ here is the stretching rate σ/ε
 * (1/time); its default is σ_opt = 0.8 (m + 1) / (h sqrt(εμ)) (eq. 7.67 in these units). */
#include <math.h>
#include <stdlib.h>

#include "fields/internal.h"

typedef struct profile {
  double sigma, kappa, alpha;
} profile;

/* Depth ρ in [0, 1] of position x (cell units) into the layers of axis a, and that face's
 * parameters; ρ = 0 outside the layers. */
static double depth(const gm_yee *s, int a, double x, const gm_cpml **pml) {
  const double n = (double)s->L.n[a];
  const gm_yee_boundary *lo = &s->opt.boundary[2 * a], *hi = &s->opt.boundary[2 * a + 1];
  if (lo->kind == GM_BOUNDARY_CPML && x < (double)lo->pml.thickness) {
    *pml = &lo->pml;
    return ((double)lo->pml.thickness - x) / (double)lo->pml.thickness;
  }
  if (hi->kind == GM_BOUNDARY_CPML && x > n - (double)hi->pml.thickness) {
    *pml = &hi->pml;
    return (x - (n - (double)hi->pml.thickness)) / (double)hi->pml.thickness;
  }
  *pml = NULL;
  return 0.0;
}

/* ε and μ of the medium next to the layer of face f (the cell at the face's centre, just
 * inside the interface). */
static void adjacent_medium(const gm_yee *s, int f, double *eps, double *mu) {
  if (s->eps_cell == NULL) {
    *eps = s->eps0;
    *mu = s->mu0;
    return;
  }
  const int a = f / 2;
  size_t ijk[3];
  for (int b = 0; b < 3; ++b) ijk[b] = s->L.n[b] / 2;
  const size_t t = s->opt.boundary[f].pml.thickness;
  ijk[a] = (f % 2 == 0) ? t : s->L.n[a] - 1 - t;
  const size_t c = ijk[0] + s->L.n[0] * (ijk[1] + s->L.n[1] * ijk[2]);
  *eps = s->eps_cell[c];
  *mu = s->mu_cell[c];
}

static profile profile_at(const gm_yee *s, int a, double x, const double sigma_max[2]) {
  const gm_cpml *p;
  const double rho = depth(s, a, x, &p);
  profile pr = {0.0, 1.0, 0.0};
  if (p == NULL || rho <= 0.0) return pr;
  const double smax = (p == &s->opt.boundary[2 * a].pml) ? sigma_max[0] : sigma_max[1];
  const double g = pow(rho, p->grading);
  pr.sigma = smax * g;
  pr.kappa = 1.0 + (p->kappa_max - 1.0) * g;
  pr.alpha = p->alpha_max * pow(1.0 - rho, p->alpha_grading);
  return pr;
}

static void coefficients(const profile *pr, double dt, double *b, double *c) {
  *b = exp(-(pr->sigma / pr->kappa + pr->alpha) * dt);
  const double den = pr->sigma * pr->kappa + pr->kappa * pr->kappa * pr->alpha;
  *c = (pr->sigma > 0.0 && den > 0.0) ? pr->sigma * (*b - 1.0) / den : 0.0;
}

static gm_status add_term(gm_yee *s, const yee_cpml_term *t, gm_error *err) {
  yee_cpml_term *grown = realloc(s->cpml, (s->n_cpml + 1) * sizeof *grown);
  if (grown == NULL) return gm_error_set(err, GM_ENOMEM, "yee: out of memory (CPML)");
  s->cpml = grown;
  yee_cpml_term *u = &s->cpml[s->n_cpml];
  *u = *t;
  u->n = t->box.cnt[0] * t->box.cnt[1] * t->box.cnt[2];
  u->psi = calloc(u->n * (size_t)s->n_parts + 1, sizeof(double));
  u->w = calloc(u->n + 1, sizeof(double));
  if (u->psi == NULL || u->w == NULL) {
    free(u->psi);
    free(u->w);
    return gm_error_set(err, GM_ENOMEM, "yee: out of memory (CPML slab)");
  }
  ++s->n_cpml;
  return GM_OK;
}

/* Fill w = sign × (Δt ⋆⁻¹ coefficient of the target) over the slab. */
static void fill_weights(gm_yee *s, yee_cpml_term *t, double sign) {
  size_t l = 0;
  for (size_t k = 0; k < t->box.cnt[2]; ++k)
    for (size_t j = 0; j < t->box.cnt[1]; ++j)
      for (size_t i = 0; i < t->box.cnt[0]; ++i, ++l) {
        const size_t q = yee_idx(&s->L, (long)(t->box.lo[0] + i), (long)(t->box.lo[1] + j),
                                 (long)(t->box.lo[2] + k));
        const double cb = s->cb[t->target] ? s->cb[t->target][q] : s->cb0[t->target];
        t->w[l] = sign * cb;
      }
}

gm_status yee_cpml_setup(gm_yee *s, gm_error *err) {
  for (int a = 0; a < s->n_axes; ++a) {
    const int has_lo = s->opt.boundary[2 * a].kind == GM_BOUNDARY_CPML;
    const int has_hi = s->opt.boundary[2 * a + 1].kind == GM_BOUNDARY_CPML;
    if (!has_lo && !has_hi) continue;
    double smax[2] = {0.0, 0.0};
    for (int side = 0; side < 2; ++side) {
      const gm_cpml *p = &s->opt.boundary[2 * a + side].pml;
      if (s->opt.boundary[2 * a + side].kind != GM_BOUNDARY_CPML) continue;
      double eps, mu;
      adjacent_medium(s, 2 * a + side, &eps, &mu);
      smax[side] = p->sigma_max > 0.0
                       ? p->sigma_max
                       : p->sigma_factor * 0.8 * (p->grading + 1.0) / (s->L.h[a] * sqrt(eps * mu));
    }
    const size_t ext = s->L.extent[a];
    s->cpml_be[a] = calloc(ext, sizeof(double));
    s->cpml_ce[a] = calloc(ext, sizeof(double));
    s->cpml_bh[a] = calloc(ext, sizeof(double));
    s->cpml_ch[a] = calloc(ext, sizeof(double));
    if (!s->cpml_be[a] || !s->cpml_ce[a] || !s->cpml_bh[a] || !s->cpml_ch[a])
      return gm_error_set(err, GM_ENOMEM, "yee: out of memory (CPML)");
    const long off = (long)s->L.offset[a];
    for (long j = 0; j <= (long)s->L.n[a]; ++j) {
      profile pe = profile_at(s, a, (double)j, smax);
      coefficients(&pe, s->dt, &s->cpml_be[a][j + off], &s->cpml_ce[a][j + off]);
      s->inv_e[a][j + off] = 1.0 / (pe.kappa * s->L.h[a]);
      if (j == (long)s->L.n[a]) break;
      profile ph = profile_at(s, a, (double)j + 0.5, smax);
      coefficients(&ph, s->dt, &s->cpml_bh[a][j + off], &s->cpml_ch[a][j + off]);
      s->inv_h[a][j + off] = 1.0 / (ph.kappa * s->L.h[a]);
    }
    /* slabs: one per (face, target component, derivative axis a) */
    for (int side = 0; side < 2; ++side) {
      if (s->opt.boundary[2 * a + side].kind != GM_BOUNDARY_CPML) continue;
      const size_t th = s->opt.boundary[2 * a + side].pml.thickness, n = s->L.n[a];
      for (int t = 0; t < GM_YEE_N_COMPONENTS; ++t) {
        const int comp_axis = t % 3;
        if (!s->active[t] || comp_axis == a) continue;
        const int b = (comp_axis + 1) % 3, c = (comp_axis + 2) % 3;
        const int e = yee_is_e(t);
        /* the other field's component differentiated along a, and the sign of its term */
        const int src = (e ? 3 : 0) + (a == b ? c : b);
        const double term_sign = (a == b) ? 1.0 : -1.0;
        if (!s->active[src]) continue;
        yee_cpml_term u = {0};
        u.box = s->upd[t];
        u.target = t;
        u.src = src;
        u.e_field = e;
        u.inv_h = 1.0 / s->L.h[a];
        u.m[a] = 1;
        /* positions along a where c ≠ 0: E nodes strictly inside the layer, H half nodes */
        size_t lo, hi; /* [lo, hi) */
        if (e) {
          lo = side == 0 ? 1 : n - th + 1;
          hi = side == 0 ? th : n;
          u.o1 = 0;
          u.o0 = -s->s[a];
          u.b = s->cpml_be[a] + s->L.offset[a];
          u.c = s->cpml_ce[a] + s->L.offset[a];
        } else {
          lo = side == 0 ? 0 : n - th;
          hi = side == 0 ? th : n;
          u.o1 = s->s[a];
          u.o0 = 0;
          u.b = s->cpml_bh[a] + s->L.offset[a];
          u.c = s->cpml_ch[a] + s->L.offset[a];
        }
        const size_t ulo = s->upd[t].lo[a], uhi = ulo + s->upd[t].cnt[a];
        if (lo < ulo) lo = ulo;
        if (hi > uhi) hi = uhi;
        if (hi <= lo) continue;
        u.box.lo[a] = lo;
        u.box.cnt[a] = hi - lo;
        gm_status st = add_term(s, &u, err);
        if (st != GM_OK) return st;
        /* E: E += cb (+ψ_b − ψ_c); H: H −= cbh (+ψ_b − ψ_c) */
        fill_weights(s, &s->cpml[s->n_cpml - 1], e ? term_sign : -term_sign);
      }
    }
  }
  return GM_OK;
}

static void apply_term(gm_yee *s, yee_cpml_term *t, int p) {
  double *restrict target = s->f[p][t->target];
  const double *restrict src = s->f[p][t->src];
  double *restrict psi = t->psi + (size_t)p * t->n;
  const double *restrict w = t->w;
  const double *bb = t->b, *cc = t->c;
  const long i0 = (long)t->box.lo[0], ni = (long)t->box.cnt[0];
  const long j0 = (long)t->box.lo[1], nj = (long)t->box.cnt[1];
  const long k0 = (long)t->box.lo[2], nk = (long)t->box.cnt[2];
  const long m0 = (long)t->m[0], m1 = (long)t->m[1], m2 = (long)t->m[2];
  const long o1 = t->o1, o0 = t->o0;
  const double ih = t->inv_h;
  const int nt = s->n_threads;
  YEE_OMP(omp parallel for collapse(2) schedule(static) num_threads(nt)
              if (t->n > YEE_OMP_MIN))
  for (long k = 0; k < nk; ++k)
    for (long j = 0; j < nj; ++j) {
      const long row = (long)yee_idx(&s->L, i0, j0 + j, k0 + k);
      const long lrow = (k * nj + j) * ni;
      const long prow = (j0 + j) * m1 + (k0 + k) * m2;
      for (long i = 0; i < ni; ++i) {
        const long q = row + i, l = lrow + i, pos = prow + (i0 + i) * m0;
        psi[l] = bb[pos] * psi[l] + cc[pos] * (src[q + o1] - src[q + o0]) * ih;
        target[q] += w[l] * psi[l];
      }
    }
}

void yee_cpml_apply(gm_yee *s, int e_field) {
  for (size_t t = 0; t < s->n_cpml; ++t) {
    if (s->cpml[t].e_field != e_field) continue;
    for (int p = 0; p < s->n_parts; ++p) apply_term(s, &s->cpml[t], p);
  }
}
