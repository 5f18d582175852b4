#!/usr/bin/env bash
# The C++ sources follow .clang-format: clang-format 14 (Debian 12's; other versions lay out some lines
# differently) changes nothing in them. Usage: format.sh SOURCE_DIR. Exit 77 (skipped) without clang-format 14.
set -euo pipefail
cd "$1"
format=$(command -v clang-format-14 || true)
if [[ -z $format ]] && command -v clang-format >/dev/null && clang-format --version | grep -q 'version 14\.'; then
  format=$(command -v clang-format)
fi
[[ -n $format ]] || { echo "style.format: skipped: no clang-format 14 (apt-get install clang-format-14)"; exit 77; }
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files '*.cpp' '*.hpp')
else
  mapfile -t files < <(find lib tools tests bench -name '*.cpp' -o -name '*.hpp' | sort)
fi
bad=()
for f in "${files[@]}"; do
  "$format" --style=file --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done
if ((${#bad[@]} > 0)); then
  echo "style.format: ${#bad[@]} of ${#files[@]} files differ from .clang-format; to fix: $format -i ${bad[*]}" >&2
  exit 1
fi
echo "style.format: ${#files[@]} files follow .clang-format"
