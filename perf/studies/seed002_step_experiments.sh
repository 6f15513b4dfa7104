#!/usr/bin/env bash
# What holds seed 002's step back (docs/integration_methods.md, "What holds the step back"):
#   1. the first 20 ms of jobs/scenes/seed002_40hz.toml with one change at a time: steps and
#      error-test failures;
#   2. the radial velocity of every roller sampled every 1 us over 10-12 ms: its rms, its main
#      frequency, the roller's mean race loads;
#   3. build/perf/bench/step_limits at three sampling intervals, and without gravity.
# Usage: perf/studies/seed002_step_experiments.sh [BUILD_DIR] > perf/studies/results/seed002_step_experiments.txt
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene=$root/jobs/scenes/seed002_40hz.toml

variant() {  # SED-EXPRESSION LABEL
  sed -e "$1" -e 's/^end_time = .*/end_time = "20 ms"/' "$scene" >"$work/v.toml"
  "$build/raceway" run "$work/v.toml" -o "$work/v.h5" --summary-json "$work/v.json" >/dev/null 2>&1
  /usr/bin/python3 -c "import json,sys; j=json.load(open('$work/v.json')); print(f\"| {sys.argv[1]} | {j['steps']} | {j['error_test_failures']} | {j['cage_speed_rpm']:.3f} |\")" "$2"
}
echo "## 1. the first 20 ms, one change at a time (rtol 1e-7 unless said)"
echo "| change | steps | error-test failures | cage speed, second half [rpm] |"
echo "|---|---|---|---|"
variant 's/x/x/' "the scene as shipped"
variant 's/^gravity = true/gravity = false/' "gravity off"
variant '/^\[contact.roller_cage\]/,/^$/s/^friction_coefficient = .*/friction_coefficient = 0.0/' "roller-cage (bar) friction 0"
variant 's/^pocket_clearance = .*/pocket_clearance = "1 mm"/' "pocket clearance 1 mm"
variant 's/^damping_factor = .*/damping_factor = "2 s\/m"/' "race damping factor 2 s/m"
variant 's/^damping_factor = .*/damping_factor = "0.1 s\/m"/' "race damping factor 0.1 s/m"
variant 's/^translation = "free"/translation = "free"\nmass = "1 kg"/' "inner ring mass 1 kg"
variant 's/^rtol = .*/rtol = 1e-7\nstability_limit_detection = true/' "stability_limit_detection = true"
variant 's/^rtol = .*/rtol = 1e-7\nmax_order = 3/' "max_order = 3"
variant 's/^rtol = .*/rtol = 1e-7\nmax_order = 2/' "max_order = 2"
variant 's/^rtol = .*/rtol = 1e-6/' "rtol 1e-6"
variant 's/^rtol = .*/rtol = 1e-7\natol = { velocity = "1e-5 m\/s" }/' "atol velocity 1e-5 m/s"

echo
echo "## 2. roller radial velocity, sampled every 1 us over 10-12 ms"
sed -e 's/^end_time = .*/end_time = "12 ms"/' -e 's/^output_interval = .*/output_interval = "1 us"/' "$scene" >"$work/fine.toml"
"$build/raceway" run "$work/fine.toml" -o "$work/fine.h5" 2>&1 | grep "done:" || true
/usr/bin/python3 - "$work/fine.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
t = f["time"][()].ravel(); w = t >= 0.010
p, v = f["rollers/position"][()][w], f["rollers/velocity"][()][w]
fi, fo = f["segments/roller_inner_race/normal_force"][()][w], f["segments/roller_outer_race/normal_force"][()][w]
r = np.sqrt(p[..., 0] ** 2 + p[..., 1] ** 2)
vr = (v * (p / r[..., None])).sum(-1)
for k in range(vr.shape[1]):
    x = vr[:, k] - vr[:, k].mean()
    spectrum = np.abs(np.fft.rfft(x * np.hanning(len(x))))
    freq = np.fft.rfftfreq(len(x), t[1] - t[0])
    i = np.argmax(spectrum[5:]) + 5
    print(f"roller {k:2d}: inner race {fi[:, k].mean():6.1f} N, outer race {fo[:, k].mean():6.1f} N; radial velocity "
          f"rms {x.std():.2e} m/s at {freq[i] / 1e3:5.1f} kHz; radial displacement rms {(r[:, k] - r[:, k].mean()).std():.2e} m")
PY

echo
echo "## 3. build/perf/bench/step_limits: steps held by contact state"
for dt in 1e-4 1e-5 2e-6; do
  echo "### interval $dt s"
  "$build/perf/bench/step_limits" "$scene" 0.02 "$dt" 2>&1 >/dev/null
done
echo "### gravity off, interval 2e-6 s"
sed 's/^gravity = true/gravity = false/' "$scene" >"$work/nog.toml"
"$build/perf/bench/step_limits" "$work/nog.toml" 0.02 2e-6 2>&1 >/dev/null
