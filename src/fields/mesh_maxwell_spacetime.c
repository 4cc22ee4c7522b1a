/* Maxwell on a 2+1 prismal spacetime complex as one sparse solve (seed 000 §3.4.4, notes A13;
 * the κ-signed Lorentzian star of A7 / seed 001 §3.4).
 *
 * The complex is the 2-D triangle mesh K times the times t_n = n Δt, n = 0..N. Cells: vertices
 * (v,n); spatial edges (e,n) and temporal edges (v, n→n+1); spatial faces (f,n) and extruded
 * faces (e, n→n+1); prisms (f, n→n+1). Orientation: ∂(c × I) = (∂c) × I + (−1)^{dim c} c × ∂I,
 * so ∂(f×I) = (∂f)×I + f×{t_{n+1}} − f×{t_n} and ∂(e×I) = (∂e)×I − e×{t_{n+1}} + e×{t_n}
 * (∂∂ = 0 is checked by the test through dF = 0 on the solution).
 *
 * F = E∧dt + B is a primal 2-cochain: F(f,n) = B_f^n, F(e, n→n+1) = Δt E_e^{n+½}. The diagonal
 * star of a 2-cell σ is κ(σ) |⋆σ| / |σ| times the material, with κ = +1 for the spacelike
 * spatial faces (dual: the timelike segment of length Δt through the circumcentre, |σ| = |f|:
 * ⋆ = Δt ν_f) and κ = −1 for the extruded faces (dual: the spatial dual edge ⋆e at t_{n+½},
 * |σ| = |e| Δt: ⋆ = −⋆_ε[e] / Δt). G = ⋆F lives on dual edges; dG on the dual 2-cell of a
 * primal edge c is (Dᵀ ⋆F)_c, D the coboundary from 1- to 2-cochains of the prismal complex.
 * On a spatial edge (e,n) this is Δt (d₁ᵀ⋆_ν B^n)_e − ⋆_ε[e](E^{n+½} − E^{n−½}) = Δt J_e^n
 * (Ampère); on a temporal edge (v, n→n+1) it is −(d₀ᵀ D^{n+½})_v = −ρ_v^{n+½} (Gauss).
 *
 * The square system for x = (B⁰..B^N, Φ⁰..Φ^{N−1}), Φ^n = Δt E^{n+½}: the initial data B⁰ and
 * Φ⁰ = Δt E^{½}; dF = 0 on every prism; dG = 𝒥 on the interior spatial edges at n = 1..N−1;
 * Φ^n = 0 on PEC edges. Gauss's law (the temporal edges) is not imposed: it follows, and the
 * residuals of dF = 0 and of dG = 𝒥 on every interior spatial and temporal edge are measured
 * on the solution. Solved by UMFPACK (gm_sparse_lu). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "fields/mesh_maxwell.h"

typedef struct trip { size_t n, cap, *r, *c; double *v; } trip;

static int trip_add(trip *t, size_t r, size_t c, double v) {
  if (t->n == t->cap) {
    const size_t cap = t->cap ? 2 * t->cap : 1024;
    size_t *nr = realloc(t->r, cap * sizeof(size_t)), *nc = nr ? realloc(t->c, cap * sizeof(size_t)) : NULL;
    if (nr) t->r = nr;
    if (nc) t->c = nc;
    double *nv = nc ? realloc(t->v, cap * sizeof(double)) : NULL;
    if (!nv) return 0;
    t->v = nv;
    t->cap = cap;
  }
  t->r[t->n] = r, t->c[t->n] = c, t->v[t->n++] = v;
  return 1;
}

static void trip_free(trip *t) { free(t->r), free(t->c), free(t->v); }

gm_status gm_mesh_maxwell_spacetime(const gm_geometry *g, const double *epsilon, const double *mu,
                                    size_t n_slabs, double dt, const double *B0,
                                    const double *E_half, const double *J, double *B, double *E,
                                    gm_mesh_maxwell_spacetime_residuals *res, gm_error *err) {
  if (!g || !B0 || !E_half || !B || !E || n_slabs < 1 || !(dt > 0.0) || !isfinite(dt))
    return gm_error_set(err, GM_EINVAL, "spacetime: geometry, B0, E_half, B, E, n_slabs >= 1 "
                                        "and dt > 0 are required");
  const gm_complex *cx = gm_geometry_complex(g);
  if (gm_complex_dim(cx) != 2 || gm_complex_embedding_dim(cx) != 2)
    return gm_error_set(err, GM_EINVAL, "spacetime: needs a triangle mesh in the plane (2+1)");
  gm_mesh_maxwell *s = NULL; /* for its checks and its stars */
  gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
  gm_status st = gm_mesh_maxwell_create(g, epsilon, mu, &o, &s, err);
  if (st != GM_OK) return st;
  const size_t N = n_slabs, nv = s->nv, ne = s->ne, nf = s->nf;
  /* 2-cells: (f,n) at n nf + f (n = 0..N), (e, n→n+1) at (N+1) nf + n ne + e.
     1-cells: (e,n) at n ne + e (n = 0..N), (v, n→n+1) at (N+1) ne + n nv + v.
     3-cells: (f, n→n+1) at n nf + f. */
  const size_t n2 = (N + 1) * nf + N * ne, n1 = (N + 1) * ne + N * nv, n3 = N * nf;
  const size_t oPhi = (N + 1) * nf, oT = (N + 1) * ne;
  const gm_csr *d1 = s->d1, *d0 = s->d0;
  trip D = {0}, P = {0}, A = {0};
  double *star = malloc(n2 * sizeof(double)), *rhs = calloc(n2, sizeof(double));
  double *x = malloc(n2 * sizeof(double));
  double *dG = calloc(n1, sizeof(double)), *dF = calloc(n3, sizeof(double));
  double *rho = malloc(nv * sizeof(double));
  gm_csr *M = NULL;
  gm_sparse_lu *lu = NULL;
  st = GM_ENOMEM;
  if (!star || !rhs || !x || !dG || !dF || !rho) goto done;
  /* the coboundary D (2-cells × 1-cells) and the prisms' boundary P (3-cells × 2-cells) */
  for (size_t n = 0; n <= N; ++n)
    for (size_t f = 0; f < nf; ++f)
      for (size_t p = d1->row_start[f]; p < d1->row_start[f + 1]; ++p)
        if (!trip_add(&D, n * nf + f, n * ne + d1->col[p], d1->val[p])) goto done;
  for (size_t n = 0; n < N; ++n)
    for (size_t e = 0; e < ne; ++e) {
      const size_t r = oPhi + n * ne + e;
      if (!trip_add(&D, r, n * ne + e, 1.0) || !trip_add(&D, r, (n + 1) * ne + e, -1.0)) goto done;
      for (size_t p = d0->row_start[e]; p < d0->row_start[e + 1]; ++p)
        if (!trip_add(&D, r, oT + n * nv + d0->col[p], d0->val[p])) goto done;
    }
  for (size_t n = 0; n < N; ++n)
    for (size_t f = 0; f < nf; ++f) {
      const size_t r = n * nf + f;
      if (!trip_add(&P, r, (n + 1) * nf + f, 1.0) || !trip_add(&P, r, n * nf + f, -1.0)) goto done;
      for (size_t p = d1->row_start[f]; p < d1->row_start[f + 1]; ++p)
        if (!trip_add(&P, r, oPhi + n * ne + d1->col[p], d1->val[p])) goto done;
    }
  /* κ-signed stars: spatial faces +Δt ν (half at the first and last level: the dual segment
     is cut by the initial and final slices), extruded faces −⋆_ε / Δt */
  for (size_t n = 0; n <= N; ++n)
    for (size_t f = 0; f < nf; ++f)
      star[n * nf + f] = (n == 0 || n == N ? 0.5 : 1.0) * dt * s->nu_star[f];
  for (size_t n = 0; n < N; ++n)
    for (size_t e = 0; e < ne; ++e) star[oPhi + n * ne + e] = -s->eps_star[e] / dt;
  gm_csr *Dm = NULL, *Dt = NULL, *Pm = NULL;
  st = gm_csr_from_triplets(n2, n1, D.n, D.r, D.c, D.v, &Dm, err);
  if (st == GM_OK) st = gm_csr_from_triplets(n3, n2, P.n, P.r, P.c, P.v, &Pm, err);
  if (st == GM_OK) st = gm_csr_transpose(Dm, &Dt);
  gm_csr_free(Dm);
  if (st != GM_OK) { gm_csr_free(Pm); gm_csr_free(Dt); goto done; }
  /* dG = Dᵀ ⋆ F: scale the columns of Dᵀ by the star */
  for (size_t i = 0; i < gm_csr_nnz(Dt); ++i) Dt->val[i] *= star[Dt->col[i]];
  /* the square system, one row per unknown */
  size_t row = 0;
  for (size_t f = 0; f < nf; ++f, ++row) {                       /* B⁰ given */
    if (!trip_add(&A, row, f, 1.0)) goto fail;
    rhs[row] = B0[f];
  }
  for (size_t r = 0; r < n3; ++r, ++row) {                       /* dF = 0 on the prisms */
    for (size_t p = Pm->row_start[r]; p < Pm->row_start[r + 1]; ++p)
      if (!trip_add(&A, row, Pm->col[p], Pm->val[p])) goto fail;
  }
  for (size_t e = 0; e < ne; ++e, ++row) {                       /* Φ⁰ = Δt E^{½} */
    if (!trip_add(&A, row, oPhi + e, 1.0)) goto fail;
    rhs[row] = s->bnd_e[e] ? 0.0 : dt * E_half[e];
  }
  for (size_t n = 1; n < N; ++n)
    for (size_t e = 0; e < ne; ++e, ++row) {
      if (s->bnd_e[e]) {                                         /* PEC */
        if (!trip_add(&A, row, oPhi + n * ne + e, 1.0)) goto fail;
        continue;
      }
      const size_t c = n * ne + e;                               /* dG = 𝒥 (Ampère) */
      for (size_t p = Dt->row_start[c]; p < Dt->row_start[c + 1]; ++p)
        if (!trip_add(&A, row, Dt->col[p], Dt->val[p])) goto fail;
      rhs[row] = J ? dt * J[n * ne + e] : 0.0;
    }
  st = gm_csr_from_triplets(n2, n2, A.n, A.r, A.c, A.v, &M, err);
  if (st == GM_OK) st = gm_sparse_lu_create(M, &lu, err);
  if (st == GM_OK) st = gm_sparse_lu_solve(lu, rhs, x);
  if (st != GM_OK) goto fail;
  for (size_t n = 0; n <= N; ++n) memcpy(B + n * nf, x + n * nf, nf * sizeof(double));
  for (size_t n = 0; n < N; ++n)
    for (size_t e = 0; e < ne; ++e) E[n * ne + e] = x[oPhi + n * ne + e] / dt;
  if (res) { /* residuals on the solution, relative to the largest term of each equation */
    memset(res, 0, sizeof *res);
    gm_csr_matvec(Pm, 1.0, x, 0.0, dF);
    double scale = 0.0;
    for (size_t i = 0; i < n2; ++i) scale = fmax(scale, fabs(x[i]));
    for (size_t r = 0; r < n3; ++r) res->dF = fmax(res->dF, fabs(dF[r]));
    res->dF /= scale > 0.0 ? scale : 1.0;
    gm_csr_matvec(Dt, 1.0, x, 0.0, dG);
    double gscale = 0.0;
    for (size_t i = 0; i < gm_csr_nnz(Dt); ++i) gscale = fmax(gscale, fabs(Dt->val[i] * x[Dt->col[i]]));
    for (size_t n = 1; n < N; ++n)
      for (size_t e = 0; e < ne; ++e)
        if (!s->bnd_e[e])
          res->dG_ampere = fmax(res->dG_ampere, fabs(dG[n * ne + e] - (J ? dt * J[n * ne + e] : 0.0)));
    /* Gauss: 𝒥 on (v,n) is −ρ^{n+½} with div D = −d₀ᵀD (outflow at the tail, as
       gm_mesh_maxwell_gauss); ρ^{½} from the initial data, then moved by the currents' charge
       Δt div J^n; interior vertices only (the PEC walls carry surface charge) */
    for (size_t v = 0; v < nv; ++v) rho[v] = dG[oT + v];
    for (size_t n = 1; n < N; ++n) {
      for (size_t e = 0; J && e < ne; ++e) /* dG on (v,n) = −d₀ᵀD: it moves by +Δt d₀ᵀJ^n */
        for (size_t p = d0->row_start[e]; p < d0->row_start[e + 1] && !s->bnd_e[e]; ++p)
          rho[d0->col[p]] += dt * d0->val[p] * J[n * ne + e];
      for (size_t v = 0; v < nv; ++v)
        if (!s->bnd_v[v]) res->dG_gauss = fmax(res->dG_gauss, fabs(dG[oT + n * nv + v] - rho[v]));
    }
    res->dG_ampere /= gscale > 0.0 ? gscale : 1.0;
    res->dG_gauss /= gscale > 0.0 ? gscale : 1.0;
    res->unknowns = n2;
  }
  st = GM_OK;
fail:
  gm_csr_free(Pm);
  gm_csr_free(Dt);
done:
  if (st == GM_ENOMEM && err && !err->message[0]) gm_error_set(err, GM_ENOMEM, "spacetime: out of memory");
  trip_free(&D), trip_free(&P), trip_free(&A);
  free(star), free(rhs), free(x), free(dG), free(dF), free(rho);
  gm_csr_free(M);
  gm_sparse_lu_free(lu);
  gm_mesh_maxwell_free(s);
  return st;
}
