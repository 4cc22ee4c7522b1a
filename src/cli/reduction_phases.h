/* geomint reduction phases (reduction_phases.c): prints the phases table; returns a CLI exit code. */
#ifndef GM_CLI_REDUCTION_PHASES_H
#define GM_CLI_REDUCTION_PHASES_H

int cli_reduction_phases(void);

#endif
