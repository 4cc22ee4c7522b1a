#!/bin/sh
# docs/maxwell-mesh.md: the E4 table from the two runs it names (scripts/docs_regen.py runs it).
set -e
echo '| mesh | face updates | uniform stepping at the smallest step | ratio | max \|E(t) − E₀\|/E₀ | Gauss drift |'
echo '|---|---|---|---|---|---|'
for run in "acute, 20 columns:" "random partitions:--warp 0.3"; do
  geomint maxwell mesh --rect 20 ${run#*:} --avi --exact-steps --t-end 8 | awk -v name="${run%%:*}" '
    /^run:/ { for (i = 1; i <= NF; ++i) { if ($i == "updates" && $(i-1) == "face" && !fu) fu = $(i+1);
                                          if ($i == "step:") us = $(i+1); if ($i == "ratio") r = $(i+1) }
              sub(/,$/, "", fu); sub(/\)$/, "", r) }
    /^energy:/ { for (i = 1; i <= NF; ++i) if ($i == "|plain") e = $(i+3); sub(/,$/, "", e) }
    /^invariants:/ { g = $NF }
    END { printf "| %s | %s | %s | %s | %s | %s |\n", name, fu, us, r, e, g }'
done
