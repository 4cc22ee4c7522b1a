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
 * momenta are p_i = m_i v_i. */
#include "problems/internal.h"

#define N_BODIES 6

typedef struct {
  gm_gravity gravity; /* first: the shared gravity callbacks read it */
  double mass[N_BODIES];
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
  (void)params;
  (void)t0;
  (void)errmsg;
  (void)cap;
  outer_solar_system *s = ctx;
  for (size_t i = 0; i < N_BODIES; ++i) s->mass[i] = mass[i];
  s->gravity = (gm_gravity){3 * N_BODIES, N_BODIES, gravitational_constant, 0.0, s->mass};
  gm_gravity_setup(pb);
  for (size_t i = 0; i < N_BODIES; ++i)
    for (size_t k = 0; k < 3; ++k) {
      y0[3 * i + k] = position[i][k];
      y0[3 * N_BODIES + 3 * i + k] = mass[i] * velocity[i][k];
    }
  return GM_OK;
}

const gm_model_def gm_model_outer_solar_system = {
    {"outer-solar-system",
     "Sun (with the inner planets), Jupiter, Saturn, Uranus, Neptune, Pluto; HLW Table I.2.1, "
     "AU, days",
     GM_PROBLEM_SEPARABLE, 3 * N_BODIES, 0, NULL, GM_GRAVITY_N_INVARIANTS,
     gm_gravity_invariant_names, 0},
    sizeof(outer_solar_system), NULL, setup, NULL, NULL};
