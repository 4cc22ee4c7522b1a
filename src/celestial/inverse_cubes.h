/* out[k] = 1/(s[k] √s[k]) for k < count, VW at a time (lanes.h): instantiated by lanes2.c and
 * lanes4.c as INVERSE_CUBES. The square roots and divisions of a kick queue on the one
 * divider, which takes a vector of 2 or 4 lanes as fast as one double (measured on this
 * machine: 2.5 ns per square root and 1.3 ns per division for 1, 2 or 4 lanes), so lanes are
 * what makes a kick cheaper. A short last vector repeats its last value. */
#include "celestial/lanes.h"

void INVERSE_CUBES(size_t count, const double *s, double *out) {
  const vd one = vd_splat(1.0);
  for (size_t i = 0; i < count; i += VW) {
    vd x;
    for (int j = 0; j < VW; ++j) x[j] = s[i + (size_t)j < count ? i + (size_t)j : count - 1];
    const vd y = one / (x * vd_sqrt(x));
    for (int j = 0; j < VW && i + (size_t)j < count; ++j) out[i + (size_t)j] = y[j];
  }
}
