/* The vector kernels of the celestial module at 2 lanes (lanes.h): the short path of the
 * Kepler drift and the sums of a kick. */
#define VW 2
#define KEPLER_SHORT gm_kepler_short2
#define ROW_SUMS gm_row_sums2
#define CENTRAL_TERMS gm_central_terms2
#include "celestial/kepler_short.h"
#include "celestial/row_sums.h"
