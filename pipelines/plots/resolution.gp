# Resolution: error of K against the finest mesh, and wall time, against the cell count (issue 7).
set datafile separator ','
set logscale xy
set xlabel 'cells'
set grid
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 1100,450 } else { set terminal svg size 1100,450 }
  set output out.'.'.fmt
  set multiplot layout 1,2
  set ylabel '|K − K_{finest}| / K_{finest}'
  plot csv using 2:($8 > 0 ? $8 : 1/0) with linespoints title 'K error'
  set ylabel 'wall time (s)'
  plot csv using 2:4 with linespoints title 'wall time'
  unset multiplot
}
