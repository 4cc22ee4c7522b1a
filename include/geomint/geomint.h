/* geomint: geometric numerical integration of mechanics and field theories. Umbrella header. */
#ifndef GEOMINT_GEOMINT_H
#define GEOMINT_GEOMINT_H

#include "geomint/core.h"
#include "geomint/ode.h"
#include "geomint/methods.h"
#include "geomint/problems.h"
#include "geomint/io.h"
#include "geomint/sparse.h"
#include "geomint/dec.h"
#include "geomint/mesh.h"
#include "geomint/multigrid.h"
#include "geomint/mimetic.h"
#include "geomint/variational.h"
#include "geomint/fields.h"
#include "geomint/yee_scene.h"
#include "geomint/lie.h"
#include "geomint/oscillatory.h"
#include "geomint/celestial.h"
#include "geomint/reduction.h"
#include "geomint/pde.h"
#include "geomint/experiments.h"
#include "geomint/fluids.h"

#define GM_VERSION_MAJOR 0
#define GM_VERSION_MINOR 1
#define GM_VERSION_PATCH 0
#define GM_VERSION_STRING "0.1.0"

#endif
