# gnuplot script for docs/images/lie_flip.png; data from
#   geomint run rigid-body --method lgvi --dt 0.01 --t-end 150 --every 10 --out frb_lgvi.csv
set datafile separator ","
set terminal pngcairo size 900,600 font ",10"
set output "lie_flip.png"
set multiplot layout 2,1 title "free rigid body I = (1, 2, 3) spinning near the intermediate axis, lgvi, h = 0.01"
set key outside right
set ylabel "body angular momentum"
plot "frb_lgvi.csv" using 1:11 with lines lw 1.5 title "Pi_1", \
     "frb_lgvi.csv" using 1:12 with lines lw 1.5 title "Pi_2", \
     "frb_lgvi.csv" using 1:13 with lines lw 1.5 title "Pi_3"
set xlabel "t"
set ylabel "body axis 2 in space, R e_2"
plot "frb_lgvi.csv" using 1:3 with lines lw 1.5 title "x", \
     "frb_lgvi.csv" using 1:6 with lines lw 1.5 title "y", \
     "frb_lgvi.csv" using 1:9 with lines lw 1.5 title "z"
unset multiplot
