#!/bin/bash
# The automatic BDF order ([solver] automatic_order, solver/numerics/order_choice.hpp) against a fixed
# largest order, per shipped scene over its full end time: steps, right-hand sides, Jacobians,
# contact evaluations and the choice made (the summary's order_choice). Counts only: they do not
# depend on the machine's load, wall times do.
#
#   perf/studies/automatic_order.sh [BINARY] [WORKDIR] [SETTINGS] [SCENE...]
#     BINARY    build/raceway
#     WORKDIR   a scratch folder (outputs and summaries), default /tmp/automatic_order
#     SETTINGS  "auto 5": auto = the scene as shipped (automatic where it gives no max_order), a
#               number = --set solver.max_order=N (fixed)
#     SCENE     names in jobs/scenes (default: every one)
# Prints one tab-separated row per run: scene, setting, steps, rhs, jacobians, contact evaluations,
# choice. perf/studies/results/automatic_order.md records the table.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
binary=${1:-$root/build/raceway}
work=${2:-/tmp/automatic_order}
settings=${3:-"auto 5"}
shift $(( $# < 3 ? $# : 3 ))
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  for f in "$root"/jobs/scenes/*.toml; do scenes+=("$(basename "$f" .toml)"); done
fi
mkdir -p "$work"
for sc in "${scenes[@]}"; do
  for s in $settings; do
    extra=()
    [ "$s" != auto ] && extra=(--set "solver.max_order=$s")
    out="$work/${sc}_$s"
    if ! "$binary" run "$root/jobs/scenes/$sc.toml" -o "$out.h5" "${extra[@]}" --summary-json "$out.json" \
        > "$out.log" 2>&1; then
      printf '%s\t%s\tfailed\n' "$sc" "$s"
      continue
    fi
    python3 - "$sc" "$s" "$out.json" <<'PY'
import json, sys
sc, s, path = sys.argv[1:4]
j = json.load(open(path))
print("\t".join(str(x) for x in (sc, s, j["steps"], j["rhs_evaluations"], j["jacobian_evaluations"],
                                 j["segment_evaluations"], j.get("order_choice", ""))))
PY
    rm -f "$out.h5"
  done
done
