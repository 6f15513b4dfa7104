#!/usr/bin/env bash
# What a coarser output sampling costs in the pocket-contact metrics the ball-bearing scenes are
# validated on, beside what it saves in output time. Each scene is run at several output_interval
# values with the same step sequence ([solver] initial_step fixed: CVODE otherwise scales its first
# step by the first output time, see docs/output_layout.md), one rank pinned to core 0 with
# --output-thread off (full load: no core for the output), then `raceway report` reads the pocket
# contacts from the samples (the segment diagnostics at every sample: 6309 R3 and QJ215 store them at
# every 5th). One TSV line per run: the output's share of the wall time, and the
# report's contact events (runs of samples above the threshold), peak bar forces, impulses, mean
# contact duration and the cage speed. perf/studies/results/output_notes.md ("Sampling against accuracy")
# reads it.
#
#   perf/studies/output_sampling_accuracy.sh RACEWAY OUT_DIR [SCENES_DIR] > perf/studies/results/output_sampling_accuracy.tsv
set -eu
raceway=${1:?raceway}
out=${2:?output folder}
scenes=${3:-$(dirname "$0")/../../jobs/scenes}
mkdir -p "$out"
declare -A intervals=(
  [6309_R3]="5_us 10_us 20_us 50_us 100_us 175_us"
  [qj215_validation]="25_us 100_us 250_us 500_us 1_ms 1.25_ms"
)
printf "scene\toutput_interval\tsamples\tsteps\twall_s\toutput_share_%%\tfront_events\trear_events\tfront_peak_n\trear_peak_n\tfront_impulse_n_s\trear_impulse_n_s\tfront_mean_duration_us\tcage_speed_rad_s\tload_1min\n"
for scene in 6309_R3 qj215_validation; do
  for interval in ${intervals[$scene]}; do
    iv=${interval/_/ }
    load=$(cut -d' ' -f1 /proc/loadavg)
    taskset -c 0 "$raceway" run "$scenes/$scene.toml" -o "$out/run.h5" --output-thread off --summary-json "$out/run.json" \
      --set "scene.output_interval=\"$iv\"" --set 'solver.initial_step="1 us"' --set output.segment_every=1 \
      >"$out/log" 2>&1
    "$raceway" report "$out/run.h5" -o "$out/report" --no-plots >>"$out/log" 2>&1
    /usr/bin/python3 - "$out/run.json" "$out/report/summary.json" "$scene" "$iv" "$load" <<'PY'
import json, sys
run, rep = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
scene, interval, load = sys.argv[3:]
p = rep["pocket_forces"]
f, r = p["front"], p["rear"]
print("\t".join(str(x) for x in (
    scene, interval, run["output_samples"], run["steps"], f"{run['wall_time_s']:.3f}",
    f"{100 * run['output_time_s'] / run['wall_time_s']:.1f}", f["events"], r["events"], f"{f['peak_n']:.2f}",
    f"{r['peak_n']:.2f}", f"{f['impulse_n_s']:.5f}", f"{r['impulse_n_s']:.5f}", f"{1e6 * f['mean_duration_s']:.1f}",
    f"{rep['cage_speed']['mean_rad_s']:.4f}", load)))
PY
  done
done
