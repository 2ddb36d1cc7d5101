# Constraint solver: cloth cost vs size, Gauss-Seidel vs Jacobi convergence, substeps vs iterations.
set terminal pngcairo size 1500,500 font ",10"
set output dir.'/constraints.png'
set datafile separator ','
set multiplot layout 1,3 title 'tether: position constraints (hanging cloth, structural + shear + bend links)'
set grid
set key top left noenhanced
set logscale xy
set xlabel 'particles'
set ylabel 'ms per step (10 sweeps)'
set title 'cloth 32^2 … 256^2, cost per step'
set label 1 'target: 128^2 ≤ 2 ms' at 16384,2 point pt 9 ps 2 offset 1,-1
plot '< grep ",gs," '.dir.'/constraints_scale.csv' using 2:5 with linespoints lw 2 pt 7 title 'Gauss-Seidel', \
     '< grep ",jacobi," '.dir.'/constraints_scale.csv' using 2:5 with linespoints lw 2 pt 5 title 'Jacobi'
unset label 1
set xlabel 'sweeps per step'
set ylabel 'mean structural stretch after 1 s'
set title '64^2 cloth, top row pinned: error vs sweeps'
set key top right
plot dir.'/constraints_orders.csv' using 2:3 skip 1 with linespoints lw 2 pt 7 title 'Gauss-Seidel', \
     '' using 2:4 skip 1 with linespoints lw 2 pt 5 title 'Jacobi'
set xlabel 'substeps (sweeps per substep = 24 / substeps)'
set ylabel 'mean structural stretch after 1 s'
set title 'equal cost (24 sweeps per step): substeps vs iterations'
plot dir.'/constraints_substeps.csv' using 1:4 skip 1 with linespoints lw 2 pt 7 title 'substeps x iterations = 24'
unset multiplot
