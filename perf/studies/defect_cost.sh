#!/usr/bin/env bash
# The cost of a race defect: each CWRU scene (jobs/scenes/cwru_6205_*_race_007.toml) against the same
# scene without its spall, over the same window, per shaft revolution (wall and CPU seconds of the
# process, steps, right-hand sides). The goal: a defect scene costs at most 2x a clean one.
#
#   perf/studies/defect_cost.sh RACEWAY [END_TIME]      (END_TIME default "0.2 s": 6 revolutions)
#
# Run it on a quiet machine (nothing else running): the ratio of two timings of the same machine.
set -euo pipefail
raceway=${1:?usage: defect_cost.sh RACEWAY [END_TIME]}
end=${2:-0.2 s}
here=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
measure() {  # NAME SCENE: prints name, wall s, cpu s, steps, rhs
  local name=$1 scene=$2
  /usr/bin/time -f "%e %U" -o "$work/$name.time" "$raceway" run "$scene" -o "$work/$name.h5" \
    --set "scene.end_time=$end" > "$work/$name.log" 2>&1
  local steps rhs
  steps=$(sed -n 's/.* \([0-9]*\) steps, \([0-9]*\) rhs.*/\1/p' "$work/$name.log")
  rhs=$(sed -n 's/.* \([0-9]*\) steps, \([0-9]*\) rhs.*/\2/p' "$work/$name.log")
  read -r wall cpu < "$work/$name.time"
  echo "$name $wall $cpu $steps $rhs"
}
printf '%-8s %-6s %10s %10s %10s %10s\n' scene case "wall s" "cpu s" steps rhs
for ring in outer inner; do
  scene=$here/jobs/scenes/cwru_6205_${ring}_race_007.toml
  grep -v '^spall = ' "$scene" > "$work/clean_$ring.toml"
  read -r _ w1 c1 s1 r1 < <(measure "defect_$ring" "$scene")
  read -r _ w0 c0 s0 r0 < <(measure "clean_$ring" "$work/clean_$ring.toml")
  printf '%-8s %-6s %10s %10s %10s %10s\n' "$ring" spall "$w1" "$c1" "$s1" "$r1" "$ring" clean "$w0" "$c0" "$s0" "$r0"
  awk -v a="$c1" -v b="$c0" -v s="$s1" -v t="$s0" -v ring="$ring" \
    'BEGIN { printf "%-8s ratio  cpu %.2fx, steps %.2fx (goal: at most 2x)\n", ring, a / b, s / t }'
done
