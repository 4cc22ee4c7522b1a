#!/bin/sh
# docs/maxwell.md: the relative errors of the lowest and the tenth mode against N, with rates,
# from `geomint maxwell cavity --dim 3 --n N` (scripts/docs_regen.py runs it).
echo '| N | (1,1,0) | rate | (1,2,1) | rate | computed vs Yee, max over the ten |'
echo '|---|---|---|---|---|---|'
for n in 8 16 32; do
  geomint maxwell cavity --dim 3 --n $n --out /tmp/geomint-docs-cavity | awk -v n=$n '
    $2 == "(1,1,0)" { a = $6 } $2 == "(1,2,1)" { b = $6 }
    $1 ~ /^[0-9]+$/ && NF == 7 { y = $7 < 0 ? -$7 : $7; if (y > m) m = y }
    END { printf "%s %s %s %.1e\n", n, a, b, m }'
done | awk '
  { r1 = r2 = ""
    if (NR > 1) { r1 = sprintf("%.2f", log(pa / $2) / log($1 / pn)); r2 = sprintf("%.2f", log(pb / $3) / log($1 / pn)) }
    printf "| %s | %s | %s | %s | %s | %s |\n", $1, $2, r1, $3, r2, $4; pn = $1; pa = $2; pb = $3 }'
