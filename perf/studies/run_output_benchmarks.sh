#!/usr/bin/env bash
# The output's cost and size and the cost of periodic checkpoints; records perf/studies/results/
# output_write_bench.txt, output_overhead.md and checkpoint_cost.md (their notes: output_notes.md).
#   perf/studies/run_output_benchmarks.sh [BASELINE_RACEWAY]   (a build of the previous writer, optional)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out="$root/perf/studies/results"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
header="# $(date -u +%FT%TZ) $(uname -srm), $(nproc) cores,$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2), load average $(cut -d" " -f1-3 /proc/loadavg)"
# 1. The writer alone: every series of a 6309 R3 and a seed 002 output written again per setting.
sed 's/^end_time = .*/end_time = "0.05 s"/' "$root/jobs/scenes/seed002_40hz.toml" >"$tmp/seed002.toml"
"$root/build/raceway" run "$tmp/seed002.toml" -o "$tmp/seed002.h5" >/dev/null 2>&1
sed 's/^end_time = .*/end_time = "0.02 s"/' "$root/jobs/scenes/6309_R3.toml" >"$tmp/6309_R3.toml"
"$root/build/raceway" run "$tmp/6309_R3.toml" -o "$tmp/6309_R3.h5" >/dev/null 2>&1
{
  echo "$header"
  for f in "$tmp/6309_R3.h5" "$tmp/seed002.h5"; do
    for every in 1000 100000; do "$root/build/perf/bench/output_write_bench" "$f" "$every" 3; done
  done
} | tee "$out/output_write_bench.txt"
# 2. and 3. The output's share of whole runs, and checkpoints' restarts: the job scenes with the
# reference end times (default 0.1 s, seed 002 0.05 s, 6309 R3 0.02 s, QJ215 0.03 s).
mkdir -p "$tmp/scenes"
cp "$root/jobs/scenes/default.toml" "$tmp/6309_R3.toml" "$tmp/scenes/"
sed 's/^end_time = .*/end_time = "0.05 s"/' "$root/jobs/scenes/seed002_40hz.toml" >"$tmp/scenes/seed002_40hz.toml"
sed 's/^end_time = .*/end_time = "0.03 s"/' "$root/jobs/scenes/qj215_validation.toml" >"$tmp/scenes/qj215_validation.toml"
/usr/bin/python3 "$root/perf/studies/output_benchmarks.py" "$root/build/raceway" "$tmp/scenes" "$tmp/results" "$@"
for f in output_overhead.md checkpoint_cost.md; do
  { echo "$header"; echo; cat "$tmp/results/$f"; } | tee "$out/$f"
done
