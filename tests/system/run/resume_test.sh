#!/usr/bin/env bash
# Checkpoints, --resume and signals of `raceway run` (docs/output_layout.md, "Checkpoints and
# resume"), one case per ctest:
#
#   resume_test.sh CASE RACEWAY MPIEXEC SOURCE_DIR
#
#   kill_resume_np1, kill_resume_np2: a short 6309 R3 run with a checkpoint every 50 output samples,
#     killed with SIGKILL at random times four times (each run resuming the one before) and resumed
#     to the end: after every kill the .partial file opens in h5py, and the final file's datasets and
#     summary are bitwise those of the uninterrupted run (tests/system/parallel/compare_outputs.py). At 2
#     ranks the whole mpirun job is killed. The random delays are printed, to repeat a failure.
#   kill_resume_pocket_factor: kill_resume_np1 with [solver] pocket_tolerance_factor = 10 (error
#     weights that follow the pocket contacts: a function of the state alone, nothing in the checkpoint).
#   kill_resume_np2_parallel_output: the same at 2 ranks with every rank writing its segment
#     diagnostics (--parallel-output, MPI-IO), compared with the uninterrupted run of the same kind.
#   signals_np1, signals_np2: SIGINT, SIGTERM and SIGUSR1 (np2: to both ranks, and SIGUSR1 to mpirun,
#     which forwards it) stop the run within 5 s with exit code 4, a signal checkpoint and a readable
#     .partial holding the samples up to it; --resume then completes the file with every output time
#     once, the restart listed in restart_times, and values within 1 % of the uninterrupted run's.
#   wall_clock: checkpoints every 0.05 s of wall clock leave the results bitwise unchanged.
#   refusals: --resume with another scene, other PETSc options, another build (the checkpoint's build
#     edited), or without the .partial file: exit 2 naming the reason and nothing written; --resume
#     without a checkpoint starts from the beginning, saying so; a run without --resume discards an
#     earlier checkpoint, saying so.
set -u
case_name=${1:?case}
raceway=${2:?raceway}
mpiexec=${3:?mpiexec}
source_dir=${4:?source dir}
source "$source_dir/tests/system/test_lib.sh"
python=/usr/bin/python3
compare=("$python" "$source_dir/tests/system/parallel/compare_outputs.py")

# The scene: 6309 R3 for 100 ms (5000 output samples of 20 us, about a second of wall time on one
# core, long enough for kills to land mid-run), a checkpoint every 2 ms.
sed -e 's/^end_time = .*/end_time = "100 ms"/' -e 's/^\[output\]/[output]\ncheckpoint_interval = "2 ms"/' \
  "$source_dir/jobs/scenes/6309_R3.toml" >"$work/scene.toml"
grep -q '^checkpoint_interval' "$work/scene.toml" || printf '[output]\ncheckpoint_interval = "2 ms"\n' >>"$work/scene.toml"

# launch NP OUT ARGS...: raceway run in the background (under mpirun when NP > 1); sets $pid.
launch() {
  local np=$1 out=$2
  shift 2
  if [[ $np -eq 1 ]]; then
    "$raceway" run "$work/scene.toml" -o "$out" "$@" >>"$work/log" 2>&1 &
  else
    "$mpiexec" --oversubscribe -np "$np" "$raceway" run "$work/scene.toml" -o "$out" "$@" >>"$work/log" 2>&1 &
  fi
  pid=$!
}

# diagnosis: what a failed run said (its raceway errors and warnings, then the log's last lines:
# under mpirun those are its own banner).
diagnosis() {
  grep -E '^\[raceway\] (error|warning)' "$work/log" | tail -5
  tail -3 "$work/log"
}

# wait_for FILE: until FILE exists (at most 30 s).
wait_for() {
  for _ in $(seq 1 600); do [[ -e "$1" ]] && return 0; sleep 0.05; done
  return 1
}

# wait_for_line FILE PATTERN: until FILE has a line matching PATTERN (at most 30 s).
wait_for_line() {
  for _ in $(seq 1 600); do grep -q "$2" "$1" 2>/dev/null && return 0; sleep 0.05; done
  return 1
}

# h5 FILE EXPRESSION: evaluates a Python expression with f = h5py.File(FILE) (prints an error line
# if the file does not open).
h5() {
  "$python" -c "import h5py, numpy as np, sys; f = h5py.File(sys.argv[1], 'r'); print($2)" "$1" 2>&1 | tail -1
}

# reference NP [OPTION...]: the uninterrupted run; sets $reference_ms, its wall time in milliseconds
# from the output's layout on ("readable from here on") to its end: the stretch a kill can land in
# (mpirun's and the model's start-up before it are most of a short run's wall on a loaded machine).
reference() {
  local np=$1 t0
  shift
  : >"$work/log"
  t0=$(date +%s%N)
  launch "$np" "$work/ref.h5" "$@"
  wait_for_line "$work/log" "readable from here on" && t0=$(date +%s%N)
  wait "$pid" || fail "the uninterrupted run failed: $(diagnosis)"
  reference_ms=$((($(date +%s%N) - t0) / 1000000))
}

# kill_resume NP [OPTION...]: OPTIONs go to every run (e.g. --parallel-output).
kill_resume() {
  local np=$1 kills=0 resumed=0 round delays=""
  shift
  local options=("$@")
  reference "$np" "${options[@]}"
  local args=("${options[@]}")
  # Four runs killed at random times (each resuming the one before), then a resume to the end.
  for round in 1 2 3 4 5; do
    : >"$work/log"
    launch "$np" "$work/k.h5" "${args[@]}"
    args=("${options[@]}" --resume)
    if [[ $round -lt 5 ]]; then
      wait_for_line "$work/log" "readable from here on" || true  # printed once the output's layout is flushed
      # A random delay below a quarter of the uninterrupted run's wall time, so that the kills land
      # mid-run on a fast machine as on a slow one.
      local delay
      delay=$(printf '%d.%03d' 0 $((RANDOM % (reference_ms / 4 < 999 ? reference_ms / 4 + 1 : 999))))
      delays+=" $delay"
      sleep "$delay"
      local ranks=""
      [[ $np -gt 1 ]] && ranks=$(pgrep -P "$pid" | tr '\n' ' ') && pkill -KILL -P "$pid" 2>/dev/null
      kill -KILL "$pid" 2>/dev/null
      # The ranks are not mpirun's to wait for: wait until they are gone (a process killed inside
      # an fsync lives until the disk answers, and holds the file's lock until then).
      local rank
      for rank in $ranks; do
        for _ in $(seq 1 200); do kill -0 "$rank" 2>/dev/null || break; sleep 0.05; done
      done
    fi
    wait "$pid" 2>/dev/null
    local rc=$?
    grep -q "resuming .* from its periodic checkpoint" "$work/log" && resumed=$((resumed + 1))
    [[ -e "$work/k.h5" ]] && break
    [[ $round -eq 5 ]] && fail "the last resume failed (exit $rc): $(diagnosis)"
    kills=$((kills + 1))
    local rows
    rows=$(h5 "$work/k.h5.partial" "len(f['time'])")
    [[ "$rows" =~ ^[0-9]+$ ]] || fail "after kill $kills (delay $delay s) the .partial does not open: $rows"
  done
  echo "np $np: uninterrupted run $reference_ms ms; kills after$delays s; $kills kills, $resumed resumes from a checkpoint"
  [[ -e "$work/k.h5" ]] || { fail "no complete file"; return; }
  [[ $kills -ge 2 ]] || fail "only $kills kill(s) landed before the end (the test did not test)"
  [[ $resumed -ge 1 ]] || fail "no resume started from a checkpoint (the test did not test)"
  "${compare[@]}" "$work/ref.h5" "$work/k.h5" >"$work/cmp" 2>&1 || fail "resumed file differs: $(tail -4 "$work/cmp")"
  [[ -e "$work/k.h5.checkpoint" || -e "$work/k.h5.partial" ]] && fail "checkpoint or .partial left after the end"
}

# stop_by NP SIGNAL TARGET: TARGET is "ranks" (every raceway process) or "mpirun".
stop_by() {
  local np=$1 signal=$2 target=$3
  rm -f "$work"/s.h5*
  : >"$work/log"
  launch "$np" "$work/s.h5"
  wait_for "$work/s.h5.checkpoint" || { fail "$signal: no first checkpoint"; return; }
  local started=$SECONDS victims=$pid
  [[ $np -gt 1 && $target == ranks ]] && victims=$(pgrep -P "$pid" | tr '\n' ' ')
  local t0
  t0=$(date +%s%N)
  # shellcheck disable=SC2086
  kill -"$signal" $victims
  wait "$pid"
  local rc=$? ms=$((($(date +%s%N) - t0) / 1000000))
  echo "np $np: SIG$signal to $target: exit $rc after $ms ms"
  [[ $rc -eq 4 ]] || fail "np $np SIG$signal to $target: exit code $rc, expected 4: $(diagnosis)"
  [[ $ms -lt 5000 ]] || fail "np $np SIG$signal to $target: took $ms ms to stop"
  (( SECONDS - started < 30 )) || true
  pgrep -f "$work/s.h5" >/dev/null && fail "np $np SIG$signal: a raceway process is still running"
  local kind sample rows
  kind=$(h5 "$work/s.h5.checkpoint" "f.attrs['kind']")
  sample=$(h5 "$work/s.h5.checkpoint" "f.attrs['sample']")
  rows=$(h5 "$work/s.h5.partial" "len(f['time'])")
  [[ $kind == signal ]] || fail "np $np SIG$signal: checkpoint kind '$kind'"
  [[ "$rows" =~ ^[0-9]+$ && $rows -eq $((sample + 1)) ]] ||
    fail "np $np SIG$signal: the .partial holds '$rows' samples, the checkpoint is at sample $sample"
  launch "$np" "$work/s.h5" --resume
  wait "$pid" || { fail "np $np SIG$signal: the resume failed: $(diagnosis)"; return; }
  local check
  check=$("$python" - "$work/ref.h5" "$work/s.h5" <<'PY'
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
same_times = a["time"].shape == b["time"].shape and np.array_equal(a["time"][()], b["time"][()])
w_a, w_b = a["cage/angular_velocity"][()], b["cage/angular_velocity"][()]
rel = float(np.max(np.abs(w_a - w_b)) / np.max(np.abs(w_a)))
print(same_times, rel < 0.01, len(b.attrs["restart_times"]), rel)
PY
)
  [[ $check == "True True 1 "* ]] || fail "np $np SIG$signal: resumed file: same times, within 1 %, one restart? $check"
}

signals() {
  local np=$1
  reference "$np"
  for signal in INT TERM USR1; do stop_by "$np" "$signal" ranks; done
  [[ $np -gt 1 ]] && stop_by "$np" USR1 mpirun
}

# refused WHAT EXPECTED ARGS...: raceway run ARGS --resume exits 2 naming EXPECTED, writing nothing.
refused() {
  local what=$1 expected=$2
  shift 2
  local before
  before=$(cksum "$work/r.h5.partial" "$work/r.h5.checkpoint" 2>/dev/null)
  "$raceway" run "$@" --resume >"$work/out" 2>&1
  local rc=$?
  [[ $rc -eq 2 ]] || fail "$what: exit code $rc, expected 2: $(tail -2 "$work/out")"
  grep -qF -- "$expected" "$work/out" || fail "$what: no '$expected' in: $(tail -2 "$work/out")"
  [[ $(cksum "$work/r.h5.partial" "$work/r.h5.checkpoint" 2>/dev/null) == "$before" ]] || fail "$what: files changed"
}

refusals() {
  launch 1 "$work/r.h5"
  wait_for "$work/r.h5.checkpoint"
  kill -KILL "$pid"
  wait "$pid" 2>/dev/null
  sed 's/^rolling_elements = .*/&  # edited/' "$work/scene.toml" >"$work/edited.toml"
  refused "another scene" "the scene differs from the checkpoint's: line" "$work/edited.toml" -o "$work/r.h5"
  refused "other PETSc options" "other options" "$work/scene.toml" -o "$work/r.h5" --petsc-options "-ksp_type gmres"
  cp "$work/r.h5.checkpoint" "$work/saved.checkpoint"
  # The build edited, then the checkpoint's checksums made again (its payload's and its seal, as
  # solver/run/checkpoint.cpp and io/h5/h5_checksums.cpp make them): only the build differs.
  "$python" - "$work/r.h5.checkpoint" "$source_dir/tests/system/run" <<'PY'
import sys
import h5py
import numpy as np
sys.path.insert(0, sys.argv[2])
from checkpoint_damage_test import payload_crc, reseal
with h5py.File(sys.argv[1], "r+") as f:
    f.attrs["build"] = "raceway 0.0 (another build)"
    f.attrs["payload_crc32"] = np.int64(payload_crc(f))
reseal(sys.argv[1])
PY
  refused "another build" "another build of raceway" "$work/scene.toml" -o "$work/r.h5"
  cp "$work/saved.checkpoint" "$work/r.h5.checkpoint"
  mv "$work/r.h5.partial" "$work/saved.partial"
  refused "no .partial file" "which is missing" "$work/scene.toml" -o "$work/r.h5"
  mv "$work/saved.partial" "$work/r.h5.partial"
  # A run without --resume discards the checkpoint (and says so) rather than leaving it to be
  # matched with its new .partial file.
  "$raceway" run "$work/scene.toml" -o "$work/r.h5" >"$work/out" 2>&1 &
  pid=$!
  wait_for_line "$work/out" "Newton linear solver"
  kill -KILL "$pid"
  wait "$pid" 2>/dev/null
  grep -q "discarded the checkpoint of an earlier run" "$work/out" || fail "a fresh run did not discard the checkpoint"
  rm -f "$work"/n.h5*
  "$raceway" run "$work/scene.toml" -o "$work/n.h5" --resume >"$work/out" 2>&1 || fail "--resume without a checkpoint failed"
  grep -q "no checkpoint of .*n.h5.*starting from the beginning" "$work/out" || fail "--resume without a checkpoint: not said"
}

case "$case_name" in
kill_resume_np1) kill_resume 1 ;;
kill_resume_np2) kill_resume 2 ;;
kill_resume_np2_parallel_output) kill_resume 2 --parallel-output ;;
kill_resume_pocket_factor) kill_resume 1 --set solver.pocket_tolerance_factor=10 ;;
signals_np1) signals 1 ;;
signals_np2) signals 2 ;;
wall_clock)
  reference 1
  sed 's/^checkpoint_interval = .*/checkpoint_interval = 0\ncheckpoint_wall_interval = "0.05 s"/' "$work/scene.toml" >"$work/wall.toml"
  "$raceway" run "$work/wall.toml" -o "$work/w.h5" >"$work/log" 2>&1 || fail "wall-clock run failed"
  sed 's/^checkpoint_interval = .*/checkpoint_interval = 0\ncheckpoint_wall_interval = 0/' "$work/scene.toml" >"$work/none.toml"
  "$raceway" run "$work/none.toml" -o "$work/none.h5" >"$work/log" 2>&1 || fail "run without checkpoints failed"
  # The probe runs long (a completed run removes its checkpoint, and the 100 ms scene can end before
  # Python has opened the file), and is stopped once its checkpoint has been read.
  sed 's/^end_time = .*/end_time = "2 s"/' "$work/wall.toml" >"$work/probe.toml"
  "$raceway" run "$work/probe.toml" -o "$work/probe.h5" >"$work/log" 2>&1 &
  pid=$!
  wait_for "$work/probe.h5.checkpoint" || fail "no wall-clock checkpoint was written"
  [[ $(h5 "$work/probe.h5.checkpoint" "f.attrs['kind']") == wall_clock ]] || fail "the checkpoint is not a wall-clock one"
  kill "$pid" 2>/dev/null
  wait "$pid"
  # Same results with or without wall-clock checkpoints (the scene text differs, so compare datasets).
  "$python" - "$work/none.h5" "$work/w.h5" <<'PY' || fail "wall-clock checkpoints changed the results"
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
names = []
a.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
bad = [n for n in names if a[n].dtype.kind == "f" and a[n][()].tobytes() != b[n][()].tobytes()]
print("differ:", bad[:5])
sys.exit(1 if bad or not names else 0)
PY
  ;;
refusals) refusals ;;
*)
  echo "unknown case '$case_name'" >&2
  exit 2
  ;;
esac
finish
