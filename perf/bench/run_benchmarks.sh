#!/usr/bin/env bash
# Reruns the planar benchmarks and records their output in perf/bench/results/.
#   1. micro-benchmarks (segment, right-hand side, Jacobian, bordered vs dense factor + solve);
#   2. wall time of 20 shaft revolutions of the seed 002 bearing at 40 Hz (one rank), with the run
#      summary (steps, right-hand sides, time per right-hand side).
# Usage: scripts/bootstrap.sh && perf/bench/run_benchmarks.sh
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out="$root/perf/bench/results"
mkdir -p "$out"
{
  echo "# $(date -u +%FT%TZ) $(uname -srm), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
  "$root/build/perf/bench/bench_planar" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
} 2>&1 | tee "$out/bench_planar.txt"
tmp="$(mktemp -d)"
{
  TIMEFORMAT="wall %R s (bash time)"
  time "$root/build/raceway" run "$root/jobs/scenes/seed002_40hz.toml" \
    -o "$tmp/seed002_40hz.h5" --summary-json "$out/seed002_40hz_20rev_summary.json"
} 2>&1 | tail -5 | tee "$out/seed002_40hz_20rev.txt"
rm -rf "$tmp"
# Spatial right-hand side split into contact kinds (ball bearings: 6309 and QJ215).
"$root/build/perf/bench/rhs_split_spatial" "$root/jobs/scenes/6309_R3.toml" 20000 | tee "$out/rhs_split_6309_R3.txt"
"$root/build/perf/bench/rhs_split_spatial" "$root/jobs/scenes/qj215_validation.toml" 10000 | tee "$out/rhs_split_qj215_validation.txt"
