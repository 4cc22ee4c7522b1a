/* Geometric versus classical at equal cost: geomint's kahan-li-8 (a symmetric composition of
 * Störmer–Verlet, order 8, symplectic) against GSL's rk8pd (the Prince–Dormand 8(7) explicit
 * Runge–Kutta pair, used here at a FIXED step through gsl_odeiv2_step_apply, no error control)
 * on Kepler with e = 0.6 over 10⁴ orbits (t_end = 2π·10⁴), both making the same number of force
 * evaluations.
 *
 * kahan-li-8 takes h_k = 2π/200 (200 steps an orbit, well inside its asymptotic range: see
 * docs/work-precision.md). Force evaluations are counted, not assumed: for kahan-li-8 from
 * gm_stats.force_evals, for rk8pd by a counter in the right-hand side given to GSL (one call
 * evaluates ∇V once). A probe of a few steps gives the evaluations per step of each, e_k and
 * e_g; rk8pd then takes N_g = round(N_k·e_k/e_g) steps of h_g = t_end/N_g, i.e.
 * h_g ≈ h_k·e_g/e_k, so both evaluate the force the same number of times (to a relative 1e-6).
 *
 * Measured for both, in one run: the relative energy error |H − H0|/|H0|, its maximum over the
 * run (sampled every SAMPLE_EVERY steps and at the end) and its final value; the final-position
 * error |q − q_exact| against the exact solution (the model's exact callback, Kepler's equation
 * solved by Newton); and the CPU time of the integration alone (sampling excluded). Reports the
 * ratios rk8pd / kahan-li-8 and writes DIR/gsl_comparison.json.
 *
 * rk8pd: Prince & Dormand, "High order embedded Runge-Kutta formulae", J. Comput. Appl. Math.
 * 7 (1981) 67–75, as implemented in GSL (gsl_odeiv2_step_rk8pd, 13 stages). kahan-li-8: Kahan &
 * Li, "Composition constants for raising the orders of unconventional schemes for ordinary
 * differential equations", Math. Comp. 66 (1997) 1089–1099, the 17-stage method. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "geomint/geomint.h"

#if GM_HAVE_GSL
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#define ORBITS 10000
#define STEPS_PER_ORBIT 200
#define SAMPLE_EVERY 10
static const double two_pi = 6.283185307179586476925286766559;

typedef struct counted_rhs {
  const gm_problem *pb;
  size_t calls;
} counted_rhs;

/* y = (q, p): q' = ∇T(p), p' = −∇V(q). */
static int kepler_rhs(double t, const double y[], double dydt[], void *params) {
  (void)t;
  counted_rhs *c = params;
  const size_t d = c->pb->dim;
  ++c->calls;
  if (c->pb->kinetic_gradient(c->pb->ctx, y + d, dydt) != 0 ||
      c->pb->potential_gradient(c->pb->ctx, y, dydt + d) != 0)
    return GSL_EBADFUNC;
  for (size_t i = 0; i < d; ++i) dydt[d + i] = -dydt[d + i];
  return GSL_SUCCESS;
}

typedef struct outcome {
  const char *name;
  double h;
  size_t steps, force_evals;
  double evals_per_step;
  double max_rel_energy, final_rel_energy, position_error, cpu_s;
} outcome;

typedef struct setup {
  const gm_problem *pb;
  double y0[4], h0, t_end, exact[4];
} setup;

static double rel_energy(const setup *s, const double *y) {
  return fabs(gm_problem_energy(s->pb, y) - s->h0) / fabs(s->h0);
}

static double position_error(const setup *s, const double *y) {
  return hypot(y[0] - s->exact[0], y[1] - s->exact[1]);
}

/* kahan-li-8: n_steps of h through the library, sampled every SAMPLE_EVERY steps. */
static outcome run_kahan_li(const setup *s, size_t n_steps, double h) {
  outcome o = {"kahan-li-8", h, n_steps, 0, 0, 0, 0, 0, 0};
  gm_integrator *it = NULL;
  gm_error err;
  if (gm_integrator_create(gm_method_find("kahan-li-8"), s->pb, &it, &err) != GM_OK) {
    fprintf(stderr, "kahan-li-8: %s\n", err.message);
    exit(1);
  }
  gm_integrator_set_state(it, 0.0, s->y0);
  for (size_t done = 0; done < n_steps;) {
    size_t k = n_steps - done < SAMPLE_EVERY ? n_steps - done : SAMPLE_EVERY;
    double c0 = bench_cpu_now();
    if (gm_integrator_run(it, k, h) != GM_OK) {
      fprintf(stderr, "kahan-li-8: %s\n", gm_integrator_errmsg(it));
      exit(1);
    }
    o.cpu_s += bench_cpu_now() - c0;
    done += k;
    o.max_rel_energy = fmax(o.max_rel_energy, rel_energy(s, gm_integrator_state(it)));
  }
  const double *y = gm_integrator_state(it);
  gm_stats st = gm_integrator_stats(it);
  o.force_evals = st.force_evals;
  o.evals_per_step = (double)st.force_evals / (double)st.steps;
  o.final_rel_energy = rel_energy(s, y);
  o.position_error = position_error(s, y);
  gm_integrator_free(it);
  return o;
}

/* rk8pd at a fixed step: n_steps of h, sampled every SAMPLE_EVERY steps. */
static outcome run_rk8pd(const setup *s, size_t n_steps, double h) {
  outcome o = {"rk8pd (GSL)", h, n_steps, 0, 0, 0, 0, 0, 0};
  counted_rhs c = {s->pb, 0};
  gsl_odeiv2_system sys = {kepler_rhs, NULL, 4, &c};
  gsl_odeiv2_step *step = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 4);
  double y[4], yerr[4], t = 0.0;
  memcpy(y, s->y0, sizeof y);
  for (size_t done = 0; done < n_steps;) {
    size_t k = n_steps - done < SAMPLE_EVERY ? n_steps - done : SAMPLE_EVERY;
    double c0 = bench_cpu_now();
    for (size_t i = 0; i < k; ++i) {
      /* no derivative in or out: the stepper evaluates what it needs, which we count */
      if (gsl_odeiv2_step_apply(step, t, h, y, yerr, NULL, NULL, &sys) != GSL_SUCCESS) {
        fprintf(stderr, "rk8pd failed at t = %g\n", t);
        exit(1);
      }
      t = (double)(done + i + 1) * h; /* no accumulated round-off in t */
    }
    o.cpu_s += bench_cpu_now() - c0;
    done += k;
    o.max_rel_energy = fmax(o.max_rel_energy, rel_energy(s, y));
  }
  o.force_evals = c.calls;
  o.evals_per_step = (double)c.calls / (double)n_steps;
  o.final_rel_energy = rel_energy(s, y);
  o.position_error = position_error(s, y);
  gsl_odeiv2_step_free(step);
  return o;
}

/* Force evaluations per step of each, from a probe of `probe` steps (kahan-li-8's first step
 * makes one extra evaluation that later steps share: first same as last). */
static void probe_costs(const setup *s, double *per_step_kl8, double *per_step_rk8pd) {
  const size_t probe = 100;
  gm_integrator *it = NULL;
  gm_integrator_create(gm_method_find("kahan-li-8"), s->pb, &it, NULL);
  gm_integrator_set_state(it, 0.0, s->y0);
  gm_integrator_run(it, 1, 0.01);
  size_t first = gm_integrator_stats(it).force_evals;
  gm_integrator_run(it, probe, 0.01);
  *per_step_kl8 = (double)(gm_integrator_stats(it).force_evals - first) / (double)probe;
  gm_integrator_free(it);

  counted_rhs c = {s->pb, 0};
  gsl_odeiv2_system sys = {kepler_rhs, NULL, 4, &c};
  gsl_odeiv2_step *step = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 4);
  double y[4], yerr[4];
  memcpy(y, s->y0, sizeof y);
  for (size_t i = 0; i < probe; ++i) gsl_odeiv2_step_apply(step, 0.01 * (double)i, 0.01, y, yerr, NULL, NULL, &sys);
  *per_step_rk8pd = (double)c.calls / (double)probe;
  gsl_odeiv2_step_free(step);
}

int main(int argc, char **argv) {
  gsl_set_error_handler_off();
  gm_model *model = NULL;
  if (gm_model_create("kepler", &model) != GM_OK || gm_model_set(model, "e", 0.6) != GM_OK ||
      gm_model_build(model) != GM_OK) {
    fprintf(stderr, "cannot build kepler\n");
    return 1;
  }
  setup s;
  double t0;
  s.pb = gm_model_problem(model);
  gm_model_initial_state(model, &t0, s.y0);
  s.h0 = gm_problem_energy(s.pb, s.y0);
  s.t_end = two_pi * ORBITS;
  s.pb->exact(s.pb->ctx, s.t_end, s.exact);

  double e_k, e_g;
  probe_costs(&s, &e_k, &e_g);
  const size_t n_k = (size_t)ORBITS * STEPS_PER_ORBIT;
  const size_t n_g = (size_t)llround((double)n_k * e_k / e_g);
  double start = bench_now();
  outcome o[2];
  o[0] = run_kahan_li(&s, n_k, s.t_end / (double)n_k);
  o[1] = run_rk8pd(&s, n_g, s.t_end / (double)n_g);
  double wall = bench_now() - start;

  printf("Kepler e = 0.6, %d orbits (t_end = 2 pi 10^4), fixed steps, equal force evaluations\n"
         "force evaluations per step: kahan-li-8 %.3f, rk8pd %.3f (probe of 100 steps)\n\n",
         ORBITS, e_k, e_g);
  printf("%-12s %12s %10s %12s %14s %14s %14s %9s\n", "method", "h", "steps", "force evals",
         "max rel dH", "final rel dH", "|q - q_exact|", "cpu s");
  for (int i = 0; i < 2; ++i)
    printf("%-12s %12.6g %10zu %12zu %14.3e %14.3e %14.3e %9.3f\n", o[i].name, o[i].h,
           o[i].steps, o[i].force_evals, o[i].max_rel_energy, o[i].final_rel_energy,
           o[i].position_error, o[i].cpu_s);
  double r_max = o[1].max_rel_energy / o[0].max_rel_energy;
  double r_final = o[1].final_rel_energy / o[0].final_rel_energy;
  double r_pos = o[1].position_error / o[0].position_error;
  double r_time = o[1].cpu_s / o[0].cpu_s;
  double r_evals = (double)o[1].force_evals / (double)o[0].force_evals;
  printf("\nratios rk8pd / kahan-li-8: max energy error %.3g, final energy error %.3g, "
         "position error %.3g, cpu time %.3g, force evaluations %.6f (%.1f s in all)\n",
         r_max, r_final, r_pos, r_time, r_evals, wall);

  FILE *f = bench_open_json(argc, argv, "gsl_comparison");
  if (f != NULL) {
    fprintf(f, "{\n  \"benchmark\": \"gsl_comparison\",\n  \"problem\": \"kepler\",\n"
               "  \"eccentricity\": 0.6,\n  \"orbits\": %d,\n  \"t_end\": %.17g,\n"
               "  \"energy_sampled_every_steps\": %d,\n  \"rows\": [\n",
            ORBITS, s.t_end, SAMPLE_EVERY);
    for (int i = 0; i < 2; ++i)
      fprintf(f,
              "    {\"method\": \"%s\", \"h\": %.17g, \"steps\": %zu, \"force_evals\": %zu, "
              "\"force_evals_per_step\": %.4f, \"max_rel_energy_error\": %.6g, "
              "\"final_rel_energy_error\": %.6g, \"final_position_error\": %.6g, "
              "\"cpu_s\": %.6f}%s\n",
              i == 0 ? "kahan-li-8" : "gsl-rk8pd", o[i].h, o[i].steps, o[i].force_evals,
              o[i].evals_per_step, o[i].max_rel_energy, o[i].final_rel_energy,
              o[i].position_error, o[i].cpu_s, i == 0 ? "," : "");
    fprintf(f,
            "  ],\n  \"ratios_rk8pd_over_kahan_li_8\": {\"max_energy_error\": %.6g, "
            "\"final_energy_error\": %.6g, \"position_error\": %.6g, \"time\": %.6g, "
            "\"force_evals\": %.8f}\n}\n",
            r_max, r_final, r_pos, r_time, r_evals);
    fclose(f);
  }
  gm_model_free(model);
  return 0;
}

#else /* no GSL: nothing to compare against */
int main(void) {
  puts("gsl_comparison: skipped, GSL (libgsl-dev, pkg-config gsl) was not found at configure "
       "time");
  return 0;
}
#endif
