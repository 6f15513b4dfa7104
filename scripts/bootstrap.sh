#!/usr/bin/env bash
# Installs raceway's Debian packages (idempotent: apt runs only when something is missing), then
# configures and builds raceway in ./build (Release, warnings as errors).
# Usage: scripts/bootstrap.sh            (from the repository root or anywhere)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

packages=(build-essential cmake pkg-config openmpi-bin libopenmpi-dev libhwloc-dev
  libpetsc-real-dev libsundials-dev libeigen3-dev libhdf5-openmpi-dev hdf5-tools libmetis-dev
  libgtest-dev libbenchmark-dev libtomlplusplus-dev libcli11-dev libspdlog-dev libfmt-dev
  python3-matplotlib python3-h5py python3-numpy
  slurm-wlm munge  # the Slurm recipes' test (tests/campaign/real_slurm_test.sh): a one-node Slurm
  chromium python3-vtk9 ffmpeg)  # the report tests: page screenshot, VTK read-back, MP4 animation

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "bootstrap: installing ${#missing[@]} Debian packages: ${missing[*]}"
  sudo_cmd=()
  [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${packages[@]}"
else
  echo "bootstrap: all Debian packages present"
fi

jobs="$(nproc 2>/dev/null || echo 2)"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DRACEWAY_WERROR=ON
cmake --build "$root/build" -j"$jobs"
