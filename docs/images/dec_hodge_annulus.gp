# Draws docs/images/dec_hodge_annulus.png from the CSV of examples/dec_hodge_annulus.c:
#   example_dec_hodge_annulus DIR && cd DIR && gnuplot .../docs/images/dec_hodge_annulus.gp
set terminal pngcairo size 1400,1400 font ",13"
set output 'dec_hodge_annulus.png'
set datafile separator ','
set multiplot layout 2,2 title "Hodge decomposition on the annulus 0.5 < r < 1 (examples/dec\\_hodge\\_annulus.c)"
set size ratio -1
set xrange [-1.05:1.05]; set yrange [-1.05:1.05]
unset key
s = 0.06
set object 1 circle at 0,0 size 1 fc rgb "#f0f0f0" behind fillstyle solid noborder
set object 2 circle at 0,0 size 0.5 fc rgb "white" behind fillstyle solid noborder
do for [p=0:3] {
  t = p==0 ? "field X (flat, then sharp)" : p==1 ? "exact part dβ" : p==2 ? "coexact part δγ" : "harmonic part h"
  set title t
  plot 'dec_hodge_annulus.csv' every 4::1 using 1:2:(s*column(3+2*p)):(s*column(4+2*p)) with vectors head size 0.012,20 lc rgb (p==0 ? "black" : p==1 ? "#c03020" : p==2 ? "#2060c0" : "#208040")
}
unset multiplot
