#!/usr/bin/env bash
# Installs the Debian 12 packages the toolkit needs to build and test, if any is missing.
# As root it runs apt-get; otherwise it prints the exact apt-get line and stops with exit 1.
set -euo pipefail

packages=(
  cmake g++ make pkg-config git
  libeigen3-dev libcgal-dev libboost-program-options-dev libgsl-dev
  libhdf5-dev zlib1g-dev hdf5-tools libgtest-dev libcairo2-dev gnuplot-nox time
  libopenmpi-dev openmpi-bin
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

line="apt-get install -y --no-install-recommends ${missing[*]}"
if [[ $(id -u) -ne 0 ]]; then
  echo "install-deps: missing Debian packages: ${missing[*]}" >&2
  echo "install-deps: run as root:  apt-get update && $line" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done" >&2
