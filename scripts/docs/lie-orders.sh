#!/bin/sh
# docs/lie-groups.md: the orders table, `geomint order PROBLEM --method M` for each row on the
# heavy top and the body in a central field (scripts/docs_regen.py runs it).
fit() { geomint order "$2" --method "$1" 2>/dev/null | sed -n 's/^fitted order \([0-9.]*\) .*/\1/p'; }
echo '| row | heavy-top | central-body |'
echo '|---|---|---|'
for m in lgvi lgvi-galerkin-1 lgvi-galerkin-2 lgvi-galerkin-3 rkmk4 crouch-grossman-3 rigid-splitting; do
  echo "| $m | $(fit $m heavy-top) | $(fit $m central-body) |"
done
