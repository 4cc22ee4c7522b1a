#!/bin/sh
# docs/fluids.md: `geomint fluid rates` for both flows and the table of their rates beside the
# seed's (scripts/docs_regen.py runs it).
set -e
c=$(geomint fluid rates --flow couette)
p=$(geomint fluid rates --flow poiseuille)
printf '`geomint fluid rates --flow couette`:\n\n```\n%s\n```\n\n' "$c"
printf '`geomint fluid rates --flow poiseuille`:\n\n```\n%s\n```\n\n' "$p"
rates() { printf '%s\n' "$1" | awk '/^ *rate/ { printf "%s | %s | %s | %s", $2, $3, $4, $5 }'; }
echo '| rate over the seven meshes | ψ | θ | velocity (per triangle) | flux per length |'
echo '|---|---|---|---|---|'
echo "| Couette, geomint | $(rates "$c") |"
echo '| Couette, seed | 1.84 | 2 | 1 | 1 |'
echo "| Poiseuille, geomint | $(rates "$p") |"
echo '| Poiseuille, seed | 1.37 | 1.95 | 1 | 1 |'
