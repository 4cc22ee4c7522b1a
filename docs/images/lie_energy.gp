# gnuplot script for docs/images/lie_energy.png; data from (M = lgvi, rkmk4, rigid-splitting,
# crouch-grossman-3)
#   geomint run rigid-body --method M --dt 0.2 --t-end 20000 --every 50 --out e_M.csv
set datafile separator ","
set terminal pngcairo size 900,700 font ",10"
set output "lie_energy.png"
c0 = 1.0024968827881711   # |Pi(0)|
lowcut(x) = x > 1e-17 ? x : 1e-17
set logscale y
set format y "10^{%L}"
set key outside right
set multiplot layout 2,1 title "free rigid body, h = 0.2, 10^5 steps: LGVI against RKMK"
set ylabel "|H - H_0| / |H_0|"
plot "e_lgvi.csv" using 1:(lowcut(abs($15))) with lines lw 1.5 title "lgvi", \
     "e_rigid-splitting.csv" using 1:(lowcut(abs($15))) with lines lw 1 title "rigid-splitting", \
     "e_rkmk4.csv" using 1:(lowcut(abs($15))) with lines lw 1.5 title "rkmk4", \
     "e_crouch-grossman-3.csv" using 1:(lowcut(abs($15))) with lines lw 1 title "crouch-grossman-3"
set xlabel "t"
set ylabel "| |Pi| - |Pi_0| | / |Pi_0|"
plot "e_lgvi.csv" using 1:(lowcut(abs($16 - c0) / c0)) with lines lw 1.5 title "lgvi", \
     "e_rigid-splitting.csv" using 1:(lowcut(abs($16 - c0) / c0)) with lines lw 1 title "rigid-splitting", \
     "e_rkmk4.csv" using 1:(lowcut(abs($16 - c0) / c0)) with lines lw 1.5 title "rkmk4", \
     "e_crouch-grossman-3.csv" using 1:(lowcut(abs($16 - c0) / c0)) with lines lw 1 title "crouch-grossman-3"
unset multiplot
