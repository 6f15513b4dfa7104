#!/bin/bash
# Time per inner-ring revolution of a scene on one core: the whole run (integrator, output, the
# compressor) on one thread (--output-thread off) pinned to one CPU (taskset), the difference of two
# runs whose end times are REVS revolutions apart (start-up, seating and file set-up drop out),
# repeated REPS times in alternation. Wall and CPU (user + system) per revolution, one line each.
#
#   perf/studies/revolution_time.sh BINARY SCENE PERIOD_S REVS REPS [--set key=value ...]
#   perf/studies/revolution_time.sh build/raceway jobs/scenes/6309_R3.toml 0.02 5 3 --set output.segment_every=5
set -euo pipefail
binary=$1 scene=$2 period=$3 revs=$4 reps=$5
shift 5
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
short=$(python3 -c "print($period * $revs)")
long=$(python3 -c "print(2 * $period * $revs)")
run() {  # end time, extra options -> "wall cpu"
  local end=$1
  shift
  /usr/bin/time -f "%e %U %S" -o "$work/t" taskset -c "${CORE:-1}" "$binary" run "$scene" -o "$work/o.h5" \
    --output-thread off --set "scene.end_time=\"$end s\"" "$@" > /dev/null 2>&1 || { echo "run failed" >&2; exit 1; }
  awk '{print $1, $2 + $3}' "$work/t"
}
for ((i = 1; i <= reps; i++)); do
  read -r ws cs < <(run "$short" "${@}")
  read -r wl cl < <(run "$long" "${@}")
  python3 -c "print(f'pair $i: wall {1e3 * ($wl - $ws) / $revs:.1f} ms, cpu {1e3 * ($cl - $cs) / $revs:.1f} ms per revolution')"
done
