# σ(ε) in tension and compression (Kun et al. 1999 Fig. 4).
# gnuplot -e "csv='curves.csv'; out='curves'" curves.gp  -> curves.png, curves.svg
set datafile separator ','
set key left top
set xlabel 'axial strain ΔL/L'
set ylabel 'stress σ (Pa)'
set grid
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 700,500 } else { set terminal svg size 700,500 }
  set output out.'.'.fmt
  plot csv using 1:2 every ::1 with lines title 'E = 5e8 Pa, Y = 1e9 Pa'
}
