#!/usr/bin/env bash
# End-to-end check of the experiment pipelines: runs a miniature of one experiment (MINI=1: small meshes,
# short runs, one seed) through its real Make target with the tools already built, then checks that each
# table exists, has the expected columns and only finite values, and that each picture is a PNG.
# Usage: pipelines.sh SOURCE_DIR BUILD_DIR WORK_DIR EXPERIMENT
set -euo pipefail
src=$1 build=$2 work=$3 experiment=$4
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

# columns FILE "a,b,c": the header (after any '#' lines: a tool's provenance) is exactly that; at least
# one row; no field is nan or inf.
columns() {
  local file=$work/$experiment/$1
  [[ -s $file ]] || fail "$1: missing or empty"
  local header; header=$(awk '!/^#/ { print; exit }' "$file")
  [[ $header == "$2" ]] || fail "$1: header '$header', expected '$2'"
  [[ $(grep -cv '^#' "$file") -ge 2 ]] || fail "$1: no rows"
  awk -F, -v f="$1" '/^#/ { next } ++n > 1 { for (i = 1; i <= NF; i++) if (tolower($i) ~ /^[+-]?(nan|inf)/) { print f ": line " NR " field " i " is " $i; bad = 1 } }
    END { exit bad }' "$file" || fail "$1: non-finite values"
}
# markdown FILE: exists, has a table, no nan/inf anywhere.
markdown() {
  local file=$work/$experiment/$1
  [[ -s $file ]] || fail "$1: missing or empty"
  grep -q '^|---' "$file" || fail "$1: no Markdown table"
  ! grep -qiwE 'nan|-?inf' "$file" || fail "$1: non-finite values: $(grep -iwE 'nan|-?inf' "$file" | head -3)"
}
png() {
  local file=$work/$experiment/$1
  [[ -s $file ]] || fail "$1: missing"
  [[ $(head -c 8 "$file" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]] || fail "$1: not a PNG"
}

make -C "$src" -f Makefile.analysis MINI=1 NO_BUILD=1 BUILD="$build" RESULTS="$work" JOBS=2 "$experiment" > "$work/make.log" 2>&1 ||
  { tail -n 30 "$work/make.log"; fail "make $experiment"; }

# Both estimators of β (scripts/fit-row.awk) and the largest fragment against the energy (scripts/largest-share.sh).
fit_columns=fragments,beta_mle,beta_mle_stderr,beta_bootstrap_std,xmin_cells,n_tail,gof_p,beta_mle_seed_mean,beta_mle_seed_stderr,beta_logbin,beta_logbin_jackknife,logbin_chi2_per_dof,beta_logbin_seed_mean,beta_logbin_seed_stderr,logbin_min_cells,logbin_max_cells
largest_columns=energy_J,energy_per_mass_J_per_kg,seeds,largest_share,largest_share_stderr
case $experiment in
  demo)
    markdown summary.md
    columns histogram.csv "center,density,count,lower,upper"
    head -n 1 "$work/demo/histogram.csv" | grep -q '^# tool=powerlaw-fit ' || fail "histogram.csv: no provenance line first"
    for p in explosion-1e-4 explosion-1e-3 explosion-4e-3 fragments histogram; do png $p.png; done
    [[ -s $work/demo/explosion.xmf ]] || fail "explosion.xmf: no XDMF sidecar"
    ;;
  elastic-moduli)
    columns moduli.csv "beam_modulus_Pa,mode,seed,K_Pa,K_stderr_Pa,nu,nu_stderr"
    columns curves.csv "axial_strain,stress_Pa"
    columns ours.csv "quantity,value,error"
    markdown table.md
    png moduli.png; png curves.png
    ;;
  compression)
    columns peaks.csv "seed,failure_strain,peak_stress_Pa,post_peak_stress_drop,broken_fraction"
    columns curve-s1.csv "strain,stress_Pa,intact_beams"
    columns ours.csv "quantity,value,error"
    markdown table.md
    png stress-strain.png
    for t in 0.025 0.028 0.03; do png broken-maps/broken-$t.png; done
    ;;
  explosion)
    columns betas.csv "t_eps_percent,t_theta_deg,seeds,$fit_columns"
    columns largest.csv "$largest_columns"
    columns ours.csv "quantity,value,error"
    markdown table.md
    png histograms.png; png largest.png
    for t in 1e-4 1e-3 4e-3; do png snapshots/explosion-$t.png; done
    png snapshots/fragments.png
    for t in 1e-4 3e-4 5e-4; do png pulse/pulse-$t.png; done
    ;;
  impact)
    columns betas.csv "size,block_m,cells,seeds,impact_energy_J,energy_per_mass_J_per_kg,$fit_columns"
    columns largest.csv "$largest_columns"
    columns ours.csv "quantity,value,error"
    markdown table.md
    png histogram.png; png largest.png
    for t in 4e-4 1.5e-3 3e-3; do png snapshots/impact-$t.png; done
    ;;
  rubber-crack)
    columns table.csv "$(head -n 1 "$work/rubber-crack/table.csv")"
    markdown table.md
    png snapshot.png
    # Energy-neutral failure with a crack path: the steady crack of the miniature runs faster than c_L
    # behind a wedge whose front leans back from the crack line.
    columns freeze.csv "$(bash "$src/scripts/rubber-crack-row.sh" --header)"
    markdown freeze.md
    awk -F, '$1 == "b1.5-y3-c3-p1.3" { found = 1; ok = $18 > 1 && $20 < 80 && $28 == "steady wedge" }
      END { exit !(found && ok) }' "$work/rubber-crack/freeze.csv" ||
      fail "freeze.csv: the steady crack is not a supersonic wedge: $(grep '^b1.5-y3-c3-p1.3,' "$work/rubber-crack/freeze.csv")"
    png crack.png
    png crack-toughened.png
    ;;
  accuracy-cost)
    columns dem-timestep.csv "series,integrator,start,level,dt_s,omega_dt,steps,wall_s,loop_s,peak_MB,cell_steps_per_s,energy_drift,rms_displacement_error_m,max_displacement_error_m,wave_speed_deviation"
    columns dem-orders.csv "series,observed_order_displacement,levels_displacement,observed_order_energy,levels_energy"
    columns dem-resolution.csv "grid,cells,steps,dt_s,wall_s,loop_s,peak_MB,cell_steps_per_s,K_Pa,K_stderr_Pa,K_error_vs_finest"
    columns fragmentation.csv "$(head -n 1 "$work/accuracy-cost/fragmentation.csv")"
    columns rubber-timestep.csv "series,integrator,start,level,dt_s,omega_dt,steps,wall_s,loop_s,peak_MB,cell_steps_per_s,energy_drift,rms_displacement_error_m,max_displacement_error_m,wave_speed_deviation"
    columns rubber-resolution.csv "grid,nodes,spacing_m,steps,dt_s,wall_s,loop_s,peak_MB,node_steps_per_s,energy_drift,c_L_m_per_s,c_L_stderr_m_per_s,c_L_mooney_rivlin_m_per_s,deviation"
    markdown table.md
    png error-vs-time.png
    ;;
  *) fail "unknown experiment $experiment" ;;
esac
echo "ok: $experiment"
