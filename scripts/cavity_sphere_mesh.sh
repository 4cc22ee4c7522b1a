#!/bin/sh
# Regenerate examples/cavity_sphere_{1,2,3}.msh (the PEC sphere cavity of
# `geomint maxwell mesh-cavity --shape sphere`, issue 11) from examples/cavity_sphere.geo
# with Debian's gmsh (apt-get install gmsh; 4.8.4 was used). Sizes h = 0.14, 0.1, 0.07 (a
# factor ~1/sqrt(2) per level). Run from the repository root. GEO and OUT (a directory) may be
# given to try other settings: OUT=/tmp/m scripts/cavity_sphere_mesh.sh
set -e
geo=${GEO:-examples/cavity_sphere.geo}
out=${OUT:-examples}
k=1
for h in 0.14 0.1 0.07; do
  gmsh -3 -format msh22 -setnumber h "$h" "$geo" -o "$out/cavity_sphere_$k.msh" > /dev/null
  k=$((k + 1))
done
