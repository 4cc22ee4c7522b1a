/* The gravitational problems: the outer solar system's data and invariants, the n-body
 * clusters (Plummer virial ratio, cold sphere energy, determinism, centre-of-mass frame), the
 * file of bodies (good and bad files, with line numbers) and text parameters. */
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "test_util.h"

typedef struct built_model {
  gm_model *model;
  const gm_problem *pb;
  size_t n; /* state size */
  double *y0;
} built_model;

/* Build a model after gm_model_set(name_k, value_k) for the n_set pairs given. */
static built_model build_with(const char *name, size_t n_set, const char *const *names,
                              const double *values) {
  built_model bm = {0};
  cr_assert_eq(gm_model_create(name, &bm.model), GM_OK);
  for (size_t k = 0; k < n_set; ++k)
    cr_assert_eq(gm_model_set(bm.model, names[k], values[k]), GM_OK, "%s",
                 gm_model_errmsg(bm.model));
  cr_assert_eq(gm_model_build(bm.model), GM_OK, "%s", gm_model_errmsg(bm.model));
  bm.pb = gm_model_problem(bm.model);
  bm.n = gm_model_state_size(bm.model);
  bm.y0 = calloc(bm.n, sizeof *bm.y0);
  cr_assert_not_null(bm.y0);
  gm_model_initial_state(bm.model, NULL, bm.y0);
  return bm;
}

static void free_model(built_model *bm) {
  gm_model_free(bm->model);
  free(bm->y0);
}

static double invariant(const gm_problem *pb, const double *y, const char *name) {
  for (size_t k = 0; k < pb->n_invariants; ++k)
    if (strcmp(pb->invariants[k].name, name) == 0) return pb->invariants[k].value(pb->ctx, y);
  cr_assert_fail("no invariant %s", name);
  return NAN;
}

/* ---- outer solar system ------------------------------------------------------------------ */

/* HLW Table 2.1, copied here again so that a typo in one place shows. */
static const double osc_mass[6] = {1.00000597682,      0.000954786104043,  0.000285583733151,
                                   0.0000437273164546, 0.0000517759138449, 1.0 / 1.3e8};
static const double osc_q[6][3] = {{0, 0, 0},
                                   {-3.5023653, -3.8169847, -1.5507963},
                                   {9.0755314, -3.0458353, -1.6483708},
                                   {8.3101420, -16.2901086, -7.2521278},
                                   {11.4707666, -25.7294829, -10.8169456},
                                   {-15.5387357, -25.2225594, -3.1902382}};
static const double osc_v[6][3] = {{0, 0, 0},
                                   {0.00565429, -0.00412490, -0.00190589},
                                   {0.00168318, 0.00483525, 0.00192462},
                                   {0.00354178, 0.00137102, 0.00055029},
                                   {0.00288930, 0.00114527, 0.00039677},
                                   {0.00276725, -0.00170702, -0.00136504}};

Test(gravity, outer_solar_system_data) {
  built_model bm = build_with("outer-solar-system", 0, NULL, NULL);
  const gm_problem *pb = bm.pb;
  cr_assert_eq(pb->kind, GM_PROBLEM_SEPARABLE);
  cr_assert_eq(pb->dim, 18);
  for (size_t i = 0; i < 6; ++i)
    for (size_t k = 0; k < 3; ++k) {
      cr_expect_eq(bm.y0[3 * i + k], osc_q[i][k]);
      cr_expect_eq(bm.y0[18 + 3 * i + k], osc_mass[i] * osc_v[i][k]);
    }
  /* The energy and momenta of the initial state, computed independently with 50-digit decimal
   * arithmetic (Python's decimal module) from the table:
   *   T = 2.99676319092538587e-8, V = −6.21221637413354944e-8, H = −3.21545318320816357e-8,
   *   P = (6.18381631747749895e-6, −2.43829315951694056e-6, −1.22548178933708515e-6),
   *   L = (1.59611558205336482e-6, −2.37033015924439115e-5, 5.59474902290504888e-5).
   * (HLW's data are heliocentric, so P ≠ 0: the barycentre drifts.) */
  const double *y = bm.y0;
  cr_expect(fabs(pb->kinetic(pb->ctx, y + 18) - 2.99676319092538587e-8) < 1e-14 * 3e-8);
  cr_expect(fabs(pb->potential(pb->ctx, y) + 6.21221637413354944e-8) < 1e-14 * 6e-8);
  double h = gm_problem_energy(pb, y);
  cr_expect(fabs(h + 3.21545318320816357e-8) < 1e-13 * 3.2e-8, "H0 = %.17g", h);
  const double P[3] = {6.18381631747749895e-6, -2.43829315951694056e-6, -1.22548178933708515e-6};
  const double L[3] = {1.59611558205336482e-6, -2.37033015924439115e-5, 5.59474902290504888e-5};
  const char *pn[3] = {"momentum-x", "momentum-y", "momentum-z"};
  const char *ln[3] = {"angular-momentum-x", "angular-momentum-y", "angular-momentum-z"};
  for (size_t k = 0; k < 3; ++k) {
    cr_expect(fabs(invariant(pb, y, pn[k]) - P[k]) < 1e-14 * fabs(P[k]), "%s", pn[k]);
    cr_expect(fabs(invariant(pb, y, ln[k]) - L[k]) < 1e-14 * fabs(L[k]), "%s", ln[k]);
  }
  free_model(&bm);
}

/* The units and the data make sense: the heliocentric osculating semi-major axis
 * a = −G(m0 + m)/(2ε), ε = |v|²/2 − G(m0 + m)/r, of each planet is its well-known value
 * (Jupiter 5.20, Saturn 9.55, Uranus 19.2, Neptune 30.1, Pluto 39.5 AU) within 3 %. A wrong
 * G, a wrong unit of time or a garbled velocity would move them far off. */
Test(gravity, outer_solar_system_orbits) {
  const double G = 2.95912208286e-4, a_known[6] = {0, 5.20, 9.55, 19.2, 30.1, 39.5};
  built_model bm = build_with("outer-solar-system", 0, NULL, NULL);
  for (size_t i = 1; i < 6; ++i) {
    double r2 = 0, v2 = 0;
    for (size_t k = 0; k < 3; ++k) {
      double dq = bm.y0[3 * i + k] - bm.y0[k];
      double dv = bm.y0[18 + 3 * i + k] / osc_mass[i] - bm.y0[18 + k] / osc_mass[0];
      r2 += dq * dq;
      v2 += dv * dv;
    }
    double mu = G * (osc_mass[0] + osc_mass[i]);
    double a = -mu / (2.0 * (0.5 * v2 - mu / sqrt(r2)));
    cr_expect(fabs(a / a_known[i] - 1.0) < 0.03, "planet %zu: a = %g AU", i, a);
  }
  free_model(&bm);
}

/* Invariants along an accurate integration: RK4 with a step of 2 days over 20 000 days (4.6
 * orbits of Jupiter) keeps the energy to 1e-11 and the angular momentum to 1e-12 relative
 * (measured 1.7e-13 and 7e-14); linear momentum is linear, kept to round-off by any RK
 * method (measured 1e-14 relative). */
Test(gravity, outer_solar_system_invariants_along_rk4) {
  built_model bm = build_with("outer-solar-system", 0, NULL, NULL);
  gm_integrator *it = test_integrator(gm_method_find("rk4"), bm.pb, 0.0, bm.y0);
  gm_monitor *mon = NULL;
  cr_assert_eq(gm_monitor_create(bm.pb, bm.y0, &mon), GM_OK);
  cr_assert_eq(gm_integrator_add_observer(it, gm_monitor_observe, mon, 10), GM_OK);
  cr_assert_eq(gm_integrator_integrate(it, 20000.0, 2.0), GM_OK);
  double e = gm_monitor_max_rel_energy_error(mon);
  cr_expect(e < 1e-11, "energy %.3e", e);
  for (size_t k = 0; k < 6; ++k) {
    double scale = fabs(bm.pb->invariants[k].value(bm.pb->ctx, bm.y0));
    double drift = gm_monitor_max_invariant_drift(mon, k);
    cr_expect(drift < (k < 3 ? 1e-13 : 1e-12) * scale, "%s drift %.3e of %.3e",
              bm.pb->invariants[k].name, drift, scale);
  }
  /* and the planets moved: Jupiter went round more than four times */
  const double *y = gm_integrator_state(it);
  cr_expect(fabs(y[3] - bm.y0[3]) + fabs(y[4] - bm.y0[4]) > 0.1);
  gm_monitor_free(mon);
  gm_integrator_free(it);
  free_model(&bm);
}

/* ---- drawn clusters ---------------------------------------------------------------------- */

static double virial_ratio(const gm_problem *pb, const double *y) {
  return pb->kinetic(pb->ctx, y + pb->dim) / fabs(pb->potential(pb->ctx, y));
}

/* A Plummer sphere in equilibrium has 2T + V = 0: T/|V| = ½ and, in standard units, E = −¼.
 * Over 40 seeds at n = 2000 the sample's T/|V| has mean 0.499 and standard deviation 0.009,
 * E mean −0.251, deviation 0.008: each seed must be within 0.05 of ½ (about 5σ), the mean of
 * three within 0.025, E within 0.04 of −¼. A missing factor (√2 in the escape speed, the
 * length unit 3π/16) moves T/|V| to 0.25 or 0.29. */
Test(gravity, plummer_sphere_is_in_virial_equilibrium) {
  double mean = 0.0;
  for (double seed = 1; seed <= 3; ++seed) {
    const char *names[] = {"n", "seed"};
    const double values[] = {2000, seed};
    built_model bm = build_with("n-body", 2, names, values);
    double q = virial_ratio(bm.pb, bm.y0), e = gm_problem_energy(bm.pb, bm.y0);
    cr_expect(fabs(q - 0.5) < 0.05, "seed %g: T/|V| = %g", seed, q);
    cr_expect(fabs(e + 0.25) < 0.04, "seed %g: E = %g", seed, e);
    mean += q / 3.0;
    free_model(&bm);
  }
  cr_expect(fabs(mean - 0.5) < 0.025, "mean T/|V| = %g", mean);
  /* with G = 4 velocities scale by 2: T/|V| unchanged, E = −G/4 */
  const char *names[] = {"n", "G"};
  const double values[] = {2000, 4.0};
  built_model bm = build_with("n-body", 2, names, values);
  cr_expect(fabs(virial_ratio(bm.pb, bm.y0) - 0.5) < 0.05);
  cr_expect(fabs(gm_problem_energy(bm.pb, bm.y0) + 1.0) < 0.16);
  free_model(&bm);
}

/* A cold uniform ball of radius 1 and mass 1: at rest, inside the ball (up to the shift to the
 * centre of mass), and V = −(3/5)(1 − 1/n) up to sampling noise (the mean of 1/r between two
 * uniform points of the unit ball is 6/5; measured deviation 0.004 at n = 1000). */
Test(gravity, cold_sphere) {
  const char *names[] = {"n", "cluster", "seed"};
  const double values[] = {1000, 0, 7};
  built_model bm = build_with("n-body", 3, names, values);
  const gm_problem *pb = bm.pb;
  const size_t d = pb->dim;
  cr_expect_eq(pb->kinetic(pb->ctx, bm.y0 + d), 0.0);
  double rmax = 0.0;
  for (size_t i = 0; i < 1000; ++i) {
    const double *x = bm.y0 + 3 * i;
    rmax = fmax(rmax, sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]));
  }
  cr_expect(rmax < 1.1 && rmax > 0.9, "rmax %g", rmax);
  double v = pb->potential(pb->ctx, bm.y0);
  cr_expect(fabs(v + 0.6 * (1.0 - 1.0 / 1000)) < 0.02, "V = %g", v);
  free_model(&bm);
}

/* The same seed gives the same cluster, another seed another; the cluster is in its
 * centre-of-mass frame; all masses are 1/n (the kinetic Hessian's diagonal is n). */
Test(gravity, clusters_are_deterministic_and_centred) {
  for (double cluster = 0; cluster <= 1; ++cluster) {
    const char *names[] = {"n", "cluster", "seed"};
    const double v1[] = {50, cluster, 11}, v2[] = {50, cluster, 12};
    built_model a = build_with("n-body", 3, names, v1), b = build_with("n-body", 3, names, v1),
                c = build_with("n-body", 3, names, v2);
    cr_assert_eq(a.n, 300);
    cr_expect(memcmp(a.y0, b.y0, a.n * sizeof *a.y0) == 0, "same seed, other state");
    cr_expect(memcmp(a.y0, c.y0, a.n * sizeof *a.y0) != 0, "other seed, same state");
    double com[3] = {0, 0, 0};
    for (size_t i = 0; i < 50; ++i)
      for (size_t k = 0; k < 3; ++k) com[k] += a.y0[3 * i + k] / 50.0;
    for (size_t k = 0; k < 3; ++k) {
      cr_expect(fabs(com[k]) < 1e-15, "centre of mass %g", com[k]);
      cr_expect(fabs(a.pb->invariants[k].value(a.pb->ctx, a.y0)) < 1e-16, "momentum");
    }
    double *hess = calloc(150 * 150, sizeof *hess);
    cr_assert_not_null(hess);
    cr_assert_eq(a.pb->kinetic_hessian(a.pb->ctx, a.y0 + 150, hess), 0);
    for (size_t i = 0; i < 150; ++i) cr_expect_eq(hess[i * 150 + i], 50.0);
    free(hess);
    free_model(&a);
    free_model(&b);
    free_model(&c);
  }
}

/* Momenta along an accurate integration of a small softened cluster: Störmer–Verlet keeps
 * linear and angular momentum exactly (up to round-off: measured 2e-15), RK4 the linear one
 * to round-off and the energy to 1e-9 at this step (measured 7e-11). */
Test(gravity, n_body_invariants_along_integrations) {
  const char *names[] = {"n", "eps", "seed"};
  const double values[] = {8, 0.05, 5};
  built_model bm = build_with("n-body", 3, names, values);
  const char *methods[] = {"verlet", "rk4"};
  for (size_t k = 0; k < 2; ++k) {
    gm_integrator *it = test_integrator(gm_method_find(methods[k]), bm.pb, 0.0, bm.y0);
    gm_monitor *mon = NULL;
    cr_assert_eq(gm_monitor_create(bm.pb, bm.y0, &mon), GM_OK);
    cr_assert_eq(gm_integrator_add_observer(it, gm_monitor_observe, mon, 1), GM_OK);
    cr_assert_eq(gm_integrator_integrate(it, 2.0, 1e-3), GM_OK);
    for (size_t j = 0; j < 6; ++j) {
      double drift = gm_monitor_max_invariant_drift(mon, j);
      if (k == 0 || j < 3)
        cr_expect(drift < 1e-14, "%s %s drift %.3e", methods[k], bm.pb->invariants[j].name,
                  drift);
    }
    if (k == 1)
      cr_expect(gm_monitor_max_rel_energy_error(mon) < 1e-9, "rk4 energy %.3e",
                gm_monitor_max_rel_energy_error(mon));
    gm_monitor_free(mon);
    gm_integrator_free(it);
  }
  free_model(&bm);
}

/* ---- files of bodies and text parameters -------------------------------------------------- */

static char tmpdir[256];

static void make_tmpdir(void) {
  snprintf(tmpdir, sizeof tmpdir, "/tmp/geomint-bodies-XXXXXX");
  cr_assert_not_null(mkdtemp(tmpdir));
}

static void remove_tmpdir(void) {
  char cmd[320];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
  cr_assert_eq(system(cmd), 0);
}

/* Write text to tmpdir/name; returns the path (static buffer). */
static const char *write_file(const char *name, const char *text) {
  static char path[512];
  snprintf(path, sizeof path, "%s/%s", tmpdir, name);
  FILE *f = fopen(path, "w");
  cr_assert_not_null(f);
  fputs(text, f);
  fclose(f);
  return path;
}

/* Build n-body from the file; returns the status, the message in msg. */
static gm_status load(const char *path, char *msg, size_t cap, gm_model **out) {
  gm_model *m = NULL;
  cr_assert_eq(gm_model_create("n-body", &m), GM_OK);
  cr_assert_eq(gm_model_set_text(m, "file", path), GM_OK, "%s", gm_model_errmsg(m));
  gm_status st = gm_model_build(m);
  snprintf(msg, cap, "%s", gm_model_errmsg(m));
  if (out != NULL && st == GM_OK)
    *out = m;
  else
    gm_model_free(m);
  return st;
}

TestSuite(bodies_file, .init = make_tmpdir, .fini = remove_tmpdir);

/* Two bodies, m = 1 at (−1, 0, 0) with v = (1, 0, 0) and m = 2 at (1, 0, 0) with
 * v = (−0.5, 0.25, 0), G = 1: V = −1·2/2 = −1, T = ½·1·1 + ½·2·(0.25 + 0.0625) = 0.8125,
 * P = (1 − 1, 0.5, 0), L_z = Σ x p_y − y p_x = 1·0.5. */
Test(bodies_file, good_file) {
  const char *path = write_file("two.txt",
                                "# m x y z vx vy vz\n"
                                "\n"
                                "1   -1 0 0   1 0 0   # the light one\n"
                                "   \t\n"
                                "2e0  1 0 0  -0.5 0.25 0\n");
  char msg[256];
  gm_model *m = NULL;
  cr_assert_eq(load(path, msg, sizeof msg, &m), GM_OK, "%s", msg);
  const gm_problem *pb = gm_model_problem(m);
  cr_assert_eq(pb->dim, 6);
  double y[12];
  gm_model_initial_state(m, NULL, y);
  const double expect[12] = {-1, 0, 0, 1, 0, 0, 1, 0, 0, -1, 0.5, 0};
  for (size_t i = 0; i < 12; ++i) cr_expect_eq(y[i], expect[i], "y[%zu] = %g", i, y[i]);
  cr_expect_float_eq(pb->potential(pb->ctx, y), -1.0, 1e-15);
  cr_expect_float_eq(pb->kinetic(pb->ctx, y + 6), 0.8125, 1e-15);
  cr_expect_float_eq(invariant(pb, y, "momentum-x"), 0.0, 1e-15);
  cr_expect_float_eq(invariant(pb, y, "momentum-y"), 0.5, 1e-15);
  cr_expect_float_eq(invariant(pb, y, "angular-momentum-z"), 0.5, 1e-15);
  /* parameters still apply: G and the softening */
  cr_assert_eq(gm_model_set(m, "G", 3.0), GM_OK);
  cr_assert_eq(gm_model_set(m, "eps", 1.0), GM_OK);
  cr_assert_eq(gm_model_build(m), GM_OK, "%s", gm_model_errmsg(m));
  pb = gm_model_problem(m);
  cr_expect_float_eq(pb->potential(pb->ctx, y), -3.0 * 2.0 / sqrt(5.0), 1e-15);
  /* "" unsets the file: back to the drawn cluster of 100 */
  cr_assert_eq(gm_model_set_text(m, "file", ""), GM_OK);
  cr_assert_eq(gm_model_build(m), GM_OK, "%s", gm_model_errmsg(m));
  cr_expect_eq(gm_model_problem(m)->dim, 300);
  gm_model_free(m);
}

/* Each bad file is refused with GM_EINVAL (GM_EIO when it cannot be read) and a message that
 * names the file and the line. */
Test(bodies_file, bad_files) {
  static const struct {
    const char *text;
    const char *needle[2];
  } cases[] = {
      {"1 0 0 0 0 0 0\n1 1 0 0 0 0\n", {"bad.txt:2", "expected 7 numbers"}},
      {"1 0 0 0 0 0 0\n# fine\n1 1 0 0 0 0 0 9\n", {"bad.txt:3", "more than 7"}},
      {"\n\n1 0 0 0 0 zero 0\n", {"bad.txt:3", "'zero' is not a number"}},
      {"1 0 0 0 0 0 0\n-2 1 0 0 0 0 0\n", {"bad.txt:2", "mass must be positive"}},
      {"0 1 0 0 0 0 0\n", {"bad.txt:1", "mass must be positive"}},
      {"1 0 0 0 0 0 0\n1 nan 0 0 0 0 0\n", {"bad.txt:2", "not finite"}},
      {"1 0 0 0 0 0 0\n1 1e999 0 0 0 0 0\n", {"bad.txt:2", "not finite"}},
      {"1 0 0 0 0 0 0\n1 1,0 0 0 0 0 0\n", {"bad.txt:2", "'1,0' is not a number"}},
      {"# only comments\n\n", {"no bodies", "bad.txt"}},
      {"1 0 0 0 0 0 0\n# a\n1 1 1 1 0 0 0\n1 0 0 0 1 1 1\n", {"lines 1 and 4", "same place"}},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
    const char *path = write_file("bad.txt", cases[k].text);
    char msg[256];
    cr_expect_eq(load(path, msg, sizeof msg, NULL), GM_EINVAL, "case %zu: %s", k, msg);
    for (size_t j = 0; j < 2; ++j)
      cr_expect(strstr(msg, cases[k].needle[j]) != NULL, "case %zu: '%s' not in: %s", k,
                cases[k].needle[j], msg);
  }
  /* coincident bodies are fine with softening */
  gm_model *m = NULL;
  cr_assert_eq(gm_model_create("n-body", &m), GM_OK);
  const char *soft = write_file("soft.txt", "1 0 0 0 0 0 0\n1 0 0 0 1 0 0\n");
  cr_assert_eq(gm_model_set_text(m, "file", soft), GM_OK);
  cr_assert_eq(gm_model_set(m, "eps", 0.1), GM_OK);
  cr_expect_eq(gm_model_build(m), GM_OK, "%s", gm_model_errmsg(m));
  gm_model_free(m);
  /* a file that does not exist */
  char msg[256], missing[300];
  snprintf(missing, sizeof missing, "%s/no-such-file.txt", tmpdir);
  cr_expect_eq(load(missing, msg, sizeof msg, NULL), GM_EIO);
  cr_expect(strstr(msg, "no-such-file.txt") != NULL && strstr(msg, "cannot open") != NULL, "%s",
            msg);
}

Test(bodies_file, text_parameters) {
  gm_model *m = NULL;
  cr_assert_eq(gm_model_create("n-body", &m), GM_OK);
  /* a number for a text parameter, a text for a number parameter, unknown names */
  cr_expect_eq(gm_model_set(m, "file", 1.0), GM_EINVAL);
  cr_expect(strstr(gm_model_errmsg(m), "file is a text parameter") != NULL, "%s",
            gm_model_errmsg(m));
  cr_expect_eq(gm_model_set_text(m, "n", "many"), GM_EINVAL);
  cr_expect(strstr(gm_model_errmsg(m), "n is a number") != NULL, "%s", gm_model_errmsg(m));
  cr_expect_eq(gm_model_set_text(m, "files", "x"), GM_EINVAL);
  cr_expect(strstr(gm_model_errmsg(m), "no parameter 'files'") != NULL, "%s", gm_model_errmsg(m));
  cr_expect_eq(gm_model_set_text(m, "file", NULL), GM_EINVAL);
  cr_expect_eq(gm_model_set_text(NULL, "file", "x"), GM_EINVAL);
  cr_expect(isnan(gm_model_param(m, "file")));
  /* the value is copied: changing the caller's buffer afterwards does not matter */
  char path[512];
  snprintf(path, sizeof path, "%s", write_file("one.txt", "2 0 0 0 0 0 0\n3 0 0 1 0 0 0\n"));
  cr_assert_eq(gm_model_set_text(m, "file", path), GM_OK);
  memset(path, 'x', 20);
  cr_expect_eq(gm_model_build(m), GM_OK, "%s", gm_model_errmsg(m));
  cr_expect_eq(gm_model_problem(m)->dim, 6);
  /* other problems have no text parameters */
  gm_model *k = NULL;
  cr_assert_eq(gm_model_create("kepler", &k), GM_OK);
  cr_expect_eq(gm_model_set_text(k, "e", "0.5"), GM_EINVAL);
  gm_model_free(k);
  gm_model_free(m);
}

Test(gravity, bad_parameters) {
  static const struct {
    const char *name;
    double value;
    const char *needle;
  } cases[] = {{"n", 1, "n must be an integer from 2"},     {"n", 2.5, "n must be"},
               {"cluster", 2, "cluster must be 0"},         {"seed", -1, "seed must be"},
               {"seed", 0.5, "seed must be"},               {"G", 0, "G must be positive"},
               {"eps", -0.1, "softening eps must be >= 0"}, {"n", 2e6, "n must be"}};
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
    gm_model *m = NULL;
    cr_assert_eq(gm_model_create("n-body", &m), GM_OK);
    cr_assert_eq(gm_model_set(m, cases[k].name, cases[k].value), GM_OK);
    cr_expect_eq(gm_model_build(m), GM_EINVAL, "%s = %g", cases[k].name, cases[k].value);
    cr_expect(strstr(gm_model_errmsg(m), cases[k].needle) != NULL, "'%s' not in: %s",
              cases[k].needle, gm_model_errmsg(m));
    cr_expect_null(gm_model_problem(m));
    gm_model_free(m);
  }
  gm_model *m = NULL;
  cr_assert_eq(gm_model_create("outer-solar-system", &m), GM_OK);
  cr_expect_eq(gm_model_set(m, "G", 1.0), GM_EINVAL); /* it has no parameters */
  cr_expect_eq(gm_model_set(m, "q19", 1.0), GM_OK);
  cr_expect_eq(gm_model_build(m), GM_EINVAL); /* 18 degrees of freedom */
  cr_expect(strstr(gm_model_errmsg(m), "q19") != NULL, "%s", gm_model_errmsg(m));
  gm_model_free(m);
  /* Jupiter moved onto the Sun: the energy is infinite */
  cr_assert_eq(gm_model_create("outer-solar-system", &m), GM_OK);
  for (int k = 4; k <= 6; ++k) {
    char name[8];
    snprintf(name, sizeof name, "q%d", k);
    cr_assert_eq(gm_model_set(m, name, 0.0), GM_OK);
  }
  cr_expect_eq(gm_model_build(m), GM_EINVAL);
  cr_expect(strstr(gm_model_errmsg(m), "energy") != NULL, "%s", gm_model_errmsg(m));
  gm_model_free(m);
}
