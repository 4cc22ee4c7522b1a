/* geomint mesh refine | transfer, and the solver choice of mesh poisson (src/cli/mesh_multigrid.c). */
#ifndef GM_CLI_MESH_MULTIGRID_H
#define GM_CLI_MESH_MULTIGRID_H

#include <stddef.h>

#include "geomint/mesh.h"

/* mesh refine FILE --levels L --out F.msh */
int cli_mesh_refine(const gm_mesh *m, const char *path, size_t levels, const char *out,
                    size_t max_bytes, int json);
/* mesh transfer A B */
int cli_mesh_transfer(const gm_mesh *a, const char *path_a, const gm_mesh *b, const char *path_b,
                      int json);
/* "cholmod" or "mg"; -1 for anything else */
int cli_mesh_solver(const char *name);

#endif
