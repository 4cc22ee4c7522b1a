/* The discrete Levi-Civita connection of tetrahedral meshes (gm_dec_levi_civita_3d,
 * gm_dec_curvature_3d): the holonomy of the SO(3)-valued dual 1-form around each interior edge's
 * dual cycle is a rotation about the edge by the deficit angle 2π − Σ dihedral angles — 0 to
 * round-off on a flat (jittered) mesh of a cube, the closed-form deficit on a cone singularity
 * (a wedge ring in R⁴) and on two meshes of S³ (the boundaries of the 4-simplex and the 16-cell). */
#include "test_util.h"

#define PI 3.14159265358979323846

static double wrap(double x) { return x - 2.0 * PI * floor((x + PI) / (2.0 * PI)); }

typedef struct {
  double worst_angle, worst_deficit, worst_diff, worst_axis;
  size_t interior;
} result;

/* every interior edge: angle = deficit (mod 2π), the holonomy fixes the edge */
static result check(gm_complex *cx) {
  const size_t nf = gm_complex_count(cx, 2), ne = gm_complex_count(cx, 1);
  double *R = malloc(9 * nf * sizeof *R), *H = malloc(9 * ne * sizeof *H);
  double *ang = malloc(ne * sizeof *ang), *def = malloc(ne * sizeof *def);
  cr_assert(R && H && ang && def);
  cr_assert_eq(gm_dec_levi_civita_3d(cx, R), GM_OK);
  for (size_t f = 0; f < nf; ++f)
    cr_expect_lt(gm_so3_orthogonality_defect(R + 9 * f), 1e-14, "transport %zu not a rotation", f);
  gm_error err;
  cr_assert_eq(gm_dec_curvature_3d(cx, R, H, ang, def, &err), GM_OK, "%s", err.message);
  const unsigned char *bd = gm_complex_boundary_mask(cx, 1);
  result r = {0, 0, 0, 0, 0};
  for (size_t e = 0; e < ne; ++e) {
    if (bd[e]) continue;
    ++r.interior;
    r.worst_angle = fmax(r.worst_angle, fabs(ang[e]));
    r.worst_deficit = fmax(r.worst_deficit, fabs(wrap(def[e])));
    r.worst_diff = fmax(r.worst_diff, fabs(wrap(ang[e] - def[e])));
  }
  free(R), free(H), free(ang), free(def);
  return r;
}

static size_t vid(size_t n, size_t i, size_t j, size_t k) { return (i * (n + 1) + j) * (n + 1) + k; }

Test(dec_levi_civita_3d, flat_jittered_cube_has_no_curvature) {
  enum { n = 3 };
  const size_t nv = (n + 1) * (n + 1) * (n + 1);
  double x[3 * (n + 1) * (n + 1) * (n + 1)];
  unsigned s = 12345u;
  for (size_t i = 0; i <= n; ++i)
    for (size_t j = 0; j <= n; ++j)
      for (size_t k = 0; k <= n; ++k) {
        const size_t v = vid(n, i, j, k);
        const size_t c[3] = {i, j, k};
        for (int a = 0; a < 3; ++a) {
          s = s * 1103515245u + 12345u;
          const double jit = (c[a] > 0 && c[a] < n) ? 0.2 * ((double)(s >> 8) / 16777216.0 - 0.5) : 0.0;
          x[3 * v + a] = (double)c[a] + jit;
        }
      }
  /* Kuhn subdivision: 6 tets per cube, one per permutation of the axes */
  static const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  size_t top[4 * 6 * n * n * n], nt = 0;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j)
      for (size_t k = 0; k < n; ++k)
        for (int p = 0; p < 6; ++p) {
          size_t c[3] = {i, j, k};
          top[4 * nt] = vid(n, c[0], c[1], c[2]);
          for (int q = 0; q < 3; ++q) {
            ++c[perm[p][q]];
            top[4 * nt + q + 1] = vid(n, c[0], c[1], c[2]);
          }
          ++nt;
        }
  gm_complex *cx = NULL;
  gm_error err;
  cr_assert_eq(gm_complex_create(3, nv, x, 3, nt, top, &cx, &err), GM_OK, "%s", err.message);
  result r = check(cx);
  cr_log_info("flat cube (%zu tets, %zu interior edges): max |angle| %.3g, max |deficit| %.3g, "
              "max |angle - deficit| %.3g", nt, r.interior, r.worst_angle, r.worst_deficit, r.worst_diff);
  cr_expect_gt(r.interior, 50);
  cr_expect_lt(r.worst_angle, 1e-13);
  cr_expect_lt(r.worst_deficit, 1e-13);
  gm_complex_free(cx);
}

/* the gmsh cube of tests/data (unstructured, flat) */
Test(dec_levi_civita_3d, flat_gmsh_cube_has_no_curvature) {
  char path[1024];
  snprintf(path, sizeof path, "%s/tests/data/cube_v41.msh", GM_SOURCE_DIR);
  gm_mesh *mesh = NULL;
  gm_complex *cx = NULL;
  gm_error err;
  cr_assert_eq(gm_mesh_read(path, &mesh, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_mesh_complex(mesh, &cx, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_complex_dim(cx), 3);
  result r = check(cx);
  cr_log_info("gmsh cube (%zu tets, %zu interior edges): max |angle| %.3g, max |deficit| %.3g",
              gm_complex_count(cx, 3), r.interior, r.worst_angle, r.worst_deficit);
  cr_expect_gt(r.interior, 0);
  cr_expect_lt(r.worst_angle, 1e-12);
  cr_expect_lt(r.worst_deficit, 1e-12);
  gm_complex_free(cx);
  gm_mesh_free(mesh);
}

/* m wedges about the edge (c0, c1) = ((0,0,0,0), (0,0,0,1)); ring points at depth −h, radius 1:
 * the product of a 2-D cone of total angle m∠ with an interval, embedded in R⁴. */
Test(dec_levi_civita_3d, cone_singularity_deficit) {
  enum { m = 7 };
  const double h = 0.6;
  double x[4 * (2 + 2 * m)];
  memset(x, 0, sizeof x);
  x[4 + 3] = 1.0; /* c1 */
  for (int j = 0; j < m; ++j) {
    const double t = 2.0 * PI * j / m;
    double *p = x + 4 * (2 + j), *q = x + 4 * (2 + m + j);
    p[0] = q[0] = cos(t);
    p[1] = q[1] = sin(t);
    p[2] = q[2] = -h;
    q[3] = 1.0;
  }
  /* each prism (A, B, C | A', B', C'), bottom sorted by index: (A,B,C,C'), (A,B,B',C'),
   * (A,A',B',C') — quad diagonals from the lower bottom vertex to the higher top one, so
   * neighbouring prisms agree */
  size_t top[4 * 3 * m], nt = 0;
  for (int j = 0; j < m; ++j) {
    size_t bot[3] = {0, 2 + (size_t)j, 2 + (size_t)((j + 1) % m)};
    if (bot[1] > bot[2]) {
      size_t t = bot[1];
      bot[1] = bot[2];
      bot[2] = t;
    }
    size_t up[3];
    for (int k = 0; k < 3; ++k) up[k] = bot[k] == 0 ? 1 : bot[k] + m;
    const size_t tets[3][4] = {{bot[0], bot[1], bot[2], up[2]},
                               {bot[0], bot[1], up[1], up[2]},
                               {bot[0], up[0], up[1], up[2]}};
    memcpy(top + 4 * nt, tets, sizeof tets);
    nt += 3;
  }
  gm_complex *cx = NULL;
  gm_error err;
  cr_assert_eq(gm_complex_create(4, 2 + 2 * m, x, 3, nt, top, &cx, &err), GM_OK, "%s", err.message);
  const double cosang = (cos(2.0 * PI / m) + h * h) / (1.0 + h * h);
  const double exact = 2.0 * PI - m * acos(cosang);
  const size_t ne = gm_complex_count(cx, 1), nf = gm_complex_count(cx, 2);
  double *R = malloc(9 * nf * sizeof *R), *ang = malloc(ne * sizeof *ang), *def = malloc(ne * sizeof *def);
  cr_assert_eq(gm_dec_levi_civita_3d(cx, R), GM_OK);
  cr_assert_eq(gm_dec_curvature_3d(cx, R, NULL, ang, def, &err), GM_OK, "%s", err.message);
  const size_t centre = gm_complex_find(cx, 1, (const size_t[2]){0, 1});
  cr_log_info("cone (m = %d, h = %.1f): deficit closed form %.15f, from dihedrals %.15f, holonomy "
              "angle %.15f", m, h, exact, def[centre], ang[centre]);
  cr_expect(fabs(def[centre] - exact) < 1e-13, "deficit %.17g vs %.17g", def[centre], exact);
  cr_expect(fabs(ang[centre] - exact) < 1e-13, "holonomy %.17g vs %.17g", ang[centre], exact);
  free(R), free(ang), free(def);
  result r = check(cx);
  cr_log_info("cone: %zu interior edges, max |angle - deficit| %.3g", r.interior, r.worst_diff);
  cr_expect_eq(r.interior, 1 + m, "the central edge and the m radial diagonals");
  cr_expect_lt(r.worst_diff, 1e-13);
  gm_complex_free(cx);
}

Test(dec_levi_civita_3d, meshes_of_the_three_sphere) {
  /* the boundary of the regular 4-simplex: e1..e4 and c(1,1,1,1), c = (1 − √5)/4 (edges √2) */
  const double c = (1.0 - sqrt(5.0)) / 4.0;
  double x5[20] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, c, c, c, c};
  size_t t5[20], k = 0;
  for (size_t skip = 0; skip < 5; ++skip)
    for (size_t v = 0; v < 5; ++v)
      if (v != skip) t5[k++] = v;
  gm_complex *cx = NULL;
  gm_error err;
  cr_assert_eq(gm_complex_create(4, 5, x5, 3, 5, t5, &cx, &err), GM_OK, "%s", err.message);
  result r = check(cx);
  const double d5 = 2.0 * PI - 3.0 * acos(1.0 / 3.0);
  cr_log_info("4-simplex boundary: %zu interior edges, deficit %.15f (closed form %.15f), max "
              "|angle - deficit| %.3g", r.interior, r.worst_deficit, d5, r.worst_diff);
  cr_expect_eq(r.interior, 10);
  cr_expect(fabs(r.worst_deficit - d5) < 1e-13);
  cr_expect_lt(r.worst_diff, 1e-13);
  gm_complex_free(cx);
  /* the boundary of the 16-cell: ±e_i, one tet per sign choice, 4 tets about each edge */
  double x16[32];
  memset(x16, 0, sizeof x16);
  for (int i = 0; i < 4; ++i) x16[4 * (2 * i) + i] = 1.0, x16[4 * (2 * i + 1) + i] = -1.0;
  size_t t16[64];
  for (size_t s = 0; s < 16; ++s)
    for (size_t i = 0; i < 4; ++i) t16[4 * s + i] = 2 * i + ((s >> i) & 1);
  cr_assert_eq(gm_complex_create(4, 8, x16, 3, 16, t16, &cx, &err), GM_OK, "%s", err.message);
  r = check(cx);
  const double d16 = 2.0 * PI - 4.0 * acos(1.0 / 3.0);
  cr_log_info("16-cell boundary: %zu interior edges, deficit %.15f (closed form %.15f), max "
              "|angle - deficit| %.3g", r.interior, r.worst_deficit, d16, r.worst_diff);
  cr_expect_eq(r.interior, 24);
  cr_expect(fabs(r.worst_deficit - d16) < 1e-13);
  cr_expect_lt(r.worst_diff, 1e-13);
  gm_complex_free(cx);
  /* the same with perturbed vertices: a closed piecewise-flat 3-manifold whose 24 deficits differ */
  unsigned seed = 777u;
  for (int i = 0; i < 32; ++i) {
    seed = seed * 1103515245u + 12345u;
    x16[i] += 0.15 * ((double)(seed >> 8) / 16777216.0 - 0.5);
  }
  cr_assert_eq(gm_complex_create(4, 8, x16, 3, 16, t16, &cx, &err), GM_OK, "%s", err.message);
  {
    const size_t ne = gm_complex_count(cx, 1), nf = gm_complex_count(cx, 2);
    double R[9 * 64], ang[64], def[64], lo = INFINITY, hi = -INFINITY, worst = 0.0;
    cr_assert(ne <= 64 && nf <= 64);
    cr_assert_eq(gm_dec_levi_civita_3d(cx, R), GM_OK);
    cr_assert_eq(gm_dec_curvature_3d(cx, R, NULL, ang, def, &err), GM_OK, "%s", err.message);
    for (size_t e = 0; e < ne; ++e) {
      lo = fmin(lo, def[e]), hi = fmax(hi, def[e]);
      worst = fmax(worst, fabs(wrap(ang[e] - def[e])));
    }
    cr_log_info("perturbed 16-cell: deficits from %.4f to %.4f, max |angle - deficit| %.3g", lo, hi, worst);
    cr_expect_gt(hi - lo, 0.05, "the deficits differ");
    cr_expect_lt(worst, 1e-13);
  }
  gm_complex_free(cx);
  /* bad input */
  cr_expect_eq(gm_dec_levi_civita_3d(NULL, NULL), GM_EINVAL);
}
