# Fragment mass histograms pooled over seeds (Kun et al. 1999 Fig. 11): left t_ε sweep at t_Θ = 4°,
# right t_Θ sweep at t_ε = 3 %. Each file dir/<teps>-<ttheta>.hist.csv: center,density,... (header line).
# gnuplot -e "dir='fits'; teps='1 2 3'; ttheta='1 2'; out='histograms'" histograms.gp
set datafile separator ','
set logscale xy
set xlabel 'fragment mass m (kg)'
set ylabel 'F(m) (kg^{-1})'
set key right top
set format y '10^{%L}'
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 1200,500 } else { set terminal svg size 1200,500 }
  set output out.'.'.fmt
  set multiplot layout 1,2
  set title 't_Θ = 4°'
  plot for [e in teps] dir.'/'.e.'-4.hist.csv' using 1:2 every ::1 with linespoints title 't_ε = '.e.' %', \
       [1e-3:1] 1e-4 * x**-2 with lines dashtype 2 lc 'black' title 'slope −2'
  set title 't_ε = 3 %'
  plot for [t in ttheta] dir.'/3-'.t.'.hist.csv' using 1:2 every ::1 with linespoints title 't_Θ = '.t.'°', \
       [1e-3:1] 1e-4 * x**-2 with lines dashtype 2 lc 'black' title 'slope −2'
  unset multiplot
}
