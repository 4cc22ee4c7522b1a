/* Mesh Maxwell solver: the Bossavit–Kettunen leapfrog (seed 000 §3.4.2, notes A11), sources,
 * observers. Nothing here allocates. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "fields/mesh_maxwell.h"

gm_status gm_mesh_maxwell_add_current(gm_mesh_maxwell *s, size_t n_edges, const size_t *edges,
                                      const double *weights, const gm_waveform *wave,
                                      size_t *id) {
  if (s->opt.scheme == GM_MESH_AVI && s->started)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "add_current: the AVI takes its currents before the first advance");
  if (!n_edges || !edges || !wave)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "add_current: no edges or waveform");
  gm_error e;
  if (gm_waveform_check(wave, &e) != GM_OK)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "add_current: %s", e.message);
  for (size_t i = 0; i < n_edges; ++i) {
    if (edges[i] >= s->ne)
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                     "add_current: edge %zu out of range (%zu edges)", edges[i], s->ne);
    if (s->bnd_e[edges[i]])
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                     "add_current: edge %zu lies on the PEC boundary", edges[i]);
    if (weights && !isfinite(weights[i]))
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_EDOMAIN, "add_current: weight %zu", i);
  }
  mm_current *grown = realloc(s->cur, (s->n_cur + 1) * sizeof *grown);
  if (!grown) return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "add_current: no memory");
  s->cur = grown;
  mm_current *c = &s->cur[s->n_cur];
  c->n = n_edges;
  c->edges = malloc(n_edges * sizeof(size_t));
  c->w = malloc(n_edges * sizeof(double));
  if (!c->edges || !c->w) {
    free(c->edges); free(c->w);
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "add_current: no memory");
  }
  memcpy(c->edges, edges, n_edges * sizeof(size_t));
  for (size_t i = 0; i < n_edges; ++i) c->w[i] = weights ? weights[i] : 1.0;
  c->wave = *wave;
  if (s->opt.scheme == GM_MESH_AVI && mm_avi_currents_build(s, s->n_cur + 1) != GM_OK) {
    free(c->edges); free(c->w);
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "add_current: no memory");
  }
  if (id) *id = s->n_cur;
  ++s->n_cur;
  return GM_OK;
}

gm_status gm_mesh_maxwell_add_observer(gm_mesh_maxwell *s, size_t every,
                                       gm_mesh_maxwell_observer_fn fn, void *ctx) {
  if (!every || !fn)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "add_observer: every >= 1 and fn");
  mm_observer *grown = realloc(s->obs, (s->n_obs + 1) * sizeof *grown);
  if (!grown) return gm_fail(s->errmsg, sizeof s->errmsg, GM_ENOMEM, "add_observer: no memory");
  s->obs = grown;
  s->obs[s->n_obs++] = (mm_observer){every, fn, ctx};
  return GM_OK;
}

gm_status mm_observe(gm_mesh_maxwell *s, size_t counter) {
  for (size_t i = 0; i < s->n_obs; ++i)
    if (counter % s->obs[i].every == 0 && s->obs[i].fn(s->obs[i].ctx, s) != 0)
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_ECALLBACK,
                     "observer %zu stopped the run at %zu", i, counter);
  return GM_OK;
}

/* − Δt J^n on the source edges, charge booked; E refreshed there when the star is diagonal. */
static void apply_currents(gm_mesh_maxwell *s, double t_n, int refresh_e) {
  const double dt = s->dt;
  const size_t *ev = gm_complex_simplices(s->cx, 1);
  for (size_t i = 0; i < s->n_cur; ++i) {
    const mm_current *c = &s->cur[i];
    const double g = gm_waveform_value(&c->wave, t_n);
    for (size_t j = 0; j < c->n; ++j) {
      const size_t e = c->edges[j];
      const double J = c->w[j] * g;
      s->D[e] -= dt * J;
      if (refresh_e) s->E[e] = s->inv_eps[e] * s->D[e];
      /* div J = −d₀ᵀJ: +J at the tail, −J at the head; ρ ← ρ − Δt div J */
      s->rho[ev[2 * e]] -= dt * J;
      s->rho[ev[2 * e + 1]] += dt * J;
    }
  }
}

/* One leapfrog step from (B^n, E^{n−½}) to (B^{n+1}, E^{n+½}). With the diagonal star the step
 * is two gather passes, the same memory traffic as the CSR floor (d₁ᵀ then d₁): Ampère with the
 * fused operator d₁ᵀ⋆_ν (PEC rows zero) also writes E = ⋆_ε⁻¹D, Faraday reads it. */
static void leapfrog_step(gm_mesh_maxwell *s) {
  const double dt = s->dt, t_n = (double)s->step * dt;
  const gm_csr *d1 = s->d1;
  double *restrict D = s->D, *restrict E = s->E, *restrict B = s->B;
  if (s->curl_h) {
    const gm_csr *K = s->curl_h;
    const size_t *rs = K->row_start, *col = K->col;
    const double *val = K->val, *ie = s->inv_eps;
    for (size_t e = 0; e < s->ne; ++e) {                                  /* Ampère */
      double curl = 0.0;
      for (size_t p = rs[e]; p < rs[e + 1]; ++p) curl += val[p] * B[col[p]];
      const double d = D[e] + dt * curl;             /* D^{n+½} = D^{n−½} + Δt d₁ᵀ⋆_ν B^n */
      D[e] = d;
      E[e] = ie[e] * d;                              /* E = ⋆_ε⁻¹ D, 0 on PEC edges */
    }
    if (s->n_cur) apply_currents(s, t_n, 1);
  } else {
    double *H = s->work_f;
    mm_apply_nu(s, B, H);                                                 /* H^n = ⋆_ν B^n */
    const gm_csr *d1t = s->d1t;
    for (size_t e = 0; e < s->ne; ++e) {                                  /* Ampère */
      if (s->inv_eps[e] == 0.0) continue;                                 /* PEC edge */
      double curl = 0.0;
      for (size_t p = d1t->row_start[e]; p < d1t->row_start[e + 1]; ++p)
        curl += d1t->val[p] * H[d1t->col[p]];
      D[e] += dt * curl;                             /* D^{n+½} = D^{n−½} + Δt d₁ᵀH^n */
    }
    apply_currents(s, t_n, 0);
    mm_solve_eps(s, D, E);                                                /* E = ⋆_ε⁻¹ D */
  }
  const size_t *rs = d1->row_start, *col = d1->col;
  const double *val = d1->val;
  for (size_t f = 0; f < s->nf; ++f) {                                    /* Faraday */
    double curl = 0.0;
    for (size_t p = rs[f]; p < rs[f + 1]; ++p) curl += val[p] * E[col[p]];
    B[f] -= dt * curl;                               /* B^{n+1} = B^n − Δt d₁E^{n+½} */
  }
  ++s->step;
  s->t = (double)s->step * dt;
  s->face_updates += s->nf;
  s->edge_updates += s->ne;
}

gm_status mm_avi_advance_to(gm_mesh_maxwell *s, double t);

gm_status gm_mesh_maxwell_advance(gm_mesh_maxwell *s, size_t n_steps) {
  if (s->opt.scheme != GM_MESH_LEAPFROG)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "advance: the AVI has no global step; use advance_to");
  for (size_t i = 0; i < s->n_probe; ++i)
    if (s->probe[i].cap - s->probe[i].n < n_steps)
      return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                     "advance: probe %zu has room for %zu more samples, not %zu", i,
                     s->probe[i].cap - s->probe[i].n, n_steps);
  gm_status st;
  if (!s->started) {
    s->started = 1;
    if ((st = mm_observe(s, 0)) != GM_OK) return st;
  }
  /* Non-finite fields are looked for every MM_FINITE_EVERY steps (a pass over E and B, under
     1 % of the steps' work), so a blown-up run stops near where it blew up, not at the end. */
  enum { MM_FINITE_EVERY = 64 };
  double t_finite = s->t;
  for (size_t k = 0; k < n_steps; ++k) {
    leapfrog_step(s);
    if ((st = mm_probe_record(s, s->t, s->B)) != GM_OK) return st;
    if (s->n_obs && (st = mm_observe(s, s->step)) != GM_OK) return st;
    if (s->step % MM_FINITE_EVERY == 0 || k + 1 == n_steps) {
      if (gm_first_nonfinite(s->ne, s->E) != s->ne || gm_first_nonfinite(s->nf, s->B) != s->nf)
        return gm_fail(s->errmsg, sizeof s->errmsg, GM_EDOMAIN,
                       "advance: the fields became non-finite between t = %.6g and t = %.6g "
                       "(step %zu)", t_finite, s->t, s->step);
      t_finite = s->t;
    }
  }
  return GM_OK;
}

gm_status gm_mesh_maxwell_advance_to(gm_mesh_maxwell *s, double t) {
  if (!isfinite(t))
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL, "advance_to: non-finite time");
  if (s->opt.scheme == GM_MESH_AVI) return mm_avi_advance_to(s, t);
  const double n = floor(t / s->dt * (1.0 + 1e-14));
  if (n <= (double)s->step) return GM_OK;
  return gm_mesh_maxwell_advance(s, (size_t)n - s->step);
}
