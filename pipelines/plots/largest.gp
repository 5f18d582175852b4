# The largest fragment's share of the mass against the imparted energy per mass, mean ± standard error over
# seeds, with the fitted power law over its range (scripts/loglog-fit.awk key value lines: exponent, prefactor,
# x_min, x_max).
#   gnuplot -e "csv='largest.csv'; fit='largest-fit.txt'; xlabel='E/M (J/kg)'; title='impact'; out='largest'" largest.gp
set datafile separator ','
set logscale xy
set xlabel xlabel
set ylabel 'm_{max} / M'
set title title
set key right top
b = system("awk '$1 == \"exponent\" { print $2 }' ".fit)
c = system("awk '$1 == \"prefactor\" { print $2 }' ".fit)
x0 = system("awk '$1 == \"x_min\" { print $2 }' ".fit)
x1 = system("awk '$1 == \"x_max\" { print $2 }' ".fit)
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 700,500 } else { set terminal svg size 700,500 }
  set output out.'.'.fmt
  if (b eq "") {  # fewer than 3 points in the fragmented regime: no fit
    plot csv using 2:4:5 every ::1 with yerrorbars pt 7 title 'm_{max}/M, mean ± SE over seeds'
  } else {
    plot csv using 2:4:5 every ::1 with yerrorbars pt 7 title 'm_{max}/M, mean ± SE over seeds', \
         [real(x0):real(x1)] real(c) * x**real(b) with lines dashtype 2 lc 'black' title sprintf('fit: (E/M)^{%.2f}', real(b))
  }
}
