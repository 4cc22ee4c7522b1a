#!/bin/sh
# Regenerate examples/e5_cavity.msh (issue 11, experiment E5) from examples/e5_cavity.geo with
# Debian's gmsh (apt-get install gmsh; 4.8.4 was used). Run from the repository root.
set -e
gmsh -3 -format msh22 examples/e5_cavity.geo -o examples/e5_cavity.msh
