#!/usr/bin/env bash
# Tests of `mpirun -np P raceway run` (scheduler/mpi_executor.hpp), one case per ctest:
#
#   parallel_test.sh CASE RACEWAY MPIEXEC SOURCE_DIR
#
#   bitwise_planar, bitwise_spatial: every output dataset bitwise identical for np = 1, 2, 3, 4
#     (3 and 4 oversubscribed: correctness, not speed) and with a new plan before every evaluation
#     (--replan-every-step), and with rank 0 evaluating no tasks (--master-share 0), on a short
#     seed 002 run and a short 6309 R3 run; /scheduler and timing
#     fields of the summary are left out (tests/system/parallel/compare_outputs.py).
#     Also with tasks claimed on demand (--tail-share): every task (1) at np 2, 30 % with forced
#     re-plans at np 3, every task by the workers alone (--master-share 0) at np 3. And with the
#     commands and replies by message instead of shared memory (--exchange messages) at np 4 and np 3.
#   bitwise_spatial_roller: the same on seed 002 in space with its rollers' diameters scattered and a
#     spall on roller 0 (the rollers' angles about their axes are states); and killed at np 2 after a
#     checkpoint, resumed at np 1: bitwise the np 1 run.
#   bitwise_cut: the same on a short run of the high-fidelity scene (6309_R3_fine_traction: its
#     ball-race contacts cut into traction-grid blocks, sub-tasks the master combines), where the
#     plans really cut segments over ranks (checked in the plan log lines).
#   worker_failure, master_failure: an exception inside a task on rank 1 (or 0) at evaluation 30
#     (test-only --inject-failure): the job ends within the timeout, non-zero, with the rank's
#     message.
#   integration_failure: rank 0's integration fails (step budget 50): exit 3, the workers leave too.
#   stopped_worker: rank 1 is stopped (SIGSTOP) mid-run; rank 0's bounded waits (--rank-timeout 3)
#     end the job naming rank 1 (exit 1) within seconds, and no rank is left behind.
#   stopped_worker_messages: the same with commands and replies by message (--exchange messages).
#   stopped_master: rank 0 is stopped (SIGSTOP) mid-run; rank 1, waiting for its next command, sees
#     rank 0's heartbeat stop and ends the job (--rank-timeout 3) naming rank 0, non-zero, within
#     seconds, and no rank is left behind (the stopped one included).
#   stopped_master_messages: the same with commands by broadcast (--exchange messages).
#   busy_master: rank 0 works 6 s between two commands (test-only --inject-pause) with
#     --rank-timeout 2: a live rank 0 keeps beating, the workers wait, the run ends with exit 0.
#   busy_master_messages: the same with commands by broadcast.
#   bad_option: a non-finite option value (--master-share nan) at 2 ranks: exit 2, one message.
#   output_disk_full: the parallel output (--parallel-output: each rank writes the segment diagnostics it evaluated,
#     MPI-IO): rank 1, which evaluates every segment (--master-share 0), can write no more (its
#     file-size limit lowered with prlimit) when the output is written: exit 1 (no hang), the
#     failure (rank, file, system's reason) said by rank 0 and by rank 1, no crash.
#   killed_worker: rank 1 is killed (SIGKILL) mid-run, holding rows of the parallel output: the job
#     ends (non-zero, no hang) and no rank is left behind.
set -u
case_name=${1:?case}
raceway=${2:?raceway}
mpiexec=${3:?mpiexec}
source_dir=${4:?source dir}
compare=(/usr/bin/python3 "$source_dir/tests/system/parallel/compare_outputs.py")

source "$source_dir/tests/system/test_lib.sh"
# mpirun NP ARGS...: raceway under mpirun, output in $work/log.NP; sets $rc.
mpi() {
  local np=$1
  shift
  timeout 300 "$mpiexec" --oversubscribe -np "$np" "$raceway" "$@" >"$work/log" 2>&1
  rc=$?
}

# Short scenes from the job files (the physics of the full runs, fewer revolutions).
sed -e 's/^end_time = .*/end_time = "6 ms"/' "$source_dir/jobs/scenes/seed002_40hz.toml" >"$work/planar.toml"
# The spatial scene with its balls' diameters and its pockets' clearances scattered (drawn from a
# seed while the scene is read: the same on every rank).
sed -e 's/^end_time = .*/end_time = "3 ms"/' -e 's/^\[bearing\]$/[bearing]\nball_diameter_scatter = "1 um"\nscatter_seed = 11/' \
  -e 's/^\[cage\]$/[cage]\npocket_clearance_scatter = "5 um"/' \
  "$source_dir/jobs/scenes/6309_R3.toml" >"$work/spatial.toml"
sed -e 's/^end_time = .*/end_time = "2 ms"/' "$source_dir/jobs/scenes/6309_R3_fine_traction.toml" >"$work/cut.toml"
# The spatial roller bearing: seed 002 in space (its race contacts in slices, one task each), its
# rollers' diameters scattered and a spall on roller 0 (every roller's angle about its axis a state),
# 10 degrees ahead of its outer race contact at the start (it strikes it at about 0.3 ms), and a
# checkpoint every 1 ms (the kill and resume below). It keeps the planar scene's former solver (rtol
# 1e-5, no pocket factor): the orbital frame is the planar rollers' and the balls'.
sed -e 's/^end_time = .*/end_time = "2 ms"/' -e 's/^model = "planar"/model = "spatial"/' \
  -e 's/^\[bearing\]$/[bearing]\nroller_diameter_scatter = "1 um"\nscatter_seed = 5/' \
  -e 's/^rtol = 2e-5$/rtol = 1e-5/' -e '/^element_velocity_frame = /d' -e '/^pocket_tolerance_/d' \
  "$source_dir/jobs/scenes/seed002_40hz.toml" >"$work/spatial_roller.toml"
printf '[output]\ncheckpoint_interval = "1 ms"\n[rolling_element]\nspall = { element = 0, angle = "-80 deg", %s\n' \
  'length = "0.5 mm", width = "4 mm", depth = "0.1 mm" }' >>"$work/spatial_roller.toml"

bitwise() {
  local scene=$1
  "$raceway" run "$scene" -o "$work/np1.h5" >"$work/log" 2>&1 || { fail "np 1 run failed: $(tail -3 "$work/log")"; return; }
  local files=()
  for np in 2 3 4; do
    mpi "$np" run "$scene" -o "$work/np$np.h5" --parallel-output
    [[ $rc -eq 0 ]] || { fail "np $np: exit code $rc: $(tail -3 "$work/log")"; continue; }
    grep -q "contact tasks on all ranks" "$work/log" || fail "np $np: no parallel run announced"
    cp "$work/log" "$work/log.np$np"
    files+=("$work/np$np.h5")
  done
  for np in 2 3; do
    mpi "$np" run "$scene" -o "$work/forced$np.h5" --replan-every-step --parallel-output
    [[ $rc -eq 0 ]] || { fail "forced re-planning np $np: exit code $rc: $(tail -3 "$work/log")"; continue; }
    files+=("$work/forced$np.h5")
    # The plans must really have changed: at least one per evaluation.
    /usr/bin/python3 - "$work/forced$np.h5" <<'PY' || fail "np $np --replan-every-step: too few plans"
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    g = f["scheduler"]
    plans, evaluations = g["plans"].shape[0], g.attrs["evaluations_rhs"] + g.attrs["evaluations_jacobian"]
    print(f"{plans} plans for {evaluations} evaluations, ranks {g.attrs['ranks']}")
    sys.exit(0 if plans >= evaluations and g.attrs["ranks"] > 1 else 1)
PY
  done
  # Rank 0 writing the whole file (the default, no MPI-IO).
  mpi 2 run "$scene" -o "$work/serial2.h5"
  [[ $rc -eq 0 ]] && files+=("$work/serial2.h5") || fail "np 2, rank 0 writing: exit code $rc: $(tail -3 "$work/log")"
  # Tasks claimed on demand (--tail-share, scheduler/tail_claims.hpp): every task (share 1) at np 2,
  # with --parallel-output (a tail task's record is written by rank 0); 30 % of each rank's work
  # with a new plan (and tail) before every evaluation at np 3; every task claimed by the workers
  # alone (--master-share 0) at np 3.
  for run in "2 tail1 --tail-share 1 --parallel-output" "3 tailforced --tail-share 0.3 --replan-every-step" \
    "3 tailshare0 --tail-share 1 --master-share 0"; do
    set -- $run
    local np=$1 name=$2
    shift 2
    mpi "$np" run "$scene" -o "$work/$name.h5" "$@"
    [[ $rc -eq 0 ]] || { fail "np $np $*: exit code $rc: $(tail -3 "$work/log")"; continue; }
    grep -q "no tail shared" "$work/log" && fail "np $np $*: the tail was not shared"
    files+=("$work/$name.h5")
    # The workers evaluated tasks (with share 1 they have no fixed list: they claimed them); rank 0
    # did too, except with --master-share 0. (Which worker claims how many is a race: on a light
    # scene the first one to wake may take them all.)
    /usr/bin/python3 -c "import sys, h5py; s = h5py.File(sys.argv[1])['scheduler/rank_task_seconds'][()]; \
print('rank task seconds', list(s)); sys.exit(0 if sum(s[1:]) > 0 and (s[0] > 0) == (sys.argv[2] != 'tailshare0') else 1)" \
      "$work/$name.h5" "$name" || fail "np $np $*: no worker claimed tail tasks, or rank 0 did with --master-share 0"
  done
  # The workers' records by message instead of through shared memory (--exchange messages, as
  # between nodes): at np 4 (a reply tree two deep: rank 3 through rank 2), and at np 3 with a tail
  # and a new plan before every evaluation.
  for run in "4 messages4 --exchange messages --parallel-output" \
    "3 messagestail --exchange messages --tail-share 0.3 --replan-every-step"; do
    set -- $run
    local np=$1 name=$2
    shift 2
    mpi "$np" run "$scene" -o "$work/$name.h5" "$@"
    [[ $rc -eq 0 ]] && files+=("$work/$name.h5") || fail "np $np $*: exit code $rc: $(tail -3 "$work/log")"
  done
  # Rank 0 evaluating no tasks at all (--master-share 0), adaptive schedule.
  mpi 3 run "$scene" -o "$work/share0.h5" --master-share 0 --parallel-output
  if [[ $rc -eq 0 ]]; then
    files+=("$work/share0.h5")
    /usr/bin/python3 -c "import sys, h5py; sys.exit(0 if h5py.File(sys.argv[1])['scheduler/rank_task_seconds'][0] == 0 else 1)" \
      "$work/share0.h5" || fail "--master-share 0: rank 0 evaluated tasks"
  else
    fail "--master-share 0 np 3: exit code $rc: $(tail -3 "$work/log")"
  fi
  "${compare[@]}" "$work/np1.h5" "${files[@]}" || fail "outputs differ (see above)"
}

# killed_resumed SCENE: np 2, killed as soon as its first checkpoint is on disk (rank 0 pauses
# before its evaluation at 90 % of the np 2 run's, --inject-pause, so that the run cannot end
# first), resumed at np 1: the file bitwise the uninterrupted np 1 run's ($work/np1.h5 of bitwise).
killed_resumed() {
  local scene=$1 evaluations
  evaluations=$(/usr/bin/python3 -c "import sys, h5py; a = h5py.File(sys.argv[1])['scheduler'].attrs; \
print(int(0.9 * (a['evaluations_rhs'] + a['evaluations_jacobian'])))" "$work/np2.h5") ||
    { fail "no evaluation count in np2.h5"; return; }
  timeout 120 "$mpiexec" --oversubscribe -np 2 "$raceway" run "$scene" -o "$work/killed.h5" \
    --inject-pause "$evaluations:60" >"$work/log" 2>&1 &
  local job=$! launcher ranks
  for _ in $(seq 600); do [[ -e "$work/killed.h5.checkpoint" ]] && break; sleep 0.05; done
  launcher=$(pgrep -P "$job" | head -n 1)
  ranks=$(pgrep -P "$launcher" | tr '\n' ' ')
  kill -KILL $ranks "$launcher" 2>/dev/null
  wait "$job" 2>/dev/null
  for rank in $ranks; do for _ in $(seq 200); do kill -0 "$rank" 2>/dev/null || break; sleep 0.05; done; done
  [[ -e "$work/killed.h5.checkpoint" && ! -e "$work/killed.h5" ]] || { fail "the job was not killed after a checkpoint"; return; }
  "$raceway" run "$scene" -o "$work/killed.h5" --resume >"$work/log" 2>&1 || { fail "resume: $(tail -3 "$work/log")"; return; }
  grep -q "resuming .* from its" "$work/log" || fail "the run did not resume from the checkpoint: $(tail -3 "$work/log")"
  "${compare[@]}" "$work/np1.h5" "$work/killed.h5" || fail "killed at np 2 and resumed at np 1: outputs differ"
}

injected() {
  local rank=$1
  local start=$(date +%s)
  mpi 2 run "$work/spatial.toml" -o "$work/f.h5" --inject-failure "$rank:30"
  local elapsed=$(($(date +%s) - start))
  [[ $rc -ne 0 ]] || fail "exit code 0 after an injected failure on rank $rank"
  [[ $rc -ne 124 ]] || fail "the job hung (killed by timeout)"
  grep -q "rank $rank of 2: error: in a .* task at evaluation 30: injected failure" "$work/log" ||
    fail "no message from rank $rank: $(tail -5 "$work/log")"
  echo "rank $rank failure: exit $rc after $elapsed s"
  [[ $elapsed -le 60 ]] || fail "took $elapsed s to end"
}

# The raceway processes (ranks) of an mpirun started by this script: "PID RANK" lines.
ranks_of() {
  local child
  for child in $(pgrep -P "$1"); do
    [[ -r /proc/$child/environ ]] || continue
    echo "$child $(tr '\0' '\n' </proc/"$child"/environ | sed -n 's/^OMPI_COMM_WORLD_RANK=//p')"
  done
}

# The pid of rank $2 under the mpirun started as job $1 (empty if not found).
rank_pid() {
  local mpirun_pid victim=""
  mpirun_pid=$(pgrep -P "$1" -f "$mpiexec" | head -n 1)
  [[ -n "$mpirun_pid" ]] || mpirun_pid=$1
  while read -r pid rank; do [[ "$rank" == "$2" ]] && victim=$pid; done < <(ranks_of "$mpirun_pid")
  echo "$victim"
}

output_disk_full() {
  sed -e 's/^end_time = .*/end_time = "30 ms"/' "$source_dir/jobs/scenes/default.toml" >"$work/disk.toml"
  # At order 5 (not the automatic order's 2, 50 times fewer steps): the run lasts long enough to be
  # caught between its first progress line and its write.
  timeout 120 "$mpiexec" --oversubscribe -np 2 "$raceway" run "$work/disk.toml" -o "$work/d.h5" --master-share 0 --parallel-output \
    --set solver.automatic_order=false \
    >"$work/log" 2>&1 &
  local job=$!
  # The first progress line: the layout is on disk, the rows are in memory until the end.
  for _ in $(seq 400); do grep -q " s of " "$work/log" && break; sleep 0.05; done
  local victim size
  victim=$(rank_pid "$job" 1)
  [[ -n "$victim" ]] || { fail "rank 1 not found"; kill "$job"; wait "$job"; return; }
  size=$(stat -c %s "$work/d.h5.partial" 2>/dev/null || echo 0)
  prlimit --pid "$victim" --fsize=$((size + 4096)) || fail "prlimit failed"
  local start=$(date +%s)
  wait "$job"
  rc=$?
  local elapsed=$(($(date +%s) - start))
  echo "rank 1 limited to $((size + 4096)) bytes: exit $rc after $elapsed s"
  [[ $rc -eq 1 ]] || fail "exit code $rc, expected 1 (124: the job hung; 134, 139: a crash)"
  [[ $(grep -c "rank 1 of 2: writing the shared series of '.*d.h5.partial' failed: .*File too large" "$work/log") -ge 2 ]] ||
    fail "the failure is not said by both ranks with the rank, file, dataset and reason: $(tail -5 "$work/log")"
  grep -qiE "segmentation|signal 11|core dumped" "$work/log" && fail "crashed: $(tail -5 "$work/log")"
  [[ -e "$work/d.h5" ]] && fail "d.h5 written although a rank could not write"
}

# signal_worker SIGNAL OUT ARGS...: a 10 s run of the default scene on 2 ranks writing OUT (with
# ARGS), rank 1 sent SIGNAL a second after the integration starts; waits for the job and sets
# $rc, $elapsed (seconds from the signal to the end) and $victim (rank 1's pid; empty: not found).
signal_worker() {
  local signal=$1 out=$2 target=${target_rank:-1}
  shift 2
  sed -e 's/^end_time = .*/end_time = "10 s"/' "$source_dir/jobs/scenes/default.toml" >"$work/long.toml"
  timeout 120 "$mpiexec" --oversubscribe -np 2 "$raceway" run "$work/long.toml" -o "$out" "$@" >"$work/log" 2>&1 &
  local job=$!
  # Wait for the integration to start (the linear solver is announced just before).
  for _ in $(seq 100); do grep -q "Newton linear solver" "$work/log" && break; sleep 0.2; done
  sleep 1
  victim=$(rank_pid "$job" "$target")
  [[ -n "$victim" ]] || { fail "rank $target not found under the mpirun of job $job"; kill "$job"; wait "$job"; return; }
  local start=$(date +%s)
  kill -"$signal" "$victim"
  wait "$job"
  rc=$?
  elapsed=$(($(date +%s) - start))
  echo "rank $target (pid $victim) sent SIG$signal: exit $rc after $elapsed s"
}

# Rank 0 stopped: the workers' waits for it end the job (its heartbeat, scheduler/rank_watch.cpp).
stopped_master() {
  target_rank=0 signal_worker STOP "$work/m.h5" --rank-timeout 3 "$@"
  [[ -n "$victim" ]] || return
  [[ $rc -ne 0 && $rc -ne 124 ]] || fail "exit code $rc (0: a silent success; 124: the job hung): $(tail -5 "$work/log")"
  grep -q "rank 1 of 2: error: rank 0 sent nothing for 3 s and its heartbeat stopped (--rank-timeout)" "$work/log" ||
    fail "no message from rank 1 naming rank 0: $(tail -5 "$work/log")"
  [[ $elapsed -le 30 ]] || fail "took $elapsed s to end: $(tail -5 "$work/log")"
  # mpirun may return while the kill of the stopped rank is still under way: 5 s for it to go.
  for _ in $(seq 50); do
    [[ -e /proc/$victim ]] && ! grep -q '^State:.*Z' "/proc/$victim/status" 2>/dev/null || break
    sleep 0.1
  done
  if [[ -e /proc/$victim ]] && ! grep -q '^State:.*Z' "/proc/$victim/status" 2>/dev/null; then
    fail "the stopped rank 0 ($victim) is still alive 5 s after the job ended"
    kill -CONT "$victim"; kill -KILL "$victim"
  fi
  pgrep -f "$work/long.toml" >/dev/null && fail "a rank is left behind"
  [[ -e "$work/m.h5" ]] && fail "m.h5 written by a failed job"
}

# A live rank 0 busy for longer than the timeout between two commands is not a stalled one.
busy_master() {
  sed -e 's/^end_time = .*/end_time = "20 ms"/' "$source_dir/jobs/scenes/default.toml" >"$work/busy.toml"
  local start=$(date +%s)
  timeout 120 "$mpiexec" --oversubscribe -np 2 "$raceway" run "$work/busy.toml" -o "$work/b.h5" --rank-timeout 2 \
    --inject-pause 40:6 "$@" >"$work/log" 2>&1
  rc=$?
  local elapsed=$(($(date +%s) - start))
  echo "rank 0 paused 6 s before evaluation 40 (--rank-timeout 2): exit $rc after $elapsed s"
  [[ $rc -eq 0 ]] || fail "exit code $rc: a busy rank 0 was taken for a stalled one: $(tail -5 "$work/log")"
  [[ $elapsed -ge 6 ]] || fail "the pause did not happen ($elapsed s)"
  [[ -e "$work/b.h5" ]] || fail "no output"
}

stopped_worker() {
  signal_worker STOP "$work/s.h5" --rank-timeout 3 "$@"
  [[ -n "$victim" ]] || return
  [[ $rc -eq 1 ]] || fail "exit code $rc, expected 1 (124: the job hung): $(tail -5 "$work/log")"
  grep -q "rank 0 of 2: error: rank 1 did not answer .* within 3 s (--rank-timeout)" "$work/log" ||
    fail "no message naming rank 1: $(tail -5 "$work/log")"
  [[ $elapsed -le 30 ]] || fail "took $elapsed s to end: $(tail -5 "$work/log")"
  # No rank is left behind (a zombie, reaped with its parent, is gone).
  if [[ -e /proc/$victim ]] && ! grep -q '^State:.*Z' "/proc/$victim/status" 2>/dev/null; then
    fail "the stopped rank $victim is still alive"
    kill -CONT "$victim"; kill -KILL "$victim"
  fi
  [[ -e "$work/s.h5" ]] && fail "s.h5 written by a failed job"
}

# Rank 1 holds its segments' rows of every sample since the last write: the job must still end.
killed_worker() {
  signal_worker KILL "$work/k.h5" --parallel-output
  [[ -n "$victim" ]] || return
  [[ $rc -ne 0 && $rc -ne 124 ]] || fail "exit code $rc (0: a silent success; 124: the job hung)"
  [[ $elapsed -le 60 ]] || fail "took $elapsed s to end"
  pgrep -f "$work/long.toml" >/dev/null && fail "a rank is left behind"
  [[ -e "$work/k.h5" ]] && fail "k.h5 written by a failed job"
}

case "$case_name" in
stopped_master) stopped_master ;;
stopped_master_messages) stopped_master --exchange messages ;;
busy_master) busy_master ;;
busy_master_messages) busy_master --exchange messages ;;
output_disk_full) output_disk_full ;;
killed_worker) killed_worker ;;
bitwise_planar) bitwise "$work/planar.toml" ;;
bitwise_spatial)
  "$raceway" check "$work/spatial.toml" 2>&1 | grep -q "ball diameters (drawn" || fail "the scene's balls are not scattered"
  bitwise "$work/spatial.toml"
  ;;
bitwise_spatial_roller)
  "$raceway" check "$work/spatial_roller.toml" >"$work/check" 2>&1 || fail "check: $(tail -3 "$work/check")"
  grep -q "roller diameters (drawn" "$work/check" || fail "the scene's rollers are not scattered"
  grep -q "roller\[0\]: spall" "$work/check" || fail "the scene's roller 0 carries no spall"
  bitwise "$work/spatial_roller.toml"
  killed_resumed "$work/spatial_roller.toml"
  ;;
bitwise_cut)
  bitwise "$work/cut.toml"
  # Segments were really cut over ranks in some plan (the 13 blocks of a loaded contact).
  cat "$work"/log.np* | grep -qE "and [1-9][0-9]* segment\(s\) split" || fail "no plan cut a segment over ranks"
  ;;
worker_failure) injected 1 ;;
master_failure) injected 0 ;;
integration_failure)
  sed 's/^\[solver\]/[solver]\nmax_steps = 50/' "$source_dir/jobs/scenes/default.toml" >"$work/fails.toml"
  mpi 2 run "$work/fails.toml" -o "$work/f.h5"
  [[ $rc -eq 3 ]] || fail "exit code $rc, expected 3: $(tail -5 "$work/log")"
  grep -q "integration failed at t = " "$work/log" || fail "no diagnosis in the output"
  ;;
stopped_worker) stopped_worker ;;
stopped_worker_messages) stopped_worker --exchange messages ;;
bad_option)
  mpi 2 run "$work/planar.toml" -o "$work/b.h5" --master-share nan
  [[ $rc -eq 2 ]] || fail "exit code $rc, expected 2: $(tail -5 "$work/log")"
  [[ $(grep -c "error: --master-share: expected a finite number >= 0, got 'nan'" "$work/log") -eq 1 ]] ||
    fail "not one message from rank 0: $(cat "$work/log")"
  grep -qE "MPI_ABORT|Signal: Aborted|terminate called" "$work/log" && fail "an abort: $(cat "$work/log")"
  ;;
*) echo "unknown case $case_name" >&2; exit 2 ;;
esac
[[ $failures -eq 0 ]] && echo "PASS: $case_name" || echo "$failures failure(s) in $case_name"
[[ $failures -eq 0 ]]
