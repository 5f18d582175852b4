# What accuracy costs (issue 7 §1): error against wall time, log-log, one panel per knob and error measure.
# Top row the polygon DEM, bottom row the rubber lattice; the CSV files of pipelines/accuracy-cost.mk.
# gnuplot -e "dir='results/accuracy-cost'; out='results/accuracy-cost/error-vs-time'" accuracy.gp
set datafile separator ','
set datafile columnheaders
set logscale xy
set format y '10^{%L}'
set grid
set key top right font ',9' samplen 2
dem = dir.'/dem-timestep.csv'
rub = dir.'/rubber-timestep.csv'
series(s, x) = (strcol(1) eq s ? x : 1/0)
set style line 1 lc rgb '#9400d3' pt 7 lw 1.5   # gear5, zero start
set style line 2 lc rgb '#009e73' pt 5 lw 1.5   # gear5, exact start
set style line 3 lc rgb '#0072b2' pt 9 lw 1.5   # verlet
set style line 4 lc rgb '#e69f00' pt 13 lw 1.5  # other
pos(x) = (x > 0 ? x : 1/0)
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 2000,900 font ',10' } else { set terminal svg size 2000,900 font 'sans,10' }
  set output out.'.'.fmt
  set multiplot layout 2,4 title 'What accuracy costs: error against wall time (each point one run; along a line dt halves, or the resolution grows)'
  # --- DEM
  set xlabel 'wall time of the time loop (s)'
  set title 'DEM time step: pulse, beams only, 1100 cells'
  set ylabel 'rms displacement error at t = 0.2 ms (m)'
  plot dem using (series('gear5-zero', $9)):(pos($13)) with linespoints ls 1 title 'gear5, zero start', \
       dem using (series('gear5-exact', $9)):(pos($13)) with linespoints ls 2 title 'gear5, exact start', \
       dem using (series('verlet-zero', $9)):(pos($13)) with linespoints ls 3 title 'verlet'
  set title 'DEM time step: energy drift'
  set ylabel 'max |E(t) - E(0)| / E(0)'
  plot dem using (series('gear5-zero', $9)):(pos($12)) with linespoints ls 1 title 'gear5, zero start', \
       dem using (series('gear5-exact', $9)):(pos($12)) with linespoints ls 2 title 'gear5, exact start', \
       dem using (series('verlet-zero', $9)):(pos($12)) with linespoints ls 3 title 'verlet'
  set title 'DEM resolution: beam lattice K; pulse front speed'
  set ylabel 'relative error against the finest mesh'
  set xlabel 'wall time per run (s)'
  plot dir.'/dem-resolution.csv' using 5:(pos($11)) with linespoints ls 1 title 'K (uniaxial, 160-16000 cells)', \
       dir.'/dem-wavespeed.csv' using 3:(pos(abs($8))):9 with yerrorbars ls 2 title 'c_L (pulse, 300-4400 cells) ± 1σ'
  set title 'DEM fragmentation: β of the explosion'
  set ylabel 'β difference or scatter'
  fr = dir.'/fragmentation.csv'
  plot fr using 4:(pos(abs($8))):9 with yerrorbars ls 1 title '|Δβ| vs finest dt (paired by seed) ± sd', \
       fr using 4:(pos(abs($10))):11 with yerrorbars ls 2 title '|Δβ| vs most cells ± σ', \
       fr using 4:(pos($6)) with points ls 3 title 'seed-to-seed sd of β'
  # --- rubber
  set xlabel 'wall time of the time loop (s)'
  set title 'Rubber time step: wave, 1000 nodes'
  set ylabel 'rms displacement error at t = 0.6 ms (m)'
  plot rub using (series('gear5-zero', $9)):(pos($13)) with linespoints ls 1 title 'gear5 (zero start)', \
       rub using (series('verlet-zero', $9)):(pos($13)) with linespoints ls 3 title 'verlet'
  set title 'Rubber time step: energy drift'
  set ylabel 'max |E(t) - E(0)| / pulse energy'
  plot rub using (series('gear5-zero', $9)):(pos($12)) with linespoints ls 1 title 'gear5 (zero start)', \
       rub using (series('verlet-zero', $9)):(pos($12)) with linespoints ls 3 title 'verlet'
  set title 'Rubber time step: wave speed'
  set ylabel '|c_L - c_{MR}| / c_{MR}'
  plot rub using (series('gear5-zero', $9)):(pos(abs($15))) with linespoints ls 1 title 'gear5 (zero start)', \
       rub using (series('verlet-zero', $9)):(pos(abs($15))) with linespoints ls 3 title 'verlet'
  set title 'Rubber resolution: 160-16000 nodes'
  set ylabel '|c_L - c_{MR}| / c_{MR}'
  set xlabel 'wall time per run (s)'
  plot dir.'/rubber-resolution.csv' using 6:(pos(abs($14))):($12/$13) with yerrorbars ls 1 title 'wave speed ± 1σ', \
       '' using 6:(pos(abs($14))) with lines ls 1 notitle
  unset multiplot
}
