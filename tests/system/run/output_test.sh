#!/usr/bin/env bash
# Output paths, the output lock, a full disk and the scheduler-log flag of `raceway run`, one case per
# ctest (docs/output_layout.md, "One file per run"):
#
#   output_test.sh CASE RACEWAY SOURCE_DIR
#
#   bad_paths: -o a directory, "", a missing folder, a folder without write permission, and the same
#     for --summary-json: exit 2, a message naming the path and the reason, before the simulation
#     starts (no start-up line), and no file created.
#   locked_output: a second run on the output a first run is writing (with HDF5's own locking off,
#     HDF5_USE_FILE_LOCKING=FALSE) fails at once with exit 2 naming the holder, and the first run
#     still ends with a complete file; a lock left by a SIGKILLed run does not block the next run.
#   disk_full: the file-size limit of a running raceway is lowered (prlimit) so that its next flush
#     cannot be written: exit 1 (not a crash), a message naming the file and the system's reason, and
#     the .partial file still opens in h5py.
#   scheduler_log: a serial run writes no /scheduler; with --scheduler-log it does.
set -u
case_name=${1:?case}
raceway=${2:?raceway}
source_dir=${3:?source dir}
source "$source_dir/tests/system/test_lib.sh"
python=/usr/bin/python3

# Runs raceway with stdout and stderr captured in $work/out and $work/err; sets $rc.
run() {
  "$raceway" "$@" >"$work/out" 2>"$work/err"
  rc=$?
}

# A short scene: the default one, end time $1.
short_scene() {
  # At order 5 (fixed): the lock case needs a run that lasts (the automatic order is 50 times faster here).
  sed -e "s/^end_time *=.*/end_time = \"$1\"/" -e "s/^\\[solver\\]/[solver]\\nmax_order = 5/" "$source_dir/jobs/scenes/default.toml" >"$work/short.toml"
}

# refused WHAT EXPECTED ARGS...: raceway run ARGS must exit 2 before the simulation, naming EXPECTED.
refused() {
  local what=$1 expected=$2
  shift 2
  run run "$work/short.toml" "$@"
  [[ $rc -eq 2 ]] || fail "$what: exit code $rc, expected 2"
  grep -qF -- "$expected" "$work/err" || fail "$what: stderr lacks '$expected': $(tail -2 "$work/err")"
  grep -q "start-up" "$work/err" && fail "$what: the simulation started before the path was checked"
  ls "$work" | grep -qE '\.(h5|partial|json)$' && fail "$what: a file was created: $(ls "$work")"
}

# The number of output samples in FILE (rows of /time), or an error line.
rows_of() {
  "$python" -c "import h5py,sys; f=h5py.File(sys.argv[1],'r'); print(len(f['time']))" "$1" 2>&1 | tail -1
}

case "$case_name" in

bad_paths)
  short_scene "2 ms"
  refused "-o a directory" "is a directory" -o "$work"
  refused "-o empty" "the path is empty" -o ""
  refused "-o in a missing folder" "does not exist" -o "$work/missing/x.h5"
  if [[ $(id -u) -eq 0 ]]; then
    refused "-o where nothing can be created" "cannot create" -o /proc/raceway_output_test.h5
  else
    mkdir "$work/readonly" && chmod 555 "$work/readonly"
    refused "-o in a read-only folder" "cannot create" -o "$work/readonly/x.h5"
  fi
  refused "--summary-json a directory" "is a directory" -o "$work/x.h5" --summary-json "$work"
  refused "--summary-json in a missing folder" "does not exist" -o "$work/x.h5" --summary-json "$work/no/s.json"
  ;;

locked_output)
  # Long enough (about 2 s here) that the first run still holds its lock when the second one starts.
  short_scene "400 ms"
  export HDF5_USE_FILE_LOCKING=FALSE
  "$raceway" run "$work/short.toml" -o "$work/out.h5" >"$work/first.log" 2>&1 &
  first=$!
  for _ in $(seq 1 600); do [[ -e "$work/out.h5.partial" ]] && break; sleep 0.05; done  # up to 30 s: a loaded machine starts slowly
  [[ -e "$work/out.h5.partial" ]] || fail "the first run created no .partial file"
  run run "$work/short.toml" -o "$work/out.h5"
  [[ $rc -eq 2 ]] || fail "second run: exit code $rc, expected 2"
  grep -q "being written by another raceway run (pid $first" "$work/err" ||
    fail "second run: no message naming the first run: $(tail -2 "$work/err")"
  wait "$first" || fail "the first run failed after the second one tried: $(tail -3 "$work/first.log")"
  rows=$(rows_of "$work/out.h5")
  [[ "$rows" == 801 ]] || fail "the first run's file has '$rows' samples, expected 801"
  [[ -e "$work/out.h5.lock" ]] && fail "the lock file is left behind after a normal end"
  # A run killed by SIGKILL leaves its lock file; the kernel released the lock, so the next run goes.
  "$raceway" run "$work/short.toml" -o "$work/killed.h5" >"$work/killed.log" 2>&1 &
  victim=$!
  for _ in $(seq 1 600); do [[ -e "$work/killed.h5.partial" ]] && break; sleep 0.05; done
  kill -KILL "$victim"
  wait "$victim" 2>/dev/null
  [[ -e "$work/killed.h5.lock" ]] || fail "no lock file left by the killed run (the test cannot tell)"
  run run "$work/short.toml" -o "$work/killed.h5"
  [[ $rc -eq 0 ]] || fail "the run after a killed one: exit code $rc: $(tail -2 "$work/err")"
  ;;

disk_full)
  command -v prlimit >/dev/null || { echo "prlimit not found (util-linux)" >&2; exit 1; }
  short_scene "60 ms"
  "$raceway" run "$work/short.toml" -o "$work/out.h5" >"$work/run.log" 2>&1 &
  pid=$!
  # The first progress line: the output's layout is on disk (flushed), its rows are still in memory.
  for _ in $(seq 1 400); do grep -q " s of " "$work/run.log" && break; sleep 0.02; done
  size=$(stat -c %s "$work/out.h5.partial" 2>/dev/null || echo 0)
  prlimit --pid "$pid" --fsize=$((size + 4096)) || fail "prlimit failed"
  wait "$pid"
  rc=$?
  [[ $rc -eq 1 ]] || fail "exit code $rc, expected 1 (139 or 134 would be a crash)"
  grep -q "out.h5.partial" "$work/run.log" || fail "the message does not name the file: $(tail -2 "$work/run.log")"
  grep -q "File too large" "$work/run.log" || fail "the message lacks the system's reason: $(tail -2 "$work/run.log")"
  grep -qiE "segmentation|signal 11|core dumped" "$work/run.log" && fail "crashed: $(tail -5 "$work/run.log")"
  rows=$(rows_of "$work/out.h5.partial")
  [[ "$rows" =~ ^[0-9]+$ ]] || fail "the .partial file does not open in h5py: $rows"
  [[ -e "$work/out.h5" ]] && fail "out.h5 written although the disk was full"
  ;;

scheduler_log)
  short_scene "2 ms"
  run run "$work/short.toml" -o "$work/plain.h5"
  [[ $rc -eq 0 ]] || fail "run: exit code $rc"
  run run "$work/short.toml" -o "$work/logged.h5" --scheduler-log
  [[ $rc -eq 0 ]] || fail "run --scheduler-log: exit code $rc"
  has() { "$python" -c "import h5py,sys; print('scheduler' in h5py.File(sys.argv[1],'r'))" "$1"; }
  [[ $(has "$work/plain.h5") == False ]] || fail "a serial run wrote /scheduler without --scheduler-log"
  [[ $(has "$work/logged.h5") == True ]] || fail "--scheduler-log wrote no /scheduler"
  ;;

*)
  echo "unknown case '$case_name'" >&2
  exit 2
  ;;
esac
finish
