#!/usr/bin/env bash
# Seed 000 validation (docs/validation_ball_bearings.md): runs the four 6309 cases (R3, R5, A12, M24),
# writes each report (OUTDIR/<case>_report/: summary.json, figures, report.html) and prints the
# cage-pocket figures the validation page reads. It writes only into OUTDIR: the tracked
# docs/figures/6309_<case>_*.png are copies of OUTDIR/<case>_report/pocket_force_*.png, made by hand
# when the validation page is updated.
# Usage: jobs/run_6309_cases.sh [OUTDIR]   (default 6309_runs; RACEWAY=path/to/raceway, default build/raceway)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-6309_runs}
raceway=${RACEWAY:-$root/build/raceway}
mkdir -p "$out"
for c in R3 R5 A12 M24; do
  # The segment diagnostics at every 20 us sample (R3 ships them at every 5th): the pocket force
  # figures show the impacts' shapes, about 100 us long.
  "$raceway" run "$root/jobs/scenes/6309_$c.toml" -o "$out/$c.h5" --summary-json "$out/$c.json" \
    --set output.segment_every=1 2> "$out/$c.log"
  "$raceway" report "$out/$c.h5" -o "$out/${c}_report" 2> "$out/$c.report.log"
done
/usr/bin/python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
rows = {}
for c in ["R3", "R5", "A12", "M24"]:
    r = json.load(open(f"{out}/{c}_report/summary.json"))
    s = json.load(open(f"{out}/{c}.json"))
    rows[c] = (s, r, r["pocket_forces"])
print(f"{'case':5} {'wall s':>7} {'steps':>7} {'cage rpm':>9} {'slip %':>7} {'RMS circ N':>10} {'front ev':>8} {'rear ev':>7} "
      f"{'rear imp %':>10} {'duty':>7} {'mean dur ms':>11} {'peak N':>7} {'ball N mean':>11} {'ball N peak':>11}")
for c, (s, r, p) in rows.items():
    f, b = p["front"], p["rear"]
    events = f["events"] + b["events"]
    duty = f["duty_cycle"] + b["duty_cycle"]
    duration = (f["contact_time_s"] + b["contact_time_s"]) / events if events else 0.0
    print(f"{c:5} {s['wall_time_s']:7.2f} {s['steps']:7d} {s['cage_speed_rpm']:9.2f} {100*s['cage_slip']:7.3f} "
          f"{p['rms_circumferential_force_n']:10.3f} {f['events']:8d} {b['events']:7d} "
          f"{100*p['rear_impulse_fraction']:10.1f} {duty:7.4f} {1e3*duration:11.3f} {max(f['peak_n'], b['peak_n']):7.1f} "
          f"{r['ball_load']['largest_mean_n']:11.1f} {r['ball_load']['max_n']:11.1f}")
PY
echo "reports: $out/<case>_report/report.html" >&2
