/* The vector kernels of the celestial module at 4 lanes (lanes.h): the short path of the
 * Kepler drift and the sums of a kick. CMake compiles this file
 * with -mavx2 on x86-64 (GM_CELESTIAL_AVX2), and the module calls it only on a CPU that has
 * AVX2 (gm_lane_width); elsewhere it is plain vector code that is not used. */
#define VW 4
#define KEPLER_SHORT gm_kepler_short4
#define ROW_SUMS gm_row_sums4
#define CENTRAL_TERMS gm_central_terms4
#include "celestial/kepler_short.h"
#include "celestial/row_sums.h"
