#!/usr/bin/env bash
# The largest fragment's share of the mass, m_max / M, over the runs of one imparted energy E (fragment-count's
# files: /fragments/mass is sorted largest first, the attribute total_mass is M): one CSV row
#   energy_J,energy_per_mass_J_per_kg,seeds,largest_share,largest_share_stderr
# (the mean of m_max / M over the files ± its standard error; E/M with the mean M).
#   bash scripts/largest-share.sh --header
#   bash scripts/largest-share.sh 457 frag-s1.h5 frag-s2.h5 ...
set -euo pipefail
if [[ $1 == --header ]]; then echo "energy_J,energy_per_mass_J_per_kg,seeds,largest_share,largest_share_stderr"; exit; fi
energy=$1; shift
# first: the first number h5dump prints after "DATA {" (17 significant digits).
first() { awk '/DATA \{/ { getline; sub(/^ *(\([0-9]+\): *)?/, ""); sub(/[ ,].*$/, ""); print; exit }'; }
for f in "$@"; do
  echo "$(h5dump -m %.17g -w 0 -d /fragments/mass -s 0 -c 1 "$f" | first) $(h5dump -m %.17g -w 0 -a /fragments/total_mass "$f" | first)"
done | awk -v e="$energy" '$2 > 0 { n++; r = $1 / $2; s += r; ss += r * r; mass += $2 }
  END { if (!n) exit 1; a = s / n; v = n > 1 ? (ss - n * a * a) / (n - 1) / n : 0
        printf "%s,%.4g,%d,%.4g,%.2g\n", e, e / (mass / n), n, a, sqrt(v > 0 ? v : 0) }'
