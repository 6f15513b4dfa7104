#!/usr/bin/env bash
# Where the whole run's wall goes at np=1 and np=2 on the heavy spatial roller scene
# (jobs/scenes/nj_heavy_spatial_roller.toml, or SCENE=path), RUNS paired, interleaved runs
# (np=1 then np=2): each line the run summary's time_split_s (rhs, jacobian, linear setup and solve,
# integrator, output, other = start-up, output file and what no timer covers), the counts of
# right-hand sides and Jacobians, the time per right-hand side and per Jacobian, the load average,
# and from the scheduler log (--scheduler-log): every rank's task seconds summed (task_s: at np=1
# wall - task_s is the run's serial part), and per evaluation (medians) the slowest rank's task
# seconds and rank 0's wall inside the executor, for right-hand sides and Jacobians (the rest of
# us_rhs / us_jac is rank 0's assembly). The phases are what a shared machine's load moves least: compare them, not only the
# walls. Both runs write the output on the run's thread (--output-thread off: at np=2 on a 2-core
# machine there is no free core for it anyway). END_TIME shortens or lengthens the scene (default
# "200 ms"); BUILD picks the build folder (default build); BASE=path/to/another/raceway runs that
# one too, interleaved with this build's (an A/B: rows "build 0" this build, "build 1" BASE). Then
# the medians of each column per rank count and build.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
builds=("$root/${BUILD:-build}/raceway")  # build 0; with BASE=path/to/raceway, build 1 (an A/B)
[[ -n "${BASE:-}" ]] && builds+=("$BASE")
runs=${RUNS:-3}
py=/usr/bin/python3
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
source "$root/perf/bench_lib.sh"  # header, load
scene="$tmp/scene.toml"
sed "s/^end_time = .*/end_time = \"${END_TIME:-200 ms}\"/" "${SCENE:-$root/jobs/scenes/nj_heavy_spatial_roller.toml}" >"$scene"
row() {  # np, summary json
  "$py" - "$1" "$2" <<'PY'
import json, sys
import h5py, numpy as np
s = json.load(open(sys.argv[2])); t = s["time_split_s"]
with h5py.File(sys.argv[2].replace(".json", ".h5"), "r") as f:
    g = f["scheduler"]; tasks = float(np.sum(g["rank_task_seconds"][()]))
    im = g["imbalance"][()]  # evaluation, phase, t, imbalance, max rank task s, mean, master wall s, plan
def med(phase, col):
    rows = im[im[:, 1] == phase]
    return 1e6 * float(np.median(rows[:, col])) if len(rows) else 0.0
print(f"np={sys.argv[1]} wall {s['wall_time_s']:.3f} rhs {t['rhs']:.3f} jac {t['jacobian']:.3f} "
      f"lsetup {t['linear_setup']:.3f} lsolve {t['linear_solve']:.3f} integ {t['integrator']:.3f} "
      f"acct {t['accounting']:.3f} output {t['output']:.3f} other {t['other']:.3f} "
      f"n_rhs {s['rhs_evaluations']} n_jac {s['jacobian_evaluations']} steps {s['steps']} "
      f"us_rhs {1e6 * s['time_per_rhs_s']:.1f} us_jac {1e6 * s['time_per_jacobian_s']:.1f} "
      f"task_s {tasks:.3f} rhs_tasks_us {med(0, 4):.1f} rhs_exec_us {med(0, 6):.1f} "
      f"jac_tasks_us {med(1, 4):.1f} jac_exec_us {med(1, 6):.1f}", end="")
PY
}
{
  header
  echo "# $(basename "${SCENE:-nj_heavy_spatial_roller.toml}"), end_time ${END_TIME:-200 ms}, $runs paired runs, build 0 ${builds[0]}${BASE:+, build 1 $BASE}"
  for i in $(seq "$runs"); do
    for np in 1 2; do
      for b in "${!builds[@]}"; do
        exe=${builds[$b]}
        launch=("$exe"); ((np > 1)) && launch=(mpirun -np "$np" "$exe")
        "${launch[@]}" run "$scene" -o "$tmp/r.h5" --summary-json "$tmp/r.json" --output-thread off --scheduler-log 2>/dev/null
        echo "$(row "$np" "$tmp/r.json")${BASE:+ build $b}  ($(load))"
      done
    done
  done
} 2>&1 | tee "$tmp/rows.txt"
# Medians of every column, per rank count.
"$py" - "$tmp/rows.txt" <<'PY'
import statistics, sys
rows = {}
for line in open(sys.argv[1]):
    if not line.startswith("np="): continue
    w = line.split("(")[0].split()
    key = w[0] + (" build " + w[w.index("build") + 1] if "build" in w else "")
    if "build" in w: del w[w.index("build"):w.index("build") + 2]
    rows.setdefault(key, []).append({w[i]: float(w[i + 1]) for i in range(1, len(w) - 1, 2)})
med = {k: {c: statistics.median(r[c] for r in v) for c in v[0]} for k, v in rows.items()}
for k, m in med.items():
    print(f"median {k} " + " ".join(f"{c} {m[c]:.4g}" for c in m))
for suffix in ("", " build 0", " build 1"):
    if "np=1" + suffix in med and "np=2" + suffix in med:
        a, b = med["np=1" + suffix], med["np=2" + suffix]
        print(f"np1/np2{suffix} " + " ".join(f"{c} {a[c] / b[c]:.3f}" for c in a if b[c] > 0))
PY
