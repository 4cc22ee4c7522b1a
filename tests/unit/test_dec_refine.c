/* Red refinement (triangles; tetrahedra by Bey's rule), its parent maps, and the nested transfers
 * of cochains: restriction R (the seed's coarsening sums) and Whitney prolongation P are cochain
 * maps (d R = R d, d P = P d to round-off), R P = I, constants, linear 0-forms, closed 1-forms
 * and top-form totals are carried exactly. */
#include <string.h>

#include "dec_util.h"
#include "geomint/multigrid.h"

typedef struct nested {
  gm_mesh *cm, *fm;
  gm_complex *c, *f;
  gm_refinement *r;
} nested;

static nested make_nested(gm_mesh *coarse) {
  nested s = {coarse, NULL, NULL, NULL, NULL};
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_refine(coarse, 0, &s.fm, &err), GM_OK, "%s", err.message);
  s.c = test_complex(s.cm);
  s.f = test_complex(s.fm);
  cr_assert_eq(gm_refinement_create(s.c, s.f, &s.r, &err), GM_OK, "%s", err.message);
  return s;
}

static void free_nested(nested *s) {
  gm_refinement_free(s->r);
  gm_complex_free(s->c), gm_complex_free(s->f);
  gm_mesh_free(s->cm), gm_mesh_free(s->fm);
}

static gm_mesh *jiggled_square(void) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, 5, 4, GM_DIAGONAL_ALTERNATE, &m, &err), GM_OK);
  gm_complex *cx = test_complex(m);
  test_jiggle(m, cx, 0.2, 0.2, 7);
  gm_complex_free(cx);
  return m;
}

static gm_mesh *jiggled_cube(void) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_box(lo, hi, 3, 2, 2, GM_BOX_FIVE, &m, &err), GM_OK);
  gm_complex *cx = test_complex(m);
  test_jiggle(m, cx, 0.3, 0.2, 11);
  gm_complex_free(cx);
  return m;
}

Test(refine, counts_volumes_and_parents) {
  for (int dim = 2; dim <= 3; ++dim) {
    nested s = make_nested(dim == 2 ? jiggled_square() : jiggled_cube());
    const size_t V = gm_complex_count(s.c, 0), E = gm_complex_count(s.c, 1),
                 F = gm_complex_count(s.c, 2), T = dim == 3 ? gm_complex_count(s.c, 3) : 0;
    cr_assert_eq(gm_complex_count(s.f, 0), V + E);
    if (dim == 2) {
      cr_assert_eq(gm_complex_count(s.f, 1), 2 * E + 3 * F);
      cr_assert_eq(gm_complex_count(s.f, 2), 4 * F);
    } else {
      cr_assert_eq(gm_complex_count(s.f, 1), 2 * E + 3 * F + T);
      cr_assert_eq(gm_complex_count(s.f, 2), 4 * F + 8 * T);
      cr_assert_eq(gm_complex_count(s.f, 3), 8 * T);
    }
    cr_assert_eq(gm_complex_euler_characteristic(s.f), gm_complex_euler_characteristic(s.c));
    /* each child has 1/2^n of its parent's volume (the red rule's children are congruent to
     * the parent scaled by 1/2, or, for Bey's inner four, of the same volume) */
    gm_geometry *gc = test_geometry(s.c), *gf = test_geometry(s.f);
    const size_t per = (size_t)1 << dim;
    const double *vc = gm_geometry_primal_volumes(gc, (size_t)dim);
    const double *vf = gm_geometry_primal_volumes(gf, (size_t)dim);
    double worst = 0.0;
    for (size_t t = 0; t < gm_complex_count(s.f, (size_t)dim); ++t)
      worst = fmax(worst, fabs(vf[t] * (double)per / vc[t / per] - 1.0));
    cr_expect_leq(worst, 1e-13, "dim %d: child volume off by %.3g", dim, worst); /* 2.2e-15 */
    /* every fine vertex is its own parent or the midpoint of its parent edge */
    const unsigned char *pd = gm_refinement_parent_dim(s.r, 0);
    for (size_t v = 0; v < V + E; ++v) cr_assert_eq(pd[v], v < V ? 0 : 1);
    /* each coarse edge has two children, each coarse face 4 (triangle's own pieces) */
    size_t *kids = calloc(E, sizeof(size_t));
    const unsigned char *pe = gm_refinement_parent_dim(s.r, 1);
    const size_t *pp = gm_refinement_parent(s.r, 1);
    for (size_t e = 0; e < gm_complex_count(s.f, 1); ++e)
      if (pe[e] == 1) kids[pp[e]]++;
    for (size_t e = 0; e < E; ++e) cr_assert_eq(kids[e], 2);
    free(kids);
    gm_geometry_free(gc), gm_geometry_free(gf);
    free_nested(&s);
  }
}

/* Bey's rule on the Kuhn cube mesh: every level is a Kuhn mesh again (congruent tetrahedra),
 * so the shortest and longest edges halve exactly and the DEC stars stay non-negative. */
Test(refine, bey_rule_keeps_kuhn_meshes_congruent) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_box(lo, hi, 2, 2, 2, GM_BOX_KUHN, &m, &err), GM_OK);
  for (int level = 0; level < 3; ++level) {
    gm_mesh *f = NULL;
    cr_assert_eq(gm_mesh_refine(m, 0, &f, &err), GM_OK, "%s", err.message);
    gm_mesh_free(m);
    m = f;
    gm_mesh_report rep;
    cr_assert_eq(gm_mesh_quality(m, &rep, &err), GM_OK);
    const double h = 0.5 / (double)(2 << level);
    cr_expect_float_eq(rep.shortest_edge, h, 1e-14, "level %d", level);
    cr_expect_float_eq(rep.longest_edge, h * sqrt(3.0), 1e-14, "level %d", level);
    cr_expect_float_eq(rep.min_volume, rep.max_volume, 1e-14 * rep.max_volume);
    /* Kuhn tetrahedra have right angles: some dual edges are 0, none negative */
    cr_expect_geq(rep.star_min[1], -1e-15 * rep.star_max[1], "level %d: ⋆1 min %.3g", level,
                  rep.star_min[1]);
  }
  gm_mesh_free(m);
}

/* Well-centred input: acute triangles stay well-centred (the four children are similar to the
 * parent); so do the BCC tetrahedra under Bey's rule (measured: all 1728 children of 216
 * well-centred parents, margin 0.25 before and after — the children are congruent to the parent
 * scaled by 1/2). */
Test(refine, well_centredness_report) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, 6, 7, GM_DIAGONAL_ACUTE, &m, &err), GM_OK);
  nested s = make_nested(m);
  gm_well_centredness wc;
  cr_assert_eq(gm_refinement_well_centredness(s.r, &wc), GM_OK);
  cr_expect_gt(wc.coarse_well_centred, 0);
  cr_expect_eq(wc.children_of_well_centred, 4 * wc.coarse_well_centred);
  cr_expect_eq(wc.children_well_centred, wc.children_of_well_centred);
  cr_expect_gt(wc.children_margin, 0.0);
  free_nested(&s);
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_bcc(lo, hi, 3, 3, 3, 0, &m, &err), GM_OK);
  s = make_nested(m);
  cr_assert_eq(gm_refinement_well_centredness(s.r, &wc), GM_OK);
  cr_expect_eq(wc.coarse_well_centred, wc.coarse_cells);
  cr_expect_gt(wc.coarse_margin, 0.0);
  cr_expect_eq(wc.children_of_well_centred, 8 * wc.coarse_cells);
  cr_expect_eq(wc.children_well_centred, wc.children_of_well_centred, "%zu of %zu",
               wc.children_well_centred, wc.children_of_well_centred);
  cr_expect_float_eq(wc.children_margin, 0.25, 1e-14, "%.17g", wc.children_margin);
  cr_expect_float_eq(wc.coarse_margin, 0.25, 1e-14, "%.17g", wc.coarse_margin);
  free_nested(&s);
}

Test(refine, refuses_too_large_and_bad_input) {
  gm_mesh *m = NULL, *f = NULL;
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  cr_assert_eq(gm_mesh_box(lo, hi, 10, 10, 10, GM_BOX_KUHN, &m, &err), GM_OK);
  cr_assert_eq(gm_mesh_refine(m, 1 << 20, &f, &err), GM_ENOMEM);
  cr_expect_not_null(strstr(err.message, "bytes"), "%s", err.message);
  cr_expect_null(f);
  double bytes = 0.0;
  cr_assert_eq(gm_mesh_refine_estimate(m, 6, &bytes, &err), GM_OK);
  cr_expect_gt(bytes, 5e10); /* 6000·8^6 = 1.6e9 tets: beyond any machine here */
  gm_mesh_free(m);
  /* non-manifold: three triangles on one edge */
  cr_assert_eq(gm_mesh_create(2, 5, 2, 3, &m), GM_OK);
  const double x[10] = {0, 0, 1, 0, 0.5, 1, 0.5, -1, 0.2, 0.7};
  const size_t c[9] = {0, 1, 2, 0, 1, 3, 0, 1, 4};
  memcpy(m->x, x, sizeof x), memcpy(m->cells, c, sizeof c);
  cr_assert_eq(gm_mesh_refine(m, 0, &f, &err), GM_EINVAL);
  cr_expect_not_null(strstr(err.message, "manifold"), "%s", err.message);
  gm_mesh_free(m);
}

/* ‖d_f P v − P d_c v‖ and ‖d_c R w − R d_f w‖ for random v, w, relative. */
Test(refine, restriction_and_prolongation_are_cochain_maps) {
  for (int dim = 2; dim <= 3; ++dim) {
    nested s = make_nested(dim == 2 ? jiggled_square() : jiggled_cube());
    gm_error err = {{0}};
    for (size_t k = 0; k < (size_t)dim; ++k) {
      gm_csr *Pk = NULL, *Pk1 = NULL, *Rk = NULL, *Rk1 = NULL;
      cr_assert_eq(gm_refinement_prolongation(s.r, k, &Pk, &err), GM_OK, "%s", err.message);
      cr_assert_eq(gm_refinement_prolongation(s.r, k + 1, &Pk1, &err), GM_OK);
      cr_assert_eq(gm_refinement_restriction(s.r, k, &Rk, &err), GM_OK);
      cr_assert_eq(gm_refinement_restriction(s.r, k + 1, &Rk1, &err), GM_OK);
      const size_t nck = gm_complex_count(s.c, k), nfk = gm_complex_count(s.f, k);
      const size_t nck1 = gm_complex_count(s.c, k + 1), nfk1 = gm_complex_count(s.f, k + 1);
      double *v = malloc(nck * sizeof(double)), *dv = malloc(nck1 * sizeof(double));
      double *a = malloc(nfk1 * sizeof(double)), *b = malloc(nfk1 * sizeof(double));
      double *pv = malloc(nfk * sizeof(double));
      test_random_fill(nck, v, 3 + k);
      gm_csr_matvec(gm_complex_d(s.c, k), 1.0, v, 0.0, dv);
      gm_csr_matvec(Pk1, 1.0, dv, 0.0, a); /* P d v */
      gm_csr_matvec(Pk, 1.0, v, 0.0, pv);
      gm_csr_matvec(gm_complex_d(s.f, k), 1.0, pv, 0.0, b); /* d P v */
      double defect = 0.0;
      for (size_t i = 0; i < nfk1; ++i) defect = fmax(defect, fabs(a[i] - b[i]));
      cr_expect_leq(defect, 1e-14, "dim %d k %zu: |dP - Pd| = %.3g", dim, k, defect); /* 4.4e-16 */
      /* R P = I */
      double *rpv = malloc(nck * sizeof(double));
      gm_csr_matvec(Rk, 1.0, pv, 0.0, rpv);
      double rp = 0.0;
      for (size_t i = 0; i < nck; ++i) rp = fmax(rp, fabs(rpv[i] - v[i]));
      cr_expect_leq(rp, 1e-14, "dim %d k %zu: |RP - I| = %.3g", dim, k, rp);
      /* d R = R d on a random fine cochain */
      double *w = malloc(nfk * sizeof(double)), *dw = malloc(nfk1 * sizeof(double));
      double *c1 = malloc(nck1 * sizeof(double)), *c2 = malloc(nck1 * sizeof(double));
      test_random_fill(nfk, w, 17 + k);
      gm_csr_matvec(gm_complex_d(s.f, k), 1.0, w, 0.0, dw);
      gm_csr_matvec(Rk1, 1.0, dw, 0.0, c1);
      gm_csr_matvec(Rk, 1.0, w, 0.0, rpv);
      gm_csr_matvec(gm_complex_d(s.c, k), 1.0, rpv, 0.0, c2);
      double dr = 0.0;
      for (size_t i = 0; i < nck1; ++i) dr = fmax(dr, fabs(c1[i] - c2[i]));
      cr_expect_leq(dr, 1e-14, "dim %d k %zu: |dR - Rd| = %.3g", dim, k, dr); /* 4.4e-16 */
      free(v), free(dv), free(a), free(b), free(pv), free(rpv), free(w), free(dw), free(c1),
          free(c2);
      gm_csr_free(Pk), gm_csr_free(Pk1), gm_csr_free(Rk), gm_csr_free(Rk1);
    }
    free_nested(&s);
  }
}

/* Constants and linear 0-forms are prolonged exactly (linear interpolation) and restricted
 * exactly (injection); a closed 1-form stays closed and keeps its values; the total of a top
 * form is kept exactly by R and by P. */
Test(refine, constants_linear_closed_and_totals) {
  for (int dim = 2; dim <= 3; ++dim) {
    nested s = make_nested(dim == 2 ? jiggled_square() : jiggled_cube());
    gm_error err = {{0}};
    const size_t n = (size_t)dim, V = gm_complex_count(s.c, 0), Vf = gm_complex_count(s.f, 0);
    gm_csr *P0 = NULL, *R0 = NULL, *P1 = NULL, *Pn = NULL, *Rn = NULL;
    cr_assert_eq(gm_refinement_prolongation(s.r, 0, &P0, &err), GM_OK);
    cr_assert_eq(gm_refinement_restriction(s.r, 0, &R0, &err), GM_OK);
    cr_assert_eq(gm_refinement_prolongation(s.r, 1, &P1, &err), GM_OK);
    cr_assert_eq(gm_refinement_prolongation(s.r, n, &Pn, &err), GM_OK);
    cr_assert_eq(gm_refinement_restriction(s.r, n, &Rn, &err), GM_OK);
    const double *xc = gm_complex_coordinates(s.c), *xf = gm_complex_coordinates(s.f);
    double *f = malloc(V * sizeof(double)), *pf = malloc(Vf * sizeof(double));
    for (size_t v = 0; v < V; ++v) f[v] = 2.0 + 0.5 * xc[n * v] - 1.25 * xc[n * v + 1];
    gm_csr_matvec(P0, 1.0, f, 0.0, pf);
    double lin = 0.0;
    for (size_t v = 0; v < Vf; ++v)
      lin = fmax(lin, fabs(pf[v] - (2.0 + 0.5 * xf[n * v] - 1.25 * xf[n * v + 1])));
    cr_expect_leq(lin, 1e-15, "dim %d: linear 0-form prolonged with error %.3g", dim, lin);
    double *rf = malloc(V * sizeof(double));
    gm_csr_matvec(R0, 1.0, pf, 0.0, rf);
    for (size_t v = 0; v < V; ++v) cr_assert_eq(rf[v], f[v]);
    /* closed 1-form: ω = d g for a random g; P ω is closed on the fine mesh */
    const size_t E = gm_complex_count(s.c, 1), Ef = gm_complex_count(s.f, 1);
    const size_t F2 = gm_complex_count(s.f, 2);
    double *g = malloc(V * sizeof(double)), *om = malloc(E * sizeof(double));
    double *pom = malloc(Ef * sizeof(double)), *dpom = malloc(F2 * sizeof(double));
    test_random_fill(V, g, 5);
    gm_csr_matvec(gm_complex_d(s.c, 0), 1.0, g, 0.0, om);
    gm_csr_matvec(P1, 1.0, om, 0.0, pom);
    gm_csr_matvec(gm_complex_d(s.f, 1), 1.0, pom, 0.0, dpom);
    double closed = test_max_abs(F2, dpom);
    cr_expect_leq(closed, 1e-15, "dim %d: d(P dg) = %.3g", dim, closed);
    /* top form totals */
    const size_t T = gm_complex_count(s.c, n), Tf = gm_complex_count(s.f, n);
    double *w = malloc(T * sizeof(double)), *pw = malloc(Tf * sizeof(double));
    double *rw = malloc(T * sizeof(double)), *wf = malloc(Tf * sizeof(double));
    test_random_fill(T, w, 9);
    test_random_fill(Tf, wf, 10);
    gm_csr_matvec(Pn, 1.0, w, 0.0, pw);
    gm_csr_matvec(Rn, 1.0, wf, 0.0, rw);
    double sw = 0, spw = 0, swf = 0, srw = 0, scale = 0;
    for (size_t t = 0; t < T; ++t) sw += w[t], srw += rw[t], scale += fabs(w[t]);
    for (size_t t = 0; t < Tf; ++t) spw += pw[t], swf += wf[t];
    cr_expect_leq(fabs(sw - spw), 1e-15 * scale, "dim %d: total %.17g -> %.17g", dim, sw, spw);
    cr_expect_leq(fabs(swf - srw), 1e-15 * (double)Tf, "dim %d: total %.17g -> %.17g", dim, swf,
                  srw);
    free(f), free(pf), free(rf), free(g), free(om), free(pom), free(dpom), free(w), free(pw),
        free(rw), free(wf);
    gm_csr_free(P0), gm_csr_free(R0), gm_csr_free(P1), gm_csr_free(Pn), gm_csr_free(Rn);
    free_nested(&s);
  }
}

/* The prolongation reproduces the de Rham map of a constant 1-form (Whitney forms reproduce
 * constant forms), and a complex that is not the refinement is refused. */
Test(refine, constant_one_form_and_not_nested) {
  nested s = make_nested(jiggled_cube());
  gm_error err = {{0}};
  gm_csr *P1 = NULL;
  cr_assert_eq(gm_refinement_prolongation(s.r, 1, &P1, &err), GM_OK);
  const double a[3] = {0.3, -1.1, 0.7};
  const size_t E = gm_complex_count(s.c, 1), Ef = gm_complex_count(s.f, 1);
  double *om = malloc(E * sizeof(double)), *pom = malloc(Ef * sizeof(double));
  const double *xc = gm_complex_coordinates(s.c), *xf = gm_complex_coordinates(s.f);
  const size_t *ec = gm_complex_simplices(s.c, 1), *ef = gm_complex_simplices(s.f, 1);
  for (size_t e = 0; e < E; ++e) {
    om[e] = 0;
    for (int j = 0; j < 3; ++j) om[e] += a[j] * (xc[3 * ec[2 * e + 1] + j] - xc[3 * ec[2 * e] + j]);
  }
  gm_csr_matvec(P1, 1.0, om, 0.0, pom);
  double worst = 0.0;
  for (size_t e = 0; e < Ef; ++e) {
    double ex = 0;
    for (int j = 0; j < 3; ++j) ex += a[j] * (xf[3 * ef[2 * e + 1] + j] - xf[3 * ef[2 * e] + j]);
    worst = fmax(worst, fabs(pom[e] - ex));
  }
  cr_expect_leq(worst, 1e-15, "constant 1-form prolonged with error %.3g", worst);
  free(om), free(pom);
  gm_csr_free(P1);
  gm_refinement *bad = NULL;
  cr_assert_eq(gm_refinement_create(s.f, s.c, &bad, &err), GM_EINVAL);
  cr_expect_not_null(strstr(err.message, "red refinement"), "%s", err.message);
  free_nested(&s);
}
