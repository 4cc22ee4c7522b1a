/* Asynchronous variational integrator for Maxwell on a simplicial mesh (seed 000 §3.4.3,
 * Fig. 3.6, eqs. 3.12–3.13), with the three corrections of notes A12: the stars in
 * "H_σ ← ⋆_μ B_σ" and "E_e ← ⋆_ε D_e" are the inverse ones (here H = ⋆_ν B, E = ⋆_ε⁻¹ D),
 * τ_e is set to t after A_e is brought up to date (the figure never updates it), and the
 * first time is t_σ^1, not t_α^1.
 *
 * Each face σ has its own step Δt_σ and times t_σ^k = t_0 + k Δt_σ (computed by multiplication,
 * so equal steps give exactly equal times and the scheme is the leapfrog). An event (t, σ):
 *   A_e ← A_e − E_e (t − τ_e), τ_e ← t               for the edges e of σ  (A = −∫E dt)
 *   B_σ ← B_σ(t_0) + (d₁A)_σ                           (Faraday, eq. 3.12)
 *   H_σ ← ⋆_ν B_σ
 *   D_e ← D_e + d₁(σ,e) H_σ (t − τ_σ), E_e ← ⋆_ε⁻¹D_e  (Ampère impulse, eq. 3.13; Lew et al.'s
 *                                                        elemental impulse over the face's last
 *                                                        interval)
 *   τ_σ ← t, next event at t_σ^{k+1}.
 * B is stored relative to B(t_0) so that no vector potential of the initial B is needed.
 * Events come from a binary min-heap allocated at create time; nothing here allocates. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/internal.h"
#include "fields/mesh_maxwell.h"

static int heap_less(const mm_event *a, const mm_event *b) {
  return a->t < b->t || (a->t == b->t && a->f < b->f); /* ties: lower face first */
}

static void heap_down(gm_mesh_maxwell *s, size_t i) {
  mm_event *h = s->heap;
  const mm_event x = h[i];
  for (;;) {
    const size_t l = 2 * i + 1, r = l + 1;
    if (l >= s->heap_n) break;
    const size_t c = (r < s->heap_n && heap_less(&h[r], &h[l])) ? r : l;
    if (!heap_less(&h[c], &x)) break;
    h[i] = h[c];
    i = c;
  }
  h[i] = x;
}

void mm_heap_build(gm_mesh_maxwell *s) {
  s->heap_n = 0;
  for (size_t f = 0; f < s->nf; ++f) {
    if (!isfinite(s->face_dt[f])) continue; /* no interior edge: B_σ never changes */
    s->heap[s->heap_n].t = s->face_dt[f];
    s->heap[s->heap_n++].f = f;
  }
  for (size_t i = s->heap_n / 2; i-- > 0;) heap_down(s, i);
}

static void avi_event(gm_mesh_maxwell *s, size_t f, double t) {
  const gm_csr *d1 = s->d1;
  double b = s->B0[f];
  for (size_t p = d1->row_start[f]; p < d1->row_start[f + 1]; ++p) {
    const size_t e = d1->col[p];
    s->A[e] -= s->E[e] * (t - s->tau_e[e]);
    s->tau_e[e] = t;
    b += d1->val[p] * s->A[e];
  }
  s->B[f] = b;
  const double h = s->nu_star[f] * b, w = t - s->tau_f[f];
  for (size_t p = d1->row_start[f]; p < d1->row_start[f + 1]; ++p) {
    const size_t e = d1->col[p];
    if (s->inv_eps[e] == 0.0) continue; /* PEC edge */
    s->D[e] += d1->val[p] * h * w;
    s->E[e] = s->inv_eps[e] * s->D[e];
    ++s->edge_updates;
  }
  s->tau_f[f] = t;
  ++s->face_updates;
  ++s->step;
  s->t = t;
  s->heap[0].t = (double)(++s->k_f[f] + 1) * s->face_dt[f]; /* f is the top: re-key, sift */
  heap_down(s, 0);
}

void gm_mesh_maxwell_sync_b(const gm_mesh_maxwell *s, double *B) {
  if (s->opt.scheme == GM_MESH_LEAPFROG) {
    memcpy(B, s->B, s->nf * sizeof(double));
    return;
  }
  const gm_csr *d1 = s->d1;
  for (size_t f = 0; f < s->nf; ++f) {
    double b = s->B0[f];
    for (size_t p = d1->row_start[f]; p < d1->row_start[f + 1]; ++p) {
      const size_t e = d1->col[p];
      b += d1->val[p] * (s->A[e] - s->E[e] * (s->t - s->tau_e[e]));
    }
    B[f] = b;
  }
}

gm_status gm_mesh_maxwell_set_sample_dt(gm_mesh_maxwell *s, double sample_dt) {
  if (s->opt.scheme != GM_MESH_AVI || !(sample_dt > 0.0) || !isfinite(sample_dt) || s->started)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EINVAL,
                   "set_sample_dt: AVI only, before the first advance, > 0");
  s->sample_dt = sample_dt;
  s->next_sample = sample_dt;
  return GM_OK;
}

/* Probes of the AVI at time ts (<= the next event): fields synchronised to ts. */
static gm_status avi_sample(gm_mesh_maxwell *s, double ts) {
  const double t_keep = s->t;
  s->t = ts; /* sync_b reads s->t */
  gm_mesh_maxwell_sync_b(s, s->work_f);
  gm_status st = mm_probe_record(s, ts, s->work_f);
  ++s->n_samples;
  if (st == GM_OK && s->n_obs) st = mm_observe(s, s->n_samples);
  s->t = t_keep > ts ? t_keep : ts;
  return st;
}

gm_status mm_avi_advance_to(gm_mesh_maxwell *s, double t) {
  gm_status st;
  if (!s->started) {
    s->started = 1;
    if ((st = mm_observe(s, 0)) != GM_OK) return st;
  }
  const int sampling = s->n_probe || s->n_obs;
  while (s->heap_n && s->heap[0].t <= t) {
    const size_t f = s->heap[0].f;
    const double te = s->heap[0].t;
    while (sampling && s->next_sample < te) {
      if ((st = avi_sample(s, s->next_sample)) != GM_OK) return st;
      s->next_sample = (double)(s->n_samples + 1) * s->sample_dt;
    }
    avi_event(s, f, te);
  }
  while (sampling && s->next_sample <= t) {
    if ((st = avi_sample(s, s->next_sample)) != GM_OK) return st;
    s->next_sample = (double)(s->n_samples + 1) * s->sample_dt;
  }
  if (t > s->t) s->t = t;
  if (gm_first_nonfinite(s->ne, s->E) != s->ne)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EDOMAIN,
                   "advance_to: the fields became non-finite after %zu events", s->step);
  return GM_OK;
}
