#!/usr/bin/env bash
# Where a step's time goes: runs a scene three times (default jobs/scenes/6309_R3.toml, 10
# revolutions) and prints the median of each part of the run summary's time_split_s, per run, share
# and per step. Usage: perf/studies/step_time_split.sh [SCENE] [BUILD_DIR] > perf/studies/results/step_time_split_6309_R3.txt
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
scene=${1:-$root/jobs/scenes/6309_R3.toml}
build=${2:-$root/build}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "# $(basename "$scene"), three runs, $(nproc) cores, load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for i in 1 2 3; do
  "$build/raceway" run "$scene" -o "$work/out.h5" --summary-json "$work/run_$i.json" >/dev/null 2>&1
done
/usr/bin/python3 - "$work" <<'PY'
import json, statistics, sys
runs = [json.load(open(f"{sys.argv[1]}/run_{i}.json")) for i in (1, 2, 3)]
r0 = runs[0]
steps = r0["steps"]
print(f"# {r0['method']}: {steps} steps, {r0['rhs_evaluations']} right-hand sides, {r0['jacobian_evaluations']} Jacobians, "
      f"{r0['linear_setups']} linear setups, {r0['newton_iterations']} Newton iterations, {r0['output_samples']} output samples")
print("# wall times of the three runs: " + ", ".join(f"{r['wall_time_s']:.3f} s" for r in runs))
wall = statistics.median(r["wall_time_s"] for r in runs)
print(f"{'part':13s} {'seconds':>8s} {'share':>7s} {'us/step':>8s}")
for k in r0["time_split_s"]:
    v = statistics.median(r["time_split_s"][k] for r in runs)
    print(f"{k:13s} {v:8.3f} {100 * v / wall:6.1f}% {1e6 * v / steps:8.2f}")
print(f"{'wall':13s} {wall:8.3f} {100.0:6.1f}% {1e6 * wall / steps:8.2f}")
PY
