#!/usr/bin/env bash
# A checking build with AddressSanitizer and UndefinedBehaviorSanitizer, and the test suite on it.
#
#   scripts/sanitize.sh [CTEST ARGS...]     e.g. scripts/sanitize.sh -LE long   (without the long runs)
#
# Configures build-asan (RelWithDebInfo, -DRACEWAY_SANITIZE=address,undefined, benchmarks off),
# builds it and runs ctest in it; the ctest summary goes to stdout and to build-asan/sanitize.log.
# Any sanitizer report fails the test that produced it (-fno-sanitize-recover=all; halt_on_error).
#
# Leak detection is off (detect_leaks=0): Open MPI and its transport libraries keep allocations
# until exit that LeakSanitizer reports as leaks in every MPI test, including the serial ones
# (the executable calls MPI_Init), and in the test discovery that runs each test executable at
# build time. Memory errors and undefined behaviour are still detected.
# Not run by CI: the build and suite take several times as long as the Release ones.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${RACEWAY_JOBS:-2}"
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
# Before the build: gtest_discover_tests runs each test executable at build time to list its tests.
export ASAN_OPTIONS="detect_leaks=0:halt_on_error=1:detect_stack_use_after_return=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRACEWAY_SANITIZE=address,undefined \
  -DRACEWAY_BUILD_BENCHMARKS=OFF "${launcher[@]}"
cmake --build build-asan -j"$jobs"
# The per-test timeouts are those of the Release build; sanitized code runs 2-5 times slower, so the
# long whole-run tests may need more: pass e.g. --timeout 1800 (it sets tests without a timeout of
# their own) or leave them out with -LE long.
ctest --test-dir build-asan -j"$jobs" --output-on-failure "$@" 2>&1 | tee build-asan/sanitize.log
