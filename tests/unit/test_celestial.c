/* Coordinates (Jacobi, democratic heliocentric) and the near-integrable integrator: round
 * trips to round-off, conserved total momentum, canonical kinetic energy, bad input, results
 * independent of observation, the step-size warning's period, and the corrector's internal
 * state. */
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "test_util.h"

static const gm_coordinates kinds[] = {GM_COORDINATES_JACOBI,
                                       GM_COORDINATES_DEMOCRATIC_HELIOCENTRIC};

Test(celestial, coordinates_round_trip_and_momentum) {
  test_model tm = test_model_make("outer-solar-system");
  const gm_celestial *c = tm.problem->celestial;
  cr_assert_not_null(c);
  const size_t n = c->n_bodies, d = 3 * n;
  for (size_t k = 0; k < 2; ++k) {
    double Q[64], P[64], q[64], p[64];
    cr_assert_eq(gm_coordinates_from_barycentric(kinds[k], n, c->mass, tm.y0, tm.y0 + d, Q, P),
                 GM_OK);
    cr_assert_eq(gm_coordinates_to_barycentric(kinds[k], n, c->mass, Q, P, q, p), GM_OK);
    double eq = 0, ep = 0, sq = 0, sp = 0;
    for (size_t i = 0; i < d; ++i) {
      eq = fmax(eq, fabs(q[i] - tm.y0[i]));
      ep = fmax(ep, fabs(p[i] - tm.y0[d + i]));
      sq = fmax(sq, fabs(tm.y0[i]));
      sp = fmax(sp, fabs(tm.y0[d + i]));
    }
    /* P_0 is the total momentum; the kinetic energy is the same sum in both */
    double total[3] = {0, 0, 0}, T = 0, T2 = 0, M = 0;
    for (size_t i = 0; i < n; ++i) {
      M += c->mass[i];
      for (int j = 0; j < 3; ++j) {
        total[j] += tm.y0[d + 3 * i + j];
        T += tm.y0[d + 3 * i + j] * tm.y0[d + 3 * i + j] / (2 * c->mass[i]);
      }
    }
    double eta = c->mass[0], S[3] = {0, 0, 0};
    for (size_t i = 1; i < n; ++i) {
      double eta_next = eta + c->mass[i];
      double mr = kinds[k] == GM_COORDINATES_JACOBI ? c->mass[i] * eta / eta_next : c->mass[i];
      for (int j = 0; j < 3; ++j) {
        T2 += P[3 * i + j] * P[3 * i + j] / (2 * mr);
        S[j] += P[3 * i + j];
      }
      eta = eta_next;
    }
    for (int j = 0; j < 3; ++j) {
      T2 += P[j] * P[j] / (2 * M);
      if (kinds[k] == GM_COORDINATES_DEMOCRATIC_HELIOCENTRIC) T2 += S[j] * S[j] / (2 * c->mass[0]);
      cr_expect_leq(fabs(P[j] - total[j]), 1e-16 * sp, "%s: P_0 is not the total momentum",
                    gm_coordinates_name(kinds[k]));
    }
    printf("coordinates %s: round trip |dq|/|q| = %.2g, |dp|/|p| = %.2g, kinetic energy %.2g\n",
           gm_coordinates_name(kinds[k]), eq / sq, ep / sp, fabs(T2 - T) / T);
    cr_expect_leq(eq / sq, 4e-16, "%s q round trip %.3g", gm_coordinates_name(kinds[k]), eq / sq);
    cr_expect_leq(ep / sp, 4e-16, "%s p round trip %.3g", gm_coordinates_name(kinds[k]), ep / sp);
    cr_expect_leq(fabs(T2 - T) / T, 1e-15, "%s: kinetic energy %.3g vs %.3g",
                  gm_coordinates_name(kinds[k]), T2, T);
  }
  double Q[3 * 2], P[3 * 2], m_bad[2] = {1.0, 0.0}, y[6] = {0};
  cr_expect_eq(gm_coordinates_from_barycentric(GM_COORDINATES_JACOBI, 2, m_bad, y, y, Q, P),
               GM_EINVAL);
  m_bad[1] = -1.0;
  cr_expect_eq(gm_coordinates_to_barycentric(GM_COORDINATES_JACOBI, 2, m_bad, y, y, Q, P),
               GM_EINVAL);
  gm_model_free(tm.model);
}

/* Total momentum and angular momentum of the outer solar system through 2000 steps of each
 * near-integrable row: both are conserved by the splitting (to round-off). */
Test(celestial, rows_conserve_momenta) {
  test_model tm = test_model_make("outer-solar-system");
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (m->family != GM_FAMILY_NEAR_INTEGRABLE) continue;
    gm_integrator *it = test_integrator(m, tm.problem, tm.t0, tm.y0);
    cr_assert_eq(gm_integrator_run(it, 2000, 50.0), GM_OK, "%s: %s", m->name,
                 gm_integrator_errmsg(it));
    const double *y = gm_integrator_state(it);
    for (size_t k = 0; k < tm.problem->n_invariants; ++k) {
      double a = tm.problem->invariants[k].value(tm.problem->ctx, tm.y0);
      double b = tm.problem->invariants[k].value(tm.problem->ctx, y);
      cr_expect_leq(fabs(a - b), 1e-13 * fmax(1e-5, fabs(a)), "%s: %s %.17g -> %.17g", m->name,
                    tm.problem->invariants[k].name, a, b);
    }
    gm_integrator_free(it);
  }
  gm_model_free(tm.model);
}

/* What a run computes does not depend on how often it is observed (correctors are applied to
 * the outputs only), and an observed run equals the same steps one at a time. */
static int count_calls(void *ctx, size_t step, double t, const double *y) {
  (void)step, (void)t, (void)y;
  ++*(size_t *)ctx;
  return 0;
}

Test(celestial, observation_does_not_change_the_run) {
  test_model tm = test_model_make("outer-solar-system");
  const char *names[] = {"wh", "wh-c11", "sbab-3-jacobi", "wh-dh", "sabac-2-jacobi"};
  for (size_t k = 0; k < sizeof names / sizeof names[0]; ++k) {
    const gm_method *m = gm_method_find(names[k]);
    gm_integrator *a = test_integrator(m, tm.problem, tm.t0, tm.y0);
    gm_integrator *b = test_integrator(m, tm.problem, tm.t0, tm.y0);
    gm_integrator *c = test_integrator(m, tm.problem, tm.t0, tm.y0);
    size_t calls = 0;
    cr_assert_eq(gm_integrator_add_observer(b, count_calls, &calls, 7), GM_OK);
    cr_assert_eq(gm_integrator_run(a, 700, 30.0), GM_OK);
    cr_assert_eq(gm_integrator_run(b, 700, 30.0), GM_OK);
    for (size_t s = 0; s < 700; ++s) cr_assert_eq(gm_integrator_step(c, 30.0), GM_OK);
    cr_expect_gt(calls, 100);
    cr_expect_eq(memcmp(gm_integrator_state(a), gm_integrator_state(b), tm.n * sizeof(double)), 0,
                 "%s: observing changed the run", names[k]);
    cr_expect_eq(memcmp(gm_integrator_state(a), gm_integrator_state(c), tm.n * sizeof(double)), 0,
                 "%s: single steps differ from a run", names[k]);
    gm_integrator_free(a);
    gm_integrator_free(b);
    gm_integrator_free(c);
  }
  gm_model_free(tm.model);
}

/* Bad input: near-integrable rows refuse problems without a central body, non-positive
 * masses; the shortest period is Jupiter's (4332 days) and unbound planets are counted. */
Test(celestial, bad_input_and_period) {
  test_model kepler = test_model_make("kepler");
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  cr_expect_eq(gm_integrator_create(gm_method_find("wh"), kepler.problem, &it, &err),
               GM_EUNSUPPORTED);
  cr_expect_not_null(strstr(err.message, "central body"), "%s", err.message);
  gm_model_free(kepler.model);

  test_model tm = test_model_make("outer-solar-system");
  gm_problem pb = *tm.problem;
  double mass[6];
  gm_celestial c = *tm.problem->celestial;
  memcpy(mass, c.mass, sizeof mass);
  c.mass = mass;
  pb.celestial = &c;
  for (int sign = 0; sign < 2; ++sign) {
    mass[2] = sign ? -1e-4 : 0.0;
    err.message[0] = '\0';
    cr_expect_eq(gm_integrator_create(gm_method_find("wh"), &pb, &it, &err), GM_EINVAL);
    cr_expect_not_null(strstr(err.message, "body 3 has mass"), "%s", err.message);
  }
  mass[2] = tm.problem->celestial->mass[2];
  size_t unbound = 9;
  double period = gm_celestial_shortest_period(&c, GM_COORDINATES_JACOBI, tm.y0, &unbound);
  cr_expect(fabs(period - 4332) < 20, "shortest period %g days (Jupiter: 4332)", period);
  cr_expect_eq(unbound, 0);
  /* Pluto on an escape orbit: counted, and the integration still works (the Kepler drift
   * takes any conic: no row needs bound orbits) */
  double y[36];
  memcpy(y, tm.y0, sizeof y);
  for (int j = 0; j < 3; ++j) y[18 + 15 + j] *= 3.0;
  period = gm_celestial_shortest_period(&c, GM_COORDINATES_JACOBI, y, &unbound);
  cr_expect_eq(unbound, 1);
  it = test_integrator(gm_method_find("wh-c5"), &pb, 0.0, y);
  cr_expect_eq(gm_integrator_run(it, 200, 50.0), GM_OK, "%s", gm_integrator_errmsg(it));
  gm_integrator_free(it);
  cr_expect_eq(gm_method_coordinates(gm_method_find("wh-dh")),
               GM_COORDINATES_DEMOCRATIC_HELIOCENTRIC);
  cr_expect_eq(gm_method_corrector_order(gm_method_find("wh-c17")), 17);
  cr_expect_eq(gm_method_corrector_order(gm_method_find("wh")), 0);
  cr_expect_eq(gm_method_coordinates(gm_method_find("verlet")), 0);
  gm_model_free(tm.model);
}

/* A state is loaded through C⁻¹ and output through C: for a tiny step (1e-9 days, where the
 * corrector is the identity to ~ε h²) wh-c17 agrees with wh to round-off. */
Test(celestial, corrector_inverse) {
  test_model tm = test_model_make("outer-solar-system");
  gm_integrator *a = test_integrator(gm_method_find("wh-c17"), tm.problem, tm.t0, tm.y0);
  gm_integrator *b = test_integrator(gm_method_find("wh"), tm.problem, tm.t0, tm.y0);
  cr_assert_eq(gm_integrator_run(a, 1, 1e-9), GM_OK);
  cr_assert_eq(gm_integrator_run(b, 1, 1e-9), GM_OK);
  const double *ya = gm_integrator_state(a), *yb = gm_integrator_state(b);
  double e = 0, s = 0;
  for (size_t i = 0; i < tm.n; ++i) e = fmax(e, fabs(ya[i] - yb[i])), s = fmax(s, fabs(yb[i]));
  printf("corrector 17: C(WH(C^-1(y))) - WH(y) after a step of 1e-9 days: %.2g relative\n",
         e / s);
  cr_expect_leq(e / s, 1e-14, "%.3g", e / s);
  gm_integrator_free(a);
  gm_integrator_free(b);
  gm_model_free(tm.model);
}

/* The ε h^{s1} conditions: to first order in ε a near-integrable step is exact iff its kicks
 * are a quadrature rule on [0, 1] at the drift times t_k = a_1 + … + a_k, exact for
 * polynomials of degree < s1 (Laskar & Robutel 2001, §3; Blanes et al. 2013, §2). Every row
 * meets its s1 to round-off and fails degree s1 (so the check can fail). */
Test(celestial, kick_quadrature_orders) {
  static const struct {
    const char *name;
    int s1;
  } rows[] = {{"wh", 2},          {"wh-dh", 2},         {"saba-2-jacobi", 4}, {"saba-3-jacobi", 6},
              {"saba-4-jacobi", 8}, {"sbab-1-jacobi", 2}, {"sbab-2-jacobi", 4}, {"sbab-3-jacobi", 6},
              {"sbab-4-jacobi", 8}, {"wh-c3", 2},         {"wh-c5", 2},         {"wh-c7", 2},
              {"wh-c11", 2},        {"wh-c17", 2},        {"aba-10-4", 10},     {"aba-8-6-4", 8},
              {"aba-10-6-4", 10},   {"sabac-1-jacobi", 2}, {"sabac-2-jacobi", 4},
              {"sabac-3-jacobi", 6}, {"sabac-4-jacobi", 8}};
  size_t checked = 0;
  for (size_t r = 0; r < sizeof rows / sizeof rows[0]; ++r) {
    const gm_method *m = gm_method_find(rows[r].name);
    cr_assert_not_null(m, "%s", rows[r].name);
    gm_tableau *t = NULL;
    cr_assert_eq(gm_method_tableau(m, &t), GM_OK);
    double worst = 0, at_s1 = 0, sum_a = 0;
    for (int j = 0; j <= rows[r].s1; ++j) {
      double q = 0, time = 0;
      for (size_t i = 0; i < t->n_stages; ++i) {
        time += t->a[i];
        q += t->b[i] * pow(time, j);
      }
      double defect = fabs(q - 1.0 / (j + 1));
      if (j < rows[r].s1) worst = fmax(worst, defect);
      else at_s1 = defect;
    }
    for (size_t i = 0; i < t->n_stages; ++i) sum_a += t->a[i];
    cr_expect_leq(worst, 1e-14, "%s: degree < %d defect %.2e", m->name, rows[r].s1, worst);
    cr_expect_gt(at_s1, 1e-8, "%s: exact at degree %d too (%.2e)", m->name, rows[r].s1, at_s1);
    cr_expect_leq(fabs(sum_a - 1), 1e-15, "%s: drifts sum to %.17g", m->name, sum_a);
    gm_tableau_free(t);
    ++checked;
  }
  size_t n_rows = 0;
  for (size_t i = 0; i < gm_method_count(); ++i)
    n_rows += gm_method_at(i)->family == GM_FAMILY_NEAR_INTEGRABLE;
  cr_expect_eq(checked, n_rows, "a near-integrable row is missing from this test");
}

/* n-body with central=1 is the same "central body + perturbed orbits" problem: Sun–Jupiter–
 * Saturn read from a file integrates to the same state as outer-solar-system planets=2. */
Test(celestial, n_body_with_a_central_body) {
  test_model oss = test_model_with("outer-solar-system", "planets", 2);
  const gm_celestial *c = oss.problem->celestial;
  char path[] = "/tmp/geomint-celestial-XXXXXX";
  int fd = mkstemp(path);
  cr_assert_geq(fd, 0);
  FILE *f = fdopen(fd, "w");
  cr_assert_not_null(f);
  for (size_t i = 0; i < 3; ++i)
    fprintf(f, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", c->mass[i], oss.y0[3 * i],
            oss.y0[3 * i + 1], oss.y0[3 * i + 2], oss.y0[9 + 3 * i] / c->mass[i],
            oss.y0[9 + 3 * i + 1] / c->mass[i], oss.y0[9 + 3 * i + 2] / c->mass[i]);
  fclose(f);
  gm_model *nb = NULL;
  cr_assert_eq(gm_model_create("n-body", &nb), GM_OK);
  cr_assert_eq(gm_model_set_text(nb, "file", path), GM_OK);
  cr_assert_eq(gm_model_set(nb, "G", c->G), GM_OK);
  cr_assert_eq(gm_model_set(nb, "central", 1), GM_OK);
  cr_assert_eq(gm_model_build(nb), GM_OK, "%s", gm_model_errmsg(nb));
  const gm_problem *pb = gm_model_problem(nb);
  cr_assert_not_null(pb->celestial);
  double y0[18];
  gm_model_initial_state(nb, NULL, y0);
  gm_integrator *a = test_integrator(gm_method_find("aba-10-6-4"), pb, 0.0, y0);
  gm_integrator *b = test_integrator(gm_method_find("aba-10-6-4"), oss.problem, 0.0, oss.y0);
  cr_assert_eq(gm_integrator_run(a, 100, 100.0), GM_OK, "%s", gm_integrator_errmsg(a));
  cr_assert_eq(gm_integrator_run(b, 100, 100.0), GM_OK);
  double d = 0;
  for (size_t i = 0; i < 18; ++i)
    d = fmax(d, fabs(gm_integrator_state(a)[i] - gm_integrator_state(b)[i]));
  cr_expect_leq(d, 1e-13, "n-body central=1 and outer-solar-system differ by %.3g", d);
  gm_integrator_free(a);
  gm_integrator_free(b);
  /* softening with a central body is refused */
  cr_assert_eq(gm_model_set(nb, "eps", 0.01), GM_OK);
  cr_expect_eq(gm_model_build(nb), GM_EINVAL);
  cr_expect_not_null(strstr(gm_model_errmsg(nb), "eps = 0"), "%s", gm_model_errmsg(nb));
  gm_model_free(nb);
  remove(path);
  gm_model_free(oss.model);
}

/* The splitting's own Newtonian sums (gm_row_sums and gm_central_terms, used when the
 * problem says V is point-mass gravity) against a naive long double sum, for a few bodies and
 * for more than one vector's worth, with the padding of the arrays full of garbage (it must be
 * ignored); coinciding bodies and a zero distance are reported; both lane widths agree bitwise
 * where the CPU has both. */
#include "celestial/internal.h"

Test(celestial, newtonian_sums) {
  const size_t sizes[] = {2, 5, 6, 40, 150};
  srand(7);
  double worst = 0, worst_central = 0;
  for (size_t t = 0; t < sizeof sizes / sizeof sizes[0]; ++t) {
    const size_t n = sizes[t], np = (n + 3) / 4 * 4;
    double *x = malloc(5 * np * sizeof *x), *y = x + np, *z = y + np, *m = z + np, *mu = m + np;
    double *a = malloc(3 * n * sizeof *a), *a2 = malloc(3 * n * sizeof *a2);
    double *acc = malloc(3 * np * sizeof *acc);
    cr_assert(x && a && a2 && acc);
    for (size_t i = 0; i < np; ++i) {
      m[i] = i < n ? (i == 0 ? 1.0 : 1e-3 * (0.5 + rand() / (double)RAND_MAX)) : NAN;
      mu[i] = i < n ? 0.5 + rand() / (double)RAND_MAX : NAN;
      x[i] = i < n ? 20.0 * rand() / (double)RAND_MAX - 10.0 : NAN;
      y[i] = i < n ? 20.0 * rand() / (double)RAND_MAX - 10.0 : (i == n ? y[0] : NAN);
      z[i] = i < n ? 20.0 * rand() / (double)RAND_MAX - 10.0 : 0.0;
    }
    cr_assert_eq(gm_row_sums(n, np, x, y, z, m, 0.7, a, acc), 0);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        long double sum = 0, size = 0;
        for (size_t j = 0; j < n; ++j) {
          if (j == i) continue;
          const long double d[3] = {(long double)x[j] - x[i], (long double)y[j] - y[i],
                                    (long double)z[j] - z[i]};
          const long double s = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
          const long double term = 0.7L * m[j] * d[c] / (s * sqrtl(s));
          sum += term;
          size += fabsl(term);
        }
        worst = fmax(worst, (double)(fabsl(a[3 * i + c] - sum) / size));
      }
    cr_assert_eq(gm_central_terms(n, x, y, z, mu, a), 0);
    for (size_t i = 0; i < n; ++i) {
      const double c[3] = {x[i], y[i], z[i]};
      const long double s = (long double)c[0] * c[0] + (long double)c[1] * c[1] +
                            (long double)c[2] * c[2];
      for (int k = 0; k < 3; ++k) {
        const long double exact = mu[i] * c[k] / (s * sqrtl(s));
        worst_central = fmax(worst_central, (double)(fabsl(a[3 * i + k] - exact) / fabsl(exact)));
      }
    }
    if (gm_lane_width() == 4) {
      cr_assert_eq(gm_row_sums2(n, np, x, y, z, m, 0.7, a2, acc), 0);
      cr_assert_eq(gm_row_sums4(n, np, x, y, z, m, 0.7, a, acc), 0);
      cr_expect(memcmp(a, a2, 3 * n * sizeof *a) == 0, "row sums differ between widths, n = %zu",
                n);
    }
    x[n - 1] = x[0], y[n - 1] = y[0], z[n - 1] = z[0];
    cr_expect_eq(gm_row_sums(n, np, x, y, z, m, 0.7, a, acc), 1, "coinciding bodies, n = %zu", n);
    x[0] = y[0] = z[0] = 0.0;
    cr_expect_eq(gm_central_terms(n, x, y, z, mu, a), 1, "zero distance, n = %zu", n);
    free(x), free(a), free(a2), free(acc);
  }
  printf("newtonian sums: worst error %.2g relative to the sum of |terms|, Kepler terms %.2g\n",
         worst, worst_central);
  cr_expect_leq(worst, 1e-14, "%.3g", worst); /* measured 1.4e-15 (150 bodies: ~6 u) */
  cr_expect_leq(worst_central, 1e-15, "%.3g", worst_central);
}

/* The stepper's own interaction and the problem's potential_gradient callback give the same
 * run (to the rounding of their different sums) and count the same force evaluations, for
 * both coordinate systems and a corrected row. */
Test(celestial, newtonian_path_equals_the_callback) {
  test_model tm = test_model_make("outer-solar-system");
  cr_assert_eq(tm.problem->celestial->newtonian, 1);
  gm_celestial generic_c = *tm.problem->celestial;
  generic_c.newtonian = 0;
  gm_problem generic = *tm.problem;
  generic.celestial = &generic_c;
  const char *rows[] = {"aba-10-4", "wh-dh", "sabac-2-jacobi", "wh-c5"};
  for (size_t r = 0; r < sizeof rows / sizeof rows[0]; ++r) {
    gm_integrator *a = test_integrator(gm_method_find(rows[r]), tm.problem, 0.0, tm.y0);
    gm_integrator *b = test_integrator(gm_method_find(rows[r]), &generic, 0.0, tm.y0);
    cr_assert_eq(gm_integrator_run(a, 200, 50.0), GM_OK, "%s", gm_integrator_errmsg(a));
    cr_assert_eq(gm_integrator_run(b, 200, 50.0), GM_OK, "%s", gm_integrator_errmsg(b));
    double d = 0, size = 0;
    for (size_t i = 0; i < tm.n; ++i) {
      d = fmax(d, fabs(gm_integrator_state(a)[i] - gm_integrator_state(b)[i]));
      size = fmax(size, fabs(gm_integrator_state(b)[i]));
    }
    printf("%s: own interaction vs callback %.2g relative\n", rows[r], d / size);
    cr_expect_leq(d / size, 1e-12, "%s: %.3g", rows[r], d / size);
    cr_expect_eq(gm_integrator_stats(a).force_evals, gm_integrator_stats(b).force_evals, "%s",
                 rows[r]);
    gm_integrator_free(a);
    gm_integrator_free(b);
  }
  gm_model_free(tm.model);
}

/* The same for 21 bodies (n-body central=1: a star and 20 planets on near-circular orbits from
 * 1 to 20 au), so the kick's sums run over six chunks of four and the drift over groups of
 * several vectors: own sums and callback give the same run. */
Test(celestial, newtonian_path_many_planets) {
  char path[] = "/tmp/geomint-celestial-many-XXXXXX";
  int fd = mkstemp(path);
  cr_assert_geq(fd, 0);
  FILE *f = fdopen(fd, "w");
  cr_assert_not_null(f);
  const double G = 2.95912208286e-4;
  fprintf(f, "1 0 0 0 0 0 0\n");
  for (int k = 1; k <= 20; ++k) {
    const double r = k, phase = 2.4 * k, speed = sqrt(G / r);
    fprintf(f, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", 1e-6 * (1 + k % 3),
            r * cos(phase), r * sin(phase), 0.01 * r * sin(3.0 * k), -speed * sin(phase),
            speed * cos(phase), 0.0);
  }
  fclose(f);
  gm_model *nb = NULL;
  cr_assert_eq(gm_model_create("n-body", &nb), GM_OK);
  cr_assert_eq(gm_model_set_text(nb, "file", path), GM_OK);
  cr_assert_eq(gm_model_set(nb, "G", G), GM_OK);
  cr_assert_eq(gm_model_set(nb, "central", 1), GM_OK);
  cr_assert_eq(gm_model_build(nb), GM_OK, "%s", gm_model_errmsg(nb));
  const gm_problem *pb = gm_model_problem(nb);
  cr_assert_eq(pb->celestial->newtonian, 1);
  gm_celestial generic_c = *pb->celestial;
  generic_c.newtonian = 0;
  gm_problem generic = *pb;
  generic.celestial = &generic_c;
  const size_t n = gm_model_state_size(nb);
  double y0[126];
  cr_assert_leq(n, 126);
  gm_model_initial_state(nb, NULL, y0);
  const char *rows[] = {"aba-10-4", "wh-dh"};
  for (size_t r = 0; r < 2; ++r) {
    gm_integrator *a = test_integrator(gm_method_find(rows[r]), pb, 0.0, y0);
    gm_integrator *b = test_integrator(gm_method_find(rows[r]), &generic, 0.0, y0);
    cr_assert_eq(gm_integrator_run(a, 100, 20.0), GM_OK, "%s", gm_integrator_errmsg(a));
    cr_assert_eq(gm_integrator_run(b, 100, 20.0), GM_OK, "%s", gm_integrator_errmsg(b));
    double d = 0, size = 0;
    for (size_t i = 0; i < n; ++i) {
      d = fmax(d, fabs(gm_integrator_state(a)[i] - gm_integrator_state(b)[i]));
      size = fmax(size, fabs(gm_integrator_state(b)[i]));
    }
    printf("%s, 21 bodies: own interaction vs callback %.2g relative\n", rows[r], d / size);
    cr_expect_leq(d / size, 1e-12, "%s: %.3g", rows[r], d / size);
    gm_integrator_free(a);
    gm_integrator_free(b);
  }
  gm_model_free(nb);
  remove(path);
}
