/* libFuzzer target for the mesh readers (`make fuzz`): the first byte picks the parser (even:
 * Gmsh .msh, odd: OFF), the rest is the file. Every input must give GM_OK with a mesh that
 * turns into a complex or is refused with a message, or an error with a "line N:" message;
 * AddressSanitizer and UBSan catch the rest. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size == 0) return 0;
  const char *text = (const char *)data + 1;
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  gm_status st = (data[0] & 1) ? gm_mesh_parse_off(text, size - 1, &m, &err)
                               : gm_mesh_parse_msh(text, size - 1, &m, &err);
  if (st == GM_OK) {
    if (m == NULL) abort();
    for (size_t i = 0; i < (m->dim + 1) * m->n_cells; ++i)
      if (m->cells[i] >= m->n_vertices) abort(); /* the reader promised valid indices */
    gm_complex *cx = NULL;
    if (gm_mesh_complex(m, &cx, &err) == GM_OK) gm_complex_free(cx);
    gm_mesh_free(m);
  } else {
    if (m != NULL) abort();
    if (st != GM_ENOMEM && strncmp(err.message, "line ", 5) != 0) abort();
  }
  return 0;
}
