# gnuplot script for docs/images/variational_double_pendulum.png; data from
#   example_double_spherical_pendulum 100000 0.005 > dsp.csv
set datafile separator ","
set terminal pngcairo size 900,600 font ",10"
set output "variational_double_pendulum.png"
set multiplot layout 2,1 title "double spherical pendulum, vi-galerkin-gauss-2, h = 0.005, 10^5 steps"
set ylabel "relative energy error"
set format y "%.0e"
plot "dsp.csv" using 1:2 with lines lw 1 title "(E - E_0)/|E_0|"
set xlabel "t"
set ylabel "J_z - J_z(0), max |g(q)|"
plot "dsp.csv" using 1:3 with lines title "vertical angular momentum drift", \
     "dsp.csv" using 1:4 with lines title "constraint residual"
unset multiplot
