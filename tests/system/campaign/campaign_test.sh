#!/bin/bash
# Campaigns (raceway campaign, docs/campaigns.md) on 2 ranks in 2 groups of 1:
#   resume:    the table of an uninterrupted campaign has every scene, its metrics equal the ones
#              this test recomputes from the scene's output file (independent code below) and the
#              swept values are the SI values the run's summary reports; the same campaign in 1 group
#              of 2 ranks gives bitwise the same files. Then rank 1 is killed (SIGKILL) while it runs a scene that has a periodic checkpoint;
#              --resume finishes the campaign, the killed scene equals the uninterrupted run's
#              bitwise (tests/system/parallel/compare_outputs.py) and every scene is in the table.
#   retry:     a scene that fails (its wall-clock budget) is retried once, then recorded as failed
#              with its diagnosis; the campaign exits non-zero.
#   bad_files: bad campaign files and overrides give file, line, key and reason (exit 2) before
#              anything is written.
#   spatial:   a spatial campaign's rows hold `raceway report`'s cage-centroid metrics (vortex radius
#              ratio, sigma_v, ...) over the window after settling, and only the metrics asked for.
#   early_signal: SIGUSR1 the moment raceway takes the stop signals (Slurm may send it within a
#              second of a job's start): a run on 1 and 2 ranks and a campaign stop cleanly (exit 4)
#              and the runs resume.
#   slurm_array: jobs/campaigns/slurm_array.sh under Slurm's environment without Slurm (the same on a
#              real Slurm: real_slurm_test.sh): it submits an
#              array of the 4 scenes and a dependent aggregation job (stub sbatch); the tasks run
#              (two at once, one on 2 ranks, one killed with SIGKILL mid-scene, one stopped by
#              SIGUSR1); the aggregation step submits the killed and the stopped scene again; their
#              tasks resume; the next aggregation step writes the table, equal to the one-allocation
#              campaign's but for the wall times and the scene stopped by SIGUSR1 (resumed from the
#              signal's checkpoint, off the uninterrupted step sequence); the killed one is bitwise.
#   plan:      without ranks_per_scene the group size is the one of the shortest predicted campaign
#              from the scene's predicted speed-up (data/rank_table.csv, read here too): one
#              6309 R3 scene on 2 ranks runs on both when its speed-up there is above 1, the 8 QJ215
#              speeds on 8 ranks one each, 2 of them 4 each;
#              --only with no such scene is refused (exit 2) before anything is written.
#   overrides: --set is stored in the summary with the resolved parameters; a resume with other
#              overrides is refused.
#   refused_resume: a finished campaign resumed with its file edited (a swept value), or with another
#              campaign's file, is refused (exit 2) naming the difference, and the folder is left as it
#              was; the same file resumes (nothing to run) and redraws the table.
#   check_fuzz: random mutations of small_campaign.toml (and the extreme ones users found: ranges to
#              +-inf, 1e9 scenes, negative settling, fractional ranks...) through `campaign check`
#              under a timeout: each passes (exit 0) or is refused with FILE:LINE and exit 2, never a
#              hang or a crash.
#   table_signal: a campaign with a failing scene writes its table itself, the failure in it; SIGUSR1
#              to mpirun and to the table's process while the table is drawn does not lose it; a
#              deterministic failure (exit 2: an output path the run refuses) is not retried.
# Usage: campaign_test.sh CASE RACEWAY MPIEXEC SOURCE_DIR
set -u
case_name=$1 raceway=$2 mpiexec=$3 source_dir=$4
source "$source_dir/tests/system/test_lib.sh"
export OMPI_MCA_rmaps_base_oversubscribe=1
python=/usr/bin/python3
small="$source_dir/tests/system/campaign/small_campaign.toml"

# Recomputes the table's metrics from each scene's file (numpy and h5py only) and compares.
check_table() {
  "$python" - "$1" <<'PY' || fail "table of $1"
import csv, json, sys, h5py, numpy as np
folder = sys.argv[1]
manifest = json.load(open(f"{folder}/campaign.json"))
rows = {r["scene"]: r for r in csv.DictReader(open(f"{folder}/campaign_table.csv"))}
assert sorted(rows) == sorted(manifest["scenes"]), (sorted(rows), sorted(manifest["scenes"]))
bad = 0
for sid, scene in manifest["scenes"].items():
    row = rows[sid]
    assert row["status"] == "done", (sid, row["status"], row["diagnosis"])
    with h5py.File(f"{folder}/{sid}.h5") as f:
        t = f["time"][:]
        keep = t >= scene["settling_time_s"] - 1e-12
        w = f["cage/angular_velocity"][:][keep]
        r = np.hypot(*(f["cage/position"][:][keep][:, :2] - f["outer_ring/position"][:][keep][:, :2]).T)
        inner = [k for k in f["segments"] if "inner" in k][0]
        load = f[f"segments/{inner}/normal_force"][:][keep].max(axis=1)
        pocket = np.hstack([f[f"segments/{k}/normal_force"][:][keep] for k in f["segments"] if "cage_bar" in k])
        summary = json.loads(f.attrs["summary_json"])
        p = summary["scene_parameters"]
        ratio = p["bearing.roller_diameter"]["value"] / p["bearing.pitch_diameter"]["value"]
        loads = f[f"segments/{inner}/normal_force"][:][keep]
        # Impacts: the contact onsets at the integrator's steps (/cage/pocket_step_onsets) in the
        # output intervals after the window's first sample; the cages turn in +z, so the front bar
        # is side 0 (cage_bar_front).
        onsets = f["cage/pocket_step_onsets"][:][np.flatnonzero(keep)[0] + 1:]
        runs = {"front": int(onsets[:, :, 0].sum()), "rear": int(onsets[:, :, 1].sum())}
        epicyclic = 0.5 * (f["inner_ring/angular_velocity"][:][keep] * (1 - ratio)
                           + f["outer_ring/angular_velocity"][:][keep] * (1 + ratio))
    assert pocket.max() > 0, f"{sid}: no pocket force, the pocket metrics are not checked"
    expect = {"cage_speed_rpm": w.mean() * 60 / (2 * np.pi), "cage_slip": 1 - w.mean() / epicyclic.mean(),
              "pocket_force_mean_n": pocket.mean(), "pocket_force_peak_n": pocket.max(), "cage_whirl_radius_m": r.mean(),
              "cage_whirl_radius_std_m": r.std(), "max_element_load_mean_n": load.mean(),
              "window_samples": keep.sum(), "element_load_min_n": loads.min(), "element_load_max_n": loads.max(),
              "impacts_front_per_rev": runs["front"] / 0.5, "impacts_rear_per_rev": runs["rear"] / 0.5}
    assert runs["front"] + runs["rear"] > 0, f"{sid}: no impacts, the impact counts are not checked"
    for key, value in expect.items():
        got = float(row[key])
        if not abs(got - value) <= 1e-12 * max(abs(value), 1e-30):
            print(f"{sid} {key}: table {got!r}, recomputed {value!r}"); bad += 1
    for name, key in manifest["axes"].items():
        if float(row[f"{name}_si"]) != summary["scene_parameters"][key]["value"]:
            print(f"{sid} {name}: table {row[name + '_si']}, summary {summary['scene_parameters'][key]}"); bad += 1
sys.exit(1 if bad else 0)
PY
}

# The pid of world rank RANK among the children of mpirun PID.
rank_pid() {
  local p
  for p in $(pgrep -P "$1"); do
    tr '\0' '\n' < /proc/$p/environ 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=$2" && { echo "$p"; return; }
  done
}


# A campaign of 2 short scenes of the default bearing, 1 rank each (refused_resume, table_signal).
tiny_campaign() {  # FILE NAME SPEED2
  cat > "$1" <<EOF
[campaign]
name = "$2"
scene = "$source_dir/jobs/scenes/default.toml"
end_time = "4 ms"
settling_time = "2 ms"
ranks_per_scene = 1

[[axis]]
key = "inner_ring.speed"
name = "speed"
values = [
  "1000 rpm",
  "$3",
]
EOF
}

case $case_name in
resume)
  # The uninterrupted campaign: its table.
  "$mpiexec" -np 2 "$raceway" campaign "$small" -o "$work/ref" > "$work/ref.log" 2>&1 || fail "reference campaign"
  grep -q "4 of 4 scenes done, 0 failed" "$work/ref.log" || fail "no final count: $(tail -3 "$work/ref.log")"
  grep -q "2 ranks in 2 groups of 1" "$work/ref.log" || fail "not 2 groups of 1"
  check_table "$work/ref"
  ls "$work/ref/plots/"cage_speed_rpm_vs_speed.png > /dev/null || fail "no trend plot"
  # The plots drawn by a pool of processes (one per core: the campaign lets its table use the
  # ranks' cores) are the bytes one process draws, and there is one per metric and axis.
  drawn=$(sed -n 's/.*campaign table: .*, \([0-9]*\) plots in .*/\1/p' "$work/ref.log")
  [[ "$drawn" -gt 1 && $(ls "$work/ref/plots/"*.png | wc -l) -eq "$drawn" ]] || fail "plots: $drawn reported, $(ls "$work/ref/plots" | wc -l) there"
  cp -r "$work/ref" "$work/serial" && rm -r "$work/serial/plots"
  taskset -c "$(taskset -cp $$ | sed 's/.*: //; s/[-,].*//')" \
    "$python" "$source_dir/io/report/campaign_table.py" "$work/serial" 2> /dev/null || fail "table on one core"
  for f in "$work/ref/plots/"*.png; do
    cmp -s "$f" "$work/serial/plots/$(basename "$f")" || fail "$(basename "$f"): the pool's differs from one process's"
  done
  # The same scenes in 1 group of 2 ranks: bitwise the same files (results do not depend on the
  # rank count).
  sed 's/^ranks_per_scene = 1/ranks_per_scene = 2/; s|"\.\./\.\./\.\./jobs|"'"$source_dir"'/jobs|' "$small" > "$work/pairs.toml"
  "$mpiexec" -np 2 "$raceway" campaign "$work/pairs.toml" -o "$work/pairs" > "$work/pairs.log" 2>&1 || fail "groups of 2"
  grep -q "2 ranks in 1 groups of 2" "$work/pairs.log" || fail "not 1 group of 2: $(head -3 "$work/pairs.log")"
  for s in s000 s001 s002 s003; do
    "$python" "$source_dir/tests/system/parallel/compare_outputs.py" "$work/ref/$s.h5" "$work/pairs/$s.h5" > /dev/null \
      || fail "$s on 2 ranks differs from 1 rank"
  done
  # Killed and resumed.
  "$mpiexec" -np 2 "$raceway" campaign "$small" -o "$work/c" > "$work/log" 2>&1 &
  mpirun_pid=$!
  killed=""
  for _ in $(seq 1 600); do
    scene=$(grep -o "s[0-9]* on group 1" "$work/log" | tail -1 | cut -d' ' -f1)
    if [[ -n $scene && -f "$work/c/$scene.h5.checkpoint" && ! -f "$work/c/$scene.h5" ]]; then
      pid=$(rank_pid $mpirun_pid 1)
      # Stopped first, then looked at again: the scene cannot finish between the look and the kill
      # (finding the pid takes tens of ms; a scene that finished meanwhile is let go on).
      if [[ -n $pid ]] && kill -STOP "$pid"; then
        [[ -f "$work/c/$scene.h5" ]] || { kill -KILL "$pid"; killed=$scene; break; }
        kill -CONT "$pid"
      fi
    fi
    sleep 0.05
  done
  wait $mpirun_pid && fail "the campaign with a killed rank exited 0"
  [[ -n $killed ]] || fail "no scene was killed mid-run"
  [[ -f "$work/c/$killed.h5" ]] && fail "$killed finished although its rank was killed"
  "$mpiexec" -np 2 "$raceway" campaign "$small" -o "$work/c" > "$work/log2" 2>&1 && fail "a second call without --resume was accepted"
  "$mpiexec" -np 2 "$raceway" campaign "$small" -o "$work/c" --resume > "$work/log3" 2>&1 || fail "resume: $(tail -3 "$work/log3")"
  grep -q "resuming" "$work/log3" || true
  "$python" "$source_dir/tests/system/parallel/compare_outputs.py" "$work/ref/$killed.h5" "$work/c/$killed.h5" \
    || fail "$killed resumed differs from the uninterrupted run"
  check_table "$work/c"
  echo "killed $killed on rank 1"
  ;;
retry)
  "$mpiexec" -np 2 "$raceway" campaign "$source_dir/tests/system/campaign/failing_campaign.toml" -o "$work/c" > "$work/log" 2>&1 \
    && fail "a campaign with a failing scene exited 0"
  grep -q "s001 failed, retried once" "$work/log" || fail "no retry: $(cat "$work/log")"
  grep -q "s001 failed twice" "$work/log" || fail "not recorded as failed twice"
  [[ -f "$work/c/campaign_table.csv" ]] || fail "the campaign wrote no table: $(tail -3 "$work/log")"
  "$python" - "$work/c" <<'PY' || fail "failed scene not in the table with its diagnosis"
import csv, sys
rows = {r["scene"]: r for r in csv.DictReader(open(f"{sys.argv[1]}/campaign_table.csv"))}
assert rows["s000"]["status"] == "done", rows["s000"]
assert rows["s001"]["status"] == "failed" and rows["s001"]["attempts"] == "2", rows["s001"]
assert "max_wall_time" in rows["s001"]["diagnosis"] or "wall" in rows["s001"]["diagnosis"], rows["s001"]["diagnosis"]
PY
  ;;
bad_files)
  bad() {  # NAME EXPECTED-TEXT: the campaign file text on stdin
    cat > "$work/$1.toml"
    "$raceway" campaign "$work/$1.toml" -o "$work/out_$1" > "$work/$1.log" 2>&1
    local rc=$?
    [[ $rc == 2 ]] || fail "$1: exit $rc, expected 2"
    grep -q -- "$2" "$work/$1.log" || fail "$1: expected '$2', got: $(cat "$work/$1.log")"
    [[ -e "$work/out_$1" ]] && fail "$1: output folder created"
  }
  head='[campaign]
scene = "'$source_dir'/jobs/scenes/default.toml"
end_time = "10 ms"'
  bad unknown_axis_key "$work/unknown_axis_key.toml:6: key 'axis\[0\].valeus': unknown key 'valeus'" <<EOF
$head
[[axis]]
key = "inner_ring.speed"
valeus = ["1 rpm"]
EOF
  bad empty_axis "$work/empty_axis.toml:4: key 'axis\[0\].values': the axis has no values" <<EOF
$head
[[axis]]
key = "inner_ring.speed"
values = []
EOF
  bad rejected_value "$work/rejected_value.toml:8: key 'axis\[0\].values': scene s001 (-5 mm) is rejected" <<EOF
$head
[[axis]]
key = "bearing.roller_diameter"
values = [
  "6 mm",
  "-5 mm",
]
EOF
  "$raceway" check --set inner_ring.speed=fast > "$work/o.log" 2>&1; rc=$?
  [[ $rc == 2 ]] || fail "--set bad value: exit $rc"
  grep -q -- "--set inner_ring.speed=fast: key 'inner_ring.speed'" "$work/o.log" || fail "override not named: $(cat "$work/o.log")"
  "$raceway" check --set bearing.no_such_key=1 > "$work/o.log" 2>&1 && fail "unknown override key accepted"
  grep -q "unknown key 'no_such_key' in \[bearing\]" "$work/o.log" || fail "unknown override key: $(cat "$work/o.log")"
  ;;
plan)
  "$mpiexec" -np 2 "$raceway" campaign "$source_dir/tests/system/campaign/ranks_campaign.toml" -o "$work/c" > "$work/log" 2>&1 \
    || fail "campaign: $(tail -5 "$work/log")"
  speedup2=$(awk -F, '$1 == "6309_R3" && $2 == "here" && $3 == 2 {printf "%.2f", $5}' "$source_dir/data/rank_table.csv")
  [[ -n $speedup2 ]] || fail "no 6309_R3 prediction for 2 ranks in data/rank_table.csv"
  grep -q "2 ranks per scene: 1 groups, speed-up $speedup2 " "$work/log" || fail "no speed-up $speedup2 line: $(cat "$work/log")"
  if awk -v s="$speedup2" 'BEGIN {exit !(s > 1)}'; then
    grep -q "chosen: 2 ranks per scene" "$work/log" || fail "not 2 ranks per scene (speed-up $speedup2): $(cat "$work/log")"
    grep -q "2 ranks in 1 groups of 2" "$work/log" || fail "not run on 1 group of 2: $(cat "$work/log")"
  else
    grep -q "chosen: 1 ranks per scene" "$work/log" || fail "not 1 rank per scene (speed-up $speedup2): $(cat "$work/log")"
  fi
  grep -q "^s000,.*,done," "$work/c/campaign_table.csv" || fail "no table row: $(cat "$work/c/campaign_table.csv")"
  "$raceway" campaign check "$source_dir/jobs/campaigns/qj215_speed.toml" --ranks 8 > "$work/check8.log" 2>&1 || fail "check --ranks 8"
  grep -q "chosen: 1 ranks per scene" "$work/check8.log" || fail "8 scenes on 8 ranks: $(cat "$work/check8.log")"
  sed 's/range = \[1000, 8000, 1000\]/range = [1000, 2000, 1000]/; s|"\.\./scenes|"'"$source_dir"'/jobs/scenes|' \
    "$source_dir/jobs/campaigns/qj215_speed.toml" > "$work/two.toml"
  "$raceway" campaign check "$work/two.toml" --ranks 8 > "$work/check2.log" 2>&1 || fail "check two scenes"
  grep -q "chosen: 4 ranks per scene" "$work/check2.log" || fail "2 scenes on 8 ranks: $(cat "$work/check2.log")"
  "$raceway" campaign "$small" -o "$work/only" --only 9 > "$work/only.log" 2>&1; rc=$?
  [[ $rc == 2 ]] || fail "--only 9: exit $rc, expected 2"
  grep -q -- "--only 9: no such scene" "$work/only.log" || fail "--only 9: $(cat "$work/only.log")"
  [[ -e "$work/only" ]] && fail "--only 9 created the output folder"
  ;;
slurm_array)
  # The one-allocation campaign's table, the reference.
  "$mpiexec" -np 2 "$raceway" campaign "$small" -o "$work/ref" > "$work/ref.log" 2>&1 || fail "reference campaign"
  # A stub sbatch: records its arguments, answers job ids 1001, 1002, ... as --parsable does.
  printf '#!/bin/bash\nn=$(( $(wc -l < %q/sbatch_args 2> /dev/null || echo 0) + 1001 ))\necho "$n $*" >> %q/sbatch_args\necho "$n;cluster"\n' \
    "$work" "$work" > "$work/sbatch"
  chmod +x "$work/sbatch"
  script=$source_dir/jobs/campaigns/slurm_array.sh
  export RACEWAY=$raceway SBATCH=$work/sbatch SLURM_SUBMIT_DIR=$work RACEWAY_SBATCH_OPTIONS="--ntasks=1 --time=1:00:00"
  bash "$script" "$small" "$work/c" > "$work/submit.log" 2>&1 || fail "submit: $(cat "$work/submit.log")"
  expect_args() {  # LINE EXPECTED: line LINE of the stub's record
    [[ "$(sed -n "$1p" "$work/sbatch_args")" == "$2" ]] || fail "sbatch call $1: '$(sed -n "$1p" "$work/sbatch_args")', expected '$2'"
  }
  expect_args 1 "1001 --parsable --array=0-3 --ntasks=1 --time=1:00:00 --export=ALL,RACEWAY_ARRAY_STEP=task,RACEWAY_SLURM_SCRIPT=$script $script $small $work/c"
  expect_args 2 "1002 --parsable --dependency=afterany:1001 --ntasks=1 --time=1:00:00 --nodes=1 --ntasks=1 --job-name=raceway-array-report --export=ALL,RACEWAY_ARRAY_STEP=report,RACEWAY_JOB_NUMBER=1,RACEWAY_SLURM_SCRIPT=$script $script $small $work/c"
  # The array tasks, as Slurm would start them (one rank each, s003 on 2).
  task() {  # INDEX LAUNCHER; exec: a task started with & is the script's own process (signals reach it)
    exec env SLURM_ARRAY_JOB_ID=1001 SLURM_ARRAY_TASK_ID="$1" SLURM_JOB_ID=$((2000 + $1)) RACEWAY_ARRAY_STEP=task \
      RACEWAY_LAUNCHER="$2" RACEWAY_SLURM_SCRIPT="$script" bash "$script" "$small" "$work/c"
  }
  wait_for_checkpoint() {  # ID
    for _ in $(seq 1 600); do [[ -f "$work/c/$1.h5.checkpoint" && ! -f "$work/c/$1.h5" ]] && return 0; sleep 0.05; done
    fail "$1: no checkpoint to interrupt"
  }
  task 0 "" > "$work/t0.log" 2>&1 &
  t0=$!
  task 1 "" > "$work/t1.log" 2>&1 &
  t1=$!
  wait_for_checkpoint s001
  kill -KILL "$(pgrep -P $t1)"  # the scene's process: a hard time limit or a lost node
  wait $t1 && fail "task 1 survived SIGKILL"
  wait $t0 || fail "task 0: $(tail -3 "$work/t0.log")"
  task 2 "" > "$work/t2.log" 2>&1 &
  t2=$!
  wait_for_checkpoint s002
  kill -USR1 $t2
  wait $t2; rc=$?
  [[ $rc == 4 ]] || fail "task 2 after SIGUSR1: exit $rc, expected 4: $(tail -3 "$work/t2.log")"
  grep -q '"exit_code": 4' "$work/c/campaign_status_s002_0.json" || fail "s002's record: $(cat "$work/c/"campaign_status_*)"
  (task 3 "$mpiexec -np 2") > "$work/t3.log" 2>&1 || fail "task 3: $(tail -3 "$work/t3.log")"
  [[ -f "$work/c/campaign_table.csv" ]] && fail "an array task wrote the table"
  # The aggregation step: s001 (killed) and s002 (stopped) again, with a new aggregation step.
  RACEWAY_ARRAY_STEP=report RACEWAY_SLURM_SCRIPT=$script bash "$script" "$small" "$work/c" > "$work/r1.log" 2>&1 \
    || fail "aggregation 1: $(cat "$work/r1.log")"
  expect_args 3 "1003 --parsable --array=1,2 --ntasks=1 --time=1:00:00 --export=ALL,RACEWAY_ARRAY_STEP=task,RACEWAY_SLURM_SCRIPT=$script $script $small $work/c"
  expect_args 4 "1004 --parsable --dependency=afterany:1003 --ntasks=1 --time=1:00:00 --nodes=1 --ntasks=1 --job-name=raceway-array-report --export=ALL,RACEWAY_ARRAY_STEP=report,RACEWAY_JOB_NUMBER=2,RACEWAY_SLURM_SCRIPT=$script $script $small $work/c"
  [[ -f "$work/c/campaign_table.csv" ]] && fail "a table with scenes left"
  [[ -f "$work/c/s001.h5.checkpoint" ]] || fail "s001: no checkpoint to resume from"
  (task 1 "") > "$work/t1b.log" 2>&1 || fail "task 1 again: $(tail -3 "$work/t1b.log")"
  (task 2 "") > "$work/t2b.log" 2>&1 || fail "task 2 again: $(tail -3 "$work/t2b.log")"
  RACEWAY_ARRAY_STEP=report RACEWAY_JOB_NUMBER=2 RACEWAY_SLURM_SCRIPT=$script bash "$script" "$small" "$work/c" \
    > "$work/r2.log" 2>&1 || fail "aggregation 2: $(cat "$work/r2.log")"
  [[ $(wc -l < "$work/sbatch_args") == 4 ]] || fail "a finished campaign was submitted again"
  "$python" "$source_dir/tests/system/parallel/compare_outputs.py" "$work/ref/s001.h5" "$work/c/s001.h5" > /dev/null \
    || fail "s001 killed and resumed differs from the one-allocation run"
  check_table "$work/c"
  # The same table as the one allocation's: every column but the wall time. Not s002: stopped by
  # SIGUSR1, it resumed from a checkpoint written at the signal, which is not on the uninterrupted
  # run's step sequence; the cage's motion then drifts apart (its metrics by 10-30 % here), so that
  # scene is only checked against its own file (check_table above).
  "$python" - "$work/ref/campaign_table.csv" "$work/c/campaign_table.csv" <<'PY' || fail "the array's table differs"
import csv, sys
ref, got = (list(csv.DictReader(open(p))) for p in sys.argv[1:])
assert [r["scene"] for r in ref] == [r["scene"] for r in got]
assert list(ref[0]) == list(got[0]), (list(ref[0]), list(got[0]))
bad = 0
for a, b in zip(ref, got):
    for k in a:
        if k == "wall_time_s" or a[k] == b[k] or a["scene"] == "s002":
            continue
        print(f"{a['scene']} {k}: one allocation {a[k]}, array {b[k]}"); bad += 1
sys.exit(1 if bad else 0)
PY
  # A scene that fails twice (its wall-clock budget) is recorded and not submitted again; the
  # aggregation step writes the table with it and exits 1.
  failing=$source_dir/tests/system/campaign/failing_campaign.toml
  for i in 0 1; do
    (exec env SLURM_ARRAY_TASK_ID=$i RACEWAY_ARRAY_STEP=task RACEWAY_LAUNCHER="" bash "$script" "$failing" "$work/f") \
      > "$work/f$i.log" 2>&1
  done
  RACEWAY_ARRAY_STEP=report RACEWAY_SLURM_SCRIPT=$script bash "$script" "$failing" "$work/f" > "$work/rf.log" 2>&1 \
    && fail "aggregation with a failed scene exited 0"
  [[ $(wc -l < "$work/sbatch_args") == 4 ]] || fail "a failed scene was submitted again"
  grep -q "(1 failed, 0 not finished)" "$work/rf.log" || fail "aggregation: $(cat "$work/rf.log")"
  grep -q "^s001,.*,failed,2," "$work/f/campaign_table.csv" || fail "failed scene: $(cat "$work/f/campaign_table.csv")"
  ;;
overrides)
  "$raceway" run --set scene.end_time="20 ms" --set 'inner_ring.speed="2000 rpm"' -o "$work/o.h5" \
    --summary-json "$work/o.json" > "$work/log" 2>&1 || fail "run with --set"
  grep -q -- "--set inner_ring.speed=\"2000 rpm\"" "$work/log" || fail "override not in the log"
  "$python" - "$work/o.json" "$work/o.h5" <<'PY' || fail "summary"
import json, math, sys, h5py
j = json.load(open(sys.argv[1]))
assert j["scene_overrides"] == {"scene.end_time": "20 ms", "inner_ring.speed": "\"2000 rpm\""}, j["scene_overrides"]
p = j["scene_parameters"]
assert abs(p["inner_ring.speed"]["value"] - 2000 * 2 * math.pi / 60) < 1e-12 and p["inner_ring.speed"]["unit"] == "rad/s"
assert p["scene.end_time"] == {"value": 0.02, "unit": "s"}, p["scene.end_time"]
assert p["bearing.pitch_diameter"] == {"value": 0.03, "unit": "m"}, p["bearing.pitch_diameter"]  # the file's value
assert h5py.File(sys.argv[2]).attrs["scene_overrides"].count("\n") == 2
PY
  "$raceway" run --set scene.end_time="2 s" --set output.checkpoint_interval="5 ms" -o "$work/r.h5" > /dev/null 2>&1 &
  pid=$!
  for _ in $(seq 1 400); do [[ -f "$work/r.h5.checkpoint" ]] && break; sleep 0.05; done
  kill -KILL $pid; wait $pid 2> /dev/null
  "$raceway" run --set scene.end_time="2 s" --set output.checkpoint_interval="10 ms" -o "$work/r.h5" --resume \
    > "$work/r.log" 2>&1; rc=$?
  [[ $rc == 2 ]] || fail "resume with other overrides: exit $rc"
  grep -q "checkpoint_interval=5 ms', now '# --set output.checkpoint_interval=10 ms'" "$work/r.log" \
    || fail "refusal does not name the override: $(cat "$work/r.log")"
  ;;
spatial)
  # A spatial campaign: its rows carry `raceway report`'s metrics over the same window, and only the
  # metrics the campaign file asks for.
  "$mpiexec" -np 2 "$raceway" campaign "$source_dir/tests/system/campaign/spatial_campaign.toml" -o "$work/c" \
    > "$work/log" 2>&1 || fail "spatial campaign: $(tail -3 "$work/log")"
  settling=$("$python" -c "import json,sys; print(repr(json.load(open(sys.argv[1]))['scenes']['s001']['settling_time_s']))" "$work/c/campaign.json")
  "$raceway" report "$work/c/s001.h5" -o "$work/r" --no-plots --window-start "$settling" > /dev/null 2>&1 || fail "report"
  "$python" - "$work/c" "$work/r/summary.json" <<'PY' || fail "spatial table"
import csv, json, sys
rows = {r["scene"]: r for r in csv.DictReader(open(f"{sys.argv[1]}/campaign_table.csv"))}
report = json.load(open(sys.argv[2]))
row = rows["s001"]
assert float(row["power_loss_w"]) == report["power_loss"]["total_mean_w"] > 0, (row["power_loss_w"], report["power_loss"])
assert float(row["pocket_force_rms_n"]) == report["pocket_forces"]["rms_circumferential_force_n"]
import math
same = lambda text, value: float(text) == value if text else value is None or math.isnan(value)  # NaN: empty, null
for key in ("vortex_radius_ratio", "sigma_v", "whirl_frequency_hz"):
    assert same(row[key], report["cage_centroid"][key]), (key, row[key], report["cage_centroid"][key])
# Impacts: the report's contact events on the front and rear bars in the window, per revolution of
# the inner ring (a quarter revolution here at constant speed).
assert abs(float(row["window_revolutions"]) - 0.25) < 1e-6, row["window_revolutions"]
for bar in ("front", "rear"):
    events = report["pocket_forces"][bar]["events"]
    assert float(row[f"impacts_{bar}_per_rev"]) == events / float(row["window_revolutions"]), (bar, row, events)
    assert float(row[f"pocket_force_{bar}_peak_n"]) == report["pocket_forces"][bar]["peak_n"]
assert "cage_speed_rpm" in row and "steps" in row and "cage_slip" not in row and "wall_time_s" not in row, list(row)
PY
  ;;
early_signal)
  # SIGUSR1 at the first moment raceway can take it (its first act in main blocks it), long before
  # MPI, the scene and the run are ready: Slurm may send it within a second of a job's start. A run
  # (1 and 2 ranks) and a campaign stop cleanly (exit 4, not 138, a death by the signal) and resume.
  # LOG PIDS_OF N COMMAND...: runs the command, sends SIGUSR1 to the N processes `PIDS_OF JOB_PID`
  # names as soon as every one of them blocks it (10: bit 9 of SigBlk); rc = the command's exit code.
  usr1_at_start() {
    local log=$1 pids_of=$2 n=$3 pids p key value ready job
    shift 3
    "$@" > "$log" 2>&1 &
    job=$!
    for _ in $(seq 1 20000); do
      pids=$($pids_of "$job") ready=0
      for p in $pids; do
        key="" value=0
        { while read -r key value; do [[ $key == SigBlk: ]] && break; done < "/proc/$p/status"; } 2> /dev/null
        [[ $key == SigBlk: ]] && (( 0x$value & 0x200 )) && ready=$((ready + 1))
      done
      (( ready == n )) && break
      kill -0 "$job" 2> /dev/null || break
    done
    (( ready == n )) || fail "$*: never blocked SIGUSR1"
    # shellcheck disable=SC2086  # pids
    kill -USR1 $pids
    wait "$job"
    rc=$?
  }
  self() { echo "$1"; }
  ranks() { rank_pid "$1" 0; rank_pid "$1" 1; }
  short='scene.end_time=20 ms'
  usr1_at_start "$work/run1.log" self 1 "$raceway" run --set "$short" -o "$work/r1.h5"
  [[ $rc == 4 ]] || fail "run, SIGUSR1 at once: exit $rc, expected 4: $(tail -3 "$work/run1.log")"
  grep -q "stopped by signal 10" "$work/run1.log" || fail "run: no stop message: $(tail -3 "$work/run1.log")"
  "$raceway" run --set "$short" -o "$work/r1.h5" --resume > "$work/run1b.log" 2>&1 || fail "run --resume: $(tail -3 "$work/run1b.log")"
  usr1_at_start "$work/run2.log" ranks 2 "$mpiexec" -np 2 "$raceway" run --set "$short" -o "$work/r2.h5"
  [[ $rc == 4 ]] || fail "run on 2 ranks, SIGUSR1 at once to both: exit $rc, expected 4: $(tail -3 "$work/run2.log")"
  "$mpiexec" -np 2 "$raceway" run --set "$short" -o "$work/r2.h5" --resume > "$work/run2b.log" 2>&1 \
    || fail "run on 2 ranks --resume: $(tail -3 "$work/run2b.log")"
  "$python" "$source_dir/tests/system/parallel/compare_outputs.py" "$work/r1.h5" "$work/r2.h5" > /dev/null \
    || fail "the two runs stopped at once and resumed differ"
  usr1_at_start "$work/c.log" self 1 "$raceway" campaign "$small" -o "$work/c"
  [[ $rc == 4 ]] || fail "campaign, SIGUSR1 at once: exit $rc, expected 4: $(tail -3 "$work/c.log")"
  grep -q "campaign stopped by a signal" "$work/c.log" || fail "campaign: no stop message: $(tail -3 "$work/c.log")"
  ;;
refused_resume)
  tiny_campaign "$work/a.toml" tiny "2000 rpm"
  "$raceway" campaign "$work/a.toml" -o "$work/c" > "$work/a.log" 2>&1 || fail "campaign: $(tail -3 "$work/a.log")"
  [[ -f "$work/c/campaign_table.csv" && -f "$work/c/campaign_identity.txt" ]] || fail "no table or identity: $(ls "$work/c")"
  listing() { (cd "$work/c" && find . -type f -printf '%p %s %T@\n' | sort); }
  before=$(listing)
  # The same file with one swept value edited: refused, naming the value's line and the difference.
  tiny_campaign "$work/a.toml" tiny "3000 rpm"
  "$raceway" campaign "$work/a.toml" -o "$work/c" --resume > "$work/edit.log" 2>&1; rc=$?
  [[ $rc == 2 ]] || fail "edited campaign resumed: exit $rc: $(cat "$work/edit.log")"
  grep -q "a.toml:13: key 'axis\[0\].values': .* s001 --set inner_ring.speed: '3000 rpm' here, '2000 rpm' in the folder" \
    "$work/edit.log" || fail "edited campaign: $(cat "$work/edit.log")"
  # Another campaign's file: refused, its name the first difference.
  tiny_campaign "$work/b.toml" other "2000 rpm"
  "$raceway" campaign "$work/b.toml" -o "$work/c" --resume > "$work/other.log" 2>&1; rc=$?
  [[ $rc == 2 ]] || fail "another campaign resumed: exit $rc"
  grep -q "b.toml:2: key 'campaign.name': .*campaign.name: 'other' here, 'tiny' in the folder" "$work/other.log" \
    || fail "another campaign: $(cat "$work/other.log")"
  "$raceway" campaign "$work/b.toml" -o "$work/c" > "$work/other2.log" 2>&1 && fail "another campaign without --resume accepted"
  [[ "$(listing)" == "$before" ]] || fail "a refused call changed the folder: $(diff <(echo "$before") <(listing))"
  # The file it began with: nothing left to run, the table again.
  tiny_campaign "$work/a.toml" tiny "2000 rpm"
  "$raceway" campaign "$work/a.toml" -o "$work/c" --resume > "$work/same.log" 2>&1 || fail "same campaign: $(tail -3 "$work/same.log")"
  grep -q "2 scenes, 2 finished, 0 to run" "$work/same.log" || fail "same campaign: $(cat "$work/same.log")"
  ;;
check_fuzz)
  "$python" - "$raceway" "$small" "$source_dir" "$work" <<'PY' || fail "fuzz"
import concurrent.futures, random, re, subprocess, sys
raceway, small, source, work = sys.argv[1:]
lines = open(small).read().replace('"../../../jobs', f'"{source}/jobs').splitlines()
# The mistakes users found, then random ones: a line dropped, doubled, swapped or given an extreme value.
found = ["range = [1000, inf, 500]", "range = [-inf, 1000, 500]", "range = [1, 1e9, 1]", "settling_revolutions = -0.5",
         "ranks_per_scene = 1e10", "ranks_per_scene = 0.5", "samples_per_revolution = 1e12"]
extremes = ["inf", "-inf", "nan", "0", "-1", "1e9", "1e308", "0.5", "\"\"", "\"x\"", "[]", "{}", "true", "[1, inf, 1]",
            "\"inner_ring.speed\"", "[1e300, 1e301, 1]"]
rng = random.Random(20261127)
cases = []
for f in found:
    key = f.split(" = ")[0]
    cases.append([f if l.startswith(key + " =") else l for l in lines])
for _ in range(30):
    m = list(lines)
    for _ in range(rng.randint(1, 3)):
        i, j = rng.randrange(len(m)), rng.randrange(len(m))
        op = rng.randrange(4)
        if op == 0: del m[i]
        elif op == 1: m.insert(i, m[j])
        elif op == 2: m[i], m[j] = m[j], m[i]
        elif " = " in m[i]: m[i] = m[i].split(" = ")[0] + " = " + rng.choice(extremes)
    cases.append(m)
def check(n, m):  # (exit code, output) of `campaign check`, or None when it did not answer
    path = f"{work}/fuzz{n}.toml"
    open(path, "w").write("\n".join(m) + "\n")
    try:
        p = subprocess.run([raceway, "campaign", "check", path], capture_output=True, text=True, timeout=30)
    except subprocess.TimeoutExpired:
        return None
    return p.returncode, p.stdout + p.stderr
# Four at a time: a check costs little CPU, most of its wall time is MPI's start-up.
with concurrent.futures.ThreadPoolExecutor(4) as pool:
    answers = list(pool.map(check, range(len(cases)), cases))
bad = passed = refused = 0
for n, (m, answer) in enumerate(zip(cases, answers)):
    path = f"{work}/fuzz{n}.toml"
    if answer is None:
        print(f"{path}: no answer within 30 s:\n" + "\n".join(m)); bad += 1; continue
    rc, out = answer
    if rc == 0 and "campaign OK" in out:
        passed += 1
    elif rc == 2 and re.search(r"\.toml:\d+: ", out):
        refused += 1
    else:
        print(f"{path}: exit {rc}: {out[-500:]}\n" + "\n".join(m)); bad += 1
    if n < len(found) and rc != 2:
        print(f"{path}: a mistake users found was accepted:\n" + "\n".join(m)); bad += 1
print(f"{len(cases)} campaign files: {passed} passed check, {refused} refused with exit 2")
sys.exit(1 if bad or passed == 0 else 0)
PY
  ;;
table_signal)
  # s001 cannot finish within its wall-clock budget (exit 3), so it is retried and fails.
  cat > "$work/t.toml" <<EOF
[campaign]
scene = "$source_dir/jobs/scenes/default.toml"
sweep = "zip"
end_time = "4 ms"
settling_time = "2 ms"
ranks_per_scene = 1
[[axis]]
key = "inner_ring.speed"
name = "speed"
values = ["1000 rpm", "1500 rpm"]
[[axis]]
key = "solver.max_wall_time"
name = "budget"
values = ["10 min", "1 us"]
EOF
  "$mpiexec" -np 2 "$raceway" campaign "$work/t.toml" -o "$work/c" > "$work/log" 2>&1 &
  mpirun_pid=$!
  table_pid=""
  for _ in $(seq 1 3000); do
    rank0=$(rank_pid $mpirun_pid 0)
    for p in $( [[ -n $rank0 ]] && pgrep -P "$rank0"); do
      # The table's process, once it ignores SIGUSR1 (its first line): signal 10, bit 9 of SigIgn.
      grep -q campaign_table /proc/$p/cmdline 2> /dev/null || continue
      (( 0x$(sed -n 's/^SigIgn:\t//p' /proc/$p/status 2> /dev/null || echo 0) & 0x200 )) && table_pid=$p
    done
    [[ -n $table_pid ]] && break
    sleep 0.01
  done
  [[ -n $table_pid ]] || fail "the table's process was never seen"
  # What a batch system's warning does: every process of the job gets SIGUSR1.
  kill -USR1 $mpirun_pid "$table_pid" 2> /dev/null
  wait $mpirun_pid; rc=$?
  [[ $rc == 1 ]] || fail "a campaign with a failed scene: exit $rc: $(tail -5 "$work/log")"
  grep -q "s001 failed twice" "$work/log" || fail "s001 not retried: $(cat "$work/log")"
  grep -q "the table of .* failed" "$work/log" && fail "the table failed: $(cat "$work/log")"
  grep -q "^s000,.*,done," "$work/c/campaign_table.csv" || fail "s000: $(cat "$work/c/campaign_table.csv")"
  grep -q "^s001,.*,failed,2,.*wall" "$work/c/campaign_table.csv" || fail "s001: $(cat "$work/c/campaign_table.csv")"
  # A failure that the same input repeats (exit 2: the scene's output lock cannot be made) is not retried.
  tiny_campaign "$work/d.toml" deterministic "2000 rpm"
  mkdir -p "$work/d/s001.h5.lock"
  "$mpiexec" -np 2 "$raceway" campaign "$work/d.toml" -o "$work/d" > "$work/d.log" 2>&1 && fail "a failed scene: exit 0"
  grep -q "s001 failed, not retried" "$work/d.log" || fail "deterministic failure: $(cat "$work/d.log")"
  grep -q "retried once" "$work/d.log" && fail "a deterministic failure was retried"
  grep -q "^s001,.*,failed,1," "$work/d/campaign_table.csv" || fail "s001: $(cat "$work/d/campaign_table.csv")"
  ;;
*) fail "unknown case $case_name" ;;
esac
finish
