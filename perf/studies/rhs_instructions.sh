#!/usr/bin/env bash
# Instructions per right-hand side of a spatial scene (callgrind, independent of the machine's load):
#
#   perf/studies/rhs_instructions.sh [BUILD_DIR...]     (default: build)
#
# For each build directory: `valgrind --tool=callgrind --toggle-collect='raceway::bearing::Equations::rhs(*'`
# around BUILD_DIR/perf/bench/rhs_split_spatial on SCENE (default jobs/scenes/6309_R3.toml) for
# EVALUATIONS right-hand sides (default 200) at the start-up state; prints the instructions per call
# and the share of the functions named in FUNCTIONS (default: the body kinematics and rotations,
# inclusive). Give the build before a change and the one after to compare them.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
scene=${SCENE:-$root/jobs/scenes/6309_R3.toml}
evaluations=${EVALUATIONS:-200}
functions=${FUNCTIONS:-'Model::kinematics|cardan_rotation|sincos'}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
[[ $# -gt 0 ]] || set -- "$root/build"
for build in "$@"; do
  out="$work/callgrind.out"
  valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect='raceway::bearing::Equations::rhs(*' \
    "$build/perf/bench/rhs_split_spatial" "$scene" "$evaluations" >/dev/null 2>&1
  total=$(callgrind_annotate "$out" 2>/dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}')
  echo "$build: $(basename "$scene") $((total / evaluations)) instructions per right-hand side ($evaluations calls)"
  callgrind_annotate --inclusive=yes "$out" 2>/dev/null | grep -E "$functions" | sed -E 's/ \[.*//; s/^/    /' | head -6
done
