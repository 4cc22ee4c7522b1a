/* Angle-deficit Gaussian curvature and the discrete Levi-Civita holonomy of triangle meshes
 * (seed 000 §4.3.1–4.3.2; seed 001 §1F "discrete Levi-Civita connection"). */
#include <math.h>
#include <stdlib.h>

#include "dec/internal.h"

static double angle_at(const double *a, const double *b, const double *c, size_t N) {
  /* angle at a between ab and ac, by atan2(|u×v|, u·v) (accurate for all angles) */
  double u[3] = {0, 0, 0}, v[3] = {0, 0, 0};
  for (size_t j = 0; j < N && j < 3; ++j) u[j] = b[j] - a[j], v[j] = c[j] - a[j];
  double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
  return atan2(sqrt(cx * cx + cy * cy + cz * cz), u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
}

gm_status gm_dec_angle_deficit(const gm_complex *cx, double *deficit) {
  if (cx == NULL || deficit == NULL || cx->n != 2 || cx->N > 3) return GM_EINVAL;
  const size_t N = cx->N;
  for (size_t v = 0; v < cx->n_vertices; ++v) deficit[v] = cx->boundary[0][v] ? GM_PI : 2.0 * GM_PI;
  for (size_t t = 0; t < cx->count[2]; ++t) {
    const size_t *s = cx->simplices[2] + 3 * t;
    for (int i = 0; i < 3; ++i) {
      const double *a = cx->x + N * s[i], *b = cx->x + N * s[(i + 1) % 3], *c = cx->x + N * s[(i + 2) % 3];
      deficit[s[i]] -= angle_at(a, b, c, N);
    }
  }
  return GM_OK;
}

static void normal_of(const gm_complex *cx, size_t t, double *n) {
  const size_t N = cx->N;
  const size_t *s = cx->simplices[2] + 3 * t;
  double u[3] = {0, 0, 0}, w[3] = {0, 0, 0};
  for (size_t j = 0; j < N; ++j) u[j] = cx->x[N * s[1] + j] - cx->x[N * s[0] + j],
                                 w[j] = cx->x[N * s[2] + j] - cx->x[N * s[0] + j];
  n[0] = u[1] * w[2] - u[2] * w[1];
  n[1] = u[2] * w[0] - u[0] * w[2];
  n[2] = u[0] * w[1] - u[1] * w[0];
  double r = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) * cx->orient[t];
  for (int j = 0; j < 3; ++j) n[j] /= r;
}

/* Rotate w about the unit axis a by the angle that takes unit n0 to unit n1 (both ⊥ a):
 * Rodrigues' formula with cos θ = n0·n1, sin θ = (n0 × n1)·a. */
static void rotate_about(const double *a, const double *n0, const double *n1, double *w) {
  double c = n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2];
  double x[3] = {n0[1] * n1[2] - n0[2] * n1[1], n0[2] * n1[0] - n0[0] * n1[2], n0[0] * n1[1] - n0[1] * n1[0]};
  double s = x[0] * a[0] + x[1] * a[1] + x[2] * a[2];
  double axw[3] = {a[1] * w[2] - a[2] * w[1], a[2] * w[0] - a[0] * w[2], a[0] * w[1] - a[1] * w[0]};
  double adw = a[0] * w[0] + a[1] * w[1] + a[2] * w[2];
  for (int j = 0; j < 3; ++j) w[j] = w[j] * c + axw[j] * s + a[j] * adw * (1.0 - c);
}

gm_status gm_dec_holonomy(const gm_complex *cx, size_t v, double *angle) {
  if (cx == NULL || angle == NULL || cx->n != 2 || cx->N > 3 || v >= cx->n_vertices) return GM_EINVAL;
  if (cx->boundary[0][v]) return GM_EINVAL;
  const size_t N = cx->N;
  /* a first triangle containing v */
  size_t t0 = SIZE_MAX;
  for (size_t t = 0; t < cx->count[2] && t0 == SIZE_MAX; ++t)
    for (int i = 0; i < 3; ++i)
      if (cx->simplices[2][3 * t + i] == v) t0 = t;
  if (t0 == SIZE_MAX) return GM_EINVAL;
  /* walk counterclockwise: in the oriented triangle (v, a, b), leave through edge (v, b) */
  double n0[3], n[3], w[3] = {0, 0, 0}, w0[3];
  normal_of(cx, t0, n0);
  size_t t = t0, steps = 0;
  int first = 1;
  for (;;) {
    const size_t *s = cx->simplices[2] + 3 * t;
    size_t i = 0;
    while (s[i] != v) ++i;
    /* oriented order of t: sorted order if orient > 0, else reversed */
    size_t a = cx->orient[t] > 0 ? s[(i + 1) % 3] : s[(i + 2) % 3];
    size_t b = cx->orient[t] > 0 ? s[(i + 2) % 3] : s[(i + 1) % 3];
    double e[3] = {0, 0, 0}, len = 0.0;
    if (first) {
      for (size_t j = 0; j < N; ++j) w[j] = cx->x[N * a + j] - cx->x[N * v + j];
      double r = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
      for (int j = 0; j < 3; ++j) w[j] /= r, w0[j] = w[j];
      first = 0;
    }
    for (size_t j = 0; j < N; ++j) e[j] = cx->x[N * b + j] - cx->x[N * v + j], len += e[j] * e[j];
    len = sqrt(len);
    for (int j = 0; j < 3; ++j) e[j] /= len;
    size_t ends[2] = {v, b};
    size_t edge = gm_complex_find(cx, 1, ends);
    size_t next = cx->cofaces[2 * edge] == t ? cx->cofaces[2 * edge + 1] : cx->cofaces[2 * edge];
    if (next == SIZE_MAX || ++steps > cx->count[2]) return GM_EINVAL;
    double nt[3], nn[3];
    normal_of(cx, t, nt);
    normal_of(cx, next, nn);
    rotate_about(e, nt, nn, w);
    t = next;
    if (t == t0) break;
  }
  normal_of(cx, t0, n);
  double x[3] = {w0[1] * w[2] - w0[2] * w[1], w0[2] * w[0] - w0[0] * w[2], w0[0] * w[1] - w0[1] * w[0]};
  double s = x[0] * n[0] + x[1] * n[1] + x[2] * n[2];
  double c = w0[0] * w[0] + w0[1] * w[1] + w0[2] * w[2];
  *angle = atan2(s, c);
  return GM_OK;
}
