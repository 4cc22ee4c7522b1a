/* Unit quaternions q = (w, x, y, z) = (cos(θ/2), sin(θ/2) n) for the rotation exp(θ n):
 * products, conversions to and from rotation vectors and matrices. Matrix → quaternion by
 * Shepperd's method (J. Guidance Control 1 (1978) 223): the largest of 1 + tr R and
 * 1 + 2R_ii − tr R picks the component computed by a square root. */
#include <math.h>

#include "geomint/lie.h"

void gm_quat_mul(const double a[4], const double b[4], double out[4]) {
  double w = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  double x = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  double y = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  double z = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
  out[0] = w;
  out[1] = x;
  out[2] = y;
  out[3] = z;
}

void gm_quat_conj(const double q[4], double out[4]) {
  out[0] = q[0];
  out[1] = -q[1];
  out[2] = -q[2];
  out[3] = -q[3];
}

void gm_quat_from_rotvec(const double w[3], double q[4]) {
  double theta = gm_vec3_norm(w);
  double s = 0.5 * gm_so3_sinc(0.5 * theta); /* sin(θ/2)/θ */
  q[0] = cos(0.5 * theta);
  for (int i = 0; i < 3; ++i) q[i + 1] = s * w[i];
}

void gm_quat_to_rotvec(const double q[4], double w[3]) {
  double v[3] = {q[1], q[2], q[3]};
  double s = gm_vec3_norm(v), c = q[0];
  if (c < 0.0) { /* −q is the same rotation; take the half angle in [0, π/2] */
    c = -c;
    for (int i = 0; i < 3; ++i) v[i] = -v[i];
  }
  double half = atan2(s, c); /* accurate near 0 (s) and near π (c) */
  double f = 2.0 / gm_so3_sinc(half) / hypot(s, c);
  for (int i = 0; i < 3; ++i) w[i] = f * v[i];
}

void gm_quat_to_matrix(const double q[4], double r[9]) {
  double n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  double s = 2.0 / n2;
  double w = q[0], x = q[1], y = q[2], z = q[3];
  r[0] = 1.0 - s * (y * y + z * z);
  r[1] = s * (x * y - w * z);
  r[2] = s * (x * z + w * y);
  r[3] = s * (x * y + w * z);
  r[4] = 1.0 - s * (x * x + z * z);
  r[5] = s * (y * z - w * x);
  r[6] = s * (x * z - w * y);
  r[7] = s * (y * z + w * x);
  r[8] = 1.0 - s * (x * x + y * y);
}

void gm_quat_from_matrix(const double r[9], double q[4]) {
  double tr = r[0] + r[4] + r[8];
  double d[4] = {1.0 + tr, 1.0 + 2.0 * r[0] - tr, 1.0 + 2.0 * r[4] - tr, 1.0 + 2.0 * r[8] - tr};
  int k = 0;
  for (int i = 1; i < 4; ++i)
    if (d[i] > d[k]) k = i;
  double s = 0.5 * sqrt(d[k]), f = 0.25 / s;
  switch (k) {
    case 0:
      q[0] = s;
      q[1] = f * (r[7] - r[5]);
      q[2] = f * (r[2] - r[6]);
      q[3] = f * (r[3] - r[1]);
      break;
    case 1:
      q[1] = s;
      q[0] = f * (r[7] - r[5]);
      q[2] = f * (r[1] + r[3]);
      q[3] = f * (r[2] + r[6]);
      break;
    case 2:
      q[2] = s;
      q[0] = f * (r[2] - r[6]);
      q[1] = f * (r[1] + r[3]);
      q[3] = f * (r[5] + r[7]);
      break;
    default:
      q[3] = s;
      q[0] = f * (r[3] - r[1]);
      q[1] = f * (r[2] + r[6]);
      q[2] = f * (r[5] + r[7]);
      break;
  }
  if (q[0] < 0.0)
    for (int i = 0; i < 4; ++i) q[i] = -q[i];
}

void gm_quat_rotate(const double q[4], const double v[3], double out[3]) {
  double r[9];
  gm_quat_to_matrix(q, r);
  gm_mat3_vec(r, v, out);
}
