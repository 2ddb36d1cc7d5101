# The reference pour onto the mask bowl at 20 s (make bench, section terrain): every circle coloured by its
# speed, in tether (1 x 8), in Box2D 2.4.1 with circles that do not turn and that do, and in tether with anchored
# friction (bowl.csv).
set terminal png size 2160,560 font ",10"  # libgd: a fifth of pngcairo's size for 40 000 discs
set output dir.'/bowl.png'
set datafile separator ','
set multiplot layout 1,4 title 'The reference pour onto a bowl at 20 s, coloured by speed (issue 19: KE <= 1e-3 J/kg at 20 s)'
set size ratio -1
set xrange [-52:52]
set yrange [-2:104]
set cbrange [-4:0]
set cblabel 'log10 speed, m/s'
set palette defined (-4 '#d8d8d8', -2 '#4060c0', -1 '#f0a000', 0 '#d00000')
unset key
set tics out
spd(s) = log10(s > 1e-4 ? s : 1e-4)
arc(x) = 80 - sqrt(6400 - x * x)
titles = "tether,_mask_bowl,_1_x_8 Box2D,_400_edges,_circles_that_do_not_turn Box2D,_circles_that_turn tether,_anchored_friction"
do for [e = 0:3] {
  set title system(sprintf("echo %s | tr _ ' '", word(titles, e + 1)))
  plot dir.'/bowl.csv' using ($1 == e ? $2 : 1/0):3:(0.5):(spd($4)) with circles fill solid noborder lc palette, \
       [-50:50] arc(x) with lines lc rgb 'black' lw 1.5
}
unset multiplot
