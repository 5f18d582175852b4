# Both estimators of the fragment mass exponent β, F(m) ~ m^-β, from one powerlaw-fit text output (key value
# lines; several seeds pooled), as the tail of a CSV row: the maximum-likelihood fit (pooled: β, asymptotic
# error, bootstrap σ, x_min in cells, n_tail, goodness-of-fit p; per seed: mean ± standard error) and the
# paper's estimator, the slope of the log-binned F(m) over the stated range (pooled: β, its jackknife error
# over seeds, its χ²/dof; per seed: mean ± standard error; the range in cells). Undefined values are left empty.
#   awk -v header=1 -f scripts/fit-row.awk < /dev/null      the header
#   awk -f scripts/fit-row.awk fit.txt                      the row
BEGIN {
  if (header) {
    print "fragments,beta_mle,beta_mle_stderr,beta_bootstrap_std,xmin_cells,n_tail,gof_p,beta_mle_seed_mean,beta_mle_seed_stderr," \
          "beta_logbin,beta_logbin_jackknife,logbin_chi2_per_dof,beta_logbin_seed_mean,beta_logbin_seed_stderr,logbin_min_cells,logbin_max_cells"
    exit
  }
}
!/^#/ { v[$1] = $2 }
function num(x, f) { return (x == "" || tolower(x) ~ /nan|inf/) ? "" : sprintf(f, x) }
END {
  if (header) exit
  u = v["logbin_cell_mass"] > 0 ? v["logbin_cell_mass"] : 1
  printf "%d,%s,%s,%s,%s,%d,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", v["n_values"], num(v["alpha"], "%.4f"), num(v["alpha_stderr"], "%.3f"),
    num(v["alpha_bootstrap_std"], "%.3f"), num(v["xmin"] / u, "%.3g"), v["n_tail"], num(v["gof_p"], "%.3g"),
    num(v["alpha_input_mean"], "%.4f"), num(v["alpha_input_stderr"], "%.3f"), num(v["logbin_alpha"], "%.4f"),
    num(v["logbin_alpha_jackknife_stderr"], "%.3f"), num(v["logbin_chi2_per_dof"], "%.3g"),
    num(v["logbin_alpha_input_mean"], "%.4f"), num(v["logbin_alpha_input_stderr"], "%.3f"),
    num(v["logbin_range_min"] / u, "%.3g"), num(v["logbin_range_max"] / u, "%.3g")
}
