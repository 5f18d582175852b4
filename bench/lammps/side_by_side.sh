#!/bin/bash
# Side-by-side timing of LAMMPS and the fracture toolkit's kernels, one round: the anchors' harness
# (shared/bench-anchors/side_by_side.sh: its method, its TSV lines), with the command lines of today's tools,
# the contact comparison (W4: LAMMPS body/rounded/polygon vs dem-run overlap contacts) and, in plan big,
# 10^6-particle rows. See README.md beside this file.
#
# usage: W=SCRATCH T=BUILD/tools S=data/scenes bash bench/lammps/side_by_side.sh ROUND [PLAN]
#   e.g. W=/work/sbs T=/work/build-l/tools S=/work/main/data/scenes bash bench/lammps/side_by_side.sh 1 big
#   then python3 bench/lammps/summarize.py $W/results.tsv   (the anchors' side_by_side_summarize.py + the W4 pair)
# PLAN = main     W1/W1h/W2/W2h/W3 vs dem beams, beams+breaking, full model; rubber 10^4..10^6 (as the
#                 anchors' main plan), plus W4 vs dem contacts at 10^4 and 10^5
#        big      main, then W1 vs dem beams+breaking and W1h vs dem beams at 10^6 (a few steps each)
#        contacts W4 vs dem contacts only;   1M  the 10^6 rows only;   w3big  W3 and rubber at 10^6 (anchors')
# THREADS="1" measures the one-thread rows only (default "1 2").
# Needs: $W/build-lmp/lmp (LAMMPS with BPM, GRANULAR, MOLECULE, OPENMP, BODY), GNU time, h5dump, python3;
# python3 with h5py for compress_mesh.py (apt-get install python3-h5py). Missing inputs are made first
# (prepare): $W/data/tri_*_a15.data, $W/data/poly-N.data, $W/tk/dem-N.h5, pack-N.h5, rub-SIDE.h5.
# A = the anchors' folder (default: shared/bench-anchors beside the repository), P = this folder.
# Columns: time code workload N threads steps ns_per_step aux load1 idle% note
#   LAMMPS: ns = loop time / (N*steps); aux = LAMMPS "% CPU use"
#   dem-run: ns = (wall(2S) - wall(S)) / (N*S) (the toolkit's bench/lib.sh step_ns method); aux = CPU-time ns;
#     the note adds loopns2S (the 2S run's own loop wall / (N 2S): the summary's default figure) and loopdiff
#     (the two runs' loop walls differenced / (N S): no start-up, no first force evaluation)
#   rubber-run: ns = its own "ns per node-step" (time loop only); aux = wall s of the whole process
# Tiny-run figures and the reasons for the step counts: README.md.
set -u
R=${1:-1}
PLAN=${2:-main}
W=${W:?set W to a scratch folder with lmp built in W/build-lmp and data in W/data}
P=$(cd "$(dirname "$0")" && pwd)
A=${A:-$(cd "$P/../../../shared/bench-anchors" 2>/dev/null && pwd)}
[ -n "$A" ] && [ -f "$A/in.w1_bpm.lmp" ] || { echo "set A to the anchors' folder (shared/bench-anchors)" >&2; exit 2; }
LMP=$W/build-lmp/lmp
T=${T:?set T to the toolkit build/tools folder}
S=${S:?set S to the toolkit data/scenes folder}
RES=$W/results.tsv
# 10^6 rows (plan big / 1M): LAMMPS steps of W1 and W1h, and S of dem-run (runs of S and 2S steps)
S1M_W1=${S1M_W1:-20}
S1M_W1H=${S1M_W1H:-200}
S1M_DEM=${S1M_DEM:-100}
THREADS_LIST=${THREADS:-"1 2"}  # the thread counts of each row
mkdir -p $W/logs $W/tk $W/data
cd $W || exit 2

# ---------------------------------------------------------------- inputs, made when missing
PYH5=""
for py in python3 /usr/bin/python3; do
  if $py -c 'import h5py' 2>/dev/null; then PYH5=$py; break; fi
done
need_tri() {  # NX: data/tri_NXxNX_a15.data
  [ -f data/tri_$1x$1_a15.data ] || { echo "prepare: data/tri_$1x$1_a15.data" >&2; python3 $A/make_tri_lattice.py $1 $1 15 > data/tri_$1x$1_a15.data; }
}
need_dem() {  # SIDE: tk/dem-SIDE^2.h5, as bench/dem_run.sh (S = SIDE * 0.01 m)
  local n=$(( $1 * $1 )) size
  size=$(awk -v s=$1 'BEGIN { print s * 0.01 }')
  [ -f tk/dem-$n.h5 ] || { echo "prepare: tk/dem-$n.h5" >&2; $T/mesh-gen voronoi --shape rect --size ${size}x${size} --cells $1x$1 --seed 1 -q -o tk/dem-$n.h5; }
}
need_rub() {  # SIDE: tk/rub-SIDE.h5, as bench/rubber_run.sh
  [ -f tk/rub-$1.h5 ] || { echo "prepare: tk/rub-$1.h5" >&2; $T/mesh-gen triangular --nodes $1x$1 --spacing 1e-3 -q -o tk/rub-$1.h5; }
}
need_pack() {  # SIDE: tk/pack-N.h5 (compressed, no beams) and data/poly-N.data (its LAMMPS bodies)
  local n=$(( $1 * $1 ))
  need_dem $1
  if [ ! -f tk/pack-$n.h5 ]; then
    [ -n "$PYH5" ] || { echo "prepare: compress_mesh.py needs python3 with h5py (apt-get install python3-h5py)" >&2; exit 2; }
    $PYH5 $P/compress_mesh.py tk/dem-$n.h5 tk/pack-$n.h5 >&2
  fi
  [ -f data/poly-$n.data ] || python3 $P/make_polygon_bodies.py tk/pack-$n.h5 data/poly-$n.data >&2
}
prepare() {
  case $PLAN in
    main|big) need_tri 100; need_tri 316; need_dem 100; need_dem 316; need_rub 100; need_rub 316; need_rub 1000
              need_pack 100; need_pack 316; [ $PLAN = big ] && need_dem 1000;;
    contacts) need_pack 100; need_pack 316;;
    1M)       need_dem 1000;;
    w3big)    need_tri 1000; need_rub 1000;;
    *) echo "unknown PLAN $PLAN (main, big, contacts, 1M, w3big)" >&2; exit 2;;
  esac
}

# ---------------------------------------------------------------- measuring
# idle% of both cores over 1 s; waits (up to QUIET_MAX s, default 4) for >= 90% idle
IDLE=0
quiet() {
  local t=0
  while :; do
    read -r _ a1 b1 c1 d1 e1 f1 g1 h1 _ < /proc/stat; sleep 1
    read -r _ a2 b2 c2 d2 e2 f2 g2 h2 _ < /proc/stat
    local tot=$(( (a2+b2+c2+d2+e2+f2+g2+h2) - (a1+b1+c1+d1+e1+f1+g1+h1) ))
    IDLE=$(( 100 * ((d2+e2) - (d1+e1)) / tot ))
    t=$((t+1))
    [ $IDLE -ge 90 ] && return 0
    [ $t -ge ${1:-4} ] && return 0
  done
}
load1() { cut -d' ' -f1 /proc/loadavg; }
rec() { printf '%s\t%s\n' "$(date -u +%H:%M:%S)" "$*" | tee -a $RES; }

# LAMMPS: lmp_run WORKLOAD SIZE THREADS STEPS   (SIZE 10k | 100k | 1M)
lmp_run() {
  local w=$1 s=$2 t=$3 steps=$4 input vars nx ny d n dir=$A
  case $s in 10k) nx=100; ny=50; d=data/tri_100x100; n=10000;; 100k) nx=316; ny=158; d=data/tri_316x316; n=99856;;
             1M) nx=1000; ny=500; d=data/tri_1000x1000; n=1000000;; esac
  case $w in
    w3_angle15) input=in.w3_angle.lmp; vars="-var data ${d}_a15.data";;
    w4_body_polygon) input=in.w4_body_polygon.lmp; vars="-var data data/poly-$n.data"; dir=$P;;
    *)          input=in.$w.lmp;      vars="-var nx $nx -var ny $ny";;
  esac
  local log=logs/lmp.$w.$s.t$t.r$R.log
  if [ $t = 1 ]; then quiet 4; else quiet ${QUIET2:-15}; fi; local l=$(load1)
  if [ $t = 1 ]; then OMP_NUM_THREADS=1 $LMP -in $dir/$input $vars -var steps $steps -log $log -screen none
  else OMP_NUM_THREADS=$t $LMP -sf omp -pk omp $t -in $dir/$input $vars -var steps $steps -log $log -screen none; fi
  local lt sec n cpu bonds
  lt=$(sed -n 's/^Loop time of \([0-9.e+-]*\) on .* with \([0-9]*\) atoms/\1 \2/p' $log)
  read -r sec n <<<"$lt"
  cpu=$(sed -n 's/^\([0-9.]*\)% CPU use.*/\1/p' $log)
  bonds=$(awk '/^ *Step/{f=1;next} f&&NF>=4&&$1+0==$1{last=$NF} /^Loop time/{f=0} END{print last}' $log)
  rec "lammps	$w	$n	$t	$steps	$(awk -v s=$sec -v n=$n -v k=$steps 'BEGIN{printf "%.1f", s*1e9/(n*k)}')	$cpu	$l	$IDLE	loop=${sec}s last_thermo_col=$bonds"
}

# dem-run: dem_run MODEL CELLS THREADS STEPS   (MODEL beams | beamsbrk | full on tk/dem-CELLS.h5, pulse scene;
# contacts on tk/pack-CELLS.h5, contacts.ini beside this script)
beams_only="--physics.contacts off --physics.breaking off --physics.friction off --physics.damping off"
beams_brk="--physics.contacts off --physics.breaking on --physics.friction off --physics.damping off"
full_model="--physics.contacts on --physics.breaking on --physics.friction on --physics.damping on --material.friction 0.3 --material.gamma_n 1000 --material.gamma_t 1000"
quiet_output="--output.frame_interval 1 --output.observe_every 1000000 --stop.t_max 1 --stop.steps_without_breaking 0"
t_once() {  # prints "WALL CPU"
  local t0 t1
  t0=$EPOCHREALTIME
  /usr/bin/time -f "%U %S" -o tk/time.txt "$@" >/dev/null 2>tk/stderr.txt || { echo "FAILED: $*" >&2; cat tk/stderr.txt >&2; }
  t1=$EPOCHREALTIME
  awk -v t0="$t0" -v t1="$t1" '{ printf "%.4f %.2f\n", t1 - t0, $1 + $2 }' tk/time.txt
}
dem_run() {
  local m=$1 n=$2 t=$3 steps=$4 extra scene=$S/pulse.ini mesh=tk/dem-$2.h5
  case $m in
    beams) extra="$beams_only --loading.energy 1";;
    beamsbrk) extra="$beams_brk --loading.energy 1";;
    full) extra="$full_model --loading.energy 1";;
    contacts) extra=""; scene=$P/contacts.ini; mesh=tk/pack-$n.h5;;  # contacts.ini: contacts, damping, friction, no beams
  esac
  # The 10^6-cell mesh's stability bound (8.1e-7 s for gear5) is below pulse.ini's dt = 1e-6 s: dt = auto there
  # (0.5 x the bound); the cost of a step does not depend on dt.
  [ $n = 1000000 ] && extra="$extra --integrator.dt auto"
  local cmd="$T/dem-run --threads $t --scene $scene $mesh -o tk/dem-out-$m-$n-$t.h5 $quiet_output $extra"
  if [ $t = 1 ]; then quiet 4; else quiet ${QUIET2:-15}; fi; local l=$(load1) w1 c1 w2 c2 sw1 sw2
  read -r w1 c1 <<<"$(t_once $cmd --stop.max_steps $steps)"
  sw1=$(sed -n 's/.* \([0-9.e+-]*\) s wall.*/\1/p' tk/stderr.txt | tail -1)
  read -r w2 c2 <<<"$(t_once $cmd --stop.max_steps $((2*steps)))"
  sw2=$(sed -n 's/.* \([0-9.e+-]*\) s wall.*/\1/p' tk/stderr.txt | tail -1)
  local summ=$(grep -o '[0-9]* of [0-9]* beams broken' tk/stderr.txt)
  local nc=$(h5dump -d /observables/contacts/value tk/dem-out-$m-$n-$t.h5 2>/dev/null | sed -n 's/^ *(0): \(.*\)/\1/p' | head -1 | tr -d ' ')
  rec "toolkit	dem-$m	$n	$t	$steps	$(awk -v a=$w1 -v b=$w2 -v n=$n -v s=$steps 'BEGIN{printf "%.1f", (b-a)*1e9/(n*s)}')	$(awk -v a=$c1 -v b=$c2 -v n=$n -v s=$steps 'BEGIN{printf "%.0f", (b-a)*1e9/(n*s)}')	$l	$IDLE	walls=${w1}/${w2}s steps${steps}-$((2*steps)) ${summ} contacts(0,end)=${nc} runwall=${sw1}/${sw2} loopns2S=$(awk -v b=$sw2 -v n=$n -v s=$steps 'BEGIN{printf "%.1f", b*1e9/(n*2*s)}') loopdiff=$(awk -v a=$sw1 -v b=$sw2 -v n=$n -v s=$steps 'BEGIN{printf "%.1f", (b-a)*1e9/(n*s)}')"
}

# rubber-run: rub_run NODES_SIDE THREADS STEPS ANGLE
rub_run() {
  local side=$1 t=$2 steps=$3 ang=$4 n=$(( $1 * $1 ))
  if [ $t = 1 ]; then quiet 4; else quiet ${QUIET2:-15}; fi; local l=$(load1) w c
  read -r w c <<<"$(t_once $T/rubber-run --scene $S/stretch.ini tk/rub-$side.h5 --stop.max_steps $steps \
      --output.frame_interval 0 --output.observe_every 100000000 --threads $t --law.angle $ang -o tk/rub-out.h5)"
  local ns=$(sed -n 's/.*(\([0-9.e+-]*\) ns per node-step.*/\1/p' tk/stderr.txt | tail -1)
  rec "toolkit	rubber-$ang	$n	$t	$steps	$ns	$w	$l	$IDLE	wall_total=${w}s cpu_total=${c}s"
}

# ---------------------------------------------------------------- plans
# W4 vs dem contacts: the released packing loosens as it runs (LAMMPS's bodies faster, see README.md), so
# the step counts stay short: LAMMPS 100 / 30 steps, dem-run S = 200 / 100 (runs of S and 2S).
contact_rows() {  # THREADS
  lmp_run w4_body_polygon 10k $1 100
  dem_run contacts 10000 $1 200
  lmp_run w4_body_polygon 100k $1 30
  dem_run contacts 99856 $1 100
}
big_rows() {  # THREADS
  lmp_run w1_bpm 1M $1 $S1M_W1
  dem_run beamsbrk 1000000 $1 $S1M_DEM
  lmp_run w1h_harmonic 1M $1 $S1M_W1H
  dem_run beams 1000000 $1 $S1M_DEM
}

prepare
if [ $PLAN = main ] || [ $PLAN = big ]; then
  for s in 10k 100k; do
    if [ $s = 10k ]; then n=10000; k=1; else n=99856; k=10; fi
    for t in $THREADS_LIST; do
      lmp_run w1_bpm $s $t $((1000 / k))
      dem_run beamsbrk $n $t $((2000 / k))
      lmp_run w1h_harmonic $s $t $((20000 / k))
      dem_run beams $n $t $((2000 / k))
      lmp_run w2_bpm_gran $s $t $((800 / k))
      dem_run full $n $t $((400 / k))
      lmp_run w2h_harmonic_gran $s $t $((5000 / k))
      lmp_run w3_angle15 $s $t $((1000 / k))
      if [ $s = 10k ]; then rub_run 100 $t 5000 marder; else rub_run 316 $t 1000 marder; rub_run 316 $t 500 marder-pairwise; fi
    done
  done
  for t in $THREADS_LIST; do rub_run 1000 $t 100 marder; done
  for t in $THREADS_LIST; do contact_rows $t; done
  if [ $PLAN = big ]; then for t in $THREADS_LIST; do big_rows $t; done; fi
elif [ $PLAN = contacts ]; then
  for t in $THREADS_LIST; do contact_rows $t; done
elif [ $PLAN = 1M ]; then
  for t in $THREADS_LIST; do big_rows $t; done
elif [ $PLAN = w3big ]; then
  for t in $THREADS_LIST; do lmp_run w3_angle15 1M $t 20; rub_run 1000 $t 100 marder; done
fi
