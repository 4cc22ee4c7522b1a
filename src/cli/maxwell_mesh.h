/* geomint maxwell mesh: Maxwell on a simplicial mesh (leapfrog or AVI). */
#ifndef GM_CLI_MAXWELL_MESH_H
#define GM_CLI_MAXWELL_MESH_H

/* argv[0] is the first argument after "maxwell mesh". Returns the exit status (0, 1 failed
 * run, 2 bad input). */
int cli_maxwell_mesh(int argc, char **argv);

#endif
