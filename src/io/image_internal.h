/* Private to src/io: sizes of a validated snapshot. */
#ifndef GM_IO_IMAGE_INTERNAL_H
#define GM_IO_IMAGE_INTERNAL_H

#include <stddef.h>

#include "geomint/io.h"

/* Cells along axis (0 for a flat axis past dim). */
size_t gm_image_extent(const gm_image *image, size_t axis);
/* Tuples of the array: cells or points. */
size_t gm_image_array_count(const gm_image *image, const gm_image_array *array);

#endif
