#!/usr/bin/env bash
# The Markdown report of pipelines/accuracy-cost.mk: recommendations per use with their measured price,
# then every table. Usage: accuracy-cost-table.sh RESULTS_DIR "SEEDS" JOBS > table.md
set -euo pipefail
dir=$1 seeds=$2 jobs=$3

# row FILE SERIES LEVEL: the timestep CSV row of one run (fields as in the header).
row() { awk -F, -v s="$2" -v l="$3" '$1 == s && $4 == l' "$1"; }
# field FILE SERIES LEVEL COLUMN
field() { row "$1" "$2" "$3" | cut -d, -f"$4"; }
g() { awk -v x="$1" -v f="${2:-%.2g}" 'BEGIN { printf f, x }'; }

dem=$dir/dem-timestep.csv rub=$dir/rubber-timestep.csv
u=$(cat "$dir/dem/displacement.txt")  # rms displacement of the DEM pulse at T, m

cat <<EOF
# What accuracy costs in time

Measured by \`make -f Makefile.analysis accuracy-cost\` on $(nproc) cores with JOBS=$jobs runs at a time,
on a machine shared with other jobs: wall times scatter by tens of percent from run to run, so compare
them as ratios. *wall* is the whole process (GNU time: start-up, mesh input, output included), *loop*
the time loop alone; *peak* the maximum resident set. Errors are against the finest setting of the same
knob (or the continuum), so they measure discretisation only. Methods and discussion:
docs/accuracy-cost.md.

## Recommendations

EOF

# DEM picks (smooth problem): quick = verlet 2^-1, publication = gear5 exact 2^-1, reference = gear5 exact 2^-3.
dem_pick() {  # label series level settings
  local r; r=$(row "$dem" "$2" "$3")
  [[ -n $r ]] || return 0
  awk -F, -v label="$1" -v set="$4" -v u="$u" '{ printf "| %s | %s | %.2g m (%.1e of the displacement) | %.2g | %d steps, %.2g s wall (%.2g s loop) |\n", \
    label, set, $13, $13 / u, $12, $7, $8, $9 }' <<< "$r"
}
echo "**Polygon DEM**, smooth problem (pulse scene with contacts off, 1100 cells, E0 = 500 J, to 0.2 ms; rms"
echo "displacement of the pulse $(g "$u") m):"
echo
echo "| use | settings | rms displacement error | energy drift | price |"
echo "|---|---|---|---|---|"
dem_pick "quick look" verlet-zero 1 "\`integrator.kind = verlet\`, \`safety = 0.5\` (dt = 0.5 × Verlet's bound, itself 6.5 × gear5's)"
dem_pick "publication" gear5-exact 1 "\`kind = gear5\`, \`start = exact\`, \`safety = 0.5\` (the scenes' default step)"
dem_pick "reference" gear5-exact 3 "\`kind = gear5\`, \`start = exact\`, \`safety = 0.125\`"
z1=$(field "$dem" gear5-zero 1 13) e1=$(field "$dem" gear5-exact 1 13)
evals=$(h5dump -a /start_evaluations "$dir/dem/dt/gear5-exact-1.h5" | awk '/\(0\)/ { print $2 }')
cat <<EOF

gear5 with the usual zero start at the same step costs the same and is $(g "$(awk -v a="$z1" -v b="$e1" 'BEGIN { print a / b }')" '%.0f') times less accurate
($(g "$z1") m): turn \`integrator.start = exact\` on (it costs $evals force evaluations once, as many as
$evals steps). With contacts and breaking the motion is no longer smooth (contact onsets, beam removal) and every
scheme falls back to low order; there the step is set by stability (\`safety = 0.5\`), and the fragment
statistics are limited by seeds, not by the step (fragmentation table below).

EOF

# Rubber picks: quick = verlet 2^-1 (the scenes' default), publication = gear5 2^-1, reference = gear5 2^-2.
rub_pick() {
  local r; r=$(row "$rub" "$2" "$3")
  [[ -n $r ]] || return 0
  awk -F, -v label="$1" -v set="$4" '{ printf "| %s | %s | %.2g m | %.2g | %.2g | %d steps, %.2g s wall (%.2g s loop) |\n", \
    label, set, $13, $12, ($15 < 0 ? -$15 : $15), $7, $8, $9 }' <<< "$r"
}
res=$dir/rubber-resolution.csv
echo "**Rubber lattice**, wave scene (cut-off off, 1000 nodes, Δ = 1.6 mm, pulse width 4 mm = 2.5Δ, amplitude 0.1 mm, to 0.6 ms):"
echo
echo "| use | settings | rms displacement error | energy drift (of the pulse energy) | wave speed vs Mooney-Rivlin | price |"
echo "|---|---|---|---|---|---|"
rub_pick "quick look" verlet-zero 1 "\`kind = verlet\`, \`safety = 0.5\` (the scenes' default)"
rub_pick "publication" gear5-zero 1 "\`kind = gear5\`, \`safety = 0.5\`"
rub_pick "reference" gear5-zero 2 "\`kind = gear5\`, \`safety = 0.25\`"
cat <<EOF

The wave speed is off by the lattice's dispersion, not by the step: it needs the resolution. Against
Mooney-Rivlin, by lattice spacing (pulse width 4 mm, default step):

$(awk -F, 'NR > 1 { printf "- Δ = %.2g mm (%.2g nodes per pulse width, %d nodes): %.2g, %.2g s wall\n", $3 * 1e3, 4e-3 / $3, $2, ($14 < 0 ? -$14 : $14), $6 }' "$res")

For a publication take at least 5 nodes per pulse width (error ~0.1 %), for a reference 10.
With the Fermi cut-off on (crack runs) the bound is set by a bond passing through the cut-off and is
about ten times smaller: every row costs ten times more steps and is correspondingly more accurate on
the smooth part of the motion.

EOF

fr=$dir/fragmentation.csv
echo "**Fragmentation** (explosion scene, E0 = 500 J, 0.4 m disc, seeds $seeds; β = maximum-likelihood exponent of F(m)):"
awk -F, 'NR > 1 { n = $3; if ($3 > 1) { if (lo == "" || $6 < lo) lo = $6; if ($6 > hi) hi = $6 } \
    if ($8 != 0 || $9 != 0) { se = $9 / sqrt(n); z = (se > 0 ? ($8 < 0 ? -$8 : $8) / se : 0); if (z > zd) zd = z; \
      dts = dts sprintf("%s%+.2f ± %.2f at dt = %s s (%d cells)", (dts == "" ? "" : ", "), $8, se, $2, $1); if ($9 > psd) psd = $9 } \
    if ($10 != 0 || $11 != 0) { z = ($11 > 0 ? ($10 < 0 ? -$10 : $10) / $11 : 0); if (z > zc) zc = z; \
      cs = cs sprintf("%s%+.2f ± %.2f at %d cells", (cs == "" ? "" : ", "), $10, $11, $1) } \
    if ($1 + 0 > big) big = $1 + 0 } \
  END { printf "the seed-to-seed standard deviation of β is %.2g to %.2g. Against the finest time step (same meshes, paired by\n", lo, hi; \
    printf "seed; ± standard error) Δβ = %s; the paired differences scatter by up to %.2g", dts, psd; \
    if (psd >= 0.7 * hi) printf ", as much as\ndifferent seeds: a changed dt re-rolls the chaotic break-up like a new seed"; \
    else printf ", less than different seeds"; \
    printf ". Against %d cells at the same\n", big; \
    printf "dt, Δβ = %s. ", cs; \
    if (zd < 2 && zc < 2) printf "No discretisation effect is resolved at 2σ with these seeds: spend the time on seeds\n(the scatter of the mean falls as 1/√seeds) before a finer dt or mesh; the paper'"'"'s dt = 1e-6 s is enough.\n"; \
    else printf "An effect of %s beyond 2σ: report β with the resolution it was measured at.\n", (zc >= 2 && zd >= 2 ? "dt and resolution" : zc >= 2 ? "the resolution" : "the time step") }' "$fr"
echo
echo "## Polygon DEM: time step and integrator (smooth problem)"
echo
echo "Pulse scene with contacts off (beams only; no breaking, damping or friction), 1100-cell disc of 0.4 m,"
echo "E0 = 500 J, to T = 0.2 ms; level k: dt = T/(2^k·ceil(T/bound)) of each integrator's own bound. Errors"
echo "against gear5 with the exact start at 2^-9 of its bound. *order*: log2 of the error ratio to the next level."
echo
echo "| integrator | start | dt / bound | dt (s) | ω_max·dt | steps | wall (s) | loop (s) | peak (MB) | cell-steps/s | energy drift | rms displacement error (m) | max error (m) | order |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
awk -F, 'NR > 1 { r[NR] = $0; s[NR] = $1; e[NR] = $13 } END { for (i = 2; i <= NR; i++) { split(r[i], f, ","); \
    o = (i < NR && s[i + 1] == s[i] && e[i + 1] > 0) ? sprintf("%.2f", log(e[i] / e[i + 1]) / log(2)) : ""; \
    printf "| %s | %s | 2^-%s | %.3g | %.3g | %s | %s | %.3g | %s | %.3g | %.2g | %.2g | %.2g | %s |\n", f[2], f[3], f[4], f[5], f[6], f[7], f[8], f[9], f[10], f[11], f[12], f[13], f[14], o } }' "$dem"
echo
echo "Observed orders (least-squares slope of log error against log dt over the levels at least 30 times above"
echo "the rounding floor, the smallest error in the table):"
echo
awk -F, 'NR > 1 { printf "- %s: displacement %s (%d levels), energy drift %s (%d levels)\n", $1, $2, $3, $4, $5 }' "$dir/dem-orders.csv"
echo
echo "## Polygon DEM: resolution"
echo
echo "Uniaxial tension of the beam lattice (contacts off), 0.25 m × 0.40 m, to 10 ms; K = slope of σ(ε) after 3 ms."
echo
echo "| cells | steps | dt (s) | wall (s) | loop (s) | peak (MB) | cell-steps/s | K (Pa) | ± | error vs finest |"
echo "|---|---|---|---|---|---|---|---|---|---|"
awk -F, 'NR > 1 { printf "| %s | %s | %.3g | %s | %.3g | %s | %.3g | %.4g | %.2g | %.2g |\n", $2, $3, $4, $5, $6, $7, $8, $9, $10, $11 }' "$dir/dem-resolution.csv"
echo
echo "Radial front of the pulse (beams only, E0 = 5 J), longitudinal speed by wave-speed against the finest disc:"
echo
echo "| cells | steps | wall (s) | peak (MB) | c_L (m/s) | ± | arrivals | deviation vs finest | ± |"
echo "|---|---|---|---|---|---|---|---|---|"
awk -F, 'NR > 1 { printf "| %s | %s | %s | %s | %.4g | %.2g | %s | %.2g | %.2g |\n", $1, $2, $3, $4, $5, $6, $7, $8, $9 }' "$dir/dem-wavespeed.csv"
echo
echo "## Polygon DEM: fragmentation over seeds"
echo
echo "Explosion scene (contacts and breaking on), 0.4 m disc, E0 = 500 J; per run a maximum-likelihood β of the"
echo "fragment masses (fragments of at least 2 cells) and the largest fragment's share of the mass. Per setting:"
echo "mean and seed-to-seed standard deviation over seeds $seeds; Δ against the finest dt at the same cell count"
echo "(paired by seed: same meshes; mean ± sd of the differences) and against the most cells at the same dt"
echo "(different meshes: difference of the means ± its standard error)."
echo
echo "| cells | dt (s) | seeds | wall per run (s) | β | seed sd | fit σ | Δβ vs finest dt | Δβ vs most cells | largest share | seed sd | Δ vs finest dt | Δ vs most cells |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
awk -F, 'NR > 1 { printf "| %s | %s | %s | %s | %.3g | %.2g | %.2g | %.2g ± %.2g | %.2g ± %.2g | %.3g | %.2g | %.2g ± %.2g | %.2g ± %.2g |\n", \
  $1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14, $15, $16, $17 }' "$fr"
echo
echo "## Rubber lattice: time step and integrator"
echo
echo "Wave scene with the cut-off off, 100×10 nodes (Δ = 1.6 mm; periodic in y), (λx, λy) = (1.2, 3), Gaussian pulse of"
echo "width 4 mm and amplitude 0.1 mm, to T = 0.6 ms; levels as for the DEM; errors against gear5 at 2^-8 of its"
echo "bound; energy drift over the pulse energy (2 × kinetic energy at T); wave speed of the front between 16 and 66 mm."
echo "rubber-run has no exact start: gear5 starts from zero (the sheet starts at rest, so its r3 = 0 is exact)."
echo
echo "| integrator | dt / bound | dt (s) | ω_max·dt | steps | wall (s) | loop (s) | peak (MB) | node-steps/s | energy drift | rms displacement error (m) | max error (m) | wave speed vs MR | order |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
awk -F, 'NR > 1 { r[NR] = $0; s[NR] = $1; e[NR] = $13 } END { for (i = 2; i <= NR; i++) { split(r[i], f, ","); \
    o = (i < NR && s[i + 1] == s[i] && e[i + 1] > 0) ? sprintf("%.2f", log(e[i] / e[i + 1]) / log(2)) : ""; \
    printf "| %s | 2^-%s | %.3g | %.3g | %s | %s | %.3g | %s | %.3g | %.2g | %.2g | %.2g | %.2g | %s |\n", f[2], f[4], f[5], f[6], f[7], f[8], f[9], f[10], f[11], f[12], f[13], f[14], f[15], o } }' "$rub"
echo
echo "Observed orders (as for the DEM; n/a: the errors are at the rounding floor of the comparison, ~3e-14 m):"
echo
awk -F, 'NR > 1 { printf "- %s: displacement %s (%d levels), energy drift %s (%d levels)\n", $1, $2, $3, $4, $5 }' "$dir/rubber-orders.csv"
echo
echo "## Rubber lattice: resolution"
echo
echo "The same strip (0.16 m) and pulse at lattice spacings from 4 mm (one pulse width) to 0.4 mm, each at the"
echo "default step (0.5 of the Verlet bound); wave speed against Mooney-Rivlin at (1.2, 3)."
echo
echo "| nodes | Δ (mm) | steps | dt (s) | wall (s) | loop (s) | peak (MB) | node-steps/s | energy drift | c_L (m/s) | ± | Mooney-Rivlin | deviation |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
awk -F, 'NR > 1 { printf "| %s | %.3g | %s | %.3g | %s | %.3g | %s | %.3g | %.2g | %.5g | %.2g | %.5g | %.2g |\n", $2, $3 * 1e3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14 }' "$res"
echo
echo "Plot: error-vs-time.png (and .svg) beside this file."
