#!/bin/sh
# docs/variational.md: the vi-sem-galerkin table, each row the command and what it prints
# (scripts/docs_regen.py runs it).
order() { # ARGS...: the fitted order, or why not and the exit status
  out=$(geomint order "$@" 2>/dev/null); status=$?
  fit=$(printf '%s\n' "$out" | sed -n 's/^fitted order \([0-9.]*\) .*/\1/p')
  if [ -n "$fit" ]; then echo "$fit"
  else printf '%s (exit %d)\n' "$(printf '%s\n' "$out" | sed -n 's/^order not measured: \([^(]*\).*/\1/p' | sed 's/ *$//')" "$status"; fi
}
run() { # ARGS...: steps, t, E_d error, fallbacks
  geomint run "$@" | awk '
    /^steps/ { n = $2; t = $NF }
    /^discrete energy/ { for (i = 1; i <= NF; ++i) { if ($i == "|E_d") e = $(i+3); if ($i == "least-squares") f = $(i-1) } }
    END { printf "%s steps, t = %s, E_d %s, %s fallbacks\n", n, t, e, f }'
}
echo '| command | result |'
echo '|---|---|'
echo "| \`geomint order --method vi-sem-galerkin-2\` (Kepler e = 0.1) | $(order --method vi-sem-galerkin-2) |"
echo "| \`geomint order --method vi-sem-galerkin-3\` (Kepler e = 0.1) | $(order --method vi-sem-galerkin-3) |"
echo "| \`geomint order pendulum --set q1=1 --method vi-sem-galerkin-2\` | $(order pendulum --set q1=1 --method vi-sem-galerkin-2) |"
echo "| \`geomint order pendulum --set q1=2 --method vi-sem-galerkin-3\` | $(order pendulum --set q1=2 --method vi-sem-galerkin-3) |"
echo "| \`geomint order pendulum --method vi-sem-galerkin-2\` (q = π/2) | $(order pendulum --method vi-sem-galerkin-2) |"
echo "| \`geomint run kepler --method vi-sem-galerkin-2 --dt 0.05 --t-end 31.4\` | $(run kepler --method vi-sem-galerkin-2 --dt 0.05 --t-end 31.4) |"
echo "| \`geomint run kepler --method vi-sem-galerkin-3 --dt 0.05 --t-end 31.4\` (e = 0.6) | $(run kepler --method vi-sem-galerkin-3 --dt 0.05 --t-end 31.4) |"
