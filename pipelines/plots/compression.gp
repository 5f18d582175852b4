# σ(ε) of the confined compression test, one curve per seed (Kun et al. 1999 Fig. 9).
# gnuplot -e "files='a.csv b.csv'; out='stress-strain'" compression.gp
set datafile separator ','
set key left top
set xlabel 'compressive strain ε'
set ylabel 'compressive stress σ (Pa)'
set grid
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 700,500 } else { set terminal svg size 700,500 }
  set output out.'.'.fmt
  plot for [f in files] f using 1:2 every ::1 with lines title f
}
