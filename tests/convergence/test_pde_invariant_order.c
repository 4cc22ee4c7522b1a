/* Invariant schemes: measured order of consistency of each scheme, standard and invariantized,
 * as the one-step error from exact data divided by k (the local truncation error) on the front
 * (u_L, u_R, x0, ν) = (1, 0, 0, 0.1), k = h/2, h = 0.02 → 0.0025 (docs/pde.md table; the
 * command `geomint pde invariant orders` prints the same numbers). */
#include <criterion/criterion.h>
#include <math.h>

#include "geomint/pde.h"

Test(pde_invariant, orders_of_consistency) {
  const char *names[] = {"ftcs", "lax-wendroff", "crank-nicolson"};
  /* measured (std, inv): ftcs 1.02, 0.99; lax-wendroff 0.98, 0.99; crank-nicolson 2.00, 2.00 */
  const double doc[3] = {1.0, 1.0, 2.0};
  for (size_t i = 0; i < 3; i++)
    for (int inv = 0; inv < 2; inv++) {
      const gm_inv_scheme *s;
      cr_assert_eq(gm_inv_scheme_find(names[i], &s), GM_OK);
      double p;
      gm_error err = {{0}};
      cr_assert_eq(gm_inv_consistency_order(s, inv ? &gm_inv_burgers_g0 : NULL, &p, NULL, &err),
                   GM_OK, "%s", err.message);
      cr_log_info("%s %s: %.3f", names[i], inv ? "invariant" : "standard", p);
      cr_assert(fabs(p - doc[i]) <= 0.2, "%s %s: order %.3f, docs %.1f", names[i],
                inv ? "invariant" : "standard", p, doc[i]);
    }
}
