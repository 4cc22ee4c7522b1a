/* The short path of the Kepler drift (kepler.c) for VW orbits at a time (lanes.h):
 * instantiated by lanes2.c and lanes4.c as KEPLER_SHORT. Because each lane computes what it
 * would alone, both widths give bitwise the same drifts, and a single drift, done as a group
 * of copies of itself, is bitwise the drift of the same orbit in any group.
 *
 * From a third-order start s0, one Householder step d, the G functions carried to s0 + d by
 * their Taylor series, Kepler's equation evaluated again, a last Newton correction applied to
 * s, to G and to 1/r: the derivation and the bounds are in kepler.c ("The short path"). */
#include "celestial/lanes.h"

#define SHORT_STEP 0x1p-13
#define SHORT_Z 0.09

/* whether a lane takes the short path: μ > 0, all finite, r0 > 0, dt ≠ 0, elliptic,
 * |ΔM| = |dt| β^{3/2}/μ < 0.3 (squared: no root), s0 on the side of dt, |β s0²| < SHORT_Z */
static inline int lane_ok(vd mu, vd t, vd r0, vd eta, vd beta, vd s0) {
  return lanes((mu > 0.0) & vd_finite(mu + t + r0 + eta + beta + s0) & (r0 > 0.0) & (t != 0.0) &
               (beta > 0.0) & (t * t * beta * beta * beta < 0.09 * mu * mu) & (s0 * t > 0.0) &
               (beta * s0 * s0 < SHORT_Z));
}

/* Short drifts of count ≤ VW·KEPLER_MAX_GROUPS orbits by dt: orbit k has μ = mu[k] and starts
 * at x + 3k, v + 3k; its increments go to dx + 3k, dv + 3k (with apply: the end state x + dx,
 * v + dv, and dx, dv may then be x, v), 1/|x(dt)| to ir[k] unless ir is NULL, and done[k]
 * says whether it was done (the others' outputs are untouched). Lanes past count repeat the
 * last orbit. The work goes phase by phase over all groups of VW orbits: each phase is a
 * latency chain (square root and division, the series, the Householder division, the Newton
 * division), so the groups of one phase run side by side; a group at a time was measured
 * slower than scalar code. */
void KEPLER_SHORT(size_t count, const double *mu, double dt, const double *x, const double *v,
                  double *dx, double *dv, int apply, double *ir_out, int *done) {
  vd X[KEPLER_MAX_GROUPS][3], V[KEPLER_MAX_GROUPS][3], m[KEPLER_MAX_GROUPS],
      r0[KEPLER_MAX_GROUPS], eta[KEPLER_MAX_GROUPS], beta[KEPLER_MAX_GROUPS],
      zeta[KEPLER_MAX_GROUPS], ir[KEPLER_MAX_GROUPS], s0[KEPLER_MAX_GROUPS],
      d[KEPLER_MAX_GROUPS], g[KEPLER_MAX_GROUPS][4];
  if (count == 0 || count > VW * KEPLER_MAX_GROUPS) return; /* outside the contract */
  const vd t = vd_splat(dt), one = vd_splat(1.0);
  const size_t np = (count + VW - 1) / VW;
  int ok[KEPLER_MAX_GROUPS], any = 0;
  for (size_t i = 0; i < np; ++i) { /* r0, η, β, ζ, 1/r0 and the start */
    size_t k[VW];
    for (int j = 0; j < VW; ++j) k[j] = VW * i + j < count ? VW * i + j : count - 1;
    for (int c = 0; c < 3; ++c) {
      X[i][c] = vd_gather(x, k, c);
      V[i][c] = vd_gather(v, k, c);
    }
    m[i] = vd_pick(mu, k);
    r0[i] = vd_sqrt(X[i][0] * X[i][0] + X[i][1] * X[i][1] + X[i][2] * X[i][2]);
    eta[i] = X[i][0] * V[i][0] + X[i][1] * V[i][1] + X[i][2] * V[i][2];
    beta[i] = 2.0 * m[i] / r0[i] - (V[i][0] * V[i][0] + V[i][1] * V[i][1] + V[i][2] * V[i][2]);
    zeta[i] = m[i] - beta[i] * r0[i];
    ir[i] = one / r0[i];
    const vd tr = t * ir[i];
    s0[i] = tr * (1.0 + tr * (-0.5 * eta[i] * ir[i] +
                              tr * (0.5 * eta[i] * eta[i] * ir[i] * ir[i] -
                                    zeta[i] * ir[i] * (1.0 / 6.0))));
    ok[i] = lane_ok(m[i], t, r0[i], eta[i], beta[i], s0[i]);
    any |= ok[i];
  }
  for (size_t i = 0; i < count; ++i) done[i] = 0;
  if (!any) return;
  for (size_t i = 0; i < np; ++i) { /* G at s0 and Householder's fourth-order step */
    /* c2 = Σ_{j<6} y^j/(2j+2)!, c3 = Σ_{j<6} y^j/(2j+3)!, y = −β s0², by Estrin's scheme (Estrin,
     * Proc. Western Joint Computer Conf. 1960, 33: pairs of terms, then y²): half the dependent
     * multiply-adds of Horner's rule on this latency chain */
    const vd y = -(beta[i] * s0[i] * s0[i]), y2 = y * y;
    const double *c = gm_inverse_factorial;
    const vd c2 = (c[0] + c[2] * y) + y2 * ((c[4] + c[6] * y) + y2 * (c[8] + c[10] * y));
    const vd c3 = (c[1] + c[3] * y) + y2 * ((c[5] + c[7] * y) + y2 * (c[9] + c[11] * y));
    const vd s = s0[i], b = beta[i], e = eta[i], k = zeta[i];
    const vd g2 = s * s * c2, g3 = s * s * s * c3, g1 = s - b * g3, g0 = 1.0 - b * g2;
    const vd f = r0[i] * s + e * g2 + k * g3 - t;
    const vd df = r0[i] + e * g1 + k * g2;
    const vd d2f = e * g0 + k * g1;
    const vd d3f = k * g0 - e * b * g1;
    const vd df2 = df * df;
    d[i] = -(6.0 * f * df2 - 3.0 * f * f * d2f) /
           (6.0 * df2 * df - 6.0 * f * df * d2f + f * f * d3f);
    g[i][0] = g0, g[i][1] = g1, g[i][2] = g2, g[i][3] = g3;
    ok[i] &= lanes(vd_abs(d[i]) <= SHORT_STEP * vd_abs(s));
  }
  for (size_t i = 0; i < np; ++i) { /* G at s0 + d, Newton's correction, the increments */
    if (!ok[i]) continue;
    const vd b = beta[i], e = eta[i], k = zeta[i], dd = d[i];
    const vd g0 = g[i][0], g1 = g[i][1], g2 = g[i][2], g3 = g[i][3];
    const vd e1 = -b * g1, e2 = -b * g0, e3 = -b * e1, e4 = -b * e2;
    const vd h2 = 0.5 * dd, h3 = dd * (1.0 / 3.0), h4 = 0.25 * dd;
    const vd G3 = g3 + dd * (g2 + h2 * (g1 + h3 * (g0 + h4 * e1)));
    const vd G2 = g2 + dd * (g1 + h2 * (g0 + h3 * (e1 + h4 * e2)));
    const vd G1 = g1 + dd * (g0 + h2 * (e1 + h3 * (e2 + h4 * e3)));
    const vd G0 = g0 + dd * (e1 + h2 * (e2 + h3 * (e3 + h4 * e4)));
    const vd s1 = s0[i] + dd;
    const vd f1 = r0[i] * s1 + e * G2 + k * G3 - t;
    const vd r1 = r0[i] + e * G1 + k * G2;
    const vd inv_r1 = one / r1, d2 = -f1 * inv_r1;
    ok[i] &= lanes(vd_abs(d2) <= 0x1p-40 * vd_abs(s1));
    const vd n2 = G2 + d2 * G1, n1 = G1 + d2 * G0;
    /* 1/r at s1 + d2: r = r1 + d2 f''(s1) */
    const vd ri = inv_r1 * (1.0 - d2 * (e * G0 + k * G1) * inv_r1);
    /* dx = (f − 1) x0 + g v0, dv = ḟ x0 + (ġ − 1) v0 */
    const vd f_1 = -m[i] * n2 * ir[i], gg = r0[i] * n1 + e * n2;
    const vd fdot = -m[i] * n1 * ri * ir[i], gdot_1 = -m[i] * n2 * ri;
    vd DX[3], DV[3];
    for (int c = 0; c < 3; ++c) {
      DX[c] = f_1 * X[i][c] + gg * V[i][c];
      DV[c] = fdot * X[i][c] + gdot_1 * V[i][c];
    }
    ok[i] &= lanes(vd_finite(DX[0] + DX[1] + DX[2] + DV[0] + DV[1] + DV[2]));
    if (apply) /* x + dx, rounded as the caller's own sum would be */
      for (int c = 0; c < 3; ++c) {
        DX[c] = X[i][c] + DX[c];
        DV[c] = V[i][c] + DV[c];
      }
    for (int j = 0; j < VW && VW * i + j < count; ++j) {
      if (!(ok[i] >> j & 1)) continue;
      for (int c = 0; c < 3; ++c) {
        dx[3 * (VW * i + j) + c] = DX[c][j];
        dv[3 * (VW * i + j) + c] = DV[c][j];
      }
      if (ir_out != NULL) ir_out[VW * i + j] = ri[j];
      done[VW * i + j] = 1;
    }
  }
}

