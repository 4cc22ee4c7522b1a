/* Small pieces shared by the steppers that solve stage equations (implicit Runge–Kutta,
 * mimetic, discrete gradient, variational). */
#include <string.h>

#include "methods/internal.h"

gm_status gm_stage_solve_failed(gm_integrator *it, gm_status status, double t, double h) {
  if (status == GM_ECALLBACK) return status; /* the callback's own message stands */
  if (status == GM_ENOCONV || status == GM_ESINGULAR || status == GM_EDOMAIN)
    it->stats.newton_failures++;
  char why[GM_ERRMSG_SIZE];
  memcpy(why, it->errmsg, sizeof why);
  return gm_fail(it->errmsg, sizeof it->errmsg, status,
                 "%s: %s in the step from t = %.17g (h = %g)", it->method->name, why, t, h);
}

void gm_stage_extrapolate(size_t s, size_t m, const double *e, const double *z_prev, double *z) {
  memset(z, 0, s * m * sizeof *z);
  for (size_t i = 0; i < s; ++i)
    for (size_t j = 0; j < s; ++j) {
      const double eij = e[i * s + j];
      for (size_t k = 0; k < m; ++k) z[i * m + k] += eij * z_prev[j * m + k];
    }
}
