# Fragment mass histograms (log-binned density, bins between the cell-count clusters) with slope guides
# (Kun et al. 1999 Figs. 11, 12).
# One histogram, F(m) against m:
#   gnuplot -e "csv='histogram.csv'; out='histogram'; title='explosion'" histogram.gp
# Several (dir/<size>/histogram.csv, mean cell masses u in kg), against the fragment size in cells m/u, the
# density per cell u F(m); the first size's fitted log-binned line over [lo, hi] cells (ln F = a + s ln m),
# and the paper's slope -beta through it at lo:
#   gnuplot -e "dir='impact'; sizes='paper large'; units='0.005 0.005'; a=1.0; s=-2.0; lo=2; hi=25; beta=1.98;
#               title='impact'; out='histogram'" histogram.gp
set datafile separator ','
set logscale xy
set format y '10^{%L}'
set title title
set key right top
multi = exists("sizes")
if (multi) {
  set xlabel 'fragment size m / ⟨m_{cell}⟩ (cells)'
  set ylabel 'F(m) ⟨m_{cell}⟩'
  u1 = real(word(units, 1))
  fitted(x) = u1 * exp(a + s * log(x * u1))
  guide(x) = fitted(lo) * (x / lo)**(-beta)
} else {
  set xlabel 'fragment mass m (kg)'
  set ylabel 'F(m) (kg^{-1})'
}
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 700,500 } else { set terminal svg size 700,500 }
  set output out.'.'.fmt
  if (multi) {
    plot for [i = 1:words(sizes)] dir.'/'.word(sizes, i).'/histogram.csv' \
           using ($1 / real(word(units, i))):($2 * real(word(units, i))) every ::1 with linespoints pt 7 title word(sizes, i), \
         [lo:hi] fitted(x) with lines lw 2 lc 'black' title sprintf('%s, log-binned fit: slope %.2f', word(sizes, 1), s), \
         [lo:hi] guide(x) with lines dashtype 2 lc 'black' title sprintf('slope -%.2f (paper)', beta)
  } else {
    plot csv using 1:2 every ::1 with linespoints pt 7 title 'F(m)', [1e-3:1] 1e-4 * x**-2 with lines dashtype 2 lc 'black' title 'slope −2'
  }
}
