#!/usr/bin/env bash
# The library's layers (lib/CMakeLists.txt) as the build enforces them: each layer compiles against a view of
# the layers it may see, so an include of a layer above it (or beside it in the top row) is not found.
# For every layer: a header of its own compiles in its view, a header of every layer it may not see fails there
# with "No such file", and no file of the layer includes a layer its view lacks.
# Usage: check_layers.sh SOURCE_DIR LAYER_VIEWS_DIR CXX [-I... of the dependencies, or one ';'-separated list]
set -euo pipefail
src=$1 views=$2 cxx=$3
shift 3
deps=()
for arg in "$@"; do
  IFS=';' read -ra parts <<< "$arg"
  deps+=("${parts[@]}")
done
layers=(core geometry mesh io dynamics continuum comm run dem rubber analysis render)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
for layer in "${layers[@]}"; do
  view=$views/$layer
  [[ -d $view ]] || { echo "no view for layer $layer in $views" >&2; exit 1; }
  for other in "${layers[@]}"; do
    header=$(cd "$src/lib/$other" && ls *.hpp | head -1)
    printf '#include "%s/%s"\nint main() { return 0; }\n' "$other" "$header" > "$work/probe.cpp"
    if [[ $other == "$layer" ]]; then
      if ! "$cxx" -std=c++20 -fsyntax-only -I"$view" "${deps[@]}" "$work/probe.cpp" 2> "$work/err"; then
        echo "layer $layer: its view does not compile its own $other/$header:" >&2
        head -5 "$work/err" >&2
        failures=$((failures + 1))
      fi
    elif [[ ! -e $view/$other ]]; then
      if "$cxx" -std=c++20 -fsyntax-only -I"$view" "${deps[@]}" "$work/probe.cpp" 2> "$work/err" ||
         ! grep -q "$other/$header: No such file" "$work/err"; then
        echo "layer $layer: an include of $other/$header, a layer it may not see, was not refused as missing" >&2
        failures=$((failures + 1))
      fi
    fi
  done
  # Every include of the layer's own files names a layer of its view.
  while IFS=: read -r file inc; do
    if [[ ! -e $view/$inc ]]; then
      echo "layer $layer: $file includes $inc, a layer it may not see" >&2
      failures=$((failures + 1))
    fi
  done < <(grep -H -o -E '^#include "[a-z_]+/' "$src/lib/$layer"/*.[ch]pp | sed -E 's/:#include "([a-z_]+)\/$/:\1/')
done
if (( failures > 0 )); then
  echo "$failures layer violations" >&2
  exit 1
fi
echo "layers: ${#layers[@]} layers, each compiling against its own view, every include of a layer above refused"
