# The exponent of a power law y = c x^b by least squares of ln y on ln x (with the column err given, each point
# weighted by 1/σ² of ln y, σ = y_err / y; otherwise equal weights), over the points with y < ymax and, with
# to_min=1, x no larger than where y is smallest (rows in increasing x: a power law that falls, then turns).
# Input: CSV lines (a header and '#' lines skipped). Output: key value lines exponent,
# exponent_stderr (from the scatter about the line: points - 2 degrees of freedom), prefactor, points, x_min,
# x_max (the range fitted).
#   awk -F, -v x=2 -v y=4 [-v err=5] -v ymax=0.5 -v to_min=1 -f scripts/loglog-fit.awk table.csv   (column numbers)
FNR == 1 || /^#/ { next }
$y + 0 > 0 && $x + 0 > 0 {
  m++; X[m] = $x + 0; Y[m] = $y + 0; W[m] = (err != "" && $err + 0 > 0) ? ($y / $err) ^ 2 : 1
  if (lowest == "" || Y[m] < Y[lowest]) lowest = m
}
END {
  last = to_min ? lowest : m
  for (i = 1; i <= last; i++) {
    if (ymax != "" && Y[i] >= ymax) continue
    n++; lx = log(X[i]); ly = log(Y[i]); w = W[i]
    sw += w; sx += w * lx; sy += w * ly; sxx += w * lx * lx; sxy += w * lx * ly
    xs[n] = lx; ys[n] = ly; ws[n] = w
    if (n == 1) from = X[i]
    to = X[i]
  }
  if (n < 3) { print "points " n; exit }
  d = sw * sxx - sx * sx; b = (sw * sxy - sx * sy) / d; a = (sy - b * sx) / sw
  for (i = 1; i <= n; i++) chi2 += ws[i] * (ys[i] - a - b * xs[i]) ^ 2
  printf "exponent %.4g\nexponent_stderr %.2g\nprefactor %.4g\npoints %d\nx_min %.4g\nx_max %.4g\n", \
    b, sqrt(chi2 / (n - 2) * sw / d), exp(a), n, from, to
}
