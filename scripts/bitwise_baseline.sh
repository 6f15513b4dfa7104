#!/usr/bin/env bash
# A bitwise baseline for refactors: six shipped scenes over short windows at 1, 2 and 3 ranks,
# kept in a folder, and the comparison of another build's folder against it.
#
#   scripts/bitwise_baseline.sh run RACEWAY DIR [--scenes SCENE_DIR]
#       runs every scene of BASELINE_SCENES at 1, 2 and 3 ranks (mpirun --oversubscribe) with
#       RACEWAY into DIR (new or empty): DIR/<scene>_np<P>.h5, .json (summary), .log; copies the
#       scene files into DIR/scenes and writes DIR/commands.txt (every command as run) and
#       DIR/build.txt (raceway --version); then checks that 2 and 3 ranks gave the bits of 1 rank
#       (DIR/ranks_check.txt). SCENE_DIR (default: this repository's jobs/scenes) is where the
#       scenes are read; give an earlier baseline's DIR/scenes to repeat it exactly.
#   scripts/bitwise_baseline.sh compare DIR_A DIR_B [compare_outputs.py options: --map OLD=NEW ...]
#       compares every output (datasets and attributes, scripts/compare_outputs.py), every summary
#       and the CVODE counters of DIR_B with DIR_A's; exit 0 when all are bitwise identical.
#   scripts/bitwise_baseline.sh ranks DIR
#       the rank check of `run` alone: np 2 and 3 against np 1 within DIR.
#
# What legitimately differs and is left out (the build's commit and version, the scene's path,
# wall times, /scheduler) is listed in scripts/compare_outputs.py. Needs mpirun (Open MPI), numpy
# and h5py (/usr/bin/python3).
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
compare_outputs=(/usr/bin/python3 "$root/scripts/compare_outputs.py")

# scene:window. The windows are those of the scene answer files (tests/system/scenes/answers): 1-5 s of
# one rank each on a 2-core machine, long enough to reach loaded contacts and the cage's motion.
BASELINE_SCENES=(
  "default:40 ms"
  "seed002_40hz:25 ms"
  "6309_R3:10 ms"
  "qj215_validation:30 ms"
  "seed003_flexible_bridges:1 ms"
  "seed003_flexible_ring:1.5 ms"
)
RANKS=(1 2 3)
# Open MPI as root, oversubscribed (3 ranks on 2 cores: correctness, not speed), in a container
# (no single-copy transfers), ranks that yield the cores while they wait.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_mpi_yield_when_idle=1

die() {
  echo "bitwise_baseline: $*" >&2
  exit 2
}

# The rank check: every output and summary at P ranks against the one at 1 rank.
ranks_check() {
  local dir=$1 failures=0 entry name np
  for entry in "${BASELINE_SCENES[@]}"; do
    name=${entry%%:*}
    [[ -f "$dir/${name}_np1.h5" ]] || { echo "$name: no np 1 output in $dir"; failures=$((failures + 1)); continue; }
    for np in "${RANKS[@]:1}"; do
      "${compare_outputs[@]}" "$dir/${name}_np1.h5" "$dir/${name}_np$np.h5" || failures=$((failures + 1))
      "${compare_outputs[@]}" "$dir/${name}_np1.json" "$dir/${name}_np$np.json" || failures=$((failures + 1))
    done
  done
  echo "rank check of $dir: $([[ $failures -eq 0 ]] && echo "every output at 2 and 3 ranks bitwise that of 1 rank" || echo "$failures comparison(s) differ")"
  [[ $failures -eq 0 ]]
}

run_baseline() {
  local raceway=${1:?raceway executable} dir=${2:?output folder} scenes="$root/jobs/scenes"
  shift 2
  [[ ${1:-} == --scenes ]] && scenes=${2:?--scenes DIR}
  [[ -x $raceway ]] || die "$raceway: not an executable"
  command -v mpirun >/dev/null || die "no mpirun (apt install openmpi-bin)"
  if [[ -e $dir && -n $(ls -A "$dir" 2>/dev/null) ]]; then
    die "$dir exists and is not empty: a baseline is never overwritten (remove it or choose another folder)"
  fi
  mkdir -p "$dir/scenes" || die "cannot create $dir"
  raceway=$(realpath "$raceway")
  dir=$(realpath "$dir")
  local entry name window np
  for entry in "${BASELINE_SCENES[@]}"; do
    name=${entry%%:*}
    cp "$scenes/$name.toml" "$dir/scenes/" || die "$scenes/$name.toml: cannot copy"
  done
  "$raceway" --version >"$dir/build.txt" || die "$raceway --version failed"
  {
    echo "# $(date -u +%Y-%m-%dT%H:%M:%SZ), in $dir, environment:"
    echo "# OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_mpi_yield_when_idle=1"
  } >"$dir/commands.txt"
  local failures=0
  for entry in "${BASELINE_SCENES[@]}"; do
    name=${entry%%:*}
    window=${entry#*:}
    for np in "${RANKS[@]}"; do
      local command=(mpirun --oversubscribe --allow-run-as-root -np "$np" "$raceway" run "scenes/$name.toml"
        --set "scene.end_time=$window" -o "${name}_np$np.h5" --summary-json "${name}_np$np.json")
      printf '%q ' "${command[@]}" >>"$dir/commands.txt"
      echo >>"$dir/commands.txt"
      local start=$SECONDS
      if (cd "$dir" && timeout 900 "${command[@]}" >"${name}_np$np.log" 2>&1); then
        echo "$name np $np: $(grep -o 'done: .*' "$dir/${name}_np$np.log" | cut -c1-110) ($((SECONDS - start)) s)"
      else
        echo "$name np $np: FAILED, see $dir/${name}_np$np.log: $(tail -2 "$dir/${name}_np$np.log")"
        failures=$((failures + 1))
      fi
    done
  done
  ranks_check "$dir" >"$dir/ranks_check.txt" 2>&1 || failures=$((failures + 1))
  tail -1 "$dir/ranks_check.txt"
  [[ $failures -eq 0 ]] || die "$failures failure(s)"
  echo "baseline written to $dir"
}

compare_folders() {
  local a=${1:?folder A} b=${2:?folder B}
  shift 2
  [[ -d $a && -d $b ]] || die "compare needs two folders"
  local failures=0 compared=0 file name
  for file in "$a"/*_np*.h5 "$a"/*_np*.json; do
    [[ -e $file ]] || continue
    name=$(basename "$file")
    if [[ ! -e $b/$name ]]; then
      echo "$name: missing in $b"
      failures=$((failures + 1))
      continue
    fi
    compared=$((compared + 1))
    if [[ $file == *.json ]]; then
      "${compare_outputs[@]}" "$file" "$b/$name" || failures=$((failures + 1))
    else
      "${compare_outputs[@]}" "$file" "$b/$name" "$@" || failures=$((failures + 1))
    fi
  done
  # The CVODE counters side by side (also compared above, as part of the summaries).
  /usr/bin/python3 - "$a" "$b" <<'PY'
import glob, json, os, sys
keys = {"steps": "steps", "rhs_evaluations": "rhs", "jacobian_evaluations": "jac",
        "newton_iterations": "newton", "newton_failures": "newton fail", "error_test_failures": "err test",
        "linear_setups": "setups"}
print("CVODE counters (A | B):")
for path in sorted(glob.glob(os.path.join(sys.argv[1], "*_np*.json"))):
    other = os.path.join(sys.argv[2], os.path.basename(path))
    if not os.path.exists(other):
        continue
    with open(path) as fa, open(other) as fb:
        a, b = json.load(fa), json.load(fb)
    cells = [f"{short} {a.get(k)}" + ("" if a.get(k) == b.get(k) else f" | {b.get(k)} DIFFERS")
             for k, short in keys.items()]
    print(f"  {os.path.basename(path)[:-5]:32s} " + ", ".join(cells))
PY
  [[ $compared -gt 0 ]] || die "$a holds no outputs (*_np*.h5, *_np*.json)"
  if [[ $failures -eq 0 ]]; then
    echo "all $compared files of $b bitwise identical to $a"
  else
    echo "$failures of $compared files of $b differ from $a"
    exit 1
  fi
}

case ${1:-} in
  run) shift; run_baseline "$@" ;;
  compare) shift; compare_folders "$@" ;;
  ranks) shift; ranks_check "${1:?folder}" ;;
  *) sed -n '2,22p' "${BASH_SOURCE[0]}" >&2; exit 2 ;;
esac
