#!/usr/bin/env bash
# Output's share of run time with the parallel output (each rank writes the segment diagnostics it
# evaluated, MPI-IO: --parallel-output) against rank 0 writing everything (the default), at
# the scenes' default sampling, 1 and 2 ranks, 3 repeats each; one line per run with the machine's
# load average (uptime). perf/studies/results/output_notes.md, "Parallel output (MPI-IO)", reads the medians.
#
#   [SCENES="..."] [REPEATS=3] [MODES="np1 np2_serial np2_parallel"] perf/studies/parallel_output_timings.sh RACEWAY OUT_DIR [SCENES_DIR]
set -eu
raceway=${1:?raceway}
out=${2:?output folder}
scenes=${3:-$(dirname "$0")/../../jobs/scenes}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$out"
printf "scene\tranks\twriter\trepeat\twall_s\toutput_s\toutput_write_s\tload_1min\n"
for scene in ${SCENES:-6309_R3 qj215_validation seed002_40hz}; do
  for repeat in $(seq 1 "${REPEATS:-3}"); do
    for mode in ${MODES:-np1 np2_serial np2_parallel}; do
      case $mode in
        np1) cmd=("$raceway") ;;
        np2_serial) cmd=(mpirun -np 2 "$raceway") ;;
        np2_parallel) cmd=(mpirun -np 2 "$raceway") ;;
      esac
      extra=()
      [[ $mode == np2_parallel ]] && extra=(--parallel-output)
      json="$out/$scene.$mode.$repeat.json"
      load=$(cut -d' ' -f1 /proc/loadavg)
      "${cmd[@]}" run "$scenes/$scene.toml" -o "$out/$scene.$mode.h5" --summary-json "$json" "${extra[@]}" >/dev/null 2>&1
      /usr/bin/python3 - "$json" "$scene" "$mode" "$repeat" "$load" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
scene, mode, repeat, load = sys.argv[2:]
ranks, writer = ("1", "rank 0") if mode == "np1" else ("2", "rank 0" if "serial" in mode else "all ranks (MPI-IO)")
print(f"{scene}\t{ranks}\t{writer}\t{repeat}\t{j['wall_time_s']:.4f}\t{j['output_time_s']:.4f}\t{j['output_write_time_s']:.4f}\t{load}")
PY
    done
  done
done
