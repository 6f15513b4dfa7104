#!/usr/bin/env bash
# The output's share of a run's wall time at the scenes' default sampling, one rank, for two builds
# run back to back (before, after; REPEATS rounds), one line per run with the machine's load average.
# output_s is the summary's output_time_s (the output's wall time on the run's thread: with the
# output thread, handing over the samples, flushes at checkpoints and the commit), thread_s its
# output_thread_time_s (the output thread's busy wall time beside it; absent before: "-").
# perf/studies/results/output_notes.md reads the medians.
#
#   [SCENES="..."] [REPEATS=3] perf/studies/output_share.sh RACEWAY_BEFORE RACEWAY_AFTER OUT_DIR [SCENES_DIR]
set -eu
before=${1:?raceway before}
after=${2:?raceway after}
out=${3:?output folder}
scenes=${4:-$(dirname "$0")/../../jobs/scenes}
mkdir -p "$out"
printf "scene\tbuild\trepeat\twall_s\toutput_s\toutput_write_s\tthread_s\tshare\tload_1min\n"
for scene in ${SCENES:-6309_R3 qj215_validation seed002_40hz}; do
  for repeat in $(seq 1 "${REPEATS:-3}"); do
    for build in before after; do
      bin=$before
      [[ $build == after ]] && bin=$after
      json="$out/$scene.$build.$repeat.json"
      load=$(cut -d' ' -f1 /proc/loadavg)
      "$bin" run "$scenes/$scene.toml" -o "$out/$scene.$build.h5" --summary-json "$json" >/dev/null 2>&1
      /usr/bin/python3 - "$json" "$scene" "$build" "$repeat" "$load" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
scene, build, repeat, load = sys.argv[2:]
thread = j.get("output_thread_time_s")
print(f"{scene}\t{build}\t{repeat}\t{j['wall_time_s']:.4f}\t{j['output_time_s']:.4f}\t{j['output_write_time_s']:.4f}\t"
      f"{'-' if thread is None else f'{thread:.4f}'}\t{100 * j['output_time_s'] / j['wall_time_s']:.1f} %\t{load}")
PY
    done
  done
done
