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
  libdeflate-dev
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
  python3-sklearn    # io.atlas.*, and `raceway atlas` itself: the search's Gaussian-process classifier (it
                     # brings scipy, 247 MB, which the runtime list avoids: an atlas user installs it)
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
sudo_cmd=()
[[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
if ((${#missing[@]})); then
  echo "bootstrap: installing ${#missing[@]} Debian packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${packages[@]}"
else
  echo "bootstrap: all Debian packages present"
fi

# SUNDIALS built with optimisation. Debian's libsundials is compiled without any -O (its rules pass
# CMAKE_C_FLAGS=-fcommon, which replaces dpkg's CFLAGS), so CVODE's own work costs about 2.8 times
# the instructions of an -O2 build of the same source, whose results are bitwise the same
# (perf/studies/results/sundials_o2.md). -O3 vectorises the serial vectors' element loops (two
# doubles per SSE2 instruction; the sums of the norms stay in order, no FMA at the baseline ISA):
# CVODE's own work another 26 % fewer instructions, the results bitwise the same again
# (perf/studies/results/revolution_instructions.md, "SUNDIALS at -O3"). Built once from Debian's own source package of the
# installed version, only the modules raceway links (CVODE, ARKODE and the serial vectors, dense
# matrices and solvers they carry), into RACEWAY_DEPS (default /opt/raceway-deps), outside the
# clone: sundials-VERSION-O3, with the link `sundials` to it that CMake looks in first
# (CMakeLists.txt). Skipped when already there; when the source cannot be fetched raceway builds
# against Debian's library as before (slower, the same results).
deps_root="${RACEWAY_DEPS:-/opt/raceway-deps}"
build_optimised_sundials() {
  local version prefix work
  version=$(dpkg-query -W -f='${Version}' libsundials-dev)
  prefix="$deps_root/sundials-$version-O3"
  if [[ -f "$prefix/.complete" ]]; then
    echo "bootstrap: SUNDIALS $version -O3 present in $prefix"
  else
    echo "bootstrap: building SUNDIALS $version with -O3 into $prefix (once)"
    if ! apt-cache showsrc "sundials=$version" 2>/dev/null | grep -q '^Package: sundials'; then
      # Debian's source packages: a deb-src entry of bookworm beside the binary ones, and its index.
      local list=/etc/apt/sources.list.d/raceway-deb-src.sources
      printf '%s\n' "# raceway's scripts/bootstrap.sh: Debian's source packages (SUNDIALS is built from them)" \
        "Types: deb-src" "URIs: http://deb.debian.org/debian" "Suites: bookworm bookworm-updates" \
        "Components: main" "Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg" |
        "${sudo_cmd[@]}" tee "$list" >/dev/null
      "${sudo_cmd[@]}" apt-get update -q -o Dir::Etc::sourcelist="$list" -o Dir::Etc::sourceparts=- \
        -o APT::Get::List-Cleanup=0 || return 1
    fi
    work=$(mktemp -d)
    # shellcheck disable=SC2064
    trap "rm -rf '$work'; trap - RETURN" RETURN
    (cd "$work" && apt-get source -q "sundials=$version" >/dev/null 2>"$work/source.log") ||
      { cat "$work/source.log" >&2; return 1; }
    local src
    src=$(find "$work" -mindepth 1 -maxdepth 1 -type d -name 'sundials-*' | head -1)
    # Debian's configuration (MPI on, 64-bit indices, double precision, -fcommon) with -O3, the
    # other solvers, the examples and the static libraries left out.
    cmake -S "$src" -B "$work/build" -DCMAKE_BUILD_TYPE=None -DCMAKE_C_FLAGS="-O3 -fcommon" \
      -DCMAKE_INSTALL_PREFIX="$prefix" -DBUILD_SHARED_LIBS=ON -DBUILD_STATIC_LIBS=OFF -DENABLE_MPI=ON \
      -DSUNDIALS_INDEX_SIZE=64 -DBUILD_CVODE=ON -DBUILD_ARKODE=ON -DBUILD_CVODES=OFF -DBUILD_IDA=OFF \
      -DBUILD_IDAS=OFF -DBUILD_KINSOL=OFF -DEXAMPLES_ENABLE_C=OFF -DEXAMPLES_ENABLE_CXX=OFF \
      -DEXAMPLES_INSTALL=OFF >"$work/configure.log" 2>&1 || { tail -20 "$work/configure.log" >&2; return 1; }
    cmake --build "$work/build" -j"$jobs" >"$work/build.log" 2>&1 || { tail -20 "$work/build.log" >&2; return 1; }
    "${sudo_cmd[@]}" rm -rf "$prefix"
    "${sudo_cmd[@]}" cmake --install "$work/build" >/dev/null || return 1
    "${sudo_cmd[@]}" touch "$prefix/.complete"
  fi
  "${sudo_cmd[@]}" ln -sfn "$(basename "$prefix")" "$deps_root/sundials"
  sundials_dir="$prefix/lib/cmake/sundials"
}
jobs="$(nproc 2>/dev/null || echo 2)"
sundials_dir=""
build_optimised_sundials ||
  echo "bootstrap: could not build the optimised SUNDIALS (above); building against Debian's libsundials" >&2
sundials_args=()
# An existing build keeps the SUNDIALS it found unless told: point it at the optimised one.
[[ -n "$sundials_dir" ]] && sundials_args=(-DSUNDIALS_DIR="$sundials_dir")

# --tests switches the tests and benchmarks on; without it a new build leaves them out and an
# existing one keeps its choice (a plain run after --tests does not drop the tests).
targets=()
if ((tests)); then
  targets=(-DRACEWAY_BUILD_TESTS=ON -DRACEWAY_BUILD_BENCHMARKS=ON)
elif [[ ! -f "$root/build/CMakeCache.txt" ]]; then
  targets=(-DRACEWAY_BUILD_TESTS=OFF -DRACEWAY_BUILD_BENCHMARKS=OFF)
fi
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DRACEWAY_WERROR=ON "${targets[@]}" "${sundials_args[@]}"
cmake --build "$root/build" -j"$jobs"
