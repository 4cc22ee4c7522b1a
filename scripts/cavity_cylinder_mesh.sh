#!/bin/sh
# Regenerate examples/cavity_cylinder_{1,2,3}.msh (the PEC cylinder cavity of
# `geomint maxwell mesh-cavity --shape cylinder`, issue 11) from examples/cavity_cylinder.geo
# with Debian's gmsh (apt-get install gmsh; 4.8.4 was used). Sizes h = 0.14, 0.1, 0.07 (a
# factor ~1/sqrt(2) per level). Run from the repository root.
set -e
k=1
for h in 0.14 0.1 0.07; do
  gmsh -3 -format msh22 -setnumber h "$h" examples/cavity_cylinder.geo \
    -o "examples/cavity_cylinder_$k.msh" > /dev/null
  k=$((k + 1))
done
