#!/usr/bin/env bash
# Parallel benchmarks of the MPI master/worker executor (scheduler/mpi_executor.hpp), recorded in
# perf/studies/results/:
#   (a) parallel_speedup.txt: wall time np=1 and np=2 on the heavy scene (6309 R3, 100 ms, 40 x 40
#       traction grid), RUNS runs each, alternating; speed-up = median(np1) / median(np2);
#   (b) parallel_imbalance.txt: time-averaged imbalance (sum over evaluations of the slowest
#       rank's task seconds / sum of the mean rank's) with --schedule adaptive and static, np=2, on
#       the moving-work scene (rotating radial load), plus the imbalance over simulated time;
#   (c) pingpong.txt and replay_model.txt: network parameters here, and the replay model's
#       predicted speed-up for P = 1..64 from one-rank runs of 6309 R3, QJ215 and seed 002 (and the
#       heavy scene, checked against (a)).
# Every timing line carries the load average: the machine has 2 cores and is shared; a run while
# `uptime` shows a load near or above 2 measures the neighbours as much as raceway. Rerun on a quiet
# machine: perf/studies/run_parallel_benchmarks.sh (RUNS=5 by default; PARTS="a b c" selects parts).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out="$root/perf/studies/results"
raceway="$root/build/raceway"
runs=${RUNS:-5}
parts=${PARTS:-"a b c"}
mkdir -p "$out"
py=/usr/bin/python3
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
source "$root/perf/bench_lib.sh"  # the MPI environment; header, load, wall, median, measure_network
"$py" "$root/perf/studies/make_parallel_scenes.py" "$root" "$tmp"

# WAIT_QUIET=S: before every timed run of (a), wait up to S seconds until nothing else is runnable
# (/proc/loadavg's running count is 1, the reader itself, for 5 checks 1 s apart). A run that
# starts without that is marked "BUSY" in its line.
quiet() {
  [[ -z "${WAIT_QUIET:-}" ]] && { echo -n ""; return; }
  local waited=0 calm=0
  while ((calm < 5 && waited < WAIT_QUIET)); do
    # `read` is a builtin: this shell is the only runnable process it adds to the count.
    read -r _ _ _ running _ </proc/loadavg
    if [[ ${running%/*} -le 1 ]]; then calm=$((calm + 1)); else calm=0; fi
    sleep 1
    waited=$((waited + 1))
  done
  ((calm >= 5)) && echo -n "quiet after ${waited} s; " || echo -n "BUSY after ${waited} s; "
}

if [[ " $parts " == *" a "* ]]; then
  {
    header
    echo "# (a) heavy scene: 6309 R3, 40 x 40 ball-race traction grid, 100 ms; wall = run summary's wall_time_s"
    echo "# (model, start-up, integration, output; not mpirun's start-up)"
    w1=() w2=()
    for i in $(seq "$runs"); do
      state=$(quiet)
      "$raceway" run "$tmp/heavy_6309_R3.toml" -o "$tmp/h1.h5" --summary-json "$tmp/h1.json" --output-thread off 2>/dev/null
      w1+=("$(wall "$tmp/h1.json")")
      echo "run $i np=1 wall ${w1[-1]} s  (${state}$(load))"
      state=$(quiet)
      mpirun -np 2 "$raceway" run "$tmp/heavy_6309_R3.toml" -o "$tmp/h2.h5" --summary-json "$tmp/h2.json" 2>/dev/null
      w2+=("$(wall "$tmp/h2.json")")
      echo "run $i np=2 wall ${w2[-1]} s  (${state}$(load))"
    done
    m1=$(median "${w1[@]}") m2=$(median "${w2[@]}")
    echo "median np=1 $m1 s, np=2 $m2 s, speed-up $(awk -v a="$m1" -v b="$m2" 'BEGIN {printf "%.3f", a / b}')"
    "$py" - "$tmp/h2.h5" <<'PY'
import sys, h5py
g = h5py.File(sys.argv[1], "r")["scheduler"]
print("last np=2 run: time-averaged imbalance %.3f (rhs %.3f, jacobian %.3f); %d plans" % (
    g.attrs["time_averaged_imbalance"], g.attrs["time_averaged_imbalance_rhs"],
    g.attrs["time_averaged_imbalance_jacobian"], g["plans"].shape[0]))
PY
  } 2>&1 | tee "$out/parallel_speedup.txt"
  cp "$tmp/h1.h5" "$tmp/heavy_6309_R3.h5"  # a one-rank run of the heavy scene for (c)
fi

if [[ " $parts " == *" b "* ]]; then
  {
    header
    echo "# (b) moving work: 6309 R3, 30 x 30 grid, 1019.6 N radial load turning at -50 Hz, 60 ms, np=2"
    for policy in adaptive static; do
      echo "policy $policy ($(load))"
      mpirun -np 2 "$raceway" run "$tmp/moving_6309_R3.toml" -o "$tmp/m_$policy.h5" --schedule "$policy" 2>&1 |
        grep -E "scheduler: 2 ranks|done:" | sed 's/^/  /'
    done
    "$py" - "$tmp/m_adaptive.h5" "$tmp/m_static.h5" <<'PY'
import sys, h5py, numpy as np
print("imbalance over simulated time (rhs evaluations, sum of max / sum of mean per 5 ms window):")
rows = {}
for path, name in zip(sys.argv[1:], ("adaptive", "static")):
    g = h5py.File(path, "r")["scheduler"]
    s = g["imbalance"][()]
    s = s[s[:, 1] == 0]
    edges = np.arange(0, s[:, 2].max() + 0.005, 0.005)
    rows[name] = [(s[(s[:, 2] >= a) & (s[:, 2] < a + 0.005), 4].sum() / max(1e-30, s[(s[:, 2] >= a) & (s[:, 2] < a + 0.005), 5].sum()))
                  for a in edges[:-1]]
    print(f"  {name}: time-averaged imbalance all evaluations {g.attrs['time_averaged_imbalance']:.3f}, "
          f"rhs {g.attrs['time_averaged_imbalance_rhs']:.3f}, "
          f"jacobian {g.attrs['time_averaged_imbalance_jacobian']:.3f}, {g['plans'].shape[0]} plans, "
          f"rhs wall {g.attrs['wall_seconds_rhs']:.2f} s")
print("  window_ms  adaptive  static")
for i, (a, b) in enumerate(zip(rows["adaptive"], rows["static"])):
    print(f"  {5 * i:4d}-{5 * i + 5:<4d} {a:8.3f} {b:8.3f}")
PY
  } 2>&1 | tee "$out/parallel_imbalance.txt"
fi

if [[ " $parts " == *" c "* ]]; then
  measure_network "$root" | tee "$out/pingpong.txt"
  # Latency and bandwidth for the replay: the 8 B latency, and the bandwidth at 8 KB (the size of
  # a rank's records in these scenes: tens of tasks x tens of doubles).
  lat=$(awk '$1 == 8 {print $2}' "$out/pingpong.txt")
  bw=$(awk '$1 == 8192 {print $3}' "$out/pingpong.txt")
  files=()
  for s in short_6309_R3 short_qj215_validation short_seed002_40hz heavy_qj215_validation heavy_6309_R3; do
    [[ -f "$tmp/$s.h5" ]] || "$raceway" run "$tmp/$s.toml" -o "$tmp/$s.h5" --output-thread off 2>/dev/null
    files+=("$tmp/$s.h5")
  done
  measured=()
  if [[ -f "$out/parallel_speedup.txt" ]]; then
    # The check: the replay of the heavy scene at P=2 against (a)'s measured median speed-up.
    measured=(--measured-np2 0 --measured-np2 0 --measured-np2 0 --measured-np2 0 --measured-np2
              "$(sed -n 's/.*speed-up \([0-9.]*\)$/\1/p' "$out/parallel_speedup.txt")")
  fi
  { header; echo "# $(load)"; "$py" "$root/perf/calibration/replay_model.py" --latency-us "$lat" --bandwidth-gbs "$bw" "${measured[@]}" "${files[@]}"; } 2>&1 |
    sed "s|$tmp/||" | tee "$out/replay_model.txt"
fi
