/* geomint maxwell run|cavity|e4: the Yee FDTD solver from the command line. */
#include <stdio.h>
#include <string.h>

#include "cli/maxwell.h"
#include "cli/maxwell_mesh.h"

int mx_run_main(int argc, char **argv);    /* maxwell_run.c */
int mx_cavity_main(int argc, char **argv); /* maxwell_cavity.c */
int mx_e4_main(int argc, char **argv);     /* maxwell_e4.c */
int mx_bands_main(int argc, char **argv);  /* maxwell_bands.c */

static const char usage[] =
    "usage: geomint maxwell run SCENE.json [--out DIR] [--json] [--check] [--threads K]\n"
    "                           [--plot FILE.png [--plot-field C]]\n"
    "       mpirun -np N geomint maxwell run SCENE.json [--out DIR] [--json] [--check]\n"
    "                           [--dims AxBxC] [--checkpoint PREFIX [--checkpoint-every N]]\n"
    "                           [--restart PREFIX]   (built with MPI: the distributed solver;\n"
    "                           SIGINT/SIGTERM write a checkpoint and stop)\n"
    "       geomint maxwell cavity [--dim 2|3] [--n N] [--periods P] [--out DIR] [--json]\n"
    "                              [--threads K]\n"
    "       geomint maxwell bands SCENE.json --k-path G,X,M,G [--points N] [--bands B] ...\n"
    "                              (band structure of a periodic cell; see 'bands --help')\n"
    "       geomint maxwell e4 [--n N] [--time T] [--seed S] [--out DIR] [--json] [--threads K]\n"
    "       geomint maxwell mesh FILE.msh | --rect NX [--avi] ... (see 'maxwell mesh --help')\n"
    "       geomint maxwell mesh-cavity [--shape box|cylinder|sphere] [--levels K] ...\n\n"
    "Maxwell's equations on a Cartesian grid with the Yee scheme (E on primal edges at half\n"
    "steps, H on primal faces at whole steps; seed 000 section 3.4.1). See docs/maxwell.md.\n\n"
    "  run     run the scene file: grid, materials, boundaries (pec, pmc, periodic, cpml),\n"
    "          sources, probes, flux planes, output. Writes to DIR (default maxwell-output):\n"
    "          probes.csv, energy.csv, flux.csv, flux_spectra.csv/.png (scene key \"dft\"),\n"
    "          snapshot_<step>.vti/.h5 with snapshot.pvd (ParaView), and prints the\n"
    "          resonances of the probe signals (harminv) and the time-integrated Poynting\n"
    "          flux of each plane. Dispersive media: materials' \"poles\" and \"library\"\n"
    "  cavity  PEC box [0,1]x[0,0.8](x[0,0.6]) with N cells per axis, a broadband pulse, and\n"
    "          harminv: the first 10 computed resonant frequencies against the analytic\n"
    "          ones and Yee's discrete dispersion relation; writes cavity-spectrum.png\n"
    "  e4      seed 000 experiment E4 on the uniform grid: random initial E in a PEC unit\n"
    "          square (2-D TE, N x N cells), steps of 1/10 of the Courant limit for T = 8;\n"
    "          prints the energy's bounded oscillation and writes e4-energy.png\n"
    "  mesh    PEC cavity on a triangle or tetrahedron mesh: DEC leapfrog or the AVI\n"
    "          (docs/maxwell-mesh.md)\n"
    "  mesh-cavity  PEC box, cylinder or sphere on tetrahedra at K resolutions: harminv\n"
    "          resonances against the analytic ones, rates, spurious peaks (see\n"
    "          'mesh-cavity --help')\n\n"
    "options:\n"
    "  --out DIR     output directory (created if missing)\n"
    "  --json        print one JSON object instead of the text summary\n"
    "  --check       (run) read the scene and create the solver, print what it would run\n"
    "  --threads K   (run, cavity, e4) OpenMP threads of the updates (default: OpenMP's,\n"
    "                OMP_NUM_THREADS)\n"
    "  --plot FILE   (run) a colour map of the final field (2-D: the grid, 3-D: the middle\n"
    "                z slice) drawn by gnuplot; --plot-field C picks the component (default\n"
    "                Ez, or Hz on a 2-D TE grid)\n"
    "  --dim 2|3     (cavity) 2: TM (Ez) in the rectangle, 3: the box (default 3)\n"
    "  --n N         cells per axis (cavity default 16, e4 default 32)\n"
    "  --periods P   (cavity) run length in periods of the lowest mode (default 200)\n"
    "  --time T      (e4) simulated time (default 8)\n"
    "  --seed S      (e4) seed of the random initial field (default 1)\n\n"
    "Exit status: 0 success, 1 a failure during the run (or writing output), 2 bad input\n"
    "(a malformed scene names the JSON path of the bad value).\n";

static int maxwell_main(int argc, char **argv) {
  if (argc < 1) {
    fputs(usage, stderr);
    return CLI_EXIT_USAGE;
  }
  if (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (strcmp(argv[0], "run") == 0) return mx_run_main(argc - 1, argv + 1);
  if (strcmp(argv[0], "cavity") == 0) return mx_cavity_main(argc - 1, argv + 1);
  if (strcmp(argv[0], "e4") == 0) return mx_e4_main(argc - 1, argv + 1);
  if (strcmp(argv[0], "bands") == 0) return mx_bands_main(argc - 1, argv + 1);
  if (strcmp(argv[0], "mesh") == 0) return cli_maxwell_mesh(argc - 1, argv + 1);
  if (strcmp(argv[0], "mesh-cavity") == 0) return cli_maxwell_mesh_cavity(argc - 1, argv + 1);
  cli_error("maxwell", "unknown subcommand '%s' (run, cavity, bands, e4, mesh, mesh-cavity); see 'geomint maxwell --help'",
            argv[0]);
  return CLI_EXIT_USAGE;
}

const cli_command cli_maxwell_command = {"maxwell",
                                         "Maxwell: Yee FDTD scenes, cavity check, E4; meshes (DEC "
                                         "leapfrog, AVI)",
                                         usage, maxwell_main};

/* The usage text, for the subcommands' --help. */
const char *mx_usage(void) { return usage; }
