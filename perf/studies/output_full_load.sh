#!/usr/bin/env bash
# The output's share at full load (every core runs a rank, so no core for the output thread),
# imitated by a one-rank run pinned to core 0 with --output-thread off (the chunk compressor on the
# same core): the scenes at their default sampling, with [output] segments = false, with a 10x
# coarser output_interval, and both. Then `mpirun -np 1` (the rank bound to core 0) with the
# thread off (what auto decided under mpirun's binding before) and auto (bound to a free core).
# One line per run with the 1-minute load average; cpu_s is the process's CPU (all threads).
# With PROFILE=1 also where the CPU per sample goes (perf record, perf/studies/output_cost_profile.py).
# perf/studies/results/output_notes.md ("At full load") reads it.
#
#   [REPEATS=2] [PROFILE=1] perf/studies/output_full_load.sh RACEWAY OUT_DIR [SCENES_DIR]
set -eu
raceway=${1:?raceway}
out=${2:?output folder}
scenes=${3:-$(dirname "$0")/../../jobs/scenes}
here=$(dirname "$0")
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
line() {  # line SCENE CASE REPEAT LOAD CPU_S: one TSV line from $out/s.json
  /usr/bin/python3 - "$out/s.json" "$@" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
scene, case, repeat, load, cpu = sys.argv[2:]
print(f"{scene}\t{case}\t{repeat}\t{j['output_samples']}\t{j['steps']}\t{j['wall_time_s']:.3f}\t{j['output_time_s']:.4f}\t"
      f"{100 * j['output_time_s'] / j['wall_time_s']:.1f}\t{j['output_thread_time_s']:.3f}\t{cpu}\t{load}")
PY
}
printf "scene\tcase\trepeat\tsamples\tsteps\twall_s\toutput_s\tshare_%%\tthread_s\tcpu_s\tload_1min\n"
for repeat in $(seq 1 "${REPEATS:-2}"); do
  for scene in 6309_R3 qj215_validation; do
    coarse="200 us"
    [[ $scene == qj215_validation ]] && coarse="1 ms"  # 10x the scenes' output_interval
    for case in default segments_false interval_10x both; do
      args=()
      [[ $case == segments_false || $case == both ]] && args+=(--set output.segments=false)
      [[ $case == interval_10x || $case == both ]] && args+=(--set "scene.output_interval=\"$coarse\"")
      load=$(cut -d' ' -f1 /proc/loadavg)
      /usr/bin/time -f "%U %S" -o "$out/time" taskset -c 0 "$raceway" run "$scenes/$scene.toml" -o "$out/o.h5" \
        --output-thread off --summary-json "$out/s.json" "${args[@]}" >/dev/null 2>&1
      read -r user sys <"$out/time"
      line "$scene" "one core, $case" "$repeat" "$load" "$(echo "$user + $sys" | bc)"
    done
    for mode in off auto; do
      load=$(cut -d' ' -f1 /proc/loadavg)
      /usr/bin/time -f "%U %S" -o "$out/time" mpirun -np 1 "$raceway" run "$scenes/$scene.toml" -o "$out/o.h5" \
        --output-thread "$mode" --summary-json "$out/s.json" >/dev/null 2>&1
      read -r user sys <"$out/time"
      line "$scene" "mpirun -np 1, $mode" "$repeat" "$load" "$(echo "$user + $sys" | bc)"
    done
  done
done
[[ ${PROFILE:-0} == 1 ]] || exit 0
for scene in 6309_R3 qj215_validation; do
  taskset -c 0 perf record -q -F 2000 --call-graph dwarf,16384 -o "$out/$scene.perf" "$raceway" run "$scenes/$scene.toml" \
    -o "$out/o.h5" --output-thread off --summary-json "$out/s.json" >/dev/null 2>&1
  perf script -i "$out/$scene.perf" -F tid,ip,sym 2>/dev/null >"$out/$scene.stacks"
  echo "== $scene, one core, --output-thread off, load $(cut -d' ' -f1 /proc/loadavg)"
  /usr/bin/python3 "$here/output_cost_profile.py" "$out/$scene.stacks" 2000 "$out/s.json"
done
