/* The vector kernels of the celestial module at 2 lanes (lanes.h): the short path of the
 * Kepler drift and the inverse cubes of a kick. */
#define VW 2
#define KEPLER_SHORT gm_kepler_short2
#define INVERSE_CUBES gm_inverse_cubes2
#include "celestial/kepler_short.h"
#include "celestial/inverse_cubes.h"
