/* Boundary conditions as ghost values, refreshed after each half step (O(surface) work):
 *   PEC (and the PEC backing CPML): tangential E on the wall is never updated (stays 0).
 *   PMC: the image H_t(−½) = −H_t(+½), so the wall's E edges see half dual cells
 *        (seed 000 §3.3.2: the boundary dual with extra dual vertices on the wall).
 *   periodic / Bloch: E(n) = e^{ikL} E(0) on the wall nodes and H(−½) = e^{−ikL} H(n−½);
 *        with k ≠ 0 the fields are complex (two arrays per component) and only these maps
 *        couple the real and imaginary parts. */
#include "fields/internal.h"

/* dst plane = (cr + i ci) · src plane of component c, planes normal to axis a at the given
 * indices, over the whole extent of the two other axes. */
static void plane_map(gm_yee *s, int c, int a, long dst, long src, double cr, double ci) {
  const gm_yee_layout *L = &s->L;
  const int b = (a + 1) % 3, d = (a + 2) % 3;
  const long ob = (long)L->offset[b], od = (long)L->offset[d];
  double *re = s->f[0][c], *im = s->n_parts == 2 ? s->f[1][c] : NULL;
  for (long v = -od; v < (long)L->extent[d] - od; ++v)
    for (long u = -ob; u < (long)L->extent[b] - ob; ++u) {
      long p[3], q[3];
      p[a] = dst;
      q[a] = src;
      p[b] = q[b] = u;
      p[d] = q[d] = v;
      const size_t ip = yee_idx(L, p[0], p[1], p[2]), iq = yee_idx(L, q[0], q[1], q[2]);
      if (im == NULL) {
        re[ip] = cr * re[iq];
      } else {
        const double r = re[iq], m = im[iq];
        re[ip] = cr * r - ci * m;
        im[ip] = ci * r + cr * m;
      }
    }
}

void yee_apply_ghosts_e(gm_yee *s) {
  for (int a = 0; a < s->n_axes; ++a) {
    if (!s->periodic[a]) continue;
    const long n = (long)s->L.n[a];
    for (int c = 0; c < 3; ++c)
      if (s->active[c] && c != a) plane_map(s, c, a, n, 0, s->phase_cos[a], s->phase_sin[a]);
  }
}

void yee_apply_ghosts_h(gm_yee *s) {
  for (int a = 0; a < s->n_axes; ++a) {
    const long n = (long)s->L.n[a];
    for (int c = 3; c < 6; ++c) {
      if (!s->active[c]) continue;
      if (s->periodic[a]) {
        if (c - 3 == a) {
          plane_map(s, c, a, n, 0, s->phase_cos[a], s->phase_sin[a]);
        } else {
          plane_map(s, c, a, -1, n - 1, s->phase_cos[a], -s->phase_sin[a]);
          plane_map(s, c, a, n, 0, s->phase_cos[a], s->phase_sin[a]);
        }
        continue;
      }
      if (c - 3 == a) continue; /* normal H needs no ghost */
      if (s->opt.boundary[2 * a].kind == GM_BOUNDARY_PMC) plane_map(s, c, a, -1, 0, -1.0, 0.0);
      if (s->opt.boundary[2 * a + 1].kind == GM_BOUNDARY_PMC)
        plane_map(s, c, a, n, n - 1, -1.0, 0.0);
    }
  }
}
