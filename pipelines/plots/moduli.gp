# K(E) and ν(E) for tension, compression and the pure beam lattice (Kun et al. 1999 Figs. 5-6).
# gnuplot -e "csv='moduli.csv'; out='moduli'" moduli.gp  -> moduli.png, moduli.svg
set datafile separator ','
set key left top
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 1100,450 } else { set terminal svg size 1100,450 }
  set output out.'.'.fmt
  set multiplot layout 1,2
  set logscale xy
  set xlabel 'beam modulus E (Pa)'
  set ylabel 'effective Young modulus K (Pa)'
  plot csv using (strcol(2) eq 'tension' ? $1 : 1/0):4 with linespoints title 'tension', \
       csv using (strcol(2) eq 'compression' ? $1 : 1/0):4 with linespoints title 'compression', \
       csv using (strcol(2) eq 'beams' ? $1 : 1/0):4 with linespoints title 'beams only'
  unset logscale y
  set ylabel 'Poisson ratio ν'
  plot csv using (strcol(2) eq 'tension' ? $1 : 1/0):6 with linespoints title 'tension', \
       csv using (strcol(2) eq 'compression' ? $1 : 1/0):6 with linespoints title 'compression', \
       csv using (strcol(2) eq 'beams' ? $1 : 1/0):6 with linespoints title 'beams only'
  unset multiplot
  unset logscale
}
