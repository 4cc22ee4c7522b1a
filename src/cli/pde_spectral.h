/* geomint pde schrodinger | spectral-star | tent-vi (pde_spectral.c), dispatched from pde.c. */
#ifndef GM_CLI_PDE_SPECTRAL_H
#define GM_CLI_PDE_SPECTRAL_H

extern const char cli_pde_spectral_usage[];
int cli_pde_schrodinger(int argc, char **argv);
int cli_pde_spectral_star(int argc, char **argv);
int cli_pde_tent_vi(int argc, char **argv);

#endif
