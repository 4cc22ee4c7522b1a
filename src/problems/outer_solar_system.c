/* The outer solar system: the Sun and Jupiter, Saturn, Uranus, Neptune and Pluto under mutual
 * Newtonian gravity (gravity.c), H = Σ |p_i|²/(2 m_i) − G Σ_{i<j} m_i m_j / |q_i − q_j|.
 *
 * Data of Hairer, Lubich & Wanner, Geometric Numerical Integration (2nd ed., Springer 2006),
 * §I.2.4, Table 2.1: masses relative to the Sun, whose mass m0 = 1.00000597682 includes the
 * inner planets; distances in astronomical units, time in (Earth) days, so that the
 * gravitational constant is G = 2.95912208286e-4 AU³/(day² solar mass); positions and
 * velocities at the epoch September 5, 1994, 0h00 GMT. The numbers below were checked against
 * several independent transcriptions of that table (among them the SciML "Outer Solar System"
 * benchmark and the MatMol group's G_solar model); two further copies carry typos
 * (x of Jupiter −3.5025653, Jupiter's mass 0.00095486104043) that the majority does not. The
 * momenta are p_i = m_i v_i.
 *
 * The problem is a "central body + perturbed orbits" (gm_problem.celestial), so the
 * near-integrable rows (wh, saba-n-jacobi, ...) integrate it. Parameter planets = k keeps the
 * Sun and the first k planets (planets = 2: Sun, Jupiter, Saturn); epsilon multiplies the
 * planets' masses (the size of the perturbation; the initial velocities stay). */
#include <math.h>

#include "geomint/celestial.h"
#include "problems/internal.h"

#define N_BODIES 6

typedef struct {
  gm_gravity gravity; /* first: the shared gravity callbacks read it */
  double mass[N_BODIES];
  gm_celestial celestial;
} outer_solar_system;

static const double mass[N_BODIES] = {
    1.00000597682,      /* Sun, with the inner planets */
    0.000954786104043,  /* Jupiter */
    0.000285583733151,  /* Saturn */
    0.0000437273164546, /* Uranus */
    0.0000517759138449, /* Neptune */
    1.0 / 1.3e8,        /* Pluto */
};

/* positions in AU */
static const double position[N_BODIES][3] = {
    {0.0, 0.0, 0.0},
    {-3.5023653, -3.8169847, -1.5507963},
    {9.0755314, -3.0458353, -1.6483708},
    {8.3101420, -16.2901086, -7.2521278},
    {11.4707666, -25.7294829, -10.8169456},
    {-15.5387357, -25.2225594, -3.1902382},
};

/* velocities in AU/day */
static const double velocity[N_BODIES][3] = {
    {0.0, 0.0, 0.0},
    {0.00565429, -0.00412490, -0.00190589},
    {0.00168318, 0.00483525, 0.00192462},
    {0.00354178, 0.00137102, 0.00055029},
    {0.00288930, 0.00114527, 0.00039677},
    {0.00276725, -0.00170702, -0.00136504},
};

static const double gravitational_constant = 2.95912208286e-4;

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  (void)t0;
  outer_solar_system *s = ctx;
  const size_t n = (size_t)params[0] + 1;
  for (size_t i = 0; i < n; ++i) s->mass[i] = i == 0 ? mass[0] : params[1] * mass[i];
  s->gravity = (gm_gravity){3 * n, n, gravitational_constant, 0.0, s->mass};
  gm_gravity_setup(pb);
  s->celestial = (gm_celestial){n, s->mass, gravitational_constant, 1};
  pb->celestial = &s->celestial;
  for (size_t i = 0; i < n; ++i)
    for (size_t k = 0; k < 3; ++k) {
      y0[3 * i + k] = position[i][k];
      y0[3 * n + 3 * i + k] = s->mass[i] * velocity[i][k];
    }
  (void)errmsg;
  (void)cap;
  return GM_OK;
}

static gm_status prepare(void *ctx, const double *params, const char *const *texts, size_t *dim,
                         char *errmsg, size_t cap) {
  (void)ctx;
  (void)texts;
  const double k = params[0];
  if (!(k >= 1.0 && k <= N_BODIES - 1 && k == floor(k)))
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "outer-solar-system: planets must be an integer from 1 to %d, got %g",
                   N_BODIES - 1, k);
  if (!(params[1] > 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "outer-solar-system: epsilon (the planets' mass factor) must be positive, "
                   "got %g",
                   params[1]);
  *dim = 3 * ((size_t)k + 1);
  return GM_OK;
}

static const gm_param_info params[] = {
    {"planets", 5.0, "keep the Sun and the first k planets (2: Sun-Jupiter-Saturn)",
     GM_PARAM_NUMBER},
    {"epsilon", 1.0, "factor on the planets' masses (the perturbation's size)",
     GM_PARAM_NUMBER}};

const gm_model_def gm_model_outer_solar_system = {
    {"outer-solar-system",
     "Sun (with the inner planets), Jupiter, Saturn, Uranus, Neptune, Pluto; HLW Table I.2.1, "
     "AU, days",
     GM_PROBLEM_SEPARABLE, 3 * N_BODIES, 2, params, GM_GRAVITY_N_INVARIANTS,
     gm_gravity_invariant_names, 0},
    sizeof(outer_solar_system), prepare, setup, NULL, NULL};
