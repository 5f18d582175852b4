# Long-wave speeds along x of Marder's lattice versus the stretch across the crack: measured (points with
# error bars) and Mooney-Rivlin (lines). gnuplot -e "csv='waves.csv'; out='waves'" rubber-waves.gp
set datafile separator ','
set key left top
set xlabel 'stretch across the crack λ_y'
set ylabel 'wave speed along x (m/s)'
set logscale y
set grid
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 700,500 } else { set terminal svg size 700,500 }
  set output out.'.'.fmt
  plot csv using 2:3:4 every ::1 with yerrorbars pt 7 lc rgb '#1f77b4' title 'c_L measured', \
       csv using 2:5 every ::1 with lines lc rgb '#1f77b4' title 'c_L Mooney-Rivlin', \
       csv using 2:7:8 every ::1 with yerrorbars pt 5 lc rgb '#d62728' title 'c_T measured', \
       csv using 2:9 every ::1 with lines lc rgb '#d62728' title 'c_T Mooney-Rivlin'
}
