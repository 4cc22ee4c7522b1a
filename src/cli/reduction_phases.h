/* geomint reduction phases (reduction_phases.c): prints the phases table; returns a CLI exit code. */
#ifndef GM_CLI_REDUCTION_PHASES_H
#define GM_CLI_REDUCTION_PHASES_H

#include <stdio.h>

int cli_reduction_phases(void);
/* The convergence data behind the table (CSV, errors vs points per loop / steps per period). */
int cli_reduction_phases_convergence(FILE *f);

#endif
