#!/bin/sh
# docs/fluids.md: the B14 table from `geomint fluid channel` (scripts/docs_regen.py runs it).
geomint fluid channel | awk '
  /^profile error/ { flux = $(NF-2) }
  /^velocity per triangle/ { vel = $NF }
  /^max \|theta/ { theta = $NF }
  /^max \|delta omega/ { dw = $NF }
  END {
    print "| quantity (developed region x ∈ [L/4, 3L/4]) | geomint | seed |"
    print "|---|---|---|"
    printf "| flux per unit length vs Poiseuille, mean absolute error | **%s** | 2.4e-4 |\n", flux
    printf "| velocity per triangle vs Poiseuille at the centroid, mean | %s | — |\n", vel
    printf "| max \\|θ − 20y\\| | %s (of 20) | \"linear\" |\n", theta
    printf "| max ‖δω‖∞ over 500 steps | %s | — |\n", dw }'
