#!/usr/bin/env bash
# Installs raceway's Debian packages (apt runs only when something is missing), then configures and
# builds raceway in ./build (Release, warnings as errors).
#
#   scripts/bootstrap.sh           what building and running raceway and the report's figures need;
#                                  builds the executable and its tools (no tests, no benchmarks)
#   scripts/bootstrap.sh --tests   also the packages of the test suite; builds the tests and benchmarks
#                                  (what CI runs before ctest: .ci/run)
#   scripts/bootstrap.sh --list [--tests]   prints the packages it would install, one a line, and exits
#
# Install footprint of each: docs/install.md. Run from the repository root or anywhere.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

# Running raceway: the compiler and the libraries it links, h5dump to look into an output, and
# the report's Python (numpy, h5py, matplotlib: summary, figures, page, the ParaView exports).
# python3-munkres: matplotlib's python3-fonttools needs python3-scipy or python3-munkres; apt takes
# the first, which brings 247 MB (scipy, pythran, Boost's headers) that raceway never uses.
runtime_packages=(
  build-essential cmake pkg-config
  openmpi-bin libopenmpi-dev libhwloc-dev libpetsc-real-dev libsundials-dev libeigen3-dev
  libhdf5-openmpi-dev libmetis-dev libtomlplusplus-dev libcli11-dev libspdlog-dev libfmt-dev
  hdf5-tools
  python3-numpy python3-h5py python3-matplotlib python3-munkres
)

# Testing adds these, one a line with what needs it (a test that needs one skips when it is absent,
# except the C++ test libraries, which the tests are built with). Add a test's package here.
test_packages=(
  libgtest-dev       # the C++ unit tests (GoogleTest)
  libbenchmark-dev   # perf/: the micro-benchmarks, built with the tests
  python3-paraview   # io.paraview_export.*: ParaView's own readers (carries VTK's Python; replaces python3-vtk9)
  chromium           # io.report_page_screenshot: the report page in headless chromium
  ffmpeg             # io.report_run.6309_R3: the animation as MP4 (GIF without it)
  slurm-wlm munge    # campaign.real_slurm_*: a one-node Slurm on localhost for the Slurm recipes
  python3-pandas     # run.output_layout_package: the reader's pandas view (the test also runs without it)
)

tests=0 list=0
for arg in "$@"; do
  case "$arg" in
    --tests) tests=1 ;;
    --list) list=1 ;;
    -h|--help) sed -n '2,11p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "bootstrap: unknown option '$arg' (--tests, --list, --help)" >&2; exit 2 ;;
  esac
done

packages=("${runtime_packages[@]}")
((tests)) && packages+=("${test_packages[@]}")
if ((list)); then
  printf '%s\n' "${packages[@]}"
  exit 0
fi

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

# --tests switches the tests and benchmarks on; without it a new build leaves them out and an
# existing one keeps its choice (a plain run after --tests does not drop the tests).
targets=()
if ((tests)); then
  targets=(-DRACEWAY_BUILD_TESTS=ON -DRACEWAY_BUILD_BENCHMARKS=ON)
elif [[ ! -f "$root/build/CMakeCache.txt" ]]; then
  targets=(-DRACEWAY_BUILD_TESTS=OFF -DRACEWAY_BUILD_BENCHMARKS=OFF)
fi
jobs="$(nproc 2>/dev/null || echo 2)"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DRACEWAY_WERROR=ON "${targets[@]}"
cmake --build "$root/build" -j"$jobs"
