/* Hodge decomposition of a vector field on an annulus, written to VTU (ParaView) and to a CSV for
 * plotting: the field X = ∇φ + J∇ψ + h is flattened to a 1-cochain, split into exact, coexact
 * and harmonic parts (b1 = 1 on the annulus), and each part is sharpened back to vectors at
 * the vertices.
 *
 *   example_dec_hodge_annulus [OUT_DIR]   (default: the current directory)
 * writes OUT_DIR/dec_hodge_annulus.vtu and OUT_DIR/dec_hodge_annulus.csv, prints the norms. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "geomint/dec.h"
#include "geomint/mesh.h"

/* X(x, y) = ∇(x y) + J∇(exp(−4 r²)... ) + the rotation (−y, x)/r²: a gradient, a divergence-free
 * bump swirl, and the harmonic field dθ. */
static void field(const double *p, double *X) {
  const double x = p[0], y = p[1], r2 = x * x + y * y;
  const double g = exp(-8.0 * ((x - 0.75) * (x - 0.75) + y * y)); /* stream function ψ */
  const double gx = -16.0 * (x - 0.75) * g, gy = -16.0 * y * g;
  X[0] = y + (-gy) + 0.5 * (-y / r2);
  X[1] = x + gx + 0.5 * (x / r2);
}

int main(int argc, char **argv) {
  const char *dir = argc > 1 ? argv[1] : ".";
  gm_error err = {{0}};
  gm_mesh *m = NULL;
  gm_complex *cx = NULL;
  gm_geometry *g = NULL;
  gm_hodge_decomposition *hd = NULL;
  if (gm_mesh_annulus(0.5, 1.0, 12, 96, &m, &err) || gm_mesh_complex(m, &cx, &err) ||
      gm_geometry_create(cx, NULL, &g, &err) || gm_hodge_decomposition_create(g, 1, &hd, &err)) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  const size_t nv = gm_complex_count(cx, 0), ne = gm_complex_count(cx, 1), nt = gm_complex_count(cx, 2);
  const size_t *tri = gm_complex_simplices(cx, 2);
  double *X = malloc(2 * nt * sizeof(double)), *a = malloc(4 * ne * sizeof(double));
  double *V = malloc(4 * 2 * nv * sizeof(double));
  if (!X || !a || !V) return 1;
  /* the field at the triangles (here at their barycenters), flattened to a 1-cochain */
  for (size_t t = 0; t < nt; ++t) {
    double c[2] = {0, 0};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 2; ++j) c[j] += m->x[2 * tri[3 * t + i] + j] / 3.0;
    field(c, X + 2 * t);
  }
  double *alpha = a, *ex = a + ne, *co = a + 2 * ne, *h = a + 3 * ne;
  if (gm_dec_flat(g, X, alpha) != GM_OK ||
      gm_hodge_decomposition_apply(hd, alpha, ex, co, h) != GM_OK) {
    fprintf(stderr, "decomposition failed: %s\n", gm_hodge_decomposition_errmsg(hd));
    return 1;
  }
  /* back to vectors at the vertices */
  const char *names[4] = {"field", "exact", "coexact", "harmonic"};
  double norm[4];
  const double *star1 = gm_geometry_hodge_star(g, 1);
  for (int p = 0; p < 4; ++p) {
    gm_dec_sharp(g, a + (size_t)p * ne, V + (size_t)p * 2 * nv);
    double s = 0.0;
    for (size_t i = 0; i < ne; ++i) s += star1[i] * a[(size_t)p * ne + i] * a[(size_t)p * ne + i];
    norm[p] = sqrt(s);
  }
  double cross = 0.0; /* (exact, coexact) in the ⋆_1 inner product: zero */
  for (size_t i = 0; i < ne; ++i) cross += star1[i] * ex[i] * co[i];
  printf("annulus 0.5 < r < 1: %zu vertices, %zu edges, %zu triangles\n", nv, ne, nt);
  for (int p = 0; p < 4; ++p) printf("  |%s|_* = %.6f\n", names[p], norm[p]);
  printf("  (exact, coexact)_* = %.3g\n", cross);
  /* VTU: the cochains on the edges, the vectors at the vertices */
  double *V3 = malloc(4 * 3 * nv * sizeof(double));
  if (!V3) return 1;
  for (int p = 0; p < 4; ++p)
    for (size_t v = 0; v < nv; ++v) {
      V3[(size_t)p * 3 * nv + 3 * v] = V[(size_t)p * 2 * nv + 2 * v];
      V3[(size_t)p * 3 * nv + 3 * v + 1] = V[(size_t)p * 2 * nv + 2 * v + 1];
      V3[(size_t)p * 3 * nv + 3 * v + 2] = 0.0;
    }
  gm_vtu_field f[8] = {
      {"alpha", 1, 1, alpha},         {"alpha_exact", 1, 1, ex},
      {"alpha_coexact", 1, 1, co},    {"alpha_harmonic", 1, 1, h},
      {"X", 0, 3, V3},                {"X_exact", 0, 3, V3 + 3 * nv},
      {"X_coexact", 0, 3, V3 + 6 * nv}, {"X_harmonic", 0, 3, V3 + 9 * nv}};
  char path[1024];
  snprintf(path, sizeof path, "%s/dec_hodge_annulus.vtu", dir);
  if (gm_vtu_write(path, cx, 8, f, &err) != GM_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  printf("  wrote %s\n", path);
  /* CSV for a plot: x, y and the four vector fields at the vertices */
  snprintf(path, sizeof path, "%s/dec_hodge_annulus.csv", dir);
  FILE *csv = fopen(path, "w");
  if (csv == NULL) return 1;
  fprintf(csv, "x,y,X,Y,exact_x,exact_y,coexact_x,coexact_y,harmonic_x,harmonic_y\n");
  for (size_t v = 0; v < nv; ++v) {
    fprintf(csv, "%.6f,%.6f", m->x[2 * v], m->x[2 * v + 1]);
    for (int p = 0; p < 4; ++p)
      fprintf(csv, ",%.6f,%.6f", V[(size_t)p * 2 * nv + 2 * v], V[(size_t)p * 2 * nv + 2 * v + 1]);
    fputc('\n', csv);
  }
  fclose(csv);
  printf("  wrote %s\n", path);
  free(X), free(a), free(V), free(V3);
  gm_hodge_decomposition_free(hd);
  gm_geometry_free(g);
  gm_complex_free(cx);
  gm_mesh_free(m);
  return 0;
}
