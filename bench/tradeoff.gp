# Speed/accuracy trade per integrator: error at t = 10 s against the cost of reaching it.
set terminal pngcairo size 900,600 font ",11"
set output dir.'/tradeoff.png'
set datafile separator ','
set logscale xy
set format y '10^{%L}'
set xlabel 'cost to simulate 10 s: ns per particle (median step time × steps)'
set ylabel 'max position error vs exact orbit'
set title 'tether: integrator speed/accuracy trade (1000 oscillators, dt 0.1 … 0.002)'
set key top right noenhanced
set grid
plot for [name in 'euler symplectic_euler leapfrog verlet rk4'] \
  '< grep "^'.name.'," '.dir.'/tradeoff.csv' using 5:3 with linespoints lw 2 pt 7 title name
