/* What each family's stepper keeps between steps (gm_stepper_state): the flag of steppers that
 * choose their own step sizes, and the state a checkpoint must save for a restarted run to
 * continue bitwise (src/ode/checkpoint.c). Explicit Runge–Kutta keeps nothing. */
#include "methods/internal.h"

extern const gm_stepper_state gm_implicit_rk_stepper_state, gm_splitting_stepper_state,
    gm_variational_stepper_state, gm_sem_stepper_state, gm_mimetic_stepper_state,
    gm_discrete_gradient_stepper_state, gm_composition_stepper_state;

const gm_stepper_state *gm_stepper_state_of(const gm_stepper *stepper) {
  static const struct {
    const gm_stepper *stepper;
    const gm_stepper_state *state;
  } table[] = {{&gm_implicit_rk_stepper, &gm_implicit_rk_stepper_state},
               {&gm_splitting_stepper, &gm_splitting_stepper_state},
               {&gm_variational_stepper, &gm_variational_stepper_state},
               {&gm_sem_stepper, &gm_sem_stepper_state},
               {&gm_mimetic_stepper, &gm_mimetic_stepper_state},
               {&gm_discrete_gradient_stepper, &gm_discrete_gradient_stepper_state},
               {&gm_composition_stepper, &gm_composition_stepper_state}};
  for (size_t i = 0; i < sizeof table / sizeof table[0]; ++i)
    if (table[i].stepper == stepper) return table[i].state;
  return NULL;
}
