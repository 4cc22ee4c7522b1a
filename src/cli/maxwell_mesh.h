/* geomint maxwell mesh: Maxwell on a simplicial mesh (leapfrog or AVI). */
#ifndef GM_CLI_MAXWELL_MESH_H
#define GM_CLI_MAXWELL_MESH_H

/* argv[0] is the first argument after "maxwell mesh". Returns the exit status (0, 1 failed
 * run, 2 bad input). */
int cli_maxwell_mesh(int argc, char **argv);

/* Seed 000 experiment E5 on the Gmsh box cavity `mesh` (borrowed); see maxwell_mesh_e5.c. */
#include <stdint.h>
#include "geomint/mesh.h"
int cli_maxwell_mesh_e5(const gm_mesh *mesh, const char *out_dir, double t_end, uint64_t seed,
                        double f_max, double fraction, double sample_dt, double t_compare);

/* geomint maxwell mesh-cavity (maxwell_mesh_cavity.c): the PEC cavity convergence table. */
int cli_maxwell_mesh_cavity(int argc, char **argv);

#endif
