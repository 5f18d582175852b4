# Error against wall time, per integrator, log-log (issue 7): displacement error and energy drift.
set datafile separator ','
set logscale xy
set xlabel 'wall time (s)'
set key left bottom
set grid
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 1100,450 } else { set terminal svg size 1100,450 }
  set output out.'.'.fmt
  set multiplot layout 1,2
  set ylabel 'rms displacement error at t = 2e-4 s (m)'
  plot csv using (strcol(1) eq 'gear5' ? $5 : 1/0):9 with linespoints title 'gear5', \
       csv using (strcol(1) eq 'verlet' ? $5 : 1/0):9 with linespoints title 'verlet'
  set ylabel 'relative energy drift'
  plot csv using (strcol(1) eq 'gear5' ? $5 : 1/0):8 with linespoints title 'gear5', \
       csv using (strcol(1) eq 'verlet' ? $5 : 1/0):8 with linespoints title 'verlet'
  unset multiplot
}
