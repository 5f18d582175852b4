#!/usr/bin/env bash
# Nothing lost, whatever the user types or the machine does: every tool, tried as a careless or hostile user
# would. In every case: no input changed (checksums), no temporary left, no signal (exit below 128), no hang
# (a time limit), a refusal exits 2 and a run-time fault exits 1, each with a message naming its cause.
# Usage: nothing_lost.sh SOURCE_DIR BIN_DIR WORK_DIR CASE [SANITIZED]
#   clobber      an output that is an input (the same name, ./name, an absolute name, a symbolic or hard link,
#                standard input redirected from it), two outputs that are one file, --resume naming the output
#   devices      outputs that are no regular file: /dev/null, /dev/full, a link to /dev/stdout, a FIFO with and
#                without a reader, a socket, a folder; as root also a device node of our own, which must stay one
#   checkpoints  checkpoints on a full disk (periodic and at SIGTERM, both runners; a tmpfs in a private mount
#                namespace, skipped where none can be made) and past a file size limit: the run stops with exit
#                1 naming its last good checkpoint, which is intact and continues to the uninterrupted run's bits;
#                a checkpoint folder that does not exist is refused before the run starts
#   file-size    every writer past a file size limit (ulimit -f): exit 1 naming the limit, no SIGXFSZ
#   memory       every reader and runner under address-space limits (ulimit -v) from tight to ample: exit 0 or
#                exit 1 "out of memory" naming what, never "damaged" or a signal (not under the sanitizers)
#   endless      /dev/zero, /dev/urandom and endless text as every kind of input: refused at once
set -euo pipefail
src=$1 bin=$2 work=$3 case=$4 sanitized=${5:-0}
self=$(cd "$(dirname "$0")" && pwd)/$(basename "$0")
source "$(cd "$(dirname "$0")" && pwd)/lib.sh"  # fail
rm -rf "$work" && mkdir -p "$work" && cd "$work"
cp "$src"/data/scenes/*.ini .
cases=0

# Small inputs: a 60-cell disc, a short run of it, its fragments, a rubber strip and a short wave run.
inputs() {
  "$bin/mesh-gen" voronoi --shape disc --diameter 0.06 --cells 60 --seed 3 -q -o mesh.h5
  "$bin/dem-run" --scene explosion.ini mesh.h5 --stop.t_max 1e-4 --output.frame_interval 2e-6 -q -o run.h5
  "$bin/fragment-count" run.h5 -q -o fragments.h5
  "$bin/mesh-gen" triangular --nodes 12x6 --spacing 1e-3 -q -o strip.h5
  "$bin/mesh-gen" triangular --nodes 100x4 --spacing 1e-3 -q -o line.h5
  "$bin/rubber-run" --scene wave.ini line.h5 --stop.t_max 5e-4 --output.frame_interval 2e-5 -q -o wave.h5
  printf 'seed = 3\n' > mesh.cfg
  seal
}

# Records the checksums of every file present: the inputs no case may change.
seal() { find . -maxdepth 1 -type f -print0 | xargs -0 md5sum > ../sums-$case.md5; }

# expect RC NEEDLE COMMAND...: exits RC within 60 s, its message holds NEEDLE, no input changed, no temporary
# left. NEEDLE may be several alternatives separated by '|' (grep -E).
expect() {
  local rc=$1 needle=$2
  shift 2
  set +e
  timeout -s KILL 60 "$@" > stdout.out 2> stderr.txt
  local got=$?
  set -e
  [[ $got -ne 137 ]] || fail "hung (killed after 60 s): $*"
  [[ $got -lt 128 ]] || fail "ended by signal $((got - 128)): $* ($(cat stderr.txt))"
  [[ $got -eq $rc ]] || fail "exit $got, expected $rc: $* ($(cat stderr.txt))"
  [[ -z $needle ]] || grep -qE -- "$needle" stderr.txt || fail "the message does not say '$needle': $* ($(cat stderr.txt))"
  md5sum --quiet -c ../sums-$case.md5 || fail "an input changed: $*"
  [[ -z $(find . -name '.*.tmp-*' | head -1) ]] || fail "temporaries left: $(find . -name '.*.tmp-*'): $*"
  rm -f stdout.out stderr.txt
  cases=$((cases + 1))
}

# The writers: "tool args" whose output goes where {} stands.
writers() {
  cat <<EOF
mesh-gen voronoi --cells 8x4 --config mesh.cfg -q -o {}
mesh-gen triangular --nodes 8x4 --spacing 1e-3 -q -o {}
dem-run --scene explosion.ini mesh.h5 --stop.t_max 1e-5 -q -o {}
rubber-run --scene stretch.ini strip.h5 --crack.seed_length 0 --stop.t_max 1e-5 -q -o {}
fragment-count run.h5 -q -o {}
powerlaw-fit fragments.h5 --bootstrap 0 --gof-samples 0 -q -o {}
powerlaw-fit fragments.h5 --bootstrap 0 --gof-samples 0 --format text -q -o {}
wave-speed wave.h5 -q -o {}
wave-speed wave.h5 --format text -q -o {}
render run.h5 --format png -q -o {}
h5-xdmf run.h5 -q -o {}
EOF
}

# Runs `line` (a writer) with its output at `out`, after the command in the array `launch` (if any).
launch=()
run_writer() {
  local rc=$1 needle=$2 line=$3 out=$4
  read -ra cmd <<< "${line//\{\}/$out}"
  expect "$rc" "$needle" "${launch[@]}" "$bin/${cmd[0]}" "${cmd[@]:1}"
}

case $case in
  clobber)
    inputs
    ln -s mesh.h5 mesh-link.h5
    ln mesh.h5 mesh-hard.h5
    ln -s run.h5 run-link.h5
    seal
    # Each writer's first input (the file after its options), under every alias.
    while read -r line; do
      input=$(awk '{ for (k = 2; k <= NF; ++k) if ($k ~ /\.(h5|cfg)$/) { print $k; exit } }' <<< "$line")
      [[ -n $input ]] || continue
      for alias in "$input" "./$input" "$PWD/$input" "../$(basename "$PWD")/$input"; do
        run_writer 2 "is the input" "$line" "$alias"
      done
    done < <(writers)
    for alias in mesh-link.h5 mesh-hard.h5; do
      run_writer 2 "is the input MESH 'mesh.h5'" "dem-run --scene explosion.ini mesh.h5 -q -o {}" "$alias"
    done
    run_writer 2 "is the input" "render run-link.h5 -q -o {}" run.h5
    # The scene and the --config file are inputs too; standard input redirected from the output.
    run_writer 2 "is the input --scene" "dem-run --scene explosion.ini mesh.h5 -q -o {}" explosion.ini
    run_writer 2 "is the input --scene" "rubber-run --scene stretch.ini strip.h5 -q -o {}" stretch.ini
    run_writer 2 "is the input --config" "dem-run --scene explosion.ini mesh.h5 --config mesh.cfg -q -o {}" mesh.cfg
    expect 2 "is the input MESH - " "$bin/dem-run" --scene explosion.ini - -q -o mesh.h5 < mesh.h5
    expect 2 "is the input RUN - " "$bin/fragment-count" - -q -o run.h5 < run.h5
    # Two outputs that are one file, and --resume naming the output.
    for runner in "dem-run --scene explosion.ini mesh.h5" "rubber-run --scene stretch.ini strip.h5"; do
      read -ra cmd <<< "$runner"
      expect 2 "are one file" "$bin/${cmd[0]}" "${cmd[@]:1}" -q --checkpoint x.h5 -o x.h5
      expect 2 "are one file" "$bin/${cmd[0]}" "${cmd[@]:1}" -q --checkpoint ./x.h5 -o "$PWD/x.h5"
      expect 2 "is the input --resume" "$bin/${cmd[0]}" "${cmd[@]:1}" -q --resume run.h5 -o run.h5
    done
    expect 2 "are one file" "$bin/powerlaw-fit" fragments.h5 --format text -q -o a.txt --histogram-csv ./a.txt
    expect 2 "is the input" "$bin/powerlaw-fit" fragments.h5 --format text -q -o out.txt --histogram-csv fragments.h5
    expect 2 "is the input --fragments" "$bin/render" run.h5 --fragments fragments.h5 -q -o fragments.h5
    ;;
  devices)
    inputs
    mkfifo fifo
    python3 -c 'import socket, sys; socket.socket(socket.AF_UNIX).bind(sys.argv[1])' sock
    ln -s /dev/stdout to-stdout
    mkdir folder
    seal
    while read -r line; do
      run_writer 0 "" "$line" /dev/null
      [[ -c /dev/null ]] || fail "/dev/null is no longer a device: $line"
      run_writer 1 "No space left on device|disk is full" "$line" /dev/full
      run_writer 1 "a FIFO that no process reads" "$line" fifo
      run_writer 2 "is a socket" "$line" sock
      run_writer 2 "is a folder" "$line" folder
      # Through a link to /dev/stdout (a pipe here): the output arrives on standard output, the link stays.
      read -ra cmd <<< "${line//\{\}/to-stdout}"
      "$bin/${cmd[0]}" "${cmd[@]:1}" | cat > piped.out
      [[ -s piped.out && -L to-stdout ]] || fail "through a link to /dev/stdout: $line"
      # A FIFO with a reader gets the whole output.
      read -ra cmd <<< "${line//\{\}/fifo}"
      cat fifo > fifo.out &
      reader=$!
      "$bin/${cmd[0]}" "${cmd[@]:1}"
      wait $reader
      [[ -s fifo.out && -p fifo ]] || fail "through a FIFO: $line"
      rm -f piped.out fifo.out
    done < <(writers)
    h5ls -r fifo.out >/dev/null 2>&1 || true
    expect 2 "a checkpoint is a file" "$bin/dem-run" --scene explosion.ini mesh.h5 -q --checkpoint /dev/null -o out.h5
    expect 2 "a checkpoint is a file" "$bin/rubber-run" --scene stretch.ini strip.h5 --crack.seed_length 0 -q --checkpoint fifo -o out.h5
    rm -f out.h5
    if [[ $(id -u) -eq 0 ]]; then
      # A device node of our own (the null device): written through, still a device afterwards.
      mknod null-node c 1 3
      seal
      while read -r line; do
        run_writer 0 "" "$line" null-node
        [[ -c null-node ]] || fail "the device node was replaced: $line"
      done < <(writers)
    else
      echo "not root: the device-node cases are skipped"
    fi
    ;;
  checkpoints)
    # The full disk is a tmpfs in a private mount namespace: it disappears with the test, whatever happens.
    if [[ ${FAULTS_IN_NAMESPACE:-} != 1 ]]; then
      for enter in "unshare --mount --propagation private" "unshare --user --map-root-user --mount"; do
        if $enter true 2>/dev/null; then
          FAULTS_IN_NAMESPACE=1 exec $enter bash "$self" "$@"
        fi
      done
    fi
    inputs
    "$bin/mesh-gen" voronoi --shape disc --diameter 0.2 --cells 600 --seed 3 -q -o disc.h5
    "$bin/mesh-gen" triangular --nodes 60x30 --spacing 1e-3 -q -o sheet.h5
    seal
    dem=("$bin/dem-run" --scene explosion.ini disc.h5 --integrator.dt auto --output.frame_interval 5e-6 -q)
    rubber=("$bin/rubber-run" --scene stretch.ini sheet.h5 --crack.seed_length 0 --output.frame_interval 2e-6 -q)
    # A checkpoint folder that does not exist: refused before the run starts.
    expect 2 "folder 'nowhere' does not exist" "${dem[@]}" --stop.t_max 4e-4 --checkpoint nowhere/c.h5 -o out.h5
    expect 2 "folder 'nowhere' does not exist" "${rubber[@]}" --stop.t_max 4e-4 --checkpoint nowhere/c.h5 -o out.h5
    # Past a file size limit: the first checkpoint fails, the run stops with exit 1, nothing is left.
    expect 1 "file size limit.*the run stopped.*no checkpoint" \
      bash -c 'ulimit -f 150; exec "$@"' _ "${dem[@]}" --stop.t_max 4e-4 --checkpoint-every 50 --checkpoint c.h5 -o out.h5
    [[ ! -e c.h5 && ! -e out.h5 ]] || fail "a file left after the file size limit"
    mkdir disk
    if [[ ${FAULTS_IN_NAMESPACE:-} != 1 ]] || ! mount -t tmpfs -o size=3m tmpfs disk; then
      echo "note: no tmpfs can be mounted here (needs root or user namespaces): the full-disk cases are not run"
      echo "ok: $case, $cases cases"
      exit 0
    fi
    for runner in dem rubber; do
      declare -n cmd=$runner
      "${cmd[@]}" --stop.t_max 4e-4 -o full.h5
      # The disk fills as the run goes: a checkpoint or two succeed, then one fails.
      stopped=
      for fill in 2200 1800 1400 1000; do
        rm -rf disk/* disk/.[!.]*
        head -c ${fill}k /dev/zero > disk/fill
        set +e
        timeout -s KILL 120 "${cmd[@]}" --stop.t_max 4e-4 --checkpoint-every 50 --checkpoint disk/c.h5 -o disk/out.h5 2> stderr.txt
        rc=$?
        set -e
        [[ $rc -lt 128 ]] || fail "$runner on a full disk: ended by signal $((rc - 128)) ($(cat stderr.txt))"
        [[ $rc -eq 1 ]] || continue
        [[ -z $(find disk -name '.*.tmp-*') ]] || fail "$runner: temporaries left on the full disk: $(ls -A disk)"
        grep -qE "the disk is full" stderr.txt || fail "$runner: no word of the full disk: $(cat stderr.txt)"
        if [[ -e disk/c.h5 ]]; then
          step=$(h5dump -a /step disk/c.h5 | awk '/\(0\):/ { print $2 }')
          grep -qF "its last checkpoint, disk/c.h5 (step $step), is intact" stderr.txt ||
            fail "$runner: the message does not name the last checkpoint (step $step): $(cat stderr.txt)"
          # The last good checkpoint continues, on a disk with room, to the uninterrupted run's bits.
          "${cmd[@]}" --stop.t_max 4e-4 --resume disk/c.h5 -o resumed.h5
          h5diff --exclude-path /provenance full.h5 resumed.h5 || fail "$runner: the continued run differs"
          stopped=yes
          break
        fi
      done
      [[ -n $stopped ]] || fail "$runner: no fill level gave a good checkpoint then a failed one"
      # SIGTERM on a full disk: the checkpoint cannot be written; exit 1 with the reason, not the signal.
      rm -rf disk/* disk/.[!.]*
      head -c 2900k /dev/zero > disk/fill 2>/dev/null || true
      # A run that lasts (the explosion's stop rule off), signalled once its loop has written 1 MB of frames: the
      # checkpoint, a copy of that output, cannot fit in what is left of the disk.
      long=(--stop.t_max 1)
      [[ $runner == dem ]] && long+=(--stop.steps_without_breaking 0)
      "${cmd[@]}" "${long[@]}" --checkpoint-every 0 --checkpoint disk/c.h5 -o out.h5 2> stderr.txt &
      pid=$!
      for _ in $(seq 600); do
        size=$( (stat -c %s .out.h5.tmp-* 2>/dev/null || true) | head -1)
        ((${size:-0} > 1000000)) && break
        sleep 0.1
      done
      kill -TERM $pid
      set +e
      wait $pid
      rc=$?
      set -e
      [[ $rc -eq 1 ]] || fail "$runner: SIGTERM on a full disk: exit $rc, expected 1 ($(cat stderr.txt))"
      grep -qE "stopped by SIGTERM after step [0-9]+.*cannot write the checkpoint.*the disk is full" stderr.txt ||
        fail "$runner: SIGTERM on a full disk: $(cat stderr.txt)"
      [[ -z $(find . disk -name '.*.tmp-*') ]] || fail "$runner: temporaries left after SIGTERM"
      rm -f full.h5 resumed.h5 stderr.txt
      cases=$((cases + 6))
    done
    umount disk
    ;;
  file-size)
    inputs
    # 20 KiB: every output below is larger (the text outputs and the sidecar are a few kB: not here).
    while read -r line; do
      [[ $line == *"--format text"* || $line == h5-xdmf* ]] && continue
      line=${line/--cells 8x4/--cells 40x20}
      line=${line/--nodes 8x4/--nodes 60x20}
      line=${line/--stop.t_max 1e-5/--stop.t_max 1e-4}
      out=out.h5
      [[ $line == render* ]] && out=out.png
      launch=(bash -c 'ulimit -f 20; exec "$@"' _)
      run_writer 1 "file size limit is reached \(ulimit -f: 20480 bytes\)" "$line" "$out"
    done < <(writers)
    ;;
  memory)
    if [[ $sanitized == 1 ]]; then
      echo "SKIP: AddressSanitizer reserves more address space than any limit here leaves"
      exit 0
    fi
    "$bin/mesh-gen" voronoi --size 0.3x0.3 --cells 300x300 -q -o big.h5
    "$bin/mesh-gen" triangular --nodes 600x300 --spacing 1e-3 -q -o sheet.h5
    "$bin/dem-run" --scene uniaxial.ini big.h5 --stop.t_max 2e-6 --output.frame_interval 1e-6 -q -o run.h5
    "$bin/fragment-count" run.h5 -q -o fragments.h5
    awk 'BEGIN { srand(1); for (k = 0; k < 1000000; ++k) print 1 / (rand() + 1e-9) }' > masses.txt
    seal
    out_of_memory=0
    for limit in 50 60 70 90 120 160 300; do
      while read -r line; do
        read -ra cmd <<< "$line"
        set +e
        timeout -s KILL 120 bash -c "ulimit -v $((limit * 1024)); exec \"\$@\"" _ "$bin/${cmd[0]}" "${cmd[@]:1}" \
          > /dev/null 2> stderr.txt
        rc=$?
        set -e
        # (a limit below what the loader needs ends before our code runs: exit 127)
        grep -q "error while loading shared libraries" stderr.txt && continue
        [[ $rc -lt 128 ]] || fail "$limit MB: ended by signal $((rc - 128)): $line ($(cat stderr.txt))"
        [[ $rc -eq 0 || $rc -eq 1 ]] || fail "$limit MB: exit $rc, expected 0 or 1: $line ($(cat stderr.txt))"
        if [[ $rc -eq 1 ]]; then
          grep -q "out of memory: .* (the process may use .*: ulimit -v)" stderr.txt ||
            fail "$limit MB: exit 1 without 'out of memory': $line ($(cat stderr.txt))"
          out_of_memory=$((out_of_memory + 1))
        fi
        md5sum --quiet -c ../sums-$case.md5 || fail "an input changed: $line"
        [[ -z $(find . -name '.*.tmp-*' | head -1) ]] || fail "temporaries left: $line"
        rm -f out.h5 out.png
        cases=$((cases + 1))
      done <<EOF
mesh-gen check big.h5
mesh-gen voronoi --size 0.3x0.3 --cells 300x300 -q -o out.h5
dem-run --scene uniaxial.ini big.h5 --stop.t_max 2e-6 -q -o out.h5
dem-run --scene uniaxial.ini big.h5 --stop.t_max 2e-6 --threads 2 -q -o out.h5
rubber-run --scene stretch.ini sheet.h5 --stop.t_max 1e-6 -q -o out.h5
fragment-count run.h5 -q -o out.h5
render run.h5 -q -o out.png
powerlaw-fit masses.txt --bootstrap 0 --gof-samples 0 -q -o out.h5
EOF
    done
    [[ $out_of_memory -ge 12 ]] || fail "only $out_of_memory runs met the limits: make the inputs larger"
    echo "$out_of_memory runs ran out of memory, each with its message"
    ;;
  endless)
    inputs
    head -c 100000 /dev/urandom > random.bin
    seal
    for source in /dev/zero /dev/urandom random.bin; do
      expect 2 "not a text file|not a single number" "$bin/dem-run" --scene "$source" mesh.h5 -q -o out.h5
      expect 2 "not a text file|not a single number" "$bin/rubber-run" --scene "$source" strip.h5 -q -o out.h5
      expect 2 "not an HDF5 file" "$bin/dem-run" --scene explosion.ini "$source" -q -o out.h5
      expect 2 "not an HDF5 file" "$bin/dem-run" --scene explosion.ini - -q -o out.h5 < "$source"
      for reader in "fragment-count" "mesh-gen check" "render" "wave-speed" "observables"; do
        read -ra cmd <<< "$reader"
        expect 2 "not an HDF5 file" "$bin/${cmd[0]}" "${cmd[@]:1}" "$source"
        expect 2 "not an HDF5 file" "$bin/${cmd[0]}" "${cmd[@]:1}" - < "$source"
      done
      expect 2 "not a text file|not a single number|not a column of numbers" "$bin/powerlaw-fit" "$source" -q -o out.h5
      expect 2 "not a text file|not a single number|not a column of numbers" "$bin/powerlaw-fit" - -q -o out.h5 < "$source"
    done
    # Endless text: words, one endless line (numbers without end: the unit test of read_number_column).
    expect 2 "not a single number" bash -c 'yes | exec "$@"' _ "$bin/powerlaw-fit" - -q -o out.h5
    expect 2 "longer than" bash -c 'tr "\\0" 1 < /dev/zero | exec "$@"' _ "$bin/powerlaw-fit" - -q -o out.h5
    # A stream that is HDF5 but cut short, or HDF5 followed by more than its superblock says.
    head -c 20000 run.h5 > cut.h5
    expect 2 "truncated HDF5 file" bash -c 'cat cut.h5 | exec "$@"' _ "$bin/fragment-count" - -q -o out.h5
    expect 0 "" bash -c 'cat run.h5 /dev/zero | exec "$@"' _ "$bin/fragment-count" - -q -o out.h5
    rm -f out.h5
    ;;
  *) fail "unknown case $case" ;;
esac
echo "ok: $case, $cases cases"
