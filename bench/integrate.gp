# Verlet integrate stage vs a bare struct-of-arrays loop, per particle.
set terminal pngcairo size 900,600 font ",11"
set output dir.'/integrate.png'
set datafile separator ','
set logscale x
set xrange [500:2e6]
set xlabel 'particles'
set ylabel 'ns per particle per step (median)'
set yrange [0:*]
set title 'tether: gravity-only Verlet integrate stage (target: within 2x of the bare loop)'
set key top left
set grid
plot dir.'/integrate.csv' using 1:2 every ::1 with linespoints lw 2 pt 7 title 'bare SoA loop', \
     ''                    using 1:3 every ::1 with linespoints lw 2 pt 7 title 'engine integrate stage', \
     ''                    using 1:($2*2) every ::1 with lines dt 2 lc rgb 'gray' title '2x bare (target)'
