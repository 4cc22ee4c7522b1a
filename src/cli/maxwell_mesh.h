/* geomint maxwell mesh: Maxwell on a simplicial mesh (leapfrog or AVI). */
#ifndef GM_CLI_MAXWELL_MESH_H
#define GM_CLI_MAXWELL_MESH_H

/* argv[0] is the first argument after "maxwell mesh". Returns the exit status (0, 1 failed
 * run, 2 bad input). */
int cli_maxwell_mesh(int argc, char **argv);

/* The blow-up guard of `maxwell mesh` and --e5. The AVI has no stability bound for neighbouring
 * faces with different steps (coupling resonances), so its runs watch the plain field energy and
 * stop above MM_BLOWUP_RATIO times the reference (these runs have no sources, random initial E:
 * the reference is the energy at t_0; legitimate AVI runs stay below 2.7, docs/maxwell-mesh.md
 * "Blow-ups"). The leapfrog's plain energy swings legitimately up to 1/(1 − Courant) times E_0
 * and its modified energy is conserved even while it blows up (an insisted-on diagonal star with
 * non-positive entries), so it stops only on non-finite energy (limit = INFINITY). */
#define MM_BLOWUP_RATIO 10.0
typedef struct mm_guard {
  const char *command;
  double limit;      /* MM_BLOWUP_RATIO (AVI) or INFINITY (leapfrog: non-finite only) */
  int started;       /* e0 is set */
  double e0;         /* plain energy at t_0 */
  double max_ratio;  /* largest |plain| / |e0| seen (NaN once non-finite) */
  int fired;         /* the run blew up (the message is printed) */
  char advice[200];  /* appended to the message: what to change */
} mm_guard;
/* Record the plain energy at time t (the first call sets the reference); returns 1 after
 * printing "COMMAND: the run blew up at t = ...: the field energy is R x its initial value
 * (...); ADVICE" when it is non-finite or above limit × e0, else 0. */
int mm_guard_check(mm_guard *g, double t, double plain);

/* Advance s to t in 200 pieces (the same run as one advance_to) with the progress line of the
 * maxwell commands on a terminal (mx_progress: leapfrog steps, or AVI face updates, whose total
 * is estimated from the first piece). Returns advance_to's status. */
gm_status mm_advance_progress(gm_mesh_maxwell *s, double t);

/* Seed 000 experiment E5 on the Gmsh box cavity `mesh` (borrowed); see maxwell_mesh_e5.c. */
#include <stdint.h>
#include "geomint/mesh.h"
int cli_maxwell_mesh_e5(const gm_mesh *mesh, const char *out_dir, double t_end, uint64_t seed,
                        double f_max, double fraction, double sample_dt, double t_compare,
                        int json);

/* geomint maxwell mesh-cavity (maxwell_mesh_cavity.c): the PEC cavity convergence table. */
int cli_maxwell_mesh_cavity(int argc, char **argv);

#endif
