/* Partitioned Runge–Kutta methods for non-separable H(q, p), solved by Newton's method. */
#include "methods/internal.h"

/* Lobatto IIIA for q with Lobatto IIIB for p, s stages: order 2s − 2, symplectic and symmetric
 * (Sun Geng, J. Comput. Math. 11 (1993) 365; Jay, SIAM J. Numer. Anal. 33 (1996) 368;
 * GNI (2006), §II.2.2, Thm VI.4.6). s = 2 is Störmer–Verlet for separable problems. */
#define LOBATTO(s_, name_)                                                                    \
  {.name = name_, .family = GM_FAMILY_PARTITIONED_RK, .order = 2 * (s_)-2, .n_stages = (s_),  \
   .flags = GM_SYMPLECTIC | GM_SYMMETRIC | GM_IMPLICIT, .accepts = GM_PROBLEM_HAMILTONIAN,    \
   .compute = gm_lobatto_iiia_iiib_tableau,                                                   \
   .description = "Lobatto IIIA-IIIB pair, " #s_ " stages, for non-separable H",              \
   .reference = "Sun Geng, J. Comput. Math. 11 (1993) 365; Hairer, Lubich & Wanner, GNI "     \
                "(2006), Sect. II.2.2, Thm VI.4.6"}

const gm_method gm_partitioned_rk_methods[] = {
    LOBATTO(2, "lobatto-iiia-iiib-2"),
    LOBATTO(3, "lobatto-iiia-iiib-3"),
    LOBATTO(4, "lobatto-iiia-iiib-4"),
};
const size_t gm_n_partitioned_rk_methods =
    sizeof gm_partitioned_rk_methods / sizeof gm_partitioned_rk_methods[0];
