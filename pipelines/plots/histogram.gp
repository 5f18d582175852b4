# One fragment mass histogram (log-binned density) with a slope −2 guide (Kun et al. 1999 Fig. 12).
# gnuplot -e "csv='histogram.csv'; out='histogram'; title='impact'" histogram.gp
set datafile separator ','
set logscale xy
set xlabel 'fragment mass m (kg)'
set ylabel 'F(m) (kg^{-1})'
set format y '10^{%L}'
set title title
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 700,500 } else { set terminal svg size 700,500 }
  set output out.'.'.fmt
  plot csv using 1:2 every ::1 with linespoints pt 7 title 'F(m)', [1e-3:1] 1e-4 * x**-2 with lines dashtype 2 lc 'black' title 'slope −2'
}
