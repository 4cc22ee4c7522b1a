/* The discrete Levi-Civita connection of tetrahedral meshes as an SO(3)-valued dual 1-form and
 * its curvature on dual faces (seed 001 §4 "discrete Levi-Civita connection", notes §1F; seed 000
 * §4.2.2: holonomy is the ordered product of the dual-edge elements around a dual cycle).
 * Conventions in include/geomint/dec.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dec/internal.h"
#include "geomint/lie.h"

static void sort4(const size_t *in, size_t *out) {
  memcpy(out, in, 4 * sizeof *out);
  for (int i = 1; i < 4; ++i)
    for (int j = i; j > 0 && out[j - 1] > out[j]; --j) {
      size_t t = out[j];
      out[j] = out[j - 1];
      out[j - 1] = t;
    }
}

/* Local coordinates P (4 × 3) of tet t's ascending vertices in its frame; 0 or −1 (degenerate). */
static int tet_local(const gm_complex *cx, size_t t, size_t *v, double *P) {
  const size_t N = cx->N;
  sort4(cx->simplices[3] + 4 * t, v);
  double e[3][GM_DEC_MAX_EMBED];
  for (int k = 0; k < 3; ++k) {
    for (size_t j = 0; j < N; ++j) e[k][j] = cx->x[N * v[k + 1] + j] - cx->x[N * v[0] + j];
    for (int l = 0; l < k; ++l) { /* modified Gram–Schmidt, twice for accuracy */
      for (int pass = 0; pass < 2; ++pass) {
        double d = 0.0;
        for (size_t j = 0; j < N; ++j) d += e[k][j] * e[l][j];
        for (size_t j = 0; j < N; ++j) e[k][j] -= d * e[l][j];
      }
    }
    double r = 0.0;
    for (size_t j = 0; j < N; ++j) r += e[k][j] * e[k][j];
    r = sqrt(r);
    if (!(r > 0.0) || !isfinite(r)) return -1;
    for (size_t j = 0; j < N; ++j) e[k][j] /= r;
  }
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      double d = 0.0;
      for (size_t j = 0; j < N; ++j) d += (cx->x[N * v[i] + j] - cx->x[N * v[0] + j]) * e[k][j];
      P[3 * i + k] = k == 2 ? d * cx->orient[t] : d;
    }
  return 0;
}

/* Frame (columns e1, e2, e3) of the triangle with ascending vertices (p, q, r) in tet coords. */
static void face_frame(const size_t *v, const double *P, const size_t *tri, double *F) {
  const double *a = NULL, *b = NULL, *c = NULL;
  for (int i = 0; i < 4; ++i) {
    if (v[i] == tri[0]) a = P + 3 * i;
    if (v[i] == tri[1]) b = P + 3 * i;
    if (v[i] == tri[2]) c = P + 3 * i;
  }
  double e1[3], e2[3], e3[3];
  for (int k = 0; k < 3; ++k) e1[k] = b[k] - a[k], e2[k] = c[k] - a[k];
  double r = gm_vec3_norm(e1);
  for (int k = 0; k < 3; ++k) e1[k] /= r;
  double d = gm_vec3_dot(e2, e1);
  for (int k = 0; k < 3; ++k) e2[k] -= d * e1[k];
  r = gm_vec3_norm(e2);
  for (int k = 0; k < 3; ++k) e2[k] /= r;
  gm_vec3_cross(e1, e2, e3);
  for (int k = 0; k < 3; ++k) F[3 * k] = e1[k], F[3 * k + 1] = e2[k], F[3 * k + 2] = e3[k];
}

gm_status gm_dec_levi_civita_3d(const gm_complex *cx, double *transport) {
  if (cx == NULL || transport == NULL || cx->n != 3) return GM_EINVAL;
  const size_t nf = cx->count[2];
  for (size_t f = 0; f < nf; ++f) {
    double *R = transport + 9 * f;
    const size_t t0 = cx->cofaces[2 * f], t1 = cx->cofaces[2 * f + 1];
    if (t1 == SIZE_MAX) {
      memset(R, 0, 9 * sizeof *R);
      R[0] = R[4] = R[8] = 1.0;
      continue;
    }
    size_t v0[4], v1[4];
    double P0[12], P1[12], F0[9], F1[9];
    if (tet_local(cx, t0, v0, P0) != 0 || tet_local(cx, t1, v1, P1) != 0) return GM_EDOMAIN;
    const size_t *tri = cx->simplices[2] + 3 * f;
    face_frame(v0, P0, tri, F0);
    face_frame(v1, P1, tri, F1);
    gm_mat3_mul_nt(F1, F0, R); /* F1 F0ᵀ: T0 coordinates → T1 coordinates */
  }
  return GM_OK;
}

/* dihedral angle at edge (a, b) of a tet in local coordinates, c and d the other two vertices */
static double dihedral(const double *a, const double *b, const double *c, const double *d) {
  double u[3], wc[3], wd[3], x[3];
  for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], wc[k] = c[k] - a[k], wd[k] = d[k] - a[k];
  const double uu = gm_vec3_dot(u, u), pc = gm_vec3_dot(wc, u) / uu, pd = gm_vec3_dot(wd, u) / uu;
  for (int k = 0; k < 3; ++k) wc[k] -= pc * u[k], wd[k] -= pd * u[k];
  gm_vec3_cross(wc, wd, x);
  return atan2(gm_vec3_norm(x), gm_vec3_dot(wc, wd));
}

static int local_index(const size_t *v, size_t x) {
  for (int i = 0; i < 4; ++i)
    if (v[i] == x) return i;
  return -1;
}

gm_status gm_dec_curvature_3d(const gm_complex *cx, const double *transport, double *holonomy,
                              double *angle, double *deficit, gm_error *err) {
  if (cx == NULL || transport == NULL || cx->n != 3)
    return gm_error_set(err, GM_EINVAL, "curvature 3d: need a tetrahedral complex and its transport");
  const size_t ne = cx->count[1], nt = cx->count[3];
  /* edge → tets (CSR) */
  size_t *start = calloc(ne + 1, sizeof *start), *list = malloc(6 * nt * sizeof *list);
  size_t *fill = calloc(ne, sizeof *fill);
  if (start == NULL || list == NULL || fill == NULL) {
    free(start), free(list), free(fill);
    return gm_error_set(err, GM_ENOMEM, "curvature 3d: out of memory");
  }
  gm_status st = GM_OK;
  for (int pass = 0; pass < 2; ++pass)
    for (size_t t = 0; t < nt; ++t) {
      size_t v[4];
      sort4(cx->simplices[3] + 4 * t, v);
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const size_t e = gm_complex_find(cx, 1, (const size_t[2]){v[i], v[j]});
          if (pass == 0) ++start[e + 1];
          else list[start[e] + fill[e]++] = t;
        }
      if (pass == 0 && t + 1 == nt)
        for (size_t e = 0; e < ne; ++e) start[e + 1] += start[e];
    }
  for (size_t e = 0; e < ne && st == GM_OK; ++e) {
    const size_t a = cx->simplices[1][2 * e], b = cx->simplices[1][2 * e + 1];
    const int interior = !cx->boundary[1][e];
    double sum = 0.0;
    for (size_t i = start[e]; i < start[e + 1]; ++i) {
      size_t v[4];
      double P[12];
      if (tet_local(cx, list[i], v, P) != 0) {
        st = gm_error_set(err, GM_EDOMAIN, "curvature 3d: tet %zu is degenerate", list[i]);
        break;
      }
      const int ia = local_index(v, a), ib = local_index(v, b);
      int ic = -1, id = -1;
      for (int k = 0; k < 4; ++k)
        if (k != ia && k != ib) {
          if (ic < 0) ic = k;
          else id = k;
        }
      sum += dihedral(P + 3 * ia, P + 3 * ib, P + 3 * ic, P + 3 * id);
    }
    if (st != GM_OK) break;
    if (deficit) deficit[e] = (interior ? 2.0 : 1.0) * GM_PI - sum;
    double H[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    double ang = 0.0;
    if (interior) {
      /* walk the ring counterclockwise about a → b from the first tet containing e */
      const size_t t0 = list[start[e]];
      size_t t = t0, v[4], steps = 0, ring = start[e + 1] - start[e];
      double P[12];
      tet_local(cx, t, v, P);
      const int ia = local_index(v, a), ib = local_index(v, b);
      int ic = -1, id = -1;
      for (int k = 0; k < 4; ++k)
        if (k != ia && k != ib) {
          if (ic < 0) ic = k;
          else id = k;
        }
      double u[3], wc[3], wd[3], x[3];
      for (int k = 0; k < 3; ++k)
        u[k] = P[3 * ib + k] - P[3 * ia + k], wc[k] = P[3 * ic + k] - P[3 * ia + k],
        wd[k] = P[3 * id + k] - P[3 * ia + k];
      gm_vec3_cross(u, wc, x);
      /* d lies counterclockwise of c about u: leave through (a, b, d) */
      size_t exit_v = gm_vec3_dot(x, wd) > 0.0 ? v[id] : v[ic];
      do {
        size_t tri[3] = {a, b, exit_v};
        const size_t f = gm_complex_find(cx, 2, tri);
        const size_t c0 = cx->cofaces[2 * f], c1 = cx->cofaces[2 * f + 1];
        const double *R = transport + 9 * f;
        double Rt[9], tmp[9];
        if (t == c0) {
          memcpy(Rt, R, sizeof Rt);
        } else {
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) Rt[3 * i + j] = R[3 * j + i];
        }
        gm_mat3_mul(Rt, H, tmp); /* H ← R H: the later crossing acts last */
        memcpy(H, tmp, sizeof H);
        const size_t next = t == c0 ? c1 : c0;
        /* in the next tet, leave through the other triangle containing (a, b) */
        const size_t *nv = cx->simplices[3] + 4 * next;
        size_t other = SIZE_MAX;
        for (int k = 0; k < 4; ++k)
          if (nv[k] != a && nv[k] != b && nv[k] != exit_v) other = nv[k];
        exit_v = other;
        t = next;
      } while (t != t0 && ++steps <= ring);
      if (t != t0) {
        st = gm_error_set(err, GM_EINVAL, "curvature 3d: the tets about edge %zu do not form a ring", e);
        break;
      }
      /* H is a rotation about u (the edge is fixed by every crossing) */
      double w[3] = {0.5 * (H[7] - H[5]), 0.5 * (H[2] - H[6]), 0.5 * (H[3] - H[1])};
      ang = atan2(gm_vec3_dot(w, u) / gm_vec3_norm(u), 0.5 * (H[0] + H[4] + H[8] - 1.0));
    }
    if (holonomy) memcpy(holonomy + 9 * e, H, sizeof H);
    if (angle) angle[e] = ang;
  }
  free(start), free(list), free(fill);
  return st;
}
