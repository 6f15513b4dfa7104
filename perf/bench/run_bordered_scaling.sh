#!/usr/bin/env bash
# Newton linear algebra against the number of rolling elements (README "Newton linear solvers"):
# Jacobian evaluation, assembly + factorisation + one solve, and one solve, for petsc-bordered,
# block-elimination and sundials-dense, N = 8 .. 512 balls of a synthetic ball bearing plus the real
# bearings; fitted exponents and a plot. Records perf/bench/results/bordered_scaling.{csv,txt,png}.
# Usage: scripts/bootstrap.sh && cmake --build build && perf/bench/run_bordered_scaling.sh [budget_s] [max_dense_N]
# The CPU is shared: `uptime` before and after is recorded with the results; times are minima over
# repetitions (the least disturbed), medians beside them in the CSV.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out="$root/perf/bench/results"
mkdir -p "$out"
budget="${1:-0.5}"
max_dense="${2:-512}"
{
  echo "# $(date -u +%FT%TZ) $(uname -srm), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
  echo "# uptime before: $(uptime)"
} >"$out/bordered_scaling.txt"
"$root/build/perf/bench/bench_bordered" "$budget" "$max_dense" >"$out/bordered_scaling.csv"
echo "# uptime after: $(uptime)" >>"$out/bordered_scaling.txt"
/usr/bin/python3 "$root/perf/bench/plot_bordered_scaling.py" "$out/bordered_scaling.csv" "$out/bordered_scaling.png" \
  | tee -a "$out/bordered_scaling.txt"
