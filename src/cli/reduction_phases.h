/* geomint reduction phases (reduction_phases.c): prints the phases table; returns a CLI exit code. */
#ifndef GM_CLI_REDUCTION_PHASES_H
#define GM_CLI_REDUCTION_PHASES_H

/* The table (or with json one JSON object); with dir non-NULL, the convergence data
 * dir/phases-convergence.csv (errors vs points per loop / steps per period) too. */
int cli_reduction_phases(const char *dir, int json);

#endif
