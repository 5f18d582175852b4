#!/usr/bin/env bash
# One CSV row for a crack run of rubber-run (pipelines/rubber-crack.mk, the runs with energy-neutral failure).
#   bash scripts/rubber-crack-row.sh --header          the header
#   bash scripts/rubber-crack-row.sh BIN RUN.h5 NAME   the row of RUN.h5 (BIN: the tools' directory)
# The speed is the least-squares slope of λx × reference tip x after the tip's first 50Δ of advance (the
# seed's start-up), and again over each successive window of 0.1 ms: the windows' spread around the slope
# says whether the crack runs steadily. The shape comes from the frame nearest the moment the tip passes 60 %
# of the strip's length, or the final frame if it never does (observables --crack-shape):
# the angle of the front behind which the sheet lets go, against the Mach angles of the Mooney-Rivlin
# sheet at the tip's speed, v sin α = c(n) (anisotropic) and asin(c_L,x / v); how far that front trails
# the tip; and the grips (the bonds to the clamped rows behind the tip that broke, and the debris: free nodes
# flung further past the outer rows than a half strip folded over its grip could reach). The outcome: stalled (under 50Δ of advance), full-height front (a front at
# 80° or more to the crack line: the sheet fails across its height, not along the line), front ahead of the
# tip (the sheet lets go more than 10Δ ahead of the broken line: a blunt opening, the line trailing it), a
# wedge too short for a speed (under 20Δ after the first 50Δ), steady wedge (the windows within ±10 %) or
# unsteady wedge.
set -euo pipefail
if [[ ${1:-} == --header ]]; then
  echo "run,b,stretch_y,rows,u0_over_spacing,uc_over_spacing,path_ratio,toughening,damping,advance_spacings,advance_after_50_spacings,speed_m_s,window_min_percent,window_max_percent,lattice_c_T_m_s,lattice_c_L_m_s,v_over_c_T,v_over_c_L,energy_change_percent,front_angle_deg,mach_angle_L_deg,asin_cL_over_v_deg,mach_angle_T_deg,front_lag_spacings,broken_bulk_bonds,grip_bonds_broken_percent,nodes_past_grips_percent,outcome"
  exit 0
fi
bin=$1 run=$2 name=$3
p() { "$bin/observables" "$run" --parameter "$1"; }
d=$(p derived.spacing)
u0=$(printf '%s\n' "$(p derived.bond_length_0deg)" "$(p derived.bond_length_60deg)" "$(p derived.bond_length_120deg)" | sort -g | tail -1)
damping=$(p physics.damping)
[[ $damping == on ]] && damping=$(p damping.kind)
nx=$(h5dump -a /particles/nodes/nx "$run" | sed -n 's/.*(0): *//p')
at=$("$bin/observables" "$run" --columns crack_tip_reference_x -q | grep -v '^#' | tail -n +2 |
  awk -F, -v end="$(awk -v n="$nx" -v d="$d" 'BEGIN { print 0.6 * n * d }')" '!found && $2 >= end { print $1; found = 1 }')
shape=$("$bin/observables" "$run" --crack-shape ${at:+--time "$at"} -q | grep -v '^#' | tr '\n' ' ')
"$bin/observables" "$run" --columns crack_tip_reference_x,total_energy -q | grep -v '^#' | tail -n +2 |
  awk -F, -v name="$name" -v b="$(p material.b)" -v lx="$(p loading.stretch_x)" -v ly="$(p loading.stretch_y)" \
      -v rows="$(h5dump -a /particles/nodes/ny "$run" | sed -n 's/.*(0): *//p')" \
      -v d="$d" -v u0="$u0" -v uc="$(p law.cutoff_length)" -v ratio="$(p crack.path_cutoff_ratio)" \
      -v tough="$(p physics.toughening)" -v damping="$damping" -v ct="$(p derived.lattice.c_T_x)" \
      -v cl="$(p derived.lattice.c_L_x)" -v shape="$shape" '
  function slope(a, z,   i, k, mt, mx, stt, stx) {
    k = 0; mt = mx = 0
    for (i = a; i <= z; i++) { k++; mt += t[i]; mx += lx * x[i] }
    mt /= k; mx /= k; stt = stx = 0
    for (i = a; i <= z; i++) { stt += (t[i] - mt)^2; stx += (t[i] - mt) * (lx * x[i] - mx) }
    return stx / stt
  }
  function num(v, f) { return (v == "" || tolower(v) ~ /nan|inf/) ? "" : sprintf(f, v) }
  NR == 1 { x0 = $2; e0 = $3 }
  { t[NR] = $1; x[NR] = $2; e = $3; n = NR }
  END {
    k = split(shape, kv, " "); for (i = 1; i + 1 <= k; i += 2) s[kv[i]] = kv[i + 1]
    for (i = 1; i <= n; i++) if (x[i] - x0 >= 50 * d) { start = i; break }
    adv = (x[n] - x0) / d; adv50 = start ? (x[n] - x[start]) / d : 0
    v = lo = hi = ""
    if (adv50 >= 20) {
      v = slope(start, n); w0 = start
      for (i = start + 1; i <= n; i++) if (t[i] - t[w0] >= 1e-4 - 1e-9) {
        w = 100 * (slope(w0, i) / v - 1); if (lo == "" || w < lo) lo = w; if (hi == "" || w > hi) hi = w; w0 = i }
    }
    angle = s["front_angle"]
    if (adv < 50) outcome = "stalled"
    else if (angle == "" || tolower(angle) ~ /nan/ || angle + 0 >= 80) outcome = "full-height front"
    else if (s["front_lag"] / d < -10) outcome = "front ahead of the tip"
    else if (v == "") outcome = "wedge (too short for a speed)"
    else if (lo >= -10 && hi <= 10) outcome = "steady wedge"
    else outcome = "unsteady wedge"
    asin_l = (v != "" && v > cl) ? atan2(cl / v, sqrt(1 - (cl / v)^2)) * 180 / 3.14159265358979 : ""
    printf "%s,%s,%s,%s,%.4g,%.4g,%s,%s,%s,%.1f,%.1f,%s,%s,%s,%.4g,%.4g,%s,%s,%.3g,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", name, b, ly, rows,
      u0 / d, uc / d, ratio, tough, damping, adv, adv50, num(v, "%.4g"), num(lo, "%+.1f"), num(hi, "%+.1f"), ct, cl,
      num(v == "" ? "" : v / ct, "%.3g"), num(v == "" ? "" : v / cl, "%.3g"), 100 * (e - e0) / e0,
      num(angle, "%.1f"), num(s["mach_angle_L"], "%.1f"), num(asin_l, "%.1f"), num(s["mach_angle_T"], "%.1f"),
      num(s["front_lag"] / d, "%.1f"), s["broken_bulk"], num(s["grip_bonds"] > 0 ? 100 * s["grip_bonds_broken"] / s["grip_bonds"] : "", "%.0f"),
      num(100 * s["nodes_past_grips"] / s["free_nodes"], "%.0f"), outcome
  }'
