# Headless 800x600 frame time vs particle count (OSMesa software GL).
set terminal pngcairo size 900,600 font ",11"
set output dir.'/render.png'
set datafile separator ','
set logscale xy
set xrange [500:6e5]
set xlabel 'particles'
set ylabel 'ms per 800x600 frame (median)'
set title 'tether: headless debug-draw frame (target: <= 50 ms at 100 000 particles)'
set key bottom right
set grid
set arrow from 100000, graph 0 to 100000, graph 1 nohead dt 3 lc rgb 'gray'
plot dir.'/render.csv' using 1:2 every ::1 with linespoints lw 2 pt 7 title 'debug draw (canvas batches)', \
     ''                using 1:3 every ::1 with linespoints lw 2 pt 7 title 'GL render (one call per kind)', \
     ''                using 1:4 every ::1 with linespoints lw 2 pt 7 title 'frame = draw + render', \
     ''                using 1:6 every ::1 with linespoints lw 1 pt 4 dt 2 title 'frame, process CPU time (all threads)', \
     ''                using 1:5 every ::1 with linespoints lw 1 pt 6 title 'PNG write (apart)', \
     50 with lines dt 2 lc rgb 'red' title '50 ms target'
