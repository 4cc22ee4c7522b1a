/* A block of an MPI-decomposed grid seen from the whole grid (internal.h, yee_view): where the
 * subpixel smoothing of a block must read the whole grid's geometry at global indices. */
#include "fields/internal.h"

void yee_view_index(const gm_yee *s, const long ijk[3], long g[3]) {
  const yee_view *v = s->view;
  for (int a = 0; a < 3; ++a) {
    if (v == NULL) {
      g[a] = ijk[a];
      continue;
    }
    g[a] = ijk[a] + v->offset[a];
    const long n = (long)v->L.n[a];
    if (v->periodic[a] && v->L.extent[a] > 1) g[a] = ((g[a] % n) + n) % n;
  }
}

const gm_yee_materials *yee_view_materials(const gm_yee *s, const gm_yee_materials *local) {
  return s->view ? s->view->materials : local;
}
const gm_yee_layout *yee_view_layout(const gm_yee *s) { return s->view ? &s->view->L : &s->L; }
const int *yee_view_periodic(const gm_yee *s) {
  return s->view ? s->view->periodic : s->periodic;
}

/* The whole grid's update range of E component c (as update_ranges in yee_create.c) and its
 * CPML layers (as eligible in yee_aniso.c). */
int yee_view_eligible(const gm_yee *s, int c, const long g[3]) {
  const yee_view *v = s->view;
  if (v == NULL) return 1;
  double sh[3];
  gm_yee_component_shift(v->L.dim, (gm_yee_component)c, sh);
  for (int a = 0; a < 3; ++a) {
    if (v->L.extent[a] == 1) continue;
    const long n = (long)v->L.n[a];
    long lo = 0, hi = sh[a] > 0.0 ? n : n + 1;
    if (sh[a] == 0.0) {
      const int klo = v->opt.boundary[2 * a].kind, khi = v->opt.boundary[2 * a + 1].kind;
      if (v->periodic[a]) {
        hi = n;
      } else {
        if (klo == GM_BOUNDARY_PEC || klo == GM_BOUNDARY_CPML) lo = 1;
        if (khi == GM_BOUNDARY_PEC || khi == GM_BOUNDARY_CPML) hi = n;
      }
    }
    if (g[a] < lo || g[a] >= hi) return 0;
    for (int f = 0; f < 2; ++f) {
      const gm_yee_boundary *bd = &v->opt.boundary[2 * a + f];
      if (bd->kind != GM_BOUNDARY_CPML) continue;
      const long t = (long)bd->pml.thickness;
      if (f == 0 ? g[a] <= t : g[a] >= n - t) return 0;
    }
  }
  return 1;
}
