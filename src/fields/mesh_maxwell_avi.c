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
 *   D_e ← D_e − J_e(t)(t − τ_J,e), τ_J,e ← t            (currents on the edges touched, once
 *                                                        per event time; avi_currents)
 *   τ_σ ← t, next event at t_σ^{k+1}.
 * B is stored relative to B(t_0) so that no vector potential of the initial B is needed.
 * Faces with bitwise equal steps form a group whose events share their times; the binary
 * min-heap (allocated at create time) holds groups, so one heap operation serves a whole group
 * and the faces of a group are swept in ascending order like a leapfrog half-step (with equal
 * steps everywhere there is one group and the scheme is the leapfrog's order of operations).
 * Nothing here allocates after create. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "fields/mesh_maxwell.h"

static int heap_less(const mm_event *a, const mm_event *b) {
  return a->t < b->t || (a->t == b->t && a->g < b->g); /* ties: the group of smaller step first */
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

typedef struct face_key { double dt; size_t f; } face_key;

static int face_key_cmp(const void *pa, const void *pb) {
  const face_key *a = pa, *b = pb;
  if (a->dt != b->dt) return a->dt < b->dt ? -1 : 1;
  return a->f < b->f ? -1 : a->f > b->f;
}

/* Groups of faces with bitwise equal steps (ascending step, faces ascending inside a group) and
 * the heap of their next times. At create time only. */
gm_status mm_groups_build(gm_mesh_maxwell *s) {
  face_key *k = malloc((s->nf ? s->nf : 1) * sizeof *k);
  s->group_face = malloc((s->nf ? s->nf : 1) * sizeof(size_t));
  s->group_start = malloc((s->nf + 1) * sizeof(size_t));
  s->group_dt = malloc((s->nf ? s->nf : 1) * sizeof(double));
  s->k_g = calloc(s->nf ? s->nf : 1, sizeof(size_t));
  s->heap = malloc((s->nf ? s->nf : 1) * sizeof(mm_event));
  if (!k || !s->group_face || !s->group_start || !s->group_dt || !s->k_g || !s->heap) {
    free(k);
    return GM_ENOMEM;
  }
  size_t n = 0;
  for (size_t f = 0; f < s->nf; ++f) /* no interior edge: B_σ never changes, no events */
    if (isfinite(s->face_dt[f])) k[n++] = (face_key){s->face_dt[f], f};
  qsort(k, n, sizeof *k, face_key_cmp);
  s->n_groups = 0;
  for (size_t i = 0; i < n; ++i) {
    if (i == 0 || k[i].dt != k[i - 1].dt) {
      s->group_start[s->n_groups] = i;
      s->group_dt[s->n_groups++] = k[i].dt;
    }
    s->group_face[i] = k[i].f;
  }
  s->group_start[s->n_groups] = n;
  free(k);
  mm_heap_build(s);
  return GM_OK;
}

void mm_heap_build(gm_mesh_maxwell *s) {
  s->heap_n = 0;
  for (size_t g = 0; g < s->n_groups; ++g) {
    s->heap[s->heap_n].t = s->group_dt[g];
    s->heap[s->heap_n++].g = g;
  }
  for (size_t i = s->heap_n / 2; i-- > 0;) heap_down(s, i);
}

gm_status mm_avi_currents_build(gm_mesh_maxwell *s, size_t n_cur) {
  size_t nnz = 0;
  for (size_t i = 0; i < n_cur; ++i) nnz += s->cur[i].n;
  size_t *start = calloc(s->ne + 1, sizeof *start), *src = malloc(nnz * sizeof *src);
  size_t *list = malloc(nnz * sizeof *list);
  double *w = malloc(nnz * sizeof *w), *tau = s->j_tau ? s->j_tau : calloc(s->ne, sizeof *tau);
  if (!start || !src || !w || !tau || !list) {
    free(start); free(src); free(w); free(list);
    if (tau != s->j_tau) free(tau);
    return GM_ENOMEM;
  }
  for (size_t i = 0; i < n_cur; ++i)
    for (size_t j = 0; j < s->cur[i].n; ++j) ++start[s->cur[i].edges[j] + 1];
  for (size_t e = 0; e < s->ne; ++e) start[e + 1] += start[e];
  for (size_t i = 0; i < n_cur; ++i) /* fill, then shift start back */
    for (size_t j = 0; j < s->cur[i].n; ++j) {
      const size_t p = start[s->cur[i].edges[j]]++;
      src[p] = i;
      w[p] = s->cur[i].w[j];
    }
  for (size_t e = s->ne; e > 0; --e) start[e] = start[e - 1];
  start[0] = 0;
  size_t n_list = 0;
  for (size_t e = 0; e < s->ne; ++e)
    if (start[e + 1] != start[e]) list[n_list++] = e;
  free(s->j_start); free(s->j_src); free(s->j_w); free(s->j_edges);
  s->j_start = start; s->j_src = src; s->j_w = w; s->j_tau = tau;
  s->j_edges = list; s->n_j_edges = n_list;
  return GM_OK;
}

/* The current impulses at an event at time t: every current edge a face of the group touched
 * (its A was brought to t: tau_e = t) and not yet served at t gets D_e −= J_e(t)(t − τ_J,e)
 * (J at t, as the face impulse takes H at t), E_e refreshed, the charge booked at e's ends as
 * the leapfrog books it. After the sweep, not inside it: faces later in the sweep see E_e only
 * through A_e −= E_e (t − τ_e) = 0, so the order is immaterial, and the sweep carries no test. */
static void avi_currents(gm_mesh_maxwell *s, double t) {
  const size_t *ev = gm_complex_simplices(s->cx, 1);
  for (size_t k = 0; k < s->n_j_edges; ++k) {
    const size_t e = s->j_edges[k];
    if (s->tau_e[e] != t || s->j_tau[e] == t) continue;
    double J = 0.0;
    for (size_t p = s->j_start[e]; p < s->j_start[e + 1]; ++p)
      J += s->j_w[p] * gm_waveform_value(&s->cur[s->j_src[p]].wave, t);
    const double q = J * (t - s->j_tau[e]);
    s->D[e] -= q;
    s->E[e] = s->inv_eps[e] * s->D[e];
    s->rho[ev[2 * e]] -= q;
    s->rho[ev[2 * e + 1]] += q;
    s->j_tau[e] = t;
  }
}

/* The events of the faces of one group at time t, in ascending face order. */
static void avi_group_event(gm_mesh_maxwell *s, size_t g, double t) {
  const size_t *restrict rs = s->d1->row_start, *restrict col = s->d1->col;
  const double *restrict val = s->d1->val, *restrict nu = s->nu_star, *restrict ie = s->inv_eps;
  const double *restrict B0 = s->B0;
  double *restrict A = s->A, *restrict tau_e = s->tau_e, *restrict E = s->E, *restrict D = s->D;
  double *restrict B = s->B, *restrict tau_f = s->tau_f;
  size_t edge_updates = 0;
  const size_t *faces = s->group_face;
  for (size_t i = s->group_start[g]; i < s->group_start[g + 1]; ++i) {
    const size_t f = faces[i];
    double b = B0[f];
    for (size_t p = rs[f]; p < rs[f + 1]; ++p) {
      const size_t e = col[p];
      A[e] -= E[e] * (t - tau_e[e]);
      tau_e[e] = t;
      b += val[p] * A[e];
    }
    B[f] = b;
    const double hw = nu[f] * b * (t - tau_f[f]);
    for (size_t p = rs[f]; p < rs[f + 1]; ++p) {
      const size_t e = col[p];
      if (ie[e] == 0.0) continue; /* PEC edge */
      D[e] += val[p] * hw;
      E[e] = ie[e] * D[e];
      ++edge_updates;
    }
    tau_f[f] = t;
  }
  if (s->n_j_edges) avi_currents(s, t);
  const size_t nfg = s->group_start[g + 1] - s->group_start[g];
  s->edge_updates += edge_updates;
  s->face_updates += nfg;
  s->step += nfg;
  s->t = t;
  s->heap[0].t = (double)(++s->k_g[g] + 1) * s->group_dt[g]; /* g is the top: re-key, sift */
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

void mm_avi_sync_a(const gm_mesh_maxwell *s, double t, double *out) {
  for (size_t e = 0; e < s->ne; ++e) out[e] = s->A[e] - s->E[e] * (t - s->tau_e[e]);
}

/* Probes of the AVI at time ts (<= the next event): fields synchronised to ts. */
static gm_status avi_sample(gm_mesh_maxwell *s, double ts) {
  const double t_keep = s->t;
  s->t = ts; /* sync_b reads s->t */
  gm_mesh_maxwell_sync_b(s, s->work_f);
  mm_avi_sync_a(s, ts, s->work_e);
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
    const size_t g = s->heap[0].g;
    const double te = s->heap[0].t;
    while (sampling && s->next_sample < te) {
      if ((st = avi_sample(s, s->next_sample)) != GM_OK) return st;
      s->next_sample = (double)(s->n_samples + 1) * s->sample_dt;
    }
    avi_group_event(s, g, te);
  }
  while (sampling && s->next_sample <= t) {
    if ((st = avi_sample(s, s->next_sample)) != GM_OK) return st;
    s->next_sample = (double)(s->n_samples + 1) * s->sample_dt;
  }
  if (t > s->t) s->t = t;
  if (gm_first_nonfinite(s->ne, s->E) != s->ne)
    return gm_fail(s->errmsg, sizeof s->errmsg, GM_EDOMAIN,
                   "advance_to: the fields became non-finite by t = %.6g (%zu events)", s->t,
                   s->step);
  return GM_OK;
}
