#!/usr/bin/env bash
# np=1 against np=2 on the heavy spatial roller scene (jobs/scenes/nj_heavy_spatial_roller.toml: 20
# rollers, 32 slices per race, 8 per pocket bar, 1381 contact tasks), recorded in
# perf/studies/results/spatial_roller_timings.txt: RUNS paired runs (np=1 then np=2, alternating),
# wall = the run summary's wall_time_s (model, start-up, integration, output; not mpirun's start);
# speed-up = median(np1) / median(np2); beside it the replay model's prediction for P = 2 from the
# last one-rank run (perf/calibration/replay_model.py, this machine's network from pingpong.txt
# where it exists). Every line carries the load average: the machine has 2 cores and is shared;
# run it when nothing else runs (WAIT_QUIET=S waits up to S seconds for a quiet machine before each
# run, as run_parallel_benchmarks.sh does). END_TIME shortens or lengthens the scene (default its 20 ms).
# SCENE names another scene of jobs/scenes (default nj_heavy_spatial_roller; nj_heavy_spatial_roller_oil
# is the same bearing with the EHD film on every slice); a run's record is appended to the file.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out="$root/perf/studies/results"
raceway="$root/build/raceway"
runs=${RUNS:-3}
mkdir -p "$out"
py=/usr/bin/python3
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
source "$root/perf/bench_lib.sh"  # header, load, wall, median
scene_name=${SCENE:-nj_heavy_spatial_roller}
scene="$tmp/heavy_roller.toml"
if [[ -n "${END_TIME:-}" ]]; then
  sed "s/^end_time = .*/end_time = \"$END_TIME\"/" "$root/jobs/scenes/$scene_name.toml" >"$scene"
else
  cp "$root/jobs/scenes/$scene_name.toml" "$scene"
fi
quiet() {
  [[ -z "${WAIT_QUIET:-}" ]] && return
  local waited=0 calm=0
  while ((calm < 5 && waited < WAIT_QUIET)); do
    read -r _ _ _ running _ </proc/loadavg
    if [[ ${running%/*} -le 1 ]]; then calm=$((calm + 1)); else calm=0; fi
    sleep 1
    waited=$((waited + 1))
  done
  ((calm >= 5)) && echo -n "quiet after ${waited} s; " || echo -n "BUSY after ${waited} s; "
}
{
  header
  echo "# heavy spatial roller scene ($scene_name.toml${END_TIME:+, end_time $END_TIME}), $runs paired runs"
  w1=() w2=()
  for i in $(seq "$runs"); do
    state=$(quiet)
    "$raceway" run "$scene" -o "$tmp/r1.h5" --summary-json "$tmp/r1.json" --output-thread off --scheduler-log 2>/dev/null
    w1+=("$(wall "$tmp/r1.json")")
    echo "run $i np=1 wall ${w1[-1]} s  (${state:-}$(load))"
    state=$(quiet)
    mpirun -np 2 "$raceway" run "$scene" -o "$tmp/r2.h5" --summary-json "$tmp/r2.json" 2>/dev/null
    w2+=("$(wall "$tmp/r2.json")")
    echo "run $i np=2 wall ${w2[-1]} s  (${state:-}$(load))"
  done
  m1=$(median "${w1[@]}") m2=$(median "${w2[@]}")
  speedup=$(awk -v a="$m1" -v b="$m2" 'BEGIN {printf "%.3f", a / b}')
  echo "median np=1 $m1 s, np=2 $m2 s, speed-up $speedup"
  network=()
  if [[ -f "$out/pingpong.txt" ]]; then
    network=(--latency-us "$(awk '$1 == 8 {print $2}' "$out/pingpong.txt")"
             --bandwidth-gbs "$(awk '$1 == 8192 {print $3}' "$out/pingpong.txt")")
  fi
  echo "# replay model (perf/calibration/replay_model.py) from the last one-rank run, measured np=2 beside it"
  "$py" "$root/perf/calibration/replay_model.py" "${network[@]}" --measured-np2 "$speedup" "$tmp/r1.h5" 2>&1 | sed "s|$tmp/||"
} 2>&1 | tee -a "$out/spatial_roller_timings.txt"
