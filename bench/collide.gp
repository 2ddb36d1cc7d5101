# Collisions: ms/step against particle count, grid vs brute force, equal radii and a 1:4 mix.
set terminal pngcairo size 900,600 font ",11"
set output dir.'/collide.png'
set datafile separator ','
set logscale xy
set xrange [500:2e6]
set yrange [0.01:20000]
set xlabel 'colliding particles (packed in a box under gravity)'
set ylabel 'ms per step (median; 1 substep, 1 iteration)'
set title 'tether collisions: uniform grid is linear in N; brute force is N^2 (target: 100k <= 5 ms)'
set key bottom right
set grid
set format y '%g'
plot dir.'/collide.csv' using 1:(strcol(2) eq 'equal' ? $3 : 1/0) with linespoints lw 2 pt 7 title 'grid, equal radii', \
     ''                 using 1:(strcol(2) eq 'mix' ? $3 : 1/0) with linespoints lw 2 pt 5 title 'grid, radii 1:4', \
     ''                 using 1:(strcol(2) eq 'equal' ? $8 : 1/0) with linespoints lw 1 dt 4 pt 6 title 'the grid itself (build, pairs), equal radii', \
     ''                 using 1:(strcol(2) eq 'mix' ? $8 : 1/0) with linespoints lw 1 dt 4 pt 4 title 'the grid itself, radii 1:4', \
     ''                 using 1:(strcol(2) eq 'equal' && $4 == $4 ? $4 : 1/0) with linespoints lw 2 pt 9 title 'brute force, equal radii', \
     ''                 using 1:(strcol(2) eq 'mix' && $4 == $4 ? $4 : 1/0) with linespoints lw 2 pt 11 title 'brute force, radii 1:4', \
     5 * x / 100000 with lines dt 2 lc rgb 'gray' title 'linear through the target (5 ms at 100k)', \
     1000 with lines dt 3 lc rgb 'red' title '1 s'
